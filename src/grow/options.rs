//! The options of one growth ([`GrowOptions`]) and the small pieces every
//! part of the grower shares: the default clearance, the place of a rule in
//! the text. A leaf: it imports nothing else of `grow`, so the grower's
//! parts and `grow/mod.rs` read it without importing each other.

use crate::diag::Span;
use crate::limits::Limits;
use crate::model::{GrowthOrder, Loc, StemParams};

/// What a seed over `--max-stems` by itself is, in the error message.
pub(super) const SEED_STEMS: &str = "stems drawn by the seed alone";

/// The default clearance as a fraction of `L` (the order-0 segment length):
/// `C = L / 10`, so the paper's `L=10` gives `C=1`. A fraction of `L` keeps
/// growth scale-free: scaling root, `L` and layout by a factor scales the
/// grown tree by the same factor, decision for decision.
pub const DEFAULT_CLEARANCE_FRACTION: f64 = 0.1;

/// The clearance used when neither `--clearance` nor `C=` gives one.
pub fn default_clearance(params: &StemParams) -> f64 {
    (params.length.base * DEFAULT_CLEARANCE_FRACTION).max(0.0)
}

/// Options of one growth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrowOptions {
    /// Breadth-first (levels) or depth-first (a branch's subtree before its sibling).
    pub growth: GrowthOrder,
    /// Clearance override (`--clearance`); else `C=` of the OD, else the default.
    pub clearance: Option<f64>,
    /// Limits (`max_stems` among them).
    pub limits: Limits,
    /// Whether `limits.max_stems` was asked for explicitly (`--max-stems N`
    /// on the command line). Only an explicit limit lets growth with no
    /// other bound (no layout, count or decrement) go ahead; the default
    /// limit is a safety net, not a design.
    pub max_stems_explicit: bool,
    /// The seed of stochastic rules (`--seed`, default 0): every choice is
    /// a pure function of it and the growth point's place
    /// ([`crate::choice`]). A description without alternatives grows the
    /// same tree whatever it is.
    pub seed: u64,
}

impl Default for GrowOptions {
    /// Breadth-first (the paper's conventional strategy), no clearance
    /// override, default limits, `--max-stems` not given, seed 0.
    fn default() -> Self {
        GrowOptions {
            growth: GrowthOrder::Bfs,
            clearance: None,
            limits: Limits::default(),
            max_stems_explicit: false,
            seed: 0,
        }
    }
}

/// The span of `loc`, unless it is empty (text made by growth, the default
/// seed).
pub(super) fn span_of(loc: &Loc) -> Option<Span> {
    (loc.0.end > loc.0.start).then(|| loc.0.clone())
}
