//! Seeded choices keyed by place: how stochastic rules pick a successor.
//!
//! A stochastic rule (`rule F (0.34) -> ...` in an `.lsys`, `R1 (0.6): ...`
//! in an `.od`) picks one of its alternatives at every place it applies. The
//! pick is a pure function of the seed and that place's *path* in the
//! derivation tree, never of the order places are visited in, so:
//!
//! - depth-first and breadth-first derivations make the same choices and
//!   derive the same word;
//! - a subtree's choices do not change when something elsewhere changes;
//! - the same seed gives the same bytes, on every machine.
//!
//! # The function
//!
//! A place's [`Key`] is a 64-bit value:
//!
//! - the root of a derivation (an `.lsys` axiom, one tree of a forest) has
//!   `Key::root(seed)`;
//! - the child at index `i` of the place with key `k` has
//!   `k.child(i)` = `mix(k + (i + 1) * GAMMA)`: the `(i + 1)`-th output of a
//!   SplitMix64 generator whose state is `k` (Steele, Lea and Flood,
//!   *Fast splittable pseudorandom number generators*, OOPSLA 2014).
//!   `GAMMA` is SplitMix64's golden-ratio increment and `mix` its finaliser
//!   (David Stafford's "Mix13" variant of the MurmurHash3 finaliser).
//! - the place picks with `k.unit()`, the top 53 bits of `mix(k)` as a
//!   number in `[0, 1)`: the first alternative whose cumulative probability
//!   exceeds it ([`Alternatives::pick`]).
//!
//! SplitMix64 is written here rather than taken from a crate on purpose:
//! these eight lines decide every byte of a stochastic BED, so they must
//! never change with a dependency's version (general-purpose generators such
//! as `rand`'s `StdRng` explicitly do not promise a stable stream).

