//! Command-line interface (binary only).

use std::process::ExitCode;

/// Runs the CLI.
pub fn main() -> ExitCode {
    ExitCode::SUCCESS
}
