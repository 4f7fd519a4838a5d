//! Rendering: segments to PNG (tiny-skia) or SVG.
//!
//! [`render`] runs a drawing twice: a bounding pass (000's `GetCurveSize`)
//! that fits the picture to the requested size, unless a fixed view (the
//! layout's canvas) is given, then the drawing pass into the PNG or SVG
//! backend. Layout shapes can be painted underneath ([`Fill`]).

pub mod png;
pub mod svg;

use std::io::Write;

use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use crate::num::Linear;
use crate::progress::{Phase, Progress};
use crate::turtle::{BBox, Bounds, Counter, Fill, Point, Turtle};

pub use png::PngTurtle;
pub use svg::SvgTurtle;

/// Output image format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// PNG through tiny-skia.
    Png,
    /// SVG text.
    Svg,
}

/// How wide strokes are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Width {
    /// The same width in output pixels for every stem (classic L-systems).
    Pixels(f64),
    /// `base - order * decrement` canvas units, scaled with the picture (STL's `B`).
    Canvas(Linear),
}

/// Colours and widths.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Style {
    /// Stroke colour.
    pub stroke: Rgb,
    /// Canvas colour; `None` for transparent.
    pub background: Option<Rgb>,
    /// Stroke width.
    pub width: Width,
}

/// Size and format of the output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// PNG or SVG.
    pub format: ImageFormat,
    /// Output size in pixels; `None`: longest side [`DEFAULT_SIDE`], the
    /// other from the picture's aspect ratio.
    pub size: Option<(u32, u32)>,
    /// Most segments an SVG may hold (`--max-svg-segments`); a PNG's size
    /// does not grow with the drawing, so it has no such limit.
    pub max_svg_segments: u64,
    /// Draw every segment (`--exact`); otherwise the backends ask for a
    /// level of detail of [`LOD_PX`] ([`crate::turtle::Turtle::detail`]).
    pub exact: bool,
}

impl RenderOptions {
    /// `format` at `size`, with the default SVG segment limit and the
    /// default level of detail.
    pub fn new(format: ImageFormat, size: Option<(u32, u32)>) -> Self {
        RenderOptions {
            format,
            size,
            max_svg_segments: DEFAULT_MAX_SVG_SEGMENTS,
            exact: false,
        }
    }

    /// The level of detail the backends ask for, in output pixels.
    pub fn detail_px(&self) -> Option<f64> {
        (!self.exact).then_some(LOD_PX)
    }
}

/// Level of detail, in output pixels: a part of a drawing (an L-system
/// subtree) whose whole extent is at most this is drawn as one stand-in
/// segment. See docs/rendering.md for what it changes and why this value.
pub const LOD_PX: f64 = 0.5;

/// Stand-ins ([`Turtle::blot`]) at least this dense (drawn length over
/// their own length) are drawn as blots; sparser ones (a straight run, a
/// sparse twig) as ordinary segments.
pub const BLOT_DENSITY: f64 = 2.0;

/// A blot is this much wider than the stems, in output pixels: the exact
/// drawing of a sub-pixel bush is many overlapping anti-aliased hairlines,
/// each with its round caps, which saturate a spot about this much wider
/// than one stroke. Chosen by measurement against `--exact`
/// (docs/rendering.md, *Level of detail*: 0.5 to 1.25 tried, 1.0 closest).
pub const BLOT_EXTRA_PX: f64 = 1.0;

/// How [`render_framed`] decides what the picture shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Frame {
    /// Fit the drawing, measured by a bounding pass (000's GetCurveSize).
    Fit,
    /// Show exactly this canvas area (a layout's bounds).
    View(BBox),
    /// Fit the drawing whose box (`None`: nothing drawn) and number of
    /// segments are already known (an L-system's memoized geometry): no
    /// bounding pass.
    Known {
        /// The drawing's box.
        bbox: Option<BBox>,
        /// Its segments, drawn exactly (saturating).
        segments: u64,
    },
}

/// Counts the segments a drawing hands over at a level of detail.
struct DetailCounter {
    count: u64,
    detail: Option<f64>,
}

impl Turtle for DetailCounter {
    fn segment(&mut self, _seg: crate::turtle::Segment) {
        self.count += 1;
    }

    fn detail(&self) -> Option<f64> {
        self.detail
    }
}

