//! The region of a 3D layout: volumes painted in order, `clWhite` carving,
//! and the test that a stem's capsule lies inside it.
//!
//! Two cases (`docs/3d.md`, *Growth in volumes*):
//!
//! - **A prism**: every volume is an `Extrude` between the same `z1` and
//!   `z2`. The region is the 2D region of their shapes (painted in order
//!   as in 2D, [`Region`]) times the open interval (`z1`, `z2`), and the
//!   test is exact: a capsule lies in a product exactly when its shadow on
//!   the xy plane (the 2D capsule of the projected segment, same radius)
//!   lies in the 2D region, which is the 2D test itself, and its z extent
//!   lies in the interval. So an extruded layout grows what the 2D layout
//!   grows.
//! - **Otherwise** each volume says of a capsule *in* (wholly inside it),
//!   *out* (wholly outside) or *unsure*, never wrongly in or out; painting
//!   in order, a coloured volume makes *in* what it holds and leaves the
//!   rest, a white one makes *out* what it holds; *unsure* stays unsure
//!   unless the state was already what the volume would make it. A capsule
//!   left unsure is cut at its middle into two capsules of the same radius
//!   (together exactly the capsule) and each is asked again, up to
//!   [`SPLITS`] times deep; it is accepted only if every piece ends *in*.
//!   So a stem passing from a trunk volume into a crown volume grows, and
//!   the test is conservative: it may refuse a capsule that barely fits,
//!   never accept one that pokes out.

use super::super::occupancy::{Cap, Seg, Seg3, point_seg_dist2};
use super::super::region::Region;
use crate::color::Rgb;
use crate::diag::Diagnostics;
use crate::model::{Layout, LayoutShape, Shape, Solid};
use crate::turtle::Point;

/// How deep an unsure capsule is cut in halves (at most 2^SPLITS pieces).
pub const SPLITS: u32 = 6;

/// What a volume says of a capsule.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rel {
    In,
    Out,
    Unsure,
}

/// One volume, ready for the test.
#[derive(Debug, Clone)]
enum Vol {
    /// An axis-aligned box, its smallest and largest corners.
    Box { lo: [f64; 3], hi: [f64; 3] },
    /// An ellipsoid (a sphere: equal radii).
    Ellipsoid { centre: [f64; 3], radii: [f64; 3] },
    /// A vertical cylinder: its axis at (x, z), from `top` to `bottom` in y.
    Cylinder {
        axis: [f64; 2],
        r: f64,
        top: f64,
        bottom: f64,
    },
    /// A 2D shape between `z1` and `z2`.
    Extrude { area: Region, z1: f64, z2: f64 },
    /// A 2D profile turned about the vertical line through `axis` (x, z).
    Revolve { profile: Region, axis: [f64; 2] },
}

/// The region a 3D tree may grow in.
#[derive(Debug, Clone)]
pub struct Region3 {
    kind: Kind,
}

#[derive(Debug, Clone)]
enum Kind {
    Prism { area: Region, z1: f64, z2: f64 },
    Paint(Vec<(bool, Vol)>),
}

/// The 2D region of one shape (its colour does not matter here).
fn area_of(shape: &Shape, max_vertices: usize) -> Result<Region, Diagnostics> {
    let layout = Layout::new(vec![LayoutShape::new(Rgb::BLACK, shape.clone())]);
    Region::from_layout(&layout, max_vertices)
}

