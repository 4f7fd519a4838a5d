//! The alphabet of an L-system as dense ids, and the lengths of its derived
//! words: saturating per level (for limits and progress), exact with big
//! integers (for `exact_lengths` and error messages). The limit checks of
//! `draw` and `expand` are made from them, before any derivation.

use std::collections::BTreeMap;

use num_bigint::BigUint;

use crate::diag::Diagnostics;
use crate::diag::{Help, Knob};
use crate::interpret::Derivation;
use crate::limits::{Bound, Limits};
use crate::model::lsys::LSystem;

/// Most limb additions spent on an exact (big integer) word length for an
/// error message; beyond it the message gives a bound.
pub(super) const EXACT_WORK: u64 = 1 << 28;

/// Progress is reported about every this many symbols.
pub(super) const PROGRESS_STEP: u64 = 1 << 20;

/// The system's symbols as dense ids.
pub(crate) struct Alphabet {
    /// Id to symbol, sorted.
    pub(crate) chars: Vec<char>,
    /// Successor of each symbol, if it has a rule.
    pub(crate) succ: Vec<Option<Vec<u32>>>,
    /// The axiom.
    pub(crate) axiom: Vec<u32>,
    /// The symbols that have a rule (the others keep length 1 at every depth).
    ruled: Vec<u32>,
    /// How often each symbol of `ruled` occurs in the axiom, and how many
    /// axiom symbols have no rule: word lengths are computed from these, not
    /// by walking the axiom once per level.
    axiom_ruled: Vec<u64>,
    axiom_inert: u64,
}

impl Alphabet {
    pub(crate) fn new(sys: &LSystem) -> Self {
        let chars = sys.alphabet();
        let index: BTreeMap<char, u32> = chars
            .iter()
            .enumerate()
            .map(|(i, &c)| (c, i as u32))
            .collect();
        let ids = |w: &[char]| -> Vec<u32> { w.iter().map(|c| index[c]).collect() };
        let succ: Vec<Option<Vec<u32>>> =
            chars.iter().map(|c| sys.successor(*c).map(ids)).collect();
        let ruled: Vec<u32> = (0..chars.len() as u32)
            .filter(|&s| succ[s as usize].is_some())
            .collect();
        let axiom = ids(&sys.axiom);
        let mut axiom_ruled = vec![0u64; ruled.len()];
        let mut axiom_inert = 0u64;
        for &s in &axiom {
            match ruled.binary_search(&s) {
                Ok(i) => axiom_ruled[i] += 1,
                Err(_) => axiom_inert += 1,
            }
        }
        Alphabet {
            succ,
            axiom,
            chars,
            ruled,
            axiom_ruled,
            axiom_inert,
        }
    }

    /// Saturating lengths of the derived word, `W(axiom, r)` for `r` in
    /// `0..=depth`. Memory is O(alphabet), not O(alphabet x depth): level by
    /// level, only symbols with a rule are recomputed, and once a level
    /// equals the one before (saturated or stationary lengths) every later
    /// level is the same, so the rest is filled in at once.
    pub(super) fn word_lengths(&self, depth: u32) -> Vec<u64> {
        let mut len = vec![1u64; self.chars.len()];
        let mut out = Vec::with_capacity(depth as usize + 1);
        out.push(self.word_len(&len));
        let mut next = vec![0u64; self.ruled.len()];
        for _ in 0..depth {
            for (v, &s) in next.iter_mut().zip(&self.ruled) {
                *v = self.succ[s as usize]
                    .iter()
                    .flatten()
                    .fold(0u64, |a, &c| a.saturating_add(len[c as usize]));
            }
            let mut changed = false;
            for (&v, &s) in next.iter().zip(&self.ruled) {
                changed |= len[s as usize] != v;
                len[s as usize] = v;
            }
            let w = self.word_len(&len);
            out.push(w);
            if !changed {
                out.resize(depth as usize + 1, w);
                break;
            }
        }
        out
    }

