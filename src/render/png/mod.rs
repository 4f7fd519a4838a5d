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
//! Wide strokes (two pixels or more) cost their area: a path holds at most
//! `INK_PER_BATCH` images' worth of ink, so overlapping thick stems never
//! crowd one path's scanlines with thousands of edges, and a wide capsule
//! drawn again exactly where it was just drawn is skipped (one path would
//! have unioned it away), so 50,000 copies of one stem cost one.
//!
//! At a level of detail ([`Turtle::detail`], asked for with
//! [`PngTurtle::with_detail`]) the drawing hands over stand-ins for
//! sub-pixel subtrees ([`Turtle::blot`]): sparse ones are drawn as ordinary
//! segments, dense ones as blots: anti-aliased capsules [`BLOT_EXTRA_PX`]
//! wider than the stems, painted straight into the raster by distance
//! (tiny-skia's stroker costs about 4 us a blot, the stamp a few dozen
//! pixel blends; docs/rendering.md, *Level of detail*). Blots and segments
//! are one colour, source-over, so the order in which they land does not
//! matter.
//!
//! It does not decide sizes or widths: [`Fit`] and [`stroke_px`] in the
//! parent module do. Its sections mirror `svg.rs`, so the two read side by side.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, Path, PathBuilder, Pixmap, Stroke, Transform,
};

use super::{
    BATCH_SEGMENTS, BLOT_DENSITY, BLOT_EXTRA_PX, FOLD_PX, Fit, SPREAD_EXTRA_PX, SPREAD_MIN_PX,
    Style, Width, stroke_px,
};
use crate::color::Rgb;
use crate::diag::Diagnostics;
use crate::diag::{Diagnostic, RenderError};
use crate::turtle::Fill;
use crate::turtle::{Point, Segment, Turtle};

mod raster;

