//! Rule definitions under `RULE`: their names (reserved, malformed,
//! duplicate) and bodies, and the names a rule may not have.

use pest::iterators::Pair;

use super::super::Rule;
use super::builder::{Builder, span_of};
use crate::choice::{self, BadProbabilities};
use crate::diag::Help;
use crate::diag::{Diagnostic, Diagnostics, RuleError, Span};
use crate::limits::Bound;
use crate::model::{Alternative, Format, Loc, RuleDef, RuleId};

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

/// Refuses a `RULE` section of more parts (definitions, and top-level
/// bracket groups of bodies: branches and fixed figures) than
/// `--max-rule-parts` before the parser reads it. Each part costs the
/// parser and the model a few hundred bytes, whatever its length, so a
/// generated section of millions of tiny parts would cost far more than
/// its text (docs/limits.md). A byte scan from `RULE` to the next `SEED`
/// or `LAYOUT`, comments skipped.
pub(super) fn prescan_rules(src: &str, max_parts: usize) -> Result<(), Diagnostics> {
    let Some(start) = find_word(src, 0, KW_RULE) else {
        return Ok(());
    };
    let from = start + KW_RULE.len();
    let end = [KW_SEED, KW_LAYOUT]
        .iter()
        .filter_map(|kw| find_word(src, from, kw))
        .min()
        .unwrap_or(src.len());
    let b = &src.as_bytes()[..end];
    let (mut parts, mut depth, mut i) = (0usize, 0usize, from);
    while i < b.len() {
        match b[i] {
            b'#' => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b':' | b'=' => parts += 1,
            b'[' => {
                if depth == 0 {
                    parts += 1;
                }
                depth += 1;
            }
            b']' => depth = depth.saturating_sub(1),
            _ => {}
        }
        i += 1;
    }
    if parts <= max_parts {
        return Ok(());
    }
    Err(Bound::RuleParts
        .exceeded(parts, max_parts as u64)
        .with_span(start..from)
        .with_label("this section")
        .with_help(Help::from("use fewer rules or branches, or ") + Bound::RuleParts)
        .into())
}

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

/// The first occurrence of `word` at or after `from` that stands alone
/// (no name character on either side).
pub(super) fn find_word(src: &str, from: usize, word: &str) -> Option<usize> {
    let b = src.as_bytes();
    let name = |c: u8| c.is_ascii_alphanumeric() || c == b'_';
    let mut at = from;
    while let Some(k) = src.get(at..)?.find(word) {
        let p = at + k;
        let before = p == 0 || !name(b[p - 1]);
        let after = b.get(p + word.len()).is_none_or(|&c| !name(c));
        if before && after {
            return Some(p);
        }
        at = p + word.len();
    }
    None
}

