//! Bushes drawn from themselves ([`Turtle::stand_in`] with a sample): each distinct bush
//! is rasterised once, by this backend, at sixteen sub-pixel positions
//! (a grid a quarter pixel apart), into the ink it leaves around its
//! start; wherever the bush recurs the ink of the grid point nearest
//! each pixel is stamped (its own drawing moved at most an eighth of a
//! pixel each way). So a stand-in inks what its own strokes
//! ink, caps, folds and hairline coverage included, instead of a model
//! of them (docs/rendering.md, *Silhouette*).
//!
//! The ink is kept as the sample's coverage (0-255) at each grid point,
//! and stamped source-over: a pixel under bushes of coverages `c1, c2,
//! ...` keeps `(1 - c1)(1 - c2)...` of its colour, as under the strokes
//! themselves, each blended over the others.

/// The memo's map, hashed by foldhash's fixed state: SipHash cost about
/// 5 % of a dense picture (issue 37); nothing iterates it into output.
type HashMap<K, V> = std::collections::HashMap<K, V, foldhash::fast::FixedState>;
use std::sync::Arc;

use tiny_skia::Pixmap;

use crate::color::Rgb;
use crate::render::fit::{Fit, stroke_px};
use crate::render::style::{Style, Width};
use crate::turtle::{Point, Sample};

/// A bush is drawn at `SUB x SUB` offsets: a grid `1 / SUB` px apart.
pub(super) const SUB: usize = 4;

/// A bush of at most this many segments is sampled exactly; a larger one
/// at a sixteenth of the detail (its own bushes then stand-ins as
/// [`Bush`](super::raster::Bush) models them).
pub(super) const EXACT_SEGMENTS: u64 = 4096;

/// A solid piece (docs/rendering.md, *Dense curves*) of at most this
/// many segments is drawn exactly, as a bush is, so it has the exact
/// drawing's tone (a dark grey where hairlines blended in 8 bits stall);
/// a larger one is drawn at the detail, which makes it its hatched box
/// (what the exact drawing's ink converges to), sampled once per
/// distinct piece and stamped like the others: tiny-skia's hairlines
/// hatching every occurrence were most of Hilbert at depth 30 (issue 37).
pub(super) const SOLID_SEGMENTS: u64 = 1 << 16;

/// Marks a dense piece's key (a dense piece's field): the top bit
/// of [`Sample::piece_key`]'s depth.
pub(super) const DENSE_KEY: u128 = 1 << 95;

/// At most this many bushes are sampled in one drawing (a few hundred
/// bytes each with hairlines); past it, the rest are modelled.
const MAX_FIELDS: usize = 16_384;

/// And at most this many grid points (bytes) in all: 8 MB.
const MAX_POINTS: usize = 1 << 23;

/// A bush's ink around its start: its coverage at grid points `1 / sub`
/// px apart, the first at `min` (output pixels, relative to the start).
#[derive(Debug)]
pub(super) struct Field {
    sub: usize,
    min: Point,
    nx: usize,
    ny: usize,
    /// At least half of the points it inks are full ink: its strokes ink
    /// its footprint fully ([`Turtle::dense`](crate::turtle::Turtle::dense)).
    pub(super) full: bool,
    cov: Vec<u8>,
}

impl Field {
    /// The rows the field can ink, its start at `at`, with a pixel to
    /// spare at each end: pixel row `y`'s grid row is within half a step
    /// of `(y + 0.5 - at.y - min.y) sub`, so it is on the grid only from
    /// `at.y + min.y - 1` to `at.y + min.y + ny / sub`.
    pub(super) fn rows(&self, at: Point) -> (f64, f64) {
        let top = at.y + self.min.y;
        (top - 2.0, top + self.ny as f64 / self.sub as f64 + 2.0)
    }

    /// The grid point nearest a pixel whose centre is at `q` from the
    /// start: the bush's own drawing moved at most half a grid step each
    /// way (interpolating between the grid's points would blur it).
    fn nearest(&self, q: Point) -> (i64, i64) {
        let s = self.sub as f64;
        let u = round_i64((q.x - self.min.x) * s);
        let v = round_i64((q.y - self.min.y) * s);
        (u, v)
    }
}

