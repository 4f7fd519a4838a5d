//! `.od` and `.bed` files into [`Description`], names resolved.
//!
//! The grammar (`stl_` section of `grammar.pest`) reads the header, the
//! sections and the layout, but reads rule bodies and the seed only as
//! chunks of text (one parser token each, spaces and comments included):
//! `lex` tokenises them as a stream into words, brackets, braces, commas
//! and turn symbols, so a generated seed of millions of terms never becomes
//! a token list. This module then
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
//! One file per part: this one holds the entry point and the builder;
//! `header` the stem parameters, `rules` the rule definitions and reserved
//! names, `lex` the tokens and word splitting, `body` rule bodies and
//! `[I n X]`, `seed` the seed's terms, `layout` the shapes, `solid` a 3D layout's
//! volumes.
//!
//! It does not check what needs the whole tree (stem orders, derived size):
//! that is [`crate::bed::validate`].

mod body;
mod header;
mod layout;
mod lex;
mod rules;
mod seed;
mod solid;

use pest::Parser;
use pest::iterators::Pair;

use super::{GrammarParser, Rule, pest_error, precheck};
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, InputError, Span, StlError};
use crate::limits::Limits;
use crate::model::{Description, Format, Loc, RuleId};

pub use header::Param;
pub use layout::ShapeName;
pub use rules::{DRAWING_LETTERS, KEYWORDS, REPEAT_MARK, is_reserved};
pub use solid::SolidName;

/// Parses an Outline Description (`Format::Od`) or a Branch-Expansion
/// Description (`Format::Bed`).
///
/// In a BED a bare rule reference `R1` is stored as the full term with every
/// slot empty (`bare: false`); in an OD it stays a growth point (`bare: true`).
pub fn parse(src: &str, format: Format, limits: &Limits) -> Result<Description, Diagnostics> {
    let src = precheck(src.as_bytes(), limits)?;
    layout::prescan_polygons(src, limits.max_layout_vertices)?;
    rules::prescan_rules(src, limits.max_rule_parts)?;
    layout::prescan_shapes(src, limits.max_layout_shapes)?;
    let mut pairs = GrammarParser::parse(Rule::stl_file, src).map_err(|e| {
        pest_error(e).with_help(
            "a description reads: tree name, root `(x, y)`, stem parameters \
             (`L=10(0) B=1(0)`), `RULE` and its rules (`R1: [+F][-F]`), then optional \
             `SEED ... ENDSEED` and `LAYOUT ... ENDLAYOUT` (see docs/language.md)",
        )
    })?;
    let file = pairs
        .next()
        .expect("grammar: a successful parse of stl_file yields it");
    let mut b = Builder {
        format,
        limits,
        diags: Diagnostics::new(),
        names: Vec::new(),
        by_name: std::collections::HashMap::new(),
        longest_name: 0,
        branches: Vec::new(),
        alternatives: Vec::new(),
        three_d: false,
        flat_root: None,
        turn3_reported: false,
    };
    let desc = b.file(file);
    b.diags.into_result(desc)
}

/// Collects the description and its diagnostics.
struct Builder<'l> {
    format: Format,
    limits: &'l Limits,
    diags: Diagnostics,
    /// Declared rule names, by [`RuleId`](crate::model::RuleId) (invalid
    /// ones as `""`).
    names: Vec<String>,
    /// The first rule of each valid name (looked up, never iterated).
    by_name: std::collections::HashMap<String, RuleId>,
    /// The longest valid name's length in bytes.
    longest_name: usize,
    /// Branch counts by [`RuleId`](crate::model::RuleId).
    branches: Vec<usize>,
    /// How many alternatives the name of each rule has (0: it has one
    /// body, without a probability), by [`RuleId`](crate::model::RuleId).
    alternatives: Vec<usize>,
    /// Whether the first root has three coordinates (section 11: the
    /// description is 3D). Known before the header, bodies, seed and
    /// layout are read: the grammar puts the roots first.
    three_d: bool,
    /// In a 2D description, the first root's span and its text with `, 0`
    /// added (`(150, 298, 0)`), for the hint of what needs a 3D root.
    flat_root: Option<(Span, String)>,
    /// Whether a 3D turn in a 2D description has been reported (the first
    /// one is; the rest would repeat it).
    turn3_reported: bool,
}

/// A root as read: `(x, y)`, its `z` if it has one, and where it is.
type RootRead = ((f64, f64), Option<f64>, Loc);

fn span_of(p: &Pair<'_, Rule>) -> Span {
    let s = p.as_span();
    s.start()..s.end()
}

/// A child the grammar does not allow under `parent`: pest produced a tree
/// `grammar.pest` rules out.
fn not_in_grammar(parent: &str, child: Rule) -> ! {
    unreachable!("grammar: {parent} has no {child:?} child")
}

