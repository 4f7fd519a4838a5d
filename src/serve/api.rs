//! The JSON API of `stlc serve`, typed: the request body ([`Body`]) and
//! what comes back ([`RenderAnswer`], [`Failed`]), derived with serde, and
//! the one mapping from a body to a [`pipeline::Request`].
//!
//! No pipeline logic lives here: loading, growing, the BED text, the SVG
//! and the PNG all come from [`Request::render`], the call `stlc render`
//! makes, so the bytes are the same for the same options.
//!
//! A field the API does not know is refused (HTTP 400, naming it): a
//! misspelt `"clearence"` would otherwise be ignored in silence.

use serde::{Deserialize, Serialize};

use super::{shapes, space};

use stlc::diag::{Diagnostic, Diagnostics, line_column};
use stlc::pipeline::{
    GrowthOrder, ImageFormat, InputKind, Limits, Progress, RenderOptions, Request, Rgb, ShowLayout,
};

/// The server's own settings that every request works within.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The `--max-*` limits `stlc serve` was started with.
    pub limits: Limits,
    /// `--max-stems` of `stlc serve`, if given.
    pub max_stems: Option<u64>,
    /// `--max-svg-segments`.
    pub max_svg_segments: u64,
    /// `--time-budget`: how long one request's work may run.
    pub time_budget: std::time::Duration,
}

/// A request body: `{"source", "kind"?, "strategy"?, "depth"?,
/// "clearance"?, "max_stems"?, "seed"?}`. Absent and `null` fields take
/// their defaults; any other field is refused.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// The text.
    pub source: String,
    /// Its kind; `None`: guessed from the text, as for standard input.
    #[serde(default)]
    pub kind: Option<Kind>,
    /// Growth order of an .od (`--growth`).
    #[serde(default)]
    pub strategy: Option<Order>,
    /// Derivation depth of an .lsys (`--depth`).
    #[serde(default)]
    pub depth: Option<u32>,
    /// `--clearance`.
    #[serde(default)]
    pub clearance: Option<f64>,
    /// `--max-stems`.
    #[serde(default)]
    pub max_stems: Option<u64>,
    /// `--seed` of stochastic rules: a number, or a string of digits (a
    /// seed may be any u64, past what a JavaScript number holds exactly).
    #[serde(default)]
    pub seed: Option<Seed>,
    /// `--size WxH` of the picture, `[w, h]`, each 1 to 16384 pixels;
    /// `None`: the default size.
    #[serde(default)]
    pub size: Option<[u32; 2]>,
    /// Whether the layout is painted under a tree (`--show-layout`);
    /// `None`: wherever there is one (the editor's view).
    #[serde(default)]
    pub show_layout: Option<bool>,
    /// `--background`: `"none"` (transparent), `#rrggbb` or a Delphi name;
    /// `None`: the input's own.
    #[serde(default)]
    pub background: Option<String>,
    /// `--view AZ,EL` of a 3D input's picture, `[az, el]` degrees.
    #[serde(default)]
    pub view: Option<[f64; 2]>,
}

/// `"od"`, `"bed"` or `"lsys"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// An Outline Description.
    Od,
    /// A Branch-Expansion Description.
    Bed,
    /// A classic L-system.
    Lsys,
}

impl From<Kind> for InputKind {
    fn from(k: Kind) -> Self {
        match k {
            Kind::Od => InputKind::Od,
            Kind::Bed => InputKind::Bed,
            Kind::Lsys => InputKind::Lsys,
        }
    }
}

impl From<InputKind> for Kind {
    fn from(k: InputKind) -> Self {
        match k {
            InputKind::Od => Kind::Od,
            InputKind::Bed => Kind::Bed,
            InputKind::Lsys => Kind::Lsys,
        }
    }
}

/// `"bfs"` or `"dfs"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Order {
    /// Breadth-first.
    Bfs,
    /// Depth-first.
    Dfs,
}

/// A seed: a JSON number or a string of digits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(try_from = "SeedText")]
pub struct Seed(pub u64);

#[derive(Deserialize)]
#[serde(untagged)]
enum SeedText {
    Number(u64),
    Text(String),
}

impl TryFrom<SeedText> for Seed {
    type Error = String;
    fn try_from(s: SeedText) -> Result<Self, String> {
        match s {
            SeedText::Number(n) => Ok(Seed(n)),
            SeedText::Text(t) => t.trim().parse().map(Seed).map_err(|_| {
                format!(
                    "`seed` must be a whole number from 0 to {}, not `{t}`",
                    u64::MAX
                )
            }),
        }
    }
}

