//! Memoized reach of a deterministic 3D L-system (`dimensions 3`): per
//! `(symbol, remaining depth)` what its expansion does relative to the
//! frame it starts in, composed exactly instead of traversed.
//!
//! A 3D turtle's drawing of `W(s, r)` started at position `p` with frame
//! `F` (the columns H, L, U) is its drawing from the origin with the
//! identity frame, turned by `F` and moved by `p`: every operation is
//! linear in the frame (section 11's formulas combine H, L, U with the
//! same `cos a`, `sin a` whatever they are), and brackets restore what
//! they saved. So one [`Reach`] per `(s, r)`, with no heading key at all,
//! gives everything rotation can carry: the local end vector `end` and
//! end frame `rot` (the end is `p + F end`, the frame `F rot`), and what
//! rotation cannot change: the radius of a ball about the start holding
//! every drawn point (a bound, composed by the triangle inequality), the
//! drawn length, the counts. A parent's reach is its successor's reaches
//! (at `r - 1`) composed in order, `O(alphabet x depth x successor)` work
//! whatever the word's length.
//!
//! Exactness: at multiples of 90 degrees (and a start heading that is one)
//! every frame is a signed permutation of the axes and every coordinate an
//! integer number of steps, so ends, frames and the box are exact; the box
//! of a child turned by such a frame is the turned box, exactly, so the
//! memo also keeps each expansion's local box ([`Reach::bbox`], only then).
//! At other angles the composed end and frame differ from a traversal's
//! by rounding only (the same `libm` products in another order).
//!
//! The memo applies when every successor is bracket-balanced and `[` and
//! `]` have no rule (as the 2D memo, geometry.rs), to deterministic
//! systems only: the occurrences of a symbol in a stochastic one differ.

use super::Alphabet;
use super::geometry::Refusal;
use crate::model::lsys::LSystem;
use crate::turtle::turtle3::{Op3, cos_sin};

/// A vector (or point) in 3D.
pub(crate) type V = [f64; 3];

/// Most `(symbol, depth)` entries one memo may hold (about 250 bytes each:
/// at most about 64 MB).
pub const REACH_ENTRIES: usize = 1 << 18;

/// `a + b * k`.
#[inline]
fn axpy(a: V, b: V, k: f64) -> V {
    [a[0] + b[0] * k, a[1] + b[1] * k, a[2] + b[2] * k]
}

/// `a ca + b cb`: the combination of section 11's rotation formulas.
#[inline]
fn comb(a: V, ca: f64, b: V, cb: f64) -> V {
    [
        a[0] * ca + b[0] * cb,
        a[1] * ca + b[1] * cb,
        a[2] * ca + b[2] * cb,
    ]
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(v: V) -> f64 {
    libm::sqrt(dot(v, v))
}

/// A frame: the columns H, L, U.
pub(crate) type M = [V; 3];

/// The identity frame.
pub(crate) const IDENTITY: M = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// `f v`: the local vector `v` (along H, L, U) in the frame's coordinates.
#[inline]
pub(crate) fn apply(f: &M, v: V) -> V {
    let a = comb(f[0], v[0], f[1], v[1]);
    axpy(a, f[2], v[2])
}

/// `f g`: the local frame `g` turned by `f`.
#[inline]
pub(crate) fn compose(f: &M, g: &M) -> M {
    [apply(f, g[0]), apply(f, g[1]), apply(f, g[2])]
}

/// What `W(s, r)` does relative to its start (position 0, the identity
/// frame), in canvas units of the memo's step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Reach {
    /// Where it ends.
    pub end: V,
    /// The frame it ends in.
    pub rot: M,
    /// The net turn when it only turns in the plane (`+ - |` outside
    /// brackets, at every level): turns and flip, as the planar turtle
    /// keeps them.
    pub planar: Option<(i64, bool)>,
    /// Every drawn point is within this distance of the start (a bound;
    /// 0 when nothing is drawn).
    pub radius: f64,
    /// Total drawn length.
    pub length: f64,
    /// The sum over drawn stems of length times midpoint (the centroid of
    /// the drawing times `length`).
    pub moment: V,
    /// The sum over drawn stems of length times the squared distance of
    /// the midpoint from the start (rotation invariant: with `moment` and
    /// `length` it gives the drawing's spread about its centroid).
    pub second: f64,
    /// Saturating number of `F`.
    pub stems: u64,
    /// Saturating number of symbols.
    pub syms: u64,
    /// Whether it moves without drawing (an `f`) or returns (a `]`)
    /// somewhere: not one connected run.
    pub jumps: bool,
    /// How many times it moves without drawing or returns (each `f` and
    /// `]`): the runs its strokes come in, less one.
    pub breaks: f64,
    /// The box of every drawn point `[minx, miny, minz, maxx, maxy, maxz]`
    /// in local coordinates, kept only where frames are signed
    /// permutations (then exact); `min > max` when nothing is drawn.
    pub bbox: Option<[f64; 6]>,
}

