//! The compiled `dfs` derivation of an L-system.
//!
//! Every `(symbol, remaining depth)` whose whole expansion is at most
//! [`MACRO_CAP`] units is precomputed once as a *macro* (a slice of the
//! pool); every larger one becomes a *plan*: its successor as runs (child
//! macros referenced, or short ones merged into glue runs) and calls to
//! child plans. [`Program::run`] executes the plans with an explicit stack
//! of `(plan, index)` frames, one per level above the macros, handing each
//! run of units to the executor.

use super::alphabet::{Alphabet, PROGRESS_STEP};
use super::units::Unit;
use crate::progress::Progress;

/// Largest precomputed expansion of one `(symbol, remaining depth)`, in
/// units (ops or bytes). 4096 ops are 64 KiB: a macro stays in L2 cache.
pub const MACRO_CAP: usize = 4096;

/// Child macros up to this size are copied into their parent's glue runs
/// (one run instead of several short ones); larger ones are referenced.
const GLUE_CAP: usize = 64;

/// Macros stop being made once the pool holds this many units (a bound on
/// compile memory for systems whose expansions grow slowly).
const POOL_CAP: usize = 1 << 20;

/// Most plan items and glue units one program may hold (plans are a
/// successor's length each, per level: a 40 MB successor at depth 3 would
/// be 120 M items). Past it, `Program::compile` gives up and the caller
/// streams the word without precomputation (`Alphabet::plain_each`).
/// About 16 bytes each: at most about 64 MB, plus the pool.
pub const PROGRAM_CAP: usize = 1 << 22;

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
pub(super) struct Program<U> {
    pool: Vec<U>,
    plans: Vec<Vec<Item>>,
    /// The entry of every symbol at the full depth: the axiom is streamed
    /// through these, never compiled (it may be as long as the input).
    top: Vec<Entry>,
}

impl<U: Unit> Program<U> {
    /// The program of `alpha` to `depth`, or `None` when its plans would
    /// pass [`PROGRAM_CAP`].
    pub(super) fn compile(alpha: &Alphabet, depth: u32) -> Option<Self> {
        Self::compile_capped(alpha, depth, PROGRAM_CAP)
    }

    /// [`Program::compile`] with a cap of `cap` items.
    fn compile_capped(alpha: &Alphabet, depth: u32, cap: usize) -> Option<Self> {
        let mut items_total = 0usize;
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
                if let Some(p2) = &prev2
                    && succ.iter().all(|&c| prev[c as usize] == p2[c as usize])
                {
                    row.push(prev[s]);
                    continue;
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
                items_total = items_total.saturating_add(items.len());
                if items_total.saturating_add(pool.len().saturating_sub(POOL_CAP)) > cap {
                    return None;
                }
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
        Some(Program {
            pool,
            plans,
            top: prev,
        })
    }

    /// Executes the program for `axiom` with an explicit stack, handing
    /// each run of units to `exec`. The axiom's symbols are taken one by
    /// one (a child macro run directly, a plan called).
    pub(super) fn run(
        &self,
        axiom: &[u32],
        mut exec: impl FnMut(&[U]),
        progress: &mut dyn Progress,
    ) {
        let mut stack: Vec<(u32, u32)> = Vec::new();
        let mut done = 0u64;
        let mut next_report = PROGRESS_STEP;
        for &s in axiom {
            match self.top[s as usize] {
                Entry::Macro { start, end, syms } => {
                    exec(&self.pool[start as usize..end as usize]);
                    done = done.saturating_add(syms);
                    if done >= next_report {
                        progress.update(done);
                        next_report = done.saturating_add(PROGRESS_STEP);
                    }
                }
                Entry::Plan(p) => {
                    stack.push((p, 0));
                    self.run_stack(&mut stack, &mut exec, &mut done, &mut next_report, progress);
                }
            }
        }
    }

    fn run_stack(
        &self,
        stack: &mut Vec<(u32, u32)>,
        exec: &mut impl FnMut(&[U]),
        done: &mut u64,
        next_report: &mut u64,
        progress: &mut dyn Progress,
    ) {
        let (mut d, mut next) = (*done, *next_report);
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
                    d = d.saturating_add(syms);
                    if d >= next {
                        progress.update(d);
                        next = d.saturating_add(PROGRESS_STEP);
                    }
                }
                Item::Call(p) => stack.push((p, 0)),
            }
        }
        (*done, *next_report) = (d, next);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interpret::lsys::FastOp;
    use crate::limits::Limits;

    #[test]
    fn a_program_over_its_cap_is_not_built_and_the_word_streams_the_same() {
        let src = "axiom F[X]+F\nangle 30\nrule F F[+F]F[-F]F\nrule X FX-\n";
        let sys = crate::syntax::lsys::parse(src, &Limits::default()).unwrap();
        let alpha = Alphabet::new(&sys);
        // Depth 6: F at 6 is over MACRO_CAP, so there are plans.
        assert!(Program::<FastOp>::compile_capped(&alpha, 6, 0).is_none());
        let program = Program::<u8>::compile(&alpha, 6).unwrap();
        let mut compiled = Vec::new();
        program.run(
            &alpha.axiom,
            |b| compiled.extend_from_slice(b),
            &mut crate::progress::NoProgress,
        );
        // The fallback streams every symbol, drawing or not; the compiled
        // text has them all too.
        let mut plain = String::new();
        alpha.plain_each(6, |_, s| plain.push(alpha.chars[s as usize]));
        let mut bfs = String::new();
        alpha.bfs_each(6, |_, s| bfs.push(alpha.chars[s as usize]));
        assert_eq!(plain, bfs);
        assert_eq!(String::from_utf8(compiled).unwrap(), bfs);
    }
}
