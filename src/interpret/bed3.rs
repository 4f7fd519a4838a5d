//! A 3D BED (`../shared/stl-language.md` section 11: a root with three
//! coordinates) drawn with the 3D turtle ([`Turtle3`]).
//!
//! The operations are the 2D interpreter's ([`super::bed::stream`], the
//! same `dfs` and `bfs` expansions), read as [`Op3`]s: `& ^ \ /` pitch
//! and roll by `A`, and every rule application (`Enter`: a term from the
//! seed or a slot, each level of `[I n X]`) raises the stem order and
//! first rolls the frame by the divergence `D=` about its heading
//! ([`Turtle3::roll_by`], as growth does). Each tree starts at its root,
//! `(x, y, z)`, heading up the screen. A planar 3D BED (`D=0` or none, no
//! 3D turn) keeps the 2D turtle's exact frame, so its stems are the 2D
//! BED's, x and y bit for bit, at z = its root's.

use std::cell::Cell;

use crate::bed::Bed;
use crate::diag::Diagnostics;
use crate::interpret::Derivation;
use crate::interpret::bed::{Event, StlOp, stream, write_expansion};
use crate::limits::Limits;
use crate::num::Linear;
use crate::progress::Progress;
use crate::turtle::UP;
use crate::turtle::turtle3::{Op3, Point3, Segment3, Turtle3, divergence};

/// An operation of a 3D BED's stream: a 3D turtle operation, or a rule
/// application starting or ending.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op3s {
    /// A turtle operation.
    Turtle(Op3),
    /// A rule application starts: one order higher, rolled by `D=`.
    Enter,
    /// It ends: one order lower (the roll is kept, as a `\` in its body
    /// would be).
    Leave,
}

impl StlOp for Op3s {
    #[inline]
    fn of_byte(c: u8) -> Option<Op3s> {
        match c {
            b'L' => Some(Op3::Turn(1)),
            b'R' => Some(Op3::Turn(-1)),
            c => Op3::of_lsys(char::from(c)),
        }
        .map(Op3s::Turtle)
    }
    const ENTER: Op3s = Op3s::Enter;
    const LEAVE: Op3s = Op3s::Leave;
    const PUSH: Op3s = Op3s::Turtle(Op3::Push);
    const POP: Op3s = Op3s::Turtle(Op3::Pop);
}

/// Draws a 3D BED's trees, in root order, handing every stem to `sink` in
/// drawing order (its `order` the number of rule applications above it);
/// returns where the turtle ends (the last tree's end).
pub fn draw3(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    sink: &mut dyn FnMut(Segment3),
    progress: &mut dyn Progress,
) -> Result<Point3, Diagnostics> {
    let desc = bed.description();
    let p = &desc.params;
    let zs: Vec<f64> = std::iter::once(desc.root_z)
        .chain(desc.forest.iter().map(|t| t.root_z))
        .map(|z| z.unwrap_or(0.0))
        .collect();
    // The order of the stem being drawn, read by the sink; kept here and
    // saved at each `[` beside the turtle's own stack.
    let order = Cell::new(0u32);
    let mut orders: Vec<u32> = Vec::new();
    let length: Linear = p.length;
    let roll = divergence(p.divergence);
    let mut turtle = Turtle3::new(UP, p.angle(), length.at(0), |mut s: Segment3| {
        s.order = order.get();
        sink(s)
    });
    stream::<Op3s>(bed, strategy, limits, progress, &mut |e| {
        match e {
            Event::Tree(i, root) => {
                turtle.state.pos = Point3::new(root.x, root.y, zs[i]);
                turtle.state.frame = crate::turtle::turtle3::Frame::Planar { k: 0, flip: false };
                order.set(0);
                orders.clear();
            }
            Event::Op(Op3s::Turtle(op)) => {
                match op {
                    Op3::Draw | Op3::Move => turtle.set_step(length.at(order.get())),
                    Op3::Push => orders.push(order.get()),
                    Op3::Pop => {
                        if let Some(o) = orders.pop() {
                            order.set(o);
                        }
                    }
                    _ => {}
                }
                turtle.apply(op);
            }
            Event::Op(Op3s::Enter) => {
                order.set(order.get() + 1);
                if let Some((c, s)) = roll {
                    turtle.roll_by(c, s);
                }
            }
            Event::Op(Op3s::Leave) => order.set(order.get().saturating_sub(1)),
        }
        Ok(())
    })?;
    Ok(turtle.state.pos)
}

