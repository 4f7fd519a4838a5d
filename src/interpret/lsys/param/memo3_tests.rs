//! Tests of the view memo (memo3.rs) against the exact drawing
//! ([`super::super::draw3_marks`]): the walk at detail 0 hands out the
//! very marks, and a piece's composed length, area, ink and colours are
//! those of deriving the piece on its own and summing its marks.

use super::*;
use crate::interpret::Derivation;
use crate::interpret::lsys::param::draw3_marks;
use crate::limits::Limits;
use crate::progress::NoProgress;

fn parse(src: &str) -> LSystem {
    crate::syntax::lsys::parse(src, &Limits::DEFAULT).unwrap()
}

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// A mark as plain data: stems with their order, colour indices,
/// polygons' vertices.
#[derive(Debug, PartialEq)]
enum Seen {
    Stem([f64; 6], u32),
    Paint(usize),
    Polygon(Vec<[f64; 3]>),
}

fn exact(sys: &LSystem, depth: u32) -> Vec<Seen> {
    let p = sys.parametric.as_deref().unwrap();
    let mut out = Vec::new();
    draw3_marks(sys, p, depth, Derivation::Dfs, &Limits::DEFAULT, &mut |m| {
        out.push(match m {
            Mark::Step(s, _) => Seen::Stem(
                [s.from.x, s.from.y, s.from.z, s.to.x, s.to.y, s.to.z],
                s.order,
            ),
            Mark::Paint(i) => Seen::Paint(i),
            Mark::Polygon(ps) => Seen::Polygon(ps.iter().map(|q| [q.x, q.y, q.z]).collect()),
        })
    })
    .unwrap();
    out
}

fn walked(sys: &LSystem, depth: u32, detail: f64) -> (Vec<Seen>, usize) {
    let p = sys.parametric.as_deref().unwrap();
    let memo = ViewMemo::new(sys, p, depth)
        .unwrap()
        .expect("the memo applies");
    let (mut out, mut stand_ins) = (Vec::new(), 0);
    let plan = memo.plan(detail);
    memo.walk(
        sys,
        detail,
        plan.visits,
        (1.0, 1.0),
        [0.0, 0.0, 1.0],
        &mut |m| match m {
            Mark3::Stem(s) => out.push(Seen::Stem(
                [s.from.x, s.from.y, s.from.z, s.to.x, s.to.y, s.to.z],
                s.order,
            )),
            Mark3::Paint(i) => out.push(Seen::Paint(i)),
            Mark3::Polygon(ps) => {
                out.push(Seen::Polygon(ps.iter().map(|q| [q.x, q.y, q.z]).collect()))
            }
            Mark3::StandIn { .. } => stand_ins += 1,
        },
        &mut NoProgress,
    );
    (out, stand_ins)
}

#[test]
fn at_detail_zero_the_walk_is_the_exact_drawing_mark_for_mark() {
    for (name, depth) in [("abop-1.26.lsys", 4), ("plant3d.lsys", 3)] {
        let sys = parse(&example(name));
        let want = exact(&sys, depth);
        let (got, stand_ins) = walked(&sys, depth, 0.0);
        assert_eq!(stand_ins, 0, "{name}");
        assert!(want.len() > 100, "{name}: {} marks", want.len());
        assert_eq!(got, want, "{name}");
        // Cut coarsely, fewer marks come, some as stand-ins.
        let (coarse, stand_ins) = walked(&sys, depth, 50.0);
        assert!(stand_ins > 0 && coarse.len() < want.len(), "{name}");
    }
}

/// Twice a polygon's area from its vertices (the cross products summed).
fn area(ps: &[[f64; 3]]) -> f64 {
    let mut s = [0.0; 3];
    for i in 0..ps.len() {
        let (a, b) = (ps[i], ps[(i + 1) % ps.len()]);
        s[0] += a[1] * b[2] - a[2] * b[1];
        s[1] += a[2] * b[0] - a[0] * b[2];
        s[2] += a[0] * b[1] - a[1] * b[0];
    }
    libm::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2])
}

