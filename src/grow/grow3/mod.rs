//! Growth in space: the 3D turtle ([`crate::turtle::turtle3`]) with stem
//! orders and `D=` divergence, and the region of a 3D layout's volumes
//! ([`region`]), for the one grower (`grower.rs`, over the `Space` of
//! `plane.rs`).
//!
//! `stl-language.md` section 11: every rule application (from the seed, a
//! slot, a count or a successor; a term written in the seed too) first
//! rolls its frame by `D` about H, as `\` does, relative to the frame it
//! grows from; the roll is part of the application, so drawing after it
//! goes on in the rolled frame. With `D` 0 (or none) nothing rolls and a
//! planar tree keeps the 2D turtle's exact frame, so it grows the 2D
//! tree's decisions.

pub mod region;

use super::occupancy::Seg3;
use super::plane::{Class, Space};
use crate::model::{Description, StemParams};
use crate::turtle::turtle3::{Frame, Op3, Point3, Segment3, State3, Turtle3, divergence};
use region::Region3;

/// The 3D turtle with stem orders, and the region of the volumes.
pub(crate) struct Volume<'a> {
    turtle: Turtle3<fn(Segment3)>,
    /// The stem order.
    order: u32,
    /// The orders saved at each `[`, beside the turtle's own stack.
    orders: Vec<u32>,
    params: &'a StemParams,
    /// `cos` and `sin` of the divergence, unless it is 0.
    divergence: Option<(f64, f64)>,
    region: Option<Region3>,
    roots: Vec<Point3>,
}

impl<'a> Volume<'a> {
    /// The space of `od`, with its region and its roots in root order.
    pub(crate) fn new(od: &'a Description, region: Option<Region3>, roots: Vec<Point3>) -> Self {
        let divergence = divergence(od.params.divergence);
        Volume {
            turtle: Turtle3::new(90.0, od.params.angle(), 0.0, |_| {}),
            order: 0,
            orders: Vec::new(),
            params: &od.params,
            divergence,
            region,
            roots,
        }
    }
}

impl Space<3> for Volume<'_> {
    type State = (State3, u32);
    type Op = Op3;

    fn op(c: char) -> Option<Op3> {
        match c {
            'L' => Some(Op3::Turn(1)),
            'R' => Some(Op3::Turn(-1)),
            c => Op3::of_lsys(c),
        }
    }

    fn class(op: Op3) -> Class {
        match op {
            Op3::Draw => Class::Draws,
            Op3::Move => Class::Moves,
            Op3::Push => Class::Push,
            Op3::Pop => Class::Pop,
            Op3::Turn(_) | Op3::Pitch(_) | Op3::Roll(_) | Op3::Flip => Class::Turns,
        }
    }

    fn push() -> Op3 {
        Op3::Push
    }

    fn pop() -> Op3 {
        Op3::Pop
    }

    fn order(state: &(State3, u32)) -> u32 {
        state.1
    }

    #[inline]
    fn state(&self) -> (State3, u32) {
        (self.turtle.state, self.order)
    }

    #[inline]
    fn set_state(&mut self, state: (State3, u32)) {
        (self.turtle.state, self.order) = state;
    }

    fn start(&mut self, t: usize) {
        self.turtle.state = State3 {
            pos: self.roots[t],
            frame: Frame::Planar { k: 0, flip: false },
        };
        self.order = 0;
    }

    #[inline]
    fn stack_depth(&self) -> usize {
        self.orders.len()
    }

    #[inline]
    fn apply(&mut self, op: Op3) -> Option<Seg3> {
        match op {
            Op3::Draw => {
                self.turtle.set_step(self.params.length.at(self.order));
                let from = self.turtle.state.pos;
                self.turtle.apply(op);
                let to = self.turtle.state.pos;
                return Some(Seg3::capsule(
                    from.to_array(),
                    to.to_array(),
                    self.params.width.at(self.order) / 2.0,
                ));
            }
            Op3::Move => self.turtle.set_step(self.params.length.at(self.order)),
            Op3::Push => self.orders.push(self.order),
            Op3::Pop => {
                // An extra `]` is ignored, by the turtle too.
                if let Some(o) = self.orders.pop() {
                    self.order = o;
                }
            }
            _ => {}
        }
        self.turtle.apply(op);
        None
    }

    fn enter(&mut self) {
        self.order += 1;
        if let Some((c, s)) = self.divergence {
            self.turtle.roll_by(c, s);
        }
    }

    fn leave(&mut self) {
        self.order = self.order.saturating_sub(1);
    }

    #[inline]
    fn inside(&self, s: &Seg3, from_inside: bool) -> bool {
        self.region
            .as_ref()
            .is_none_or(|r| r.capsule_inside(s, from_inside))
    }

    fn bounded(&self) -> bool {
        self.region.is_some()
    }

    fn covers_root(&self, t: usize) -> bool {
        self.region
            .as_ref()
            .is_none_or(|r| r.covers_point(self.roots[t].to_array()))
    }

    #[inline]
    fn position(state: &(State3, u32)) -> [f64; 3] {
        state.0.pos.to_array()
    }

    fn attraction(&self, n: Option<u64>, unit: f64, seed: u64) -> Vec<[f64; 3]> {
        let Some(r) = &self.region else {
            return Vec::new();
        };
        let (lo, hi) = r.bounds();
        super::colonize::sample::volume(lo, hi, |p| r.covers_point(p), n, unit, seed)
    }
}
