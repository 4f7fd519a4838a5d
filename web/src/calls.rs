//! The calls the page makes, as bytes: a request's JSON in, the answer's
//! bytes out. Each is the library's call ([`stlc::api`]), the one `stlc
//! serve` answers `POST /api/render`, `/api/export` and `/api/words` with
//! (docs/serve.md, "HTTP API"), so the page's two engines answer alike;
//! this file only reads the body and writes the answer.

use serde::Serialize;
use stlc::api::{self, BadRequest, Body, Format};
use stlc::pipeline::{ImageFormat, NoProgress};

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
    api::Settings::defaults(api::Page::Web)
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

/// Writes a call's answer: its bytes, or its failure as JSON.
fn answer<T>(done: Result<T, api::Failed>, bytes: impl FnOnce(T) -> Vec<u8>) -> Answer {
    match done {
        Ok(t) => (Status::Done, bytes(t)),
        Err(failed) => json(Status::Failed, &failed),
    }
}

/// JSON bytes of a value.
fn to_json(value: &impl Serialize) -> Vec<u8> {
    json(Status::Done, value).1
}

/// `POST /api/render`: the picture (SVG), the BED, the growth order, the
/// root and layout with their places in the text; or the diagnostics. A
/// big grown tree is left out of the SVG, as `stlc serve`'s render does.
pub fn render(input: &[u8]) -> Answer {
    let big = Some(api::BIG_TREE_STEMS);
    match body(input) {
        Ok(b) => answer(
            api::render(&b, &settings(), ImageFormat::Svg, big, &mut NoProgress),
            |(a, _)| to_json(&a),
        ),
        Err(a) => a,
    }
}

/// `POST /api/export?format=...`: the file's bytes (what `stlc render -f
/// png|svg` or `stlc compile` writes for the same options), or the
/// diagnostics.
pub fn export(input: &[u8], format: Option<Format>) -> Answer {
    let Some(format) = format else {
        return refused("say format png, svg, bed or glb");
    };
    match body(input) {
        Ok(b) => answer(api::export(&b, &settings(), format, &mut NoProgress), |x| x),
        Err(a) => a,
    }
}

/// `POST /api/words`: an `.lsys`'s word generation by generation.
pub fn words(input: &[u8]) -> Answer {
    match body(input) {
        Ok(b) => answer(api::words(&b, &settings(), &mut NoProgress), |a| {
            to_json(&a)
        }),
        Err(a) => a,
    }
}

/// `stlc compile`: an OD grown into its BED text, or the diagnostics.
pub fn compile(input: &[u8]) -> Answer {
    match body(input) {
        Ok(b) => answer(
            api::compile(&b, &settings(), &mut NoProgress),
            String::into_bytes,
        ),
        Err(a) => a,
    }
}

/// `stlc check`: `{ok: true, summary, warnings}` (the summary's lines of
/// text, as the CLI prints them), or the diagnostics.
pub fn check(input: &[u8]) -> Answer {
    match body(input) {
        Ok(b) => answer(api::check(&b, &settings()), |c| to_json(&c)),
        Err(a) => a,
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
        let input = request(TREE, ", \"growth\": \"dfs\"");
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
    fn a_mesh_export_is_the_cli_mesh_at_the_unit_asked() {
        // `stlc render --mesh glb --unit 0.02`: Request::mesh with that unit.
        let cube = include_str!("../../examples/hilbert3d.lsys");
        let input = request(cube, ", \"unit\": 0.02");
        let mut want = Vec::new();
        stlc::pipeline::Request {
            mesh: stlc::pipeline::MeshOptions {
                unit: 0.02,
                ..Default::default()
            },
            ..api::parse(&request(cube, ""))
                .unwrap()
                .request(&settings(), ImageFormat::Svg)
        }
        .mesh(stlc::pipeline::MeshFormat::Glb, &mut want, &mut NoProgress)
        .unwrap();
        assert_eq!(&want[..4], b"glTF");
        assert_eq!(export(&input, Some(Format::Glb)), (Status::Done, want));
        let bad = export(&request(cube, ", \"unit\": -1"), Some(Format::Glb));
        assert_eq!(bad.0, Status::Failed);
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
