//! 3D ODs and BEDs (section 11, docs/language.md *Three dimensions*): a
//! BED whose root has three coordinates drawn with the 3D turtle, in
//! `stats`, views and meshes. Expected values are worked by hand.

use stlc::pipeline::{ImageFormat, MeshFormat, RenderOptions, Request, View};

use crate::support::{manifest_path, numbers, outcome, stlc_line, stlc_piped};

fn bed_request(text: &str) -> Request {
    Request {
        name: Some("x.bed".into()),
        ..Request::new(text.as_bytes().to_vec())
    }
}

/// `stlc stats --json` of a BED given as text (through standard input).
fn stats_json(text: &str) -> serde_json::Value {
    serde_json::from_slice(&stlc_piped("stats --from bed --json -", text)).unwrap()
}

/// Section 11's worked ends with A=90 and unit steps, from a 3D BED's seed.
#[test]
fn stats_of_a_3d_bed_give_the_worked_ends_of_section_11() {
    for (word, end, bbox) in [
        ("F+F", [-1.0, -1.0, 0.0], [-1.0, -1.0, 0.0, 0.0, 0.0, 0.0]),
        ("F&F", [0.0, -1.0, 1.0], [0.0, -1.0, 0.0, 0.0, 0.0, 1.0]),
        ("F/+F", [0.0, -1.0, -1.0], [0.0, -1.0, -1.0, 0.0, 0.0, 0.0]),
    ] {
        let bed = format!("T\n(0, 0, 0)\nL=1(0) A=90\nRULE\nR1: [F]\nSEED\n{word}\nENDSEED\n");
        let j = stats_json(&bed);
        assert_eq!(j["dimensions"], 3, "{word}");
        assert_eq!(j["stems"], "2", "{word}");
        assert_eq!(numbers(&j["end"]), end, "{word}");
        assert_eq!(numbers(&j["bbox"]), bbox, "{word}");
    }
}

/// `D=90`, `A=90`, seed `R1{} +F` with `R1: [F]`, by hand: the
/// application of R1 first rolls L = (-1, 0, 0) to L cos 90 - U sin 90 =
/// -U = (0, 0, 1); its branch draws up, `]` returns to the root with the
/// rolled frame, which the application keeps, so `+` heads along (0, 0, 1)
/// and the last `F` ends at (0, 0, 1). Without `D=` the same seed turns
/// left: (-1, 0, 0). The root (5, 6, 7) shifts everything.
#[test]
fn divergence_rolls_each_rule_application_in_stats() {
    let bed = |d: &str| format!("T (5, 6, 7) L=1(0) A=90 {d} RULE R1: [F] SEED R1{{}} +F ENDSEED");
    let j = stats_json(&bed("D=90"));
    assert_eq!(numbers(&j["end"]), [5.0, 6.0, 8.0]);
    assert_eq!(numbers(&j["bbox"]), [5.0, 5.0, 7.0, 5.0, 6.0, 8.0]);
    // 1 R1 application (Enter, `[`, F, `]`, Leave), then `+F`.
    assert_eq!(j["symbols"], "7");
    let j = stats_json(&bed(""));
    assert_eq!(numbers(&j["end"]), [4.0, 6.0, 7.0]);
    // D=360 is no roll either.
    assert_eq!(numbers(&stats_json(&bed("D=360"))["end"]), [4.0, 6.0, 7.0]);
    // `[I 2 R1]`: the second level grows at the first's branch tip
    // (5, 5, 7), rolled once more, and draws up to (5, 4, 7); the first's
    // `]` then restores the frame rolled once, so `+F` ends as above.
    let j = stats_json("T (5, 6, 7) L=1(0) A=90 D=90 RULE R1: [F] SEED [I 2 R1] +F ENDSEED");
    assert_eq!(numbers(&j["end"]), [5.0, 6.0, 8.0]);
    assert_eq!(numbers(&j["bbox"]), [5.0, 4.0, 7.0, 5.0, 6.0, 8.0]);
}

