//! The grower (issue 4): an OD grown into a BED under space occupancy.
//!
//! The parser is built elsewhere, so descriptions are made here with a small
//! builder. Every grown BED is checked by walking it again, independently of
//! the grower: every segment recomputed with the interpreter's turtle, tested
//! against the layout with geo's `Contains`, and every pair of segments
//! against the clearance (O(n^2), with the joint exception).

use geo::{
    BooleanOps, Contains, Coord, Distance, Euclidean, Line, LineString, MultiPolygon, Polygon,
};

use stlc::color::Rgb;
use stlc::grow::GrowthOrder;
use stlc::grow::occupancy::Backend;
use stlc::grow::{GrowOptions, Grown, grow, grow_with};
use stlc::layout::shape_ring;
use stlc::model::*;
use stlc::num::Linear;
use stlc::progress::NoProgress;
use stlc::turtle::{Interp, Op};
use stlc::turtle::{Point, Recorder, Segment};
use stlc::{ErrorKind, Limits, Severity};

// ---------------------------------------------------------------- builder

fn loc() -> Loc {
    Loc::default()
}

/// A rule body from text: top-level bracket groups are branches (a trailing
/// rule name after a space is the successor), `{I n w}` at top level is a
/// fixed figure, the rest trunk.
fn body(names: &[&str], text: &str) -> Body {
    let mut items = Vec::new();
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    let mut trunk = String::new();
    while i < chars.len() {
        match chars[i] {
            '[' => {
                if !trunk.is_empty() {
                    items.push(BodyItem::Draw(DrawRun {
                        text: std::mem::take(&mut trunk),
                        loc: loc(),
                    }));
                }
                let mut depth = 0;
                let start = i + 1;
                loop {
                    match chars[i] {
                        '[' => depth += 1,
                        ']' => depth -= 1,
                        _ => {}
                    }
                    if depth == 0 {
                        break;
                    }
                    i += 1;
                }
                let inner: String = chars[start..i].iter().collect();
                let (draw, succ) = match inner.rsplit_once(' ') {
                    Some((d, n)) if names.contains(&n) => (d.to_string(), Some(n)),
                    _ => (inner.clone(), None),
                };
                items.push(BodyItem::Branch(Branch {
                    pieces: pieces(&draw),
                    successor: succ.map(|n| RuleRef {
                        rule: RuleId(names.iter().position(|x| *x == n).unwrap()),
                        loc: loc(),
                    }),
                    loc: loc(),
                }));
            }
            '{' => {
                let end = chars[i..].iter().position(|&c| c == '}').unwrap() + i;
                let inner: String = chars[i + 1..end].iter().collect();
                let parts: Vec<&str> = inner.split_whitespace().collect();
                assert_eq!(parts[0], "I");
                items.push(BodyItem::Fixed(Fixed {
                    count: parts[1].parse().unwrap(),
                    word: parts[2].to_string(),
                    loc: loc(),
                }));
                i = end;
            }
            ' ' => {}
            c => trunk.push(c),
        }
        i += 1;
    }
    if !trunk.is_empty() {
        items.push(BodyItem::Draw(DrawRun {
            text: trunk,
            loc: loc(),
        }));
    }
    Body { items }
}

/// Branch contents: drawing runs, and `{I n w}` fixed figures.
fn pieces(text: &str) -> Vec<Piece> {
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(open) = rest.find('{') {
        let close = rest.find('}').unwrap();
        if open > 0 {
            out.push(Piece::Draw(DrawRun {
                text: rest[..open].replace(' ', ""),
                loc: loc(),
            }));
        }
        let parts: Vec<&str> = rest[open + 1..close].split_whitespace().collect();
        assert_eq!(parts[0], "I");
        out.push(Piece::Fixed(Fixed {
            count: parts[1].parse().unwrap(),
            word: parts[2].to_string(),
            loc: loc(),
        }));
        rest = &rest[close + 1..];
    }
    if !rest.trim().is_empty() {
        out.push(Piece::Draw(DrawRun {
            text: rest.replace(' ', ""),
            loc: loc(),
        }));
    }
    out
}

