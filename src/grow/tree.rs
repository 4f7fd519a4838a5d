//! What growth records: the grown tree (every successful application and
//! what grew in its slots) and the budget it spends against the limits.

use crate::diag::{Diagnostic, GrowError};
use crate::diag::{Help, Knob};
use crate::limits::Bound;
use crate::model::RuleId;

/// Where a decision is recorded.
#[derive(Debug, Clone, Copy)]
pub(super) enum Parent {
    /// Growth point number `i` of the seed.
    Seed(u32),
    /// Entry `i` of [`Tree::slot_child`].
    Slot(u32),
}

/// A successful application.
#[derive(Debug, Clone, Copy)]
pub(super) struct Node {
    /// The rule applied.
    pub(super) rule: RuleId,
    /// First of its entries in [`Tree::slot_child`], one per branch.
    pub(super) slots: u32,
}

/// No node: nothing grew there.
pub(super) const NO_NODE: u32 = u32::MAX;

/// The grown tree: every successful application, and what grew in each of
/// its slots and at each growth point of the seed. A child is always
/// recorded after its parent.
#[derive(Debug, Default)]
pub(super) struct Tree {
    /// The applications, in the order they succeeded.
    pub(super) nodes: Vec<Node>,
    /// For each slot of each node, the node grown there or [`NO_NODE`].
    pub(super) slot_child: Vec<u32>,
    /// The node grown at each growth point of the seed, or [`NO_NODE`]:
    /// in a forest, tree `t`'s points are entries `t * gps ..`.
    pub(super) seed_result: Vec<u32>,
    /// How many trees (roots) grew.
    pub(super) trees: usize,
}

impl Tree {
    /// Records an application of `rule` (with `branches` slots) at
    /// `parent`; returns the index of its first slot in `slot_child`.
    pub(super) fn record(&mut self, rule: RuleId, branches: usize, parent: Parent) -> u32 {
        let id = self.nodes.len() as u32;
        let first = self.slot_child.len() as u32;
        self.nodes.push(Node { rule, slots: first });
        self.slot_child
            .extend(std::iter::repeat_n(NO_NODE, branches));
        match parent {
            Parent::Seed(i) => self.seed_result[i as usize] = id,
            Parent::Slot(i) => self.slot_child[i as usize] = id,
        }
        first
    }
}

/// What growth has spent against its limits, and the warnings of the
/// limits that cut it short.
#[derive(Debug, Default)]
pub(super) struct Budget {
    /// Stems drawn so far, the seed's included.
    pub(super) stems: u64,
    /// Stems drawn by the seed alone.
    pub(super) seed_stems: u64,
    /// Successful rule applications (limited like stems, so rules that
    /// draw nothing still end).
    pub(super) applications: u64,
    /// `--max-stems` stopped all growth.
    pub(super) stopped: bool,
    /// `--max-depth` refused an application (warned once).
    pub(super) depth_capped: bool,
    /// Stems at the last progress report, in units of 2^14.
    pub(super) reported: u64,
    /// The warnings, in the order they arose.
    pub(super) warnings: Vec<Diagnostic>,
}

impl Budget {
    /// Stops all growth at `--max-stems` or the file's `M=` (once, with a
    /// warning that names the one in force: `design` is the file's `M=`).
    pub(super) fn stop(&mut self, max_stems: u64, design: Option<u64>) {
        if self.stopped {
            return;
        }
        self.stopped = true;
        let warning = if design == Some(max_stems) {
            Diagnostic::warning(GrowError::DesignStemCount {
                stems: self.stems,
                limit: max_stems,
            })
            .with_help(
                "the file's M= caps its stems (a part of its design); raise or remove M= in the header to grow more",
            )
        } else {
            Diagnostic::warning(GrowError::GrowthStopped {
                stems: self.stems,
                limit: max_stems,
            })
            .with_help(Help::from("the BED is valid but its tree is cut short; ") + Bound::Stems)
        };
        self.warnings.push(warning);
    }

    /// Notes that `--max-depth` refused an application (warned once).
    pub(super) fn cap_depth(&mut self, max_depth: u32) {
        if self.depth_capped {
            return;
        }
        self.depth_capped = true;
        self.warnings.push(
            Diagnostic::warning(GrowError::DepthCapped { limit: max_depth }).with_help(
                Help::from("raise it with ") + Help::knob(Knob::Limit(Bound::Depth), "N"),
            ),
        );
    }
}
