//! How strokes look and the pixel sizes the backends work to: stroke
//! widths and colours ([`Style`]), the level of detail, stand-ins, folding
//! and batching. A leaf the backends (`png`, `svg`) and the fitting read.

use crate::color::Rgb;
use crate::num::Linear;

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

/// Level of detail, in output pixels: a part of a drawing (an L-system
/// subtree) whose whole extent is at most this is drawn as one stand-in
/// segment. See docs/rendering.md for what it changes and why this value.
pub const LOD_PX: f64 = 0.5;

/// Stand-ins ([`crate::turtle::Turtle::stand_in`]) at least this dense (drawn length over
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
/// ([`super::png::BAND_ROWS`] rows each), which threads can share
/// ([`super::RenderOptions::threads`]). Smaller drawings are painted on one
/// raster as they always were: banding changes the anti-aliasing of lines
/// that cross a band's edge a little (docs/rendering.md), and a drawing
/// this small takes well under a second anyway.
pub const BANDED_SEGMENTS: u64 = 1 << 20;

/// A sparse bush (density under [`BLOT_DENSITY`]) whose spread is under
/// this many output pixels is drawn as its chord, an ordinary segment.
pub const SPREAD_MIN_PX: f64 = 0.1;

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

/// Longest side of the output when no size is asked for.
pub const DEFAULT_SIDE: u32 = 800;
