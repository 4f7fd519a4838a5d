//! The `dfs` turtle of L-systems: executes [`FastOp`]s with
//! [`Interp`](crate::turtle::Interp)'s state and arithmetic, so its
//! segments are bit-identical to op-by-op interpretation.

use super::units::FastOp;
use crate::turtle::{Headings, Point, Segment, Turtle};

/// Directions cached for headings `-DIR_OFFSET..DIR_OFFSET`.
const DIR_OFFSET: i64 = 1 << 12;

/// The `dfs` turtle: [`Interp`](crate::turtle::Interp)'s state and arithmetic, for [`FastOp`]s.
///
/// The step vector of the current heading, `dir * len`, is kept in locals
/// and looked up again only after a turn or a pop: `x + dx * len` is
/// computed as `x + step_x` with `step_x = dx * len` taken from a table of
/// the very same products (and `(-dx) * len == -(dx * len)` exactly for a
/// flipped turtle), so positions are bit-identical to [`Interp`](crate::turtle::Interp)'s.
pub(super) struct Exec<T: Turtle> {
    pub(super) x: f64,
    pub(super) y: f64,
    k: i64,
    flip: bool,
    stack: Vec<Saved>,
    len: f64,
    headings: Headings,
    /// `steps[k + DIR_OFFSET]`: [`Headings::dir`]`(k, false)` times `len`,
    /// NaN until first needed.
    steps: Vec<(f64, f64)>,
    turtle: T,
}

/// A `[`: the state and its step vector.
#[derive(Clone, Copy)]
struct Saved {
    x: f64,
    y: f64,
    k: i64,
    flip: bool,
    sx: f64,
    sy: f64,
}

impl<T: Turtle> Exec<T> {
    pub(super) fn new(turtle: T, headings: Headings, len: f64) -> Self {
        Exec {
            x: 0.0,
            y: 0.0,
            k: 0,
            flip: false,
            stack: Vec::new(),
            len,
            headings,
            steps: vec![(f64::NAN, f64::NAN); 2 * DIR_OFFSET as usize],
            turtle,
        }
    }

    /// `dir(k, flip) * len`, with the products [`Interp`](crate::turtle::Interp) computes.
    #[inline(always)]
    fn step(&mut self, k: i64, flip: bool) -> (f64, f64) {
        let i = k.wrapping_add(DIR_OFFSET) as u64;
        let (sx, sy) = match self.steps.get(i as usize) {
            Some(&(sx, sy)) if !sx.is_nan() => (sx, sy),
            _ => self.step_slow(k),
        };
        if flip { (-sx, -sy) } else { (sx, sy) }
    }

    #[cold]
    #[inline(never)]
    fn step_slow(&mut self, k: i64) -> (f64, f64) {
        let (dx, dy) = self.headings.dir(k, false);
        let s = (dx * self.len, dy * self.len);
        let i = k.wrapping_add(DIR_OFFSET) as u64;
        if let Some(slot) = self.steps.get_mut(i as usize) {
            *slot = s;
        }
        s
    }

    #[inline]
    pub(super) fn run(&mut self, ops: &[FastOp]) {
        let (mut x, mut y, mut k, mut flip) = (self.x, self.y, self.k, self.flip);
        let (mut sx, mut sy) = self.step(k, flip);
        for &op in ops {
            match op {
                FastOp::Draw(n) => {
                    for _ in 0..n {
                        // Interp::forward: pos + dir * len.
                        let to = Point::new(x + sx, y + sy);
                        self.turtle.segment(Segment {
                            from: Point::new(x, y),
                            to,
                            order: 0,
                        });
                        x = to.x;
                        y = to.y;
                    }
                }
                FastOp::Move(n) => {
                    for _ in 0..n {
                        x += sx;
                        y += sy;
                    }
                }
                FastOp::Turn(n, f) => {
                    k = k.wrapping_add(n);
                    flip ^= f;
                    (sx, sy) = self.step(k, flip);
                }
                FastOp::Push => self.stack.push(Saved {
                    x,
                    y,
                    k,
                    flip,
                    sx,
                    sy,
                }),
                FastOp::Pop => {
                    if let Some(s) = self.stack.pop() {
                        (x, y, k, flip, sx, sy) = (s.x, s.y, s.k, s.flip, s.sx, s.sy);
                    }
                }
                FastOp::Leaf { turn, flip: f, n } => {
                    let (bx, by) = self.step(k.wrapping_add(turn), flip ^ f);
                    let (mut px, mut py) = (x, y);
                    for _ in 0..n {
                        let to = Point::new(px + bx, py + by);
                        self.turtle.segment(Segment {
                            from: Point::new(px, py),
                            to,
                            order: 0,
                        });
                        px = to.x;
                        py = to.y;
                    }
                }
            }
        }
        (self.x, self.y, self.k, self.flip) = (x, y, k, flip);
    }
}