/// A seed from text: drawing components, rule names (bare: growth points),
/// `R1{...,...}` written terms, `(I n R1)` counted growth points.
struct SeedParser<'a> {
    names: &'a [&'a str],
    branches: Vec<usize>,
    s: Vec<char>,
    i: usize,
}

impl SeedParser<'_> {
    fn name(&mut self) -> Option<RuleId> {
        // Longest declared name at i.
        let rest: String = self.s[self.i..].iter().collect();
        let (k, n) = self
            .names
            .iter()
            .enumerate()
            .filter(|(_, n)| rest.starts_with(**n))
            .max_by_key(|(_, n)| n.len())?;
        self.i += n.len();
        Some(RuleId(k))
    }

    fn term(&mut self, rule: RuleId) -> Term {
        if self.s.get(self.i) != Some(&'{') {
            return Term {
                rule,
                slots: vec![None; self.branches[rule.0]],
                bare: true,
                loc: loc(),
            };
        }
        self.i += 1;
        let mut slots = Vec::new();
        let mut cur: Option<Slot> = None;
        loop {
            match self.s[self.i] {
                ',' => {
                    slots.push(cur.take());
                    self.i += 1;
                }
                '}' => {
                    slots.push(cur.take());
                    self.i += 1;
                    break;
                }
                '(' => cur = Some(Slot::Repeat(self.repeat())),
                _ => {
                    let r = self.name().expect("rule name in slot");
                    cur = Some(Slot::Term(self.term(r)));
                }
            }
        }
        if self.branches[rule.0] == 0 {
            slots.clear();
        }
        Term {
            rule,
            slots,
            bare: false,
            loc: loc(),
        }
    }

    fn repeat(&mut self) -> Repeat {
        let end = self.s[self.i..].iter().position(|&c| c == ')').unwrap() + self.i;
        let inner: String = self.s[self.i + 1..end].iter().collect();
        let parts: Vec<&str> = inner.split_whitespace().collect();
        self.i = end + 1;
        Repeat {
            count: parts[1].parse().unwrap(),
            rule: RuleId(self.names.iter().position(|n| *n == parts[2]).unwrap()),
            loc: Loc(0..1),
        }
    }

    fn seed(&mut self) -> Seed {
        let mut items = Vec::new();
        let mut run = String::new();
        while self.i < self.s.len() {
            let c = self.s[self.i];
            let item = if c == '(' {
                Some(SeedItem::Repeat(self.repeat()))
            } else if let Some(r) = self.name() {
                Some(SeedItem::Term(self.term(r)))
            } else {
                if c != ' ' {
                    run.push(c);
                }
                self.i += 1;
                None
            };
            if let Some(item) = item {
                if !run.is_empty() {
                    items.push(SeedItem::Draw(DrawRun {
                        text: std::mem::take(&mut run),
                        loc: loc(),
                    }));
                }
                items.push(item);
            }
        }
        if !run.is_empty() {
            items.push(SeedItem::Draw(DrawRun {
                text: run,
                loc: loc(),
            }));
        }
        Seed { items, loc: loc() }
    }
}

const GREEN: Rgb = Rgb::new(0, 128, 0);

struct Od {
    root: (f64, f64),
    params: StemParams,
    rules: Vec<(&'static str, &'static str)>,
    seed: Option<&'static str>,
    layout: Option<Vec<(Rgb, Shape)>>,
}

fn params(l: f64, dl: f64, b: f64, db: f64) -> StemParams {
    StemParams {
        length: Linear::new(l, dl),
        width: Linear::new(b, db),
        angle: None,
        clearance: None,
        stroke: None,
        background: None,
        loc: loc(),
    }
}

