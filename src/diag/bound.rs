//! Which limit was exceeded ([`Bound`]): each knows its flag, its words
//! and the error that reports it ([`Bound::exceeded`]), so every limit
//! error in stlc is built one way. The values in force are
//! [`crate::limits::Limits`]'s (which imports this, not the other way).

use super::{Diagnostic, ErrorKind, Help};

/// Which limit: one variant per `--max-*` flag's quantity, as named by
/// [`ErrorKind::Limit`]. Each knows its flag, its default and
/// the words the error message uses for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Bound {
    /// Input size in bytes ([`crate::limits::Limits::max_input_bytes`]).
    InputBytes,
    /// Nesting of brackets and braces ([`crate::limits::Limits::max_nesting`]).
    Nesting,
    /// Derivation depth, an `.lsys`'s `generations` ([`crate::limits::Limits::max_depth`]).
    Depth,
    /// The count `n` of `[I n X]` ([`crate::limits::Limits::max_repeat`], raised with
    /// `--max-depth`).
    Repeat,
    /// Symbols one traversal may visit ([`crate::limits::Limits::max_symbols`]).
    Symbols,
    /// Symbols the `bfs` strategy may hold as one word ([`crate::limits::Limits::max_word`]).
    Word,
    /// Stems growth may draw ([`crate::limits::Limits::max_stems`]).
    Stems,
    /// Vertices of a layout's outline ([`crate::limits::Limits::max_layout_vertices`]).
    LayoutVertices,
    /// Rule definitions and top-level bracket groups of bodies
    /// ([`crate::limits::Limits::max_rule_parts`]).
    RuleParts,
    /// Shapes of a LAYOUT ([`crate::limits::Limits::max_layout_shapes`]).
    LayoutShapes,
    /// Segments an SVG may hold ([`crate::limits::DEFAULT_MAX_SVG_SEGMENTS`]).
    SvgSegments,
}

impl Bound {
    /// Every limit.
    pub const ALL: [Bound; 11] = [
        Bound::InputBytes,
        Bound::Nesting,
        Bound::Depth,
        Bound::Repeat,
        Bound::Symbols,
        Bound::Word,
        Bound::Stems,
        Bound::LayoutVertices,
        Bound::RuleParts,
        Bound::LayoutShapes,
        Bound::SvgSegments,
    ];

    /// The command-line flag that raises it.
    pub fn flag(self) -> &'static str {
        match self {
            Bound::InputBytes => "--max-input",
            Bound::Nesting => "--max-nesting",
            Bound::Depth | Bound::Repeat => "--max-depth",
            Bound::Symbols => "--max-symbols",
            Bound::Word => "--max-word",
            Bound::Stems => "--max-stems",
            Bound::LayoutVertices => "--max-layout-vertices",
            Bound::RuleParts => "--max-rule-parts",
            Bound::LayoutShapes => "--max-layout-shapes",
            Bound::SvgSegments => "--max-svg-segments",
        }
    }

    /// The flag's value placeholder, as its help shows it.
    pub fn value_name(self) -> &'static str {
        match self {
            Bound::InputBytes => "BYTES",
            _ => "N",
        }
    }

    /// What is limited, in the words of an error message
    /// (`derivation depth: 20000 exceeds the limit of 10000`).
    pub fn describe(self) -> &'static str {
        match self {
            Bound::InputBytes => "input size in bytes",
            Bound::Nesting => "nesting depth",
            Bound::Depth => "derivation depth",
            Bound::Repeat => "self-resemblance count",
            Bound::Symbols => "symbols in the expansion",
            Bound::Word => "bfs word length",
            Bound::Stems => "stems",
            Bound::LayoutVertices => "layout outline vertices",
            Bound::RuleParts => "rule definitions and branches",
            Bound::LayoutShapes => "layout shapes",
            Bound::SvgSegments => "segments in the SVG",
        }
    }

    /// The end of a hint: how to raise the limit (`raise the limit with
    /// --max-depth N` on the command line; each front end spells it).
    pub fn raise(self) -> Help {
        Help::from(self)
    }

    /// The error for `value` over this bound's `limit` in force: `derivation
    /// depth: 20000 exceeds the limit of 10000`, with the hint [`Bound::raise`]
    /// (a caller with a better hint replaces it with
    /// [`Diagnostic::with_help`]).
    pub fn exceeded(self, value: impl ToString, limit: u64) -> Diagnostic {
        Diagnostic::error(ErrorKind::Limit {
            bound: self,
            what: None,
            value: value.to_string(),
            limit,
        })
        .with_help(self.raise())
    }

    /// [`Bound::exceeded`] where the bound's own words are not precise
    /// enough: `what` is what was measured (`derived word length at depth
    /// 30`).
    pub fn exceeded_by(
        self,
        what: impl Into<String>,
        value: impl ToString,
        limit: u64,
    ) -> Diagnostic {
        Diagnostic::error(ErrorKind::Limit {
            bound: self,
            what: Some(what.into()),
            value: value.to_string(),
            limit,
        })
        .with_help(self.raise())
    }
}
