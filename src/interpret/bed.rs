//! Expansion of Branch-Expansion Descriptions into drawing components.
//!
//! A term `X{s1,...,sm}` at order c emits `Enter`, then X's body in written
//! order (trunk runs, fixed figures, branches as `[ ... ]`) with slot i's
//! expansion inserted just before branch i's closing `]`, then `Leave`. The
//! successor name at the end of a branch draws nothing in a BED. So with
//! `R1 = [F][+F][-F]` and `R2 = [++F][-F]`, `R1{R1{,,},R2{,},R1{,,}}` is
//! `[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]`.
//!
//! - `[I n X]`, X a rule: `X`, with `[I n-1 X]` in every slot (`n` levels).
//! - `[I n w]`, w drawing components: `F` rewritten by `w`, `n - 1` times on
//!   `w` itself (`[I 1 w]` is `w`), drawn at the current order.
//!
//! [`Derivation::Dfs`] streams the operations with an explicit stack and never
//! builds the expanded word (memory grows with nesting depth only);
//! [`Derivation::Bfs`] rewrites the whole word level by level (refusing words
//! longer than `limits.max_word`), then interprets it. Both feed the same
//! [`Interp`], so their segments agree bit for bit.

use std::io::Write;

use crate::bed::Bed;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use crate::interpret::Derivation;
use crate::limits::Limits;
use crate::model::{BodyItem, Description, Piece, RuleDef, RuleId, Seed, SeedItem, Slot, Term};
use crate::progress::Progress;
use crate::turtle::{Interp, Op};
use crate::turtle::{Point, Turtle};

/// How often (in operations) progress is reported.
const PROGRESS_EVERY: u64 = 1 << 16;

/// Draws a BED's seed into `turtle`: the turtle starts at the root, heading
/// up, order 0; stems of order k have length `L - k*dL`.
pub fn draw(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    draw_into(bed, strategy, limits, turtle, progress).map(|_| ())
}

/// [`draw`] into a turtle of a known type, which is handed back.
pub fn draw_into<T: Turtle>(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    turtle: T,
    progress: &mut dyn Progress,
) -> Result<T, Diagnostics> {
    let desc = bed.description();
    let p = &desc.params;
    let mut interp = Interp::new(
        turtle,
        Point::new(desc.root.0, desc.root.1),
        p.angle(),
        p.length,
    );
    ops(bed, strategy, limits, progress, &mut |op| {
        interp.apply(op);
        Ok(())
    })?;
    Ok(interp.into_turtle())
}

/// Prints the seed's expansion as drawing components (`F f + - [ ] |`; `L`
/// and `R` come out as `+` and `-`), then a newline. Streams with `dfs`.
pub fn expand(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
    let flush = |buf: &mut Vec<u8>, out: &mut dyn Write| -> Result<(), Diagnostics> {
        out.write_all(buf)
            .map_err(|e| io_error(&e, "writing the expansion"))?;
        buf.clear();
        Ok(())
    };
    ops(bed, strategy, limits, progress, &mut |op| {
        match op {
            Op::Draw => buf.push(b'F'),
            Op::Move => buf.push(b'f'),
            Op::Turn(n) => {
                let c = if n >= 0 { b'+' } else { b'-' };
                for _ in 0..n.unsigned_abs() {
                    buf.push(c);
                }
            }
            Op::Flip => buf.push(b'|'),
            Op::Push => buf.push(b'['),
            Op::Pop => buf.push(b']'),
            Op::Enter | Op::Leave => {}
        }
        if buf.len() >= 1 << 16 {
            flush(&mut buf, out)?;
        }
        Ok(())
    })?;
    buf.push(b'\n');
    flush(&mut buf, out)?;
    out.flush()
        .map_err(|e| io_error(&e, "writing the expansion"))?;
    Ok(())
}

/// The stream of turtle operations a description's seed denotes, fed to
/// `sink` in order.
pub fn ops(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    progress: &mut dyn Progress,
    sink: &mut dyn FnMut(Op) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let desc = bed.description();
    let Some(seed) = desc.effective_seed() else {
        return Ok(());
    };
    let seed: &Seed = &seed;
    let total = bed.size().symbols;
    progress.start("symbols", total);
    let mut done = 0u64;
    let mut counted = |op: Op| -> Result<(), Diagnostics> {
        done += 1;
        if done % PROGRESS_EVERY == 0 {
            progress.update(done);
        }
        sink(op)
    };
    let r = match strategy {
        Derivation::Dfs => dfs(desc, seed, &mut counted),
        Derivation::Bfs => bfs(desc, seed, limits, &mut counted),
    };
    progress.finish();
    r
}

