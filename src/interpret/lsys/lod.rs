//! The one level-of-detail walk, generic over a memo ([`Memo`]).
//!
//! Every memo of a classic system keys a *piece*, `W(s, r)` (symbol `s`
//! expanded `r` more times), by module and depth, and knows what it
//! reaches and where it ends: the 2D deterministic memo by heading too
//! (`geometry.rs`), the stochastic one in expectation over the choices
//! (`chance.rs`), the 3D one by a ball about its start (`reach.rs`). The
//! walk over the word is the same for all of them: depth first, with an
//! explicit stack of frames (a successor and the remaining depth of its
//! symbols); at each piece the memo either draws a stand-in and moves its
//! turtle to the piece's end, or hands back the successor to walk into;
//! every other symbol is applied as the exact turtle applies it. So at
//! detail 0, where nothing that draws is cut, each walk is the exact
//! drawing, segment for segment.
//!
//! What differs is only what a frame carries (a stochastic system's key:
//! a place's choices are its parent's key and its index in the parent's
//! successor, never a position in a stream, so a skipped subtree changes
//! no later choice) and what a memo does at a piece ([`Memo::piece`]). A
//! 2D stand-in is worked out once here ([`stand_in_2d`]) for both 2D
//! memos, and every stand-in that breaks off in branches reaches the
//! backend through the one call [`Turtle::stand_in`](crate::turtle::Turtle::stand_in).

use super::alphabet::PROGRESS_STEP;
use super::geometry::Piece;
use crate::progress::Progress;
use crate::turtle::{Point, Segment};

/// What the walk asks of a memo, with the turtle it draws into. `'m` is
/// the memo's lifetime: successors are borrowed from it.
pub(crate) trait Memo<'m> {
    /// What a frame carries besides its word: the choices' key of a
    /// stochastic system, nothing for a deterministic one.
    type Ctx: Copy;

    /// The context of the symbol at index `at` of a word in context `ctx`.
    fn child(ctx: Self::Ctx, at: usize) -> Self::Ctx;

    /// Whether `c` at remaining depth `r` is a piece (expanded further and
    /// in the memo), not a terminal symbol.
    fn is_piece(&self, c: u32, r: u32) -> bool;

    /// At piece `c` (remaining depth `r`, context `ctx`): either draws its
    /// stand-in (or nothing, for a piece that only moves or turns) and
    /// moves the turtle to where the piece ends, returning `None`, or
    /// returns the successor to walk into (its symbols at `r - 1`, in
    /// context `ctx`).
    fn piece(&mut self, c: u32, r: u32, ctx: Self::Ctx) -> Option<&'m [u32]>;

    /// Applies a symbol that is not a piece, as the exact turtle does.
    fn terminal(&mut self, c: u32);
}

/// Walks `word`, whose symbols are at remaining depth `r` in context
/// `ctx`, through memo `m`, reporting the symbols visited to `progress`
/// about every [`PROGRESS_STEP`]. Returns how many it visited.
pub(crate) fn walk<'m, M: Memo<'m>>(
    m: &mut M,
    word: &'m [u32],
    r: u32,
    ctx: M::Ctx,
    progress: &mut dyn Progress,
) -> u64 {
    struct Frame<'w, C> {
        word: &'w [u32],
        at: usize,
        /// Remaining depth of the word's symbols.
        r: u32,
        ctx: C,
    }
    let mut frames = vec![Frame {
        word,
        at: 0,
        r,
        ctx,
    }];
    let mut done = 0u64;
    let mut next_report = PROGRESS_STEP;
    while let Some(top) = frames.last_mut() {
        let Some(&c) = top.word.get(top.at) else {
            frames.pop();
            continue;
        };
        let at = top.at;
        top.at += 1;
        let r = top.r;
        done += 1;
        if done >= next_report {
            progress.update(done);
            next_report = done.saturating_add(PROGRESS_STEP);
        }
        if m.is_piece(c, r) {
            let ctx = M::child(top.ctx, at);
            if let Some(succ) = m.piece(c, r, ctx) {
                frames.push(Frame {
                    word: succ,
                    at: 0,
                    r: r - 1,
                    ctx,
                });
            }
            continue;
        }
        m.terminal(c);
    }
    progress.update(done);
    done
}

/// A 2D piece cut at the detail, as both 2D memos see it.
pub(crate) struct Part2 {
    /// Where the turtle is.
    pub start: Point,
    /// Where the piece ends.
    pub end: Point,
    /// Its chord, `|end - start|` as the memo works it out.
    pub chord: f64,
    /// Its box's corners (turned around with the turtle if flipped).
    pub lo: Point,
    /// See `lo`.
    pub hi: Point,
    /// The piece (for its box's extent).
    pub piece: Piece,
    /// The segments it stands for (expected, for a stochastic piece).
    pub segments: f64,
    /// Whether it breaks off somewhere (a `]` or `f` inside): a bush, not
    /// one connected run.
    pub jumps: bool,
    /// The turtle's step.
    pub len: f64,
}

/// How a cut 2D piece is handed to the backend.
pub(crate) enum Stand2 {
    /// One connected run: its chord (or its box's diagonal) and the
    /// segments it stands for, for [`Turtle::run`](crate::turtle::Turtle::run).
    Run(Segment, f64),
    /// A bush: a segment along its box's middle, its density and
    /// footprint (the runs left for the caller), for
    /// [`Turtle::stand_in`](crate::turtle::Turtle::stand_in).
    Bush(Segment, f64, f64),
}

/// The stand-in of a cut 2D piece: its chord, or its box's diagonal when
/// the chord is less than half the box; a bush's moved across onto the
/// box's middle with the box's half-width as its spread.
pub(crate) fn stand_in_2d(p: &Part2) -> Stand2 {
    let (from, to) = if p.chord * 2.0 >= p.piece.extent() {
        (p.start, p.end)
    } else {
        (p.lo, p.hi)
    };
    if !p.jumps {
        // A connected run is drawn as one line however it winds, so it
        // stays a line.
        return Stand2::Run(Segment { from, to, order: 0 }, p.segments);
    }
    let seg_len = libm::hypot(to.x - from.x, to.y - from.y);
    let density = (p.segments * p.len.abs() / seg_len).max(1.0);
    let density = if density.is_finite() { density } else { 1.0 };
    let (seg, spread) = across(from, to, p.lo, p.hi);
    Stand2::Bush(seg, density, spread)
}

/// A bush's stand-in along `from`-`to`, moved across onto the middle of
/// the box `a`-`b` (opposite corners), and the box's half-width across
/// it: its [`Footprint`]'s spread.
pub(crate) fn across(from: Point, to: Point, a: Point, b: Point) -> (Segment, f64) {
    let (dx, dy) = (to.x - from.x, to.y - from.y);
    let l = libm::hypot(dx, dy);
    let (nx, ny) = if l > 0.0 {
        (-dy / l, dx / l)
    } else {
        (1.0, 0.0)
    };
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (x, y) in [(a.x, a.y), (a.x, b.y), (b.x, a.y), (b.x, b.y)] {
        let t = (x - from.x) * nx + (y - from.y) * ny;
        lo = lo.min(t);
        hi = hi.max(t);
    }
    let mid = (lo + hi) / 2.0;
    let (ox, oy) = (nx * mid, ny * mid);
    let seg = Segment {
        from: Point::new(from.x + ox, from.y + oy),
        to: Point::new(to.x + ox, to.y + oy),
        order: 0,
    };
    (seg, (hi - lo) / 2.0)
}
