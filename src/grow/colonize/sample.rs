//! Attraction points, scattered uniformly over a region from a seed.
//!
//! - **The plane** ([`plane`]): the region's outline and holes are the
//!   constraint edges of a constrained Delaunay triangulation (`spade`);
//!   a triangle is inside when an odd number of constraint edges separate
//!   it from the outside (a walk from the convex hull across the triangles,
//!   so no point-in-polygon test), and the points are drawn by area: a
//!   triangle with probability in proportion to its area, then a point
//!   uniform in it.
//! - **Space** ([`volume`]): points drawn uniformly in the region's box,
//!   kept where the region holds them.
//!
//! The numbers are the seed's SplitMix64 stream ([`crate::choice::Key`]),
//! and only `+ - * /` and comparisons act on them, so the points are the
//! same on every machine and in the browser.

use spade::handles::FixedFaceHandle;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

use crate::choice::Key;
use crate::grow::region::Region;

/// At most this many points (a default that would pass it is cut down to
/// it; the syntax refuses an `N=` above it): a million points cost about
/// 100 MB with their grid (measured at 2 million: 200 MB, `docs/growth.md`).
pub const MAX_POINTS: u64 = crate::model::MAX_ATTRACTION_POINTS;

/// The key of the points' stream: apart from the choices' keys of the
/// same seed (those are `Key::root(seed).child(tree)`).
fn stream(seed: u64) -> Key {
    Key(Key::root(seed).0 ^ 0x5350_4143_455F_5054)
}

/// The number of points: `n` if given, else `measure / unit` (one per
/// `L` x `L`, or `L` cubed), at least 1, at most [`MAX_POINTS`].
fn count(n: Option<u64>, measure: f64, unit: f64) -> usize {
    let n = n.unwrap_or_else(|| {
        let d = measure / unit;
        if d.is_finite() {
            d.round().max(1.0) as u64
        } else {
            0
        }
    });
    n.min(MAX_POINTS) as usize
}

/// A triangle of the region's triangulation.
type Tri = [[f64; 2]; 3];

/// The triangles of `region`'s constrained Delaunay triangulation that lie
/// inside it.
pub fn triangles(region: &Region) -> Vec<Tri> {
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> = Default::default();
    for poly in &region.area().0 {
        for ring in std::iter::once(poly.exterior()).chain(poly.interiors()) {
            let mut prev = None;
            for c in ring.coords() {
                let Ok(h) = cdt.insert(Point2::new(c.x, c.y)) else {
                    prev = None;
                    continue;
                };
                if let Some(p) = prev
                    && p != h
                    && cdt.can_add_constraint(p, h)
                {
                    cdt.add_constraint(p, h);
                }
                prev = Some(h);
            }
        }
    }
    // Inside: an odd number of constraint edges crossed from outside.
    let mut inside: Vec<Option<bool>> = vec![None; cdt.num_all_faces()];
    let mut stack: Vec<(FixedFaceHandle<spade::handles::InnerTag>, bool)> = Vec::new();
    for e in cdt.convex_hull() {
        let e = if e.face().is_outer() { e.rev() } else { e };
        if let Some(f) = e.face().as_inner() {
            stack.push((f.fix(), e.as_undirected().data().is_constraint_edge()));
        }
    }
    while let Some((f, odd)) = stack.pop() {
        let slot = &mut inside[f.index()];
        if slot.is_some() {
            continue;
        }
        *slot = Some(odd);
        for e in cdt.face(f).adjacent_edges() {
            if let Some(g) = e.rev().face().as_inner()
                && inside[g.fix().index()].is_none()
            {
                let crossed = e.as_undirected().data().is_constraint_edge();
                stack.push((g.fix(), odd != crossed));
            }
        }
    }
    let mut out = Vec::new();
    for f in cdt.inner_faces() {
        if inside[f.fix().index()] == Some(true) {
            let [a, b, c] = f.positions();
            out.push([[a.x, a.y], [b.x, b.y], [c.x, c.y]]);
        }
    }
    out
}

/// Twice the area of a triangle.
fn area2(t: &Tri) -> f64 {
    ((t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[2][0] - t[0][0]) * (t[1][1] - t[0][1])).abs()
}

