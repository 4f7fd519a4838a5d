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

use super::PngTurtle;
use crate::color::Rgb;
use crate::render::fit::{Fit, stroke_px};
use crate::render::style::{Style, Width};
use crate::turtle::{Point, Sample};

/// A bush is drawn at `SUB x SUB` offsets: a grid `1 / SUB` px apart.
const SUB: usize = 4;

/// A bush of at most this many segments is sampled exactly; a larger one
/// at a sixteenth of the detail (its own bushes then stand-ins as
/// [`Bush`](super::raster::Bush) models them).
pub(super) const EXACT_SEGMENTS: u64 = 4096;

/// A solid piece (docs/rendering.md, *Dense curves*) of at most this
/// many segments is drawn exactly, as a bush is, so it has the exact
/// drawing's tone (a dark grey where hairlines blended in 8 bits stall);
/// a larger one is left to its hatch, which is what the exact drawing's
/// ink converges to (black).
pub(super) const SOLID_SEGMENTS: u64 = 1 << 16;

/// Marks a dense piece's key ([`PngTurtle::dense_field`]): the top bit
/// of [`Sample::piece_key`]'s depth.
const DENSE_KEY: u128 = 1 << 95;

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
    full: bool,
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
        let u = super::raster::round_i64((q.x - self.min.x) * s);
        let v = super::raster::round_i64((q.y - self.min.y) * s);
        (u, v)
    }
}

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
            let mut turtle = PngTurtle::new(fit, &style).ok()?.with_detail(detail);
            // Its own bushes are modelled, not sampled again, unless
            // `nested`; its own dense pieces are walked.
            turtle.fields = nested.as_deref_mut().map(std::mem::take);
            turtle.dense = false;
            (sample.draw)(detail.map_or(0.0, |d| d / scale), &mut turtle);
            if let (Some(outer), Some(inner)) = (nested.as_deref_mut(), turtle.fields.take()) {
                *outer = inner;
            }
            let raster = turtle.into_raster()?;
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

impl PngTurtle {
    /// [`Turtle::stand_in`] with a sample: the bush's sampled field, exactly up to
    /// [`EXACT_SEGMENTS`], past them at a sixteenth of the detail.
    pub(super) fn sampled_bush(&mut self, sample: &Sample) -> Option<Arc<Field>> {
        let detail = self.detail? * self.fit.scale;
        if !self.hairline() {
            return None;
        }
        let detail = (sample.segments > EXACT_SEGMENTS).then_some(detail / 16.0);
        let fields = self.fields.as_mut()?;
        fields.get(sample, self.fit.scale, self.width, (SUB, detail, false))
    }

    /// [`Turtle::solid`]: the solid piece's field, drawn exactly, if it
    /// has at most [`SOLID_SEGMENTS`].
    pub(super) fn sampled_solid(&mut self, sample: &Sample) -> Option<Arc<Field>> {
        self.detail?;
        if sample.segments > SOLID_SEGMENTS || !self.hairline() {
            return None;
        }
        let fields = self.fields.as_mut()?;
        fields.get(sample, self.fit.scale, self.width, (4, None, false))
    }

    /// [`Turtle::dense`]: the piece's field, drawn at the detail with its
    /// own bushes sampled, if its strokes ink its footprint fully. Keyed
    /// apart from the same piece cut as a bush.
    pub(super) fn dense_field(&mut self, sample: &Sample) -> Option<Arc<Field>> {
        let detail = self.detail? * self.fit.scale;
        if !self.dense || !self.hairline() {
            return None;
        }
        let keyed = Sample {
            key: sample.key | DENSE_KEY,
            ..*sample
        };
        let fields = self.fields.as_mut()?;
        let field = fields.get(
            &keyed,
            self.fit.scale,
            self.width,
            (SUB, Some(detail), true),
        )?;
        field.full.then_some(field)
    }

