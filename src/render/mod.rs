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
use crate::diag::Diagnostics;
use crate::progress::Progress;
use crate::turtle::{BBox, Point, Turtle};

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
    Canvas {
        /// Width at order 0.
        base: f64,
        /// Decrease per order.
        decrement: f64,
    },
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

/// A filled area painted under the drawing (a layout shape).
#[derive(Debug, Clone, PartialEq)]
pub struct Fill {
    /// Fill colour.
    pub color: Rgb,
    /// Closed rings, canvas units; filled with the even-odd rule.
    pub rings: Vec<Vec<Point>>,
}

/// Size and format of the output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// PNG or SVG.
    pub format: ImageFormat,
    /// Output size in pixels; `None`: longest side [`DEFAULT_SIDE`], the
    /// other from the picture's aspect ratio.
    pub size: Option<(u32, u32)>,
}

/// Longest side of the output when no size is asked for.
pub const DEFAULT_SIDE: u32 = 800;

/// Something that can draw itself into a turtle, any number of times.
pub type Drawing<'a> =
    dyn FnMut(&mut dyn Turtle, &mut dyn Progress) -> Result<(), Diagnostics> + 'a;

/// Renders `drawing` to `out`. `view`: the canvas area to show (a layout's
/// bounds), or `None` to fit the picture from a bounding pass.
pub fn render(
    drawing: &mut Drawing<'_>,
    view: Option<BBox>,
    underlay: &[Fill],
    style: &Style,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    let _ = (drawing, view, underlay, style, opts, out, progress);
    unimplemented!("issue 2")
}
