//! The turtle of parametric systems (docs/lsys.md, *The turtle*): a frame
//! of three float vectors (H, L, U, section 11's), turned by any angle,
//! bent by tropism after every drawn step.
//!
//! `F(x) f(x)` move x times `length`, `+(a) -(a)` turn by a degrees (and
//! `& ^ \ /` in 3D), `$` (3D) rolls L horizontal, `!(w)` sets the width;
//! without a parameter each acts as in a classic system. In 2D the frame
//! never leaves the canvas plane (U stays (0, 0, -1)).

use crate::model::lsys::LSystem;
use crate::model::param::{Parametric, WIDTH_QUANTUM};
use crate::turtle::turtle3::{Point3, Segment3, cos_sin};
use crate::turtle::{Point, Segment, Turtle};

type V = [f64; 3];

fn comb(a: V, ca: f64, b: V, cb: f64) -> V {
    [
        a[0] * ca + b[0] * cb,
        a[1] * ca + b[1] * cb,
        a[2] * ca + b[2] * cb,
    ]
}

fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: V) -> f64 {
    libm::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])
}

#[derive(Debug, Clone, Copy)]
struct State {
    pos: V,
    h: V,
    l: V,
    u: V,
    width: f64,
}

/// The parametric turtle.
pub struct Turtle3P {
    state: State,
    stack: Vec<State>,
    len: f64,
    angle: f64,
    three: bool,
    tropism: Option<(V, f64)>,
}

impl Turtle3P {
    /// A turtle at the origin with `sys`'s heading, angle and length.
    pub fn new(sys: &LSystem, p: &Parametric) -> Turtle3P {
        let (c, s) = cos_sin(sys.heading);
        let h = [c, -s, 0.0];
        Turtle3P {
            state: State {
                pos: [0.0; 3],
                h,
                l: [h[1], -h[0], 0.0],
                u: [0.0, 0.0, -1.0],
                width: sys.width,
            },
            stack: Vec::new(),
            len: sys.length,
            angle: sys.angle,
            three: sys.is_3d(),
            tropism: p.tropism.filter(|_| p.bends()).map(|t| {
                let t = if sys.is_3d() { t } else { [t[0], t[1], 0.0] };
                (t, p.elasticity)
            }),
        }
    }

    /// Where the turtle is.
    pub fn pos(&self) -> Point3 {
        let p = self.state.pos;
        Point3::new(p[0], p[1], p[2])
    }

    /// The frame: H, L, U.
    pub(crate) fn frame(&self) -> [V; 3] {
        [self.state.h, self.state.l, self.state.u]
    }

    /// Moves to `to` with frame `frame` (H, L, U) without drawing: past a
    /// piece of the level of detail.
    pub(crate) fn jump(&mut self, to: V, frame: [V; 3]) {
        self.state.pos = to;
        [self.state.h, self.state.l, self.state.u] = frame;
    }

    fn turn(&mut self, deg: f64) {
        let (c, s) = cos_sin(deg);
        let st = &mut self.state;
        let (h, l) = (comb(st.h, c, st.l, s), comb(st.l, c, st.h, -s));
        (st.h, st.l) = (h, l);
    }

    fn pitch(&mut self, deg: f64) {
        let (c, s) = cos_sin(deg);
        let st = &mut self.state;
        let (h, u) = (comb(st.h, c, st.u, -s), comb(st.u, c, st.h, s));
        (st.h, st.u) = (h, u);
    }

    fn roll(&mut self, deg: f64) {
        let (c, s) = cos_sin(deg);
        let st = &mut self.state;
        let (l, u) = (comb(st.l, c, st.u, -s), comb(st.u, c, st.l, s));
        (st.l, st.u) = (l, u);
    }

    /// `$`: L = V x H / |V x H|, U = H x L, V up the canvas.
    fn level(&mut self) {
        let st = &mut self.state;
        let l = cross([0.0, -1.0, 0.0], st.h);
        let n = norm(l);
        if n > 1e-12 {
            st.l = [l[0] / n, l[1] / n, l[2] / n];
            st.u = cross(st.h, st.l);
        }
    }

