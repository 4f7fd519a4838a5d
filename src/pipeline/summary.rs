//! Summaries without drawing: `stats` (exact counts of an L-system) and
//! `check` (would compile and render succeed?).

use std::fmt::Write as _;

use super::{Command, Loaded, grow, inert_turns, lsys_depth, wrong_kind};
use crate::bed::Bed;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind};
use crate::grow::GrowOptions;
use crate::grow::explain::RuleTally;
use crate::interpret::Derivation;
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::model::{Description, Format, SeedItem};

/// Exact word lengths and counts of an L-system (`stlc stats`), as text or
/// JSON. Any other input is refused.
pub fn stats(
    loaded: &Loaded,
    depth: Option<u32>,
    json: bool,
    limits: &Limits,
) -> Result<String, Diagnostics> {
    if let Loaded::Bed(bed) = loaded
        && bed.description().is_3d()
    {
        return super::tree3::stats_bed3(bed, json, limits);
    }
    let Loaded::Lsys(sys) = loaded else {
        return Err(wrong_kind(Command::Stats, loaded.kind()));
    };
    let depth = lsys_depth(sys, depth, limits)?;
    if sys.is_3d() {
        return super::stats3::stats3(sys, depth, json, limits);
    }
    if sys.parametric.is_some() {
        let stats = crate::interpret::stats::stats(sys, depth, limits)?;
        return Ok(if json {
            stats.to_json()
        } else {
            stats.to_text()
        });
    }
    if sys.is_stochastic() {
        let stats = crate::interpret::expected::stochastic_stats(sys, depth, limits)?;
        return Ok(if json {
            stats.to_json()
        } else {
            stats.to_text()
        });
    }
    let stats = crate::interpret::stats::stats(sys, depth, limits)?;
    Ok(if json {
        stats.to_json()
    } else {
        stats.to_text()
    })
}

// --------------------------------------------------------------- check --

/// What [`check`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct Checked {
    /// The summary, lines of text.
    pub summary: String,
    /// Warnings (growth cut short, inert symbols, ...).
    pub warnings: Vec<Diagnostic>,
}

/// Answers "would compile and render succeed?" without drawing, and
/// summarises the input (`stlc check`): its rules, seed and layout; an
/// L-system with `generations` is checked against the limits at that depth
/// (its word's length is computed, not derived); an OD is
/// grown with `opts` (every check compile makes: bounded growth, the root
/// inside the layout, a layout with an area, the limits) and its stems
/// counted; a BED's stems come from its measure.
pub fn check(loaded: &Loaded, opts: &GrowOptions) -> Result<Checked, Diagnostics> {
    let limits = &opts.limits;
    Ok(match loaded {
        Loaded::Lsys(sys) => {
            // With its own depth, would it derive within the limits?
            if let Some(depth) = sys.generations {
                crate::interpret::lsys::check(sys, depth, Derivation::Dfs, limits)?;
            }
            Checked {
                summary: lsys_summary(sys),
                warnings: inert_turns(sys),
            }
        }
        Loaded::Od(desc) => {
            let grown = grow(desc, opts, &mut crate::progress::NoProgress)?;
            let mut summary = stl_summary(desc, None, limits)?;
            let order = opts.growth;
            let _ = writeln!(summary, "  grows       {} stems ({order})", grown.stems);
            for (rule, tally) in desc.rules.iter().zip(&grown.tallies) {
                let mut line = tally_line(&rule.full_name(), tally);
                if order == crate::grow::GrowthOrder::Space && tally.tries > 0 {
                    let _ = write!(
                        line,
                        "; points claimed {}, killed {}",
                        tally.claimed, tally.killed
                    );
                }
                let _ = writeln!(summary, "{line}");
            }
            Checked {
                summary,
                warnings: grown.warnings,
            }
        }
        Loaded::Bed(bed) => Checked {
            summary: stl_summary(bed.description(), Some(bed), limits)?,
            warnings: Vec::new(),
        },
    })
}

/// One rule's line in an OD's summary: its tries, its fits, and the reason
/// most failed tries failed for.
fn tally_line(name: &str, t: &RuleTally) -> String {
    let label = format!("rule {name}");
    let mut line = format!("  {label:<11} ");
    if t.tries == 0 {
        line.push_str("never tried");
        return line;
    }
    let _ = write!(
        line,
        "{} {}, {} fit{}",
        t.tries,
        if t.tries == 1 { "try" } else { "tries" },
        t.fits,
        if t.fits == 1 { "" } else { "s" }
    );
    if let Some((reason, n)) = t.most_common() {
        let _ = write!(
            line,
            "; most misses: {reason} ({n} of {})",
            t.tries - t.fits
        );
    }
    line
}

/// A probability as the summary writes it: six decimals, or, below what
/// six decimals show, in scientific notation (`1e-300`, never a `0` for a
/// probability that is not).
fn probability(q: f64) -> String {
    if q > 0.0 && q < 0.000_000_5 {
        format!("{q:e}")
    } else {
        crate::num::fixed(q, 6, crate::num::Trim::Zeros)
    }
}

