//! Expansion of Branch-Expansion Descriptions into drawing components.
//!
//! A term `X{s1,...,sm}` at order c emits `Enter`, then X's body in written
//! order (trunk runs, fixed figures, branches as `[ ... ]`) with slot i's
//! expansion inserted just before branch i's closing `]`, then `Leave`. The
//! successor name at the end of a branch draws nothing in a BED. So with
//! `R1 = [F][+F][-F]` and `R2 = [++F][-F]`, `R1{R1{,,},R2{,},R1{,,}}` is
//! `[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]`.
//!
//! - `[I n X]`, X a rule: `X`, with `[I n-1 X]` in every slot (`n` levels;
//!   `[I 0 X]` is nothing), by [`Levels`], the one repeat expander.
//! - `[I n w]`, w drawing components: `F` rewritten by `w`, `n` times
//!   (`[I 1 w]` is `w`), drawn at the current order; [`FixedWord`] expands it.
//!
//! `dfs` reads the seed through the one seed walk ([`SeedWalk`]), `bfs`
//! its items through it and the rule bodies through [`walk::steps`].
//! [`Derivation::Dfs`] streams the operations with an explicit stack and never
//! builds the expanded word (memory grows with nesting depth only);
//! [`Derivation::Bfs`] rewrites the whole word one level of rule
//! applications at a time (refusing words longer than `limits.max_word`),
//! then interprets it. Both issue the same stream of [`Op`]s into the same
//! [`Interp`], so their segments agree bit for bit.

use std::io::Write;

use crate::bed::Bed;
use crate::diag::{Diagnostics, io_error};
use crate::diag::{Help, Knob};
use crate::interpret::Derivation;
use crate::limits::{Bound, Limits};
use crate::model::seed_walk::{Points, SeedStep, SeedWalk};
use crate::model::walk::{self, FixedWord, Levels, Step};
use crate::model::{Description, Fixed, Repeat, RuleDef, RuleId, Seed, Slot, Term};
use crate::progress::Progress;
use crate::turtle::{Interp, Op, State};
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
    stream::<Op>(bed, strategy, limits, progress, &mut |e| {
        match e {
            Event::Tree(_, root) => interp.state = State::start(root),
            Event::Op(op) => interp.apply(op),
        }
        Ok(())
    })?;
    Ok(interp.into_turtle())
}

/// Writes the seed's expansion to `out` as drawing components (`F f + - [ ]
/// |`; `L` and `R` come out as `+` and `-`), then a newline, in pieces of
/// 64 KiB as they come (with `dfs`, while the expansion streams). A
/// forest writes one line per tree, in root order.
pub fn expand(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    write_expansion::<Op>(bed, strategy, limits, out, progress, |op, buf| match op {
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
    })
}

