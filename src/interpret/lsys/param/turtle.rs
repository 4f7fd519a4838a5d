//! The turtle of parametric systems (docs/lsys.md, *The turtle*): a frame
//! of three float vectors (H, L, U, section 11's), turned by any angle,
//! bent by tropism after every drawn step.
//!
//! `F(x) f(x)` move x times `length`, `+(a) -(a)` turn by a degrees (and
//! `& ^ \ /` in 3D), `$` (3D) rolls L horizontal, `!(w)` sets the width;
//! without a parameter each acts as in a classic system. In 2D the frame
//! never leaves the canvas plane (U stays (0, 0, -1)).

use std::rc::Rc;

use crate::model::lsys::LSystem;
use crate::model::param::{MAX_POLYGON_VERTICES, Parametric, WIDTH_QUANTUM, eval_const};
use crate::turtle::turtle3::{Point3, Segment3, cos_sin};
use crate::turtle::{Point, Segment, Turtle};

/// What the turtle hands on besides moving: a drawn step with its width,
/// a change of colour index, a closed polygon's vertices.
pub enum Mark<'a> {
    /// A drawn step, with the width in force (canvas units).
    Step(Segment3, f64),
    /// The colour index is now this (section 13: `' ; ,`, brackets).
    Paint(usize),
    /// A polygon `{ ... }` closed: its vertices, filled with the colour
    /// in force.
    Polygon(&'a [Point3]),
}

/// A surface's word, its parameters evaluated.
type SurfaceWord = Rc<[(char, Vec<f64>)]>;

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
    /// The colour index (brackets save and restore it).
    color: usize,
}

/// Each surface's name and word, its arguments evaluated once.
fn surface_words(surfaces: &[crate::model::param::Surface]) -> Vec<(char, SurfaceWord)> {
    surfaces
        .iter()
        .map(|s| {
            let w: Vec<(char, Vec<f64>)> = s
                .word
                .iter()
                .map(|m| (m.symbol, m.args.iter().map(eval_const).collect()))
                .collect();
            (s.name, Rc::from(w))
        })
        .collect()
}

