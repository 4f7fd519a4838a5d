//! Command-line interface (binary only): argument parsing, one library
//! request per command, the progress bar, exit codes. Reading inputs,
//! writing outputs and reporting diagnostics are [`crate::frontend`]'s.
//!
//! Exit codes: 0 success (warnings may be printed), 1 the input or the work
//! failed (diagnostics printed, nothing written), 2 usage error (clap).

pub(crate) mod args;
mod progress;
mod run;

use std::io::IsTerminal;
use std::process::ExitCode;

use clap::Parser;

pub use args::Cli;

/// Stack for the worker thread. No pass recurses on input depth (the
/// grammar is flat, every pass and the syntax tree's Clone/PartialEq/Drop
/// use explicit stacks); this stack is a second line of defence, not a
/// requirement. 64 MiB: an address-space limit counts the reservation, so
/// a 1 GiB stack kept stlc from starting under `ulimit -v 1000000`; the
/// deepest inputs of the robustness tests run in it.
const WORKER_STACK: usize = 64 << 20;

/// On SIGINT or SIGTERM: remove the temporary output files (their targets
/// were never touched) and exit with 128 + the signal's number (130, 143),
/// as a shell reports a process killed by it, or 0 for a server.
fn install_interrupt_handler() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
        // Without the handler the default action still stops stlc; only
        // the temporary file may be left behind.
        return;
    };
    let _ = std::thread::Builder::new()
        .name("stlc-signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                crate::frontend::interrupt::remove_pending();
                progress::clear_on_interrupt();
                std::process::exit(crate::frontend::interrupt::exit_status(signal));
            }
        });
}

/// Parses arguments, runs the command on a big-stack thread, maps the result
/// to an exit code.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    install_interrupt_handler();
    let color = match cli.color {
        args::ColorChoice::Always => true,
        args::ColorChoice::Never => false,
        args::ColorChoice::Auto => {
            std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none()
        }
    };
    let worker = std::thread::Builder::new()
        .name("stlc".into())
        .stack_size(WORKER_STACK)
        .spawn(move || run::run(&cli, color));
    match worker.map(|h| h.join()) {
        Ok(Ok(code)) => code,
        Ok(Err(_)) => {
            eprintln!("error: stlc crashed; this is a bug, please report it with the input file");
            ExitCode::from(101)
        }
        Err(e) => {
            eprintln!("error: cannot start the worker thread: {e}");
            ExitCode::FAILURE
        }
    }
}
