//! The one walk over a seed.
//!
//! Every pass over a seed (measuring, validation, the writer, growth's
//! flattening and its grown seed, BED expansion `dfs` and `bfs`) sees it as
//! the same sequence of [`SeedStep`]s, from one iterator, [`SeedWalk`],
//! with an explicit stack (terms written out in a seed nest as deep as the
//! input allows). It walks in one of two orders:
//!
//! - **written** ([`SeedWalk::written`]): the items, and each term's slots
//!   in order, every slot once ([`SeedStep::Empty`] for an empty one), each
//!   term closed by [`SeedStep::End`] after its slots. No rule body is
//!   read, so it serves passes over seeds not yet validated.
//! - **drawing** ([`SeedWalk::drawing`]): a term is its rule's body (read
//!   through [`walk::steps`]) between [`SeedStep::Term`] and
//!   [`SeedStep::End`], with slot `i`'s content just before branch `i`'s
//!   [`SeedStep::Close`]. [`Points::Grow`] leaves bare references and
//!   repeats as growth points; [`Points::Expand`] draws a bare reference
//!   as its rule with every slot empty and unrolls every `[I n X]` by
//!   [`walk::Levels`], the one repeat expander.

use super::walk::{self, Levels, Step, Steps};
use super::{Body, DrawRun, Fixed, Repeat, RuleDef, RuleId, Seed, SeedItem, Slot, Term};

/// Where a term, a repeat or an empty slot stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum At {
    /// Seed item number `i`, at the top level.
    Item(usize),
    /// Slot `index` of an application with `count` slots.
    Slot {
        /// Which slot.
        index: usize,
        /// How many slots its application has.
        count: usize,
    },
}

impl At {
    /// Whether this is the last slot of its application (never for an item).
    pub fn last_slot(self) -> bool {
        matches!(self, At::Slot { index, count } if index + 1 == count)
    }
}

/// One step of a seed.
#[derive(Debug, Clone, Copy)]
pub enum SeedStep<'a> {
    /// Drawing components: written in the seed, or (in drawing order) a
    /// run of an applied rule's body.
    Run(&'a DrawRun),
    /// A fixed figure `[I n w]`, of the seed or of an applied body.
    Fixed(&'a Fixed),
    /// A term (or bare reference) begins: its rule is applied at `order`
    /// (1 for an item of the seed). Its slots (written order) or its body
    /// (drawing order) follow, then its [`SeedStep::End`], unless the
    /// caller [steps over](SeedWalk::step_over) them. In drawing order with
    /// [`Points::Grow`] a bare reference is a growth point: nothing of it
    /// follows.
    Term {
        /// The term.
        term: Term<'a>,
        /// Its order.
        order: u32,
        /// Where it stands.
        at: At,
    },
    /// `[I n X]`, left whole (written order, or drawing with
    /// [`Points::Grow`]): its first level would be applied at `order`.
    Repeat {
        /// The repeat.
        repeat: &'a Repeat,
        /// The order of its first level.
        order: u32,
        /// Where it stands.
        at: At,
    },
    /// One level of an unrolled `[I n X]` ([`Points::Expand`]): `X` applied
    /// at `order` with `levels` levels from here down; its body follows,
    /// with the next level in every slot, then its [`SeedStep::End`].
    Level {
        /// `X`.
        rule: RuleId,
        /// Levels from this one down (at least 1).
        levels: Levels,
        /// Its order.
        order: u32,
        /// Where it stands.
        at: At,
    },
    /// An empty slot (written order only: in drawing order an empty slot is
    /// just its branch's [`SeedStep::Close`]).
    Empty {
        /// The order its content would have had.
        order: u32,
        /// Which slot.
        at: At,
    },
    /// Drawing order: a branch's `[`.
    Open,
    /// Drawing order: a branch's `]`, after what grew in its slot.
    Close,
    /// The application begun last at `order`, standing at `at`, ends.
    End {
        /// Its order.
        order: u32,
        /// Where it stood.
        at: At,
    },
}

/// What the drawing order does with the seed's growth points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Points {
    /// Bare references and repeats are growth points, stepped over whole
    /// (growth decides them).
    Grow,
    /// Bare references are their rule with every slot empty, repeats are
    /// unrolled (a BED draws them).
    Expand,
}

/// What grows in the slots of an application in drawing order.
#[derive(Debug, Clone, Copy)]
enum Slots<'a> {
    /// A term's slots.
    Term(Term<'a>),
    /// A repeat's level: the next level in every slot, or nothing.
    Level(RuleId, Option<Levels>),
}

