//! The generated pest parser and what its rules look like to a user.
//!
//! [`Rule`] and [`GrammarParser`] are crate-private: callers get typed trees
//! and [`Diagnostic`]s, never pest pairs. [`describe`] is the one place a
//! grammar rule is put into words; it matches every rule, so a rule added to
//! `grammar.pest` does not compile until it has a description.

use crate::diag::{Diagnostic, InputError};

mod parser {
    //! The generated parser; `Rule` names are the grammar's.
    #![allow(missing_docs)]

    /// The pest parser for `grammar.pest` (found from `CARGO_MANIFEST_DIR`).
    #[derive(pest_derive::Parser)]
    #[grammar = "grammar.pest"]
    pub struct GrammarParser;
}

pub(crate) use parser::{GrammarParser, Rule};

/// Turns a pest error into a diagnostic whose message names what the user
/// would type, not grammar rule names.
pub(crate) fn pest_error(e: pest::error::Error<Rule>) -> Diagnostic {
    use pest::error::{ErrorVariant, InputLocation};
    let span = match e.location {
        InputLocation::Pos(p) => p..p,
        InputLocation::Span((a, b)) => a..b,
    };
    let message = match &e.variant {
        ErrorVariant::ParsingError {
            positives,
            negatives,
        } => {
            let mut parts = Vec::new();
            if !positives.is_empty() {
                parts.push(format!("expected {}", list(positives)));
            }
            if !negatives.is_empty() {
                parts.push(format!("unexpected {}", list(negatives)));
            }
            if parts.is_empty() {
                "unexpected text".to_string()
            } else {
                parts.join("; ")
            }
        }
        ErrorVariant::CustomError { message } => message.clone(),
    };
    Diagnostic::error(InputError::Syntax(message)).with_span(span)
}

/// The rules' descriptions, sorted, without repeats, as `a, b or c`.
fn list(rules: &[Rule]) -> String {
    let mut names: Vec<String> = rules.iter().map(|r| describe(*r)).collect();
    names.sort();
    names.dedup();
    match names.pop() {
        None => String::new(),
        Some(last) if names.is_empty() => last,
        Some(last) => format!("{} or {}", names.join(", "), last),
    }
}

