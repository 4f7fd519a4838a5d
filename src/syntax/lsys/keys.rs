//! The keys of a `.lsys` file: one table of spellings, one enum.

use super::super::Rule;

/// The keys a `.lsys` file may use, in the order the docs list them:
/// the one spelling of each [`Key`] (indexed by `Key as usize`).
/// `grammar.pest` spells them again in its `lsys_*` rules, as pest must.
pub const KEYS: &[&str] = &[
    "generations",
    "axiom",
    "rule",
    "angle",
    "heading",
    "length",
    "width",
    "color",
    "background",
    "seed",
    "dimensions",
];

/// A key of a `.lsys` file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Key {
    /// `generations N`: the default derivation depth.
    Generations,
    /// `axiom WORD`: the start word.
    Axiom,
    /// `rule X SUCCESSOR`: one production.
    Rule,
    /// `angle DEGREES`: the turn of `+` and `-`.
    Angle,
    /// `heading DEGREES`: the turtle's first direction.
    Heading,
    /// `length L`: the step of `F` and `f`.
    Length,
    /// `width W`: the line width.
    Width,
    /// `color C`: the line colour.
    Color,
    /// `background C`: the background colour or `none`.
    Background,
    /// `seed N`: the seed of stochastic rules.
    Seed,
    /// `dimensions N`: 2 (the default) or 3 (docs/3d.md).
    Dimensions,
}

impl Key {
    /// Every key, in the order of [`KEYS`].
    pub const ALL: [Key; 11] = [
        Key::Generations,
        Key::Axiom,
        Key::Rule,
        Key::Angle,
        Key::Heading,
        Key::Length,
        Key::Width,
        Key::Color,
        Key::Background,
        Key::Seed,
        Key::Dimensions,
    ];

    /// The key as written in a file.
    pub fn name(self) -> &'static str {
        KEYS[self as usize]
    }

    /// A line that gives the key, for hints.
    pub(super) fn example(self) -> &'static str {
        match self {
            Key::Generations => "`generations 5`",
            Key::Axiom => "`axiom F`",
            Key::Rule => "`rule F F+F`",
            Key::Angle => "`angle 25.7`",
            Key::Heading => "`heading 0`",
            Key::Length => "`length 1`",
            Key::Width => "`width 1.5`",
            Key::Color => "`color clGreen`",
            Key::Background => "`background none`",
            Key::Seed => "`seed 7`",
            Key::Dimensions => "`dimensions 3`",
        }
    }

    /// The grammar rule of a line with this key.
    pub(super) fn rule(self) -> Rule {
        match self {
            Key::Generations => Rule::lsys_generations,
            Key::Axiom => Rule::lsys_axiom,
            Key::Rule => Rule::lsys_rule,
            Key::Angle => Rule::lsys_angle,
            Key::Heading => Rule::lsys_heading,
            Key::Length => Rule::lsys_length,
            Key::Width => Rule::lsys_width,
            Key::Color => Rule::lsys_color,
            Key::Background => Rule::lsys_background,
            Key::Seed => Rule::lsys_seed,
            Key::Dimensions => Rule::lsys_dimensions,
        }
    }

    /// The key whose line `rule` reads, if any.
    pub(super) fn of_rule(rule: Rule) -> Option<Key> {
        Key::ALL.into_iter().find(|k| k.rule() == rule)
    }
}

/// The value of `dimensions`: 2 or 3; anything else is an error that says
/// what each means. `integer`: whether the text read as a whole number.
pub(super) fn dimensions(
    text: &str,
    span: crate::diag::Span,
    integer: bool,
) -> Result<u8, Box<crate::diag::Diagnostic>> {
    use crate::diag::{Diagnostic, LsysError};
    match text.parse::<u8>() {
        Ok(n @ (2 | 3)) if integer => Ok(n),
        _ => Err(Box::new(
            Diagnostic::error(LsysError::BadDimensions {
                text: text.to_string(),
            })
            .with_span(span)
            .with_label("not 2 or 3")
            .with_help(
                "write `dimensions 3` for a 3D system (`& ^ \\ /` pitch and roll the \
                 turtle), or leave the line out for a flat one (2, the default)",
            ),
        )),
    }
}
