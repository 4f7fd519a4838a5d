//! The seed, in and out: flattened into a program of drawing operations,
//! fixed figures and growth points before growth, and written back with its
//! growth points replaced by what grew after it.
//!
//! Both read the seed through the one seed walk
//! ([`crate::model::seed_walk`]), which keeps its own explicit stack: terms
//! written out in a seed may nest as deep as the input allows.

use super::options::span_of;
use super::tree::{NO_NODE, Tree};
use crate::diag::{Diagnostic, Diagnostics, RuleError};
use crate::model::seed_walk::{Points, SeedStep, SeedWalk};
use crate::model::walk::{self, Step};
use crate::model::{Description, Fixed, Loc, RuleDef, RuleId, Seed, SeedItem, SlotId, Term, Terms};
use crate::turtle::Op;

/// A growth point written in the seed: a bare rule reference (no count) or
/// `[I n X]`.
#[derive(Debug, Clone)]
pub(super) struct SeedGp {
    /// The rule that grows there.
    pub(super) rule: RuleId,
    /// Levels to grow, `None` for a bare reference.
    pub(super) count: Option<u32>,
    /// Where it is written (empty for the default seed's).
    pub(super) loc: Loc,
}

/// One instruction of the flattened seed.
#[derive(Debug)]
pub(super) enum Instr<'a> {
    /// A drawing component, as written (`[` and `]` included); what it
    /// does is the turtle's business ([`super::plane::Space::op`]).
    Op(char),
    /// A written term's body starts (a rule application).
    Enter,
    /// It ends.
    Leave,
    /// A fixed figure `[I n w]`, drawn as given.
    Fixed(&'a Fixed),
    /// Growth point number `i` of [`Flat::gps`].
    Gp(usize),
}

/// Whether `c` is a drawing component in 2D or 3D (`F f + - L R | [ ]`,
/// and the 3D turtle's `& ^ \ /`).
fn draws(c: char) -> bool {
    Op::of_stl(c).is_some() || matches!(c, '&' | '^' | '\\' | '/')
}

/// The seed as a flat program, in drawing order.
#[derive(Debug)]
pub(super) struct Flat<'a> {
    /// The instructions.
    pub(super) instrs: Vec<Instr<'a>>,
    /// The growth points, in the order their [`Instr::Gp`] appear.
    pub(super) gps: Vec<SeedGp>,
}

/// The stems the seed draws by itself, before anything grows: its `F`s,
/// its fixed figures', and those of the rules of the terms written out in
/// it (growth points count nothing), counted without flattening,
/// saturating.
pub(super) fn drawn_stems(od: &Description, seed: &Seed) -> u64 {
    let own: Vec<u64> = od.rules.iter().map(own_stems).collect();
    let mut total = 0u64;
    let mut walk = SeedWalk::written(seed);
    while let Some(step) = walk.next() {
        let n = match step {
            SeedStep::Run(r) => stems_of(&r.text),
            SeedStep::Fixed(f) => walk::fixed_counts(&f.word, f.count).1,
            SeedStep::Term { term, .. } if term.bare() => {
                walk.step_over();
                0
            }
            SeedStep::Term { term, .. } => own.get(term.rule().0).copied().unwrap_or(0),
            _ => 0,
        };
        total = total.saturating_add(n);
    }
    total
}

/// The `F`s of a run of drawing components.
fn stems_of(text: &str) -> u64 {
    text.bytes().filter(|&b| b == b'F').count() as u64
}

/// The stems rule `r` draws itself, its slots aside.
fn own_stems(r: &RuleDef) -> u64 {
    walk::steps(&r.body)
        .map(|step| match step {
            Step::Run(run) => stems_of(&run.text),
            Step::Fixed(f) => walk::fixed_counts(&f.word, f.count).1,
            Step::Open { .. } | Step::Tip { .. } => 0,
        })
        .fold(0u64, u64::saturating_add)
}

/// The error for a reference to rule number `rule` if no such rule is
/// declared (only a description built by hand can have one).
fn rule_error(od: &Description, rule: RuleId, loc: &Loc) -> Option<Diagnostic> {
    if rule.0 < od.rules.len() {
        return None;
    }
    let mut d = Diagnostic::error(RuleError::UndeclaredRule { number: rule.0 });
    if let Some(s) = span_of(loc) {
        d = d.with_span(s);
    }
    Some(d)
}

/// Flattens the seed into drawing operations, fixed figures and growth
/// points, in drawing order. A written term is `Enter`, its rule's body with
/// slot `i` at the tip of branch `i`, `Leave`.
pub(super) fn flatten<'a>(od: &'a Description, seed: &'a Seed) -> Result<Flat<'a>, Diagnostics> {
    let mut flat = Flat {
        instrs: Vec::new(),
        gps: Vec::new(),
    };
    for step in SeedWalk::drawing(seed, &od.rules, Points::Grow) {
        let op = match step {
            SeedStep::Run(r) => {
                flat.instrs
                    .extend(r.text.chars().filter(|&c| draws(c)).map(Instr::Op));
                continue;
            }
            SeedStep::Fixed(f) => {
                flat.instrs.push(Instr::Fixed(f));
                continue;
            }
            SeedStep::Repeat { repeat: r, .. } => {
                if let Some(d) = rule_error(od, r.rule, &r.loc) {
                    return Err(d.into());
                }
                flat.instrs.push(Instr::Gp(flat.gps.len()));
                flat.gps.push(SeedGp {
                    rule: r.rule,
                    count: Some(r.count),
                    loc: r.loc.clone(),
                });
                continue;
            }
            SeedStep::Term { term: t, .. } => {
                let loc = Loc(t.loc());
                if let Some(d) = rule_error(od, t.rule(), &loc) {
                    return Err(d.into());
                }
                let rule = od.rule(t.rule());
                if t.bare() {
                    flat.instrs.push(Instr::Gp(flat.gps.len()));
                    flat.gps.push(SeedGp {
                        rule: t.rule(),
                        count: None,
                        loc,
                    });
                    continue;
                }
                if t.slot_count() != rule.branch_count() {
                    let mut d = Diagnostic::error(RuleError::SlotCount {
                        rule: rule.full_name().into_owned(),
                        expected: rule.branch_count(),
                        found: t.slot_count(),
                    });
                    if let Some(s) = span_of(&loc) {
                        d = d.with_span(s);
                    }
                    return Err(d.into());
                }
                Instr::Enter
            }
            SeedStep::End { .. } => Instr::Leave,
            SeedStep::Open => Instr::Op('['),
            SeedStep::Close => Instr::Op(']'),
            // Not in drawing order with growth points.
            SeedStep::Level { .. } | SeedStep::Empty { .. } => continue,
        };
        flat.instrs.push(op);
    }
    Ok(flat)
}