use raster::Recent;

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
    /// Pixels the batch's strokes cover, overlaps counted again.
    batch_ink: f64,
    /// Largest `batch_ink` of one path ([`INK_PER_BATCH`] images' worth).
    max_ink: f64,
    /// The last wide capsules drawn: a repeat of one is skipped.
    recent: Recent,
    /// Paths stroked so far (tests count the work with it).
    paths: u64,
    /// Where the last segment ended (canvas units), to extend subpaths.
    last_to: Option<Point>,
    /// The open subpath's pen, `None` when no subpath is open.
    pen: Option<Pen>,
    /// Level of detail in canvas units ([`Turtle::detail`]), `None`: exact.
    detail: Option<f64>,
    /// The stroke colour, for blots painted straight into the raster.
    ink: Rgb,
    /// A stroke has covered every pixel: the raster is the stroke colour
    /// and nothing drawn later can change it.
    covered: bool,
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
            Diagnostic::error(RenderError::NoRaster {
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
            batch_ink: 0.0,
            max_ink: INK_PER_BATCH * f64::from(fit.width) * f64::from(fit.height),
            recent: Recent::new(),
            paths: 0,
            last_to: None,
            pen: None,
            detail: None,
            ink: style.stroke,
            covered: false,
        })
    }

    /// The same turtle asking for a level of detail of `px` output pixels
    /// (see [`Turtle::detail`]); `None` draws every segment.
    pub fn with_detail(mut self, px: Option<f64>) -> Self {
        self.detail = px.map(|px| px / self.fit.scale);
        self
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
        self.batch_ink = 0.0;
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
            self.paths += 1;
            // Keep the allocation for the next batch.
            self.batch = Path::clear(path);
        }
    }

    /// A stroke covers every pixel: the raster becomes the (opaque) stroke
    /// colour, what is batched is dropped (it is under the stroke), and
    /// every later stroke is skipped (it could only paint that colour
    /// again). The path rasteriser never sees a stroke wider than the
    /// picture many times over.
    fn cover(&mut self) {
        self.batch = PathBuilder::new();
        self.batch_len = 0;
        self.batch_ink = 0.0;
        self.pen = None;
        self.last_to = None;
        self.pixmap.fill(color(self.ink));
        self.covered = true;
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
            Diagnostic::error(RenderError::PngEncoding {
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
    fn detail(&self) -> Option<f64> {
        self.detail
    }

    fn blot(&mut self, seg: Segment, density: f64) {
        if self.covered {
            return;
        }
        if density < BLOT_DENSITY {
            self.segment(seg);
            return;
        }
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y].iter().all(|v| v.is_finite()) {
            return;
        }
        let radius = (stroke_px(&self.width, self.fit.scale, seg.order) + BLOT_EXTRA_PX) / 2.0;
        raster::stamp(&mut self.pixmap, self.ink, from, to, radius);
    }

    fn blot_spread(&mut self, seg: Segment, density: f64, spread: f64) {
        if self.covered {
            return;
        }
        let spread = spread * self.fit.scale;
        if density < BLOT_DENSITY && spread < SPREAD_MIN_PX {
            self.segment(seg);
            return;
        }
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y, spread]
            .iter()
            .all(|v| v.is_finite())
        {
            return;
        }
        let stroke = stroke_px(&self.width, self.fit.scale, seg.order);
        raster::stamp(
            &mut self.pixmap,
            self.ink,
            from,
            to,
            stroke / 2.0 + spread + SPREAD_EXTRA_PX * (1.0 - 1.0 / libm::sqrt(density.max(1.0))),
        );
    }

    fn segment(&mut self, seg: Segment) {
        if self.covered {
            return;
        }
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y].iter().all(|v| v.is_finite()) {
            // Nothing sensible to draw; the SVG backend skips it too.
            return;
        }
        let width = stroke_px(&self.width, self.fit.scale, seg.order);
        if width / 2.0 >= raster::farthest_corner(&self.pixmap, from, to) {
            self.cover();
            return;
        }
        let width = width.min(MAX_STROKE_PX);
        if width >= WIDE_PX {
            // A wide stroke costs its area in pixels; drawing the very same
            // capsule again adds nothing (one path would union it away).
            if self.recent.repeats(from, to, width) {
                return;
            }
        }
        // Only wide strokes count towards a path's ink: hairlines cost
        // little however they overlap, and skip the length on the hot path
        // of deep L-systems.
        let ink = if width >= WIDE_PX {
            width * (libm::hypot(to.x - from.x, to.y - from.y) + width)
        } else {
            0.0
        };
        if self.batch_len >= BATCH_SEGMENTS
            || (self.batch_len > 0
                && (width != self.batch_width || self.batch_ink + ink > self.max_ink))
        {
            self.flush();
        }
        self.batch_ink += ink;
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

/// Strokes at least this wide (output pixels) are checked against the
/// recently drawn ones: their cost is their area, and a thick tree that
/// draws the same stem many times (50,000 terms at one point) would pay it
/// each time. Thinner strokes are cheap and are not checked.
const WIDE_PX: f64 = 2.0;

/// The widest stroke handed to the rasteriser, in pixels. A wider stroke
/// that covers the whole raster paints it all ([`PngTurtle::cover`]); one
/// that does not (its segment lies more than half this far outside the
/// picture) is drawn this wide. tiny-skia 0.12 panics on strokes around
/// 10^10 pixels wide (found by the `lsys_render` fuzz body; 10^9 draws).
const MAX_STROKE_PX: f64 = 1.0e6;

/// Most ink one path may hold, in images' worth of pixels. tiny-skia
/// rasterizes a path's strokes together, and the edges of many overlapping
/// wide strokes crowd every scanline (the cost grows with their square);
/// a path that covers the picture several times over is drawn and a new
/// one started.
const INK_PER_BATCH: f64 = 2.0;

/// An opaque tiny-skia colour.
fn color(c: Rgb) -> Color {
    Color::from_rgba8(c.r, c.g, c.b, 255)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::Style;

    fn turtle() -> PngTurtle {
        wide_turtle(1.0)
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

    /// A blot is a capsule painted by distance: full ink within its
    /// radius less half a pixel, half at its radius, none a pixel out;
    /// two blots accumulate. A sparse stand-in is an ordinary segment.
    #[test]
    fn blots_paint_by_distance_and_accumulate() {
        // Stems 1 px, so blots are 2 px wide: radius 1 around (10.5, 10.5).
        let mut t = turtle();
        let dot = stem(10.5, 10.5, 10.5, 10.5);
        t.blot(dot, 5.0);
        let p = t.into_pixmap();
        let at = |p: &Pixmap, x, y| p.pixel(x, y).unwrap().red();
        assert_eq!(at(&p, 10, 10), 0, "centre: full ink");
        // Centre 1 px away: coverage 0.5, 255 * (1 - 128/255) rounded.
        assert_eq!(at(&p, 11, 10), 127);
        assert_eq!(at(&p, 10, 9), 127);
        assert_eq!(at(&p, 12, 10), 255, "1.5 px out: untouched");
        let mut twice = turtle();
        twice.blot(dot, 5.0);
        twice.blot(dot, 5.0);
        assert_eq!(at(&twice.into_pixmap(), 11, 10), 63, "source-over twice");
        // Density under BLOT_DENSITY: a 1 px hairline segment, not a blot.
        let mut sparse = turtle();
        sparse.blot(stem(20.0, 10.5, 40.0, 10.5), 1.0);
        assert_eq!(sparse.paths, 0);
        sparse.flush();
        assert_eq!(sparse.paths, 1);
        let p = sparse.into_pixmap();
        assert!(at(&p, 30, 10) < 128 && at(&p, 30, 12) == 255);
    }

    fn wide_turtle(width: f64) -> PngTurtle {
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
            width: Width::Pixels(width),
        };
        PngTurtle::new(fit, &style).unwrap()
    }

    fn stem(ax: f64, ay: f64, bx: f64, by: f64) -> Segment {
        Segment {
            from: Point::new(ax, ay),
            to: Point::new(bx, by),
            order: 0,
        }
    }

    /// A stroke wider than the picture many times over (tiny-skia 0.12
    /// panics near 10^10 px) paints every pixel the stroke colour, with no
    /// path stroked, and later strokes change nothing. One whose half
    /// width falls short of the farthest corner is a real stroke: a 100 x
    /// 100 raster's farthest corner from the point (50, 50) is 70.7 px away.
    #[test]
    fn a_stroke_wider_than_the_picture_covers_it_without_the_rasteriser() {
        let all = |p: &Pixmap, v: u8| {
            (0..100).all(|y| (0..100).all(|x| p.pixel(x, y).unwrap().red() == v))
        };
        for width in [1.0e10, 1.0e300, 142.0] {
            let mut t = wide_turtle(width);
            t.segment(stem(50.0, 50.0, 50.0, 50.0));
            t.segment(stem(10.0, 10.0, 20.0, 20.0));
            assert_eq!(t.paths, 0, "{width}");
            assert!(t.covered);
            assert!(all(&t.into_pixmap(), 0), "{width}: all stroke colour");
        }
        let mut t = wide_turtle(140.0);
        t.segment(stem(50.0, 50.0, 50.0, 50.0));
        assert!(!t.covered, "70 < 70.7: a stroke");
        t.flush();
        assert_eq!(t.paths, 1);
        let mut t = wide_turtle(130.0);
        t.segment(stem(50.0, 50.0, 50.0, 50.0));
        let p = t.into_pixmap();
        // The corner pixel's centre is 70.0 px from (50, 50), 5 px out.
        assert_eq!(p.pixel(0, 0).unwrap().red(), 255);
        assert_eq!(p.pixel(50, 50).unwrap().red(), 0);
        // Far outside the picture, too far to reach it even 10^10 px wide:
        // drawn at the widest the rasteriser takes, and nothing panics.
        let mut t = wide_turtle(1.0e10);
        t.segment(stem(1.0e11, 0.0, 1.0e11, 10.0));
        assert!(!t.covered);
        assert!(all(&t.into_pixmap(), 255));
    }

    /// One path unions its strokes, so the same wide stem drawn 10,000 times
    /// (more than a batch) paints exactly what drawing it once paints, and
    /// is stroked once.
    #[test]
    fn a_repeated_wide_stem_paints_what_one_paints_and_is_stroked_once() {
        let mut once = wide_turtle(12.0);
        once.segment(stem(20.0, 80.0, 70.0, 30.0));
        let mut many = wide_turtle(12.0);
        for _ in 0..10_000 {
            many.segment(stem(20.0, 80.0, 70.0, 30.0));
            many.segment(stem(70.0, 30.0, 60.0, 10.0));
        }
        many.flush();
        assert_eq!(many.paths, 1);
        let mut twice = wide_turtle(12.0);
        twice.segment(stem(20.0, 80.0, 70.0, 30.0));
        twice.segment(stem(70.0, 30.0, 60.0, 10.0));
        assert_eq!(many.into_pixmap(), twice.into_pixmap());
        assert_ne!(
            once.into_pixmap().data(),
            wide_turtle(12.0).into_pixmap().data()
        );
    }

    /// Overlapping wide strokes are split into paths of at most
    /// INK_PER_BATCH images' worth of ink: 100 x 100 px allows 20,000 px;
    /// each 90 px stroke 10 px wide counts 10 x (90 + 10) = 1,000, so 20 go
    /// in a path and 100 distinct strokes make 5 paths.
    #[test]
    fn overlapping_wide_strokes_are_drawn_in_paths_of_bounded_ink() {
        let mut t = wide_turtle(10.0);
        for i in 0..100 {
            let x = 5.0 + f64::from(i) * 0.5;
            t.segment(stem(x, 5.0, x, 95.0));
        }
        t.flush();
        assert_eq!(t.paths, 5);
        // Hairlines never count as wide: 100 of them go in one path.
        let mut h = turtle();
        for i in 0..100 {
            let x = 5.0 + f64::from(i) * 0.5;
            h.segment(stem(x, 5.0, x, 95.0));
        }
        h.flush();
        assert_eq!(h.paths, 1);
    }
}
