//! Colours, widths, polygons and surfaces in `.lsys` files (issue 33,
//! items 1 and 2; stl-language.md section 13): hand-worked paints,
//! widths and vertices, the pictures they give, and the hostile inputs
//! that end in an error with nothing written.

use stlc::color::Rgb;
use stlc::interpret::Derivation::Dfs;
use stlc::limits::Limits;
use stlc::syntax::lsys::parse;
use stlc::turtle::{Point, Recorder};

use crate::param::first_error;
use crate::render::rgba;

const RED: Rgb = Rgb::new(0xff, 0, 0);
const GREEN: Rgb = Rgb::new(0, 0xaa, 0);
const BLUE: Rgb = Rgb::new(0, 0, 0xff);

/// What the parametric turtle hands a backend for `src` at `depth`.
fn recorded(src: &str, depth: u32) -> Recorder {
    let sys = parse(src, &Limits::default()).unwrap_or_else(|e| panic!("{e:?}"));
    crate::lsys::recorded_of(&sys, depth, Dfs)
}

/// The picture `stlc render` writes for `src` as `name` (its extension
/// the format), at 100 x 100 pixels.
fn rendered(src: &str, name: &str) -> Vec<u8> {
    rendered_with(src, name, "")
}

/// [`rendered`] with more arguments.
fn rendered_with(src: &str, name: &str, more: &str) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in.lsys");
    std::fs::write(&input, src).unwrap();
    let out = dir.path().join(name);
    let (input, out_path) = (input.display(), out.display());
    let line = format!("render --size 100x100 {more} {input} -o {out_path}");
    crate::support::stlc_line(&line).assert().success();
    std::fs::read(&out).unwrap()
}

const STEPS: &str = "generations 0\nangle 90\npalette #ff0000 #00aa00 #0000ff\n";

#[test]
fn colour_steps_up_and_down_stop_at_the_ends_and_brackets_restore_them() {
    // F red, 'F green, 'F blue, ' stays blue (the palette's end), F F;
    // [,,F] steps back twice (green, red) and ] restores blue.
    let rec = recorded(&format!("{STEPS}axiom F'F'F'FF[,,F]F\n"), 0);
    assert_eq!(rec.segments.len(), 7);
    let (at, paint) = ([0, 1, 2, 5, 5, 6], [RED, GREEN, BLUE, GREEN, RED, BLUE]);
    assert_eq!(rec.paints, at.into_iter().zip(paint).collect::<Vec<_>>());
    // Below the first colour: stays red; `'(i)` and `;(i)` set, clamped.
    let rec = recorded(&format!("{STEPS}axiom ,F'(7)F;(1)F,(-3)F\n"), 0);
    assert_eq!(rec.paints, vec![(0, RED), (1, BLUE), (2, GREEN), (3, RED)]);
}

#[test]
fn without_a_palette_nothing_changes_the_paint() {
    let rec = recorded("generations 0\nangle 90\naxiom F'F;F,F\n", 0);
    assert_eq!(rec.segments.len(), 4);
    assert!(rec.paints.is_empty());
}

#[test]
fn a_bare_bang_multiplies_the_width_by_width_decay() {
    // Widths travel as orders of 1/1024 canvas unit: 2, 1, 0.5, [0.25], 0.5.
    let src = "generations 0\nangle 90\nwidth_decay 0.5\naxiom !(2)F!F!F[!F]F\n";
    let orders: Vec<u32> = recorded(src, 0).segments.iter().map(|s| s.order).collect();
    assert_eq!(orders, vec![2048, 1024, 512, 256, 512]);
    // The default decay is 0.7 (ABOP's `!` decrements the width):
    // 1024 x 0.7 = 716.8, carried as 717; the file's `width` is the first.
    let src = "generations 0\nangle 90\nwidth 1\naxiom F!F\n";
    let orders: Vec<u32> = recorded(src, 0).segments.iter().map(|s| s.order).collect();
    assert_eq!(orders, vec![1024, 717]);
}

