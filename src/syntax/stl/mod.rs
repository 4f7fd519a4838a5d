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
//! One file per part: this one holds the entry point and reads the file's
//! parts in order; `builder` the state they all add to and the reports
//! they share, `names` the words a layout line starts with, `header` the stem parameters, `rules` the rule definitions and reserved
//! names, `lex` the tokens and word splitting, `body` rule bodies and
//! `[I n X]`, `seed` the seed's terms, `layout` the shapes, `solid` a 3D layout's
//! volumes.
//!
//! It does not check what needs the whole tree (stem orders, derived size):
//! that is [`crate::bed::validate`].

mod body;
mod builder;
mod header;
mod layout;
mod lex;
mod names;
mod rules;
mod seed;
mod solid;
mod surfaces;

use pest::Parser;
use pest::iterators::Pair;

use super::{GrammarParser, Rule, pest_error, precheck};
use crate::diag::{Diagnostics, StlError};
use crate::limits::Limits;
use crate::model::{Description, Format, Loc};
use builder::{Builder, not_in_grammar, span_of};

pub use header::Param;
pub use names::{ShapeName, SolidName};
pub use rules::{DRAWING_LETTERS, KEYWORDS, REPEAT_MARK, is_reserved};

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

impl Builder<'_> {
    // ------------------------------------------------------------- file --

    fn file(&mut self, file: Pair<'_, Rule>) -> Description {
        let mut name = None;
        let mut roots = Vec::new();
        let mut params = Vec::new();
        let mut defs = Vec::new();
        let mut seed_pairs = Vec::new();
        let mut layout = None;
        let mut surfaces = None;
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
                Rule::stl_surfaces => surfaces = Some(self.surfaces(p)),
                Rule::stl_kw_rule | Rule::EOI => {}
                other => not_in_grammar("stl_file", other),
            }
        }
        let (name, name_loc) = name.expect("grammar: stl_file starts with stl_tree_name");
        let mut roots = roots.into_iter();
        let (root, root_z, root_loc) = roots.next().expect("grammar: stl_file has stl_root");
        let params = self.params(params, &root_loc);
        self.check_leaf(&params, surfaces.as_ref());
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
            surfaces,
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