#[derive(Debug, Clone)]
enum Frame<'a> {
    /// Written order: a term, its next slot.
    Slots {
        term: Term<'a>,
        next: usize,
        order: u32,
        at: At,
    },
    /// Drawing order: an application's body.
    Body {
        steps: Steps<'a>,
        slots: Slots<'a>,
        count: usize,
        order: u32,
        at: At,
    },
    /// Drawing order: a branch's `]`, once its slot's content is done.
    Close,
}

/// The body of a rule the description does not declare (only a program
/// can refer to one; validation and growth report it).
static NO_BODY: Body = Body { items: Vec::new() };

/// Iterator of a seed's [`SeedStep`]s.
#[derive(Debug, Clone)]
pub struct SeedWalk<'a> {
    seed: &'a Seed,
    /// Next item.
    item: usize,
    /// The rules, in drawing order.
    rules: Option<&'a [RuleDef]>,
    points: Points,
    stack: Vec<Frame<'a>>,
    /// The last step pushed a frame (a term's or a level's).
    entered: bool,
}

impl<'a> SeedWalk<'a> {
    /// The seed in written order.
    pub fn written(seed: &'a Seed) -> Self {
        SeedWalk {
            seed,
            item: 0,
            rules: None,
            points: Points::Grow,
            stack: Vec::new(),
            entered: false,
        }
    }

    /// The seed in drawing order, its terms applying `rules`.
    pub fn drawing(seed: &'a Seed, rules: &'a [RuleDef], points: Points) -> Self {
        SeedWalk {
            rules: Some(rules),
            points,
            ..SeedWalk::written(seed)
        }
    }

    /// Only item `i` of the seed, in written order.
    pub fn item(seed: &'a Seed, i: usize) -> impl Iterator<Item = SeedStep<'a>> {
        let mut w = SeedWalk::written(seed);
        w.item = i;
        let mut first = true;
        std::iter::from_fn(move || {
            if !first && w.stack.is_empty() {
                return None;
            }
            first = false;
            w.step()
        })
    }

    /// Right after a [`SeedStep::Term`] or [`SeedStep::Level`]: leaves out
    /// what follows of it (its slots or body, and its `End`).
    pub fn step_over(&mut self) {
        if std::mem::take(&mut self.entered) {
            self.stack.pop();
        }
    }

    fn body(&self, rule: RuleId) -> &'a Body {
        match self.rules.and_then(|r| r.get(rule.0)) {
            Some(r) => &r.body,
            None => &NO_BODY,
        }
    }

    fn term(&mut self, term: Term<'a>, order: u32, at: At) -> SeedStep<'a> {
        let step = SeedStep::Term { term, order, at };
        if self.rules.is_none() {
            self.stack.push(Frame::Slots {
                term,
                next: 0,
                order,
                at,
            });
        } else if !(term.bare() && self.points == Points::Grow) {
            self.stack.push(Frame::Body {
                steps: walk::steps(self.body(term.rule())),
                slots: Slots::Term(term),
                count: term.slot_count(),
                order,
                at,
            });
        } else {
            return step;
        }
        self.entered = true;
        step
    }

    /// A repeat: whole, or its first level (`None` for `[I 0 X]` unrolled:
    /// nothing at all).
    fn repeat(&mut self, repeat: &'a Repeat, order: u32, at: At) -> Option<SeedStep<'a>> {
        if self.rules.is_none() || self.points == Points::Grow {
            return Some(SeedStep::Repeat { repeat, order, at });
        }
        Some(self.level(repeat.rule, Levels::of(repeat.count)?, order, at))
    }

    fn level(&mut self, rule: RuleId, levels: Levels, order: u32, at: At) -> SeedStep<'a> {
        let body = self.body(rule);
        let count = self
            .rules
            .and_then(|r| r.get(rule.0))
            .map_or(0, RuleDef::branch_count);
        self.stack.push(Frame::Body {
            steps: walk::steps(body),
            slots: Slots::Level(rule, levels.next()),
            count,
            order,
            at,
        });
        self.entered = true;
        SeedStep::Level {
            rule,
            levels,
            order,
            at,
        }
    }
}

impl<'a> SeedWalk<'a> {
    /// Calls `each` with every step in turn, stopping at its first error:
    /// the same steps as the iterator, for a hot loop (BED `dfs`), which
    /// gets the walk's own loop compiled into it.
    pub fn try_each<E>(
        mut self,
        mut each: impl FnMut(SeedStep<'a>) -> Result<(), E>,
    ) -> Result<(), E> {
        while let Some(step) = self.step() {
            each(step)?;
        }
        Ok(())
    }
}

impl<'a> Iterator for SeedWalk<'a> {
    type Item = SeedStep<'a>;

