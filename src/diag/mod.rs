//! Diagnostics: every error and warning the library produces, as data.
//!
//! The library never prints. A stage returns `Result<T, Diagnostics>`; the CLI
//! (`cli/report.rs`, the only place that knows ariadne) turns each
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

pub mod excerpt;
mod kind;

pub use excerpt::{Excerpt, line_column};
pub use kind::{ErrorKind, SHOWN_DIGITS, short_number};

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
    /// How to fix it, in one sentence.
    pub help: Option<String>,
}

impl Diagnostic {
    /// An error of `kind` with no location yet.
    pub fn error(kind: ErrorKind) -> Self {
        Diagnostic {
            severity: Severity::Error,
            kind,
            span: None,
            label: None,
            labels: Vec::new(),
            help: None,
        }
    }

    /// A warning of `kind` with no location yet.
    pub fn warning(kind: ErrorKind) -> Self {
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
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
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
            write!(f, "; help: {help}")?;
        }
        Ok(())
    }
}

/// One or more diagnostics: the error type of every fallible stage.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostics {
    /// No diagnostics yet.
    pub fn new() -> Self {
        Diagnostics(Vec::new())
    }

    /// Adds one.
    pub fn push(&mut self, d: Diagnostic) {
        self.0.push(d);
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
