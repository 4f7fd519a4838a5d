//! The level of detail of a 3D view of a parametric system, or of one
//! that paints: colours, widths, polygons and surfaces inside stand-ins
//! (docs/3d.md, *Level of detail*).
//!
//! The pieces are memo.rs's ([`Pieces`]): in a context-free system whose
//! rules choose by no probability, equal modules at equal depth expand to
//! equal words, and without tropism or `$` (both look at the absolute
//! heading) the turtle's operations are linear in its frame, so a piece's
//! drawing is its drawing from the origin in the identity frame, turned
//! and moved. What a piece does to the pen is no rotation: its end width
//! is the start's times a factor, or one `!(w)` set ([`WidthFx`]), and
//! its colour index a function of the start's, a table over the palette
//! (at most [`VIEW_COLORS`] colours). Each piece is composed by the exact
//! turtle ([`Turtle3P`]) itself, from the origin, its sub-pieces jumped
//! over by their reach: twice per start colour, at start widths 0 and 1,
//! since a piece's ink (length times width) is affine in its start width.
//!
//! The walk hands out every stem, colour change and polygon the exact
//! drawing would, except inside a cut piece: that is one stand-in, its
//! strokes' and polygons' ink seen from a random direction (a stroke's
//! length times pi / 4, a flat polygon's area times 1 / 2) in the colour
//! that ink mixes to, and the pen is set to the piece's end width and
//! colour. A piece met while a polygon is open, or a surface's name is
//! awaited, is expanded (its vertices belong to the open polygon); one
//! whose own successor leaves that so refuses the memo (drawn exactly).

use super::lie::{Sym, add_sym, axpy, dot, norm, outer, quad, turned, vector_area};
use super::pieces::{PARAM_SUCC, Pieces};
use super::turtle::{Mark, Turtle3P, order_of};
use crate::color::Rgb;
use crate::diag::Diagnostics;
use crate::interpret::lsys::lod::{self, Memo};
use crate::interpret::lsys::reach::{IDENTITY, M, V, apply, compose};
use crate::interpret::lsys::reach_lod::{Mark3, Part3, Plan3, ViewLod, stand_in_at};
use crate::model::lsys::LSystem;
use crate::model::param::Parametric;
use crate::progress::Progress;
use crate::render::SPREAD_MIN_PX;
use crate::render::view::SEEN_SHARE;
use crate::turtle::turtle3::Point3;

/// Most palette colours a view memo composes each piece for.
pub const VIEW_COLORS: usize = 16;

/// What a piece does to the width: the end width from the start's.
#[derive(Debug, Clone, Copy, PartialEq)]
enum WidthFx {
    /// Times this (a bare `!` multiplies by the width decay).
    Scale(f64),
    /// Set to this (`!(w)`).
    Set(f64),
}

impl WidthFx {
    fn apply(self, w: f64) -> f64 {
        match self {
            WidthFx::Scale(k) => w * k,
            WidthFx::Set(v) => v,
        }
    }
}

/// What a piece does relative to its start (origin, identity frame).
#[derive(Debug, Clone, Copy)]
struct Reach3 {
    end: V,
    rot: M,
    /// Every drawn point (stems and polygons) is within this distance.
    radius: f64,
    /// Drawn length.
    length: f64,
    /// Sum over stems of length times midpoint, and of length times the
    /// midpoint's squared distance (reach.rs's centroid).
    moment: V,
    second: f64,
    /// Saturating drawn steps, modules.
    stems: u64,
    modules: u64,
    /// `f`, `g` and `]` met.
    breaks: f64,
    /// The strokes' ink (length times width) at start width `w`:
    /// `ink.0 w + ink.1`.
    ink: (f64, f64),
    /// The polygons' area.
    area: f64,
    /// How the strokes lie: the sum of length times `h h^T` (`h` a
    /// stroke's direction), and the polygons: area times `n n^T` (`n` a
    /// normal); turned with the piece ([`turned`]).
    strokes_lie: Sym,
    polygons_lie: Sym,
    width: WidthFx,
    /// Neither the colour nor the width changes inside.
    plain: bool,
}

