//! Three dimensions (docs/3d.md): `dimensions 3` in an `.lsys`, its views,
//! its stats, and meshes of any input.

use std::collections::BTreeMap;

use stlc::pipeline::{ImageFormat, MeshFormat, NoProgress, RenderOptions, Request, View};

use crate::support::{
    example_text as example, gltf_validate, gltf_validator_present, limits_with, manifest_path,
    numbers, outcome, stlc_line, stlc_piped,
};

fn lsys_request(text: &str) -> Request {
    Request {
        name: Some("x.lsys".into()),
        ..Request::new(text.as_bytes().to_vec())
    }
}

fn render(req: &Request) -> Vec<u8> {
    let mut out = Vec::new();
    req.render(&mut out, &mut NoProgress).unwrap();
    out
}

/// `stats --json` of `req`, read back.
fn stats_of(req: &Request) -> serde_json::Value {
    let (s, _) = req.stats(true).unwrap();
    serde_json::from_str(&s).unwrap()
}

/// A planar branching system at an angle whose directions are not exact.
const PLANAR: &str = "generations 4\nangle 25.7\naxiom F\nrule F F[+F]F[-F]F\nwidth 2\n";

/// `--view 0,0` of a planar system with `dimensions 3` is its 2D picture,
/// byte for byte, PNG and SVG. The 2D side is drawn `--exact`: this small
/// view cuts nothing, so it draws every stem by the exact path, as
/// `--exact` does.
#[test]
fn the_front_view_of_a_planar_system_is_its_2d_picture() {
    for format in [ImageFormat::Png, ImageFormat::Svg] {
        let image = RenderOptions::new(format, Some((300, 240)));
        let mut flat = lsys_request(PLANAR);
        (flat.image, flat.image.exact) = (image, true);
        let flat = render(&flat);
        let mut req = lsys_request(&format!("dimensions 3\n{PLANAR}"));
        (req.image, req.view) = (image, Some(View::FRONT));
        let deep = render(&req);
        assert!(flat.len() > 500);
        assert!(flat == deep, "{format:?} differs");
        // Another view is another picture.
        req.view = Some(View { az: 0.0, el: 60.0 });
        let turned = render(&req);
        assert!(turned != deep);
    }
}

fn stats_json(text: &str) -> serde_json::Value {
    stats_of(&lsys_request(text))
}

/// Section 11's worked ends, in `stats --json`.
#[test]
fn stats_give_the_worked_ends_and_a_3d_box() {
    for (word, end, bbox) in [
        ("F+F", [-1.0, -1.0, 0.0], [-1.0, -1.0, 0.0, 0.0, 0.0, 0.0]),
        ("F&F", [0.0, -1.0, 1.0], [0.0, -1.0, 0.0, 0.0, 0.0, 1.0]),
        ("F/+F", [0.0, -1.0, -1.0], [0.0, -1.0, -1.0, 0.0, 0.0, 0.0]),
    ] {
        let three = "dimensions 3\nangle 90\ngenerations 0\naxiom";
        let j = stats_json(&format!("{three} {word}\n"));
        assert_eq!(numbers(&j["end"]), end, "{word}");
        assert_eq!(numbers(&j["bbox"]), bbox, "{word}");
        assert_eq!(j["segments"], "2");
    }
    // The 3D Hilbert curve at depth 3: 8^3 points, a cube of side 7.
    let mut req = lsys_request(&example("hilbert3d.lsys"));
    req.depth = Some(3);
    let j = stats_of(&req);
    assert_eq!(j["segments"], "511");
    let b: Vec<f64> = numbers(&j["bbox"]);
    assert_eq!((b[3] - b[0], b[4] - b[1], b[5] - b[2]), (7.0, 7.0, 7.0));
}

/// Past the traversal budget stats give a bound, marked as such; at right
/// angles the reach memo gives the exact box at any depth instead.
#[test]
fn stats_past_the_budget_give_a_bound() {
    let small = limits_with(|l| l.max_symbols = 100);
    let mut req = lsys_request(&example("plant3d-bare.lsys"));
    (req.limits, req.depth) = (small, Some(2));
    let j = stats_of(&req);
    assert!(j["bbox"].is_null() && j["end"].is_null());
    // Depth 2: two steps, the second pitched 22.5 degrees from the first,
    // so the farthest point is 2 cos 11.25 = 1.9616 steps from the start;
    // the reach memo's ball (triangle inequality) has radius 2, where the
    // step count (12 `F`) bounded before.
    let n = j["bound"][3].as_f64().unwrap();
    assert!((n - 2.0).abs() < 1e-9, "{n}");
    assert_eq!(j["segments"], "12");
    // The Hilbert curve at depth 16 (2.8 * 10^14 symbols): exact, a cube
    // of side 2^16 - 1, on the lattice.
    let mut req = lsys_request(&example("hilbert3d.lsys"));
    for depth in [2, 10, 16] {
        (req.limits, req.depth) = (small, Some(depth));
        let j = stats_of(&req);
        assert!(j["bound"].is_null(), "{j}");
        let b = numbers(&j["bbox"]);
        let side = f64::from((1u32 << depth) - 1);
        assert_eq!((b[3] - b[0], b[4] - b[1], b[5] - b[2]), (side, side, side));
        assert!(b.iter().all(|v| v.fract() == 0.0));
    }
}

