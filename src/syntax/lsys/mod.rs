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
use pest::iterators::{Pair, Pairs};

use super::{GrammarParser, Rule};
use crate::choice::{self, BadProbabilities};
use crate::color::Rgb;
use crate::diag::Help;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, InputError, LsysError, RuleError, Span};
use crate::limits::{Bound, Limits};
use crate::model::Loc;
use crate::model::lsys::{Background, DEFAULT_HEADING, LSystem, Production};

pub(crate) mod expr;
mod keys;
mod organs;
pub use organs::{ORGAN_KEYS, too_many};
pub(crate) use param::surface_block;
pub mod param;
pub use param::PARAM_KEYS;

pub use keys::{KEYS, Key};

/// Parses a `.lsys` file.
///
/// Every problem found is reported, each with the span of the text at fault
/// and a hint: unknown keys (with the nearest known one), keys given twice,
/// two rules for one symbol, malformed or out-of-range numbers and colours,
/// unbalanced brackets, a missing `axiom` or `angle`, and `generations` above
/// `limits.max_depth`.
pub fn parse(src: &str, limits: &Limits) -> Result<LSystem, Diagnostics> {
    let text = super::precheck(src.as_bytes(), limits)?;
    if param::uses_parameters(text) {
        // The classic keys checked on a copy without the parametric lines
        // (same offsets), the parametric lines read on their own.
        let masked = param::mask(text);
        let classic = parse_classic(&masked, limits);
        let parametric = param::parse(text);
        return match (classic, parametric) {
            (Ok(mut sys), Ok(p)) => {
                sys.axiom = p.axiom.iter().map(|m| m.symbol).collect();
                sys.parametric = Some(Box::new(p));
                Ok(sys)
            }
            (Err(mut a), Err(b)) => {
                for d in b.iter() {
                    a.push(d.clone());
                }
                Err(a)
            }
            (Err(a), _) | (_, Err(a)) => Err(a),
        };
    }
    parse_classic(text, limits)
}

/// [`parse`] of a classic (parameterless) file.
fn parse_classic(src: &str, limits: &Limits) -> Result<LSystem, Diagnostics> {
    let text = src;
    let file = GrammarParser::parse(Rule::lsys_file, text).map_err(|e| {
        let mut d = super::pest_error(e);
        // At the start of a line pest lists every key's form; say it short.
        if let Some(span) = &d.span {
            let line_start = text[..span.start].rfind(['\n', '\r']).map_or(0, |i| i + 1);
            if text[line_start..span.start].trim().is_empty() {
                d.kind = ErrorKind::Input(InputError::Syntax(
                    "expected a line `key value` or a `#` comment".into(),
                ));
            }
        }
        Diagnostics::from(d.with_help(format!(
            "each line of a .lsys file is `key value` ({}) or a `#` comment",
            KEYS.join(", ")
        )))
    })?;
    let mut ck = Checker {
        diags: Diagnostics::new(),
        seen: BTreeMap::new(),
        mixed: Default::default(),
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
        seed: 0,
        dimensions: 2,
        parametric: None,
    };
    let mut have_axiom = false;
    let mut have_angle = false;
    for entry in file.into_iter().flat_map(|p| p.into_inner()) {
        let span = pair_span(&entry);
        let rule = entry.as_rule();
        let mut inner = entry.into_inner();
        let key_span = span.start..span.start + key_len(&src[span.clone()]);
        if rule == Rule::EOI {
            continue;
        }
        if rule == Rule::lsys_unknown {
            let key = inner
                .next()
                .expect("grammar: lsys_unknown starts with lsys_key");
            ck.unknown_key(key.as_str(), key_span);
            continue;
        }
        let key = Key::of_rule(rule)
            .expect("grammar: an lsys_file entry is a key line, lsys_unknown or EOI");
        if key != Key::Rule && !ck.first_time(key, key_span) {
            continue;
        }
        match key {
            Key::Rule => ck.production(&mut sys, inner, span),
            Key::Generations => sys.generations = ck.generations(&value(&mut inner), limits),
            Key::Axiom => {
                let value = value(&mut inner);
                sys.axiom = ck.word(&value, "axiom");
                sys.axiom_loc = Loc(pair_span(&value));
                have_axiom = true;
            }
            Key::Angle => {
                have_angle = true;
                if let Some(a) = ck.number(&value(&mut inner), key, false) {
                    sys.angle = a;
                }
            }
            Key::Heading => {
                if let Some(h) = ck.number(&value(&mut inner), key, false) {
                    sys.heading = h;
                }
            }
            Key::Length => {
                if let Some(l) = ck.number(&value(&mut inner), key, true) {
                    sys.length = l;
                }
            }
            Key::Width => {
                if let Some(w) = ck.number(&value(&mut inner), key, true) {
                    sys.width = w;
                }
            }
            Key::Color => {
                if let Some(Some(c)) = ck.colour(&value(&mut inner), false) {
                    sys.color = Some(c);
                }
            }
            Key::Background => {
                sys.background = match ck.colour(&value(&mut inner), true) {
                    Some(Some(c)) => Background::Color(c),
                    Some(None) => Background::None,
                    None => Background::White,
                };
            }
            Key::Seed => {
                if let Some(n) = ck.seed(&value(&mut inner)) {
                    sys.seed = n;
                }
            }
            Key::Dimensions => {
                let v = value(&mut inner);
                let (text, span) = value_text(&v);
                match keys::dimensions(text, span, value_rule(&v) == Rule::integer) {
                    Ok(n) => sys.dimensions = n,
                    Err(d) => ck.diags.push(*d),
                }
            }
        }
    }
    ck.probabilities(&sys);
    let end = src.len()..src.len();
    if !have_axiom {
        ck.diags.push(
            Diagnostic::error(LsysError::MissingKey {
                key: Key::Axiom.name(),
            })
            .with_span(end.clone())
            .with_label("the file ends without an axiom")
            .with_help(format!(
                "add a line `axiom WORD`, the start word, e.g. {}",
                Key::Axiom.example()
            )),
        );
    }
    if !have_angle {
        ck.diags.push(
            Diagnostic::error(LsysError::MissingKey {
                key: Key::Angle.name(),
            })
            .with_span(end)
            .with_label("the file ends without an angle")
            .with_help(format!(
                "add a line `angle DEGREES`, the turning angle of `+` and `-`, e.g. {}",
                Key::Angle.example()
            )),
        );
    }
    ck.diags.into_result(sys)
}

