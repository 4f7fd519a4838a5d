//! The turtle: where drawing components end up.
//!
//! The turtle state machine ([`Interp`], in `interp.rs`) keeps the turtle
//! *state* (position, heading, stack), applies [`Op`]s and hands every drawn
//! stem to a [`Turtle`] backend as a [`Segment`]. [`Fill`]s are the areas a
//! backend paints under the drawing (layout shapes). Backends: [`Recorder`] (segment lists, for tests),
//! [`Bounds`] (the first, bounding pass: 000's `GetCurveSize`), and the PNG and
//! SVG backends in `render`.
//!
//! Coordinates are canvas coordinates: origin top-left, y grows downward. The
//! turtle starts heading up the canvas (-y); a left turn is counter-clockwise
//! on screen.
//!
//! Headings are kept exactly, as an integer number of turns `k` plus a
//! half-turn flag (`|`), never as an accumulated float angle. The unit
//! direction of a heading comes from [`Headings::dir`], a pure function of
//! `(k, flip)` computed with `libm` and cached, so every strategy that issues
//! the same operations computes bit-identical positions.

mod interp;
pub mod turtle3;

pub use interp::{Interp, Op, State};

use crate::color::Rgb;

/// A filled area painted under the drawing (a layout shape).
#[derive(Debug, Clone, PartialEq)]
pub struct Fill {
    /// Fill colour.
    pub color: Rgb,
    /// Closed rings, canvas units; filled with the even-odd rule.
    pub rings: Vec<Vec<Point>>,
}

/// A point in canvas units.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Point {
    /// Rightwards.
    pub x: f64,
    /// Downwards.
    pub y: f64,
}

impl Point {
    /// A point from its coordinates.
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }
}

/// One drawn stem: a straight line from `from` to `to`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Where the pen went down.
    pub from: Point,
    /// Where it came up.
    pub to: Point,
    /// Stem order: number of enclosing rule applications (0 for the seed and
    /// for every segment of a classic L-system). Backends map it to a width.
    pub order: u32,
}

/// A drawing backend. It is told about each drawn segment, in drawing order.
pub trait Turtle {
    /// Draw one segment.
    fn segment(&mut self, seg: Segment);

    /// The level of detail the backend shows, in canvas units: a part of
    /// the drawing whose whole extent is at most this may be handed over as
    /// one stand-in segment instead of all of its own (the renderer's level
    /// of detail). `None`, the default: every segment.
    fn detail(&self) -> Option<f64> {
        None
    }

    /// A stand-in for a part of the drawing no larger than
    /// [`Turtle::detail`] that breaks off in branches (a bush), or that
    /// folds on itself: the one call every level-of-detail walk (2D, 3D,
    /// deterministic or stochastic) hands such a part to, with what it
    /// knows of it ([`StandIn`]: its segment and density always, its
    /// footprint and a way to draw it when the walk has them). The
    /// default draws `seg` as one segment; the PNG backend paints the
    /// ink the part's strokes leave ([`StandIn`] says how), the SVG one a
    /// wider stroke for a dense one.
    fn stand_in(&mut self, stand_in: &StandIn) {
        self.segment(stand_in.seg);
    }

    /// Whether drawing anything inside the canvas box `lo`-`hi` (corners;
    /// the strokes' reach around it included) would change nothing: a
    /// raster backend whose pixels there are all the opaque stroke colour
    /// says so, and the level-of-detail walk then skips that part of the
    /// drawing. The default: `false`.
    fn covered(&mut self, lo: Point, hi: Point) -> bool {
        let _ = (lo, hi);
        false
    }

    /// A piece of a dense curve whose strokes cover its whole box (a
    /// solid stand-in): `true` if the backend drew it from `sample`,
    /// `false` (the default) to have it drawn as its hatched box.
    fn solid(&mut self, sample: &Sample) -> bool {
        let _ = sample;
        false
    }

    /// A piece larger than [`Turtle::detail`] that breaks off in branches
    /// (a bush not cut): `true` if the backend drew it whole from
    /// `sample`, as the coverage its drawing at the detail leaves, because
    /// that drawing inks its footprint fully (its strokes overlap many
    /// times over); `false` (the default) to have the walk draw it.
    fn dense(&mut self, sample: &Sample) -> bool {
        let _ = sample;
        false
    }

