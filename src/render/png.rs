//! PNG backend (tiny-skia).
//!
//! [`PngTurtle`] paints onto a [`tiny_skia::Pixmap`] of the fitted size:
//! background, then the underlay ([`Fill`]s, even-odd), then the segments as
//! anti-aliased strokes with round caps and joins. Segments are batched into
//! one path per stroke width, flushed every [`BATCH_SEGMENTS`] segments and
//! on every width change, so millions of segments stream through in bounded
//! memory; a segment that starts where the previous one ended extends the
//! current subpath (so a polyline gets proper joins).
//!
//! Along such a run, vertices closer than [`FOLD_PX`] to the last vertex
//! written are folded away (the run's exact end is always written): a deep
//! L-system streams tens of millions of segments of a hundredth of a pixel,
//! and tiny-skia's stroking cost is per segment. Runs are never joined
//! across a jump, so every subpath keeps its own round caps.
//!
//! It does not decide sizes or widths: [`Fit`] and [`stroke_px`] in the
//! parent module do. Its sections mirror `svg.rs`, so the two read side by side.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, Path, PathBuilder, Pixmap, Stroke, Transform,
};

use super::{BATCH_SEGMENTS, FOLD_PX, Fit, Style, Width, stroke_px};
use crate::color::Rgb;
use crate::diag::Diagnostics;
use crate::diag::{Diagnostic, ErrorKind};
use crate::turtle::Fill;
use crate::turtle::{Point, Segment, Turtle};

// ---------------------------------------------------------------------------
// Canvas

/// A turtle that paints onto a raster and encodes it as PNG.
pub struct PngTurtle {
    pixmap: Pixmap,
    fit: Fit,
    width: Width,
    paint: Paint<'static>,
    /// The path being collected: all its segments share `batch_width`.
    batch: PathBuilder,
    batch_width: f64,
    batch_len: usize,
    /// Where the last segment ended (canvas units), to extend subpaths.
    last_to: Option<Point>,
    /// The open subpath's pen, `None` when no subpath is open.
    pen: Option<Pen>,
}

/// The pen of the open subpath, in output pixels, for [`FOLD_PX`] folding.
#[derive(Debug, Clone, Copy)]
struct Pen {
    /// The last vertex written into the path.
    kept: Point,
    /// Where the pen is: the end of the last segment.
    at: Point,
    /// `at` is not written yet (it is closer than [`FOLD_PX`] to `kept`).
    pending: bool,
}

impl PngTurtle {
    /// A `fit.width` x `fit.height` raster filled with the background
    /// (transparent when there is none).
    pub fn new(fit: Fit, style: &Style) -> Result<PngTurtle, Diagnostics> {
        let mut pixmap = Pixmap::new(fit.width, fit.height).ok_or_else(|| {
            Diagnostic::error(ErrorKind::NoRaster {
                width: fit.width,
                height: fit.height,
            })
            .with_help("ask for a smaller `--size`")
        })?;
        if let Some(bg) = style.background {
            pixmap.fill(color(bg));
        }
        let mut paint = Paint::default();
        paint.set_color(color(style.stroke));
        paint.anti_alias = true;
        Ok(PngTurtle {
            pixmap,
            fit,
            width: style.width,
            paint,
            batch: PathBuilder::new(),
            batch_width: 0.0,
            batch_len: 0,
            last_to: None,
            pen: None,
        })
    }

    // -----------------------------------------------------------------------
    // Underlay

    /// Paints a filled area (a layout shape) with the even-odd rule. Call
    /// before drawing segments: it paints over whatever is there.
    pub fn fill(&mut self, fill: &Fill) {
        self.flush();
        let mut pb = PathBuilder::new();
        for ring in &fill.rings {
            let mut points = ring.iter().map(|&p| self.fit.map(p));
            if let Some(first) = points.next() {
                pb.move_to(first.x as f32, first.y as f32);
                for p in points {
                    pb.line_to(p.x as f32, p.y as f32);
                }
                pb.close();
            }
        }
        if let Some(path) = pb.finish() {
            let mut paint = Paint::default();
            paint.set_color(color(fill.color));
            paint.anti_alias = true;
            self.pixmap.fill_path(
                &path,
                &paint,
                FillRule::EvenOdd,
                Transform::identity(),
                None,
            );
        }
    }

    // -----------------------------------------------------------------------
    // Strokes

    /// Strokes the collected path and starts an empty one.
    fn flush(&mut self) {
        self.end_subpath();
        let batch = std::mem::take(&mut self.batch);
        self.batch_len = 0;
        self.last_to = None;
        if let Some(path) = batch.finish() {
            let stroke = Stroke {
                width: self.batch_width as f32,
                line_cap: LineCap::Round,
                line_join: LineJoin::Round,
                ..Stroke::default()
            };
            self.pixmap
                .stroke_path(&path, &self.paint, &stroke, Transform::identity(), None);
            // Keep the allocation for the next batch.
            self.batch = Path::clear(path);
        }
    }

    /// Ends the open subpath: writes the pen's pending end point, so the
    /// exact end of every run is in the path.
    fn end_subpath(&mut self) {
        if let Some(pen) = self.pen.take()
            && pen.pending
        {
            self.batch.line_to(pen.at.x as f32, pen.at.y as f32);
        }
    }

