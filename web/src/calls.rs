//! The calls the page makes, in safe Rust: a request's JSON in, the
//! answer's bytes out. The request and answer shapes are `stlc serve`'s
//! (`POST /api/render`, `/api/export`, `/api/words`; docs/serve.md, "HTTP
//! API"), read and written by the same code (src/serve/api.rs, compiled
//! into this crate), so the two engines of the page answer alike.

use serde::Serialize;
use stlc::pipeline::{DEFAULT_MAX_SVG_SEGMENTS, ImageFormat, Limits, NoProgress};

use crate::api::{self, BadRequest, Body, Failed};

/// How a call ended: what the bytes out are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum Status {
    /// The answer: JSON for render, words and check; the file's bytes for
    /// export and compile.
    Done = 0,
    /// JSON of a failure: `{ok: false, diagnostics}` for an input error,
    /// `{ok: false, error}` for a refused request.
    Failed = 1,
}

/// What a call gives back.
pub type Answer = (Status, Vec<u8>);

/// The limits in the browser: the CLI's defaults (docs/limits.md). There
/// is no time budget: the page ends a render by ending its worker.
pub fn settings() -> api::Settings {
    api::Settings {
        limits: Limits::DEFAULT,
        max_stems: None,
        max_svg_segments: DEFAULT_MAX_SVG_SEGMENTS,
        time_budget: std::time::Duration::MAX,
    }
}

fn json(status: Status, value: &impl Serialize) -> Answer {
    let bytes = serde_json::to_vec(value).unwrap_or_else(|e| {
        format!("{{\"ok\":false,\"error\":\"the answer could not be written: {e}\"}}").into_bytes()
    });
    (status, bytes)
}

/// A request refused before any work, as `stlc serve` answers it with an
/// HTTP error: `{ok: false, error}`.
fn refused(message: &str) -> Answer {
    #[derive(Serialize)]
    struct Refused<'a> {
        ok: bool,
        error: &'a str,
    }
    json(
        Status::Failed,
        &Refused {
            ok: false,
            error: message,
        },
    )
}

/// Reads a body as `stlc serve` does, within the same input limit.
fn body(input: &[u8]) -> Result<Body, Answer> {
    let limit = settings().limits.max_input_bytes;
    if input.len() as u64 > limit {
        return Err(refused(&format!(
            "the request is larger than the input limit of {limit} bytes"
        )));
    }
    api::parse(input).map_err(|BadRequest(m)| refused(&m))
}

/// `POST /api/render`: the picture (SVG), the BED, the growth order, the
/// root and layout with their places in the text; or the diagnostics.
pub fn render(input: &[u8]) -> Answer {
    let body = match body(input) {
        Ok(b) => b,
        Err(a) => return a,
    };
    // A big grown tree is left out of the SVG, as stlc serve's render does.
    let big = Some(api::BIG_TREE_STEMS);
    match api::run(&body, &settings(), ImageFormat::Svg, big, &mut NoProgress) {
        Ok((answer, _)) => json(Status::Done, &answer),
        Err(failed) => json(Status::Failed, &failed),
    }
}

/// What an export writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `stlc render -f png`.
    Png,
    /// `stlc render -f svg`.
    Svg,
    /// `stlc compile`.
    Bed,
}

impl Format {
    /// The format numbered `n` by the JavaScript glue (0 PNG, 1 SVG, 2 BED).
    pub fn from_number(n: u32) -> Option<Format> {
        match n {
            0 => Some(Format::Png),
            1 => Some(Format::Svg),
            2 => Some(Format::Bed),
            _ => None,
        }
    }
}

/// `POST /api/export?format=...`: the file's bytes (what `stlc render -f
/// png|svg` or `stlc compile` writes for the same options), or the
/// diagnostics.
pub fn export(input: &[u8], format: Option<Format>) -> Answer {
    let Some(format) = format else {
        return refused("say format png, svg or bed");
    };
    let body = match body(input) {
        Ok(b) => b,
        Err(a) => return a,
    };
    let image = match format {
        Format::Png => ImageFormat::Png,
        Format::Svg | Format::Bed => ImageFormat::Svg,
    };
    match api::run(&body, &settings(), image, None, &mut NoProgress) {
        Ok((answer, _)) if format == Format::Bed => match answer.bed {
            Some(bed) => (Status::Done, bed.into_bytes()),
            None => json(
                Status::Failed,
                &Failed::message("only an .od grows into a BED", "export a picture instead"),
            ),
        },
        Ok((answer, png)) => match format {
            Format::Png => (Status::Done, png),
            _ => (Status::Done, answer.svg.into_bytes()),
        },
        Err(failed) => json(Status::Failed, &failed),
    }
}

/// `POST /api/words`: an `.lsys`'s word generation by generation.
pub fn words(input: &[u8]) -> Answer {
    let body = match body(input) {
        Ok(b) => b,
        Err(a) => return a,
    };
    match api::words(&body, &settings(), &mut NoProgress) {
        Ok(answer) => json(Status::Done, &answer),
        Err(failed) => json(Status::Failed, &failed),
    }
}