fn rect(x: f64, y: f64, w: f64, h: f64) -> Shape {
    Shape::Rect { x, y, w, h }
}

impl Od {
    fn new(root: (f64, f64), rules: Vec<(&'static str, &'static str)>) -> Self {
        Od {
            root,
            params: params(10.0, 0.0, 1.0, 0.0),
            rules,
            seed: None,
            layout: None,
        }
    }

    fn build(&self) -> Description {
        let names: Vec<&str> = self.rules.iter().map(|r| r.0).collect();
        let rules: Vec<RuleDef> = self
            .rules
            .iter()
            .map(|(n, b)| RuleDef {
                name: n.to_string(),
                name_loc: loc(),
                body: body(&names, b),
                loc: loc(),
            })
            .collect();
        let branches = rules.iter().map(|r| r.branch_count()).collect();
        let seed = self.seed.map(|s| {
            SeedParser {
                names: &names,
                branches,
                s: s.chars().collect(),
                i: 0,
            }
            .seed()
        });
        Description {
            format: Format::Od,
            name: "T".into(),
            name_loc: loc(),
            root: self.root,
            root_loc: Loc(0..1),
            params: self.params.clone(),
            rules,
            seed,
            layout: self.layout.as_ref().map(|shapes| Layout {
                shapes: shapes
                    .iter()
                    .map(|(c, s)| LayoutShape {
                        color: *c,
                        color_text: String::new(),
                        shape: s.clone(),
                        spelling: Spelling::StartSize,
                        angled: false,
                        loc: loc(),
                    })
                    .collect(),
                loc: loc(),
            }),
        }
    }
}

fn opts(growth: GrowthOrder) -> GrowOptions {
    GrowOptions {
        growth,
        ..GrowOptions::default()
    }
}

fn grown(od: &Description, o: GrowOptions) -> Grown {
    grow(od, &o, &mut NoProgress).unwrap_or_else(|e| panic!("{e}"))
}

// ------------------------------------------------- independent BED walk