/// The tree (root index) each node of `tree` grew in: a seed growth
/// point's node belongs to its tree, a slot's child to its parent's.
pub(super) fn owners(tree: &Tree) -> Vec<u32> {
    let mut owner = vec![0u32; tree.nodes.len()];
    let per_tree = (tree.seed_result.len() / tree.trees.max(1)).max(1);
    for (i, &id) in tree.seed_result.iter().enumerate() {
        if id != NO_NODE {
            owner[id as usize] = (i / per_tree) as u32;
        }
    }
    // A child is recorded after its parent: one pass forward.
    for id in 0..tree.nodes.len() {
        let first = tree.nodes[id].slots as usize;
        let end = tree
            .nodes
            .get(id + 1)
            .map_or(tree.slot_child.len(), |n| n.slots as usize);
        for &c in &tree.slot_child[first..end] {
            if c != NO_NODE {
                owner[c as usize] = owner[id];
            }
        }
    }
    owner
}

/// The grown seed: the seed's items with every growth point replaced by its
/// grown term (left out, or its slot left empty, where nothing grew), and
/// the terms they refer to, built children first without recursion. Growth
/// points are met in the order [`flatten`] numbered them.
///
/// In a forest the seed's growth points of tree `t` are entries
/// `t * gps ..` of [`Tree::seed_result`]; `owner` gives each node's tree
/// ([`owners`]), and only tree `t`'s nodes are built.
pub(super) fn grown_seed(
    od: &Description,
    tree: &Tree,
    seed: &Seed,
    t: usize,
    owner: &[u32],
) -> (Vec<SeedItem>, Terms) {
    let mut terms = Terms::new();
    // The term of each grown node. A child is always made after its
    // parent, so it has a larger id: building in reverse puts children first.
    let mut built: Vec<Option<SlotId>> = vec![None; tree.nodes.len()];
    let mut cells: Vec<Option<SlotId>> = Vec::new();
    for id in (0..tree.nodes.len()).rev() {
        if owner[id] != t as u32 {
            continue;
        }
        let n = tree.nodes[id];
        let k = od.rule(n.rule).branch_count();
        cells.clear();
        cells.extend((0..k).map(|j| {
            let c = tree.slot_child[n.slots as usize + j];
            (c != NO_NODE).then(|| built[c as usize]).flatten()
        }));
        built[id] = Some(Terms::slot_of(terms.push(n.rule, false, 0..0, &cells)));
    }
    let mut gp_index = t * (tree.seed_result.len() / tree.trees.max(1));
    let mut next_gp = || -> Option<SlotId> {
        let id = tree.seed_result[gp_index];
        gp_index += 1;
        (id != NO_NODE).then(|| built[id as usize]).flatten()
    };
    let mut items = Vec::with_capacity(seed.items.len());
    // The written terms being rebuilt, each with its slots so far.
    let mut stack: Vec<(Term<'_>, Vec<Option<SlotId>>)> = Vec::new();
    // Where a slot's content goes: its term's slots, or the seed's items.
    fn deliver(
        stack: &mut [(Term<'_>, Vec<Option<SlotId>>)],
        items: &mut Vec<SeedItem>,
        s: Option<SlotId>,
    ) {
        match stack.last_mut() {
            Some((_, built)) => built.push(s),
            None => items.extend(s.map(|s| SeedItem::Term(Terms::term_of(s)))),
        }
    }
    let mut walk = SeedWalk::written(seed);
    while let Some(step) = walk.next() {
        match step {
            SeedStep::Run(r) => items.push(SeedItem::Draw(Box::new(r.clone()))),
            SeedStep::Fixed(f) => items.push(SeedItem::Fixed(Box::new(f.clone()))),
            SeedStep::Term { term, .. } if !term.bare() => stack.push((term, Vec::new())),
            // A growth point: what grew there, if anything.
            SeedStep::Term { .. } | SeedStep::Repeat { .. } => {
                walk.step_over();
                deliver(&mut stack, &mut items, next_gp());
            }
            SeedStep::Empty { .. } => deliver(&mut stack, &mut items, None),
            SeedStep::End { .. } => {
                let Some((term, slots)) = stack.pop() else {
                    continue;
                };
                let id = terms.push(term.rule(), false, term.loc(), &slots);
                deliver(&mut stack, &mut items, Some(Terms::slot_of(id)));
            }
            SeedStep::Level { .. } | SeedStep::Open | SeedStep::Close => {}
        }
    }
    (items, terms)
}
