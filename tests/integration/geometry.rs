//! The memoized geometry of L-systems (`interpret::lsys::measure`) and the
//! renderer's level of detail: against a full traversal where one is
//! possible, against an independent recursive computation at depth 30 and
//! more, and the level of detail against the exact drawing.

use std::collections::{BTreeMap, HashMap};

use proptest::prelude::*;
use stlc::interpret::Derivation::Dfs;
use stlc::interpret::lsys::{Measured, Memo, Refusal, draw, draw_into, draw_lod, measure};
use stlc::limits::Limits;
use stlc::model::lsys::LSystem;
use stlc::progress::NoProgress;
use stlc::turtle::{BBox, Bounds, Recorder, Segment, StandIn, Turtle};

use crate::lsys::{ALPHABET, source, sys, word};
use crate::support::stlc_line;

/// Within `rel` of the larger magnitude (at least 1).
fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(1.0)
}

fn close_box(a: &BBox, b: &BBox, rel: f64) -> bool {
    close(a.min_x, b.min_x, rel)
        && close(a.min_y, b.min_y, rel)
        && close(a.max_x, b.max_x, rel)
        && close(a.max_y, b.max_y, rel)
}

/// The traversal: every segment into a bounding turtle.
fn traversed(s: &LSystem, depth: u32) -> (Option<BBox>, stlc::turtle::Point, u64) {
    let (mut b, limits) = (Bounds::default(), Limits::default());
    let end = draw_into(s, depth, Dfs, &limits, &mut b, &mut NoProgress).unwrap();
    (b.bbox(), end, b.count)
}

// ------------------------------------------------- against a traversal --

/// A turtle that records segments and stand-ins and asks for a level of
/// detail.
#[derive(Default)]
struct Detailed {
    rec: Recorder,
    blots: u64,
    detail: f64,
    /// Segments the runs' stand-ins stand for.
    stood: f64,
}

impl Turtle for Detailed {
    fn segment(&mut self, seg: Segment) {
        self.rec.segments.push(seg);
    }
    fn detail(&self) -> Option<f64> {
        Some(self.detail)
    }
    fn stand_in(&mut self, stand_in: &StandIn) {
        assert!(stand_in.density >= 1.0, "{}", stand_in.density);
        self.blots += 1;
        self.rec.segments.push(stand_in.seg);
    }
    fn run(&mut self, seg: Segment, segments: f64) {
        assert!(segments >= 1.0, "{segments}");
        self.stood += segments;
        self.blots += 1;
        self.rec.segments.push(seg);
    }
}

/// A [`Detailed`] turtle asking for `detail`.
fn detailed(detail: f64) -> Detailed {
    Detailed {
        detail,
        ..Detailed::default()
    }
}

fn lod(s: &LSystem, depth: u32, detail: f64) -> Detailed {
    let (mut t, limits) = (detailed(detail), Limits::default());
    draw(s, depth, Dfs, &limits, &mut t, &mut NoProgress).unwrap();
    t
}

/// The exact segments of `s` at `depth`.
fn exact(s: &LSystem, depth: u32) -> Recorder {
    let (mut rec, limits) = (Recorder::default(), Limits::default());
    draw_into(s, depth, Dfs, &limits, &mut rec, &mut NoProgress).unwrap();
    rec
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// The memo's box, end and count match a full traversal, and the level
    /// of detail at 0 draws the exact segments bit for bit.
    #[test]
    fn memo_matches_a_traversal(
        axiom in word(ALPHABET, 8),
        rules in proptest::collection::vec(word(ALPHABET, 9), 4),
        angle in prop_oneof![Just(90.0), Just(60.0), Just(25.7), -400.0..400.0f64],
        heading in prop_oneof![Just(90.0), Just(0.0), -720.0..720.0f64],
        depth in 0u32..=5,
    ) {
        let src = source(axiom, &rules, angle, heading);
        let s = sys(&src);
        let (bbox, end, count) = traversed(&s, depth);
        let m: Measured = measure(&s, depth, s.length).unwrap();
        prop_assert_eq!(m.segments, count, "{}", src);
        prop_assert_eq!(m.bbox.is_some(), bbox.is_some(), "{}", src);
        if let (Some(a), Some(b)) = (m.bbox, bbox) {
            prop_assert!(close_box(&a, &b, 1e-9), "{:?} {:?} {}", a, b, src);
        }
        prop_assert!(close(m.end.x, end.x, 1e-9) && close(m.end.y, end.y, 1e-9), "{}", src);

        let exact = exact(&s, depth);
        let mut at0 = Detailed::default();
        prop_assert!(draw_lod(&s, depth, 0.0, &Limits::default(), &mut at0, &mut NoProgress).unwrap());
        prop_assert_eq!(at0.blots, 0);
        prop_assert_eq!(&at0.rec.segments, &exact.segments, "{}", src);
    }
}

