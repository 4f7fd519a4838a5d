//! Layout geometry shared by growth and rendering: each shape's closed ring
//! (curves flattened), the fills the renderer paints, and the canvas view a
//! layout defines.
//!
//! Growth builds its region from these rings (`grow::region`), and the
//! renderer paints exactly the same rings, so the picture and the region
//! agree. Nothing here knows geo or the spatial index.

use crate::model::{Layout, Shape};
use crate::turtle::{BBox, Fill, Point};

/// Largest distance, in canvas units, between a flattened curve (rounded
/// corner, ellipse) and the true curve. The flattened polygon's vertices lie
/// on the curve, so the polygon lies inside it.
pub const FLATTEN_TOLERANCE: f64 = 0.05;

/// Most segments a quarter of a curve is flattened into; reached only for
/// radii above about 1.2 million canvas units, where the deviation then
/// exceeds [`FLATTEN_TOLERANCE`].
pub const MAX_SEGMENTS_PER_QUARTER: usize = 4096;

/// The closed polygon of a layout shape, canvas units, in drawing order; the
/// first point is not repeated at the end. Rectangles give their 4 corners,
/// polygons their points as written (a repeated closing point dropped),
/// rounded rectangles and ellipses their flattening (see
/// [`FLATTEN_TOLERANCE`]). Corner radii larger than half the side are
/// clamped to half the side, as Windows' `RoundRect` (the paper's) does.
pub fn shape_ring(shape: &Shape) -> Vec<Point> {
    match *shape {
        Shape::Rect { x, y, w, h } => rect_ring(x, y, w, h),
        Shape::RoundRect { x, y, w, h, rx, ry } => {
            let rx = rx.min(w / 2.0);
            let ry = ry.min(h / 2.0);
            if rx.is_nan() || ry.is_nan() || rx <= 0.0 || ry <= 0.0 {
                return rect_ring(x, y, w, h);
            }
            let q = quarter(rx, ry);
            // Corner centres, and the quarter each corner uses, going round
            // clockwise on screen from the top-right corner.
            let corners = [
                (x + w - rx, y + ry, 1.0, -1.0),    // top right
                (x + w - rx, y + h - ry, 1.0, 1.0), // bottom right
                (x + rx, y + h - ry, -1.0, 1.0),    // bottom left
                (x + rx, y + ry, -1.0, -1.0),       // top left
            ];
            let mut ring = Vec::with_capacity(4 * q.len());
            for (i, &(cx, cy, sx, sy)) in corners.iter().enumerate() {
                // Top-right and bottom-left run from the vertical axis to the
                // horizontal one; the other two the other way round.
                let forward = i % 2 == 1;
                for j in 0..q.len() {
                    let (c, s) = if forward { q[j] } else { q[q.len() - 1 - j] };
                    push_distinct(&mut ring, Point::new(cx + sx * rx * c, cy + sy * ry * s));
                }
            }
            dedup_closing(&mut ring);
            ring
        }
        Shape::Ellipse { x, y, w, h } => {
            let (rx, ry) = (w / 2.0, h / 2.0);
            let (cx, cy) = (x + rx, y + ry);
            let q = quarter(rx, ry);
            let n = q.len() - 1; // points per quarter without its end
            let mut ring = Vec::with_capacity(4 * n);
            // (cos, sin) of the quarter, mirrored into the four quadrants so
            // the polygon is exactly symmetric.
            let up = &q[..n]; // 0 to just before 90 degrees
            let down = || q[1..].iter().rev(); // 90 down to just after 0
            ring.extend(
                up.iter()
                    .map(|&(c, s)| Point::new(cx + rx * c, cy - ry * s)),
            );
            ring.extend(down().map(|&(c, s)| Point::new(cx - rx * c, cy - ry * s)));
            ring.extend(
                up.iter()
                    .map(|&(c, s)| Point::new(cx - rx * c, cy + ry * s)),
            );
            ring.extend(down().map(|&(c, s)| Point::new(cx + rx * c, cy + ry * s)));
            ring
        }
        Shape::Polygon(ref pts) => {
            let mut ring: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
            dedup_closing(&mut ring);
            ring
        }
    }
}

/// The layout as the renderer paints it (`--show-layout`): one [`Fill`] per
/// shape, in painting order, white ones included so the holes show.
pub fn fills(layout: &Layout) -> Vec<Fill> {
    layout
        .shapes
        .iter()
        .map(|s| Fill {
            color: s.color,
            rings: vec![shape_ring(&s.shape)],
        })
        .collect()
}

/// The bounding box of every layout shape, white ones included (the whole
/// painted canvas); `None` for a layout without shapes.
pub fn layout_bbox(layout: &Layout) -> Option<BBox> {
    let mut bbox: Option<BBox> = None;
    for s in &layout.shapes {
        for p in shape_ring(&s.shape) {
            match &mut bbox {
                Some(b) => b.add(p),
                None => bbox = Some(BBox::at(p)),
            }
        }
    }
    bbox
}

fn rect_ring(x: f64, y: f64, w: f64, h: f64) -> Vec<Point> {
    vec![
        Point::new(x, y),
        Point::new(x + w, y),
        Point::new(x + w, y + h),
        Point::new(x, y + h),
    ]
}

