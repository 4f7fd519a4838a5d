//! The JSON API of `stlc serve`: a request's fields mapped to library
//! pipeline requests ([`stlc::pipeline`]), and what comes back as JSON.
//!
//! No pipeline logic lives here: loading, growing, the BED text, the SVG
//! and the PNG all come from the same library calls `stlc compile` and
//! `stlc render` make, so the bytes are the same for the same options.

use serde_json::{Map, Value, json};

use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, line_column};
use stlc::grow::{GrowOptions, GrowthOrder, PlacedStem};
use stlc::interpret::Derivation;
use stlc::limits::{Bound, Limits};
use stlc::model::Description;
use stlc::model::layout::Shape;
use stlc::pipeline::{self, Given, Loaded, Look, SceneRequest};
use stlc::progress::NoProgress;
use stlc::render::{ImageFormat, RenderOptions};
use stlc::syntax::InputKind;

/// What a request asks for, once its JSON is read.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The text.
    pub source: String,
    /// Its kind; `None`: guessed from the text, as for standard input.
    pub kind: Option<InputKind>,
    /// Growth order of an .od (`--growth`).
    pub growth: GrowthOrder,
    /// Derivation depth of an .lsys (`--depth`).
    pub depth: Option<u32>,
    /// `--clearance`.
    pub clearance: Option<f64>,
    /// `--max-stems`.
    pub max_stems: Option<u64>,
    /// `--seed` of stochastic rules.
    pub seed: Option<u64>,
}

/// The server's own settings that every request works within.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The `--max-*` limits `stlc serve` was started with.
    pub limits: Limits,
    /// Whether `--max-stems` was given to `stlc serve`.
    pub max_stems_explicit: bool,
    /// `--max-svg-segments`.
    pub max_svg_segments: u64,
}

/// A malformed request (HTTP 400): the JSON is not what the API takes.
#[derive(Debug, Clone, PartialEq)]
pub struct BadRequest(pub String);

/// Reads a request body: `{"source": TEXT, "kind"?, "strategy"?, "depth"?,
/// "clearance"?, "max_stems"?, "seed"?}`; absent and `null` fields take defaults;
/// `seed` is a number or a string of digits.
pub fn parse_request(body: &[u8]) -> Result<(Request, Map<String, Value>), BadRequest> {
    let value: Value =
        serde_json::from_slice(body).map_err(|e| BadRequest(format!("malformed JSON: {e}")))?;
    let Value::Object(obj) = value else {
        return Err(BadRequest("the body must be a JSON object".into()));
    };
    let field = |name: &str| obj.get(name).filter(|v| !v.is_null());
    let source = match field("source") {
        Some(Value::String(s)) => s.clone(),
        _ => return Err(BadRequest("`source` must be a string".into())),
    };
    let kind = match field("kind") {
        None => None,
        Some(Value::String(k)) => Some(match k.as_str() {
            "od" => InputKind::Od,
            "bed" => InputKind::Bed,
            "lsys" => InputKind::Lsys,
            _ => {
                return Err(BadRequest(
                    "`kind` must be \"od\", \"bed\" or \"lsys\"".into(),
                ));
            }
        }),
        Some(_) => return Err(BadRequest("`kind` must be a string".into())),
    };
    let growth = match field("strategy") {
        None => GrowthOrder::Bfs,
        Some(Value::String(s)) if s == "bfs" => GrowthOrder::Bfs,
        Some(Value::String(s)) if s == "dfs" => GrowthOrder::Dfs,
        Some(_) => return Err(BadRequest("`strategy` must be \"bfs\" or \"dfs\"".into())),
    };
    let whole = |name: &str| -> Result<Option<u64>, BadRequest> {
        match field(name) {
            None => Ok(None),
            Some(v) => v
                .as_u64()
                .map(Some)
                .ok_or_else(|| BadRequest(format!("`{name}` must be a whole number >= 0"))),
        }
    };
    let depth = match whole("depth")? {
        None => None,
        Some(d) => Some(u32::try_from(d).map_err(|_| BadRequest("`depth` is too large".into()))?),
    };
    let max_stems = whole("max_stems")?;
    // A seed may be any u64, past what a JavaScript number holds exactly
    // (2^53), so the page sends it as a string of digits.
    let seed = match field("seed") {
        Some(Value::String(t)) => Some(t.trim().parse::<u64>().map_err(|_| {
            BadRequest(format!(
                "`seed` must be a whole number from 0 to {}, not `{t}`",
                u64::MAX
            ))
        })?),
        _ => whole("seed")?,
    };
    let clearance = match field("clearance") {
        None => None,
        Some(v) => Some(
            v.as_f64()
                .ok_or_else(|| BadRequest("`clearance` must be a number".into()))?,
        ),
    };
    Ok((
        Request {
            source,
            kind,
            growth,
            depth,
            clearance,
            max_stems,
            seed,
        },
        obj,
    ))
}

