//! The layout region: shapes painted in order on white, white erasing.
//!
//! The paper's Graphics Tool painted the layout: each shape is filled over
//! what came before, on a white canvas, and the tree may grow where the final
//! colour is not white. [`Region::from_layout`] builds that area once, before
//! growth, with geo's boolean operations: a union for every coloured shape,
//! a difference for every white one, in painting order.
//!
//! Curved shapes become polygons first ([`shape_ring`], in [`crate::rings`]): rounded-rectangle
//! corners and ellipses are flattened with their vertices on the curve and a
//! maximum deviation (sagitta) of [`FLATTEN_TOLERANCE`](crate::rings::FLATTEN_TOLERANCE) canvas units, so the
//! polygon lies inside the true curve and no farther than that from it. The
//! renderer paints exactly these rings ([`crate::rings::fills`]), so the picture and the
//! region agree.
//!
//! Self-intersecting polygons are read with the even-odd rule, the rule the
//! renderer fills with: a pentagram's centre is outside it.
//!
//! The segment test ([`Region::segment_inside`]) is what growth calls for
//! every stem: an R-tree over the region's boundary edges answers whether a
//! segment touches the boundary; a segment that touches no boundary edge
//! lies wholly inside or wholly outside, and which one is decided by its
//! start point (known to be inside for growth points at branch tips, else
//! found by a point-in-polygon test).

use geo::{BooleanOps, BoundingRect, Coord, Intersects, LineString, MultiPolygon, Polygon};
use rstar::{AABB, RTree, RTreeObject};

use super::occupancy::{Seg, seg_seg_dist2};
use crate::diag::Help;
use crate::diag::{Diagnostic, Diagnostics, LayoutError};
use crate::limits::Bound;
use crate::model::Layout;
use crate::rings::shape_ring;
use crate::turtle::{BBox, Point};

/// The area a tree may grow in.
#[derive(Debug, Clone)]
pub struct Region {
    area: MultiPolygon<f64>,
    edges: RTree<Edge>,
    bbox: BBox,
}

/// One boundary edge of the region, for the R-tree.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Edge {
    a: Coord<f64>,
    b: Coord<f64>,
}

impl RTreeObject for Edge {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        AABB::from_corners([self.a.x, self.a.y], [self.b.x, self.b.y])
    }
}

impl Region {
    /// Paints the layout's shapes in order and keeps what is not white.
    ///
    /// Errors: a shape with non-finite numbers, a layout that leaves no area
    /// at all (only white shapes, or every coloured shape erased), or more
    /// than `max_vertices` vertices in a shape plus the area painted so far
    /// (see [`Limits::max_layout_vertices`](crate::limits::Limits)): geo's
    /// overlay fragments its input above 16 000 edges, and that path takes
    /// tens of seconds on some shapes.
    pub fn from_layout(layout: &Layout, max_vertices: usize) -> Result<Region, Diagnostics> {
        let mut area: MultiPolygon<f64> = MultiPolygon::new(Vec::new());
        for s in &layout.shapes {
            let ring = shape_ring(&s.shape);
            if ring.iter().any(|p| !p.x.is_finite() || !p.y.is_finite()) {
                return Err(Diagnostic::error(LayoutError::LayoutNotFinite)
                    .with_span(s.loc.0.clone())
                    .into());
            }
            let vertices = vertex_count(&area).saturating_add(ring.len());
            if vertices > max_vertices {
                return Err(too_many_vertices(vertices, max_vertices, s.loc.0.clone()));
            }
            let poly = polygon_of(&ring);
            area = if s.color.is_white() {
                area.difference(&poly)
            } else {
                area.union(&poly)
            };
        }
        let vertices = vertex_count(&area);
        if vertices > max_vertices {
            return Err(too_many_vertices(
                vertices,
                max_vertices,
                layout.loc.0.clone(),
            ));
        }
        Region::from_area(area).ok_or_else(|| {
            Diagnostic::error(LayoutError::EmptyRegion)
            .with_span(layout.loc.0.clone())
            .with_help(
                "paint at least one coloured (non-white) shape that later white shapes do not cover entirely",
            )
            .into()
        })
    }

