//! The bound on growth: growth that nothing would stop is refused before it
//! starts.
//!
//! With no LAYOUT, no decrement of `L` or `B` and no explicit `--max-stems`,
//! only counts end growth; a growth point without a count whose rule can
//! reach a cycle of branching rules would grow until the default
//! `--max-stems` cut it off, which is a safety net, not a design. The rules
//! form a successor graph: each branch of rule `X` leads to the rule named
//! at its end, or to `X` itself.

use super::options::{GrowOptions, span_of};
use super::seed::SeedGp;
use crate::diag::{Diagnostic, Diagnostics, GrowError, Help, Knob};
use crate::limits::Bound;
use crate::model::walk::{self, Step};
use crate::model::{Description, RuleGroups, RuleId};

/// The rules that grow at the branch tips of rule `r`, in branch order: the
/// rule named at the branch's end, or `r` itself.
pub(super) fn successors(od: &Description, r: RuleId) -> impl Iterator<Item = RuleId> + '_ {
    walk::steps(&od.rule(r).body).filter_map(move |s| match s {
        Step::Tip { branch, .. } => Some(branch.successor.as_ref().map_or(r, |s| s.rule)),
        Step::Run(_) | Step::Fixed(_) | Step::Open { .. } => None,
    })
}

/// Refuses growth that nothing bounds: no layout, no decrement, no explicit
/// `--max-stems`, and a growth point without a count from which the rules
/// can branch forever (a cycle of rules with branches, following each
/// branch's successor).
pub(super) fn check_bounded(
    od: &Description,
    gps: &[SeedGp],
    opts: &GrowOptions,
) -> Result<(), Diagnostics> {
    let p = &od.params;
    if od.layout.is_some()
        || p.length.decrement > 0.0
        || p.width.decrement > 0.0
        || opts.max_stems_explicit
    {
        return Ok(());
    }
    let groups = od.groups();
    for gp in gps.iter().filter(|g| g.count.is_none()) {
        let endless = groups
            .members(gp.rule)
            .iter()
            .find_map(|&r| endless_from(od, &groups, r));
        if let Some(cycle_rule) = endless {
            let name = &od.rule(gp.rule).name;
            let mut d = Diagnostic::error(GrowError::UnboundedGrowth {
                rule: name.clone(),
                through: od.rule(cycle_rule).name.clone(),
            })
            .with_help(
                Help::from(format!(
                    "add a LAYOUT section, write `[I n {name}]` to grow n levels, give L or B a decrement (`L=10(1)`), or stop after N stems with "
                )) + Help::knob(Knob::Limit(Bound::Stems), "N"),
            );
            if let Some(s) = span_of(&gp.loc) {
                d = d.with_span(s).with_label("this growth point");
            } else if let Some(s) = span_of(&od.rule(gp.rule).name_loc) {
                // The default seed `F R1` has no text of its own.
                d = d.with_span(s).with_label(
                    "the seed's default growth point (no SEED section) grows this rule",
                );
            }
            return Err(d.into());
        }
    }
    Ok(())
}

/// A rule on a cycle of the successor graph reachable from `start`, if any
/// (iterative depth-first search with colours).
///
/// A successor with alternatives leads to each of them: any may be chosen.
fn endless_from(od: &Description, groups: &RuleGroups, start: RuleId) -> Option<RuleId> {
    let succ = |r: RuleId| -> Vec<RuleId> {
        successors(od, r)
            .filter(|s| s.0 < od.rules.len())
            .flat_map(|s| groups.members(s).iter().copied())
            .collect()
    };
    // 0 unvisited, 1 on the path, 2 done.
    let mut colour = vec![0u8; od.rules.len()];
    let mut stack: Vec<(RuleId, Vec<RuleId>)> = vec![(start, succ(start))];
    colour[start.0] = 1;
    while let Some((r, next)) = stack.last_mut() {
        match next.pop() {
            Some(n) => match colour[n.0] {
                1 => return Some(n),
                0 => {
                    colour[n.0] = 1;
                    let s = succ(n);
                    stack.push((n, s));
                }
                _ => {}
            },
            None => {
                colour[r.0] = 2;
                stack.pop();
            }
        }
    }
    None
}
