//! The parametric lines of a `.lsys` file (docs/lsys.md, *Parametric
//! systems*): `define`, `ignore`, `tropism`, `elasticity`, and an axiom or
//! rules with modules, contexts, conditions or `$`.
//!
//! A file that uses none of them ([`uses_parameters`] is false) is read by
//! the classic parser alone, as before. One that does is read twice: the
//! classic parser checks its other keys on a copy with these lines blanked
//! ([`mask`]), and [`parse`] reads them.

use std::collections::{BTreeMap, BTreeSet};

use super::expr::{self, Scope, error, is_boolean};
use super::organs::Line;
use crate::diag::{Diagnostic, Diagnostics, Span};
use crate::model::Loc;
use crate::model::param::{Expr, Formal, MAX_PARAMS, ModuleExpr, ParamRule, Parametric};

/// The keys only parametric files have.
pub const PARAM_KEYS: [&str; 7] = [
    "define",
    "ignore",
    "tropism",
    "elasticity",
    "palette",
    "width_decay",
    "surface",
];

/// One line of the file: its key, the text after it, and where that text
/// starts (comments cut off).
fn lines(text: &str) -> Vec<Line<'_>> {
    let mut out = Vec::new();
    let mut start = 0;
    for raw in text.split_inclusive('\n') {
        let end = start + raw.trim_end_matches(['\n', '\r']).len();
        let body = &text[start..end];
        let body = &body[..body.find('#').unwrap_or(body.len())];
        let lead = body.len() - body.trim_start().len();
        let trimmed = body.trim_start();
        let key_len = trimmed
            .find(|c: char| c.is_whitespace())
            .unwrap_or(trimmed.len());
        let key = &trimmed[..key_len];
        let rest = &trimmed[key_len..];
        out.push(Line {
            key,
            rest,
            at: start + lead + key_len,
            start,
            end,
        });
        start += raw.len();
    }
    out
}

/// Whether a word has a module with parameters or `$`.
fn word_is_parametric(w: &str) -> bool {
    w.contains('(') || w.contains('$') || super::organs::word_uses_organs(w)
}

/// Splits a rule's text after `rule` into head and successor: at `->`, or
/// the classic way (a symbol, an optional `(p)`, `=` or spaces).
fn split_rule(rest: &str) -> (&str, usize, &str, usize) {
    if let Some(k) = rest.find("->") {
        return (&rest[..k], 0, &rest[k + 2..], k + 2);
    }
    let t = rest.trim_start();
    let lead = rest.len() - t.len();
    let first = t.chars().next().map_or(0, char::len_utf8);
    let mut k = lead + first;
    let after = rest[k..].trim_start();
    if after.starts_with('(')
        && let Some(close) = after.find(')')
    {
        k = rest.len() - after.len() + close + 1;
    }
    let tail = rest[k..].trim_start();
    let mut s = rest.len() - tail.len();
    if tail.starts_with('=') {
        s += 1;
    }
    (&rest[..k], 0, &rest[s..], s)
}

/// Whether the file uses parameters, contexts, conditions, `define`,
/// `ignore`, tropism, `$`, or colours and organs (section 13's keys and
/// symbols): then it is parametric.
pub fn uses_parameters(text: &str) -> bool {
    lines(text).iter().any(|l| match l.key {
        k if PARAM_KEYS.contains(&k) => true,
        "axiom" => word_is_parametric(l.rest),
        "rule" => {
            let (head, _, succ, _) = split_rule(l.rest);
            let head_t = head.trim();
            word_is_parametric(succ)
                || head_t.contains(['<', '>', ':'])
                || head_t
                    .char_indices()
                    .skip(1)
                    .any(|(i, c)| c == '(' && !head_t[..i].ends_with(char::is_whitespace))
        }
        _ => false,
    })
}

/// The file with its parametric lines blanked (same offsets) and the
/// axiom's value replaced by `F`: what the classic parser checks.
pub fn mask(text: &str) -> String {
    let mut out = text.as_bytes().to_vec();
    for l in lines(text) {
        if PARAM_KEYS.contains(&l.key) || l.key == "rule" {
            out[l.start..l.end].fill(b' ');
        } else if l.key == "axiom" && !l.rest.trim().is_empty() {
            out[l.at..l.end].fill(b' ');
            out[l.at + 1] = b'F';
        }
    }
    String::from_utf8(out).unwrap_or_default()
}

