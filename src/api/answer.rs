//! What comes back: the answer of a render ([`RenderAnswer`]) and of
//! the words view ([`WordsAnswer`]), an input's errors ([`Failed`]) and
//! diagnostics with their places in the text ([`DiagnosticJson`]),
//! written with serde.

use serde::Serialize;

use super::{Page, shapes, stems3};
use crate::diag::{Diagnostic, Diagnostics, line_column};

/// The answer of `POST /api/render` when the input could be drawn.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RenderAnswer {
    /// Always `true`.
    pub ok: bool,
    /// The picture, as `stlc render -f svg --show-layout` writes it; for
    /// a big grown tree (`tree_in_svg` false), without the tree.
    pub svg: String,
    /// Whether `svg` shows the tree: `false` for a grown tree of more than
    /// [`BIG_TREE_STEMS`] stems, which the page draws from `growth` instead
    /// (the export's SVG always has it).
    pub tree_in_svg: bool,
    /// The tree's stroke colour, `#rrggbb`.
    pub stroke: String,
    /// The grown BED (an .od only), as `stlc compile` writes it; `None`
    /// for a big grown tree (`tree_in_svg` false): `/api/export` writes it.
    pub bed: Option<String>,
    /// Stems grown (an .od), else segments drawn, as decimal digits:
    /// exact at any depth (a JSON number is exact only to 2^53).
    pub stems: String,
    /// Whether `stems` is exact; `false`: at least that many (a count
    /// past what the measure holds).
    pub stems_exact: bool,
    /// Warnings.
    pub warnings: Vec<DiagnosticJson>,
    /// The stems in growth order, for the replay.
    pub growth: Growth,
    /// The layout's canvas area `[min_x, min_y, max_x, max_y]`, if any.
    pub view: Option<[f64; 4]>,
    /// An .od's root, where it is written.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub root: Option<shapes::RootJson>,
    /// An .od's LAYOUT as written (`null` without one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layout: Option<Option<shapes::LayoutJson>>,
    /// A 3D input's stems and volumes, drawn by the page (`svg` is empty).
    /// On the wire `space`, its name before 3D was named with a `3` (the
    /// page and scripts read it so).
    #[serde(rename = "space", skip_serializing_if = "Option::is_none")]
    pub stems3: Option<stems3::Stems3Json>,
}

/// A grown tree of more stems than this is drawn by the page from its
/// stems, not from the SVG: the page reads and imports an SVG in one task,
/// about 20 ms at 10,000 stems, 30 ms at 20,000 and 370 ms at 200,000
/// (docs/performance.md), and a task over 50 ms stalls it.
pub const BIG_TREE_STEMS: u64 = 10_000;

/// The stems in growth order: six numbers a stem (`from.x, from.y, to.x,
/// to.y, width, decision`), three decimals; and the last decision.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Growth {
    /// Six numbers a stem.
    pub stems: Vec<f64>,
    /// The last decision's number.
    pub decisions: u64,
}

/// The answer for an input error: `{"ok": false, "diagnostics": [...]}`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Failed {
    /// Always `false`.
    pub ok: bool,
    /// What went wrong.
    pub diagnostics: Vec<DiagnosticJson>,
}

impl Failed {
    /// The answer for `diags` about `text`.
    pub fn new(text: &str, diags: &Diagnostics, page: Page) -> Self {
        let list: Vec<Diagnostic> = diags.iter().cloned().collect();
        Failed {
            ok: false,
            diagnostics: diagnostics_json(text, &list, page),
        }
    }

    /// One error without a place.
    pub fn message(message: &str, help: &str) -> Self {
        Failed {
            ok: false,
            diagnostics: vec![DiagnosticJson {
                message: message.into(),
                severity: "error",
                line: None,
                column: None,
                end_line: None,
                end_column: None,
                label: None,
                help: Some(help.into()),
            }],
        }
    }
}

/// A diagnostic: message, severity, 1-based line and column of the span's
/// start and end (`null` when it has none; columns count characters, not
/// bytes or UTF-16 units), label, help.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiagnosticJson {
    message: String,
    severity: &'static str,
    line: Option<usize>,
    column: Option<usize>,
    end_line: Option<usize>,
    end_column: Option<usize>,
    label: Option<String>,
    help: Option<String>,
}

/// Generations [`super::words`] shows at most (depths 0 to 7).
pub const WORD_DEPTHS: u32 = 8;

/// Characters of each word [`super::words`] shows at most.
pub const WORD_CHARS: usize = 2_000;

/// The answer of `POST /api/words`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WordsAnswer {
    /// Always `true`.
    pub ok: bool,
    /// Depth 0 (the axiom) and on.
    pub words: Vec<Word>,
}

/// One generation's word.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Word {
    /// The generation.
    pub depth: u32,
    /// The word, cut at [`WORD_CHARS`] characters.
    pub word: String,
    /// Its exact length in symbols (modules, for a parametric system), as
    /// digits.
    pub length: String,
    /// `stlc stats --json --depth N`'s text for this generation (without
    /// the CLI's closing newline): its counts, box and end.
    pub stats: String,
    /// Whether `word` was cut at [`WORD_CHARS`] (a parametric word has
    /// more characters than modules, so `length` does not tell).
    pub cut: bool,
}

/// Diagnostics in the answer's terms, their hints spelt for `page`.
pub fn diagnostics_json(text: &str, diags: &[Diagnostic], page: Page) -> Vec<DiagnosticJson> {
    diags
        .iter()
        .map(|d| {
            let at = |p: usize| {
                let p = shapes::floor_char(text, p.min(text.len()));
                line_column(text, p)
            };
            let (start, end) = match &d.span {
                Some(span) if span.end <= text.len() => (Some(at(span.start)), Some(at(span.end))),
                _ => (None, None),
            };
            DiagnosticJson {
                message: d.kind.to_string(),
                severity: if d.is_error() { "error" } else { "warning" },
                line: start.map(|s| s.0),
                column: start.map(|s| s.1),
                end_line: end.map(|e| e.0),
                end_column: end.map(|e| e.1),
                label: d.label.clone(),
                help: d.help.as_ref().map(|h| h.spell(&page)),
            }
        })
        .collect()
}