/// The limits and growth options of one request: the server's, with the
/// page's stem limit if it asked for one within the server's.
fn options(req: &Request, s: &Settings) -> Result<(Limits, GrowOptions), Diagnostics> {
    let mut limits = s.limits;
    let mut explicit = s.max_stems_explicit;
    if let Some(n) = req.max_stems {
        if n > s.limits.max_stems {
            return Err(Diagnostic::error(ErrorKind::Limit {
                bound: Bound::Stems,
                what: Some("max stems asked for".into()),
                value: n.to_string(),
                limit: s.limits.max_stems,
            })
            .with_help(format!(
                "ask for fewer, or start `stlc serve` with {} N",
                Bound::Stems.flag()
            ))
            .into());
        }
        limits.max_stems = n;
        explicit = true;
    }
    let grow = GrowOptions {
        growth: req.growth,
        clearance: req.clearance,
        limits,
        max_stems_explicit: explicit,
        seed: req.seed.unwrap_or(0),
    };
    Ok((limits, grow))
}

/// What a request grew and drew.
struct Outcome {
    svg: String,
    bed: Option<String>,
    stems: u64,
    placed: Vec<PlacedStem>,
    view: Option<[f64; 4]>,
    warnings: Vec<Diagnostic>,
    /// An .od's root and LAYOUT as JSON, for the page to draw and edit.
    od: Option<(Value, Value)>,
}

/// Loads, grows (an .od) and draws the request's input as `format`: the
/// library calls `stlc compile` and `stlc render --show-layout` make.
fn run(
    req: &Request,
    s: &Settings,
    format: ImageFormat,
) -> Result<(Outcome, Vec<u8>), Diagnostics> {
    let (limits, grow) = options(req, s)?;
    let bytes = req.source.as_bytes();
    let kind = match req.kind {
        Some(k) => k,
        None => pipeline::detect_kind(None, bytes)?,
    };
    let loaded = pipeline::load(bytes, kind, &limits)?.seeded(req.seed);
    let given = Given {
        growth: false,
        clearance: req.clearance.is_some(),
        max_stems: req.max_stems.is_some(),
        depth: req.depth.is_some(),
        seed: req.seed.is_some(),
    };
    let mut warnings = pipeline::ignored_flags(&loaded, &given);
    let scene_req = SceneRequest {
        grow,
        derivation: Derivation::Dfs,
        depth: req.depth,
        limits,
    };
    let (scene, bed, stems, placed, od) = match &loaded {
        Loaded::Od(desc) => {
            let drawn = (root_json(&req.source, desc), layout_json(&req.source, desc));
            let (compiled, placed) = pipeline::compile_traced(&loaded, &grow, &mut NoProgress)?;
            warnings.extend(compiled.grown.warnings);
            let stems = compiled.grown.stems;
            // The grown BED drawn as it is: the same tree `render x.od`
            // grows and draws, grown once.
            let scene =
                pipeline::scene(Loaded::Bed(compiled.grown.bed), &scene_req, &mut NoProgress)?;
            (scene, Some(compiled.text), Some(stems), placed, Some(drawn))
        }
        _ => {
            let scene = pipeline::scene(loaded, &scene_req, &mut NoProgress)?;
            (scene, None, None, Vec::new(), None)
        }
    };
    warnings.extend(scene.warnings.iter().cloned());
    let look = Look {
        show_layout: scene.has_layout(),
        ..Look::default()
    };
    let opts = RenderOptions {
        format,
        size: None,
        max_svg_segments: s.max_svg_segments,
        // The CLI's default level of detail (no `--exact`): the same bytes.
        exact: false,
    };
    let mut image = Vec::new();
    let rendered = pipeline::render(&scene, &look, &opts, &mut image, &mut NoProgress)?;
    warnings.extend(rendered.warnings);
    let view = pipeline::layout_view(&scene, false)
        .0
        .map(|b| [b.min_x, b.min_y, b.max_x, b.max_y]);
    let svg = match format {
        ImageFormat::Svg => String::from_utf8(image.clone()).unwrap_or_default(),
        ImageFormat::Png => String::new(),
    };
    Ok((
        Outcome {
            svg,
            bed,
            stems: stems.unwrap_or(rendered.segments),
            placed,
            view,
            warnings,
            od,
        },
        image,
    ))
}

