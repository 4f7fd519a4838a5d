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
//!
//! Rule applications (a BED's or a grown OD's terms, `Op3::Enter`) raise
//! the stem order, so a stem's length is `L - k*dL` ([`Turtle3::with_length`]),
//! and first roll the frame by the divergence `D=` about H
//! ([`Divergence`], [`Turtle3::with_divergence`]): section 11's "every rule
//! application first rolls its frame by d about H, as `\` does by d,
//! relative to the frame it grows from". The roll is part of the
//! application, like a `\` written at the start of its body: whatever the
//! application leaves the turtle at (a seed's `F R1 F`: the second `F`)
//! keeps it, as it keeps the trunk's turns; branches restore it with `]`
//! as always. A divergence of 0 (or any multiple of 360) rolls nothing, so
//! a planar tree stays [`Frame::Planar`].

use super::Headings;
use crate::num::Linear;

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

/// The divergence `D=` of a 3D OD or BED, in degrees (section 11): the
/// roll about H every rule application starts with. Its cos and sin are
/// computed once, exactly at multiples of 90 degrees ([`cos_sin`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Divergence {
    cos: f64,
    sin: f64,
}

impl Divergence {
    /// The roll by `deg` degrees; `None` for no roll (`deg` a multiple of
    /// 360, 0 included), which leaves a planar frame planar.
    pub fn new(deg: f64) -> Option<Divergence> {
        let (cos, sin) = cos_sin(deg);
        (sin != 0.0 || cos != 1.0).then_some(Divergence { cos, sin })
    }

    /// `frame` rolled by this divergence about its heading, as `\` rolls
    /// by the turtle's angle (L <- L cos d - U sin d, U <- U cos d + L sin d).
    /// `headings` are the turtle's (a planar frame's vectors come from them).
    pub fn roll(self, frame: Frame, headings: &mut Headings) -> Frame {
        let (h, l, u) = frame.hlu(headings);
        Frame::Free {
            h,
            l: comb(l, self.cos, u, -self.sin),
            u: comb(u, self.cos, l, self.sin),
        }
    }
}

impl Frame {
    /// The frame's vectors (H, L, U); a planar frame's from `headings`.
    pub fn hlu(self, headings: &mut Headings) -> (V, V, V) {
        match self {
            Frame::Planar { k, flip } => {
                let (hx, hy) = headings.dir(k, flip);
                ([hx, hy, 0.0], [hy, -hx, 0.0], [0.0, 0.0, -1.0])
            }
            Frame::Free { h, l, u } => (h, l, u),
        }
    }
}

/// A 3D turtle operation: what a symbol of a 3D `.lsys` (or a 3D OD's or
/// BED's drawing component) means.
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
    /// Start of a rule application (an OD's or BED's term, each level of
    /// `[I n X]`): stems one order higher from here, the frame first
    /// rolled by the divergence.
    Enter,
    /// End of a rule application: one order lower.
    Leave,
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

    /// The operation of a drawing component of a 3D OD or BED: as in a 3D
    /// `.lsys`, with `L` and `R` turning as `+` and `-` (the STL alphabet).
    pub fn of_stl(c: char) -> Option<Op3> {
        match c {
            'L' => Some(Op3::Turn(1)),
            'R' => Some(Op3::Turn(-1)),
            c => Op3::of_lsys(c),
        }
    }
}

/// The turtle's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State3 {
    /// Where it is.
    pub pos: Point3,
    /// Its orientation.
    pub frame: Frame,
    /// Stem order: rule applications entered and not left (0 in an
    /// `.lsys`).
    pub order: u32,
}

impl State3 {
    /// The state at a root: at `pos`, heading first (up), order 0.
    pub fn start(pos: Point3) -> State3 {
        State3 {
            pos,
            frame: Frame::Planar { k: 0, flip: false },
            order: 0,
        }
    }
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
    length: Linear,
    divergence: Option<Divergence>,
    sink: S,
}

impl<S: FnMut(Segment3)> Turtle3<S> {
    /// A turtle at the origin, first heading `start_deg` (degrees
    /// counter-clockwise from the canvas's right, in the screen plane; 90
    /// is up), turning by `angle_deg`, stepping `len`.
    pub fn new(start_deg: f64, angle_deg: f64, len: f64, sink: S) -> Self {
        let (cos, sin) = cos_sin(angle_deg);
        Turtle3 {
            state: State3::start(Point3::default()),
            stack: Vec::new(),
            headings: Headings::starting(start_deg, angle_deg),
            cos,
            sin,
            length: Linear::constant(len),
            divergence: None,
            sink,
        }
    }

