//! Trees grown from an OD dressed (issue 33; stl-language.md section 13):
//! an `S=` ramp by order, `P=` leaves at the tips that grew no further
//! from a `SURFACES` block, kept by the BED; hand-worked paints and
//! leaves, the BED round trip and the mesh's leaf material. The hostile
//! inputs (an undefined surface, no `ENDSURFACES`, an unclosed `{`, a
//! surface that places itself, a polygon over 4,096 vertices, a ramp on
//! `G=`, a long `P=` name) are the command line's page
//! `tests/cmd/leaves.md`: each error as shown, its exit status, and that
//! nothing is written.

use stlc::bed::Bed;
use stlc::color::Rgb;
use stlc::interpret::Derivation::Dfs;
use stlc::limits::Limits;
use stlc::model::Format;
use stlc::progress::NoProgress;
use stlc::turtle::{Point, Recorder};

/// A BED by hand: a trunk F (order 0) and R1 applied once (two stems of
/// order 1, left and right, at a right angle), a ramp from black to blue,
/// and a square leaf of side L at each tip.
const BED: &str = "T\n(0, 0)\nL=10(0) B=1(0) A=90 S=#000000..#0000ff P=L\nRULE\nR1: [+F][-F]\n\
SEED\nF R1{,}\nENDSEED\nSURFACES\nsurface L { {.f.+f.+f.} }\nENDSURFACES\n";

fn parse(src: &str, format: Format) -> Result<stlc::model::Description, String> {
    stlc::syntax::stl::parse(src, format, &Limits::default()).map_err(|e| {
        let d = e.iter().next().unwrap();
        let span = d.span.clone().unwrap_or(0..0);
        format!("{} @ {}", d.kind, &src[span])
    })
}

fn recorded(src: &str) -> Recorder {
    let desc = parse(src, Format::Bed).unwrap();
    let bed = Bed::new(desc, &Limits::default()).unwrap();
    let (mut rec, limits) = (Recorder::default(), Limits::default());
    stlc::interpret::dress::draw2(&bed, Dfs, &limits, &mut rec, &mut NoProgress).unwrap();
    rec
}

/// Twice the signed area of a polygon (shoelace).
fn area2(p: &[Point]) -> f64 {
    (0..p.len())
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            a.x * b.y - b.x * a.y
        })
        .sum()
}

#[test]
fn a_ramp_paints_by_order_and_a_leaf_grows_at_each_tip() {
    let rec = recorded(BED);
    // The trunk, then the two branches.
    assert_eq!(rec.segments.len(), 3);
    assert_eq!(rec.segments[0].to, Point::new(0.0, -10.0));
    // Order 0 is the ramp's start, order 1 (the deepest) its end; the
    // leaves take the end colour too.
    let blue = Rgb::new(0, 0, 0xff);
    assert_eq!(rec.paints, [(0, Rgb::new(0, 0, 0)), (1, blue), (3, blue)]);
    // Two tips (the trunk's end is where the branches start): a 10 x 10
    // square at each, its first vertex the tip.
    assert_eq!(rec.polygons.len(), 2);
    for ((at, poly), tip) in rec.polygons.iter().zip(&rec.segments[1..]) {
        assert_eq!(*at, 3);
        assert_eq!(poly.len(), 4, "{poly:?}");
        assert_eq!(poly[0], tip.to);
        assert!((area2(poly).abs() - 200.0).abs() < 1e-9, "{poly:?}");
        // The square starts along the tip's stem: its second vertex is
        // one L further on.
        let d = (poly[1].x - 2.0 * tip.to.x + tip.from.x).abs()
            + (poly[1].y - 2.0 * tip.to.y + tip.from.y).abs();
        assert!(d < 1e-9, "{poly:?} {tip:?}");
    }
}

#[test]
fn a_ramp_over_three_orders_mixes_the_middle_colour() {
    // Orders 0, 1, 2: the middle is half way, rounded per channel.
    let src = BED
        .replace("S=#000000..#0000ff P=L", "S=#000000..#0000ff")
        .replace("F R1{,}", "F R1{R1{,},}");
    let rec = recorded(&src);
    let colours: Vec<Rgb> = rec.paints.iter().map(|p| p.1).collect();
    let blue = |b| Rgb::new(0, 0, b);
    assert_eq!(colours, [blue(0), blue(0x80), blue(0xff), blue(0x80)]);
    assert!(rec.polygons.is_empty());
}

