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

use std::collections::HashMap;

use super::turtle::Turtle3P;
use super::{Deriver, PARAM_COST, Word};
use crate::diag::{Diagnostics, Help, Knob};
use crate::interpret::lsys::lod::{self, Memo};
use crate::limits::{Bound, Limits};
use crate::model::lsys::LSystem;
use crate::model::param::{Parametric, eval};
use crate::progress::Progress;
use crate::turtle::turtle3::cos_sin;
use crate::turtle::{Footprint, Point, Segment, StandIn, Turtle};

/// Most pieces one memo may hold (about 200 bytes each).
pub const PARAM_NODES: usize = 1 << 17;

/// Most successor entries all pieces together may hold.
const PARAM_SUCC: usize = 1 << 22;

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

/// The memo of one system at one depth.
pub struct ParamMemo {
    sym: Vec<char>,
    /// `off[i]..off[i + 1]`: node `i`'s parameters in `vals`.
    off: Vec<u32>,
    vals: Vec<f64>,
    /// A node's successor, as nodes one level down (`None`: a module no
    /// rule rewrites, or at depth 0).
    succ: Vec<Option<Vec<u32>>>,
    reach: Vec<Reach>,
    axiom: Vec<u32>,
    /// Per remaining depth, its nodes (a module no rule rewrites at 0).
    levels: Vec<Vec<u32>>,
    depth: u32,
}

/// A node's interning key: symbol, parameters' bits, remaining depth.
type NodeKey = (char, Vec<u64>, u32);

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
        let d = Deriver::new(sys, p);
        let mut m = ParamMemo {
            sym: Vec::new(),
            off: vec![0],
            vals: Vec::new(),
            succ: Vec::new(),
            reach: Vec::new(),
            axiom: Vec::new(),
            levels: Vec::new(),
            depth,
        };
        let mut index: HashMap<NodeKey, u32> = HashMap::new();
        // Per level, the nodes first met there, in the order met.
        let mut levels: Vec<Vec<u32>> = vec![Vec::new(); depth as usize + 1];
        let mut axiom = Vec::with_capacity(p.axiom.len());
        for md in &p.axiom {
            let vals: Vec<f64> = md.args.iter().map(|e| eval(e, &[])).collect();
            match m.intern(&d, &mut index, &mut levels, md.symbol, &vals, depth) {
                Some(id) => axiom.push(id),
                None => return Ok(None),
            }
        }
        m.axiom = axiom;
        let mut entries = 0usize;
        let (mut one, mut out, mut bind) = (Word::new(), Word::new(), Vec::new());
        for r in (1..=depth).rev() {
            let level = std::mem::take(&mut levels[r as usize]);
            for &id in &level {
                one.clear();
                one.push(
                    m.sym[id as usize],
                    m.params(id),
                    crate::choice::Key::root(0),
                );
                out.clear();
                d.rewrite(&one, &[], 0, depth - r + 1, &mut out, &mut bind)?;
                entries += out.len();
                if entries > PARAM_SUCC {
                    return Ok(None);
                }
                let mut kids = Vec::with_capacity(out.len());
                for j in 0..out.len() {
                    match m.intern(
                        &d,
                        &mut index,
                        &mut levels,
                        out.syms[j],
                        out.params(j),
                        r - 1,
                    ) {
                        Some(k) => kids.push(k),
                        None => return Ok(None),
                    }
                }
                m.succ[id as usize] = Some(kids);
            }
            levels[r as usize] = level;
        }
        m.levels = levels;
        m.compose_all(sys);
        Ok(Some(m))
    }

    fn params(&self, id: u32) -> &[f64] {
        &self.vals[self.off[id as usize] as usize..self.off[id as usize + 1] as usize]
    }

    /// The node of module `sym(vals)` at remaining depth `r` (depth 0 for
    /// a module no rule rewrites: it is the same at every depth), new ones
    /// queued on their level; `None` past [`PARAM_NODES`].
    fn intern(
        &mut self,
        d: &Deriver,
        index: &mut HashMap<NodeKey, u32>,
        levels: &mut [Vec<u32>],
        sym: char,
        vals: &[f64],
        r: u32,
    ) -> Option<u32> {
        let mut key: NodeKey = (sym, vals.iter().map(|v| v.to_bits()).collect(), r);
        if let Some(&id) = index.get(&key) {
            return Some(id);
        }
        if r > 0 && !d.applies(sym, vals) {
            key.2 = 0;
            if let Some(&id) = index.get(&key) {
                return Some(id);
            }
        }
        let r = key.2;
        if self.sym.len() >= PARAM_NODES {
            return None;
        }
        let id = self.sym.len() as u32;
        self.sym.push(sym);
        self.vals.extend_from_slice(vals);
        self.off.push(self.vals.len() as u32);
        self.succ.push(None);
        self.reach.push(Reach::NOTHING);
        index.insert(key, id);
        levels[r as usize].push(id);
        Some(id)
    }

    /// Every node's reach, level by level from depth 0 up.
    fn compose_all(&mut self, sys: &LSystem) {
        let (len, angle) = (sys.length, sys.angle);
        let levels = std::mem::take(&mut self.levels);
        for level in &levels {
            for &id in level {
                let reach = match &self.succ[id as usize] {
                    None => Reach::module(self.sym[id as usize], self.params(id), len, angle),
                    Some(kids) => self.compose(kids),
                };
                self.reach[id as usize] = reach;
            }
        }
        self.levels = levels;
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
            match self.sym[k as usize] {
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
        let mut cost = vec![1u64; self.sym.len()];
        // Level by level from depth 0 up: children before parents.
        for &id in self.levels.iter().flatten() {
            let id = id as usize;
            if let Some(kids) = &self.succ[id]
                && !Self::cut(&self.reach[id], detail)
            {
                cost[id] = kids
                    .iter()
                    .fold(1u64, |a, &k| a.saturating_add(cost[k as usize]));
            }
        }
        self.axiom
            .iter()
            .fold(0u64, |a, &k| a.saturating_add(cost[k as usize]))
    }

    /// Distinct pieces (module and depth) the word reaches.
    pub fn nodes(&self) -> usize {
        self.sym.len()
    }

    /// Modules of the whole word (saturating).
    pub fn modules(&self) -> u64 {
        self.axiom.iter().fold(0u64, |a, &k| {
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
        self.axiom
            .iter()
            .fold(0u64, |a, &k| a.saturating_add(self.reach[k as usize].stems))
    }

    /// A ball about the start holding the whole drawing: its radius.
    pub fn radius(&self) -> f64 {
        self.compose(&self.axiom).radius
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
            return Err(Bound::Symbols
                .exceeded_by(
                    format!(
                        "modules to visit at depth {} at this level of detail",
                        self.depth
                    ),
                    visits,
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
        lod::walk(&mut w, &self.axiom, self.depth, (), progress);
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
        self.m.succ[c as usize].is_some()
    }

    fn piece(&mut self, c: u32, _: u32, _: ()) -> Option<&'m [u32]> {
        let m = self.m;
        let p = &m.reach[c as usize];
        if !ParamMemo::cut(p, self.detail) {
            return m.succ[c as usize].as_deref();
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
        self.t.module(m.sym[c as usize], m.params(c), &mut |mark| {
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
