//! Work on the raster without tiny-skia's path rasteriser: blots painted
//! by distance, the test for a stroke that covers the whole picture, and
//! the table of recently drawn wide capsules. Points are output pixels.

use crate::color::Rgb;
use crate::turtle::Point;

/// What a stand-in paints around its chord: the ink of a pixel as a
/// function of its centre's distance to the chord.
#[derive(Debug, Clone)]
pub(super) enum Shape {
    /// A solid capsule of this radius: covered by `radius + 0.5` minus the
    /// distance, clamped to 0..1 ([`Turtle::stand_in`](crate::turtle::Turtle::stand_in)).
    Capsule(f64),
    /// A bush's hairlines spread evenly across its footprint
    /// ([`Bush::new`]).
    Bush(Bush),
    /// A bush's own ink, sampled ([`field`](super::field)): `a` is
    /// its start.
    Field(std::sync::Arc<super::field::Field>),
}

/// The expected ink of a bush's stand-in: the strokes it stands for,
/// spread evenly `spread` to either side of the chord, each leaving the
/// ink a stroke leaves across it (tiny-skia draws strokes up to a pixel
/// wide as anti-aliased hairlines: coverage `width x (1 - distance)`;
/// wider ones cover `width / 2 + 0.5 - distance`, clamped), and their
/// coverages piling up as independent layers: a pixel whose strokes'
/// coverages sum to `lambda` is inked `1 - exp(-lambda)`. So a stand-in
/// inks what the exact drawing of so many strokes in so small an area
/// inks on average, darker in the middle, fading over the strokes' own
/// reach at the edge, and the deeper the subtree (the more strokes), the
/// farther out its edge is half inked, as the exact drawing's is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Bush {
    /// Half-width of the footprint across the chord, pixels.
    spread: f64,
    /// The stroke's coverage across it: `height` within `plateau` of its
    /// middle, falling linearly to 0 over the next pixel.
    height: f64,
    plateau: f64,
    /// Total coverage over the integral of the profile: `lambda` at a
    /// pixel is `scale x profile(distance)`.
    scale: f64,
}

impl Bush {
    /// The bush of strokes `stroke` pixels wide, `length` pixels in all,
    /// in `runs` separate runs (each with its two caps: a hairline run is
    /// drawn `pi / 8` longer at each end, a wider one has round caps),
    /// spread `spread` pixels to either side of a chord `chord` pixels
    /// long.
    pub(super) fn new(stroke: f64, spread: f64, chord: f64, length: f64, runs: f64) -> Bush {
        // A hairline run is drawn `pi / 8` longer at each end, in the
        // run's direction: that part of the ink (the caps' share of it)
        // lies up to `pi / 8` beyond the bush's box, about evenly spread
        // over directions. The footprint is widened to the spread whose
        // even distribution has the same second moment: the box's
        // `spread^2 / 3` plus the caps' share of `outset^2 / 6`.
        let (height, plateau, cap, outset) = if stroke <= 1.0 {
            let outset = std::f64::consts::PI / 8.0;
            (stroke, 0.0, 2.0 * outset, outset)
        } else {
            (
                1.0,
                stroke / 2.0 - 0.5,
                std::f64::consts::PI * stroke / 4.0,
                0.0,
            )
        };
        let caps = runs * cap / (length + runs * cap);
        let caps = if caps.is_finite() { caps } else { 0.0 };
        let spread = spread.max(0.0);
        let mut b = Bush {
            spread: libm::sqrt(spread * spread + caps * outset * outset / 2.0),
            height,
            plateau,
            scale: 0.0,
        };
        // The profile's integral over the plane: along the chord its
        // integral across (the stroke width) per unit length, plus the
        // half-discs at the ends, summed in rings.
        // (Midpoint rule on a piecewise quadratic: within 0.1 %.)
        const RINGS: usize = 12;
        let reach = b.reach();
        let dr = reach / RINGS as f64;
        let ends: f64 = (0..RINGS)
            .map(|i| {
                let r = (i as f64 + 0.5) * dr;
                b.profile(r) * r * dr
            })
            .sum();
        let integral = chord * stroke + 2.0 * std::f64::consts::PI * ends;
        let ink = stroke * (length + runs * cap);
        b.scale = if integral > 0.0 && ink.is_finite() {
            ink / integral
        } else {
            0.0
        };
        b
    }

    /// Beyond this distance from the chord nothing is inked.
    fn reach(&self) -> f64 {
        self.spread + self.plateau + 1.0
    }

    /// Integral of one stroke's coverage from its middle out to `x`
    /// (odd in `x`).
    fn half(&self, x: f64) -> f64 {
        let a = x.abs();
        let v = if a <= self.plateau {
            a
        } else {
            let t = (a - self.plateau).min(1.0);
            self.plateau + t - t * t / 2.0
        };
        self.height * v.copysign(x)
    }