#[test]
fn without_a_ramp_the_stems_keep_the_stroke_and_leaves_are_green() {
    let rec = recorded(&BED.replace("S=#000000..#0000ff ", ""));
    assert_eq!(rec.paints, vec![(3, stlc::interpret::dress::LEAF_GREEN)]);
    assert_eq!(rec.polygons.len(), 2);
}

#[test]
fn the_bed_writer_keeps_the_ramp_the_leaf_and_the_surfaces() {
    let desc = parse(BED, Format::Bed).unwrap();
    let text = stlc::bed::write::write(&desc);
    assert!(text.contains(" S=#000000..#0000ff P=L\n"), "{text}");
    let surfaces = "SURFACES\nsurface L { {.f.+f.+f.} }\nENDSURFACES\n";
    assert!(text.ends_with(surfaces), "{text}");
    // Read again, it writes the same.
    let again = stlc::bed::write::write(&parse(&text, Format::Bed).unwrap());
    assert_eq!(again, text);
}

/// A small 2D OD with a ramp and leaves, and its layout.
const OD: &str = "Leafy\n(100, 190)\nL=12(1) B=3(0.3) A=30 C=1 S=#5b3a1e..#3b5e2b P=L\n\
RULE\nR1: [+F R1][-F R1]\nSEED\nFF R1\nENDSEED\nSURFACES\n\
surface L { [{.-(30)f(0.5).+(60)f(0.5).+(120)f(0.5).+(60)f(0.5)}] }\nENDSURFACES\n\
LAYOUT\n(clGreen) Rectangle (0, 0), 200, 200\nENDLAYOUT\n";

fn run_ok(args: &[&str], dir: &std::path::Path) {
    crate::support::stlc()
        .current_dir(dir)
        .args(args)
        .assert()
        .success();
}

#[test]
fn an_od_and_its_bed_draw_the_same_leafy_picture() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    std::fs::write(p.join("t.od"), OD).unwrap();
    run_ok(&["compile", "t.od", "-o", "t.bed"], p);
    let bed = std::fs::read_to_string(p.join("t.bed")).unwrap();
    assert!(bed.contains("P=L") && bed.contains("SURFACES\n"), "{bed}");
    for ext in ["png", "svg"] {
        let (a, b) = (format!("od.{ext}"), format!("bed.{ext}"));
        run_ok(&["render", "t.od", "--size", "200x200", "-o", &a], p);
        run_ok(&["render", "t.bed", "--size", "200x200", "-o", &b], p);
        let read = |name| std::fs::read(p.join(name)).unwrap();
        assert_eq!(read(a), read(b), "{ext}");
    }
    // The SVG fills the leaves in the ramp's end colour and strokes the
    // seed's stems in its start.
    let svg = std::fs::read_to_string(p.join("od.svg")).unwrap();
    assert!(svg.contains("#3b5e2b"), "no leaf colour");
    assert!(svg.contains("#5b3a1e"), "no trunk colour");
    assert!(svg.contains("<polygon") || svg.contains("<path"), "no leaf");
}

#[test]
fn a_leafy_mesh_has_bark_materials_by_order_and_a_leaf_material() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path();
    std::fs::write(p.join("t.od"), OD).unwrap();
    run_ok(&["render", "t.od", "-o", "t.gltf"], p);
    let gltf: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("t.gltf")).unwrap()).unwrap();
    let materials = gltf["materials"].as_array().unwrap();
    let names: Vec<&str> = materials
        .iter()
        .map(|m| m["name"].as_str().unwrap())
        .collect();
    // The ramp's ends among the bark's, and one leaf material (its faces
    // written on both sides, as an .lsys's polygons are).
    assert_eq!(names.first(), Some(&"#5b3a1e"), "{names:?}");
    assert!(names.contains(&"#3b5e2b"), "{names:?}");
    let leaves: Vec<_> = names.iter().filter(|n| n.starts_with("leaf ")).collect();
    assert_eq!(leaves, [&"leaf #3b5e2b"]);
}
