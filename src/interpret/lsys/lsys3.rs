//! A 3D `.lsys` (`dimensions 3`) derived into 3D segments.
//!
//! The word is streamed exactly as the 2D paths stream it, by the same
//! derivations: for a deterministic system `plain_each` (dfs, an explicit
//! stack of successors, memory O(depth)) or `bfs_each` (Saupe's levels);
//! for a stochastic one `Stochastic::dfs_each` or `Stochastic::bfs_each`
//! (keyed by place), so the choices are the 2D drawing's for the
//! same seed. A deterministic dfs runs the compiled program of 2D over 3D
//! units (program3.rs: inert symbols dropped, runs of `F` counted),
//! or, when the program would be too large, the plain stream; every
//! operation goes through [`Turtle3`] either way, so both draw the same
//! stems. (Views at a level of detail walk the reach memo instead:
//! reach_lod.rs.) The same refusals as 2D apply
//! before any work: the derived word over `--max-symbols` (a stochastic
//! system's budget a tenth of it), bfs's word over `--max-word`.

use super::alphabet::{Alphabet, PROGRESS_STEP};
use super::program::Program;
use super::program3::Fast3;
use super::stochastic::Stochastic;
use crate::diag::Diagnostics;
use crate::interpret::Derivation;
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::progress::Progress;
use crate::turtle::turtle3::{Op3, Point3, Segment3, Turtle3};

/// Derives `sys` to `depth` with `strategy` and hands every drawn stem to
/// `sink`, in drawing order, from the origin with step `sys.length`;
/// returns where the turtle ends. Refuses, before any work, a word over
/// the limits.
pub fn draw3(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    sink: &mut dyn FnMut(Segment3),
    progress: &mut dyn Progress,
) -> Result<Point3, Diagnostics> {
    if let Some(p) = super::param::of(sys) {
        return super::param::draw3(sys, p, depth, strategy, limits, sink);
    }
    let mut turtle = Turtle3::new(sys.heading, sys.angle, sys.length, sink);
    if sys.is_stochastic() {
        let st = Stochastic::new(sys);
        let ops: Vec<Option<Op3>> = st.chars.iter().map(|&c| Op3::of_lsys(c)).collect();
        super::stream_stochastic(&st, depth, strategy, limits, progress, |s| {
            if let Some(op) = ops[s as usize] {
                turtle.apply(op);
            }
        })?;
        return Ok(turtle.state.pos);
    }
    let alpha = Alphabet::new(sys);
    let lens = alpha.check(depth, strategy, limits)?;
    let total = lens[depth as usize];
    let ops: Vec<Option<Op3>> = alpha.chars.iter().map(|&c| Op3::of_lsys(c)).collect();
    progress.start("symbols", total);
    match strategy {
        Derivation::Dfs => match Program::<Fast3>::compile(&alpha, depth) {
            Some(program) => program.run(
                &alpha.axiom,
                |units| super::program3::run(&mut turtle, units),
                progress,
            ),
            None => alpha.plain_each(depth, |i, s| {
                if let Some(op) = ops[s as usize] {
                    turtle.apply(op);
                }
                if i % PROGRESS_STEP == PROGRESS_STEP - 1 {
                    progress.update(i + 1);
                }
            }),
        },
        Derivation::Bfs => alpha.bfs_each(depth, |i, s| {
            if let Some(op) = ops[s as usize] {
                turtle.apply(op);
            }
            if i as u64 % PROGRESS_STEP == PROGRESS_STEP - 1 {
                progress.update(i as u64 + 1);
            }
        }),
    }
    progress.update(total);
    progress.finish();
    Ok(turtle.state.pos)
}

/// The box `[minx, miny, minz, maxx, maxy, maxz]` of every drawn stem
/// (`None`: nothing drawn), where the turtle ends, and the number of
/// stems, with the file's step `sys.length` (`stats` passes a unit-step
/// copy).
pub type Bounds3 = (Option<[f64; 6]>, Point3, u64);

