//! Stochastic L-systems: a symbol's rule is chosen at every occurrence,
//! by the seed and the occurrence's place in the derivation tree.
//!
//! The word is `W(s, k, r)` for a symbol `s` with key `k` and `r` rewriting
//! steps left: `s` itself if `r = 0` or `s` has no rule; otherwise, with
//! `succ` the successor of the rule chosen for `k` (`Alternatives::pick`,
//! [`crate::choice`]), the concatenation of `W(succ[j], k.child(j), r - 1)`
//! over `j`. The axiom's `i`-th symbol has key `Key::root(seed).child(i)`
//! (the axiom is the successor of a root with key `Key::root(seed)`). A
//! choice so depends only on the seed and the path of successor positions
//! from the axiom, never on the order of the traversal: `dfs` (an explicit
//! stack of frames, memory O(depth)) and `bfs` (the word of `(symbol,
//! key)` pairs, rewritten level by level) derive the same word, and a
//! subtree's choices do not change when something elsewhere does.
//!
//! Deterministic symbols of a stochastic system keep their one rule; their
//! successors' keys are derived all the same. A system without stochastic
//! rules never comes here: its word does not depend on any key, and the
//! compiled and memoized paths of [`super`] derive it.
//!
//! Word lengths are not known before the traversal (each run chooses), so
//! the limits are enforced while deriving: the traversal stops with an
//! error when it passes `limits.max_symbols`, `bfs` when a level passes its
//! word budget. A depth whose *shortest* possible word (each symbol's
//! shortest alternative, [`Stochastic::length_bounds`]) is already over
//! the limit is refused before any symbol is derived. The renderer fits the picture with a bounding traversal
//! first, so a refusal comes before any output is written.

use num_bigint::BigUint;

use crate::choice::{Alternatives, Key};
use crate::diag::{Diagnostics, ErrorKind, saturated};
use crate::diag::{Help, Knob};
use crate::limits::{Bound, Limits};
use crate::model::lsys::LSystem;

use super::alphabet::{Alphabet, EXACT_WORK};

/// Bytes `bfs` holds per symbol of a stochastic word (the symbol and its
/// key), against one for a deterministic word: its word budget is
/// `limits.max_word / BFS_BYTES_PER_SYMBOL` symbols, the same memory.
pub const BFS_BYTES_PER_SYMBOL: u64 = 16;

/// One symbol's rules as dense successor words.
struct Rules {
    /// The alternatives' successors (one for a deterministic rule).
    succ: Vec<Vec<u32>>,
    /// The probabilities, for a stochastic rule.
    table: Option<Alternatives>,
}

/// A stochastic system over the dense ids of an [`Alphabet`].
pub(crate) struct Stochastic {
    /// By symbol id: its rules, if it has any.
    rules: Vec<Option<Rules>>,
    /// The axiom.
    pub(crate) axiom: Vec<u32>,
    /// `Key::root(seed)`: the axiom's symbols are its children.
    root: Key,
    /// Id to symbol.
    pub(crate) chars: Vec<char>,
}

/// One level of the `dfs` stack: a successor being walked.
struct Frame<'a> {
    succ: &'a [u32],
    next: usize,
    key: Key,
    /// Rewriting steps left for the symbols of `succ`.
    left: u32,
}

impl Stochastic {
    /// The system `sys` with its seed.
    pub(crate) fn new(sys: &LSystem) -> Self {
        let alpha = Alphabet::new(sys);
        let id = |c: &char| {
            alpha
                .chars
                .binary_search(c)
                .expect("the alphabet holds every symbol") as u32
        };
        let rules = alpha
            .chars
            .iter()
            .map(|c| {
                let ps = sys.rules.get(c)?;
                let succ: Vec<Vec<u32>> = ps
                    .iter()
                    .map(|p| p.successor.iter().map(id).collect())
                    .collect();
                let p: Vec<f64> = ps.iter().filter_map(|p| p.probability).collect();
                // The parser checked the probabilities; a system made in
                // code with bad ones takes its first rule.
                let table = (!p.is_empty()).then(|| {
                    Alternatives::new(&p)
                        .unwrap_or_else(|_| Alternatives::new(&[1.0]).expect("one certain choice"))
                });
                Some(Rules { succ, table })
            })
            .collect();
        Stochastic {
            rules,
            axiom: alpha.axiom,
            root: Key::root(sys.seed),
            chars: alpha.chars,
        }
    }