/// The length of a leading parenthesis of a rule's successor that stands
/// where a probability goes but is not one: `(1/3) -> F` (an arrow follows
/// it, so the successor would be `(1/3)->F`). `None` for anything else.
fn unreadable_probability(successor: &str) -> Option<usize> {
    let close = successor.strip_prefix('(')?.find(')')? + 2;
    let rest = successor[close..].trim_start_matches([' ', '\t', '\u{FEFF}']);
    (rest.starts_with("->") || rest.starts_with('=')).then_some(close)
}

/// Collects diagnostics while the entries are checked.
struct Checker {
    diags: Diagnostics,
    /// Where each single-valued key was first given.
    seen: BTreeMap<Key, Span>,
    /// Symbols with rules both with and without a probability (reported
    /// once, where the odd one is; their probabilities are not summed).
    mixed: std::collections::BTreeSet<char>,
}

impl Checker {
    /// Reports a key that is not one of [`KEYS`], with the nearest known one.
    fn unknown_key(&mut self, key: &str, span: Span) {
        let d = Diagnostic::error(LsysError::UnknownKey {
            key: key.to_string(),
        })
        .with_span(span)
        .with_label("not a key of a .lsys file");
        self.diags.push(match nearest_key(key) {
            Some(k) => d.with_help(format!("did you mean `{k}`?")),
            None => d.with_help(format!("the keys are {}", KEYS.join(", "))),
        });
    }

