//! Interpretation: from a derivation (classic L-system or BED) to turtle
//! operations, and from operations to segments.
//!
//! A derivation denotes one stream of [`Op`](crate::turtle::Op)s. Two strategies produce it:
//! [`Derivation::Dfs`] expands depth-first straight into the turtle with an
//! explicit stack, never holding the expanded word (000's method);
//! [`Derivation::Bfs`] rewrites the whole word level by level and then
//! interprets it (Saupe's method, the baseline). Both feed the same
//! [`Interp`](crate::turtle::Interp), so they draw bit-identical segments.
//!
//! - [`lsys`]: derivation of classic L-systems, `expand` and `stats`.
//! - [`bed`]: expansion of Branch-Expansion Descriptions.

pub mod bed;
pub mod lsys;
pub mod stats;

/// How a derivation is produced (`--strategy`): the same picture at a
/// different cost. The default is depth-first, which streams.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Derivation {
    /// Depth-first streaming: memory grows with nesting depth only.
    #[default]
    Dfs,
    /// Breadth-first string rewriting, then interpretation (the baseline).
    Bfs,
}
