//! `.lsys` files: the key-value L-system format of 002 §3.5.
//!
//! ```text
//! # Sierpinski arrowhead
//! generations 6
//! angle 60
//! axiom YF
//! rule X YF+XF+Y
//! rule Y XF-YF-X
//! ```

use std::collections::BTreeMap;

use pest::Parser;
use pest::iterators::Pair;

use super::{GrammarParser, Rule};
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, Span};
use crate::limits::Limits;
use crate::model::Loc;
use crate::model::lsys::{Background, DEFAULT_HEADING, LSystem, Production};

/// The keys a `.lsys` file may use, in the order the docs list them.
pub const KEYS: &[&str] = &[
    "generations",
    "axiom",
    "rule",
    "angle",
    "heading",
    "length",
    "width",
    "color",
    "background",
];

/// Parses a `.lsys` file.
///
/// Every problem found is reported, each with the span of the text at fault
/// and a hint: unknown keys (with the nearest known one), keys given twice,
/// two rules for one symbol, malformed or out-of-range numbers and colours,
/// unbalanced brackets, a missing `axiom` or `angle`, and `generations` above
/// `limits.max_depth`.
pub fn parse(src: &str, limits: &Limits) -> Result<LSystem, Diagnostics> {
    let text = super::precheck(src.as_bytes(), limits)?;
    let file = GrammarParser::parse(Rule::lsys_file, text).map_err(|e| {
        let mut d = super::pest_error(e);
        // At the start of a line pest lists every key's form; say it short.
        if let Some(span) = &d.span {
            let line_start = text[..span.start].rfind(['\n', '\r']).map_or(0, |i| i + 1);
            if text[line_start..span.start].trim().is_empty() {
                d.kind = ErrorKind::Syntax("expected a line `key value` or a `#` comment".into());
            }
        }
        Diagnostics::from(d.with_help(
            "each line of a .lsys file is `key value` (generations, axiom, rule, \
                 angle, heading, length, width, color, background) or a `#` comment",
        ))
    })?;
    let mut ck = Checker {
        diags: Diagnostics::new(),
        seen: BTreeMap::new(),
    };
    let mut sys = LSystem {
        axiom: Vec::new(),
        axiom_loc: Loc(0..0),
        rules: BTreeMap::new(),
        generations: None,
        angle: 0.0,
        heading: DEFAULT_HEADING,
        length: 1.0,
        width: 1.0,
        color: None,
        background: Background::White,
    };
    let mut have_axiom = false;
    let mut have_angle = false;
    for entry in file.into_iter().flat_map(|p| p.into_inner()) {
        let span = entry.as_span().start()..entry.as_span().end();
        let rule = entry.as_rule();
        if rule == Rule::EOI {
            continue;
        }
        let mut inner = entry.into_inner();
        let key_span = span.start..span.start + key_len(&src[span.clone()]);
        match rule {
            Rule::lsys_unknown => {
                let key = inner.next().map(|k| k.as_str()).unwrap_or("");
                let mut d = Diagnostic::error(ErrorKind::Lsys(format!("unknown key `{key}`")))
                    .with_span(key_span)
                    .with_label("not a key of a .lsys file");
                d = match nearest_key(key) {
                    Some(k) => d.with_help(format!("did you mean `{k}`?")),
                    None => d.with_help(format!("the keys are {}", KEYS.join(", "))),
                };
                ck.diags.push(d);
            }
            Rule::lsys_rule => {
                let pred = inner.next().expect("grammar: rule has a predecessor");
                let pred_span = pair_span(&pred);
                let succ = inner.find(|p| p.as_rule() == Rule::lsys_word);
                let mut chars = pred.as_str().chars();
                let c = chars.next().unwrap_or(' ');
                if chars.next().is_some() {
                    ck.diags.push(
                        Diagnostic::error(ErrorKind::Lsys(format!(
                            "a rule rewrites one symbol, but `{}` is {} symbols",
                            pred.as_str(),
                            pred.as_str().chars().count()
                        )))
                        .with_span(pred_span)
                        .with_label("the predecessor")
                        .with_help(
                            "write `rule X SUCCESSOR` with a single-symbol X \
                             (separate it from the successor with a space, `->` or `=`)",
                        ),
                    );
                    continue;
                }
                let successor = match &succ {
                    Some(w) => ck.word(w, "successor"),
                    None => Vec::new(),
                };
                if let Some(first) = sys.rules.get(&c) {
                    ck.diags.push(
                        Diagnostic::error(ErrorKind::Lsys(format!("two rules for `{c}`")))
                            .with_span(span.clone())
                            .with_label("the second rule")
                            .with_note_at(first.loc.0.clone(), "the first rule")
                            .with_help(format!(
                                "a 0L-system has one rule per symbol: keep one of the rules for `{c}`"
                            )),
                    );
                    continue;
                }
                sys.rules.insert(
                    c,
                    Production {
                        successor,
                        loc: Loc(span.clone()),
                    },
                );
            }
            _ => {
                let key = &src[key_span.clone()];
                if !ck.first_time(key, key_span.clone()) {
                    continue;
                }
                let value = inner.next().expect("grammar: a key has a value");
                match rule {
                    Rule::lsys_generations => {
                        sys.generations = ck.generations(&value, limits);
                    }
                    Rule::lsys_axiom => {
                        sys.axiom = ck.word(&value, "axiom");
                        sys.axiom_loc = Loc(pair_span(&value));
                        have_axiom = true;
                    }
                    Rule::lsys_angle => {
                        have_angle = true;
                        if let Some(a) = ck.number(&value, "angle", false) {
                            sys.angle = a;
                        }
                    }
                    Rule::lsys_heading => {
                        if let Some(h) = ck.number(&value, "heading", false) {
                            sys.heading = h;
                        }
                    }
                    Rule::lsys_length => {
                        if let Some(l) = ck.number(&value, "length", true) {
                            sys.length = l;
                        }
                    }
                    Rule::lsys_width => {
                        if let Some(w) = ck.number(&value, "width", true) {
                            sys.width = w;
                        }
                    }
                    Rule::lsys_color => {
                        if let Some(Some(c)) = ck.colour(&value, false) {
                            sys.color = Some(c);
                        }
                    }
                    Rule::lsys_background => {
                        sys.background = match ck.colour(&value, true) {
                            Some(Some(c)) => Background::Color(c),
                            Some(None) => Background::None,
                            None => Background::White,
                        };
                    }
                    _ => {}
                }
            }
        }
    }
    let end = src.len()..src.len();
    if !have_axiom {
        ck.diags.push(
            Diagnostic::error(ErrorKind::Lsys("missing `axiom`".into()))
                .with_span(end.clone())
                .with_label("the file ends without an axiom")
                .with_help("add a line `axiom WORD`, the start word, e.g. `axiom F`"),
        );
    }
    if !have_angle {
        ck.diags.push(
            Diagnostic::error(ErrorKind::Lsys("missing `angle`".into()))
                .with_span(end)
                .with_label("the file ends without an angle")
                .with_help("add a line `angle DEGREES`, the turning angle of `+` and `-`, e.g. `angle 25.7`"),
        );
    }
    ck.diags.into_result(sys)
}