    /// A `rule` line: one symbol and its successor, at most one rule per
    /// symbol.
    fn production(&mut self, sys: &mut LSystem, mut inner: Pairs<'_, Rule>, span: Span) {
        let pred = inner.next().expect("grammar: a rule has a predecessor");
        let rest: Vec<Pair<'_, Rule>> = inner.collect();
        let probability = rest
            .iter()
            .find(|p| p.as_rule() == Rule::lsys_probability)
            .cloned();
        let succ = rest.into_iter().find(|p| p.as_rule() == Rule::lsys_word);
        let mut chars = pred.as_str().chars();
        let c = chars.next().expect("grammar: lsys_pred has a symbol");
        if chars.next().is_some() {
            let text = pred.as_str();
            let help = if text[c.len_utf8()..].starts_with('(') {
                format!("put a space before the probability: `rule {c} (0.5) -> ...`")
            } else {
                "write `rule X SUCCESSOR` with a single-symbol X \
                 (separate it from the successor with a space, `->` or `=`)"
                    .to_string()
            };
            self.diags.push(
                Diagnostic::error(LsysError::LongPredecessor {
                    predecessor: text.to_string(),
                    symbols: text.chars().count(),
                })
                .with_span(pair_span(&pred))
                .with_label("the predecessor")
                .with_help(help),
            );
            return;
        }
        if probability.is_none()
            && let Some(w) = &succ
            && let Some(len) = unreadable_probability(w.as_str())
        {
            let at = w.as_span().start();
            self.diags.push(
                Diagnostic::error(LsysError::UnreadableProbability {
                    text: w.as_str()[..len].to_string(),
                })
                .with_span(at..at + len)
                .with_label("not a decimal number")
                .with_help(format!(
                    "write the probability as a decimal number above 0, `rule {c} (0.5) -> ...`; \
                     a symbol's probabilities sum to 1 within 1e-6, so thirds are \
                     (0.34), (0.33), (0.33)"
                )),
            );
            return;
        }
        let successor = match &succ {
            Some(w) => self.word(w, "successor"),
            None => Vec::new(),
        };
        let probability = probability.map(|p| {
            let text = p
                .into_inner()
                .next()
                .expect("grammar: a probability holds a number");
            text.as_str().parse::<f64>().unwrap_or(f64::NAN)
        });
        if let Some(first) = sys.rules.get(&c).and_then(|ps| ps.first()) {
            match (first.probability.is_some(), probability.is_some()) {
                (true, true) => {}
                (false, false) => {
                    self.diags.push(
                        Diagnostic::error(LsysError::DuplicateProduction { symbol: c })
                            .with_span(span)
                            .with_label("the second rule")
                            .with_note_at(first.loc.0.clone(), "the first rule")
                            .with_help(format!(
                                "a 0L-system has one rule per symbol: keep one of the rules \
                                 for `{c}`, or give each a probability, `rule {c} (0.5) ...`"
                            )),
                    );
                    return;
                }
                (first_has, _) => {
                    self.mixed.insert(c);
                    let (at, other) = if first_has {
                        (span, first.loc.0.clone())
                    } else {
                        (first.loc.0.clone(), span)
                    };
                    self.diags.push(
                        Diagnostic::error(RuleError::MissingProbability {
                            name: c.to_string(),
                        })
                        .with_span(at)
                        .with_label("no probability")
                        .with_note_at(other, "a rule with one")
                        .with_help(format!(
                            "a symbol with several rules chooses among them: give each a \
                             probability, `rule {c} (0.5) ...`"
                        )),
                    );
                    return;
                }
            }
        }
        sys.rules.entry(c).or_default().push(Production {
            successor,
            probability,
            loc: Loc(span),
        });
    }

    /// The probabilities of each symbol's stochastic rules: each above 0,
    /// together 1 (within [`choice::SUM_TOLERANCE`]).
    fn probabilities(&mut self, sys: &LSystem) {
        for (c, ps) in &sys.rules {
            let p: Vec<f64> = ps.iter().filter_map(|p| p.probability).collect();
            if p.is_empty() || self.mixed.contains(c) {
                // A rule without a probability beside ones with is
                // reported where it is (and left out): a sum would only
                // repeat it.
                continue;
            }
            match choice::check(&p) {
                Ok(()) => {}
                Err(BadProbabilities::NotPositive(i)) => self.diags.push(
                    Diagnostic::error(RuleError::BadProbability {
                        name: c.to_string(),
                        value: p[i],
                    })
                    .with_span(ps[i].loc.0.clone())
                    .with_label("this rule's probability")
                    .with_help("a probability is a number above 0, e.g. `(0.5)`"),
                ),
                Err(BadProbabilities::Sum(sum)) => {
                    let mut d = Diagnostic::error(RuleError::ProbabilitySum {
                        name: c.to_string(),
                        sum,
                    })
                    .with_span(ps[0].loc.0.clone())
                    .with_label("first rule");
                    for q in ps.iter().skip(1).take(4) {
                        d = d.with_note_at(q.loc.0.clone(), "another rule");
                    }
                    self.diags.push(d.with_help(if ps.len() == 1 {
                        format!(
                            "one rule for `{c}` needs no probability: write `rule {c} -> ...`, \
                             or add rules for `{c}` whose probabilities add up to 1"
                        )
                    } else {
                        format!(
                            "make the probabilities of the rules for `{c}` add up to 1, e.g. \
                             `(0.5)` and `(0.5)`"
                        )
                    }));
                }
            }
        }
    }