#[test]
fn dimensions_other_than_2_or_3_are_refused_with_help() {
    let four = "dimensions 4\nangle 90\naxiom F\n";
    let (code, _, err) = outcome(stlc_line("check -").write_stdin(four));
    let said = ["`dimensions` is 2 or 3, not `4`", "dimensions 3"];
    assert!(code != 0 && said.iter().all(|s| err.contains(s)), "{err}");
}

/// In a 2D file `&` is an ordinary symbol, and `--view` a warning.
#[test]
fn a_2d_file_keeps_its_meaning_and_warns_of_a_view() {
    let j = stats_json("angle 90\ngenerations 0\naxiom F&F\n");
    let end: Vec<f64> = numbers(&j["end"]);
    assert_eq!(end, [0.0, -2.0]);
    let mut req = lsys_request("angle 90\ngenerations 0\naxiom F&F\n");
    req.view = Some(View::DEFAULT);
    let drawn = req.render(&mut Vec::new(), &mut NoProgress).unwrap();
    let names_view = |w: &stlc::Diagnostic| w.to_string().contains("--view");
    assert!(drawn.warnings.iter().any(names_view));
}

fn mesh(req: &Request, format: MeshFormat) -> Vec<u8> {
    let mut out = Vec::new();
    req.mesh(format, &mut out, &mut NoProgress).unwrap();
    out
}

/// The Hilbert curve's glTF: 63 stems of 4 * 6 - 4 triangles and
/// 4 * 6 + 2 vertices, read back
/// with serde_json; the same bytes on a second run; the `.glb` carries the
/// same buffer.
#[test]
fn a_3d_system_exports_a_gltf_that_reads_back() {
    let req = lsys_request(&example("hilbert3d.lsys"));
    let a = mesh(&req, MeshFormat::Gltf);
    assert_eq!(a, mesh(&req, MeshFormat::Gltf), "not deterministic");
    let j: serde_json::Value = serde_json::from_slice(&a).unwrap();
    let prim = &j["meshes"][0]["primitives"][0];
    let idx = &j["accessors"][prim["indices"].as_u64().unwrap() as usize];
    assert_eq!(idx["count"].as_u64(), Some(63 * 20 * 3));
    let pos = &j["accessors"][prim["attributes"]["POSITION"].as_u64().unwrap() as usize];
    assert_eq!(pos["count"].as_u64(), Some(63 * 26));
    // The cube of side 3 units, 0.01 m a unit, plus the tubes' radius
    // (width 3: a tenth of a step per pixel, so 0.15 units) on each side:
    // along x a hexagon across the tubes along y and z reaches
    // r cos 30 degrees.
    let span = pos["max"][0].as_f64().unwrap() - pos["min"][0].as_f64().unwrap();
    let r = 0.0015 * (3f64.sqrt() / 2.0);
    assert!((span - 0.03 - 2.0 * r).abs() < 1e-6, "{span}");
    let glb = mesh(&req, MeshFormat::Glb);
    assert_eq!(&glb[..4], b"glTF");
}

/// A 2D BED lifted to z = 0 exports an OBJ with a vertex, a texture
/// coordinate, a normal and faces per stem; a triangle limit refuses with the flag to raise it.
#[test]
fn a_2d_tree_exports_an_obj_and_the_limit_refuses() {
    let mut req = Request::new(example("paper-worked.bed").into_bytes());
    (req.name, req.mesh.sides) = (Some("t.bed".into()), 4);
    // `stlc check` counts 11 stems in this BED.
    let stems = 11;
    let text = String::from_utf8(mesh(&req, MeshFormat::Obj)).unwrap();
    let mut count: BTreeMap<&str, u64> = BTreeMap::new();
    for l in text.lines() {
        *count.entry(l.split(' ').next().unwrap()).or_default() += 1;
    }
    assert_eq!(count["v"], 18 * stems, "4 x sides + 2 vertices a stem");
    let tubes = stems;
    assert_eq!(count["vn"], count["v"]);
    assert_eq!(count["vt"], count["v"]);
    assert_eq!(count["f"], tubes * 12);
    let mut too_small = req.clone();
    too_small.mesh.max_triangles = 12 * tubes - 1;
    let err = too_small.mesh(MeshFormat::Obj, &mut Vec::new(), &mut NoProgress);
    let err = err.unwrap_err();
    assert!(err.to_string().contains("--max-triangles"), "{err}");
}

/// The command line: `-o x.glb` writes a binary glTF, `--view` takes
/// negative angles.
#[test]
fn the_command_line_writes_meshes_and_views() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("h.glb");
    let png = dir.path().join("h.png");
    let input = manifest_path("examples/hilbert3d.lsys");
    let (from, to) = (input.display(), glb.display());
    stlc_piped(&format!("render {from} -o {to}"), "");
    assert_eq!(&std::fs::read(&glb).unwrap()[..4], b"glTF");
    let (shown, to) = (input.display(), png.display());
    let line = format!("render {shown} --view -45,10 -o {to}");
    stlc_piped(&line, "");
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
}

