//! What a compiled `dfs` program is made of: for drawing, [`FastOp`]s (turtle
//! operations merged where no turtle could tell: runs of `F` counted, turns
//! and flips summed, `[`…`]` pairs that draw nothing removed, leaf branches
//! fused); for `expand`, the UTF-8 bytes of the word.

use crate::turtle::Op;

/// A turtle operation of the `dfs` fast path: [`Op`]s of one run merged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FastOp {
    /// `n` consecutive `F`s.
    Draw(u32),
    /// `n` consecutive `f`s.
    Move(u32),
    /// Turns and flips merged: heading `k += n`, flip toggled if the bool.
    Turn(i64, bool),
    /// `[`.
    Push,
    /// `]`.
    Pop,
    /// `[`, turn, `n` x `F`, `]` in one: a leaf branch. Draws from the
    /// current state with the heading turned by `turn` (and flipped if
    /// `flip`), then leaves the state as it was.
    Leaf {
        /// Turns added to the heading.
        turn: i64,
        /// Whether the branch is turned around.
        flip: bool,
        /// Number of segments.
        n: u32,
    },
}

/// What a compiled program is made of: drawing ops or text bytes.
pub(super) trait Unit: Copy {
    /// Appends the code of terminal symbol `c`.
    fn terminal(c: char, out: &mut Vec<Self>);
    /// Appends `piece` to `out`, merging at the junction where possible.
    fn append(out: &mut Vec<Self>, piece: &[Self]);
}

impl Unit for u8 {
    fn terminal(c: char, out: &mut Vec<u8>) {
        let mut buf = [0u8; 4];
        out.extend_from_slice(c.encode_utf8(&mut buf).as_bytes());
    }
    fn append(out: &mut Vec<u8>, piece: &[u8]) {
        out.extend_from_slice(piece);
    }
}

impl Unit for FastOp {
    fn terminal(c: char, out: &mut Vec<FastOp>) {
        let op = match Op::of_lsys(c) {
            Some(Op::Draw) => FastOp::Draw(1),
            Some(Op::Move) => FastOp::Move(1),
            Some(Op::Turn(n)) => FastOp::Turn(i64::from(n), false),
            Some(Op::Flip) => FastOp::Turn(0, true),
            Some(Op::Push) => FastOp::Push,
            Some(Op::Pop) => FastOp::Pop,
            Some(Op::Enter | Op::Leave) | None => return,
        };
        push_op(out, op);
    }
    fn append(out: &mut Vec<FastOp>, piece: &[FastOp]) {
        let mut it = piece.iter();
        if let Some(&first) = it.next() {
            push_op(out, first);
        }
        // Only the junction can merge: the rest of `piece` is already merged.
        out.extend(it);
    }
}

/// Appends `op`, merging it with the ops before it where that changes
/// nothing a turtle could observe.
fn push_op(out: &mut Vec<FastOp>, op: FastOp) {
    use FastOp::*;
    match (out.last().copied(), op) {
        (Some(Draw(a)), Draw(b)) if a.checked_add(b).is_some() => {
            *out.last_mut().unwrap_or(&mut Draw(0)) = Draw(a + b);
        }
        (Some(Move(a)), Move(b)) if a.checked_add(b).is_some() => {
            *out.last_mut().unwrap_or(&mut Move(0)) = Move(a + b);
        }
        (Some(Turn(a, fa)), Turn(b, fb)) => {
            out.pop();
            let (n, f) = (a.wrapping_add(b), fa != fb);
            if n != 0 || f {
                out.push(Turn(n, f));
            }
        }
        // `[` `]` and `[` turn-or-move `]` restore what they saved.
        (Some(Push), Pop) => {
            out.pop();
        }
        (Some(Turn(..) | Move(_)), Pop) if out.len() >= 2 && out[out.len() - 2] == Push => {
            out.truncate(out.len() - 2);
        }
        // A leaf branch: `[` (turn) F..F `]`.
        (Some(Draw(d)), Pop) => {
            let len = out.len();
            let (turn, flip, drop) = match out.get(len.wrapping_sub(3)..len - 1) {
                Some([Push, Turn(t, f)]) => (*t, *f, 3),
                _ if len >= 2 && out[len - 2] == Push => (0, false, 2),
                _ => (0, false, 0),
            };
            if drop == 0 {
                out.push(Pop);
            } else {
                out.truncate(len - drop);
                out.push(Leaf { turn, flip, n: d });
            }
        }
        _ => out.push(op),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merging_keeps_what_a_turtle_sees() {
        let mut out = Vec::new();
        for c in "FF+-+|f[+]F[f]F[[]]X".chars() {
            FastOp::terminal(c, &mut out);
        }
        assert_eq!(
            out,
            vec![
                FastOp::Draw(2),
                FastOp::Turn(1, true),
                FastOp::Move(1),
                FastOp::Draw(2),
            ]
        );
        let mut out = Vec::new();
        for c in "F[+F]F[-|FF]F[F]".chars() {
            FastOp::terminal(c, &mut out);
        }
        use FastOp::*;
        assert_eq!(
            out,
            vec![
                Draw(1),
                Leaf {
                    turn: 1,
                    flip: false,
                    n: 1
                },
                Draw(1),
                Leaf {
                    turn: -1,
                    flip: true,
                    n: 2
                },
                Draw(1),
                Leaf {
                    turn: 0,
                    flip: false,
                    n: 1
                },
            ]
        );
    }
}