// ------------------------------------- against an independent recursion --

/// What an independent recursion computes per (symbol, depth, heading):
/// net move, net turn in degrees, flip, and the box of drawn points.
#[derive(Clone, Copy)]
struct Geo {
    x: f64,
    y: f64,
    turn: f64,
    flip: bool,
    bbox: Option<[f64; 4]>,
}

/// Plain recursion over the rule strings with float headings in degrees
/// (no integer turns, no composition by pieces of the library), memoized
/// by (symbol, depth, heading in millionths of a degree modulo 360).
struct Recursion {
    rules: BTreeMap<char, Vec<char>>,
    angle: f64,
    memo: HashMap<(char, u32, i64), Geo>,
}

impl Recursion {
    fn new(s: &LSystem) -> Self {
        let rules = s.rules.iter().map(|(k, p)| (*k, p[0].successor.clone()));
        Recursion {
            rules: rules.collect(),
            angle: s.angle,
            memo: HashMap::new(),
        }
    }

    /// The word `w` (symbols at depth `r`) walked from the origin at
    /// `heading` degrees, unflipped.
    fn walk(&mut self, w: &[char], r: u32, heading: f64) -> Geo {
        let (mut x, mut y, mut h, mut flip) = (0.0f64, 0.0f64, heading, false);
        let mut bbox: Option<[f64; 4]> = None;
        let mut stack = Vec::new();
        let add = |bbox: &mut Option<[f64; 4]>, px: f64, py: f64| {
            let b = bbox.get_or_insert([px, py, px, py]);
            b[0] = b[0].min(px);
            b[1] = b[1].min(py);
            b[2] = b[2].max(px);
            b[3] = b[3].max(py);
        };
        for &c in w {
            let sign = if flip { -1.0 } else { 1.0 };
            match c {
                '[' => stack.push((x, y, h, flip)),
                ']' => (x, y, h, flip) = stack.pop().unwrap(),
                c if r > 0 && self.rules.contains_key(&c) => {
                    let g = self.geo(c, r - 1, h);
                    if let Some(b) = g.bbox {
                        add(&mut bbox, x + sign * b[0], y + sign * b[1]);
                        add(&mut bbox, x + sign * b[2], y + sign * b[3]);
                    }
                    x += sign * g.x;
                    y += sign * g.y;
                    h += g.turn;
                    flip ^= g.flip;
                }
                'F' | 'f' => {
                    // Right angles exactly (the Hilbert curve's 4^31 steps
                    // would otherwise drift by cos(90 degrees) = 6e-17 each).
                    let deg = h.rem_euclid(360.0);
                    let quarter = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
                    let right = deg % 90.0 == 0.0 && deg < 360.0;
                    let rad = deg.to_radians();
                    let exact = right.then(|| quarter[(deg / 90.0) as usize]);
                    let (co, si) = exact.unwrap_or((libm::cos(rad), libm::sin(rad)));
                    let (dx, dy) = (sign * co, -sign * si);
                    if c == 'F' {
                        add(&mut bbox, x, y);
                        add(&mut bbox, x + dx, y + dy);
                    }
                    x += dx;
                    y += dy;
                }
                '+' => h += self.angle,
                '-' => h -= self.angle,
                '|' => flip = !flip,
                _ => {}
            }
        }
        Geo {
            x,
            y,
            turn: h - heading,
            flip,
            bbox,
        }
    }

