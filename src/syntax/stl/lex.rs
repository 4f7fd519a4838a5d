//! The tokens of bodies and seeds, words split into drawing letters and
//! rule names.
//!
//! A word (`FR1`, `R1R2R2`) is split left to right by longest match against
//! the declared rule names; the leftovers must be [`DRAWING_LETTERS`].
//! Anything else is an unknown rule, reported with the nearest declared one.

use std::collections::VecDeque;

use pest::iterators::Pair;

use super::super::Rule;
use super::builder::{Builder, not_in_grammar};
use super::rules::DRAWING_LETTERS;
use crate::diag::{Diagnostic, RuleError, Span, StlError};
use crate::limits::Bound;
use crate::model::{Format, RuleId};

/// One lexical item of a body or seed, words already split.
#[derive(Debug, Clone)]
pub(super) enum Lex {
    /// A drawing component `F f L R + - |`.
    Draw(char, Span),
    /// Drawing components written together at `Span` (no space, no rule
    /// name among them): what consecutive [`Lex::Draw`]s of a seed become.
    Draws(String, Span),
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

/// Streams the tokens of a seed's or a body's text (the grammar's
/// `stl_seed_text`, the whole seed, and `stl_body_text`; spaces and comments
/// included) one at a time, words split as
/// [`Builder::split_word`] does and consecutive drawing components merged
/// into one [`Lex::Draws`]. A seed of millions of terms so never becomes a
/// token list: the parser holds one pair for it and this holds one word.
pub(super) struct TextLex<'s> {
    text: &'s str,
    /// Where `text` starts in the file.
    at: usize,
    /// The next byte of `text` to read.
    i: usize,
    /// Tokens read but not yet taken, in order.
    ready: VecDeque<Lex>,
    /// Drawing components written together, not yet ended.
    draws: Option<(String, Span)>,
    /// Scratch for one word's split.
    word: Vec<Lex>,
}

/// What a 3D turn does, in words.
fn turn3_name(c: char) -> &'static str {
    match c {
        '&' => "pitch down",
        '^' => "pitch up",
        '\\' => "roll left",
        _ => "roll right",
    }
}

