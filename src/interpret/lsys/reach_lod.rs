//! The level of detail of 3D views on the reach memo (reach.rs): which
//! parts are cut at a detail, what a walk at that detail visits and hands
//! out (counted from the memo before walking), and the walk itself.
//!
//! A part `W(s, r)` lies in a ball of its [`Reach::radius`] about its
//! start whatever the frame, so under any orthographic view it covers at
//! most `2 radius` on the screen: the cut depends on `(s, r)` alone, not
//! on where or how the part is turned. That makes the count exact: the
//! plan of a detail is computed level by level over the alphabet, and the
//! walk visits exactly that. A part within the detail (half of it for one
//! connected run, as in 2D) is handed out as one stand-in and the turtle
//! jumps to its end ([`Turtle3::jump`]: the local end and frame turned by
//! the current frame; exact at right angles, within rounding elsewhere);
//! a part that draws nothing is jumped over without a stand-in, and one
//! straight run (its stems end to end along one line: an internode
//! `F -> FF`) is its chord whatever its size. Every
//! other symbol goes through [`Turtle3::apply`], so at detail 0 the walk
//! is the exact drawing, stem for stem.

use std::cell::RefCell;

use super::lod;
use super::reach::{Reach, ReachMemo, V, apply};
use crate::color::Rgb;
use crate::progress::Progress;
use crate::turtle::turtle3::{Op3, Point3, Segment3, Turtle3};

/// What a walk at a level of detail hands out, in drawing order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mark3<'a> {
    /// A stem of the exact drawing, or the chord of a cut connected run
    /// (which joins the stems before and after it).
    Stem(Segment3),
    /// A stand-in for a part that breaks off in branches, or a connected
    /// run that folds on itself (its stems at least twice its chord): a
    /// capsule about `seg` reaching `spread` to either side of it.
    StandIn {
        /// From the part's start through twice its centroid (clamped to
        /// its reach): the segment a straight part would be.
        seg: Segment3,
        /// Length stood for over `seg`'s length (infinite for a dot).
        density: f64,
        /// How far the part spreads about `seg`: its radius of gyration
        /// left after the segment's own.
        spread: f64,
        /// The length of its strokes.
        length: f64,
        /// The runs they come in (one more than its `]` and `f`).
        runs: f64,
        /// The colour its ink mixes to, where the drawing paints (else the
        /// colour in force).
        color: Option<Rgb>,
        /// The stem order of its strokes' width (0: the picture's).
        order: u32,
    },
    /// Later stems and polygons take colour index `i` (a system that
    /// paints, section 13).
    Paint(usize),
    /// A polygon `{ ... }` closed, filled with the colour in force.
    Polygon(&'a [Point3]),
}

/// A memo a 3D view's level of detail walks: the reach memo of a classic
/// system (reach.rs), the view memo of a parametric one or one that
/// paints (`param/memo3.rs`).
pub(crate) trait ViewLod {
    /// Every drawn point of the whole drawing is within this distance of
    /// its start.
    fn radius(&self) -> f64;
    /// What a walk at `detail` visits and hands out.
    fn plan(&self, detail: f64) -> Plan3;
    /// The whole word's symbols and drawn stems (saturating).
    fn size(&self) -> (u64, u64);
    /// Walks the word at `detail` (canvas units) from the origin, handing
    /// every mark to `sink` in drawing order; `visits` (the plan's) is
    /// reported to `progress`. `pen`: the width of a stroke of order 0,
    /// canvas units, and the output pixels per canvas unit (the ink a
    /// stand-in's polygons and caps stand for is given as strokes'
    /// length); `toward`: the view's direction (how much of its strokes
    /// and polygons a stand-in shows).
    #[allow(clippy::too_many_arguments)]
    fn walk(
        &self,
        sys: &crate::model::lsys::LSystem,
        detail: f64,
        visits: u64,
        pen: (f64, f64),
        toward: V,
        sink: &mut dyn FnMut(Mark3<'_>),
        progress: &mut dyn Progress,
    );
}

impl ViewLod for ReachMemo {
    fn radius(&self) -> f64 {
        self.whole().radius
    }