    /// The saturating word length for the per-symbol lengths `len`.
    fn word_len(&self, len: &[u64]) -> u64 {
        self.ruled
            .iter()
            .zip(&self.axiom_ruled)
            .fold(self.axiom_inert, |a, (&s, &k)| {
                a.saturating_add(len[s as usize].saturating_mul(k))
            })
    }

    /// Refuses depths and words over the limits; returns the saturating
    /// word length of every level `0..=depth`.
    pub(super) fn check(
        &self,
        depth: u32,
        strategy: Derivation,
        limits: &Limits,
    ) -> Result<Vec<u64>, Diagnostics> {
        limits.check_depth(depth)?;
        let lens = self.word_lengths(depth);
        let exact = |r: u32| -> String {
            // Saturated lengths are recomputed exactly for the message.
            let len = lens[r as usize];
            if len < u64::MAX {
                len.to_string()
            } else {
                self.exact_len(r)
            }
        };
        if lens[depth as usize] > limits.max_symbols {
            return Err(Bound::Symbols
                .exceeded_by(
                    format!("derived word length at depth {depth}"),
                    exact(depth),
                    limits.max_symbols,
                )
                .with_help(
                    Help::from("use a smaller depth, or raise the traversal budget with ")
                        + Help::knob(Knob::Limit(Bound::Symbols), "N"),
                )
                .into());
        }
        if strategy == Derivation::Bfs
            && let Some(r) = (0..=depth).find(|&r| lens[r as usize] > limits.max_word)
        {
            return Err(Bound::Word
                .exceeded_by(format!("bfs word at level {r}"), exact(r), limits.max_word)
                .with_help(
                    Help::from("use ")
                        + Help::knob(Knob::Derivation, "dfs")
                        + " (it never holds the word), a smaller depth, or "
                        + Bound::Word,
                )
                .into());
        }
        Ok(lens)
    }

    /// The exact word length at level `r`, in decimal, for a message. Big
    /// integers cost time in proportion to their size: when the work would
    /// exceed [`EXACT_WORK`] limb additions, a bound is given instead.
    fn exact_len(&self, r: u32) -> String {
        let per_level: u64 = self
            .ruled
            .iter()
            .map(|&s| self.succ[s as usize].as_ref().map_or(0, |w| w.len() as u64) + 1)
            .sum::<u64>()
            + self.ruled.len() as u64;
        // Lengths grow by at most log2(longest successor) bits per level.
        let longest = self
            .succ
            .iter()
            .flatten()
            .map(Vec::len)
            .max()
            .unwrap_or(1)
            .max(2);
        let bits = u64::from(r) * u64::from(usize::BITS - longest.leading_zeros());
        let limbs = bits / 64 + 1;
        let work = u64::from(r).saturating_mul(per_level).saturating_mul(limbs);
        if work > EXACT_WORK {
            return format!("more than {}", u64::MAX - 1);
        }
        let mut last = BigUint::default();
        self.exact_each(r, |len| last = len);
        last.to_string()
    }

    /// Exact word lengths `W(axiom, r)` for `r` in `0..=depth`, each handed
    /// to `f` in order; only symbols with a rule are recomputed per level.
    pub(super) fn exact_each(&self, depth: u32, mut f: impl FnMut(BigUint)) {
        let one = BigUint::from(1u32);
        let mut len: Vec<BigUint> = vec![one; self.chars.len()];
        let word = |len: &[BigUint]| -> BigUint {
            let mut w = BigUint::from(self.axiom_inert);
            for (&s, &k) in self.ruled.iter().zip(&self.axiom_ruled) {
                if k > 0 {
                    w += &len[s as usize] * k;
                }
            }
            w
        };
        f(word(&len));
        for _ in 0..depth {
            let next: Vec<BigUint> = self
                .ruled
                .iter()
                .map(|&s| {
                    self.succ[s as usize]
                        .iter()
                        .flatten()
                        .map(|&c| &len[c as usize])
                        .sum()
                })
                .collect();
            for (v, &s) in next.into_iter().zip(&self.ruled) {
                len[s as usize] = v;
            }
            f(word(&len));
        }
    }
}