/// `POST /api/render`: the answer as JSON (always HTTP 200 once the
/// request itself is well formed).
pub fn render(req: &Request, s: &Settings) -> Value {
    match run(req, s, ImageFormat::Svg) {
        Ok((out, _)) => {
            let mut growth = Vec::with_capacity(out.placed.len() * 6);
            let mut decisions = 0;
            for p in &out.placed {
                growth.extend([
                    round(p.from.x),
                    round(p.from.y),
                    round(p.to.x),
                    round(p.to.y),
                    round(p.width),
                    Value::from(p.decision),
                ]);
                decisions = decisions.max(p.decision);
            }
            let text = &req.source;
            let mut answer = json!({
                "ok": true,
                "svg": out.svg,
                "bed": out.bed,
                "stems": out.stems,
                "warnings": diagnostics_json(text, &out.warnings),
                "growth": {"stems": growth, "decisions": decisions},
                "view": out.view,
            });
            if let Some((root, layout)) = out.od {
                answer["root"] = root;
                answer["layout"] = layout;
            }
            answer
        }
        Err(diags) => failed(&req.source, &diags),
    }
}

/// `POST /api/export`: the file's bytes and media type, or the
/// diagnostics as JSON.
pub fn export(req: &Request, s: &Settings, format: &str) -> Result<(Vec<u8>, &'static str), Value> {
    let image = match format {
        "png" => ImageFormat::Png,
        "svg" | "bed" => ImageFormat::Svg,
        _ => unreachable!("checked by the caller"),
    };
    let (out, bytes) = run(req, s, image).map_err(|d| failed(&req.source, &d))?;
    match format {
        "png" => Ok((bytes, "image/png")),
        "svg" => Ok((bytes, "image/svg+xml")),
        _ => match out.bed {
            Some(bed) => Ok((bed.into_bytes(), "text/plain; charset=utf-8")),
            None => Err(json!({"ok": false, "diagnostics": [{
                "message": "only an .od grows into a BED",
                "severity": "error", "line": null, "column": null,
                "end_line": null, "end_column": null,
                "help": "export a picture instead", "label": null,
            }]})),
        },
    }
}

/// The answer for an input error.
fn failed(text: &str, diags: &Diagnostics) -> Value {
    let list: Vec<Diagnostic> = diags.iter().cloned().collect();
    json!({"ok": false, "diagnostics": diagnostics_json(text, &list)})
}

/// A number with three decimals, as JSON (a replay needs no more).
fn round(x: f64) -> Value {
    let r = (x * 1000.0).round() / 1000.0;
    serde_json::Number::from_f64(if r == 0.0 { 0.0 } else { r }).map_or(Value::Null, Value::Number)
}

/// Diagnostics as JSON: message, severity, 1-based line and column of the
/// span's start and end (`null` when it has none), label, help.
pub fn diagnostics_json(text: &str, diags: &[Diagnostic]) -> Value {
    Value::Array(
        diags
            .iter()
            .map(|d| {
                let at = |p: usize| {
                    let p = floor_char(text, p.min(text.len()));
                    line_column(text, p)
                };
                let (start, end) = match &d.span {
                    Some(span) if span.end <= text.len() => {
                        (Some(at(span.start)), Some(at(span.end)))
                    }
                    _ => (None, None),
                };
                json!({
                    "message": d.kind.to_string(),
                    "severity": if d.is_error() { "error" } else { "warning" },
                    "line": start.map(|s| s.0),
                    "column": start.map(|s| s.1),
                    "end_line": end.map(|e| e.0),
                    "end_column": end.map(|e| e.1),
                    "label": d.label,
                    "help": d.help,
                })
            })
            .collect(),
    )
}

