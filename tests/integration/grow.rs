//! The grower (issue 4): an OD grown into a BED under space occupancy.
//!
//! Every description is `.od` text read by the real parser. Every grown BED
//! is checked by walking it again, independently of the grower: every
//! segment recomputed with the interpreter's turtle, tested against the
//! layout with geo's `Contains`, and every pair of segments against the
//! clearance (O(n^2), with the joint exception).

use geo::{
    BooleanOps, Contains, Coord, Distance, Euclidean, Line, LineString, MultiPolygon, Polygon,
};

use crate::support::{limit_kind, near_pairs, od, opts};
use stlc::bed::Bed;
use stlc::diag::GrowError;
use stlc::grow::{GrowOptions, Grown, GrowthOrder, grow, grow_traced};
use stlc::model::*;
use stlc::progress::NoProgress;
use stlc::rings::shape_ring;
use stlc::syntax::stl::parse;
use stlc::turtle::{Interp, Op};
use stlc::turtle::{Point, Recorder, Segment};
use stlc::{Bound, Diagnostics, ErrorKind, Limits, Severity};

// ------------------------------------------------------------ descriptions

/// The span of the first `needle` in `text`.
pub fn span_of(text: &str, needle: &str) -> std::ops::Range<usize> {
    let at = text.find(needle).expect("needle in text");
    at..at + needle.len()
}

/// What `od` grows with the options `o`, which must succeed.
pub fn grown(od: &Description, o: GrowOptions) -> Grown {
    grow(od, &o, &mut NoProgress).unwrap_or_else(|e| panic!("{e}"))
}

fn grow_err(od: &Description, o: GrowOptions) -> Diagnostics {
    let grown = grow(od, &o, &mut NoProgress).map(|g| g.stems);
    grown.expect_err("grew stems, expected an error")
}

/// [`seed_text`] of what grew.
fn seed_of(g: &Grown) -> String {
    seed_text(g.bed.description())
}

/// [`draw_bed`] of what grew.
fn drawn(g: &Grown) -> Vec<Segment> {
    draw_bed(g.bed.description())
}

// ------------------------------------------------- independent BED walk

/// Every segment a BED draws, recomputed: seed items in order, a term as
/// Enter, its rule's body (slot i at the tip of branch i), Leave; a
/// forest's trees one after another, each from its root.
fn draw_bed(bed: &Description) -> Vec<Segment> {
    let mut trees = vec![(bed.root, bed.seed.as_ref().unwrap())];
    for t in &bed.forest {
        let seed = t.seed.as_ref().expect("a grown forest has a seed per root");
        trees.push((t.root, seed));
    }
    let tree = |(root, seed)| draw_tree(bed, root, seed);
    trees.into_iter().flat_map(tree).collect()
}

