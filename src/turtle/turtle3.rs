//! The 3D turtle: frames (H, L, U) as `../shared/stl-language.md` section
//! 11 defines them, positions in 3D, segments in 3D.
//!
//! Axes are the canvas's, extended: x right, y down, z away from the
//! viewer (right-handed). The turtle starts at the origin with heading
//! H = (0, -1, 0) (up the screen), left L = (-1, 0, 0) and up
//! U = H x L = (0, 0, -1) (toward the viewer).
//!
//! Exactness: while a state has only turned in the plane (`+ - |`), its
//! frame is kept as the 2D turtle keeps it, an integer number of turns and
//! a flip ([`Frame::Planar`]), and a step is computed with the 2D turtle's
//! expression (`pos + dir(k) * len`, [`Headings::dir`]); so a planar system
//! draws the 2D picture's x and y bit for bit. The first pitch or roll
//! turns it into three float vectors ([`Frame::Free`]) rotated by the
//! formulas of section 11 with `cos a` and `sin a` computed once; at
//! multiples of 90 degrees those are exactly 0 and +-1 ([`cos_sin`]), so
//! the vectors stay integer and nothing drifts (the 3D Hilbert curve lands
//! on lattice points at any depth). Elsewhere `libm`.

use super::Headings;

/// A point (or vector) in 3D canvas units: x right, y down, z away from
/// the viewer.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Point3 {
    /// Rightwards.
    pub x: f64,
    /// Downwards.
    pub y: f64,
    /// Away from the viewer.
    pub z: f64,
}

impl Point3 {
    /// A point from its coordinates.
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Point3 { x, y, z }
    }

    /// The coordinates as an array.
    pub fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
}

/// One drawn stem in 3D.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment3 {
    /// Where the pen went down.
    pub from: Point3,
    /// Where it came up.
    pub to: Point3,
    /// Stem order, as [`super::Segment::order`].
    pub order: u32,
}

/// The box of 3D stems as they are drawn, and how many: what `stats`
/// reports of a 3D `.lsys` or BED.
#[derive(Debug, Clone, Copy)]
pub struct StemBox {
    /// `[minx, miny, minz, maxx, maxy, maxz]`, empty (min > max) at first.
    b: [f64; 6],
    /// Stems added.
    n: u64,
}

impl Default for StemBox {
    fn default() -> Self {
        StemBox {
            b: [
                f64::INFINITY,
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ],
            n: 0,
        }
    }
}

impl StemBox {
    /// Takes in one stem's ends.
    pub fn add(&mut self, s: Segment3) {
        for p in [s.from, s.to] {
            for (i, v) in p.to_array().into_iter().enumerate() {
                self.b[i] = self.b[i].min(v);
                self.b[i + 3] = self.b[i + 3].max(v);
            }
        }
        self.n += 1;
    }

    /// The box (`None` when nothing was drawn), `end` and the stem count.
    pub fn finish(self, end: Point3) -> (Option<[f64; 6]>, Point3, u64) {
        ((self.n > 0).then_some(self.b), end, self.n)
    }
}

/// `cos` and `sin` of a divergence (`D=`), `None` for none (a multiple
/// of 360 degrees, 0 included: a planar frame stays planar). Growth and
/// a 3D BED's drawing roll every rule application by it ([`Turtle3::roll_by`]).
pub fn divergence(d: Option<f64>) -> Option<(f64, f64)> {
    d.filter(|d| d.rem_euclid(360.0) != 0.0).map(cos_sin)
}

/// `cos` and `sin` of `deg` degrees: exactly 0 and +-1 at multiples of 90
/// degrees, `libm` elsewhere.
pub fn cos_sin(deg: f64) -> (f64, f64) {
    let d = deg.rem_euclid(360.0);
    if d == 0.0 {
        (1.0, 0.0)
    } else if d == 90.0 {
        (0.0, 1.0)
    } else if d == 180.0 {
        (-1.0, 0.0)
    } else if d == 270.0 {
        (0.0, -1.0)
    } else {
        let r = d.to_radians();
        (libm::cos(r), libm::sin(r))
    }
}

type V = [f64; 3];

