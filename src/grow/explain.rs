//! Growth explains itself: for every rule (every alternative on its own),
//! how often it was tried, how often it fitted, why the tries that failed
//! failed (counted by [`MissReason`]), and the first failure with its
//! numbers ([`Misfit`]). A rule tried and never fitted is a warning that
//! says why and what to change; `stlc check` lists the counts.
//!
//! Counting costs two increments a try; the numbers of a failure (which
//! stem, the distance found) are worked out only for a rule's first.

use super::span_of;
use crate::diag::{Diagnostic, GrowError, Misfit, MissReason};
use crate::model::Description;

/// What growth did with one rule: the tries, the fits, the misses by
/// reason, and the first miss with its numbers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RuleTally {
    /// Growth points decided with this rule (with alternatives: those that
    /// chose it).
    pub tries: u64,
    /// Tries that fitted and grew.
    pub fits: u64,
    /// Failed tries by the first test each failed, by [`MissReason::index`].
    pub misses: [u64; MissReason::COUNT],
    /// Why the first failed try failed.
    pub first_miss: Option<Misfit>,
}

impl RuleTally {
    /// The reason most failed tries failed for, and how many (the first in
    /// [`MissReason::ALL`] order on a tie); `None` if none failed.
    pub fn most_common(&self) -> Option<(MissReason, u64)> {
        MissReason::ALL
            .iter()
            .map(|&r| (r, self.misses[r.index()]))
            .filter(|&(_, n)| n > 0)
            .fold(None, |best: Option<(MissReason, u64)>, (r, n)| match best {
                Some((_, m)) if m >= n => best,
                _ => Some((r, n)),
            })
    }

    /// Tried, and never fitted.
    pub fn never_fitted(&self) -> bool {
        self.tries > 0 && self.fits == 0
    }

    /// Counts a failed try; `misfit` works out the numbers, asked only for
    /// the first.
    pub(super) fn miss(&mut self, reason: MissReason, misfit: impl FnOnce() -> Misfit) {
        self.misses[reason.index()] += 1;
        if self.first_miss.is_none() {
            self.first_miss = Some(misfit());
        }
    }
}

/// A warning for every rule of `od` tried and never fitted, in rule order,
/// pointing at the rule, with the first failure's reason and numbers and a
/// hint. A limit that stopped the first try (`--max-depth`,
/// `--max-stems`) has its own warning already.
pub(super) fn never_fitted(od: &Description, tallies: &[RuleTally]) -> Vec<Diagnostic> {
    od.rules
        .iter()
        .zip(tallies)
        .filter(|(_, t)| t.never_fitted())
        .filter_map(|(rule, t)| {
            let why = t.first_miss?;
            if why.reason().is_limit() {
                return None;
            }
            let mut d = Diagnostic::warning(GrowError::NeverFitted {
                rule: rule.full_name().into_owned(),
                tries: t.tries,
                why,
            })
            .with_help(why.hint());
            if let Some(s) = span_of(&rule.loc) {
                d = d.with_span(s).with_label("this rule never grew");
            }
            Some(d)
        })
        .collect()
}
