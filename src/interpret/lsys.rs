//! Derivation of classic L-systems: `dfs` streaming and `bfs` rewriting.
//!
//! Both strategies denote the same word `W(axiom, depth)`, where
//! `W(s, 0) = s`, `W(s, r) = s` for a symbol without a rule, and otherwise
//! `W(s, r)` is the concatenation of `W(c, r - 1)` over the successor of `s`
//! (parallel rewriting).
//!
//! **`dfs`** never builds that word. A [`Program`] is compiled first:
//! - every `(symbol, remaining depth)` whose whole expansion is small (at
//!   most [`MACRO_CAP`] units) is precomputed once as a *macro*: for drawing,
//!   a list of [`FastOp`]s with inert symbols dropped, runs of `F` counted,
//!   consecutive turns and flips merged and `[`…`]` pairs that draw nothing
//!   removed; for `expand`, the UTF-8 text;
//! - every larger `(symbol, remaining depth)` becomes a *plan*: its successor
//!   as a list of runs (references to child macros, or short glue runs of
//!   merged terminal symbols) and calls to child plans.
//!
//! The plans are then executed with an explicit stack of `(plan, index)`
//! frames, one per level above the macros: memory is O(depth x longest
//! successor) plus the macros, whatever the word length.
//!
//! Positions stay bit-identical to op-by-op [`Interp`] interpretation: a
//! counted `Draw(n)` still advances `pos + dir * len` one step at a time with
//! the direction of [`Headings::dir`]; merging only touches the integer
//! heading and the flip flag, and removed `[`…`]` pairs restore the state
//! they saved. The property test in `tests/integration/lsys.rs` checks
//! `dfs == bfs` segment for segment.
//!
//! **`bfs`** is Saupe's method: the whole word is rewritten level by level
//! (one byte per symbol when the alphabet has at most 256 symbols), then
//! every symbol is fed to [`Interp::apply`]. It refuses up front, from the
//! exact word lengths, when a level would hold more than `limits.max_word`
//! symbols.

use std::collections::BTreeMap;
use std::io::Write;

use num_bigint::BigUint;

use crate::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use crate::interpret::Derivation;
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::num::Linear;
use crate::progress::Progress;
use crate::turtle::{Headings, Point, Segment, Turtle};
use crate::turtle::{Interp, Op};

/// Largest precomputed expansion of one `(symbol, remaining depth)`, in
/// units (ops or bytes). 4096 ops are 64 KiB: a macro stays in L2 cache.
pub const MACRO_CAP: usize = 4096;

/// Child macros up to this size are copied into their parent's glue runs
/// (one run instead of several short ones); larger ones are referenced.
const GLUE_CAP: usize = 64;

/// Macros stop being made once the pool holds this many units (a bound on
/// compile memory for systems whose expansions grow slowly).
const POOL_CAP: usize = 1 << 20;

/// Most limb additions spent on an exact (big integer) word length for an
/// error message; beyond it the message gives a bound.
const EXACT_WORK: u64 = 1 << 28;

/// Progress is reported about every this many symbols.
const PROGRESS_STEP: u64 = 1 << 20;