impl Builder<'_> {
    /// The rule definitions: names first, so bodies and the seed may refer
    /// to any rule, then each body.
    pub(super) fn rules(&mut self, defs: Vec<Pair<'_, Rule>>) -> Vec<RuleDef> {
        // Names as written and their spans, by `RuleId`.
        let mut heads: Vec<(String, Span)> = Vec::new();
        let mut alternatives: Vec<Option<Alternative>> = Vec::new();
        for d in &defs {
            let mut inner = d.clone().into_inner();
            let n = inner.next();
            let n = n.expect("grammar: stl_rule_def starts with stl_rule_name");
            let written = n.as_str().to_string();
            let span = span_of(&n);
            let probability = inner
                .next()
                .filter(|p| p.as_rule() == Rule::stl_probability)
                .map(|p| {
                    let num = p.into_inner().next();
                    self.number(&num.expect("grammar: stl_probability holds a number"))
                });
            let (name, alternative) = self.split_alternative(&written, &span, probability);
            let valid = !name.is_empty()
                && self.check_name(&name, &written, &span, &heads, &alternatives, &alternative);
            if valid && !self.by_name.contains_key(&written) {
                self.by_name
                    .insert(written.clone(), RuleId(self.names.len()));
                self.longest_name = self.longest_name.max(written.len());
            }
            // A BED's body names the rule a branch grows (`R1`) without
            // its alternative: the name stands for the first one.
            if valid && alternative.is_some() && !self.by_name.contains_key(&name) {
                self.by_name.insert(name.clone(), RuleId(self.names.len()));
            }
            self.names.push(if valid { written } else { String::new() });
            heads.push((name, span));
            alternatives.push(alternative);
        }
        if self.format == Format::Od {
            self.check_alternatives(&heads, &mut alternatives);
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
                    Diagnostic::error(RuleError::MissingBody)
                        .with_span(at..at)
                        .with_label("the rule ends here")
                        .with_help("write what the rule draws, e.g. `R1: [+F][-F]`"),
                );
            }
            // The definition ends with its body's last chunk, not with the
            // spaces and comments the parser skipped after it.
            let end = body
                .as_ref()
                .and_then(|b| b.clone().into_inner().last())
                .map_or(span_of(d).end, |t| t.as_span().end());
            let lex = body.map(|b| self.lex(b)).unwrap_or_default();
            bodies.push((lex, end));
        }
        let mut out = Vec::new();
        for (((d, (name, span)), (lex, end)), alternative) in
            defs.iter().zip(heads).zip(bodies).zip(alternatives)
        {
            let body = self.body(&lex);
            out.push(RuleDef {
                name,
                name_loc: Loc(span),
                alternative,
                body,
                loc: Loc(span_of(d).start..end),
            });
        }
        self.branches = out.iter().map(RuleDef::branch_count).collect();
        let mut per_name: std::collections::BTreeMap<&str, usize> = Default::default();
        for r in out.iter().filter(|r| r.alternative.is_some()) {
            *per_name.entry(&r.name).or_default() += 1;
        }
        self.alternatives = out
            .iter()
            .map(|r| match r.alternative {
                None => 0,
                Some(_) => per_name[r.name.as_str()],
            })
            .collect();
        out
    }

    /// A rule's name as written into its name and alternative: in an OD,
    /// `R1 (0.6)` (the number is given later, by line order); in a BED,
    /// `R1.2 (0.6)` or `R1.2`. A dot in an OD, or a BED's number that is
    /// not a whole number from 1, is reported (the name comes back empty).
    fn split_alternative(
        &mut self,
        written: &str,
        span: &Span,
        probability: Option<f64>,
    ) -> (String, Option<Alternative>) {
        let Some((name, number)) = written.split_once('.') else {
            if self.format == Format::Bed && probability.is_some() {
                // A BED chooses nothing: a probability only annotates a
                // recorded alternative (`R1.1 (0.5)`).
                self.report(
                    RuleError::ProbabilityWithoutAlternative {
                        name: written.to_string(),
                    },
                    span.clone(),
                    "a probability on a rule with one body",
                    &format!(
                        "in a BED a probability belongs to a recorded alternative: \
                         `{written}.1 (0.5): ...`; or drop it: `{written}: ...`"
                    ),
                );
                return (written.to_string(), None);
            }
            let alternative = probability.map(|p| Alternative {
                number: 0,
                probability: Some(p),
            });
            return (written.to_string(), alternative);
        };
        let number = number.parse::<u32>().ok().filter(|&n| n >= 1);
        match (self.format, number) {
            (Format::Bed, Some(number)) => (
                name.to_string(),
                Some(Alternative {
                    number,
                    probability,
                }),
            ),
            (format, _) => {
                let help = if format == Format::Od {
                    format!(
                        "a dot is reserved for the alternatives a BED records (`{name}.1`); \
                         rename the rule (`{name}_{n}`), or give `{name}` several bodies \
                         with probabilities: `{name} (0.6): ...` and `{name} (0.4): ...`",
                        n = written.split_once('.').map_or("", |x| x.1)
                    )
                } else {
                    format!("alternatives are numbered from 1: `{name}.1`, `{name}.2`")
                };
                self.report(
                    RuleError::DottedName {
                        name: written.to_string(),
                    },
                    span.clone(),
                    "not a rule name here",
                    &help,
                );
                (String::new(), None)
            }
        }
    }

    /// In an OD: the bodies of one name are its alternatives, numbered in
    /// line order; each needs a probability and together they sum to 1.
    fn check_alternatives(
        &mut self,
        heads: &[(String, Span)],
        alternatives: &mut [Option<Alternative>],
    ) {
        // The alternatives of each name, in line order, and the names with
        // a body that has no probability.
        let mut groups: std::collections::BTreeMap<&str, Vec<usize>> = Default::default();
        let mut unweighted = std::collections::BTreeSet::new();
        for (j, (name, _)) in heads.iter().enumerate() {
            if name.is_empty() {
                continue;
            }
            if alternatives[j].is_some() {
                groups.entry(name).or_default().push(j);
            }
            if alternatives[j]
                .as_ref()
                .is_none_or(|a| a.probability.is_none())
            {
                unweighted.insert(name.as_str());
            }
        }
        for (name, group) in groups {
            let name = name.to_string();
            let probabilities: Vec<f64> = group
                .iter()
                .map(|&j| {
                    alternatives[j]
                        .as_ref()
                        .and_then(|a| a.probability)
                        .unwrap_or(0.0)
                })
                .collect();
            for (k, &j) in group.iter().enumerate() {
                if let Some(a) = &mut alternatives[j] {
                    a.number = k as u32 + 1;
                }
            }
            if unweighted.contains(name.as_str()) {
                // Reported where the body without one is: a sum of the
                // others would only repeat it.
                continue;
            }
            match choice::check(&probabilities) {
                Ok(()) => {}
                Err(BadProbabilities::NotPositive(k)) => self.report(
                    RuleError::BadProbability {
                        name: name.clone(),
                        value: probabilities[k],
                    },
                    heads[group[k]].1.clone(),
                    "this alternative's probability",
                    "a probability is a number above 0, e.g. `(0.5)`",
                ),
                Err(BadProbabilities::Sum(sum)) => {
                    let mut d = Diagnostic::error(RuleError::ProbabilitySum {
                        name: name.clone(),
                        sum,
                    })
                    .with_span(heads[group[0]].1.clone())
                    .with_label("first alternative");
                    for &j in group.iter().skip(1).take(4) {
                        d = d.with_note_at(heads[j].1.clone(), "another alternative");
                    }
                    self.err(d.with_help(if group.len() == 1 {
                        format!(
                            "a rule with one body needs no probability: write `{name}: ...`, \
                             or give `{name}` more bodies whose probabilities add up to 1"
                        )
                    } else {
                        "make the probabilities of a rule's alternatives add up to 1, \
                         e.g. `(0.6)` and `(0.4)`"
                            .to_string()
                    }));
                }
            }
        }
    }

    /// Whether `name` (written `written`) may name a rule (else reports
    /// why); `heads` and `alternatives` are the definitions before it.
    /// In an OD a name may have several bodies if each has a probability.
    fn check_name(
        &mut self,
        name: &str,
        written: &str,
        span: &Span,
        heads: &[(String, Span)],
        alternatives: &[Option<Alternative>],
        alternative: &Option<Alternative>,
    ) -> bool {
        if is_reserved(name) {
            let letters: Vec<String> = DRAWING_LETTERS.iter().map(char::to_string).collect();
            self.report(
                RuleError::ReservedName {
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
                RuleError::RuleNameNotLetter {
                    name: name.to_string(),
                },
                span.clone(),
                "not a rule name",
                "a rule name is a letter followed by letters, digits or `_`, e.g. `R1`",
            );
            return false;
        }
        // In an OD `written` is `name`; a BED's alternatives differ in it.
        if let Some(&RuleId(i)) = self.by_name.get(written) {
            if self.format == Format::Od {
                match (alternatives[i].is_some(), alternative.is_some()) {
                    (true, true) => return true,
                    (false, false) => {}
                    (first, _) => {
                        let (at, other) = if first {
                            (span.clone(), heads[i].1.clone())
                        } else {
                            (heads[i].1.clone(), span.clone())
                        };
                        self.err(
                            Diagnostic::error(RuleError::MissingProbability {
                                name: name.to_string(),
                            })
                            .with_span(at)
                            .with_label("no probability")
                            .with_note_at(other, "an alternative with one")
                            .with_help(format!(
                                "a rule with several bodies chooses among them: give each \
                                 a probability, `{name} (0.5): ...`"
                            )),
                        );
                        return false;
                    }
                }
            }
            self.err(
                Diagnostic::error(RuleError::DuplicateRule {
                    name: written.to_string(),
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
    use super::prescan_rules;

    /// A body is read from chunks of text: spaces and comments inside it
    /// change nothing, and a definition's span ends at its body's last
    /// symbol, not at the comment or spaces before the next definition.
    #[test]
    fn bodies_read_through_spaces_and_comments() {
        use super::super::testing::bed;
        let src = "T (0,0) L=1(0) B=1(0) RULE R1: [ + F ] # note: [x]\n [ -F R2 ]  # end\n R2 = F [I 2 F] SEED R1{,} ENDSEED";
        let spaced = bed(src).unwrap();
        let compact =
            bed("T (0,0) L=1(0) B=1(0) RULE R1:[+F][-F R2] R2=F[I 2 F] SEED R1{,} ENDSEED")
                .unwrap();
        assert!(spaced.rules == compact.rules);
        assert_eq!(
            &src[spaced.rules[0].loc.0.clone()],
            "R1: [ + F ] # note: [x]\n [ -F R2 ]"
        );
        assert_eq!(&src[spaced.rules[1].loc.0.clone()], "R2 = F [I 2 F]");
    }

    /// Definitions and top-level bracket groups count; nested brackets,
    /// comments and anything after `SEED` do not.
    #[test]
    fn rule_parts_are_counted_before_parsing() {
        let src =
            "T (0,0) L=1(0) B=1(0) RULE R1: [+F[F]][-F] # [x]: [y]\n R2=[I 2 F]F SEED [F] ENDSEED";
        // R1:, [+F[F]], [-F], R2=, [I 2 F]: five.
        assert!(prescan_rules(src, 5).is_ok());
        let e = prescan_rules(src, 4).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            crate::diag::ErrorKind::Limit {
                bound: crate::limits::Bound::RuleParts,
                what: None,
                value: "5".into(),
                limit: 4
            }
        );
        let at = src.find("RULE").unwrap();
        assert_eq!(e.0[0].span, Some(at..at + 4));
    }

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
