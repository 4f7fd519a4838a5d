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
//! - `chance.rs`: the expected geometry of a stochastic system and its
//!   level-of-detail walk, which follows the seed's choices;
//! - `reach.rs`, `reach_lod.rs`: the memoized reach of a 3D system (end,
//!   frame, a ball about the start, per `(symbol, depth)`) and the 3D
//!   views' level of detail on it; `space.rs`, `program3.rs`: 3D
//!   derivation (the compiled program over 3D units);
//! - `lod.rs`: the one level-of-detail walk, generic over the three
//!   memos above (`geometry/lod.rs`, `chance/walk.rs` and `reach_lod.rs`
//!   say only what each does at a piece);
//! - `bfs.rs`: Saupe's level-by-level rewriting.

mod alphabet;
mod bfs;
mod chance;
mod exec;
mod geometry;
mod lod;
pub mod lsys3;
pub mod param;
mod program;
mod program3;
mod reach;
mod reach_lod;
mod stochastic;
mod units;

use std::io::Write;

use num_bigint::BigUint;

use crate::diag::{Diagnostics, Help, Knob, io_error};
use crate::interpret::Derivation;
use crate::limits::{Bound, Limits};
use crate::model::lsys::LSystem;
use crate::num::Linear;
use crate::progress::Progress;
use crate::turtle::{BBox, Headings, Point, Turtle};
use crate::turtle::{Interp, Op};

pub(crate) use alphabet::Alphabet;
use alphabet::PROGRESS_STEP;
pub use chance::{Chance, ChancePlan, FIT_SYMBOLS, LOD_WORK, draw_chance};
use exec::Exec;
use geometry::Geometry;
pub use geometry::{GEOMETRY_ENTRIES, MAX_PERIOD, Refusal};
use program::Program;
pub use program::{MACRO_CAP, PROGRAM_CAP};
pub use reach::REACH_ENTRIES;
pub(crate) use reach::ReachMemo;
pub(crate) use reach_lod::ViewLod;
pub use reach_lod::{Mark3, Plan3};
pub use stochastic::BFS_BYTES_PER_SYMBOL;
pub(crate) use stochastic::Stochastic;
pub use units::FastOp;

/// Checks that `sys` can be derived to `depth` with `strategy` within
/// `limits` (depth, the traversal's length, bfs's word), as [`draw`] and
/// [`expand`] do before any work, without deriving.
pub fn check(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
) -> Result<(), Diagnostics> {
    if sys.parametric.is_some() {
        // Its length is known only by deriving (`param`), which stops at
        // the limits.
        return limits.check_depth(depth);
    }
    if sys.is_stochastic() {
        // Its length is known only by deriving (stochastic.rs); its
        // shortest word must fit the stochastic budget.
        limits.check_depth(depth)?;
        let within = stochastic::budget(limits);
        return Stochastic::new(sys)
            .check_shortest(
                depth,
                Bound::Symbols,
                within.max_symbols,
                "derived word length",
            )
            .map_err(|d| stochastic::explain_budget(d, limits));
    }
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
    if sys.parametric.is_some() {
        return Err(Refusal::Parametric);
    }
    if sys.is_stochastic() {
        return Err(Refusal::Stochastic);
    }
    let g = Geometry::new(Alphabet::new(sys), sys, depth, len, GEOMETRY_ENTRIES)?;
    Ok(measured(&g))
}

fn measured(g: &Geometry) -> Measured {
    let (bbox, end) = g.whole();
    Measured {
        bbox,
        end,
        segments: g.segments(),
    }
}

/// The level-of-detail walk draws only when it visits at most this
/// fraction of the symbols the exact compiled path visits (the word's
/// length); otherwise the exact path draws (the same picture as
/// `--exact`), being faster per symbol. Chosen by measurement
/// (docs/rendering.md, *When the walk is used*).
pub const LOD_MAX_VISITS: f64 = 0.35;

/// The memoized geometry of one `.lsys` at one depth, built once per
/// render and used for everything the render needs from it: fitting the
/// picture ([`Memo::measured`]), deciding how to draw ([`Memo::plan`]) and
/// drawing ([`draw_with`]).
pub struct Memo {
    g: Geometry,
}