/// A BED grown in 2D and the same BED with its root at z = 0 and `D=0`:
/// the 3D front view is the 2D picture byte for byte, PNG and SVG.
#[test]
fn the_front_view_of_a_planar_3d_bed_is_the_2d_picture() {
    let od = manifest_path("examples/successors.od");
    let out = stlc_piped(&format!("compile -o - {}", od.display()), "");
    let text = String::from_utf8(out).unwrap();
    // Without its LAYOUT (a 2D layout frames the 2D picture; a 3D BED's
    // volumes are not drawn yet).
    let flat = &text[..text.find("LAYOUT").unwrap()];
    let root = "(150, 296)";
    assert!(flat.contains(root), "{flat}");
    let deep = flat
        .replacen(root, "(150, 296, 0)", 1)
        .replacen("RULE", "D=0\nRULE", 1);
    for format in [ImageFormat::Png, ImageFormat::Svg] {
        let image = RenderOptions::new(format, Some((300, 240)));
        let draw = |text: &str, view: Option<View>| {
            let (mut req, mut out) = (bed_request(text), Vec::new());
            (req.image, req.view) = (image, view);
            let quiet = &mut stlc::pipeline::NoProgress;
            req.render(&mut out, quiet).unwrap();
            out
        };
        let a = draw(flat, None);
        let b = draw(&deep, Some(View::FRONT));
        assert!(a.len() > 1000);
        assert!(a == b, "{format:?} differs");
        // The default view (30, 20) is another picture.
        let c = draw(&deep, None);
        assert!(c != b, "{format:?}");
    }
}

/// OBJ vertices: `(x, y, z)` lines after `v`.
fn obj_vertices(obj: &str) -> Vec<[f64; 3]> {
    obj.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let mut v = l.split_whitespace().map(|x| x.parse().unwrap());
            [0; 3].map(|_| v.next().unwrap())
        })
        .collect()
}

fn obj(text: &str) -> String {
    let (mut out, mut progress) = (Vec::new(), stlc::pipeline::NoProgress);
    let req = bed_request(text);
    req.mesh(MeshFormat::Obj, &mut out, &mut progress).unwrap();
    String::from_utf8(out).unwrap()
}

/// A 3D BED's mesh has its stems in space, each as wide as `B` at its
/// order; a planar one at z = 0 is the 2D BED's mesh.
#[test]
fn a_3d_bed_meshes_in_space() {
    // D=90 as above: a stem up from (0, 0, 0) (order 1, width 0.5 with
    // B=1(0.5)) and one from (0, 0, 0) to (0, 0, 1) (order 0, width 1).
    // OBJ maps z to -z times 0.01: the second spans z in [-0.01, 0] plus
    // nothing across (its radius is across x and y); the first, vertical,
    // reaches 0.25 across z: [-0.0025, 0.0025].
    let m = obj("T (0, 0, 0) L=1(0) B=1(0.5) A=90 D=90 RULE R1: [F] SEED R1{} +F ENDSEED");
    let zs: Vec<f64> = obj_vertices(&m).iter().map(|v| v[2]).collect();
    let min = zs.iter().copied().fold(f64::INFINITY, f64::min);
    let max = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!((min + 0.01).abs() < 1e-6, "{min}");
    assert!((max - 0.0025).abs() < 1e-6, "{max}");
    let flat = "T (3, 4) L=2(0.5) B=1(0.25) A=30 RULE R1: [+F][-F] SEED F R1{R1{,},} ENDSEED";
    let deep = flat.replacen("(3, 4)", "(3, 4, 0)", 1);
    assert_eq!(obj(flat), obj(&deep));
}

/// `stlc expand` of a 3D BED writes its 3D turns.
#[test]
fn a_3d_bed_expands_with_its_turns() {
    let bed = "T (0, 0, 0) RULE R1: [&F][/F] SEED F R1{,} ENDSEED";
    let out = stlc_piped("expand --from bed -", bed);
    assert_eq!(String::from_utf8(out).unwrap(), "F[&F][/F]\n");
}

/// A 3D OD grows into a 3D BED: the trunk (L=10) and, at order 1 (L=5),
/// `&F` pitched down to +z and `/F` rolled (straight on); at order 2 the
/// length is 0, so the slots stay empty. Worked by hand: the box is
/// x 0..0, y -15..0, z 0..5 and the trunk ends at (0, -10, 0).
#[test]
fn a_3d_od_grows_into_a_3d_bed() {
    let dir = tempfile::tempdir().unwrap();
    let bed = dir.path().join("t.bed");
    let od = "T (0, 0, 0) L=10(5) B=1(0) A=90 RULE R1: [&F][/F] SEED F R1 ENDSEED";
    stlc_piped(&format!("compile --from od -o {} -", bed.display()), od);
    let text = std::fs::read_to_string(&bed).unwrap();
    assert!(text.starts_with("T\n(0, 0, 0)\n"), "{text}");
    let out = stlc_piped(&format!("stats --json {}", bed.display()), "");
    let out = String::from_utf8(out).unwrap();
    let json = "{\"dimensions\": 3, \"symbols\": \"11\", \"stems\": \"3\", \
         \"bbox\": [0.000000, -15.000000, 0.000000, 0.000000, 0.000000, 5.000000], \
         \"end\": [0.000000, -10.000000, 0.000000]}";
    assert_eq!(out.trim(), json);
}