    fn geo(&mut self, c: char, r: u32, heading: f64) -> Geo {
        let turn = libm::round(heading.rem_euclid(360.0) * 1e6) as i64 % 360_000_000;
        let key = (c, r, turn);
        if let Some(g) = self.memo.get(&key) {
            return *g;
        }
        let succ = self.rules[&c].clone();
        let g = self.walk(&succ, r, heading);
        self.memo.insert(key, g);
        g
    }
}

#[test]
fn memo_matches_an_independent_recursion_at_depth_30_and_more() {
    let hilbert = "axiom L\nrule L +RF-LFL-FR+\nrule R -LF+RFR+FL-\nangle 90\n";
    let plant = "axiom X\nrule X F-[[X]+X]+F[+FX]-X\nrule F FF\nangle 22.5\nheading 80\n";
    let cases = [
        ("axiom F\nrule F F[+F]F[-F]F\nangle 25.7\n", 30),
        ("axiom F\nrule F F[+F]F[-F]F\nangle 25.7\n", 57),
        ("axiom X\nrule X F[+X]F[-X]+X\nrule F FF\nangle 20\n", 40),
        ("axiom F--F--F\nrule F F+F--F+F\nangle 60\n", 30),
        (hilbert, 31),
        (plant, 33),
        ("axiom F|F\nrule F F[+F|f]F[-fF]|F\nangle 33.3\n", 30),
    ];
    for (src, depth) in cases {
        let s = sys(src);
        let m = measure(&s, depth, 1.0).unwrap();
        let mut rec = Recursion::new(&s);
        let g = rec.walk(&s.axiom, depth, s.heading);
        let b = g.bbox.expect("draws");
        let mut want = BBox::at(stlc::turtle::Point::new(b[0], b[1]));
        want.add(stlc::turtle::Point::new(b[2], b[3]));
        let got = m.bbox.expect("draws");
        // The two sum the same directions in different orders and compute
        // them differently (integer turns vs float degrees): relative
        // agreement to 1e-9 of the drawing's size.
        let size = want.width().max(want.height());
        let tol = 1e-9 * size;
        let lo = [got.min_x - want.min_x, got.min_y - want.min_y];
        let hi = [got.max_x - want.max_x, got.max_y - want.max_y];
        let holds = lo.iter().chain(&hi).all(|d| d.abs() <= tol);
        assert!(holds, "{src} at {depth}: {got:?} vs {want:?}");
        let (end, gx, gy) = (m.end, g.x, g.y);
        let near = (end.x - gx).abs() <= tol && (end.y - gy).abs() <= tol;
        assert!(near, "{src} at {depth}: end {end:?} vs ({gx}, {gy})");
    }
}

/// ABOP 1.24a at depth n: the trunk is 3^n steps straight up, so the box's
/// top is exactly -3^n (integer steps up are exact in floating point).
#[test]
fn tree_height_is_three_to_the_depth() {
    let s = sys("axiom F\nrule F F[+F]F[-F]F\nangle 25.7\n");
    for depth in [10u32, 20, 33] {
        let m = measure(&s, depth, 1.0).unwrap();
        assert_eq!(m.bbox.unwrap().min_y, -(3f64.powi(depth as i32)));
        assert_eq!(m.bbox.unwrap().max_y, 0.0);
        assert_eq!(m.end.x, 0.0);
        assert_eq!(m.end.y, -(3f64.powi(depth as i32)));
    }
}

#[test]
fn the_memo_refuses_what_it_cannot_bound() {
    // Net turn x 5 per level: headings past 2^63 at depth 30 and no period.
    let s = sys("axiom F\nrule F F+F+F+F+F\nangle 25.123456789\n");
    assert!(measure(&s, 5, 1.0).is_ok());
    let refused = measure(&s, 40, 1.0);
    assert!(matches!(refused, Err(Refusal::Budget | Refusal::Turns)));
}

// ------------------------------------------------------ level of detail --