    /// Whether the strokes are hairlines (at most a pixel wide), whose
    /// every segment blends over the others, so stamps that blend over
    /// each other ink what they stand for. A wider stroke's path is
    /// filled as one outline (a union: overlaps ink once), which stamps
    /// cannot be: its bushes keep the model.
    fn hairline(&self) -> bool {
        stroke_px(&self.width, self.fit.scale, 0) <= 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::turtle::{Footprint, Segment, StandIn, Turtle};
    use tiny_skia::Pixmap;

    /// A twig of 1.24a's shape, `F[+F]F[-F]F` twice over (25 segments of
    /// `len` px, 25.7 degrees), from the origin upwards, into `t` moved
    /// by `at`.
    fn twig(t: &mut dyn Turtle, at: Point, len: f64) {
        fn go(t: &mut dyn Turtle, p: &mut (f64, f64, f64), depth: u32, len: f64, at: Point) {
            if depth == 0 {
                let (x, y, a) = *p;
                let (nx, ny) = (x + len * libm::sin(a), y - len * libm::cos(a));
                t.segment(Segment {
                    from: Point::new(at.x + x, at.y + y),
                    to: Point::new(at.x + nx, at.y + ny),
                    order: 0,
                });
                *p = (nx, ny, a);
                return;
            }
            let turn = 25.7f64.to_radians();
            for part in 0..5 {
                if part % 2 == 1 {
                    let saved = *p;
                    p.2 += if part == 1 { turn } else { -turn };
                    go(t, p, depth - 1, len, at);
                    *p = saved;
                } else {
                    go(t, p, depth - 1, len, at);
                }
            }
        }
        go(t, &mut (0.0, 0.0, 0.0), 2, len, at);
    }

    fn picture() -> PngTurtle {
        let fit = Fit {
            width: 16,
            height: 16,
            scale: 1.0,
            dx: 0.0,
            dy: 0.0,
        };
        let style = Style {
            stroke: Rgb::BLACK,
            background: Some(Rgb::WHITE),
            width: Width::Pixels(1.0),
        };
        PngTurtle::new(fit, &style).unwrap().with_detail(Some(0.5))
    }

    /// The twig drawn exactly at `at`, and stood in for by its sample.
    fn both(at: Point, len: f64, lo: Point) -> (Vec<u8>, Vec<u8>) {
        let mut exact = picture().with_detail(None);
        twig(&mut exact, at, len);
        let exact = exact.into_raster().unwrap();
        let draw = |_: f64, t: &mut dyn Turtle| twig(t, Point::new(0.0, 0.0), len);
        let sample = Sample {
            at,
            key: 1,
            bounds: (lo, Point::new(0.5, 0.0)),
            segments: 25,
            draw: &draw,
        };
        let mut stood = picture();
        let seg = Segment {
            from: at,
            to: at,
            order: 0,
        };
        stood.stand_in(&StandIn {
            seg,
            density: 25.0,
            footprint: Some(Footprint {
                spread: 0.5,
                runs: 8.0,
            }),
            sample: Some(&sample),
        });
        let red = |p: Pixmap| p.data().chunks(4).map(|c| c[0]).collect();
        (red(exact), red(stood.into_raster().unwrap()))
    }

    /// Where the bush starts on the sample's grid (a quarter pixel), its
    /// stand-in is its own drawing, to the rounding of the stamp.
    #[test]
    fn a_bush_on_the_grid_is_stamped_as_drawn() {
        for (at, len) in [
            (Point::new(8.25, 9.5), 0.04),
            (Point::new(7.75, 9.25), 0.02),
            (Point::new(8.5, 8.0), 0.1),
        ] {
            let (exact, stood) = both(at, len, Point::new(-0.5, -1.0));
            assert!(exact.iter().any(|&v| v < 128), "{at:?} draws");
            for (i, (a, b)) in exact.iter().zip(&stood).enumerate() {
                assert!(
                    a.abs_diff(*b) <= 2,
                    "{at:?} {len} pixel {i}: {a} drawn, {b} stamped"
                );
            }
        }
    }

    /// Anywhere else it is its drawing moved by at most an eighth of a
    /// pixel each way: over 169 starts a thirteenth of a pixel apart,
    /// about as much ink and as many pixels half inked as its drawing.
    /// (Measured: ink +1.4 %, +2.0 %, -0.1 %, inked pixels -1.7 %,
    /// +3.5 %, +2.4 %: a bush this small inks very differently a
    /// fraction of a pixel apart, and 16 offsets sample that.)
    #[test]
    fn a_bush_off_the_grid_inks_about_what_it_draws() {
        for len in [0.02, 0.04, 0.1] {
            let (mut ink, mut inked) = ([0u32; 2], [0usize; 2]);
            for i in 0..13 {
                for j in 0..13 {
                    let at = Point::new(8.0 + f64::from(i) / 13.0, 9.0 + f64::from(j) / 13.0);
                    let (exact, stood) = both(at, len, Point::new(-0.537, -1.013));
                    for (k, p) in [exact, stood].iter().enumerate() {
                        ink[k] += p.iter().map(|&v| 255 - u32::from(v)).sum::<u32>();
                        inked[k] += p.iter().filter(|&&v| v < 128).count();
                    }
                }
            }
            assert!(
                ink[0].abs_diff(ink[1]) * 100 <= 3 * ink[0],
                "{len}: ink {ink:?}"
            );
            assert!(
                inked[0].abs_diff(inked[1]) * 100 <= 5 * inked[0],
                "{len}: {inked:?}"
            );
        }
    }
}