impl Region3 {
    /// The region of `layout`'s volumes; `axis`: the first root's x and z
    /// (the axis of `Revolve`).
    pub fn from_layout(
        layout: &Layout,
        axis: [f64; 2],
        max_vertices: usize,
    ) -> Result<Region3, Diagnostics> {
        let solids = &layout.solids;
        let slab = match solids.first().map(|s| &s.solid) {
            Some(Solid::Extrude { z1, z2, .. }) => Some((*z1, *z2)),
            _ => None,
        };
        if let Some((z1, z2)) = slab
            && solids.iter().all(
                |s| matches!(&s.solid, Solid::Extrude { z1: a, z2: b, .. } if *a == z1 && *b == z2),
            )
        {
            let shapes = solids
                .iter()
                .filter_map(|s| match &s.solid {
                    Solid::Extrude { shape, .. } => Some(LayoutShape::new(s.color, shape.clone())),
                    _ => None,
                })
                .collect();
            let area = Region::from_layout(&Layout::new(shapes), max_vertices)?;
            return Ok(Region3 {
                kind: Kind::Prism { area, z1, z2 },
            });
        }
        let mut ops = Vec::with_capacity(solids.len());
        for s in solids {
            let vol = match &s.solid {
                Solid::Box { corner, size } => Vol::Box {
                    lo: *corner,
                    hi: std::array::from_fn(|i| corner[i] + size[i]),
                },
                Solid::Sphere { centre, r } => Vol::Ellipsoid {
                    centre: *centre,
                    radii: [*r; 3],
                },
                Solid::Ellipsoid { centre, radii } => Vol::Ellipsoid {
                    centre: *centre,
                    radii: *radii,
                },
                Solid::Cylinder { base, r, h } => Vol::Cylinder {
                    axis: [base[0], base[2]],
                    r: *r,
                    top: base[1] - h,
                    bottom: base[1],
                },
                Solid::Extrude { shape, z1, z2 } => Vol::Extrude {
                    area: area_of(shape, max_vertices)?,
                    z1: *z1,
                    z2: *z2,
                },
                Solid::Revolve { shape } => Vol::Revolve {
                    profile: area_of(shape, max_vertices)?,
                    axis,
                },
            };
            ops.push((s.color != Rgb::WHITE, vol));
        }
        Ok(Region3 {
            kind: Kind::Paint(ops),
        })
    }

    /// Whether the point `p` lies in the region or on its boundary, as in
    /// 2D (a root at the foot of a trunk `Cylinder` is in it): in a
    /// coloured volume or on it, and not strictly inside a white one
    /// painted later.
    pub fn covers_point(&self, p: [f64; 3]) -> bool {
        match &self.kind {
            Kind::Prism { area, z1, z2 } => {
                *z1 <= p[2] && p[2] <= *z2 && area.covers_point(Point::new(p[0], p[1]))
            }
            Kind::Paint(ops) => {
                ops.iter().fold(
                    false,
                    |inside, (adds, vol)| {
                        if vol.holds(p, *adds) { *adds } else { inside }
                    },
                )
            }
        }
    }

    /// A box that holds the region: the smallest and largest corners (the
    /// box of its coloured volumes; white ones only carve).
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        match &self.kind {
            Kind::Prism { area, z1, z2 } => {
                let b = area.bbox();
                ([b.min_x, b.min_y, *z1], [b.max_x, b.max_y, *z2])
            }
            Kind::Paint(ops) => {
                let mut lo = [f64::INFINITY; 3];
                let mut hi = [f64::NEG_INFINITY; 3];
                for (_, v) in ops.iter().filter(|(adds, _)| *adds) {
                    let (a, b) = v.bounds();
                    for i in 0..3 {
                        lo[i] = lo[i].min(a[i]);
                        hi[i] = hi[i].max(b[i]);
                    }
                }
                (lo, hi)
            }
        }
    }

    /// Whether the capsule `s` lies inside the region (exactly for a
    /// prism, conservatively otherwise: the module documentation).
    /// `a_inside`: its start is known to lie inside (a prism skips a test).
    pub fn capsule_inside(&self, s: &Seg3, a_inside: bool) -> bool {
        match &self.kind {
            Kind::Prism { area, z1, z2 } => {
                let (lo, hi) = (s.a[2].min(s.b[2]), s.a[2].max(s.b[2]));
                if lo - s.r <= *z1 || hi + s.r >= *z2 {
                    return false;
                }
                area.capsule_inside(
                    Point::new(s.a[0], s.a[1]),
                    Point::new(s.b[0], s.b[1]),
                    s.r,
                    a_inside,
                )
            }
            Kind::Paint(ops) => pieces_inside(ops, s, SPLITS),
        }
    }
}