    /// A stand-in for one connected run of `segments` segments (a
    /// straight or winding line, no jump inside) no larger than half of
    /// [`Turtle::detail`]: `seg` is its chord (or its box's diagonal).
    /// The default draws it as one segment; a raster backend folds it as
    /// it would fold the run.
    fn run(&mut self, seg: Segment, segments: f64) {
        let _ = segments;
        self.segment(seg);
    }

    /// The paint changes: later segments and polygons are this colour
    /// (a `.lsys` palette, stl-language.md section 13). Only systems
    /// with a palette call it; the default ignores it.
    fn paint(&mut self, rgb: Rgb) {
        let _ = rgb;
    }

    /// A closed polygon (`{ ... }`, canvas units), filled with the paint
    /// in force. The default ignores it.
    fn polygon(&mut self, points: &[Point]) {
        let _ = points;
    }
}

impl<T: Turtle + ?Sized> Turtle for &mut T {
    #[inline]
    fn segment(&mut self, seg: Segment) {
        (**self).segment(seg)
    }

    fn detail(&self) -> Option<f64> {
        (**self).detail()
    }

    fn stand_in(&mut self, stand_in: &StandIn) {
        (**self).stand_in(stand_in)
    }

    fn covered(&mut self, lo: Point, hi: Point) -> bool {
        (**self).covered(lo, hi)
    }

    fn solid(&mut self, sample: &Sample) -> bool {
        (**self).solid(sample)
    }

    fn dense(&mut self, sample: &Sample) -> bool {
        (**self).dense(sample)
    }

    fn run(&mut self, seg: Segment, segments: f64) {
        (**self).run(seg, segments)
    }

    fn paint(&mut self, rgb: Rgb) {
        (**self).paint(rgb)
    }

    fn polygon(&mut self, points: &[Point]) {
        (**self).polygon(points)
    }
}

/// A stand-in handed to [`Turtle::stand_in`]: what a level-of-detail
/// walk knows of the part it stands for. Each field a walk fills in lets a
/// backend draw the part more closely: `seg` and `density` alone are a
/// blot, a `footprint` is the bush's own spread of ink, a `sample` its own
/// drawing.
#[derive(Clone, Copy)]
pub struct StandIn<'a> {
    /// Its chord (or its box's diagonal, or a segment along its box's
    /// middle when it has a `footprint`).
    pub seg: Segment,
    /// The length of the segments it stands for over the length of
    /// `seg` (at least 1).
    pub density: f64,
    /// How its strokes spread about `seg`, when the walk knows.
    pub footprint: Option<Footprint>,
    /// Its own drawing, when the walk can draw it again.
    pub sample: Option<&'a Sample<'a>>,
}

impl StandIn<'_> {
    /// A blot: a part known only by its segment and density.
    pub fn blot(seg: Segment, density: f64) -> StandIn<'static> {
        StandIn {
            seg,
            density,
            footprint: None,
            sample: None,
        }
    }
}

/// How a bush's strokes spread about its stand-in's segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// How far the part reaches to either side of the segment, canvas
    /// units (its box's half-width across it).
    pub spread: f64,
    /// About how many separate runs its strokes come in (one per `]` or
    /// `f` inside: each run of a stroke has its own caps).
    pub runs: f64,
}

/// A bush handed over in a [`StandIn`]: where it is, which one it is,
/// and how to draw it.
pub struct Sample<'a> {
    /// Where the subtree starts (canvas units).
    pub at: Point,
    /// Within one drawing, equal keys stand for equal subtrees, the same
    /// way up, drawn from their start.
    pub key: u128,
    /// The subtree's box relative to its start: its least and greatest
    /// corners (canvas units).
    pub bounds: (Point, Point),
    /// Segments its exact drawing has (saturating).
    pub segments: u64,
    /// Draws the subtree from the origin into a turtle, at a level of
    /// detail of the given canvas units (0: exactly).
    pub draw: &'a dyn Fn(f64, &mut dyn Turtle),
}