/// SplitMix64's increment: `2^64 / φ`, odd.
const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output function (Stafford's Mix13): a bijection of `u64`
/// with full avalanche.
#[inline]
const fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The key of a place in a derivation tree (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Key(pub u64);

impl Key {
    /// The key of a derivation's root under `seed`.
    #[inline]
    pub const fn root(seed: u64) -> Key {
        Key(mix(seed.wrapping_add(GAMMA)))
    }

    /// The key of this place's child at `index` (0-based).
    #[inline]
    pub const fn child(self, index: u64) -> Key {
        Key(mix(self
            .0
            .wrapping_add(index.wrapping_add(1).wrapping_mul(GAMMA))))
    }

    /// The number in `[0, 1)` this place picks with: 53 bits, so every
    /// value is an exact `f64`.
    #[inline]
    pub fn unit(self) -> f64 {
        (mix(self.0) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// How far a rule's probabilities may sum from 1.
pub const SUM_TOLERANCE: f64 = 1e-6;

/// Why a set of probabilities cannot be used.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BadProbabilities {
    /// The probability at this index is not a finite number > 0.
    NotPositive(usize),
    /// They do not sum to 1 within [`SUM_TOLERANCE`]; the sum.
    Sum(f64),
}

/// The alternatives of one stochastic rule, as a cumulative table.
#[derive(Debug, Clone, PartialEq)]
pub struct Alternatives {
    /// `cumulative[i]`: the sum of the first `i + 1` probabilities, divided
    /// by their total (so the last is exactly 1).
    cumulative: Vec<f64>,
}

impl Alternatives {
    /// The table of `probabilities`, in written order: each must be > 0 and
    /// they must sum to 1 within [`SUM_TOLERANCE`].
    pub fn new(probabilities: &[f64]) -> Result<Alternatives, BadProbabilities> {
        check(probabilities)?;
        let total: f64 = probabilities.iter().sum();
        let mut acc = 0.0;
        let mut cumulative: Vec<f64> = probabilities
            .iter()
            .map(|p| {
                acc += p;
                acc / total
            })
            .collect();
        if let Some(last) = cumulative.last_mut() {
            *last = 1.0;
        }
        Ok(Alternatives { cumulative })
    }

    /// How many alternatives there are.
    pub fn len(&self) -> usize {
        self.cumulative.len()
    }

    /// Whether there are none (never, for a table [`Alternatives::new`]
    /// accepted with at least one probability).
    pub fn is_empty(&self) -> bool {
        self.cumulative.is_empty()
    }

    /// The (normalised) probability of alternative `i`, 0 past the end.
    pub fn probability(&self, i: usize) -> f64 {
        let below = if i == 0 {
            0.0
        } else {
            self.cumulative.get(i - 1).copied().unwrap_or(1.0)
        };
        self.cumulative.get(i).map_or(0.0, |c| c - below)
    }

    /// The alternative (0-based) the place with `key` picks.
    #[inline]
    pub fn pick(&self, key: Key) -> usize {
        let u = key.unit();
        // `u < 1 = cumulative.last()`, so the search always lands inside.
        self.cumulative
            .partition_point(|&c| c <= u)
            .min(self.cumulative.len().saturating_sub(1))
    }
}

/// Checks `probabilities`: each a finite number > 0, summing to 1 within
/// [`SUM_TOLERANCE`].
pub fn check(probabilities: &[f64]) -> Result<(), BadProbabilities> {
    if let Some(i) = probabilities
        .iter()
        .position(|p| !(p.is_finite() && *p > 0.0))
    {
        return Err(BadProbabilities::NotPositive(i));
    }
    let sum: f64 = probabilities.iter().sum();
    if (sum - 1.0).abs() > SUM_TOLERANCE {
        return Err(BadProbabilities::Sum(sum));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SplitMix64's published first outputs for state 0 (the reference
    /// implementation's `next()` adds GAMMA, then mixes).
    #[test]
    fn mix_is_splitmix64() {
        let mut state: u64 = 0;
        let mut next = || {
            state = state.wrapping_add(GAMMA);
            mix(state)
        };
        assert_eq!(next(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(next(), 0x6E78_9E6A_A1B9_65F4);
        assert_eq!(next(), 0x06C4_5D18_8009_454F);
        // `child(i)` is output i + 1 of the generator whose state is the key.
        assert_eq!(Key(0).child(0).0, 0xE220_A839_7B1D_CDAF);
        assert_eq!(Key(0).child(2).0, 0x06C4_5D18_8009_454F);
    }

    #[test]
    fn probabilities_are_checked() {
        assert!(check(&[0.34, 0.33, 0.33]).is_ok());
        assert!(check(&[1.0]).is_ok());
        assert_eq!(
            check(&[0.5, 0.0, 0.5]),
            Err(BadProbabilities::NotPositive(1))
        );
        assert_eq!(check(&[0.5, -0.1]), Err(BadProbabilities::NotPositive(1)));
        assert_eq!(check(&[f64::NAN]), Err(BadProbabilities::NotPositive(0)));
        match check(&[0.5, 0.4]) {
            Err(BadProbabilities::Sum(s)) => assert!((s - 0.9).abs() < 1e-12),
            other => panic!("{other:?}"),
        }
        // Within the tolerance: accepted.
        assert!(check(&[0.3333333, 0.3333333, 0.3333334]).is_ok());
    }

    /// Over 300,000 sibling places the picks follow the probabilities: each
    /// count within 4 standard deviations of its expectation (a binomial
    /// bound a correct generator fails about once in 16,000 runs; the keys
    /// are fixed, so this test is deterministic).
    #[test]
    fn picks_follow_the_probabilities() {
        let probs = [0.6, 0.3, 0.1];
        let alts = Alternatives::new(&probs).unwrap();
        let n = 300_000u64;
        let parent = Key::root(7);
        let mut counts = [0u64; 3];
        for i in 0..n {
            counts[alts.pick(parent.child(i))] += 1;
        }
        for (c, p) in counts.iter().zip(probs) {
            let mean = n as f64 * p;
            let sd = (n as f64 * p * (1.0 - p)).sqrt();
            assert!(
                (*c as f64 - mean).abs() < 4.0 * sd,
                "{counts:?} against {probs:?}"
            );
        }
    }

    /// Chi-square of picks along *paths* (children of children), the shape
    /// a derivation has: 3 alternatives, 2 degrees of freedom; 13.8 is the
    /// 0.999 quantile.
    #[test]
    fn picks_along_paths_are_uniform() {
        let alts = Alternatives::new(&[1.0 / 3.0; 3]).unwrap();
        let mut counts = [0u64; 3];
        let root = Key::root(0);
        for a in 0..60u64 {
            for b in 0..50u64 {
                for c in 0..10u64 {
                    counts[alts.pick(root.child(a).child(b).child(c))] += 1;
                }
            }
        }
        let n = counts.iter().sum::<u64>() as f64;
        let chi2: f64 = counts
            .iter()
            .map(|&c| (c as f64 - n / 3.0).powi(2) / (n / 3.0))
            .sum();
        assert!(chi2 < 13.8, "{counts:?}: chi2 {chi2}");
    }

    #[test]
    fn keys_depend_on_the_whole_path() {
        let r = Key::root(1);
        assert_ne!(r.child(0).child(1), r.child(1).child(0));
        assert_ne!(Key::root(1), Key::root(2));
        assert_ne!(r.child(0), r);
        let u = r.child(3).unit();
        assert!((0.0..1.0).contains(&u));
    }

    #[test]
    fn the_last_alternative_takes_the_top() {
        let alts = Alternatives::new(&[0.5, 0.5]).unwrap();
        assert_eq!(alts.len(), 2);
        // Scan many keys: every pick is in range.
        assert!((0..10_000).all(|i| alts.pick(Key(i)) < 2));
    }
}