/// Draws a sample onto a transparent raster of `fit` in `style`, at a
/// level of detail in output pixels (`None`: exactly), its own bushes
/// sampled from the fields given (modelled without): the raster (`None`
/// if it cannot be drawn) and the fields back. The backend's own drawing,
/// handed in so the fields need not know the backend.
pub(super) type Draw =
    fn(&Sample, Fit, &Style, Option<f64>, Option<Fields>) -> (Option<Pixmap>, Option<Fields>);

/// The bushes sampled so far in one drawing.
#[derive(Default)]
pub(super) struct Fields {
    by_key: HashMap<u128, Option<Arc<Field>>>,
    /// Grid points held.
    points: usize,
}

impl Fields {
    /// The field of `sample`, drawn with strokes of `width` at `fit`'s
    /// scale at `sub x sub` offsets, exactly or at a level of detail of
    /// `detail_px`; `None` when there are too many or it cannot be drawn.
    ///
    /// `nested`: its own bushes are sampled too (from these fields, at
    /// the same scale), as a dense piece's are; else they are modelled.
    pub(super) fn get(
        &mut self,
        sample: &Sample,
        scale: f64,
        width: Width,
        (sub, detail_px, nested): (usize, Option<f64>, bool),
        draw: Draw,
    ) -> Option<Arc<Field>> {
        if let Some(f) = self.by_key.get(&sample.key) {
            return f.clone();
        }
        if self.by_key.len() >= MAX_FIELDS || self.points >= MAX_POINTS {
            return None;
        }
        let room = MAX_POINTS - self.points;
        let field = build(
            sample,
            scale,
            width,
            (sub, detail_px),
            room,
            nested.then_some(&mut *self),
            draw,
        );
        let field = field.map(Arc::new);
        self.points += field.as_ref().map_or(0, |f| f.cov.len());
        self.by_key.insert(sample.key, field.clone());
        field
    }
}

/// How far beyond its lines a drawing of strokes `width` wide at `scale`
/// can ink, output pixels: a hairline a pixel beyond its line and its
/// caps `pi / 8` past its ends; a wider stroke half its width and the
/// pixel's half. (A little more, to be sure.)
pub(super) fn reach_px(width: Width, scale: f64) -> f64 {
    stroke_px(&width, scale, 0).max(1.0) / 2.0 + 1.5
}

/// Rasterises `sample` at `sub x sub` offsets, each on its own small
/// transparent raster in black, and keeps its coverage (alpha);
/// `None` if the grid would have more than `room` points.
fn build(
    sample: &Sample,
    scale: f64,
    width: Width,
    (sub, detail): (usize, Option<f64>),
    room: usize,
    mut nested: Option<&mut Fields>,
    draw: Draw,
) -> Option<Field> {
    let step = 1.0 / sub as f64;
    let (lo, hi) = sample.bounds;
    let margin = reach_px(width, scale);
    let min = Point::new(lo.x * scale - margin, lo.y * scale - margin);
    let span = |a: f64, b: f64| ((b - a) * scale + 2.0 * margin) / step;
    let (sx, sy) = (span(lo.x, hi.x), span(lo.y, hi.y));
    if !(sx.is_finite() && sy.is_finite() && sx < 1024.0 && sy < 1024.0) {
        return None;
    }
    let (nx, ny) = (sx.ceil() as usize + 1, sy.ceil() as usize + 1);
    if nx * ny > room {
        return None;
    }
    let (tw, th) = (nx.div_ceil(sub), ny.div_ceil(sub));
    let style = Style {
        stroke: Rgb { r: 0, g: 0, b: 0 },
        background: None,
        width,
    };
    let mut cov = vec![0u8; nx * ny];
    for j in 0..sub {
        for i in 0..sub {
            // Tile pixel (px, py) has its centre at
            // `min + ((sub px + i) step, (sub py + j) step)` from the start.
            let fit = Fit {
                width: tw as u32,
                height: th as u32,
                scale,
                dx: 0.5 - min.x - i as f64 * step,
                dy: 0.5 - min.y - j as f64 * step,
            };
            // Its own bushes are modelled, not sampled again, unless
            // `nested`.
            let (raster, inner) = draw(
                sample,
                fit,
                &style,
                detail,
                nested.as_deref_mut().map(std::mem::take),
            );
            if let (Some(outer), Some(inner)) = (nested.as_deref_mut(), inner) {
                *outer = inner;
            }
            let raster = raster?;
            let data = raster.data();
            for py in 0..th {
                let gy = sub * py + j;
                if gy >= ny {
                    break;
                }
                for px in 0..tw {
                    let gx = sub * px + i;
                    if gx >= nx {
                        break;
                    }
                    cov[gy * nx + gx] = data[(py * tw + px) * 4 + 3];
                }
            }
        }
    }
    let inked = cov.iter().filter(|&&c| c > 0).count();
    let full = cov.iter().filter(|&&c| c == 255).count();
    Some(Field {
        sub,
        min,
        nx,
        ny,
        full: full * 2 >= inked && inked > 0,
        cov,
    })
}

