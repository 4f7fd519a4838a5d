//! Rendering: segments to PNG (tiny-skia) or SVG.
//!
//! [`render`] runs a drawing twice: a bounding pass (000's `GetCurveSize`)
//! that fits the picture to the requested size, unless a fixed view (the
//! layout's canvas) is given, then the drawing pass into the PNG or SVG
//! backend. Layout shapes can be painted underneath ([`Fill`]).

mod fit;
pub mod mesh;
pub mod png;
pub mod svg;
mod svg_merge;
pub mod view;
pub mod volumes;

use std::io::Write;

use crate::color::Rgb;
use crate::diag::Help;
use crate::diag::{Diagnostic, Diagnostics, RenderError, io_error};
use crate::limits::Bound;
use crate::num::Linear;
use crate::progress::{Phase, Progress};
use crate::turtle::{BBox, Bounds, Counter, Fill, Point, Turtle};

use fit::checked_size;
pub use fit::{Fit, fills_bbox, layout_frame, stroke_px};
pub use png::PngTurtle;
pub use svg::SvgTurtle;

/// Output image format (also the values of `--format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum ImageFormat {
    /// PNG image.
    Png,
    /// SVG drawing.
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
    /// Most lines an SVG may hold (`--max-svg-segments`): a segment each
    /// with `exact`, merged runs without; a PNG's size does not grow with
    /// the drawing, so it has no such limit.
    pub max_svg_segments: u64,
    /// Draw every segment (`--exact`); otherwise the backends ask for a
    /// level of detail of [`LOD_PX`] ([`crate::turtle::Turtle::detail`]).
    pub exact: bool,
    /// Threads that paint a PNG's bands (`--threads`): a picture of
    /// [`BANDED_SEGMENTS`] or more is painted in bands of
    /// [`png::BAND_ROWS`] rows, the same pixels with any number; 1 (the
    /// default here; the CLI's is the machine's cores) never starts a
    /// thread.
    pub threads: usize,
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
            threads: 1,
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

/// Stand-ins ([`Turtle::stand_in`]) at least this dense (drawn length over
/// their own length) are drawn as blots; sparser ones (a straight run, a
/// sparse twig) as ordinary segments.
pub const BLOT_DENSITY: f64 = 2.0;

/// A blot is this much wider than the stems, in output pixels: the exact
/// drawing of a sub-pixel bush is many overlapping anti-aliased hairlines,
/// each with its round caps, which saturate a spot about this much wider
/// than one stroke. Chosen by measurement against `--exact`
/// (docs/rendering.md, *Level of detail*: 0.5 to 1.25 tried, 1.0 closest).
pub const BLOT_EXTRA_PX: f64 = 1.0;

/// A PNG of a drawing of at least this many segments is painted in bands
/// ([`png::BAND_ROWS`] rows each), which threads can share
/// ([`RenderOptions::threads`]). Smaller drawings are painted on one
/// raster as they always were: banding changes the anti-aliasing of lines
/// that cross a band's edge a little (docs/rendering.md), and a drawing
/// this small takes well under a second anyway.
pub const BANDED_SEGMENTS: u64 = 1 << 20;

/// A sparse bush (density under [`BLOT_DENSITY`]) whose spread is under
/// this many output pixels is drawn as its chord, an ordinary segment.
pub const SPREAD_MIN_PX: f64 = 0.1;

/// How [`render_framed`] decides what the picture shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Frame {
    /// Fit the drawing, measured by a bounding pass (000's GetCurveSize).
    Fit,
    /// Show exactly this canvas area (a layout's bounds); `segments`: the
    /// drawing's number of segments, if known (a grown tree's stems).
    View {
        /// The canvas area.
        view: BBox,
        /// Segments the drawing has, if known.
        segments: Option<u64>,
    },
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

/// Default of [`RenderOptions::max_svg_segments`] (lines written: a
/// segment each with `--exact`): about 22 bytes a line, so an SVG of at
/// most about 220 MB (already more than browsers open).
pub const DEFAULT_MAX_SVG_SEGMENTS: u64 = crate::limits::DEFAULT_MAX_SVG_SEGMENTS;

