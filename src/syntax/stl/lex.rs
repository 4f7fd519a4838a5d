//! The tokens of bodies and seeds, words split into drawing letters and
//! rule names.
//!
//! A word (`FR1`, `R1R2R2`) is split left to right by longest match against
//! the declared rule names; the leftovers must be [`DRAWING_LETTERS`].
//! Anything else is an unknown rule, reported with the nearest declared one.

use pest::iterators::Pair;

use super::{Builder, DRAWING_LETTERS, Rule, not_in_grammar, span_of};
use crate::diag::{Diagnostic, ErrorKind, Span};
use crate::model::RuleId;

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

/// Appends the drawing component at `span`, extending a [`Lex::Draws`]
/// that ends where it starts.
fn push_draw(out: &mut Vec<Lex>, c: char, span: Span) {
    if let Some(Lex::Draws(text, s)) = out.last_mut()
        && s.end == span.start
    {
        text.push(c);
        s.end = span.end;
        return;
    }
    out.push(Lex::Draws(c.to_string(), span));
}

impl Builder<'_> {
    /// Longest declared rule name that `text` starts with.
    fn longest(&self, text: &str) -> Option<(RuleId, usize)> {
        self.names
            .iter()
            .enumerate()
            .filter(|(_, n)| !n.is_empty() && text.starts_with(n.as_str()))
            .max_by_key(|(i, n)| (n.len(), std::cmp::Reverse(*i)))
            .map(|(i, n)| (RuleId(i), n.len()))
    }

    /// The tokens of a body or seed (`stl_body`, `stl_seed_body`), words
    /// split into drawing letters and rule names.
    pub(super) fn lex(&mut self, p: Pair<'_, Rule>) -> Vec<Lex> {
        let mut out = Vec::new();
        for tok in p.into_inner() {
            let t = tok.into_inner().next();
            let t = t.expect("grammar: stl_token holds one token");
            let span = span_of(&t);
            match t.as_rule() {
                Rule::stl_open => out.push(Lex::Open(span)),
                Rule::stl_close => out.push(Lex::Close(span)),
                Rule::stl_lbrace => out.push(Lex::LBrace(span)),
                Rule::stl_rbrace => out.push(Lex::RBrace(span)),
                Rule::stl_comma => out.push(Lex::Comma(span)),
                Rule::stl_sym => {
                    let c = t.as_str().chars().next();
                    out.push(Lex::Draw(c.expect("grammar: stl_sym is one symbol"), span));
                }
                Rule::stl_word => self.split_word(t.as_str(), span.start, &mut out),
                Rule::stl_run => self.split_run(t.as_str(), span.start, &mut out),
                Rule::stl_repeat_open => {
                    let count = t.into_inner().find(|x| x.as_rule() == Rule::integer);
                    let count = count.expect("grammar: stl_repeat_open holds an integer");
                    let n = self.count(&count);
                    out.push(Lex::RepeatOpen(n, span));
                }
                other => not_in_grammar("stl_token", other),
            }
        }
        out
    }

    /// The `n` of `[I n`: at least 1, at most `limits.max_repeat`.
    fn count(&mut self, c: &Pair<'_, Rule>) -> Option<u32> {
        let text = c.as_str();
        let limit = self.limits.max_repeat;
        match text.parse::<u32>() {
            Ok(0) => {
                self.report(
                    ErrorKind::ZeroCount,
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

    /// Splits a seed's run (`F+R1-FF`) into its symbols and words, each word
    /// split as [`Builder::split_word`] does; consecutive drawing
    /// components become one [`Lex::Draws`], so a run of a million of them
    /// is one item.
    fn split_run(&mut self, run: &str, at: usize, out: &mut Vec<Lex>) {
        let b = run.as_bytes();
        // One scratch list for every word of the run, not one a word.
        let mut word = Vec::new();
        let mut i = 0;
        while i < b.len() {
            if matches!(b[i], b'+' | b'-' | b'|') {
                push_draw(out, char::from(b[i]), at + i..at + i + 1);
                i += 1;
                continue;
            }
            let mut e = i;
            while e < b.len() && !matches!(b[e], b'+' | b'-' | b'|') {
                e += 1;
            }
            self.split_word(&run[i..e], at + i, &mut word);
            for l in word.drain(..) {
                match l {
                    Lex::Draw(c, s) => push_draw(out, c, s),
                    other => out.push(other),
                }
            }
            i = e;
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

    /// Reports a part of a word that is no declared rule, with the nearest
    /// declared one.
    fn unknown(&mut self, name: &str, span: Span) {
        if !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
            self.report(
                ErrorKind::UnexpectedInWord {
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
            Diagnostic::error(ErrorKind::UnknownRule {
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
    use crate::diag::ErrorKind;
    use crate::model::{RuleId, SeedItem};

    use super::super::testing::{HEAD, bed};

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
    fn digits_that_start_no_name_are_unexpected() {
        // `f` is drawing and takes no part of the name after it.
        let src = format!("{HEAD} SEED f3 ENDSEED");
        let e = bed(&src).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::UnexpectedInWord { text: "3".into() }
        );
        let at = src.find("f3").unwrap() + 1;
        assert_eq!(e.0[0].span, Some(at..at + 1));
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
    fn a_zero_count_is_refused_at_the_count() {
        let src = format!("{HEAD} SEED [I 0 R1] ENDSEED");
        let e = bed(&src).unwrap_err();
        assert_eq!(e.0[0].kind, ErrorKind::ZeroCount);
        let at = src.find(" 0 ").unwrap() + 1;
        assert_eq!(e.0[0].span, Some(at..at + 1));
    }
}