impl Reach3 {
    const NOTHING: Reach3 = Reach3 {
        end: [0.0; 3],
        rot: IDENTITY,
        radius: 0.0,
        length: 0.0,
        moment: [0.0; 3],
        second: 0.0,
        stems: 0,
        modules: 0,
        breaks: 0.0,
        ink: (0.0, 0.0),
        area: 0.0,
        strokes_lie: [0.0; 6],
        polygons_lie: [0.0; 6],
        width: WidthFx::Scale(1.0),
        plain: true,
    };

    fn draws(&self) -> bool {
        self.stems > 0 || self.area > 0.0
    }

    fn centroid(&self) -> (V, f64) {
        if self.length <= 0.0 {
            return ([0.0; 3], 0.0);
        }
        let c = self.moment.map(|m| m / self.length);
        let g2 = self.second / self.length - dot(c, c);
        (c, libm::sqrt(g2.max(0.0)))
    }
}

/// What a piece paints from one start colour index.
#[derive(Debug, Clone, Copy, Default)]
struct Paint3 {
    /// The colour index it ends with.
    end: usize,
    /// Its strokes' colours weighted by their ink at start width `w`:
    /// `stroke.0 w + stroke.1`.
    stroke: ([f64; 3], [f64; 3]),
    /// Its polygons' colours weighted by their area.
    poly: [f64; 3],
    /// Its stems' colours summed (each stem's caps).
    stems: [f64; 3],
}

/// The memo; see the module documentation.
pub struct ViewMemo {
    pieces: Pieces,
    reach: Vec<Reach3>,
    /// `paint[node * colors + c]`: from start colour index `c`.
    paint: Vec<Paint3>,
    colors: usize,
    /// The palette as `[r, g, b]` (empty: the picture's one colour).
    palette: Vec<[f64; 3]>,
    /// Whether the system sets widths (`!`): strokes' widths are their
    /// own, else every stroke is the picture's.
    widths: bool,
    /// The turtle at the drawing's start.
    turtle: Turtle3P,
    /// The whole word's reach (from the origin, the identity frame).
    whole: Reach3,
}

/// A piece composed from one start pen: its reach and paint, `None` where
/// a sub-piece is met inside an open polygon or surface placing.
type Composed = Option<(Reach3, Paint3, f64)>;

impl ViewMemo {
    /// The memo of the 3D system `p` to `depth`; `None` where it does not
    /// apply (contexts, probabilities, tropism, `$`, more than
    /// [`VIEW_COLORS`] colours, a piece inside an open polygon, past the
    /// pieces' budget).
    pub fn new(sys: &LSystem, p: &Parametric, depth: u32) -> Result<Option<ViewMemo>, Diagnostics> {
        let levels_anywhere = std::iter::once(&p.axiom)
            .chain(p.rules.iter().map(|r| &r.successor))
            .chain(p.organs.surfaces.iter().map(|s| &s.word))
            .flatten()
            .any(|m| m.symbol == '$');
        let colors = p.organs.palette.len().max(1);
        if !sys.is_3d()
            || p.has_context()
            || p.bends()
            || levels_anywhere
            || colors > VIEW_COLORS
            || p.rules.iter().any(|r| r.probability.is_some())
        {
            return Ok(None);
        }
        let Some(pieces) = Pieces::new(sys, p, depth)? else {
            return Ok(None);
        };
        if pieces.entries.saturating_mul(colors) > PARAM_SUCC {
            return Ok(None);
        }
        let n = pieces.len();
        let mut m = ViewMemo {
            reach: vec![Reach3::NOTHING; n],
            paint: vec![Paint3::default(); n * colors],
            colors,
            palette: p
                .organs
                .palette
                .iter()
                .map(|c| [f64::from(c.r), f64::from(c.g), f64::from(c.b)])
                .collect(),
            widths: p.sets_width(),
            turtle: Turtle3P::new(sys, p),
            whole: Reach3::NOTHING,
            pieces,
        };
        let mut work = m.turtle.clone();
        let levels = std::mem::take(&mut m.pieces.levels);
        for &id in levels.iter().flatten() {
            let Some(kids) = m.pieces.succ[id as usize].take() else {
                continue;
            };
            let ok = m.compose_piece(&mut work, id as usize, &kids);
            m.pieces.succ[id as usize] = Some(kids);
            if !ok {
                return Ok(None);
            }
        }
        m.pieces.levels = levels;
        let axiom = std::mem::take(&mut m.pieces.axiom);
        let whole = m.compose_with(&mut work, &axiom, sys.width, 0);
        m.pieces.axiom = axiom;
        let Some((whole, _, _)) = whole else {
            return Ok(None);
        };
        m.whole = whole;
        Ok(Some(m))
    }