/// `(cos t, sin t)` for `t` from 0 to 90 degrees in equal steps, both ends
/// included and exact, with as many steps as keep the chord's deviation from
/// an ellipse of radii `rx`, `ry` within [`FLATTEN_TOLERANCE`]. The ellipse is
/// an affine image of the unit circle, so the circle's sagitta scaled by the
/// larger radius bounds the deviation.
fn quarter(rx: f64, ry: f64) -> Vec<(f64, f64)> {
    let r = rx.max(ry);
    let n = if r <= FLATTEN_TOLERANCE || r.is_nan() {
        1
    } else {
        // sagitta r * (1 - cos(step / 2)) <= tol
        let step = 2.0 * libm::acos(1.0 - FLATTEN_TOLERANCE / r);
        let n = (std::f64::consts::FRAC_PI_2 / step).ceil();
        if n.is_finite() {
            (n as usize).clamp(1, MAX_SEGMENTS_PER_QUARTER)
        } else {
            MAX_SEGMENTS_PER_QUARTER
        }
    };
    (0..=n)
        .map(|j| {
            if j == 0 {
                (1.0, 0.0)
            } else if j == n {
                (0.0, 1.0)
            } else {
                let t = std::f64::consts::FRAC_PI_2 * (j as f64) / (n as f64);
                (libm::cos(t), libm::sin(t))
            }
        })
        .collect()
}

fn push_distinct(ring: &mut Vec<Point>, p: Point) {
    if ring.last() != Some(&p) {
        ring.push(p);
    }
}

fn dedup_closing(ring: &mut Vec<Point>) {
    while ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::model::layout::testing::{GREEN, layout, rect, shape};

    /// The area of a simple closed ring (the shoelace formula).
    fn area(ring: &[Point]) -> f64 {
        let n = ring.len();
        let twice: f64 = (0..n)
            .map(|i| {
                let (a, b) = (ring[i], ring[(i + 1) % n]);
                a.x * b.y - b.x * a.y
            })
            .sum();
        twice.abs() / 2.0
    }

    #[test]
    fn ellipse_is_flattened_within_tolerance_and_symmetric() {
        for &(w, h) in &[(200.0, 100.0), (3.0, 3.0), (1000.0, 40.0)] {
            let ring = shape_ring(&Shape::Ellipse {
                x: 0.0,
                y: 0.0,
                w,
                h,
            });
            assert_eq!(ring.len() % 4, 0);
            let (rx, ry) = (w / 2.0, h / 2.0);
            // Vertices on the curve.
            for p in &ring {
                let u = (p.x - rx) / rx;
                let v = (p.y - ry) / ry;
                assert!((u * u + v * v - 1.0).abs() < 1e-12);
            }
            // Mid-chord points within the tolerance of the curve: sample the
            // curve densely and take the distance to the nearest chord midpoint
            // of the same arc (chord midpoints are the farthest points).
            for i in 0..ring.len() {
                let a = ring[i];
                let b = ring[(i + 1) % ring.len()];
                let m = Point::new((a.x + b.x) / 2.0, (a.y + b.y) / 2.0);
                // Radial distance from the curve, scaled: an upper bound.
                let u = (m.x - rx) / rx;
                let v = (m.y - ry) / ry;
                let k = (u * u + v * v).sqrt();
                let dev = (1.0 - k) * rx.max(ry);
                assert!(dev <= FLATTEN_TOLERANCE + 1e-9, "deviation {dev}");
            }
        }
    }

    #[test]
    fn round_rect_area_close_to_the_true_one() {
        let (w, h, r) = (180.0, 192.0, 7.0);
        let ring = shape_ring(&Shape::RoundRect {
            x: 0.0,
            y: 0.0,
            w,
            h,
            rx: r,
            ry: r,
        });
        let a = area(&ring);
        let exact = w * h - (4.0 - std::f64::consts::PI) * r * r;
        assert!(
            a < exact && exact - a < 0.05 * 4.0 * 2.0 * r,
            "{a} vs {exact}"
        );
        // Clamped radii: a full stadium never exceeds its box.
        let ring = shape_ring(&Shape::RoundRect {
            x: 0.0,
            y: 0.0,
            w: 10.0,
            h: 4.0,
            rx: 50.0,
            ry: 50.0,
        });
        assert!(
            ring.iter()
                .all(|p| p.x >= 0.0 && p.x <= 10.0 && p.y >= 0.0 && p.y <= 4.0)
        );
    }

    #[test]
    fn fills_keep_painting_order_and_white() {
        let l = layout(vec![
            shape(GREEN, rect(0.0, 0.0, 100.0, 100.0)),
            shape(Rgb::WHITE, rect(20.0, 20.0, 40.0, 40.0)),
        ]);
        let f = fills(&l);
        assert_eq!(f.len(), 2);
        assert_eq!(f[1].color, Rgb::WHITE);
        assert_eq!(f[1].rings[0].len(), 4);
        let b = layout_bbox(&l).unwrap();
        assert_eq!(
            (b.min_x, b.min_y, b.max_x, b.max_y),
            (0.0, 0.0, 100.0, 100.0)
        );
    }
}
