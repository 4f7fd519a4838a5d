//! The level of detail of a parametric system where its pieces repeat
//! (docs/architecture.md, *What a system gives up*).
//!
//! A piece is a module (its symbol and parameter values, bit for bit)
//! expanded `r` more times. In a context-free system whose rules choose
//! by no probability, two equal modules at equal depth expand to equal
//! words (a rule's condition and successor see only the parameters), and
//! without tropism the turtle's operations are linear in its frame, so
//! the drawing of a piece started at position `p` with frame `F` is its
//! drawing from the origin with the identity frame, turned by `F` and
//! moved by `p`, as a 3D classic piece's (`reach.rs`). The memo interns
//! every distinct piece the word reaches, from the axiom down (a node per
//! module and depth, its successor as nodes one level down), and composes
//! each one's reach bottom-up: where it ends, its end frame, a ball about
//! its start holding every drawn point, its stems. Headings are floats:
//! nothing is keyed by heading, and a piece jumped over lands where a
//! traversal would within rounding.
//!
//! It applies to 2D systems without contexts, probabilities, tropism or
//! `!(w)` (a piece's stems would take the width in effect where it
//! starts), within [`PARAM_NODES`] pieces; elsewhere the system is drawn
//! exactly within the symbol budget. The walk is the one walk
//! ([`lod::walk`]): a module that is not cut is applied by the exact
//! turtle ([`Turtle3P::module`]), so at detail 0 it is the exact drawing.

use super::PARAM_COST;
pub use super::pieces::PARAM_NODES;
use super::pieces::Pieces;
use super::turtle::Turtle3P;
use crate::diag::{Diagnostics, Help, Knob};
use crate::interpret::lsys::lod::{self, Memo};
use crate::limits::{Bound, Limits};
use crate::model::lsys::LSystem;
use crate::model::param::Parametric;
use crate::progress::Progress;
use crate::turtle::turtle3::cos_sin;
use crate::turtle::{Footprint, Point, Segment, StandIn, Turtle};

type V = [f64; 3];
type M = [V; 3];

const IDENTITY: M = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// `f v`: local `v` (along H, L, U) in the frame's coordinates, with the
/// turtle's own products (`comb`, then U's share).
fn apply(f: &M, v: V) -> V {
    let a = [
        f[0][0] * v[0] + f[1][0] * v[1],
        f[0][1] * v[0] + f[1][1] * v[1],
        f[0][2] * v[0] + f[1][2] * v[1],
    ];
    [
        a[0] + f[2][0] * v[2],
        a[1] + f[2][1] * v[2],
        a[2] + f[2][2] * v[2],
    ]
}

fn compose(f: &M, g: &M) -> M {
    [apply(f, g[0]), apply(f, g[1]), apply(f, g[2])]
}

fn norm(v: V) -> f64 {
    libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
}

/// What a piece does relative to its start (origin, identity frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Reach {
    /// Where it ends.
    pub end: V,
    /// The frame it ends in.
    pub rot: M,
    /// Every drawn point is within this distance of the start.
    pub radius: f64,
    /// Drawn length.
    pub length: f64,
    /// Saturating number of drawn steps.
    pub stems: u64,
    /// Saturating number of modules.
    pub modules: u64,
    /// How many times it moves without drawing or returns (`f`, `]`).
    pub breaks: f64,
}

impl Reach {
    const NOTHING: Reach = Reach {
        end: [0.0; 3],
        rot: IDENTITY,
        radius: 0.0,
        length: 0.0,
        stems: 0,
        modules: 1,
        breaks: 0.0,
    };

    fn draws(&self) -> bool {
        self.stems > 0
    }