    /// Composes piece `id` from its successor `kids` for every start
    /// colour; false where it cannot be.
    fn compose_piece(&mut self, t: &mut Turtle3P, id: usize, kids: &[u32]) -> bool {
        for c in 0..self.colors {
            let (Some((r1, p1, e1)), Some((r0, p0, e0))) = (
                self.compose_with(t, kids, 1.0, c),
                self.compose_with(t, kids, 0.0, c),
            ) else {
                return false;
            };
            if c == 0 {
                self.reach[id] = Reach3 {
                    ink: (r1.ink.1 - r0.ink.1, r0.ink.1),
                    width: if e0 == 0.0 {
                        WidthFx::Scale(e1)
                    } else {
                        WidthFx::Set(e0)
                    },
                    ..r1
                };
            }
            let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
            self.paint[id * self.colors + c] = Paint3 {
                end: p1.end,
                stroke: (sub(p1.stroke.1, p0.stroke.1), p0.stroke.1),
                poly: p1.poly,
                stems: p1.stems,
            };
        }
        true
    }

    /// The colour of index `c` as `[r, g, b]` (black without a palette:
    /// its weights are not used then).
    fn rgb(&self, c: usize) -> [f64; 3] {
        self.palette.get(c).copied().unwrap_or([0.0; 3])
    }

