//! Interpretation: from a derivation (classic L-system or BED) to turtle
//! operations, and from operations to segments.
//!
//! A derivation denotes one stream of [`Op`]s. Two strategies produce it:
//! [`Strategy::Dfs`] expands depth-first straight into the turtle with an
//! explicit stack, never holding the expanded word (000's method);
//! [`Strategy::Bfs`] rewrites the whole word level by level and then
//! interprets it (Saupe's method, the baseline). Both feed the same
//! [`Interp`], so they draw bit-identical segments.
//!
//! - [`lsys`]: derivation of classic L-systems, `expand` and `stats`.
//! - [`bed`]: expansion of Branch-Expansion Descriptions.

pub mod bed;
pub mod lsys;
pub mod stats;

use crate::turtle::{Headings, Point, Segment, Turtle};

/// How a derivation is produced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    /// Depth-first streaming: memory grows with nesting depth only.
    #[default]
    Dfs,
    /// Breadth-first string rewriting, then interpretation (the baseline).
    Bfs,
}

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

/// Segment length for each stem order: `base - order * decrement`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StemLength {
    /// Length at order 0.
    pub base: f64,
    /// Decrease per order.
    pub decrement: f64,
}

impl StemLength {
    /// The same length at every order.
    pub fn constant(len: f64) -> Self {
        StemLength {
            base: len,
            decrement: 0.0,
        }
    }

    /// Length of a stem of `order`.
    #[inline]
    pub fn at(&self, order: u32) -> f64 {
        self.base - f64::from(order) * self.decrement
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

/// The turtle state machine: applies [`Op`]s and hands segments to a backend.
pub struct Interp<T: Turtle> {
    /// Current state.
    pub state: State,
    stack: Vec<State>,
    headings: Headings,
    length: StemLength,
    /// The backend.
    pub turtle: T,
}

impl<T: Turtle> Interp<T> {
    /// A turtle at `start`, heading up, order 0.
    pub fn new(turtle: T, start: Point, angle_deg: f64, length: StemLength) -> Self {
        Interp {
            state: State {
                pos: start,
                k: 0,
                flip: false,
                order: 0,
            },
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