/// Collects diagnostics while the entries are checked.
struct Checker {
    diags: Diagnostics,
    /// Where each single-valued key was first given.
    seen: BTreeMap<String, Span>,
}

impl Checker {
    /// Records a single-valued key; false (and an error) if it was given before.
    fn first_time(&mut self, key: &str, span: Span) -> bool {
        if let Some(first) = self.seen.get(key) {
            self.diags.push(
                Diagnostic::error(ErrorKind::Lsys(format!("`{key}` is given twice")))
                    .with_span(span)
                    .with_label("given again here")
                    .with_note_at(first.clone(), "first given here")
                    .with_help(format!("keep one `{key}` line")),
            );
            return false;
        }
        self.seen.insert(key.to_string(), span);
        true
    }

    /// The symbols of a word (spaces inside it dropped), brackets checked.
    fn word(&mut self, pair: &Pair<'_, Rule>, what: &str) -> Vec<char> {
        let base = pair.as_span().start();
        let mut out = Vec::new();
        let mut open: Vec<usize> = Vec::new();
        for (i, c) in pair.as_str().char_indices() {
            if c == ' ' || c == '\t' || c == '\u{FEFF}' {
                continue;
            }
            match c {
                '[' => open.push(base + i),
                ']' if open.pop().is_none() => {
                    self.diags.push(
                        Diagnostic::error(ErrorKind::Unbalanced(']'))
                            .with_span(base + i..base + i + 1)
                            .with_label(format!("this `]` closes no `[` in the {what}"))
                            .with_help("remove it, or add the `[` it should close"),
                    );
                }
                _ => {}
            }
            out.push(c);
        }
        if let Some(&at) = open.last() {
            let mut d = Diagnostic::error(ErrorKind::Unbalanced('['))
                .with_span(at..at + 1)
                .with_label(format!("this `[` is never closed in the {what}"))
                .with_help(format!(
                    "add the matching `]` in the same {what}: brackets must balance within each word"
                ));
            for &other in open.iter().rev().skip(1) {
                d = d.with_note_at(other..other + 1, "also never closed");
            }
            self.diags.push(d);
        }
        out
    }

