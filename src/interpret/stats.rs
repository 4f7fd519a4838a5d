//! Exact word statistics of classic L-systems with big integers.
//!
//! The count of each symbol in `W(axiom, depth)` follows from the counts one
//! level up: `count(s, r)[c]` is the sum of `count(x, r - 1)[c]` over the
//! successor of `s`. [`stats`] computes it level by level for the word (the
//! memo of every `(symbol, depth)` folded into one count vector per level),
//! so `F -> F[+F]F[-F]F` at depth 57 costs 57 x 6 big-integer additions.
//!
//! The geometric part (`bbox`, `end`) comes from the memoized geometry
//! (`interpret::lsys::measure`: net move, turn and box per `(symbol,
//! depth, heading)`, composed, no traversal; depth 57 of `F -> F[+F]F[-F]F`
//! in well under a millisecond) whenever it applies within its budget
//! (`lsys::GEOMETRY_ENTRIES` pieces). When it does not (a successor with
//! unbalanced brackets, too many headings), a traversal (the `dfs` fast
//! path, unit step) runs if the word has at most `min(limits.max_symbols,
//! STATS_TRAVERSAL_SYMBOLS)` symbols: `stats` is meant to answer at once,
//! and 2^30 symbols take about 2 to 4 seconds; beyond that `bbox` and `end`
//! are `None` (`null` in JSON).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use num_bigint::BigUint;

use crate::diag::Diagnostics;
use crate::interpret::Derivation;
use crate::interpret::lsys::{Alphabet, draw_into};
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::progress::NoProgress;
use crate::turtle::Bounds;

/// Most symbols the geometric pass of [`stats`] traverses (2^30, a few
/// seconds), unless `limits.max_symbols` is smaller.
pub const STATS_TRAVERSAL_SYMBOLS: u64 = 1 << 30;

/// What [`stats`] finds out about a derived word.
#[derive(Debug, Clone, PartialEq)]
pub struct Stats {
    /// The depth the word was derived to.
    pub depth: u32,
    /// Number of symbols.
    pub length: BigUint,
    /// Number of `F`: the segments a drawing has.
    pub segments: BigUint,
    /// Count of every symbol of the system's alphabet (zeros included).
    pub symbols: BTreeMap<char, BigUint>,
    /// `[min_x, min_y, max_x, max_y]` of the drawn segments of a unit-step
    /// turtle from the origin, canvas coordinates (y down, heading up). The
    /// origin itself if nothing is drawn. `None` if neither the memoized
    /// geometry nor a traversal within the budget could give it.
    pub bbox: Option<[f64; 4]>,
    /// Where that turtle ends, `None` when `bbox` is.
    pub end: Option<[f64; 2]>,
    /// For a stochastic system, the seed its word was derived with (the
    /// counts are this seed's); `None` for a deterministic one.
    pub seed: Option<u64>,
}

/// Statistics of `sys` derived to `depth`: exact length and symbol counts,
/// and the unit-step turtle's box and end when the word is at most
/// `min(limits.max_symbols, STATS_TRAVERSAL_SYMBOLS)` symbols long.
pub fn stats(sys: &LSystem, depth: u32, limits: &Limits) -> Result<Stats, Diagnostics> {
    stats_with_budget(
        sys,
        depth,
        limits,
        limits.max_symbols.min(STATS_TRAVERSAL_SYMBOLS),
    )
}

/// [`stats`] with an explicit traversal budget (in symbols) for the
/// geometric pass when the memoized geometry does not apply; 0 skips the
/// geometric part altogether (memo included).
pub fn stats_with_budget(
    sys: &LSystem,
    depth: u32,
    limits: &Limits,
    budget: u64,
) -> Result<Stats, Diagnostics> {
    limits.check_depth(depth)?;
    if let Some(p) = crate::interpret::lsys::param::of(sys) {
        return param_stats(sys, p, depth, limits, budget);
    }
    let alpha = Alphabet::new(sys);
    let n = alpha.chars.len();
    // Sparse substitution matrix: for each symbol, (child, multiplicity).
    let matrix: Vec<Vec<(usize, u32)>> = (0..n)
        .map(|s| match &alpha.succ[s] {
            Some(succ) => {
                let mut m: BTreeMap<usize, u32> = BTreeMap::new();
                for &c in succ {
                    *m.entry(c as usize).or_default() += 1;
                }
                m.into_iter().collect()
            }
            None => vec![(s, 1)],
        })
        .collect();
    let mut counts: Vec<BigUint> = vec![BigUint::default(); n];
    for &s in &alpha.axiom {
        counts[s as usize] += 1u32;
    }
    for _ in 0..depth {
        let mut next: Vec<BigUint> = vec![BigUint::default(); n];
        for (s, row) in matrix.iter().enumerate() {
            if counts[s].bits() == 0 {
                continue;
            }
            for &(c, m) in row {
                if m == 1 {
                    next[c] += &counts[s];
                } else {
                    next[c] += &counts[s] * m;
                }
            }
        }
        counts = next;
    }
    let length: BigUint = counts.iter().sum();
    let symbols: BTreeMap<char, BigUint> = alpha.chars.iter().copied().zip(counts).collect();
    let segments = symbols.get(&'F').cloned().unwrap_or_default();

    let fits = u64::try_from(&length).is_ok_and(|l| l <= budget);
    let memo = if budget > 0 {
        crate::interpret::lsys::measure(sys, depth, 1.0).ok()
    } else {
        None
    };
    let (bbox, end) = if let Some(m) = memo {
        let bbox = match m.bbox {
            Some(b) => [b.min_x, b.min_y, b.max_x, b.max_y],
            None => [0.0; 4],
        };
        (Some(bbox), Some([m.end.x, m.end.y]))
    } else if fits {
        let mut unit = sys.clone();
        unit.length = 1.0;
        let mut bounds = Bounds::default();
        let end = draw_into(
            &unit,
            depth,
            Derivation::Dfs,
            limits,
            &mut bounds,
            &mut NoProgress,
        )?;
        let bbox = match bounds.bbox() {
            Some(b) => [b.min_x, b.min_y, b.max_x, b.max_y],
            None => [0.0; 4],
        };
        (Some(bbox), Some([end.x, end.y]))
    } else {
        (None, None)
    };
    Ok(Stats {
        depth,
        length,
        segments,
        symbols,
        bbox,
        end,
        seed: None,
    })
}

