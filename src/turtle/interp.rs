//! The turtle state machine: drawing components as [`Op`]s, applied to a
//! [`State`], handing [`Segment`]s to a [`Turtle`] backend.
//!
//! The grower and the BED and L-system interpreters all draw through
//! [`Interp`]. The L-system renderer's fast path (`interpret::lsys`'s
//! compiled executor) is the one other place positions are computed; it uses
//! the same expression (`pos + dir(k) * len`, with `dir` from [`Headings`]),
//! so both give bit-identical segments.

use super::{Headings, Point, Segment, Turtle};
use crate::num::Linear;

/// One turtle operation: what a drawing component means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// `F`: draw one stem segment forward.
    Draw,
    /// `f`: move forward without drawing.
    Move,
    /// `+`/`L` (positive, left) or `-`/`R` (negative, right), `n` times.
    Turn(i32),
    /// `|`: turn around.
    Flip,
    /// `[`: save the state (position, heading, order).
    Push,
    /// `]`: restore the last saved state.
    Pop,
    /// Start of a rule application: stems are one order higher from here.
    Enter,
    /// End of a rule application.
    Leave,
}

impl Op {
    /// The operation of a drawing component, for the STL alphabet
    /// (`F f + - L R [ ] |`). Other characters have none.
    pub fn of_stl(c: char) -> Option<Op> {
        match c {
            'L' => Some(Op::Turn(1)),
            'R' => Some(Op::Turn(-1)),
            c => Op::of_lsys(c),
        }
    }

    /// The operation of a symbol in a classic L-system (`F f + - [ ] |`);
    /// every other symbol, `L` and `R` included, is inert.
    pub fn of_lsys(c: char) -> Option<Op> {
        match c {
            'F' => Some(Op::Draw),
            'f' => Some(Op::Move),
            '+' => Some(Op::Turn(1)),
            '-' => Some(Op::Turn(-1)),
            '|' => Some(Op::Flip),
            '[' => Some(Op::Push),
            ']' => Some(Op::Pop),
            _ => None,
        }
    }
}

/// The turtle's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Where the turtle is.
    pub pos: Point,
    /// Heading: `k` turns left of straight up.
    pub k: i64,
    /// Turned around (an odd number of `|`).
    pub flip: bool,
    /// Current stem order.
    pub order: u32,
}

impl State {
    /// The state at a root: at `pos`, heading up, not flipped, order 0.
    pub fn start(pos: Point) -> State {
        State {
            pos,
            k: 0,
            flip: false,
            order: 0,
        }
    }
}

/// The turtle state machine: applies [`Op`]s and hands segments to a backend.
pub struct Interp<T: Turtle> {
    /// Current state.
    pub state: State,
    stack: Vec<State>,
    headings: Headings,
    length: Linear,
    /// The backend.
    pub turtle: T,
}

impl<T: Turtle> Interp<T> {
    /// A turtle at `start`, heading up, order 0.
    pub fn new(turtle: T, start: Point, angle_deg: f64, length: Linear) -> Self {
        Interp {
            state: State::start(start),
            stack: Vec::new(),
            headings: Headings::new(angle_deg),
            length,
            turtle,
        }
    }

    /// The same turtle with its first heading at `start_deg` (degrees
    /// counter-clockwise from the canvas's right) instead of up.
    pub fn heading(mut self, start_deg: f64) -> Self {
        self.headings = Headings::starting(start_deg, self.headings.angle());
        self
    }

    /// Applies one operation.
    #[inline]
    pub fn apply(&mut self, op: Op) {
        match op {
            Op::Draw => {
                let to = self.forward();
                self.turtle.segment(Segment {
                    from: self.state.pos,
                    to,
                    order: self.state.order,
                });
                self.state.pos = to;
            }
            Op::Move => self.state.pos = self.forward(),
            Op::Turn(n) => self.state.k += i64::from(n),
            Op::Flip => self.state.flip = !self.state.flip,
            Op::Push => self.stack.push(self.state),
            Op::Pop => {
                // Inputs are checked for balance before interpretation; an
                // extra `]` is ignored rather than trusted.
                if let Some(s) = self.stack.pop() {
                    self.state = s;
                }
            }
            Op::Enter => self.state.order += 1,
            Op::Leave => self.state.order = self.state.order.saturating_sub(1),
        }
    }

    /// The point one stem ahead. Every strategy computes positions with
    /// exactly this expression, so their segments agree bit for bit.
    #[inline]
    fn forward(&mut self) -> Point {
        let (dx, dy) = self.headings.dir(self.state.k, self.state.flip);
        let len = self.length.at(self.state.order);
        Point::new(self.state.pos.x + dx * len, self.state.pos.y + dy * len)
    }

    /// Depth of the state stack.
    pub fn stack_depth(&self) -> usize {
        self.stack.len()
    }

    /// Gives the backend back.
    pub fn into_turtle(self) -> T {
        self.turtle
    }
}