    /// The reach and paint of `kids` drawn by `t` from the origin with
    /// start width `w0` and colour index `c0` (the ink and colour sums in
    /// the second fields, `.1`), and its end width.
    fn compose_with(&self, t: &mut Turtle3P, kids: &[u32], w0: f64, c0: usize) -> Composed {
        t.restart(w0, c0);
        let mut acc = Reach3::NOTHING;
        let mut paint = Paint3::default();
        let mut color = t.pen().1;
        let widths = self.widths;
        for &k in kids {
            let k = k as usize;
            if self.pieces.succ[k].is_some() {
                if t.open() {
                    return None;
                }
                let c = self.reach[k];
                let (w, ci) = t.pen();
                let pos = t.pos();
                let pos = [pos.x, pos.y, pos.z];
                let f = t.frame();
                self.join(&c, pos, &f, &mut acc);
                let w_ink = if widths { w } else { 1.0 };
                acc.ink.1 += c.ink.0 * w_ink + c.ink.1;
                let pc = &self.paint[k * self.colors + ci];
                for j in 0..3 {
                    paint.stroke.1[j] += pc.stroke.0[j] * w_ink + pc.stroke.1[j];
                    paint.poly[j] += pc.poly[j];
                    paint.stems[j] += pc.stems[j];
                }
                acc.plain &= c.plain;
                t.jump(axpy(pos, apply(&f, c.end), 1.0), compose(&f, &c.rot));
                t.set_pen(c.width.apply(w), pc.end, &mut |_| {});
                color = pc.end;
                continue;
            }
            let sym = self.pieces.sym[k];
            acc.modules = acc.modules.saturating_add(1);
            match sym {
                'f' | 'g' | ']' => acc.breaks += 1.0,
                '\'' | ';' | ',' | '!' => acc.plain = false,
                _ => {}
            }
            let params = self.pieces.params(k as u32);
            t.module(sym, params, &mut |m| match m {
                Mark::Step(s, w) => {
                    let (a, b) = ([s.from.x, s.from.y, s.from.z], [s.to.x, s.to.y, s.to.z]);
                    let len = norm(axpy(b, a, -1.0));
                    acc.radius = acc.radius.max(norm(a)).max(norm(b));
                    acc.length += len;
                    let mid = [
                        (a[0] + b[0]) / 2.0,
                        (a[1] + b[1]) / 2.0,
                        (a[2] + b[2]) / 2.0,
                    ];
                    acc.moment = axpy(acc.moment, mid, len);
                    acc.second += len * dot(mid, mid);
                    acc.stems = acc.stems.saturating_add(1);
                    if len > 0.0 {
                        add_sym(&mut acc.strokes_lie, &outer(axpy(b, a, -1.0), 1.0 / len));
                    }
                    let ink = len * if widths { w } else { 1.0 };
                    acc.ink.1 += ink;
                    paint.stroke.1 = axpy(paint.stroke.1, self.rgb(color), ink);
                    paint.stems = axpy(paint.stems, self.rgb(color), 1.0);
                }
                Mark::Paint(i) => color = i,
                Mark::Polygon(points) => {
                    let va = vector_area(points);
                    let a = norm(va);
                    if a > 0.0 {
                        add_sym(&mut acc.polygons_lie, &outer(va, 1.0 / a));
                    }
                    acc.area += a;
                    paint.poly = axpy(paint.poly, self.rgb(color), a);
                    for q in points {
                        acc.radius = acc.radius.max(norm([q.x, q.y, q.z]));
                    }
                }
            });
        }
        if t.open() {
            return None;
        }
        let pos = t.pos();
        acc.end = [pos.x, pos.y, pos.z];
        acc.rot = t.frame();
        paint.end = t.pen().1;
        Some((acc, paint, t.pen().0))
    }

    /// Appends piece `c`, started at `pos` in frame `f`, to `acc`'s
    /// geometry (reach.rs's join).
    fn join(&self, c: &Reach3, pos: V, f: &M, acc: &mut Reach3) {
        if c.draws() {
            acc.radius = acc.radius.max(norm(pos) + c.radius);
            let m = apply(f, c.moment);
            acc.second += c.second + 2.0 * dot(pos, m) + c.length * dot(pos, pos);
            acc.moment = axpy(axpy(acc.moment, m, 1.0), pos, c.length);
        }
        acc.length += c.length;
        acc.area += c.area;
        add_sym(&mut acc.strokes_lie, &turned(f, &c.strokes_lie));
        add_sym(&mut acc.polygons_lie, &turned(f, &c.polygons_lie));
        acc.stems = acc.stems.saturating_add(c.stems);
        acc.modules = acc.modules.saturating_add(c.modules);
        acc.breaks += c.breaks;
    }

    /// Whether a piece is cut at `detail` (never at 0): one that draws
    /// nothing, one straight run of one width and colour (its chord), one
    /// smaller than the detail.
    fn cut(r: &Reach3, detail: f64) -> bool {
        if detail <= 0.0 || detail.is_nan() {
            return false;
        }
        if !r.draws() {
            return true;
        }
        let straight =
            r.area == 0.0 && r.plain && r.breaks == 0.0 && r.length <= norm(r.end) * (1.0 + 1e-9);
        if straight {
            return true;
        }
        let d = 2.0 * r.radius;
        if r.breaks > 0.0 {
            d < detail
        } else {
            d < detail / 2.0
        }
    }
}

impl ViewLod for ViewMemo {
    fn radius(&self) -> f64 {
        self.whole.radius
    }