const EMPTY_BOX: [f64; 6] = [
    f64::INFINITY,
    f64::INFINITY,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
    f64::NEG_INFINITY,
];

fn add_point(b: &mut [f64; 6], p: V) {
    for k in 0..3 {
        b[k] = b[k].min(p[k]);
        b[k + 3] = b[k + 3].max(p[k]);
    }
}

impl Reach {
    fn empty(boxed: bool) -> Reach {
        Reach {
            end: [0.0; 3],
            rot: IDENTITY,
            planar: Some((0, false)),
            radius: 0.0,
            length: 0.0,
            moment: [0.0; 3],
            second: 0.0,
            stems: 0,
            syms: 0,
            jumps: false,
            breaks: 0.0,
            bbox: boxed.then_some(EMPTY_BOX),
        }
    }

    /// Whether anything is drawn.
    pub fn draws(&self) -> bool {
        self.stems > 0
    }

    /// Whether it is one straight run: its stems end to end along one
    /// line from the start to the end, so its chord draws it (the drawn
    /// length equals the chord within rounding).
    pub fn straight(&self) -> bool {
        self.draws() && !self.jumps && self.length <= norm(self.end) * (1.0 + 1e-9)
    }

    /// The centroid of the drawing (stems weighted by length, at their
    /// midpoints) and its radius of gyration about it.
    pub fn centroid(&self) -> (V, f64) {
        if self.length <= 0.0 {
            return ([0.0; 3], 0.0);
        }
        let c = self.moment.map(|m| m / self.length);
        let g2 = self.second / self.length - dot(c, c);
        (c, libm::sqrt(g2.max(0.0)))
    }
}

/// The composing turtle: position, frame, planar turn, and what was
/// drawn so far.
#[derive(Clone, Copy)]
struct Pen {
    pos: V,
    frame: M,
    planar: Option<(i64, bool)>,
}

/// The memo; see the module documentation.
pub(crate) struct ReachMemo {
    pub(super) alpha: Alphabet,
    pub(super) ops: Vec<Option<Op3>>,
    pub(super) depth: u32,
    /// `reach[r * n + s]`.
    reach: Vec<Reach>,
    cos: f64,
    sin: f64,
    len: f64,
    /// Whether frames stay signed permutations (angle and start heading
    /// multiples of 90 degrees): boxes kept, everything exact.
    pub(crate) ortho: bool,
    /// The start frame of the whole drawing.
    pub(crate) start: M,
}

/// Whether `v` is 0 or +-1 exactly.
fn unit(v: f64) -> bool {
    v == 0.0 || v == 1.0 || v == -1.0
}

/// The start frame of a 3D turtle with first heading `heading` degrees.
pub(crate) fn start_frame(heading: f64, angle: f64) -> M {
    let (hx, hy) = crate::turtle::Headings::starting(heading, angle).dir(0, false);
    [[hx, hy, 0.0], [hy, -hx, 0.0], [0.0, 0.0, -1.0]]
}

