//! Rule bodies, built from their tokens with explicit state (no recursion
//! the input can drive), and the `[I n ...]` form both bodies and seeds use.
//!
//! A body is a trunk of drawing runs and fixed figures, and top-level
//! branches `[...]`; brackets nested inside a branch stay part of its
//! drawing. A rule name in a body may only end a top-level branch: it names
//! the rule that grows at that tip.

use super::builder::Builder;
use super::lex::Lex;
use crate::diag::{Diagnostic, InputError, Span, StlError};
use crate::model::{Body, BodyItem, Branch, DrawRun, Fixed, Loc, Piece, Repeat, RuleId, RuleRef};

/// What `[I n ...]` held.
pub(super) enum RepeatBody {
    /// A rule name: a [`Repeat`].
    Rule(Repeat),
    /// Drawing components: a [`Fixed`] figure.
    Word(Fixed),
    /// Already reported.
    Invalid,
}

/// A run of drawing components being collected.
#[derive(Default)]
pub(super) struct Run {
    text: String,
    span: Option<Span>,
}

impl Run {
    /// Appends `c`, written at `span`.
    pub(super) fn push(&mut self, c: char, span: &Span) {
        self.text.push(c);
        self.span = Some(match self.span.take() {
            Some(s) => s.start..span.end,
            None => span.clone(),
        });
    }

    /// Appends `text`, written at `span` (one component a byte).
    pub(super) fn push_str(&mut self, text: &str, span: &Span) {
        self.text.push_str(text);
        self.span = Some(match self.span.take() {
            Some(s) => s.start..span.end,
            None => span.clone(),
        });
    }

    /// The run so far, if any, leaving this one empty.
    pub(super) fn take(&mut self) -> Option<DrawRun> {
        let span = self.span.take()?;
        Some(DrawRun {
            text: std::mem::take(&mut self.text),
            loc: Loc(span),
        })
    }
}

/// A top-level branch whose `[` is open.
struct OpenBranch {
    open: Span,
    pieces: Vec<Piece>,
    run: Run,
    /// Brackets open inside it.
    nested: Vec<Span>,
    successor: Option<RuleRef>,
}

impl Builder<'_> {
    /// Reads `[I n ...]` whose `[I n` (`count`, written at `open`) is
    /// `lex[i]`; returns what it held and the index after it.
    pub(super) fn repeat(
        &mut self,
        lex: &[Lex],
        i: usize,
        count: Option<u32>,
        open: &Span,
    ) -> (RepeatBody, usize) {
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
                Some(Lex::Draws(t, s)) => {
                    word.push_str(t);
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
                        Diagnostic::error(InputError::Unbalanced('['))
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
            self.report(
                StlError::MixedRepeat,
                m,
                "unexpected here",
                "write `[I 3 R1]` for a subtree of R1, or `[I 2 F[+F]F]` for a rewritten figure",
            );
            return (RepeatBody::Invalid, j + 1);
        }
        let Some(count) = count else {
            return (RepeatBody::Invalid, j + 1);
        };
        let body = match rule {
            Some((rule, _)) => RepeatBody::Rule(Repeat {
                count,
                rule,
                loc: Loc(span),
            }),
            None if word.is_empty() => {
                self.report(
                    StlError::EmptyRepeat,
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

    /// A rule body from its tokens.
    pub(super) fn body(&mut self, lex: &[Lex]) -> Body {
        let mut items = Vec::new();
        let mut trunk = Run::default();
        let mut br: Option<OpenBranch> = None;
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
                Lex::Draws(t, s) => match &mut br {
                    Some(b) => b.run.push_str(t, s),
                    None => trunk.push_str(t, s),
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
                        br = Some(OpenBranch {
                            open: s.clone(),
                            pieces: Vec::new(),
                            run: Run::default(),
                            nested: Vec::new(),
                            successor: None,
                        });
                    }
                },
                Lex::Close(s) => match br.take() {
                    Some(mut b) if !b.nested.is_empty() => {
                        b.nested.pop();
                        b.run.push(']', s);
                        br = Some(b);
                    }
                    Some(mut b) => {
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
                Lex::RepeatOpen(count, open) => {
                    let (what, next) = self.repeat(lex, i, *count, open);
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
                        RepeatBody::Rule(r) => self.report(
                            StlError::RepeatInBody,
                            r.loc.0,
                            "a subtree inside a rule",
                            "name the rule at the end of a branch (`[+F R2]`), or put `[I n R2]` in the seed",
                        ),
                        RepeatBody::Invalid => {}
                    }
                    i = next;
                    continue;
                }
                Lex::LBrace(s) => self.term_syntax_in_body('{', s.clone()),
                Lex::RBrace(s) => self.term_syntax_in_body('}', s.clone()),
                Lex::Comma(s) => self.term_syntax_in_body(',', s.clone()),
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

    fn term_syntax_in_body(&mut self, symbol: char, span: Span) {
        self.report(
            StlError::TermSyntaxInBody { symbol },
            span,
            "only in the seed",
            "branch-expansion terms `X{...}` are written in the seed (SEED ... ENDSEED)",
        );
    }

    fn not_at_end(&mut self, span: Span) {
        self.report(
            StlError::NameNotAtBranchEnd,
            span,
            "not at the end of a top-level branch",
            "a name in a body says which rule grows at a branch tip: write it last inside a top-level `[...]`, as in `R1: [+F R2][-F]`",
        );
    }

    /// Reports the unmatched bracket or brace `c` at `span`.
    pub(super) fn unbalanced(&mut self, c: char, span: Span, label: &str) {
        let help = match c {
            '[' => "add the matching `]`",
            ']' => "remove it or add the matching `[` before it",
            '{' => "add the matching `}` after the term's slots",
            '}' => "remove it or add the matching `{` after a rule name",
            other => unreachable!("`{other}` is no bracket or brace"),
        };
        self.err(
            Diagnostic::error(InputError::Unbalanced(c))
                .with_span(span)
                .with_label(label)
                .with_help(help),
        );
    }
}