/// [`draw_bed`] for one tree.
fn draw_tree(bed: &Description, root: (f64, f64), seed: &Seed) -> Vec<Segment> {
    enum Task<'a> {
        Text(std::borrow::Cow<'a, str>),
        Term(Term<'a>),
        Op(Op),
    }
    fn fixed_text(f: &Fixed) -> String {
        let mut w = "F".to_string();
        for _ in 0..f.count {
            w = w.replace('F', &f.word);
        }
        w
    }
    let p = &bed.params;
    let at = Point::new(root.0, root.1);
    let mut it = Interp::new(Recorder::default(), at, p.angle(), p.length);
    let mut stack: Vec<Task> = Vec::new();
    for item in seed.items.iter().rev() {
        stack.push(match item {
            SeedItem::Draw(d) => Task::Text((&d.text).into()),
            SeedItem::Fixed(f) => Task::Text(fixed_text(f).into()),
            SeedItem::Term(t) => {
                let t = seed.term(*t);
                assert!(!t.bare(), "a BED has no bare terms");
                Task::Term(t)
            }
            SeedItem::Repeat(_) => panic!("a grown BED has no [I n X] left"),
        });
    }
    while let Some(t) = stack.pop() {
        match t {
            Task::Text(s) => s.chars().filter_map(Op::of_stl).for_each(|o| it.apply(o)),
            Task::Op(o) => it.apply(o),
            Task::Term(term) => {
                let rule = bed.rule(term.rule());
                assert_eq!(term.slot_count(), rule.branch_count());
                let mut seq = vec![Task::Op(Op::Enter)];
                let mut k = 0;
                for item in &rule.body.items {
                    match item {
                        BodyItem::Draw(d) => seq.push(Task::Text((&d.text).into())),
                        BodyItem::Fixed(f) => seq.push(Task::Text(fixed_text(f).into())),
                        BodyItem::Branch(b) => {
                            seq.push(Task::Op(Op::Push));
                            for piece in &b.pieces {
                                match piece {
                                    Piece::Draw(d) => seq.push(Task::Text((&d.text).into())),
                                    Piece::Fixed(f) => seq.push(Task::Text(fixed_text(f).into())),
                                }
                            }
                            match term.slot(k) {
                                Some(Slot::Term(t)) => seq.push(Task::Term(t)),
                                Some(Slot::Repeat(_)) => panic!("no repeats in a grown BED"),
                                None => {}
                            }
                            seq.push(Task::Op(Op::Pop));
                            k += 1;
                        }
                    }
                }
                seq.push(Task::Op(Op::Leave));
                stack.extend(seq.into_iter().rev());
            }
        }
    }
    it.into_turtle().segments
}

/// The BED's seed as text, iteratively (`R1{R1{,},}`), for comparisons.
fn seed_text(bed: &Description) -> String {
    enum Tok<'a> {
        Term(Term<'a>),
        Lit(&'static str),
    }
    let mut out = String::new();
    let mut stack: Vec<Tok> = Vec::new();
    let seed = bed.seed.as_ref().unwrap();
    for item in seed.items.iter() {
        match item {
            SeedItem::Draw(d) => out.push_str(&d.text),
            SeedItem::Fixed(f) => out.push_str(&format!("[I {} {}]", f.count, f.word)),
            SeedItem::Term(t) => stack.push(Tok::Term(seed.term(*t))),
            SeedItem::Repeat(_) => out.push('?'),
        }
        while let Some(tok) = stack.pop() {
            match tok {
                Tok::Lit(s) => out.push_str(s),
                Tok::Term(t) => {
                    out.push_str(&bed.rule(t.rule()).name);
                    out.push('{');
                    let mut seq = Vec::new();
                    for (i, s) in t.slots().enumerate() {
                        if i > 0 {
                            seq.push(Tok::Lit(","));
                        }
                        if let Some(Slot::Term(c)) = s {
                            seq.push(Tok::Term(c));
                        }
                    }
                    seq.push(Tok::Lit("}"));
                    stack.extend(seq.into_iter().rev());
                }
            }
        }
    }
    out
}

/// Number of terms (rule applications) under a term, itself included.
fn subtree_size(t: Term<'_>) -> usize {
    let mut n = 0;
    let mut stack = vec![t];
    while let Some(t) = stack.pop() {
        n += 1;
        for s in t.slots().flatten() {
            if let Slot::Term(c) = s {
                stack.push(c);
            }
        }
    }
    n
}

fn max_order(segs: &[Segment]) -> u32 {
    segs.iter().map(|s| s.order).max().unwrap_or(0)
}

// ------------------------------------------------------- invariants

/// The layout painted with geo directly (union / difference in order).
fn oracle_region(od: &Description) -> MultiPolygon<f64> {
    let mut area = MultiPolygon::<f64>::new(vec![]);
    for s in &od.layout.as_ref().unwrap().shapes {
        let mut ring: Vec<Coord<f64>> = match &s.shape {
            Shape::Rect { x, y, w, h } => {
                let corners = [(*x, *y), (x + w, *y), (x + w, y + h), (*x, y + h)];
                corners.map(Coord::from).to_vec()
            }
            Shape::Polygon(p) => p.iter().map(|&(x, y)| Coord { x, y }).collect(),
            other => shape_ring(other)
                .into_iter()
                .map(|p| Coord { x: p.x, y: p.y })
                .collect(),
        };
        ring.push(ring[0]);
        let poly = Polygon::new(LineString::new(ring), vec![]);
        area = if s.color.is_white() {
            area.difference(&poly)
        } else {
            area.union(&poly)
        };
    }
    area
}

fn line(s: &Segment) -> Line<f64> {
    Line::new((s.from.x, s.from.y), (s.to.x, s.to.y))
}

/// The nearest point of segment `l` to `p`.
fn nearest(p: Point, l: &Line<f64>) -> Point {
    let (dx, dy) = (l.end.x - l.start.x, l.end.y - l.start.y);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.x - l.start.x) * dx + (p.y - l.start.y) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    if t <= 0.0 {
        Point::new(l.start.x, l.start.y)
    } else if t >= 1.0 {
        Point::new(l.end.x, l.end.y)
    } else {
        Point::new(l.start.x + t * dx, l.start.y + t * dy)
    }
}

/// Checks every invariant of a grown BED, with stems as drawn (capsules
/// of half their stroke width, `B - k dB` at order k); returns its
/// segments. Computed by brute force with geo, independently of the
/// grower's indexes:
/// - every grown stem (order >= 1) lies inside the region with its whole
///   stroke: inside, and at least its half width from the boundary;
/// - every pair of stems, one of them grown, keeps the clearance between
///   their drawn edges (`C + r1 + r2` between centre lines), except at a
///   joint, where only a far end may not come that close to the other stem
///   at a point other than the joint.
fn check_invariants(od: &Description, g: &Grown) -> Vec<Segment> {
    let desc = g.bed.description();
    let segs = draw_bed(desc);
    assert_eq!(segs.len() as u64, g.stems, "stems reported vs drawn");
    let c = desc.params.clearance.expect("clearance recorded");
    let radius = |s: &Segment| (desc.params.width.at(s.order) / 2.0).max(0.0);
    let tol = 1e-9;
    if od.layout.is_some() {
        let region = oracle_region(od);
        let boundary: Vec<Line<f64>> = region
            .0
            .iter()
            .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
            .flat_map(|r| r.lines())
            .collect();
        for s in &segs {
            let holds = region.contains(&line(s));
            assert!(holds, "segment {s:?} is not inside the region");
            if s.order == 0 {
                continue; // the seed is drawn as given
            }
            let l = line(s);
            let distances = boundary.iter().map(|e| Euclidean.distance(&l, e));
            let d = distances.fold(f64::INFINITY, f64::min);
            let r = radius(s);
            let ok = d >= r - tol;
            assert!(ok, "the stroke of {s:?} pokes out of the region: {d} < {r}");
        }
    }
    // Pairwise clearance with the joint exception, brute force over the
    // pairs whose x spans come within the largest clearance needed.
    let span = |s: &Segment| (s.from.x.min(s.to.x), s.from.x.max(s.to.x));
    let spans: Vec<(f64, f64)> = segs.iter().map(span).collect();
    let widest = segs.iter().map(radius).fold(0.0, f64::max);
    near_pairs(&spans, c + 2.0 * widest, |a, b| {
        let (s, t) = (&segs[a], &segs[b]);
        let ls = line(s);
        if s.order == 0 && t.order == 0 {
            return; // two seed stems: drawn as given
        }
        let need = c + radius(s) + radius(t);
        let lt = line(t);
        let ends_t = [t.from, t.to];
        if let Some(j) = [s.from, s.to].into_iter().find(|p| ends_t.contains(p)) {
            // A joint is where at least one of them starts.
            let holds = s.from == j || t.from == j;
            assert!(holds, "{s:?} and {t:?} meet end to end");
            let far_s = if s.from == j { s.to } else { s.from };
            let far_t = if t.from == j { t.to } else { t.from };
            for (far, other) in [(far_s, &lt), (far_t, &ls)] {
                let at = nearest(far, other);
                if at == j {
                    continue; // nearest at the joint: no fold
                }
                let d = Euclidean.distance(&geo::Point::new(far.x, far.y), other);
                let holds = d >= need - tol;
                assert!(holds, "joint too tight: {s:?} {t:?} ({d}) < {need}");
            }
        } else {
            let d = Euclidean.distance(&ls, &lt);
            assert!(d >= need - tol, "too close: {s:?} {t:?} {d} < {need}");
        }
    });
    segs
}

/// `d` grown in each order, the invariants checked on each, which drew
/// more than `more_than` stems.
fn grown_checked(d: &Description, more_than: usize, what: &str) -> Vec<Grown> {
    let orders = [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space];
    orders
        .map(|s| {
            let g = grown(d, opts(s));
            let n = check_invariants(d, &g).len();
            assert!(n > more_than, "{what} {s:?} grew only {n}");
            g
        })
        .into()
}

// ---------------------------------------------------------- trees

/// The paper's 2DTree (Figure 8), as `examples/2dtree.od` has it: Delphi's
/// corners spelling, `RoundRect (x1,y1,x2,y2,rx,ry)` with the corner
/// ellipse's width and height.
const TWO_D_TREE: &str = "2DTree (76, 150) L=10(0) B=1(0)
    RULE R1: [+F][-F]
    LAYOUT
    (clGreen) RoundRect (0,0,180,192,7,7)
    (clWhite) RoundRect (55,30,40,15,4,4)
    (clWhite) RoundRect (35,125,76,30,5,5)
    ENDLAYOUT";

/// Figures 9 and 10 (`Seed = FR1`, `R1 = [-F][+F]`) in a 200 x 200 square,
/// with stem parameters `params` and a `SEED ... ENDSEED` section `seed`
/// (empty: the default seed `F R1`).
fn figure_9_10_with(params: &str, seed: &str) -> Description {
    od(&format!(
        "Fig9 (100, 195) {params}
        RULE R1: [-F][+F]
        {seed}
        LAYOUT (clGreen) Rectangle (0,0), 200, 200 ENDLAYOUT"
    ))
}

fn figure_9_10() -> Description {
    figure_9_10_with("L=10(0) B=1(0)", "")
}

/// The binary tree `R1 = [+F][-F]` from the root (0, 0), no layout.
const BINARY: &str = "Binary (0, 0) L=10(0) B=1(0) RULE R1: [+F][-F]";

#[test]
fn invariants_hold_on_several_grown_trees() {
    let ellipse = "Ellipse (100, 150) L=8(0) B=1(0)
        RULE R1: [+F][F][-F]
        LAYOUT (clGreen) Ellipse (0,0), 200, 160 ENDLAYOUT";
    let polygon = "Polygon (50, 95) L=10(0) B=1(0) A=25
        RULE
        R1: F[+F R2][-F]
        R2: [++F][F]
        LAYOUT (clGreen) Polygon (0,100), (100,100), (80,0), (10,20) ENDLAYOUT";
    let fixed = "Fixed (60, 118) L=5(0) B=1(0)
        RULE
        R1: [+F[I 2 F[+F]F]][-FF R2]
        R2: [I 1 F[-F]][+F R1]
        LAYOUT (clGreen) Rectangle (0,0), 120, 120 ENDLAYOUT";
    let (ellipse, polygon, fixed) = (od(ellipse), od(polygon), od(fixed));
    for d in [od(TWO_D_TREE), figure_9_10(), ellipse, polygon, fixed] {
        for g in grown_checked(&d, 40, &d.name) {
            assert!(g.warnings.is_empty());
        }
    }
}

/// Every example outline, thick stems and tapering widths included, grows
/// into a tree whose strokes stay inside the outline and apart, as drawn.
#[test]
fn invariants_hold_on_every_example_with_strokes_as_drawn() {
    let names = crate::support::files_with("examples", "od");
    assert!(names.len() >= 8, "{names:?}");
    for path in names {
        let d = od(&std::fs::read_to_string(&path).unwrap());
        if d.is_3d() {
            continue; // grow3d.rs checks the 3D examples in their volumes
        }
        grown_checked(&d, 10, &path.display().to_string());
    }
}

/// The grove's trees compete for one outline: for the gallery's seeds, in
/// both orders, every tree's strokes stay inside and clear of every other
/// tree's as of its own (the pairwise check runs over all trees' stems).
/// (A tree may find no room: dfs lets the first trees take it.)
#[test]
fn trees_of_a_forest_keep_clear_of_each_other() {
    let d = od(&crate::support::example_text("grove.od"));
    assert_eq!(d.forest.len(), 3, "four roots");
    for seed in [7, 8] {
        for s in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
            let g = grown(&d, GrowOptions { seed, ..opts(s) });
            let segs = check_invariants(&d, &g);
            let forest = &g.bed.description().forest;
            assert_eq!(forest.len(), 3);
            assert!(forest.iter().all(|t| t.seed.is_some()));
            // Stems start at every root: each tree drew at least its seed.
            for t in forest {
                let (x, y) = t.root;
                let holds = segs.iter().any(|p| p.from.x == x && p.from.y == y);
                assert!(holds, "seed {seed} {s:?}: nothing at root ({x}, {y})");
            }
        }
    }
}

