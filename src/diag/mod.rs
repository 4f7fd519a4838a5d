//! Diagnostics: every error and warning the library produces, as data.
//!
//! The library never prints. A stage returns `Result<T, Diagnostics>`; the CLI
//! (`frontend/report.rs`, the only place that knows ariadne) turns each
//! [`Diagnostic`] into a report that points at the offending text. Tests assert
//! on [`Diagnostic::kind`] and [`Diagnostic::span`].

use std::fmt;
use std::ops::Range;

/// A byte range into the source text a diagnostic refers to.
pub type Span = Range<usize>;

/// How bad a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    /// The work went on; the user should know.
    Warning,
    /// The work stopped; nothing was written.
    Error,
}

mod bound;
pub mod excerpt;
mod help;
mod kind;
mod number;

pub use bound::Bound;
pub use excerpt::{Excerpt, line_column};
pub use help::{Flags, Help, Knob, Part, Spelling};
pub use kind::{
    BedError, ErrorKind, GrowError, InputError, Kin, LayoutError, LsysError, Misfit, MissReason,
    RenderError, RuleError, StlError,
};
pub(crate) use number::plural;
pub use number::{SHOWN_DIGITS, saturated, short_number};

/// The diagnostic for an I/O error while writing output: a broken pipe gets
/// its own kind so the CLI can exit quietly.
pub fn io_error(e: &std::io::Error, doing: &str) -> Diagnostic {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        Diagnostic::error(ErrorKind::BrokenPipe)
    } else {
        Diagnostic::error(ErrorKind::Io {
            doing: doing.to_string(),
            error: e.to_string(),
        })
    }
}

/// A secondary pointer into the source with its own message.
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    /// Where.
    pub span: Span,
    /// What about it.
    pub message: String,
}

/// One error or warning, with where it is and how to fix it.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// What went wrong; its `Display` is the headline.
    pub kind: ErrorKind,
    /// The main place in the source, if the problem has one.
    pub span: Option<Span>,
    /// Text for the main label (defaults to the headline).
    pub label: Option<String>,
    /// Further places worth pointing at.
    pub labels: Vec<Label>,
    /// How to fix it, in one sentence, the options it names as data
    /// (each front end spells them: [`Help::spell`]).
    pub help: Option<Help>,
}

impl Diagnostic {
    /// An error of `kind` with no location yet.
    pub fn error(kind: impl Into<ErrorKind>) -> Self {
        Diagnostic {
            severity: Severity::Error,
            kind: kind.into(),
            span: None,
            label: None,
            labels: Vec::new(),
            help: None,
        }
    }

    /// A warning of `kind` with no location yet.
    pub fn warning(kind: impl Into<ErrorKind>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(kind)
        }
    }

    /// Sets the main location.
    pub fn with_span(mut self, span: Span) -> Self {
        self.span = Some(span);
        self
    }

    /// Sets the text of the main label.
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = Some(label.into());
        self
    }

    /// Adds a secondary location.
    pub fn with_note_at(mut self, span: Span, message: impl Into<String>) -> Self {
        self.labels.push(Label {
            span,
            message: message.into(),
        });
        self
    }

    /// Sets the hint that says how to fix it.
    pub fn with_help(mut self, help: impl Into<Help>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// The hint as the command line writes it (options as flags).
    pub fn help_text(&self) -> Option<String> {
        self.help.as_ref().map(Help::flags)
    }

    /// True for errors (as opposed to warnings).
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.severity {
            Severity::Error => write!(f, "error: {}", self.kind)?,
            Severity::Warning => write!(f, "warning: {}", self.kind)?,
        }
        if let Some(span) = &self.span {
            write!(f, " (at bytes {}..{})", span.start, span.end)?;
        }
        if let Some(help) = &self.help {
            write!(f, "; help: {}", help.flags())?;
        }
        Ok(())
    }
}

/// The most diagnostics one [`Diagnostics`] keeps; the rest are counted.
pub const MAX_DIAGNOSTICS: usize = 100;

/// One or more diagnostics: the error type of every fallible stage.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostics {
    /// No diagnostics yet.
    pub fn new() -> Self {
        Diagnostics(Vec::new())
    }

    /// Adds one. Past [`MAX_DIAGNOSTICS`] the rest are only counted, in
    /// one last [`ErrorKind::MoreDiagnostics`] (an error if any of them is),
    /// so a file with a million mistakes costs neither a million reports
    /// nor the memory to hold them.
    pub fn push(&mut self, d: Diagnostic) {
        if self.0.len() < MAX_DIAGNOSTICS {
            self.0.push(d);
            return;
        }
        let error = d.is_error();
        match self.0.last_mut() {
            Some(last) if matches!(last.kind, ErrorKind::MoreDiagnostics { .. }) => {
                if let ErrorKind::MoreDiagnostics { count } = &mut last.kind {
                    *count += 1;
                }
                if error {
                    last.severity = Severity::Error;
                }
            }
            _ => {
                let more = ErrorKind::MoreDiagnostics { count: 1 };
                let mut more = if error {
                    Diagnostic::error(more)
                } else {
                    Diagnostic::warning(more)
                };
                more = more.with_help("fix the ones shown first");
                self.0.push(more);
            }
        }
    }

    /// True if any of them is an error.
    pub fn has_errors(&self) -> bool {
        self.0.iter().any(Diagnostic::is_error)
    }

    /// True if there are none at all.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Iterates over them in the order they were found.
    pub fn iter(&self) -> std::slice::Iter<'_, Diagnostic> {
        self.0.iter()
    }

    /// The first error's kind, handy in tests.
    pub fn first_kind(&self) -> Option<&ErrorKind> {
        self.0.iter().find(|d| d.is_error()).map(|d| &d.kind)
    }

    /// `Err(self)` if there are errors, else `Ok(value)`.
    pub fn into_result<T>(self, value: T) -> Result<T, Diagnostics> {
        if self.has_errors() {
            Err(self)
        } else {
            Ok(value)
        }
    }
}

impl From<Diagnostic> for Diagnostics {
    fn from(d: Diagnostic) -> Self {
        Diagnostics(vec![d])
    }
}

impl fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, d) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostics {}

impl IntoIterator for Diagnostics {
    type Item = Diagnostic;
    type IntoIter = std::vec::IntoIter<Diagnostic>;
    fn into_iter(self) -> Self::IntoIter {
        self.0.into_iter()
    }
}

#[cfg(test)]
mod cap_tests {
    use super::*;

    /// Past the cap the rest are counted in one last diagnostic, an error
    /// as soon as one of them is.
    #[test]
    fn diagnostics_past_the_cap_are_counted() {
        let mut d = Diagnostics::new();
        for _ in 0..MAX_DIAGNOSTICS {
            d.push(Diagnostic::warning(InputError::EmptyInput));
        }
        assert!(!d.has_errors());
        for _ in 0..5 {
            d.push(Diagnostic::warning(InputError::EmptyInput));
        }
        assert_eq!(d.0.len(), MAX_DIAGNOSTICS + 1);
        assert!(!d.has_errors(), "five more warnings are no error");
        d.push(Diagnostic::error(InputError::EmptyInput));
        assert_eq!(d.0.len(), MAX_DIAGNOSTICS + 1);
        assert!(d.has_errors(), "an error among the rest is an error");
        assert_eq!(
            d.0.last().map(|l| &l.kind),
            Some(&ErrorKind::MoreDiagnostics { count: 6 })
        );
    }
}