/// The body of `POST /api/save`: `{"source", "version"?}`. `version` is
/// the version the edit is based on (`null`: the file did not exist yet);
/// without it the file is written whatever it holds (a script's save).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SaveBody {
    /// The text to write.
    pub source: String,
    /// The base version; `Some(None)` for `null`.
    #[serde(default, deserialize_with = "present")]
    pub version: Option<Option<String>>,
}

/// A field that is present (even as `null`) is `Some`.
fn present<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Option<String>>, D::Error> {
    Option::<String>::deserialize(d).map(Some)
}

/// Reads a save body.
pub fn parse_save(body: &[u8]) -> Result<SaveBody, BadRequest> {
    serde_json::from_slice(body).map_err(|e| BadRequest(format!("malformed request: {e}")))
}

/// A malformed request (HTTP 400): the JSON is not what the API takes.
#[derive(Debug, Clone, PartialEq)]
pub struct BadRequest(pub String);

/// Reads a request body.
pub fn parse(body: &[u8]) -> Result<Body, BadRequest> {
    let b: Body =
        serde_json::from_slice(body).map_err(|e| BadRequest(format!("malformed request: {e}")))?;
    if let Some([w, h]) = b.size
        && !((1..=16384).contains(&w) && (1..=16384).contains(&h))
    {
        return Err(BadRequest(
            "`size`: each side must be between 1 and 16384 pixels".into(),
        ));
    }
    if let Some(c) = &b.background
        && c != "none"
        && Rgb::parse(c).is_none()
    {
        return Err(BadRequest(format!(
            "`background`: unknown colour `{c}` (none, #rrggbb or a Delphi name such as clWhite)"
        )));
    }
    Ok(b)
}

