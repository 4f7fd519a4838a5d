//! `.od` and `.bed` files into [`Description`], names resolved.
//!
//! The grammar (`stl_` section of `grammar.pest`) reads the header, the
//! sections and the layout, but only *tokenises* rule bodies and seeds: a
//! flat list of words, brackets, braces, commas and turn symbols. This file
//! then
//!
//! 1. splits each word (`FR1`, `R1R2R2`) left to right by longest match
//!    against the declared rule names, the leftovers being drawing letters
//!    (`F f L R`); anything else is an unknown rule, with a suggestion;
//! 2. builds bodies and seeds with explicit stacks (no recursion the input
//!    can drive), reporting unbalanced `[ ] { }` at the unmatched one;
//! 3. checks everything the grammar cannot (reserved and duplicate names,
//!    slot counts, sizes, colours, section ends, limits), collecting as many
//!    diagnostics as it can before giving up.
//!
//! It does not check what needs the whole tree (stem orders, derived size):
//! that is [`crate::bed::validate`].

use pest::Parser;
use pest::iterators::Pair;

use super::{GrammarParser, Rule, pest_error, precheck};
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, Span};
use crate::limits::Limits;
use crate::model::{
    Body, BodyItem, Branch, Description, DrawRun, Fixed, Format, Layout, LayoutShape, Loc, Piece,
    Repeat, RuleDef, RuleId, RuleRef, Seed, SeedItem, Shape, Slot, Spelling, StemParams, Term,
};
use crate::num::Linear;

/// Names a rule may not have: the drawing letters, the `I` of `[I n X]`,
/// and the section keywords.
pub const RESERVED: &[&str] = &[
    "F",
    "f",
    "L",
    "R",
    "I",
    "RULE",
    "SEED",
    "ENDSEED",
    "LAYOUT",
    "ENDLAYOUT",
];

/// Parses an Outline Description (`Format::Od`) or a Branch-Expansion
/// Description (`Format::Bed`).
///
/// In a BED a bare rule reference `R1` is stored as the full term with every
/// slot empty (`bare: false`); in an OD it stays a growth point (`bare: true`).
pub fn parse(src: &str, format: Format, limits: &Limits) -> Result<Description, Diagnostics> {
    let src = precheck(src.as_bytes(), limits)?;
    let mut pairs = GrammarParser::parse(Rule::stl_file, src).map_err(|e| {
        pest_error(e).with_help(
            "a description reads: tree name, root `(x, y)`, stem parameters \
             (`L=10(0) B=1(0)`), `RULE` and its rules (`R1: [+F][-F]`), then optional \
             `SEED ... ENDSEED` and `LAYOUT ... ENDLAYOUT` (see docs/language.md)",
        )
    })?;
    let Some(file) = pairs.next() else {
        return Err(Diagnostic::error(ErrorKind::Syntax("empty input".into())).into());
    };
    let mut b = Builder {
        format,
        limits,
        diags: Diagnostics::new(),
        names: Vec::new(),
        branches: Vec::new(),
    };
    let desc = b.file(file);
    b.diags.into_result(desc)
}

/// A user-facing description of a grammar rule of the od/bed section.
pub fn describe_rule(rule: Rule) -> Option<&'static str> {
    Some(match rule {
        Rule::stl_file => "an STL description",
        Rule::stl_tree_name => "a tree name",
        Rule::stl_root => "the root coordinate `(x, y)`",
        Rule::stl_param => "a stem parameter like `L=10(0)`",
        Rule::stl_param_key => "a parameter name",
        Rule::stl_param_dec => "a decrement `(d)`",
        Rule::stl_kw_rule => "`RULE`",
        Rule::stl_kw_seed => "`SEED`",
        Rule::stl_kw_endseed => "`ENDSEED`",
        Rule::stl_kw_layout => "`LAYOUT`",
        Rule::stl_kw_endlayout => "`ENDLAYOUT`",
        Rule::stl_rule_def => "a rule definition like `R1: [+F][-F]`",
        Rule::stl_rule_name => "a rule name",
        Rule::stl_defines => "`:` or `=`",
        Rule::stl_body => "a rule body",
        Rule::stl_token => "a drawing component or rule name",
        Rule::stl_repeat_open => "`[I n`",
        Rule::stl_kw_i => "`I`",
        Rule::stl_open => "`[`",
        Rule::stl_close => "`]`",
        Rule::stl_lbrace => "`{`",
        Rule::stl_rbrace => "`}`",
        Rule::stl_comma => "`,`",
        Rule::stl_sym => "`+`, `-` or `|`",
        Rule::stl_word => "drawing letters or a rule name",
        Rule::stl_seed => "a `SEED` section",
        Rule::stl_seed_body => "the seed",
        Rule::stl_layout => "a `LAYOUT` section",
        Rule::stl_shape_line => "a layout shape like `(clGreen) Rectangle (0,0), 200, 100`",
        Rule::stl_angled => "`<`",
        Rule::stl_colour => "a colour (`clGreen` or `#rrggbb`)",
        Rule::stl_shape => "a shape",
        Rule::stl_shape_name => "a shape name (`Rectangle`, `RoundRect`, `Ellipse`, `Polygon`)",
        Rule::stl_shape_arg => "a shape argument",
        Rule::stl_point_list => "a point `(x, y)`",
        Rule::EOI => "end of input",
        _ => return None,
    })
}

/// One lexical item of a body or seed, words already split.
#[derive(Debug, Clone)]
enum Lex {
    /// A drawing component `F f L R + - |`.
    Draw(char, Span),
    /// `[`.
    Open(Span),
    /// `]`.
    Close(Span),
    /// `{`.
    LBrace(Span),
    /// `}`.
    RBrace(Span),
    /// `,`.
    Comma(Span),
    /// A declared rule's name.
    Name(RuleId, Span),
    /// `[I n` (count already checked; `None` if invalid).
    RepeatOpen(Option<u32>, Span),
}

