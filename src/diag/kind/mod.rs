//! What went wrong: [`ErrorKind`]. Each stage that reports errors has its
//! own enum in its own file here ([`InputError`], [`LsysError`],
//! [`StlError`], [`RuleError`], [`LayoutError`], [`GrowError`],
//! [`BedError`], [`RenderError`]), wrapped in one variant of [`ErrorKind`];
//! the kinds every stage shares (a limit, I/O, the cap on diagnostics, an
//! error a front end brings) are [`ErrorKind`]'s own variants. The message
//! is the `Display` text; where and how to fix it live on
//! [`super::Diagnostic`].
//!
//! A stage builds its error as `Diagnostic::error(GrowError::RootOutside { .. })`
//! (any stage error converts into an [`ErrorKind`]); a test matches it as
//! `ErrorKind::Grow(GrowError::RootOutside { .. })`.

mod bed;
mod grow;
mod input;
mod layout;
mod lsys;
mod render;
mod rules;
mod stl;

pub use bed::BedError;
pub use grow::{GrowError, Kin, Misfit, MissReason};
pub use input::InputError;
pub use layout::LayoutError;
pub use lsys::LsysError;
pub use render::RenderError;
pub use rules::RuleError;
pub use stl::StlError;

use super::number::short_number;

/// What went wrong: a stage's error, or one every stage shares. The message
/// is the `Display` text, the span and hints live on [`super::Diagnostic`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ErrorKind {
    /// A problem with the input text as text, before any format's meaning
    /// (`kind/input.rs`).
    #[error(transparent)]
    Input(#[from] InputError),
    /// A problem with an `.lsys` file (`kind/lsys.rs`).
    #[error(transparent)]
    Lsys(#[from] LsysError),
    /// A problem with the text of an `.od` or `.bed`: header, body, seed
    /// (`kind/stl.rs`).
    #[error(transparent)]
    Stl(#[from] StlError),
    /// A problem with a rule, its alternatives or a reference to it
    /// (`kind/rules.rs`).
    #[error(transparent)]
    Rule(#[from] RuleError),
    /// A problem with a LAYOUT's shapes or the region they make
    /// (`kind/layout.rs`).
    #[error(transparent)]
    Layout(#[from] LayoutError),
    /// A problem, or a warning, of growth (`kind/grow.rs`).
    #[error(transparent)]
    Grow(#[from] GrowError),
    /// A BED that reads but does not hold together (`kind/bed.rs`).
    #[error(transparent)]
    Bed(#[from] BedError),
    /// A problem, or a warning, of drawing and writing the picture
    /// (`kind/render.rs`).
    #[error(transparent)]
    Render(#[from] RenderError),
    /// More diagnostics than [`super::MAX_DIAGNOSTICS`]: the rest are
    /// counted, not kept (a generated file can hold a million mistakes).
    #[error("{count} more problem(s) of the same input not shown")]
    MoreDiagnostics {
        /// How many were left out.
        count: usize,
    },
    /// A limit (depth, word length, stems, ...) would be exceeded.
    #[error(
        "{}: {} exceeds the limit of {limit}",
        what.as_deref().unwrap_or(bound.describe()),
        short_number(value)
    )]
    Limit {
        /// Which limit.
        bound: crate::diag::Bound,
        /// What was measured against it, where the bound's own words
        /// ([`crate::diag::Bound::describe`]) are not precise enough
        /// (`derived word length at depth 30`).
        what: Option<String>,
        /// The value asked for (decimal; may be a big integer, or a bound
        /// such as `more than 10000`).
        value: String,
        /// The limit in force.
        limit: u64,
    },
    /// The reader of our standard output went away (`stlc expand | head`).
    /// The CLI exits quietly on it.
    #[error("broken pipe")]
    BrokenPipe,
    /// Reading the input or writing the output failed: `doing` says what
    /// (`cannot read \`tree.od\``), `error` is the system's message.
    #[error("{doing}: {error}")]
    Io {
        /// What was being done.
        doing: String,
        /// The operating system's message.
        error: String,
    },
    /// A flag given that does nothing for this input (a warning).
    #[error("{flag} was ignored: {reason}")]
    IgnoredFlag {
        /// The flag as written (`--depth`).
        flag: String,
        /// Why it does nothing here.
        reason: String,
    },
    /// An error only a front end makes (its command line, the files it
    /// writes): the front end's own error type (`frontend/error.rs` in the
    /// binary) converts into this, keeping its message and whether it is a
    /// usage error.
    #[error("{message}")]
    FrontEnd {
        /// The message.
        message: String,
        /// Whether it is a usage error (exit status 2).
        usage: bool,
    },
}

impl ErrorKind {
    /// Whether this is a usage error: the command line asks for something
    /// contradictory, rather than the input or the work failing. The CLI
    /// exits with status 2 on these, as it does on clap's own.
    pub fn is_usage(&self) -> bool {
        matches!(
            self,
            ErrorKind::Render(
                RenderError::FormatMismatch { .. }
                    | RenderError::UnknownOutputExtension { .. }
                    | RenderError::SolidUsage { .. }
            ) | ErrorKind::FrontEnd { usage: true, .. }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Bound;

    /// A stage's error reads the same wrapped as alone, and a usage error
    /// is one whichever way it is built.
    #[test]
    fn wrapped_kinds_keep_their_message_and_usage() {
        let grow = GrowError::NothingToGrow;
        assert_eq!(ErrorKind::from(grow.clone()).to_string(), grow.to_string());
        let mismatch = RenderError::FormatMismatch {
            format: "svg".into(),
            path: "a.png".into(),
        };
        assert_eq!(
            ErrorKind::from(mismatch).to_string(),
            "`-f svg` contradicts the output name `a.png`"
        );
        assert!(
            ErrorKind::from(RenderError::UnknownOutputExtension {
                path: "a.gif".into(),
                extension: "gif".into(),
            })
            .is_usage()
        );
        assert!(!ErrorKind::from(RenderError::DrawingNotFinite).is_usage());
        let front = |usage| ErrorKind::FrontEnd {
            message: "m".into(),
            usage,
        };
        assert!(front(true).is_usage() && !front(false).is_usage());
    }

    /// A limit's message uses the bound's words unless the site gives its own.
    #[test]
    fn a_limit_names_its_bound() {
        let limit = |what: Option<&str>| ErrorKind::Limit {
            bound: Bound::Depth,
            what: what.map(String::from),
            value: "20000".into(),
            limit: 10_000,
        };
        assert_eq!(
            limit(None).to_string(),
            "derivation depth: 20000 exceeds the limit of 10000"
        );
        assert_eq!(
            limit(Some("generations")).to_string(),
            "generations: 20000 exceeds the limit of 10000"
        );
    }
}