    fn plan(&self, detail: f64) -> Plan3 {
        let n = self.pieces.len();
        let mut cost: Vec<(u64, u64)> = (0..n as u32)
            .map(|id| {
                let s = self.pieces.sym[id as usize];
                (1, u64::from(matches!(s, 'F' | 'G' | '}')))
            })
            .collect();
        for &id in self.pieces.levels.iter().flatten() {
            let id = id as usize;
            let Some(kids) = &self.pieces.succ[id] else {
                continue;
            };
            let me = &self.reach[id];
            cost[id] = if Self::cut(me, detail) {
                (1, u64::from(me.draws()))
            } else {
                kids.iter().fold((1u64, 0u64), |(v, m), &k| {
                    let (cv, cm) = cost[k as usize];
                    (v.saturating_add(cv), m.saturating_add(cm))
                })
            };
        }
        let (visits, marks) = self.pieces.axiom.iter().fold((0u64, 0u64), |(v, m), &k| {
            let (cv, cm) = cost[k as usize];
            (v.saturating_add(cv), m.saturating_add(cm))
        });
        Plan3 { visits, marks }
    }

    fn size(&self) -> (u64, u64) {
        (self.whole.modules, self.whole.stems)
    }

    fn walk(
        &self,
        sys: &LSystem,
        detail: f64,
        visits: u64,
        pen: (f64, f64),
        toward: V,
        sink: &mut dyn FnMut(Mark3<'_>),
        progress: &mut dyn Progress,
    ) {
        let _ = sys;
        let t = self.turtle.clone();
        progress.start("modules", visits);
        let mut w = WalkView {
            m: self,
            detail,
            stroke: pen.0,
            scale: pen.1,
            toward,
            t,
            sink,
        };
        lod::walk(&mut w, &self.pieces.axiom, self.pieces.depth, (), progress);
        progress.finish();
    }
}

/// A walk of the view memo: the exact turtle, and where marks go.
struct WalkView<'m, 's> {
    m: &'m ViewMemo,
    detail: f64,
    /// A stroke of order 0's width, canvas units.
    stroke: f64,
    /// Output pixels per canvas unit.
    scale: f64,
    /// The view's direction (away from the camera).
    toward: V,
    t: Turtle3P,
    sink: &'s mut dyn FnMut(Mark3<'_>),
}

