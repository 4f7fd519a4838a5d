//! The builder every part of the parser adds to: the description's
//! names and counts read so far, its diagnostics, and the reports parts
//! share. A leaf: the parts (`header`, `rules`, `body`, `seed`, `layout`,
//! `solid`) each add an `impl Builder` of their own.

use pest::iterators::Pair;

use super::super::Rule;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, InputError, Span, StlError};
use crate::limits::Limits;
use crate::model::{Format, Loc, RuleId};

/// Collects the description and its diagnostics.
pub(super) struct Builder<'l> {
    pub(super) format: Format,
    pub(super) limits: &'l Limits,
    pub(super) diags: Diagnostics,
    /// Declared rule names, by [`RuleId`](crate::model::RuleId) (invalid
    /// ones as `""`).
    pub(super) names: Vec<String>,
    /// The first rule of each valid name (looked up, never iterated).
    pub(super) by_name: std::collections::HashMap<String, RuleId>,
    /// The longest valid name's length in bytes.
    pub(super) longest_name: usize,
    /// Branch counts by [`RuleId`](crate::model::RuleId).
    pub(super) branches: Vec<usize>,
    /// How many alternatives the name of each rule has (0: it has one
    /// body, without a probability), by [`RuleId`](crate::model::RuleId).
    pub(super) alternatives: Vec<usize>,
    /// Whether the first root has three coordinates (section 11: the
    /// description is 3D). Known before the header, bodies, seed and
    /// layout are read: the grammar puts the roots first.
    pub(super) three_d: bool,
    /// In a 2D description, the first root's span and its text with `, 0`
    /// added (`(150, 298, 0)`), for the hint of what needs a 3D root.
    pub(super) flat_root: Option<(Span, String)>,
    /// Whether a 3D turn in a 2D description has been reported (the first
    /// one is; the rest would repeat it).
    pub(super) turn3_reported: bool,
}

/// A root as read: `(x, y)`, its `z` if it has one, and where it is.
pub(super) type RootRead = ((f64, f64), Option<f64>, Loc);

pub(super) fn span_of(p: &Pair<'_, Rule>) -> Span {
    let s = p.as_span();
    s.start()..s.end()
}

/// A child the grammar does not allow under `parent`: pest produced a tree
/// `grammar.pest` rules out.
pub(super) fn not_in_grammar(parent: &str, child: Rule) -> ! {
    unreachable!("grammar: {parent} has no {child:?} child")
}

impl Builder<'_> {
    pub(super) fn err(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    /// An error at `span` with its label and hint.
    pub(super) fn report(
        &mut self,
        kind: impl Into<ErrorKind>,
        span: Span,
        label: &str,
        help: &str,
    ) {
        self.err(
            Diagnostic::error(kind)
                .with_span(span)
                .with_label(label)
                .with_help(help),
        );
    }

    /// Reports a root whose coordinates are not as many as the first
    /// root's (`roots`, read so far).
    pub(super) fn mixed_root(&mut self, roots: &[RootRead], three: bool, loc: &Loc) {
        let (first, this) = if three { (2, 3) } else { (3, 2) };
        let help = if three {
            "every root of a forest is 2D or every one 3D: give the first root a third \
             coordinate too, or remove this one's"
        } else {
            "every root of a forest is 2D or every one 3D: give this root a third \
             coordinate, as in `(140, 280, 0)`"
        };
        self.err(
            Diagnostic::error(StlError::MixedRoots { first, this })
                .with_span(loc.0.clone())
                .with_label(format!("{this} coordinates"))
                .with_note_at(roots[0].2.0.clone(), format!("the first root has {first}"))
                .with_help(help),
        );
    }

    /// Reports `what` (a 3D turn, `D=`) at `span` in a 2D description:
    /// a 3D root is needed, the first root shown with `, 0` added.
    pub(super) fn needs_3d(&mut self, what: String, span: Span, label: &str) {
        let mut d = Diagnostic::error(StlError::Needs3d { what })
            .with_span(span)
            .with_label(label);
        if let Some((root, fixed)) = self.flat_root.clone() {
            d = d.with_note_at(root, "a 2D root").with_help(format!(
                "give the root a third coordinate to make the description 3D: `{fixed}` \
                 (docs/language.md, Three dimensions)"
            ));
        }
        self.err(d);
    }

    /// A number of the grammar's `number` rule; a value too large for a
    /// 64-bit float is reported and read as 0.
    pub(super) fn number(&mut self, p: &Pair<'_, Rule>) -> f64 {
        match p.as_str().parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            _ => {
                self.report(
                    InputError::NotFinite {
                        text: p.as_str().to_string(),
                    },
                    span_of(p),
                    "too large to represent",
                    "write a number of ordinary size",
                );
                0.0
            }
        }
    }
}