fn comb(a: V, ca: f64, b: V, cb: f64) -> V {
    [
        a[0] * ca + b[0] * cb,
        a[1] * ca + b[1] * cb,
        a[2] * ca + b[2] * cb,
    ]
}

/// The turtle's orientation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Frame {
    /// Turned only in the plane: `k` turns left of the first heading,
    /// turned around if `flip`; U is (0, 0, -1).
    Planar {
        /// Turns to the left.
        k: i64,
        /// An odd number of `|`.
        flip: bool,
    },
    /// Any orientation: heading, left and up.
    Free {
        /// Heading H.
        h: V,
        /// Left L.
        l: V,
        /// Up U.
        u: V,
    },
}

/// A 3D turtle operation: what a symbol of a 3D `.lsys` means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op3 {
    /// `F`: draw one step.
    Draw,
    /// `f`: move one step.
    Move,
    /// `+` (1) or `-` (-1): turn about U.
    Turn(i8),
    /// `&` (1, pitch down) or `^` (-1): turn about L.
    Pitch(i8),
    /// `\` (1, roll left) or `/` (-1): turn about H.
    Roll(i8),
    /// `|`: half a turn about U.
    Flip,
    /// `[`: save the state.
    Push,
    /// `]`: restore it.
    Pop,
}

impl Op3 {
    /// The operation of a symbol of a 3D `.lsys`; other symbols are inert.
    pub fn of_lsys(c: char) -> Option<Op3> {
        Some(match c {
            'F' => Op3::Draw,
            'f' => Op3::Move,
            '+' => Op3::Turn(1),
            '-' => Op3::Turn(-1),
            '&' => Op3::Pitch(1),
            '^' => Op3::Pitch(-1),
            '\\' => Op3::Roll(1),
            '/' => Op3::Roll(-1),
            '|' => Op3::Flip,
            '[' => Op3::Push,
            ']' => Op3::Pop,
            _ => return None,
        })
    }
}

/// The turtle's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State3 {
    /// Where it is.
    pub pos: Point3,
    /// Its orientation.
    pub frame: Frame,
}

/// The 3D turtle state machine: applies [`Op3`]s, hands each drawn stem to
/// `sink`.
pub struct Turtle3<S: FnMut(Segment3)> {
    /// Current state.
    pub state: State3,
    stack: Vec<State3>,
    headings: Headings,
    cos: f64,
    sin: f64,
    len: f64,
    sink: S,
}

impl<S: FnMut(Segment3)> Turtle3<S> {
    /// A turtle at the origin, first heading `start_deg` (degrees
    /// counter-clockwise from the canvas's right, in the screen plane; 90
    /// is up), turning by `angle_deg`, stepping `len`.
    pub fn new(start_deg: f64, angle_deg: f64, len: f64, sink: S) -> Self {
        let (cos, sin) = cos_sin(angle_deg);
        Turtle3 {
            state: State3 {
                pos: Point3::default(),
                frame: Frame::Planar { k: 0, flip: false },
            },
            stack: Vec::new(),
            headings: Headings::starting(start_deg, angle_deg),
            cos,
            sin,
            len,
            sink,
        }
    }

    /// Sets the step length (growth steps a tree's `L` at each order).
    pub fn set_step(&mut self, len: f64) {
        self.len = len;
    }

    /// Rolls the frame about H by the angle of `cos` and `sin`, as `\`
    /// rolls by its angle: the divergence `D=` of section 11, which every
    /// rule application applies first ([`cos_sin`] of `D`).
    pub fn roll_by(&mut self, cos: f64, sin: f64) {
        let (h, l, u) = self.hlu();
        self.state.frame = Frame::Free {
            h,
            l: comb(l, cos, u, -sin),
            u: comb(u, cos, l, sin),
        };
    }

    /// The frame's vectors (H, L, U).
    pub fn hlu(&mut self) -> (V, V, V) {
        match self.state.frame {
            Frame::Planar { k, flip } => {
                let (hx, hy) = self.headings.dir(k, flip);
                ([hx, hy, 0.0], [hy, -hx, 0.0], [0.0, 0.0, -1.0])
            }
            Frame::Free { h, l, u } => (h, l, u),
        }
    }

