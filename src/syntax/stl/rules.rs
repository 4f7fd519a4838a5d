//! Rule definitions under `RULE`: their names (reserved, malformed,
//! duplicate) and bodies, and the names a rule may not have.

use pest::iterators::Pair;

use super::{Builder, Rule, span_of};
use crate::diag::{Diagnostic, ErrorKind, Span};
use crate::model::{Loc, RuleDef};

/// The drawing letters of bodies and seeds. A word's leftovers after the
/// rule names are taken out must be these.
pub const DRAWING_LETTERS: &[char] = &['F', 'f', 'L', 'R'];

/// The `I` of the self-resemblance form `[I n X]`.
pub const REPEAT_MARK: &str = "I";

pub(super) const KW_RULE: &str = "RULE";
pub(super) const KW_SEED: &str = "SEED";
pub(super) const KW_ENDSEED: &str = "ENDSEED";
pub(super) const KW_LAYOUT: &str = "LAYOUT";
pub(super) const KW_ENDLAYOUT: &str = "ENDLAYOUT";

/// The section keywords (`grammar.pest` spells them again in its
/// `stl_kw_*` rules, as pest must).
pub const KEYWORDS: &[&str] = &[KW_RULE, KW_SEED, KW_ENDSEED, KW_LAYOUT, KW_ENDLAYOUT];

/// Whether `name` may not name a rule: a drawing letter, [`REPEAT_MARK`]
/// or one of the [`KEYWORDS`].
pub fn is_reserved(name: &str) -> bool {
    let mut chars = name.chars();
    let letter =
        matches!((chars.next(), chars.next()), (Some(c), None) if DRAWING_LETTERS.contains(&c));
    letter || name == REPEAT_MARK || KEYWORDS.contains(&name)
}

impl Builder<'_> {
    /// The rule definitions: names first, so bodies and the seed may refer
    /// to any rule, then each body.
    pub(super) fn rules(&mut self, defs: Vec<Pair<'_, Rule>>) -> Vec<RuleDef> {
        // Names as written and their spans, by `RuleId`.
        let mut heads: Vec<(String, Span)> = Vec::new();
        for d in &defs {
            let n = d.clone().into_inner().next();
            let n = n.expect("grammar: stl_rule_def starts with stl_rule_name");
            let name = n.as_str().to_string();
            let span = span_of(&n);
            let valid = self.check_name(&name, &span, &heads);
            heads.push((name.clone(), span));
            self.names.push(if valid { name } else { String::new() });
        }
        let mut bodies = Vec::new();
        for d in &defs {
            let body = d
                .clone()
                .into_inner()
                .find(|p| p.as_rule() == Rule::stl_body);
            if body.is_none() {
                let defines = d
                    .clone()
                    .into_inner()
                    .find(|p| p.as_rule() == Rule::stl_defines)
                    .expect("grammar: stl_rule_def has `:` or `=`");
                let at = span_of(&defines).end;
                self.err(
                    Diagnostic::error(ErrorKind::MissingBody)
                        .with_span(at..at)
                        .with_label("the rule ends here")
                        .with_help("write what the rule draws, e.g. `R1: [+F][-F]`"),
                );
            }
            let lex = body.map(|b| self.lex(b)).unwrap_or_default();
            bodies.push(lex);
        }
        let mut out = Vec::new();
        for ((d, (name, span)), lex) in defs.iter().zip(heads).zip(bodies) {
            let body = self.body(&lex);
            out.push(RuleDef {
                name,
                name_loc: Loc(span),
                body,
                loc: Loc(span_of(d)),
            });
        }
        self.branches = out.iter().map(RuleDef::branch_count).collect();
        out
    }

    /// Whether `name` may name a rule (else reports why); `heads` are the
    /// names before it.
    fn check_name(&mut self, name: &str, span: &Span, heads: &[(String, Span)]) -> bool {
        if is_reserved(name) {
            let letters: Vec<String> = DRAWING_LETTERS.iter().map(char::to_string).collect();
            self.report(
                ErrorKind::ReservedName {
                    name: name.to_string(),
                },
                span.clone(),
                "reserved name",
                &format!(
                    "`{}` are drawing components, `{REPEAT_MARK}` starts `[{REPEAT_MARK} n X]`, \
                     and the section keywords are taken: choose another name, e.g. `R1`",
                    letters.join(" ")
                ),
            );
            return false;
        }
        if !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
            self.report(
                ErrorKind::RuleNameNotLetter {
                    name: name.to_string(),
                },
                span.clone(),
                "not a rule name",
                "a rule name is a letter followed by letters, digits or `_`, e.g. `R1`",
            );
            return false;
        }
        if let Some(i) = self.names.iter().position(|x| x == name) {
            self.err(
                Diagnostic::error(ErrorKind::DuplicateRule {
                    name: name.to_string(),
                })
                .with_span(span.clone())
                .with_label("defined again here")
                .with_note_at(heads[i].1.clone(), "first defined here")
                .with_help("rename one of them or merge their bodies"),
            );
            return false;
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reserved_names_are_the_letters_the_mark_and_the_keywords() {
        for name in [
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
        ] {
            assert!(is_reserved(name), "{name}");
        }
        for name in ["FF", "r", "R1", "Seed", "I2", ""] {
            assert!(!is_reserved(name), "{name}");
        }
    }
}