    /// `generations`: a whole number no larger than `limits.max_depth`.
    fn generations(&mut self, value: &Pair<'_, Rule>, limits: &Limits) -> Option<u32> {
        let (text, span) = value_text(value);
        let Some(Rule::integer) = value.clone().into_inner().next().map(|p| p.as_rule()) else {
            self.diags.push(
                Diagnostic::error(ErrorKind::Lsys(format!(
                    "`generations` takes a whole number, not `{text}`"
                )))
                .with_span(span)
                .with_label("not a whole number")
                .with_help("write the number of rewriting steps, e.g. `generations 5`"),
            );
            return None;
        };
        match text.parse::<u32>() {
            Ok(n) if n <= limits.max_depth => Some(n),
            _ => {
                self.diags.push(
                    Diagnostic::error(ErrorKind::Limit {
                        what: "generations".into(),
                        value: text.trim_start_matches('0').to_string(),
                        limit: limits.max_depth.to_string(),
                    })
                    .with_span(span)
                    .with_label("too many generations")
                    .with_help("use fewer generations, or raise the limit with --max-depth N"),
                );
                None
            }
        }
    }

    /// A finite number; `positive`: also greater than zero.
    fn number(&mut self, value: &Pair<'_, Rule>, key: &str, positive: bool) -> Option<f64> {
        let (text, span) = value_text(value);
        let is_number = matches!(
            value.clone().into_inner().next().map(|p| p.as_rule()),
            Some(Rule::number)
        );
        let parsed = if is_number {
            text.parse::<f64>().ok()
        } else {
            None
        };
        let example = match key {
            "angle" => "`angle 25.7`",
            "heading" => "`heading 0`",
            "length" => "`length 1`",
            _ => "`width 1.5`",
        };
        match parsed {
            None => {
                self.diags.push(
                    Diagnostic::error(ErrorKind::Lsys(format!("malformed number `{text}`")))
                        .with_span(span)
                        .with_label(format!("`{key}` takes a number"))
                        .with_help(format!("write a decimal number, e.g. {example}")),
                );
                None
            }
            Some(v) if !v.is_finite() => {
                self.diags.push(
                    Diagnostic::error(ErrorKind::Lsys(format!("`{key}` {text} is too large")))
                        .with_span(span)
                        .with_label("does not fit a 64-bit float")
                        .with_help(format!("write a finite number, e.g. {example}")),
                );
                None
            }
            Some(v) if positive && v <= 0.0 => {
                self.diags.push(
                    Diagnostic::error(ErrorKind::Lsys(format!(
                        "`{key}` must be greater than 0, not {text}"
                    )))
                    .with_span(span)
                    .with_label("zero or negative")
                    .with_help(format!("write a positive number, e.g. {example}")),
                );
                None
            }
            Some(v) => Some(v),
        }
    }