/// Paints `field`, its start at `at` (whole-picture pixels), blended
/// source-over in `ink` into the band `rows` of `data` (`width` pixels
/// wide), as [`raster::stamp`](super::raster::stamp) paints a blot.
pub(super) fn stamp(
    data: &mut [u8],
    width: u32,
    rows: std::ops::Range<u32>,
    ink: Rgb,
    at: Point,
    field: &Field,
) {
    // A band the field cannot reach is left at once.
    let (lo, hi) = field.rows(at);
    if hi < f64::from(rows.start) || lo > f64::from(rows.end) {
        return;
    }
    // Pixel (x, y)'s nearest grid point is (u0 + sub x, v0 + sub y): a
    // pixel further is `sub` grid points further.
    let (u0, v0) = field.nearest(Point::new(0.5 - at.x, 0.5 - at.y));
    let sub = field.sub as i64;
    let (nx, ny) = (field.nx as i64, field.ny as i64);
    // The pixels whose grid points are inside the grid.
    let first = |o: i64| (-o).max(0).div_euclid(sub) + i64::from((-o).max(0) % sub != 0);
    let last = |o: i64, n: i64| (n - 1 - o).div_euclid(sub);
    let (x0, x1) = (first(u0).max(0), last(u0, nx).min(i64::from(width) - 1));
    let (y0, y1) = (
        first(v0).max(i64::from(rows.start)),
        last(v0, ny).min(i64::from(rows.end) - 1),
    );
    if x0 > x1 || y0 > y1 {
        return;
    }
    let first_row = i64::from(rows.start);
    let stride = width as usize;
    let src = [u32::from(ink.r), u32::from(ink.g), u32::from(ink.b), 255];
    for y in y0..=y1 {
        let grid = ((v0 + sub * y) * nx) as usize;
        let line = (y - first_row) as usize * stride;
        for x in x0..=x1 {
            let c = u32::from(field.cov[grid + (u0 + sub * x) as usize]);
            if c == 0 {
                continue;
            }
            let i = (line + x as usize) * 4;
            for (ch, &s) in src.iter().enumerate() {
                let d = u32::from(data[i + ch]);
                data[i + ch] = ((s * c + d * (255 - c) + 127) / 255) as u8;
            }
        }
    }
}

/// `libm::round(v) as i64` (halves away from zero) without a call: the
/// cast truncates, and `v` less its truncation is exact (the fraction of
/// a double is a double), so comparing it with one half rounds as
/// `round` does; past `i64`'s range both saturate, and NaN gives 0.
#[inline]
pub(super) fn round_i64(v: f64) -> i64 {
    let t = v as i64;
    let f = v - t as f64;
    if f >= 0.5 {
        t.saturating_add(1)
    } else if f <= -0.5 {
        t.saturating_sub(1)
    } else {
        t
    }
}