/// Draws `sys` derived to `depth` into `turtle`, starting at the origin
/// heading up, unit step `sys.length`, order 0.
pub fn draw(
    sys: &LSystem,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    draw_into(sys, depth, strategy, limits, turtle, progress).map(|_| ())
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
        Derivation::Dfs => {
            let program = Program::<FastOp>::compile(&alpha, depth);
            let mut exec = Exec::new(turtle, Headings::starting(sys.heading, sys.angle), step);
            program.run(|ops| exec.run(ops), progress);
            Point::new(exec.x, exec.y)
        }
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
        Derivation::Dfs => {
            let program = Program::<u8>::compile(&alpha, depth);
            program.run(
                |bytes| {
                    if failed.is_none() {
                        if let Err(e) = w.write_all(bytes) {
                            failed = Some(e);
                        }
                    }
                },
                progress,
            );
        }
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
    if failed.is_none() {
        if let Err(e) = w.write_all(b"\n").and_then(|()| w.flush()) {
            failed = Some(e);
        }
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

/// The system's symbols as dense ids.
pub(crate) struct Alphabet {
    /// Id to symbol, sorted.
    pub(crate) chars: Vec<char>,
    /// Successor of each symbol, if it has a rule.
    pub(crate) succ: Vec<Option<Vec<u32>>>,
    /// The axiom.
    pub(crate) axiom: Vec<u32>,
    /// The symbols that have a rule (the others keep length 1 at every depth).
    ruled: Vec<u32>,
    /// How often each symbol of `ruled` occurs in the axiom, and how many
    /// axiom symbols have no rule: word lengths are computed from these, not
    /// by walking the axiom once per level.
    axiom_ruled: Vec<u64>,
    axiom_inert: u64,
}

impl Alphabet {
    pub(crate) fn new(sys: &LSystem) -> Self {
        let chars = sys.alphabet();
        let index: BTreeMap<char, u32> = chars
            .iter()
            .enumerate()
            .map(|(i, &c)| (c, i as u32))
            .collect();
        let ids = |w: &[char]| -> Vec<u32> { w.iter().map(|c| index[c]).collect() };
        let succ: Vec<Option<Vec<u32>>> =
            chars.iter().map(|c| sys.successor(*c).map(ids)).collect();
        let ruled: Vec<u32> = (0..chars.len() as u32)
            .filter(|&s| succ[s as usize].is_some())
            .collect();
        let axiom = ids(&sys.axiom);
        let mut axiom_ruled = vec![0u64; ruled.len()];
        let mut axiom_inert = 0u64;
        for &s in &axiom {
            match ruled.binary_search(&s) {
                Ok(i) => axiom_ruled[i] += 1,
                Err(_) => axiom_inert += 1,
            }
        }
        Alphabet {
            succ,
            axiom,
            chars,
            ruled,
            axiom_ruled,
            axiom_inert,
        }
    }

    /// Saturating lengths of the derived word, `W(axiom, r)` for `r` in
    /// `0..=depth`. Memory is O(alphabet), not O(alphabet x depth): level by
    /// level, only symbols with a rule are recomputed, and once a level
    /// equals the one before (saturated or stationary lengths) every later
    /// level is the same, so the rest is filled in at once.
    fn word_lengths(&self, depth: u32) -> Vec<u64> {
        let mut len = vec![1u64; self.chars.len()];
        let mut out = Vec::with_capacity(depth as usize + 1);
        out.push(self.word_len(&len));
        let mut next = vec![0u64; self.ruled.len()];
        for _ in 0..depth {
            for (v, &s) in next.iter_mut().zip(&self.ruled) {
                *v = self.succ[s as usize]
                    .iter()
                    .flatten()
                    .fold(0u64, |a, &c| a.saturating_add(len[c as usize]));
            }
            let mut changed = false;
            for (&v, &s) in next.iter().zip(&self.ruled) {
                changed |= len[s as usize] != v;
                len[s as usize] = v;
            }
            let w = self.word_len(&len);
            out.push(w);
            if !changed {
                out.resize(depth as usize + 1, w);
                break;
            }
        }
        out
    }

    /// The saturating word length for the per-symbol lengths `len`.
    fn word_len(&self, len: &[u64]) -> u64 {
        self.ruled
            .iter()
            .zip(&self.axiom_ruled)
            .fold(self.axiom_inert, |a, (&s, &k)| {
                a.saturating_add(len[s as usize].saturating_mul(k))
            })
    }

    /// Refuses depths and words over the limits; returns the saturating
    /// word length of every level `0..=depth`.
    fn check(
        &self,
        depth: u32,
        strategy: Derivation,
        limits: &Limits,
    ) -> Result<Vec<u64>, Diagnostics> {
        limits.check_depth(depth)?;
        let lens = self.word_lengths(depth);
        let exact = |r: u32| -> String {
            // Saturated lengths are recomputed exactly for the message.
            let len = lens[r as usize];
            if len < u64::MAX {
                len.to_string()
            } else {
                self.exact_len(r)
            }
        };
        if lens[depth as usize] > limits.max_symbols {
            return Err(Diagnostic::error(ErrorKind::Limit {
                what: format!("derived word length at depth {depth}"),
                value: exact(depth),
                limit: limits.max_symbols.to_string(),
            })
            .with_help("use a smaller depth, or raise the traversal budget with --max-symbols N")
            .into());
        }
        if strategy == Derivation::Bfs {
            if let Some(r) = (0..=depth).find(|&r| lens[r as usize] > limits.max_word) {
                return Err(Diagnostic::error(ErrorKind::Limit {
                    what: format!("bfs word at level {r}"),
                    value: exact(r),
                    limit: limits.max_word.to_string(),
                })
                .with_help(
                    "use --strategy dfs (it never holds the word), a smaller depth, \
                     or raise the limit with --max-word N",
                )
                .into());
            }
        }
        Ok(lens)
    }

    /// The exact word length at level `r`, in decimal, for a message. Big
    /// integers cost time in proportion to their size: when the work would
    /// exceed [`EXACT_WORK`] limb additions, a bound is given instead.
    fn exact_len(&self, r: u32) -> String {
        let per_level: u64 = self
            .ruled
            .iter()
            .map(|&s| self.succ[s as usize].as_ref().map_or(0, |w| w.len() as u64) + 1)
            .sum::<u64>()
            + self.ruled.len() as u64;
        // Lengths grow by at most log2(longest successor) bits per level.
        let longest = self
            .succ
            .iter()
            .flatten()
            .map(Vec::len)
            .max()
            .unwrap_or(1)
            .max(2);
        let bits = u64::from(r) * u64::from(usize::BITS - longest.leading_zeros());
        let limbs = bits / 64 + 1;
        let work = u64::from(r).saturating_mul(per_level).saturating_mul(limbs);
        if work > EXACT_WORK {
            return format!("more than {}", u64::MAX - 1);
        }
        let mut last = BigUint::default();
        self.exact_each(r, |len| last = len);
        last.to_string()
    }

    /// Exact word lengths `W(axiom, r)` for `r` in `0..=depth`, each handed
    /// to `f` in order; only symbols with a rule are recomputed per level.
    fn exact_each(&self, depth: u32, mut f: impl FnMut(BigUint)) {
        let one = BigUint::from(1u32);
        let mut len: Vec<BigUint> = vec![one; self.chars.len()];
        let word = |len: &[BigUint]| -> BigUint {
            let mut w = BigUint::from(self.axiom_inert);
            for (&s, &k) in self.ruled.iter().zip(&self.axiom_ruled) {
                if k > 0 {
                    w += &len[s as usize] * k;
                }
            }
            w
        };
        f(word(&len));
        for _ in 0..depth {
            let next: Vec<BigUint> = self
                .ruled
                .iter()
                .map(|&s| {
                    self.succ[s as usize]
                        .iter()
                        .flatten()
                        .map(|&c| &len[c as usize])
                        .sum()
                })
                .collect();
            for (v, &s) in next.into_iter().zip(&self.ruled) {
                len[s as usize] = v;
            }
            f(word(&len));
        }
    }

    /// Saupe's string rewriting: builds the word level by level, then calls
    /// `f(index, symbol id)` for each symbol of the final one, in order.
    fn bfs_each(&self, depth: u32, mut f: impl FnMut(usize, u32)) {
        if self.chars.len() <= 256 {
            for (i, s) in self.rewrite::<u8>(depth).into_iter().enumerate() {
                f(i, u32::from(s));
            }
        } else {
            for (i, s) in self.rewrite::<u32>(depth).into_iter().enumerate() {
                f(i, s);
            }
        }
    }

    fn rewrite<S: SymId>(&self, depth: u32) -> Vec<S> {
        let succ: Vec<Option<Vec<S>>> = self
            .succ
            .iter()
            .map(|s| {
                s.as_ref()
                    .map(|w| w.iter().map(|&c| S::from_id(c)).collect())
            })
            .collect();
        let mut word: Vec<S> = self.axiom.iter().map(|&c| S::from_id(c)).collect();
        for _ in 0..depth {
            let mut next = Vec::with_capacity(word.len());
            for &s in &word {
                match &succ[s.id() as usize] {
                    Some(w) => next.extend_from_slice(w),
                    None => next.push(s),
                }
            }
            word = next;
        }
        word
    }
}

/// A compact symbol id for the `bfs` word.
trait SymId: Copy {
    fn from_id(id: u32) -> Self;
    fn id(self) -> u32;
}

impl SymId for u8 {
    fn from_id(id: u32) -> Self {
        id as u8
    }
    fn id(self) -> u32 {
        u32::from(self)
    }
}

impl SymId for u32 {
    fn from_id(id: u32) -> Self {
        id
    }
    fn id(self) -> u32 {
        self
    }
}

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
trait Unit: Copy {
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

/// How one `(symbol, remaining depth)` is produced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Entry {
    /// Precomputed: `pool[start..end]`, `syms` symbols of the word.
    Macro { start: u32, end: u32, syms: u64 },
    /// Executed through `plans[id]`.
    Plan(u32),
}

/// One step of a plan.
#[derive(Debug, Clone, Copy)]
enum Item {
    /// Execute `pool[start..end]`, which stands for `syms` symbols.
    Run { start: u32, end: u32, syms: u64 },
    /// Descend into another plan.
    Call(u32),
}

/// A compiled derivation, see the module documentation.
struct Program<U> {
    pool: Vec<U>,
    plans: Vec<Vec<Item>>,
    root: u32,
}

impl<U: Unit> Program<U> {
    fn compile(alpha: &Alphabet, depth: u32) -> Self {
        let n = alpha.chars.len();
        let mut pool: Vec<U> = Vec::new();
        let mut plans: Vec<Vec<Item>> = Vec::new();
        // Terminal code of every symbol (what it is at 0 remaining steps).
        let mut terminal: Vec<Entry> = Vec::with_capacity(n);
        for &c in &alpha.chars {
            let start = pool.len() as u32;
            let mut code = Vec::new();
            U::terminal(c, &mut code);
            pool.extend_from_slice(&code);
            terminal.push(Entry::Macro {
                start,
                end: pool.len() as u32,
                syms: 1,
            });
        }
        // `prev[s]`: the entry of (s, r - 1) while level r is compiled.
        let mut prev = terminal.clone();
        // The row before `prev`, to spot expansions that stopped changing.
        let mut prev2: Option<Vec<Entry>> = None;
        let mut scratch: Vec<U> = Vec::new();
        // Saturating lengths of every symbol's expansion at the level before.
        let mut len_prev = vec![1u64; n];
        for _ in 0..depth {
            let lens_r: Vec<u64> = (0..n)
                .map(|s| match &alpha.succ[s] {
                    Some(succ) => succ
                        .iter()
                        .fold(0u64, |a, &c| a.saturating_add(len_prev[c as usize])),
                    None => 1,
                })
                .collect();
            let mut row = Vec::with_capacity(n);
            for s in 0..n {
                let Some(succ) = &alpha.succ[s] else {
                    row.push(terminal[s]);
                    continue;
                };
                // Same children as one level up: the same expansion.
                if let Some(p2) = &prev2 {
                    if succ.iter().all(|&c| prev[c as usize] == p2[c as usize]) {
                        row.push(prev[s]);
                        continue;
                    }
                }
                // A macro if every child is one and the whole fits.
                let all_macros = succ
                    .iter()
                    .all(|&c| matches!(prev[c as usize], Entry::Macro { .. }));
                if all_macros {
                    scratch.clear();
                    let mut fits = true;
                    for &c in succ {
                        if let Entry::Macro { start, end, .. } = prev[c as usize] {
                            let size = scratch.len() + (end - start) as usize;
                            if size > MACRO_CAP || pool.len() + size > POOL_CAP {
                                fits = false;
                                break;
                            }
                            let piece = pool[start as usize..end as usize].to_vec();
                            U::append(&mut scratch, &piece);
                        }
                    }
                    if fits {
                        let start = pool.len() as u32;
                        pool.extend_from_slice(&scratch);
                        row.push(Entry::Macro {
                            start,
                            end: pool.len() as u32,
                            syms: lens_r[s],
                        });
                        continue;
                    }
                }
                let items = plan_items(succ, &prev, &mut pool);
                plans.push(items);
                row.push(Entry::Plan(plans.len() as u32 - 1));
            }
            // A level equal to the one before repeats for ever: the
            // remaining levels would compile to the same row.
            let stationary = row == prev;
            prev2 = Some(std::mem::replace(&mut prev, row));
            len_prev = lens_r;
            if stationary {
                break;
            }
        }
        let root = plan_items(&alpha.axiom, &prev, &mut pool);
        plans.push(root);
        Program {
            pool,
            root: plans.len() as u32 - 1,
            plans,
        }
    }

    /// Executes the program with an explicit stack, handing each run of
    /// units to `exec`.
    fn run(&self, mut exec: impl FnMut(&[U]), progress: &mut dyn Progress) {
        let mut stack: Vec<(u32, u32)> = vec![(self.root, 0)];
        let mut done = 0u64;
        let mut next_report = PROGRESS_STEP;
        while let Some(top) = stack.last_mut() {
            let plan = &self.plans[top.0 as usize];
            let Some(&item) = plan.get(top.1 as usize) else {
                stack.pop();
                continue;
            };
            top.1 += 1;
            match item {
                Item::Run { start, end, syms } => {
                    exec(&self.pool[start as usize..end as usize]);
                    done = done.saturating_add(syms);
                    if done >= next_report {
                        progress.update(done);
                        next_report = done.saturating_add(PROGRESS_STEP);
                    }
                }
                Item::Call(p) => stack.push((p, 0)),
            }
        }
    }
}

/// The items of a plan for the word `children`, each at the level `prev`
/// describes: short child macros merged into glue runs, long ones
/// referenced, plans called.
fn plan_items<U: Unit>(children: &[u32], prev: &[Entry], pool: &mut Vec<U>) -> Vec<Item> {
    let mut items = Vec::new();
    let mut glue: Vec<U> = Vec::new();
    let mut glue_syms = 0u64;
    let flush = |glue: &mut Vec<U>, syms: &mut u64, pool: &mut Vec<U>, items: &mut Vec<Item>| {
        if *syms > 0 {
            let start = pool.len() as u32;
            pool.extend_from_slice(glue);
            if !glue.is_empty() {
                items.push(Item::Run {
                    start,
                    end: pool.len() as u32,
                    syms: *syms,
                });
            } else if let Some(Item::Run { syms: s, .. }) = items.last_mut() {
                // Inert symbols only: count them with the previous run.
                *s = s.saturating_add(*syms);
            } else {
                items.push(Item::Run {
                    start,
                    end: start,
                    syms: *syms,
                });
            }
            glue.clear();
            *syms = 0;
        }
    };
    for &c in children {
        match prev[c as usize] {
            Entry::Macro { start, end, syms } if (end - start) as usize <= GLUE_CAP => {
                let piece = pool[start as usize..end as usize].to_vec();
                U::append(&mut glue, &piece);
                glue_syms = glue_syms.saturating_add(syms);
            }
            Entry::Macro { start, end, syms } => {
                flush(&mut glue, &mut glue_syms, pool, &mut items);
                items.push(Item::Run { start, end, syms });
            }
            Entry::Plan(p) => {
                flush(&mut glue, &mut glue_syms, pool, &mut items);
                items.push(Item::Call(p));
            }
        }
    }
    flush(&mut glue, &mut glue_syms, pool, &mut items);
    items
}

/// Directions cached for headings `-DIR_OFFSET..DIR_OFFSET`.
const DIR_OFFSET: i64 = 1 << 12;

/// The `dfs` turtle: [`Interp`]'s state and arithmetic, for [`FastOp`]s.
///
/// The step vector of the current heading, `dir * len`, is kept in locals
/// and looked up again only after a turn or a pop: `x + dx * len` is
/// computed as `x + step_x` with `step_x = dx * len` taken from a table of
/// the very same products (and `(-dx) * len == -(dx * len)` exactly for a
/// flipped turtle), so positions are bit-identical to [`Interp`]'s.
struct Exec<T: Turtle> {
    x: f64,
    y: f64,
    k: i64,
    flip: bool,
    stack: Vec<Saved>,
    len: f64,
    headings: Headings,
    /// `steps[k + DIR_OFFSET]`: [`Headings::dir`]`(k, false)` times `len`,
    /// NaN until first needed.
    steps: Vec<(f64, f64)>,
    turtle: T,
}

/// A `[`: the state and its step vector.
#[derive(Clone, Copy)]
struct Saved {
    x: f64,
    y: f64,
    k: i64,
    flip: bool,
    sx: f64,
    sy: f64,
}

impl<T: Turtle> Exec<T> {
    fn new(turtle: T, headings: Headings, len: f64) -> Self {
        Exec {
            x: 0.0,
            y: 0.0,
            k: 0,
            flip: false,
            stack: Vec::new(),
            len,
            headings,
            steps: vec![(f64::NAN, f64::NAN); 2 * DIR_OFFSET as usize],
            turtle,
        }
    }

    /// `dir(k, flip) * len`, with the products [`Interp`] computes.
    #[inline(always)]
    fn step(&mut self, k: i64, flip: bool) -> (f64, f64) {
        let i = k.wrapping_add(DIR_OFFSET) as u64;
        let (sx, sy) = match self.steps.get(i as usize) {
            Some(&(sx, sy)) if !sx.is_nan() => (sx, sy),
            _ => self.step_slow(k),
        };
        if flip { (-sx, -sy) } else { (sx, sy) }
    }

    #[cold]
    #[inline(never)]
    fn step_slow(&mut self, k: i64) -> (f64, f64) {
        let (dx, dy) = self.headings.dir(k, false);
        let s = (dx * self.len, dy * self.len);
        let i = k.wrapping_add(DIR_OFFSET) as u64;
        if let Some(slot) = self.steps.get_mut(i as usize) {
            *slot = s;
        }
        s
    }

    #[inline]
    fn run(&mut self, ops: &[FastOp]) {
        let (mut x, mut y, mut k, mut flip) = (self.x, self.y, self.k, self.flip);
        let (mut sx, mut sy) = self.step(k, flip);
        for &op in ops {
            match op {
                FastOp::Draw(n) => {
                    for _ in 0..n {
                        // Interp::forward: pos + dir * len.
                        let to = Point::new(x + sx, y + sy);
                        self.turtle.segment(Segment {
                            from: Point::new(x, y),
                            to,
                            order: 0,
                        });
                        x = to.x;
                        y = to.y;
                    }
                }
                FastOp::Move(n) => {
                    for _ in 0..n {
                        x += sx;
                        y += sy;
                    }
                }
                FastOp::Turn(n, f) => {
                    k = k.wrapping_add(n);
                    flip ^= f;
                    (sx, sy) = self.step(k, flip);
                }
                FastOp::Push => self.stack.push(Saved {
                    x,
                    y,
                    k,
                    flip,
                    sx,
                    sy,
                }),
                FastOp::Pop => {
                    if let Some(s) = self.stack.pop() {
                        (x, y, k, flip, sx, sy) = (s.x, s.y, s.k, s.flip, s.sx, s.sy);
                    }
                }
                FastOp::Leaf { turn, flip: f, n } => {
                    let (bx, by) = self.step(k.wrapping_add(turn), flip ^ f);
                    let (mut px, mut py) = (x, y);
                    for _ in 0..n {
                        let to = Point::new(px + bx, py + by);
                        self.turtle.segment(Segment {
                            from: Point::new(px, py),
                            to,
                            order: 0,
                        });
                        px = to.x;
                        py = to.y;
                    }
                }
            }
        }
        (self.x, self.y, self.k, self.flip) = (x, y, k, flip);
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