/// Whether `s` is inside the painting, cutting it in halves while unsure.
fn pieces_inside(ops: &[(bool, Vol)], s: &Seg3, depth: u32) -> bool {
    match paint(ops, s) {
        Rel::In => true,
        Rel::Out => false,
        Rel::Unsure if depth == 0 || s.a == s.b => false,
        Rel::Unsure => {
            let m = std::array::from_fn(|i| (s.a[i] + s.b[i]) / 2.0);
            pieces_inside(ops, &Seg3::capsule(s.a, m, s.r), depth - 1)
                && pieces_inside(ops, &Seg3::capsule(m, s.b, s.r), depth - 1)
        }
    }
}

/// What painting the volumes in order makes of `s`.
fn paint(ops: &[(bool, Vol)], s: &Seg3) -> Rel {
    ops.iter().fold(Rel::Out, |state, (adds, vol)| {
        let made = if *adds { Rel::In } else { Rel::Out };
        match vol.rel(s) {
            Rel::In => made,
            Rel::Out => state,
            Rel::Unsure if state == made => made,
            Rel::Unsure => Rel::Unsure,
        }
    })
}

/// The smallest and largest coordinate `i` of the capsule.
fn extent(s: &Seg3, i: usize) -> (f64, f64) {
    (s.a[i].min(s.b[i]) - s.r, s.a[i].max(s.b[i]) + s.r)
}

/// The shadow of `s` on the xz plane, as a 2D segment.
fn xz(s: &Seg3) -> Seg {
    Seg::new([s.a[0], s.a[2]], [s.b[0], s.b[2]])
}