    /// One module's reach, as [`Turtle3P::module`] moves the frame in 2D.
    fn module(sym: char, params: &[f64], len: f64, angle: f64) -> Reach {
        let a = || params.first().copied();
        let step = || params.first().map_or(len, |x| x * len);
        let turn = |deg: f64| {
            let (c, s) = cos_sin(deg);
            let h = [c, s, 0.0];
            let l = [-s, c, 0.0];
            Reach {
                rot: [h, l, [0.0, 0.0, 1.0]],
                ..Reach::NOTHING
            }
        };
        match sym {
            'F' | 'G' => {
                let d = step();
                Reach {
                    end: [d, 0.0, 0.0],
                    radius: d.abs(),
                    length: d.abs(),
                    stems: 1,
                    ..Reach::NOTHING
                }
            }
            'f' | 'g' => Reach {
                end: [step(), 0.0, 0.0],
                breaks: 1.0,
                ..Reach::NOTHING
            },
            '+' => turn(a().unwrap_or(angle)),
            '-' => turn(-a().unwrap_or(angle)),
            '|' => turn(180.0),
            _ => Reach::NOTHING,
        }
    }
}

/// The memo of one system at one depth: its pieces, and each one's reach.
pub struct ParamMemo {
    pieces: Pieces,
    reach: Vec<Reach>,
}

impl ParamMemo {
    /// The memo of `sys` to `depth`, `None` when it does not apply (see
    /// the module documentation) or would pass [`PARAM_NODES`]; an error
    /// where deriving would fail (a non-finite parameter).
    pub fn new(
        sys: &LSystem,
        p: &Parametric,
        depth: u32,
    ) -> Result<Option<ParamMemo>, Diagnostics> {
        if sys.is_3d()
            || p.has_context()
            || p.bends()
            || p.sets_width()
            || p.paints()
            || p.rules.iter().any(|r| r.probability.is_some())
        {
            return Ok(None);
        }
        let Some(pieces) = Pieces::new(sys, p, depth)? else {
            return Ok(None);
        };
        let mut m = ParamMemo {
            reach: vec![Reach::NOTHING; pieces.sym.len()],
            pieces,
        };
        m.compose_all(sys);
        Ok(Some(m))
    }

    /// Every node's reach, level by level from depth 0 up.
    fn compose_all(&mut self, sys: &LSystem) {
        let (len, angle) = (sys.length, sys.angle);
        let levels = std::mem::take(&mut self.pieces.levels);
        for level in &levels {
            for &id in level {
                let reach = match &self.pieces.succ[id as usize] {
                    None => Reach::module(
                        self.pieces.sym[id as usize],
                        self.pieces.params(id),
                        len,
                        angle,
                    ),
                    Some(kids) => self.compose(kids),
                };
                self.reach[id as usize] = reach;
            }
        }
        self.pieces.levels = levels;
    }

    /// The reach of a word of nodes (their reaches known) from the origin.
    fn compose(&self, kids: &[u32]) -> Reach {
        let (mut pos, mut rot) = ([0.0f64; 3], IDENTITY);
        let mut stack: Vec<(V, M)> = Vec::new();
        let mut acc = Reach {
            modules: 0,
            ..Reach::NOTHING
        };
        for &k in kids {
            match self.pieces.sym[k as usize] {
                '[' => stack.push((pos, rot)),
                ']' => {
                    if let Some((p, r)) = stack.pop() {
                        (pos, rot) = (p, r);
                    }
                    acc.breaks += 1.0;
                }
                _ => {
                    let c = &self.reach[k as usize];
                    if c.draws() {
                        acc.radius = acc.radius.max(norm(pos) + c.radius);
                    }
                    let e = apply(&rot, c.end);
                    pos = [pos[0] + e[0], pos[1] + e[1], pos[2] + e[2]];
                    rot = compose(&rot, &c.rot);
                    acc.length += c.length;
                    acc.stems = acc.stems.saturating_add(c.stems);
                    acc.breaks += c.breaks;
                }
            }
            acc.modules = acc.modules.saturating_add(self.reach[k as usize].modules);
        }
        acc.end = pos;
        acc.rot = rot;
        acc
    }

