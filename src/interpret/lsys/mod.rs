//! Derivation of classic L-systems: `dfs` streaming and `bfs` rewriting.
//!
//! Both strategies denote the same word `W(axiom, depth)`, where
//! `W(s, 0) = s`, `W(s, r) = s` for a symbol without a rule, and otherwise
//! `W(s, r)` is the concatenation of `W(c, r - 1)` over the successor of `s`
//! (parallel rewriting).
//!
//! **`dfs`** never builds that word. A program is compiled first:
//! - every `(symbol, remaining depth)` whose whole expansion is small (at
//!   most [`MACRO_CAP`] units) is precomputed once as a *macro*: for drawing,
//!   a list of [`FastOp`]s with inert symbols dropped, runs of `F` and of
//!   `f` counted, consecutive turns and flips merged, `[`…`]` pairs that
//!   draw nothing removed and leaf branches (`[`, turns, `F`s, `]`) fused
//!   into one op; for `expand`, the UTF-8 text;
//! - every larger `(symbol, remaining depth)` becomes a *plan*: its successor
//!   as a list of runs (references to child macros, or short glue runs of
//!   merged terminal symbols) and calls to child plans.
//!
//! The plans are then executed with an explicit stack of `(plan, index)`
//! frames, one per level above the macros: memory is O(depth x longest
//! successor) plus the macros, whatever the word length.
//!
//! `dfs` does not draw through [`Interp`]: its merged operations are a
//! shorter stream than `bfs`'s one [`Op`] per symbol, run by its own
//! executor, the one place besides [`Interp`] where positions are computed.
//! It computes them with [`Interp`]'s expression, so the segments are
//! bit-identical: a counted `Draw(n)` still advances `pos + dir * len` one
//! step at a time with the direction of [`Headings::dir`]; merging only
//! touches the integer heading and the flip flag, and removed `[`…`]` pairs
//! restore the state they saved. The property test in
//! `tests/integration/lsys.rs` checks `dfs == bfs` segment for segment.
//!
//! **`bfs`** is Saupe's method: the whole word is rewritten level by level
//! (one byte per symbol when the alphabet has at most 256 symbols), then
//! every symbol is fed to [`Interp::apply`]. It refuses up front, from the
//! exact word lengths, when a level would hold more than `limits.max_word`
//! symbols.
//!
//! - `alphabet.rs`: the symbols as dense ids, word lengths (saturating,
//!   and exact with big integers) and the limit checks made from them;
//! - `program.rs`: the compiled `dfs` program (macros and plans) and its
//!   stack machine;
//! - `units.rs`: what programs are made of ([`FastOp`]s and their merging,
//!   or text bytes);
//! - `exec.rs`: the `dfs` turtle executing [`FastOp`]s;
//! - `geometry.rs`: the memoized geometry (net move, turn and box per
//!   `(symbol, depth, heading)`), for `bbox`/`end` at any depth, the
//!   renderer's fitting and its level of detail;
//! - `bfs.rs`: Saupe's level-by-level rewriting.

mod alphabet;
mod bfs;
mod exec;
mod geometry;
mod program;
mod units;

use std::io::Write;

use num_bigint::BigUint;

use crate::diag::{Diagnostic, ErrorKind};
use crate::diag::{Diagnostics, io_error};
use crate::interpret::Derivation;
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::num::Linear;
use crate::progress::Progress;
use crate::turtle::{BBox, Headings, Point, Turtle};
use crate::turtle::{Interp, Op};

pub(crate) use alphabet::Alphabet;
use exec::Exec;
use geometry::Geometry;
pub use geometry::{GEOMETRY_ENTRIES, MAX_PERIOD, Refusal};
use program::Program;
pub use program::{MACRO_CAP, PROGRAM_CAP};
pub use units::FastOp;

/// Progress is reported about every this many symbols.
const PROGRESS_STEP: u64 = 1 << 20;

/// Checks that `sys` can be derived to `depth` with `strategy` within
/// `limits` (depth, the traversal's length, bfs's word), as [`draw`] and
/// [`expand`] do before any work, without deriving.
pub fn check(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
) -> Result<(), Diagnostics> {
    Alphabet::new(sys)
        .check(depth, strategy, limits)
        .map(|_| ())
}

