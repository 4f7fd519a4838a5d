//! Derivation of parametric L-systems (docs/lsys.md, *Parametric
//! systems*): modules with real parameters, rules with contexts,
//! conditions and probabilities.
//!
//! A word is a [`Word`]: symbols, their parameters in one flat array, and
//! each module's choice key ([`crate::choice::Key`]: the axiom's `i`-th
//! module has `root(seed).child(i)`, the `j`-th module of a successor
//! `k.child(j)`, a module no rule rewrites `k.child(0)`), so `dfs` and
//! `bfs` choose alike.
//!
//! - **`dfs`** streams a context-free system: one [`Word`] per level (the
//!   successor being walked at that level), never the whole word: memory
//!   O(depth x longest successor).
//! - **`bfs`** rewrites level by level; a system with contexts always
//!   does (a context needs the whole previous word), whatever the order.
//!
//! `turtle.rs` draws the modules; `expand` writes them.

mod lie;
mod memo;
mod memo3;
mod pieces;
mod turtle;

use std::collections::{BTreeMap, HashMap};
use std::io::Write;

use crate::choice::Key;
use crate::diag::{Diagnostic, Diagnostics, Help, Knob, LsysError, io_error};
use crate::interpret::Derivation;
use crate::limits::{Bound, Limits};
use crate::model::Loc;
use crate::model::lsys::LSystem;
use crate::model::param::{ParamRule, Parametric, eval};
pub use memo::{PARAM_NODES, ParamMemo};
pub use memo3::{VIEW_COLORS, ViewMemo};
pub use turtle::{Mark, Turtle3P, draw3_marks};
pub(crate) use turtle::{draw2, draw3};

/// A word of modules.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Word {
    /// Each module's symbol.
    pub syms: Vec<char>,
    /// `off[i]..off[i + 1]`: module `i`'s parameters in `vals`.
    off: Vec<u32>,
    vals: Vec<f64>,
    keys: Vec<Key>,
}

impl Word {
    fn new() -> Word {
        Word {
            off: vec![0],
            ..Word::default()
        }
    }

    fn clear(&mut self) {
        self.syms.clear();
        self.off.truncate(1);
        self.vals.clear();
        self.keys.clear();
    }

    /// Number of modules.
    pub fn len(&self) -> usize {
        self.syms.len()
    }

    /// Whether the word is empty.
    pub fn is_empty(&self) -> bool {
        self.syms.is_empty()
    }

    /// Module `i`'s parameters.
    pub fn params(&self, i: usize) -> &[f64] {
        &self.vals[self.off[i] as usize..self.off[i + 1] as usize]
    }

    fn push(&mut self, sym: char, params: &[f64], key: Key) {
        self.syms.push(sym);
        self.vals.extend_from_slice(params);
        self.off.push(self.vals.len() as u32);
        self.keys.push(key);
    }
}

/// Writes module `sym(params)` as `expand` does: each number in the
/// shortest form that reads back to the same f64, commas, no spaces.
pub fn write_module(out: &mut String, sym: char, params: &[f64]) {
    use std::fmt::Write as _;
    out.push(sym);
    if !params.is_empty() {
        out.push('(');
        for (i, v) in params.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            let _ = write!(out, "{v}");
        }
        out.push(')');
    }
}

/// A parametric system ready to derive.
pub struct Deriver<'a> {
    p: &'a Parametric,
    by_sym: BTreeMap<char, Vec<usize>>,
    seed: u64,
    ignore: Vec<char>,
    /// Whether some rule's successor is empty (a word may shrink).
    erases: bool,
}

/// What bracket each bracket of a word closes or opens (itself when it
/// has none).
fn brackets(w: &Word) -> Vec<u32> {
    let mut m: Vec<u32> = (0..w.len() as u32).collect();
    let mut stack = Vec::new();
    for (i, &c) in w.syms.iter().enumerate() {
        if c == '[' {
            stack.push(i);
        } else if c == ']'
            && let Some(o) = stack.pop()
        {
            m[i] = o as u32;
            m[o] = i as u32;
        }
    }
    for o in stack {
        m[o] = w.len() as u32;
    }
    m
}

