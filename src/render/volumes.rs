//! A 3D layout's volumes seen from a view (`--show-layout` of a 3D tree,
//! docs/3d.md): each volume's outline on the screen, filled faintly under
//! the tree like a 2D layout's shapes.
//!
//! Each volume's surface is cut into small planar pieces (quads and caps:
//! `surface`), every piece is projected, and their union is the
//! volume's outline, holes included (a ring seen down its axis); for the
//! convex volumes (Box, Sphere, Ellipsoid, Cylinder) that union is the
//! convex hull of the projected corners, which is what is computed. The union
//! is `geo`'s ([`geo::unary_union`]), so a Revolve of a notched profile or an
//! Extrude of a concave polygon gets its true outline, not a convex hull.
//! Curved surfaces are cut into [`SIDES`] pieces round, so their outlines are
//! polygons inside the true ones (a sphere's is a 48-gon).
//!
//! Volumes are painted in their order, as 2D shapes are: a white volume
//! (one that carves) is painted white over the outline of what it carves,
//! so a hollow shows in every view, even one inside its volume.

use geo::orient::{Direction, Orient};
use geo::{Area, ConvexHull, Coord, LineString, MultiPolygon, Polygon};

use super::view::Projection;
use crate::model::{Layout, Solid};
use crate::turtle::turtle3::Point3;
use crate::turtle::{Fill, Point};

/// Projected pieces with less area than this (square canvas units) are
/// seen edge-on and left out of the union.
const EDGE_ON: f64 = 1e-9;

/// Pieces round a curved surface (sphere, ellipsoid, cylinder, revolve).
pub const SIDES: usize = 48;

/// The outlines of `layout`'s volumes seen through `projection`, one fill
/// a volume in painting order. `axis` is the first root's x and z, the
/// axis `Revolve` turns about.
pub fn outlines(layout: &Layout, axis: [f64; 2], projection: &Projection) -> Vec<Fill> {
    layout
        .solids
        .iter()
        .map(|s| {
            let faces = surface(&s.solid, axis);
            let outline = if convex(&s.solid) {
                // A convex polyhedron's outline is the hull of its
                // projected corners: no union needed.
                let points: Vec<geo::Point> = faces
                    .iter()
                    .flatten()
                    .map(|&p| {
                        let (q, _) = projection.project(p);
                        geo::Point::new(q.x, q.y)
                    })
                    .collect();
                MultiPolygon::new(vec![geo::MultiPoint::new(points).convex_hull()])
            } else {
                let pieces: Vec<Polygon> = faces
                    .iter()
                    .map(|face| polygon(face, projection))
                    // Pieces seen edge-on (and the poles' slivers) cover nothing.
                    .filter(|p| p.unsigned_area() > EDGE_ON)
                    .collect();
                geo::unary_union(&pieces)
            };
            Fill {
                color: s.color,
                rings: rings(outline),
            }
        })
        .collect()
}

/// Whether `solid` is convex (its surface pieces make a convex
/// polyhedron).
fn convex(solid: &Solid) -> bool {
    matches!(
        solid,
        Solid::Box { .. } | Solid::Sphere { .. } | Solid::Ellipsoid { .. } | Solid::Cylinder { .. }
    )
}

/// A planar piece of a surface: its corners in order.
type Face = Vec<Point3>;

/// The projected piece, as a `geo` polygon.
fn polygon(face: &Face, projection: &Projection) -> Polygon {
    let ring: Vec<Coord> = face
        .iter()
        .map(|&p| {
            let (q, _) = projection.project(p);
            Coord { x: q.x, y: q.y }
        })
        .collect();
    // The union needs every piece counter-clockwise (pieces facing away
    // from the camera come out clockwise).
    Polygon::new(LineString::new(ring), Vec::new()).orient(Direction::Default)
}

/// The rings of a union, outer and inner alike (fills are even-odd).
fn rings(m: MultiPolygon) -> Vec<Vec<Point>> {
    let ring = |l: &LineString| l.coords().map(|c| Point::new(c.x, c.y)).collect();
    m.iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .map(ring)
        .collect()
}

