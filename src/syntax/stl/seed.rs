//! The seed, `SEED ... ENDSEED`: drawing runs, fixed figures, repeats and
//! branch-expansion terms `R1{R2{,},}`, built with an explicit stack of
//! open terms (no recursion the input can drive).
//!
//! A slot of a term holds one term, one `[I n R1]`, or nothing. In a BED a
//! bare rule name `R1` is the term with every slot empty; in an OD it stays
//! a growth point.

use std::collections::VecDeque;

use pest::iterators::Pair;

use super::super::Rule;
use super::body::{RepeatBody, Run};
use super::builder::{Builder, not_in_grammar, span_of};
use super::lex::{Lex, TextLex};
use super::rules::{KW_ENDSEED, KW_SEED};
use crate::diag::{Diagnostic, RuleError, Span, StlError, plural};
use crate::model::{Format, Loc, Repeat, RuleId, Seed, SeedItem, SlotId, TermId, Terms};

/// A term whose `{` is open.
struct TermFrame {
    /// `None` after a `{` that followed no rule name (already reported).
    rule: Option<RuleId>,
    start: usize,
    open: Span,
    slots: Vec<Option<SlotId>>,
    cur: Option<SlotId>,
    saw_comma: bool,
}

/// A finished term or repeat, to put in a slot or the seed.
enum Made {
    /// A term in the arena, written at `Span`.
    Term(TermId, Span),
    /// `[I n X]`.
    Repeat(Repeat),
}

/// The seed being built.
#[derive(Default)]
struct Out {
    items: Vec<SeedItem>,
    terms: Terms,
    /// Drawing since the last item.
    run: Run,
}