/// Drawn flat (what 2D-only consumers of a scene get), a 3D tree is its
/// front view: a planar 3D BED gives the 2D BED's segments exactly; pitched
/// stems keep their x and y.
#[test]
fn a_3d_tree_drawn_flat_is_its_front_view() {
    use stlc::pipeline::{self, InputKind, Limits, NoProgress, SceneRequest};
    let flat_draw = |text: &str| {
        let limits = Limits::default();
        let loaded = pipeline::load(text.as_bytes(), InputKind::Bed, &limits).unwrap();
        let req = SceneRequest {
            grow: Default::default(),
            derivation: Default::default(),
            depth: None,
            limits,
        };
        let scene = pipeline::scene(loaded, &req, &mut NoProgress).unwrap();
        let mut rec = stlc::turtle::Recorder::default();
        scene.draw(&mut rec, &mut NoProgress).unwrap();
        rec.segments
    };
    let flat = "T (3, 4) L=2(0.5) B=1(0.25) A=30 RULE R1: [+F][-F] SEED F R1{R1{,},} ENDSEED";
    let a = flat_draw(flat);
    assert_eq!(a.len(), 5);
    assert_eq!(a, flat_draw(&flat.replacen("(3, 4)", "(3, 4, 9)", 1)));
    // `F&F` at A=90: the second stem goes away from the viewer, a point.
    let b = flat_draw("T (0, 0, 0) L=1(0) A=90 RULE R1: [F] SEED F&F ENDSEED");
    let ends: Vec<(f64, f64)> = b.iter().map(|s| (s.to.x, s.to.y)).collect();
    assert_eq!(ends, [(0.0, -1.0), (0.0, -1.0)]);
}

/// `--show-layout` paints a 3D tree's volumes faintly under it: a Box seen
/// from the front is its 40 x 40 face, painted clGreen a third of the way
/// from white (#aad5aa), at the scale of the 15-unit trunk drawn over it;
/// without the flag nothing is painted.
#[test]
fn show_layout_paints_the_volumes_of_a_3d_tree() {
    let od = "T (0, 0, 0) L=10(5) B=1(0) A=90 RULE R1: [&F][/F] SEED F R1 ENDSEED \
              LAYOUT (clGreen) Box (-20, -30, -20), 40, 40, 40 ENDLAYOUT";
    let svg = |flag: Option<&str>| {
        let flag = flag.unwrap_or("");
        let line = format!("render --from od --view 0,0 -f svg -o - - {flag}");
        String::from_utf8(stlc_piped(&line, od)).unwrap()
    };
    assert!(!svg(None).contains("#aad5aa"));
    let shown = svg(Some("--show-layout"));
    let line = shown.lines().find(|l| l.contains("fill=\"#aad5aa\""));
    let line = line.unwrap_or_else(|| panic!("{shown}"));
    // The points of a path's `d`, as (xs, ys).
    let points = |line: &str| -> (Vec<f64>, Vec<f64>) {
        let d = line.split("d=\"").nth(1).unwrap();
        let numbers = d.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'));
        let v: Vec<f64> = numbers
            .filter(|t| !t.is_empty())
            .map(|t| t.parse().unwrap())
            .collect();
        v.chunks(2).map(|p| (p[0], p[1])).unzip()
    };
    let (xs, ys) = points(line);
    let span = |v: &[f64]| {
        v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
    };
    // The trunk and the rolled branch: one vertical line 15 units long.
    let trunk = shown.lines().find(|l| l.contains("stroke=\"#4a2c12\""));
    let trunk = trunk.unwrap();
    let (_, ty) = points(trunk);
    let unit = span(&ty) / 15.0;
    assert!((span(&xs) / unit - 40.0).abs() < 0.01, "{line}");
    assert!((span(&ys) / unit - 40.0).abs() < 0.01, "{line}");
}

/// Growth, pictures and meshes of a 3D tree are the same bytes run after
/// run: the oak grown twice gives one BED, one PNG view, one `.glb`.
#[test]
fn the_3d_oak_grows_draws_and_meshes_the_same_bytes_twice() {
    let od = manifest_path("examples/oak3d.od");
    let run = |line: &str| stlc_piped(&format!("{line} {}", od.display()), "");
    let lines = ["compile -o -", "render --view 30,20 -f png -o -"];
    for line in lines.into_iter().chain(["render --mesh glb -o -"]) {
        let first = run(line);
        assert!(first.len() > 1000, "{line}");
        assert_eq!(first, run(line), "{line}");
    }
}