/// What drawing at a level of detail will do, counted from the memo
/// before drawing ([`Memo::plan`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Plan {
    /// Symbols and stand-ins the level-of-detail walk would visit
    /// (saturating).
    pub visits: u64,
    /// Symbols the exact compiled path visits: the word's length
    /// (saturating).
    pub word: u64,
    /// Stand-ins that draw or move (approximations); with none, the walk
    /// would draw the exact segments.
    pub cuts: u64,
    /// Whether the walk draws (else the exact path): something is cut, and
    /// it visits at most [`LOD_MAX_VISITS`] of the word, or the word is
    /// over `max_symbols` (the exact path would refuse).
    pub walk: bool,
}

impl Memo {
    /// The memo of `sys` derived to `depth` with its own step, or why it
    /// does not apply. `depth` must be within the limits (callers check
    /// it).
    pub fn new(sys: &LSystem, depth: u32) -> Result<Memo, Refusal> {
        if sys.parametric.is_some() {
            return Err(Refusal::Parametric);
        }
        if sys.is_stochastic() {
            return Err(Refusal::Stochastic);
        }
        let step = Linear::constant(sys.length).at(0);
        Geometry::new(Alphabet::new(sys), sys, depth, step, GEOMETRY_ENTRIES).map(|g| Memo { g })
    }

    /// Box, end and segment count of the whole drawing.
    pub fn measured(&self) -> Measured {
        measured(&self.g)
    }

    /// What drawing at `detail` canvas units will do, and whether the walk
    /// or the exact path draws, for a traversal budget of `max_symbols`.
    pub fn plan(&self, detail: f64, max_symbols: u64) -> Plan {
        let [visits, _, cuts] = self.g.lod_cost(detail);
        let word = self.g.word();
        Plan {
            visits,
            word,
            cuts,
            walk: walk_pays(visits, cuts, word, max_symbols),
        }
    }
}

/// The rule of [`Plan::walk`].
fn walk_pays(visits: u64, cuts: u64, word: u64, max_symbols: u64) -> bool {
    cuts > 0 && (word > max_symbols || visits as f64 <= LOD_MAX_VISITS * word as f64)
}

/// Draws `sys` derived to `depth` into `turtle`, starting at the origin
/// heading up, unit step `sys.length`, order 0.
///
/// With `dfs`, when the turtle asks for a level of detail
/// ([`Turtle::detail`]) and the memoized geometry applies, subtrees that
/// fit inside it are drawn as one stand-in segment each, when that pays
/// ([`Plan::walk`]; else every segment is drawn by the compiled path); the traversal
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
    if strategy == Derivation::Dfs && turtle.detail().is_some() {
        limits.check_depth(depth)?;
        if let Ok(memo) = Memo::new(sys, depth) {
            return draw_with(&memo, sys, depth, limits, turtle, progress);
        }
    }
    draw_into(sys, depth, strategy, limits, turtle, progress).map(|_| ())
}

/// [`draw`] with `--strategy dfs` and the memo of `sys` at `depth` already
/// built (once per render): at the turtle's level of detail, by the walk
/// when [`Memo::plan`] says it pays, else by the exact compiled path.
pub fn draw_with(
    memo: &Memo,
    sys: &LSystem,
    depth: u32,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    if let Some(detail) = turtle.detail()
        && lod(&memo.g, depth, detail, limits, turtle, progress, false)?
    {
        return Ok(());
    }
    draw_into(sys, depth, Derivation::Dfs, limits, turtle, progress).map(|_| ())
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
    limits.check_depth(depth)?;
    match Memo::new(sys, depth) {
        Ok(memo) => lod(&memo.g, depth, detail, limits, turtle, progress, true),
        Err(_) => Ok(false),
    }
}

