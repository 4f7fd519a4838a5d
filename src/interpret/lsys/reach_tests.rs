//! Tests of the reach memo (reach.rs) and its level of detail
//! (reach_lod.rs): composed ends, frames and boxes against walking the
//! word with the 3D turtle; the walk at detail 0 against the exact
//! drawing; the plan's counts against the walk's.

#![allow(clippy::needless_range_loop)] // vectors compared by coordinate

use super::*;
use crate::interpret::Derivation;
use crate::interpret::lsys::lsys3::draw3;
use crate::interpret::lsys::reach_lod::Mark3;
use crate::limits::Limits;
use crate::progress::{NoProgress, Progress};
use crate::turtle::turtle3::{Point3, Segment3, Turtle3};

fn parse(src: &str) -> LSystem {
    crate::syntax::lsys::parse(src, &Limits::DEFAULT).unwrap()
}

/// xorshift64*: reproducible random systems without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// A random balanced word of about `items` items over the 3D symbols and
/// `A`, `B`.
fn word(rng: &mut Rng, items: u64, nest: u32) -> String {
    const SYMS: [&str; 12] = ["F", "F", "f", "+", "-", "&", "^", "\\", "/", "|", "A", "B"];
    let mut out = String::new();
    for _ in 0..1 + rng.below(items) {
        if nest > 0 && rng.below(5) == 0 {
            out.push('[');
            out.push_str(&word(rng, 3, nest - 1));
            out.push(']');
        } else {
            out.push_str(SYMS[rng.below(SYMS.len() as u64) as usize]);
        }
    }
    out
}

fn system(rng: &mut Rng, angle: f64) -> String {
    let mut src = format!(
        "dimensions 3\nangle {angle}\naxiom {}\nrule A {}\nrule B {}\n",
        word(rng, 4, 1),
        word(rng, 6, 2),
        word(rng, 6, 2)
    );
    if rng.below(3) == 0 {
        src.push_str("rule F F+F\n");
    }
    src
}

/// Walks the derived word with the 3D turtle: its stems, end and frame.
fn walk(sys: &LSystem, depth: u32) -> (Vec<Segment3>, Point3, M) {
    let alpha = Alphabet::new(sys);
    let ops: Vec<Option<Op3>> = alpha.chars.iter().map(|&c| Op3::of_lsys(c)).collect();
    let mut segs = Vec::new();
    let mut t = Turtle3::new(sys.heading, sys.angle, sys.length, |s| segs.push(s));
    alpha.plain_each(depth, |_, s| {
        if let Some(op) = ops[s as usize] {
            t.apply(op);
        }
    });
    let (h, l, u) = t.hlu();
    let end = t.state.pos;
    drop(t);
    (segs, end, [h, l, u])
}

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * scale.max(1.0)
}

#[test]
fn composed_ends_frames_and_boxes_equal_walking() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut checked = [0usize; 2];
    for case in 0..400 {
        let right = case % 2 == 0;
        let angle = if right { 90.0 } else { 37.0 };
        let src = system(&mut rng, angle);
        let sys = parse(&src);
        let depth = rng.below(6) as u32;
        let (segs, end, frame) = walk(&sys, depth);
        if segs.len() > 200_000 {
            continue;
        }
        let memo = ReachMemo::new(&sys, depth, sys.length).unwrap();
        assert_eq!(memo.ortho, right);
        let whole = memo.whole();
        let pts: Vec<V> = segs
            .iter()
            .flat_map(|s| [s.from.to_array(), s.to.to_array()])
            .collect();
        let scale = pts
            .iter()
            .flatten()
            .chain(end.to_array().iter())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        assert_eq!(whole.stems, segs.len() as u64, "{src} depth {depth}");
        if right {
            // Exact: ends, frames and boxes equal to the bit.
            assert_eq!(whole.end, end.to_array(), "{src} depth {depth}");
            assert_eq!(whole.rot, frame, "{src} depth {depth}");
            let mut b = EMPTY_BOX;
            for &p in &pts {
                add_point(&mut b, p);
            }
            assert_eq!(whole.bbox, Some(b), "{src} depth {depth}");
        } else {
            assert_eq!(whole.bbox, None);
            for k in 0..3 {
                assert!(close(whole.end[k], end.to_array()[k], scale), "{src}");
                for j in 0..3 {
                    assert!(close(whole.rot[k][j], frame[k][j], 1.0), "{src}");
                }
            }
        }
        // The ball holds every drawn point; the centroid is the walk's.
        for &p in &pts {
            assert!(norm(p) <= whole.radius + 1e-9 * scale.max(1.0), "{src}");
        }
        if !segs.is_empty() {
            let len = sys.length;
            let mut m = [0.0; 3];
            for s in &segs {
                for k in 0..3 {
                    m[k] += len * (s.from.to_array()[k] + s.to.to_array()[k]) / 2.0;
                }
            }
            for k in 0..3 {
                assert!(
                    close(whole.moment[k], m[k], scale * segs.len() as f64),
                    "{src}"
                );
            }
        }
        checked[usize::from(right)] += 1;
    }
    assert!(checked[0] > 150 && checked[1] > 150, "{checked:?}");
}