    /// A region from an area already built; `None` if the area is empty.
    pub fn from_area(area: MultiPolygon<f64>) -> Option<Region> {
        let rect = area.bounding_rect()?;
        let mut edges = Vec::new();
        for poly in &area.0 {
            for ring in std::iter::once(poly.exterior()).chain(poly.interiors()) {
                for l in ring.lines() {
                    if l.start != l.end {
                        edges.push(Edge {
                            a: l.start,
                            b: l.end,
                        });
                    }
                }
            }
        }
        if edges.is_empty() {
            return None;
        }
        Some(Region {
            area,
            edges: RTree::bulk_load(edges),
            bbox: BBox {
                min_x: rect.min().x,
                min_y: rect.min().y,
                max_x: rect.max().x,
                max_y: rect.max().y,
            },
        })
    }

    /// The area as geo polygons (holes included).
    pub fn area(&self) -> &MultiPolygon<f64> {
        &self.area
    }

    /// The bounding box of the growable area (not of the white shapes
    /// around it): the canvas a renderer can show.
    pub fn bbox(&self) -> BBox {
        self.bbox
    }

    /// Number of boundary edges.
    pub fn edge_count(&self) -> usize {
        self.edges.size()
    }

    /// Whether `p` lies in the region or on its boundary. Linear in the
    /// number of edges: growth calls it only where it cannot know the answer
    /// (the root, growth points of the seed, after an `f` move).
    pub fn covers_point(&self, p: Point) -> bool {
        let c = Coord { x: p.x, y: p.y };
        if c.x < self.bbox.min_x
            || c.x > self.bbox.max_x
            || c.y < self.bbox.min_y
            || c.y > self.bbox.max_y
        {
            return false;
        }
        self.area.intersects(&c)
    }

    /// Whether the closed segment `a`-`b` touches or crosses the boundary
    /// anywhere (exact predicates).
    pub fn touches_boundary(&self, a: Point, b: Point) -> bool {
        let env = AABB::from_corners([a.x, a.y], [b.x, b.y]);
        let seg = geo::Line::new(Coord { x: a.x, y: a.y }, Coord { x: b.x, y: b.y });
        self.edges
            .locate_in_envelope_intersecting(&env)
            .any(|e| seg.intersects(&geo::Line::new(e.a, e.b)))
    }

    /// Whether the segment `a`-`b` lies in the open interior of the region:
    /// it touches no boundary edge and `a` is inside. `a_inside`: the caller
    /// already knows `a` lies in the open interior (skips the point test).
    pub fn segment_inside(&self, a: Point, b: Point, a_inside: bool) -> bool {
        !self.touches_boundary(a, b) && (a_inside || self.covers_point(a))
    }

    /// Whether the capsule of radius `r` around the segment `a`-`b` (the
    /// stem as drawn, `2 r` wide with round caps) lies inside the region:
    /// the segment is inside ([`Region::segment_inside`]) and no boundary
    /// edge comes closer to it than `r`.
    pub fn capsule_inside(&self, a: Point, b: Point, r: f64, a_inside: bool) -> bool {
        if r <= 0.0 {
            return self.segment_inside(a, b, a_inside);
        }
        // One query covers both tests: the exact crossing test of
        // `segment_inside` and the distance, on the same candidate edges.
        let seg = Seg::new([a.x, a.y], [b.x, b.y]);
        let line = geo::Line::new(Coord { x: a.x, y: a.y }, Coord { x: b.x, y: b.y });
        let env = AABB::from_corners(
            [a.x.min(b.x) - r, a.y.min(b.y) - r],
            [a.x.max(b.x) + r, a.y.max(b.y) + r],
        );
        let r2 = r * r;
        let near_edge = self.edges.locate_in_envelope_intersecting(&env).any(|e| {
            line.intersects(&geo::Line::new(e.a, e.b))
                || seg_seg_dist2(&seg, &Seg::new([e.a.x, e.a.y], [e.b.x, e.b.y])) < r2
        });
        !near_edge && (a_inside || self.covers_point(a))
    }
}

