//! The calls: what `stlc serve` answers and the WebAssembly module
//! returns, for a [`Body`] within [`Settings`]. No pipeline logic lives
//! here: loading, growing, the BED text, the SVG and the PNG all come
//! from [`Request`]'s methods, the calls `stlc render`, `compile` and
//! `check` make, so the bytes are the same for the same options.

use super::answer::{
    DiagnosticJson, Failed, Growth, RenderAnswer, WORD_CHARS, WORD_DEPTHS, Word, WordsAnswer,
    diagnostics_json,
};
use super::body::{Body, Settings};
use super::{shapes, stems3};
use crate::pipeline::{ImageFormat, MeshFormat, Progress, Request};

/// A writer that keeps the first `cap` bytes and stops the rest.
struct Capped {
    kept: Vec<u8>,
    cap: usize,
    /// Whether bytes past the cap were offered (and stopped).
    cut: bool,
}

impl std::io::Write for Capped {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let room = self.cap - self.kept.len();
        if room == 0 {
            self.cut = true;
            return Err(std::io::Error::other("enough"));
        }
        let n = buf.len().min(room);
        self.cut |= n < buf.len();
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
    let (loaded, _) = base.open().map_err(|d| Failed::new(text, &d, s.page))?;
    let Some(last) = (match &loaded {
        crate::pipeline::Loaded::Lsys(sys) => body.depth.or(sys.generations),
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
        let (stats, _) = req.stats(true).map_err(|d| Failed::new(text, &d, s.page))?;
        let length = serde_json::from_str::<serde_json::Value>(&stats)
            .ok()
            .and_then(|v| v["length"].as_str().map(str::to_string))
            .unwrap_or_default();
        let mut out = Capped {
            kept: Vec::new(),
            cap: WORD_CHARS,
            cut: false,
        };
        // A word longer than the cap stops the writer: what was kept is shown.
        let _ = req.expand(&mut out, progress);
        let word = String::from_utf8_lossy(&out.kept).trim_end().to_string();
        words.push(Word {
            depth,
            word,
            length,
            stats,
            cut: out.cut,
        });
    }
    Ok(WordsAnswer { ok: true, words })
}

/// What a render request drew, in the answer's terms, and a PNG's bytes
/// (an SVG is the answer's `svg`, moved there, not copied); a grown tree
/// of more than `tree_up_to` stems left out of the picture.
pub fn render(
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
        .map_err(|d| Failed::new(text, &d, s.page))?;
    let (bed, placed) = match drawn.trace {
        Some(t) => (Some(t.text), t.placed),
        None => (None, Vec::new()),
    };
    let mut stems = Vec::with_capacity(placed.len() * 6);
    let mut decisions = 0;
    // A 3D tree's stems are in `space`, with their third coordinates.
    for p in placed.iter().filter(|_| drawn.stems3.is_none()) {
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
        tree_in_svg: !drawn.tree_left_out && drawn.stems3.is_none(),
        stroke: drawn.stroke.to_string(),
        bed: bed.filter(|_| !drawn.tree_left_out),
        stems: match (drawn.grown, &drawn.count) {
            (Some(n), _) => n.to_string(),
            (None, Some(c)) => c.clone(),
            (None, None) => drawn.segments.to_string(),
        },
        stems_exact: drawn.grown.is_some() || drawn.count.is_some(),
        warnings: diagnostics_json(text, &drawn.warnings, s.page),
        growth: Growth { stems, decisions },
        view: drawn.view.map(|b| [b.min_x, b.min_y, b.max_x, b.max_y]),
        root: drawn.od.as_ref().map(|od| shapes::root_json(text, od)),
        layout: drawn.od.as_ref().map(|od| shapes::layout_json(text, od)),
        stems3: drawn.stems3.map(|s| stems3::stems3_json(s, round)),
    };
    Ok((answer, image))
}

/// A number with three decimals (a replay needs no more), never `-0`.
fn round(x: f64) -> f64 {
    let r = (x * 1000.0).round() / 1000.0;
    if r == 0.0 { 0.0 } else { r }
}

/// What an export writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// The picture as `stlc render -f png` writes it.
    Png,
    /// The picture as `stlc render -f svg` writes it.
    Svg,
    /// An OD's BED as `stlc compile` writes it.
    Bed,
    /// A 3D input's mesh as `stlc render --mesh glb` writes it (binary
    /// glTF, the body's `unit`; a mesh has no view).
    Glb,
}

impl Format {
    /// The format named `png`, `svg`, `bed` or `glb`.
    pub fn from_name(name: &str) -> Option<Format> {
        match name {
            "png" => Some(Format::Png),
            "svg" => Some(Format::Svg),
            "bed" => Some(Format::Bed),
            "glb" => Some(Format::Glb),
            _ => None,
        }
    }

