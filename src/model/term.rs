//! Branch-expansion terms `X{s1,...,sm}` and `[I n X]`: the recursive part
//! of a seed. Terms nest as deep as the input does, so every trait that would
//! recurse (Clone, PartialEq, Drop, Debug) is written with an explicit stack
//! or a depth cap.

use std::fmt;

use super::{Loc, RuleId};

/// `X{s1,...,sm}`: rule `X` drawn here, slot `i` growing at the tip of branch `i`.
///
/// Terms nest as deep as the input does (up to `--max-nesting`), so
/// `Clone`, `PartialEq` and `Drop` are written with explicit stacks rather
/// than derived: derived ones recurse once per level and would overflow a
/// thread's stack on a deeply nested BED. `Debug` shows the first
/// [`DEBUG_DEPTH`] levels and elides the rest.
pub struct Term {
    /// The rule.
    pub rule: RuleId,
    /// One slot per branch of the rule.
    pub slots: SlotList,
    /// Written as a bare name (`R1`) rather than `R1{...}`. In an OD a bare
    /// reference is a growth point. In a BED a bare name means every slot
    /// empty, so the BED parser stores it as `bare: false` with empty slots
    /// (the writer always writes the full form).
    pub bare: bool,
    /// The whole term.
    pub loc: Loc,
}

impl Clone for Term {
    fn clone(&self) -> Self {
        /// A term being copied: its source and the slots copied so far.
        struct Frame<'a> {
            src: &'a Term,
            slots: Vec<Option<Slot>>,
        }
        fn frame(src: &Term) -> Frame<'_> {
            Frame {
                src,
                slots: Vec::with_capacity(src.slots.filled.len()),
            }
        }
        let mut stack = vec![frame(self)];
        loop {
            let top = stack.last_mut().expect("a frame until the root is done");
            if let Some(slot) = top.src.slots.filled.get(top.slots.len()) {
                match slot {
                    None => top.slots.push(None),
                    Some(Slot::Repeat(r)) => top.slots.push(Some(Slot::Repeat(r.clone()))),
                    Some(Slot::Term(t)) => stack.push(frame(t)),
                }
                continue;
            }
            let done = stack.pop().expect("the top frame");
            let copy = Term {
                rule: done.src.rule,
                slots: SlotList {
                    filled: done.slots.into_boxed_slice(),
                    len: done.src.slots.len,
                },
                bare: done.src.bare,
                loc: done.src.loc.clone(),
            };
            match stack.last_mut() {
                Some(parent) => parent.slots.push(Some(Slot::Term(copy))),
                None => return copy,
            }
        }
    }
}

impl PartialEq for Term {
    fn eq(&self, other: &Self) -> bool {
        let mut stack = vec![(self, other)];
        while let Some((a, b)) = stack.pop() {
            if a.rule != b.rule
                || a.bare != b.bare
                || a.loc != b.loc
                || a.slots.len() != b.slots.len()
            {
                return false;
            }
            for pair in a.slots.iter().zip(b.slots.iter()) {
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

impl Drop for Term {
    fn drop(&mut self) {
        // Detach every nested term's slots before it is dropped, so each
        // drop below meets empty slots and nothing recurses.
        let mut pending = std::mem::take(&mut self.slots.filled).into_vec();
        while let Some(slot) = pending.pop() {
            if let Some(Slot::Term(mut t)) = slot {
                pending.extend(std::mem::take(&mut t.slots.filled));
            }
        }
    }
}

/// How many levels of nested terms `{:?}` shows; deeper terms print as
/// `Term { rule: .., .. }`. Formatting recurses once per level shown, so the
/// cap keeps `{:?}` of a hostile, 10 000-deep term within an ordinary stack.
pub const DEBUG_DEPTH: usize = 32;

impl fmt::Debug for Term {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        TermDebug(self, DEBUG_DEPTH).fmt(f)
    }
}

/// A term formatted with `levels` more levels of nesting to show.
struct TermDebug<'a>(&'a Term, usize);

/// A slot inside a [`TermDebug`].
struct SlotDebug<'a>(Option<&'a Slot>, usize);

impl fmt::Debug for TermDebug<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let TermDebug(term, levels) = *self;
        let mut s = f.debug_struct("Term");
        s.field("rule", &term.rule);
        if levels == 0 {
            return s.finish_non_exhaustive();
        }
        let slots: Vec<SlotDebug<'_>> = term
            .slots
            .iter()
            .map(|slot| SlotDebug(slot, levels - 1))
            .collect();
        s.field("slots", &slots)
            .field("bare", &term.bare)
            .field("loc", &term.loc)
            .finish()
    }
}

impl fmt::Debug for SlotDebug<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        /// The slot inside `Some(..)`.
        struct Inner<'a>(&'a Slot, usize);
        impl fmt::Debug for Inner<'_> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                match self.0 {
                    Slot::Term(t) => f.debug_tuple("Term").field(&TermDebug(t, self.1)).finish(),
                    Slot::Repeat(r) => f.debug_tuple("Repeat").field(r).finish(),
                }
            }
        }
        match self.0 {
            None => f.write_str("None"),
            Some(slot) => f.debug_tuple("Some").field(&Inner(slot, self.1)).finish(),
        }
    }
}

