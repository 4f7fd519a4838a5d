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
            what: "derivation depth".into(),
            value: depth.to_string(),
            limit: self.max_depth.to_string(),
        })
        .with_help("use a smaller depth, or raise the limit with --max-depth N")
        .into())
    }
}