/// `stlc compile`: an OD grown into its BED text, or the diagnostics.
pub fn compile(input: &[u8]) -> Answer {
    let body = match body(input) {
        Ok(b) => b,
        Err(a) => return a,
    };
    match body
        .request(&settings(), ImageFormat::Svg)
        .compile(&mut NoProgress)
    {
        Ok((compiled, _)) => (Status::Done, compiled.text.into_bytes()),
        Err(d) => json(Status::Failed, &Failed::new(&body.source, &d)),
    }
}

/// `stlc check`: `{ok: true, summary, warnings}` (the summary's lines of
/// text, as the CLI prints them), or the diagnostics.
pub fn check(input: &[u8]) -> Answer {
    #[derive(Serialize)]
    struct Checked {
        ok: bool,
        summary: String,
        warnings: Vec<api::DiagnosticJson>,
    }
    let body = match body(input) {
        Ok(b) => b,
        Err(a) => return a,
    };
    match body.request(&settings(), ImageFormat::Svg).check() {
        Ok(c) => json(
            Status::Done,
            &Checked {
                ok: true,
                warnings: api::diagnostics_json(&body.source, &c.warnings),
                summary: c.summary,
            },
        ),
        Err(d) => json(Status::Failed, &Failed::new(&body.source, &d)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TREE: &str = include_str!("../../examples/2dtree.od");

    fn request(source: &str, extra: &str) -> Vec<u8> {
        format!(
            "{{\"source\": {}{extra}}}",
            serde_json::to_string(source).unwrap()
        )
        .into_bytes()
    }

    fn value(a: &Answer) -> serde_json::Value {
        serde_json::from_slice(&a.1).unwrap()
    }

    #[test]
    fn render_answers_as_the_server_does() {
        let a = render(&request(TREE, ""));
        assert_eq!(a.0, Status::Done);
        let v = value(&a);
        assert_eq!(v["ok"], true);
        assert!(v["svg"].as_str().unwrap().starts_with("<svg"));
        assert!(v["bed"].as_str().unwrap().starts_with("2DTree"));
        // The root as written: `(76, 150)` in the file.
        assert_eq!(
            (v["root"]["x"].as_f64(), v["root"]["y"].as_f64()),
            (Some(76.0), Some(150.0))
        );
    }

    #[test]
    fn an_input_error_is_diagnostics_and_a_bad_request_an_error() {
        let text = "2DTree (1, 2) L=10(0) B=1(0)\nRULE\nR1: [+F][-F]\nSEED\nR2\nENDSEED\n";
        let a = render(&request(text, ""));
        assert_eq!(a.0, Status::Failed);
        let v = value(&a);
        assert_eq!(v["ok"], false);
        let d = &v["diagnostics"][0];
        assert_eq!(d["message"], "unknown rule `R2`");
        assert_eq!(
            (d["severity"].as_str(), d["line"].as_u64()),
            (Some("error"), Some(5))
        );
        let a = render(&request("x", ", \"clearence\": 2"));
        assert_eq!(a.0, Status::Failed);
        let error = value(&a)["error"].as_str().unwrap().to_string();
        assert!(error.contains("unknown field `clearence`"), "{error}");
        assert_eq!(export(b"{}", None).0, Status::Failed);
    }

    #[test]
    fn exports_are_the_cli_bytes_for_the_same_request() {
        // The CLI's own call for the same options: Request::render and
        // Request::compile with the body's request.
        let input = request(TREE, ", \"strategy\": \"dfs\"");
        let body = api::parse(&input).unwrap();
        let mut svg = Vec::new();
        body.request(&settings(), ImageFormat::Svg)
            .render(&mut svg, &mut NoProgress)
            .unwrap();
        assert_eq!(export(&input, Some(Format::Svg)), (Status::Done, svg));
        let (bed, _) = body
            .request(&settings(), ImageFormat::Svg)
            .compile(&mut NoProgress)
            .unwrap();
        let exported = export(&input, Some(Format::Bed));
        assert_eq!(exported, (Status::Done, bed.text.clone().into_bytes()));
        assert_eq!(compile(&input), (Status::Done, bed.text.into_bytes()));
        let png = export(&input, Some(Format::Png));
        assert_eq!(&png.1[..8], b"\x89PNG\r\n\x1a\n");
    }

    #[test]
    fn words_and_check_answer_json() {
        let koch = include_str!("../../examples/koch-snowflake.lsys");
        let v = value(&words(&request(koch, ", \"depth\": 1")));
        assert_eq!(v["words"][0]["depth"], 0);
        assert_eq!(v["words"].as_array().unwrap().len(), 2);
        let v = value(&check(&request(TREE, "")));
        assert_eq!(v["ok"], true);
        assert!(v["summary"].as_str().unwrap().contains("2DTree"));
    }
}