fn floor_char(text: &str, mut i: usize) -> usize {
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// A byte offset of `text` as a UTF-16 offset (a JavaScript string index).
fn utf16(text: &str, byte: usize) -> usize {
    let b = floor_char(text, byte.min(text.len()));
    text[..b].encode_utf16().count()
}

/// Where the root is written, and where, so the page can move it; a
/// forest's further roots as `others` (drawn, not moved by the page).
fn root_json(text: &str, od: &Description) -> Value {
    let span = &od.root_loc.0;
    let others: Vec<Value> = od
        .forest
        .iter()
        .map(|t| json!({"x": t.root.0, "y": t.root.1}))
        .collect();
    json!({
        "x": od.root.0,
        "y": od.root.1,
        "start": utf16(text, span.start),
        "end": utf16(text, span.end),
        "others": others,
    })
}

/// The LAYOUT as written: its shapes in painting order, each with its
/// geometry and colour, and where the section is, so the page can draw
/// the shapes and write the section anew.
fn layout_json(text: &str, od: &Description) -> Value {
    let Some(layout) = &od.layout else {
        return Value::Null;
    };
    let shapes: Vec<Value> = layout
        .shapes
        .iter()
        .map(|s| {
            let mut v = match &s.shape {
                Shape::Rect { x, y, w, h } => {
                    json!({"type": "Rectangle", "x": x, "y": y, "w": w, "h": h})
                }
                Shape::RoundRect { x, y, w, h, rx, ry } => json!({
                    "type": "RoundRect", "x": x, "y": y, "w": w, "h": h, "rx": rx, "ry": ry
                }),
                Shape::Ellipse { x, y, w, h } => {
                    json!({"type": "Ellipse", "x": x, "y": y, "w": w, "h": h})
                }
                Shape::Polygon(points) => json!({
                    "type": "Polygon",
                    "points": points.iter().map(|&(x, y)| json!([x, y])).collect::<Vec<_>>(),
                }),
            };
            v["color"] = Value::String(s.color.to_string());
            v["name"] = Value::String(
                s.color
                    .delphi_name()
                    .map_or_else(|| s.color.to_string(), str::to_string),
            );
            v
        })
        .collect();
    let span = &layout.loc.0;
    json!({
        "start": utf16(text, span.start),
        "end": utf16(text, span.end),
        "shapes": shapes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_take_defaults_and_refuse_wrong_types() {
        let (r, _) =
            parse_request(br#"{"source": "x", "strategy": "dfs", "depth": null}"#).unwrap();
        assert_eq!(r.source, "x");
        assert_eq!(r.growth, GrowthOrder::Dfs);
        assert_eq!(r.depth, None);
        assert_eq!(r.kind, None);
        for bad in [
            &br#"{"source": 3}"#[..],
            br#"[1]"#,
            br#"{"source": "x", "kind": "png"}"#,
            br#"{"source": "x", "depth": -1}"#,
            br#"{"source": "x", "depth": 5000000000}"#,
            br#"{"source": "x", "clearance": "1"}"#,
            b"{",
        ] {
            assert!(
                parse_request(bad).is_err(),
                "{}",
                String::from_utf8_lossy(bad)
            );
        }
    }

    #[test]
    fn utf16_offsets_count_javascript_units() {
        // `é` is 2 bytes and 1 unit; `𝄞` is 4 bytes and 2 units.
        let t = "é𝄞x";
        assert_eq!(utf16(t, 0), 0);
        assert_eq!(utf16(t, 2), 1);
        assert_eq!(utf16(t, 6), 3);
        assert_eq!(utf16(t, 7), 4);
        // Inside a character: floored to its start.
        assert_eq!(utf16(t, 3), 1);
    }
}
