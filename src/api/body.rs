//! What a caller asks: the request body ([`Body`]) and the save body
//! ([`SaveBody`]), read with serde, within the caller's [`Settings`], and
//! the one mapping from a body to a [`crate::pipeline::Request`].
//!
//! A field the API does not know is refused (a [`BadRequest`] naming it;
//! HTTP 400 from the server): a misspelt `"clearence"` would otherwise be
//! ignored in silence.

use serde::Deserialize;

use crate::pipeline::{
    GrowthOrder, ImageFormat, InputKind, Limits, RenderOptions, Request, Rgb, ShowLayout,
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
    /// The page that reads the answers: how their hints name options.
    pub page: super::Page,
}

impl Settings {
    /// The command line's defaults (docs/limits.md) for `page`, with no
    /// time budget: the static site's settings (its page ends a render by
    /// ending its worker), and a test's.
    pub fn defaults(page: super::Page) -> Settings {
        Settings {
            limits: Limits::DEFAULT,
            max_stems: None,
            max_svg_segments: crate::pipeline::DEFAULT_MAX_SVG_SEGMENTS,
            time_budget: std::time::Duration::MAX,
            page,
        }
    }
}

/// A request body: `{"source", "kind"?, "growth"?, "depth"?,
/// "clearance"?, "max_stems"?, "seed"?, "size"?, "show_layout"?,
/// "background"?, "view"?, "unit"?}`. Absent and `null` fields take
/// their defaults; any other field is refused.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// The text.
    pub source: String,
    /// Its kind; `None`: guessed from the text, as for standard input.
    #[serde(default)]
    pub kind: Option<Kind>,
    /// Growth order of an .od (`--growth`); `strategy`, its old name, is
    /// still read.
    #[serde(default, alias = "strategy")]
    pub growth: Option<GrowthOrder>,
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
    /// `--unit` of a mesh export: metres per canvas unit, a positive
    /// number; `None`: the CLI's default (0.01).
    #[serde(default)]
    pub unit: Option<f64>,
}

/// `"od"`, `"bed"` or `"lsys"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
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
    if let Some(u) = b.unit
        && !(u.is_finite() && u > 0.0)
    {
        return Err(BadRequest(format!(
            "`unit`: {u} is not a positive number of metres, e.g. 0.01"
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
            growth: self.growth,
            depth: self.depth,
            seed: self.seed.map(|s| s.0),
            clearance: self.clearance,
            max_stems: self.max_stems.or(s.max_stems),
            limits: s.limits,
            look: crate::pipeline::Look {
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
            view: self.view.map(|[az, el]| crate::pipeline::View { az, el }),
            mesh: crate::pipeline::MeshOptions {
                unit: self.unit.unwrap_or(crate::pipeline::DEFAULT_UNIT),
                ..Default::default()
            },
            ..Request::new(self.source.clone().into_bytes())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bodies_take_defaults_and_refuse_wrong_types_and_unknown_fields() {
        let b = parse(br#"{"source": "x", "growth": "dfs", "depth": null}"#).unwrap();
        assert_eq!(b.source, "x");
        assert_eq!(b.growth, Some(GrowthOrder::Dfs));
        let b = parse(br#"{"source": "x", "growth": "space"}"#).unwrap();
        assert_eq!(b.growth, Some(GrowthOrder::Space));
        // `strategy`, the old name, is still read; both at once are refused.
        let b = parse(br#"{"source": "x", "strategy": "bfs"}"#).unwrap();
        assert_eq!(b.growth, Some(GrowthOrder::Bfs));
        assert!(parse(br#"{"source": "x", "strategy": "bfs", "growth": "dfs"}"#).is_err());
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
}
