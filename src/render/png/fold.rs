//! Folding a run of segments into the batch's path (docs/rendering.md,
//! *Level of detail*): along a subpath, vertices closer than [`FOLD_PX`]
//! to the last one written are held back, and a stand-in's chord is folded
//! as the run of segments it stands for.

use super::PngTurtle;
use crate::render::style::FOLD_PX;
use crate::turtle::Point;

impl PngTurtle {
    /// Ends the open subpath: writes the pen's pending end point, so the
    /// exact end of every run is in the path.
    pub(super) fn end_subpath(&mut self) {
        if let Some(pen) = self.pen.take() {
            if pen.pending {
                self.put(pen.at, false);
            }
            if let Some(router) = &mut self.router {
                router.end(self.batch_width as f32);
            }
        }
    }

    /// Writes a vertex of the batch (a subpath's start if `start`).
    #[inline]
    pub(super) fn put(&mut self, p: Point, start: bool) {
        match &mut self.router {
            Some(router) => router.point(p.x as f32, p.y as f32),
            None if start => self.batch.move_to(p.x as f32, p.y as f32),
            None => self.batch.line_to(p.x as f32, p.y as f32),
        }
    }

    /// Moves the pen of the open subpath along a segment to `q` (output
    /// pixels): written as a vertex once it is [`FOLD_PX`] or more from the
    /// last vertex written, else held as the pending end.
    pub(super) fn pen_to(&mut self, q: Point) {
        let Some(pen) = self.pen.as_mut() else {
            return;
        };
        pen.at = q;
        let (dx, dy) = (q.x - pen.kept.x, q.y - pen.kept.y);
        if dx * dx + dy * dy >= FOLD_PX * FOLD_PX {
            pen.kept = q;
            pen.pending = false;
            self.put(q, false);
        } else {
            pen.pending = true;
        }
    }

    /// Moves the pen of the open subpath along a stand-in's chord to `q`
    /// (output pixels), folding it as [`PngTurtle::pen_to`] folds the run
    /// of segments it stands for: a vertex wherever the run is `spacing`
    /// from the last vertex written (the first segment end at least
    /// [`FOLD_PX`] on), not only at the chord's end. Folding at the
    /// chord's end alone would write vertices farther apart than the
    /// exact drawing's, and a hairline drawn in fewer, longer segments is
    /// darker (each segment's coverage of a pixel is blended over the
    /// others').
    pub(super) fn pen_along(&mut self, q: Point, spacing: f64) {
        let Some(mut pen) = self.pen else {
            return;
        };
        let a = pen.at;
        let (dx, dy) = (q.x - a.x, q.y - a.y);
        let d2 = dx * dx + dy * dy;
        if d2 > 0.0 && spacing > 0.0 {
            // The first vertex: where the chord leaves the circle of
            // `spacing` around the last vertex (the larger root; at once if
            // `a` is outside it), then one every `spacing` along the chord.
            let (ax, ay) = (a.x - pen.kept.x, a.y - pen.kept.y);
            let b = ax * dx + ay * dy;
            let c = ax * ax + ay * ay - spacing * spacing;
            let first = ((-b + libm::sqrt((b * b - d2 * c).max(0.0))) / d2).max(0.0);
            let step = spacing / libm::sqrt(d2);
            // A vertex within a billionth of the end is the end, written
            // as the pen's pending point.
            let mut i = 0.0;
            loop {
                let t = first + i * step;
                if t >= 1.0 - 1e-9 {
                    break;
                }
                let v = Point::new(a.x + t * dx, a.y + t * dy);
                if v != pen.kept {
                    self.put(v, false);
                    pen.kept = v;
                }
                i += 1.0;
            }
        }
        pen.at = q;
        pen.pending = pen.kept != q;
        self.pen = Some(pen);
    }
}