fn op_of(c: u8) -> Option<Op> {
    Op::of_stl(char::from(c))
}

fn emit_text(
    text: &str,
    sink: &mut dyn FnMut(Op) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    for b in text.bytes() {
        if let Some(op) = op_of(b) {
            sink(op)?;
        }
    }
    Ok(())
}

/// What grows in the slots of one rule application.
#[derive(Clone, Copy)]
enum Slots<'a> {
    /// A written term's slots.
    Written(&'a [Option<Slot>]),
    /// `[I n X]` with `n` levels left for the children (0: all empty).
    Repeat(RuleId, u32),
}

impl<'a> Slots<'a> {
    fn child(self, i: usize) -> Option<Child<'a>> {
        match self {
            Slots::Written(s) => match s.get(i)? {
                Some(Slot::Term(t)) => Some(Child::Term(t)),
                Some(Slot::Repeat(r)) => Some(Child::Repeat(r.rule, r.count)),
                None => None,
            },
            Slots::Repeat(_, 0) => None,
            Slots::Repeat(rule, n) => Some(Child::Repeat(rule, n)),
        }
    }
}

/// A rule application to start.
#[derive(Clone, Copy)]
enum Child<'a> {
    Term(&'a Term),
    /// `[I n X]`, `n >= 1`.
    Repeat(RuleId, u32),
}

impl<'a> Child<'a> {
    fn parts(self, desc: &'a Description) -> Option<(&'a RuleDef, Slots<'a>)> {
        match self {
            Child::Term(t) => Some((desc.rules.get(t.rule.0)?, Slots::Written(&t.slots))),
            Child::Repeat(rule, n) => Some((
                desc.rules.get(rule.0)?,
                Slots::Repeat(rule, n.saturating_sub(1)),
            )),
        }
    }
}