impl<'a> Deriver<'a> {
    /// The deriver of `sys`'s parametric part.
    pub fn new(sys: &LSystem, p: &'a Parametric) -> Deriver<'a> {
        let mut by_sym: BTreeMap<char, Vec<usize>> = BTreeMap::new();
        for (i, r) in p.rules.iter().enumerate() {
            by_sym.entry(r.pred.symbol).or_default().push(i);
        }
        Deriver {
            p,
            by_sym,
            seed: sys.seed,
            ignore: p.ignore.clone(),
            erases: p.rules.iter().any(|r| r.successor.is_empty()),
        }
    }

    /// Whether a rule rewrites module `sym(params)` (its contexts not
    /// looked at: for a system without them).
    fn applies(&self, sym: char, params: &[f64]) -> bool {
        let Some(rules) = self.by_sym.get(&sym) else {
            return false;
        };
        let mut w = Word::new();
        w.push(sym, params, Key::root(0));
        let mut bind = Vec::new();
        rules
            .iter()
            .any(|&r| self.matches(&self.p.rules[r], &w, &[], 0, &mut bind))
    }

    /// The axiom as a word.
    fn axiom(&self) -> Word {
        let root = Key::root(self.seed);
        let mut w = Word::new();
        for (i, m) in self.p.axiom.iter().enumerate() {
            let vals: Vec<f64> = m.args.iter().map(|e| eval(e, &[])).collect();
            w.push(m.symbol, &vals, root.child(i as u64));
        }
        w
    }

    /// The left context's modules of `w[i]` for `rule`, bound in reading
    /// order into `bind`; false if they do not match.
    fn left(&self, rule: &ParamRule, w: &Word, br: &[u32], i: usize, bind: &mut Vec<f64>) -> bool {
        let mut j = i as isize - 1;
        let mut found = Vec::with_capacity(rule.left.len());
        for f in rule.left.iter().rev() {
            loop {
                if j < 0 {
                    return false;
                }
                let s = w.syms[j as usize];
                if s == ']' {
                    j = br[j as usize] as isize - 1;
                } else if s == '[' || self.ignore.contains(&s) {
                    j -= 1;
                } else {
                    break;
                }
            }
            let ju = j as usize;
            if w.syms[ju] != f.symbol || w.params(ju).len() != f.arity {
                return false;
            }
            found.push(ju);
            j -= 1;
        }
        for &ju in found.iter().rev() {
            bind.extend_from_slice(w.params(ju));
        }
        true
    }

    /// As [`Deriver::left`], to the right.
    fn right(&self, rule: &ParamRule, w: &Word, br: &[u32], i: usize, bind: &mut Vec<f64>) -> bool {
        let mut j = i + 1;
        for f in &rule.right {
            loop {
                if j >= w.len() {
                    return false;
                }
                let s = w.syms[j];
                if s == '[' {
                    j = br[j] as usize + 1;
                } else if s == ']' {
                    return false;
                } else if self.ignore.contains(&s) {
                    j += 1;
                } else {
                    break;
                }
            }
            if w.syms[j] != f.symbol || w.params(j).len() != f.arity {
                return false;
            }
            bind.extend_from_slice(w.params(j));
            j += 1;
        }
        true
    }

    /// Whether `rule` matches `w[i]`, with its bindings in `bind`.
    fn matches(
        &self,
        rule: &ParamRule,
        w: &Word,
        br: &[u32],
        i: usize,
        bind: &mut Vec<f64>,
    ) -> bool {
        let params = w.params(i);
        if rule.pred.arity != params.len() {
            return false;
        }
        bind.clear();
        if !rule.left.is_empty() && !self.left(rule, w, br, i, bind) {
            return false;
        }
        bind.extend_from_slice(params);
        if !rule.right.is_empty() && !self.right(rule, w, br, i, bind) {
            return false;
        }
        rule.condition.as_ref().is_none_or(|c| eval(c, bind) != 0.0)
    }

    /// Rewrites `w[i]` (generation `generation`) onto `out`.
    fn rewrite(
        &self,
        w: &Word,
        br: &[u32],
        i: usize,
        generation: u32,
        out: &mut Word,
        bind: &mut Vec<f64>,
    ) -> Result<(), Diagnostics> {
        let sym = w.syms[i];
        let key = w.keys[i];
        let Some(rules) = self.by_sym.get(&sym) else {
            out.push(sym, w.params(i), key.child(0));
            return Ok(());
        };
        let mut chosen = None;
        for (n, &r) in rules.iter().enumerate() {
            let rule = &self.p.rules[r];
            if !self.matches(rule, w, br, i, bind) {
                continue;
            }
            let Some(pe) = &rule.probability else {
                chosen = Some(r);
                break;
            };
            // A stochastic alternative: weigh every matching one.
            let mut cands = vec![(r, eval(pe, bind))];
            for &r2 in &rules[n + 1..] {
                let rule2 = &self.p.rules[r2];
                if let Some(pe2) = &rule2.probability
                    && self.matches(rule2, w, br, i, bind)
                {
                    cands.push((r2, eval(pe2, bind)));
                }
            }
            let total: f64 = cands.iter().map(|c| c.1.max(0.0)).sum();
            if !total.is_finite() || total <= 0.0 {
                return Err(self.not_finite(r, generation, "a probability", total, None));
            }
            let mut t = key.unit() * total;
            chosen = Some(cands.last().map_or(r, |c| c.0));
            for (rc, q) in cands {
                t -= q.max(0.0);
                if t < 0.0 {
                    chosen = Some(rc);
                    break;
                }
            }
            break;
        }
        let Some(r) = chosen else {
            out.push(sym, w.params(i), key.child(0));
            return Ok(());
        };
        let rule = &self.p.rules[r];
        // `matches` left the bindings of the chosen rule only if it was
        // the last one tried: bind again.
        self.matches(rule, w, br, i, bind);
        let mut vals: Vec<f64> = Vec::new();
        for (j, m) in rule.successor.iter().enumerate() {
            vals.clear();
            for (k, e) in m.args.iter().enumerate() {
                let v = eval(e, bind);
                if !v.is_finite() {
                    return Err(self.not_finite(
                        r,
                        generation,
                        &format!("a parameter of `{}`", m.symbol),
                        v,
                        m.spans.get(k),
                    ));
                }
                vals.push(v);
            }
            out.push(m.symbol, &vals, key.child(j as u64));
        }
        Ok(())
    }

    /// The error of rule `r` making a value `v` that is not finite, at the
    /// expression that made it (`at`) where it is known, else the rule.
    fn not_finite(
        &self,
        r: usize,
        generation: u32,
        what: &str,
        v: f64,
        at: Option<&Loc>,
    ) -> Diagnostics {
        let (span, label) = match at {
            Some(l) => (l.0.clone(), "this expression"),
            None => (self.p.rules[r].loc.0.clone(), "the rule"),
        };
        Diagnostic::error(LsysError::Param {
            message: format!("this rule made {what} that is not a finite number ({v}) at generation {generation}"),
        })
        .with_span(span)
        .with_label(label)
        .with_help("check the rule's expressions for a division by zero or a growth without bound (add a condition)")
        .into()
    }

    /// Streams the word derived to `depth` to `each(symbol, parameters)`,
    /// at most `limits.max_symbols` modules (and `max_word` held by
    /// `bfs`). Returns the number of modules.
    pub fn each(
        &self,
        depth: u32,
        strategy: Derivation,
        limits: &Limits,
        mut each: impl FnMut(char, &[f64]),
    ) -> Result<u64, Diagnostics> {
        let most = (limits.max_symbols / PARAM_COST).max(1);
        if let Some((generation, work)) = self.precount(depth, most) {
            let what = "modules derived over the generations";
            return Err(over(Bound::Symbols, generation, work, most, what));
        }
        self.each_until(depth, strategy, limits, |c, p| {
            each(c, p);
            true
        })
    }

    /// The modules a context-free system without choices derives over the
    /// generations to `depth`, counted on its distinct modules (equal
    /// modules rewrite alike): the first generation where they pass
    /// `most`, and their number there. So a word that doubles is refused
    /// in a few thousand rewrites, not after deriving `most` modules (30
    /// s). None when the system has contexts or choices, when modules
    /// stop repeating (past [`PRECOUNT`] distinct ones) or when a rewrite
    /// fails (the derivation says where).
    fn precount(&self, depth: u32, most: u64) -> Option<(u32, u64)> {
        if self.p.has_context() || self.p.is_stochastic() {
            return None;
        }
        let mut level = self.axiom();
        let mut mult = vec![1u64; level.len()];
        let (mut one, mut bind, mut work, mut left) = (Word::new(), Vec::new(), 0u64, PRECOUNT);
        for generation in 1..=depth {
            let (mut next, mut next_mult) = (Word::new(), Vec::new());
            let mut index: HashMap<(char, Vec<u64>), usize> = HashMap::new();
            for (i, &times) in mult.iter().enumerate() {
                left = left.checked_sub(1)?;
                one.clear();
                self.rewrite(&level, &[], i, generation, &mut one, &mut bind)
                    .ok()?;
                for j in 0..one.len() {
                    let bits = one.params(j).iter().map(|v| v.to_bits()).collect();
                    let k = *index.entry((one.syms[j], bits)).or_insert_with(|| {
                        next.push(one.syms[j], one.params(j), Key::root(0));
                        next_mult.push(0u64);
                        next_mult.len() - 1
                    });
                    next_mult[k] = next_mult[k].saturating_add(times);
                }
                work = work.saturating_add(times.saturating_mul(one.len() as u64));
            }
            if work > most {
                return Some((generation, work));
            }
            (level, mult) = (next, next_mult);
        }
        None
    }

    /// [`Deriver::each`] until `each` returns false (the modules derived
    /// so far are counted). At most `limits.max_symbols / PARAM_COST`
    /// modules ([`PARAM_COST`]) in the word, and as many written over
    /// all the generations (a word rewritten level by level is scanned
    /// whole at each).
    pub fn each_until(
        &self,
        depth: u32,
        strategy: Derivation,
        limits: &Limits,
        mut each: impl FnMut(char, &[f64]) -> bool,
    ) -> Result<u64, Diagnostics> {
        limits.check_depth(depth)?;
        let most = (limits.max_symbols / PARAM_COST).max(1);
        let mut count = 0u64;
        let mut emit = |w: &Word, i: usize| -> Result<bool, Diagnostics> {
            count += 1;
            if count > most {
                return Err(over(
                    Bound::Symbols,
                    depth,
                    count,
                    most,
                    "modules to derive",
                ));
            }
            Ok(each(w.syms[i], w.params(i)))
        };
        let mut bind = Vec::new();
        // Every module written at every generation counts against the
        // same budget as the word's: a word that grows by a little each
        // generation (Anabaena) is rescanned whole each time, and past
        // generation 1,000 that work, not the last word, is the cost.
        let mut work = 0u64;
        // `ahead`: the modules the generations still to come derive at
        // least (a word rewritten level by level, no rule erasing a
        // module: no word is shorter than the one before), so that
        // Anabaena at depth 2,000 is refused at generation 850, not 1,158.
        let mut worked = |made: usize, generation: u32, ahead: u64| -> Result<(), Diagnostics> {
            work = work.saturating_add(made as u64);
            let least = work.saturating_add(ahead);
            if least > most {
                let what = if ahead == 0 {
                    "modules derived over the generations".to_string()
                } else {
                    format!("modules derived over the generations to depth {depth}, at least")
                };
                return Err(over(Bound::Symbols, generation, least, most, &what));
            }
            Ok(())
        };
        if strategy == Derivation::Bfs || self.p.has_context() {
            let mut w = self.axiom();
            let mut next = Word::new();
            for generation in 1..=depth {
                next.clear();
                let br = if self.p.has_context() {
                    brackets(&w)
                } else {
                    Vec::new()
                };
                for i in 0..w.len() {
                    self.rewrite(&w, &br, i, generation, &mut next, &mut bind)?;
                    let held = next.len().max(next.vals.len()) as u64;
                    if held > limits.max_word {
                        return Err(over(
                            Bound::Word,
                            generation,
                            held,
                            limits.max_word,
                            "modules in one word",
                        ));
                    }
                }
                let ahead = if self.erases {
                    0
                } else {
                    u64::from(depth - generation).saturating_mul(next.len() as u64)
                };
                worked(next.len(), generation, ahead)?;
                std::mem::swap(&mut w, &mut next);
            }
            for i in 0..w.len() {
                if !emit(&w, i)? {
                    break;
                }
            }
            return Ok(count);
        }
        // dfs: one word per level, the successor being walked there.
        let mut levels: Vec<Word> = (0..=depth).map(|_| Word::new()).collect();
        let mut next = vec![0usize; depth as usize + 1];
        levels[0] = self.axiom();
        let mut level = 0usize;
        loop {
            if next[level] == levels[level].len() {
                if level == 0 {
                    break;
                }
                level -= 1;
                continue;
            }
            let i = next[level];
            next[level] += 1;
            if level == depth as usize {
                if !emit(&levels[level], i)? {
                    break;
                }
                continue;
            }
            let (lo, hi) = levels.split_at_mut(level + 1);
            hi[0].clear();
            self.rewrite(&lo[level], &[], i, level as u32 + 1, &mut hi[0], &mut bind)?;
            worked(hi[0].len(), level as u32 + 1, 0)?;
            level += 1;
            next[level] = 0;
        }
        Ok(count)
    }
}

/// What a parametric module costs against `--max-symbols`: expressions
/// evaluated, rules matched, parameters copied, and no compiled program
/// or memo; measured about 15 M modules/s against the compiled classic
/// dfs's 500 M symbols/s, so a parametric derivation may derive a
/// thirtieth of the limit (docs/lsys.md), in about the same time.
pub const PARAM_COST: u64 = 30;

/// The most rewrites [`Deriver::precount`] makes before it gives up.
const PRECOUNT: u32 = 1 << 16;

/// The number of drawn steps (`F`, `G`) of `sys` at `depth`, counted until
/// it passes `most` (then `most + 1`).
pub fn count_steps(
    sys: &LSystem,
    p: &Parametric,
    depth: u32,
    limits: &Limits,
    most: u64,
) -> Result<u64, Diagnostics> {
    let mut n = 0u64;
    Deriver::new(sys, p).each_until(depth, Derivation::Dfs, limits, |c, _| {
        if c == 'F' || c == 'G' {
            n += 1;
        }
        n <= most
    })?;
    Ok(n)
}

fn over(bound: Bound, generation: u32, value: u64, limit: u64, what: &str) -> Diagnostics {
    let help = if bound == Bound::Symbols {
        Help::from(
            "a parametric system is derived and drawn exactly (no level of detail) and may derive \
             a thirtieth of ",
        ) + Help::knob(Knob::Limit(bound), "")
            + format!(
                " ({limit} modules): use a smaller depth, add a condition that stops the growth, or "
            )
            + bound
    } else {
        Help::from(
            "a parametric system is derived exactly: use a smaller depth, add a condition that \
             stops the growth, or ",
        ) + bound
    };
    bound
        .exceeded_by(format!("{what} (at generation {generation})"), value, limit)
        .with_help(help)
        .into()
}

/// The parametric part of `sys`, if it has one.
pub fn of(sys: &LSystem) -> Option<&Parametric> {
    sys.parametric.as_deref()
}

/// `expand` of a parametric system: its modules, then a newline.
pub fn expand(
    sys: &LSystem,
    p: &Parametric,
    depth: u32,
    strategy: Derivation,
    limits: &Limits,
    out: &mut dyn Write,
) -> Result<(), Diagnostics> {
    let d = Deriver::new(sys, p);
    // Counted first, so that a refusal comes before a byte is written.
    d.each(depth, strategy, limits, |_, _| {})?;
    let mut w = std::io::BufWriter::with_capacity(1 << 16, out);
    let mut buf = String::new();
    let mut failed = None;
    d.each(depth, strategy, limits, |s, ps| {
        buf.clear();
        write_module(&mut buf, s, ps);
        if failed.is_none()
            && let Err(e) = w.write_all(buf.as_bytes())
        {
            failed = Some(e);
        }
    })?;
    if failed.is_none()
        && let Err(e) = w.write_all(b"\n").and_then(|()| w.flush())
    {
        failed = Some(e);
    }
    match failed {
        Some(e) => Err(io_error(&e, "writing the derived word").into()),
        None => Ok(()),
    }
}
