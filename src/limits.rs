//! Every limit stlc enforces, in one place, with its default.
//!
//! A limit turns runaway work (a huge depth, a runaway layout, hostile input)
//! into a clear error that names the flag raising it, instead of an
//! out-of-memory kill, a stack overflow or a hang. `docs/limits.md` explains
//! each default.

/// The limits in force for one run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Largest input file, bytes (`--max-input`).
    pub max_input_bytes: u64,
    /// Deepest nesting of `[ ] { } ( )` the parsers accept (`--max-nesting`).
    pub max_nesting: usize,
    /// Largest derivation depth / `generations` (`--max-depth`).
    pub max_depth: u32,
    /// Largest `n` in `[I n X]` (`--max-depth` too).
    pub max_repeat: u32,
    /// Most symbols a traversal (render, expand, stats' turtle pass) may
    /// visit (`--max-symbols`).
    pub max_symbols: u64,
    /// Most symbols the `bfs` strategy may hold as one word (`--max-word`).
    pub max_word: u64,
    /// Most stems (drawn segments) growth may add (`--max-stems`).
    pub max_stems: u64,
    /// Most vertices a layout's outline may have: each shape once flattened,
    /// and the painted area after each shape (`--max-layout-vertices`).
    pub max_layout_vertices: usize,
    /// Most rule definitions and top-level bracket groups of rule bodies an
    /// OD or BED may have (`--max-rule-parts`).
    pub max_rule_parts: usize,
    /// Most shapes a LAYOUT may have (`--max-layout-shapes`).
    pub max_layout_shapes: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits::DEFAULT
    }
}

impl Limits {
    /// The defaults (docs/limits.md explains each), usable in constants:
    /// `Limits { max_depth: 16, ..Limits::DEFAULT }`.
    pub const DEFAULT: Limits = Limits {
        max_input_bytes: 64 * 1024 * 1024,
        max_nesting: 10_000,
        max_depth: 10_000,
        max_repeat: 10_000,
        max_symbols: 20_000_000_000,
        max_word: 200_000_000,
        max_stems: 1_000_000,
        max_layout_vertices: 16_000,
        max_rule_parts: 100_000,
        max_layout_shapes: 10_000,
    };

    /// Refuses a derivation depth over [`Limits::max_depth`], naming the flag.
    pub fn check_depth(&self, depth: u32) -> Result<(), crate::diag::Diagnostics> {
        use crate::diag::{Diagnostic, ErrorKind};
        if depth <= self.max_depth {
            return Ok(());
        }
        Err(Diagnostic::error(ErrorKind::Limit {
            bound: Bound::Depth,
            what: None,
            value: depth.to_string(),
            limit: self.max_depth.into(),
        })
        .with_help(format!("use a smaller depth, or {}", Bound::Depth.raise()))
        .into())
    }

    /// The value of `bound` in force.
    pub fn get(&self, bound: Bound) -> u64 {
        match bound {
            Bound::InputBytes => self.max_input_bytes,
            Bound::Nesting => self.max_nesting as u64,
            Bound::Depth => self.max_depth.into(),
            Bound::Repeat => self.max_repeat.into(),
            Bound::Symbols => self.max_symbols,
            Bound::Word => self.max_word,
            Bound::Stems => self.max_stems,
            Bound::LayoutVertices => self.max_layout_vertices as u64,
            Bound::RuleParts => self.max_rule_parts as u64,
            Bound::LayoutShapes => self.max_layout_shapes as u64,
            Bound::SvgSegments => DEFAULT_MAX_SVG_SEGMENTS,
        }
    }
}

/// Default of `--max-svg-segments` (`render::RenderOptions::max_svg_segments`,
/// not a field of [`Limits`]: only rendering an SVG has it): about 22 bytes
/// a segment, so an SVG of at most about 220 MB (already more than browsers
/// open).
pub const DEFAULT_MAX_SVG_SEGMENTS: u64 = 10_000_000;

/// Which limit: one variant per `--max-*` flag's quantity, as named by
/// [`crate::diag::ErrorKind::Limit`]. Each knows its flag, its default and
/// the words the error message uses for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Bound {
    /// Input size in bytes ([`Limits::max_input_bytes`]).
    InputBytes,
    /// Nesting of brackets and braces ([`Limits::max_nesting`]).
    Nesting,
    /// Derivation depth, an `.lsys`'s `generations` ([`Limits::max_depth`]).
    Depth,
    /// The count `n` of `[I n X]` ([`Limits::max_repeat`], raised with
    /// `--max-depth`).
    Repeat,
    /// Symbols one traversal may visit ([`Limits::max_symbols`]).
    Symbols,
    /// Symbols the `bfs` strategy may hold as one word ([`Limits::max_word`]).
    Word,
    /// Stems growth may draw ([`Limits::max_stems`]).
    Stems,
    /// Vertices of a layout's outline ([`Limits::max_layout_vertices`]).
    LayoutVertices,
    /// Rule definitions and top-level bracket groups of bodies
    /// ([`Limits::max_rule_parts`]).
    RuleParts,
    /// Shapes of a LAYOUT ([`Limits::max_layout_shapes`]).
    LayoutShapes,
    /// Segments an SVG may hold ([`DEFAULT_MAX_SVG_SEGMENTS`]).
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

    /// Its default ([`Limits::DEFAULT`]).
    pub fn default_value(self) -> u64 {
        Limits::DEFAULT.get(self)
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

    /// The end of a hint: `raise the limit with --max-depth N`.
    pub fn raise(self) -> String {
        format!("raise the limit with {} {}", self.flag(), self.value_name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each bound's default is its own field of [`Limits::DEFAULT`], read
    /// here by name (not through [`Limits::get`]), and the flags are
    /// those of docs/limits.md.
    #[test]
    fn every_bound_defaults_to_its_field() {
        let d = Limits::DEFAULT;
        for b in Bound::ALL {
            let (field, flag) = match b {
                Bound::InputBytes => (d.max_input_bytes, "--max-input"),
                Bound::Nesting => (d.max_nesting as u64, "--max-nesting"),
                Bound::Depth => (u64::from(d.max_depth), "--max-depth"),
                Bound::Repeat => (u64::from(d.max_repeat), "--max-depth"),
                Bound::Symbols => (d.max_symbols, "--max-symbols"),
                Bound::Word => (d.max_word, "--max-word"),
                Bound::Stems => (d.max_stems, "--max-stems"),
                Bound::LayoutVertices => (d.max_layout_vertices as u64, "--max-layout-vertices"),
                Bound::RuleParts => (d.max_rule_parts as u64, "--max-rule-parts"),
                Bound::LayoutShapes => (d.max_layout_shapes as u64, "--max-layout-shapes"),
                Bound::SvgSegments => (10_000_000, "--max-svg-segments"),
            };
            assert_eq!(b.default_value(), field, "{b:?}");
            assert_eq!(b.flag(), flag, "{b:?}");
        }
    }
}