/// Hands a mark of the exact turtle to a view's sink: a stem with its
/// width's order where the system sets widths.
fn forward(widths: bool, sink: &mut dyn FnMut(Mark3<'_>), m: Mark<'_>) {
    match m {
        Mark::Step(mut s, w) => {
            if widths {
                s.order = order_of(w);
            }
            sink(Mark3::Stem(s));
        }
        Mark::Paint(i) => sink(Mark3::Paint(i)),
        Mark::Polygon(points) => sink(Mark3::Polygon(points)),
    }
}

impl WalkView<'_, '_> {
    /// The stand-in of piece `p` (paint `pc` from the colour in force)
    /// started at `from` in `frame` with width `w`: its ink seen along
    /// the view, in the colour that ink mixes to. The exact view draws
    /// every stem on its own, its caps and anti-aliased edges piling up
    /// where stems overlap: the bush has a run per stem, a straight run
    /// included (a bush along its chord, not one line).
    fn stand_in(&self, p: &Reach3, pc: &Paint3, from: Point3, frame: &M, w: f64) -> Mark3<'static> {
        let m = self.m;
        let part = Part3 {
            end: p.end,
            radius: p.radius,
            length: p.length,
            jumps: p.breaks > 0.0 || p.area > 0.0,
            breaks: p.breaks,
            centroid: p.centroid(),
        };
        let (seg, spread) = match stand_in_at(from, frame, &part) {
            Mark3::StandIn { seg, spread, .. } => (seg, spread),
            Mark3::Stem(seg) => (seg, 0.0),
            _ => unreachable!("a stand-in is a stem or a bush"),
        };
        let w_ink = if m.widths { w } else { 1.0 };
        // The share of its strokes' length and polygons' area seen along
        // the view: each stroke shows `|h x v|` of its length, each
        // polygon `|n . v|` of its area; their root mean squares over the
        // piece (exact for one stroke or polygon, sqrt(2/3) and sqrt(1/3)
        // for ones turned every way alike).
        let v = frame.map(|axis| dot(axis, self.toward));
        let along = if p.length > 0.0 {
            libm::sqrt((1.0 - quad(&p.strokes_lie, v) / p.length).max(0.0))
        } else {
            0.0
        };
        let facing = if p.area > 0.0 {
            libm::sqrt((quad(&p.polygons_lie, v) / p.area).max(0.0))
        } else {
            0.0
        };
        let unit = if m.widths { 1.0 } else { self.stroke };
        let strokes = (p.ink.0 * w_ink + p.ink.1) * unit;
        // Strokes of the mean width carry all the ink.
        let mean = if p.length > 0.0 && strokes > 0.0 {
            strokes / p.length
        } else if m.widths {
            w
        } else {
            self.stroke
        };
        let seen = strokes * along + p.area * facing;
        // Each stem's two caps: a wide stroke's round ends (a disc of its
        // width), a hairline's pi / 8 past each end (stroke_px's floor).
        let px = (mean * self.scale).max(crate::render::HAIRLINE);
        let cap = if px > 1.0 {
            std::f64::consts::FRAC_PI_4 * px * px
        } else {
            std::f64::consts::FRAC_PI_4 * px
        } / (self.scale * self.scale);
        let stems = p.stems as f64;
        let color = (!m.palette.is_empty() && seen + stems * cap > 0.0).then(|| {
            let mut rgb = [0.0; 3];
            for (j, v) in rgb.iter_mut().enumerate() {
                let s = (pc.stroke.0[j] * w_ink + pc.stroke.1[j]) * unit;
                *v = (s * along + pc.poly[j] * facing + pc.stems[j] * cap) / (seen + stems * cap);
            }
            let byte = |v: f64| libm::round(v.clamp(0.0, 255.0)) as u8;
            Rgb {
                r: byte(rgb[0]),
                g: byte(rgb[1]),
                b: byte(rgb[2]),
            }
        });
        Mark3::StandIn {
            seg,
            density: 0.0,
            // Just over the PNG backend's narrowest bush: it paints the
            // piled-up ink, not one line.
            spread: spread.max(1.1 * SPREAD_MIN_PX / self.scale),
            length: if mean > 0.0 {
                seen / (SEEN_SHARE * mean)
            } else {
                0.0
            },
            runs: stems.max(1.0),
            color,
            order: if m.widths { order_of(mean) } else { 0 },
        }
    }
}

impl<'m> Memo<'m> for WalkView<'m, '_> {
    type Ctx = ();

    #[inline]
    fn child(_: (), _: usize) {}

    #[inline]
    fn is_piece(&self, c: u32, _: u32) -> bool {
        self.m.pieces.succ[c as usize].is_some()
    }

    fn piece(&mut self, c: u32, _: u32, _: ()) -> Option<&'m [u32]> {
        let m = self.m;
        let p = &m.reach[c as usize];
        if self.t.open() || !ViewMemo::cut(p, self.detail) {
            return m.pieces.succ[c as usize].as_deref();
        }
        let (w, ci) = self.t.pen();
        let pc = &m.paint[c as usize * m.colors + ci];
        let from = self.t.pos();
        let frame = self.t.frame();
        if p.draws() {
            let mark = self.stand_in(p, pc, from, &frame, w);
            (self.sink)(mark);
        }
        let pos = [from.x, from.y, from.z];
        self.t.jump(
            axpy(pos, apply(&frame, p.end), 1.0),
            compose(&frame, &p.rot),
        );
        let widths = m.widths;
        let sink = &mut *self.sink;
        self.t.set_pen(p.width.apply(w), pc.end, &mut |mk| {
            forward(widths, sink, mk)
        });
        None
    }

    #[inline]
    fn terminal(&mut self, c: u32) {
        let m = self.m;
        let widths = m.widths;
        let sink = &mut *self.sink;
        self.t
            .module(m.pieces.sym[c as usize], m.pieces.params(c), &mut |mk| {
                forward(widths, sink, mk)
            });
    }
}

#[cfg(test)]
#[path = "memo3_tests.rs"]
mod tests;