/// Reads the parametric lines of `text`.
pub fn parse(text: &str) -> Result<Parametric, Diagnostics> {
    let mut diags = Diagnostics::new();
    let mut p = Parametric::default();
    let mut defines: Vec<(String, f64)> = Vec::new();
    let all = lines(text);
    let no_formals: Vec<String> = Vec::new();
    for l in all.iter().filter(|l| l.key == "define") {
        match define(l, &defines) {
            Ok((name, v)) => {
                defines.push((name.clone(), v));
                p.defines.push((name, v, Loc(l.start..l.end)));
            }
            Err(d) => diags.push(*d),
        }
    }
    let scope = Scope {
        formals: &no_formals,
        defines: &defines,
    };
    let mut heads: Vec<Span> = Vec::new();
    for l in &all {
        let r = match l.key {
            "ignore" => {
                p.ignore = l.rest.chars().filter(|c| !c.is_whitespace()).collect();
                Ok(())
            }
            "tropism" => numbers(l, &scope, 3).map(|v| p.tropism = Some([v[0], v[1], v[2]])),
            "elasticity" => numbers(l, &scope, 1).map(|v| p.elasticity = v[0]),
            "axiom" => super::organs::braces(l.rest, l.at)
                .and_then(|b| {
                    first_brace(&mut p, b);
                    word(l.rest, l.at, &scope)
                })
                .and_then(|w| balanced(w, l.at..l.end))
                .map(|w| p.axiom = w),
            "rule" => {
                let (_, _, succ, soff) = split_rule(l.rest);
                super::organs::braces(succ, l.at + soff)
                    .and_then(|b| {
                        first_brace(&mut p, b);
                        rule(l, &defines)
                    })
                    .map(|(r, head)| {
                        p.rules.push(r);
                        heads.push(head);
                    })
            }
            "palette" | "width_decay" | "surface" => {
                super::organs::line(text, l, &scope, word, &mut p.organs)
            }
            _ => Ok(()),
        };
        if let Err(d) = r {
            diags.push(*d);
        }
    }
    super::organs::cycles(&p.organs, &mut diags);
    if diags.is_empty() {
        arities(&p, &heads, &mut diags);
        probabilities(&p, &heads, &mut diags);
    }
    diags.into_result(p)
}

/// Keeps where the file's first `{` is.
fn first_brace(p: &mut Parametric, at: Option<usize>) {
    if let Some(k) = at
        && p.organs.first_polygon.is_none()
    {
        p.organs.first_polygon = Some(Loc(k..k + 1));
    }
}

fn define(l: &Line, defines: &[(String, f64)]) -> Result<(String, f64), Box<Diagnostic>> {
    let t = l.rest.trim_start();
    let at = l.at + l.rest.len() - t.len();
    let n = t.find(char::is_whitespace).unwrap_or(t.len());
    let name = &t[..n];
    let valid = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !valid {
        return Err(error(
            format!("`{name}` is not a name for a constant"),
            at..at + n.max(1),
            "write `define NAME VALUE`: a name of letters, digits and `_`, starting with a letter",
        ));
    }
    if crate::model::param::FUNCS
        .iter()
        .any(|(f, _, _)| *f == name)
    {
        return Err(error(
            format!("`{name}` is a function"),
            at..at + n,
            "give the constant another name",
        ));
    }
    let no: Vec<String> = Vec::new();
    let scope = Scope {
        formals: &no,
        defines,
    };
    let e = expr::parse(&t[n..], at + n, &scope)?;
    let v = crate::model::param::eval_const(&e);
    if !v.is_finite() {
        return Err(error(
            format!("`{name}` is not a finite number ({v})"),
            at..at + t.len(),
            "check for a division by zero or an overflow",
        ));
    }
    Ok((name.to_string(), v))
}

fn numbers(l: &Line, scope: &Scope, n: usize) -> Result<Vec<f64>, Box<Diagnostic>> {
    let t = l.rest.trim_start();
    let mut at = l.at + l.rest.len() - t.len();
    let mut out = Vec::new();
    for part in t.split_whitespace() {
        let off = text_offset(t, part);
        let e = expr::parse(part, at + off, scope)?;
        out.push(crate::model::param::eval_const(&e));
    }
    at = l.at;
    if out.len() != n || out.iter().any(|v| !v.is_finite()) {
        return Err(error(
            format!("`{}` takes {n} number(s)", l.key),
            at..l.end,
            if n == 3 {
                "write `tropism TX TY TZ`, e.g. `tropism 0 1 0` (down the canvas: gravity)"
            } else {
                "write `elasticity E`, e.g. `elasticity 0.22`"
            },
        ));
    }
    Ok(out)
}

