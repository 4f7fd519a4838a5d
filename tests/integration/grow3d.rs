//! Growth in volumes (issue 26, item 3): a 3D OD grown into a BED.
//!
//! Until the 3D syntax reads them, the descriptions are 2D `.od` texts read
//! by the real parser and made 3D here (a root z, `D=`, volumes). Every
//! grown stem is checked independently of the grower: its capsule sampled
//! (points along the centre line and around it at the radius) against
//! point-membership tests written here, and every pair of stems against
//! the clearance with a distance computed here (a ternary search of the
//! point-to-segment distance, which is convex along a segment).

use crate::support::{cuboid, cylinder, ellipsoid, files_with, near_pairs, opts, sphere};
use stlc::Limits;
use stlc::color::Rgb;
use stlc::diag::MissReason;
use stlc::grow::{GrowthOrder, PlacedStem, grow, grow_traced};
use stlc::interpret::Derivation;
use stlc::model::*;
use stlc::progress::NoProgress;
use stlc::syntax::stl::parse;

const GREEN: Rgb = Rgb::new(0, 128, 0);

/// `od` made 3D: root z 0 (every root), `D`, the volumes `solids`.
fn lift(mut od: Description, d: f64, solids: Vec<(Rgb, Solid)>) -> Description {
    od.root_z = Some(0.0);
    for t in &mut od.forest {
        t.root_z = Some(0.0);
    }
    od.params.divergence = Some(d);
    let mut layout = Layout::new(Vec::new());
    layout.solids = solids
        .into_iter()
        .map(|(color, solid)| LayoutSolid {
            color,
            color_text: String::new(),
            solid,
            loc: Loc::default(),
        })
        .collect();
    od.layout = Some(layout);
    od
}