impl Sample<'_> {
    /// The key of an L-system's piece: `symbol` at remaining depth
    /// `depth`, starting with heading `heading` (the memo's key of it)
    /// and `flip`.
    pub fn piece_key(symbol: u32, depth: u32, heading: i64, flip: bool) -> u128 {
        u128::from(symbol) << 96
            | u128::from(depth) << 64
            | u128::from(heading as u64) << 1
            | u128::from(flip)
    }

    /// The least and greatest corners of the box with corners `a` and `b`.
    pub fn corners(a: Point, b: Point) -> (Point, Point) {
        (
            Point::new(a.x.min(b.x), a.y.min(b.y)),
            Point::new(a.x.max(b.x), a.y.max(b.y)),
        )
    }
}

/// Records every segment: the test backend.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Recorder {
    /// The segments in drawing order.
    pub segments: Vec<Segment>,
    /// Each change of paint: how many segments came before it, and the
    /// colour.
    pub paints: Vec<(usize, Rgb)>,
    /// Each polygon: how many segments came before it, and its vertices.
    pub polygons: Vec<(usize, Vec<Point>)>,
}

impl Turtle for Recorder {
    #[inline]
    fn segment(&mut self, seg: Segment) {
        self.segments.push(seg);
    }

    fn paint(&mut self, rgb: Rgb) {
        self.paints.push((self.segments.len(), rgb));
    }

    fn polygon(&mut self, points: &[Point]) {
        self.polygons.push((self.segments.len(), points.to_vec()));
    }
}

/// An axis-aligned box in canvas units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BBox {
    /// Smallest x.
    pub min_x: f64,
    /// Smallest y.
    pub min_y: f64,
    /// Largest x.
    pub max_x: f64,
    /// Largest y.
    pub max_y: f64,
}

impl BBox {
    /// The box holding just `p`.
    pub fn at(p: Point) -> Self {
        BBox {
            min_x: p.x,
            min_y: p.y,
            max_x: p.x,
            max_y: p.y,
        }
    }

    /// Grows the box to hold `p`. Written as selects, which compile to
    /// `minsd`/`maxsd` rather than data-dependent branches (the bounding pass
    /// runs once per segment); a NaN coordinate is ignored as before.
    #[inline]
    pub fn add(&mut self, p: Point) {
        self.min_x = if p.x < self.min_x { p.x } else { self.min_x };
        self.max_x = if p.x > self.max_x { p.x } else { self.max_x };
        self.min_y = if p.y < self.min_y { p.y } else { self.min_y };
        self.max_y = if p.y > self.max_y { p.y } else { self.max_y };
    }

    /// Grows the box to hold `other`.
    pub fn union(&mut self, other: &BBox) {
        self.add(Point::new(other.min_x, other.min_y));
        self.add(Point::new(other.max_x, other.max_y));
    }

    /// Width.
    pub fn width(&self) -> f64 {
        self.max_x - self.min_x
    }

    /// Height.
    pub fn height(&self) -> f64 {
        self.max_y - self.min_y
    }
}

/// The bounding pass: the box of every drawn segment, and how many there are.
///
/// The box starts empty (`+inf`/`-inf`), so adding a point is four selects
/// and no branch on "first point yet?"; [`Bounds::bbox`] gives `None` until
/// something is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Bounds {
    acc: BBox,
    /// Number of segments seen.
    pub count: u64,
    /// Highest stem order seen.
    pub max_order: u32,
}

impl Default for Bounds {
    fn default() -> Self {
        Bounds {
            acc: BBox {
                min_x: f64::INFINITY,
                min_y: f64::INFINITY,
                max_x: f64::NEG_INFINITY,
                max_y: f64::NEG_INFINITY,
            },
            count: 0,
            max_order: 0,
        }
    }
}

impl Bounds {
    /// The box of every segment drawn, `None` until one is (or when every
    /// coordinate was NaN, which the box ignores).
    pub fn bbox(&self) -> Option<BBox> {
        (self.acc.min_x <= self.acc.max_x && self.acc.min_y <= self.acc.max_y).then_some(self.acc)
    }
}

impl Turtle for Bounds {
    #[inline]
    fn segment(&mut self, seg: Segment) {
        self.acc.add(seg.from);
        self.acc.add(seg.to);
        self.count += 1;
        self.max_order = self.max_order.max(seg.order);
    }