/// What `[I n ...]` held.
enum RepeatBody {
    /// A rule name: a [`Repeat`].
    Rule(Repeat),
    /// Drawing components: a [`Fixed`] figure.
    Word(Fixed),
    /// Already reported.
    Invalid,
}

/// A run of drawing components being collected.
#[derive(Default)]
struct Run {
    text: String,
    span: Option<Span>,
}

impl Run {
    fn push(&mut self, c: char, span: &Span) {
        self.text.push(c);
        self.span = Some(match self.span.take() {
            Some(s) => s.start..span.end,
            None => span.clone(),
        });
    }

    fn take(&mut self) -> Option<DrawRun> {
        let span = self.span.take()?;
        Some(DrawRun {
            text: std::mem::take(&mut self.text),
            loc: Loc(span),
        })
    }
}

/// A term whose `{` is open.
struct TermFrame {
    /// `None` after a `{` that followed no rule name (already reported).
    rule: Option<RuleId>,
    start: usize,
    open: Span,
    slots: Vec<Option<Slot>>,
    cur: Option<Slot>,
    saw_comma: bool,
}

struct Builder<'l> {
    format: Format,
    limits: &'l Limits,
    diags: Diagnostics,
    /// Declared rule names, by [`RuleId`] (invalid ones as `""`).
    names: Vec<String>,
    /// Branch counts by [`RuleId`].
    branches: Vec<usize>,
}

fn span_of(p: &Pair<'_, Rule>) -> Span {
    let s = p.as_span();
    s.start()..s.end()
}

