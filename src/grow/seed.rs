//! The seed, in and out: flattened into a program of drawing operations,
//! fixed figures and growth points before growth, and written back with its
//! growth points replaced by what grew after it.
//!
//! Both walks use explicit stacks: terms written out in a seed may nest as
//! deep as the input allows.

use super::grower::{NO_NODE, Tree};
use super::span_of;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind};
use crate::model::walk::{self, Step};
use crate::model::{Description, Fixed, Loc, RuleId, Seed, SeedItem, Slot, Term};
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
    /// A drawing operation (`Enter`/`Leave` around a written term's body).
    Op(Op),
    /// A fixed figure `[I n w]`, drawn as given.
    Fixed(&'a Fixed),
    /// Growth point number `i` of [`Flat::gps`].
    Gp(usize),
}

/// The seed as a flat program, in drawing order.
#[derive(Debug)]
pub(super) struct Flat<'a> {
    /// The instructions.
    pub(super) instrs: Vec<Instr<'a>>,
    /// The growth points, in the order their [`Instr::Gp`] appear.
    pub(super) gps: Vec<SeedGp>,
}

/// The stems the seed's top-level drawing makes by itself (its `F`s and
/// fixed figures'; terms written out in the seed are counted as they are
/// drawn), counted without flattening, saturating.
pub(super) fn drawn_stems(seed: &Seed) -> u64 {
    seed.items
        .iter()
        .map(|i| match i {
            SeedItem::Draw(r) => r.text.bytes().filter(|&b| b == b'F').count() as u64,
            SeedItem::Fixed(f) => walk::fixed_counts(&f.word, f.count).1,
            SeedItem::Term(_) | SeedItem::Repeat(_) => 0,
        })
        .fold(0u64, u64::saturating_add)
}

/// The error for a reference to rule number `rule` if no such rule is
/// declared (only a description built by hand can have one).
fn rule_error(od: &Description, rule: RuleId, loc: &Loc) -> Option<Diagnostic> {
    if rule.0 < od.rules.len() {
        return None;
    }
    let mut d = Diagnostic::error(ErrorKind::UndeclaredRule { number: rule.0 });
    if let Some(s) = span_of(loc) {
        d = d.with_span(s);
    }
    Some(d)
}

