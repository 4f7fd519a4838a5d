//! Space-first growth (`O=space`, `stl-language.md` section 14): its order,
//! its keys, its BED. The brute-force invariants (every stem inside the
//! region with its clearance) run on space-first growth in `grow.rs`
//! beside bfs and dfs.

use crate::grow::grown;
use crate::od_variation::bed_text;
use crate::support::{od, opts, segment_distance};
use stlc::grow::region::Region;
use stlc::grow::{GrowOptions, GrowthOrder, PlacedStem, grow_traced};
use stlc::model::{Description, Format};
use stlc::progress::NoProgress;
use stlc::syntax::stl::parse;
use stlc::{ErrorKind, Limits};

/// The BED `d` grows in the order `o`.
fn bed_in(d: &Description, o: GrowthOrder) -> String {
    bed_text(&grown(d, opts(o)))
}

/// The box: 200 x 200 with a 100 x 100 hole in the middle.
fn box_with_hole(head: &str) -> String {
    format!(
        "Box (100, 195) L=10(0) B=1(0) A=30 {head}
        RULE R1: [+F][-F]
        LAYOUT
        (clGreen) Rectangle (0,0), 200, 200
        (clWhite) Rectangle (50,50), 100, 100
        ENDLAYOUT"
    )
}

/// With no attraction points every growth point scores nothing, so
/// space-first growth decides in bfs order: `N=0`, and a tree with no
/// LAYOUT (nothing to scatter points over), grow bfs's very BED.
#[test]
fn without_points_space_first_is_bfs() {
    let d = od(&box_with_hole("N=0"));
    assert_eq!(bed_in(&d, GrowthOrder::Space), bed_in(&d, GrowthOrder::Bfs));
    let free = od("Free (0, 0) L=10(1) B=1(0) RULE R1: [+F][-F]");
    let want = bed_in(&free, GrowthOrder::Bfs);
    assert_eq!(bed_in(&free, GrowthOrder::Space), want);
    // With points the order changes, and so does the tree.
    let d = od(&box_with_hole(""));
    assert_ne!(bed_in(&d, GrowthOrder::Space), bed_in(&d, GrowthOrder::Bfs));
}

/// The root stands 20 from the left wall of a long box: the left growth
/// point's reach is cut by the wall, the right one's is not, so the right
/// one owns more points and grows first; bfs decides the written order,
/// left (`[+F R1]`) first.
#[test]
fn the_growth_point_with_more_free_space_grows_first() {
    let text = "Long (20, 95) L=10(0) B=1(0) A=45 Q=40
        RULE R1: [+F][-F]
        SEED F[+F R1][-F R1] ENDSEED
        LAYOUT (clGreen) Rectangle (0,0), 300, 100 ENDLAYOUT";
    let d = od(text);
    let first_decision = |o: GrowthOrder| -> Vec<PlacedStem> {
        let (_, trace) = grow_traced(&d, &opts(o), &mut NoProgress).unwrap();
        trace.into_iter().filter(|s| s.decision == 1).collect()
    };
    // The seed's tips: F to (20, 85), then 45 degrees each way.
    let space = first_decision(GrowthOrder::Space);
    let bfs = first_decision(GrowthOrder::Bfs);
    assert_eq!(space.len(), 2);
    assert!(space.iter().all(|s| s.from.x > 20.0), "{space:?}");
    assert!(bfs.iter().all(|s| s.from.x < 20.0), "{bfs:?}");
}

/// The share of the region's points (a 2-unit grid) within `2 L` of a
/// stem, and their mean distance to the nearest stem.
fn coverage(stems: &[PlacedStem], inside: impl Fn(f64, f64) -> bool, l: f64) -> (f64, f64) {
    let (mut n, mut near, mut sum) = (0u32, 0u32, 0.0);
    for i in 0..100 {
        for j in 0..100 {
            let (x, y) = (1.0 + 2.0 * f64::from(i), 1.0 + 2.0 * f64::from(j));
            if !inside(x, y) {
                continue;
            }
            let d = stems
                .iter()
                .map(|s| segment_distance((x, y), (s.from.x, s.from.y), (s.to.x, s.to.y)))
                .fold(f64::INFINITY, f64::min);
            n += 1;
            near += u32::from(d <= 2.0 * l);
            sum += d;
        }
    }
    (f64::from(near) / f64::from(n), sum / f64::from(n))
}

/// Coverage (share within `2 L`, mean distance) of `d` grown space-first,
/// bfs and dfs with a third of the stems bfs grows unbounded.
fn at_a_third(
    d: &Description,
    inside: impl Fn(f64, f64) -> bool + Copy,
    l: f64,
) -> [(f64, f64); 3] {
    let all = grown(d, opts(GrowthOrder::Bfs)).stems;
    [GrowthOrder::Space, GrowthOrder::Bfs, GrowthOrder::Dfs].map(|o| {
        let mut g = opts(o);
        g.limits.max_stems = all / 3;
        let (_, trace) = grow_traced(d, &g, &mut NoProgress).unwrap();
        coverage(&trace, inside, l)
    })
}

/// The acceptance figure: on the box with a hole, with a third of
/// the stems bfs grows unbounded, space-first covers more of the region
/// than bfs and dfs, and leaves its points nearer a stem.
#[test]
fn space_first_covers_more_on_the_same_budget() {
    let d = od(&box_with_hole(""));
    let inside = |x: f64, y: f64| !((50.0..=150.0).contains(&x) && (50.0..=150.0).contains(&y));
    let [space, bfs, dfs] = at_a_third(&d, inside, 10.0);
    let holds = space.0 > bfs.0 && space.0 > dfs.0 && space.1 < bfs.1 && space.1 < dfs.1;
    assert!(holds, "{space:?} {bfs:?} {dfs:?}");
}