impl Builder<'_> {
    fn err(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    fn stl(&mut self, msg: impl Into<String>, span: Span, label: &str, help: &str) {
        self.err(
            Diagnostic::error(ErrorKind::Stl(msg.into()))
                .with_span(span)
                .with_label(label)
                .with_help(help),
        );
    }

    // ------------------------------------------------------------- file --

    fn file(&mut self, file: Pair<'_, Rule>) -> Description {
        let mut name = String::new();
        let mut name_loc = Loc::default();
        let mut root = (0.0, 0.0);
        let mut root_loc = Loc::default();
        let mut params = Vec::new();
        let mut defs = Vec::new();
        let mut seed_pair = None;
        let mut layout = None;
        for p in file.into_inner() {
            match p.as_rule() {
                Rule::stl_tree_name => {
                    name = p.as_str().to_string();
                    name_loc = Loc(span_of(&p));
                }
                Rule::stl_root => {
                    root_loc = Loc(span_of(&p));
                    let mut it = p.into_inner();
                    let x = it.next().map_or(0.0, |n| self.number(&n));
                    let y = it.next().map_or(0.0, |n| self.number(&n));
                    root = (x, y);
                }
                Rule::stl_param => params.push(p),
                Rule::stl_rule_def => defs.push(p),
                Rule::stl_seed => seed_pair = Some(p),
                Rule::stl_layout => layout = Some(self.layout(p)),
                _ => {}
            }
        }
        let params = self.params(params, &root_loc);
        let rules = self.rules(defs);
        let seed = seed_pair.map(|p| self.seed(p));
        Description {
            format: self.format,
            name,
            name_loc,
            root,
            root_loc,
            params,
            rules,
            seed,
            layout,
        }
    }

    fn number(&mut self, p: &Pair<'_, Rule>) -> f64 {
        match p.as_str().parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            _ => {
                self.stl(
                    format!("`{}` is not a finite number", p.as_str()),
                    span_of(p),
                    "too large to represent",
                    "write a number of ordinary size",
                );
                0.0
            }
        }
    }

    // ----------------------------------------------------------- header --

    fn params(&mut self, pairs: Vec<Pair<'_, Rule>>, root_loc: &Loc) -> StemParams {
        let mut out = StemParams {
            length: Linear::constant(10.0),
            width: Linear::constant(1.0),
            angle: None,
            clearance: None,
            loc: Loc(root_loc.0.end..root_loc.0.end),
        };
        let mut seen: Vec<(String, Span)> = Vec::new();
        let mut whole: Option<Span> = None;
        for p in pairs {
            let span = span_of(&p);
            whole = Some(whole.map_or(span.clone(), |w| w.start..span.end));
            let mut it = p.into_inner();
            let (Some(key), Some(val)) = (it.next(), it.next()) else {
                continue;
            };
            let dec = it.next();
            let k = key.as_str().to_string();
            let kspan = span_of(&key);
            if let Some((_, first)) = seen.iter().find(|(s, _)| *s == k) {
                let first = first.clone();
                self.err(
                    Diagnostic::error(ErrorKind::Stl(format!("`{k}` is given twice")))
                        .with_span(kspan.clone())
                        .with_label("given again here")
                        .with_note_at(first, "first given here")
                        .with_help("keep one of them"),
                );
                continue;
            }
            seen.push((k.clone(), kspan.clone()));
            let v = self.number(&val);
            let vspan = span_of(&val);
            let d = dec.as_ref().and_then(|d| d.clone().into_inner().next());
            let dv = d.as_ref().map(|d| self.number(d));
            match k.as_str() {
                "L" | "B" => {
                    let what = if k == "L" { "length" } else { "broadness" };
                    if v <= 0.0 {
                        self.stl(
                            format!("the stem {what} `{k}` must be positive"),
                            vspan,
                            "zero or negative",
                            &format!("write a positive {what}, e.g. `{k}=10(0)`"),
                        );
                    }
                    if let (Some(dv), Some(d)) = (dv, &d)
                        && dv < 0.0
                    {
                        self.stl(
                            format!("the decrement of `{k}` must not be negative"),
                            span_of(d),
                            "negative decrement",
                            "stems get shorter and slimmer with order: write a decrement of 0 or more",
                        );
                    }
                    if k == "L" {
                        out.length = Linear::new(v, dv.unwrap_or(0.0));
                    } else {
                        out.width = Linear::new(v, dv.unwrap_or(0.0));
                    }
                }
                "A" | "C" => {
                    if let Some(dec) = &dec {
                        self.stl(
                            format!("`{k}` takes no decrement"),
                            span_of(dec),
                            "not allowed here",
                            &format!("write `{k}=value` without parentheses"),
                        );
                    }
                    if k == "A" {
                        out.angle = Some(v);
                    } else {
                        if v < 0.0 {
                            self.stl(
                                "the clearance `C` must not be negative",
                                vspan,
                                "negative",
                                "write a clearance of 0 or more",
                            );
                        }
                        out.clearance = Some(v);
                    }
                }
                _ => {
                    let sugg = ["L", "B", "A", "C"]
                        .iter()
                        .find(|c| c.eq_ignore_ascii_case(&k))
                        .map(|c| format!("did you mean `{c}`? "))
                        .unwrap_or_default();
                    self.stl(
                        format!("unknown stem parameter `{k}`"),
                        kspan,
                        "not a stem parameter",
                        &format!(
                            "{sugg}the parameters are L (length), B (broadness), A (angle) and C (clearance)"
                        ),
                    );
                }
            }
        }
        if let Some(w) = whole {
            out.loc = Loc(w);
        }
        out
    }

    // ------------------------------------------------------------ rules --

    fn rules(&mut self, defs: Vec<Pair<'_, Rule>>) -> Vec<RuleDef> {
        // First pass: names, so bodies and the seed may refer to any rule.
        let mut heads = Vec::new();
        for d in &defs {
            let mut it = d.clone().into_inner();
            let Some(n) = it.next() else { continue };
            let name = n.as_str().to_string();
            let span = span_of(&n);
            let mut valid = true;
            if RESERVED.contains(&name.as_str()) {
                valid = false;
                self.stl(
                    format!("`{name}` is reserved and cannot name a rule"),
                    span.clone(),
                    "reserved name",
                    "`F f L R` are drawing components, `I` starts `[I n X]`, and the section keywords are taken: choose another name, e.g. `R1`",
                );
            } else if !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
                valid = false;
                self.stl(
                    format!("rule name `{name}` does not start with a letter"),
                    span.clone(),
                    "not a rule name",
                    "a rule name is a letter followed by letters, digits or `_`, e.g. `R1`",
                );
            } else if let Some(i) = self.names.iter().position(|x| *x == name) {
                valid = false;
                let first: Span = heads
                    .iter()
                    .find_map(|(j, s): &(usize, Span)| (*j == i).then(|| s.clone()))
                    .unwrap_or(0..0);
                self.err(
                    Diagnostic::error(ErrorKind::Stl(format!("rule `{name}` is defined twice")))
                        .with_span(span.clone())
                        .with_label("defined again here")
                        .with_note_at(first, "first defined here")
                        .with_help("rename one of them or merge their bodies"),
                );
            }
            heads.push((self.names.len(), span));
            self.names.push(if valid { name } else { String::new() });
        }
        let mut bodies = Vec::new();
        for d in &defs {
            let body = d
                .clone()
                .into_inner()
                .find(|p| p.as_rule() == Rule::stl_body);
            if body.is_none() {
                let at = d
                    .clone()
                    .into_inner()
                    .find(|p| p.as_rule() == Rule::stl_defines)
                    .map_or(span_of(d).end, |p| span_of(&p).end);
                self.err(
                    Diagnostic::error(ErrorKind::Syntax("expected a rule body".into()))
                        .with_span(at..at)
                        .with_label("the rule ends here")
                        .with_help("write what the rule draws, e.g. `R1: [+F][-F]`"),
                );
            }
            let lex = body.map(|b| self.lex(b)).unwrap_or_default();
            bodies.push(lex);
        }
        let mut out = Vec::new();
        for (d, lex) in defs.iter().zip(bodies) {
            let mut it = d.clone().into_inner();
            let n = it.next();
            let body = self.body(&lex);
            let name = n
                .as_ref()
                .map(|n| n.as_str().to_string())
                .unwrap_or_default();
            let name_loc = Loc(n.as_ref().map(span_of).unwrap_or(0..0));
            out.push(RuleDef {
                name,
                name_loc,
                body,
                loc: Loc(span_of(d)),
            });
        }
        self.branches = out.iter().map(RuleDef::branch_count).collect();
        out
    }

    // ------------------------------------------------------------ words --

    /// Longest declared rule name that `text` starts with.
    fn longest(&self, text: &str) -> Option<(RuleId, usize)> {
        self.names
            .iter()
            .enumerate()
            .filter(|(_, n)| !n.is_empty() && text.starts_with(n.as_str()))
            .max_by_key(|(i, n)| (n.len(), std::cmp::Reverse(*i)))
            .map(|(i, n)| (RuleId(i), n.len()))
    }

    /// The tokens of a body or seed, words split into drawing letters and
    /// rule names.
    fn lex(&mut self, p: Pair<'_, Rule>) -> Vec<Lex> {
        let mut out = Vec::new();
        for tok in p.into_inner() {
            let Some(t) = tok.into_inner().next() else {
                continue;
            };
            let span = span_of(&t);
            match t.as_rule() {
                Rule::stl_open => out.push(Lex::Open(span)),
                Rule::stl_close => out.push(Lex::Close(span)),
                Rule::stl_lbrace => out.push(Lex::LBrace(span)),
                Rule::stl_rbrace => out.push(Lex::RBrace(span)),
                Rule::stl_comma => out.push(Lex::Comma(span)),
                Rule::stl_sym => {
                    let c = t.as_str().chars().next().unwrap_or('+');
                    out.push(Lex::Draw(c, span));
                }
                Rule::stl_word => self.split_word(t.as_str(), span.start, &mut out),
                Rule::stl_repeat_open => {
                    let count = t.into_inner().find(|x| x.as_rule() == Rule::integer);
                    let n = count.map(|c| self.count(&c));
                    out.push(Lex::RepeatOpen(n.flatten(), span));
                }
                _ => {}
            }
        }
        out
    }

    fn count(&mut self, c: &Pair<'_, Rule>) -> Option<u32> {
        let text = c.as_str();
        let limit = self.limits.max_repeat;
        match text.parse::<u32>() {
            Ok(0) => {
                self.stl(
                    "a self-resemblance count must be at least 1",
                    span_of(c),
                    "zero",
                    "write `[I 1 X]` or more, or leave the form out",
                );
                None
            }
            Ok(n) if n <= limit => Some(n),
            _ => {
                self.err(
                    Diagnostic::error(ErrorKind::Limit {
                        what: "self-resemblance count".into(),
                        value: text.trim_start_matches('0').to_string(),
                        limit: limit.to_string(),
                    })
                    .with_span(span_of(c))
                    .with_label("count too large")
                    .with_help("raise the limit with --max-depth N"),
                );
                None
            }
        }
    }

    /// Splits a word left to right by longest match against the declared
    /// rule names; the leftovers must be drawing letters.
    fn split_word(&mut self, word: &str, at: usize, out: &mut Vec<Lex>) {
        let b = word.as_bytes();
        let mut i = 0;
        while i < b.len() {
            if let Some((id, len)) = self.longest(&word[i..]) {
                out.push(Lex::Name(id, at + i..at + i + len));
                i += len;
                continue;
            }
            let c = b[i] as char;
            if matches!(c, 'F' | 'f' | 'L' | 'R') {
                out.push(Lex::Draw(c, at + i..at + i + 1));
                i += 1;
                continue;
            }
            // Not a drawing letter and no rule starts here: the unknown name
            // takes the letter before (`FR3` -> `R3`) and the digits,
            // lower-case letters and `_` after it.
            let mut s = i;
            if i > 0
                && matches!(out.last(), Some(Lex::Draw(c, sp))
                    if sp.start == at + i - 1 && c.is_ascii_uppercase())
            {
                out.pop();
                s = i - 1;
            }
            let mut e = i + 1;
            while e < b.len()
                && (b[e].is_ascii_digit() || b[e] == b'_' || b[e].is_ascii_lowercase())
                && self.longest(&word[e..]).is_none()
            {
                e += 1;
            }
            self.unknown(&word[s..e], at + s..at + e);
            i = e;
        }
    }

    fn unknown(&mut self, name: &str, span: Span) {
        if !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
            self.stl(
                format!("unexpected `{name}`"),
                span,
                "not a drawing component or rule name",
                "numbers stand only in a self-resemblance count `[I n X]`",
            );
            return;
        }
        let best = self
            .names
            .iter()
            .filter(|n| !n.is_empty())
            .map(|n| (strsim::levenshtein(n, name), n))
            .min_by_key(|(d, _)| *d);
        let help = match best {
            Some((d, n)) if d <= name.len().max(2) => {
                format!("did you mean `{n}`? Declared rules: {}", self.declared())
            }
            Some(_) => format!(
                "declare it under RULE (`{name}: [+F][-F]`), or use a declared rule: {}",
                self.declared()
            ),
            None => format!("declare it under RULE, e.g. `{name}: [+F][-F]`"),
        };
        self.err(
            Diagnostic::error(ErrorKind::UnknownRule {
                name: name.to_string(),
            })
            .with_span(span)
            .with_label("no rule has this name")
            .with_help(help),
        );
    }

    fn declared(&self) -> String {
        let v: Vec<&str> = self
            .names
            .iter()
            .filter(|n| !n.is_empty())
            .map(String::as_str)
            .collect();
        v.join(", ")
    }

    // ----------------------------------------------------------- repeat --

    /// Reads `[I n ...]` starting at `lex[i]` (the `RepeatOpen`); returns
    /// what it held and the index after it.
    fn repeat(&mut self, lex: &[Lex], i: usize) -> (RepeatBody, usize) {
        let Lex::RepeatOpen(count, open) = &lex[i] else {
            return (RepeatBody::Invalid, i + 1);
        };
        let mut word = String::new();
        let mut rule: Option<(RuleId, Span)> = None;
        let mut mixed: Option<Span> = None;
        let mut depth = 0usize;
        let mut j = i + 1;
        let end = loop {
            match lex.get(j) {
                Some(Lex::Close(s)) if depth == 0 => break s.end,
                Some(Lex::Close(s)) => {
                    depth -= 1;
                    word.push(']');
                    if rule.is_some() {
                        mixed.get_or_insert(s.clone());
                    }
                }
                Some(Lex::Open(s)) => {
                    depth += 1;
                    word.push('[');
                    if rule.is_some() {
                        mixed.get_or_insert(s.clone());
                    }
                }
                Some(Lex::Draw(c, s)) => {
                    word.push(*c);
                    if rule.is_some() {
                        mixed.get_or_insert(s.clone());
                    }
                }
                Some(Lex::Name(id, s)) => {
                    if rule.is_some() || !word.is_empty() {
                        mixed.get_or_insert(s.clone());
                    }
                    rule = Some((*id, s.clone()));
                }
                None
                | Some(Lex::LBrace(_) | Lex::RBrace(_) | Lex::Comma(_) | Lex::RepeatOpen(..)) => {
                    self.err(
                        Diagnostic::error(ErrorKind::Unbalanced('['))
                            .with_span(open.start..open.start + 1)
                            .with_label("this `[I n` is never closed")
                            .with_help("close it with `]`: `[I 3 R1]` or `[I 2 F[+F]F]`"),
                    );
                    return (RepeatBody::Invalid, j);
                }
            }
            j += 1;
        };
        let span = open.start..end;
        if let Some(m) = mixed {
            self.stl(
                "`[I n X]` takes one rule name or a string of drawing components",
                m,
                "unexpected here",
                "write `[I 3 R1]` for a subtree of R1, or `[I 2 F[+F]F]` for a rewritten figure",
            );
            return (RepeatBody::Invalid, j + 1);
        }
        let Some(count) = *count else {
            return (RepeatBody::Invalid, j + 1);
        };
        let body = match rule {
            Some((rule, _)) => RepeatBody::Rule(Repeat {
                count,
                rule,
                loc: Loc(span),
            }),
            None if word.is_empty() => {
                self.stl(
                    "`[I n X]` needs a rule name or drawing components",
                    span,
                    "nothing to repeat",
                    "write `[I 3 R1]` or `[I 2 F[+F]F]`",
                );
                RepeatBody::Invalid
            }
            None => RepeatBody::Word(Fixed {
                count,
                word,
                loc: Loc(span),
            }),
        };
        (body, j + 1)
    }

    // ------------------------------------------------------------- body --

    fn body(&mut self, lex: &[Lex]) -> Body {
        struct Open {
            open: Span,
            pieces: Vec<Piece>,
            run: Run,
            nested: Vec<Span>,
            successor: Option<RuleRef>,
        }
        let mut items = Vec::new();
        let mut trunk = Run::default();
        let mut br: Option<Open> = None;
        let mut i = 0;
        while i < lex.len() {
            let l = &lex[i];
            // A successor name must be the last thing of its branch.
            if let Some(b) = &mut br
                && b.nested.is_empty()
                && !matches!(l, Lex::Close(_))
                && let Some(s) = b.successor.take()
            {
                self.not_at_end(s.loc.0);
            }
            match l {
                Lex::Draw(c, s) => match &mut br {
                    Some(b) => b.run.push(*c, s),
                    None => trunk.push(*c, s),
                },
                Lex::Open(s) => match &mut br {
                    Some(b) => {
                        b.run.push('[', s);
                        b.nested.push(s.clone());
                    }
                    None => {
                        if let Some(r) = trunk.take() {
                            items.push(BodyItem::Draw(r));
                        }
                        br = Some(Open {
                            open: s.clone(),
                            pieces: Vec::new(),
                            run: Run::default(),
                            nested: Vec::new(),
                            successor: None,
                        });
                    }
                },
                Lex::Close(s) => match &mut br {
                    Some(b) if !b.nested.is_empty() => {
                        b.nested.pop();
                        b.run.push(']', s);
                    }
                    Some(_) => {
                        let Some(mut b) = br.take() else { break };
                        if let Some(r) = b.run.take() {
                            b.pieces.push(Piece::Draw(r));
                        }
                        items.push(BodyItem::Branch(Branch {
                            pieces: b.pieces,
                            successor: b.successor,
                            loc: Loc(b.open.start..s.end),
                        }));
                    }
                    None => self.unbalanced(']', s.clone(), "this `]` closes nothing"),
                },
                Lex::Name(id, s) => match &mut br {
                    Some(b) if b.nested.is_empty() => {
                        b.successor = Some(RuleRef {
                            rule: *id,
                            loc: Loc(s.clone()),
                        })
                    }
                    _ => self.not_at_end(s.clone()),
                },
                Lex::RepeatOpen(..) => {
                    let (what, next) = self.repeat(lex, i);
                    match what {
                        RepeatBody::Word(f) => match &mut br {
                            Some(b) => {
                                if let Some(r) = b.run.take() {
                                    b.pieces.push(Piece::Draw(r));
                                }
                                b.pieces.push(Piece::Fixed(f));
                            }
                            None => {
                                if let Some(r) = trunk.take() {
                                    items.push(BodyItem::Draw(r));
                                }
                                items.push(BodyItem::Fixed(f));
                            }
                        },
                        RepeatBody::Rule(r) => self.stl(
                            "`[I n X]` with a rule cannot stand in a rule body",
                            r.loc.0,
                            "a subtree inside a rule",
                            "name the rule at the end of a branch (`[+F R2]`), or put `[I n R2]` in the seed",
                        ),
                        RepeatBody::Invalid => {}
                    }
                    i = next;
                    continue;
                }
                Lex::LBrace(s) | Lex::RBrace(s) | Lex::Comma(s) => {
                    let c = self_char(l);
                    self.stl(
                        format!("`{c}` cannot stand in a rule body"),
                        s.clone(),
                        "only in the seed",
                        "branch-expansion terms `X{...}` are written in the seed (SEED ... ENDSEED)",
                    );
                }
            }
            i += 1;
        }
        if let Some(b) = br {
            let at = b.nested.last().cloned().unwrap_or(b.open);
            self.unbalanced('[', at, "this `[` is never closed");
        }
        if let Some(r) = trunk.take() {
            items.push(BodyItem::Draw(r));
        }
        Body { items }
    }

    fn not_at_end(&mut self, span: Span) {
        self.stl(
            "a rule name in a rule body must end a branch",
            span,
            "not at the end of a top-level branch",
            "a name in a body says which rule grows at a branch tip: write it last inside a top-level `[...]`, as in `R1: [+F R2][-F]`",
        );
    }

    fn unbalanced(&mut self, c: char, span: Span, label: &str) {
        let help = match c {
            '[' => "add the matching `]`",
            ']' => "remove it or add the matching `[` before it",
            '{' => "add the matching `}` after the term's slots",
            _ => "remove it or add the matching `{` after a rule name",
        };
        self.err(
            Diagnostic::error(ErrorKind::Unbalanced(c))
                .with_span(span)
                .with_label(label)
                .with_help(help),
        );
    }

    // ------------------------------------------------------------- seed --

    fn seed(&mut self, p: Pair<'_, Rule>) -> Seed {
        let span = span_of(&p);
        let mut kw = None;
        let mut closed = false;
        let mut lex = Vec::new();
        for c in p.into_inner() {
            match c.as_rule() {
                Rule::stl_kw_seed => kw = Some(span_of(&c)),
                Rule::stl_kw_endseed => closed = true,
                Rule::stl_seed_body => lex = self.lex(c),
                _ => {}
            }
        }
        if !closed {
            self.err(
                Diagnostic::error(ErrorKind::Stl("`SEED` without `ENDSEED`".into()))
                    .with_span(kw.unwrap_or(span.clone()))
                    .with_label("this section is never closed")
                    .with_help("end the seed with `ENDSEED`"),
            );
        }
        let items = self.seed_items(&lex);
        Seed {
            items,
            loc: Loc(span),
        }
    }

    fn seed_items(&mut self, lex: &[Lex]) -> Vec<SeedItem> {
        let mut items = Vec::new();
        let mut run = Run::default();
        let mut brackets: Vec<Span> = Vec::new();
        let mut stack: Vec<TermFrame> = Vec::new();
        let mut pending: Option<(RuleId, Span)> = None;
        let mut i = 0;
        while i < lex.len() {
            let l = &lex[i];
            if !matches!(l, Lex::LBrace(_))
                && let Some((id, s)) = pending.take()
            {
                let t = self.bare(id, s);
                self.deliver(Slot::Term(t), &mut stack, &mut items, &mut run);
            }
            match l {
                Lex::Name(id, s) => pending = Some((*id, s.clone())),
                Lex::LBrace(s) => {
                    let (rule, start) = match pending.take() {
                        Some((id, ns)) => (Some(id), ns.start),
                        None => {
                            self.stl(
                                "`{` must follow a rule name",
                                s.clone(),
                                "no rule before it",
                                "write the rule whose slots these are before `{`, as in `R1{,}`",
                            );
                            (None, s.start)
                        }
                    };
                    stack.push(TermFrame {
                        rule,
                        start,
                        open: s.clone(),
                        slots: Vec::new(),
                        cur: None,
                        saw_comma: false,
                    });
                }
                Lex::Comma(s) => match stack.last_mut() {
                    Some(f) => {
                        let cur = f.cur.take();
                        f.slots.push(cur);
                        f.saw_comma = true;
                    }
                    None => self.stl(
                        "`,` outside a term",
                        s.clone(),
                        "separates nothing",
                        "commas separate the slots of a term `R1{R1{,},}`",
                    ),
                },
                Lex::RBrace(s) => match stack.pop() {
                    Some(mut f) => {
                        let cur = f.cur.take();
                        f.slots.push(cur);
                        if let Some(rule) = f.rule {
                            let m = self.branches.get(rule.0).copied().unwrap_or(0);
                            if m == 0 && !f.saw_comma && f.slots.len() == 1 && f.slots[0].is_none()
                            {
                                f.slots.clear();
                            }
                            let span = f.start..s.end;
                            if f.slots.len() != m {
                                self.slot_count(rule, f.slots.len(), span.clone());
                            }
                            let t = Term {
                                rule,
                                slots: f.slots,
                                bare: false,
                                loc: Loc(span),
                            };
                            self.deliver(Slot::Term(t), &mut stack, &mut items, &mut run);
                        }
                    }
                    None => self.unbalanced('}', s.clone(), "this `}` closes nothing"),
                },
                Lex::RepeatOpen(..) => {
                    let (what, next) = self.repeat(lex, i);
                    match what {
                        RepeatBody::Rule(r) => {
                            self.deliver(Slot::Repeat(r), &mut stack, &mut items, &mut run)
                        }
                        RepeatBody::Word(f) => {
                            if stack.is_empty() {
                                if let Some(r) = run.take() {
                                    items.push(SeedItem::Draw(r));
                                }
                                items.push(SeedItem::Fixed(f));
                            } else {
                                self.in_slot(f.loc.0);
                            }
                        }
                        RepeatBody::Invalid => {}
                    }
                    i = next;
                    continue;
                }
                Lex::Draw(_, s) | Lex::Open(s) | Lex::Close(s) if !stack.is_empty() => {
                    self.in_slot(s.clone());
                }
                Lex::Draw(c, s) => run.push(*c, s),
                Lex::Open(s) => {
                    brackets.push(s.clone());
                    run.push('[', s);
                }
                Lex::Close(s) => {
                    if brackets.pop().is_some() {
                        run.push(']', s);
                    } else {
                        self.unbalanced(']', s.clone(), "this `]` closes nothing");
                    }
                }
            }
            i += 1;
        }
        if let Some((id, s)) = pending.take() {
            let t = self.bare(id, s);
            self.deliver(Slot::Term(t), &mut stack, &mut items, &mut run);
        }
        for f in stack.iter().rev() {
            self.unbalanced('{', f.open.clone(), "this `{` is never closed");
        }
        for b in brackets.iter().rev() {
            self.unbalanced('[', b.clone(), "this `[` is never closed");
        }
        if let Some(r) = run.take() {
            items.push(SeedItem::Draw(r));
        }
        items
    }

    fn in_slot(&mut self, span: Span) {
        self.stl(
            "drawing components cannot stand in a slot",
            span,
            "inside a term's `{...}`",
            "a slot holds one term (`R1{,}`), one `[I n R1]`, or nothing; drawing belongs in rule bodies",
        );
    }

    fn slot_count(&mut self, rule: RuleId, found: usize, span: Span) {
        let name = self.names.get(rule.0).cloned().unwrap_or_default();
        let expected = self.branches.get(rule.0).copied().unwrap_or(0);
        let empty = format!("{name}{{{}}}", ",".repeat(expected.saturating_sub(1)));
        self.err(
            Diagnostic::error(ErrorKind::SlotCount {
                rule: name.clone(),
                expected,
                found,
            })
            .with_span(span)
            .with_label(format!("{found} slot(s) here"))
            .with_help(format!(
                "`{name}` has {expected} branch(es): write one slot per branch, separated by commas (all empty: `{empty}`)"
            )),
        );
    }

    fn bare(&mut self, rule: RuleId, span: Span) -> Term {
        let m = self.branches.get(rule.0).copied().unwrap_or(0);
        Term {
            rule,
            slots: vec![None; m],
            bare: self.format == Format::Od,
            loc: Loc(span),
        }
    }

    /// Puts a finished term or repeat where it belongs: the open slot of the
    /// innermost open term, or the seed.
    fn deliver(
        &mut self,
        s: Slot,
        stack: &mut [TermFrame],
        items: &mut Vec<SeedItem>,
        run: &mut Run,
    ) {
        match stack.last_mut() {
            Some(f) => {
                if f.cur.is_some() {
                    let span = match &s {
                        Slot::Term(t) => t.loc.0.clone(),
                        Slot::Repeat(r) => r.loc.0.clone(),
                    };
                    self.stl(
                        "a slot holds one term",
                        span,
                        "second term in this slot",
                        "separate slots with `,`; to grow more at one tip, give the rule more branches",
                    );
                } else {
                    f.cur = Some(s);
                }
            }
            None => {
                if let Some(r) = run.take() {
                    items.push(SeedItem::Draw(r));
                }
                items.push(match s {
                    Slot::Term(t) => SeedItem::Term(t),
                    Slot::Repeat(r) => SeedItem::Repeat(r),
                });
            }
        }
    }

    // ----------------------------------------------------------- layout --

    fn layout(&mut self, p: Pair<'_, Rule>) -> Layout {
        let span = span_of(&p);
        let mut shapes = Vec::new();
        let mut kw = span.clone();
        let mut closed = false;
        for c in p.into_inner() {
            match c.as_rule() {
                Rule::stl_kw_layout => kw = span_of(&c),
                Rule::stl_kw_endlayout => closed = true,
                Rule::stl_shape_line => {
                    if let Some(s) = self.shape_line(c) {
                        shapes.push(s);
                    }
                }
                _ => {}
            }
        }
        if !closed {
            self.err(
                Diagnostic::error(ErrorKind::Stl("`LAYOUT` without `ENDLAYOUT`".into()))
                    .with_span(kw)
                    .with_label("this section is never closed")
                    .with_help("end the layout with `ENDLAYOUT`"),
            );
        }
        Layout {
            shapes,
            loc: Loc(span),
        }
    }

    fn shape_line(&mut self, p: Pair<'_, Rule>) -> Option<LayoutShape> {
        let loc = Loc(span_of(&p));
        let mut it = p.into_inner();
        let col = it.next()?;
        let mut shape = it.next()?;
        let angled = shape.as_rule() == Rule::stl_angled;
        if angled {
            shape = shape.into_inner().next()?;
        }
        let color_text = col.as_str().to_string();
        let color = match Rgb::parse(&color_text) {
            Some(c) => Some(c),
            None => {
                let help = match Rgb::suggest(&color_text) {
                    Some(s) => format!("did you mean `{s}`? Colours are Delphi names or `#rrggbb`"),
                    None => "use a Delphi colour name (`clGreen`, `clWhite`, ...) or `#rrggbb`"
                        .to_string(),
                };
                self.err(
                    Diagnostic::error(ErrorKind::Stl(format!("unknown colour `{color_text}`")))
                        .with_span(span_of(&col))
                        .with_label("not a colour")
                        .with_help(help),
                );
                None
            }
        };
        let (shape, spelling) = self.shape(shape)?;
        Some(LayoutShape {
            color: color?,
            color_text,
            shape,
            spelling,
            angled,
            loc,
        })
    }

    fn shape(&mut self, p: Pair<'_, Rule>) -> Option<(Shape, Spelling)> {
        let span = span_of(&p);
        let mut it = p.into_inner();
        let name_pair = it.next()?;
        let name = name_pair.as_str();
        // Arguments: parenthesised groups and single numbers, with spans.
        enum Arg {
            Group(Vec<(f64, Span)>),
            Num(f64, Span),
        }
        let mut args = Vec::new();
        for a in it {
            let Some(inner) = a.into_inner().next() else {
                continue;
            };
            let s = span_of(&inner);
            if inner.as_rule() == Rule::stl_point_list {
                let nums: Vec<(f64, Span)> = inner
                    .into_inner()
                    .map(|n| (self.number(&n), span_of(&n)))
                    .collect();
                args.push(Arg::Group(nums));
            } else {
                args.push(Arg::Num(self.number(&inner), s));
            }
        }
        let known = ["Rectangle", "RoundRect", "Ellipse", "Polygon"];
        if !known.contains(&name) {
            let best = known
                .iter()
                .map(|k| {
                    (
                        strsim::levenshtein(&k.to_ascii_lowercase(), &name.to_ascii_lowercase()),
                        *k,
                    )
                })
                .min()
                .map(|(_, k)| k)
                .unwrap_or("Rectangle");
            self.stl(
                format!("unknown shape `{name}`"),
                span_of(&name_pair),
                "not a shape",
                &format!("did you mean `{best}`? Shapes: Rectangle, RoundRect, Ellipse, Polygon"),
            );
            return None;
        }
        let usage = match name {
            "Rectangle" => "`Rectangle (x,y), w, h` or `Rectangle (x1,y1,x2,y2)`",
            "Ellipse" => "`Ellipse (x,y), w, h` or `Ellipse (x1,y1,x2,y2)`",
            "RoundRect" => "`RoundRect (x,y), w, h, r` or `RoundRect (x1,y1,x2,y2,rx,ry)`",
            _ => "`Polygon (x1,y1), (x2,y2), (x3,y3), ...`",
        };
        let bad = |b: &mut Self| {
            b.stl(
                format!("wrong arguments for `{name}`"),
                span.clone(),
                "these arguments",
                &format!("write {usage}"),
            );
            None
        };
        if name == "Polygon" {
            let mut pts = Vec::new();
            for a in &args {
                match a {
                    Arg::Group(g) if g.len() == 2 => pts.push((g[0].0, g[1].0)),
                    _ => return bad(self),
                }
            }
            if pts.len() < 3 {
                self.stl(
                    format!(
                        "a polygon needs at least 3 points, this one has {}",
                        pts.len()
                    ),
                    span,
                    "too few points",
                    "add points: `Polygon (x1,y1), (x2,y2), (x3,y3)`",
                );
                return None;
            }
            return Some((Shape::Polygon(pts), Spelling::Points));
        }
        let round = name == "RoundRect";
        let positive = |b: &mut Self, v: f64, s: &Span, what: &str| {
            if v <= 0.0 {
                b.stl(
                    format!("the {what} of `{name}` must be positive"),
                    s.clone(),
                    "zero or negative",
                    &format!("write a positive {what}"),
                );
                false
            } else {
                true
            }
        };
        match args.as_slice() {
            // Delphi's corner spelling.
            [Arg::Group(g)] if g.len() == if round { 6 } else { 4 } => {
                let (x1, x2, y1, y2) = (g[0].0, g[2].0, g[1].0, g[3].0);
                let (w, h) = ((x2 - x1).abs(), (y2 - y1).abs());
                let mut ok = true;
                if w == 0.0 {
                    ok &= positive(self, w, &(g[0].1.start..g[2].1.end), "width");
                }
                if h == 0.0 {
                    ok &= positive(self, h, &(g[1].1.start..g[3].1.end), "height");
                }
                let (x, y) = (x1.min(x2), y1.min(y2));
                let shape = if round {
                    ok &= positive(self, g[4].0, &g[4].1, "corner width");
                    ok &= positive(self, g[5].0, &g[5].1, "corner height");
                    Shape::RoundRect {
                        x,
                        y,
                        w,
                        h,
                        rx: g[4].0 / 2.0,
                        ry: g[5].0 / 2.0,
                    }
                } else if name == "Ellipse" {
                    Shape::Ellipse { x, y, w, h }
                } else {
                    Shape::Rect { x, y, w, h }
                };
                ok.then_some((shape, Spelling::Corners))
            }
            // Table 1's start-point spelling.
            [Arg::Group(g), rest @ ..]
                if g.len() == 2
                    && rest.len() == if round { 3 } else { 2 }
                    && rest.iter().all(|a| matches!(a, Arg::Num(..))) =>
            {
                let nums: Vec<(f64, Span)> = rest
                    .iter()
                    .filter_map(|a| match a {
                        Arg::Num(v, s) => Some((*v, s.clone())),
                        Arg::Group(..) => None,
                    })
                    .collect();
                let (x, y) = (g[0].0, g[1].0);
                let (w, h) = (nums[0].0, nums[1].0);
                let mut ok = positive(self, w, &nums[0].1, "width");
                ok &= positive(self, h, &nums[1].1, "height");
                let shape = if round {
                    ok &= positive(self, nums[2].0, &nums[2].1, "corner radius");
                    let r = nums[2].0;
                    Shape::RoundRect {
                        x,
                        y,
                        w,
                        h,
                        rx: r,
                        ry: r,
                    }
                } else if name == "Ellipse" {
                    Shape::Ellipse { x, y, w, h }
                } else {
                    Shape::Rect { x, y, w, h }
                };
                ok.then_some((shape, Spelling::StartSize))
            }
            _ => bad(self),
        }
    }
}

