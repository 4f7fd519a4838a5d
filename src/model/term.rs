//! Branch-expansion terms `X{s1,...,sm}` and `[I n X]`: the recursive part
//! of a seed, stored flat.
//!
//! A seed's terms live in one arena, [`Terms`]: a node of 20 bytes a term
//! and one 4-byte cell a slot (none at all for a term whose slots are all
//! empty, every leaf of a BED). A generated BED of a million terms so costs
//! tens of megabytes, not the gigabyte a tree of boxed nodes cost
//! (docs/limits.md), and nothing about a term recurses: cloning, comparing
//! and dropping a seed never use the thread's stack in proportion to the
//! input's depth.
//!
//! Programs read a term through its view [`Term`] (`rule`, `bare`, `loc`,
//! `slot(i)`); [`Slot`] is what a slot holds. Terms are built children
//! first ([`Terms::push`] takes the slots' contents as already-built ids).

use std::fmt;

use super::{Loc, RuleId};
use crate::diag::Span;

/// `[I n X]` with `X` a rule: `X` here and again at every branch tip, `n`
/// levels in all.
#[derive(Debug, Clone, PartialEq)]
pub struct Repeat {
    /// `n`.
    pub count: u32,
    /// `X`.
    pub rule: RuleId,
    /// The whole form.
    pub loc: Loc,
}

/// A term in its seed's [`Terms`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TermId(u32);

/// What a slot holds, as built: a term or a repeat already in the arena.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SlotId(u32);

/// The terms of one seed.
#[derive(Clone, Default)]
pub struct Terms {
    nodes: Vec<Node>,
    /// Slot cells of the terms that have a filled slot: 0 empty,
    /// `2k + 1` repeat `k`, `2k + 2` term `k`.
    cells: Vec<u32>,
    repeats: Vec<Repeat>,
}

/// One term: 20 bytes.
#[derive(Clone, Copy)]
struct Node {
    rule: u32,
    /// Slot count, with [`BARE`] set for a bare reference.
    count: u32,
    /// First cell in [`Terms::cells`], or [`NO_CELLS`] when every slot is empty.
    first: u32,
    start: u32,
    end: u32,
}

const BARE: u32 = 1 << 31;
const NO_CELLS: u32 = u32::MAX;

/// Converts an index or offset that the input's size bounds (at most
/// `u32::MAX`, checked where the text is read) to the arena's width.
fn narrow(n: usize) -> u32 {
    u32::try_from(n).expect("term arena: index or offset beyond 4 GiB (input size is checked)")
}

impl Terms {
    /// No terms.
    pub fn new() -> Self {
        Self::default()
    }

    /// How many terms.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Adds a repeat for a slot.
    pub fn repeat(&mut self, r: Repeat) -> SlotId {
        self.repeats.push(r);
        SlotId(narrow(2 * (self.repeats.len() - 1) + 1))
    }

    /// What a slot holding term `t` holds.
    pub fn slot_of(t: TermId) -> SlotId {
        SlotId(narrow(2 * t.0 as usize + 2))
    }

    /// The term a slot built by [`Terms::slot_of`] holds.
    ///
    /// # Panics
    /// If `s` holds a repeat.
    pub fn term_of(s: SlotId) -> TermId {
        assert!(
            s.0 >= 2 && s.0.is_multiple_of(2),
            "term arena: slot {s:?} holds no term"
        );
        TermId(s.0 / 2 - 1)
    }

    /// Adds the term `rule{slots}` (a bare reference `rule` if `bare`),
    /// written at `loc`, whose slots hold terms and repeats built before it.
    pub fn push(
        &mut self,
        rule: RuleId,
        bare: bool,
        loc: Span,
        slots: &[Option<SlotId>],
    ) -> TermId {
        if slots.iter().all(Option::is_none) {
            return self.push_leaf(rule, bare, loc, slots.len());
        }
        let first = narrow(self.cells.len());
        self.cells
            .extend(slots.iter().map(|s| s.map_or(0, |SlotId(c)| c)));
        self.push_node(rule, bare, loc, slots.len(), first)
    }

    /// Adds the term `rule{,...}` with `count` empty slots (a bare
    /// reference `rule` if `bare`): no cells, no list of empty slots.
    pub fn push_leaf(&mut self, rule: RuleId, bare: bool, loc: Span, count: usize) -> TermId {
        self.push_node(rule, bare, loc, count, NO_CELLS)
    }