    /// Whether a piece is cut at `detail` (never at 0).
    fn cut(r: &Reach, detail: f64) -> bool {
        if detail <= 0.0 || detail.is_nan() {
            return false;
        }
        if !r.draws() {
            return true;
        }
        let d = 2.0 * r.radius;
        if r.breaks > 0.0 {
            d < detail
        } else {
            d < detail / 2.0
        }
    }

    /// Modules and stand-ins a walk at `detail` visits (saturating).
    pub fn visits(&self, detail: f64) -> u64 {
        let mut cost = vec![1u64; self.pieces.sym.len()];
        // Level by level from depth 0 up: children before parents.
        for &id in self.pieces.levels.iter().flatten() {
            let id = id as usize;
            if let Some(kids) = &self.pieces.succ[id]
                && !Self::cut(&self.reach[id], detail)
            {
                cost[id] = kids
                    .iter()
                    .fold(1u64, |a, &k| a.saturating_add(cost[k as usize]));
            }
        }
        self.pieces
            .axiom
            .iter()
            .fold(0u64, |a, &k| a.saturating_add(cost[k as usize]))
    }

    /// Distinct pieces (module and depth) the word reaches.
    pub fn nodes(&self) -> usize {
        self.pieces.sym.len()
    }

    /// Modules of the whole word (saturating).
    pub fn modules(&self) -> u64 {
        self.pieces.axiom.iter().fold(0u64, |a, &k| {
            a.saturating_add(self.reach[k as usize].modules)
        })
    }

    /// Whether the walk at `detail` pays: it visits at most half the
    /// word (else the exact drawing costs about as much, and is exact).
    pub fn walk_pays(&self, detail: f64) -> bool {
        self.visits(detail) <= self.modules() / 2
    }

    /// Drawn steps of the whole word (saturating).
    pub fn stems(&self) -> u64 {
        self.pieces
            .axiom
            .iter()
            .fold(0u64, |a, &k| a.saturating_add(self.reach[k as usize].stems))
    }

    /// A ball about the start holding the whole drawing: its radius.
    pub fn radius(&self) -> f64 {
        self.compose(&self.pieces.axiom).radius
    }

    /// Draws the word at `detail` canvas units into `turtle`, refused past
    /// the parametric share of `max_symbols`; returns where it ends.
    pub fn draw(
        &self,
        sys: &LSystem,
        p: &Parametric,
        detail: f64,
        limits: &Limits,
        turtle: &mut dyn Turtle,
        progress: &mut dyn Progress,
    ) -> Result<Point, Diagnostics> {
        let visits = self.visits(detail);
        let most = (limits.max_symbols / PARAM_COST).max(1);
        if visits > most {
            // The count saturates: past u64 it is a bound, not a number.
            let value = match visits {
                u64::MAX => "more than 2^64".to_string(),
                n => n.to_string(),
            };
            return Err(Bound::Symbols
                .exceeded_by(
                    format!(
                        "modules to visit at depth {} at this level of detail",
                        self.pieces.depth
                    ),
                    value,
                    most,
                )
                .with_help(
                    Help::from(
                        "a parametric system's repeated pieces are drawn at a level of detail, \
                         and it may visit a thirtieth of ",
                    ) + Help::knob(Knob::Limit(Bound::Symbols), "")
                        + ": use a smaller depth or "
                        + Help::knob(Knob::Size, "")
                        + ", or "
                        + Bound::Symbols,
                )
                .into());
        }
        progress.start("modules", visits);
        let mut w = WalkParam {
            m: self,
            detail,
            t: Turtle3P::new(sys, p),
            turtle,
        };
        lod::walk(&mut w, &self.pieces.axiom, self.pieces.depth, (), progress);
        progress.finish();
        let end = w.t.pos();
        Ok(Point::new(end.x, end.y))
    }
}

/// A walk of the parametric memo: the exact turtle and the backend.
struct WalkParam<'m, 't> {
    m: &'m ParamMemo,
    detail: f64,
    t: Turtle3P,
    turtle: &'t mut dyn Turtle,
}