    fn next(&mut self) -> Option<SeedStep<'a>> {
        self.step()
    }
}

impl<'a> SeedWalk<'a> {
    #[inline(always)]
    fn step(&mut self) -> Option<SeedStep<'a>> {
        self.entered = false;
        loop {
            let Some(top) = self.stack.last_mut() else {
                let i = self.item;
                let item = self.seed.items.get(i)?;
                self.item += 1;
                let at = At::Item(i);
                return Some(match item {
                    SeedItem::Draw(d) => SeedStep::Run(d),
                    SeedItem::Fixed(f) => SeedStep::Fixed(f),
                    SeedItem::Term(t) => self.term(self.seed.term(*t), 1, at),
                    SeedItem::Repeat(r) => match self.repeat(r, 1, at) {
                        Some(s) => s,
                        None => continue,
                    },
                });
            };
            match top {
                Frame::Close => {
                    self.stack.pop();
                    return Some(SeedStep::Close);
                }
                Frame::Slots {
                    term,
                    next,
                    order,
                    at,
                } => {
                    let (term, order, at) = (*term, *order, *at);
                    let count = term.slot_count();
                    if *next == count {
                        self.stack.pop();
                        return Some(SeedStep::End { order, at });
                    }
                    let index = *next;
                    *next += 1;
                    let at = At::Slot { index, count };
                    let order = order.saturating_add(1);
                    return Some(match term.slot(index) {
                        None => SeedStep::Empty { order, at },
                        Some(Slot::Term(t)) => self.term(t, order, at),
                        Some(Slot::Repeat(repeat)) => SeedStep::Repeat { repeat, order, at },
                    });
                }
                Frame::Body {
                    steps,
                    slots,
                    count,
                    order,
                    at,
                } => {
                    let index = match steps.next() {
                        Some(Step::Run(r)) => return Some(SeedStep::Run(r)),
                        Some(Step::Fixed(f)) => return Some(SeedStep::Fixed(f)),
                        Some(Step::Open { .. }) => return Some(SeedStep::Open),
                        Some(Step::Tip { index, .. }) => index,
                        None => {
                            let (order, at) = (*order, *at);
                            self.stack.pop();
                            return Some(SeedStep::End { order, at });
                        }
                    };
                    let (slots, order) = (*slots, order.saturating_add(1));
                    let at = At::Slot {
                        index,
                        count: *count,
                    };
                    // The slot's content, then (from the stack) the `]`.
                    self.stack.push(Frame::Close);
                    let content = match slots {
                        Slots::Term(t) => match t.slot(index) {
                            None => None,
                            Some(Slot::Term(t)) => Some(self.term(t, order, at)),
                            Some(Slot::Repeat(r)) => self.repeat(r, order, at),
                        },
                        Slots::Level(_, None) => None,
                        Slots::Level(rule, Some(levels)) => {
                            Some(self.level(rule, levels, order, at))
                        }
                    };
                    if content.is_some() {
                        return content;
                    }
                    // An empty slot, or `[I 0 X]` unrolled: the `]` alone.
                    self.stack.pop();
                    return Some(SeedStep::Close);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::walk::testing::run;
    use crate::model::{BodyItem, Branch, Loc, Piece, Terms};

    /// `R0: F[+F][-F]`.
    fn rules() -> Vec<RuleDef> {
        let branch = |t: &str| {
            BodyItem::Branch(Branch {
                pieces: vec![Piece::Draw(run(t))],
                successor: None,
                loc: Loc::default(),
            })
        };
        vec![RuleDef {
            name: "R0".into(),
            name_loc: Loc::default(),
            alternative: None,
            body: Body {
                items: vec![BodyItem::Draw(run("F")), branch("+F"), branch("-F")],
            },
            loc: Loc::default(),
        }]
    }

    /// `f R0{R0{,}, [I 2 R0]} [I n R0]`.
    fn seed(n: u32) -> Seed {
        let mut terms = Terms::new();
        let leaf = terms.push(RuleId(0), false, 0..0, &[None, None]);
        let rep = |count| Repeat {
            count,
            rule: RuleId(0),
            loc: Loc::default(),
        };
        let two = terms.repeat(rep(2));
        let top = terms.push(
            RuleId(0),
            false,
            0..0,
            &[Some(Terms::slot_of(leaf)), Some(two)],
        );
        Seed {
            items: vec![
                SeedItem::Draw(Box::new(run("f"))),
                SeedItem::Term(top),
                SeedItem::Repeat(Box::new(rep(n))),
            ],
            terms,
            loc: Loc::default(),
        }
    }

    fn show(step: SeedStep<'_>) -> String {
        let at = |at: At| match at {
            At::Item(i) => format!("item {i}"),
            At::Slot { index, count } => format!("slot {index}/{count}"),
        };
        match step {
            SeedStep::Run(r) => r.text.clone(),
            SeedStep::Fixed(f) => format!("[I {} {}]", f.count, f.word),
            SeedStep::Term { order, at: a, .. } => format!("term {order} {}", at(a)),
            SeedStep::Repeat {
                repeat,
                order,
                at: a,
            } => {
                format!("repeat {} {order} {}", repeat.count, at(a))
            }
            SeedStep::Level { levels, order, .. } => format!("level {} {order}", levels.get()),
            SeedStep::Empty { order, at: a } => format!("empty {order} {}", at(a)),
            SeedStep::Open => "[".into(),
            SeedStep::Close => "]".into(),
            SeedStep::End { order, .. } => format!("end {order}"),
        }
    }

    #[test]
    fn written_order_visits_every_slot_once() {
        let s = seed(1);
        let steps: Vec<String> = SeedWalk::written(&s).map(show).collect();
        assert_eq!(
            steps,
            [
                "f",
                "term 1 item 1",
                "term 2 slot 0/2",
                "empty 3 slot 0/2",
                "empty 3 slot 1/2",
                "end 2",
                "repeat 2 2 slot 1/2",
                "end 1",
                "repeat 1 1 item 2",
            ]
        );
        let item1: Vec<String> = SeedWalk::item(&s, 1).map(show).collect();
        assert_eq!(item1, steps[1..8]);
        // Stepping over a term leaves out its slots and its end.
        let mut w = SeedWalk::written(&s);
        w.next();
        w.next();
        w.step_over();
        assert_eq!(w.map(show).collect::<Vec<_>>(), ["repeat 1 1 item 2"]);
    }

    #[test]
    fn drawing_order_puts_slots_at_their_tips_and_unrolls_repeats() {
        let rules = rules();
        let s = seed(1);
        let shown = |points| {
            SeedWalk::drawing(&s, &rules, points)
                .map(show)
                .collect::<Vec<_>>()
                .join(" ")
        };
        // Growth points stay whole.
        assert_eq!(
            shown(Points::Grow),
            "f term 1 item 1 F [ +F term 2 slot 0/2 F [ +F ] [ -F ] end 2 ] \
             [ -F repeat 2 2 slot 1/2 ] end 1 repeat 1 1 item 2"
        );
        // `[I 2 R0]` is R0 with `[I 1 R0]` in both slots; `[I 1 R0]` is R0.
        assert_eq!(
            shown(Points::Expand),
            "f term 1 item 1 F [ +F term 2 slot 0/2 F [ +F ] [ -F ] end 2 ] \
             [ -F level 2 2 F [ +F level 1 3 F [ +F ] [ -F ] end 3 ] \
             [ -F level 1 3 F [ +F ] [ -F ] end 3 ] end 2 ] end 1 \
             level 1 1 F [ +F ] [ -F ] end 1"
        );
        // `[I 0 R0]` unrolled is nothing.
        let s = seed(0);
        let tail: Vec<String> = SeedWalk::drawing(&s, &rules, Points::Expand)
            .map(show)
            .collect();
        assert_eq!(tail.last().map(String::as_str), Some("end 1"));
        assert!(!tail.iter().any(|t| t.starts_with("level 1 1")));
    }

    /// A chain of terms a million deep is walked without recursion.
    #[test]
    fn deep_seeds_walk_without_recursion() {
        let mut terms = Terms::new();
        let mut id = terms.push(RuleId(0), false, 0..0, &[None]);
        for _ in 0..1_000_000 {
            id = terms.push(RuleId(0), false, 0..0, &[Some(Terms::slot_of(id))]);
        }
        let s = Seed {
            items: vec![SeedItem::Term(id)],
            terms,
            loc: Loc::default(),
        };
        let ends = SeedWalk::written(&s)
            .filter(|s| matches!(s, SeedStep::End { .. }))
            .count();
        assert_eq!(ends, 1_000_001);
    }
}