#[test]
fn a_square_polygon_has_its_four_corners_in_the_svg() {
    // Vertices: `.` at (0,0), then each `f`: (0,-1), (-1,-1), (-1,0) and
    // (0,0) again, the first (kept once). Fitted into 100 px with a
    // margin of 4 px and half the 1 px stroke: -1..0 maps to 4.5..95.5.
    let src = "generations 0\nangle 90\naxiom {.f+f+f+f}\n";
    let rec = recorded(src, 0);
    assert!(rec.segments.is_empty());
    let corners = [(0.0, 0.0), (0.0, -1.0), (-1.0, -1.0), (-1.0, 0.0)];
    let expected: Vec<Point> = corners.iter().map(|&(x, y)| Point::new(x, y)).collect();
    assert_eq!(rec.polygons, vec![(0, expected)]);
    let svg = String::from_utf8(rendered(src, "out.svg")).unwrap();
    let square = "<path fill=\"#000000\" d=\"M95.50 95.50 L95.50 4.50 L4.50 4.50 L4.50 95.50 Z\"/>";
    assert!(svg.contains(square), "{svg}");
}

#[test]
fn a_polygon_is_filled_with_the_colour_in_force_in_the_png() {
    let src = "generations 0\nangle 90\npalette #ff0000 #0000ff\naxiom '{.f+f+f+f}\n";
    let svg = String::from_utf8(rendered(src, "out.svg")).unwrap();
    assert!(svg.contains("<path fill=\"#0000ff\" d=\"M95.50"), "{svg}");
    let png = tiny_skia::Pixmap::decode_png(&rendered(src, "out.png")).unwrap();
    assert_eq!(rgba(&png, 50, 50), [0, 0, 255, 255]);
    assert_eq!(rgba(&png, 1, 1), [255, 255, 255, 255]);
}

#[test]
fn g_draws_and_g_moves_without_recording_a_vertex() {
    // `.` (0,0), f (0,-1), f (-1,-1); G to (-1,0) and g back to (0,0)
    // record nothing; `.` there is the first vertex again (kept once).
    let rec = recorded("generations 0\nangle 90\naxiom {.f+f+G+g+.}\n", 0);
    assert_eq!(rec.segments.len(), 1);
    let pts = [(0.0, 0.0), (0.0, -1.0), (-1.0, -1.0)];
    let expected: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    assert_eq!(rec.polygons, vec![(1, expected)]);
}

#[test]
fn a_surface_is_drawn_in_the_turtles_frame_scaled_and_leaves_it_as_it_was() {
    let src = "generations 0\nangle 90\nsurface L { {.f+f+f+f} }\naxiom F~L(2)F\n";
    let rec = recorded(src, 0);
    let square = [(0.0, -1.0), (0.0, -3.0), (-2.0, -3.0), (-2.0, -1.0)];
    let expected: Vec<Point> = square.iter().map(|&(x, y)| Point::new(x, y)).collect();
    assert_eq!(rec.polygons, vec![(1, expected)]);
    let ends: Vec<(Point, Point)> = rec.segments.iter().map(|s| (s.from, s.to)).collect();
    let p = Point::new;
    let want = [(p(0.0, 0.0), p(0.0, -1.0)), (p(0.0, -1.0), p(0.0, -2.0))];
    assert_eq!(ends, want);
    // Unscaled, a surface turned by the turtle: after `+` the first side
    // goes left.
    let src = "generations 0\nangle 90\nsurface L { {.f+f+f+f} }\naxiom +~L\n";
    let first = recorded(src, 0).polygons[0].1[1];
    assert_eq!(first, Point::new(-1.0, 0.0));
}

#[test]
fn a_surfaces_colour_stays_inside_it() {
    let src =
        "generations 0\nangle 90\npalette #ff0000 #00aa00\nsurface L { '{.f+f+f+f} }\naxiom F~LF\n";
    let rec = recorded(src, 0);
    assert_eq!(rec.paints, vec![(0, RED), (1, GREEN), (1, RED)]);
}

#[test]
fn polygons_that_do_not_close_are_errors_at_the_brace() {
    let (msg, _, at) = first_error("generations 1\nangle 90\naxiom F{.f\n");
    assert_eq!((msg.as_str(), at.as_str()), ("this `{` is not closed", "{"));
    let (msg, _, at) = first_error("generations 1\nangle 90\naxiom F\nrule F -> F}f\n");
    assert_eq!((msg.as_str(), at.as_str()), ("`}` without its `{`", "}"));
}