impl ReachMemo {
    /// The memo of the deterministic 3D system `sys` to `depth`, step
    /// `len`.
    pub(crate) fn new(sys: &LSystem, depth: u32, len: f64) -> Result<Self, Refusal> {
        if sys.parametric.is_some() {
            return Err(Refusal::Parametric);
        }
        if sys.is_stochastic() {
            return Err(Refusal::Stochastic);
        }
        let alpha = Alphabet::new(sys);
        let n = alpha.chars.len();
        let ops: Vec<Option<Op3>> = alpha.chars.iter().map(|&c| Op3::of_lsys(c)).collect();
        for (s, succ) in alpha.succ.iter().enumerate() {
            if let Some(succ) = succ
                && (matches!(ops[s], Some(Op3::Push | Op3::Pop)) || !balanced(succ, &ops))
            {
                return Err(Refusal::Brackets);
            }
        }
        let levels = depth as usize + 1;
        if n.saturating_mul(levels) > REACH_ENTRIES {
            return Err(Refusal::Budget);
        }
        let (cos, sin) = cos_sin(sys.angle);
        let start = start_frame(sys.heading, sys.angle);
        let ortho = unit(cos) && unit(sin) && start.iter().flatten().all(|&v| unit(v));
        let mut memo = ReachMemo {
            alpha,
            ops,
            depth,
            reach: Vec::with_capacity(n * levels),
            cos,
            sin,
            len,
            ortho,
            start,
        };
        for s in 0..n {
            let r = memo.terminal(s);
            memo.reach.push(r);
        }
        for r in 1..levels {
            for s in 0..n {
                let reach = match &memo.alpha.succ[s] {
                    Some(succ) => memo.compose(succ, r as u32 - 1, &IDENTITY).0,
                    None => memo.reach[s],
                };
                memo.reach.push(reach);
            }
        }
        Ok(memo)
    }

    fn terminal(&self, s: usize) -> Reach {
        let mut acc = Reach::empty(self.ortho);
        let mut pen = Pen {
            pos: [0.0; 3],
            frame: IDENTITY,
            planar: Some((0, false)),
        };
        self.step(self.ops[s], &mut pen, &mut acc);
        acc.syms = 1;
        acc.end = pen.pos;
        acc.rot = pen.frame;
        acc.planar = pen.planar;
        acc
    }

    /// The reach of `(s, r)`.
    #[inline]
    pub(crate) fn get(&self, s: u32, r: u32) -> &Reach {
        &self.reach[r as usize * self.alpha.chars.len() + s as usize]
    }

    /// Whether `s` at remaining depth `r` is expanded (else terminal).
    #[inline]
    pub(crate) fn is_piece(&self, s: u32, r: u32) -> bool {
        r >= 1 && self.alpha.succ[s as usize].is_some()
    }

    /// Applies terminal op `op` to the pen.
    fn step(&self, op: Option<Op3>, pen: &mut Pen, acc: &mut Reach) {
        let (c, s) = (self.cos, self.sin);
        let [h, l, u] = pen.frame;
        match op {
            Some(Op3::Draw) => {
                let to = axpy(pen.pos, h, self.len);
                acc.radius = acc.radius.max(norm(pen.pos)).max(norm(to));
                acc.length += self.len;
                let mid = comb(pen.pos, 0.5, to, 0.5);
                acc.moment = axpy(acc.moment, mid, self.len);
                acc.second += self.len * dot(mid, mid);
                acc.stems = acc.stems.saturating_add(1);
                if let Some(b) = &mut acc.bbox {
                    add_point(b, pen.pos);
                    add_point(b, to);
                }
                pen.pos = to;
            }
            Some(Op3::Move) => {
                pen.pos = axpy(pen.pos, h, self.len);
                acc.jumps = true;
                acc.breaks += 1.0;
            }
            Some(Op3::Turn(n)) => {
                let s = s * f64::from(n);
                pen.frame = [comb(h, c, l, s), comb(l, c, h, -s), u];
                pen.planar = pen.planar.map(|(k, f)| (k + i64::from(n), f));
            }
            Some(Op3::Flip) => {
                pen.frame = [h.map(|v| -v), l.map(|v| -v), u];
                pen.planar = pen.planar.map(|(k, f)| (k, !f));
            }
            Some(Op3::Pitch(n)) => {
                let s = s * f64::from(n);
                pen.frame = [comb(h, c, u, -s), l, comb(u, c, h, s)];
                pen.planar = None;
            }
            Some(Op3::Roll(n)) => {
                let s = s * f64::from(n);
                pen.frame = [h, comb(l, c, u, -s), comb(u, c, l, s)];
                pen.planar = None;
            }
            Some(Op3::Push | Op3::Pop) | None => {}
        }
    }