/// Vertices of every ring of `area` (each ring's closing point not counted).
fn vertex_count(area: &MultiPolygon<f64>) -> usize {
    area.0
        .iter()
        .flat_map(|p| std::iter::once(p.exterior()).chain(p.interiors()))
        .map(|r| r.0.len().saturating_sub(1))
        .sum()
}

fn too_many_vertices(vertices: usize, limit: usize, span: crate::diag::Span) -> Diagnostics {
    Bound::LayoutVertices
        .exceeded(vertices, limit as u64)
        .with_span(span)
        .with_help(
            Help::from("use fewer polygon points or fewer, smaller curved shapes, or ")
                + Bound::LayoutVertices
                + " (above 16000 the overlay can take minutes on some shapes)",
        )
        .into()
}

fn polygon_of(ring: &[Point]) -> Polygon<f64> {
    let mut coords: Vec<Coord<f64>> = ring.iter().map(|p| Coord { x: p.x, y: p.y }).collect();
    if let Some(&first) = coords.first() {
        coords.push(first);
    }
    Polygon::new(LineString::new(coords), Vec::new())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::diag::ErrorKind;
    use crate::model::Shape;
    use crate::model::layout::testing::{GREEN, layout, rect, shape};
    use geo::Area;

    #[test]
    fn white_shape_cuts_a_hole_and_a_later_colour_fills_it_again() {
        let l = layout(vec![
            shape(GREEN, rect(0.0, 0.0, 100.0, 100.0)),
            shape(Rgb::WHITE, rect(20.0, 20.0, 40.0, 40.0)),
        ]);
        let r = Region::from_layout(&l, 16_000).unwrap();
        assert!((r.area().unsigned_area() - (10_000.0 - 1_600.0)).abs() < 1e-9);
        assert!(r.covers_point(Point::new(10.0, 10.0)));
        assert!(!r.covers_point(Point::new(40.0, 40.0)));
        // A segment crossing the hole is not inside; one beside it is.
        assert!(!r.segment_inside(Point::new(10.0, 40.0), Point::new(70.0, 40.0), true));
        assert!(r.segment_inside(Point::new(10.0, 10.0), Point::new(10.0, 90.0), true));

        let mut shapes = l.shapes.clone();
        shapes.push(shape(GREEN, rect(30.0, 30.0, 10.0, 10.0)));
        let r = Region::from_layout(&layout(shapes), 16_000).unwrap();
        assert!((r.area().unsigned_area() - (10_000.0 - 1_600.0 + 100.0)).abs() < 1e-9);
        assert!(r.covers_point(Point::new(35.0, 35.0)));
    }

    /// The vertex limit counts each shape's ring with the area painted so
    /// far before an overlay runs, and the area after the last shape.
    #[test]
    fn the_vertex_limit_counts_shapes_and_the_painted_area() {
        let limit_of = |e: Diagnostics| match &e.iter().next().unwrap().kind {
            ErrorKind::Limit { value, limit, .. } => (value.clone(), limit.to_string()),
            k => panic!("not a limit: {k:?}"),
        };
        // A 12-gon: 12 vertices fit 12, not 11.
        let gon = |n: usize| {
            Shape::Polygon(
                (0..n)
                    .map(|i| {
                        let t = std::f64::consts::TAU * i as f64 / n as f64;
                        (50.0 + 40.0 * libm::cos(t), 50.0 + 40.0 * libm::sin(t))
                    })
                    .collect(),
            )
        };
        let one = layout(vec![shape(GREEN, gon(12))]);
        assert!(Region::from_layout(&one, 12).is_ok());
        assert_eq!(
            limit_of(Region::from_layout(&one, 11).unwrap_err()),
            ("12".into(), "11".into())
        );
        // Two overlapping squares (4 + 4 vertices) paint an octagon with
        // corners (0,0) (20,0) (20,10) (30,10) (30,30)
        // (10,30) (10,20) (0,20), 8 vertices. Limit 8 holds; limit 7
        // refuses the second square before the union (4 + 4 = 8 > 7).
        let two = layout(vec![
            shape(GREEN, rect(0.0, 0.0, 20.0, 20.0)),
            shape(GREEN, rect(10.0, 10.0, 20.0, 20.0)),
        ]);
        assert_eq!(Region::from_layout(&two, 8).unwrap().edge_count(), 8);
        assert_eq!(
            limit_of(Region::from_layout(&two, 7).unwrap_err()),
            ("8".into(), "7".into())
        );
        // Two crossing bars (4 + 4) paint a plus of 12 vertices: the
        // inputs fit 8, the result does not.
        let plus = layout(vec![
            shape(GREEN, rect(0.0, 10.0, 30.0, 10.0)),
            shape(GREEN, rect(10.0, 0.0, 10.0, 30.0)),
        ]);
        assert_eq!(
            limit_of(Region::from_layout(&plus, 8).unwrap_err()),
            ("12".into(), "8".into())
        );
        assert_eq!(Region::from_layout(&plus, 12).unwrap().edge_count(), 12);
    }

    #[test]
    fn layout_that_cancels_is_an_error() {
        let l = layout(vec![
            shape(GREEN, rect(10.0, 10.0, 10.0, 10.0)),
            shape(Rgb::WHITE, rect(0.0, 0.0, 50.0, 50.0)),
        ]);
        let e = Region::from_layout(&l, 16_000).unwrap_err();
        assert_eq!(
            e.first_kind(),
            Some(&ErrorKind::Layout(LayoutError::EmptyRegion))
        );
        let only_white = layout(vec![shape(Rgb::WHITE, rect(0.0, 0.0, 5.0, 5.0))]);
        let e = Region::from_layout(&only_white, 16_000).unwrap_err();
        assert_eq!(
            e.first_kind(),
            Some(&ErrorKind::Layout(LayoutError::EmptyRegion))
        );
    }

    #[test]
    fn segment_touching_the_boundary_is_not_inside() {
        let r = Region::from_layout(
            &layout(vec![shape(GREEN, rect(0.0, 0.0, 10.0, 10.0))]),
            16_000,
        )
        .unwrap();
        assert!(r.segment_inside(Point::new(5.0, 5.0), Point::new(5.0, 9.0), false));
        assert!(!r.segment_inside(Point::new(5.0, 5.0), Point::new(5.0, 10.0), false));
        assert!(!r.segment_inside(Point::new(5.0, 5.0), Point::new(5.0, 12.0), false));
        // Wholly outside, touching nothing: decided by the start point.
        assert!(!r.segment_inside(Point::new(20.0, 5.0), Point::new(25.0, 5.0), false));
        // As drawn: a stem 1 from the right edge fits 2 wide (r = 1), not
        // 2.2 wide; its round cap counts too (the end 1 from the top).
        let (a, b) = (Point::new(9.0, 5.0), Point::new(9.0, 8.0));
        assert!(r.capsule_inside(a, b, 1.0, false));
        assert!(!r.capsule_inside(a, b, 1.1, false));
        let (a, b) = (Point::new(5.0, 5.0), Point::new(5.0, 9.0));
        assert!(r.capsule_inside(a, b, 1.0, false));
        assert!(!r.capsule_inside(a, b, 1.01, false));
    }

    #[test]
    fn self_intersecting_polygon_is_even_odd() {
        // A pentagram: its centre is outside under the even-odd rule.
        let pts: Vec<(f64, f64)> = (0..5)
            .map(|i| {
                let t = std::f64::consts::FRAC_PI_2 + (i as f64) * 4.0 * std::f64::consts::PI / 5.0;
                (50.0 + 40.0 * libm::cos(t), 50.0 - 40.0 * libm::sin(t))
            })
            .collect();
        let r =
            Region::from_layout(&layout(vec![shape(GREEN, Shape::Polygon(pts))]), 16_000).unwrap();
        assert!(!r.covers_point(Point::new(50.0, 50.0)));
        // A point inside one of the star's tips is inside.
        assert!(r.covers_point(Point::new(50.0, 15.0)));
    }
}