/// The surface of `solid` in planar pieces.
fn surface(solid: &Solid, axis: [f64; 2]) -> Vec<Face> {
    match solid {
        Solid::Box { corner: c, size: s } => {
            let x = [c[0], c[0] + s[0]];
            let y = [c[1], c[1] + s[1]];
            let z = [c[2], c[2] + s[2]];
            let p = |i: usize, j: usize, k: usize| Point3::new(x[i], y[j], z[k]);
            vec![
                vec![p(0, 0, 0), p(1, 0, 0), p(1, 1, 0), p(0, 1, 0)],
                vec![p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)],
                vec![p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)],
                vec![p(0, 1, 0), p(1, 1, 0), p(1, 1, 1), p(0, 1, 1)],
                vec![p(0, 0, 0), p(0, 1, 0), p(0, 1, 1), p(0, 0, 1)],
                vec![p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)],
            ]
        }
        Solid::Sphere { centre, r } => ellipsoid(*centre, [*r; 3]),
        Solid::Ellipsoid { centre, radii } => ellipsoid(*centre, *radii),
        Solid::Cylinder { base, r, h } => {
            // Its profile: the rectangle from the axis out to r, turned.
            let profile = [
                (0.0, base[1]),
                (*r, base[1]),
                (*r, base[1] - h),
                (0.0, base[1] - h),
            ];
            turned(&profile, [base[0], base[2]])
        }
        Solid::Extrude { shape, z1, z2 } => {
            let ring = crate::rings::shape_ring(shape);
            let at = |p: &Point, z: f64| Point3::new(p.x, p.y, z);
            let mut faces: Vec<Face> = vec![
                ring.iter().map(|p| at(p, *z1)).collect(),
                ring.iter().map(|p| at(p, *z2)).collect(),
            ];
            for (a, b) in ring.iter().zip(ring.iter().cycle().skip(1)) {
                faces.push(vec![at(a, *z1), at(b, *z1), at(b, *z2), at(a, *z2)]);
            }
            faces
        }
        Solid::Revolve { shape } => {
            // Distances from the axis, signed: both halves of the profile
            // are turned a whole turn (section 11: a point is inside when
            // either half holds it).
            let profile: Vec<(f64, f64)> = crate::rings::shape_ring(shape)
                .iter()
                .map(|p| (p.x - axis[0], p.y))
                .collect();
            let mut faces = sweep(&profile, axis, SIDES, SIDES);
            // The profile itself closes the solid seen edge-on.
            faces.push(at_angle(&profile, axis, 0));
            faces
        }
    }
}

/// The ellipsoid about `c` with radii `r`, as pieces between parallels
/// and meridians.
fn ellipsoid(c: [f64; 3], r: [f64; 3]) -> Vec<Face> {
    let rows = SIDES / 2;
    let point = |i: usize, j: usize| {
        let (ct, st) = turn(i, 2 * rows);
        let (cp, sp) = turn(j, SIDES);
        Point3::new(
            c[0] + r[0] * st * cp,
            c[1] - r[1] * ct,
            c[2] + r[2] * st * sp,
        )
    };
    let mut faces = Vec::with_capacity(rows * SIDES);
    for i in 0..rows {
        for j in 0..SIDES {
            faces.push(vec![
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ]);
        }
    }
    faces
}

/// The profile `(distance from the axis, y)` turned a whole turn about the
/// vertical axis through `axis` (x, z): its caps and sides.
fn turned(profile: &[(f64, f64)], axis: [f64; 2]) -> Vec<Face> {
    let mut faces = sweep(profile, axis, SIDES, SIDES);
    // The discs of the profile's horizontal edges (a cylinder's ends).
    for (a, b) in profile.iter().zip(profile.iter().cycle().skip(1)) {
        if a.1 == b.1 {
            let r = a.0.abs().max(b.0.abs());
            faces.push(
                (0..SIDES)
                    .map(|k| on_circle(r, a.1, axis, k, SIDES))
                    .collect(),
            );
        }
    }
    faces
}

/// Side pieces of `profile` swept over `steps` of `per_turn` steps a turn.
fn sweep(profile: &[(f64, f64)], axis: [f64; 2], steps: usize, per_turn: usize) -> Vec<Face> {
    let mut faces = Vec::with_capacity(profile.len() * steps);
    for k in 0..steps {
        for (a, b) in profile.iter().zip(profile.iter().cycle().skip(1)) {
            faces.push(vec![
                on_circle(a.0, a.1, axis, k, per_turn),
                on_circle(b.0, b.1, axis, k, per_turn),
                on_circle(b.0, b.1, axis, k + 1, per_turn),
                on_circle(a.0, a.1, axis, k + 1, per_turn),
            ]);
        }
    }
    faces
}

/// The profile placed at step `k` of [`SIDES`] round the axis.
fn at_angle(profile: &[(f64, f64)], axis: [f64; 2], k: usize) -> Face {
    profile
        .iter()
        .map(|&(r, y)| on_circle(r, y, axis, k, SIDES))
        .collect()
}

/// The point at distance `r` from the vertical axis through `axis`, at
/// height `y`, turned `k` of `per_turn` steps from +x.
fn on_circle(r: f64, y: f64, axis: [f64; 2], k: usize, per_turn: usize) -> Point3 {
    let (c, s) = turn(k, per_turn);
    Point3::new(axis[0] + r * c, y, axis[1] + r * s)
}