    /// The same turtle with stems `length.at(order)` long (an OD's or
    /// BED's `L`).
    pub fn with_length(mut self, length: Linear) -> Self {
        self.length = length;
        self
    }

    /// The same turtle rolling by `deg` degrees at every rule application
    /// ([`Op3::Enter`]; `D=`, see [`Divergence`]).
    pub fn with_divergence(mut self, deg: f64) -> Self {
        self.divergence = Divergence::new(deg);
        self
    }

    /// Starts a tree at `pos`: heading first, order 0, stack emptied.
    pub fn start_at(&mut self, pos: Point3) {
        self.state = State3::start(pos);
        self.stack.clear();
    }

    /// The frame's vectors (H, L, U).
    pub fn hlu(&mut self) -> (V, V, V) {
        self.state.frame.hlu(&mut self.headings)
    }

    /// Hands the sink back.
    pub fn into_sink(self) -> S {
        self.sink
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
                    order: self.state.order,
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
            Op3::Enter => {
                self.state.order += 1;
                if let Some(d) = self.divergence {
                    self.state.frame = d.roll(self.state.frame, &mut self.headings);
                }
            }
            Op3::Leave => self.state.order = self.state.order.saturating_sub(1),
        }
    }

    /// The point one step ahead: in the plane with the 2D turtle's
    /// expression, so a planar drawing's x and y are the 2D ones bit for
    /// bit.
    #[inline]
    fn forward(&mut self) -> Point3 {
        let p = self.state.pos;
        let len = self.length.at(self.state.order);
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

    /// Where a unit-step turtle at 90 degrees ends after `ops`, rolling by
    /// `d` at each `Enter`.
    fn end_diverging(d: f64, ops: &[Op3]) -> (Point3, Frame) {
        let mut t = Turtle3::new(90.0, 90.0, 1.0, |_| {}).with_divergence(d);
        for &op in ops {
            t.apply(op);
        }
        (t.state.pos, t.state.frame)
    }

    #[test]
    fn divergence_rolls_at_each_rule_application_as_a_backslash() {
        use Op3::*;
        // By hand: after `F` at (0, -1, 0), rolling by 90 makes
        // L = L*0 - U*1 = (0, 0, 1), so `+` heads H = L = (0, 0, 1) and the
        // second `F` ends at (0, -1, 1): what `F\+F` draws.
        let (p, _) = end_diverging(90.0, &[Draw, Enter, Turn(1), Draw]);
        assert_eq!(p, Point3::new(0.0, -1.0, 1.0));
        assert_eq!(p, end("F\\+F"));
        // Two applications roll twice: L = -L, `+` heads (1, 0, 0).
        let (p, _) = end_diverging(90.0, &[Enter, Enter, Turn(1), Draw]);
        assert_eq!(p, Point3::new(1.0, 0.0, 0.0));
        // `Leave` does not unroll (the application's roll is kept, as a
        // `\` in its body would be); `]` restores the frame before it.
        let (p, _) = end_diverging(90.0, &[Enter, Leave, Turn(1), Draw]);
        assert_eq!(p, Point3::new(0.0, 0.0, 1.0));
        let (p, _) = end_diverging(90.0, &[Push, Enter, Pop, Turn(1), Draw]);
        assert_eq!(p, Point3::new(-1.0, 0.0, 0.0));
        // No divergence (0, 360): the frame stays planar.
        for d in [0.0, 360.0, -720.0] {
            let (_, f) = end_diverging(d, &[Enter, Turn(1), Enter]);
            assert_eq!(f, Frame::Planar { k: 1, flip: false }, "D={d}");
        }
    }

    #[test]
    fn orders_shorten_stems_and_are_kept_by_the_stack() {
        use Op3::*;
        let mut got = Vec::new();
        let mut t = Turtle3::new(90.0, 90.0, 1.0, |s: Segment3| got.push((s.to, s.order)))
            .with_length(Linear::new(10.0, 2.0));
        for op in [Draw, Enter, Push, Enter, Draw, Pop, Draw, Leave, Draw] {
            t.apply(op);
        }
        let p = |y| Point3::new(0.0, y, 0.0);
        assert_eq!(
            got,
            vec![(p(-10.0), 0), (p(-16.0), 2), (p(-18.0), 1), (p(-28.0), 0)]
        );
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
}