    fn polygon(&mut self, points: &[Point]) {
        for &p in points {
            self.acc.add(p);
        }
    }
}

/// Counts segments and nothing else.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counter(pub u64);

impl Turtle for Counter {
    #[inline]
    fn segment(&mut self, _seg: Segment) {
        self.0 += 1;
    }
}

/// How many cached directions to keep on each side of heading 0 before
/// computing further ones directly (same function, so the same bits).
const HEADING_CACHE: i64 = 1 << 14;

/// The turtle's first heading unless told otherwise: up the canvas, in
/// degrees counter-clockwise from the canvas's right.
pub const UP: f64 = 90.0;

/// Unit direction vectors for every heading `start + k·angle (+180° if
/// flipped)`, in canvas coordinates; `start` is [`UP`] unless a `.lsys` file
/// gives `heading`.
#[derive(Debug, Clone)]
pub struct Headings {
    start: f64,
    angle: f64,
    /// `cache[i]` holds the direction for `k = i - HEADING_CACHE`, filled lazily.
    cache: Vec<Option<(f64, f64)>>,
    /// Where the heading's degrees are computed exactly (see [`Period`]):
    /// headings one period apart then have the very same direction, so a
    /// heading past the cache is reduced into it.
    period: Option<Period>,
}

/// The turns of the angle that make a whole turn, when `start + k·angle`
/// is exact for every `|k| <= exact_up_to`: both are multiples of
/// 1/[`PERIOD_SCALE`] degree, and `k·angle` stays below 2^52 of those.
/// Then [`direction_from`] reduces the same exact number of degrees
/// modulo 360 for `k` and for `k` modulo the period (the remainder of a
/// float division is exact), and returns the same bits.
#[derive(Clone, Copy, Debug)]
struct Period {
    turns: i64,
    exact_up_to: u64,
}

/// Angles and starts that are multiples of 1/1024 degree (90, 60, 22.5,
/// ...) have a period.
const PERIOD_SCALE: f64 = 1024.0;

impl Period {
    fn of(start_deg: f64, angle_deg: f64) -> Option<Period> {
        let (a, s) = (angle_deg * PERIOD_SCALE, start_deg * PERIOD_SCALE);
        let small = |v: f64| v.is_finite() && v.fract() == 0.0 && v.abs() < (1u64 << 30) as f64;
        if !small(a) || !small(s) || a == 0.0 {
            return None;
        }
        let full = (360.0 * PERIOD_SCALE) as i64;
        let (a, s) = (a.abs() as i64, s.abs() as i64);
        let mut g = (a % full, full);
        while g.0 != 0 {
            g = (g.1 % g.0, g.0);
        }
        Some(Period {
            turns: full / g.1,
            exact_up_to: ((1u64 << 52) - s as u64) / a as u64,
        })
    }
}

impl Headings {
    /// Headings for a turning angle in degrees, starting [`UP`].
    pub fn new(angle_deg: f64) -> Self {
        Self::starting(UP, angle_deg)
    }

    /// Headings for a turning angle in degrees, starting at `start_deg`
    /// (counter-clockwise from the canvas's right; 90 is up).
    pub fn starting(start_deg: f64, angle_deg: f64) -> Self {
        Headings {
            start: start_deg,
            angle: angle_deg,
            cache: Vec::new(),
            period: Period::of(start_deg, angle_deg),
        }
    }

    /// The turning angle in degrees.
    pub fn angle(&self) -> f64 {
        self.angle
    }

    /// Unit vector `(dx, dy)` for heading `k` turns to the left of "up",
    /// turned around if `flip`.
    #[inline]
    pub fn dir(&mut self, k: i64, flip: bool) -> (f64, f64) {
        let (dx, dy) = self.unflipped(k);
        if flip { (-dx, -dy) } else { (dx, dy) }
    }