    /// The successor of symbol `s` at key `k`, if `s` has a rule.
    fn successor(&self, s: u32, k: Key) -> Option<&[u32]> {
        let r = self.rules[s as usize].as_ref()?;
        Some(&r.succ[self.choose(s, k)?])
    }

    /// Which alternative of symbol `s`'s rule the place with key `k`
    /// takes, if `s` has a rule (0 for a deterministic one).
    #[inline]
    pub(crate) fn choose(&self, s: u32, k: Key) -> Option<usize> {
        let r = self.rules[s as usize].as_ref()?;
        Some(
            r.table
                .as_ref()
                .map_or(0, |t| t.pick(k).min(r.succ.len() - 1)),
        )
    }

    /// Symbol `s`'s alternatives as `(probability, successor)`, empty
    /// when it has no rule.
    pub(crate) fn alternatives(&self, s: u32) -> Vec<(f64, &[u32])> {
        let Some(r) = self.rules[s as usize].as_ref() else {
            return Vec::new();
        };
        r.succ
            .iter()
            .enumerate()
            .map(|(i, w)| {
                let p = r.table.as_ref().map_or(1.0, |t| t.probability(i));
                (p, w.as_slice())
            })
            .collect()
    }

    /// `Key::root(seed)`: the axiom's symbols are its children.
    pub(crate) fn root(&self) -> Key {
        self.root
    }

    /// Calls `f` with every symbol of the word at `depth`, in order, by an
    /// explicit stack (memory O(depth)). Refuses, having emitted
    /// `limits.max_symbols` symbols, a word longer than that. Returns the
    /// word's length.
    pub(crate) fn dfs_each(
        &self,
        depth: u32,
        limits: &Limits,
        mut f: impl FnMut(u32),
    ) -> Result<u64, Diagnostics> {
        self.check_shortest(
            depth,
            Bound::Symbols,
            limits.max_symbols,
            "derived word length",
        )?;
        let mut count = 0u64;
        let mut stack = vec![Frame {
            succ: &self.axiom,
            next: 0,
            key: self.root,
            left: depth,
        }];
        while let Some(top) = stack.last_mut() {
            let Some(&s) = top.succ.get(top.next) else {
                stack.pop();
                continue;
            };
            let k = top.key.child(top.next as u64);
            top.next += 1;
            let left = top.left;
            match (left > 0).then(|| self.successor(s, k)).flatten() {
                Some(succ) => stack.push(Frame {
                    succ,
                    next: 0,
                    key: k,
                    left: left - 1,
                }),
                None => {
                    count += 1;
                    if count > limits.max_symbols {
                        return Err(over(
                            depth,
                            Bound::Symbols,
                            "derived word length",
                            limits.max_symbols,
                        ));
                    }
                    f(s);
                }
            }
        }
        Ok(count)
    }

    /// Calls `f` with every symbol of the word at `depth`, in order, after
    /// rewriting the whole word level by level (Saupe's method with keys).
    /// Refuses a level over `limits.max_word / BFS_BYTES_PER_SYMBOL`
    /// symbols, or a word over `limits.max_symbols`, before emitting.
    pub(crate) fn bfs_each(
        &self,
        depth: u32,
        limits: &Limits,
        mut f: impl FnMut(u32),
    ) -> Result<u64, Diagnostics> {
        let word = limits.max_word / BFS_BYTES_PER_SYMBOL;
        let (bound, budget) = if word <= limits.max_symbols {
            (Bound::Word, word)
        } else {
            (Bound::Symbols, limits.max_symbols)
        };
        self.check_shortest(depth, bound, budget, "bfs word (symbols and keys)")?;
        let mut word: Vec<(u32, Key)> = self
            .axiom
            .iter()
            .enumerate()
            .map(|(i, &s)| (s, self.root.child(i as u64)))
            .collect();
        for level in 1..=depth {
            let mut next = Vec::with_capacity(word.len());
            for &(s, k) in &word {
                match self.successor(s, k) {
                    Some(succ) => next.extend(
                        succ.iter()
                            .enumerate()
                            .map(|(j, &c)| (c, k.child(j as u64))),
                    ),
                    None => next.push((s, k)),
                }
                if next.len() as u64 > budget {
                    return Err(over(level, bound, "bfs word (symbols and keys)", budget));
                }
            }
            word = next;
        }
        for &(s, _) in &word {
            f(s);
        }
        Ok(word.len() as u64)
    }