/// At a detail as large as the drawing, the whole word is one stand-in;
/// smaller details give more, and every stand-in and segment lies in the
/// memo's box.
#[test]
fn level_of_detail_is_bounded_and_stays_in_the_box() {
    let s = sys("axiom F\nrule F F[+F]F[-F]F\nangle 25.7\n");
    let depth = 57;
    let m = measure(&s, depth, s.length).unwrap();
    let b = m.bbox.unwrap();
    let size = b.width().max(b.height());
    let whole = lod(&s, depth, size * 1.01);
    assert_eq!((whole.blots, whole.rec.segments.len()), (1, 1));
    // The trunk is the chord, from the origin straight up to the end,
    // moved across onto the middle of the box (a bush's stand-in).
    let seg = whole.rec.segments[0];
    let mid = (b.min_x + b.max_x) / 2.0;
    assert!((seg.from.x - mid).abs() < 1e-9 * size && (seg.to.x - mid).abs() < 1e-9 * size);
    assert_eq!((seg.from.y, seg.to.y), (0.0, m.end.y));
    assert!(m.end.x.abs() < 1e-9 * size, "{:?}", m.end);
    // 1/200 of the picture: a few thousand stand-ins at depth 57 (the word
    // has 10^40 symbols).
    let fine = lod(&s, depth, size / 200.0);
    let n = fine.rec.segments.len();
    assert!(n > 100 && n < 20_000, "{n}");
    let slack = size * 1e-9;
    for seg in &fine.rec.segments {
        for p in [seg.from, seg.to] {
            let across = b.min_x - slack <= p.x && p.x <= b.max_x + slack;
            let down = b.min_y - slack <= p.y && p.y <= b.max_y + slack;
            assert!(across && down, "{p:?} outside {b:?}");
        }
    }
}

/// A straight line (`F -> FF`) cut into stand-ins is still the same line:
/// every stand-in is a run's chord ([`Turtle::run`]), of 2^30 segments,
/// joined end to end.
#[test]
fn a_straight_run_is_drawn_as_its_chords() {
    let s = sys("axiom F\nrule F FF\nangle 90\n");
    // A connected run is cut at half the detail: F at 30 steps is 2^30
    // long, under it; at 31, over it.
    let t = lod(&s, 40, 3.0 * 2f64.powi(30));
    let segs = &t.rec.segments;
    assert_eq!(segs.len(), 1024);
    assert_eq!(t.blots, 1024);
    // Each stands for 2^30 of the 2^40 segments.
    assert_eq!(t.stood, 2f64.powi(40));
    for w in segs.windows(2) {
        assert_eq!(w[0].to, w[1].from);
        assert_eq!(w[0].from.x, 0.0);
    }
    assert_eq!(segs.last().unwrap().to.y, -(2f64.powi(40)));
}

// ------------------------------------------------------------ the CLI --

/// Depth 57 (10^40 symbols) renders to PNG and to an SVG of bounded size;
/// with --exact it is refused by the traversal budget, naming the flag.
#[test]
fn depth_57_renders_at_a_level_of_detail_and_exact_refuses() {
    let dir = tempfile::tempdir().unwrap();
    let lsys = crate::support::manifest_path("examples/abop-1.24a.lsys");
    let lsys = lsys.display();
    let render = |flags: &str, out: &str| {
        let out = dir.path().join(out);
        let line = format!("render {lsys} --depth 57 {flags} -o {}", out.display());
        crate::support::outcome(&mut stlc_line(&line))
    };
    assert_eq!(render("--size 200x200", "t.png").0, 0);
    let pixmap = tiny_skia::Pixmap::load_png(dir.path().join("t.png")).unwrap();
    assert_eq!((pixmap.width(), pixmap.height()), (200, 200));
    // Something is drawn in the middle column (the trunk), not everywhere.
    let dark = pixmap.pixels().iter().filter(|p| p.red() < 128).count();
    assert!(dark > 200 && dark < 200 * 200 / 2, "{dark}");
    assert_eq!(render("--size 200x200", "t.svg").0, 0);
    let text = std::fs::read_to_string(dir.path().join("t.svg")).unwrap();
    // A few thousand stand-ins at 200 px: well under a megabyte.
    assert!(text.len() < 1_000_000, "{}", text.len());
    assert!(text.contains("<path"));
    let (code, _, err) = render("--exact", "x.png");
    assert!(code != 0 && err.contains("--max-symbols"), "{err}");
    // And the limit still holds at a level of detail: visits are counted.
    let (code, _, err) = render("--max-symbols 1000", "y.png");
    assert!(code != 0 && err.contains("level of detail"), "{err}");
}