impl Builder<'_> {
    fn err(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    /// An error at `span` with its label and hint.
    fn report(&mut self, kind: impl Into<ErrorKind>, span: Span, label: &str, help: &str) {
        self.err(
            Diagnostic::error(kind)
                .with_span(span)
                .with_label(label)
                .with_help(help),
        );
    }

    // ------------------------------------------------------------- file --

    fn file(&mut self, file: Pair<'_, Rule>) -> Description {
        let mut name = None;
        let mut roots = Vec::new();
        let mut params = Vec::new();
        let mut defs = Vec::new();
        let mut seed_pairs = Vec::new();
        let mut layout = None;
        for p in file.into_inner() {
            match p.as_rule() {
                Rule::stl_tree_name => name = Some((p.as_str().to_string(), Loc(span_of(&p)))),
                Rule::stl_root => {
                    let loc = Loc(span_of(&p));
                    let text = p.as_str().to_string();
                    let nums: Vec<f64> = p.into_inner().map(|n| self.number(&n)).collect();
                    let z = nums.get(2).copied();
                    if roots.is_empty() {
                        self.three_d = z.is_some();
                        if z.is_none() {
                            let open = text.trim_end().trim_end_matches(')').trim_end();
                            self.flat_root = Some((loc.0.clone(), format!("{open}, 0)")));
                        }
                    } else if z.is_some() != self.three_d {
                        self.mixed_root(&roots, z.is_some(), &loc);
                    }
                    roots.push(((nums[0], nums[1]), z, loc));
                }
                Rule::stl_param => params.push(p),
                Rule::stl_rule_def => defs.push(p),
                Rule::stl_seed => seed_pairs.push(p),
                Rule::stl_layout => layout = Some(self.layout(p)),
                Rule::stl_kw_rule | Rule::EOI => {}
                other => not_in_grammar("stl_file", other),
            }
        }
        let (name, name_loc) = name.expect("grammar: stl_file starts with stl_tree_name");
        let mut roots = roots.into_iter();
        let (root, root_z, root_loc) = roots.next().expect("grammar: stl_file has stl_root");
        let params = self.params(params, &root_loc);
        let rules = self.rules(defs);
        let mut seeds: Vec<_> = seed_pairs.into_iter().map(|p| self.seed(p)).collect();
        let more: Vec<_> = roots.collect();
        let wanted = match self.format {
            Format::Bed if !more.is_empty() => more.len() + 1,
            _ => 1,
        };
        // An OD has one SEED for every root; a BED of a forest one per root,
        // in root order (none: every root grows the default seed).
        if seeds.len() > wanted || (!seeds.is_empty() && seeds.len() != wanted) {
            let (at, label) = if seeds.len() > wanted {
                (seeds[wanted].loc.0.clone(), "this SEED")
            } else {
                // Fewer: the first root without one (roots after the first
                // take the SEEDs after the first, in order).
                (more[seeds.len() - 1].2.0.clone(), "this root has no SEED")
            };
            let help = match self.format {
                Format::Od => "an OD has one SEED, grown from every root: remove the others",
                Format::Bed => "a BED has one SEED per root, in root order",
            };
            self.report(
                StlError::SeedsPerRoot {
                    roots: more.len() + 1,
                    seeds: seeds.len(),
                },
                at,
                label,
                help,
            );
        }
        let mut later = seeds.drain(1.min(seeds.len())..);
        let forest = more
            .into_iter()
            .map(|(root, root_z, root_loc)| crate::model::Tree {
                root,
                root_z,
                root_loc,
                seed: match self.format {
                    Format::Bed => later.next(),
                    Format::Od => None,
                },
            })
            .collect();
        drop(later);
        let seed = seeds.pop();
        Description {
            format: self.format,
            name,
            name_loc,
            root,
            root_z,
            root_loc,
            params,
            rules,
            seed,
            layout,
            forest,
        }
    }

    /// Reports a root whose coordinates are not as many as the first
    /// root's (`roots`, read so far).
    fn mixed_root(&mut self, roots: &[RootRead], three: bool, loc: &Loc) {
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
    fn needs_3d(&mut self, what: String, span: Span, label: &str) {
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
    fn number(&mut self, p: &Pair<'_, Rule>) -> f64 {
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

/// Helpers the parser's unit tests share.
#[cfg(test)]
pub(super) mod testing {
    use crate::diag::Diagnostics;
    use crate::limits::Limits;
    use crate::model::{Description, Format};

    /// A header with two rules: `R1` (one branch) and `R2` (two).
    pub const HEAD: &str = "T (0,0) L=10(0) B=1(0) RULE R1: [F] R2: [F][F] ";

    /// `src` read as a BED with the default limits.
    pub fn bed(src: &str) -> Result<Description, Diagnostics> {
        super::parse(src, Format::Bed, &Limits::default())
    }
}