/// A term's slots, one per branch of its rule, each empty or holding a
/// [`Slot`]. A term whose slots are all empty (every leaf of a BED, most of
/// its terms) holds no allocation, so a BED of a million leaves costs its
/// terms and no more (docs/limits.md).
#[derive(Default)]
pub struct SlotList {
    /// Every slot, or nothing when all `len` are empty.
    filled: Box<[Option<Slot>]>,
    len: usize,
}

impl SlotList {
    /// `n` empty slots.
    pub fn empty(n: usize) -> Self {
        SlotList {
            filled: Box::default(),
            len: n,
        }
    }

    /// How many slots (the rule's branch count, if it is right).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are no slots (a rule without branches).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether every slot is empty.
    pub fn all_empty(&self) -> bool {
        self.filled.iter().all(Option::is_none)
    }

    /// Slot `i`: `None` if it is empty or there is no slot `i`.
    pub fn get(&self, i: usize) -> Option<&Slot> {
        self.filled.get(i)?.as_ref()
    }

    /// The slots in order, `None` for an empty one.
    pub fn iter(&self) -> impl Iterator<Item = Option<&Slot>> + '_ {
        (0..self.len).map(|i| self.get(i))
    }
}

impl From<Vec<Option<Slot>>> for SlotList {
    fn from(v: Vec<Option<Slot>>) -> Self {
        let len = v.len();
        if v.iter().all(Option::is_none) {
            return SlotList::empty(len);
        }
        SlotList {
            filled: v.into_boxed_slice(),
            len,
        }
    }
}

impl fmt::Debug for SlotList {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Shallow: a `Term`'s own Debug shows slots with its depth cap.
        f.debug_struct("SlotList")
            .field("len", &self.len)
            .field("filled", &!self.filled.is_empty())
            .finish()
    }
}

/// What grows at a branch tip.
#[derive(Debug, Clone, PartialEq)]
pub enum Slot {
    /// Another term (or bare reference).
    Term(Term),
    /// `[I n X]`.
    Repeat(Repeat),
}

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

#[cfg(test)]
mod tests {
    use super::*;

    fn term(rule: usize, slots: Vec<Option<Slot>>) -> Term {
        Term {
            rule: RuleId(rule),
            slots: slots.into(),
            bare: false,
            loc: Loc(0..1),
        }
    }

    fn repeat(count: u32) -> Option<Slot> {
        Some(Slot::Repeat(Repeat {
            count,
            rule: RuleId(0),
            loc: Loc(0..1),
        }))
    }

    /// `R1{R2{[I 2 R1],},,R1{,}}` and variants differing in one place.
    fn sample(inner_count: u32, inner_rule: usize) -> Term {
        term(
            0,
            vec![
                Some(Slot::Term(term(1, vec![repeat(inner_count), None]))),
                None,
                Some(Slot::Term(term(inner_rule, vec![None, None]))),
            ],
        )
    }

    #[test]
    fn terms_clone_equal_and_differ_where_they_differ() {
        let a = sample(2, 0);
        let copy = a.clone();
        assert!(copy == a);
        assert!(sample(3, 0) != a, "a repeat count deep inside");
        assert!(sample(2, 1) != a, "the last slot's rule");
        let with = |slots: Vec<Option<Slot>>| term(0, slots);
        let mut slots = vec![a.slots.get(0).cloned(), repeat(2), a.slots.get(2).cloned()];
        assert!(with(slots.clone()) != a, "empty slot against a repeat");
        slots[1] = None;
        assert!(with(slots.clone()) == a, "the same slots rebuilt");
        slots.pop();
        assert!(with(slots) != a, "slot count");
        // All-empty slots compare by count, however they were built.
        assert!(SlotList::from(vec![None, None]).len() == 2);
        let mut empty = term(0, vec![]);
        empty.slots = SlotList::empty(2);
        assert!(term(0, vec![None, None]) == empty);
        assert!(term(0, vec![None]) != term(0, vec![None, None]));
        // Locations never count.
        let mut moved = a.clone();
        moved.loc = Loc(5..9);
        assert!(moved == a);
    }

    /// `{:?}` reads like the derived form for shallow terms and stops at
    /// `DEBUG_DEPTH` levels for deep ones.
    #[test]
    fn debug_shows_shallow_terms_whole_and_elides_deep_ones() {
        assert_eq!(
            format!("{:?}", term(0, vec![None, repeat(2)])),
            "Term { rule: RuleId(0), slots: [None, Some(Repeat(Repeat { count: 2, \
             rule: RuleId(0), loc: Loc(0..1) }))], bare: false, loc: Loc(0..1) }"
        );
        let mut deep = term(0, vec![None]);
        for _ in 0..50_000 {
            deep = term(0, vec![Some(Slot::Term(deep))]);
        }
        let text = format!("{deep:?}");
        assert_eq!(text.matches("Term {").count(), DEBUG_DEPTH + 1);
        assert!(text.contains("Term { rule: RuleId(0), .. }"));
        let pretty = format!("{deep:#?}");
        assert_eq!(pretty.matches("Term {").count(), DEBUG_DEPTH + 1);
    }
}
