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
//! sub-pixel subtrees ([`Turtle::stand_in`]): sparse ones are drawn as ordinary
//! segments, dense ones as blots: anti-aliased capsules [`BLOT_EXTRA_PX`]
//! wider than the stems, painted straight into the raster by distance
//! (tiny-skia's stroker costs about 4 us a blot, the stamp a few dozen
//! pixel blends; docs/rendering.md, *Level of detail*). A bush's stand-in
//! ([`Turtle::stand_in`] with a footprint) is painted with the ink its strokes leave on
//! average over its footprint (`raster::Bush`); a connected run's
//! ([`Turtle::run`]) is folded as the run it stands for and broken where
//! the exact drawing would start a new path (docs/rendering.md,
//! *Silhouette*). Blots and segments are one colour, source-over, so the
//! order in which they land does not matter.
//!
//! It does not decide sizes or widths: [`Fit`] and [`stroke_px`] in the
//! parent module do. Its sections mirror `svg.rs`, so the two read side by side.

use tiny_skia::{FillRule, Paint, Path, PathBuilder, Pixmap};

pub use bands::BAND_ROWS;

use super::fit::{Fit, stroke_px};
use super::style::{
    BATCH_SEGMENTS, BLOT_DENSITY, BLOT_EXTRA_PX, FOLD_PX, SPREAD_MIN_PX, Style, Width,
};
use crate::color::Rgb;
use crate::diag::Diagnostics;
use crate::diag::{Diagnostic, Help, Knob, RenderError};
use crate::turtle::Fill;
use crate::turtle::{Footprint, Point, Sample, Segment, StandIn, Turtle};

mod bands;
mod field;
mod fold;
mod full;
mod organs;
mod pen;
mod raster;
mod repeat;
mod sample;
mod tiles;

use bands::{Canvas, Ink, Op, Router, color};
use pen::Pen;
use raster::{Bush, Recent, Shape};

// ---------------------------------------------------------------------------
// Canvas

/// A turtle that paints onto a raster and encodes it as PNG.
pub struct PngTurtle {
    /// The raster, whole or in bands, or the band threads' queues.
    canvas: Canvas,
    fit: Fit,
    width: Width,
    /// The stroke paint and colour.
    ink: Ink,
    /// Blots not yet handed to the bands (banded canvases only).
    blots: Vec<raster::Blot>,
    /// Banded canvases: the batch being split into the bands' paths (in
    /// place of `batch`).
    router: Option<Router>,
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
    /// The raster's shorter side (a little less), in pixels.
    short_side: f64,
    /// A stroke has covered every pixel: the raster is the stroke colour
    /// and nothing drawn later can change it.
    covered: bool,
    /// Segments drawn or stood for so far (at a level of detail, where
    /// the exact drawing would be in its batches).
    stood: f64,
    /// The bushes sampled so far ([`Turtle::stand_in`] with a sample); `None` in a bush's
    /// own sample, whose bushes are modelled.
    fields: Option<field::Fields>,
    /// Whether [`Turtle::dense`] may draw a piece whole (not in a
    /// sample's own drawing).
    dense: bool,
    /// The raster's tiles found full ink ([`Turtle::covered`]).
    full: tiles::Full,
    /// What the raster (or each band painted here) was stroked with lately.
    repeats: Vec<repeat::Repeats>,
}

impl PngTurtle {
    /// A `fit.width` x `fit.height` raster filled with the background
    /// (transparent when there is none), painted whole.
    pub fn new(fit: Fit, style: &Style) -> Result<PngTurtle, Diagnostics> {
        Ok(PngTurtle::on(
            Canvas::Whole(raster(fit, style)?),
            fit,
            style,
        ))
    }

    /// The same raster painted in bands of [`BAND_ROWS`] rows, one after
    /// the other: the pixels [`draw_in_threads`] paints with any number of
    /// threads.
    pub fn banded(fit: Fit, style: &Style) -> Result<PngTurtle, Diagnostics> {
        Ok(PngTurtle::on(
            Canvas::Bands(raster(fit, style)?),
            fit,
            style,
        ))
    }