impl WalkParam<'_, '_> {
    fn segment(turtle: &mut dyn Turtle, from: V, to: V) {
        turtle.segment(Segment {
            from: Point::new(from[0], from[1]),
            to: Point::new(to[0], to[1]),
            order: 0,
        });
    }
}

impl<'m> Memo<'m> for WalkParam<'m, '_> {
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
        if !ParamMemo::cut(p, self.detail) {
            return m.pieces.succ[c as usize].as_deref();
        }
        let from = self.t.pos();
        let frame = self.t.frame();
        let e = apply(&frame, p.end);
        let to = [from.x + e[0], from.y + e[1], from.z + e[2]];
        if p.draws() {
            let seg = Segment {
                from: Point::new(from.x, from.y),
                to: Point::new(to[0], to[1]),
                order: 0,
            };
            if p.breaks == 0.0 {
                self.turtle.run(seg, p.stems as f64);
            } else {
                let mut seg = seg;
                let chord = libm::hypot(seg.to.x - seg.from.x, seg.to.y - seg.from.y);
                // A bush that comes back to its start: a short segment
                // across the screen carries the ink.
                let chord = if chord > 1e-9 * (1.0 + p.radius) {
                    chord
                } else {
                    let e = 1e-6 * (1.0 + p.radius);
                    seg.to = Point::new(seg.from.x + e, seg.from.y);
                    e
                };
                let density = (p.length / chord).max(1.0);
                self.turtle.stand_in(&StandIn {
                    seg,
                    density: if density.is_finite() { density } else { 1.0 },
                    footprint: Some(Footprint {
                        spread: p.radius,
                        runs: p.breaks + 1.0,
                    }),
                    sample: None,
                });
            }
        }
        self.t.jump(to, compose(&frame, &p.rot));
        None
    }

    #[inline]
    fn terminal(&mut self, c: u32) {
        let m = self.m;
        let turtle = &mut *self.turtle;
        self.t
            .module(m.pieces.sym[c as usize], m.pieces.params(c), &mut |mark| {
                if let super::turtle::Mark::Step(s, _) = mark {
                    Self::segment(
                        turtle,
                        [s.from.x, s.from.y, s.from.z],
                        [s.to.x, s.to.y, s.to.z],
                    )
                }
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::Limits;
    use crate::progress::NoProgress;
    use crate::turtle::Recorder;

    /// `A(x) -> F(x)[+A(x)]A(x)` doubles its apices each step: at depth
    /// 1100 the modules to visit pass u64, and the error says so instead
    /// of printing the saturated count (18446744073709551615). At depth 20
    /// and detail 0 the count is a number: the 2^20 - 1 apices rewritten
    /// on the way, then the last word's 2^20 apices and 2^20 - 1 of each
    /// of `F`, `[`, `+`, `]`: 6 x 2^20 - 5, over the limit of 100 / 30 =
    /// 3 modules.
    #[test]
    fn a_count_past_u64_is_said_as_a_bound() {
        let src = "angle 20\naxiom A(1)\nrule A(x) -> F(x)[+A(x)]A(x)\n";
        let sys = crate::syntax::lsys::parse(src, &Limits::DEFAULT).unwrap();
        let p = sys.parametric.as_deref().unwrap();
        let limits = Limits {
            max_symbols: 100,
            ..Limits::DEFAULT
        };
        let said = |depth: u32| {
            let memo = ParamMemo::new(&sys, p, depth).unwrap().unwrap();
            let mut rec = Recorder::default();
            let e = memo
                .draw(&sys, p, 0.0, &limits, &mut rec, &mut NoProgress)
                .unwrap_err();
            e.iter().next().unwrap().kind.to_string()
        };
        let deep = said(1100);
        assert!(deep.contains(": more than 2^64 exceeds"), "{deep}");
        assert!(!deep.contains("18446744073709551615"), "{deep}");
        let shallow = said(20);
        let want = format!(": {} exceeds the limit of 3", 6 * (1u64 << 20) - 5);
        assert!(shallow.contains(&want), "{shallow}");
    }
}
