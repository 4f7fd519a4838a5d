//! Rules: their names, definitions, alternatives and probabilities, and the
//! references to them (`syntax::stl::rules`, `syntax::lsys`, and the
//! checks of `bed` and `grow::seed` on a description built by hand).

use super::super::number::plural;

/// A problem with a rule, its alternatives or a reference to it.
/// Wrapped in [`super::ErrorKind::Rule`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RuleError {
    /// A rule is given a reserved name: a drawing letter, `I` or a section
    /// keyword.
    #[error("`{name}` is reserved and cannot name a rule")]
    ReservedName {
        /// The name.
        name: String,
    },
    /// A rule name starts with a digit or `_`.
    #[error("rule name `{name}` does not start with a letter")]
    RuleNameNotLetter {
        /// The name.
        name: String,
    },
    /// Two rules have one name.
    #[error("rule `{name}` is defined twice")]
    DuplicateRule {
        /// The name.
        name: String,
    },
    /// A rule definition has no body.
    #[error("syntax error: expected a rule body")]
    MissingBody,
    /// A dot in a rule name where it means nothing: in an OD (dots are
    /// reserved for a BED's alternatives), or `R1.x` with `x` not a number
    /// from 1 in a BED.
    #[error("`{name}` is not a rule name here")]
    DottedName {
        /// The name as written.
        name: String,
    },
    /// A rule with several bodies where one has no probability.
    #[error("`{name}` has several bodies, but not every one has a probability")]
    MissingProbability {
        /// The rule's name.
        name: String,
    },
    /// An alternative's probability is not a finite number above 0.
    #[error("probability {} of an alternative of `{name}` is not a finite number above 0", crate::num::fixed(*value, 9, crate::num::Trim::Zeros))]
    BadProbability {
        /// The rule's name.
        name: String,
        /// The probability written.
        value: f64,
    },
    /// The probabilities of a rule's alternatives do not sum to 1.
    #[error("the probabilities of `{name}`'s alternatives sum to {}, not 1", crate::num::fixed(*sum, 9, crate::num::Trim::Zeros))]
    ProbabilitySum {
        /// The rule's name.
        name: String,
        /// Their sum.
        sum: f64,
    },
    /// A BED names an alternative its rule does not have (`R1.3` of two).
    #[error("`{name}` has no alternative {number}")]
    UnknownAlternative {
        /// The rule's name.
        name: String,
        /// The number written after the dot.
        number: String,
    },
    /// A written-out term names a rule with alternatives but not which one
    /// grew (`R1{,}` where R1 has `R1.1` and `R1.2`).
    #[error("`{name}` has {count} alternatives; a written term names the one that grew")]
    AlternativeNotNamed {
        /// The rule's name.
        name: String,
        /// How many alternatives it has.
        count: usize,
    },
    /// A BED gives a probability to a rule that is not an alternative
    /// (`R1 (0.5): ...` instead of `R1.1 (0.5): ...`).
    #[error("`{name}` has a probability, but a BED's rule without a number is not an alternative")]
    ProbabilityWithoutAlternative {
        /// The rule's name.
        name: String,
    },
    /// A BED repeats a rule with alternatives (`[I 2 R1]` or `[I 2 R1.2]`
    /// where R1 has several bodies): each application would choose, and a
    /// BED records choices instead of making them.
    #[error(
        "`[I n {name}]` would choose among {count} alternatives; a BED writes the terms that grew"
    )]
    RepeatChooses {
        /// The rule's name, without an alternative's number.
        name: String,
        /// How many alternatives it has.
        count: usize,
    },
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
    /// A rule reference of the seed names a rule number that is not
    /// declared (a description built by hand; the parser resolves names).
    #[error("rule number {number} is not declared")]
    UndeclaredRule {
        /// The rule's index.
        number: usize,
    },
}