    /// A colour; `Some(None)` is `none` (only if `allow_none`).
    fn colour(&mut self, value: &Pair<'_, Rule>, allow_none: bool) -> Option<Option<Rgb>> {
        let (text, span) = value_text(value);
        if allow_none && text.eq_ignore_ascii_case("none") {
            return Some(None);
        }
        if let Some(c) = Rgb::parse(text) {
            return Some(Some(c));
        }
        let help = match Rgb::suggest(text) {
            Some(name) => format!("did you mean `{name}`?"),
            None if allow_none => {
                "write `#rrggbb`, a Delphi colour name such as `clGreen`, or `none`".into()
            }
            None => "write `#rrggbb` or a Delphi colour name such as `clGreen`".into(),
        };
        self.diags.push(
            Diagnostic::error(ErrorKind::Lsys(format!("unknown colour `{text}`")))
                .with_span(span)
                .with_label("not a colour")
                .with_help(help),
        );
        None
    }
}

/// The value's text and span, trailing spaces dropped.
fn value_text<'a>(value: &Pair<'a, Rule>) -> (&'a str, Span) {
    let text = value.as_str().trim_end();
    let start = value.as_span().start();
    (text, start..start + text.len())
}

fn pair_span(p: &Pair<'_, Rule>) -> Span {
    p.as_span().start()..p.as_span().end()
}

/// Length of the key at the start of an entry.
fn key_len(entry: &str) -> usize {
    entry
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '-'))
        .unwrap_or(entry.len())
}

/// The known key closest to `key`, if one is close enough to be a typo.
fn nearest_key(key: &str) -> Option<&'static str> {
    let lower = key.to_ascii_lowercase();
    KEYS.iter()
        .map(|k| (strsim::damerau_levenshtein(k, &lower), *k))
        .filter(|(d, k)| *d <= 2.max(k.len() / 3))
        .min()
        .map(|(_, k)| k)
}

/// A user-facing description of a grammar rule of the lsys section.
pub fn describe_rule(rule: Rule) -> Option<&'static str> {
    Some(match rule {
        Rule::number | Rule::lsys_num => "a number",
        Rule::integer | Rule::lsys_int => "a whole number",
        Rule::lsys_file => "a line `key value` or a `#` comment",
        Rule::lsys_generations => "`generations N`",
        Rule::lsys_axiom => "`axiom WORD`",
        Rule::lsys_rule => "`rule X SUCCESSOR`",
        Rule::lsys_angle => "`angle DEGREES`",
        Rule::lsys_heading => "`heading DEGREES`",
        Rule::lsys_length => "`length L`",
        Rule::lsys_width => "`width W`",
        Rule::lsys_color => "`color C`",
        Rule::lsys_background => "`background C`",
        Rule::lsys_unknown | Rule::lsys_key => {
            "a key (generations, axiom, rule, angle, heading, length, width, color, background)"
        }
        Rule::lsys_colour | Rule::lsys_hex | Rule::lsys_name => "a colour (`#rrggbb` or `clGreen`)",
        Rule::lsys_bad | Rule::lsys_text => "a value",
        Rule::lsys_word => "a word of symbols",
        Rule::lsys_pred => "the symbol the rule rewrites",
        Rule::lsys_arrow => "`->`, `=` or a space before the successor",
        _ => return None,
    })
}
