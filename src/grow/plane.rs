//! What the grower draws with: a turtle, a region and the stems as
//! capsules, in the plane ([`Plane`]) or in space
//! ([`super::grow3::Volume`]). The grower ([`super::grower`]) is written
//! once over [`Space`]; the two implementations differ only in the turtle
//! (2D headings, or the 3D frame with `D=` divergence), the region and the
//! distance of two stems.

use super::occupancy::{Cap, Dim, Seg};
use super::region::Region;
use crate::model::{Description, StemParams};
use crate::turtle::{Interp, Op, Point, Recorder, State};

/// What a drawing component does, as the grower needs to know it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Class {
    /// Draws a stem.
    Draws,
    /// Moves without drawing (`f`): the position is no longer known to be
    /// inside the region.
    Moves,
    /// Turns the turtle.
    Turns,
    /// `[`.
    Push,
    /// `]`.
    Pop,
}

/// A turtle and a region in `N` dimensions, for the grower.
pub(super) trait Space<const N: usize>
where
    Cap<N>: Dim,
{
    /// The turtle's state (position, orientation, stem order).
    type State: Copy;
    /// A turtle operation.
    type Op: Copy;

    /// The operation of a drawing component of an OD or BED, if any.
    fn op(c: char) -> Option<Self::Op>;
    /// What `op` does.
    fn class(op: Self::Op) -> Class;
    /// `[` and `]`.
    fn push() -> Self::Op;
    /// `]`.
    fn pop() -> Self::Op;
    /// The state's stem order.
    fn order(state: &Self::State) -> u32;

    /// The turtle's state.
    fn state(&self) -> Self::State;
    /// Puts the turtle in `state`.
    fn set_state(&mut self, state: Self::State);
    /// Puts the turtle at root `t` (in root order), heading up, order 0.
    fn start(&mut self, t: usize);
    /// Depth of the turtle's stack.
    fn stack_depth(&self) -> usize;
    /// Applies `op`; the stem it drew, as drawn, if any.
    fn apply(&mut self, op: Self::Op) -> Option<Cap<N>>;
    /// A rule application starts: stems are one order higher (and, in
    /// space, the frame rolls by the divergence).
    fn enter(&mut self);
    /// The rule application ends.
    fn leave(&mut self);
    /// Whether the stem `s` lies inside the region (always, with no
    /// layout); `from_inside`: its start is known to lie inside.
    fn inside(&self, s: &Cap<N>, from_inside: bool) -> bool;
    /// Whether there is a region at all.
    fn bounded(&self) -> bool;
    /// Whether root `t` lies in the region (always, with no layout).
    fn covers_root(&self, t: usize) -> bool;
    /// Where the turtle is in `state`.
    fn position(state: &Self::State) -> [f64; N];
    /// The attraction points of space-first growth: `n` (or one per
    /// `unit` of the region's area or volume) uniform over the region, from
    /// `seed`; none without a region ([`super::colonize::sample`]).
    fn attraction(&self, n: Option<u64>, unit: f64, seed: u64) -> Vec<[f64; N]>;
}

/// The plane: the 2D turtle and the 2D region.
pub(super) struct Plane<'a> {
    interp: Interp<Recorder>,
    params: &'a StemParams,
    region: Option<Region>,
    roots: Vec<Point>,
}

impl<'a> Plane<'a> {
    /// The plane of `od`, with its region and its roots in root order.
    pub(super) fn new(od: &'a Description, region: Option<Region>, roots: Vec<Point>) -> Self {
        Plane {
            interp: Interp::new(
                Recorder::default(),
                Point::new(od.root.0, od.root.1),
                od.params.angle(),
                od.params.length,
            ),
            params: &od.params,
            region,
            roots,
        }
    }
}

impl Space<2> for Plane<'_> {
    type State = State;
    type Op = Op;

    fn op(c: char) -> Option<Op> {
        Op::of_stl(c)
    }

    fn class(op: Op) -> Class {
        match op {
            Op::Draw => Class::Draws,
            Op::Move => Class::Moves,
            Op::Push => Class::Push,
            Op::Pop => Class::Pop,
            Op::Turn(_) | Op::Flip | Op::Enter | Op::Leave => Class::Turns,
        }
    }

    fn push() -> Op {
        Op::Push
    }

    fn pop() -> Op {
        Op::Pop
    }

    fn order(state: &State) -> u32 {
        state.order
    }

    #[inline]
    fn state(&self) -> State {
        self.interp.state
    }

    #[inline]
    fn set_state(&mut self, state: State) {
        self.interp.state = state;
    }

    fn start(&mut self, t: usize) {
        self.interp.state = State::start(self.roots[t]);
    }

    #[inline]
    fn stack_depth(&self) -> usize {
        self.interp.stack_depth()
    }

    #[inline]
    fn apply(&mut self, op: Op) -> Option<Seg> {
        self.interp.apply(op);
        let s = self.interp.turtle.segments.pop()?;
        Some(Seg::capsule(
            [s.from.x, s.from.y],
            [s.to.x, s.to.y],
            self.params.width.at(s.order) / 2.0,
        ))
    }

    fn enter(&mut self) {
        self.interp.apply(Op::Enter);
    }

    fn leave(&mut self) {
        self.interp.apply(Op::Leave);
    }

    #[inline]
    fn inside(&self, s: &Seg, from_inside: bool) -> bool {
        match &self.region {
            Some(r) => r.capsule_inside(
                Point::new(s.a[0], s.a[1]),
                Point::new(s.b[0], s.b[1]),
                s.r,
                from_inside,
            ),
            None => true,
        }
    }

    fn bounded(&self) -> bool {
        self.region.is_some()
    }

    fn covers_root(&self, t: usize) -> bool {
        self.region
            .as_ref()
            .is_none_or(|r| r.covers_point(self.roots[t]))
    }

    #[inline]
    fn position(state: &State) -> [f64; 2] {
        [state.pos.x, state.pos.y]
    }

    fn attraction(&self, n: Option<u64>, unit: f64, seed: u64) -> Vec<[f64; 2]> {
        self.region
            .as_ref()
            .map(|r| super::colonize::sample::plane(r, n, unit, seed))
            .unwrap_or_default()
    }
}