    /// A turtle painting on `canvas`.
    fn on(canvas: Canvas, fit: Fit, style: &Style) -> PngTurtle {
        let router = match canvas {
            Canvas::Whole(_) => None,
            _ => Some(Router::new(fit.height)),
        };
        let mut paint = Paint::default();
        paint.set_color(color(style.stroke));
        paint.anti_alias = true;
        PngTurtle {
            fit,
            width: style.width,
            ink: Ink {
                paint,
                rgb: style.stroke,
                width: fit.width,
            },
            blots: Vec::new(),
            router,
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
            short_side: 0.99 * f64::from(fit.width.min(fit.height)),
            covered: false,
            stood: 0.0,
            fields: Some(field::Fields::default()),
            dense: true,
            full: tiles::Full::new(),
            repeats: bands::repeats_for(&canvas),
            canvas,
        }
    }

    /// The same turtle asking for a level of detail of `px` output pixels
    /// (see [`Turtle::detail`]); `None` draws every segment.
    pub fn with_detail(mut self, px: Option<f64>) -> Self {
        self.set_detail(px);
        self
    }

    /// Asks for a level of detail of `px` output pixels from now on.
    pub fn set_detail(&mut self, px: Option<f64>) {
        self.detail = px.map(|px| px / self.fit.scale);
    }

    // -----------------------------------------------------------------------
    // Underlay

    /// Paints a filled area (a layout shape) with the even-odd rule. Call
    /// before drawing segments: it paints over whatever is there.
    pub fn fill(&mut self, fill: &Fill) {
        self.fill_rings(&fill.rings, fill.color, FillRule::EvenOdd);
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
        self.send_blots();
        if let Some(router) = &mut self.router {
            let paths = router.take();
            if !paths.is_empty() {
                self.paths += 1;
                let width = self.batch_width as f32;
                self.canvas
                    .send(Op::Stroke { paths, width }, &self.ink, &mut self.repeats);
            }
            return;
        }
        let Some(path) = batch.finish() else {
            return;
        };
        self.paths += 1;
        if let (Canvas::Whole(pixmap), Some(repeats)) = (&mut self.canvas, self.repeats.first_mut())
        {
            let width = self.batch_width as f32;
            repeats.stroke(&mut pixmap.as_mut(), &path, width, &self.ink.paint);
        }
        // Keep the allocation for the next batch.
        self.batch = Path::clear(path);
    }

