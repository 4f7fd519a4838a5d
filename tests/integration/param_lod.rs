//! The level of detail of parametric systems (issue 32 item 4): equal
//! modules at equal depth are one piece of the one walk's memo; elsewhere
//! a system is drawn exactly.

use crate::lsys::sys;
use crate::support::limits_with;
use stlc::interpret::Derivation::Dfs;
use stlc::interpret::lsys::param::{ParamMemo, of};
use stlc::limits::Limits;
use stlc::model::lsys::LSystem;
use stlc::progress::NoProgress;
use stlc::turtle::{Bounds, Recorder, Turtle};

/// A binary tree whose branches shorten by `r` a generation, with a
/// closing step: every `A` of one generation is the same module.
const TREE: &str = "generations 12\nangle 30\ndefine r 0.62\naxiom A(1)\n\
    rule A(l) -> F(l)[+A(l*r)][-(40)A(l*r)]F(l*0.4)\nlength 100\n";

fn memo(s: &LSystem, depth: u32) -> Option<ParamMemo> {
    ParamMemo::new(s, of(s).unwrap(), depth).unwrap()
}

fn walked(s: &LSystem, m: &ParamMemo, detail: f64, t: &mut dyn Turtle) {
    let limits = Limits::default();
    m.draw(s, of(s).unwrap(), detail, &limits, t, &mut NoProgress)
        .unwrap();
}

fn exact(s: &LSystem, depth: u32, t: &mut dyn Turtle) {
    let limits = Limits::default();
    stlc::interpret::lsys::draw_into(s, depth, Dfs, &limits, t, &mut NoProgress).unwrap();
}

/// Each side of box `a` beside the same side of box `b`.
fn sides(a: stlc::turtle::BBox, b: stlc::turtle::BBox) -> [(f64, f64); 4] {
    [
        (a.min_x, b.min_x),
        (a.min_y, b.min_y),
        (a.max_x, b.max_x),
        (a.max_y, b.max_y),
    ]
}

/// Worked by hand at depth 40: 41 `A` (one value of `l` a generation,
/// `l = 0.62^k`), 40 `F(l)` and 40 `F(l*0.4)` (the steps of the `A`s that
/// are rewritten), and `[ ] + -(40)`: 125 pieces. The word: `A` at depth
/// `r` has `m(r) = 8 + 2 m(r - 1)` modules, `m(0) = 1`, so
/// `9 x 2^r - 8`; `s(r) = 2 + 2 s(r - 1)` steps, `2^(r + 1) - 2`.
#[test]
fn equal_modules_at_equal_depth_are_one_piece() {
    let s = sys(TREE);
    let m = memo(&s, 40).expect("the memo applies");
    assert_eq!(m.nodes(), 125);
    assert_eq!(m.modules(), 9 * (1u64 << 40) - 8);
    assert_eq!(m.stems(), (1u64 << 41) - 2);
}

#[test]
fn at_detail_zero_the_walk_is_the_exact_drawing() {
    let s = sys(TREE);
    for depth in [0, 1, 5, 9] {
        let m = memo(&s, depth).unwrap();
        let (mut a, mut b) = (Recorder::default(), Recorder::default());
        walked(&s, &m, 0.0, &mut a);
        exact(&s, depth, &mut b);
        assert_eq!(a.segments.len() as u64, (2u64 << depth) - 2);
        assert_eq!(a.segments, b.segments, "depth {depth}");
    }
}

/// The ball of `A(l)`: `R(l) = 100 l + R(0.62 l)` (its branch starts
/// after `F(l)`), so `R = 100 l / 0.38 = 263 l`. A piece that branches is
/// cut when its ball's diameter is under the detail: at detail 2, `A` at
/// `l = 0.62^k` from `k = 12` on (`526 x 0.62^11 = 2.7`, `0.62^12` gives
/// 1.70). So the walk draws the `2 (2^12 - 1)` steps of the `A`s above
/// and one stand-in for each of the `2^12` below: 12,286 of 32,766. A cut
/// piece lies in a ball about its start of diameter under the detail, so
/// the drawing's box moves by less than the detail.
#[test]
fn at_a_detail_the_box_is_the_exact_ones_within_the_detail() {
    let s = sys(TREE);
    let depth = 14;
    let m = memo(&s, depth).unwrap();
    let detail = 2.0;
    let (mut lod, mut ex) = (Bounds::default(), Bounds::default());
    walked(&s, &m, detail, &mut lod);
    exact(&s, depth, &mut ex);
    let (a, b) = (lod.bbox().unwrap(), ex.bbox().unwrap());
    for (x, y) in sides(a, b) {
        assert!((x - y).abs() < detail, "{x} vs {y}");
    }
    assert_eq!(ex.count, (2u64 << depth) - 2);
    assert_eq!(lod.count, 2 * ((1 << 12) - 1) + (1 << 12));
}