/// Every example's glTF (3D and 2D, `.glb` and `.gltf`) passes the Khronos
/// glTF validator with no error and no warning. It runs from npm
/// (`npm ci` installs it, as for ESLint); without it the test fails under
/// CI and is skipped, saying so, elsewhere.
#[test]
fn the_khronos_validator_finds_no_issue() {
    if !gltf_validator_present() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for (example, format, ext) in [
        ("hilbert3d.lsys", MeshFormat::Glb, "glb"),
        ("plant3d.lsys", MeshFormat::Gltf, "gltf"),
        ("paper-worked.bed", MeshFormat::Glb, "glb"),
        ("koch-snowflake.lsys", MeshFormat::Gltf, "gltf"),
        ("oak3d.od", MeshFormat::Glb, "glb"),
        ("forest3d.od", MeshFormat::Gltf, "gltf"),
        ("abop-1.26.lsys", MeshFormat::Glb, "glb"),
    ] {
        let path = manifest_path("examples").join(example);
        let mut req = Request::new(std::fs::read(&path).unwrap());
        req.name = Some(path.clone());
        let out = dir.path().join(format!("{example}.{ext}"));
        std::fs::write(&out, mesh(&req, format)).unwrap();
        files.push(out);
    }
    let said = gltf_validate(&files);
    let clean = said.lines().filter(|l| l.ends_with(" 0 0")).count();
    assert_eq!(clean, 7, "{said}");
}

/// `--mesh obj -o -` writes the OBJ to standard output; `--mesh` against
/// the output's extension is a usage error.
#[test]
fn a_mesh_goes_to_standard_output_when_asked() {
    let input = manifest_path("examples/hilbert3d.lsys");
    let out = stlc_piped(&format!("render {} --mesh obj -o -", input.display()), "");
    let text = String::from_utf8(out).unwrap();
    let faces = text.lines().filter(|l| l.starts_with("f ")).count();
    assert_eq!(faces, 63 * 20);
    let line = format!("render {} --mesh obj -o x.glb", input.display());
    assert_eq!(outcome(&mut stlc_line(&line)).0, 2);
}

/// A view at a depth whose stems no view could hold (the Hilbert curve at
/// depth 12: 6.9 x 10^10 stems) is drawn at a level of detail within its
/// budget of 10^6 stems and stand-ins, and a warning gives the detail.
#[test]
fn a_deep_view_is_drawn_at_a_level_of_detail_within_its_budget() {
    let mut req = lsys_request(&example("hilbert3d.lsys"));
    req.depth = Some(12);
    let mut out = Vec::new();
    let drawn = req.render(&mut out, &mut NoProgress).unwrap();
    assert!(out.starts_with(b"\x89PNG"));
    let segments = drawn.segments;
    assert!(segments > 0 && segments <= 1_000_000, "{segments}");
    let w: Vec<String> = drawn.warnings.iter().map(|d| d.to_string()).collect();
    assert!(w.iter().any(|m| m.contains("level of detail of")), "{w:?}");
}

/// `--view` takes an elevation from -90 to 90, as the editor's view
/// clamps it: `30,100` is a usage error (exit 2, before any work, nothing
/// written) that says the range and the view meant; both ends draw.
#[test]
fn a_view_past_the_top_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("h.png");
    let input = manifest_path("examples/hilbert3d.lsys");
    let run = |view: &str| {
        let (input, png) = (input.display(), png.display());
        let line = format!("render {input} -o {png} --view {view}");
        outcome(&mut stlc_line(&line))
    };
    for view in ["30,100", "30,-90.5", "0,270"] {
        let (code, _, err) = run(view);
        assert_eq!(code, 2, "{view}: {err}");
        let range = err.contains("from -90") && err.contains("to 90");
        assert!(range, "{view}: {err}");
        assert!(!png.exists(), "{view} wrote a picture");
    }
    let (_, _, err) = run("30,100");
    assert!(err.contains("210,80"), "{err}");
    for view in ["30,90", "-45,-90", "400,0"] {
        let (code, _, err) = run(view);
        assert_eq!(code, 0, "{view}: {err}");
        assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
        std::fs::remove_file(&png).unwrap();
    }
}

/// A view whose drawing outgrows f64 (`F -> F[&F]F` at depth 1100: its
/// reach is 3^1100 steps) ends at once with the error that says so; the
/// walk measuring it used to run without end.
#[test]
fn a_view_past_f64_s_range_is_refused_at_once() {
    let mut req = lsys_request("dimensions 3\nangle 90\naxiom F\nrule F -> F[&F]F\n");
    req.depth = Some(1100);
    let err = req.render(&mut Vec::new(), &mut NoProgress).unwrap_err();
    assert!(err.to_string().contains("not finite numbers"), "{err}");
}