#[test]
fn a_polygon_over_the_vertex_limit_is_an_error_as_written_and_as_derived() {
    let n = stlc::model::param::MAX_POLYGON_VERTICES;
    let src = format!("generations 1\nangle 90\naxiom {{{}}}\n", "f".repeat(n + 1));
    let (msg, _, at) = first_error(&src);
    assert_eq!(msg, format!("a polygon of more than {n} vertices"));
    assert_eq!(at, "{");
    // Exactly the limit is fine.
    let src = format!("generations 1\nangle 90\naxiom {{{}}}\n", "f".repeat(n));
    assert_eq!(recorded(&src, 0).polygons[0].1.len(), n);
    // Grown past it by a rule: the render fails and writes nothing.
    let src = "generations 4100\nangle 1\naxiom {.A}\nrule A -> +fA\n";
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("grow.lsys");
    std::fs::write(&input, src).unwrap();
    let out = dir.path().join("grow.png");
    let line = format!("render {} -o {}", input.display(), out.display());
    let (code, _, err) = crate::support::outcome(&mut crate::support::stlc_line(&line));
    assert_ne!(code, 0, "{err}");
    assert!(err.contains(&format!("more than {n} vertices")), "{err}");
    assert!(!out.exists());
}

#[test]
fn a_surface_that_places_itself_is_an_error_at_its_line() {
    let (msg, _, at) = first_error("generations 1\nangle 90\nsurface A { F~A }\naxiom ~A\n");
    assert_eq!(msg, "surface `A` places itself (~A -> ~A)");
    assert_eq!(at, "surface A { F~A }");
    let src = "generations 1\nangle 90\nsurface A { ~B }\nsurface B { [F~A] }\naxiom ~A\n";
    let (msg, _, _) = first_error(src);
    assert_eq!(msg, "surface `A` places itself (~A -> ~B -> ~A)");
    // A surface placing another, without a way back, is fine.
    let src = "generations 0\nangle 90\nsurface A { F~B }\nsurface B { {.f+f+f} }\naxiom ~A\n";
    assert_eq!(recorded(src, 0).polygons.len(), 1);
}

#[test]
fn a_palette_of_unknown_colours_is_an_error_at_the_colour() {
    let (msg, _, at) = first_error("generations 1\nangle 90\npalette #00ff00 clGrean\naxiom F\n");
    assert!(msg.contains("clGrean"), "{msg}");
    assert_eq!(at, "clGrean");
    // A `#` that starts no colour starts a comment.
    let src = "generations 0\nangle 90\npalette #ff0000 clBlue # leaves\naxiom F'F\n";
    let rec = recorded(src, 0);
    assert_eq!(rec.paints, vec![(0, RED), (1, BLUE)]);
}

#[test]
fn a_3d_view_from_the_front_draws_colours_and_polygons_as_the_2d_picture() {
    let word = "angle 90\npalette #ff0000 #0000ff\naxiom F[-F]'{.f+f+f+f}F\n";
    let flat = rendered(&format!("generations 0\n{word}"), "out.svg");
    let front = format!("generations 0\ndimensions 3\n{word}");
    let front = rendered_with(&front, "out.svg", "--view 0,0");
    let flat = String::from_utf8(flat).unwrap();
    assert!(flat.contains("fill=\"#0000ff\""), "{flat}");
    assert_eq!(flat, String::from_utf8(front).unwrap());
}

#[test]
fn abop_1_26_has_leaves_petals_and_stamens_in_their_colours() {
    let src = crate::support::example_text("abop-1.26.lsys");
    let sys = parse(&src, &Limits::default()).unwrap();
    let p = sys.parametric.as_deref().unwrap();
    use stlc::interpret::lsys::param::{Mark, draw3_marks};
    let (mut polygons, mut colours) = (0, std::collections::BTreeSet::new());
    let mut mark = |m: Mark<'_>| match m {
        Mark::Polygon(v) => {
            // A leaf records its 8 `f`s (the last comes back to where
            // it started, not recorded), a petal its 4.
            assert!(v.len() == 8 || v.len() == 4, "{}", v.len());
            polygons += 1;
        }
        Mark::Paint(i) => {
            colours.insert(i);
        }
        _ => {}
    };
    let limits = Limits::default();
    draw3_marks(&sys, p, 3, Dfs, &limits, &mut mark).unwrap();
    let word = crate::lsys::expanded_of(&sys, 2, Dfs);
    // Only L (p4) and W (p7) rewrite to polygons, one each, their
    // successors hold no L or W, and a polygon written stays: the
    // polygons at depth 3 are the `{`, L and W of the word at depth 2
    // (2, 10 and 15).
    let count = |c: char| word.chars().filter(|&x| x == c).count();
    assert_eq!((count('{'), count('L'), count('W')), (2, 10, 15));
    assert_eq!(polygons, count('{') + count('L') + count('W'));
    assert_eq!(colours, [1, 2, 3, 0].into_iter().collect());
}