#[test]
fn bfs_and_dfs_grow_different_trees_from_figure_9_10() {
    let d = figure_9_10();
    let bfs = grown(&d, opts(GrowthOrder::Bfs));
    let dfs = grown(&d, opts(GrowthOrder::Dfs));
    check_invariants(&d, &bfs);
    check_invariants(&d, &dfs);
    assert_ne!(seed_of(&bfs), seed_of(&dfs));
    // The seed's one growth point grew: F then R1{right, left}.
    let root = |g: &Grown| -> (usize, usize) {
        let seed = g.bed.description().seed.as_ref().unwrap();
        let SeedItem::Term(t) = &seed.items[1] else {
            panic!("no term")
        };
        let t = seed.term(*t);
        let size = |s: Option<Slot<'_>>| match s {
            Some(Slot::Term(t)) => subtree_size(t),
            _ => 0,
        };
        (size(t.slot(0)), size(t.slot(1)))
    };
    let ((b_right, b_left), (d_right, d_left)) = (root(&bfs), root(&dfs));
    // Breadth-first: both sides get an almost equal share (the paper's
    // "equally distributed in left and right sides").
    let b_ratio = b_right as f64 / b_left as f64;
    assert!((0.8..1.25).contains(&b_ratio), "bfs {b_right} vs {b_left}");
    // Depth-first: the right branch ([-F], first) grows its whole subtree
    // first and takes most of the space; the left one struggles.
    assert!(d_right > 2 * d_left, "dfs {d_right} vs {d_left}");
    assert!(d_right > b_right);
    // A depth-first tree is deeper (vines).
    let (bfs_depth, dfs_depth) = (max_order(&drawn(&bfs)), max_order(&drawn(&dfs)));
    assert!(dfs_depth > bfs_depth, "{dfs_depth} vs {bfs_depth}");
}