enum Frame<'a> {
    /// A rule application's body, from item `item`; `branch` branches done.
    Body {
        rule: &'a RuleDef,
        slots: Slots<'a>,
        item: usize,
        branch: usize,
    },
    /// A branch's pieces from `idx`.
    Pieces { pieces: &'a [Piece], idx: usize },
    /// `[I n w]`'s word from `idx`, each `F` rewritten `r` more times.
    Fix { word: &'a [u8], idx: usize, r: u32 },
    /// Start a rule application (a slot's content).
    Start(Child<'a>),
    /// Emit one operation (the `]` closing a branch).
    Emit(Op),
}

/// Depth-first streaming with an explicit stack.
fn dfs(
    desc: &Description,
    seed: &Seed,
    sink: &mut dyn FnMut(Op) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let mut stack: Vec<Frame<'_>> = Vec::new();
    for item in &seed.items {
        match item {
            SeedItem::Draw(d) => emit_text(&d.text, sink)?,
            SeedItem::Fixed(f) => stack.push(Frame::Fix {
                word: f.word.as_bytes(),
                idx: 0,
                r: f.count.saturating_sub(1),
            }),
            SeedItem::Term(t) => stack.push(Frame::Start(Child::Term(t))),
            SeedItem::Repeat(r) => stack.push(Frame::Start(Child::Repeat(r.rule, r.count))),
        }
        while let Some(top) = stack.last_mut() {
            match top {
                Frame::Body {
                    rule,
                    slots,
                    item,
                    branch,
                } => {
                    let Some(it) = rule.body.items.get(*item) else {
                        stack.pop();
                        sink(Op::Leave)?;
                        continue;
                    };
                    *item += 1;
                    match it {
                        BodyItem::Draw(d) => emit_text(&d.text, sink)?,
                        BodyItem::Fixed(f) => stack.push(Frame::Fix {
                            word: f.word.as_bytes(),
                            idx: 0,
                            r: f.count.saturating_sub(1),
                        }),
                        BodyItem::Branch(b) => {
                            let child = slots.child(*branch);
                            *branch += 1;
                            sink(Op::Push)?;
                            stack.push(Frame::Emit(Op::Pop));
                            if let Some(c) = child {
                                stack.push(Frame::Start(c));
                            }
                            stack.push(Frame::Pieces {
                                pieces: &b.pieces,
                                idx: 0,
                            });
                        }
                    }
                }
                Frame::Pieces { pieces, idx } => {
                    let Some(p) = pieces.get(*idx) else {
                        stack.pop();
                        continue;
                    };
                    *idx += 1;
                    match p {
                        Piece::Draw(d) => emit_text(&d.text, sink)?,
                        Piece::Fixed(f) => stack.push(Frame::Fix {
                            word: f.word.as_bytes(),
                            idx: 0,
                            r: f.count.saturating_sub(1),
                        }),
                    }
                }
                Frame::Fix { word, idx, r } => {
                    let Some(&c) = word.get(*idx) else {
                        stack.pop();
                        continue;
                    };
                    *idx += 1;
                    if c == b'F' && *r > 0 {
                        let (word, r) = (*word, *r - 1);
                        stack.push(Frame::Fix { word, idx: 0, r });
                    } else if let Some(op) = op_of(c) {
                        sink(op)?;
                    }
                }
                Frame::Start(c) => {
                    let c = *c;
                    stack.pop();
                    if let Some((rule, slots)) = c.parts(desc) {
                        sink(Op::Enter)?;
                        stack.push(Frame::Body {
                            rule,
                            slots,
                            item: 0,
                            branch: 0,
                        });
                    }
                }
                Frame::Emit(op) => {
                    let op = *op;
                    stack.pop();
                    sink(op)?;
                }
            }
        }
    }
    Ok(())
}

/// One symbol of the breadth-first word.
#[derive(Clone, Copy)]
enum Sym<'a> {
    Op(Op),
    Apply(Child<'a>),
    Fix(&'a [u8], u32),
}

/// Breadth-first rewriting: the whole word, level by level, then interpreted.
fn bfs(
    desc: &Description,
    seed: &Seed,
    limits: &Limits,
    sink: &mut dyn FnMut(Op) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let mut word: Vec<Sym<'_>> = Vec::new();
    let push_text = |w: &mut Vec<Sym<'_>>, text: &str| {
        w.extend(text.bytes().filter_map(op_of).map(Sym::Op));
    };
    for item in &seed.items {
        match item {
            SeedItem::Draw(d) => push_text(&mut word, &d.text),
            SeedItem::Fixed(f) => word.push(Sym::Fix(f.word.as_bytes(), f.count.saturating_sub(1))),
            SeedItem::Term(t) => word.push(Sym::Apply(Child::Term(t))),
            SeedItem::Repeat(r) => word.push(Sym::Apply(Child::Repeat(r.rule, r.count))),
        }
    }
    let too_long = |len: usize| -> Result<(), Diagnostics> {
        if len as u64 > limits.max_word {
            return Err(Diagnostic::error(ErrorKind::Limit {
                what: "bfs word length".into(),
                value: len.to_string(),
                limit: limits.max_word.to_string(),
            })
            .with_help(
                "raise the limit with --max-word N, or use --strategy dfs, which needs no word",
            )
            .into());
        }
        Ok(())
    };
    too_long(word.len())?;
    while word.iter().any(|s| !matches!(s, Sym::Op(_))) {
        let mut next: Vec<Sym<'_>> = Vec::with_capacity(word.len() * 2);
        for s in &word {
            match *s {
                Sym::Op(op) => next.push(Sym::Op(op)),
                Sym::Fix(w, r) => {
                    for &c in w {
                        if c == b'F' && r > 0 {
                            next.push(Sym::Fix(w, r - 1));
                        } else if let Some(op) = op_of(c) {
                            next.push(Sym::Op(op));
                        }
                    }
                }
                Sym::Apply(c) => {
                    let Some((rule, slots)) = c.parts(desc) else {
                        continue;
                    };
                    next.push(Sym::Op(Op::Enter));
                    let mut branch = 0;
                    for item in &rule.body.items {
                        match item {
                            BodyItem::Draw(d) => push_text(&mut next, &d.text),
                            BodyItem::Fixed(f) => {
                                next.push(Sym::Fix(f.word.as_bytes(), f.count.saturating_sub(1)))
                            }
                            BodyItem::Branch(b) => {
                                next.push(Sym::Op(Op::Push));
                                for p in &b.pieces {
                                    match p {
                                        Piece::Draw(d) => push_text(&mut next, &d.text),
                                        Piece::Fixed(f) => next.push(Sym::Fix(
                                            f.word.as_bytes(),
                                            f.count.saturating_sub(1),
                                        )),
                                    }
                                }
                                if let Some(c) = slots.child(branch) {
                                    next.push(Sym::Apply(c));
                                }
                                branch += 1;
                                next.push(Sym::Op(Op::Pop));
                            }
                        }
                    }
                    next.push(Sym::Op(Op::Leave));
                }
            }
            too_long(next.len())?;
        }
        word = next;
    }
    for s in word {
        if let Sym::Op(op) = s {
            sink(op)?;
        }
    }
    Ok(())
}
