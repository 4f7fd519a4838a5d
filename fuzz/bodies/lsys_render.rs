//! Parse a `.lsys`, derive it with both derivations into a bounding turtle
//! (they must agree bit for bit), then render it to a small PNG and SVG.
//! Tight limits keep every input fast; any error after a successful parse
//! must be a limit (or, when rendering a picture whose coordinates are not
//! finite, `DrawingNotFinite`), never a panic.

use stlc::color::Rgb;
use stlc::diag::{Diagnostics, ErrorKind, RenderError};
use stlc::interpret::{Derivation, lsys};
use stlc::limits::Limits;
use stlc::model::lsys::Background;
use stlc::progress::{NoProgress, Progress};
use stlc::render::{self, ImageFormat, RenderOptions, Style, Width};
use stlc::syntax::lsys::parse;
use stlc::turtle::{Bounds, Turtle};

const DEPTH_CAP: u32 = 16;

/// The defaults, tightened so every input runs in milliseconds.
const LIMITS: Limits = Limits {
    max_input_bytes: 1 << 16,
    max_nesting: 1_000,
    max_depth: 1_000,
    max_repeat: 16,
    max_symbols: 1_000_000,
    max_word: 1_000_000,
    max_stems: 10_000,
    max_rule_parts: 1_000,
    max_layout_shapes: 100,
    ..Limits::DEFAULT
};

/// Rendering walks the word twice per format: a smaller budget.
const RENDER_LIMITS: Limits = Limits {
    max_symbols: 100_000,
    ..LIMITS
};

fn bits(b: &Bounds) -> Option<[u64; 4]> {
    b.bbox()
        .map(|b| [b.min_x, b.min_y, b.max_x, b.max_y].map(f64::to_bits))
}

/// Deriving may only meet a limit; rendering (at a valid 64x64 size, into
/// memory, with no layout view) may also find coordinates that overflowed
/// to infinity or NaN.
fn only_limits(e: &Diagnostics, rendering: bool) {
    for d in e.iter().filter(|d| d.is_error()) {
        let ok = matches!(d.kind, ErrorKind::Limit { .. })
            || (rendering && matches!(d.kind, ErrorKind::Render(RenderError::DrawingNotFinite)));
        assert!(ok, "unexpected error after a successful parse: {d}");
    }
}

/// One input: returns normally, or panics on a broken promise.
pub fn run(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(sys) = parse(text, &LIMITS) else {
        return;
    };
    let depth = sys.generations.unwrap_or(3).min(DEPTH_CAP);

    let mut dfs = Bounds::default();
    let rd = lsys::draw(
        &sys,
        depth,
        Derivation::Dfs,
        &LIMITS,
        &mut dfs,
        &mut NoProgress,
    );
    let mut bfs = Bounds::default();
    let rb = lsys::draw(
        &sys,
        depth,
        Derivation::Bfs,
        &LIMITS,
        &mut bfs,
        &mut NoProgress,
    );
    match (&rd, &rb) {
        (Ok(()), Ok(())) => {
            assert_eq!(
                dfs.count, bfs.count,
                "dfs and bfs draw different segment counts"
            );
            assert_eq!(bits(&dfs), bits(&bfs), "dfs and bfs draw different boxes");
        }
        (Err(e), _) | (_, Err(e)) => only_limits(e, false),
    }
    if rd.is_err() {
        return;
    }

    let style = Style {
        stroke: sys.color.unwrap_or(Rgb::BLACK),
        background: match sys.background {
            Background::White => Some(Rgb::WHITE),
            Background::None => None,
            Background::Color(c) => Some(c),
        },
        width: Width::Pixels(sys.width),
    };
    let mut drawing = |t: &mut dyn Turtle, p: &mut dyn Progress| {
        lsys::draw(&sys, depth, Derivation::Dfs, &RENDER_LIMITS, t, p)
    };
    for format in [ImageFormat::Png, ImageFormat::Svg] {
        let opts = RenderOptions::new(format, Some((64, 64)));
        let mut out = Vec::new();
        match render::render(
            &mut drawing,
            None,
            &[],
            &style,
            &opts,
            &mut out,
            &mut NoProgress,
        ) {
            Ok(counted) => {
                // The bounding pass drew what the check above drew.
                assert_eq!(counted, Some(dfs.count), "render counted other segments");
                match format {
                    ImageFormat::Png => assert!(out.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG"),
                    ImageFormat::Svg => {
                        let svg = String::from_utf8(out).expect("SVG is UTF-8");
                        assert!(svg.contains("<svg") && svg.trim_end().ends_with("</svg>"));
                        assert!(
                            !svg.contains("NaN") && !svg.contains("inf"),
                            "non-finite number in SVG"
                        );
                    }
                }
            }
            Err(e) => only_limits(&e, true),
        }
    }
}
