//! The compiled `dfs` program of a 3D system: [`Fast3`] units, executed by
//! the 3D turtle. The same [`Program`](super::program::Program) as 2D
//! (macros of small expansions, plans of large ones) over units that drop
//! inert symbols and count runs of `F`; every operation is still applied
//! one by one with [`Turtle3::apply`], so the stems are bit-identical to
//! the plain stream's (tested against it).

use super::units::Unit;
use crate::turtle::turtle3::{Op3, Segment3, Turtle3};

/// One unit of a compiled 3D program.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Fast3 {
    /// `n` consecutive `F`.
    Draws(u32),
    /// Any other operation.
    Op(Op3),
}

impl Unit for Fast3 {
    fn terminal(c: char, out: &mut Vec<Fast3>) {
        match Op3::of_lsys(c) {
            Some(Op3::Draw) => push(out, Fast3::Draws(1)),
            Some(op) => push(out, Fast3::Op(op)),
            None => {}
        }
    }
    fn append(out: &mut Vec<Fast3>, piece: &[Fast3]) {
        let mut it = piece.iter();
        if let Some(&first) = it.next() {
            push(out, first);
        }
        out.extend(it);
    }
}

/// Appends `u`, merging runs of `F`.
fn push(out: &mut Vec<Fast3>, u: Fast3) {
    if let (Some(Fast3::Draws(a)), Fast3::Draws(b)) = (out.last_mut(), u)
        && let Some(n) = a.checked_add(b)
    {
        *a = n;
        return;
    }
    out.push(u);
}

/// Executes `units` on `turtle`.
#[inline]
pub(super) fn run<S: FnMut(Segment3)>(turtle: &mut Turtle3<S>, units: &[Fast3]) {
    for &u in units {
        match u {
            Fast3::Draws(n) => {
                for _ in 0..n {
                    turtle.apply(Op3::Draw);
                }
            }
            Fast3::Op(op) => turtle.apply(op),
        }
    }
}