    /// Tropism: the frame turns about H x T by e |H x T| radians.
    fn bend(&mut self) {
        let Some((t, e)) = self.tropism else { return };
        let st = &mut self.state;
        let a = cross(st.h, t);
        let m = norm(a);
        if m == 0.0 {
            return;
        }
        let k = [a[0] / m, a[1] / m, a[2] / m];
        let th = e * m;
        let (c, s) = (libm::cos(th), libm::sin(th));
        let rot = |v: V| -> V {
            let kv = cross(k, v);
            let d = (k[0] * v[0] + k[1] * v[1] + k[2] * v[2]) * (1.0 - c);
            [
                v[0] * c + kv[0] * s + k[0] * d,
                v[1] * c + kv[1] * s + k[1] * d,
                v[2] * c + kv[2] * s + k[2] * d,
            ]
        };
        st.h = rot(st.h);
        st.l = rot(st.l);
        st.u = rot(st.u);
    }

    fn step(&mut self, params: &[f64]) -> V {
        let d = params.first().map_or(self.len, |x| x * self.len);
        let p = self.state.pos;
        let h = self.state.h;
        [p[0] + h[0] * d, p[1] + h[1] * d, p[2] + h[2] * d]
    }

    /// Applies one module; a drawn step goes to `sink` (with the width
    /// `!` set last, in canvas units, or `None` for the file's `width`).
    pub fn module(&mut self, sym: char, params: &[f64], sink: &mut impl FnMut(Segment3, f64)) {
        let a = || params.first().copied();
        let angle = self.angle;
        match sym {
            'F' | 'G' => {
                let to = self.step(params);
                let p = self.state.pos;
                sink(
                    Segment3 {
                        from: Point3::new(p[0], p[1], p[2]),
                        to: Point3::new(to[0], to[1], to[2]),
                        order: 0,
                    },
                    self.state.width,
                );
                self.state.pos = to;
                self.bend();
            }
            'f' | 'g' => self.state.pos = self.step(params),
            '+' => self.turn(a().unwrap_or(angle)),
            '-' => self.turn(-a().unwrap_or(angle)),
            '|' => self.turn(180.0),
            '&' if self.three => self.pitch(a().unwrap_or(angle)),
            '^' if self.three => self.pitch(-a().unwrap_or(angle)),
            '\\' if self.three => self.roll(a().unwrap_or(angle)),
            '/' if self.three => self.roll(-a().unwrap_or(angle)),
            '$' if self.three => self.level(),
            '!' => {
                if let Some(w) = a() {
                    self.state.width = w;
                }
            }
            '[' => self.stack.push(self.state),
            ']' => {
                if let Some(s) = self.stack.pop() {
                    self.state = s;
                }
            }
            _ => {}
        }
    }
}

/// The stem order that carries width `w` ([`WIDTH_QUANTUM`]).
fn order_of(w: f64) -> u32 {
    let q = libm::round(w.max(0.0) / WIDTH_QUANTUM);
    if q.is_finite() {
        q.min(f64::from(u32::MAX)) as u32
    } else {
        0
    }
}

/// Draws `sys` derived to `depth` into a 2D turtle backend. Returns where
/// the turtle ends.
pub(crate) fn draw2<T: Turtle>(
    sys: &LSystem,
    p: &Parametric,
    depth: u32,
    strategy: crate::interpret::Derivation,
    limits: &crate::limits::Limits,
    mut turtle: T,
) -> Result<Point, crate::diag::Diagnostics> {
    let d = super::Deriver::new(sys, p);
    let mut t = Turtle3P::new(sys, p);
    let widths = p.sets_width();
    let mut sink = |s: Segment3, w: f64| {
        turtle.segment(Segment {
            from: Point::new(s.from.x, s.from.y),
            to: Point::new(s.to.x, s.to.y),
            order: if widths { order_of(w) } else { 0 },
        });
    };
    d.each(depth, strategy, limits, |sym, ps| {
        t.module(sym, ps, &mut sink)
    })?;
    let end = t.pos();
    Ok(Point::new(end.x, end.y))
}

/// Draws `sys` derived to `depth` in 3D into `sink`. Returns where the
/// turtle ends.
pub(crate) fn draw3(
    sys: &LSystem,
    p: &Parametric,
    depth: u32,
    strategy: crate::interpret::Derivation,
    limits: &crate::limits::Limits,
    sink: &mut dyn FnMut(Segment3),
) -> Result<Point3, crate::diag::Diagnostics> {
    let d = super::Deriver::new(sys, p);
    let mut t = Turtle3P::new(sys, p);
    let widths = p.sets_width();
    let mut each = |mut s: Segment3, w: f64| {
        if widths {
            s.order = order_of(w);
        }
        sink(s)
    };
    d.each(depth, strategy, limits, |sym, ps| {
        t.module(sym, ps, &mut each)
    })?;
    Ok(t.pos())
}
