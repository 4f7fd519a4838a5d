//! The grower: an Outline Description into a Branch-Expansion Description
//! under space occupancy, breadth-first or depth-first.

pub mod occupancy;
pub mod region;

use crate::diag::{Diagnostic, Diagnostics};
use crate::interpret::Strategy;
use crate::limits::Limits;
use crate::progress::Progress;
use crate::syntax::ast::Description;

/// Options of one growth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrowOptions {
    /// Breadth-first (levels) or depth-first (a branch's subtree before its sibling).
    pub strategy: Strategy,
    /// Clearance override (`--clearance`); else `C=` of the OD, else the default.
    pub clearance: Option<f64>,
    /// Limits (`max_stems` among them).
    pub limits: Limits,
}

/// The result of growth: the BED and any warnings (a limit that stopped growth).
#[derive(Debug, Clone, PartialEq)]
pub struct Grown {
    /// The Branch-Expansion Description.
    pub bed: Description,
    /// Warnings, e.g. `--max-stems` reached.
    pub warnings: Vec<Diagnostic>,
    /// Number of stems (segments) in the grown tree.
    pub stems: u64,
}

/// Grows `od` into a BED.
pub fn grow(
    od: &Description,
    opts: &GrowOptions,
    progress: &mut dyn Progress,
) -> Result<Grown, Diagnostics> {
    let _ = (od, opts, progress);
    unimplemented!("issue 4")
}