    /// The expected count of every symbol (by id) in the word at `depth`:
    /// the axiom's counts times the mean production matrix `depth` times
    /// (row `s`: each alternative's symbol counts weighted by its
    /// probability; a symbol without a rule maps to itself). Floats; they
    /// may overflow to infinity at great depths.
    pub(crate) fn expected(&self, depth: u32) -> Vec<f64> {
        let n = self.chars.len();
        let rows: Vec<Vec<(usize, f64)>> = (0..n)
            .map(|s| match &self.rules[s] {
                None => vec![(s, 1.0)],
                Some(r) => {
                    let weights: Vec<f64> = match &r.table {
                        Some(t) => (0..r.succ.len()).map(|i| t.probability(i)).collect(),
                        None => vec![1.0],
                    };
                    let mut row = vec![0.0; n];
                    for (succ, w) in r.succ.iter().zip(weights) {
                        for &c in succ {
                            row[c as usize] += w;
                        }
                    }
                    row.into_iter()
                        .enumerate()
                        .filter(|(_, v)| *v != 0.0)
                        .collect()
                }
            })
            .collect();
        let mut v = vec![0.0; n];
        for &s in &self.axiom {
            v[s as usize] += 1.0;
        }
        for _ in 0..depth {
            let mut next = vec![0.0; n];
            for (s, row) in rows.iter().enumerate() {
                if v[s] == 0.0 {
                    continue;
                }
                for &(c, m) in row {
                    next[c] += v[s] * m;
                }
            }
            v = next;
        }
        v
    }

    /// Refuses at once a depth whose shortest possible word (whatever the
    /// choices) is over `limit`: the traversal would only stop there after
    /// deriving `limit` symbols.
    pub(crate) fn check_shortest(
        &self,
        depth: u32,
        bound: Bound,
        limit: u64,
        what: &str,
    ) -> Result<(), Diagnostics> {
        let (least, _) = self.length_bounds(depth);
        if least <= limit {
            return Ok(());
        }
        let value = if least < u64::MAX {
            format!("at least {least}")
        } else if self.exact_work(depth) <= EXACT_WORK {
            format!("at least {}", self.exact_length_bounds(depth).0)
        } else {
            saturated(least)
        };
        Err(bound
            .exceeded_by(
                format!("{what} at depth {depth} (stochastic: the shortest any choices make)"),
                value,
                limit,
            )
            .with_help(raise_help())
            .into())
    }

    /// The fewest and the most symbols the word at `depth` can have,
    /// saturating at `u64::MAX` (for the limit checks and the progress bar).
    pub(crate) fn length_bounds(&self, depth: u32) -> (u64, u64) {
        self.bounds_with(depth, |_| 1, |a: u64, b| a.saturating_add(*b))
    }

    /// The fewest and the most segments (`F`s) the word at `depth` can
    /// draw, saturating: an SVG the fewest already overflow is refused
    /// before any derivation.
    pub(crate) fn segment_bounds(&self, depth: u32) -> (u64, u64) {
        let f = self.chars.iter().position(|&c| c == 'F');
        self.bounds_with(
            depth,
            |s| u8::from(Some(s) == f),
            |a: u64, b| a.saturating_add(*b),
        )
    }

    /// [`Self::length_bounds`] exactly, in big integers (for `stats`). The
    /// cost grows with the depth times the numbers' size, as the exact
    /// counts of a deterministic system do.
    pub(crate) fn exact_length_bounds(&self, depth: u32) -> (BigUint, BigUint) {
        self.bounds_with(depth, |_| 1, |a: BigUint, b| a + b)
    }

