//! `stats` of a stochastic L-system: each seed derives another word, so
//! the counts are either *counted*, by deriving this seed's word (when it
//! is at most the traversal budget of [`super::stats`]: `min(--max-symbols,
//! STATS_TRAVERSAL_SYMBOLS)` symbols), or *expected*: the mean over all
//! seeds, from the mean production matrix (row `s`: the symbol counts of
//! each of `s`'s alternatives weighted by its probability), computed with
//! floats at any depth and labelled as expected in text and JSON.
//!
//! Whether the word fits the budget is decided from its shortest and
//! longest possible lengths (each symbol's shortest and longest
//! alternative at every level): at most the budget, it is counted; over
//! the budget even at its shortest, the expected values are given; in
//! between, the traversal runs and gives up at the budget.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use num_bigint::BigUint;

use super::Derivation;
use super::lsys::Stochastic;
use super::stats::{STATS_TRAVERSAL_SYMBOLS, Stats, fixed};
use crate::diag::Diagnostics;
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::progress::NoProgress;
use crate::turtle::Bounds;

/// What `stats` reports of a stochastic system.
#[derive(Debug, Clone, PartialEq)]
pub enum StochasticStats {
    /// This seed's word, counted exactly (with its box and end).
    Counted(Stats),
    /// Over the traversal budget: the mean over all seeds.
    Expected(Expected),
}

/// Expected (mean) counts of a stochastic system's word.
#[derive(Debug, Clone, PartialEq)]
pub struct Expected {
    /// The depth.
    pub depth: u32,
    /// The expected number of symbols (infinite if it overflows a float).
    pub length: f64,
    /// The expected number of `F`.
    pub segments: f64,
    /// The expected count of every symbol of the alphabet.
    pub symbols: BTreeMap<char, f64>,
    /// The shortest and the longest word any seed can derive, exactly.
    pub bounds: (BigUint, BigUint),
}

/// The statistics of stochastic `sys` (its seed in force) at `depth`.
pub fn stochastic_stats(
    sys: &LSystem,
    depth: u32,
    limits: &Limits,
) -> Result<StochasticStats, Diagnostics> {
    limits.check_depth(depth)?;
    let st = Stochastic::new(sys);
    let budget = limits.max_symbols.min(STATS_TRAVERSAL_SYMBOLS);
    if st.length_bounds(depth).0 <= budget {
        let mut capped = *limits;
        capped.max_symbols = budget;
        let mut counts = vec![0u64; st.chars.len()];
        let counted = st.dfs_each(depth, &capped, |s| counts[s as usize] += 1);
        if counted.is_ok() {
            let mut unit = sys.clone();
            unit.length = 1.0;
            let mut b = Bounds::default();
            let end = super::lsys::draw_into(
                &unit,
                depth,
                Derivation::Dfs,
                &capped,
                &mut b,
                &mut NoProgress,
            )?;
            let symbols: BTreeMap<char, BigUint> = st
                .chars
                .iter()
                .zip(&counts)
                .map(|(&c, &n)| (c, BigUint::from(n)))
                .collect();
            let bbox = b
                .bbox()
                .map_or([0.0; 4], |b| [b.min_x, b.min_y, b.max_x, b.max_y]);
            return Ok(StochasticStats::Counted(Stats {
                depth,
                length: BigUint::from(counts.iter().sum::<u64>()),
                segments: symbols.get(&'F').cloned().unwrap_or_default(),
                symbols,
                bbox: Some(bbox),
                end: Some([end.x, end.y]),
                seed: Some(sys.seed),
            }));
        }
    }
    let v = st.expected(depth);
    let symbols: BTreeMap<char, f64> = st.chars.iter().copied().zip(v.iter().copied()).collect();
    Ok(StochasticStats::Expected(Expected {
        depth,
        length: v.iter().sum(),
        segments: symbols.get(&'F').copied().unwrap_or(0.0),
        symbols,
        bounds: st.exact_length_bounds(depth),
    }))
}

/// An expected count: six decimals, or scientific notation from 10^15 on;
/// `null` (JSON) or `overflow` (text) past a float's range.
fn mean(x: f64, json: bool) -> String {
    if !x.is_finite() {
        return if json { "null" } else { "overflow" }.to_string();
    }
    if x.abs() >= 1e15 {
        format!("{x:.6e}")
    } else {
        fixed(x)
    }
}

impl StochasticStats {
    /// [`Stats::to_json`] for a counted word (with its `seed`); for expected
    /// values `{"expected": true, "length": 12.5, ...}` with JSON numbers
    /// (`null` past a float's range), `bbox` and `end` `null`, and the
    /// `bounds` `[shortest, longest]` as decimal strings.
    pub fn to_json(&self) -> String {
        let e = match self {
            StochasticStats::Counted(s) => return s.to_json(),
            StochasticStats::Expected(e) => e,
        };
        let mut out = String::new();
        let _ = write!(
            out,
            "{{\"expected\": true, \"length\": {}, \"segments\": {}, \"bounds\": [\"{}\", \"{}\"], \"bbox\": null, \"end\": null, \"symbols\": {{",
            mean(e.length, true),
            mean(e.segments, true),
            e.bounds.0,
            e.bounds.1
        );
        for (i, (c, n)) in e.symbols.iter().enumerate() {
            let key = serde_json::to_string(&c.to_string()).unwrap_or_default();
            let _ = write!(
                out,
                "{}{key}: {}",
                if i > 0 { ", " } else { "" },
                mean(*n, true)
            );
        }
        out.push_str("}}");
        out
    }

    /// [`Stats::to_text`], or the expected values labelled as such.
    pub fn to_text(&self) -> String {
        let e = match self {
            StochasticStats::Counted(s) => return s.to_text(),
            StochasticStats::Expected(e) => e,
        };
        let mut out = String::new();
        let _ = writeln!(out, "depth     {}", e.depth);
        let _ = writeln!(
            out,
            "expected  (stochastic, over the traversal budget: means over all seeds)"
        );
        let _ = writeln!(out, "length    {} expected", mean(e.length, false));
        let _ = writeln!(out, "          any seed: {} .. {}", e.bounds.0, e.bounds.1);
        let _ = writeln!(out, "segments  {} expected", mean(e.segments, false));
        let _ = writeln!(out, "bbox      (skipped: the word is too long to traverse)");
        let _ = writeln!(out, "end       (skipped)");
        let _ = writeln!(out, "symbols   (expected)");
        for (c, n) in &e.symbols {
            let _ = writeln!(out, "  {c}  {}", mean(*n, false));
        }
        out
    }
}