fn text_offset(whole: &str, part: &str) -> usize {
    part.as_ptr() as usize - whole.as_ptr() as usize
}

/// The parenthesised arguments starting at byte `open` of `s` (a `(`):
/// each argument's text and offset, and the index after the `)`.
/// The arguments of a module: each one's text and offset, and the index
/// after the `)`.
type Args<'a> = (Vec<(&'a str, usize)>, usize);

fn args(s: &str, open: usize, at: usize) -> Result<Args<'_>, Box<Diagnostic>> {
    let b = s.as_bytes();
    let (mut depth, mut from, mut parts) = (0usize, open + 1, Vec::new());
    for (i, &c) in b.iter().enumerate().skip(open) {
        match c {
            b'(' => depth += 1,
            b')' => {
                depth -= 1;
                if depth == 0 {
                    parts.push((&s[from..i], from));
                    if parts.len() > MAX_PARAMS {
                        return Err(error(
                            format!("a module with {} parameters", parts.len()),
                            at + open..at + i + 1,
                            format!("a module has at most {MAX_PARAMS} parameters"),
                        ));
                    }
                    return Ok((parts, i + 1));
                }
            }
            b',' if depth == 1 => {
                parts.push((&s[from..i], from));
                from = i + 1;
            }
            _ => {}
        }
    }
    Err(error(
        "a `(` without its `)`",
        at + open..at + s.len(),
        "close the module's parameters: `A(1,2)`",
    ))
}

/// An OD's or BED's `SURFACES` block read with this file's word reader
/// (src/syntax/lsys/organs.rs, `surface_block`).
pub(crate) fn surface_block(
    text: &str,
    at: usize,
    diags: &mut crate::diag::Diagnostics,
) -> (Vec<crate::model::param::Surface>, Vec<String>) {
    super::organs::surface_block(text, at, word, diags)
}

/// A word of modules with parameter expressions (an axiom or successor).
pub(super) fn word(s: &str, at: usize, scope: &Scope) -> Result<Vec<ModuleExpr>, Box<Diagnostic>> {
    let mut out = Vec::new();
    let mut it = s.char_indices().peekable();
    while let Some((i, c)) = it.next() {
        if c.is_whitespace() {
            continue;
        }
        if matches!(c, '(' | ')') {
            return Err(error(
                format!("`{c}` outside a module"),
                at + i..at + i + 1,
                "parameters follow their symbol with no space: `F(1)`",
            ));
        }
        let mut m = ModuleExpr {
            symbol: c,
            args: Vec::new(),
            spans: Vec::new(),
        };
        let next = i + c.len_utf8();
        if s[next..].starts_with('(') {
            let (parts, after) = args(s, next, at)?;
            for (text, off) in parts {
                let e = expr::parse(text, at + off, scope)?;
                let lead = text.len() - text.trim_start().len();
                let span = at + off + lead..at + off + text.trim_end().len().max(lead);
                // Without formals (the axiom) the value is known now.
                if scope.formals.is_empty() {
                    let v = crate::model::param::eval_const(&e);
                    if !v.is_finite() {
                        return Err(error(
                            format!("this parameter is not a finite number ({v})"),
                            span,
                            "check for a division by zero or an overflow",
                        ));
                    }
                }
                m.args.push(e);
                m.spans.push(Loc(span));
            }
            while it.peek().is_some_and(|&(j, _)| j < after) {
                it.next();
            }
        }
        out.push(m);
    }
    Ok(out)
}

/// `w` if its brackets balance, else an error at `span` (the word).
fn balanced(w: Vec<ModuleExpr>, span: Span) -> Result<Vec<ModuleExpr>, Box<Diagnostic>> {
    let mut depth = 0i64;
    for m in &w {
        match m.symbol {
            '[' => depth += 1,
            ']' => depth -= 1,
            _ => {}
        }
        if depth < 0 {
            break;
        }
    }
    if depth != 0 {
        return Err(error(
            "the brackets of this word do not balance",
            span,
            "close every `[` with a `]` in the same word (the axiom, or one successor)",
        ));
    }
    Ok(w)
}