    #[inline]
    fn unflipped(&mut self, mut k: i64) -> (f64, f64) {
        let mut idx = k + HEADING_CACHE;
        if !(0..2 * HEADING_CACHE).contains(&idx)
            && let Some(p) = self.period
            && k.unsigned_abs() <= p.exact_up_to
        {
            k = k.rem_euclid(p.turns);
            idx = k + HEADING_CACHE;
        }
        if (0..2 * HEADING_CACHE).contains(&idx) {
            let idx = idx as usize;
            if let Some(Some(d)) = self.cache.get(idx) {
                return *d;
            }
            let d = direction_from(self.start, self.angle, k);
            if self.cache.len() <= idx {
                self.cache.resize(idx + 1, None);
            }
            self.cache[idx] = Some(d);
            d
        } else {
            direction_from(self.start, self.angle, k)
        }
    }
}

/// The canvas direction of heading `90° + k·angle`. Exact at multiples of 90°.
pub fn direction(angle_deg: f64, k: i64) -> (f64, f64) {
    direction_from(UP, angle_deg, k)
}

/// The canvas direction of heading `start + k·angle` (degrees,
/// counter-clockwise from the canvas's right). Exact at multiples of 90°.
pub fn direction_from(start_deg: f64, angle_deg: f64, k: i64) -> (f64, f64) {
    // Reduce in degrees first so large k stay accurate and right angles exact.
    let deg = (start_deg + (k as f64) * angle_deg).rem_euclid(360.0);
    let (c, s) = if deg == 0.0 {
        (1.0, 0.0)
    } else if deg == 90.0 {
        (0.0, 1.0)
    } else if deg == 180.0 {
        (-1.0, 0.0)
    } else if deg == 270.0 {
        (0.0, -1.0)
    } else {
        let rad = deg.to_radians();
        (libm::cos(rad), libm::sin(rad))
    };
    // Mathematical angle, counter-clockwise; the canvas's y grows downward.
    (c, -s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starts_heading_up_and_left_turns_counter_clockwise() {
        let mut h = Headings::new(90.0);
        assert_eq!(h.dir(0, false), (0.0, -1.0)); // up
        assert_eq!(h.dir(1, false), (-1.0, 0.0)); // left on screen
        assert_eq!(h.dir(-1, false), (1.0, 0.0)); // right
        assert_eq!(h.dir(0, true), (-0.0, 1.0)); // turned around: down
    }

    #[test]
    fn cached_and_direct_directions_agree_bit_for_bit() {
        let mut h = Headings::new(25.7);
        for k in [-3, 0, 5, 99] {
            assert_eq!(h.dir(k, false), direction(25.7, k));
            assert_eq!(h.dir(k, false), direction(25.7, k)); // cached now
        }
        let far = HEADING_CACHE * 3;
        assert_eq!(h.dir(far, false), direction(25.7, far));
    }

    #[test]
    fn headings_past_the_cache_reduced_by_their_period_keep_their_bits() {
        // 90 degrees: a period of 4 turns; 22.5: 16; 60 from a start of
        // 12.25: 6; 25.7 has none (not a multiple of 1/1024 degree).
        assert_eq!(Period::of(UP, 90.0).map(|p| p.turns), Some(4));
        assert_eq!(Period::of(UP, 22.5).map(|p| p.turns), Some(16));
        assert_eq!(Period::of(12.25, -60.0).map(|p| p.turns), Some(6));
        assert!(Period::of(UP, 25.7).is_none());
        // 2 million `+` at 90 degrees: up again, exactly.
        assert_eq!(Headings::new(90.0).dir(2_000_000, false), (0.0, -1.0));
        for (start, angle) in [
            (UP, 90.0),
            (UP, 22.5),
            (12.25, -60.0),
            (0.0, 45.0),
            (UP, 25.7),
        ] {
            let mut h = Headings::starting(start, angle);
            for k in [
                HEADING_CACHE,
                -HEADING_CACHE - 1,
                2_000_001,
                -7_654_321,
                1 << 40,
                -(1 << 45) - 3,
                1 << 62,
                -(1 << 62),
            ] {
                let (a, b) = (h.dir(k, false), direction_from(start, angle, k));
                assert_eq!(
                    (a.0.to_bits(), a.1.to_bits()),
                    (b.0.to_bits(), b.1.to_bits()),
                    "{start} {angle} {k}"
                );
            }
        }
    }
}
