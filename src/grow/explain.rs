//! Growth explains itself: for every rule (every alternative on its own),
//! how often it was tried, how often it fitted, why the tries that failed
//! failed (counted by [`MissReason`]), and the first failure with its
//! numbers ([`Misfit`]). A rule tried and never fitted is a warning that
//! says why and what to change; `stlc check` lists the counts.
//!
//! Counting costs two increments a try; the numbers of a failure (which
//! stem, the distance found) are worked out only for a rule's first.

use super::occupancy::{Cap, Dim, clearance_distance};
use super::options::span_of;
use crate::diag::{Diagnostic, GrowError, Kin, Misfit, MissReason};
use crate::limits::Limits;
use crate::model::{Description, StemParams};

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
    /// Space-first growth: the attraction points that belonged to this
    /// rule's growth points when they were decided (summed over tries).
    pub claimed: u64,
    /// Space-first growth: the attraction points this rule's stems killed.
    pub killed: u64,
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

/// Which stem `other` is to the new stem `new`, as the joint exception of
/// the clearance test sees them: one starting where it starts is a
/// sibling, one ending where it starts its parent.
pub(super) fn kin<const N: usize>(new: &Cap<N>, other: &Cap<N>) -> Kin {
    if new.a == other.a {
        Kin::Sibling
    } else if new.a == other.b {
        Kin::Parent
    } else {
        Kin::Other
    }
}

/// What a failed try leaves for explaining it: the stem that failed
/// (numbered from 1) and, if it came too close to a stem, the two stems
/// (the new one first) and whether the other is one of the try's own.
#[derive(Debug, Clone, Copy)]
pub(super) struct LastMiss<const N: usize> {
    stem: u32,
    clash: Option<(Cap<N>, Cap<N>, bool)>,
}

impl<const N: usize> Default for LastMiss<N> {
    fn default() -> Self {
        LastMiss {
            stem: 0,
            clash: None,
        }
    }
}

impl<const N: usize> LastMiss<N>
where
    Cap<N>: Dim,
{
    /// The try failed at its stem number `drawn + 1` (after `drawn` fitted).
    pub(super) fn at(drawn: usize, clash: Option<(Cap<N>, Cap<N>, bool)>) -> Self {
        LastMiss {
            stem: u32::try_from(drawn).unwrap_or(u32::MAX).saturating_add(1),
            clash,
        }
    }

    /// The numbers of a miss for `reason` of a try at `order`; `position`
    /// finds one of the try's own stems among them (0 for the first).
    pub(super) fn misfit(
        &self,
        reason: MissReason,
        order: u32,
        params: &StemParams,
        limits: &Limits,
        clearance: f64,
        position: impl FnOnce(&Cap<N>) -> Option<usize>,
    ) -> Misfit {
        match reason {
            MissReason::Outside => Misfit::Outside { stem: self.stem },
            MissReason::TooClose(kin) => {
                let Some((t, s, own)) = self.clash else {
                    return Misfit::Outside { stem: self.stem };
                };
                let other = if own { position(&s) } else { None };
                Misfit::TooClose {
                    stem: self.stem,
                    kin,
                    other: other.map(|i| u32::try_from(i).unwrap_or(u32::MAX).saturating_add(1)),
                    found: clearance_distance(&t, &s),
                    needed: clearance + t.r + s.r,
                    clearance,
                }
            }
            MissReason::TooShort => Misfit::TooShort {
                order,
                length: params.length.at(order),
            },
            MissReason::TooThin => Misfit::TooThin {
                order,
                width: params.width.at(order),
            },
            MissReason::Depth => Misfit::Depth {
                limit: limits.max_depth,
            },
            MissReason::StemLimit => Misfit::StemLimit {
                limit: limits.max_stems,
            },
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

/// A warning for every rule of `od` that grew and then ran out: most of
/// its failed tries failed because its stems' width or length reached zero
/// (the reasons `stlc check` gives), so growth stopped there and not at
/// the layout's edges; `stems`: the stems grown in all.
pub(super) fn ran_out(od: &Description, tallies: &[RuleTally], stems: u64) -> Vec<Diagnostic> {
    od.rules
        .iter()
        .zip(tallies)
        .filter(|(_, t)| t.fits > 0)
        .filter_map(|(rule, t)| {
            let (reason, count) = t.most_common()?;
            let hint = match reason {
                MissReason::TooThin => Misfit::TooThin {
                    order: 0,
                    width: 0.0,
                }
                .hint(),
                MissReason::TooShort => Misfit::TooShort {
                    order: 0,
                    length: 0.0,
                }
                .hint(),
                _ => return None,
            };
            let mut d = Diagnostic::warning(GrowError::RanOut {
                stems,
                rule: rule.full_name().into_owned(),
                reason,
                count,
                misses: t.tries - t.fits,
            })
            .with_help(hint);
            if let Some(s) = span_of(&rule.loc) {
                d = d.with_span(s).with_label("this rule ran out here");
            }
            Some(d)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Kin;

    #[test]
    fn the_most_common_reason_wins_and_ties_go_to_the_first() {
        let mut t = RuleTally::default();
        assert_eq!(t.most_common(), None);
        t.tries = 6;
        t.fits = 1;
        t.miss(MissReason::Outside, || Misfit::Outside { stem: 2 });
        t.miss(MissReason::TooClose(Kin::Other), || unreachable!());
        t.miss(MissReason::TooClose(Kin::Other), || unreachable!());
        assert_eq!(t.most_common(), Some((MissReason::TooClose(Kin::Other), 2)));
        t.miss(MissReason::Outside, || unreachable!());
        t.miss(MissReason::TooShort, || unreachable!());
        // Outside and Other 2 each: Outside comes first.
        assert_eq!(t.most_common(), Some((MissReason::Outside, 2)));
        // Only the first miss's numbers are kept.
        assert_eq!(t.first_miss, Some(Misfit::Outside { stem: 2 }));
        assert!(!t.never_fitted());
        for (i, r) in MissReason::ALL.iter().enumerate() {
            assert_eq!(r.index(), i);
        }
    }
}