/// Whether `b` can be part of a word (the grammar's `stl_name_char`).
fn name_char(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

impl<'s> TextLex<'s> {
    /// The tokens of `text`, which starts at byte `at` of the file.
    pub(super) fn new(text: &'s str, at: usize) -> Self {
        TextLex {
            text,
            at,
            i: 0,
            ready: VecDeque::new(),
            draws: None,
            word: Vec::new(),
        }
    }

    /// The next token, or `None` at the end of the text.
    pub(super) fn next(&mut self, b: &mut Builder<'_>) -> Option<Lex> {
        while self.ready.is_empty() && self.i < self.text.len() {
            self.step(b);
        }
        if self.ready.is_empty()
            && let Some((t, s)) = self.draws.take()
        {
            return Some(Lex::Draws(t, s));
        }
        self.ready.pop_front()
    }

    /// Reads one space, comment, symbol or word.
    fn step(&mut self, b: &mut Builder<'_>) {
        let bytes = self.text.as_bytes();
        let i = self.i;
        let here = self.at + i..self.at + i + 1;
        match bytes[i] {
            b' ' | b'\t' | b'\r' | b'\n' => self.i += 1,
            // The grammar's COMMENT: the only `#` a seed's text can hold.
            b'#' => self.i = self.skip_space(i),
            b'+' | b'-' | b'|' => {
                self.draw(char::from(bytes[i]), here);
                self.i += 1;
            }
            // The 3D turns: drawing components of a 3D description only.
            b'&' | b'^' | b'\\' | b'/' => {
                let c = char::from(bytes[i]);
                if b.three_d {
                    self.draw(c, here);
                } else if !b.turn3_reported {
                    b.turn3_reported = true;
                    b.needs_3d(format!("`{c}` ({})", turn3_name(c)), here, "a 3D turn");
                }
                self.i += 1;
            }
            b'{' => self.token(Lex::LBrace(here), i + 1),
            b'}' => self.token(Lex::RBrace(here), i + 1),
            b',' => self.token(Lex::Comma(here), i + 1),
            b']' => self.token(Lex::Close(here), i + 1),
            b'[' => match self.repeat_count(i) {
                Some((digits, end)) => {
                    let span = self.at + digits.start..self.at + digits.end;
                    let n = b.count(&self.text[digits], span);
                    self.token(Lex::RepeatOpen(n, self.at + i..self.at + end), end);
                }
                None => self.token(Lex::Open(here), i + 1),
            },
            c if name_char(c) || c == b'.' => {
                let mut e = i;
                while e < bytes.len() && (name_char(bytes[e]) || bytes[e] == b'.') {
                    e += 1;
                }
                b.split_word(&self.text[i..e], self.at + i, &mut self.word);
                for l in std::mem::take(&mut self.word) {
                    match l {
                        Lex::Draw(c, s) => self.draw(c, s),
                        other => self.end_draws_then(other),
                    }
                }
                self.i = e;
            }
            // A `BOM` (the grammar's WHITESPACE) or a byte the grammar
            // keeps out of `stl_seed_text`.
            _ => self.i += self.text[i..].chars().next().map_or(1, char::len_utf8),
        }
    }

    /// `[I n` at `open`: the digits of `n` and where the form's head ends
    /// (the grammar's `stl_repeat_open`, spaces and comments allowed between).
    fn repeat_count(&self, open: usize) -> Option<(std::ops::Range<usize>, usize)> {
        let bytes = self.text.as_bytes();
        let i = self.skip_space(open + 1);
        if bytes.get(i) != Some(&b'I') || bytes.get(i + 1).is_some_and(|&c| name_char(c)) {
            return None;
        }
        let d = self.skip_space(i + 1);
        let mut e = d;
        while e < bytes.len() && bytes[e].is_ascii_digit() {
            e += 1;
        }
        (e > d).then_some((d..e, e))
    }

    /// The first byte at or after `i` that is no space and in no comment.
    fn skip_space(&self, mut i: usize) -> usize {
        let bytes = self.text.as_bytes();
        loop {
            match bytes.get(i) {
                Some(b' ' | b'\t' | b'\r' | b'\n') => i += 1,
                Some(b'#') => {
                    while i < bytes.len() && bytes[i] != b'\n' {
                        i += 1;
                    }
                }
                _ if self.text[i..].starts_with('\u{FEFF}') => i += '\u{FEFF}'.len_utf8(),
                _ => return i,
            }
        }
    }

    /// A drawing component at `span`, joining the ones written just before it.
    fn draw(&mut self, c: char, span: Span) {
        if let Some((text, s)) = &mut self.draws
            && s.end == span.start
        {
            text.push(c);
            s.end = span.end;
            return;
        }
        if let Some((t, s)) = self.draws.replace((c.to_string(), span)) {
            self.ready.push_back(Lex::Draws(t, s));
        }
    }

    /// A token other than drawing, after the drawing before it.
    fn end_draws_then(&mut self, l: Lex) {
        if let Some((t, s)) = self.draws.take() {
            self.ready.push_back(Lex::Draws(t, s));
        }
        self.ready.push_back(l);
    }

    /// [`Self::end_draws_then`], reading on at `next`.
    fn token(&mut self, l: Lex, next: usize) {
        self.end_draws_then(l);
        self.i = next;
    }
}

impl Builder<'_> {
    /// Longest declared rule name that `text` starts with.
    /// (A lookup per prefix length: a description may declare tens of
    /// thousands of rules.)
    fn longest(&self, text: &str) -> Option<(RuleId, usize)> {
        (1..=self.longest_name.min(text.len()))
            .rev()
            .filter(|&n| text.is_char_boundary(n))
            // An alternative's number is read whole: `R1.1` is not the
            // start of `R1.18`.
            .filter(|&n| {
                !(text[..n].contains('.') && text.as_bytes().get(n).is_some_and(u8::is_ascii_digit))
            })
            .find_map(|n| self.by_name.get(&text[..n]).map(|&id| (id, n)))
    }

    /// The tokens of a rule body (`stl_body`: chunks of text), words split
    /// and drawing components written together merged, as in a seed.
    pub(super) fn lex(&mut self, p: Pair<'_, Rule>) -> Vec<Lex> {
        let mut out = Vec::new();
        for chunk in p.into_inner() {
            if chunk.as_rule() != Rule::stl_body_text {
                not_in_grammar("stl_body", chunk.as_rule());
            }
            let mut tokens = TextLex::new(chunk.as_str(), chunk.as_span().start());
            while let Some(l) = tokens.next(self) {
                out.push(l);
            }
        }
        out
    }

    /// The `n` of `[I n`: at least 1, at most `limits.max_repeat`.
    pub(super) fn count(&mut self, text: &str, span: Span) -> Option<u32> {
        let limit = self.limits.max_repeat;
        match text.parse::<u32>() {
            Ok(0) => {
                self.report(
                    StlError::ZeroCount,
                    span,
                    "zero",
                    "write `[I 1 X]` or more, or leave the form out",
                );
                None
            }
            Ok(n) if n <= limit => Some(n),
            _ => {
                self.err(
                    Bound::Repeat
                        .exceeded(text.trim_start_matches('0').to_string(), limit.into())
                        .with_span(span)
                        .with_label("count too large"),
                );
                None
            }
        }
    }

    /// Splits a word left to right by longest match against the declared
    /// rule names; the leftovers must be drawing letters.
    /// A dot belongs to a BED's alternative (`R1.2`); in an OD it is
    /// reported.
    pub(super) fn split_word(&mut self, word: &str, at: usize, out: &mut Vec<Lex>) {
        if self.format == Format::Od && word.contains('.') {
            let name = word.split('.').next().unwrap_or(word);
            self.report(
                RuleError::DottedName {
                    name: word.to_string(),
                },
                at..at + word.len(),
                "a dot in an OD",
                &format!(
                    "a dot names an alternative in a BED only; an OD refers to the rule \
                     (`{name}`) and growth chooses its body"
                ),
            );
            return;
        }
        let b = word.as_bytes();
        let mut i = 0;
        while i < b.len() {
            if let Some((id, len)) = self.longest(&word[i..]) {
                if b.get(i + len) == Some(&b'.') {
                    // `R1.3` where R1 has no third alternative.
                    let e = (i + len + 1..=b.len())
                        .find(|&e| e == b.len() || !b[e].is_ascii_digit())
                        .unwrap_or(b.len());
                    self.no_alternative(&word[i..i + len], &word[i + len + 1..e], at + i..at + e);
                    i = e;
                    continue;
                }
                out.push(Lex::Name(id, at + i..at + i + len));
                i += len;
                continue;
            }
            let c = b[i] as char;
            if DRAWING_LETTERS.contains(&c) {
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

    /// Reports `R1.3` (`name`, `number`) where R1 (`id`) has no such
    /// alternative.
    fn no_alternative(&mut self, name: &str, number: &str, span: Span) {
        let known: Vec<&str> = self
            .names
            .iter()
            .filter(|n| n.split_once('.').is_some_and(|(base, _)| base == name))
            .map(String::as_str)
            .collect();
        let help = if known.is_empty() {
            format!("`{name}` has no alternatives: write `{name}`")
        } else {
            format!("the alternatives of `{name}` are {}", known.join(", "))
        };
        self.report(
            RuleError::UnknownAlternative {
                name: name.to_string(),
                number: number.to_string(),
            },
            span,
            "no such alternative",
            &help,
        );
    }

    /// Reports a part of a word that is no declared rule, with the nearest
    /// declared one.
    fn unknown(&mut self, name: &str, span: Span) {
        if !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
            self.report(
                StlError::UnexpectedInWord {
                    text: name.to_string(),
                },
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
            Diagnostic::error(RuleError::UnknownRule {
                name: name.to_string(),
            })
            .with_span(span)
            .with_label("no rule has this name")
            .with_help(help),
        );
    }

    /// The valid declared names, `R1, R2`.
    fn declared(&self) -> String {
        let v: Vec<&str> = self
            .names
            .iter()
            .filter(|n| !n.is_empty())
            .map(String::as_str)
            .collect();
        v.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use crate::diag::{ErrorKind, RuleError, StlError};
    use crate::model::{RuleId, SeedItem};

    use super::super::testing::{HEAD, bed};

    #[test]
    fn an_unknown_name_takes_the_letter_before_it() {
        // `FR3`: F is drawing, `R3` the unknown name (not `FR3`, not `3`).
        let e = bed(&format!("{HEAD} SEED FR3R1{{}} ENDSEED")).unwrap_err();
        assert_eq!(e.0.len(), 1, "{e}");
        assert_eq!(
            e.0[0].kind,
            ErrorKind::Rule(RuleError::UnknownRule { name: "R3".into() })
        );
        // `Crwn`: a whole lower-case tail.
        let e = bed(&format!("{HEAD} SEED Crwn ENDSEED")).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::Rule(RuleError::UnknownRule {
                name: "Crwn".into()
            })
        );
    }

    #[test]
    fn digits_that_start_no_name_are_unexpected() {
        // `f` is drawing and takes no part of the name after it.
        let src = format!("{HEAD} SEED f3 ENDSEED");
        let e = bed(&src).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::Stl(StlError::UnexpectedInWord { text: "3".into() })
        );
        let at = src.find("f3").unwrap() + 1;
        assert_eq!(e.0[0].span, Some(at..at + 1));
    }

    #[test]
    fn repeat_needs_a_space_after_i() {
        // `[I2]` is a bracket around the name `I2`, unknown here.
        let e = bed(&format!("{HEAD} SEED [I2] ENDSEED")).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::Rule(RuleError::UnknownRule { name: "I2".into() })
        );
        let d = bed(&format!("{HEAD} SEED [I 2 R2] ENDSEED")).unwrap();
        assert!(
            matches!(&d.seed.unwrap().items[0], SeedItem::Repeat(r) if r.count == 2 && r.rule == RuleId(1))
        );
    }

    #[test]
    fn a_zero_count_is_refused_at_the_count() {
        let src = format!("{HEAD} SEED [I 0 R1] ENDSEED");
        let e = bed(&src).unwrap_err();
        assert_eq!(e.0[0].kind, ErrorKind::Stl(StlError::ZeroCount));
        let at = src.find(" 0 ").unwrap() + 1;
        assert_eq!(e.0[0].span, Some(at..at + 1));
    }
}