/// Default of [`RenderOptions::max_svg_segments`]: about 22 bytes a segment,
/// so an SVG of at most about 220 MB (already more than browsers open).
pub const DEFAULT_MAX_SVG_SEGMENTS: u64 = 10_000_000;

/// The error for an SVG over [`RenderOptions::max_svg_segments`]; `count`
/// is the exact number when known, else `None` ("more than the limit").
pub(crate) fn svg_too_large(count: Option<u64>, limit: u64) -> Diagnostics {
    Diagnostic::error(ErrorKind::Limit {
        what: "segments in the SVG".into(),
        value: count.map_or_else(|| format!("more than {limit}"), |c| c.to_string()),
        limit: limit.to_string(),
    })
    .with_help(
        "an SVG holds every segment (about 22 bytes each): render a PNG instead, \
         draw less (a smaller --depth), or raise the limit with --max-svg-segments N",
    )
    .into()
}

/// Longest side of the output when no size is asked for.
pub const DEFAULT_SIDE: u32 = 800;

/// Largest accepted side of the output, in pixels. A 16384 x 16384 RGBA
/// raster is already 1 GiB.
pub const MAX_SIDE: u32 = 16_384;

/// Thinnest stroke drawn, in output pixels: stems whose width scales below
/// this (or is zero or negative) are still drawn, as hairlines.
pub const HAIRLINE: f64 = 0.5;

/// Margin around a fitted picture: this fraction of the longest side ...
pub const MARGIN_FRACTION: f64 = 0.04;

/// ... but at least this many pixels (half the widest stroke comes on top).
pub const MIN_MARGIN: f64 = 4.0;

/// Segments per path (PNG) or `<path>` element (SVG). Both backends flush a
/// path when it holds this many segments or when the stroke width changes,
/// so memory stays bounded however many segments stream through.
pub const BATCH_SEGMENTS: usize = 4096;

/// Folding tolerance of the PNG backend, in output pixels: along a run of
/// connected segments (a subpath), a vertex closer than this to the last
/// vertex kept is not written, only the run's exact end. Deep L-systems
/// stream tens of millions of segments far shorter than a pixel, and
/// tiny-skia's cost is per segment; the picture moves by less than this.
pub const FOLD_PX: f64 = 0.25;

/// Something that can draw itself into a turtle, any number of times.
pub type Drawing<'a> =
    dyn FnMut(&mut dyn Turtle, &mut dyn Progress) -> Result<(), Diagnostics> + 'a;

/// How canvas units map to output pixels: `pixel = canvas * scale + (dx, dy)`.
///
/// Canvas and image are both y-down, so there is no flip. The scale is
/// uniform (circles stay round) and the picture is centred.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// Output width in pixels.
    pub width: u32,
    /// Output height in pixels.
    pub height: u32,
    /// Pixels per canvas unit (positive, finite).
    pub scale: f64,
    /// Horizontal offset in pixels.
    pub dx: f64,
    /// Vertical offset in pixels.
    pub dy: f64,
}

impl Fit {
    /// The output pixel position of a canvas point.
    #[inline]
    pub fn map(&self, p: Point) -> Point {
        Point::new(p.x * self.scale + self.dx, p.y * self.scale + self.dy)
    }

    /// Shows exactly `view` (a layout's canvas, in canvas units): the box is
    /// scaled uniformly to fit `size` and centred, with no margin. Without a
    /// size the longest side is [`DEFAULT_SIDE`] and the other follows the
    /// box's aspect ratio.
    pub fn view(view: &BBox, size: Option<(u32, u32)>) -> Result<Fit, Diagnostics> {
        let (vw, vh) = (view.width(), view.height());
        let finite = [view.min_x, view.min_y, view.max_x, view.max_y]
            .iter()
            .all(|v| v.is_finite());
        if !finite || vw < 0.0 || vh < 0.0 {
            return Err(Diagnostic::error(ErrorKind::BadCanvas {
                min_x: view.min_x,
                min_y: view.min_y,
                max_x: view.max_x,
                max_y: view.max_y,
            })
            .into());
        }
        let (w, h) = match size {
            Some(size) => checked_size(size)?,
            None => default_size(vw, vh),
        };
        let scale = uniform_scale(&[(f64::from(w), vw), (f64::from(h), vh)]);
        Ok(Fit::centred(w, h, scale, view))
    }