/// What a grammar rule looks like to a user: `` `generations N` `` rather
/// than `lsys_generations`.
///
/// Silent rules (`_{ ... }`) never appear in pest's reports; they share the
/// generic description, the rule's name with `_` turned into spaces.
pub(crate) fn describe(rule: Rule) -> String {
    use super::{lsys, stl};
    let text = match rule {
        // -- shared
        Rule::EOI => "end of input",
        Rule::number | Rule::lsys_num => "a number",
        Rule::integer | Rule::lsys_int => "a whole number",

        // -- lsys
        Rule::lsys_file => "a line `key value` or a `#` comment",
        Rule::lsys_generations => "`generations N`",
        Rule::lsys_axiom => "`axiom WORD`",
        Rule::lsys_rule => "`rule X SUCCESSOR`",
        Rule::lsys_angle => "`angle DEGREES`",
        Rule::lsys_heading => "`heading DEGREES`",
        Rule::lsys_length => "`length L`",
        Rule::lsys_width => "`width W`",
        Rule::lsys_color => "`color C`",
        Rule::lsys_background => "`background C`",
        Rule::lsys_seed => "`seed N`",
        Rule::lsys_dimensions => "`dimensions N`",
        Rule::lsys_probability => "a probability like `(0.5)`",
        Rule::lsys_unknown | Rule::lsys_key => {
            return format!("a key ({})", lsys::KEYS.join(", "));
        }
        Rule::lsys_colour | Rule::lsys_hex | Rule::lsys_name => "a colour (`#rrggbb` or `clGreen`)",
        Rule::lsys_bad | Rule::lsys_text => "a value",
        Rule::lsys_word => "a word of symbols",
        Rule::lsys_pred => "the symbol the rule rewrites",
        Rule::lsys_arrow => "`->`, `=` or a space before the successor",

        // -- od / bed
        Rule::stl_file => "an STL description",
        Rule::stl_tree_name => "a tree name",
        Rule::stl_root => "a root `(x, y)`",
        Rule::stl_param => "a stem parameter like `L=10(0)`",
        Rule::stl_param_key => "a parameter name",
        Rule::stl_param_dec => "a decrement `(d)`",
        Rule::stl_param_colour => {
            "a colour (`clMaroon`, `#rrggbb` or `none`), a ramp `#5b3a1e..#3b5e2b` or a surface's name"
        }
        Rule::stl_colour_word => "a colour (`clMaroon` or `#rrggbb`)",
        Rule::stl_kw_rule => "`RULE`",
        Rule::stl_kw_seed => "`SEED`",
        Rule::stl_kw_endseed => "`ENDSEED`",
        Rule::stl_kw_layout => "`LAYOUT`",
        Rule::stl_kw_endlayout => "`ENDLAYOUT`",
        Rule::stl_kw_surfaces => "`SURFACES`",
        Rule::stl_kw_endsurfaces => "`ENDSURFACES`",
        Rule::stl_surfaces => "a `SURFACES` section",
        Rule::stl_surfaces_text => "lines `surface X { word }`",
        Rule::stl_rule_def => "a rule definition like `R1: [+F][-F]`",
        Rule::stl_rule_name => "a rule name",
        Rule::stl_defines => "`:` or `=`",
        Rule::stl_probability => "a probability like `(0.5)`",
        Rule::stl_word => "a rule name",
        Rule::stl_body => "a rule body",
        Rule::stl_body_text => "a drawing component or rule name",
        Rule::stl_body_piece => "a drawing component or rule name",
        Rule::stl_seed => "a `SEED` section",
        Rule::stl_seed_body => "the seed",
        Rule::stl_seed_text => "a drawing component, rule name or term",
        Rule::stl_seed_space => "a space or comment",
        Rule::stl_layout => "a `LAYOUT` section",
        Rule::stl_shape_line => "a layout shape like `(clGreen) Rectangle (0,0), 200, 100`",
        Rule::stl_angled => "`<`",
        Rule::stl_colour => "a colour (`clGreen` or `#rrggbb`)",
        Rule::stl_shape => "a shape",
        Rule::stl_shape_name => {
            let names: Vec<String> = stl::ShapeName::ALL
                .iter()
                .map(|s| format!("`{}`", s.name()))
                .collect();
            let volumes: Vec<String> = stl::SolidName::ALL
                .iter()
                .map(|s| format!("`{}`", s.name()))
                .collect();
            return format!(
                "a shape name ({}) or a volume ({})",
                names.join(", "),
                volumes.join(", ")
            );
        }
        Rule::stl_inner => "a 2D shape like `Ellipse (0,0), 10, 20`",
        Rule::stl_inner_angled => "`<`",
        Rule::stl_shape_arg => "a shape argument",
        Rule::stl_point_list => "a point `(x, y)`",

        // -- silent rules
        Rule::WHITESPACE
        | Rule::COMMENT
        | Rule::hex_colour_digits
        | Rule::lsys_line
        | Rule::lsys_entry
        | Rule::lsys_known
        | Rule::lsys_kw_end
        | Rule::lsys_eov
        | Rule::lsys_sym
        | Rule::lsys_sp
        | Rule::lsys_nl
        | Rule::lsys_comment
        | Rule::stl_name_char
        | Rule::stl_keyword
        | Rule::stl_body_end
        | Rule::stl_turn3 => return format!("{rule:?}").replace('_', " "),
    };
    text.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn key_and_shape_lists_come_from_their_tables() {
        assert_eq!(
            describe(Rule::lsys_key),
            "a key (generations, axiom, rule, angle, heading, length, width, color, background, seed, \
             dimensions)"
        );
        assert_eq!(
            describe(Rule::stl_shape_name),
            "a shape name (`Rectangle`, `RoundRect`, `Ellipse`, `Polygon`) or a volume \
             (`Box`, `Sphere`, `Ellipsoid`, `Cylinder`, `Extrude`, `Revolve`)"
        );
    }

    #[test]
    fn lists_read_a_b_or_c() {
        assert_eq!(list(&[]), "");
        assert_eq!(list(&[Rule::EOI]), "end of input");
        assert_eq!(
            list(&[Rule::stl_kw_rule, Rule::EOI, Rule::number, Rule::lsys_num]),
            "`RULE`, a number or end of input"
        );
    }

    #[test]
    fn a_word_symbol_is_any_character_but_whitespace_and_hash() {
        // `lsys_sym` as ranges agrees with its definition, character by
        // character: every character but tab, line feed, carriage return,
        // space, `#` and U+FEFF is a one-symbol word.
        use pest::Parser;
        let not_symbols = ['\t', '\n', '\r', ' ', '#', '\u{FEFF}'];
        let chars = (0..0x3000u32)
            .chain(0xFE00..0xFF10)
            .chain([0xD7FF, 0xE000, 0xFFFF, 0x1_0000, 0x1F333, 0x10_FFFF])
            .filter_map(char::from_u32);
        let mut symbols = 0;
        for c in chars {
            let text = format!("{c}F");
            let read = GrammarParser::parse(Rule::lsys_word, &text)
                .map(|mut pairs| pairs.next().map_or(0, |p| p.as_str().len()))
                .unwrap_or(0);
            let is_symbol = !not_symbols.contains(&c);
            let whole = text.len();
            assert_eq!(read == whole, is_symbol, "{:?}", c);
            symbols += usize::from(is_symbol);
        }
        assert_eq!(symbols, 0x3000 + 0x110 + 6 - 6);
    }
}
