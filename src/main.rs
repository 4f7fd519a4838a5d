//! The `stlc` command line. All work is in the library and `cli`.

mod cli;
mod serve;

fn main() -> std::process::ExitCode {
    cli::main()
}