    /// Composes `word` (symbols at remaining depth `r`) from the origin in
    /// frame `frame`: its reach in the coordinates `frame` is given in.
    pub(crate) fn compose(&self, word: &[u32], r: u32, frame: &M) -> (Reach, V) {
        let mut pen = Pen {
            pos: [0.0; 3],
            frame: *frame,
            planar: Some((0, false)),
        };
        let mut acc = Reach::empty(self.ortho);
        let mut stack: Vec<Pen> = Vec::new();
        for &c in word {
            match self.ops[c as usize] {
                Some(Op3::Push) => {
                    stack.push(pen);
                    acc.syms = acc.syms.saturating_add(1);
                }
                Some(Op3::Pop) => {
                    if let Some(saved) = stack.pop() {
                        pen = saved;
                    }
                    acc.jumps = true;
                    acc.breaks += 1.0;
                    acc.syms = acc.syms.saturating_add(1);
                }
                _ if self.is_piece(c, r) => {
                    let child = self.get(c, r);
                    self.join(child, &mut pen, &mut acc);
                }
                op => {
                    self.step(op, &mut pen, &mut acc);
                    acc.syms = acc.syms.saturating_add(1);
                }
            }
        }
        acc.end = pen.pos;
        acc.rot = pen.frame;
        acc.planar = pen.planar;
        (acc, pen.pos)
    }

    /// Appends `child` (started at the pen) to `acc` and moves the pen to
    /// its end.
    fn join(&self, child: &Reach, pen: &mut Pen, acc: &mut Reach) {
        let f = &pen.frame;
        if child.draws() {
            acc.radius = acc.radius.max(norm(pen.pos) + child.radius);
            acc.length += child.length;
            let m = apply(f, child.moment);
            // |p + F x|^2 = |p|^2 + 2 p . F x + |x|^2, summed with weights.
            acc.second +=
                child.second + 2.0 * dot(pen.pos, m) + child.length * dot(pen.pos, pen.pos);
            acc.moment = axpy(axpy(acc.moment, m, 1.0), pen.pos, child.length);
            if let (Some(b), Some(cb)) = (&mut acc.bbox, &child.bbox) {
                for i in 0..8 {
                    let corner = [
                        cb[3 * (i & 1)],
                        cb[1 + 3 * ((i >> 1) & 1)],
                        cb[2 + 3 * ((i >> 2) & 1)],
                    ];
                    add_point(b, axpy(apply(f, corner), pen.pos, 1.0));
                }
            }
        }
        acc.stems = acc.stems.saturating_add(child.stems);
        acc.syms = acc.syms.saturating_add(child.syms);
        acc.jumps |= child.jumps;
        acc.breaks += child.breaks;
        pen.pos = axpy(pen.pos, apply(f, child.end), 1.0);
        pen.frame = compose(f, &child.rot);
        pen.planar = match (pen.planar, child.planar) {
            (Some((k, a)), Some((dk, b))) => k.checked_add(dk).map(|k| (k, a != b)),
            _ => None,
        };
    }

    /// The reach of the whole word from the origin in the drawing's start
    /// frame, in canvas coordinates (x right, y down, z away).
    pub(crate) fn whole(&self) -> Reach {
        self.compose(&self.alpha.axiom, self.depth, &self.start).0
    }

    /// The memo's step.
    pub(crate) fn len(&self) -> f64 {
        self.len
    }
}

/// Whether `word` is bracket-balanced.
fn balanced(word: &[u32], ops: &[Option<Op3>]) -> bool {
    let mut open = 0usize;
    for &c in word {
        match ops[c as usize] {
            Some(Op3::Push) => open += 1,
            Some(Op3::Pop) => match open.checked_sub(1) {
                Some(o) => open = o,
                None => return false,
            },
            _ => {}
        }
    }
    open == 0
}

#[cfg(test)]
#[path = "reach_tests.rs"]
mod tests;