    /// `seed`: a whole number from 0 to 2^64 - 1.
    fn seed(&mut self, value: &Pair<'_, Rule>) -> Option<u64> {
        let (text, span) = value_text(value);
        match (value_rule(value), text.parse::<u64>()) {
            (Rule::integer, Ok(n)) => Some(n),
            _ => {
                self.diags.push(
                    Diagnostic::error(LsysError::NotWholeNumber {
                        key: Key::Seed.name(),
                        text: text.to_string(),
                    })
                    .with_span(span)
                    .with_label("not a seed")
                    .with_help(format!(
                        "a seed is a whole number from 0 to 18446744073709551615, e.g. {}",
                        Key::Seed.example()
                    )),
                );
                None
            }
        }
    }

    /// Records a single-valued key; false (and an error) if it was given before.
    fn first_time(&mut self, key: Key, span: Span) -> bool {
        if let Some(first) = self.seen.get(&key) {
            self.diags.push(
                Diagnostic::error(LsysError::DuplicateKey { key: key.name() })
                    .with_span(span)
                    .with_label("given again here")
                    .with_note_at(first.clone(), "first given here")
                    .with_help(format!("keep one `{}` line", key.name())),
            );
            return false;
        }
        self.seen.insert(key, span);
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
                        Diagnostic::error(InputError::Unbalanced(']'))
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
            let mut d = Diagnostic::error(InputError::Unbalanced('['))
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
        if value_rule(value) != Rule::integer {
            self.diags.push(
                Diagnostic::error(LsysError::NotWholeNumber {
                    key: Key::Generations.name(),
                    text: text.to_string(),
                })
                .with_span(span)
                .with_label("not a whole number")
                .with_help(format!(
                    "write the number of rewriting steps, e.g. {}",
                    Key::Generations.example()
                )),
            );
            return None;
        }
        match text.parse::<u32>() {
            Ok(n) if n <= limits.max_depth => Some(n),
            _ => {
                self.diags.push(
                    Bound::Depth
                        .exceeded_by(
                            Key::Generations.name(),
                            text.trim_start_matches('0').to_string(),
                            limits.max_depth.into(),
                        )
                        .with_span(span)
                        .with_label("too many generations")
                        .with_help(Help::from("use fewer generations, or ") + Bound::Depth),
                );
                None
            }
        }
    }

    /// A finite number; `positive`: also greater than zero.
    fn number(&mut self, value: &Pair<'_, Rule>, key: Key, positive: bool) -> Option<f64> {
        let (text, span) = value_text(value);
        let parsed = if value_rule(value) == Rule::number {
            text.parse::<f64>().ok()
        } else {
            None
        };
        let example = key.example();
        let name = key.name();
        match parsed {
            None => {
                self.diags.push(
                    Diagnostic::error(LsysError::MalformedNumber {
                        text: text.to_string(),
                    })
                    .with_span(span)
                    .with_label(format!("`{name}` takes a number"))
                    .with_help(format!("write a decimal number, e.g. {example}")),
                );
                None
            }
            Some(v) if !v.is_finite() => {
                self.diags.push(
                    Diagnostic::error(LsysError::NumberTooLarge {
                        key: name,
                        text: text.to_string(),
                    })
                    .with_span(span)
                    .with_label("does not fit a 64-bit float")
                    .with_help(format!("write a finite number, e.g. {example}")),
                );
                None
            }
            Some(v) if positive && v <= 0.0 => {
                self.diags.push(
                    Diagnostic::error(LsysError::NotPositive {
                        key: name,
                        text: text.to_string(),
                    })
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
        self.diags.push(super::unknown_colour(text, span, help));
        None
    }
}

/// The value of a single-valued key's line.
fn value<'a>(inner: &mut Pairs<'a, Rule>) -> Pair<'a, Rule> {
    inner.next().expect("grammar: a key has a value")
}

/// The rule of a value's one child: `integer` or `number` when the text
/// reads as one, `lsys_bad` when not.
fn value_rule(value: &Pair<'_, Rule>) -> Rule {
    value
        .clone()
        .into_inner()
        .next()
        .expect("grammar: lsys_int and lsys_num hold a number or lsys_bad")
        .as_rule()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_has_its_spelling_at_its_index() {
        assert_eq!(KEYS.len(), Key::ALL.len());
        for (i, k) in Key::ALL.into_iter().enumerate() {
            assert_eq!(k as usize, i);
            assert_eq!(Key::of_rule(k.rule()), Some(k));
        }
        assert_eq!(Key::Background.name(), "background");
    }
}
