//! `stats` of 3D inputs (docs/3d.md, *Stats*): a 3D `.lsys`'s counts with
//! its box and end, and the box and number formats a 3D BED's report
//! (`tree3.rs`) shares.

use std::fmt::Write as _;

use crate::diag::Diagnostics;
use crate::interpret::lsys::ReachMemo;
use crate::interpret::lsys::lsys3::bounds3;
use crate::interpret::stats::{STATS_TRAVERSAL_SYMBOLS, Stats, stats_with_budget};
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::num::{Trim, fixed};
use crate::progress::NoProgress;
use crate::turtle::turtle3::Point3;

/// The 3D box and end of a stats report, or the bound that stands for
/// them past the traversal budget.
enum Geometry3 {
    Traversed {
        bbox: Option<[f64; 6]>,
        end: Point3,
    },
    /// Over the budget: every point is within this many unit steps of the
    /// origin (the reach memo's ball, or the word's `F` and `f` count).
    Bound(f64),
}

/// `stats` of a 3D `.lsys`: the counts of the 2D statistics (exact, or
/// this seed's counted word), and the unit-step turtle's box
/// `[minx, miny, minz, maxx, maxy, maxz]` and end `[x, y, z]`: composed
/// from the reach memo at any depth when the angle and the start heading
/// are multiples of 90 degrees (exact: frames are signed permutations),
/// else by a traversal when the word is at most
/// `min(--max-symbols, STATS_TRAVERSAL_SYMBOLS)` symbols; past that
/// `bbox` and `end` are `null` and `bound` is a cube every point lies in,
/// `[-n, -n, -n, n, n, n]`: `n` the memo's reach (a ball about the start)
/// where it applies, else the number of `F` and `f`.
pub(crate) fn stats3(
    sys: &LSystem,
    depth: u32,
    json: bool,
    limits: &Limits,
) -> Result<String, Diagnostics> {
    let budget = limits.max_symbols.min(STATS_TRAVERSAL_SYMBOLS);
    let mut unit = sys.clone();
    unit.length = 1.0;
    // A stochastic traversal may visit a tenth of its limit (the cost of
    // its choices, interpret::lsys::stochastic); stats counted this word
    // within `budget`, so the traversal gets ten times that.
    let capped = Limits {
        max_symbols: if sys.is_stochastic() {
            budget.saturating_mul(10)
        } else {
            budget
        },
        ..*limits
    };
    let stats = if sys.is_stochastic() {
        match crate::interpret::expected::stochastic_stats(sys, depth, limits)? {
            crate::interpret::expected::StochasticStats::Counted(s) => s,
            e => {
                return Ok(if json { e.to_json() } else { e.to_text() });
            }
        }
    } else {
        stats_with_budget(sys, depth, limits, 0)?
    };
    let fits = u64::try_from(&stats.length).is_ok_and(|l| l <= budget);
    // The reach memo (deterministic systems with balanced successors):
    // exact where frames stay signed permutations, else a tighter bound.
    let memo = if sys.is_stochastic() {
        None
    } else {
        ReachMemo::new(&unit, depth, 1.0).ok()
    };
    let geo = match &memo {
        Some(m) if m.ortho => {
            let whole = m.whole();
            Geometry3::Traversed {
                bbox: whole.bbox.filter(|_| whole.draws()),
                end: Point3::new(whole.end[0], whole.end[1], whole.end[2]),
            }
        }
        _ if fits => {
            let (bbox, end, _) = bounds3(&unit, depth, &capped, &mut NoProgress)?;
            Geometry3::Traversed { bbox, end }
        }
        Some(m) => Geometry3::Bound(m.whole().radius),
        None => {
            let steps = ['F', 'f']
                .iter()
                .filter_map(|c| stats.symbols.get(c))
                .map(|n| n.to_string().parse::<f64>().unwrap_or(f64::INFINITY))
                .sum();
            Geometry3::Bound(steps)
        }
    };
    Ok(if json {
        json3(&stats, &geo)
    } else {
        text3(&stats, &geo)
    })
}

pub(super) fn num(x: f64) -> String {
    fixed(x, crate::interpret::stats::DECIMALS, Trim::Keep)
}

/// A box `[minx, miny, minz, maxx, maxy, maxz]` as `stats` writes it in
/// text: `x a .. b, y c .. d, z e .. f`.
pub(super) fn box_text(b: &[f64; 6]) -> String {
    format!(
        "x {} .. {}, y {} .. {}, z {} .. {}",
        num(b[0]),
        num(b[3]),
        num(b[1]),
        num(b[4]),
        num(b[2]),
        num(b[5])
    )
}

pub(super) fn list(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|&x| num(x)).collect();
    format!("[{}]", parts.join(", "))
}

fn json3(s: &Stats, geo: &Geometry3) -> String {
    let mut out = String::from("{");
    if let Some(seed) = s.seed {
        let _ = write!(out, "\"seed\": {seed}, ");
    }
    let _ = write!(
        out,
        "\"dimensions\": 3, \"length\": \"{}\", \"segments\": \"{}\", ",
        s.length, s.segments
    );
    match geo {
        Geometry3::Traversed { bbox, end } => {
            let _ = write!(
                out,
                "\"bbox\": {}, \"end\": {}, ",
                list(&bbox.unwrap_or([0.0; 6])),
                list(&end.to_array())
            );
        }
        Geometry3::Bound(n) => {
            let _ = write!(
                out,
                "\"bbox\": null, \"end\": null, \"bound\": {}, ",
                list(&[-n, -n, -n, *n, *n, *n])
            );
        }
    }
    out.push_str("\"symbols\": {");
    for (i, (c, n)) in s.symbols.iter().enumerate() {
        let key = serde_json::to_string(&c.to_string()).unwrap_or_default();
        let _ = write!(out, "{}{key}: \"{n}\"", if i > 0 { ", " } else { "" });
    }
    out.push_str("}}");
    out
}

fn text3(s: &Stats, geo: &Geometry3) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "depth     {} (3D)", s.depth);
    if let Some(seed) = s.seed {
        let _ = writeln!(
            out,
            "seed      {seed} (stochastic: the counts of this seed's word)"
        );
    }
    let _ = writeln!(out, "length    {}", s.length);
    let _ = writeln!(out, "segments  {}", s.segments);
    match geo {
        Geometry3::Traversed { bbox, end } => {
            let b = bbox.unwrap_or([0.0; 6]);
            let _ = writeln!(
                out,
                "bbox      {} (unit steps, y down, z away)",
                box_text(&b)
            );
            let _ = writeln!(
                out,
                "end       ({}, {}, {})",
                num(end.x),
                num(end.y),
                num(end.z)
            );
        }
        Geometry3::Bound(n) => {
            let _ = writeln!(
                out,
                "bbox      (not traversed: the word is too long) within {} unit steps of the start on every axis",
                num(*n)
            );
            let _ = writeln!(out, "end       (not traversed)");
        }
    }
    let _ = writeln!(out, "symbols");
    for (c, n) in &s.symbols {
        let _ = writeln!(out, "  {c}  {n}");
    }
    out
}