    fn plan(&self, detail: f64) -> Plan3 {
        ReachMemo::plan(self, detail)
    }

    fn size(&self) -> (u64, u64) {
        let w = self.whole();
        (w.syms, w.stems)
    }

    fn walk(
        &self,
        sys: &crate::model::lsys::LSystem,
        detail: f64,
        visits: u64,
        _: (f64, f64),
        _: V,
        sink: &mut dyn FnMut(Mark3<'_>),
        progress: &mut dyn Progress,
    ) {
        self.draw_lod(sys.heading, sys.angle, detail, visits, sink, progress);
    }
}

/// What a walk at one detail costs, counted before walking.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Plan3 {
    /// Symbols and stand-ins visited (saturating).
    pub visits: u64,
    /// Stems and stand-ins handed out (saturating).
    pub marks: u64,
}

/// A cut connected run whose stems are at least this many times its chord
/// long folds on itself (a space-filling curve's piece): a capsule, not
/// its chord (the renderer's `BLOT_DENSITY`).
const FOLD_DENSITY: f64 = 2.0;

fn norm(v: V) -> f64 {
    libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
}

/// Whether a part is cut at `detail` (never at 0).
fn cut(r: &Reach, detail: f64) -> bool {
    if detail <= 0.0 || detail.is_nan() {
        return false;
    }
    if !r.draws() || r.straight() {
        return true;
    }
    let d = 2.0 * r.radius;
    if r.jumps {
        d < detail
    } else {
        d < detail / 2.0
    }
}

impl ReachMemo {
    /// What a walk at `detail` visits and hands out, level by level.
    pub(crate) fn plan(&self, detail: f64) -> Plan3 {
        let n = self.alpha.chars.len();
        let terminal: Vec<(u64, u64)> = (0..n)
            .map(|s| (1, u64::from(self.ops[s] == Some(Op3::Draw))))
            .collect();
        let mut prev = terminal.clone();
        for r in 1..=self.depth {
            let mut row = terminal.clone();
            for (s, slot) in row.iter_mut().enumerate() {
                let Some(succ) = &self.alpha.succ[s] else {
                    continue;
                };
                let me = self.get(s as u32, r);
                *slot = if cut(me, detail) {
                    (1, u64::from(me.draws()))
                } else {
                    succ.iter().fold((1u64, 0u64), |(v, m), &c| {
                        let (cv, cm) = prev[c as usize];
                        (v.saturating_add(cv), m.saturating_add(cm))
                    })
                };
            }
            prev = row;
        }
        let (visits, marks) = self.alpha.axiom.iter().fold((0u64, 0u64), |(v, m), &c| {
            let (cv, cm) = prev[c as usize];
            (v.saturating_add(cv), m.saturating_add(cm))
        });
        Plan3 { visits, marks }
    }

    /// Walks the word at `detail` (canvas units) from the origin, heading
    /// `heading` degrees, handing every mark to `sink` in drawing order;
    /// returns where the turtle ends. `visits` (the plan's) is reported to
    /// `progress` as the work.
    pub(crate) fn draw_lod(
        &self,
        heading: f64,
        angle: f64,
        detail: f64,
        visits: u64,
        sink: &mut dyn FnMut(Mark3<'_>),
        progress: &mut dyn Progress,
    ) -> Point3 {
        let sink = RefCell::new(sink);
        let turtle = Turtle3::new(heading, angle, self.len(), |s| {
            (sink.borrow_mut())(Mark3::Stem(s));
        });
        progress.start("symbols", visits);
        let mut w = Walk3 {
            memo: self,
            detail,
            turtle,
            sink: &sink,
        };
        lod::walk(&mut w, &self.alpha.axiom, self.depth, (), progress);
        progress.finish();
        w.turtle.state.pos
    }
}

/// A walk of the 3D memo at a detail: its turtle, and where stand-ins go.
struct Walk3<'m, 's, 'k, S: FnMut(Segment3)> {
    memo: &'m ReachMemo,
    detail: f64,
    turtle: Turtle3<S>,
    sink: &'s RefCell<&'k mut dyn FnMut(Mark3<'_>)>,
}

impl<'m, S: FnMut(Segment3)> lod::Memo<'m> for Walk3<'m, '_, '_, S> {
    type Ctx = ();