#[test]
fn growth_is_deterministic() {
    for d in [od(TWO_D_TREE), figure_9_10()] {
        for s in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
            let a = grown(&d, opts(s));
            let b = grown(&d, opts(s));
            assert_eq!(seed_of(&a), seed_of(&b));
            assert_eq!(drawn(&a), drawn(&b));
        }
    }
}

/// The full binary tree of `n` levels of R1, written out.
fn full(n: u32) -> String {
    (0..n).fold(String::new(), |c, _| format!("R1{{{c},{c}}}"))
}

#[test]
fn counts_grow_the_full_subtree_when_space_allows() {
    // [I n R1], R1 = [+F][-F], no layout. Equal lengths would make tips
    // coincide (+-+ and -++ end at one point), so the length decreases.
    // Thin stems (B=0.1): the closest tips of the 4-level tree are 0.485
    // apart, more than C + B = 0.4.
    let head = "Counted (0, 0) L=16(3) B=0.1(0) A=45 C=0.3 RULE R1: [+F][-F]";
    for n in 1..=4u32 {
        let stems = 1 + 2 * ((1u64 << n) - 1);
        // Space allows: the full tree, written out by hand as a BED, passes
        // the brute-force checks.
        let text = format!("F{}", full(n));
        let bed_text = format!("{head} SEED {text} ENDSEED");
        let written = parse(&bed_text, Format::Bed, &Limits::default()).unwrap();
        let as_bed = Grown {
            bed: Bed::new(written.clone(), &Limits::default()).unwrap(),
            warnings: vec![],
            stems,
            tallies: vec![],
        };
        check_invariants(&written, &as_bed);

        let d = od(&format!("{head} SEED F[I {n} R1] ENDSEED"));
        for s in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
            let g = grown(&d, opts(s));
            // 2^n - 1 applications of 2 stems each, plus the seed's F.
            assert_eq!(g.stems, stems, "n={n} {s:?}");
            assert_eq!(seed_of(&g), text);
            let segs = check_invariants(&d, &g);
            assert_eq!(max_order(&segs), n);
        }
    }
}