    /// Applies one operation.
    #[inline]
    pub fn apply(&mut self, op: Op3) {
        let (c, s) = (self.cos, self.sin);
        match op {
            Op3::Draw => {
                let to = self.forward();
                (self.sink)(Segment3 {
                    from: self.state.pos,
                    to,
                    order: 0,
                });
                self.state.pos = to;
            }
            Op3::Move => self.state.pos = self.forward(),
            Op3::Turn(n) => match &mut self.state.frame {
                Frame::Planar { k, .. } => *k += i64::from(n),
                Frame::Free { h, l, .. } => {
                    let s = s * f64::from(n);
                    let (nh, nl) = (comb(*h, c, *l, s), comb(*l, c, *h, -s));
                    (*h, *l) = (nh, nl);
                }
            },
            Op3::Flip => match &mut self.state.frame {
                Frame::Planar { flip, .. } => *flip = !*flip,
                Frame::Free { h, l, .. } => {
                    *h = h.map(|v| -v);
                    *l = l.map(|v| -v);
                }
            },
            Op3::Pitch(n) => {
                let (h, l, u) = self.hlu();
                let s = s * f64::from(n);
                self.state.frame = Frame::Free {
                    h: comb(h, c, u, -s),
                    l,
                    u: comb(u, c, h, s),
                };
            }
            Op3::Roll(n) => {
                let (h, l, u) = self.hlu();
                let s = s * f64::from(n);
                self.state.frame = Frame::Free {
                    h,
                    l: comb(l, c, u, -s),
                    u: comb(u, c, l, s),
                };
            }
            Op3::Push => self.stack.push(self.state),
            Op3::Pop => {
                if let Some(st) = self.stack.pop() {
                    self.state = st;
                }
            }
        }
    }

    /// Moves the turtle as a part of the drawing started here would: by
    /// the local vector `end` (along its H, L, U), its frame turned by the
    /// local frame `rot` (the columns H, L, U in the start's coordinates).
    /// A planar state whose part turns only in the plane (`turn`: turns
    /// and flip) stays planar, with the 2D turtle's exact heading.
    pub fn jump(&mut self, end: [f64; 3], rot: &[[f64; 3]; 3], turn: Option<(i64, bool)>) {
        let (h, l, u) = self.hlu();
        let w = |v: V| comb(comb(h, v[0], l, v[1]), 1.0, u, v[2]);
        let d = w(end);
        let p = self.state.pos;
        self.state.pos = Point3::new(p.x + d[0], p.y + d[1], p.z + d[2]);
        self.state.frame = match (self.state.frame, turn) {
            (Frame::Planar { k, flip }, Some((dk, df))) if k.checked_add(dk).is_some() => {
                Frame::Planar {
                    k: k + dk,
                    flip: flip != df,
                }
            }
            _ => Frame::Free {
                h: w(rot[0]),
                l: w(rot[1]),
                u: w(rot[2]),
            },
        };
    }