    fn push_node(
        &mut self,
        rule: RuleId,
        bare: bool,
        loc: Span,
        count: usize,
        first: u32,
    ) -> TermId {
        let count = narrow(count);
        assert!(count < BARE, "term arena: more than 2^31 slots");
        self.nodes.push(Node {
            rule: narrow(rule.0),
            count: count | if bare { BARE } else { 0 },
            first,
            start: narrow(loc.start),
            end: narrow(loc.end),
        });
        TermId(narrow(self.nodes.len() - 1))
    }

    /// The term `id`.
    pub fn get(&self, id: TermId) -> Term<'_> {
        Term { terms: self, id }
    }
}

impl fmt::Debug for Terms {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Terms")
            .field("terms", &self.nodes.len())
            .field("filled_slots", &self.cells.len())
            .field("repeats", &self.repeats.len())
            .finish()
    }
}

/// A term, read from its arena: `X{s1,...,sm}`, rule `X` drawn here, slot
/// `i` growing at the tip of branch `i`.
#[derive(Clone, Copy)]
pub struct Term<'a> {
    terms: &'a Terms,
    id: TermId,
}

/// What grows at a branch tip.
#[derive(Clone, Copy, Debug)]
pub enum Slot<'a> {
    /// Another term (or bare reference).
    Term(Term<'a>),
    /// `[I n X]`.
    Repeat(&'a Repeat),
}

impl<'a> Term<'a> {
    fn node(self) -> Node {
        self.terms.nodes[self.id.0 as usize]
    }

    /// Which term of its arena this is.
    pub fn id(self) -> TermId {
        self.id
    }

    /// The rule.
    pub fn rule(self) -> RuleId {
        RuleId(self.node().rule as usize)
    }

    /// Written as a bare name (`R1`) rather than `R1{...}`. In an OD a bare
    /// reference is a growth point. In a BED a bare name means every slot
    /// empty, so the BED parser stores it as not bare, with empty slots
    /// (the writer always writes the full form).
    pub fn bare(self) -> bool {
        self.node().count & BARE != 0
    }

    /// The whole term in the text.
    pub fn loc(self) -> Span {
        let n = self.node();
        n.start as usize..n.end as usize
    }

    /// How many slots (the rule's branch count, if it is right).
    pub fn slot_count(self) -> usize {
        (self.node().count & !BARE) as usize
    }

    /// Whether every slot is empty.
    pub fn all_empty(self) -> bool {
        self.node().first == NO_CELLS
    }

    /// Slot `i`: `None` if it is empty or there is no slot `i`.
    pub fn slot(self, i: usize) -> Option<Slot<'a>> {
        let n = self.node();
        if n.first == NO_CELLS || i >= (n.count & !BARE) as usize {
            return None;
        }
        let c = self.terms.cells[n.first as usize + i];
        match c {
            0 => None,
            c if !c.is_multiple_of(2) => Some(Slot::Repeat(&self.terms.repeats[(c / 2) as usize])),
            c => Some(Slot::Term(self.terms.get(TermId(c / 2 - 1)))),
        }
    }

    /// The slots in order, `None` for an empty one.
    pub fn slots(self) -> impl Iterator<Item = Option<Slot<'a>>> {
        (0..self.slot_count()).map(move |i| self.slot(i))
    }
}

/// Terms are equal when they have the same shape: rules, bareness, slots,
/// repeats, all the way down (locations and arena order never count).
/// Compared with an explicit stack.
impl PartialEq for Term<'_> {
    fn eq(&self, other: &Self) -> bool {
        let mut stack = vec![(*self, *other)];
        while let Some((a, b)) = stack.pop() {
            if a.rule() != b.rule() || a.bare() != b.bare() || a.slot_count() != b.slot_count() {
                return false;
            }
            for pair in a.slots().zip(b.slots()) {
                match pair {
                    (None, None) => {}
                    (Some(Slot::Term(x)), Some(Slot::Term(y))) => stack.push((x, y)),
                    (Some(Slot::Repeat(x)), Some(Slot::Repeat(y))) if x == y => {}
                    _ => return false,
                }
            }
        }
        true
    }
}

