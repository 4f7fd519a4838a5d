//! Reading the text: its size, encoding, nesting and grammar, the numbers
//! and colours in it, and what kind of file it is. Reported by `syntax`
//! (both formats) and by `pipeline::detect_kind` and `load`.

/// A problem with the input text as text, before any format's meaning.
/// Wrapped in [`super::ErrorKind::Input`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
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
    /// A colour is neither `#rrggbb` nor a known colour name: the value of
    /// a `.lsys` `color` or `background`, or of a layout line.
    #[error("unknown colour `{text}`")]
    UnknownColour {
        /// The colour as written.
        text: String,
    },
    /// A number in a description does not fit a 64-bit float.
    #[error("`{text}` is not a finite number")]
    NotFinite {
        /// The number as written.
        text: String,
    },
    /// The input holds nothing but white space.
    #[error("the file is empty")]
    EmptyInput,
    /// A file's kind cannot be told from its name or its text.
    #[error("cannot tell what kind of file `{name}` is")]
    UnknownInputKind {
        /// The file name as given.
        name: String,
    },
    /// A command was given a kind of input it does not take (`compile` of
    /// an `.lsys`, `stats` of an `.od`).
    #[error("{message}")]
    WrongInputKind {
        /// What the command takes and what it got.
        message: String,
    },
}