/// Growth and interpretation agree on `D=` and the 3D turtle: the stems a
/// 3D OD's growth placed (its trace) are the stems its BED draws, the same
/// set bit for bit (growth places them in another order), for the 3D
/// examples, both growth orders.
#[test]
fn growth_and_the_grown_bed_draw_the_same_3d_stems() {
    use stlc::grow::{GrowthOrder, PlacedStem, grow_traced};
    use stlc::interpret::{Derivation::Dfs, bed3::draw3};
    use stlc::progress::NoProgress;
    for name in ["examples/oak3d.od", "examples/forest3d.od"] {
        let od = crate::support::od(&std::fs::read_to_string(manifest_path(name)).unwrap());
        for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let opts = crate::support::opts(growth);
            let (grown, placed) = grow_traced(&od, &opts, &mut NoProgress).unwrap();
            let key = |a: [f64; 6]| a.map(f64::to_bits);
            let ends = |p: &PlacedStem| key([p.from.x, p.from.y, p.z[0], p.to.x, p.to.y, p.z[1]]);
            let mut grew: Vec<[u64; 6]> = placed.iter().map(ends).collect();
            let mut drawn = Vec::new();
            let mut push = |s: stlc::turtle::turtle3::Segment3| {
                let (a, b) = (s.from, s.to);
                drawn.push(key([a.x, a.y, a.z, b.x, b.y, b.z]));
            };
            let limits = &opts.limits;
            draw3(&grown.bed, Dfs, limits, &mut push, &mut NoProgress).unwrap();
            assert!(grew.len() > 100, "{name}");
            grew.sort_unstable();
            drawn.sort_unstable();
            let holds = grew == drawn;
            assert!(holds, "{name} {growth:?}: growth and the BED differ");
        }
    }
}

/// A 3D root outside its volumes is named with its three coordinates,
/// and the help speaks of volumes.
#[test]
fn a_3d_root_outside_its_volumes_is_named_in_full() {
    let od = "T (0, 0, 50) RULE R1: [+F][-F] LAYOUT (clGreen) Sphere (0, 0, 0), 10 ENDLAYOUT";
    let (code, _, err) = outcome(stlc_line("check --from od -").write_stdin(od));
    assert_eq!(code, 1);
    assert!(err.contains("the root (0, 0, 50) lies outside"), "{err}");
    assert!(err.contains("non-white) volume"), "{err}");
}

/// `stlc render FILE [--view 0,0] -o -` (default size) of an OD given as
/// text: the PNG's bytes.
fn render_od(od: &str, view: Option<&str>) -> Vec<u8> {
    let view = view.map(|v| format!("--view {v}")).unwrap_or_default();
    stlc_piped(&format!("render --from od -f png -o - - {view}"), od)
}

/// Width and height of a PNG, from its header.
fn png_size(png: &[u8]) -> (u32, u32) {
    let be = |i: usize| u32::from_be_bytes(png[i..i + 4].try_into().unwrap());
    (be(16), be(20))
}

/// Section 11: `--view 0,0` of a planar tree is its 2D picture. The
/// tutorial's successors.od made 3D (its root at z = 0, `D=0`, its
/// ellipse extruded through the tree's plane) grows the same tree, and its
/// front view at the default size is the 2D picture, size and bytes: both
/// are framed by the layout (the 2D one by the ellipse, the 3D one by the
/// volume's outline, the same ellipse seen from the front). It was fitted
/// to the stems instead: 800 x 549 against 800 x 653.
#[test]
fn the_front_view_of_a_planar_3d_od_is_fitted_as_its_2d_picture() {
    let flat = std::fs::read_to_string(manifest_path("examples/successors.od")).unwrap();
    let deep = flat
        .replacen("(150, 296)", "(150, 296, 0)", 1)
        .replacen("A=30 C=1", "A=30 C=1 D=0", 1)
        .replacen(
            "(clGreen) Ellipse (0, 60), 300, 240",
            "(clGreen) Extrude <Ellipse (0, 60), 300, 240>, -200, 200",
            1,
        );
    assert_ne!(flat, deep);
    assert!(deep.contains("Extrude") && deep.contains("D=0") && deep.contains("296, 0)"));
    let a = render_od(&flat, None);
    let b = render_od(&deep, Some("0,0"));
    // The 2D picture: the layout 300 x 240 (plus margins) fitted to 800 wide.
    assert_eq!(png_size(&a), (800, 653));
    assert_eq!(png_size(&b), png_size(&a));
    let same = a == b;
    assert!(same, "the front view's pixels differ from the 2D picture's");
    // Another view of the same OD is framed by the volume seen from there.
    assert_ne!(png_size(&render_od(&deep, Some("30,20"))), (800, 653));
}
