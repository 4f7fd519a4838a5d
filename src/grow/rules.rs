//! What growth needs to know of each rule, worked out once before growth.

use super::bounded::successors;
use crate::choice::Alternatives;
use crate::model::walk::{self, Step};
use crate::model::{Description, RuleDef, RuleId};

/// What growth needs to know of a rule, worked out once.
#[derive(Debug)]
pub(super) struct RuleInfo {
    /// The rule, and every alternative of its name, leaves the turtle
    /// where it found it: its trunk neither draws, moves nor turns (its
    /// branches restore the turtle). Drawing after it in the seed does not
    /// depend on its decision.
    pub(super) neutral: bool,
    /// The rule that grows at each branch tip, in branch order.
    pub(super) successors: Vec<RuleId>,
    /// With alternatives: the probabilities and the rules they choose.
    pub(super) choice: Option<std::sync::Arc<(Alternatives, Vec<RuleId>)>>,
}

impl RuleInfo {
    /// The information of every rule, by [`RuleId`]; `moves`: whether a
    /// drawing component draws, moves or turns the turtle.
    pub(super) fn all(od: &Description, moves: impl Fn(char) -> bool) -> Vec<RuleInfo> {
        let groups = od.groups();
        let choices: Vec<_> = groups
            .groups
            .iter()
            .map(|g| {
                let p: Vec<f64> = g
                    .iter()
                    .filter_map(|&r| od.rule(r).alternative.as_ref()?.probability)
                    .collect();
                // An OD's alternatives passed the parser's check; a
                // description made otherwise chooses the first.
                let alts = Alternatives::new(&p).unwrap_or_else(|_| {
                    Alternatives::new(&[1.0]).expect("a single certain choice")
                });
                od.rule(g[0])
                    .alternative
                    .is_some()
                    .then(|| std::sync::Arc::new((alts, g.clone())))
            })
            .collect();
        let own: Vec<bool> = od.rules.iter().map(|r| is_neutral(r, &moves)).collect();
        (0..od.rules.len())
            .map(|i| {
                let members = groups.members(RuleId(i));
                RuleInfo {
                    neutral: members.iter().all(|r| own[r.0]),
                    successors: successors(od, RuleId(i)).collect(),
                    choice: choices[groups.of_rule[i]].clone(),
                }
            })
            .collect()
    }
}

/// Whether the trunk of `rule` leaves the turtle's position and heading
/// alone (fixed figures on the trunk count as moving it).
fn is_neutral(rule: &RuleDef, moves: impl Fn(char) -> bool) -> bool {
    let mut in_branch = false;
    walk::steps(&rule.body).all(|step| match step {
        Step::Open { .. } => {
            in_branch = true;
            true
        }
        Step::Tip { .. } => {
            in_branch = false;
            true
        }
        Step::Run(r) => in_branch || !r.text.chars().any(&moves),
        Step::Fixed(_) => in_branch,
    })
}