fn parsed(text: &str) -> Description {
    parse(text, Format::Od, &Limits::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// `text` read as a 2D OD, made 3D by [`lift`].
fn od3(text: &str, d: f64, solids: Vec<(Rgb, Solid)>) -> Description {
    lift(parsed(text), d, solids)
}

fn traced(od: &Description, growth: GrowthOrder) -> Vec<PlacedStem> {
    grow_traced(od, &opts(growth), &mut NoProgress)
        .unwrap_or_else(|e| panic!("{e}"))
        .1
}

type P = [f64; 3];

fn ends(s: &PlacedStem) -> (P, P) {
    ([s.from.x, s.from.y, s.z[0]], [s.to.x, s.to.y, s.z[1]])
}

fn dist(p: P, q: P) -> f64 {
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

fn lerp(a: P, b: P, t: f64) -> P {
    [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t)
}

/// Distance from `p` to the segment `a`-`b`, and where along it (0..1).
fn to_segment(p: P, a: P, b: P) -> (f64, f64) {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = if len2 == 0.0 {
        0.0
    } else {
        (((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1] + (p[2] - a[2]) * d[2]) / len2)
            .clamp(0.0, 1.0)
    };
    (dist(p, lerp(a, b, t)), t)
}

/// Distance between two segments: ternary search along the first.
fn seg_dist(a: P, b: P, c: P, d: P) -> f64 {
    let f = |t: f64| to_segment(lerp(a, b, t), c, d).0;
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..100 {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if f(m1) <= f(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    f(lo).min(f(0.0)).min(f(1.0))
}

/// Points of the capsule of `s`: along its centre line, and at its radius
/// around it in 26 directions.
fn capsule_points(s: &PlacedStem) -> Vec<P> {
    let (a, b) = ends(s);
    let r = s.width / 2.0;
    // The 26 unit vectors toward the other cells of a 3 x 3 x 3 block.
    let dirs: Vec<P> = (0..27)
        .map(|n| [n / 9, n / 3 % 3, n % 3].map(|c| f64::from(c) - 1.0))
        .filter(|d| *d != [0.0; 3])
        .map(|d| d.map(|c| c / dist(d, [0.0; 3])))
        .collect();
    let mut out = Vec::new();
    for step in 0..=16 {
        let c = lerp(a, b, step as f64 / 16.0);
        out.push(c);
        for d in &dirs {
            out.push([c[0] + d[0] * r, c[1] + d[1] * r, c[2] + d[2] * r]);
        }
    }
    out
}

/// Whether `p` is in `solid` (the layout's semantics, written again);
/// `axis`: the first root's x and z.
fn holds(solid: &Solid, p: P, axis: [f64; 2]) -> bool {
    match solid {
        Solid::Box { corner, size } => {
            (0..3).all(|i| corner[i] < p[i] && p[i] < corner[i] + size[i])
        }
        Solid::Sphere { centre, r } => dist(p, *centre) < *r,
        Solid::Ellipsoid { centre, radii } => {
            (0..3)
                .map(|i| ((p[i] - centre[i]) / radii[i]).powi(2))
                .sum::<f64>()
                < 1.0
        }
        Solid::Cylinder { base, r, h } => {
            let rho = ((p[0] - base[0]).powi(2) + (p[2] - base[2]).powi(2)).sqrt();
            rho < *r && base[1] - h < p[1] && p[1] < base[1]
        }
        Solid::Revolve {
            shape: Shape::Ellipse { x, y, w, h },
        } => {
            let rho = ((p[0] - axis[0]).powi(2) + (p[2] - axis[1]).powi(2)).sqrt();
            let (cx, cy) = (x + w / 2.0, y + h / 2.0);
            [axis[0] + rho, axis[0] - rho]
                .iter()
                .any(|px| ((px - cx) / (w / 2.0)).powi(2) + ((p[1] - cy) / (h / 2.0)).powi(2) < 1.0)
        }
        Solid::Extrude {
            shape: Shape::Ellipse { x, y, w, h },
            z1,
            z2,
        } => {
            let (cx, cy) = (x + w / 2.0, y + h / 2.0);
            *z1 < p[2]
                && p[2] < *z2
                && ((p[0] - cx) / (w / 2.0)).powi(2) + ((p[1] - cy) / (h / 2.0)).powi(2) < 1.0
        }
        other => panic!("no test for {other:?}"),
    }
}

fn in_layout(od: &Description, p: P) -> bool {
    let axis = [od.root.0, od.root_z.unwrap_or(0.0)];
    // The last volume that holds the point paints it (white: a hole).
    let solids = &od.layout.as_ref().unwrap().solids;
    let last = solids.iter().rev().find(|s| holds(&s.solid, p, axis));
    last.is_some_and(|s| s.color != Rgb::WHITE)
}

/// Every stem lies in the volumes and keeps the clearance; returns how
/// many stems grew.
fn check(od: &Description, growth: GrowthOrder) -> usize {
    let (grown, stems) = grow_traced(od, &opts(growth), &mut NoProgress).unwrap();
    // The volume, not the orders, bounds the tree: tries fell outside.
    let outside: u64 = grown
        .tallies
        .iter()
        .map(|t| t.misses[MissReason::Outside.index()])
        .sum();
    assert!(outside > 0, "no try outside");
    let c = od.params.clearance.unwrap_or(od.params.length.base / 10.0);
    for (i, s) in stems.iter().enumerate() {
        if s.decision == 0 {
            continue;
        }
        for p in capsule_points(s) {
            assert!(in_layout(od, p), "stem {i} {s:?}: {p:?} outside");
        }
    }
    // Every pair whose x spans come within the largest clearance needed
    // (support::near_pairs), the later one growing by a decision.
    let spans: Vec<(f64, f64)> = stems
        .iter()
        .map(|s| {
            let (a, b) = ends(s);
            (a[0].min(b[0]), a[0].max(b[0]))
        })
        .collect();
    let widest = stems.iter().map(|s| s.width).fold(0.0, f64::max);
    near_pairs(&spans, c + widest, |a, b| {
        let (s, t, i) = (&stems[a], &stems[b], b);
        if t.decision == 0 {
            return;
        }
        let (ta, tb) = ends(t);
        let (sa, sb) = ends(s);
        let need = c + (t.width + s.width) / 2.0;
        // Boxes farther apart than that on some axis cannot conflict.
        if (0..3).any(|k| {
            ta[k].max(tb[k]) + need < sa[k].min(sb[k]) || sa[k].max(sb[k]) + need < ta[k].min(tb[k])
        }) {
            return;
        }
        // A joint: the far ends keep the clearance unless nearest at the joint.
        let joint = [(sa, sb), (sb, sa)].into_iter().find(|&(j, _)| ta == j);
        match joint {
            Some((_, far)) => {
                let (d1, at1) = to_segment(tb, sa, sb);
                let at_joint = if ta == sa { 0.0 } else { 1.0 };
                let ok = d1 >= need - 1e-9 || at1 == at_joint;
                assert!(ok, "stem {i}: far end {d1} < {need}");
                let (d2, at2) = to_segment(far, ta, tb);
                let ok = d2 >= need - 1e-9 || at2 == 0.0;
                assert!(ok, "stem {i}: other's far end {d2} < {need}");
            }
            None => {
                let d = seg_dist(ta, tb, sa, sb);
                assert!(d >= need - 1e-6, "stem {i} {t:?} and {s:?}: {d} < {need}");
            }
        }
    });
    stems.len()
}

const TREE: &str = "T (100, 200)L=10(0.6) B=2(0.1) A=40 C=1 RULE R1: [+F][-F]";

/// A spheroid crown: an ellipse revolved about the root's vertical line.
fn crown() -> Solid {
    let (x, y, w, h) = (50.0, 95.0, 100.0, 110.0);
    let shape = Shape::Ellipse { x, y, w, h };
    Solid::Revolve { shape }
}

#[test]
fn a_tree_grows_inside_each_kind_of_volume_and_keeps_clearance() {
    let cases: Vec<(&str, Vec<(Rgb, Solid)>)> = vec![
        ("sphere", vec![(GREEN, sphere([100.0, 150.0, 0.0], 55.0))]),
        (
            "box",
            vec![(GREEN, cuboid([60.0, 110.0, -30.0], [80.0, 95.0, 60.0]))],
        ),
        (
            "cylinder",
            vec![(GREEN, cylinder([100.0, 205.0, 0.0], 35.0, 100.0))],
        ),
        (
            "ellipsoid",
            vec![(GREEN, ellipsoid([100.0, 150.0, 0.0], [50.0, 60.0, 25.0]))],
        ),
        ("revolved ellipse", vec![(GREEN, crown())]),
        (
            "box with a sphere carved out",
            vec![
                (GREEN, cuboid([40.0, 90.0, -40.0], [120.0, 115.0, 80.0])),
                (Rgb::WHITE, sphere([100.0, 140.0, 15.0], 25.0)),
            ],
        ),
    ];
    for (name, solids) in cases {
        for d in [0.0, 137.5] {
            let od = od3(TREE, d, solids.clone());
            for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
                let n = check(&od, growth);
                assert!(n > 20, "{name} D={d} {growth:?}: only {n} stems");
            }
        }
    }
}

#[test]
fn divergence_spreads_a_planar_rule_around_the_stem() {
    let solids = vec![(GREEN, sphere([100.0, 150.0, 0.0], 55.0))];
    let flat = traced(&od3(TREE, 0.0, solids.clone()), GrowthOrder::Bfs);
    assert!(flat.iter().all(|s| s.z == [0.0, 0.0]));
    let spread = traced(&od3(TREE, 137.5, solids), GrowthOrder::Bfs);
    let off = spread.iter().filter(|s| s.z[1].abs() > 1.0).count();
    let (all, in_plane) = (spread.len(), flat.len());
    assert!(off * 2 > all, "{off} of {all} stems off the plane");
    // Room in the third dimension: more stems than in the plane.
    assert!(all > in_plane, "{all} <= {in_plane}");
}

#[test]
fn a_forest_shares_the_volume_and_the_clearance() {
    let text = "F (70, 200) (130, 200) L=10(0.6) B=2(0.1) A=40 C=1 RULE R1: [+F][-F]";
    let solids = vec![(GREEN, cuboid([20.0, 100.0, -40.0], [160.0, 105.0, 80.0]))];
    let od = od3(text, 90.0, solids);
    for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
        assert!(check(&od, growth) > 40);
    }
}

#[test]
fn growth_in_space_is_deterministic() {
    let solids = vec![(GREEN, crown())];
    let od = od3(TREE, 137.5, solids);
    for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
        let a = grow(&od, &opts(growth), &mut NoProgress).unwrap();
        let b = grow(&od, &opts(growth), &mut NoProgress).unwrap();
        assert_eq!(a, b);
        assert_eq!(traced(&od, growth), traced(&od, growth));
    }
}

/// An example's OD made 3D: root z 0, `D=0`, its layout extruded far
/// beyond the tree in z.
fn extruded(flat: &Description) -> Description {
    let solids = flat
        .layout
        .as_ref()
        .expect("a layout")
        .shapes
        .iter()
        .map(|s| {
            let (shape, z1, z2) = (s.shape.clone(), -1000.0, 1000.0);
            let solid = Solid::Extrude { shape, z1, z2 };
            (s.color, solid)
        });
    lift(flat.clone(), 0.0, solids.collect())
}

#[test]
fn a_planar_3d_tree_in_an_extruded_layout_grows_the_2d_decisions() {
    let mut tried = 0;
    for path in files_with("examples", "od") {
        let text = std::fs::read_to_string(&path).unwrap();
        let flat = parsed(&text);
        if flat.layout.is_none() || flat.is_3d() {
            continue;
        }
        tried += 1;
        let space = extruded(&flat);
        for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let (g2, p2) = grow_traced(&flat, &opts(growth), &mut NoProgress).unwrap();
            let (g3, p3) = grow_traced(&space, &opts(growth), &mut NoProgress).unwrap();
            let (d2, d3) = (g2.bed.description(), g3.bed.description());
            assert_eq!(d2.seed, d3.seed, "{path:?} {growth:?}");
            let seeds =
                |d: &Description| d.forest.iter().map(|t| t.seed.clone()).collect::<Vec<_>>();
            assert_eq!(seeds(d2), seeds(d3), "{path:?} {growth:?}");
            assert_eq!(g2.stems, g3.stems);
            assert_eq!(p2.len(), p3.len());
            for (a, b) in p2.iter().zip(&p3) {
                let stem = |s: &PlacedStem| (s.from, s.to, s.decision);
                assert_eq!(stem(a), stem(b), "{path:?}");
                assert_eq!(b.z, [0.0, 0.0]);
            }
        }
    }
    assert!(tried >= 5, "only {tried} examples with layouts");
}

/// The 3D examples (`oak3d.od`, its bare twin, `forest3d.od`): every stem inside the
/// volumes and clear of the others, by the brute force of [`check`].
#[test]
fn every_3d_example_grows_inside_its_volumes_and_keeps_clearance() {
    let mut tried = Vec::new();
    for path in files_with("examples", "od") {
        let od = parsed(&std::fs::read_to_string(&path).unwrap());
        if !od.is_3d() {
            continue;
        }
        for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
            let n = check(&od, growth);
            assert!(n > 1000, "{path:?} {growth:?}: only {n} stems");
        }
        tried.push(path.file_name().unwrap().to_string_lossy().into_owned());
    }
    assert_eq!(tried, ["forest3d.od", "oak3d-bare.od", "oak3d.od"]);
}