/// Flattens the seed into drawing operations, fixed figures and growth
/// points, in drawing order. A written term is `Enter`, its rule's body with
/// slot `i` at the tip of branch `i`, `Leave`.
pub(super) fn flatten<'a>(od: &'a Description, seed: &'a Seed) -> Result<Flat<'a>, Diagnostics> {
    enum Task<'a> {
        Item(&'a SeedItem),
        Slot(&'a Slot),
        Term(&'a Term),
        Run(&'a str),
        Fixed(&'a Fixed),
        Op(Op),
    }
    let mut flat = Flat {
        instrs: Vec::new(),
        gps: Vec::new(),
    };
    let mut stack: Vec<Task<'a>> = seed.items.iter().rev().map(Task::Item).collect();
    while let Some(task) = stack.pop() {
        match task {
            Task::Item(SeedItem::Draw(r)) => stack.push(Task::Run(&r.text)),
            Task::Item(SeedItem::Fixed(f)) | Task::Fixed(f) => flat.instrs.push(Instr::Fixed(f)),
            Task::Item(SeedItem::Term(t)) | Task::Slot(Slot::Term(t)) => stack.push(Task::Term(t)),
            Task::Item(SeedItem::Repeat(r)) | Task::Slot(Slot::Repeat(r)) => {
                if let Some(d) = rule_error(od, r.rule, &r.loc) {
                    return Err(d.into());
                }
                flat.instrs.push(Instr::Gp(flat.gps.len()));
                flat.gps.push(SeedGp {
                    rule: r.rule,
                    count: Some(r.count),
                    loc: r.loc.clone(),
                });
            }
            Task::Run(text) => flat
                .instrs
                .extend(text.chars().filter_map(Op::of_stl).map(Instr::Op)),
            Task::Op(op) => flat.instrs.push(Instr::Op(op)),
            Task::Term(t) => {
                if let Some(d) = rule_error(od, t.rule, &t.loc) {
                    return Err(d.into());
                }
                let rule = od.rule(t.rule);
                if t.bare {
                    flat.instrs.push(Instr::Gp(flat.gps.len()));
                    flat.gps.push(SeedGp {
                        rule: t.rule,
                        count: None,
                        loc: t.loc.clone(),
                    });
                    continue;
                }
                if t.slots.len() != rule.branch_count() {
                    let mut d = Diagnostic::error(ErrorKind::SlotCount {
                        rule: rule.name.clone(),
                        expected: rule.branch_count(),
                        found: t.slots.len(),
                    });
                    if let Some(s) = span_of(&t.loc) {
                        d = d.with_span(s);
                    }
                    return Err(d.into());
                }
                // Enter, the body with slot i at the tip of branch i, Leave;
                // pushed in reverse.
                let mut tasks: Vec<Task<'a>> = vec![Task::Op(Op::Enter)];
                for step in walk::steps(&rule.body) {
                    match step {
                        Step::Run(r) => tasks.push(Task::Run(&r.text)),
                        Step::Fixed(f) => tasks.push(Task::Fixed(f)),
                        Step::Open { .. } => tasks.push(Task::Op(Op::Push)),
                        Step::Tip { index, .. } => {
                            if let Some(s) = t.slots.get(index) {
                                tasks.push(Task::Slot(s));
                            }
                            tasks.push(Task::Op(Op::Pop));
                        }
                    }
                }
                tasks.push(Task::Op(Op::Leave));
                stack.extend(tasks.into_iter().rev());
            }
        }
    }
    Ok(flat)
}

/// The grown seed: the seed's items with every growth point replaced by its
/// grown term (left out, or its slot left empty, where nothing grew), built
/// bottom-up without recursion. Growth points are met in the order
/// [`flatten`] numbered them.
pub(super) fn grown_seed(od: &Description, tree: &Tree, seed: &Seed) -> Vec<SeedItem> {
    // Terms of all nodes, children first (a child is always made after its
    // parent, so it has a larger id).
    let mut terms: Vec<Option<Term>> = Vec::with_capacity(tree.nodes.len());
    terms.resize_with(tree.nodes.len(), || None);
    for id in (0..tree.nodes.len()).rev() {
        let n = tree.nodes[id];
        let k = od.rule(n.rule).branch_count();
        let slots = (0..k)
            .map(|j| {
                let c = tree.slot_child[n.slots as usize + j];
                (c != NO_NODE)
                    .then(|| terms[c as usize].take().map(Slot::Term))
                    .flatten()
            })
            .collect::<Vec<_>>()
            .into();
        terms[id] = Some(Term {
            rule: n.rule,
            slots,
            bare: false,
            loc: Loc::default(),
        });
    }
    let mut gp_index = 0usize;
    let mut next_gp = |terms: &mut Vec<Option<Term>>| -> Option<Term> {
        let id = tree.seed_result[gp_index];
        gp_index += 1;
        (id != NO_NODE).then(|| terms[id as usize].take()).flatten()
    };
    struct Frame<'t> {
        term: &'t Term,
        next: usize,
        built: Vec<Option<Slot>>,
    }
    let mut items = Vec::with_capacity(seed.items.len());
    for item in &seed.items {
        let top = match item {
            SeedItem::Draw(_) | SeedItem::Fixed(_) => {
                items.push(item.clone());
                continue;
            }
            SeedItem::Repeat(_) => {
                items.extend(next_gp(&mut terms).map(SeedItem::Term));
                continue;
            }
            SeedItem::Term(t) if t.bare => {
                items.extend(next_gp(&mut terms).map(SeedItem::Term));
                continue;
            }
            SeedItem::Term(t) => t,
        };
        let mut stack = vec![Frame {
            term: top,
            next: 0,
            built: Vec::new(),
        }];
        while let Some(f) = stack.last_mut() {
            if f.next < f.term.slots.len() {
                let slot = f.term.slots.get(f.next);
                f.next += 1;
                match slot {
                    None => f.built.push(None),
                    Some(Slot::Repeat(_)) => f.built.push(next_gp(&mut terms).map(Slot::Term)),
                    Some(Slot::Term(t)) if t.bare => {
                        f.built.push(next_gp(&mut terms).map(Slot::Term))
                    }
                    Some(Slot::Term(t)) => stack.push(Frame {
                        term: t,
                        next: 0,
                        built: Vec::new(),
                    }),
                }
            } else {
                let Some(f) = stack.pop() else { break };
                let t = Term {
                    rule: f.term.rule,
                    slots: f.built.into(),
                    bare: false,
                    loc: f.term.loc.clone(),
                };
                match stack.last_mut() {
                    Some(parent) => parent.built.push(Some(Slot::Term(t))),
                    None => items.push(SeedItem::Term(t)),
                }
            }
        }
    }
    items
}
