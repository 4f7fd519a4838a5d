//! The `stlc` binary: two front ends over the library, the command line
//! (`cli`) and the Tree Maker page (`serve`), and what they share
//! (`frontend`: inputs, atomic outputs, diagnostics on stderr). All work
//! is in the library.

mod cli;
mod frontend;
mod serve;

fn main() -> std::process::ExitCode {
    cli::main()
}