/// The stems a walk at `detail` hands out, and the stand-ins.
fn marks(sys: &LSystem, depth: u32, detail: f64) -> (Vec<Segment3>, u64, Counted) {
    let memo = ReachMemo::new(sys, depth, sys.length).unwrap();
    let plan = memo.plan(detail);
    let mut stems = Vec::new();
    let mut stand_ins = 0u64;
    let mut counted = Counted(0);
    memo.draw_lod(
        sys.heading,
        sys.angle,
        detail,
        plan.visits,
        &mut |m| match m {
            Mark3::Stem(s) => stems.push(s),
            Mark3::StandIn { .. } => stand_ins += 1,
            Mark3::Paint(_) | Mark3::Polygon(_) => unreachable!("a classic system paints nothing"),
        },
        &mut counted,
    );
    assert_eq!(
        counted.0, plan.visits,
        "the walk visits what the plan counted"
    );
    assert_eq!(stems.len() as u64 + stand_ins, plan.marks);
    (stems, stand_ins, counted)
}

/// The last progress reported.
struct Counted(u64);

impl Progress for Counted {
    fn start(&mut self, _: &str, _: u64) {}
    fn update(&mut self, done: u64) {
        self.0 = done;
    }
    fn finish(&mut self) {}
}

#[test]
fn at_detail_zero_the_walk_is_the_exact_drawing() {
    let mut rng = Rng(7);
    let mut srcs: Vec<(String, u32)> = (0..120)
        .map(|i| {
            let a = [90.0, 37.0, 22.5][i % 3];
            (system(&mut rng, a), rng.below(5) as u32)
        })
        .collect();
    for (f, d) in [("plant3d-bare", 5), ("hilbert3d", 3)] {
        let text = std::fs::read_to_string(format!("examples/{f}.lsys")).unwrap();
        srcs.push((text, d));
    }
    for (src, depth) in &srcs {
        let sys = parse(src);
        let mut exact = Vec::new();
        draw3(
            &sys,
            *depth,
            Derivation::Dfs,
            &Limits::DEFAULT,
            &mut |s| exact.push(s),
            &mut NoProgress,
        )
        .unwrap();
        if exact.len() > 100_000 {
            continue;
        }
        let (stems, stand_ins, _) = marks(&sys, *depth, 0.0);
        assert_eq!(stand_ins, 0);
        assert_eq!(stems, exact, "{src}");
    }
}

#[test]
fn a_cut_part_fits_its_detail_and_the_walk_goes_on_from_its_end() {
    // The bush at depth 6: at a detail of 3 steps the small crowns are
    // stand-ins; the trunk and first branches (longer than that) are
    // drawn exactly, and as the exact drawing draws them: every stem
    // handed out that is longer than the detail is one of its stems.
    let text = std::fs::read_to_string("examples/plant3d-bare.lsys").unwrap();
    let sys = parse(&text);
    let mut exact = Vec::new();
    draw3(
        &sys,
        6,
        Derivation::Dfs,
        &Limits::DEFAULT,
        &mut |s| exact.push(s),
        &mut NoProgress,
    )
    .unwrap();
    let detail = 3.0 * sys.length;
    let (stems, stand_ins, _) = marks(&sys, 6, detail);
    // Cut: the 3^5 = 243 occurrences of `A` one step from the end (three
    // branches of one step: a ball of radius 1, 2 < 3 steps across); `A`
    // two steps from the end reaches 2 steps (4 across) and is drawn.
    assert_eq!(stand_ins, 243);
    let d = |a: Point3, b: Point3| {
        let (x, y, z) = (a.x - b.x, a.y - b.y, a.z - b.z);
        (x * x + y * y + z * z).sqrt()
    };
    let near = |p: Point3| {
        exact
            .iter()
            .any(|e| d(e.from, p) < 1e-9 || d(e.to, p) < 1e-9)
    };
    for s in &stems {
        // Chords of straight runs and exact stems start and end on points
        // of the exact drawing (within rounding at 22.5 degrees).
        assert!(near(s.from) && near(s.to), "{s:?}");
    }
}

#[test]
fn the_hilbert_curve_box_is_exact_at_any_depth() {
    let text = std::fs::read_to_string("examples/hilbert3d.lsys").unwrap();
    let sys = parse(&text);
    for depth in [1u32, 2, 3, 4, 10, 12, 16, 20] {
        let memo = ReachMemo::new(&sys, depth, 1.0).unwrap();
        assert!(memo.ortho);
        let whole = memo.whole();
        let b = whole.bbox.unwrap();
        let side = ((1u64 << depth) - 1) as f64;
        assert_eq!(
            [b[3] - b[0], b[4] - b[1], b[5] - b[2]],
            [side; 3],
            "{depth}"
        );
        assert_eq!(whole.stems, (1u64 << (3 * depth)) - 1);
        // Every coordinate on the lattice.
        assert!(b.iter().chain(&whole.end).all(|v| v.fract() == 0.0));
        if depth <= 4 {
            let (segs, end, _) = walk(&sys, depth);
            assert_eq!(whole.end, end.to_array());
            let mut w = EMPTY_BOX;
            for s in &segs {
                add_point(&mut w, s.from.to_array());
                add_point(&mut w, s.to.to_array());
            }
            assert_eq!(b, w);
        }
    }
}