    /// Hands the blots gathered so far to the bands (a whole raster has
    /// none waiting: it stamps them at once).
    fn send_blots(&mut self) {
        if !self.blots.is_empty() {
            let blots = std::mem::take(&mut self.blots);
            self.canvas.send(
                Op::Blots(std::sync::Arc::new(blots)),
                &self.ink,
                &mut self.repeats,
            );
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
        self.blots.clear();
        if let Some(router) = &mut self.router {
            router.clear();
        }
        match &mut self.canvas {
            Canvas::Whole(pixmap) => {
                self.repeats.iter_mut().for_each(repeat::Repeats::changed);
                pixmap.fill(color(self.ink.rgb));
            }
            canvas => canvas.send(Op::Cover, &self.ink, &mut self.repeats),
        }
        self.covered = true;
    }

    /// Stamps `shape` around `from`-`to` (output pixels) in the ink: at
    /// once on a whole raster, else with the batch's blots, which every
    /// band stamps in order.
    fn stamp(&mut self, from: crate::turtle::Point, to: crate::turtle::Point, shape: Shape) {
        match &mut self.canvas {
            Canvas::Whole(pixmap) => {
                self.repeats.iter_mut().for_each(repeat::Repeats::changed);
                let (width, rows) = (pixmap.width(), 0..pixmap.height());
                raster::stamp(
                    pixmap.data_mut(),
                    width,
                    rows,
                    self.ink.rgb,
                    from,
                    to,
                    &shape,
                );
            }
            _ => {
                self.blots.push(raster::Blot::new(from, to, shape));
                if self.blots.len() >= BATCH_SEGMENTS {
                    self.send_blots();
                }
            }
        }
    }

    // -----------------------------------------------------------------------
    // Output

    /// Strokes what is left and encodes the raster as PNG bytes.
    ///
    /// The pixels are demultiplied in place and encoded with the settings
    /// of tiny-skia's `encode_png` (same bytes), which would copy the
    /// whole pixmap first: a 16384 x 16384 picture peaks at its 1 GiB
    /// pixmap plus the compressed bytes, not at twice that.
    pub fn finish(self) -> Result<Vec<u8>, Diagnostics> {
        let (width, height) = (self.fit.width, self.fit.height);
        let pixmap = self
            .into_raster()
            .ok_or_else(|| Diagnostic::error(RenderError::NoRaster { width, height }))?;
        encode(pixmap)
    }

    /// Strokes what is left and hands back the raster; `None` for the
    /// turtle of [`draw_in_threads`], whose threads hold the raster.
    pub fn into_raster(mut self) -> Option<Pixmap> {
        self.flush();
        match self.canvas {
            Canvas::Whole(pixmap) | Canvas::Bands(pixmap) => Some(pixmap),
            Canvas::Sent(_) => None,
        }
    }
}

/// Draws with `threads` threads: a turtle painting in bands (the pixels
/// of [`PngTurtle::banded`], whatever the number of threads), handed to
/// `draw`, then the raster once every band has painted everything. More
/// than one thread only where threads exist (not in the web build).
pub fn draw_in_threads(
    fit: Fit,
    style: &Style,
    threads: usize,
    draw: impl FnOnce(&mut PngTurtle) -> Result<(), Diagnostics>,
) -> Result<Pixmap, Diagnostics> {
    let threads = if cfg!(target_family = "wasm") {
        1
    } else {
        threads.max(1)
    };
    if threads == 1 {
        let mut turtle = PngTurtle::banded(fit, style)?;
        draw(&mut turtle)?;
        let (width, height) = (fit.width, fit.height);
        return turtle
            .into_raster()
            .ok_or_else(|| Diagnostic::error(RenderError::NoRaster { width, height }).into());
    }
    let mut pixmap = raster(fit, style)?;
    let probe = PngTurtle::on(Canvas::Sent(Vec::new()), fit, style);
    bands::in_threads(&mut pixmap, threads, &probe.ink, |canvas| {
        let mut turtle = PngTurtle::on(canvas, fit, style);
        let drawn = draw(&mut turtle);
        // Flushes the last batch; dropping the queues ends the threads.
        turtle.into_raster();
        drawn
    })?;
    Ok(pixmap)
}

/// A `fit.width` x `fit.height` raster filled with the background
/// (transparent when there is none).
fn raster(fit: Fit, style: &Style) -> Result<Pixmap, Diagnostics> {
    let mut pixmap = Pixmap::new(fit.width, fit.height).ok_or_else(|| {
        Diagnostic::error(RenderError::NoRaster {
            width: fit.width,
            height: fit.height,
        })
        .with_help(Help::from("ask for a smaller picture (") + Help::knob(Knob::Size, "") + ")")
    })?;
    if let Some(bg) = style.background {
        pixmap.fill(color(bg));
    }
    Ok(pixmap)
}

/// The raster as PNG bytes: demultiplied in place (no copy of the
/// pixmap) and encoded with tiny-skia's own `encode_png` settings, so the
/// bytes are the same.
pub fn encode(pixmap: Pixmap) -> Result<Vec<u8>, Diagnostics> {
    let (w, h) = (pixmap.width(), pixmap.height());
    let rgba = pixmap.take_demultiplied();
    let mut data = Vec::new();
    let mut encoder = png::Encoder::new(&mut data, w, h);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder
        .write_header()
        .and_then(|mut writer| writer.write_image_data(&rgba))
        .map_err(|e| {
            Diagnostic::error(RenderError::PngEncoding {
                error: e.to_string(),
            })
        })?;
    Ok(data)
}

impl Turtle for PngTurtle {
    fn detail(&self) -> Option<f64> {
        self.detail
    }

    fn stand_in(&mut self, stand_in: &StandIn) {
        if self.covered {
            return;
        }
        // Drawn from itself where the walk can draw it (sparse or dense:
        // no threshold), else the ink its footprint spreads, else a blot.
        if let Some(sample) = stand_in.sample
            && let Some(field) = self.sampled_bush(sample)
        {
            let at = self.fit.map(sample.at);
            if at.x.is_finite() && at.y.is_finite() {
                self.stamp(at, at, Shape::Field(field));
            }
            return;
        }
        let (seg, density) = (stand_in.seg, stand_in.density);
        match stand_in.footprint {
            Some(foot) => self.spread_blot(seg, density, foot),
            None => self.blot(seg, density),
        }
    }

    fn covered(&mut self, lo: Point, hi: Point) -> bool {
        self.full_ink(lo, hi)
    }

