//! Every limit stlc enforces, in one place, with its default.
//!
//! A limit turns runaway work (a huge depth, a runaway layout, hostile input)
//! into a clear error that names the flag raising it, instead of an
//! out-of-memory kill, a stack overflow or a hang. `docs/limits.md` explains
//! each default.

pub use crate::diag::Bound;

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
        if depth <= self.max_depth {
            return Ok(());
        }
        Err(Bound::Depth
            .exceeded(depth, self.max_depth.into())
            .with_help(crate::diag::Help::from("use a smaller depth, or ") + Bound::Depth)
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
            assert_eq!(Limits::DEFAULT.get(b), field, "{b:?}");
            assert_eq!(b.flag(), flag, "{b:?}");
        }
    }
}