/// What the memoized geometry knows about a derived word without
/// traversing it (see [`measure`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// Box of every drawn segment, `None` if nothing is drawn.
    pub bbox: Option<BBox>,
    /// Where the turtle ends.
    pub end: Point,
    /// Number of segments (`F`s), saturating.
    pub segments: u64,
}

/// The box, end and segment count of `sys` derived to `depth` with step
/// `len`, from the memoized geometry (no traversal; positions to
/// floating-point accuracy), or why the memo does not apply. At most
/// [`GEOMETRY_ENTRIES`] pieces are held. `depth` must be within the
/// limits (callers check it).
pub fn measure(sys: &LSystem, depth: u32, len: f64) -> Result<Measured, Refusal> {
    let alpha = Alphabet::new(sys);
    let mut g = Geometry::new(&alpha, sys, depth, len, GEOMETRY_ENTRIES)?;
    let (bbox, end) = g.whole();
    Ok(Measured {
        bbox,
        end,
        segments: g.segments(),
    })
}

/// Draws `sys` derived to `depth` into `turtle`, starting at the origin
/// heading up, unit step `sys.length`, order 0.
///
/// With `dfs`, when the turtle asks for a level of detail
/// ([`Turtle::detail`]) and the memoized geometry applies, subtrees that
/// fit inside it are drawn as one stand-in segment each; the traversal
/// limit (`limits.max_symbols`) then bounds the symbols and stand-ins
/// visited, which the memo counts before drawing. Otherwise every segment
/// is drawn.
pub fn draw(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    if strategy == Derivation::Dfs
        && let Some(detail) = turtle.detail()
        && lod(sys, depth, detail, limits, turtle, progress, false)?
    {
        return Ok(());
    }
    draw_into(sys, depth, strategy, limits, turtle, progress).map(|_| ())
}