/// [`Bounds3`] of `sys` at `depth` by a dfs traversal within `limits`.
pub fn bounds3(
    sys: &LSystem,
    depth: u32,
    limits: &Limits,
    progress: &mut dyn Progress,
) -> Result<Bounds3, Diagnostics> {
    let mut acc = crate::turtle::turtle3::StemBox::default();
    let end = draw3(
        sys,
        depth,
        Derivation::Dfs,
        limits,
        &mut |s| acc.add(s),
        progress,
    )?;
    Ok(acc.finish(end))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::progress::NoProgress;
    use std::collections::BTreeSet;

    fn parse(src: &str) -> LSystem {
        crate::syntax::lsys::parse(src, &Limits::DEFAULT).unwrap()
    }

    /// ABOP's 3D Hilbert curve (fig. 1.10, as issue 26 gives it).
    const HILBERT: &str = "dimensions 3\nangle 90\naxiom A\n\
        rule A B-F+CFC+F-D&F^D-F+&&CFC+F+B//\n\
        rule B A&F^CFB^F^D^^-F-D^|F^B|FC^F^A//\n\
        rule C |D^|F^B-F+C^F^A&&FA&F^C+F+B^F^D//\n\
        rule D |CFB-F+B|FA&F^A&&FB-F+B|FC//\n";

    fn points(sys: &LSystem, depth: u32, d: Derivation) -> Vec<Point3> {
        let mut pts = vec![Point3::default()];
        draw3(
            sys,
            depth,
            d,
            &Limits::DEFAULT,
            &mut |s| pts.push(s.to),
            &mut NoProgress,
        )
        .unwrap();
        pts
    }

    #[test]
    fn the_hilbert_curve_visits_every_lattice_point_of_its_cube_once() {
        let sys = parse(HILBERT);
        for depth in 1..=5u32 {
            for d in [Derivation::Dfs, Derivation::Bfs] {
                let pts = points(&sys, depth, d);
                let n = 1usize << (3 * depth);
                assert_eq!(pts.len(), n, "depth {depth}");
                let side = f64::from((1u32 << depth) - 1);
                let mut seen = BTreeSet::new();
                let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
                for (i, p) in pts.iter().enumerate() {
                    let a = p.to_array();
                    for k in 0..3 {
                        assert_eq!(a[k], a[k].round(), "off the lattice: {p:?}");
                        lo[k] = lo[k].min(a[k]);
                        hi[k] = hi[k].max(a[k]);
                    }
                    assert!(seen.insert(a.map(|v| v as i64)), "visited twice: {p:?}");
                    if i > 0 {
                        let q = pts[i - 1].to_array();
                        let dist: f64 = (0..3).map(|k| (a[k] - q[k]).abs()).sum();
                        assert_eq!(dist, 1.0, "not one unit apart");
                    }
                }
                for k in 0..3 {
                    assert_eq!(hi[k] - lo[k], side, "depth {depth} axis {k}");
                }
            }
        }
    }

    #[test]
    fn stochastic_3d_choices_are_the_2d_ones() {
        // The same file as 2D and 3D with only planar symbols: the same
        // choices give the same x and y, for both derivations.
        let src = "axiom F\nangle 30\nseed 7\nrule F (0.5) -> F[+F]F\nrule F (0.5) -> F[-F]F\n";
        let flat = parse(src);
        let deep = parse(&format!("dimensions 3\n{src}"));
        for d in [Derivation::Dfs, Derivation::Bfs] {
            let mut rec = crate::turtle::Recorder::default();
            super::super::draw_into(&flat, 5, d, &Limits::DEFAULT, &mut rec, &mut NoProgress)
                .unwrap();
            let mut got = Vec::new();
            draw3(
                &deep,
                5,
                d,
                &Limits::DEFAULT,
                &mut |s| got.push(s),
                &mut NoProgress,
            )
            .unwrap();
            assert_eq!(rec.segments.len(), got.len());
            assert!(rec.segments.len() > 20);
            for (a, b) in rec.segments.iter().zip(&got) {
                assert_eq!((a.to.x, a.to.y, 0.0), (b.to.x, b.to.y, b.to.z));
            }
        }
    }

    #[test]
    fn the_compiled_program_draws_the_plain_streams_stems() {
        // dfs runs the compiled program (macros and, at these depths,
        // plans); bfs feeds every symbol of the rewritten word to the
        // turtle: the same stems, bit for bit.
        let plant = std::fs::read_to_string("examples/plant3d-bare.lsys").unwrap();
        let odd = "dimensions 3\nangle 37\naxiom XA\nrule A F[&A]X/F[^\\A]|-A\nrule X fF+X\n";
        for (src, depth) in [(HILBERT, 5), (plant.as_str(), 8), (odd, 9)] {
            let sys = parse(src);
            let run = |d| {
                let mut got = Vec::new();
                draw3(
                    &sys,
                    depth,
                    d,
                    &Limits::DEFAULT,
                    &mut |s| got.push(s),
                    &mut NoProgress,
                )
                .unwrap();
                got
            };
            let (dfs, bfs) = (run(Derivation::Dfs), run(Derivation::Bfs));
            assert!(dfs.len() > 4096, "{}", dfs.len());
            assert!(dfs == bfs, "{src}");
        }
    }

    #[test]
    fn the_word_over_the_budget_is_refused_before_drawing() {
        let sys = parse(HILBERT);
        let limits = Limits {
            max_symbols: 1000,
            ..Limits::DEFAULT
        };
        let mut n = 0;
        let err = draw3(
            &sys,
            3,
            Derivation::Dfs,
            &limits,
            &mut |_| n += 1,
            &mut NoProgress,
        )
        .unwrap_err();
        assert_eq!(n, 0);
        assert!(err.to_string().contains("--max-symbols"), "{err}");
    }

    #[test]
    fn bounds_of_the_worked_ends() {
        let sys = parse("dimensions 3\nangle 90\naxiom F/+F\n");
        let (b, end, n) = bounds3(&sys, 0, &Limits::DEFAULT, &mut NoProgress).unwrap();
        assert_eq!(end, Point3::new(0.0, -1.0, -1.0));
        assert_eq!(b, Some([0.0, -1.0, -1.0, 0.0, 0.0, 0.0]));
        assert_eq!(n, 2);
    }
}