    /// The media type of the file.
    pub fn media(self) -> &'static str {
        match self {
            Format::Png => "image/png",
            Format::Svg => "image/svg+xml",
            Format::Bed => "text/plain; charset=utf-8",
            Format::Glb => "model/gltf-binary",
        }
    }
}

/// An export: the file's bytes, what `stlc render -f png|svg`, `stlc
/// render --mesh glb` or `stlc compile` writes for the same options; or
/// the diagnostics.
pub fn export(
    body: &Body,
    s: &Settings,
    format: Format,
    progress: &mut dyn Progress,
) -> Result<Vec<u8>, Failed> {
    let mut picture = |image| render(body, s, image, None, progress);
    match format {
        Format::Bed => picture(ImageFormat::Svg)?
            .0
            .bed
            .map(String::into_bytes)
            .ok_or_else(|| {
                Failed::message("only an .od grows into a BED", "export a picture instead")
            }),
        Format::Png => Ok(picture(ImageFormat::Png)?.1),
        Format::Svg => Ok(picture(ImageFormat::Svg)?.0.svg.into_bytes()),
        Format::Glb => {
            let mut glb = Vec::new();
            body.request(s, ImageFormat::Svg)
                .mesh(MeshFormat::Glb, &mut glb, progress)
                .map_err(|d| Failed::new(&body.source, &d, s.page))?;
            Ok(glb)
        }
    }
}

/// `stlc compile`: an OD grown into its BED text, or the diagnostics.
pub fn compile(body: &Body, s: &Settings, progress: &mut dyn Progress) -> Result<String, Failed> {
    body.request(s, ImageFormat::Svg)
        .compile(progress)
        .map(|(compiled, _)| compiled.text)
        .map_err(|d| Failed::new(&body.source, &d, s.page))
}

/// The answer of `stlc check`: the summary's lines of text, as the CLI
/// prints them, and the warnings.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Checked {
    /// Always `true`.
    pub ok: bool,
    /// The summary `stlc check` prints.
    pub summary: String,
    /// Warnings.
    pub warnings: Vec<DiagnosticJson>,
}

/// `stlc check`: the summary and warnings, or the diagnostics.
pub fn check(body: &Body, s: &Settings) -> Result<Checked, Failed> {
    match body.request(s, ImageFormat::Svg).check() {
        Ok(c) => Ok(Checked {
            ok: true,
            warnings: diagnostics_json(&body.source, &c.warnings, s.page),
            summary: c.summary,
        }),
        Err(d) => Err(Failed::new(&body.source, &d, s.page)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::parse;
    use crate::pipeline::NoProgress;

    #[test]
    fn each_layout_shape_comes_with_its_own_text() {
        // The paper's one-line spelling, after a comment with a character
        // of two UTF-16 units: each span is the shape's text, `>` included.
        let text = "# 𝄞\n2DTree (76, 150)L=10(0) B=1(0)RULE R1: [+F][-F] LAYOUT \
                    (clGreen)< RoundRect (0,0,180,192,7,7)> # big\n\
                    (clWhite) Rectangle (55,30), 40, 15 ENDLAYOUT";
        let body = parse(format!(r#"{{"source": {text:?}}}"#).as_bytes()).unwrap();
        let s = Settings::defaults(crate::api::Page::Served);
        let (answer, _) = render(&body, &s, ImageFormat::Svg, None, &mut NoProgress).unwrap();
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

    /// The page reads a hint with its own words: the stem limit that cut a
    /// tree short is named as the server's flag to restart with, never as
    /// a flag the page would take; the command line keeps its flags.
    #[test]
    fn hints_on_the_page_name_no_flag_the_page_takes() {
        let tree = include_str!("../../examples/2dtree.od");
        let body = parse(
            format!(
                r#"{{"source": {}, "max_stems": 3}}"#,
                serde_json::to_string(tree).unwrap()
            )
            .as_bytes(),
        )
        .unwrap();
        let s = Settings::defaults(crate::api::Page::Served);
        let (answer, _) = render(&body, &s, ImageFormat::Svg, None, &mut NoProgress).unwrap();
        let w = serde_json::to_value(&answer.warnings[0]).unwrap();
        assert_eq!(
            w["message"],
            "growth stopped at 3 stems: the next rule application would pass the stem limit of 3"
        );
        assert_eq!(
            w["help"],
            "the BED is valid but its tree is cut short; raise the limit with \
             `stlc serve --max-stems N` (restart the server with it)"
        );
        let cli = body
            .request(&s, ImageFormat::Svg)
            .render(&mut Vec::new(), &mut NoProgress)
            .unwrap();
        assert_eq!(
            cli.warnings[0].help_text().unwrap(),
            "the BED is valid but its tree is cut short; raise the limit with --max-stems N"
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