/// A word of modules with formal parameters (a predecessor or context);
/// their names are appended to `names`.
fn formals(s: &str, at: usize, names: &mut Vec<String>) -> Result<Vec<Formal>, Box<Diagnostic>> {
    let t = s.trim();
    if t == "*" {
        return Ok(Vec::new());
    }
    let mut out = Vec::new();
    let mut it = s.char_indices().peekable();
    while let Some((i, c)) = it.next() {
        if c.is_whitespace() {
            continue;
        }
        let mut f = Formal {
            symbol: c,
            arity: 0,
        };
        let next = i + c.len_utf8();
        if s[next..].starts_with('(') {
            let (parts, after) = args(s, next, at)?;
            for (text, off) in parts {
                let name = text.trim();
                let valid = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
                    && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
                let span = at + off..at + off + text.len().max(1);
                if !valid {
                    let help = if name.parse::<f64>().is_ok() {
                        format!(
                            "a probability follows the predecessor after a space: `rule {c} ({name}) -> ...`; \
                             `{c}(x)` names {c}'s parameters"
                        )
                    } else {
                        "a rule's head names its parameters, `A(l,w)`; compute in the successor or the condition"
                            .to_string()
                    };
                    return Err(error(
                        format!("`{name}` is not a formal parameter"),
                        span,
                        help,
                    ));
                }
                if names.iter().any(|n| n == name) {
                    return Err(error(
                        format!("`{name}` is named twice in this rule's head"),
                        span,
                        "give each formal parameter its own name",
                    ));
                }
                names.push(name.to_string());
                f.arity += 1;
            }
            while it.peek().is_some_and(|&(j, _)| j < after) {
                it.next();
            }
        }
        out.push(f);
    }
    Ok(out)
}

/// Finds `c` in `s` outside parentheses.
fn top_level(s: &str, c: u8) -> Option<usize> {
    let mut depth = 0i32;
    for (i, &b) in s.as_bytes().iter().enumerate() {
        match b {
            b'(' => depth += 1,
            b')' => depth -= 1,
            _ if b == c && depth == 0 => return Some(i),
            _ => {}
        }
    }
    None
}

/// One `rule` line, and its head's span.
fn rule(l: &Line, defines: &[(String, f64)]) -> Result<(ParamRule, Span), Box<Diagnostic>> {
    let (head, hoff, succ, soff) = split_rule(l.rest);
    let hat = l.at + hoff;
    let head_span = hat + (head.len() - head.trim_start().len())..hat + head.trim_end().len();
    let (head, cond) = match top_level(head, b':') {
        Some(k) => (&head[..k], Some((&head[k + 1..], hat + k + 1))),
        None => (head, None),
    };
    // The probability: a `(` after whitespace, outside a module.
    let mut probability = None;
    let mut rest = head;
    if let Some(k) = head
        .char_indices()
        .find(|&(i, c)| c == '(' && i > 0 && head[..i].ends_with(char::is_whitespace))
        .map(|(i, _)| i)
    {
        let (parts, after) = args(head, k, hat)?;
        if parts.len() != 1 || !head[after..].trim().is_empty() {
            return Err(error(
                "a rule's probability is one `(p)` after its predecessor and right context",
                hat + k..hat + head.len(),
                "write `rule A(x) (0.5) : x > 1 -> ...`",
            ));
        }
        probability = Some(parts[0]);
        rest = &head[..k];
    }
    let mut names = Vec::new();
    let (lc, pred_text, pred_at) = match top_level(rest, b'<') {
        Some(k) => (Some((&rest[..k], hat)), &rest[k + 1..], hat + k + 1),
        None => (None, rest, hat),
    };
    let left = match lc {
        Some((t, a)) => formals(t, a, &mut names)?,
        None => Vec::new(),
    };
    let (pred_text, rc) = match top_level(pred_text, b'>') {
        Some(k) => (
            &pred_text[..k],
            Some((&pred_text[k + 1..], pred_at + k + 1)),
        ),
        None => (pred_text, None),
    };
    let pred = formals(pred_text, pred_at, &mut names)?;
    if pred.len() != 1 {
        return Err(error(
            format!(
                "a rule rewrites one module, but `{}` is {}",
                pred_text.trim(),
                pred.len()
            ),
            pred_at..pred_at + pred_text.len().max(1),
            "write `rule LEFT < A(x) > RIGHT : CONDITION -> SUCCESSOR`",
        ));
    }
    let right = match rc {
        Some((t, a)) => formals(t, a, &mut names)?,
        None => Vec::new(),
    };
    let scope = Scope {
        formals: &names,
        defines,
    };
    let probability = probability
        .map(|(t, off)| expr::parse(t, hat + off, &scope))
        .transpose()?;
    let condition = match cond {
        Some((t, _)) if t.trim() == "*" => None,
        Some((t, a)) => {
            let e = expr::parse(t, a, &scope)?;
            if !is_boolean(&e) {
                let lead = t.len() - t.trim_start().len();
                return Err(error(
                    format!("a condition is a comparison, not `{}`", t.trim()),
                    a + lead..a + t.trim_end().len(),
                    format!(
                        "write `{} != 0` to apply the rule where it is not zero",
                        t.trim()
                    ),
                ));
            }
            Some(e)
        }
        None => None,
    };
    let successor = balanced(word(succ, l.at + soff, &scope)?, l.at + soff..l.end)?;
    Ok((
        ParamRule {
            left,
            pred: pred[0],
            right,
            probability,
            condition,
            successor,
            loc: Loc(l.start..l.end),
        },
        head_span,
    ))
}

