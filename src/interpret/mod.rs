//! Interpretation: from a derivation (classic L-system or BED) to turtle
//! operations, and from operations to segments.
//!
//! A derivation denotes one word of drawing components. Two strategies
//! produce it: [`Derivation::Dfs`] expands depth-first with an explicit
//! stack, never holding the expanded word (000's method);
//! [`Derivation::Bfs`] rewrites the whole word level by level and then
//! interprets it (Saupe's method, the baseline). Both draw bit-identical
//! segments, in the same order:
//!
//! - for a BED, both issue the same stream of [`Op`]s into the same
//!   [`Interp`];
//! - for an L-system, `bfs` feeds [`Interp`] one [`Op`] per symbol, while
//!   `dfs` runs merged operations (runs counted, turns summed, empty and
//!   leaf branches folded) through its own executor, which computes every
//!   position with [`Interp`]'s expression.
//!
//! - [`lsys`]: derivation of classic L-systems (`draw`, `expand`,
//!   `exact_lengths`).
//! - [`bed`]: expansion of Branch-Expansion Descriptions (`draw`, `expand`,
//!   `ops`).
//! - [`bed3`]: a 3D BED (three-coordinate roots) drawn with the 3D turtle.
//! - [`stats`]: exact word statistics of classic L-systems.
//!
//! [`Op`]: crate::turtle::Op
//! [`Interp`]: crate::turtle::Interp

pub mod bed;
pub mod bed3;
pub mod dress;
pub mod expected;
pub mod lsys;
pub mod stats;

/// How a derivation is produced (`--strategy`): the same picture at a
/// different cost. The default is depth-first, which streams. The
/// variants' doc comments are the help of `--strategy`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Derivation {
    /// Depth-first: streams the derivation, memory grows with depth only.
    #[default]
    Dfs,
    /// Breadth-first: rewrites the whole word level by level, then draws it
    /// (the baseline; same picture, more memory).
    Bfs,
}