    /// Fits the picture whose bounding box is `bbox` (from the bounding
    /// pass; `None` when nothing was drawn) into `size`, leaving a margin of
    /// [`MARGIN_FRACTION`] of the longest side (at least [`MIN_MARGIN`]
    /// pixels) plus half the widest stroke, so no stroke is clipped.
    /// `max_order` is the highest stem order drawn, which fixes the widest
    /// stroke of a [`Width::Canvas`].
    ///
    /// Without a size, the longest side is [`DEFAULT_SIDE`] and the other
    /// follows the picture's aspect ratio, margins included (at least 1 px).
    /// A picture with no extent (one point, or nothing at all) gives a
    /// square image with the point in the middle.
    pub fn content(
        bbox: Option<BBox>,
        max_order: u32,
        width: &Width,
        size: Option<(u32, u32)>,
    ) -> Result<Fit, Diagnostics> {
        let bbox = bbox.unwrap_or(BBox::at(Point::new(0.0, 0.0)));
        let finite = [bbox.min_x, bbox.min_y, bbox.max_x, bbox.max_y]
            .iter()
            .all(|v| v.is_finite());
        if !finite {
            return Err(Diagnostic::error(ErrorKind::DrawingNotFinite)
                .with_help("check the stem length, angle and depth")
                .into());
        }
        let (px_half, canvas_half) = half_widest(width, max_order);
        let (cw, ch) = (
            bbox.width() + 2.0 * canvas_half,
            bbox.height() + 2.0 * canvas_half,
        );
        let (w, h) = match size {
            Some(size) => checked_size(size)?,
            None => {
                let side = f64::from(DEFAULT_SIDE);
                let margin = margin(side) + px_half;
                let long = cw.max(ch);
                if long > 0.0 {
                    let scale = available(side, margin) / long;
                    let other = |extent: f64| {
                        // Round up: the short side must not limit the scale.
                        let px = libm::ceil(extent * scale + 2.0 * margin - 1e-9);
                        px.clamp(1.0, side) as u32
                    };
                    if cw >= ch {
                        (DEFAULT_SIDE, other(ch))
                    } else {
                        (other(cw), DEFAULT_SIDE)
                    }
                } else {
                    (DEFAULT_SIDE, DEFAULT_SIDE)
                }
            }
        };
        let margin = margin(f64::from(w.max(h))) + px_half;
        let scale = uniform_scale(&[
            (available(f64::from(w), margin), cw),
            (available(f64::from(h), margin), ch),
        ]);
        Ok(Fit::centred(w, h, scale, &bbox))
    }

    /// The fit of `scale` that puts the centre of `bbox` in the middle of a
    /// `w` x `h` image.
    fn centred(w: u32, h: u32, scale: f64, bbox: &BBox) -> Fit {
        let cx = (bbox.min_x + bbox.max_x) / 2.0;
        let cy = (bbox.min_y + bbox.max_y) / 2.0;
        Fit {
            width: w,
            height: h,
            scale,
            dx: f64::from(w) / 2.0 - cx * scale,
            dy: f64::from(h) / 2.0 - cy * scale,
        }
    }
}

/// The stroke width in output pixels of a stem of `order` under `scale`:
/// never thinner than [`HAIRLINE`], so every stem shows.
pub fn stroke_px(width: &Width, scale: f64, order: u32) -> f64 {
    let px = match *width {
        Width::Pixels(w) => w,
        Width::Canvas(w) => w.at(order) * scale,
    };
    // `max` also turns a NaN into the hairline.
    px.max(HAIRLINE)
}

/// Half the widest stroke, split into a part in pixels and a part in canvas
/// units (which scales with the picture).
fn half_widest(width: &Width, max_order: u32) -> (f64, f64) {
    match *width {
        Width::Pixels(w) => (w.max(HAIRLINE) / 2.0, 0.0),
        Width::Canvas(w) => {
            // Linear in the order: the widest is at one end. The hairline
            // floor is added on top, a slight overestimate.
            let last = w.at(max_order);
            let widest = w.base.max(last).max(0.0);
            let widest = if widest.is_finite() { widest } else { 0.0 };
            (HAIRLINE / 2.0, widest / 2.0)
        }
    }
}

/// The margin in pixels for an image whose longest side is `side`, strokes
/// not counted.
fn margin(side: f64) -> f64 {
    (side * MARGIN_FRACTION).max(MIN_MARGIN)
}