#[test]
fn count_follows_successors() {
    // R1 = [+F R2][-F], R2 = [F], [I 3 R1]:
    // level 1: R1 (2 stems); level 2: R2 (1) + R1 (2);
    // level 3: R2 (1) from R2, R2 (1) + R1 (2) from R1. Total 9, seed 1.
    let d = od("Successors (0, 0) L=10(0) B=1(0)
        RULE
        R1: [+F R2][-F]
        R2: [F]
        SEED F[I 3 R1] ENDSEED");
    let g = grown(&d, opts(GrowthOrder::Bfs));
    assert_eq!(g.stems, 10);
    let wanted = "FR1{R2{R2{}},R1{R2{},R1{,}}}";
    assert_eq!(seed_of(&g), wanted, "written out by hand from the rule");
}

#[test]
fn decrements_end_growth_at_the_right_order() {
    // L=10(2): lengths 10, 8, 6, 4, 2, 0: applications at orders 1..4,
    // a full binary tree of 4 levels: 15 applications, 30 stems + seed.
    // Hairline-thin stems (B=0.01): only the decrement ends growth.
    let d = od("Shorter (0, 0) L=10(2) B=0.01(0) RULE R1: [+F][-F]");
    let mut o = opts(GrowthOrder::Bfs);
    o.clearance = Some(0.0);
    let g = grown(&d, o);
    assert_eq!(g.stems, 31);
    let segs = check_invariants(&d, &g);
    assert_eq!(max_order(&segs), 4);
    // B=1(0.3): widths 1, .7, .4, .1, -.2: orders 1..3, 7 applications
    // (L=10(1): with equal lengths the tips of +- and -+ paths meet).
    let d = od("Thinner (0, 0) L=10(1) B=1(0.3) A=45 RULE R1: [+F][-F]");
    let g = grown(&d, o);
    assert_eq!(g.stems, 15);
    assert_eq!(max_order(&drawn(&g)), 3);
}

#[test]
fn max_stems_stops_growth_with_a_warning() {
    let mut o = opts(GrowthOrder::Bfs);
    (o.clearance, o.limits.max_stems, o.max_stems_explicit) = (Some(0.0), 100, true);
    let g = grown(&od(BINARY), o);
    // 1 + 2k <= 100: 49 applications fit, the 50th would make 101.
    assert_eq!(g.stems, 99);
    assert_eq!(drawn(&g).len(), 99);
    assert_eq!(g.warnings.len(), 1);
    assert_eq!(g.warnings[0].severity, Severity::Warning);
    let (stems, limit) = (99, 100);
    let stopped = ErrorKind::Grow(GrowError::GrowthStopped { stems, limit });
    assert_eq!(g.warnings[0].kind, stopped);
}

#[test]
fn unbounded_growth_is_refused_with_a_fix() {
    let e = grow_err(&od(BINARY), opts(GrowthOrder::Bfs));
    let d = &e.0[0];
    let (rule, through) = ("R1".into(), "R1".into());
    let unbounded = ErrorKind::Grow(GrowError::UnboundedGrowth { rule, through });
    assert_eq!(d.kind, unbounded);
    // The default seed has no text: the rule's name is pointed at.
    assert_eq!(d.span, Some(span_of(BINARY, "R1")));
    let help = d.help_text().unwrap();
    for fix in ["LAYOUT", "[I n R1]", "L=10(1)", "--max-stems"] {
        assert!(help.contains(fix), "help lacks {fix}: {help}");
    }
    // A chain of rules that ends is bounded: R1 -> R2 -> (no branches).
    let d = od("Chain (0, 0) L=10(0) B=1(0)
        RULE
        R1: [+F R2][-F R2]
        R2: F");
    let g = grown(&d, opts(GrowthOrder::Bfs));
    assert_eq!(g.stems, 1 + 2 + 2);
}

#[test]
fn root_outside_the_region_is_an_error() {
    let text = "Fig9 (250, 100) L=10(0) B=1(0)
        RULE R1: [-F][+F]
        LAYOUT (clGreen) Rectangle (0,0), 200, 200 ENDLAYOUT";
    let e = grow_err(&od(text), opts(GrowthOrder::Bfs));
    let (x, y, z) = (250.0, 100.0, None);
    let want = ErrorKind::Grow(GrowError::RootOutside { x, y, z });
    assert_eq!(e.0[0].kind, want);
    assert_eq!(e.0[0].span, Some(span_of(text, "(250, 100)")));
}

#[test]
fn white_holes_are_respected() {
    let d = od("Holes (100, 195) L=6(0) B=1(0)
        RULE R1: [-F][F][+F]
        LAYOUT
        (clGreen) Rectangle (0,0), 200, 200
        (clWhite) Rectangle (60,80), 80, 40
        ENDLAYOUT");
    for s in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
        let g = grown(&d, opts(s));
        let segs = check_invariants(&d, &g);
        let hole = geo::Rect::new((60.0, 80.0), (140.0, 120.0)).to_polygon();
        let hits = |s: &Segment| geo::Intersects::intersects(&hole, &line(s));
        assert!(!segs.iter().any(hits));
        // The tree grew around the hole: stems above it too.
        assert!(segs.iter().any(|s| s.to.y < 70.0));
    }
}

#[test]
fn written_terms_are_drawn_as_given_and_their_slots_grow() {
    // R1{R1,} in the seed: the written R1 is drawn unconditionally, its
    // first slot is a growth point, its second stays empty.
    let d = figure_9_10_with("L=10(0) B=1(0)", "SEED FR1{R1,} ENDSEED");
    let g = grown(&d, opts(GrowthOrder::Dfs));
    check_invariants(&d, &g);
    let text = seed_of(&g);
    assert!(text.starts_with("FR1{R1{"), "{text}");
    assert!(text.ends_with(",}"), "second slot stays empty: {text}");
}

#[test]
fn seed_with_trunk_rule_stays_consistent() {
    // R2 moves the turtle (trunk F) and more seed follows it: positions
    // after it depend on the decision; the BED must still draw what grew.
    let d = od("Trunk (100, 195) L=10(0) B=1(0)
        RULE
        R1: [-F][+F]
        R2: F[-F][+F]
        SEED F R2 F R1 [+F R1] ENDSEED
        LAYOUT (clGreen) Rectangle (0,0), 200, 200 ENDLAYOUT");
    grown_checked(&d, 100, "trunk");
}

#[test]
fn seed_drawing_is_laid_down_before_growth() {
    // Depth-first, the left R1's whole subtree grows before the right one;
    // the seed's `-F` must already be there, or the subtree could take its
    // place (the pairwise check would then fail on it).
    let d = figure_9_10_with("L=10(0) B=1(0)", "SEED F[+F R1][-F R1] ENDSEED");
    grown_checked(&d, 200, "seed drawing");
}

#[test]
fn depth_limit_stops_a_vine_with_a_warning() {
    // R1 = [F]: a straight vine, one stem per application.
    let d = od("Vine (0, 0) L=10(0) B=1(0) RULE R1: [F]");
    let mut o = opts(GrowthOrder::Dfs);
    (o.limits.max_depth, o.max_stems_explicit) = (5, true);
    let g = grown(&d, o);
    assert_eq!(g.stems, 1 + 5);
    assert_eq!(g.warnings.len(), 1);
    assert_eq!(g.warnings[0].severity, Severity::Warning);
    let want = ErrorKind::Grow(GrowError::DepthCapped { limit: 5 });
    assert_eq!(g.warnings[0].kind, want);
}

#[test]
fn progress_is_reported_rarely() {
    #[derive(Default)]
    struct Count {
        started: u64,
        updates: Vec<u64>,
        finished: bool,
    }
    impl stlc::progress::Progress for Count {
        fn start(&mut self, _what: &str, total: u64) {
            self.started = total;
        }
        fn update(&mut self, done: u64) {
            self.updates.push(done);
        }
        fn finish(&mut self) {
            self.finished = true;
        }
    }
    let d = figure_9_10_with("L=1(0) B=0.1(0)", "");
    let mut p = Count::default();
    let g = grow(&d, &opts(GrowthOrder::Bfs), &mut p).unwrap();
    assert!(g.stems > 20_000, "{}", g.stems);
    assert_eq!(p.started, Limits::default().max_stems);
    assert!(p.finished);
    assert!(!p.updates.is_empty() && p.updates.len() as u64 <= g.stems / 10_000 + 1);
    assert!(p.updates.windows(2).all(|w| w[0] <= w[1]));
}

#[test]
fn a_seed_beyond_max_stems_is_an_error_and_the_seed_is_drawn_whole() {
    let mut o = opts(GrowthOrder::Bfs);
    o.limits.max_stems = 4;
    let d = figure_9_10_with("L=10(0) B=1(0)", "SEED FFFFF ENDSEED");
    let e = grow_err(&d, o);
    let seed_alone = Some("stems drawn by the seed alone");
    assert_eq!(e.0[0].kind, limit_kind(Bound::Stems, seed_alone, "5", 4));
    // Terms written out in the seed count what their rules draw, all of
    // them, before anything is drawn: F, then 4 x R1{,} (2 stems each), 9.
    let d = figure_9_10_with("L=10(0) B=1(0)", "SEED F R1{,}R1{,} R1{R1,} ENDSEED");
    let mut few = opts(GrowthOrder::Bfs);
    few.limits.max_stems = 5;
    let e = grow_err(&d, few);
    let seven = limit_kind(Bound::Stems, seed_alone, "7", 5);
    let why = "the bare R1 is a growth point and counts nothing";
    assert_eq!(e.0[0].kind, seven, "{why}");
    // The seed (drawn first, R1 deferred) fills the limit: R1's application
    // would pass it, so growth stops with a warning and R1 is left out.
    let d = figure_9_10_with("L=10(0) B=1(0)", "SEED F R1 F ENDSEED");
    o.limits.max_stems = 2;
    let g = grown(&d, o);
    assert_eq!(g.stems, 2);
    assert_eq!(g.warnings.len(), 1);
    assert_eq!(seed_of(&g), "FF");
}

// ---------------------------------------------------- the growth order

/// `grow_traced` grows the same BED as `grow`, and its list of placed
/// stems is exactly the BED's segments (recomputed by the independent
/// walk), each once, with decisions that never go back and a seed drawn
/// first.
#[test]
fn the_traced_growth_places_exactly_the_beds_stems_in_decision_order() {
    let key = |a: Point, b: Point| {
        let r = |v: f64| (v * 1000.0).round() as i64;
        (r(a.x), r(a.y), r(b.x), r(b.y))
    };
    for file in ["fig9.od", "holes.od", "2dtree.od"] {
        let d = od(&crate::support::example_text(file));
        for order in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let plain = grown(&d, opts(order));
            let (traced, placed) = grow_traced(&d, &opts(order), &mut NoProgress).unwrap();
            assert!(traced == plain, "{file}: grow_traced grew another BED");
            assert_eq!(placed.len() as u64, plain.stems, "{file}");
            let mut from_trace: Vec<_> = placed.iter().map(|p| key(p.from, p.to)).collect();
            let mut from_bed: Vec<_> = drawn(&plain).iter().map(|s| key(s.from, s.to)).collect();
            from_trace.sort_unstable();
            from_bed.sort_unstable();
            assert_eq!(from_trace, from_bed, "{file} {order:?}");
            assert!(placed.windows(2).all(|w| w[0].decision <= w[1].decision));
            assert_eq!(placed[0].decision, 0, "{file}: the seed comes first");
            assert!(placed.last().unwrap().decision > 1, "{file}");
        }
    }
}

/// The BED draws the tree that grew, to the bit: a width decrement just
/// under 1 lets `B=3` reach order 3 with width 2.2e-10, and the BED keeps
/// every digit of it (three decimals would write `1`, leaving order 3
/// without width and the BED invalid); numbers that three decimals keep
/// stay short. Found by the `od_compile` fuzz body.
#[test]
fn the_bed_keeps_every_digit_growth_used() {
    let text = "Shrinking (0.0001234, 0.5) L=12(1) B=3(0.999999999926) A=28 C=0.5
        RULE R1: [+F][-F][F] SEED FR1 ENDSEED";
    let d = od(text);
    let g = grown(&d, opts(GrowthOrder::Bfs));
    let written = stlc::bed::write::write(g.bed.description());
    let holds = written.contains("(0.0001234, 0.5)\nL=12(1) B=3(0.999999999926) A=28 C=0.5\n");
    assert!(holds, "{written}");
    let back = parse(&written, Format::Bed, &Limits::default()).unwrap();
    let mut params = g.bed.description().params.clone();
    params.loc = back.params.loc.clone();
    assert_eq!(back.params, params);
    let bed = Bed::new(back, &Limits::default()).expect("the written BED is valid");
    assert_eq!(bed.size().stems, g.stems);
    assert_eq!(draw_bed(bed.description()), drawn(&g));
}