/// A rule whose predecessor has a number of parameters no module of its
/// symbol is made with (in the axiom or a successor) can never apply:
/// an error that says how many the symbol has.
fn arities(p: &Parametric, heads: &[Span], diags: &mut Diagnostics) {
    // The modules the axiom makes and, to a fixed point, the successors
    // of the rules that can apply to them.
    let mut reach: BTreeSet<(char, usize)> =
        p.axiom.iter().map(|m| (m.symbol, m.args.len())).collect();
    loop {
        let before = reach.len();
        for r in &p.rules {
            if reach.contains(&(r.pred.symbol, r.pred.arity)) {
                reach.extend(r.successor.iter().map(|m| (m.symbol, m.args.len())));
            }
        }
        if reach.len() == before {
            break;
        }
    }
    let mut made: BTreeMap<char, BTreeSet<usize>> = BTreeMap::new();
    for (c, n) in reach {
        made.entry(c).or_default().insert(n);
    }
    for (r, head) in p.rules.iter().zip(heads) {
        let f = r.pred;
        if let Some(ns) = made.get(&f.symbol)
            && !ns.contains(&f.arity)
        {
            let list: Vec<String> = ns.iter().map(usize::to_string).collect();
            diags.push(*error(
                format!(
                    "`{}` is made with {} parameter(s), but this rule's predecessor has {}: it never applies",
                    f.symbol,
                    list.join(" or "),
                    f.arity
                ),
                head.clone(),
                "give the predecessor as many formal parameters as the modules it should rewrite",
            ));
        }
    }
}

/// The constant probabilities of alternatives with neither context nor
/// condition, per predecessor: each above 0, together 1.
fn probabilities(p: &Parametric, heads: &[Span], diags: &mut Diagnostics) {
    let mut groups: BTreeMap<(char, usize), Vec<(f64, Span)>> = BTreeMap::new();
    for (r, head) in p.rules.iter().zip(heads) {
        if let (Some(Expr::Num(q)), false, None) = (&r.probability, r.has_context(), &r.condition) {
            groups
                .entry((r.pred.symbol, r.pred.arity))
                .or_default()
                .push((*q, head.clone()));
        }
    }
    for ((c, _), alts) in groups {
        let qs: Vec<f64> = alts.iter().map(|a| a.0).collect();
        if let Err(e) = crate::choice::check(&qs) {
            let msg = match e {
                crate::choice::BadProbabilities::NotPositive(i) => {
                    format!(
                        "the probability {} of a rule for `{c}` is not above 0",
                        qs[i]
                    )
                }
                crate::choice::BadProbabilities::Sum(s) => {
                    format!("the probabilities of `{c}`'s rules sum to {s}, not 1")
                }
            };
            diags.push(*error(
                msg,
                alts[0].1.clone(),
                "alternatives without context or condition are chosen with these weights: make them sum to 1",
            ));
        }
    }
}
