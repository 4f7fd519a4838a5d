//! Fitting: how canvas units map to output pixels, from the drawing's box
//! or a fixed view (a layout's canvas), with margins for the widest stroke,
//! and the checks on the output's size.

use super::style::{DEFAULT_SIDE, HAIRLINE, MARGIN_FRACTION, MAX_SIDE, MIN_MARGIN, Width};
use crate::diag::{Diagnostic, Diagnostics, Help, Knob, RenderError};
use crate::turtle::{BBox, Fill, Point};

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
            return Err(Diagnostic::error(RenderError::BadCanvas {
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
            return Err(Diagnostic::error(RenderError::DrawingNotFinite)
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
pub(super) fn checked_size((w, h): (u32, u32)) -> Result<(u32, u32), Diagnostics> {
    if (1..=MAX_SIDE).contains(&w) && (1..=MAX_SIDE).contains(&h) {
        Ok((w, h))
    } else {
        Err(Diagnostic::error(RenderError::ImageSize {
            width: w,
            height: h,
            max: MAX_SIDE,
        })
        .with_help(
            Help::from("ask for a smaller picture: ")
                + Help::knob(Knob::Size, &format!("{DEFAULT_SIDE}x{DEFAULT_SIDE}"))
                + " or less",
        )
        .into())
    }
}

/// The box of every point of `fills`' rings; `None` for no point.
pub fn fills_bbox(fills: &[Fill]) -> Option<BBox> {
    let mut points = fills.iter().flat_map(|f| &f.rings).flatten();
    let mut b = BBox::at(*points.next()?);
    points.for_each(|p| b.add(*p));
    Some(b)
}

/// The canvas area a picture framed by its layout shows: the layout's box
/// `b` with the fitted picture's margin and half the widest stem (`widest`,
/// the description's `B` base) around it. A 3D tree's view is framed by
/// its volumes' outlines the same way, so `--view 0,0` of a planar tree is
/// its 2D picture, size included.
pub fn layout_frame(b: BBox, widest: f64) -> BBox {
    let m = MARGIN_FRACTION * b.width().max(b.height()) + widest.max(0.0) / 2.0;
    BBox {
        min_x: b.min_x - m,
        min_y: b.min_y - m,
        max_x: b.max_x + m,
        max_y: b.max_y + m,
    }
}
