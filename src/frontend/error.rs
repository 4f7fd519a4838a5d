//! Errors only a front end makes: about its own command line and the files
//! it writes, never about the input or the work. The library knows them as
//! one kind, [`ErrorKind::FrontEnd`], holding the message and whether it is
//! a usage error (exit status 2); this enum is where they are told apart.

use stlc::diag::{Diagnostic, ErrorKind};

/// What went wrong, in a front end. The message is the `Display` text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FrontEndError {
    /// Reading standard input, `render` was not told where the picture goes
    /// (a usage error).
    #[error("no output named")]
    NoOutput,
    /// The output is the input file: writing would destroy the input.
    #[error("refusing to write over the input: `{output}` is the same file as `{input}`")]
    OutputIsInput {
        /// The input as named.
        input: String,
        /// The output as named.
        output: String,
    },
    /// A PNG would be written to a terminal.
    #[error("refusing to write a PNG to a terminal")]
    PngToTerminal,
    /// A binary mesh (`.glb`, `.stl`, `.3mf`) would be written to a
    /// terminal.
    #[error("refusing to write a binary {format} to a terminal")]
    BinaryToTerminal {
        /// The format's name.
        format: &'static str,
    },
    /// A colour flag names no colour.
    #[error("{flag}: unknown colour `{text}`")]
    UnknownColourFlag {
        /// The flag (`--stroke`, `--background`).
        flag: String,
        /// What was given.
        text: String,
    },
    /// `-o` names a directory.
    #[error("`{path}` is a directory")]
    IsADirectory {
        /// The path.
        path: String,
    },
    /// `-o` names a chain of symbolic links longer than the limit.
    #[error("`{path}`: more than {hops} symbolic links in a row")]
    TooManyLinks {
        /// The path.
        path: String,
        /// The limit.
        hops: usize,
    },
    /// The output file could not be created (its temporary file, in the
    /// target's directory, could not).
    #[error("cannot write `{path}`: cannot create a file in `{dir}`: {error}")]
    CannotCreate {
        /// The target as named.
        path: String,
        /// The target's directory.
        dir: String,
        /// The operating system's message.
        error: String,
    },
    /// `compile --strategy`: the old name of `--growth` (a warning; on
    /// render and expand `--strategy` is the derivation order).
    #[error("--strategy on compile is the growth order; its name is --growth")]
    StrategyMeansGrowth,
    /// The finished output could not be renamed over the target.
    #[error("cannot replace `{path}`: {error}")]
    CannotReplace {
        /// The target.
        path: String,
        /// The operating system's message.
        error: String,
    },
}

impl FrontEndError {
    /// Whether this is a usage error: the command line asks for something
    /// it cannot have. The CLI exits with status 2 on these.
    pub fn is_usage(&self) -> bool {
        matches!(self, FrontEndError::NoOutput)
    }

    /// This error as a [`Diagnostic`], with no location or hint yet.
    pub fn diagnostic(self) -> Diagnostic {
        Diagnostic::error(self)
    }
}

impl From<FrontEndError> for ErrorKind {
    fn from(e: FrontEndError) -> Self {
        ErrorKind::FrontEnd {
            message: e.to_string(),
            usage: e.is_usage(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The library's kind keeps the message and the usage bit.
    #[test]
    fn a_front_end_error_keeps_its_message_and_its_usage() {
        let d = FrontEndError::NoOutput.diagnostic();
        assert_eq!(d.kind.to_string(), "no output named");
        assert!(d.kind.is_usage());
        let d = FrontEndError::PngToTerminal.diagnostic();
        assert_eq!(
            d.to_string(),
            "error: refusing to write a PNG to a terminal"
        );
        assert!(!d.kind.is_usage());
    }
}