/// `n` points (or one per `unit` of area) uniform over `region`, from
/// `seed`.
pub fn plane(region: &Region, n: Option<u64>, unit: f64, seed: u64) -> Vec<[f64; 2]> {
    let tris = triangles(region);
    let mut cum = Vec::with_capacity(tris.len());
    let mut total = 0.0;
    for t in &tris {
        total += area2(t);
        cum.push(total);
    }
    let n = count(n, total / 2.0, unit);
    if tris.is_empty() || total <= 0.0 {
        return Vec::new();
    }
    let key = stream(seed);
    (0..n as u64)
        .map(|i| {
            let u = key.child(3 * i).unit() * total;
            let k = cum.partition_point(|&c| c <= u).min(tris.len() - 1);
            let t = &tris[k];
            let (mut r, mut s) = (key.child(3 * i + 1).unit(), key.child(3 * i + 2).unit());
            if r + s > 1.0 {
                (r, s) = (1.0 - r, 1.0 - s);
            }
            std::array::from_fn(|d| t[0][d] + r * (t[1][d] - t[0][d]) + s * (t[2][d] - t[0][d]))
        })
        .collect()
}

/// Draws tried to estimate a volume's share of its box.
const TRIAL: u64 = 4096;

/// `n` points (or one per `unit` of volume) uniform over the region
/// `holds` describes inside the box `lo`..`hi`, from `seed`. The volume is
/// estimated from the share of the first `TRIAL` (4096) draws it holds; the
/// points are the held draws, in order (at most 64 draws per point asked).
pub fn volume(
    lo: [f64; 3],
    hi: [f64; 3],
    holds: impl Fn([f64; 3]) -> bool,
    n: Option<u64>,
    unit: f64,
    seed: u64,
) -> Vec<[f64; 3]> {
    let key = stream(seed);
    let draw = |i: u64| -> [f64; 3] {
        std::array::from_fn(|d| lo[d] + key.child(3 * i + d as u64).unit() * (hi[d] - lo[d]))
    };
    let boxed: f64 = (0..3).map(|d| hi[d] - lo[d]).product();
    if !(boxed > 0.0 && boxed.is_finite()) {
        return Vec::new();
    }
    let held = (0..TRIAL).filter(|&i| holds(draw(i))).count();
    let n = count(n, boxed * held as f64 / TRIAL as f64, unit);
    let mut out = Vec::with_capacity(n);
    let mut i = 0;
    while out.len() < n && i < 64 * n as u64 + TRIAL {
        let p = draw(i);
        if holds(p) {
            out.push(p);
        }
        i += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{LineString, MultiPolygon, Polygon};

    /// A 200 x 200 box with a 100 x 100 hole in its middle.
    fn box_with_hole() -> Region {
        let ring = |a: f64, b: f64| LineString::from(vec![(a, a), (b, a), (b, b), (a, b), (a, a)]);
        Region::from_area(MultiPolygon::new(vec![Polygon::new(
            ring(0.0, 200.0),
            vec![ring(50.0, 150.0)],
        )]))
        .unwrap()
    }

    #[test]
    fn the_triangles_inside_cover_the_area_and_not_the_hole() {
        let tris = triangles(&box_with_hole());
        let area: f64 = tris.iter().map(|t| area2(t) / 2.0).sum();
        // 200^2 - 100^2, by hand.
        assert!((area - 30_000.0).abs() < 1e-6, "{area}");
        for t in &tris {
            let c = [0, 1].map(|d| (t[0][d] + t[1][d] + t[2][d]) / 3.0);
            let in_hole = (50.0..=150.0).contains(&c[0]) && (50.0..=150.0).contains(&c[1]);
            assert!(!in_hole, "a triangle in the hole: {t:?}");
        }
    }

    #[test]
    fn points_fall_in_the_region_by_area_and_repeat_with_the_seed() {
        let r = box_with_hole();
        // One per 10 x 10 of 30 000: 300.
        let pts = plane(&r, None, 100.0, 7);
        assert_eq!(pts.len(), 300);
        assert!(
            pts.iter()
                .all(|p| r.covers_point(crate::turtle::Point::new(p[0], p[1])))
        );
        // By area: the left strip (x < 50) is 10 000 of 30 000.
        let left = pts.iter().filter(|p| p[0] < 50.0).count();
        assert!((70..=130).contains(&left), "{left} of 300 left of x = 50");
        assert_eq!(pts, plane(&r, None, 100.0, 7));
        assert_ne!(pts, plane(&r, None, 100.0, 8));
        assert_eq!(plane(&r, Some(5), 100.0, 7).len(), 5);
    }

    #[test]
    fn points_of_a_volume_fall_in_it() {
        // The ball of radius 50 about the origin: 523 599 units, 524 of 1000.
        let holds = |p: [f64; 3]| p.iter().map(|c| c * c).sum::<f64>() < 2500.0;
        let pts = volume([-50.0; 3], [50.0; 3], holds, None, 1000.0, 3);
        assert!((490..=560).contains(&pts.len()), "{}", pts.len());
        assert!(pts.iter().all(|&p| holds(p)));
    }
}