/// The normal of the triangle `a b c` by the right hand: (b - a) x (c - a).
pub fn winding_normal(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ]
}

#[test]
fn a_leaf_in_a_mesh_is_two_faces_each_wound_to_its_own_normal() {
    use stlc::render::mesh::{Leaf, MeshOptions, build_with_leaves};
    use stlc::turtle::turtle3::Point3;
    // A unit square in the canvas plane; the files' axes are (x, -y, -z),
    // so it is counter-clockwise seen from +z: its normal is (0, 0, 1).
    let square = [(0.0, 0.0), (1.0, 0.0), (1.0, -1.0), (0.0, -1.0)];
    let points = square.map(|(x, y)| Point3::new(x, y, 0.0)).to_vec();
    let leaf = Leaf {
        points,
        color: GREEN,
    };
    let opts = MeshOptions {
        unit: 1.0,
        ..MeshOptions::default()
    };
    let mesh = build_with_leaves(&[], &[leaf], Point3::new(0.0, 0.0, 0.0), &opts);
    assert_eq!(mesh.primitives.len(), 1);
    let p = &mesh.primitives[0];
    assert!(p.leaf);
    assert_eq!(p.color, Some(GREEN));
    assert_eq!(p.positions.len(), 8);
    assert_eq!(&p.normals[..4], &[[0.0, 0.0, 1.0]; 4]);
    assert_eq!(&p.normals[4..], &[[0.0, 0.0, -1.0]; 4]);
    assert_eq!(p.indices, vec![0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6]);
    // Every triangle's winding (right hand) points along its vertices'
    // normal: each side is seen counter-clockwise from its own side.
    for t in p.indices.chunks(3) {
        let [a, b, c] = [0, 1, 2].map(|k| p.positions[t[k] as usize].map(f64::from));
        let w = winding_normal(a, b, c);
        let n = p.normals[t[0] as usize].map(f64::from);
        assert!(w[0] * n[0] + w[1] * n[1] + w[2] * n[2] > 0.0, "{t:?}");
    }
    // Texture coordinates: the square itself.
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    assert_eq!(&p.texcoords[..4], &square);
}

#[test]
fn abop_1_26_as_a_mesh_has_one_material_per_colour_and_leaf_materials() {
    let path = crate::support::manifest_path("examples/abop-1.26.lsys");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plant.gltf");
    let line = format!("render --depth 3 {} -o {}", path.display(), out.display());
    crate::support::stlc_line(&line).assert().success();
    let text = std::fs::read_to_string(&out).unwrap();
    // Stems in the stem and stamen colours; leaves and petals as leaves.
    for name in [
        "\"name\": \"#2f5d1e\"",
        "\"name\": \"#f2c230\"",
        "\"name\": \"leaf #4f9a34\"",
        "\"name\": \"leaf #e9679b\"",
    ] {
        let head = &text[..text.len().min(3000)];
        assert!(text.contains(name), "{name} in {head}");
    }
}