impl Builder<'_> {
    /// The `SEED` section.
    pub(super) fn seed(&mut self, p: Pair<'_, Rule>) -> Seed {
        let span = span_of(&p);
        let mut kw = None;
        let mut closed = false;
        let mut out = Out::default();
        for c in p.into_inner() {
            match c.as_rule() {
                Rule::stl_kw_seed => kw = Some(span_of(&c)),
                Rule::stl_kw_endseed => closed = true,
                Rule::stl_seed_body => out = self.seed_items(c),
                other => not_in_grammar("stl_seed", other),
            }
        }
        if !closed {
            self.err(
                Diagnostic::error(StlError::UnclosedSection {
                    open: KW_SEED,
                    close: KW_ENDSEED,
                })
                .with_span(kw.expect("grammar: stl_seed starts with `SEED`"))
                .with_label("this section is never closed")
                .with_help(format!("end the seed with `{KW_ENDSEED}`")),
            );
        }
        Seed {
            items: out.items,
            terms: out.terms,
            loc: Loc(span),
        }
    }

    /// The seed's items from its text, read as a stream of tokens (see
    /// [`TextLex`]): memory for the terms built, not for their tokens.
    fn seed_items(&mut self, body: Pair<'_, Rule>) -> Out {
        let mut texts = body.into_inner().map(|t| {
            debug_assert_eq!(t.as_rule(), Rule::stl_seed_text);
            TextLex::new(t.as_str(), t.as_span().start())
        });
        let mut lexer = texts.next();
        // Tokens read past the end of a `[I n ...]` form, to take first.
        let mut back: VecDeque<Lex> = VecDeque::new();
        let mut pull = |b: &mut Self, back: &mut VecDeque<Lex>| loop {
            if let Some(l) = back.pop_front() {
                return Some(l);
            }
            let lx = lexer.as_mut()?;
            match lx.next(b) {
                Some(l) => return Some(l),
                None => lexer = texts.next(),
            }
        };
        let mut out = Out::default();
        let mut brackets: Vec<Span> = Vec::new();
        let mut stack: Vec<TermFrame> = Vec::new();
        // A rule name whose `{` may follow.
        let mut pending: Option<(RuleId, Span)> = None;
        while let Some(l) = pull(self, &mut back) {
            if !matches!(l, Lex::LBrace(_))
                && let Some((id, s)) = pending.take()
            {
                let t = self.bare(&mut out.terms, id, s);
                self.deliver(t, &mut stack, &mut out);
            }
            match l {
                Lex::Name(id, s) => pending = Some((id, s)),
                Lex::LBrace(s) => {
                    let (rule, start) = match pending.take() {
                        Some((id, ns)) => {
                            self.names_alternative(id, &ns, true);
                            (Some(id), ns.start)
                        }
                        None => {
                            // Right after a word already reported (an
                            // unknown rule or alternative), the `{` is that
                            // word's: no second error.
                            let after_error = self
                                .diags
                                .iter()
                                .last()
                                .and_then(|d| d.span.as_ref())
                                .is_some_and(|e| e.end == s.start);
                            if !after_error {
                                self.report(
                                    StlError::BraceWithoutRule,
                                    s.clone(),
                                    "no rule before it",
                                    "write the rule whose slots these are before `{`, as in `R1{,}`",
                                );
                            }
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
                    None => self.report(
                        StlError::CommaOutsideTerm,
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
                            let m = self.branches[rule.0];
                            // `R0{}` for a rule without branches.
                            if m == 0 && !f.saw_comma && f.slots == [None] {
                                f.slots.clear();
                            }
                            let span = f.start..s.end;
                            if f.slots.len() != m {
                                self.slot_count(rule, f.slots.len(), span.clone());
                            }
                            let t = out.terms.push(rule, false, span.clone(), &f.slots);
                            self.deliver(Made::Term(t, span), &mut stack, &mut out);
                        }
                    }
                    None => self.unbalanced('}', s.clone(), "this `}` closes nothing"),
                },
                Lex::RepeatOpen(count, open) => {
                    // The form's tokens up to its `]` (or what ends it early).
                    let mut form = vec![Lex::RepeatOpen(count, open.clone())];
                    let mut depth = 0usize;
                    while let Some(t) = pull(self, &mut back) {
                        let last = match &t {
                            Lex::Close(_) if depth == 0 => true,
                            Lex::Close(_) => {
                                depth -= 1;
                                false
                            }
                            Lex::Open(_) => {
                                depth += 1;
                                false
                            }
                            Lex::LBrace(_)
                            | Lex::RBrace(_)
                            | Lex::Comma(_)
                            | Lex::RepeatOpen(..) => true,
                            _ => false,
                        };
                        form.push(t);
                        if last {
                            break;
                        }
                    }
                    let (what, next) = self.repeat(&form, 0, count, &open);
                    for t in form.drain(next..).rev() {
                        back.push_front(t);
                    }
                    match what {
                        RepeatBody::Rule(r) => {
                            self.repeat_chooses(&r);
                            self.deliver(Made::Repeat(r), &mut stack, &mut out);
                        }
                        RepeatBody::Word(f) => {
                            if stack.is_empty() {
                                if let Some(r) = out.run.take() {
                                    out.items.push(SeedItem::Draw(Box::new(r)));
                                }
                                out.items.push(SeedItem::Fixed(Box::new(f)));
                            } else {
                                self.in_slot(f.loc.0);
                            }
                        }
                        RepeatBody::Invalid => {}
                    }
                }
                Lex::Draw(_, s) | Lex::Open(s) | Lex::Close(s) if !stack.is_empty() => {
                    self.in_slot(s.clone());
                }
                Lex::Draws(t, s) if !stack.is_empty() => {
                    // One report a component, as separate tokens had.
                    for k in 0..t.len() {
                        self.in_slot(s.start + k..s.start + k + 1);
                    }
                }
                Lex::Draw(c, s) => out.run.push(c, &s),
                Lex::Draws(t, s) => out.run.push_str(&t, &s),
                Lex::Open(s) => {
                    out.run.push('[', &s);
                    brackets.push(s);
                }
                Lex::Close(s) => {
                    if brackets.pop().is_some() {
                        out.run.push(']', &s);
                    } else {
                        self.unbalanced(']', s.clone(), "this `]` closes nothing");
                    }
                }
            }
        }
        if let Some((id, s)) = pending.take() {
            let t = self.bare(&mut out.terms, id, s);
            self.deliver(t, &mut stack, &mut out);
        }
        for f in stack.iter().rev() {
            self.unbalanced('{', f.open.clone(), "this `{` is never closed");
        }
        for b in brackets.iter().rev() {
            self.unbalanced('[', b.clone(), "this `[` is never closed");
        }
        if let Some(r) = out.run.take() {
            out.items.push(SeedItem::Draw(Box::new(r)));
        }
        out
    }

    fn in_slot(&mut self, span: Span) {
        self.report(
            StlError::DrawingInSlot,
            span,
            "inside a term's `{...}`",
            "a slot holds one term (`R1{,}`), one `[I n R1]`, or nothing; drawing belongs in rule bodies",
        );
    }

    fn slot_count(&mut self, rule: RuleId, found: usize, span: Span) {
        let name = self.names[rule.0].clone();
        let expected = self.branches[rule.0];
        let empty = format!("{name}{{{}}}", ",".repeat(expected.saturating_sub(1)));
        self.err(
            Diagnostic::error(RuleError::SlotCount {
                rule: name.clone(),
                expected,
                found,
            })
            .with_span(span)
            .with_label(format!("{found} slot{} here", plural(found, "s")))
            .with_help(format!(
                "`{name}` has {expected} branch{}: write one slot per branch, separated by commas (all empty: `{empty}`)",
                plural(expected, "es")
            )),
        );
    }

    /// The term a bare rule name `R1` stands for.
    fn bare(&mut self, terms: &mut Terms, rule: RuleId, span: Span) -> Made {
        let bare = self.format == Format::Od;
        self.names_alternative(rule, &span, !bare);
        let id = terms.push_leaf(rule, bare, span.clone(), self.branches[rule.0]);
        Made::Term(id, span)
    }

    /// Reports a term that must say which alternative grew and does not:
    /// in a BED every term names its alternative (`R1.2`, not `R1`); in an
    /// OD a term written out (`R1{,}`, `written`) cannot, since growth
    /// chooses the body.
    fn names_alternative(&mut self, rule: RuleId, span: &Span, written: bool) {
        let count = self.alternatives[rule.0];
        let named = span.len() == self.names[rule.0].len() && self.format == Format::Bed;
        if count == 0 || named || !written {
            return;
        }
        let name = self.names[rule.0]
            .split('.')
            .next()
            .unwrap_or_default()
            .to_string();
        let help = match self.format {
            Format::Bed => format!("write which one grew: `{name}.1` to `{name}.{count}`"),
            Format::Od => format!(
                "growth chooses the body of `{name}`: write a growth point `{name}` (no braces)"
            ),
        };
        self.report(
            RuleError::AlternativeNotNamed { name, count },
            span.clone(),
            "which alternative?",
            &help,
        );
    }

    /// Reports a BED's repeat of a rule with alternatives: every level it
    /// unrolls would have to choose a body, and a BED never chooses.
    fn repeat_chooses(&mut self, r: &Repeat) {
        let count = self.alternatives[r.rule.0];
        if self.format != Format::Bed || count == 0 {
            return;
        }
        let name = self.names[r.rule.0]
            .split('.')
            .next()
            .unwrap_or_default()
            .to_string();
        let help = format!(
            "write the terms that grew (`{name}.1{{...}}` to `{name}.{count}{{...}}`), as `stlc compile` does"
        );
        self.report(
            RuleError::RepeatChooses { name, count },
            r.loc.0.clone(),
            "a repeat that would choose",
            &help,
        );
    }

    /// Puts a finished term or repeat where it belongs: the open slot of the
    /// innermost open term, or the seed.
    fn deliver(&mut self, made: Made, stack: &mut [TermFrame], out: &mut Out) {
        match stack.last_mut() {
            Some(f) => {
                if f.cur.is_some() {
                    let span = match made {
                        Made::Term(_, span) => span,
                        Made::Repeat(r) => r.loc.0,
                    };
                    self.report(
                        StlError::TwoTermsInSlot,
                        span,
                        "second term in this slot",
                        "separate slots with `,`; to grow more at one tip, give the rule more branches",
                    );
                } else {
                    f.cur = Some(match made {
                        Made::Term(t, _) => Terms::slot_of(t),
                        Made::Repeat(r) => out.terms.repeat(r),
                    });
                }
            }
            None => {
                if let Some(r) = out.run.take() {
                    out.items.push(SeedItem::Draw(Box::new(r)));
                }
                out.items.push(match made {
                    Made::Term(t, _) => SeedItem::Term(t),
                    Made::Repeat(r) => SeedItem::Repeat(Box::new(r)),
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::diag::{ErrorKind, InputError, RuleError, StlError};
    use crate::model::SeedItem;

    use super::super::testing::{HEAD, bed};

    /// A generated seed of a million drawing components is one run: one
    /// item, its text exactly (the parser holds one token for it, not two
    /// per character). Keywords still end a run that touches them.
    #[test]
    fn a_long_flat_seed_is_one_run_and_keywords_still_end_it() {
        let body = "F+F-".repeat(250_000);
        let d = bed(&format!("{HEAD} SEED {body} ENDSEED")).unwrap();
        let items = &d.seed.unwrap().items;
        assert_eq!(items.len(), 1);
        assert!(matches!(&items[0], SeedItem::Draw(r) if r.text == body));
        // `F+ENDSEED`: the run stops before the keyword, which closes the
        // seed; `FENDSEED` is one word, not `F` and a keyword (its unknown
        // name is reported; the seed stays open to the real `ENDSEED`).
        let d = bed(&format!("{HEAD} SEED F+ENDSEED")).unwrap();
        assert!(matches!(&d.seed.unwrap().items[..], [SeedItem::Draw(r)] if r.text == "F+"));
        let e = bed(&format!("{HEAD} SEED FENDSEED ENDSEED")).unwrap_err();
        assert!(
            matches!(&e.0[0].kind, ErrorKind::Rule(RuleError::UnknownRule { .. })),
            "{e}"
        );
        assert!(
            !e.iter()
                .any(|d| matches!(d.kind, ErrorKind::Stl(StlError::UnclosedSection { .. })))
        );
        // Rule names inside a run split it: `FF+R1-F` is a run, a term and
        // a run.
        let d = bed(&format!("{HEAD} SEED FF+R1-F ENDSEED")).unwrap();
        let seed = d.seed.unwrap();
        let items = &seed.items;
        assert_eq!(items.len(), 3, "{items:?}");
        assert!(matches!(&items[0], SeedItem::Draw(r) if r.text == "FF+"));
        assert!(
            matches!(&items[1], SeedItem::Term(t) if seed.term(*t).rule() == crate::model::RuleId(0))
        );
        assert!(matches!(&items[2], SeedItem::Draw(r) if r.text == "-F"));
    }

    /// The seed is tokenised in Rust from one parser token: spaces,
    /// newlines and comments anywhere between tokens (and inside `[I n`)
    /// read as the compact form does, and every span points into the file.
    #[test]
    fn spaced_and_commented_seeds_read_as_the_compact_form() {
        let compact = bed(&format!(
            "{HEAD} SEED F+R2{{R1{{}},[I 2 R1]}}[+F]-F ENDSEED"
        ))
        .unwrap();
        let spaced_src = format!(
            "{HEAD} SEED F +\n  R2 {{ # first slot\n R1{{ }} ,\n\t[ # count next\n I 2 R1 ] }}\n [ + F ] - F\nENDSEED"
        );
        let spaced = bed(&spaced_src).unwrap();
        assert!(compact.seed == spaced.seed);
        let seed = spaced.seed.unwrap();
        let spans: Vec<&str> = seed
            .items
            .iter()
            .map(|i| &spaced_src[seed.item_span(i)])
            .collect();
        assert_eq!(
            spans,
            [
                "F +",
                "R2 { # first slot\n R1{ } ,\n\t[ # count next\n I 2 R1 ] }",
                "[ + F ] - F"
            ]
        );
        // `#abc` is a colour, not a comment, so the seed stops there.
        let e = bed(&format!("{HEAD} SEED F #abc ENDSEED")).unwrap_err();
        assert!(
            matches!(e.0[0].kind, ErrorKind::Input(InputError::Syntax(_))),
            "{e}"
        );
    }

    #[test]
    fn a_slot_holds_one_term() {
        let src = format!("{HEAD} SEED R2{{R1{{}}R1{{}},}} ENDSEED");
        let e = bed(&src).unwrap_err();
        assert_eq!(e.0[0].kind, ErrorKind::Stl(StlError::TwoTermsInSlot));
        let second = src.rfind("R1{}").unwrap();
        assert_eq!(e.0[0].span, Some(second..second + 4));
        let src = format!("{HEAD} SEED R2{{F,}} ENDSEED");
        let e = bed(&src).unwrap_err();
        assert_eq!(e.0[0].kind, ErrorKind::Stl(StlError::DrawingInSlot));
        let f = src.find("{F").unwrap() + 1;
        assert_eq!(e.0[0].span, Some(f..f + 1));
    }

    #[test]
    fn empty_braces_fit_zero_or_one_branch() {
        let d = bed("T (0,0) RULE R0: F R1: [F] SEED R0{} R1{} ENDSEED").unwrap();
        let seed = d.seed.unwrap();
        let term = |i: usize| match &seed.items[i] {
            SeedItem::Term(t) => seed.term(*t),
            other => panic!("{other:?} is no term"),
        };
        assert_eq!(term(0).slot_count(), 0);
        assert!(term(1).slot_count() == 1 && term(1).all_empty());
    }

    #[test]
    fn a_comma_outside_a_term_separates_nothing() {
        let src = format!("{HEAD} SEED R1, R1 ENDSEED");
        let e = bed(&src).unwrap_err();
        assert_eq!(e.0[0].kind, ErrorKind::Stl(StlError::CommaOutsideTerm));
        let at = src.rfind(',').unwrap();
        assert_eq!(e.0[0].span, Some(at..at + 1));
    }
}