/// Room left for the picture on a side of `side` pixels: never less than
/// half the side, so a tiny `--size` with thick strokes still shows the
/// picture (clipped) rather than nothing.
fn available(side: f64, margin: f64) -> f64 {
    (side - 2.0 * margin).max(side / 2.0)
}

/// The largest scale that fits each `(room, extent)` pair; extents of zero
/// do not constrain. With no constraint at all the scale is 1.
fn uniform_scale(axes: &[(f64, f64)]) -> f64 {
    let scale = axes
        .iter()
        .filter(|(_, extent)| *extent > 0.0)
        .map(|(room, extent)| room / extent)
        .fold(f64::INFINITY, f64::min);
    if scale.is_finite() && scale > 0.0 {
        scale
    } else {
        1.0
    }
}

/// The size for a `vw` x `vh` box without `--size`: longest side
/// [`DEFAULT_SIDE`], the other by aspect ratio, at least 1 px.
fn default_size(vw: f64, vh: f64) -> (u32, u32) {
    let side = f64::from(DEFAULT_SIDE);
    let other = |short: f64, long: f64| (libm::round(side * short / long)).clamp(1.0, side) as u32;
    if vw <= 0.0 && vh <= 0.0 {
        (DEFAULT_SIDE, DEFAULT_SIDE)
    } else if vw >= vh {
        (DEFAULT_SIDE, other(vh, vw))
    } else {
        (other(vw, vh), DEFAULT_SIDE)
    }
}

/// Refuses sizes with a zero side or a side above [`MAX_SIDE`].
fn checked_size((w, h): (u32, u32)) -> Result<(u32, u32), Diagnostics> {
    if (1..=MAX_SIDE).contains(&w) && (1..=MAX_SIDE).contains(&h) {
        Ok((w, h))
    } else {
        Err(Diagnostic::error(ErrorKind::ImageSize {
            width: w,
            height: h,
            max: MAX_SIDE,
        })
        .with_help(format!(
            "ask for a size such as `--size {DEFAULT_SIDE}x{DEFAULT_SIDE}`, or leave out `--size`"
        ))
        .into())
    }
}