    /// Moves the pen of the open subpath along a segment to `q` (output
    /// pixels): written as a vertex once it is [`FOLD_PX`] or more from the
    /// last vertex written, else held as the pending end.
    fn pen_to(&mut self, q: Point) {
        let Some(pen) = self.pen.as_mut() else {
            return;
        };
        pen.at = q;
        let (dx, dy) = (q.x - pen.kept.x, q.y - pen.kept.y);
        if dx * dx + dy * dy >= FOLD_PX * FOLD_PX {
            pen.kept = q;
            pen.pending = false;
            self.batch.line_to(q.x as f32, q.y as f32);
        } else {
            pen.pending = true;
        }
    }

    // -----------------------------------------------------------------------
    // Output

    /// Strokes what is left and encodes the raster as PNG bytes.
    pub fn finish(mut self) -> Result<Vec<u8>, Diagnostics> {
        self.flush();
        self.pixmap.encode_png().map_err(|e| {
            Diagnostic::error(ErrorKind::PngEncoding {
                error: e.to_string(),
            })
            .into()
        })
    }

    /// Strokes what is left and hands back the raster (for tests and
    /// callers that want pixels, not bytes).
    pub fn into_pixmap(mut self) -> Pixmap {
        self.flush();
        self.pixmap
    }
}

impl Turtle for PngTurtle {
    fn segment(&mut self, seg: Segment) {
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y].iter().all(|v| v.is_finite()) {
            // Nothing sensible to draw; the SVG backend skips it too.
            return;
        }
        let width = stroke_px(&self.width, self.fit.scale, seg.order);
        if self.batch_len >= BATCH_SEGMENTS || (self.batch_len > 0 && width != self.batch_width) {
            self.flush();
        }
        self.batch_width = width;
        if self.last_to != Some(seg.from) {
            self.end_subpath();
            self.batch.move_to(from.x as f32, from.y as f32);
            self.pen = Some(Pen {
                kept: from,
                at: from,
                pending: false,
            });
        }
        self.pen_to(to);
        self.batch_len += 1;
        self.last_to = Some(seg.to);
    }
}

// ---------------------------------------------------------------------------
// Helpers

/// An opaque tiny-skia colour.
fn color(c: Rgb) -> Color {
    Color::from_rgba8(c.r, c.g, c.b, 255)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::Style;

    fn turtle() -> PngTurtle {
        let fit = Fit {
            width: 100,
            height: 100,
            scale: 1.0,
            dx: 0.0,
            dy: 0.0,
        };
        let style = Style {
            stroke: Rgb::BLACK,
            background: Some(Rgb::WHITE),
            width: Width::Pixels(1.0),
        };
        PngTurtle::new(fit, &style).unwrap()
    }

    /// Draws a connected run through `points` (output pixels, scale 1).
    fn run(t: &mut PngTurtle, points: &[Point]) {
        for w in points.windows(2) {
            t.segment(Segment {
                from: w[0],
                to: w[1],
                order: 0,
            });
        }
        t.end_subpath();
    }

    #[test]
    fn a_run_of_sub_pixel_segments_folds_to_its_exact_end() {
        // 100 steps of 0.001 px zigzagging right: 0.1 px in all, one line.
        let points: Vec<Point> = (0..=100)
            .map(|i| Point::new(10.0 + f64::from(i) * 0.001, 10.0 + f64::from(i % 2) * 0.01))
            .collect();
        let mut t = turtle();
        run(&mut t, &points);
        assert_eq!(t.batch.len(), 2, "move and one line");
        let end = t.batch.last_point().unwrap();
        assert_eq!((end.x, end.y), (10.1, 10.0));
    }

    #[test]
    fn segments_of_the_tolerance_or_longer_are_all_kept() {
        let points: Vec<Point> = (0..=40)
            .map(|i| Point::new(10.0 + f64::from(i) * FOLD_PX, 20.0 + f64::from(i % 2)))
            .collect();
        let mut t = turtle();
        run(&mut t, &points);
        assert_eq!(t.batch.len(), points.len());
    }

    #[test]
    fn a_long_run_keeps_a_vertex_per_tolerance_and_its_end() {
        // 1000 steps of 0.01 px along a line: 10 px, a vertex every
        // 0.25 px (25 steps; float sums may need one more step).
        let points: Vec<Point> = (0..=1000)
            .map(|i| Point::new(5.0 + f64::from(i) * 0.01, 50.0))
            .collect();
        let mut t = turtle();
        run(&mut t, &points);
        assert!((40..=42).contains(&t.batch.len()), "{}", t.batch.len());
        let end = t.batch.last_point().unwrap();
        assert_eq!((end.x, end.y), (15.0, 50.0));
    }

    #[test]
    fn runs_do_not_fold_across_a_jump() {
        // Two 0.1 px runs 0.05 px apart: two subpaths, both drawn.
        let mut t = turtle();
        run(&mut t, &[Point::new(10.0, 10.0), Point::new(10.1, 10.0)]);
        run(&mut t, &[Point::new(10.15, 10.0), Point::new(10.25, 10.0)]);
        assert_eq!(t.batch.len(), 4);
    }
}
