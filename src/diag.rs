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

/// What went wrong. Each stage owns its variants; the message is the
/// `Display` text, the span and hints live on [`Diagnostic`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ErrorKind {
    /// The text does not follow the grammar (pest's report, with rule names
    /// translated into what the user would type).
    #[error("syntax error: {0}")]
    Syntax(String),
    /// The input is not UTF-8 text.
    #[error("input is not UTF-8 text (byte {0} is not valid UTF-8)")]
    NotUtf8(usize),
    /// The input is larger than the configured limit.
    #[error("input is {size} bytes, more than the limit of {limit} bytes")]
    InputTooLarge {
        /// Size of the input in bytes.
        size: u64,
        /// The limit in force.
        limit: u64,
    },
    /// Brackets, braces or parentheses nest deeper than the limit.
    #[error("nesting is deeper than the limit of {limit} levels")]
    NestingTooDeep {
        /// The limit in force.
        limit: usize,
    },
    /// A `[`, `{` or `(` without its partner, or a closing one without an opener.
    #[error("unbalanced `{0}`")]
    Unbalanced(char),
    /// A problem in a classic L-system file (`.lsys`).
    #[error("{0}")]
    Lsys(String),
    /// A problem in an Outline or Branch-Expansion Description.
    #[error("{0}")]
    Stl(String),
    /// A rule reference names no declared rule.
    #[error("unknown rule `{name}`")]
    UnknownRule {
        /// The name as written.
        name: String,
    },
    /// A term has a different number of slots than its rule has branches.
    #[error("`{rule}` has {expected} branch{}, but this term gives {found} slot{}", plural(*expected, "es"), plural(*found, "s"))]
    SlotCount {
        /// The rule's name.
        rule: String,
        /// Branch count of the rule.
        expected: usize,
        /// Slots written.
        found: usize,
    },
    /// A limit (depth, word length, stems, ...) would be exceeded.
    #[error("{what}: {value} exceeds the limit of {limit}")]
    Limit {
        /// What is limited, in words.
        what: String,
        /// The value asked for (decimal; may be a big integer).
        value: String,
        /// The limit in force.
        limit: String,
    },
    /// Growth (compile) cannot proceed or was cut short.
    #[error("{0}")]
    Grow(String),
    /// Drawing failed or cannot be done as asked.
    #[error("{0}")]
    Render(String),
    /// Reading or writing a file failed.
    #[error("{0}")]
    Io(String),
    /// The reader of our standard output went away (`stlc expand | head`).
    /// The CLI exits quietly on it.
    #[error("broken pipe")]
    BrokenPipe,

    // ------------------------------------------------ syntax: .lsys --

    // --------------------------------------------- syntax: .od / .bed --

    // ----------------------------------------------------- growth --
    /// Growth has nothing to start from: no `SEED` and no rule.
    #[error("nothing to grow: the description has no SEED and no rule")]
    NothingToGrow,
    /// The clearance (`C=` or `--clearance`) is negative or not finite.
    #[error("the clearance must be a finite number >= 0, not {value}")]
    BadClearance {
        /// The clearance asked for.
        value: f64,
    },
    /// The root lies outside the layout region, so nothing can grow.
    #[error("the root ({x}, {y}) lies outside the layout region")]
    RootOutside {
        /// The root's x, as written.
        x: f64,
        /// The root's y, as written.
        y: f64,
    },
    /// A rule reference of the seed names a rule number that is not
    /// declared (a description built by hand; the parser resolves names).
    #[error("rule number {number} is not declared")]
    UndeclaredRule {
        /// The rule's index.
        number: usize,
    },
    /// Growth with nothing to bound it: a growth point without a count whose
    /// rules can branch forever, and no layout, decrement or explicit
    /// `--max-stems`.
    #[error(
        "growth has no bound: `{rule}` can branch forever (through `{through}`), and there is no LAYOUT, no count and no decrement to stop it"
    )]
    UnboundedGrowth {
        /// The rule of the growth point.
        rule: String,
        /// A rule on the endless cycle reachable from it.
        through: String,
    },
    /// Warning: `--max-stems` stopped growth; the BED is cut short.
    #[error(
        "growth stopped at {stems} stems: the next rule application would pass the limit of --max-stems {limit}"
    )]
    GrowthStopped {
        /// Stems grown when growth stopped.
        stems: u64,
        /// The limit in force.
        limit: u64,
    },
    /// Warning: growth reached `--max-depth`; deeper branches were not grown.
    #[error(
        "growth reached the depth limit of {limit} nested rule applications (--max-depth); deeper branches were not grown"
    )]
    DepthCapped {
        /// The limit in force.
        limit: u32,
    },
    /// A layout shape has a coordinate that is not a finite number.
    #[error("a layout shape has a coordinate that is not a finite number")]
    LayoutNotFinite,
    /// The layout's shapes leave no area to grow in.
    #[error(
        "the layout leaves no area to grow in: nothing coloured remains once the white shapes are painted"
    )]
    EmptyRegion,
    // -------------------------------------------------------- BED --

    // ------------------------------------------- interpret / stats --

    // ----------------------------------------------------- render --

    // ------------------------------------------- pipeline and I/O --
}

/// The diagnostic for an I/O error while writing output: a broken pipe gets
/// its own kind so the CLI can exit quietly.
pub fn io_error(e: &std::io::Error, doing: &str) -> Diagnostic {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        Diagnostic::error(ErrorKind::BrokenPipe)
    } else {
        Diagnostic::error(ErrorKind::Io(format!("{doing}: {e}")))
    }
}

fn plural(n: usize, suffix: &str) -> &str {
    if n == 1 { "" } else { suffix }
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