/// [`stats_with_budget`] of a parametric system: its modules counted as
/// it is derived (length, `F` and `G` steps, each symbol), and with a
/// budget, the unit-step turtle's box and end from the same derivation.
fn param_stats(
    sys: &LSystem,
    p: &crate::model::param::Parametric,
    depth: u32,
    limits: &Limits,
    budget: u64,
) -> Result<Stats, Diagnostics> {
    use crate::interpret::lsys::param::Deriver;
    let mut counts: BTreeMap<char, u64> = BTreeMap::new();
    let count = |c: char, counts: &mut BTreeMap<char, u64>| *counts.entry(c).or_default() += 1;
    let (mut bbox, mut end) = (None, None);
    if budget > 0 {
        let mut unit = sys.clone();
        unit.length = 1.0;
        let mut bounds = Bounds::default();
        let at = crate::interpret::lsys::param::draw2(
            &unit,
            p,
            depth,
            Derivation::Dfs,
            limits,
            &mut bounds,
        )?;
        bbox = Some(match bounds.bbox() {
            Some(b) => [b.min_x, b.min_y, b.max_x, b.max_y],
            None => [0.0; 4],
        });
        end = Some([at.x, at.y]);
    }
    Deriver::new(sys, p).each(depth, Derivation::Dfs, limits, |c, _| count(c, &mut counts))?;
    let length: u64 = counts.values().sum();
    let segments = counts.get(&'F').copied().unwrap_or(0) + counts.get(&'G').copied().unwrap_or(0);
    Ok(Stats {
        depth,
        length: length.into(),
        segments: segments.into(),
        symbols: counts.into_iter().map(|(c, n)| (c, n.into())).collect(),
        bbox,
        end,
        seed: p.is_stochastic().then_some(sys.seed),
    })
}

/// Decimals of floats in [`Stats::to_json`] and [`Stats::to_text`].
pub const DECIMALS: usize = 6;

/// A float with [`DECIMALS`] decimals, `-0.000000` written as `0.000000`.
pub(crate) fn fixed(x: f64) -> String {
    crate::num::fixed(x, DECIMALS, crate::num::Trim::Keep)
}

fn floats(xs: &[f64]) -> String {
    let parts: Vec<String> = xs.iter().map(|&x| fixed(x)).collect();
    format!("[{}]", parts.join(", "))
}

impl Stats {
    /// JSON with keys `length`, `segments`, `bbox`, `end`, `symbols`: exact
    /// integers as decimal strings, floats with six decimals, `null` for a
    /// skipped traversal, symbols sorted. One line, no trailing newline.
    pub fn to_json(&self) -> String {
        let mut out = String::new();
        if let Some(seed) = self.seed {
            let _ = write!(out, "{{\"seed\": {seed}, ");
        } else {
            out.push('{');
        }
        let _ = write!(
            out,
            "\"length\": \"{}\", \"segments\": \"{}\", \"bbox\": {}, \"end\": {}, \"symbols\": {{",
            self.length,
            self.segments,
            self.bbox.map_or("null".into(), |b| floats(&b)),
            self.end.map_or("null".into(), |e| floats(&e)),
        );
        for (i, (c, n)) in self.symbols.iter().enumerate() {
            let key = serde_json::to_string(&c.to_string()).unwrap_or_default();
            let _ = write!(out, "{}{key}: \"{n}\"", if i > 0 { ", " } else { "" });
        }
        out.push_str("}}");
        out
    }

    /// A few aligned lines for people.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "depth     {}", self.depth);
        if let Some(seed) = self.seed {
            let _ = writeln!(
                out,
                "seed      {seed} (stochastic: the counts of this seed's word)"
            );
        }
        let _ = writeln!(out, "length    {}", self.length);
        let _ = writeln!(out, "segments  {}", self.segments);
        match self.bbox {
            Some(b) => {
                let _ = writeln!(
                    out,
                    "bbox      x {} .. {}, y {} .. {} (unit steps, y down)",
                    fixed(b[0]),
                    fixed(b[2]),
                    fixed(b[1]),
                    fixed(b[3])
                );
            }
            None => {
                let _ = writeln!(out, "bbox      (skipped: the word is too long to traverse)");
            }
        }
        match self.end {
            Some(e) => {
                let _ = writeln!(out, "end       ({}, {})", fixed(e[0]), fixed(e[1]));
            }
            None => {
                let _ = writeln!(out, "end       (skipped)");
            }
        }
        let _ = writeln!(out, "symbols");
        for (c, n) in &self.symbols {
            let _ = writeln!(out, "  {c}  {n}");
        }
        out
    }
}