fn self_char(l: &Lex) -> char {
    match l {
        Lex::LBrace(_) => '{',
        Lex::RBrace(_) => '}',
        Lex::Comma(_) => ',',
        Lex::Open(_) => '[',
        Lex::Close(_) => ']',
        Lex::Draw(c, _) => *c,
        Lex::Name(..) | Lex::RepeatOpen(..) => '?',
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bed(src: &str) -> Result<Description, Diagnostics> {
        parse(src, Format::Bed, &Limits::default())
    }

    const HEAD: &str = "T (0,0) L=10(0) B=1(0) RULE R1: [F] R2: [F][F] ";

    #[test]
    fn an_unknown_name_takes_the_letter_before_it() {
        // `FR3`: F is drawing, `R3` the unknown name (not `FR3`, not `3`).
        let e = bed(&format!("{HEAD} SEED FR3R1{{}} ENDSEED")).unwrap_err();
        assert_eq!(e.0.len(), 1, "{e}");
        assert_eq!(e.0[0].kind, ErrorKind::UnknownRule { name: "R3".into() });
        // `Crwn`: a whole lower-case tail.
        let e = bed(&format!("{HEAD} SEED Crwn ENDSEED")).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::UnknownRule {
                name: "Crwn".into()
            }
        );
    }

    #[test]
    fn a_slot_holds_one_term() {
        let e = bed(&format!("{HEAD} SEED R2{{R1{{}}R1{{}},}} ENDSEED")).unwrap_err();
        assert!(matches!(&e.0[0].kind, ErrorKind::Stl(m) if m.contains("one term")));
        let e = bed(&format!("{HEAD} SEED R2{{F,}} ENDSEED")).unwrap_err();
        assert!(matches!(&e.0[0].kind, ErrorKind::Stl(m) if m.contains("slot")));
    }

    #[test]
    fn empty_braces_fit_zero_or_one_branch() {
        let d = bed("T (0,0) RULE R0: F R1: [F] SEED R0{} R1{} ENDSEED").unwrap();
        let items = &d.seed.unwrap().items;
        assert!(matches!(&items[0], SeedItem::Term(t) if t.slots.is_empty()));
        assert!(matches!(&items[1], SeedItem::Term(t) if t.slots == vec![None]));
    }

    #[test]
    fn repeat_needs_a_space_after_i() {
        // `[I2]` is a bracket around the name `I2`, unknown here.
        let e = bed(&format!("{HEAD} SEED [I2] ENDSEED")).unwrap_err();
        assert_eq!(e.0[0].kind, ErrorKind::UnknownRule { name: "I2".into() });
        let d = bed(&format!("{HEAD} SEED [I 2 R2] ENDSEED")).unwrap();
        assert!(
            matches!(&d.seed.unwrap().items[0], SeedItem::Repeat(r) if r.count == 2 && r.rule == RuleId(1))
        );
    }

    #[test]
    fn unknown_parameters_and_shapes_are_named() {
        let e = bed("T (0,0) l=10(0) RULE R1: [F]").unwrap_err();
        assert!(e.0[0].help.as_deref().unwrap_or("").contains("`L`"));
        let e = bed("T (0,0) RULE R1: [F] LAYOUT (clRed) Rect (0,0), 1, 1 ENDLAYOUT").unwrap_err();
        assert!(e.0[0].help.as_deref().unwrap_or("").contains("Rectangle"));
    }
}