    /// Limb additions [`Self::exact_length_bounds`] costs at `depth`, about:
    /// every alternative's symbols once per level, on numbers that grow by
    /// at most log2 of the longest successor in bits per level.
    fn exact_work(&self, depth: u32) -> u64 {
        let succs = || self.rules.iter().flatten().flat_map(|r| &r.succ);
        let per_level = succs().map(|w| w.len() as u64 + 1).sum::<u64>();
        let longest = succs().map(Vec::len).max().unwrap_or(1).max(2);
        let bits = u64::from(depth) * u64::from(usize::BITS - longest.leading_zeros());
        u64::from(depth)
            .saturating_mul(per_level)
            .saturating_mul(bits / 64 + 1)
    }

    /// The fewest and the most symbols at `depth`, level by level: a symbol
    /// with a rule has its shortest (longest) alternative's length at the
    /// level below, summed with `add`; without, length 1. Stops early once
    /// a level equals the one before (saturated or stationary lengths).
    fn bounds_with<T: Clone + Ord + Default + From<u8>>(
        &self,
        depth: u32,
        weight: impl Fn(usize) -> u8,
        add: impl Fn(T, &T) -> T,
    ) -> (T, T) {
        let n = self.chars.len();
        let sum = |len: &[T], w: &[u32]| {
            w.iter()
                .fold(T::default(), |a, &c| add(a, &len[c as usize]))
        };
        let step = |len: &[T], pick: fn(T, T) -> T| -> Vec<T> {
            (0..n)
                .map(|s| match &self.rules[s] {
                    None => T::from(weight(s)),
                    Some(r) => r
                        .succ
                        .iter()
                        .map(|w| sum(len, w))
                        .reduce(pick)
                        .unwrap_or_default(),
                })
                .collect()
        };
        let mut lo: Vec<T> = (0..n).map(|s| T::from(weight(s))).collect();
        let mut hi = lo.clone();
        for _ in 0..depth {
            let (l, h) = (step(&lo, Ord::min), step(&hi, Ord::max));
            if l == lo && h == hi {
                break;
            }
            lo = l;
            hi = h;
        }
        (sum(&lo, &self.axiom), sum(&hi, &self.axiom))
    }
}

/// The error of a stochastic traversal over a limit.
fn over(level: u32, bound: Bound, what: &str, limit: u64) -> Diagnostics {
    bound
        .exceeded_by(
            format!("{what} at depth {level} (stochastic: counted while deriving)"),
            format!("more than {limit}"),
            limit,
        )
        .with_help(raise_help())
        .into()
}

/// The hint of a stochastic traversal over a limit: either limit may be
/// the one that stopped it.
/// What a stochastic symbol costs against `--max-symbols`: a key hashed,
/// a choice drawn, a frame pushed, and every symbol through the plain
/// interpreter (no compiled program, no memo), about ten symbols of the
/// compiled dfs's (measured: 37 M symbols/s against 500 M). A drawing or
/// expansion of a stochastic system may visit a tenth of the limit, so the
/// limit means about the same time for both (docs/limits.md).
pub(crate) const STOCHASTIC_COST: u64 = 10;

/// The limits of a stochastic drawing or expansion: a tenth of
/// `max_symbols` ([`STOCHASTIC_COST`]).
pub(crate) fn budget(limits: &Limits) -> Limits {
    Limits {
        max_symbols: (limits.max_symbols / STOCHASTIC_COST).max(1),
        ..*limits
    }
}

/// A refusal at the stochastic budget says why the limit is a tenth of
/// `--max-symbols`.
pub(crate) fn explain_budget(mut d: Diagnostics, limits: &Limits) -> Diagnostics {
    for x in &mut d.0 {
        if let ErrorKind::Limit {
            bound: Bound::Symbols,
            ..
        } = x.kind
        {
            x.help = Some(
                Help::from("a stochastic system may visit a tenth of ")
                    + Help::knob(Knob::Limit(Bound::Symbols), "")
                    + format!(
                        " ({} of {}): each of its symbols costs about ten of a deterministic \
                         one's; use a smaller depth, or ",
                        budget(limits).max_symbols,
                        limits.max_symbols,
                    )
                    + Bound::Symbols,
            );
        }
    }
    d
}

fn raise_help() -> Help {
    Help::from("use a smaller depth, or ")
        + Bound::Symbols
        + " ("
        + Help::knob(Knob::Limit(Bound::Word), Bound::Word.value_name())
        + " for bfs)"
}
