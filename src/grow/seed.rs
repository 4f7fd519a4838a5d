//! The seed, in and out: flattened into a program of drawing operations,
//! fixed figures and growth points before growth, and written back with its
//! growth points replaced by what grew after it.
//!
//! Both walks use explicit stacks: terms written out in a seed may nest as
//! deep as the input allows.

use super::span_of;
use super::tree::{NO_NODE, Tree};
use crate::diag::{Diagnostic, Diagnostics, RuleError};
use crate::model::walk::{self, Step};
use crate::model::{
    Description, Fixed, Loc, RuleDef, RuleId, Seed, SeedItem, Slot, SlotId, Term, Terms,
};
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

/// The stems the seed draws by itself, before anything grows: its `F`s,
/// its fixed figures', and those of the rules of the terms written out in
/// it (growth points count nothing), counted without flattening,
/// saturating.
pub(super) fn drawn_stems(od: &Description, seed: &Seed) -> u64 {
    let own: Vec<u64> = od.rules.iter().map(own_stems).collect();
    let mut total = 0u64;
    let mut stack: Vec<Term<'_>> = Vec::new();
    for item in &seed.items {
        let n = match item {
            SeedItem::Draw(r) => stems_of(&r.text),
            SeedItem::Fixed(f) => walk::fixed_counts(&f.word, f.count).1,
            SeedItem::Term(t) => {
                stack.push(seed.term(*t));
                0
            }
            SeedItem::Repeat(_) => 0,
        };
        total = total.saturating_add(n);
        while let Some(t) = stack.pop() {
            if t.bare() {
                continue;
            }
            total = total.saturating_add(own.get(t.rule().0).copied().unwrap_or(0));
            stack.extend(t.slots().flatten().filter_map(|s| match s {
                Slot::Term(c) => Some(c),
                Slot::Repeat(_) => None,
            }));
        }
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
    enum Task<'a> {
        Item(&'a SeedItem),
        Slot(Slot<'a>),
        Term(Term<'a>),
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
            Task::Item(SeedItem::Fixed(f)) => flat.instrs.push(Instr::Fixed(f)),
            Task::Fixed(f) => flat.instrs.push(Instr::Fixed(f)),
            Task::Item(SeedItem::Term(t)) => stack.push(Task::Term(seed.term(*t))),
            Task::Slot(Slot::Term(t)) => stack.push(Task::Term(t)),
            Task::Item(SeedItem::Repeat(r)) => stack.push(Task::Slot(Slot::Repeat(r))),
            Task::Slot(Slot::Repeat(r)) => {
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
                // Enter, the body with slot i at the tip of branch i, Leave;
                // pushed in reverse.
                let mut tasks: Vec<Task<'a>> = vec![Task::Op(Op::Enter)];
                for step in walk::steps(&rule.body) {
                    match step {
                        Step::Run(r) => tasks.push(Task::Run(&r.text)),
                        Step::Fixed(f) => tasks.push(Task::Fixed(f)),
                        Step::Open { .. } => tasks.push(Task::Op(Op::Push)),
                        Step::Tip { index, .. } => {
                            if let Some(s) = t.slot(index) {
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
    /// A written term being rebuilt: its slots so far.
    struct Frame<'t> {
        term: Term<'t>,
        next: usize,
        built: Vec<Option<SlotId>>,
    }
    let frame = |term| Frame {
        term,
        next: 0,
        built: Vec::new(),
    };
    let mut items = Vec::with_capacity(seed.items.len());
    for item in &seed.items {
        let top = match item {
            SeedItem::Draw(_) | SeedItem::Fixed(_) => {
                items.push(item.clone());
                continue;
            }
            SeedItem::Term(t) if !seed.term(*t).bare() => seed.term(*t),
            SeedItem::Repeat(_) | SeedItem::Term(_) => {
                items.extend(next_gp().map(|s| SeedItem::Term(Terms::term_of(s))));
                continue;
            }
        };
        let mut stack = vec![frame(top)];
        while let Some(f) = stack.last_mut() {
            if f.next < f.term.slot_count() {
                let slot = f.term.slot(f.next);
                f.next += 1;
                match slot {
                    None => f.built.push(None),
                    Some(Slot::Term(t)) if !t.bare() => stack.push(frame(t)),
                    Some(Slot::Repeat(_) | Slot::Term(_)) => f.built.push(next_gp()),
                }
            } else {
                let Some(f) = stack.pop() else { break };
                let id = terms.push(f.term.rule(), false, f.term.loc(), &f.built);
                match stack.last_mut() {
                    Some(parent) => parent.built.push(Some(Terms::slot_of(id))),
                    None => items.push(SeedItem::Term(id)),
                }
            }
        }
    }
    (items, terms)
}