// ------------------------------------- walk or exact path: the decision --

/// `F -> F[+F]F[-F]F` (11 symbols, 5 `F`) at a detail of 4 steps cuts
/// exactly the pieces one level above the terminals (box about 3 steps;
/// two levels up the trunk alone is 9 steps long). By hand: the word has
/// `L(d) = 5 L(d-1) + 6`, `L(0) = 1`, so `2.5 * 5^d - 1.5` symbols; the
/// walk visits each expanded symbol and its successor's 6 brackets and
/// turns, `U(r) = 1 + 6 + 5 U(r-1)` down to `U(1) = 1` (the stand-in), so
/// `2.75 * 5^(d-1) - 1.75`; the stand-ins are the `5^(d-1)` pieces at
/// level 1. Visits are about 0.22 of the word: the walk draws.
#[test]
fn the_plan_counts_what_each_path_visits() {
    let s = sys("axiom F\nrule F F[+F]F[-F]F\nangle 25.7\nlength 1\n");
    for d in [3u32, 8, 11] {
        let memo = Memo::new(&s, d).unwrap();
        let p = 5u64.pow(d - 1);
        let plan = memo.plan(4.0, Limits::default().max_symbols);
        assert_eq!(plan.word, (5 * 5u64.pow(d) - 3) / 2, "depth {d}");
        assert_eq!(plan.visits, (11 * p - 7) / 4, "depth {d}");
        assert_eq!(plan.cuts, p, "depth {d}");
        assert!(plan.walk);
        // Nothing under the detail: nothing cut, the exact path draws.
        let none = memo.plan(0.5, Limits::default().max_symbols);
        assert_eq!(none.cuts, 0);
        assert!(!none.walk);
    }
}

/// Ten plain `F` and one small bush `B`: cutting the bush saves too little
/// (11 of 18 symbols visited, over `LOD_MAX_VISITS` = 0.35), so the exact
/// path draws and the segments are the exact ones; with a bush three times
/// as big (11 of 34, 0.32) the walk draws it as one stand-in.
#[test]
fn a_cut_that_saves_too_little_draws_exactly() {
    let small = sys("axiom FFFFFFFFFFB\nrule B [+F][-F]\nangle 90\nlength 1\n");
    let big = sys("axiom FFFFFFFFFFB\nrule B [+F][-F][+F][-F][+F][-F]\nangle 90\nlength 1\n");
    let max = Limits::default().max_symbols;
    // The bush spans 2 steps: a detail of 3 cuts it.
    let plan = Memo::new(&small, 1).unwrap().plan(3.0, max);
    let counts = |p: &stlc::interpret::lsys::Plan| (p.visits, p.word, p.cuts, p.walk);
    assert_eq!(counts(&plan), (11, 18, 1, false));
    let t = lod(&small, 1, 3.0);
    let exact = exact(&small, 1);
    assert_eq!(exact.segments.len(), 12);
    assert_eq!(t.blots, 0);
    assert_eq!(t.rec.segments, exact.segments);
    // Asked for the walk regardless, it cuts the bush.
    let (mut forced, limits) = (detailed(3.0), Limits::default());
    assert!(draw_lod(&small, 1, 3.0, &limits, &mut forced, &mut NoProgress).unwrap());
    assert_eq!((forced.blots, forced.rec.segments.len()), (1, 11));

    let plan = Memo::new(&big, 1).unwrap().plan(3.0, max);
    assert_eq!(counts(&plan), (11, 34, 1, true));
    let t = lod(&big, 1, 3.0);
    assert_eq!((t.blots, t.rec.segments.len()), (1, 11));
    // Over the traversal budget the exact path would refuse: the walk
    // draws whatever it saves.
    let plan = Memo::new(&small, 1).unwrap().plan(3.0, 17);
    assert!(plan.walk);
}