impl Vol {
    /// The volume's box: its smallest and largest corners.
    fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        match self {
            Vol::Box { lo, hi } => (*lo, *hi),
            Vol::Ellipsoid { centre, radii } => (
                std::array::from_fn(|i| centre[i] - radii[i]),
                std::array::from_fn(|i| centre[i] + radii[i]),
            ),
            Vol::Cylinder {
                axis,
                r,
                top,
                bottom,
            } => (
                [axis[0] - r, *top, axis[1] - r],
                [axis[0] + r, *bottom, axis[1] + r],
            ),
            Vol::Extrude { area, z1, z2 } => {
                let b = area.bbox();
                ([b.min_x, b.min_y, *z1], [b.max_x, b.max_y, *z2])
            }
            Vol::Revolve { profile, axis } => {
                let b = profile.bbox();
                let r = (b.min_x - axis[0]).abs().max((b.max_x - axis[0]).abs());
                (
                    [axis[0] - r, b.min_y, axis[1] - r],
                    [axis[0] + r, b.max_y, axis[1] + r],
                )
            }
        }
    }

    /// Whether the volume holds `p`: on its boundary too if `closed`.
    fn holds(&self, p: [f64; 3], closed: bool) -> bool {
        let below = |a: f64, b: f64| if closed { a <= b } else { a < b };
        let rho = |axis: [f64; 2]| ((p[0] - axis[0]).powi(2) + (p[2] - axis[1]).powi(2)).sqrt();
        match self {
            Vol::Box { lo, hi } => (0..3).all(|i| below(lo[i], p[i]) && below(p[i], hi[i])),
            Vol::Ellipsoid { centre, radii } => below(
                (0..3)
                    .map(|i| ((p[i] - centre[i]) / radii[i]).powi(2))
                    .sum(),
                1.0,
            ),
            Vol::Cylinder {
                axis,
                r,
                top,
                bottom,
            } => below(rho(*axis), *r) && below(*top, p[1]) && below(p[1], *bottom),
            Vol::Extrude { area, z1, z2 } => {
                below(*z1, p[2]) && below(p[2], *z2) && area.covers_point(Point::new(p[0], p[1]))
            }
            Vol::Revolve { profile, axis } => [1.0, -1.0]
                .iter()
                .any(|side| profile.covers_point(Point::new(axis[0] + side * rho(*axis), p[1]))),
        }
    }

    fn rel(&self, s: &Seg3) -> Rel {
        match self {
            Vol::Box { lo, hi } => {
                let inner = |p: [f64; 3]| (0..3).all(|i| lo[i] + s.r < p[i] && p[i] < hi[i] - s.r);
                if inner(s.a) && inner(s.b) {
                    return Rel::In;
                }
                let apart = (0..3).any(|i| {
                    let (a, b) = extent(s, i);
                    b <= lo[i] || a >= hi[i]
                });
                if apart { Rel::Out } else { Rel::Unsure }
            }
            Vol::Ellipsoid { centre, radii } => {
                // In the ellipsoid's unit coordinates a displacement of
                // length d is at most d / min_r long.
                let min_r = radii[0].min(radii[1]).min(radii[2]);
                let unit = |p: [f64; 3]| -> [f64; 3] {
                    std::array::from_fn(|i| (p[i] - centre[i]) / radii[i])
                };
                let len = |p: [f64; 3]| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
                let (ua, ub) = (unit(s.a), unit(s.b));
                let grow = s.r / min_r;
                if len(ua).max(len(ub)) + grow < 1.0 {
                    return Rel::In;
                }
                let nearest = point_seg_dist2([0.0; 3], &Cap::new(ua, ub)).sqrt();
                if nearest - grow >= 1.0 {
                    Rel::Out
                } else {
                    Rel::Unsure
                }
            }
            Vol::Cylinder {
                axis,
                r,
                top,
                bottom,
            } => {
                let radial =
                    |p: [f64; 3]| ((p[0] - axis[0]).powi(2) + (p[2] - axis[1]).powi(2)).sqrt();
                let (ylo, yhi) = extent(s, 1);
                if radial(s.a).max(radial(s.b)) + s.r < *r && *top < ylo && yhi < *bottom {
                    return Rel::In;
                }
                let near = point_seg_dist2(*axis, &xz(s)).sqrt();
                if yhi <= *top || ylo >= *bottom || near >= r + s.r {
                    Rel::Out
                } else {
                    Rel::Unsure
                }
            }
            Vol::Extrude { area, z1, z2 } => {
                let (zlo, zhi) = extent(s, 2);
                if zhi <= *z1 || zlo >= *z2 {
                    return Rel::Out;
                }
                if *z1 < zlo
                    && zhi < *z2
                    && area.capsule_inside(
                        Point::new(s.a[0], s.a[1]),
                        Point::new(s.b[0], s.b[1]),
                        s.r,
                        false,
                    )
                {
                    return Rel::In;
                }
                let b = area.bbox();
                let (xlo, xhi) = extent(s, 0);
                let (ylo, yhi) = extent(s, 1);
                if xhi <= b.min_x || xlo >= b.max_x || yhi <= b.min_y || ylo >= b.max_y {
                    Rel::Out
                } else {
                    Rel::Unsure
                }
            }
            Vol::Revolve { profile, axis } => revolve_rel(profile, *axis, s),
        }
    }
}

/// [`Vol::rel`] of a revolved profile. A point at distance rho from the
/// axis and height y is inside when the profile holds (x_axis + rho, y) or
/// (x_axis - rho, y). The map from space to (rho, y) lengthens no
/// distance, so the capsule's image lies within `r` of
/// the image of its centre line; that curve lies within `bow` of the
/// chord between its ends' images ([`bow`]). So the 2D capsule around that
/// chord, of radius `r + bow`, holds the image: inside the profile (on
/// either side of the axis) means inside the volume.
fn revolve_rel(profile: &Region, axis: [f64; 2], s: &Seg3) -> Rel {
    let rho = |p: [f64; 3]| ((p[0] - axis[0]).powi(2) + (p[2] - axis[1]).powi(2)).sqrt();
    let (r0, r1) = (rho(s.a), rho(s.b));
    let wide = s.r + bow(axis, s);
    for side in [1.0, -1.0] {
        let a = Point::new(axis[0] + side * r0, s.a[1]);
        let b = Point::new(axis[0] + side * r1, s.b[1]);
        if profile.capsule_inside(a, b, wide, false) {
            return Rel::In;
        }
    }
    // Out when the capsule's distances from the axis, or its heights, miss
    // the profile's.
    let bb = profile.bbox();
    let (dl, dr) = ((bb.min_x - axis[0]).abs(), (bb.max_x - axis[0]).abs());
    let far = dl.max(dr);
    let close = if bb.min_x <= axis[0] && axis[0] <= bb.max_x {
        0.0
    } else {
        dl.min(dr)
    };
    let near = point_seg_dist2(axis, &xz(s)).sqrt();
    let (ylo, yhi) = extent(s, 1);
    if near - s.r >= far || r0.max(r1) + s.r <= close || yhi <= bb.min_y || ylo >= bb.max_y {
        Rel::Out
    } else {
        Rel::Unsure
    }
}