/// docs/language.md's 3D example, read by the real parser: a trunk
/// `Cylinder` into a crown `Sphere`, an extruded ellipse, a white box
/// carved out, `D=137.5`, 3D turns in the rule.
const BUSH: &str = "Bush3D
(0, 0, 0)
L=10(1.5) B=2(0.3) A=40 D=137.5
RULE
R1: [+F][-F][&F/F]
SEED
F R1{,,} F R1
ENDSEED
LAYOUT
(clGreen) Sphere (0, -40, 0), 30
(clGreen) Cylinder (0, 0, 0), 3, 20
(clGreen) Extrude <Ellipse (-20, -60), 40, 20>, -10, 10
(clWhite) Box (-5, -75, -5), 10, 10, 10
ENDLAYOUT
";

/// The bits of a stem's ends, for comparing sets of stems.
fn key((a, b): (P, P)) -> [u64; 6] {
    [a[0], a[1], a[2], b[0], b[1], b[2]].map(f64::to_bits)
}

/// The grown BED, drawn again by the 3D BED interpreter (which rolls by
/// `D=` at every rule application on its own), gives exactly the stems
/// growth placed, bit for bit; and they lie in the volumes and keep the
/// clearance.
#[test]
fn a_3d_od_grows_a_bed_that_draws_the_stems_growth_placed() {
    let od = parsed(BUSH);
    assert!(od.is_3d());
    for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
        let (grown, placed) = grow_traced(&od, &opts(growth), &mut NoProgress).unwrap();
        assert!(placed.len() > 30, "{growth:?}: {} stems", placed.len());
        // The volumes: sphere, cylinder, extruded ellipse, minus the box.
        assert!(check(&od, growth) > 30);
        let mut grew: Vec<[u64; 6]> = placed.iter().map(|s| key(ends(s))).collect();
        let (mut drawn, limits, dfs) = (Vec::new(), Limits::default(), Derivation::Dfs);
        let mut push = |s: stlc::turtle::turtle3::Segment3| {
            drawn.push(key((s.from.to_array(), s.to.to_array())))
        };
        stlc::interpret::bed3::draw3(&grown.bed, dfs, &limits, &mut push, &mut NoProgress).unwrap();
        grew.sort_unstable();
        drawn.sort_unstable();
        assert_eq!(grew, drawn, "{growth:?}");
    }
}