/// Shows the term's own fields and its slots' kinds, one level only (a
/// term can nest as deep as the input does).
impl fmt::Debug for Term<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        /// A slot, one level deep.
        struct Shallow<'a>(Option<Slot<'a>>);
        impl fmt::Debug for Shallow<'_> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                match self.0 {
                    None => f.write_str("None"),
                    Some(Slot::Term(t)) => write!(f, "Term({:?}, ..)", t.rule()),
                    Some(Slot::Repeat(r)) => write!(f, "Repeat({} {:?})", r.count, r.rule),
                }
            }
        }
        let slots: Vec<Shallow<'_>> = self.slots().map(Shallow).collect();
        f.debug_struct("Term")
            .field("rule", &self.rule())
            .field("bare", &self.bare())
            .field("slots", &slots)
            .field("loc", &self.loc())
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn repeat(t: &mut Terms, count: u32) -> Option<SlotId> {
        Some(t.repeat(Repeat {
            count,
            rule: RuleId(0),
            loc: Loc(0..1),
        }))
    }

    /// `R0{R1{[I n R0],},,R{k}{,}}` in a fresh arena.
    fn sample(inner_count: u32, inner_rule: usize) -> (Terms, TermId) {
        let mut t = Terms::new();
        let r = repeat(&mut t, inner_count);
        let a = t.push(RuleId(1), false, 0..1, &[r, None]);
        let b = t.push(RuleId(inner_rule), false, 0..1, &[None, None]);
        let root = t.push(
            RuleId(0),
            false,
            0..1,
            &[Some(Terms::slot_of(a)), None, Some(Terms::slot_of(b))],
        );
        (t, root)
    }

    #[test]
    fn terms_read_back_as_built() {
        let (t, root) = sample(2, 0);
        let r = t.get(root);
        assert_eq!(
            (r.rule(), r.bare(), r.slot_count(), r.all_empty()),
            (RuleId(0), false, 3, false)
        );
        let Some(Slot::Term(a)) = r.slot(0) else {
            panic!("slot 0 holds a term")
        };
        assert_eq!(a.rule(), RuleId(1));
        assert!(matches!(
            a.slot(0),
            Some(Slot::Repeat(Repeat { count: 2, .. }))
        ));
        assert!(a.slot(1).is_none() && r.slot(1).is_none() && r.slot(3).is_none());
        let Some(Slot::Term(b)) = r.slot(2) else {
            panic!("slot 2 holds a term")
        };
        assert!(b.all_empty() && b.slot_count() == 2 && b.slot(0).is_none());
        // A leaf takes no cells: only the two terms with a filled slot do.
        assert_eq!(t.cells.len(), 2 + 3);
        let bare = {
            let mut u = Terms::new();
            let id = u.push(RuleId(4), true, 3..5, &[None]);
            (u.get(id).bare(), u.get(id).loc(), u.get(id).slot_count())
        };
        assert_eq!(bare, (true, 3..5, 1));
    }

    #[test]
    fn terms_are_equal_by_shape_not_by_place() {
        let (a, ra) = sample(2, 0);
        assert!(a.get(ra) == a.get(ra));
        let (b, rb) = sample(2, 0);
        assert!(a.get(ra) == b.get(rb));
        let (c, rc) = sample(3, 0);
        assert!(a.get(ra) != c.get(rc), "a repeat count deep inside");
        let (d, rd) = sample(2, 1);
        assert!(a.get(ra) != d.get(rd), "the last slot's rule");
        // The same shape built in another order, at other places.
        let mut e = Terms::new();
        let leaf = e.push(RuleId(0), false, 7..9, &[None, None]);
        let r = repeat(&mut e, 2);
        let inner = e.push(RuleId(1), false, 9..12, &[r, None]);
        let re = e.push(
            RuleId(0),
            false,
            0..30,
            &[
                Some(Terms::slot_of(inner)),
                None,
                Some(Terms::slot_of(leaf)),
            ],
        );
        assert!(a.get(ra) == e.get(re));
        // Empty slots against a repeat, and slot counts.
        let mut f = Terms::new();
        let x = f.push(RuleId(0), false, 0..1, &[None, None]);
        let y = repeat(&mut f, 1);
        let z = f.push(RuleId(0), false, 0..1, &[y, None]);
        let w = f.push(RuleId(0), false, 0..1, &[None]);
        assert!(f.get(x) != f.get(z) && f.get(x) != f.get(w));
    }

    /// A chain a million terms deep compares without recursion.
    #[test]
    fn deep_chains_compare_without_recursion() {
        let chain = |t: &mut Terms| {
            let mut id = t.push(RuleId(0), false, 0..1, &[None]);
            for _ in 0..1_000_000 {
                id = t.push(RuleId(0), false, 0..1, &[Some(Terms::slot_of(id))]);
            }
            id
        };
        let (mut a, mut b) = (Terms::new(), Terms::new());
        let (ra, rb) = (chain(&mut a), chain(&mut b));
        assert!(a.get(ra) == b.get(rb));
        let shallow = format!("{:?}", a.get(ra));
        assert!(shallow.contains("Term(RuleId(0), ..)"), "{shallow}");
    }
}