/// Every segment a BED draws, recomputed: seed items in order, a term as
/// Enter, its rule's body (slot i at the tip of branch i), Leave.
fn draw_bed(bed: &Description) -> Vec<Segment> {
    enum Task<'a> {
        Text(&'a str),
        Term(&'a Term),
        Op(Op),
        Fixed(&'a Fixed),
    }
    fn fixed_text(f: &Fixed) -> String {
        let mut w = "F".to_string();
        for _ in 0..f.count {
            w = w.replace('F', &f.word);
        }
        w
    }
    let p = &bed.params;
    let mut it = Interp::new(
        Recorder::default(),
        Point::new(bed.root.0, bed.root.1),
        p.angle(),
        p.length,
    );
    let seed = bed.seed.as_ref().unwrap();
    let mut stack: Vec<Task> = Vec::new();
    for item in seed.items.iter().rev() {
        stack.push(match item {
            SeedItem::Draw(d) => Task::Text(&d.text),
            SeedItem::Fixed(f) => Task::Fixed(f),
            SeedItem::Term(t) => {
                assert!(!t.bare, "a BED has no bare terms");
                Task::Term(t)
            }
            SeedItem::Repeat(_) => panic!("a grown BED has no [I n X] left"),
        });
    }
    while let Some(t) = stack.pop() {
        match t {
            Task::Text(s) => s.chars().filter_map(Op::of_stl).for_each(|o| it.apply(o)),
            Task::Fixed(f) => fixed_text(f)
                .chars()
                .filter_map(Op::of_stl)
                .for_each(|o| it.apply(o)),
            Task::Op(o) => it.apply(o),
            Task::Term(term) => {
                let rule = bed.rule(term.rule);
                assert_eq!(term.slots.len(), rule.branch_count());
                let mut seq = vec![Task::Op(Op::Enter)];
                let mut k = 0;
                for item in &rule.body.items {
                    match item {
                        BodyItem::Draw(d) => seq.push(Task::Text(&d.text)),
                        BodyItem::Fixed(f) => seq.push(Task::Fixed(f)),
                        BodyItem::Branch(b) => {
                            seq.push(Task::Op(Op::Push));
                            for piece in &b.pieces {
                                match piece {
                                    Piece::Draw(d) => seq.push(Task::Text(&d.text)),
                                    Piece::Fixed(f) => seq.push(Task::Fixed(f)),
                                }
                            }
                            match &term.slots[k] {
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
        Term(&'a Term),
        Lit(&'static str),
    }
    let mut out = String::new();
    let mut stack: Vec<Tok> = Vec::new();
    for item in bed.seed.as_ref().unwrap().items.iter() {
        match item {
            SeedItem::Draw(d) => out.push_str(&d.text),
            SeedItem::Fixed(f) => out.push_str(&format!("[I {} {}]", f.count, f.word)),
            SeedItem::Term(t) => stack.push(Tok::Term(t)),
            SeedItem::Repeat(_) => out.push('?'),
        }
        while let Some(tok) = stack.pop() {
            match tok {
                Tok::Lit(s) => out.push_str(s),
                Tok::Term(t) => {
                    out.push_str(&bed.rule(t.rule).name);
                    out.push('{');
                    let mut seq = Vec::new();
                    for (i, s) in t.slots.iter().enumerate() {
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
fn subtree_size(t: &Term) -> usize {
    let mut n = 0;
    let mut stack = vec![t];
    while let Some(t) = stack.pop() {
        n += 1;
        for s in t.slots.iter().flatten() {
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
            Shape::Rect { x, y, w, h } => vec![
                Coord { x: *x, y: *y },
                Coord { x: x + w, y: *y },
                Coord { x: x + w, y: y + h },
                Coord { x: *x, y: y + h },
            ],
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
    Line::new(
        Coord {
            x: s.from.x,
            y: s.from.y,
        },
        Coord {
            x: s.to.x,
            y: s.to.y,
        },
    )
}

/// Checks every invariant of a grown BED; returns its segments.
fn check_invariants(od: &Description, g: &Grown) -> Vec<Segment> {
    let segs = draw_bed(g.bed.description());
    assert_eq!(segs.len() as u64, g.stems, "stems reported vs drawn");
    let c = g
        .bed
        .description()
        .params
        .clearance
        .expect("clearance recorded");
    if od.layout.is_some() {
        let region = oracle_region(od);
        for s in &segs {
            assert!(
                region.contains(&line(s)),
                "segment {s:?} is not inside the region"
            );
        }
    }
    // Pairwise clearance with the joint exception, brute force.
    let tol = 1e-9;
    for i in 0..segs.len() {
        let (s, ls) = (&segs[i], line(&segs[i]));
        for t in &segs[i + 1..] {
            let lt = line(t);
            let ends_s = [s.from, s.to];
            let ends_t = [t.from, t.to];
            let shared: Vec<Point> = ends_s
                .iter()
                .filter(|p| ends_t.contains(p))
                .copied()
                .collect();
            if let Some(&j) = shared.first() {
                // A joint is where at least one of them starts.
                assert!(
                    s.from == j || t.from == j,
                    "{s:?} and {t:?} meet end to end"
                );
                let far_s = if s.from == j { s.to } else { s.from };
                let far_t = if t.from == j { t.to } else { t.from };
                let d1 = Euclidean.distance(&geo::Point::new(far_s.x, far_s.y), &lt);
                let d2 = Euclidean.distance(&geo::Point::new(far_t.x, far_t.y), &ls);
                assert!(
                    d1 >= c - tol && d2 >= c - tol,
                    "joint too tight: {s:?} {t:?} ({d1}, {d2}) < {c}"
                );
            } else {
                let d = Euclidean.distance(&ls, &lt);
                assert!(d >= c - tol, "too close: {s:?} {t:?} {d} < {c}");
            }
        }
    }
    segs
}

// ---------------------------------------------------------- trees

/// The paper's 2DTree (Figure 8). Its layout is written in Delphi's
/// corners spelling, `RoundRect (x1,y1,x2,y2,rx,ry)` with the corner
/// ellipse's width and height: (0,0,180,192,7,7), (55,30,40,15,4,4),
/// (35,125,76,30,5,5); normalised here by hand.
fn two_d_tree() -> Od {
    let mut od = Od::new((76.0, 150.0), vec![("R1", "[+F][-F]")]);
    let rr = |x, y, w, h, r| Shape::RoundRect {
        x,
        y,
        w,
        h,
        rx: r,
        ry: r,
    };
    od.layout = Some(vec![
        (GREEN, rr(0.0, 0.0, 180.0, 192.0, 3.5)),
        (Rgb::WHITE, rr(40.0, 15.0, 15.0, 15.0, 2.0)),
        (Rgb::WHITE, rr(35.0, 30.0, 41.0, 95.0, 2.5)),
    ]);
    od
}

/// Figures 9 and 10: `Seed = FR1`, `R1 = [-F][+F]`.
fn figure_9_10() -> Od {
    let mut od = Od::new((100.0, 195.0), vec![("R1", "[-F][+F]")]);
    od.layout = Some(vec![(GREEN, rect(0.0, 0.0, 200.0, 200.0))]);
    od
}

#[test]
fn invariants_hold_on_several_grown_trees() {
    let mut ellipse = Od::new((100.0, 150.0), vec![("R1", "[+F][F][-F]")]);
    ellipse.params = params(8.0, 0.0, 1.0, 0.0);
    ellipse.layout = Some(vec![(
        GREEN,
        Shape::Ellipse {
            x: 0.0,
            y: 0.0,
            w: 200.0,
            h: 160.0,
        },
    )]);
    let mut polygon = Od::new(
        (50.0, 95.0),
        vec![("R1", "F[+F R2][-F]"), ("R2", "[++F][F]")],
    );
    polygon.params.angle = Some(25.0);
    polygon.layout = Some(vec![(
        GREEN,
        Shape::Polygon(vec![
            (0.0, 100.0),
            (100.0, 100.0),
            (80.0, 0.0),
            (10.0, 20.0),
        ]),
    )]);
    let mut fixed = Od::new(
        (60.0, 118.0),
        vec![
            ("R1", "[+F{I 2 F[+F]F}][-FF R2]"),
            ("R2", "{I 1 F[-F]}[+F R1]"),
        ],
    );
    fixed.params = params(5.0, 0.0, 1.0, 0.0);
    fixed.layout = Some(vec![(GREEN, rect(0.0, 0.0, 120.0, 120.0))]);
    for od in [two_d_tree(), figure_9_10(), ellipse, polygon, fixed] {
        let d = od.build();
        for s in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let g = grown(&d, opts(s));
            let segs = check_invariants(&d, &g);
            assert!(segs.len() > 40, "{s:?} grew only {}", segs.len());
            assert!(g.warnings.is_empty());
        }
    }
}

#[test]
fn bfs_and_dfs_grow_different_trees_from_figure_9_10() {
    let d = figure_9_10().build();
    let bfs = grown(&d, opts(GrowthOrder::Bfs));
    let dfs = grown(&d, opts(GrowthOrder::Dfs));
    check_invariants(&d, &bfs);
    check_invariants(&d, &dfs);
    assert_ne!(
        seed_text(bfs.bed.description()),
        seed_text(dfs.bed.description())
    );
    // The seed's one growth point grew: F then R1{right, left}.
    let root = |g: &Grown| -> (usize, usize) {
        let items = &g.bed.description().seed.as_ref().unwrap().items;
        let SeedItem::Term(t) = &items[1] else {
            panic!("no term")
        };
        let size = |s: &Option<Slot>| match s {
            Some(Slot::Term(t)) => subtree_size(t),
            _ => 0,
        };
        (size(&t.slots[0]), size(&t.slots[1]))
    };
    let (b_right, b_left) = root(&bfs);
    let (d_right, d_left) = root(&dfs);
    // Breadth-first: both sides get an almost equal share (the paper's
    // "equally distributed in left and right sides").
    let b_ratio = b_right as f64 / b_left as f64;
    assert!((0.8..1.25).contains(&b_ratio), "bfs {b_right} vs {b_left}");
    // Depth-first: the right branch ([-F], first) grows its whole subtree
    // first and takes most of the space; the left one struggles.
    assert!(d_right > 2 * d_left, "dfs {d_right} vs {d_left}");
    assert!(d_right > b_right);
    // A depth-first tree is deeper (vines).
    let bfs_depth = max_order(&draw_bed(bfs.bed.description()));
    let dfs_depth = max_order(&draw_bed(dfs.bed.description()));
    assert!(dfs_depth > bfs_depth, "{dfs_depth} vs {bfs_depth}");
}

#[test]
fn growth_is_deterministic_and_backends_agree() {
    for od in [two_d_tree(), figure_9_10()] {
        let d = od.build();
        for s in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let a = grown(&d, opts(s));
            let b = grown(&d, opts(s));
            assert_eq!(
                seed_text(a.bed.description()),
                seed_text(b.bed.description())
            );
            assert_eq!(draw_bed(a.bed.description()), draw_bed(b.bed.description()));
            let c = grow_with(&d, &opts(s), Backend::Spade, &mut NoProgress).unwrap();
            assert_eq!(
                seed_text(a.bed.description()),
                seed_text(c.bed.description()),
                "spade differs"
            );
            assert_eq!(a.stems, c.stems);
        }
    }
}

/// The full binary tree of `n` levels of R1, written out.
fn full(n: u32) -> String {
    if n == 0 {
        String::new()
    } else {
        let c = full(n - 1);
        format!("R1{{{c},{c}}}")
    }
}

#[test]
fn counts_grow_the_full_subtree_when_space_allows() {
    // [I n R1], R1 = [+F][-F], no layout. Equal lengths would make tips
    // coincide (+-+ and -++ end at one point), so the length decreases.
    for n in 1..=4u32 {
        let mut od = Od::new((0.0, 0.0), vec![("R1", "[+F][-F]")]);
        od.params = params(16.0, 3.0, 1.0, 0.0);
        od.params.angle = Some(45.0);
        od.params.clearance = Some(0.3);
        // Space allows: the full tree, written out by hand, passes the
        // brute-force checks.
        let text = format!("F{}", full(n));
        od.seed = Some(Box::leak(text.clone().into_boxed_str()));
        let written = od.build();
        let as_bed = Grown {
            bed: stlc::bed::Bed::new(
                Description {
                    format: Format::Bed,
                    ..written.clone()
                },
                &Limits::default(),
            )
            .unwrap(),
            warnings: vec![],
            stems: 1 + 2 * ((1u64 << n) - 1),
        };
        check_invariants(&written, &as_bed);

        let seed = format!("F(I {n} R1)");
        od.seed = Some(Box::leak(seed.into_boxed_str()));
        let d = od.build();
        for s in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let g = grown(&d, opts(s));
            // 2^n - 1 applications of 2 stems each, plus the seed's F.
            assert_eq!(g.stems, 1 + 2 * ((1u64 << n) - 1), "n={n} {s:?}");
            assert_eq!(seed_text(g.bed.description()), text);
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
    let mut od = Od::new((0.0, 0.0), vec![("R1", "[+F R2][-F]"), ("R2", "[F]")]);
    od.seed = Some("F(I 3 R1)");
    let d = od.build();
    let g = grown(&d, opts(GrowthOrder::Bfs));
    assert_eq!(g.stems, 10);
    assert_eq!(
        seed_text(g.bed.description()),
        "FR1{R2{R2{}},R1{R2{},R1{,}}}",
        "written out by hand from the rule"
    );
}

#[test]
fn decrements_end_growth_at_the_right_order() {
    // L=10(2): lengths 10, 8, 6, 4, 2, 0: applications at orders 1..4,
    // a full binary tree of 4 levels: 15 applications, 30 stems + seed.
    let mut od = Od::new((0.0, 0.0), vec![("R1", "[+F][-F]")]);
    od.params = params(10.0, 2.0, 1.0, 0.0);
    let d = od.build();
    let mut o = opts(GrowthOrder::Bfs);
    o.clearance = Some(0.0);
    let g = grown(&d, o);
    assert_eq!(g.stems, 31);
    let segs = check_invariants(&d, &g);
    assert_eq!(max_order(&segs), 4);
    // B=1(0.3): widths 1, .7, .4, .1, -.2: orders 1..3, 7 applications.
    od.params = params(10.0, 0.0, 1.0, 0.3);
    let g = grown(&od.build(), o);
    assert_eq!(g.stems, 15);
    assert_eq!(max_order(&draw_bed(g.bed.description())), 3);
}

#[test]
fn max_stems_stops_growth_with_a_warning() {
    let od = Od::new((0.0, 0.0), vec![("R1", "[+F][-F]")]).build();
    let mut o = opts(GrowthOrder::Bfs);
    o.clearance = Some(0.0);
    o.limits = Limits {
        max_stems: 100,
        ..Limits::default()
    };
    o.max_stems_explicit = true;
    let g = grown(&od, o);
    // 1 + 2k <= 100: 49 applications fit, the 50th would make 101.
    assert_eq!(g.stems, 99);
    assert_eq!(draw_bed(g.bed.description()).len(), 99);
    assert_eq!(g.warnings.len(), 1);
    assert_eq!(g.warnings[0].severity, Severity::Warning);
    assert!(g.warnings[0].kind.to_string().contains("--max-stems"));
}

#[test]
fn unbounded_growth_is_refused_with_a_fix() {
    let od = Od::new((0.0, 0.0), vec![("R1", "[+F][-F]")]).build();
    let e = grow(&od, &opts(GrowthOrder::Bfs), &mut NoProgress).unwrap_err();
    let d = &e.0[0];
    assert!(matches!(d.kind, ErrorKind::Grow(_)));
    let help = d.help.as_deref().unwrap();
    for fix in ["LAYOUT", "[I n R1]", "L=10(1)", "--max-stems"] {
        assert!(help.contains(fix), "help lacks {fix}: {help}");
    }
    // A chain of rules that ends is bounded: R1 -> R2 -> (no branches).
    let od = Od::new((0.0, 0.0), vec![("R1", "[+F R2][-F R2]"), ("R2", "F")]).build();
    let g = grown(&od, opts(GrowthOrder::Bfs));
    assert_eq!(g.stems, 1 + 2 + 2);
}

#[test]
fn root_outside_the_region_is_an_error() {
    let mut od = figure_9_10();
    od.root = (250.0, 100.0);
    let e = grow(&od.build(), &opts(GrowthOrder::Bfs), &mut NoProgress).unwrap_err();
    assert!(e.0[0].kind.to_string().contains("root"));
    assert_eq!(e.0[0].span, Some(0..1));
}

#[test]
fn white_holes_are_respected() {
    let mut od = Od::new((100.0, 195.0), vec![("R1", "[-F][F][+F]")]);
    od.params = params(6.0, 0.0, 1.0, 0.0);
    od.layout = Some(vec![
        (GREEN, rect(0.0, 0.0, 200.0, 200.0)),
        (Rgb::WHITE, rect(60.0, 80.0, 80.0, 40.0)),
    ]);
    let d = od.build();
    for s in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        let g = grown(&d, opts(s));
        let segs = check_invariants(&d, &g);
        let hole = Polygon::new(
            LineString::from(vec![
                (60.0, 80.0),
                (140.0, 80.0),
                (140.0, 120.0),
                (60.0, 120.0),
            ]),
            vec![],
        );
        assert!(
            segs.iter()
                .all(|s| !geo::Intersects::intersects(&hole, &line(s)))
        );
        // The tree grew around the hole: stems above it too.
        assert!(segs.iter().any(|s| s.to.y < 70.0));
    }
}

#[test]
fn written_terms_are_drawn_as_given_and_their_slots_grow() {
    // R1{R1,} in the seed: the written R1 is drawn unconditionally, its
    // first slot is a growth point, its second stays empty.
    let mut od = figure_9_10();
    od.seed = Some("FR1{R1,}");
    let d = od.build();
    let g = grown(&d, opts(GrowthOrder::Dfs));
    check_invariants(&d, &g);
    let text = seed_text(g.bed.description());
    assert!(text.starts_with("FR1{R1{"), "{text}");
    assert!(text.ends_with(",}"), "second slot stays empty: {text}");
}

#[test]
fn seed_with_trunk_rule_stays_consistent() {
    // R2 moves the turtle (trunk F) and more seed follows it: positions
    // after it depend on the decision; the BED must still draw what grew.
    let mut od = Od::new(
        (100.0, 195.0),
        vec![("R1", "[-F][+F]"), ("R2", "F[-F][+F]")],
    );
    od.seed = Some("F R2 F R1 [+F R1]");
    od.layout = Some(vec![(GREEN, rect(0.0, 0.0, 200.0, 200.0))]);
    let d = od.build();
    for s in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        let g = grown(&d, opts(s));
        let segs = check_invariants(&d, &g);
        assert!(segs.len() > 100);
    }
}

#[test]
fn seed_drawing_is_laid_down_before_growth() {
    // Depth-first, the left R1's whole subtree grows before the right one;
    // the seed's `-F` must already be there, or the subtree could take its
    // place (the pairwise check would then fail on it).
    let mut od = figure_9_10();
    od.seed = Some("F[+F R1][-F R1]");
    let d = od.build();
    for s in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        let g = grown(&d, opts(s));
        let segs = check_invariants(&d, &g);
        assert!(segs.len() > 200);
    }
}

#[test]
fn depth_limit_stops_a_vine_with_a_warning() {
    // R1 = [F]: a straight vine, one stem per application.
    let od = Od::new((0.0, 0.0), vec![("R1", "[F]")]).build();
    let mut o = opts(GrowthOrder::Dfs);
    o.limits.max_depth = 5;
    o.max_stems_explicit = true;
    let g = grown(&od, o);
    assert_eq!(g.stems, 1 + 5);
    assert_eq!(g.warnings.len(), 1);
    assert!(g.warnings[0].kind.to_string().contains("--max-depth"));
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
    let mut od = figure_9_10();
    od.params = params(1.0, 0.0, 1.0, 0.0);
    let d = od.build();
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
    let mut od = figure_9_10();
    od.seed = Some("FFFFF");
    let mut o = opts(GrowthOrder::Bfs);
    o.limits.max_stems = 4;
    let e = grow(&od.build(), &o, &mut NoProgress).unwrap_err();
    assert!(matches!(e.0[0].kind, ErrorKind::Limit { .. }));
    // The seed (drawn first, R1 deferred) fills the limit: R1's application
    // would pass it, so growth stops with a warning and R1 is left out.
    od.seed = Some("F R1 F");
    o.limits.max_stems = 2;
    let g = grown(&od.build(), o);
    assert_eq!(g.stems, 2);
    assert_eq!(g.warnings.len(), 1);
    assert_eq!(seed_text(g.bed.description()), "FF");
}
