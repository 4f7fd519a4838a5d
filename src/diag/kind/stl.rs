//! An `.od` or `.bed` file's header parameters, rule bodies and seed as
//! written (`syntax::stl`).

use super::super::number::plural;

/// A problem with the text of an `.od` or `.bed` (header, body, seed).
/// Wrapped in [`super::ErrorKind::Stl`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StlError {
    /// A header parameter given the wrong kind of value (a colour for `L`,
    /// a number for `S`).
    #[error("`{key}` takes {expected}")]
    ParamValue {
        /// The parameter's key.
        key: &'static str,
        /// What it takes, in words.
        expected: &'static str,
    },
    /// A stem parameter is given twice.
    #[error("`{key}` is given twice")]
    DuplicateParam {
        /// The parameter's name as written.
        key: String,
    },
    /// A stem parameter's name is none of `L`, `B`, `A`, `C`.
    #[error("unknown stem parameter `{key}`")]
    UnknownParam {
        /// The name as written.
        key: String,
    },
    /// The base length `L` or broadness `B` is zero or negative.
    #[error("the stem {what} `{key}` must be positive")]
    StemSizeNotPositive {
        /// `L` or `B`.
        key: &'static str,
        /// `length` or `broadness`.
        what: &'static str,
    },
    /// The decrement of `L` or `B` is negative.
    #[error("the decrement of `{key}` must not be negative")]
    NegativeDecrement {
        /// `L` or `B`.
        key: &'static str,
    },
    /// `A` or `C` is written with a decrement.
    #[error("`{key}` takes no decrement")]
    UnexpectedDecrement {
        /// `A` or `C`.
        key: &'static str,
    },
    /// The clearance `C` is negative.
    #[error("the clearance `C` must not be negative")]
    NegativeClearance,
    /// A BED of a forest has a different number of seeds than roots.
    #[error("{roots} root{} but {seeds} SEED section{}", plural(*roots, "s"), plural(*seeds, "s"))]
    SeedsPerRoot {
        /// Roots on the root line.
        roots: usize,
        /// `SEED ... ENDSEED` sections.
        seeds: usize,
    },
    /// Part of a word that is neither a drawing letter nor a rule name and
    /// does not start with a letter (the `3` of `F3`).
    #[error("unexpected `{text}`")]
    UnexpectedInWord {
        /// The part as written.
        text: String,
    },
    /// `[I 0 X]`.
    #[error("a self-resemblance count must be at least 1")]
    ZeroCount,
    /// `[I n X]` mixes a rule name with drawing components, or names two
    /// rules.
    #[error("`[I n X]` takes one rule name or a string of drawing components")]
    MixedRepeat,
    /// `[I n]` with nothing to repeat.
    #[error("`[I n X]` needs a rule name or drawing components")]
    EmptyRepeat,
    /// `[I n R1]` in a rule body.
    #[error("`[I n X]` with a rule cannot stand in a rule body")]
    RepeatInBody,
    /// `{`, `}` or `,` in a rule body.
    #[error("`{symbol}` cannot stand in a rule body")]
    TermSyntaxInBody {
        /// The symbol.
        symbol: char,
    },
    /// A rule name in a body that does not end a top-level branch.
    #[error("a rule name in a rule body must end a branch")]
    NameNotAtBranchEnd,
    /// A section that is opened and never closed.
    #[error("`{open}` without `{close}`")]
    UnclosedSection {
        /// The keyword that opens it.
        open: &'static str,
        /// The keyword that should close it.
        close: &'static str,
    },
    /// Drawing components in a term's slot.
    #[error("drawing components cannot stand in a slot")]
    DrawingInSlot,
    /// A second term in one slot.
    #[error("a slot holds one term")]
    TwoTermsInSlot,
    /// A `{` that follows no rule name.
    #[error("`{{` must follow a rule name")]
    BraceWithoutRule,
    /// A root of a forest with a different number of coordinates than the
    /// first (section 11: every root alike).
    #[error("this root has {this} coordinates, but the first root has {first}")]
    MixedRoots {
        /// The first root's coordinates (2 or 3).
        first: usize,
        /// This root's.
        this: usize,
    },
    /// Something only a 3D description has (`D=`, a 3D turn `& ^ \ /`)
    /// in a 2D one.
    #[error("{what} needs a 3D root")]
    Needs3d {
        /// What was written, in words (`` `D=` (divergence) ``).
        what: String,
    },
    /// A `,` outside any term.
    #[error("`,` outside a term")]
    CommaOutsideTerm,
    /// `P=X` names a surface the file's `SURFACES` block does not define
    /// (section 13).
    #[error("no surface `{name}` is defined")]
    UnknownSurface {
        /// The name written after `P=`.
        name: String,
    },
}