/// Depth 40 is about 10^13 modules: the exact path refuses it, the walk
/// draws it. At detail 1 the `A`s are cut from `k = 14` on (diameter
/// `526 x 0.62^13 = 1.05`, then 0.65): the walk visits the word of depth
/// 14 (`9 x 2^14 - 8` modules) and the `2^14 - 1` `A`s it expands.
#[test]
fn a_depth_the_exact_path_refuses_is_drawn_at_a_level_of_detail() {
    let s = sys(TREE);
    let mut rec = Recorder::default();
    let limits = limits_with(|l| l.max_symbols = 30_000_000);
    let refused = stlc::interpret::lsys::draw_into(&s, 40, Dfs, &limits, &mut rec, &mut NoProgress);
    assert!(refused.is_err());
    let m = memo(&s, 40).unwrap();
    let visits = m.visits(1.0);
    assert_eq!(visits, 9 * (1 << 14) - 8 + (1 << 14) - 1);
    let mut b = Bounds::default();
    walked(&s, &m, 1.0, &mut b);
    // The 2^14 - 1 expanded `A`s' two steps each, a stand-in for each
    // of the 2^14 cut.
    assert_eq!(b.count, 2 * ((1 << 14) - 1) + (1 << 14));
}

#[test]
fn past_the_budget_the_walk_is_refused_and_says_why() {
    let s = sys(TREE);
    let m = memo(&s, 40).unwrap();
    let limits = limits_with(|l| l.max_symbols = 30 * 1000);
    let (bounds, quiet) = (&mut Bounds::default(), &mut NoProgress);
    let err = m
        .draw(&s, of(&s).unwrap(), 0.5, &limits, bounds, quiet)
        .unwrap_err();
    let text = format!("{err}");
    assert!(text.contains("at this level of detail"), "{text}");
}

/// Tropism, widths, contexts and probabilities make a piece depend on
/// more than its module and depth; a 3D system is drawn as a view: none
/// has the memo.
#[test]
fn pieces_that_depend_on_more_than_module_and_depth_have_no_memo() {
    let base = "generations 4\nangle 30\naxiom A(1)\n";
    for extra in [
        "tropism 0 1 0\nelasticity 0.2\nrule A(l) -> F(l)[+A(l)]A(l)\n",
        "rule A(l) -> !(l)F(l)[+A(l)]A(l)\n",
        "rule B < A(l) -> F(l)\nrule A(l) -> F(l)[+A(l)]A(l)\n",
        "rule A(l) (0.5) -> F(l)[+A(l)]\nrule A(l) (0.5) -> F(l)[-A(l)]\n",
        "dimensions 3\nrule A(l) -> F(l)[&A(l)]A(l)\n",
    ] {
        let s = sys(&format!("{base}{extra}"));
        assert!(memo(&s, 4).is_none(), "{extra}");
    }
    assert!(memo(&sys(&format!("{base}rule A(l) -> F(l)[+A(l)]A(l)\n")), 4).is_some());
}

/// A random deterministic context-free 2D system over `A B F f + - [ ]`
/// with conditions: the memo applies to every one.
fn system() -> impl proptest::strategy::Strategy<Value = String> {
    use proptest::prelude::*;
    let succ = prop::collection::vec(
        prop_oneof![
            Just("A(x*0.5,y+1)"),
            Just("B(y,x)"),
            Just("F(x)"),
            Just("f(y*0.1)"),
            Just("+(y*10)"),
            Just("-"),
            Just("[A(x,y+1)]"),
            Just("[-B(x+y,2)F]"),
        ],
        1..6,
    );
    (succ.clone(), succ.clone(), succ, 1u32..60).prop_map(|(a, b, c, angle)| {
        format!(
            "angle {angle}\naxiom A(1,2)B(3,4)\nrule A(x,y) : y < 4 -> {}\n\
             rule A(x,y) -> {}\nrule B(x,y) -> F(x){}\n",
            a.concat(),
            b.concat(),
            c.concat()
        )
    })
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(40))]

    /// At detail 0 nothing that draws is cut: the walk over the memo is
    /// the exact drawing, segment for segment, bit for bit; at a detail,
    /// the box moves by less than the detail.
    #[test]
    fn the_walk_over_the_memo_is_the_exact_drawing_at_detail_zero(
        src in system(),
        depth in 0u32..6,
    ) {
        let s = sys(&src);
        let m = memo(&s, depth).expect("the memo applies");
        let (mut a, mut b) = (Recorder::default(), Recorder::default());
        walked(&s, &m, 0.0, &mut a);
        exact(&s, depth, &mut b);
        proptest::prop_assert_eq!(m.stems(), b.segments.len() as u64);
        proptest::prop_assert_eq!(&a.segments, &b.segments);
        let (mut lod, mut ex) = (Bounds::default(), Bounds::default());
        walked(&s, &m, 50.0, &mut lod);
        exact(&s, depth, &mut ex);
        if let (Some(x), Some(y)) = (lod.bbox(), ex.bbox()) {
            for (p, q) in sides(x, y) {
                proptest::prop_assert!((p - q).abs() < 50.0 * (1.0 + 1e-9), "{} vs {}", p, q);
            }
        }
    }
}
