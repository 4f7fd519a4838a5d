//! Classic 0L-systems (the `.lsys` key-value format of 002 section 3.5),
//! rewritten in parallel.

use std::collections::BTreeMap;

use super::Loc;
use crate::color::Rgb;

/// The first heading when a file gives no `heading`: up the canvas, in
/// degrees counter-clockwise from the canvas's right (the turtle's own
/// default, [`crate::turtle::UP`]).
pub const DEFAULT_HEADING: f64 = 90.0;

/// A classic 0L-system, read from a `.lsys` file.
#[derive(Debug, Clone, PartialEq)]
pub struct LSystem {
    /// The start word.
    pub axiom: Vec<char>,
    /// Where the axiom is.
    pub axiom_loc: Loc,
    /// Productions: each symbol's rule, or its stochastic rules (the
    /// alternatives, each with a probability), in the file's order.
    /// Symbols without one stay.
    pub rules: BTreeMap<char, Vec<Production>>,
    /// `generations N`, if given (`--depth` overrides it).
    pub generations: Option<u32>,
    /// `angle DEGREES`.
    pub angle: f64,
    /// `heading DEGREES`: the first heading, counter-clockwise from the
    /// canvas's right (default 90, up the canvas).
    pub heading: f64,
    /// `length L`: step length in canvas units (default 1).
    pub length: f64,
    /// `width W`: stroke width in output pixels (default 1).
    pub width: f64,
    /// `color C`: stroke colour (default black).
    pub color: Option<Rgb>,
    /// `background C`: canvas colour (default white; `none` for transparent).
    pub background: Background,
    /// `seed N`: the seed of stochastic rules (default 0; `--seed`
    /// overrides it). See [`crate::choice`].
    pub seed: u64,
    /// `dimensions N`: 2 (the default) or 3. In a 3D system `& ^ \ /`
    /// pitch and roll the turtle (docs/3d.md); in a 2D one they are
    /// ordinary symbols.
    pub dimensions: u8,
    /// The parametric part (docs/lsys.md, *Parametric systems*): `None`
    /// for a file that uses no parameter, context, condition, `define`,
    /// `ignore`, tropism or `$` (the classic path).
    pub parametric: Option<Box<super::param::Parametric>>,
}

/// One production `X -> successor`, or one alternative of a stochastic rule
/// `X (p) -> successor`.
#[derive(Debug, Clone, PartialEq)]
pub struct Production {
    /// The successor word.
    pub successor: Vec<char>,
    /// The probability of a stochastic rule, `None` for a deterministic one.
    pub probability: Option<f64>,
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

impl LSystem {
    /// The successor of `c`, if it has a rule (the first alternative's,
    /// for a stochastic rule).
    pub fn successor(&self, c: char) -> Option<&[char]> {
        self.rules
            .get(&c)
            .and_then(|p| p.first())
            .map(|p| p.successor.as_slice())
    }

    /// Whether some symbol has stochastic rules (alternatives chosen by
    /// [`LSystem::seed`] and place, [`crate::choice`]).
    pub fn is_stochastic(&self) -> bool {
        self.rules
            .values()
            .any(|ps| ps.iter().any(|p| p.probability.is_some()))
    }

    /// Whether the system is 3D (`dimensions 3`).
    pub fn is_3d(&self) -> bool {
        self.dimensions == 3
    }

    /// Every symbol of the system (axiom, predecessors, successors), sorted.
    pub fn alphabet(&self) -> Vec<char> {
        let mut set: std::collections::BTreeSet<char> = self.axiom.iter().copied().collect();
        for (c, ps) in &self.rules {
            set.insert(*c);
            for p in ps {
                set.extend(p.successor.iter().copied());
            }
        }
        set.into_iter().collect()
    }
}