    /// One stroke's coverage averaged over its positions across the
    /// footprint, at distance `r` from the chord.
    fn profile(&self, r: f64) -> f64 {
        let s = self.spread;
        if s > 1e-6 {
            (self.half(r + s) - self.half(r - s)) / (2.0 * s)
        } else {
            let t = (r.abs() - self.plateau).max(0.0);
            self.height * (1.0 - t).max(0.0)
        }
    }

    /// The ink at distance `r`, 0..1.
    fn ink(&self, r: f64) -> f64 {
        let lambda = self.scale * self.profile(r);
        // Past ln(510) the ink rounds to full: no exp.
        if lambda > 6.24 {
            1.0
        } else {
            1.0 - libm::exp(-lambda)
        }
    }
}

/// A blot for the bands: its ends and shape, and the rows it can reach
/// (found once, so each band passes over the blots that miss it with a
/// comparison instead of a call).
#[derive(Debug, Clone)]
pub(super) struct Blot {
    pub(super) a: Point,
    pub(super) b: Point,
    pub(super) shape: Shape,
    /// Lowest and highest row it can ink, a pixel to spare each way.
    rows: (f64, f64),
}

impl Blot {
    pub(super) fn new(a: Point, b: Point, shape: Shape) -> Blot {
        let rows = match &shape {
            Shape::Field(field) => field.rows(a),
            Shape::Capsule(radius) => around(a, b, radius + 0.5),
            Shape::Bush(bush) => around(a, b, bush.reach()),
        };
        Blot { a, b, shape, rows }
    }

    /// Whether it may ink any of `rows` ([`stamp`] inks nothing where
    /// not).
    #[inline]
    pub(super) fn reaches(&self, rows: &std::ops::Range<u32>) -> bool {
        // NaN ends compare false and are handed on, as before.
        !(self.rows.1 < f64::from(rows.start) || self.rows.0 > f64::from(rows.end))
    }
}

/// The rows within `reach` of `a`-`b`, a pixel to spare.
fn around(a: Point, b: Point, reach: f64) -> (f64, f64) {
    (a.y.min(b.y) - reach - 1.0, a.y.max(b.y) + reach + 1.0)
}

/// Paints a blot: the `shape` around `a`-`b` (each pixel by its centre's
/// distance to the segment), blended source-over in `ink`. Overlapping
/// blots accumulate, as the strokes they stand for do. A few dozen pixels
/// each, instead of a stroked path's outline and scan conversion.
///
/// `rows` is the part of the picture `data` holds: a band of whole rows
/// (`data` is `width` pixels wide, its first row the picture's row
/// `rows.start`); `a`, `b` are in the whole picture's pixels, so every
/// pixel gets the same value whichever band paints it.
pub(super) fn stamp(
    data: &mut [u8],
    width: u32,
    rows: std::ops::Range<u32>,
    ink: Rgb,
    a: Point,
    b: Point,
    shape: &Shape,
) {
    let w = f64::from(width);
    let (top, bottom) = (f64::from(rows.start), f64::from(rows.end));
    let reach = match shape {
        Shape::Capsule(radius) => radius + 0.5,
        Shape::Bush(bush) => bush.reach(),
        Shape::Field(field) => {
            return super::field::stamp(data, width, rows, ink, a, field);
        }
    };
    let (lo_x, hi_x) = (a.x.min(b.x) - reach, a.x.max(b.x) + reach);
    let (lo_y, hi_y) = (a.y.min(b.y) - reach, a.y.max(b.y) + reach);
    if hi_x < 0.0 || hi_y < top || lo_x >= w || lo_y >= bottom {
        return;
    }
    // Every bound is at least 0 here (`max` ignores a NaN; `hi_x`, `hi_y`
    // passed the test above), where `floor` is the cast's truncation.
    let x0 = lo_x.max(0.0) as usize;
    let y0 = lo_y.max(top) as usize;
    let x1 = ceil(hi_x.min(w - 1.0));
    let y1 = ceil(hi_y.min(bottom - 1.0));
    let first_row = rows.start as usize;
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len2 = dx * dx + dy * dy;
    let inv = if len2 > 0.0 { 1.0 / len2 } else { 0.0 };
    // Beyond `outer` nothing is covered; within `inner` all is.
    let outer = reach * reach;
    let inner = match shape {
        Shape::Capsule(radius) if *radius > 0.5 => (radius - 0.5) * (radius - 0.5),
        _ => -1.0,
    };
    let stride = width as usize;
    let src = [u32::from(ink.r), u32::from(ink.g), u32::from(ink.b), 255];
    for y in y0..=y1 {
        let py = y as f64 + 0.5;
        for x in x0..=x1 {
            let px = x as f64 + 0.5;
            let t = (((px - a.x) * dx + (py - a.y) * dy) * inv).clamp(0.0, 1.0);
            let (qx, qy) = (a.x + t * dx - px, a.y + t * dy - py);
            let d2 = qx * qx + qy * qy;
            if d2 >= outer {
                continue;
            }
            let cov = match shape {
                _ if d2 <= inner => 1.0,
                Shape::Capsule(_) => (reach - libm::sqrt(d2)).clamp(0.0, 1.0),
                Shape::Bush(bush) => bush.ink(libm::sqrt(d2)),
                // Stamped by `sample::stamp` above.
                Shape::Field(_) => 0.0,
            };
            let c = (cov * 255.0 + 0.5) as u32;
            if c == 0 {
                continue;
            }
            let i = ((y - first_row) * stride + x) * 4;
            for (ch, &s) in src.iter().enumerate() {
                let d = u32::from(data[i + ch]);
                data[i + ch] = ((s * c + d * (255 - c) + 127) / 255) as u8;
            }
        }
    }
}