impl Body {
    /// The pipeline request this body asks for, drawn as the editor shows
    /// it: with the layout underneath, the default size and level of
    /// detail (the CLI's defaults, so the same bytes), depth-first.
    pub fn request(&self, s: &Settings, format: ImageFormat) -> Request {
        Request {
            kind: self.kind.map(InputKind::from),
            derivation: None,
            growth: self.strategy.map(|o| match o {
                Order::Bfs => GrowthOrder::Bfs,
                Order::Dfs => GrowthOrder::Dfs,
            }),
            depth: self.depth,
            seed: self.seed.map(|s| s.0),
            clearance: self.clearance,
            max_stems: self.max_stems.or(s.max_stems),
            limits: s.limits,
            look: stlc::pipeline::Look {
                show_layout: match self.show_layout {
                    None => ShowLayout::IfAny,
                    Some(true) => ShowLayout::Yes,
                    Some(false) => ShowLayout::No,
                },
                background: self.background.as_deref().map(|c| match c {
                    "none" => None,
                    c => Rgb::parse(c),
                }),
                ..Default::default()
            },
            image: RenderOptions {
                max_svg_segments: s.max_svg_segments,
                ..RenderOptions::new(format, self.size.map(|[w, h]| (w, h)))
            },
            trace: true,
            view: self.view.map(|[az, el]| stlc::pipeline::View { az, el }),
            ..Request::new(self.source.clone().into_bytes())
        }
    }
}

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
    #[serde(skip_serializing_if = "Option::is_none")]
    pub space: Option<space::SpaceJson>,
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
    pub fn new(text: &str, diags: &Diagnostics) -> Self {
        let list: Vec<Diagnostic> = diags.iter().cloned().collect();
        Failed {
            ok: false,
            diagnostics: diagnostics_json(text, &list),
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

/// Generations [`words`] shows at most (depths 0 to 7).
pub const WORD_DEPTHS: u32 = 8;

/// Characters of each word [`words`] shows at most.
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
    /// Its exact length in symbols, as digits.
    pub length: String,
}

/// A writer that keeps the first `cap` bytes and stops the rest.
struct Capped {
    kept: Vec<u8>,
    cap: usize,
}

impl std::io::Write for Capped {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let room = self.cap - self.kept.len();
        if room == 0 {
            return Err(std::io::Error::other("enough"));
        }
        let n = buf.len().min(room);
        self.kept.extend_from_slice(&buf[..n]);
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// An `.lsys`'s word at each depth from 0 to its depth (the request's, else
/// its `generations`), at most [`WORD_DEPTHS`] of them: the derivation a
/// teacher shows, the CLI's `stlc expand` and `stlc stats` for each.
pub fn words(
    body: &Body,
    s: &Settings,
    progress: &mut dyn Progress,
) -> Result<WordsAnswer, Failed> {
    let text = &body.source;
    let base = body.request(s, ImageFormat::Svg);
    let (loaded, _) = base.open().map_err(|d| Failed::new(text, &d))?;
    let Some(last) = (match &loaded {
        stlc::pipeline::Loaded::Lsys(sys) => body.depth.or(sys.generations),
        _ => {
            return Err(Failed::message(
                "only an .lsys has generations to show",
                "open an .lsys, or kind: .lsys",
            ));
        }
    }) else {
        return Err(Failed::message(
            "this .lsys has no depth",
            "add a line `generations N`",
        ));
    };
    let mut words = Vec::new();
    for depth in 0..=last.min(WORD_DEPTHS - 1) {
        let req = Request {
            depth: Some(depth),
            ..base.clone()
        };
        let (stats, _) = req.stats(true).map_err(|d| Failed::new(text, &d))?;
        let length = serde_json::from_str::<serde_json::Value>(&stats)
            .ok()
            .and_then(|v| v["length"].as_str().map(str::to_string))
            .unwrap_or_default();
        let mut out = Capped {
            kept: Vec::new(),
            cap: WORD_CHARS,
        };
        // A word longer than the cap stops the writer: what was kept is shown.
        let _ = req.expand(&mut out, progress);
        let word = String::from_utf8_lossy(&out.kept).trim_end().to_string();
        words.push(Word {
            depth,
            word,
            length,
        });
    }
    Ok(WordsAnswer { ok: true, words })
}

/// What a render request drew, in the answer's terms, and a PNG's bytes
/// (an SVG is the answer's `svg`, moved there, not copied); a grown tree
/// of more than `tree_up_to` stems left out of the picture.
pub fn run(
    body: &Body,
    s: &Settings,
    format: ImageFormat,
    tree_up_to: Option<u64>,
    progress: &mut dyn Progress,
) -> Result<(RenderAnswer, Vec<u8>), Failed> {
    let req = Request {
        tree_up_to,
        ..body.request(s, format)
    };
    let text = &body.source;
    let mut image = Vec::new();
    let drawn = req
        .render(&mut image, progress)
        .map_err(|d| Failed::new(text, &d))?;
    let (bed, placed) = match drawn.trace {
        Some(t) => (Some(t.text), t.placed),
        None => (None, Vec::new()),
    };
    let mut stems = Vec::with_capacity(placed.len() * 6);
    let mut decisions = 0;
    // A 3D tree's stems are in `space`, with their third coordinates.
    for p in placed.iter().filter(|_| drawn.space.is_none()) {
        stems.extend([
            round(p.from.x),
            round(p.from.y),
            round(p.to.x),
            round(p.to.y),
            round(p.width),
            p.decision as f64,
        ]);
        decisions = decisions.max(p.decision);
    }
    // An SVG is moved into the answer, not copied (a big one is hundreds
    // of megabytes); a PNG stays bytes.
    let (svg, image) = match format {
        ImageFormat::Svg => (
            String::from_utf8(image)
                .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()),
            Vec::new(),
        ),
        ImageFormat::Png => (String::new(), image),
    };
    let answer = RenderAnswer {
        ok: true,
        svg,
        tree_in_svg: !drawn.tree_left_out && drawn.space.is_none(),
        stroke: drawn.stroke.to_string(),
        bed: bed.filter(|_| !drawn.tree_left_out),
        stems: match (drawn.grown, &drawn.count) {
            (Some(n), _) => n.to_string(),
            (None, Some(c)) => c.clone(),
            (None, None) => drawn.segments.to_string(),
        },
        stems_exact: drawn.grown.is_some() || drawn.count.is_some(),
        warnings: diagnostics_json(text, &drawn.warnings),
        growth: Growth { stems, decisions },
        view: drawn.view.map(|b| [b.min_x, b.min_y, b.max_x, b.max_y]),
        root: drawn.od.as_ref().map(|od| shapes::root_json(text, od)),
        layout: drawn.od.as_ref().map(|od| shapes::layout_json(text, od)),
        space: drawn.space.map(|s| space::space_json(s, round)),
    };
    Ok((answer, image))
}

/// A number with three decimals (a replay needs no more), never `-0`.
fn round(x: f64) -> f64 {
    let r = (x * 1000.0).round() / 1000.0;
    if r == 0.0 { 0.0 } else { r }
}

/// Diagnostics in the answer's terms.
pub fn diagnostics_json(text: &str, diags: &[Diagnostic]) -> Vec<DiagnosticJson> {
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
                help: d.help.clone(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bodies_take_defaults_and_refuse_wrong_types_and_unknown_fields() {
        let b = parse(br#"{"source": "x", "strategy": "dfs", "depth": null}"#).unwrap();
        assert_eq!(b.source, "x");
        assert_eq!(b.strategy, Some(Order::Dfs));
        assert_eq!(b.depth, None);
        assert_eq!(b.kind, None);
        let b = parse(br#"{"source": "x", "seed": "18446744073709551615"}"#).unwrap();
        assert_eq!(b.seed, Some(Seed(u64::MAX)));
        assert_eq!(
            parse(br#"{"source": "x", "seed": 7}"#).unwrap().seed,
            Some(Seed(7))
        );
        for bad in [
            &br#"{"source": 3}"#[..],
            br#"[1]"#,
            br#"{"source": "x", "kind": "png"}"#,
            br#"{"source": "x", "depth": -1}"#,
            br#"{"source": "x", "depth": 5000000000}"#,
            br#"{"source": "x", "clearance": "1"}"#,
            br#"{"source": "x", "seed": "-1"}"#,
            br#"{"kind": "od"}"#,
            b"{",
        ] {
            assert!(parse(bad).is_err(), "{}", String::from_utf8_lossy(bad));
        }
        let save = |b: &[u8]| parse_save(b).unwrap().version;
        assert_eq!(save(br#"{"source": "x"}"#), None);
        assert_eq!(save(br#"{"source": "x", "version": null}"#), Some(None));
        assert_eq!(
            save(br#"{"source": "x", "version": "3-ab"}"#),
            Some(Some("3-ab".into()))
        );
        let b = parse(
            br#"{"source": "x", "size": [300, 200], "show_layout": false, "background": "none"}"#,
        )
        .unwrap();
        assert_eq!((b.size, b.show_layout), (Some([300, 200]), Some(false)));
        for bad in [
            &br#"{"source": "x", "size": [0, 10]}"#[..],
            br#"{"source": "x", "size": [20000, 10]}"#,
            br#"{"source": "x", "size": [10]}"#,
            br#"{"source": "x", "background": "clWhiet"}"#,
        ] {
            assert!(parse(bad).is_err(), "{}", String::from_utf8_lossy(bad));
        }
        let BadRequest(m) = parse(br#"{"source": "x", "clearence": 2}"#).unwrap_err();
        assert!(m.contains("unknown field `clearence`"), "{m}");
    }

    #[test]
    fn each_layout_shape_comes_with_its_own_text() {
        // The paper's one-line spelling, after a comment with a character
        // of two UTF-16 units: each span is the shape's text, `>` included.
        let text = "# 𝄞\n2DTree (76, 150)L=10(0) B=1(0)RULE R1: [+F][-F] LAYOUT \
                    (clGreen)< RoundRect (0,0,180,192,7,7)> # big\n\
                    (clWhite) Rectangle (55,30), 40, 15 ENDLAYOUT";
        let body = parse(format!(r#"{{"source": {text:?}}}"#).as_bytes()).unwrap();
        let s = Settings {
            limits: Limits::default(),
            max_stems: None,
            max_svg_segments: 1_000_000,
            time_budget: std::time::Duration::from_secs(60),
        };
        let (answer, _) = run(
            &body,
            &s,
            ImageFormat::Svg,
            None,
            &mut stlc::pipeline::NoProgress,
        )
        .unwrap();
        let units: Vec<u16> = text.encode_utf16().collect();
        let slice = |a: usize, b: usize| String::from_utf16(&units[a..b]).unwrap();
        let layout = answer.layout.flatten().unwrap();
        let spans: Vec<String> = layout
            .shapes
            .iter()
            .map(|sh| slice(sh.start, sh.end))
            .collect();
        assert_eq!(
            spans,
            [
                "(clGreen)< RoundRect (0,0,180,192,7,7)>",
                "(clWhite) Rectangle (55,30), 40, 15"
            ]
        );
    }

    #[test]
    fn utf16_offsets_count_javascript_units() {
        // `é` is 2 bytes and 1 unit; `𝄞` is 4 bytes and 2 units.
        let t = "é𝄞x";
        assert_eq!(shapes::utf16(t, 0), 0);
        assert_eq!(shapes::utf16(t, 2), 1);
        assert_eq!(shapes::utf16(t, 6), 3);
        assert_eq!(shapes::utf16(t, 7), 4);
        // Inside a character: floored to its start.
        assert_eq!(shapes::utf16(t, 3), 1);
    }
}