/// Draws `sys` at a level of detail of `detail` canvas units with the
/// memoized geometry (see [`draw`]), whether or not anything is cut.
/// Returns `false`, drawing nothing, when the memo does not apply or
/// `detail` is negative or not finite.
pub fn draw_lod(
    sys: &LSystem,
    depth: u32,
    detail: f64,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<bool, Diagnostics> {
    lod(sys, depth, detail, limits, turtle, progress, true)
}

/// The level-of-detail walk; unless `always`, only when something is cut
/// (otherwise the drawing is the exact one, which the compiled program
/// draws faster). Returns whether it drew.
fn lod(
    sys: &LSystem,
    depth: u32,
    detail: f64,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
    always: bool,
) -> Result<bool, Diagnostics> {
    if !(detail.is_finite() && detail >= 0.0) {
        return Ok(false);
    }
    limits.check_depth(depth)?;
    let alpha = Alphabet::new(sys);
    let step = Linear::constant(sys.length).at(0);
    let Ok(mut g) = Geometry::new(&alpha, sys, depth, step, GEOMETRY_ENTRIES) else {
        return Ok(false);
    };
    let [units, _, cuts] = g.lod_cost(detail);
    if cuts == 0 && !always {
        return Ok(false);
    }
    if units > limits.max_symbols {
        return Err(Diagnostic::error(ErrorKind::Limit {
            what: format!("symbols to visit at depth {depth} at this level of detail"),
            value: units.to_string(),
            limit: limits.max_symbols.to_string(),
        })
        .with_help(
            "use a smaller depth or --size, or raise the traversal budget with --max-symbols N",
        )
        .into());
    }
    progress.start("symbols", units);
    g.draw_lod(detail, turtle, progress);
    progress.update(units);
    progress.finish();
    Ok(true)
}

/// [`draw`] for a concrete backend (monomorphised: the hot loop calls the
/// backend's `segment` directly). Returns where the turtle ends.
pub fn draw_into<T: Turtle>(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    turtle: T,
    progress: &mut dyn Progress,
) -> Result<Point, Diagnostics> {
    let alpha = Alphabet::new(sys);
    let lens = alpha.check(depth, strategy, limits)?;
    let total = lens[depth as usize];
    let step = Linear::constant(sys.length).at(0);
    progress.start("symbols", total);
    let end = match strategy {
        Derivation::Dfs => match Program::<FastOp>::compile(&alpha, depth) {
            Some(program) => {
                let mut exec = Exec::new(turtle, Headings::starting(sys.heading, sys.angle), step);
                program.run(&alpha.axiom, |ops| exec.run(ops), progress);
                Point::new(exec.x, exec.y)
            }
            None => {
                // Over the program's budget: the same word, streamed.
                let mut interp = Interp::new(
                    turtle,
                    Point::default(),
                    sys.angle,
                    Linear::constant(sys.length),
                )
                .heading(sys.heading);
                let ops: Vec<Option<Op>> = alpha.chars.iter().map(|&c| Op::of_lsys(c)).collect();
                alpha.plain_each(depth, |i, s| {
                    if let Some(op) = ops[s as usize] {
                        interp.apply(op);
                    }
                    if i % PROGRESS_STEP == PROGRESS_STEP - 1 {
                        progress.update(i + 1);
                    }
                });
                interp.state.pos
            }
        },
        Derivation::Bfs => {
            let mut interp = Interp::new(
                turtle,
                Point::default(),
                sys.angle,
                Linear::constant(sys.length),
            )
            .heading(sys.heading);
            let ops: Vec<Option<Op>> = alpha.chars.iter().map(|&c| Op::of_lsys(c)).collect();
            alpha.bfs_each(depth, |i, s| {
                if let Some(op) = ops[s as usize] {
                    interp.apply(op);
                }
                if i as u64 % PROGRESS_STEP == PROGRESS_STEP - 1 {
                    progress.update(i as u64 + 1);
                }
            });
            interp.state.pos
        }
    };
    progress.update(total);
    progress.finish();
    Ok(end)
}

/// Streams the word of `sys` derived to `depth` (every symbol, not only the
/// turtle's) to `out`, followed by a newline. Writes are buffered.
pub fn expand(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    let alpha = Alphabet::new(sys);
    let lens = alpha.check(depth, strategy, limits)?;
    let total = lens[depth as usize];
    progress.start("symbols", total);
    let mut w = std::io::BufWriter::with_capacity(1 << 16, out);
    let mut failed: Option<std::io::Error> = None;
    match strategy {
        Derivation::Dfs => match Program::<u8>::compile(&alpha, depth) {
            Some(program) => program.run(
                &alpha.axiom,
                |bytes| {
                    if failed.is_none()
                        && let Err(e) = w.write_all(bytes)
                    {
                        failed = Some(e);
                    }
                },
                progress,
            ),
            None => {
                let mut buf = [0u8; 4];
                alpha.plain_each(depth, |_, s| {
                    if failed.is_none() {
                        let text = alpha.chars[s as usize].encode_utf8(&mut buf);
                        if let Err(e) = w.write_all(text.as_bytes()) {
                            failed = Some(e);
                        }
                    }
                });
            }
        },
        Derivation::Bfs => {
            let mut buf = [0u8; 4];
            alpha.bfs_each(depth, |_, s| {
                if failed.is_none() {
                    let text = alpha.chars[s as usize].encode_utf8(&mut buf);
                    if let Err(e) = w.write_all(text.as_bytes()) {
                        failed = Some(e);
                    }
                }
            });
        }
    }
    if failed.is_none()
        && let Err(e) = w.write_all(b"\n").and_then(|()| w.flush())
    {
        failed = Some(e);
    }
    progress.update(total);
    progress.finish();
    match failed {
        Some(e) => Err(io_error(&e, "writing the derived word").into()),
        None => Ok(()),
    }
}

/// The exact length of every level's word, `levels[r]` for `r` rewriting
/// steps, `0..=depth`. Memoised per (symbol, steps) with big integers.
pub fn exact_lengths(sys: &LSystem, depth: u32) -> Vec<BigUint> {
    let alpha = Alphabet::new(sys);
    let mut levels = Vec::with_capacity(depth as usize + 1);
    alpha.exact_each(depth, |len| levels.push(len));
    levels
}
