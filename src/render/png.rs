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
//! It does not decide sizes or widths: [`Fit`] and [`stroke_px`] in the
//! parent module do. Its sections mirror `svg.rs`, so the two read side by side.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, Path, PathBuilder, Pixmap, Stroke, Transform,
};

use super::{BATCH_SEGMENTS, Fill, Fit, Style, Width, render_error, stroke_px};
use crate::color::Rgb;
use crate::diag::Diagnostics;
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
}

impl PngTurtle {
    /// A `fit.width` x `fit.height` raster filled with the background
    /// (transparent when there is none).
    pub fn new(fit: Fit, style: &Style) -> Result<PngTurtle, Diagnostics> {
        let mut pixmap = Pixmap::new(fit.width, fit.height).ok_or_else(|| {
            render_error(format!("cannot make a {}x{} raster", fit.width, fit.height))
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

    // -----------------------------------------------------------------------
    // Output

    /// Strokes what is left and encodes the raster as PNG bytes.
    pub fn finish(mut self) -> Result<Vec<u8>, Diagnostics> {
        self.flush();
        self.pixmap
            .encode_png()
            .map_err(|e| render_error(format!("cannot encode the PNG image: {e}")).into())
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
            self.batch.move_to(from.x as f32, from.y as f32);
        }
        self.batch.line_to(to.x as f32, to.y as f32);
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