/// The parametric turtle.
#[derive(Clone)]
pub struct Turtle3P {
    state: State,
    stack: Vec<State>,
    len: f64,
    angle: f64,
    three: bool,
    tropism: Option<(V, f64)>,
    /// Colours of the palette (at least 1: without one, `color` alone).
    colors: usize,
    /// What a bare `!` multiplies the width by.
    decay: f64,
    /// The surfaces, by name.
    surfaces: Vec<(char, SurfaceWord)>,
    /// A `~` was the last module: the next names a surface.
    placing: bool,
    /// Lengths are multiplied by this (a surface placed by `~X(s)`).
    scale: f64,
    /// The polygons open, innermost last, with their vertices.
    polygons: Vec<Vec<Point3>>,
    /// The colour index the sink was told last.
    shown: usize,
    /// A polygon passed [`MAX_POLYGON_VERTICES`].
    pub(crate) overfull: bool,
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
                color: 0,
            },
            stack: Vec::new(),
            len: sys.length,
            angle: sys.angle,
            three: sys.is_3d(),
            tropism: p.tropism.filter(|_| p.bends()).map(|t| {
                let t = if sys.is_3d() { t } else { [t[0], t[1], 0.0] };
                (t, p.elasticity)
            }),
            colors: p.organs.palette.len().max(1),
            decay: p.organs.decay(),
            surfaces: surface_words(&p.organs.surfaces),
            placing: false,
            scale: 1.0,
            polygons: Vec::new(),
            shown: 0,
            overfull: false,
        }
    }

    /// A turtle that only places `surfaces` (an OD's leaves, section 13):
    /// turns by `angle` degrees, in 3D if `three`, one colour.
    pub fn for_surfaces(
        surfaces: &[crate::model::param::Surface],
        angle: f64,
        three: bool,
    ) -> Turtle3P {
        let h = [0.0, -1.0, 0.0];
        Turtle3P {
            state: State {
                pos: [0.0; 3],
                h,
                l: [h[1], -h[0], 0.0],
                u: [0.0, 0.0, -1.0],
                width: 1.0,
                color: 0,
            },
            stack: Vec::new(),
            len: 1.0,
            angle,
            three,
            tropism: None,
            colors: 1,
            decay: crate::model::param::DEFAULT_WIDTH_DECAY,
            surfaces: surface_words(surfaces),
            placing: false,
            scale: 1.0,
            polygons: Vec::new(),
            shown: 0,
            overfull: false,
        }
    }

    /// Draws surface `name` at `pos` in the frame `frame` (H, L, U), its
    /// steps `len` long; the turtle's state is as it was after.
    pub fn place_at(
        &mut self,
        name: char,
        pos: Point3,
        frame: [V; 3],
        len: f64,
        sink: &mut impl FnMut(Mark<'_>),
    ) {
        self.state.pos = [pos.x, pos.y, pos.z];
        [self.state.h, self.state.l, self.state.u] = frame;
        self.len = len;
        self.place(name, 1.0, sink);
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

    /// Starts again at the origin in the identity frame (H, L, U along
    /// x, y, z) with `width` and colour index `color`, nothing open: a
    /// piece's own drawing, as a memo composes it.
    pub(crate) fn restart(&mut self, width: f64, color: usize) {
        self.state = State {
            pos: [0.0; 3],
            h: [1.0, 0.0, 0.0],
            l: [0.0, 1.0, 0.0],
            u: [0.0, 0.0, 1.0],
            width,
            color: color.min(self.colors - 1),
        };
        self.stack.clear();
        self.polygons.clear();
        self.placing = false;
        self.scale = 1.0;
        self.shown = self.state.color;
    }

    /// The width in force and the colour index.
    pub(crate) fn pen(&self) -> (f64, usize) {
        (self.state.width, self.state.color)
    }

    /// Sets the width, and the colour index (told to `sink` if changed):
    /// past a piece of the level of detail.
    pub(crate) fn set_pen(&mut self, width: f64, color: usize, sink: &mut impl FnMut(Mark<'_>)) {
        self.state.width = width;
        self.paint(color, sink);
    }

    /// Whether a polygon is open or a surface's name is awaited: a piece
    /// met now takes part in them and cannot be jumped.
    pub(crate) fn open(&self) -> bool {
        self.placing || !self.polygons.is_empty()
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
        let d = params.first().map_or(self.len, |x| x * self.len) * self.scale;
        let p = self.state.pos;
        let h = self.state.h;
        [p[0] + h[0] * d, p[1] + h[1] * d, p[2] + h[2] * d]
    }

    /// Records the turtle's position in the innermost open polygon.
    fn vertex(&mut self) {
        let at = self.pos();
        if let Some(poly) = self.polygons.last_mut() {
            if poly.last() == Some(&at) {
                return;
            }
            if poly.len() >= MAX_POLYGON_VERTICES {
                self.overfull = true;
                return;
            }
            poly.push(at);
        }
    }

    /// Sets the colour index to `i`, within the palette, and says so.
    fn paint(&mut self, i: usize, sink: &mut impl FnMut(Mark<'_>)) {
        self.state.color = i.min(self.colors - 1);
        self.show(sink);
    }

    /// Tells the sink the colour index in force if it changed.
    fn show(&mut self, sink: &mut impl FnMut(Mark<'_>)) {
        if self.state.color != self.shown {
            self.shown = self.state.color;
            sink(Mark::Paint(self.shown));
        }
    }

    /// Draws surface `name`'s word in the turtle's frame, lengths times
    /// `s`; the turtle's state is as it was after.
    fn place(&mut self, name: char, s: f64, sink: &mut impl FnMut(Mark<'_>)) {
        let Some(word) = self
            .surfaces
            .iter()
            .find(|(c, _)| *c == name)
            .map(|(_, w)| Rc::clone(w))
        else {
            return;
        };
        let (scale, depth) = (self.scale, self.stack.len());
        self.stack.push(self.state);
        self.scale *= s;
        for (sym, params) in word.iter() {
            self.module(*sym, params, sink);
        }
        // A surface's word balances its brackets (it is read like a
        // successor); restore whatever it left.
        self.stack.truncate(depth + 1);
        if let Some(st) = self.stack.pop() {
            self.state = st;
        }
        self.scale = scale;
        self.placing = false;
        self.show(sink);
    }

    /// Applies one module; a drawn step, a change of colour and a closed
    /// polygon go to `sink` (a step with the width `!` set last, in
    /// canvas units, or the file's `width`).
    pub fn module(&mut self, sym: char, params: &[f64], sink: &mut impl FnMut(Mark<'_>)) {
        let a = || params.first().copied();
        let angle = self.angle;
        if std::mem::take(&mut self.placing) && sym != '~' {
            self.place(sym, a().unwrap_or(1.0), sink);
            return;
        }
        match sym {
            'F' | 'G' => {
                let to = self.step(params);
                let p = self.state.pos;
                sink(Mark::Step(
                    Segment3 {
                        from: Point3::new(p[0], p[1], p[2]),
                        to: Point3::new(to[0], to[1], to[2]),
                        order: 0,
                    },
                    self.state.width,
                ));
                self.state.pos = to;
                self.bend();
            }
            'f' => {
                self.state.pos = self.step(params);
                self.vertex();
            }
            'g' => self.state.pos = self.step(params),
            '.' => self.vertex(),
            '{' => self.polygons.push(Vec::new()),
            '}' => {
                if let Some(mut poly) = self.polygons.pop() {
                    if poly.len() > 1 && poly.first() == poly.last() {
                        poly.pop();
                    }
                    if poly.len() >= 3 {
                        sink(Mark::Polygon(&poly));
                    }
                }
            }
            '~' => self.placing = true,
            '\'' | ';' => {
                let i = match a() {
                    Some(i) => clamp_index(i),
                    None => self.state.color.saturating_add(1),
                };
                self.paint(i, sink);
            }
            ',' => {
                let i = match a() {
                    Some(i) => clamp_index(i),
                    None => self.state.color.saturating_sub(1),
                };
                self.paint(i, sink);
            }
            '+' => self.turn(a().unwrap_or(angle)),
            '-' => self.turn(-a().unwrap_or(angle)),
            '|' => self.turn(180.0),
            '&' if self.three => self.pitch(a().unwrap_or(angle)),
            '^' if self.three => self.pitch(-a().unwrap_or(angle)),
            '\\' if self.three => self.roll(a().unwrap_or(angle)),
            '/' if self.three => self.roll(-a().unwrap_or(angle)),
            '$' if self.three => self.level(),
            '!' => match a() {
                Some(w) => self.state.width = w,
                None => self.state.width *= self.decay,
            },
            '[' => self.stack.push(self.state),
            ']' => {
                if let Some(s) = self.stack.pop() {
                    self.state = s;
                    self.show(sink);
                }
            }
            _ => {}
        }
    }
}

/// A colour index from a parameter: rounded, at least 0 (the palette's
/// end is applied by the turtle).
fn clamp_index(i: f64) -> usize {
    let r = libm::round(i);
    if r.is_nan() || r <= 0.0 {
        0
    } else {
        r.min(u32::MAX as f64) as usize
    }
}

/// The stem order that carries width `w` ([`WIDTH_QUANTUM`]).
pub(crate) fn order_of(w: f64) -> u32 {
    let q = libm::round(w.max(0.0) / WIDTH_QUANTUM);
    if q.is_finite() {
        q.min(f64::from(u32::MAX)) as u32
    } else {
        0
    }
}

/// The error of a polygon derived past [`MAX_POLYGON_VERTICES`]:
/// pointed at the file's first `{`.
fn overfull(p: &Parametric) -> crate::diag::Diagnostics {
    let span = p.organs.first_polygon.clone().map_or(0..0, |l| l.0);
    let mut d = crate::syntax::lsys::too_many(span);
    d.label = Some("a polygon derived from here records too many vertices".into());
    (*d).into()
}

/// Draws `sys` derived to `depth` into a 2D turtle backend. Returns where
/// the turtle ends. A palette's colours and the polygons reach the
/// backend through [`Turtle::paint`] and [`Turtle::polygon`].
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
    let palette = &p.organs.palette;
    if let Some(&c) = palette.first() {
        turtle.paint(c);
    }
    let mut flat = Vec::new();
    let mut sink = |m: Mark<'_>| match m {
        Mark::Step(s, w) => turtle.segment(Segment {
            from: Point::new(s.from.x, s.from.y),
            to: Point::new(s.to.x, s.to.y),
            order: if widths { order_of(w) } else { 0 },
        }),
        Mark::Paint(i) => {
            if let Some(&c) = palette.get(i) {
                turtle.paint(c);
            }
        }
        Mark::Polygon(pts) => {
            flat.clear();
            flat.extend(pts.iter().map(|q| Point::new(q.x, q.y)));
            turtle.polygon(&flat);
        }
    };
    d.each(depth, strategy, limits, |sym, ps| {
        t.module(sym, ps, &mut sink)
    })?;
    if t.overfull {
        return Err(overfull(p));
    }
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
    draw3_marks(sys, p, depth, strategy, limits, &mut |m| {
        if let Mark::Step(s, _) = m {
            sink(s)
        }
    })
}

/// Draws `sys` derived to `depth` in 3D into `sink`: its steps (each
/// with its width's order when the system sets widths), changes of
/// colour index and polygons. Returns where the turtle ends.
pub fn draw3_marks(
    sys: &LSystem,
    p: &Parametric,
    depth: u32,
    strategy: crate::interpret::Derivation,
    limits: &crate::limits::Limits,
    sink: &mut dyn FnMut(Mark<'_>),
) -> Result<Point3, crate::diag::Diagnostics> {
    let d = super::Deriver::new(sys, p);
    let mut t = Turtle3P::new(sys, p);
    let widths = p.sets_width();
    let mut each = |m: Mark<'_>| match m {
        Mark::Step(mut s, w) => {
            if widths {
                s.order = order_of(w);
            }
            sink(Mark::Step(s, w))
        }
        m => sink(m),
    };
    d.each(depth, strategy, limits, |sym, ps| {
        t.module(sym, ps, &mut each)
    })?;
    if t.overfull {
        return Err(overfull(p));
    }
    Ok(t.pos())
}