/// The level-of-detail walk; unless `always`, only when it pays
/// ([`Plan::walk`]: otherwise the compiled exact program draws faster).
/// Returns whether it drew.
fn lod(
    g: &Geometry,
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
    let [units, _, cuts] = g.lod_cost(detail);
    if !always && !walk_pays(units, cuts, g.word(), limits.max_symbols) {
        return Ok(false);
    }
    if units > limits.max_symbols {
        return Err(Bound::Symbols
            .exceeded_by(
                format!("symbols to visit at depth {depth} at this level of detail"),
                units,
                limits.max_symbols,
            )
            .with_help(
                Help::from("use a smaller depth or ")
                    + Help::knob(Knob::Size, "")
                    + ", or raise the traversal budget with "
                    + Help::knob(Knob::Limit(Bound::Symbols), "N"),
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
    if let Some(p) = param::of(sys) {
        return param::draw2(sys, p, depth, strategy, limits, turtle);
    }
    if sys.is_stochastic() {
        return draw_stochastic(sys, depth, strategy, limits, turtle, progress);
    }
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
                let (mut interp, ops) = plain_interp(sys, &alpha, turtle);
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
            let (mut interp, ops) = plain_interp(sys, &alpha, turtle);
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

/// [`draw_into`] for a stochastic system: every symbol through [`Interp`]
/// (no compiled program or memo: their pieces would be shared by
/// occurrences that choose differently).
fn draw_stochastic<T: Turtle>(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    turtle: T,
    progress: &mut dyn Progress,
) -> Result<Point, Diagnostics> {
    let st = Stochastic::new(sys);
    let alpha = Alphabet::new(sys);
    let (mut interp, ops) = plain_interp(sys, &alpha, turtle);
    stream_stochastic(&st, depth, strategy, limits, progress, |s| {
        if let Some(op) = ops[s as usize] {
            interp.apply(op);
        }
    })?;
    Ok(interp.state.pos)
}

/// Streams a stochastic system's word (symbol ids of `st`, in order) to
/// `each`, within its budget (`stochastic::budget`), with progress; the
/// one derivation loop the 2D and 3D interpreters share.
pub(crate) fn stream_stochastic(
    st: &Stochastic,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    progress: &mut dyn Progress,
    mut each: impl FnMut(u32),
) -> Result<(), Diagnostics> {
    limits.check_depth(depth)?;
    let within = stochastic::budget(limits);
    // The progress bar's end is the longest word the choices can make.
    let (_, most) = st.length_bounds(depth);
    progress.start("symbols", most);
    let mut i = 0u64;
    let step = |s: u32| {
        each(s);
        i += 1;
        if i.is_multiple_of(PROGRESS_STEP) {
            progress.update(i);
        }
    };
    let done = match strategy {
        Derivation::Dfs => st.dfs_each(depth, &within, step),
        Derivation::Bfs => st.bfs_each(depth, &within, step),
    };
    progress.finish();
    done.map(|_| ())
        .map_err(|d| stochastic::explain_budget(d, limits))
}

/// The turtle state machine at `sys`'s start, and each symbol's operation:
/// what the plain (uncompiled) paths feed symbol by symbol.
fn plain_interp<T: Turtle>(
    sys: &LSystem,
    alpha: &Alphabet,
    turtle: T,
) -> (Interp<T>, Vec<Option<Op>>) {
    let interp = Interp::new(
        turtle,
        Point::default(),
        sys.angle,
        Linear::constant(sys.length),
    )
    .heading(sys.heading);
    let ops = alpha.chars.iter().map(|&c| Op::of_lsys(c)).collect();
    (interp, ops)
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
    if let Some(p) = param::of(sys) {
        return param::expand(sys, p, depth, strategy, limits, out);
    }
    let alpha = Alphabet::new(sys);
    let stochastic = sys.is_stochastic();
    let asked = limits;
    let within = stochastic::budget(limits);
    let limits = if stochastic { &within } else { limits };
    let total = if stochastic {
        limits.check_depth(depth)?;
        let st = Stochastic::new(sys);
        let (_, most) = st.length_bounds(depth);
        if strategy == Derivation::Dfs && most > limits.max_symbols {
            // The word may be over the limit: count it first, so that a
            // refusal comes before a byte is written (bfs refuses before
            // emitting anyway).
            progress.start("counting: symbols", limits.max_symbols);
            let mut n = 0u64;
            let counted = st.dfs_each(depth, limits, |_| {
                n += 1;
                if n.is_multiple_of(PROGRESS_STEP) {
                    progress.update(n);
                }
            });
            progress.finish();
            counted.map_err(|d| stochastic::explain_budget(d, asked))?;
        }
        most
    } else {
        alpha.check(depth, strategy, limits)?[depth as usize]
    };
    progress.start("symbols", total);
    let mut w = std::io::BufWriter::with_capacity(1 << 16, out);
    let mut failed: Option<std::io::Error> = None;
    if stochastic {
        let st = Stochastic::new(sys);
        let mut buf = [0u8; 4];
        let each = |s: u32| {
            if failed.is_none() {
                let text = alpha.chars[s as usize].encode_utf8(&mut buf);
                if let Err(e) = w.write_all(text.as_bytes()) {
                    failed = Some(e);
                }
            }
        };
        let derived = match strategy {
            Derivation::Dfs => st.dfs_each(depth, limits, each),
            Derivation::Bfs => st.bfs_each(depth, limits, each),
        };
        if let Err(e) = derived {
            progress.finish();
            return Err(stochastic::explain_budget(e, asked));
        }
    } else {
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