/// With a length decrement (`crown.od`, `L=10(0.35)`), too: a growth
/// point's default reach shrinks with its stems, so deep tips do not
/// hoard the points round them and spend the budget on a clump of tiny
/// stems. The crown's ellipse, measured on the grid's 200 x 200; with the
/// reach of the seed's stems at every order (`Q=40`, the default before)
/// space-first loses to bfs here.
#[test]
fn space_first_covers_more_of_a_crown_with_a_length_decrement() {
    let text = std::fs::read_to_string(crate::support::manifest_path("examples/crown.od")).unwrap();
    let in_crown = |x: f64, y: f64| {
        let (u, v) = ((x - 100.0) / 80.0, (y - 115.0) / 95.0);
        u * u + v * v <= 1.0
    };
    let [space, bfs, dfs] = at_a_third(&od(&text), in_crown, 10.0);
    let holds = space.0 > bfs.0 && space.0 > dfs.0 && space.1 < bfs.1 && space.1 < dfs.1;
    assert!(holds, "{space:?} {bfs:?} {dfs:?}");
    let fixed = text.replace("C=1\n", "C=1 Q=40\n");
    assert_ne!(fixed, text);
    let [space, bfs, _] = at_a_third(&od(&fixed), in_crown, 10.0);
    assert!(space.0 < bfs.0, "{space:?} {bfs:?}");
}

/// The BED names every decision: read back and written again it is the
/// same text, and it draws the same stems; the same file and seed grow the
/// same BED, another `V=` another one (the points move).
#[test]
fn the_bed_round_trips_and_the_seed_decides() {
    let d = od(&box_with_hole("O=space V=3"));
    let mut o = opts(GrowthOrder::Space);
    o.seed = 3;
    let g = grown(&d, o);
    let text = bed_text(&g);
    let back = parse(&text, Format::Bed, &Limits::default()).unwrap();
    assert_eq!(stlc::bed::write::write(&back), text);
    assert_eq!(bed_text(&grown(&d, o)), text);
    let other = GrowOptions { seed: 4, ..o };
    assert_ne!(bed_text(&grown(&d, other)), text);
    // No design key reaches the BED.
    for key in ["O=", "V=", "N=", "Q="] {
        assert!(!text.contains(key), "{key} in\n{text}");
    }
}

#[test]
fn the_keys_are_read_and_refused_in_a_bed() {
    let d = od(&box_with_hole("O=space N=50 Q=30"));
    assert_eq!(d.params.design.order, Some(GrowthOrder::Space));
    assert_eq!(d.params.design.points, Some(50));
    assert_eq!(d.params.design.reach, Some(30.0));
    // A million points at most (about 100 MB): one more is refused where
    // it is written, not cut down silently.
    let d = od(&box_with_hole("N=1000000"));
    assert_eq!(d.params.design.points, Some(1_000_000));
    for bad in ["Q=0", "Q=-3", "N=1.5", "O=spacey", "N=1000001"] {
        let e = parse(&box_with_hole(bad), Format::Od, &Limits::default()).unwrap_err();
        let kind = &e.0[0].kind;
        assert!(matches!(kind, ErrorKind::Stl(_)), "{bad}: {kind:?}");
    }
    let g = grown(&od(&box_with_hole("")), opts(GrowthOrder::Space));
    let text = bed_text(&g);
    for key in ["N=50", "Q=30"] {
        let with = text.replacen("L=10", &format!("{key} L=10"), 1);
        let e = parse(&with, Format::Bed, &Limits::default()).unwrap_err();
        assert!(e.to_string().contains("nothing in a BED"), "{key}: {e}");
    }
}

/// `check`'s tallies: the points the rules' stems killed are, counted by
/// brute force over the same points (`sample::plane`, one per 10 x 10 of
/// the region), those within a grown stem's length of it and not within
/// the seed's stems' (the seed kills first); bfs tallies none.
#[test]
fn the_tallies_count_the_points_killed() {
    let d = od(&box_with_hole(""));
    let region = Region::from_layout(d.layout.as_ref().unwrap(), 100_000).unwrap();
    let points = stlc::grow::colonize::sample::plane(&region, None, 100.0, 0);
    assert_eq!(points.len(), 300, "(200^2 - 100^2) / 10^2");
    let (g, trace) = grow_traced(&d, &opts(GrowthOrder::Space), &mut NoProgress).unwrap();
    let near = |p: [f64; 2], s: &PlacedStem| {
        let (dx, dy) = (s.to.x - s.from.x, s.to.y - s.from.y);
        let l2 = dx * dx + dy * dy;
        let t = (((p[0] - s.from.x) * dx + (p[1] - s.from.y) * dy) / l2).clamp(0.0, 1.0);
        let (ex, ey) = (p[0] - s.from.x - t * dx, p[1] - s.from.y - t * dy);
        ex * ex + ey * ey <= l2
    };
    let by_rules = points
        .iter()
        .filter(|&&p| {
            !trace.iter().any(|s| s.decision == 0 && near(p, s))
                && trace.iter().any(|s| s.decision > 0 && near(p, s))
        })
        .count() as u64;
    let killed: u64 = g.tallies.iter().map(|t| t.killed).sum();
    assert_eq!(killed, by_rules);
    assert!(killed > 200, "{killed}");
    let claimed: u64 = g.tallies.iter().map(|t| t.claimed).sum();
    assert!(claimed > 0);
    let bfs = grown(&d, opts(GrowthOrder::Bfs));
    assert!(bfs.tallies.iter().all(|t| t.claimed == 0 && t.killed == 0));
}