/// How far the distance from the axis along `s` falls below the straight
/// line between its ends' distances (the distance is convex along a
/// segment), at most: worked out at the one point where the two slopes
/// agree, with a margin for rounding.
fn bow(axis: [f64; 2], s: &Seg3) -> f64 {
    let p = [s.a[0] - axis[0], s.a[2] - axis[1]];
    let d = [s.b[0] - s.a[0], s.b[2] - s.a[2]];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    if len == 0.0 {
        return 0.0;
    }
    let rho = |t: f64| ((p[0] + t * d[0]).powi(2) + (p[1] + t * d[1]).powi(2)).sqrt();
    let (r0, r1) = (rho(0.0), rho(1.0));
    // The line's distance from the axis, and a's place along it.
    let h = (p[0] * d[1] - p[1] * d[0]).abs() / len;
    let s0 = (p[0] * d[0] + p[1] * d[1]) / len;
    let k = (r1 - r0) / len;
    let at = if k.abs() < 1.0 && h > 0.0 {
        k * h / (1.0 - k * k).sqrt()
    } else {
        0.0
    };
    let t = ((at - s0) / len).clamp(0.0, 1.0);
    let gap = (1.0 - t) * r0 + t * r1 - rho(t);
    gap.max(0.0) * (1.0 + 1e-9) + 1e-9 * (r0 + r1 + len)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bow_bounds_the_sampled_gap() {
        let mut x: u64 = 0x1234_5678_9abc_def1;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 20.0 - 10.0
        };
        for _ in 0..200 {
            let s = Seg3::new([next(), next(), next()], [next(), next(), next()]);
            let axis = [next() / 4.0, next() / 4.0];
            let b = bow(axis, &s);
            let rho = |p: [f64; 3]| ((p[0] - axis[0]).powi(2) + (p[2] - axis[1]).powi(2)).sqrt();
            let (r0, r1) = (rho(s.a), rho(s.b));
            let mut worst: f64 = 0.0;
            for i in 0..=2000 {
                let t = i as f64 / 2000.0;
                let p = std::array::from_fn(|j| s.a[j] + (s.b[j] - s.a[j]) * t);
                worst = worst.max((1.0 - t) * r0 + t * r1 - rho(p));
            }
            assert!(worst <= b, "{worst} > {b}");
            // And not far above it: the bound is the maximum, not a guess.
            assert!(b - worst < 1e-3 * (1.0 + b), "{worst} << {b}");
        }
    }

    fn region(solids: Vec<(Rgb, Solid)>) -> Region3 {
        let mut l = Layout::new(Vec::new());
        l.solids = solids
            .into_iter()
            .map(|(color, solid)| crate::model::LayoutSolid {
                color,
                color_text: String::new(),
                solid,
                loc: crate::model::Loc::default(),
            })
            .collect();
        Region3::from_layout(&l, [0.0, 0.0], 16_000).unwrap()
    }

    const GREEN: Rgb = Rgb::new(0, 128, 0);

    /// A trunk and a crown: a stem from one into the other is in neither
    /// alone, and grows (its halves are); one leaving both does not.
    #[test]
    fn a_stem_from_the_trunk_into_the_crown_fits_in_halves() {
        let r = region(vec![
            (
                GREEN,
                Solid::Cylinder {
                    base: [0.0, 0.0, 0.0],
                    r: 2.0,
                    h: 20.0,
                },
            ),
            (
                GREEN,
                Solid::Sphere {
                    centre: [0.0, -30.0, 0.0],
                    r: 12.0,
                },
            ),
        ]);
        let up = Seg3::capsule([0.0, -15.0, 0.0], [0.0, -25.0, 0.0], 0.5);
        assert!(r.capsule_inside(&up, false));
        // Out through the sphere's top (it reaches y = -42).
        let out = Seg3::capsule([0.0, -35.0, 0.0], [0.0, -42.5, 0.0], 0.5);
        assert!(!r.capsule_inside(&out, false));
        // Sideways out of the trunk below the crown.
        let side = Seg3::capsule([0.0, -5.0, 0.0], [0.0, -5.0, 1.8], 0.5);
        assert!(!r.capsule_inside(&side, false));
        assert!(r.capsule_inside(
            &Seg3::capsule([0.0, -5.0, 0.0], [0.0, -5.0, 1.4], 0.5),
            false
        ));
    }

    /// A box with a sphere carved out: stems through or into the hole are
    /// refused, stems beside it grow.
    #[test]
    fn a_carved_sphere_keeps_stems_out() {
        let r = region(vec![
            (
                GREEN,
                Solid::Box {
                    corner: [-50.0; 3],
                    size: [100.0; 3],
                },
            ),
            (
                Rgb::WHITE,
                Solid::Sphere {
                    centre: [0.0; 3],
                    r: 10.0,
                },
            ),
        ]);
        let through = Seg3::capsule([-20.0, 0.0, 0.0], [20.0, 0.0, 0.0], 0.5);
        assert!(!r.capsule_inside(&through, false));
        // Passing 11 from the centre: the capsule's edge 0.5 off the sphere.
        let beside = Seg3::capsule([-20.0, 11.0, 0.0], [20.0, 11.0, 0.0], 0.5);
        assert!(r.capsule_inside(&beside, false));
        let grazing = Seg3::capsule([-20.0, 10.4, 0.0], [20.0, 10.4, 0.0], 0.5);
        assert!(!r.capsule_inside(&grazing, false));
        assert!(!r.covers_point([0.0, 5.0, 0.0]));
        assert!(r.covers_point([0.0, 15.0, 0.0]));
        // Out of the box.
        let out = Seg3::capsule([40.0, 40.0, 40.0], [49.8, 40.0, 40.0], 0.5);
        assert!(!r.capsule_inside(&out, false));
    }

    /// Extrusions between one z1 and z2 are a prism: the 2D test and the
    /// z interval, exactly.
    #[test]
    fn extrusions_between_the_same_planes_are_one_prism() {
        let rect = Shape::Rect {
            x: 0.0,
            y: 0.0,
            w: 10.0,
            h: 10.0,
        };
        let hole = Shape::Rect {
            x: 4.0,
            y: 4.0,
            w: 2.0,
            h: 2.0,
        };
        let r = region(vec![
            (
                GREEN,
                Solid::Extrude {
                    shape: rect,
                    z1: -1.0,
                    z2: 1.0,
                },
            ),
            (
                Rgb::WHITE,
                Solid::Extrude {
                    shape: hole,
                    z1: -1.0,
                    z2: 1.0,
                },
            ),
        ]);
        assert!(matches!(r.kind, Kind::Prism { .. }));
        let s = |z: f64, rad: f64| Seg3::capsule([1.0, 1.0, z], [1.0, 3.0, z], rad);
        assert!(r.capsule_inside(&s(0.0, 0.5), false));
        assert!(r.capsule_inside(&s(0.49, 0.5), false));
        assert!(!r.capsule_inside(&s(0.5, 0.5), false));
        // Across the hole.
        let across = Seg3::capsule([2.0, 5.0, 0.0], [8.0, 5.0, 0.0], 0.1);
        assert!(!r.capsule_inside(&across, false));
    }
}