fn lsys_summary(sys: &LSystem) -> String {
    let mut s = String::new();
    if let Some(p) = &sys.parametric {
        param_summary(&mut s, p);
    } else {
        let _ = writeln!(s, "classic L-system: ok");
        let _ = writeln!(s, "  axiom       {}", sys.axiom.iter().collect::<String>());
    }
    for (k, p) in sys
        .rules
        .iter()
        .flat_map(|(k, ps)| ps.iter().map(move |p| (k, p)))
    {
        let chance = match p.probability {
            Some(q) => format!(" (probability {})", probability(q)),
            None => String::new(),
        };
        let _ = writeln!(
            s,
            "  rule        {k} -> {}{chance}",
            p.successor.iter().collect::<String>()
        );
    }
    if sys.is_stochastic() {
        let _ = writeln!(s, "  seed        {}", sys.seed);
    }
    let _ = writeln!(s, "  angle       {}", sys.angle);
    match sys.generations {
        Some(g) => {
            let _ = writeln!(s, "  generations {g}");
        }
        None => {
            let _ = writeln!(s, "  generations (none: pass --depth)");
        }
    }
    s
}

/// The head of a parametric system's summary: its axiom (evaluated), its
/// constants, and what its rules use.
fn param_summary(s: &mut String, p: &crate::model::param::Parametric) {
    let _ = writeln!(s, "parametric L-system: ok");
    let mut axiom = String::new();
    for m in &p.axiom {
        let vals: Vec<f64> = m.args.iter().map(crate::model::param::eval_const).collect();
        crate::interpret::lsys::param::write_module(&mut axiom, m.symbol, &vals);
    }
    let _ = writeln!(s, "  axiom       {axiom}");
    for (name, v, _) in &p.defines {
        let _ = writeln!(s, "  define      {name} = {v}");
    }
    let uses: Vec<&str> = [
        (p.has_context(), "context"),
        (p.rules.iter().any(|r| r.condition.is_some()), "conditions"),
        (p.is_stochastic(), "probabilities"),
        (p.bends(), "tropism"),
    ]
    .into_iter()
    .filter_map(|(on, what)| on.then_some(what))
    .collect();
    let _ = writeln!(
        s,
        "  rules       {}{}",
        p.rules.len(),
        if uses.is_empty() {
            String::new()
        } else {
            format!(" (with {})", uses.join(", "))
        }
    );
}

fn stl_summary(
    desc: &Description,
    bed: Option<&Bed>,
    limits: &Limits,
) -> Result<String, Diagnostics> {
    use geo::Area;
    let mut s = String::new();
    let what = match desc.format {
        Format::Od => "Outline Description",
        Format::Bed => "Branch-Expansion Description",
    };
    let _ = writeln!(s, "{what} `{}`: ok", desc.name);
    if desc.forest.is_empty() {
        match desc.root_z {
            Some(z) => {
                let _ = writeln!(
                    s,
                    "  root        ({}, {}, {z}) (3D)",
                    desc.root.0, desc.root.1
                );
            }
            None => {
                let _ = writeln!(s, "  root        ({}, {})", desc.root.0, desc.root.1);
            }
        }
    } else {
        // A few roots say where the forest stands; a root line of
        // thousands would bury the rest of the summary.
        const SHOWN: usize = 6;
        let trees = desc.trees();
        let mut roots: Vec<String> = trees
            .iter()
            .take(SHOWN)
            .zip(std::iter::once(desc.root_z).chain(desc.forest.iter().map(|t| t.root_z)))
            .map(|(((x, y), _), z)| match z {
                Some(z) => format!("({x}, {y}, {z})"),
                None => format!("({x}, {y})"),
            })
            .collect();
        if trees.len() > SHOWN {
            roots.push(format!("... and {} more", trees.len() - SHOWN));
        }
        let _ = writeln!(
            s,
            "  roots       {} (a forest): {}",
            trees.len(),
            roots.join(" ")
        );
    }
    for r in &desc.rules {
        let n = r.branch_count();
        let chance = match r.alternative.as_ref().and_then(|a| a.probability) {
            Some(p) => format!(", alternative with probability {}", probability(p)),
            None => String::new(),
        };
        let _ = writeln!(
            s,
            "  rule        {} ({} branch{}{chance})",
            r.full_name(),
            n,
            if n == 1 { "" } else { "es" }
        );
    }
    let terms = desc.effective_seed().map_or(0, |seed| {
        seed.items
            .iter()
            .filter(|i| matches!(i, SeedItem::Term(_) | SeedItem::Repeat(_)))
            .count()
    });
    let written = if desc.seed.is_some() {
        ""
    } else {
        " (default: F and the first rule)"
    };
    let _ = writeln!(s, "  seed terms  {terms}{written}");
    if let Some(bed) = bed {
        let _ = writeln!(s, "  stems       {}", bed.size().stems);
    }
    match &desc.layout {
        Some(l) if desc.is_3d() => {
            let _ = writeln!(
                s,
                "  layout      {} volume{}",
                l.solids.len(),
                crate::diag::plural(l.solids.len(), "s")
            );
        }
        Some(l) => {
            let area = match crate::grow::region::Region::from_layout(l, limits.max_layout_vertices)
            {
                Ok(r) => format!("{:.1} square units", r.area().unsigned_area()),
                Err(e) if e.iter().any(|d| matches!(d.kind, ErrorKind::Limit { .. })) => {
                    return Err(e);
                }
                Err(_) => "empty".to_string(),
            };
            let _ = writeln!(
                s,
                "  layout      {} shape{}, growth area {area}",
                l.shapes.len(),
                crate::diag::plural(l.shapes.len(), "s")
            );
        }
        None => {
            let _ = writeln!(s, "  layout      none");
        }
    }
    Ok(s)
}