/// Renders `drawing` to `out`. `view`: the canvas area to show (a layout's
/// bounds), or `None` to fit the picture from a bounding pass.
///
/// The drawing runs twice: once into a [`Bounds`] turtle (when a view is
/// given, only for an SVG and into a [`Counter`], to check
/// [`RenderOptions::max_svg_segments`] before writing; the underlay's points
/// count towards the fitted box too),
/// once into the PNG or SVG backend. `progress` is handed to both runs,
/// their work named `measuring: ...` and `drawing: ...`.
/// The underlay is painted first, in order, then the segments. SVG output
/// streams into `out` while the drawing runs; PNG is written at the end.
/// Returns the number of segments the first pass counted, if one ran.
pub fn render(
    drawing: &mut Drawing<'_>,
    view: Option<BBox>,
    underlay: &[Fill],
    style: &Style,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Option<u64>, Diagnostics> {
    let frame = match view {
        Some(v) => Frame::View(v),
        None => Frame::Fit,
    };
    render_framed(drawing, frame, underlay, style, opts, out, progress)
}

/// [`render`] with the picture's frame given as a [`Frame`]: with
/// [`Frame::Known`] there is no bounding pass (an SVG at a level of detail
/// is counted by a pass at that level instead, which costs what drawing
/// it does). The drawing pass's backend asks for
/// [`RenderOptions::detail_px`].
pub fn render_framed(
    drawing: &mut Drawing<'_>,
    frame: Frame,
    underlay: &[Fill],
    style: &Style,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Option<u64>, Diagnostics> {
    // Refuse a bad size before any work.
    if let Some(size) = opts.size {
        checked_size(size)?;
    }
    // Segments counted by a first pass, when one runs.
    let mut counted = None;
    let fit = match frame {
        Frame::Known { bbox, segments } => {
            counted = Some(segments);
            let mut bbox = bbox;
            for p in underlay.iter().flat_map(|f| &f.rings).flatten() {
                match &mut bbox {
                    Some(b) => b.add(*p),
                    None => bbox = Some(BBox::at(*p)),
                }
            }
            let fit = Fit::content(bbox, 0, &style.width, opts.size)?;
            if opts.format == ImageFormat::Svg {
                let drawn = match opts.detail_px() {
                    Some(px) => {
                        let mut count = DetailCounter {
                            count: 0,
                            detail: Some(px / fit.scale),
                        };
                        drawing(&mut count, &mut Phase::new(progress, "counting"))?;
                        count.count
                    }
                    None => segments,
                };
                if drawn > opts.max_svg_segments {
                    return Err(svg_too_large(Some(drawn), opts.max_svg_segments));
                }
            }
            fit
        }
        Frame::View(view) => {
            if opts.format == ImageFormat::Svg {
                // No bounding pass to count the segments: count them first,
                // so an SVG over the limit is refused before a byte is written.
                let mut count = Counter::default();
                drawing(&mut count, &mut Phase::new(progress, "counting"))?;
                counted = Some(count.0);
                if count.0 > opts.max_svg_segments {
                    return Err(svg_too_large(Some(count.0), opts.max_svg_segments));
                }
            }
            Fit::view(&view, opts.size)?
        }
        Frame::Fit => {
            let mut bounds = Bounds::default();
            drawing(&mut bounds, &mut Phase::new(progress, "measuring"))?;
            counted = Some(bounds.count);
            let mut bbox = bounds.bbox();
            for p in underlay.iter().flat_map(|f| &f.rings).flatten() {
                match &mut bbox {
                    Some(b) => b.add(*p),
                    None => bbox = Some(BBox::at(*p)),
                }
            }
            if opts.format == ImageFormat::Svg && bounds.count > opts.max_svg_segments {
                return Err(svg_too_large(Some(bounds.count), opts.max_svg_segments));
            }
            Fit::content(bbox, bounds.max_order, &style.width, opts.size)?
        }
    };
    match opts.format {
        ImageFormat::Png => {
            let mut turtle = PngTurtle::new(fit, style)?.with_detail(opts.detail_px());
            for fill in underlay {
                turtle.fill(fill);
            }
            drawing(&mut turtle, &mut Phase::new(progress, "drawing"))?;
            let bytes = turtle.finish()?;
            out.write_all(&bytes)
                .and_then(|()| out.flush())
                .map_err(|e| io_error(&e, "writing the PNG image"))?;
        }
        ImageFormat::Svg => {
            let mut turtle = SvgTurtle::new(std::io::BufWriter::new(&mut *out), fit, style)?
                .with_max_segments(opts.max_svg_segments)
                .with_detail(opts.detail_px());
            for fill in underlay {
                turtle.fill(fill);
            }
            drawing(&mut turtle, &mut Phase::new(progress, "drawing"))?;
            let mut buffered = turtle.finish()?;
            buffered
                .flush()
                .map_err(|e| io_error(&e, "writing the SVG image"))?;
        }
    }
    Ok(counted)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bbox(min_x: f64, min_y: f64, max_x: f64, max_y: f64) -> BBox {
        BBox {
            min_x,
            min_y,
            max_x,
            max_y,
        }
    }

    #[test]
    fn fitting_a_known_box_into_a_known_size() {
        // 100 x 50 box into 200 x 100, 2 px strokes: margin max(4, 0.04*200)
        // + 1 = 9 px; room 182 x 82; scale min(1.82, 1.64) = 1.64; the
        // centre (50, 25) goes to (100, 50).
        let fit = Fit::content(
            Some(bbox(0.0, 0.0, 100.0, 50.0)),
            0,
            &Width::Pixels(2.0),
            Some((200, 100)),
        )
        .unwrap();
        assert_eq!((fit.width, fit.height), (200, 100));
        assert!((fit.scale - 1.64).abs() < 1e-12);
        let a = fit.map(Point::new(0.0, 0.0));
        let b = fit.map(Point::new(100.0, 50.0));
        assert!(
            (a.x - 18.0).abs() < 1e-9 && (a.y - 9.0).abs() < 1e-9,
            "{a:?}"
        );
        assert!(
            (b.x - 182.0).abs() < 1e-9 && (b.y - 91.0).abs() < 1e-9,
            "{b:?}"
        );
    }

    #[test]
    fn default_size_follows_the_aspect_ratio_with_margins() {
        // Longest side 800, margin 32 + 1 = 33: scale (800 - 66) / 100 =
        // 7.34, height 50 * 7.34 + 66 = 433.
        let fit = Fit::content(
            Some(bbox(0.0, 0.0, 100.0, 50.0)),
            0,
            &Width::Pixels(2.0),
            None,
        )
        .unwrap();
        assert_eq!((fit.width, fit.height), (800, 433));
        assert!((fit.scale - 7.34).abs() < 1e-12);
        let tall = Fit::content(
            Some(bbox(0.0, 0.0, 50.0, 100.0)),
            0,
            &Width::Pixels(2.0),
            None,
        )
        .unwrap();
        assert_eq!((tall.width, tall.height), (433, 800));
    }

    #[test]
    fn canvas_widths_widen_the_margin_with_the_scale() {
        // Width 10 canvas units at order 0: half 5 units on each side, so
        // the box to fit is 110 x 10 units; margin 8 + 0.25 px; room
        // 200 - 16.5 = 183.5 px: scale 183.5 / 110.
        let fit = Fit::content(
            Some(bbox(0.0, 0.0, 100.0, 0.0)),
            3,
            &Width::Canvas(Linear::new(10.0, 1.0)),
            Some((200, 200)),
        )
        .unwrap();
        assert!((fit.scale - 183.5 / 110.0).abs() < 1e-12);
        assert_eq!(
            stroke_px(&Width::Canvas(Linear::new(10.0, 1.0)), 2.0, 3),
            14.0
        );
    }

    #[test]
    fn a_view_is_mapped_exactly() {
        let view = bbox(0.0, 0.0, 200.0, 100.0);
        let fit = Fit::view(&view, None).unwrap();
        assert_eq!((fit.width, fit.height, fit.scale), (800, 400, 4.0));
        assert_eq!((fit.dx, fit.dy), (0.0, 0.0));
        // Into a square: scale 2, centred vertically.
        let fit = Fit::view(&view, Some((400, 400))).unwrap();
        assert_eq!((fit.scale, fit.dx, fit.dy), (2.0, 0.0, 100.0));
        assert_eq!(fit.map(Point::new(200.0, 100.0)), Point::new(400.0, 300.0));
    }

    #[test]
    fn zero_extent_gives_a_square_with_the_point_in_the_middle() {
        for b in [None, Some(BBox::at(Point::new(5.0, -7.0)))] {
            let fit = Fit::content(b, 0, &Width::Pixels(1.0), None).unwrap();
            assert_eq!((fit.width, fit.height, fit.scale), (800, 800, 1.0));
            let p = fit.map(b.map_or(Point::default(), |b| Point::new(b.min_x, b.min_y)));
            assert_eq!(p, Point::new(400.0, 400.0));
        }
        // A horizontal line: full width, a short strip of margins.
        let fit = Fit::content(
            Some(bbox(0.0, 0.0, 10.0, 0.0)),
            0,
            &Width::Pixels(2.0),
            None,
        )
        .unwrap();
        assert_eq!((fit.width, fit.height), (800, 66));
        assert!(fit.scale.is_finite());
    }

    #[test]
    fn hairlines_are_the_floor() {
        let w = Width::Canvas(Linear::new(1.0, 0.5));
        assert_eq!(stroke_px(&w, 10.0, 1), 5.0);
        assert_eq!(stroke_px(&w, 10.0, 2), HAIRLINE);
        assert_eq!(stroke_px(&w, 10.0, 9), HAIRLINE);
        assert_eq!(stroke_px(&Width::Pixels(0.0), 10.0, 0), HAIRLINE);
        assert_eq!(stroke_px(&Width::Pixels(f64::NAN), 10.0, 0), HAIRLINE);
    }

    #[test]
    fn absurd_sizes_are_refused_naming_the_flag() {
        for size in [(0, 10), (10, 0), (MAX_SIDE + 1, 10)] {
            let err = Fit::content(None, 0, &Width::Pixels(1.0), Some(size)).unwrap_err();
            let d = &err.0[0];
            assert!(matches!(d.kind, ErrorKind::ImageSize { .. }));
            assert!(d.to_string().contains("--size"), "{d}");
        }
        assert!(Fit::view(&bbox(0.0, 0.0, 1.0, 1.0), Some((MAX_SIDE, 1))).is_ok());
    }

    #[test]
    fn non_finite_drawings_are_refused() {
        let err = Fit::content(
            Some(bbox(0.0, 0.0, f64::INFINITY, 1.0)),
            0,
            &Width::Pixels(1.0),
            None,
        )
        .unwrap_err();
        assert_eq!(err.first_kind(), Some(&ErrorKind::DrawingNotFinite));
    }
}
