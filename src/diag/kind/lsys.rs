//! An `.lsys` file: its keys, its rules, its numbers (`syntax::lsys`), and
//! what `pipeline` finds about it before deriving.

/// A problem with an `.lsys` file.
/// Wrapped in [`super::ErrorKind::Lsys`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LsysError {
    /// A `.lsys` line starts with no key of the format.
    #[error("unknown key `{key}`")]
    UnknownKey {
        /// The key as written.
        key: String,
    },
    /// A single-valued `.lsys` key is given on a second line.
    #[error("`{key}` is given twice")]
    DuplicateKey {
        /// The key.
        key: &'static str,
    },
    /// A `.lsys` file lacks a key it needs (`axiom`, `angle`).
    #[error("missing `{key}`")]
    MissingKey {
        /// The key.
        key: &'static str,
    },
    /// A `.lsys` rule's predecessor is more than one symbol.
    #[error("a rule rewrites one symbol, but `{predecessor}` is {symbols} symbols")]
    LongPredecessor {
        /// The predecessor as written.
        predecessor: String,
        /// Its number of symbols.
        symbols: usize,
    },
    /// Two `.lsys` rules rewrite the same symbol.
    #[error("two rules for `{symbol}`")]
    DuplicateProduction {
        /// The symbol both rewrite.
        symbol: char,
    },
    /// A `.lsys` key that takes a whole number is given something else.
    #[error("`{key}` takes a whole number, not `{text}`")]
    NotWholeNumber {
        /// The key.
        key: &'static str,
        /// The value as written.
        text: String,
    },
    /// A `.lsys` number value does not read as a number.
    #[error("malformed number `{text}`")]
    MalformedNumber {
        /// The value as written.
        text: String,
    },
    /// A `.lsys` number value does not fit a 64-bit float.
    #[error("`{key}` {text} is too large")]
    NumberTooLarge {
        /// The key.
        key: &'static str,
        /// The value as written.
        text: String,
    },
    /// A `.lsys` value that must be positive is zero or negative.
    #[error("`{key}` must be greater than 0, not {text}")]
    NotPositive {
        /// The key.
        key: &'static str,
        /// The value as written.
        text: String,
    },
    /// A `.lsys` rule has a parenthesis where a probability goes that does
    /// not hold a decimal number (`rule F (1/3) -> ...`, `(50%)`): read as
    /// it stands it would be part of the successor.
    #[error("`{text}` is not a probability")]
    UnreadableProbability {
        /// The parenthesis as written.
        text: String,
    },
    /// `dimensions` is neither 2 nor 3.
    #[error("`dimensions` is 2 or 3, not `{text}`")]
    BadDimensions {
        /// The value as written.
        text: String,
    },
    /// A parametric `.lsys` (docs/lsys.md): an expression, a module or a
    /// rule that cannot be read or evaluated; the message says which.
    #[error("{message}")]
    Param {
        /// What is wrong, with the text at fault.
        message: String,
    },
    /// An L-system has no `generations` and no `--depth` was given.
    #[error("no derivation depth")]
    NoDepth,
    /// An `.lsys` uses `L` or `R`, which do not turn there (a warning).
    #[error(
        "`{symbol}` does not turn in an .lsys file: it is an ordinary symbol there, and no rule rewrites it"
    )]
    InertTurn {
        /// `L` or `R`.
        symbol: char,
    },
}