/// `cos` and `sin` of `k` of `per_turn` steps of a whole turn (`libm`).
fn turn(k: usize, per_turn: usize) -> (f64, f64) {
    crate::turtle::turtle3::cos_sin(360.0 * k as f64 / per_turn as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{LayoutSolid, Shape};
    use crate::render::view::View;

    fn layout(solid: Solid) -> Layout {
        let mut l = Layout::new(Vec::new());
        l.solids.push(LayoutSolid {
            color: crate::color::Rgb::new(0, 128, 0),
            color_text: "clGreen".into(),
            solid,
            loc: Default::default(),
        });
        l
    }

    /// The even-odd area of a fill's rings (outer rings counter or clockwise).
    fn area(f: &Fill) -> f64 {
        let poly = |r: &Vec<Point>| {
            Polygon::new(
                LineString::new(r.iter().map(|p| Coord { x: p.x, y: p.y }).collect()),
                Vec::new(),
            )
            .unsigned_area()
        };
        // Outer rings add, holes (inside an outer ring) subtract: a ring
        // inside another is a hole here, as in these shapes.
        let areas: Vec<f64> = f.rings.iter().map(poly).collect();
        let outer = areas.iter().cloned().fold(0.0, f64::max);
        2.0 * outer - areas.iter().sum::<f64>()
    }

    fn outline(solid: Solid, az: f64, el: f64) -> Fill {
        let view = View::parse(&format!("{az},{el}")).unwrap();
        outlines(&layout(solid), [0.0, 0.0], &view.projection()).remove(0)
    }

    /// A 48-gon inscribed in a circle of radius r: (48/2) r^2 sin(2 pi / 48).
    fn inscribed(r: f64) -> f64 {
        24.0 * r * r * libm::sin(std::f64::consts::TAU / 48.0)
    }

    /// A sphere looks like its disc from every side.
    #[test]
    fn a_sphere_is_a_disc_from_any_view() {
        for (az, el) in [(0.0, 0.0), (30.0, 20.0), (-60.0, 35.0), (120.0, 89.0)] {
            let a = area(&outline(
                Solid::Sphere {
                    centre: [5.0, -3.0, 2.0],
                    r: 10.0,
                },
                az,
                el,
            ));
            let disc = std::f64::consts::PI * 100.0;
            assert!(
                a <= disc + 1e-9 && a > inscribed(10.0) * 0.99,
                "{az},{el}: {a}"
            );
        }
    }

    /// A box from the front is its w x h face; from straight above
    /// (elevation 90) its w x d footprint.
    #[test]
    fn a_box_from_the_front_and_from_above() {
        let b = Solid::Box {
            corner: [0.0, 0.0, 0.0],
            size: [4.0, 6.0, 8.0],
        };
        assert!((area(&outline(b.clone(), 0.0, 0.0)) - 24.0).abs() < 1e-9);
        assert!((area(&outline(b, 0.0, 90.0)) - 32.0).abs() < 1e-9);
    }

    /// A cylinder from the front is its 2r x h rectangle; from above its
    /// disc (a 48-gon).
    #[test]
    fn a_cylinder_from_the_front_and_from_above() {
        let c = Solid::Cylinder {
            base: [0.0, 0.0, 0.0],
            r: 3.0,
            h: 10.0,
        };
        assert!((area(&outline(c.clone(), 0.0, 0.0)) - 60.0).abs() < 1e-9);
        assert!((area(&outline(c, 0.0, 90.0)) - inscribed(3.0)).abs() < 1e-6);
    }

    /// A ring revolved (a rectangle profile off the axis) seen from above
    /// is an annulus: the hole is a ring of its own, not filled.
    #[test]
    fn a_revolved_ring_from_above_has_its_hole() {
        let shape = Shape::Rect {
            x: 5.0,
            y: 0.0,
            w: 5.0,
            h: 2.0,
        };
        let f = outline(Solid::Revolve { shape }, 0.0, 90.0);
        assert_eq!(f.rings.len(), 2, "outer and inner ring");
        let want = inscribed(10.0) - inscribed(5.0);
        assert!(
            (area(&f) - want).abs() < 1e-6,
            "{} against {want}",
            area(&f)
        );
    }

    /// An Extrude seen from the front is its 2D shape.
    #[test]
    fn an_extrusion_from_the_front_is_its_shape() {
        let shape = Shape::Polygon(vec![
            (0.0, 0.0),
            (10.0, 0.0),
            (10.0, 10.0),
            (5.0, 3.0),
            (0.0, 10.0),
        ]);
        let f = outline(
            Solid::Extrude {
                shape,
                z1: -5.0,
                z2: 5.0,
            },
            0.0,
            0.0,
        );
        // The concave pentagon: the square less the notch (10 x 10 - 5 x 7).
        assert!((area(&f) - 65.0).abs() < 1e-9, "{}", area(&f));
    }
}