/// `libm::ceil(v) as usize` for `v` from 0 up to 2^53 without a call:
/// the cast truncates, which is the ceiling unless a fraction was cut.
#[inline]
fn ceil(v: f64) -> usize {
    let t = v as usize;
    if (t as f64) < v { t + 1 } else { t }
}

/// How far the raster's farthest pixel corner is from the segment `a`-`b`:
/// the distance to a segment is convex, so its largest value over the
/// raster is at a corner.
#[inline]
pub(super) fn farthest_corner((width, height): (u32, u32), a: Point, b: Point) -> f64 {
    let (w, h) = (f64::from(width), f64::from(height));
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let len2 = dx * dx + dy * dy;
    [(0.0, 0.0), (w, 0.0), (0.0, h), (w, h)]
        .iter()
        .map(|&(px, py)| {
            let t = if len2 > 0.0 {
                (((px - a.x) * dx + (py - a.y) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            libm::hypot(a.x + t * dx - px, a.y + t * dy - py)
        })
        .fold(0.0, f64::max)
}

/// Buckets of the recent-capsule table (two capsules each; 400 KB).
const RECENT_BUCKETS: usize = 4096;

/// The last wide capsules drawn, two per bucket by a hash of their ends
/// and width: a lossy memory, so a repeat is sometimes drawn again (which
/// paints nothing new) but a capsule never drawn is never skipped.
pub(super) struct Recent {
    buckets: Vec<[Option<[u64; 5]>; 2]>,
}

impl Recent {
    pub(super) fn new() -> Recent {
        // Allocated on first use: most turtles (and every bush's sample
        // turtle) never draw a wide capsule.
        Recent {
            buckets: Vec::new(),
        }
    }

    /// Whether the capsule `from`-`to` of `width` was one of the last drawn
    /// in its bucket; if not, it is remembered as drawn.
    #[inline]
    pub(super) fn repeats(&mut self, from: Point, to: Point, width: f64) -> bool {
        let key = [from.x, from.y, to.x, to.y, width].map(f64::to_bits);
        if self.buckets.is_empty() {
            self.buckets = vec![[None; 2]; RECENT_BUCKETS];
        }
        let bucket = &mut self.buckets[bucket_of(&key)];
        if bucket.contains(&Some(key)) {
            return true;
        }
        bucket[1] = bucket[0];
        bucket[0] = Some(key);
        false
    }
}

/// The bucket of a capsule key (splitmix64's finalizer over its bits).
fn bucket_of(key: &[u64; 5]) -> usize {
    let mut h: u64 = 0;
    for k in key {
        h = (h ^ k).wrapping_add(0x9e37_79b9_7f4a_7c15);
        h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        h ^= h >> 31;
    }
    (h % RECENT_BUCKETS as u64) as usize
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::png::field::round_i64;

    /// Corner distances worked by hand on a 100 x 50 raster.
    #[test]
    fn the_farthest_corner_is_measured_to_the_segment_not_its_ends() {
        let p = (100, 50);
        let pt = Point::new;
        // From the centre point: every corner is hypot(50, 25) away.
        let c = farthest_corner(p, pt(50.0, 25.0), pt(50.0, 25.0));
        assert!((c - libm::hypot(50.0, 25.0)).abs() < 1e-12);
        // A horizontal segment across the middle: each corner is 25 away.
        let c = farthest_corner(p, pt(0.0, 25.0), pt(100.0, 25.0));
        assert!((c - 25.0).abs() < 1e-12);
    }

    /// A bush's profile worked by hand. Hairlines 1 px wide, no spread:
    /// one stroke's coverage `1 - r`, whose integral over the plane around
    /// a 10 px chord is 10 + pi / 3; 10 px of strokes there give
    /// lambda = 10 / (10 + pi / 3) (1 - r). Spread 0.5: the coverage
    /// averaged over [-0.5, 0.5] is 0.75 on the chord, 0 from 1.5 px on.
    /// A run's caps (pi / 8 px at each end) widen the spread to
    /// sqrt(spread^2 + (pi / 8)^2 / 2) when they are all its ink.
    #[test]
    fn a_bushs_ink_is_its_strokes_coverage_spread_over_its_footprint() {
        let b = Bush::new(1.0, 0.0, 10.0, 10.0, 0.0);
        let lambda = 10.0 / (10.0 + std::f64::consts::PI / 3.0);
        for r in [0.0, 0.25, 0.5, 0.9] {
            let want = 1.0 - libm::exp(-lambda * (1.0 - r));
            assert!((b.ink(r) - want).abs() < 1e-3, "{r}: {} {want}", b.ink(r));
        }
        // So many strokes that the ink rounds to full: 1.
        assert_eq!(Bush::new(1.0, 0.0, 10.0, 100.0, 0.0).ink(0.0), 1.0);
        assert_eq!(b.ink(1.0), 0.0);
        let b = Bush::new(1.0, 0.5, 10.0, 100.0, 0.0);
        assert!((b.profile(0.0) - 0.75).abs() < 1e-12);
        assert!((b.profile(1.0) - 0.125).abs() < 1e-12);
        assert_eq!(b.profile(1.5), 0.0);
        assert_eq!(b.reach(), 1.5);
        let dot = Bush::new(1.0, 0.0, 0.0, 0.0, 1.0);
        let o = std::f64::consts::PI / 8.0;
        assert!((dot.spread - o / std::f64::consts::SQRT_2).abs() < 1e-12);
        // Wider strokes: full coverage within half the width less half a
        // pixel, falling to 0 over the next pixel.
        let wide = Bush::new(3.0, 0.0, 10.0, 100.0, 0.0);
        assert_eq!(
            (wide.profile(1.0), wide.profile(1.5), wide.profile(2.0)),
            (1.0, 0.5, 0.0)
        );
    }

    /// Stamped: the pixel on the chord gets the ink at its distance, the
    /// more strokes the darker, nothing beyond the reach.
    #[test]
    fn a_bush_is_stamped_by_its_ink() {
        let black = Rgb { r: 0, g: 0, b: 0 };
        let paint = |length: f64| {
            let mut data = vec![255u8; 20 * 20 * 4];
            let bush = Bush::new(1.0, 0.0, 4.0, length, 0.0);
            let (a, b) = (Point::new(8.0, 10.5), Point::new(12.0, 10.5));
            stamp(&mut data, 20, 0..20, black, a, b, &Shape::Bush(bush));
            let at = |x: usize, y: usize| data[(y * 20 + x) * 4];
            let want = 255.0 * (1.0 - bush.ink(0.0));
            assert!(
                (f64::from(at(10, 10)) - want).abs() <= 1.0,
                "{} {want}",
                at(10, 10)
            );
            // (10.5, 11.5) is 1 px from the chord: the reach.
            assert_eq!((at(10, 11), at(10, 9), at(3, 10)), (255, 255, 255));
            at(10, 10)
        };
        assert!(paint(40.0) < paint(4.0));
    }

    /// The casts round as `libm` does, halves, signs, huge values, NaN
    /// and the infinities included, and on a sweep of quarter and tenth
    /// steps around zero and around 2^52.
    #[test]
    fn the_casts_round_as_libm_does() {
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4503599627370495.5,
            -4503599627370495.5,
            4503599627370497.0,
            9.3e18,
            -9.3e18,
            1e300,
            -1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for i in -4000..4000 {
            values.push(f64::from(i) / 4.0);
            values.push(f64::from(i) / 10.0);
            values.push(4503599627370496.0 + f64::from(i) / 4.0);
            values.push(f64::from(i) * 0.1 + 1e-9);
        }
        for v in values {
            assert_eq!(round_i64(v), libm::round(v) as i64, "round {v}");
            if (0.0..=9e15).contains(&v) {
                assert_eq!(ceil(v), libm::ceil(v) as usize, "ceil {v}");
                assert_eq!(v as usize, libm::floor(v) as usize, "floor {v}");
            }
        }
    }

    #[test]
    fn a_capsule_repeats_only_after_it_was_drawn() {
        let mut r = Recent::new();
        let (a, b) = (Point::new(1.0, 2.0), Point::new(3.0, 4.0));
        assert!(!r.repeats(a, b, 5.0));
        assert!(r.repeats(a, b, 5.0));
        assert!(!r.repeats(a, b, 6.0), "another width is another capsule");
        assert!(!r.repeats(b, a, 5.0), "and so is the other direction");
    }
}