/// Writes the stream of `bed`'s operations to `out`, each spelled by
/// `spell`, a line per tree, in pieces of 64 KiB as they come: the one
/// writer of [`expand`] and the 3D BED's `expand3`.
pub(crate) fn write_expansion<O: StlOp>(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
    mut spell: impl FnMut(O, &mut Vec<u8>),
) -> Result<(), Diagnostics> {
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
    let flush = |buf: &mut Vec<u8>, out: &mut dyn Write| -> Result<(), Diagnostics> {
        out.write_all(buf)
            .map_err(|e| io_error(&e, "writing the expansion"))?;
        buf.clear();
        Ok(())
    };
    let mut trees = 0usize;
    stream::<O>(bed, strategy, limits, progress, &mut |e| {
        match e {
            Event::Tree(..) => {
                trees += 1;
                if trees > 1 {
                    buf.push(b'\n');
                }
            }
            Event::Op(op) => spell(op, &mut buf),
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
/// `sink` in order (a forest's trees one after another, each from its own
/// root: see [`tree_ops`]).
pub fn ops(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    progress: &mut dyn Progress,
    sink: &mut dyn FnMut(Op) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    stream::<Op>(bed, strategy, limits, progress, &mut |e| match e {
        Event::Op(op) => sink(op),
        Event::Tree(..) => Ok(()),
    })
}

/// What [`tree_ops`] emits: a tree starts at its root, or an operation.
#[derive(Debug, Clone, Copy)]
pub enum Emit {
    /// The next tree starts at this root (heading up, order 0), before
    /// its operations; the first tree's too.
    Tree(Point),
    /// A turtle operation.
    Op(Op),
}

/// The operations of every tree, in root order, each tree announced by
/// [`Emit::Tree`] with its root.
pub fn tree_ops(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    progress: &mut dyn Progress,
    sink: &mut dyn FnMut(Emit) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    stream(bed, strategy, limits, progress, &mut |e| match e {
        Event::Tree(_, root) => sink(Emit::Tree(root)),
        Event::Op(op) => sink(Emit::Op(op)),
    })
}

/// A turtle operation a BED's stream is made of: the 2D [`Op`], or a 3D
/// BED's ([`super::bed3::Op3s`]: `& ^ \ /` turn, and a rule application
/// also rolls by `D=`).
pub trait StlOp: Copy {
    /// The operation of a drawing component, if it has one.
    fn of_byte(c: u8) -> Option<Self>;
    /// A rule application starts.
    const ENTER: Self;
    /// It ends.
    const LEAVE: Self;
    /// `[`.
    const PUSH: Self;
    /// `]`.
    const POP: Self;
}

impl StlOp for Op {
    #[inline]
    fn of_byte(c: u8) -> Option<Op> {
        Op::of_stl(char::from(c))
    }
    const ENTER: Op = Op::Enter;
    const LEAVE: Op = Op::Leave;
    const PUSH: Op = Op::Push;
    const POP: Op = Op::Pop;
}

/// What [`stream`] emits: a tree starts (its index in
/// [`Description::trees`] and its root), or an operation.
#[derive(Debug, Clone, Copy)]
pub enum Event<O> {
    /// Tree `i` starts at this root (its `x` and `y`), before its
    /// operations.
    Tree(usize, Point),
    /// A turtle operation.
    Op(O),
}

/// [`tree_ops`] for either kind of operation: every tree's operations, in
/// root order, each tree announced with its index.
pub fn stream<O: StlOp>(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    progress: &mut dyn Progress,
    sink: &mut dyn FnMut(Event<O>) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let desc = bed.description();
    let total = bed.size().symbols;
    progress.start("symbols", total);
    let mut done = 0u64;
    let mut r = Ok(());
    for (i, (root, seed)) in desc.trees().into_iter().enumerate() {
        let Some(seed) = seed else { continue };
        let seed: &Seed = &seed;
        r = sink(Event::Tree(i, Point::new(root.0, root.1)));
        if r.is_err() {
            break;
        }
        let mut counted = |op: O| -> Result<(), Diagnostics> {
            done += 1;
            if done.is_multiple_of(PROGRESS_EVERY) {
                progress.update(done);
            }
            sink(Event::Op(op))
        };
        r = match strategy {
            Derivation::Dfs => dfs(desc, seed, &mut counted),
            Derivation::Bfs => bfs(desc, seed, limits, &mut counted),
        };
        if r.is_err() {
            break;
        }
    }
    progress.finish();
    r
}

#[cfg(test)]
fn op_of(c: u8) -> Option<Op> {
    Op::of_stl(char::from(c))
}

fn emit_text<O: StlOp>(
    text: &str,
    sink: &mut dyn FnMut(O) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    for b in text.bytes() {
        if let Some(op) = O::of_byte(b) {
            sink(op)?;
        }
    }
    Ok(())
}

/// What grows in the slots of one rule application (`bfs`).
#[derive(Clone, Copy)]
enum Slots<'a> {
    /// A written term's slots.
    Written(Term<'a>),
    /// A level of `[I n X]`: the next level in every slot, or nothing.
    Repeat(RuleId, Option<Levels>),
}

impl<'a> Slots<'a> {
    fn child(self, i: usize) -> Option<Child<'a>> {
        match self {
            Slots::Written(t) => match t.slot(i)? {
                Slot::Term(t) => Some(Child::Term(t)),
                Slot::Repeat(r) => Child::repeat(r),
            },
            Slots::Repeat(rule, levels) => Some(Child::Repeat(rule, levels?)),
        }
    }
}

/// A rule application to start (`bfs`).
#[derive(Clone, Copy)]
enum Child<'a> {
    Term(Term<'a>),
    /// A level of `[I n X]`.
    Repeat(RuleId, Levels),
}

impl<'a> Child<'a> {
    /// The first level of `r`, if it has one (`[I 0 X]` applies nothing).
    fn repeat(r: &Repeat) -> Option<Child<'a>> {
        Some(Child::Repeat(r.rule, Levels::of(r.count)?))
    }

    fn parts(self, desc: &'a Description) -> Option<(&'a RuleDef, Slots<'a>)> {
        match self {
            Child::Term(t) => Some((desc.rules.get(t.rule().0)?, Slots::Written(t))),
            Child::Repeat(rule, levels) => {
                Some((desc.rules.get(rule.0)?, Slots::Repeat(rule, levels.next())))
            }
        }
    }
}

/// Emits the operations of the fixed figure `f`, reusing `word`'s stack.
fn emit_fixed<'a, O: StlOp>(
    f: &'a Fixed,
    word: &mut Option<FixedWord<'a>>,
    sink: &mut dyn FnMut(O) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let word = match word {
        Some(w) => {
            w.restart(f);
            w
        }
        None => word.insert(FixedWord::new(f)),
    };
    for c in word {
        if let Some(op) = O::of_byte(c) {
            sink(op)?;
        }
    }
    Ok(())
}

/// Depth-first streaming: the seed in drawing order, bare references and
/// repeats expanded ([`SeedWalk::drawing`]), whose stack holds one frame
/// per rule application in progress, so memory grows with nesting depth
/// only. A fixed figure is streamed whole when it is met (it holds no rule
/// application), by one [`FixedWord`] reused for every figure.
fn dfs<O: StlOp>(
    desc: &Description,
    seed: &Seed,
    sink: &mut dyn FnMut(O) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let mut fixed: Option<FixedWord<'_>> = None;
    SeedWalk::drawing(seed, &desc.rules, Points::Expand).try_each(|step| match step {
        SeedStep::Run(r) => emit_text(&r.text, sink),
        SeedStep::Fixed(f) => emit_fixed(f, &mut fixed, sink),
        SeedStep::Term { .. } | SeedStep::Level { .. } => sink(O::ENTER),
        SeedStep::End { .. } => sink(O::LEAVE),
        SeedStep::Open => sink(O::PUSH),
        SeedStep::Close => sink(O::POP),
        // Not in drawing order with repeats expanded.
        SeedStep::Repeat { .. } | SeedStep::Empty { .. } => Ok(()),
    })
}

/// One symbol of the breadth-first word.
#[derive(Clone, Copy)]
enum Sym<'a, O> {
    Op(O),
    Apply(Child<'a>),
}

/// Refuses a `bfs` word of `len` symbols over `limits.max_word`.
fn check_word(len: u64, limits: &Limits) -> Result<(), Diagnostics> {
    if len > limits.max_word {
        return Err(Bound::Word
            .exceeded(len, limits.max_word)
            .with_help(
                Bound::Word.raise()
                    + ", or use "
                    + Help::knob(Knob::Derivation, "dfs")
                    + ", which needs no word",
            )
            .into());
    }
    Ok(())
}

/// Appends the drawing components of `text` to `word`.
fn push_text<O: StlOp>(word: &mut Vec<Sym<'_, O>>, text: &str) {
    word.extend(text.bytes().filter_map(O::of_byte).map(Sym::Op));
}

/// Appends the fixed figure `f`, whole: it holds no rule application, so it
/// is drawn at the level that meets it. Its length is checked against
/// `limits.max_word` before it is built.
fn push_fixed<O: StlOp>(
    word: &mut Vec<Sym<'_, O>>,
    f: &Fixed,
    limits: &Limits,
) -> Result<(), Diagnostics> {
    let (symbols, _) = walk::fixed_counts(&f.word, f.count);
    check_word((word.len() as u64).saturating_add(symbols), limits)?;
    word.extend(FixedWord::new(f).filter_map(O::of_byte).map(Sym::Op));
    Ok(())
}

/// Breadth-first rewriting: the whole word, one level of rule applications
/// at a time, then interpreted. Every level is checked against
/// `limits.max_word` as it grows.
fn bfs<O: StlOp>(
    desc: &Description,
    seed: &Seed,
    limits: &Limits,
    sink: &mut dyn FnMut(O) -> Result<(), Diagnostics>,
) -> Result<(), Diagnostics> {
    let mut word: Vec<Sym<'_, O>> = Vec::new();
    // The seed's items: its terms and repeats are rewritten level by level
    // below.
    let mut items = SeedWalk::written(seed);
    while let Some(step) = items.next() {
        match step {
            SeedStep::Run(d) => push_text(&mut word, &d.text),
            SeedStep::Fixed(f) => push_fixed(&mut word, f, limits)?,
            SeedStep::Term { term, .. } => {
                items.step_over();
                word.push(Sym::Apply(Child::Term(term)));
            }
            SeedStep::Repeat { repeat, .. } => word.extend(Child::repeat(repeat).map(Sym::Apply)),
            _ => {}
        }
    }
    check_word(word.len() as u64, limits)?;
    while word.iter().any(|s| matches!(s, Sym::Apply(_))) {
        let mut next: Vec<Sym<'_, O>> = Vec::with_capacity(word.len() * 2);
        for s in &word {
            match *s {
                Sym::Op(op) => next.push(Sym::Op(op)),
                Sym::Apply(c) => {
                    let Some((rule, slots)) = c.parts(desc) else {
                        continue;
                    };
                    next.push(Sym::Op(O::ENTER));
                    for step in walk::steps(&rule.body) {
                        match step {
                            Step::Run(r) => push_text(&mut next, &r.text),
                            Step::Fixed(f) => push_fixed(&mut next, f, limits)?,
                            Step::Open { .. } => next.push(Sym::Op(O::PUSH)),
                            Step::Tip { index, .. } => {
                                if let Some(c) = slots.child(index) {
                                    next.push(Sym::Apply(c));
                                }
                                next.push(Sym::Op(O::POP));
                            }
                        }
                    }
                    next.push(Sym::Op(O::LEAVE));
                }
            }
            check_word(next.len() as u64, limits)?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::ErrorKind;
    use crate::model::{Body, BodyItem, Branch, Format, Loc, Piece, SeedItem, StemParams, Terms};
    use crate::num::Linear;
    use crate::progress::NoProgress;

    use crate::model::walk::testing::{fixed, run};

    /// `T: F[I n F-F][+F[I n F+F]]` with the seed `[I n F+F] T{T{}} [I 2 T]`,
    /// built by hand: the parser refuses `n = 0`.
    fn desc(n: u32) -> Description {
        let body = Body {
            items: vec![
                BodyItem::Draw(run("F")),
                BodyItem::Fixed(fixed(n, "F-F")),
                BodyItem::Branch(Branch {
                    pieces: vec![Piece::Draw(run("+F")), Piece::Fixed(fixed(n, "F+F"))],
                    successor: None,
                    loc: Loc::default(),
                }),
            ],
        };
        let mut terms = Terms::new();
        let leaf = terms.push(RuleId(0), false, 0..0, &[None]);
        let outer = terms.push(RuleId(0), false, 0..0, &[Some(Terms::slot_of(leaf))]);
        Description {
            format: Format::Bed,
            name: "T".into(),
            name_loc: Loc::default(),
            root: (0.0, 0.0),
            root_z: None,
            root_loc: Loc::default(),
            params: StemParams {
                length: Linear::new(10.0, 1.0),
                width: Linear::constant(1.0),
                angle: None,
                clearance: None,
                divergence: None,
                stroke: None,
                stroke_end: None,
                leaf: None,
                background: None,
                design: Default::default(),
                loc: Loc::default(),
            },
            rules: vec![RuleDef {
                name: "T".into(),
                name_loc: Loc::default(),
                alternative: None,
                body,
                loc: Loc::default(),
            }],
            seed: Some(Seed {
                items: vec![
                    SeedItem::Fixed(Box::new(fixed(n, "F+F"))),
                    SeedItem::Term(outer),
                    SeedItem::Repeat(Box::new(Repeat {
                        count: 2,
                        rule: RuleId(0),
                        loc: Loc::default(),
                    })),
                ],
                terms,
                loc: Loc::default(),
            }),
            layout: None,
            forest: Vec::new(),
            surfaces: None,
        }
    }

    fn stream(bed: &Bed, strategy: Derivation) -> Vec<Op> {
        let mut out = Vec::new();
        ops(
            bed,
            strategy,
            &Limits::default(),
            &mut NoProgress,
            &mut |op| {
                out.push(op);
                Ok(())
            },
        )
        .unwrap();
        out
    }

    /// `[I n w]` is defined once (`walk::FixedWord`): `dfs`, `bfs` and the
    /// sizer agree with it, `[I 0 w]` (a single `F`) included.
    #[test]
    fn fixed_figures_agree_across_dfs_bfs_sizer_and_fixed_word() {
        for n in 0..4 {
            let bed = Bed::new(desc(n), &Limits::default()).unwrap();
            let dfs = stream(&bed, Derivation::Dfs);
            assert_eq!(dfs, stream(&bed, Derivation::Bfs), "n = {n}");
            let stems = dfs.iter().filter(|&&op| op == Op::Draw).count() as u64;
            assert_eq!(bed.size().symbols, dfs.len() as u64, "n = {n}");
            assert_eq!(bed.size().stems, stems, "n = {n}");
            // The seed opens with the figure alone.
            let figure: Vec<Op> = FixedWord::of("F+F", n).filter_map(op_of).collect();
            assert_eq!(dfs[..figure.len()], figure[..], "n = {n}");
            assert_eq!(dfs[figure.len()], Op::Enter, "n = {n}");
            // The body's figures, right after the trunk's `F`.
            let body: Vec<Op> = FixedWord::of("F-F", n).filter_map(op_of).collect();
            let at = figure.len() + 2;
            assert_eq!(dfs[at..at + body.len()], body[..], "n = {n}");
        }
        let bed = Bed::new(desc(0), &Limits::default()).unwrap();
        assert_eq!(
            stream(&bed, Derivation::Dfs)[..3],
            [Op::Draw, Op::Enter, Op::Draw]
        );
    }

    /// A fixed figure enters the `bfs` word whole, measured before it is
    /// built.
    #[test]
    fn bfs_checks_a_fixed_figure_before_building_it() {
        let limits = Limits {
            max_word: 10,
            ..Limits::default()
        };
        let bed = Bed::new(desc(3), &limits).unwrap();
        let none = &mut |_| Ok(());
        // `[I 3 F+F]` is 15 symbols.
        let e = ops(&bed, Derivation::Bfs, &limits, &mut NoProgress, none).unwrap_err();
        assert_eq!(
            e.first_kind(),
            Some(&ErrorKind::Limit {
                bound: Bound::Word,
                what: None,
                value: "15".into(),
                limit: 10,
            })
        );
        assert!(ops(&bed, Derivation::Dfs, &limits, &mut NoProgress, none).is_ok());
    }
}