/// `stlc compile` of an OD text: the BED written, and the messages.
fn compile(text: &str) -> (String, String) {
    let mut cmd = crate::support::stlc_line("compile --from od -o - -");
    let (code, out, err) = crate::support::outcome(cmd.write_stdin(text));
    assert_eq!(code, 0, "{err}");
    (String::from_utf8(out).unwrap(), err)
}

/// Alternatives chosen by `V=`, `M=` and the explanation work in space as
/// in the plane (through `stlc compile`): the same seed grows the same
/// tree, another seed another; growth stops at `M=` with its warning; a
/// rule that never fits says so.
#[test]
fn seeds_alternatives_m_and_explanations_in_space() {
    let text = |header: &str| {
        format!(
            "A\n(0, 0, 0)\nL=10(0.6) B=2(0.1) A=40 D=90 {header}\nRULE\nR1 (0.5): [+F][-F]\nR1 (0.5): [&F][^F]\nR2: [F F F F F F F F F F]\nSEED\nF R1 R2\nENDSEED\nLAYOUT\n(clGreen) Sphere (0, -40, 0), 45\nENDLAYOUT\n"
        )
    };
    let (a, warned) = compile(&text("V=3"));
    assert_eq!(a, compile(&text("V=3")).0);
    assert_ne!(a, compile(&text("V=4")).0);
    assert!(a.contains("R1.1{") && a.contains("R1.2{"), "{a}");
    // R2 draws 100 units straight up from the trunk's tip: out of the sphere.
    let never = warned.contains("R2") && warned.contains("never");
    assert!(never, "{warned}");
    let (m, warned) = compile(&text("V=3 M=40"));
    // The seed's trunk, and two stems for each application in the seed.
    let seed = &m[m.find("SEED\n").unwrap()..];
    let stems = 1 + 2 * seed.matches("R1.").count();
    assert!((30..=40).contains(&stems), "{stems} stems\n{m}");
    assert!(warned.contains("M=40"), "{warned}");
}