/// The error for an SVG over [`RenderOptions::max_svg_segments`]; `count`
/// is the exact number when known, else `None` ("more than the limit").
pub(crate) fn svg_too_large(count: Option<u64>, limit: u64) -> Diagnostics {
    Bound::SvgSegments
        .exceeded(
            count.map_or_else(|| format!("more than {limit}"), |c| c.to_string()),
            limit,
        )
        .with_help(
            Help::from(
                "an SVG holds a line a segment with --exact (about 22 bytes each), and merges \
                 runs into as few lines as show the picture without: render a PNG instead, \
                 drop --exact, draw less (a smaller --depth or --size), or ",
            ) + Bound::SvgSegments,
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
        Some(view) => Frame::View {
            view,
            segments: None,
        },
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
    // Segments counted by a first pass, when one runs, or known.
    let mut counted;
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
            // A merged SVG's lines are counted below, when there may be
            // too many.
            if opts.format == ImageFormat::Svg && opts.exact && segments > opts.max_svg_segments {
                return Err(svg_too_large(Some(segments), opts.max_svg_segments));
            }
            Fit::content(bbox, 0, &style.width, opts.size)?
        }
        Frame::View { view, segments } => {
            counted = segments;
            if opts.format == ImageFormat::Svg && opts.exact {
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
            if opts.format == ImageFormat::Svg && opts.exact && bounds.count > opts.max_svg_segments
            {
                return Err(svg_too_large(Some(bounds.count), opts.max_svg_segments));
            }
            Fit::content(bbox, bounds.max_order, &style.width, opts.size)?
        }
    };
    // A merged SVG has at most a line a segment: only a drawing of more
    // segments than the limit (or of an unknown number) is counted first,
    // by the merging writer into nothing, so an SVG over the limit is
    // refused before a byte is written.
    if opts.format == ImageFormat::Svg
        && !opts.exact
        && counted.is_none_or(|n| n > opts.max_svg_segments)
    {
        let mut count = SvgTurtle::new(std::io::sink(), fit, style)?
            .with_detail(opts.detail_px())
            .merging();
        drawing(&mut count, &mut Phase::new(progress, "counting"))?;
        let lines = count.lines();
        if lines > opts.max_svg_segments {
            return Err(svg_too_large(Some(lines), opts.max_svg_segments));
        }
    }
    match opts.format {
        ImageFormat::Png => {
            let bytes = if counted.is_some_and(|n| n >= BANDED_SEGMENTS) {
                let pixmap = png::draw_in_threads(fit, style, opts.threads, |turtle| {
                    turtle.set_detail(opts.detail_px());
                    for fill in underlay {
                        turtle.fill(fill);
                    }
                    drawing(turtle, &mut Phase::new(progress, "drawing"))
                })?;
                png::encode(pixmap)?
            } else {
                let mut turtle = PngTurtle::new(fit, style)?.with_detail(opts.detail_px());
                for fill in underlay {
                    turtle.fill(fill);
                }
                drawing(&mut turtle, &mut Phase::new(progress, "drawing"))?;
                turtle.finish()?
            };
            out.write_all(&bytes)
                .and_then(|()| out.flush())
                .map_err(|e| io_error(&e, "writing the PNG image"))?;
        }
        ImageFormat::Svg => {
            let mut turtle = SvgTurtle::new(std::io::BufWriter::new(&mut *out), fit, style)?
                .with_max_segments(opts.max_svg_segments)
                .with_detail(opts.detail_px());
            if !opts.exact {
                turtle = turtle.merging();
            }
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
    use crate::diag::ErrorKind;

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
            assert!(matches!(
                d.kind,
                ErrorKind::Render(RenderError::ImageSize { .. })
            ));
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
        assert_eq!(
            err.first_kind(),
            Some(&ErrorKind::Render(RenderError::DrawingNotFinite))
        );
    }
}