    #[inline]
    fn child(_: (), _: usize) {}

    #[inline]
    fn is_piece(&self, c: u32, r: u32) -> bool {
        self.memo.is_piece(c, r)
    }

    fn piece(&mut self, s: u32, r: u32, _: ()) -> Option<&'m [u32]> {
        let memo = self.memo;
        let p = memo.get(s, r);
        if !cut(p, self.detail) {
            return Some(memo.alpha.succ[s as usize].as_deref().unwrap_or(&[]));
        }
        if p.draws() {
            let mark = stand_in(&mut self.turtle, p);
            (self.sink.borrow_mut())(mark);
        }
        self.turtle.jump(p.end, &p.rot, p.planar);
        None
    }

    #[inline]
    fn terminal(&mut self, s: u32) {
        if let Some(op) = self.memo.ops[s as usize] {
            self.turtle.apply(op);
        }
    }
}

/// The stand-in of part `p` drawn from the turtle's state.
fn stand_in<S: FnMut(Segment3)>(t: &mut Turtle3<S>, p: &Reach) -> Mark3<'static> {
    let (h, l, u) = t.hlu();
    let part = Part3 {
        end: p.end,
        radius: p.radius,
        length: p.length,
        jumps: p.jumps,
        breaks: p.breaks,
        centroid: p.centroid(),
    };
    stand_in_at(t.state.pos, &[h, l, u], &part)
}

/// What a stand-in is drawn from: a part's reach relative to its start.
pub(crate) struct Part3 {
    /// Where it ends.
    pub end: V,
    /// Every drawn point is within this distance of the start.
    pub radius: f64,
    /// The length of its strokes.
    pub length: f64,
    /// Whether it moves without drawing or returns somewhere.
    pub jumps: bool,
    /// How many times (each `f` and `]`).
    pub breaks: f64,
    /// Its strokes' centroid and radius of gyration about it.
    pub centroid: (V, f64),
}

/// The stand-in of `part` started at `from` in frame `frame` (H, L, U):
/// a connected run that does not fold is its chord, anything else a
/// capsule from the start through twice its centroid.
pub(crate) fn stand_in_at(from: Point3, frame: &[V; 3], p: &Part3) -> Mark3<'static> {
    let at = |v: V| {
        let d = apply(frame, v);
        Point3::new(from.x + d[0], from.y + d[1], from.z + d[2])
    };
    let chord = norm(p.end);
    if !p.jumps && p.length < FOLD_DENSITY * chord {
        return Mark3::Stem(Segment3 {
            from,
            to: at(p.end),
            order: 0,
        });
    }
    let (c, g) = p.centroid;
    let mut q = c.map(|v| 2.0 * v);
    let nq = norm(q);
    if nq > p.radius && nq > 0.0 {
        q = q.map(|v| v * (p.radius / nq));
    }
    let len = norm(q);
    // A uniform segment of length `len` about its middle: len^2 / 12.
    let spread = libm::sqrt((g * g - len * len / 12.0).max(0.0));
    Mark3::StandIn {
        seg: Segment3 {
            from,
            to: at(q),
            order: 0,
        },
        density: if len > 0.0 {
            p.length / len
        } else {
            f64::INFINITY
        },
        spread,
        length: p.length,
        runs: p.breaks + 1.0,
        color: None,
        order: 0,
    }
}