    fn dense(&mut self, sample: &Sample) -> bool {
        if self.covered {
            return true;
        }
        let Some(field) = self.dense_field(sample) else {
            return false;
        };
        let at = self.fit.map(sample.at);
        if at.x.is_finite() && at.y.is_finite() {
            self.stamp(at, at, Shape::Field(field));
        }
        true
    }

    fn solid(&mut self, sample: &Sample) -> bool {
        if self.covered {
            return true;
        }
        let Some(field) = self.sampled_solid(sample) else {
            return false;
        };
        let at = self.fit.map(sample.at);
        if at.x.is_finite() && at.y.is_finite() {
            self.stamp(at, at, Shape::Field(field));
        }
        true
    }

    fn run(&mut self, seg: Segment, segments: f64) {
        if self.covered {
            return;
        }
        let segments = if segments.is_finite() {
            segments.max(1.0)
        } else {
            1.0
        };
        // The run's segments, in output pixels: the chord over their
        // number for a straight run, shorter for a winding one, where
        // they are far under FOLD_PX anyway.
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        let each = libm::hypot(to.x - from.x, to.y - from.y) / segments;
        let spacing = if each > 0.0 && each.is_finite() {
            each * libm::ceil(FOLD_PX / each)
        } else {
            FOLD_PX
        };
        self.draw(seg, Some(spacing));
        // The exact drawing strokes every BATCH_SEGMENTS segments as one
        // path and starts the next path with a new run, whose hairline
        // caps overlap the last one's: break the run where it would.
        let batch = BATCH_SEGMENTS as f64;
        let before = libm::floor(self.stood / batch);
        self.stood += segments - 1.0;
        if libm::floor(self.stood / batch) > before {
            self.end_subpath();
            self.last_to = None;
        }
    }

    fn segment(&mut self, seg: Segment) {
        self.draw(seg, None);
    }

    fn paint(&mut self, rgb: Rgb) {
        self.repaint(rgb);
    }

    fn polygon(&mut self, points: &[Point]) {
        self.fill_polygon(points);
    }
}

impl PngTurtle {
    /// A stand-in known by its segment and density: a capsule of ink
    /// when dense, else the segment.
    fn blot(&mut self, seg: Segment, density: f64) {
        if density < BLOT_DENSITY {
            self.segment(seg);
            return;
        }
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y].iter().all(|v| v.is_finite()) {
            return;
        }
        let radius = (stroke_px(&self.width, self.fit.scale, seg.order) + BLOT_EXTRA_PX) / 2.0;
        self.stamp(from, to, Shape::Capsule(radius));
    }

    /// A stand-in with its footprint: the ink its strokes spread there,
    /// or the segment when sparse and narrow.
    fn spread_blot(&mut self, seg: Segment, density: f64, foot: Footprint) {
        let (spread, runs) = (foot.spread * self.fit.scale, foot.runs);
        if density < BLOT_DENSITY && spread < SPREAD_MIN_PX {
            self.segment(seg);
            return;
        }
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y, spread, density, runs]
            .iter()
            .all(|v| v.is_finite())
        {
            return;
        }
        let stroke = stroke_px(&self.width, self.fit.scale, seg.order);
        let chord = libm::hypot(to.x - from.x, to.y - from.y);
        let bush = Bush::new(stroke, spread, chord, density * chord, runs);
        self.stamp(from, to, Shape::Bush(bush));
    }

    /// Draws a segment; with a `spacing`, a stand-in's chord, folded as
    /// the run it stands for ([`PngTurtle::pen_along`]).
    fn draw(&mut self, seg: Segment, spacing: Option<f64>) {
        self.stood += 1.0;
        if self.covered {
            return;
        }
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y].iter().all(|v| v.is_finite()) {
            // Nothing sensible to draw; the SVG backend skips it too.
            return;
        }
        let width = stroke_px(&self.width, self.fit.scale, seg.order);
        // A stroke narrower than the picture's shorter side cannot reach
        // every corner (a capsule holding a rectangle is at least as wide
        // as its shorter side), so the corners need no measuring.
        if width >= self.short_side
            && width / 2.0 >= raster::farthest_corner((self.fit.width, self.fit.height), from, to)
        {
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
            self.put(from, true);
            self.pen = Some(Pen {
                kept: from,
                at: from,
                pending: false,
            });
        }
        match spacing {
            Some(spacing) => self.pen_along(to, spacing),
            None => self.pen_to(to),
        }
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
#[cfg(test)]
mod tests;