    /// The point one step ahead: in the plane with the 2D turtle's
    /// expression, so a planar drawing's x and y are the 2D ones bit for
    /// bit.
    #[inline]
    fn forward(&mut self) -> Point3 {
        let p = self.state.pos;
        let len = self.len;
        match self.state.frame {
            Frame::Planar { k, flip } => {
                let (dx, dy) = self.headings.dir(k, flip);
                Point3::new(p.x + dx * len, p.y + dy * len, p.z)
            }
            Frame::Free { h, .. } => {
                Point3::new(p.x + h[0] * len, p.y + h[1] * len, p.z + h[2] * len)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where a unit-step turtle at 90 degrees ends after `word`.
    fn end(word: &str) -> Point3 {
        let mut t = Turtle3::new(90.0, 90.0, 1.0, |_| {});
        for op in word.chars().filter_map(Op3::of_lsys) {
            t.apply(op);
        }
        t.state.pos
    }

    #[test]
    fn the_worked_ends_of_section_11() {
        assert_eq!(end("F+F"), Point3::new(-1.0, -1.0, 0.0));
        assert_eq!(end("F&F"), Point3::new(0.0, -1.0, 1.0));
        assert_eq!(end("F/+F"), Point3::new(0.0, -1.0, -1.0));
    }

    #[test]
    fn the_start_frame_is_up_left_and_toward_the_viewer() {
        let mut t = Turtle3::new(90.0, 30.0, 1.0, |_| {});
        let (h, l, u) = t.hlu();
        assert_eq!(
            (h, l, u),
            ([0.0, -1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0])
        );
    }

    #[test]
    fn each_rotation_and_its_inverse_cancel_and_keep_the_frame_orthonormal() {
        // At 37 degrees (floats): `&^`, `\/`, `+-` undo each other within
        // rounding; H, L, U stay orthonormal and right-handed (U = H x L).
        let mut t = Turtle3::new(90.0, 37.0, 1.0, |_| {});
        for op in "&\\+&/^-\\".chars().filter_map(Op3::of_lsys) {
            t.apply(op);
        }
        let (h, l, u) = t.hlu();
        let dot = |a: V, b: V| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let cross = |a: V, b: V| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        for (a, b) in [(h, l), (l, u), (h, u)] {
            assert!(dot(a, b).abs() < 1e-12);
        }
        for v in [h, l, u] {
            assert!((dot(v, v) - 1.0).abs() < 1e-12);
        }
        let hl = cross(h, l);
        for i in 0..3 {
            assert!((hl[i] - u[i]).abs() < 1e-12, "{hl:?} {u:?}");
        }
        let mut t = Turtle3::new(90.0, 37.0, 1.0, |_| {});
        for op in "&\\+-/^".chars().filter_map(Op3::of_lsys) {
            t.apply(op);
        }
        let (h, _, _) = t.hlu();
        assert!((h[1] + 1.0).abs() < 1e-12 && h[0].abs() < 1e-12 && h[2].abs() < 1e-12);
    }

    #[test]
    fn pitching_a_full_turn_at_90_degrees_is_exact() {
        // Four `&` bring the frame back exactly, however often repeated.
        let mut t = Turtle3::new(90.0, 90.0, 1.0, |_| {});
        for _ in 0..1000 {
            for op in "&&&&\\\\\\\\F".chars().filter_map(Op3::of_lsys) {
                t.apply(op);
            }
        }
        assert_eq!(t.state.pos, Point3::new(0.0, -1000.0, 0.0));
    }

    #[test]
    fn a_planar_turtle_steps_as_the_2d_turtle() {
        use crate::turtle::{Interp, Op, Recorder};
        let word = "F+F+F-F|F+F++F";
        let mut got = Vec::new();
        let mut t = Turtle3::new(90.0, 25.7, 1.0, |s: Segment3| got.push(s));
        for op in word.chars().filter_map(Op3::of_lsys) {
            t.apply(op);
        }
        let mut i = Interp::new(
            Recorder::default(),
            crate::turtle::Point::default(),
            25.7,
            crate::num::Linear::constant(1.0),
        );
        for op in word.chars().filter_map(Op::of_lsys) {
            i.apply(op);
        }
        let flat = i.into_turtle().segments;
        assert_eq!(flat.len(), got.len());
        for (a, b) in flat.iter().zip(&got) {
            assert_eq!((a.to.x, a.to.y, 0.0), (b.to.x, b.to.y, b.to.z));
        }
    }

    /// The divergence `D=` as [`Turtle3::roll_by`] applies it, by hand: at
    /// 90 degrees after `F` at (0, -1, 0), rolling makes L = L*0 - U*1 =
    /// (0, 0, 1), so `+` heads along it and the next `F` ends at
    /// (0, -1, 1), where `F\+F` ends; rolling twice makes L = -L, and `+`
    /// then heads right.
    #[test]
    fn rolling_by_an_angle_is_a_backslash_by_it() {
        let mut t = Turtle3::new(90.0, 90.0, 1.0, |_| {});
        t.apply(Op3::Draw);
        t.roll_by(0.0, 1.0);
        t.apply(Op3::Turn(1));
        t.apply(Op3::Draw);
        assert_eq!(t.state.pos, Point3::new(0.0, -1.0, 1.0));
        assert_eq!(t.state.pos, end("F\\+F"));
        let mut t = Turtle3::new(90.0, 90.0, 1.0, |_| {});
        t.roll_by(0.0, 1.0);
        t.roll_by(0.0, 1.0);
        t.apply(Op3::Turn(1));
        t.apply(Op3::Draw);
        assert_eq!(t.state.pos, Point3::new(1.0, 0.0, 0.0));
    }
}