/// Writes a 3D BED's expansion to `out` as drawing components (`F f + - &
/// ^ \\ / | [ ]`; `L` and `R` come out as `+` and `-`), one line per tree,
/// as [`super::bed::expand`] writes a 2D one. The divergence is no symbol:
/// the word draws the BED's tree only with `D=0` (an `.lsys` of it has no
/// rule applications to roll at).
pub fn expand3(
    bed: &Bed,
    strategy: Derivation,
    limits: &Limits,
    out: &mut dyn std::io::Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    write_expansion::<Op3s>(bed, strategy, limits, out, progress, |op, buf| {
        let Op3s::Turtle(op) = op else {
            return;
        };
        buf.push(match op {
            Op3::Draw => b'F',
            Op3::Move => b'f',
            Op3::Turn(n) if n > 0 => b'+',
            Op3::Turn(_) => b'-',
            Op3::Pitch(n) if n > 0 => b'&',
            Op3::Pitch(_) => b'^',
            Op3::Roll(n) if n > 0 => b'\\',
            Op3::Roll(_) => b'/',
            Op3::Flip => b'|',
            Op3::Push => b'[',
            Op3::Pop => b']',
        })
    })
}

/// The box `[minx, miny, minz, maxx, maxy, maxz]` of every drawn stem's
/// ends (`None`: nothing drawn), where the turtle ends, and the number of
/// stems: a 3D BED's geometry in canvas units, for `stats`.
pub fn bounds3(
    bed: &Bed,
    limits: &Limits,
    progress: &mut dyn Progress,
) -> Result<crate::interpret::lsys::lsys3::Bounds3, Diagnostics> {
    let mut acc = crate::turtle::turtle3::StemBox::default();
    let end = draw3(bed, Derivation::Dfs, limits, &mut |s| acc.add(s), progress)?;
    Ok(acc.finish(end))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Format;
    use crate::progress::NoProgress;

    fn bed(src: &str) -> Bed {
        let d = crate::syntax::stl::parse(src, Format::Bed, &Limits::DEFAULT).unwrap();
        Bed::new(d, &Limits::DEFAULT).unwrap()
    }

    fn stems(b: &Bed, d: Derivation) -> Vec<Segment3> {
        let mut out = Vec::new();
        draw3(
            b,
            d,
            &Limits::DEFAULT,
            &mut |s| out.push(s),
            &mut NoProgress,
        )
        .unwrap();
        out
    }

    fn end(seed: &str, head: &str) -> Point3 {
        let src = format!("T (0, 0, 0) L=1(0) A=90 {head} RULE R1: [F] SEED {seed} ENDSEED");
        let b = bed(&src);
        draw3(
            &b,
            Derivation::Dfs,
            &Limits::DEFAULT,
            &mut |_| {},
            &mut NoProgress,
        )
        .unwrap()
    }

    #[test]
    fn a_3d_expansion_writes_the_3d_turns() {
        let b = bed("T (0, 0, 0) (1, 1, 1) RULE R1: [&F][\\LF] R2: [^/RF] \
             SEED F R1{R2{},} ENDSEED SEED [I 2 F&F] ENDSEED");
        for d in [Derivation::Dfs, Derivation::Bfs] {
            let mut out = Vec::new();
            expand3(&b, d, &Limits::DEFAULT, &mut out, &mut NoProgress).unwrap();
            assert_eq!(
                String::from_utf8(out).unwrap(),
                "F[&F[^/-F]][\\+F]\nF&F&F&F\n"
            );
        }
    }

    #[test]
    fn the_worked_ends_of_section_11_in_a_bed() {
        assert_eq!(end("F+F", ""), Point3::new(-1.0, -1.0, 0.0));
        assert_eq!(end("F&F", ""), Point3::new(0.0, -1.0, 1.0));
        assert_eq!(end("F/+F", ""), Point3::new(0.0, -1.0, -1.0));
        // `L` and `R` turn as `+` and `-`.
        assert_eq!(end("FLF", ""), Point3::new(-1.0, -1.0, 0.0));
    }

    /// `D=90`, `R1: [+F]`, seed `F R1{R1{}}`, `A=90`, `L=1(0)`, by hand:
    /// the trunk ends at (0, -1, 0). The first R1 rolls L = (-1, 0, 0) to
    /// L cos 90 - U sin 90 = -U = (0, 0, 1); `+` heads along it: (0, -1, 1).
    /// The second R1, from that frame (H = (0, 0, 1), L = (0, 1, 0)
    /// (L' = L cos - H sin: -H of before), U = (-1, 0, 0)), rolls L to
    /// -U = (1, 0, 0); `+` heads there: (1, -1, 1).
    #[test]
    fn divergence_rolls_every_application_by_hand() {
        let src = "T (0, 0, 0) L=1(0) A=90 D=90 RULE R1: [+F] SEED F R1{R1{}} ENDSEED";
        let b = bed(src);
        for d in [Derivation::Dfs, Derivation::Bfs] {
            let got: Vec<(Point3, u32)> = stems(&b, d).iter().map(|s| (s.to, s.order)).collect();
            assert_eq!(
                got,
                vec![
                    (Point3::new(0.0, -1.0, 0.0), 0),
                    (Point3::new(0.0, -1.0, 1.0), 1),
                    (Point3::new(1.0, -1.0, 1.0), 2),
                ],
                "{d:?}"
            );
        }
        // `[I 2 R1]` is two applications too: the same stems.
        let rep = bed("T (0, 0, 0) L=1(0) A=90 D=90 RULE R1: [+F] SEED F [I 2 R1] ENDSEED");
        assert_eq!(stems(&rep, Derivation::Dfs), stems(&b, Derivation::Dfs));
    }

    /// A planar 3D BED draws the 2D BED's stems, x and y bit for bit, at
    /// its root's z; a forest's trees start at their own roots.
    #[test]
    fn a_planar_bed_draws_the_2d_stems() {
        let rules = "L=10(1.5) B=1(0) A=25.7 RULE R1: [+F][-F R1]F SEED F R1{R1{,R1{,}},R1{,}} [I 3 R1] ENDSEED SEED FF+F ENDSEED";
        let flat = bed(&format!("T (3, 200) (50, 100) {rules}"));
        let deep = bed(&format!("T (3, 200, 7) (50, 100, -2) D=0 {rules}"));
        let mut rec = crate::turtle::Recorder::default();
        crate::interpret::bed::draw(
            &flat,
            Derivation::Dfs,
            &Limits::DEFAULT,
            &mut rec,
            &mut NoProgress,
        )
        .unwrap();
        let got = stems(&deep, Derivation::Bfs);
        assert_eq!(rec.segments.len(), got.len());
        assert!(got.len() > 20);
        let first_tree = flat.size().stems as usize - 3;
        for (i, (a, b)) in rec.segments.iter().zip(&got).enumerate() {
            let z = if i < first_tree { 7.0 } else { -2.0 };
            assert_eq!((a.from.x, a.from.y, z), (b.from.x, b.from.y, b.from.z));
            assert_eq!((a.to.x, a.to.y, z), (b.to.x, b.to.y, b.to.z));
            assert_eq!(a.order, b.order);
        }
    }
}