#[test]
fn a_pieces_length_area_ink_and_colours_are_its_derived_drawings() {
    // The plant P of Fig. 1.26 and the plant3d apex A, derived on their
    // own (the file with that axiom) and their marks summed, against the
    // pieces the memo composed from sub-pieces it jumps over.
    for (name, axiom, r) in [("abop-1.26.lsys", 'P', 3), ("plant3d.lsys", 'A', 3)] {
        let text = example(name);
        let text: String = text
            .lines()
            .map(|l| {
                if l.starts_with("axiom") {
                    format!("axiom {axiom}\n")
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        let sys = parse(&text);
        let p = sys.parametric.as_deref().unwrap();
        let palette: Vec<[f64; 3]> = p
            .organs
            .palette
            .iter()
            .map(|c| [f64::from(c.r), f64::from(c.g), f64::from(c.b)])
            .collect();
        // Brute force: every stem's length x width and every polygon's
        // area, in the colour in force, from the file's width, colour 0.
        let (mut len, mut ink, mut polys, mut stems) = (0.0, 0.0, 0.0, 0u64);
        let (mut stroke_rgb, mut poly_rgb, mut color) = ([0.0; 3], [0.0; 3], 0usize);
        draw3_marks(
            &sys,
            p,
            r,
            Derivation::Dfs,
            &Limits::DEFAULT,
            &mut |m| match m {
                Mark::Step(s, w) => {
                    let d = [s.to.x - s.from.x, s.to.y - s.from.y, s.to.z - s.from.z];
                    let l = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                    len += l;
                    let w = if p.sets_width() { w } else { 1.0 };
                    ink += l * w;
                    stems += 1;
                    for j in 0..3 {
                        stroke_rgb[j] += l * w * palette[color][j];
                    }
                }
                Mark::Paint(i) => color = i,
                Mark::Polygon(ps) => {
                    let vs: Vec<[f64; 3]> = ps.iter().map(|q| [q.x, q.y, q.z]).collect();
                    let a = area(&vs) / 2.0;
                    polys += a;
                    for j in 0..3 {
                        poly_rgb[j] += a * palette[color][j];
                    }
                }
            },
        )
        .unwrap();
        let memo = ViewMemo::new(&sys, p, r)
            .unwrap()
            .expect("the memo applies");
        let id = memo.pieces.axiom[0] as usize;
        assert!(memo.pieces.succ[id].is_some(), "{name}: {axiom} is a piece");
        let piece = &memo.reach[id];
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + b.abs());
        assert_eq!(piece.stems, stems, "{name}");
        assert!(close(piece.length, len), "{name}: {} {len}", piece.length);
        assert!(
            close(piece.area, polys) && polys > 0.0,
            "{name}: {} {polys}",
            piece.area
        );
        let w = sys.width;
        let w_ink = if p.sets_width() { w } else { 1.0 };
        assert!(close(piece.ink.0 * w_ink + piece.ink.1, ink), "{name}");
        let paint = &memo.paint[id * memo.colors];
        for j in 0..3 {
            let s = paint.stroke.0[j] * w_ink + paint.stroke.1[j];
            assert!(
                close(s, stroke_rgb[j]),
                "{name}: channel {j}: {s} {}",
                stroke_rgb[j]
            );
            assert!(close(paint.poly[j], poly_rgb[j]), "{name}: channel {j}");
        }
    }
}

#[test]
fn what_looks_at_the_absolute_heading_is_drawn_exactly() {
    // `$` and tropism turn by where the turtle heads: no piece can stand
    // for its copies.
    for extra in [
        "rule B -> F$B",
        "tropism 0 -1 0\nelasticity 0.2\nrule B -> FB",
    ] {
        let sys = parse(&format!(
            "dimensions 3\nangle 30\npalette #000000 #ffffff\naxiom A\nrule A -> B'[&A]\n{extra}\n"
        ));
        let p = sys.parametric.as_deref().unwrap();
        assert!(ViewMemo::new(&sys, p, 5).unwrap().is_none(), "{extra}");
    }
}
