//! `.lsys` files: the key-value L-system format of 002 §3.5.
//!
//! ```text
//! # Sierpinski arrowhead
//! generations 6
//! angle 60
//! axiom YF
//! rule X YF+XF+Y
//! rule Y XF-YF-X
//! ```

use std::collections::BTreeMap;

use super::Rule;
use crate::color::Rgb;
use crate::diag::Diagnostics;
use crate::limits::Limits;
use crate::syntax::ast::Loc;

/// A classic 0L-system, read from a `.lsys` file.
#[derive(Debug, Clone, PartialEq)]
pub struct LSystem {
    /// The start word.
    pub axiom: Vec<char>,
    /// Where the axiom is.
    pub axiom_loc: Loc,
    /// Productions: symbol to successor word. Symbols without one stay.
    pub rules: BTreeMap<char, Production>,
    /// `generations N`, if given (`--depth` overrides it).
    pub generations: Option<u32>,
    /// `angle DEGREES`.
    pub angle: f64,
    /// `length L`: step length in canvas units (default 1).
    pub length: f64,
    /// `width W`: stroke width in output pixels (default 1).
    pub width: f64,
    /// `color C`: stroke colour (default black).
    pub color: Option<Rgb>,
    /// `background C`: canvas colour (default white; `none` for transparent).
    pub background: Background,
}

/// One production `X -> successor`.
#[derive(Debug, Clone, PartialEq)]
pub struct Production {
    /// The successor word.
    pub successor: Vec<char>,
    /// Where the `rule` line is.
    pub loc: Loc,
}

/// The canvas colour of a drawing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Background {
    /// White (the default).
    #[default]
    White,
    /// Transparent.
    None,
    /// A colour.
    Color(Rgb),
}

/// Parses a `.lsys` file.
pub fn parse(src: &str, limits: &Limits) -> Result<LSystem, Diagnostics> {
    let _ = (src, limits);
    unimplemented!("issue 2")
}

/// A user-facing description of a grammar rule of the lsys section.
pub fn describe_rule(rule: Rule) -> Option<&'static str> {
    match rule {
        Rule::number => Some("a number"),
        Rule::integer => Some("a whole number"),
        _ => None,
    }
}