#[test]
fn abop_3_2_leaves_and_flower_grow_with_their_age_worked_by_hand() {
    // a(t) lays down F(1) and a leaf ~L(0) for t = 1..6, then F(20) and
    // the flower ~K(0) at step 7. A leaf made at step k is L(16 - k) at
    // depth 16, capped at 9; K(0) made at step 8 ages to K(5). The kite
    // leaf reaches 0.2 cos 25 + 0.13 + 0.2 cos 25 from its base times its
    // scale; a petal 2 x 0.4 cos 20 times the flower's. An internode
    // steps 1, 1.2, ... by 0.2 while under 2: 1 + 5 x 0.2 is
    // 1.9999999999999998 in doubles, so it takes a sixth step, to 2.2.
    let src = crate::support::example_text("abop-3.2.lsys");
    let sys = parse(&src, &Limits::default()).unwrap();
    let p = sys.parametric.as_deref().unwrap();
    use stlc::interpret::lsys::param::{Mark, draw3_marks};
    use stlc::turtle::turtle3::Point3;
    let (mut steps, mut reaches, mut paints) = (Vec::new(), Vec::new(), Vec::new());
    let dist = |a: Point3, b: Point3| {
        libm::sqrt((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.z - b.z).powi(2))
    };
    let mut mark = |m: Mark<'_>| match m {
        Mark::Step(s, _) => steps.push(dist(s.from, s.to)),
        Mark::Polygon(v) => {
            let far = v.iter().map(|q| dist(v[0], *q)).fold(0.0, f64::max);
            reaches.push((v.len(), far));
        }
        Mark::Paint(i) => paints.push(i),
    };
    draw3_marks(&sys, p, 16, Dfs, &Limits::default(), &mut mark).unwrap();
    let near = |a: f64, b: f64| (a - b).abs() < 1e-9;
    let (mut internode, mut grown) = (1.0f64, 0);
    while internode < 2.0 {
        (internode, grown) = (internode + 0.2, grown + 1);
    }
    let sixth = grown == 6 && near(internode, 2.2);
    assert!(sixth, "{grown} steps to {internode}");
    assert_eq!(steps.len(), 7);
    let internodes = steps[..6].iter().all(|&l| near(l, 2.2)) && near(steps[6], 20.0);
    assert!(internodes, "{steps:?}");
    let kite = 0.4 * libm::cos(25f64.to_radians()) + 0.13;
    let petal = 0.8 * libm::cos(20f64.to_radians());
    // Six leaves of 7 recorded vertices (the base `.` and 6 `f`s: the
    // last lands on the base only to within rounding, so it is kept),
    // then five petals of 5 (`.` and 4 `f`s); stems in colour 0, leaves
    // 1, petals 2.
    assert_eq!(reaches.len(), 11);
    for (i, &(n, far)) in reaches.iter().enumerate() {
        let (want_n, want) = [(7, 9.0 * kite), (5, 5.0 * petal)][usize::from(i >= 6)];
        assert_eq!(n, want_n, "polygon {i}");
        assert!(near(far, want), "polygon {i}: {far} against {want}");
    }
    assert!(paints.contains(&1) && paints.contains(&2), "{paints:?}");
}

#[test]
fn abop_5_5a_leaf_is_one_polygon_of_2n_vertices_worked_by_hand() {
    // n = 20: the base `.`, then on the way up the midrib the ends of the
    // veins turned `-` (right) R0..R19, on the way down those turned `+`
    // (left) L19..L0. B(t) grows min(t, 19 - t)
    // segments (it is made at step t + 1 and loses PD = 1 a step), so R0,
    // L0, R19 and L19 lie on the midrib; L19 equals R19 just before it and
    // is kept once: 1 + 20 + 19 = 40 vertices.
    let src = crate::support::example_text("abop-5.5a.lsys");
    let rec = recorded(&src, 20);
    assert_eq!(rec.polygons.len(), 1);
    let v = &rec.polygons[0].1;
    assert_eq!(v.len(), 40);
    // The midrib's k-th G is made at step k + 1 as G(5, 1.1) and grows by
    // 1.1 for the 19 - k steps left: R0 is 5 * 1.1^19 up, the tip the sum.
    let close = |p: Point, x: f64, y: f64| (p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9;
    let first = 5.0 * 1.1f64.powi(19);
    let tip = 50.0 * (1.1f64.powi(20) - 1.0);
    assert!(close(v[0], 0.0, 0.0), "{:?}", v[0]);
    assert!(close(v[1], 0.0, -first), "{:?}", v[1]);
    assert!(close(v[39], 0.0, -first), "{:?}", v[39]);
    assert!(close(v[20], 0.0, -tip), "{:?}", v[20]);
    // Right ends right of the midrib, left ends mirrored across it.
    for i in 2..20 {
        assert!(v[i].x > 0.0, "{i}: {:?}", v[i]);
        let r = v[40 - i];
        assert!((r.x + v[i].x).abs() < 1e-9 && (r.y - v[i].y).abs() < 1e-9);
    }
    // Every G draws a stem: 20 on the midrib, 2 * (1 + ... + 9) = 90 on
    // each side.
    assert_eq!(rec.segments.len(), 20 + 2 * 90);
}
