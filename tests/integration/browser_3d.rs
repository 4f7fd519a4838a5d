//! The editor's 3D view in a real Chromium (software WebGL 2 even with
//! `--disable-gpu`): a 3D `.lsys` opens in the WebGL canvas instead of
//! the SVG preview, with pixels read back from it; dragging orbits the
//! camera, the wheel zooms, Fit comes back to the first picture exactly;
//! an edit of the text regrows it; a save and a reload keep the text; and
//! the page's volumes and replay, shown from an answer made here.
//! Screenshots go to `tests/store/browser/3d-*.png`.

use std::time::Duration;

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser_steps::{reload, settled_ok, text_of};
use super::chromium::{
    cli_line, click, file_until, js, js_async, on_served_file, press_along, settled_until, shot,
    wheel,
};
use super::serve::{Server, example, post, render};
use crate::support::{manifest_path, numbers, stlc_stdout};

/// A compact body decoded as the page decodes it (engine/http.js): the
/// head's answer with `growth.stems` (and `space.stems`, if any) put back.
pub(super) fn unpack(body: &[u8]) -> Value {
    let n = u32::from_le_bytes(body[..4].try_into().unwrap()) as usize;
    assert_eq!((4 + n) % 4, 0, "the stems start on a 4-byte boundary");
    let head: Value = serde_json::from_slice(&body[4..4 + n]).unwrap();
    let mut answer = head["answer"].clone();
    let k = head["stems"].as_u64().unwrap() as usize;
    let m = head["space"].as_u64().unwrap_or(0) as usize;
    assert_eq!(answer["growth"]["stems"], json!([]));
    assert_eq!(body.len(), 4 + n + 4 * (k + m));
    let numbers = |from: usize, count: usize, per: usize| -> Vec<f64> {
        body[from..from + 4 * count]
            .chunks(4)
            .map(|c| f64::from(i32::from_le_bytes(c.try_into().unwrap())))
            .enumerate()
            .map(|(i, x)| if i % per == per - 1 { x } else { x / 1000.0 })
            .collect()
    };
    answer["growth"]["stems"] = json!(numbers(4 + n, k, 6));
    if head.get("space").is_some() {
        assert_eq!(answer["space"]["stems"], json!([]));
        answer["space"]["stems"] = json!(numbers(4 + n + 4 * k, m, 8));
    }
    answer
}

#[test]
fn a_3d_answer_carries_its_stems_json_or_compact_and_2d_answers_do_not() {
    let server = Server::start(&[]);
    let text = std::fs::read_to_string(manifest_path("examples/hilbert3d.lsys")).unwrap();
    let body = json!({"source": text, "kind": "lsys"});
    let a = render(&server.addr, &body);
    assert_eq!(a["ok"], true, "{a}");
    assert_eq!((&a["svg"], &a["tree_in_svg"]), (&json!(""), &json!(false)));
    assert_eq!(a["stems"], "63");
    assert_eq!(a["stroke"], "#1f4e79");
    let space = &a["space"];
    assert_eq!(space["stems"].as_array().unwrap().len(), 63 * 8);
    assert_eq!(space["view"], json!([30.0, 20.0]));
    assert_eq!(space["width_in_pixels"], true);
    assert_eq!(space["volumes"], json!([]));
    assert_eq!(space["axis"], Value::Null);
    // The turtle starts at the origin.
    assert_eq!(space["stems"].as_array().unwrap()[0..3], [0.0, 0.0, 0.0]);
    // The compact body: the same answer, number for number.
    let compact = post(
        &server.addr,
        "/api/render",
        &[super::bigtree::COMPACT],
        &body,
    );
    let head = &compact.head;
    let compact_type = "content-type: application/x-stlc-render";
    assert!(head.contains(compact_type), "{head}");
    assert_eq!(unpack(&compact.body), a);
    // The export draws the view asked for: the CLI's bytes.
    let view = json!({"source": text, "kind": "lsys", "view": [-60, 35]});
    let svg = post(&server.addr, "/api/export?format=svg", &[], &view);
    let want = cli_line("render examples/hilbert3d.lsys --view -60,35 -f svg");
    assert_eq!(svg.body, want);
    // A 3D BED: its stems worked by hand (`&` at 90 degrees turns the
    // heading (0, -1, 0) to +z, `^` to -z; B=2(0.5): 2 wide at order 0,
    // 1.5 in the rule), its volumes as written, the axis at its root.
    let bed = "T\n(10, 100, 5)\nL=10(0) B=2(0.5) A=90\nRULE\nR1: [&F][^F]\nSEED\nF\nR1{,}\nENDSEED\n\
               LAYOUT\n(clGreen) Sphere (10, 90, 5), 30\n(clWhite) Box (0, 0, 0), 5, 5, 5\nENDLAYOUT\n";
    let b = render(&server.addr, &json!({"source": bed, "kind": "bed"}));
    assert_eq!(b["ok"], true, "{b}");
    let space = &b["space"];
    assert_eq!(
        space["stems"],
        json!([
            10.0, 100.0, 5.0, 10.0, 90.0, 5.0, 2.0, 0.0, //
            10.0, 90.0, 5.0, 10.0, 90.0, 15.0, 1.5, 0.0, //
            10.0, 90.0, 5.0, 10.0, 90.0, -5.0, 1.5, 0.0
        ])
    );
    assert_eq!(space["width_in_pixels"], false);
    assert_eq!(
        space["volumes"],
        json!([
            {"type": "Sphere", "centre": [10.0, 90.0, 5.0], "r": 30.0, "color": "#008000"},
            {"type": "Box", "corner": [0.0, 0.0, 0.0], "size": [5.0, 5.0, 5.0], "color": "#ffffff"}
        ])
    );
    assert_eq!(space["axis"], json!([10.0, 5.0]));
    // A 2D answer has no `space`.
    let flat = json!({"source": "axiom F+F\nangle 90\ngenerations 0\n", "kind": "lsys"});
    let flat = render(&server.addr, &flat);
    assert_eq!(flat["ok"], true, "{flat}");
    assert!(flat.get("space").is_none(), "{flat}");
    assert_eq!(flat["tree_in_svg"], true);
}

#[test]
fn a_3d_file_orbits_regrows_and_reloads_in_chromium() {
    on_served_file(
        "hilbert.lsys",
        &example("hilbert3d.lsys"),
        async |c, served| {
            let first = opens_in_the_3d_view(c).await;
            orbit_zoom_and_fit(c, &first).await;
            an_edit_regrows(c, &first).await;
            a_reload_keeps_the_text(c, served.file).await;
            the_camera_is_the_clis(c).await;
            volumes_and_replay(c).await;
        },
    );
}

/// The 3D canvas's pixels: `{count, sum, width, height}` (count: pixels
/// not the background; sum: a checksum of the whole picture).
async fn pixels(c: &Client) -> Value {
    js(c, "return window.stlc.view3d.pixels()").await
}

async fn angles(c: &Client) -> Vec<f64> {
    numbers(&js(c, "return window.stlc.view3d.angles()").await)
}

/// The centre of the 3D canvas in viewport pixels.
async fn centre(c: &Client) -> (f64, f64) {
    let probe = "const r = document.getElementById('view3d').getBoundingClientRect();
         return [r.left + r.width / 2, r.top + r.height / 2];";
    let v = js(c, probe).await;
    (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}

async fn opens_in_the_3d_view(c: &Client) -> Value {
    let probe = "const v = document.getElementById('view3d');
         return {canvas: !v.hidden && v.getBoundingClientRect().width > 100,
                 svg: getComputedStyle(document.getElementById('preview')).display,
                 gl: window.stlc.view3d.available(),
                 stems: Array.from(window.stlc.state.answer.space.stems)};";
    let shown = js(c, probe).await;
    assert_eq!(shown["canvas"], true, "{shown}");
    assert_eq!(shown["svg"], "none", "the 2D preview is hidden");
    assert_eq!(shown["gl"], true, "headless Chromium has WebGL 2");
    // The 3D Hilbert curve at depth 2 visits 8^2 lattice points: 63 unit
    // steps, each one lattice unit (the file's `length`) long, and every
    // next stem starts where the last ended.
    let s = numbers(&shown["stems"]);
    assert_eq!(s.len(), 63 * 8);
    let len =
        |t: &[f64]| ((t[3] - t[0]).powi(2) + (t[4] - t[1]).powi(2) + (t[5] - t[2]).powi(2)).sqrt();
    let unit = len(&s[0..8]);
    assert!(unit > 0.0);
    let mut points = std::collections::BTreeSet::new();
    for (i, t) in s.chunks(8).enumerate() {
        assert!((len(t) - unit).abs() < 1e-3, "stem {i} is {} long", len(t));
        assert_eq!(t[6], 3.0, "the file's width, in pixels");
        assert_eq!(t[7], 0.0, "an .lsys has no decisions");
        if i > 0 {
            assert_eq!(&t[0..3], &s[(i - 1) * 8 + 3..(i - 1) * 8 + 6]);
        }
        let point = t[3..6].iter().map(|x| (x / unit).round() as i64);
        points.insert(point.collect::<Vec<_>>());
    }
    points.insert(s[0..3].iter().map(|x| (x / unit).round() as i64).collect());
    assert_eq!(points.len(), 64, "64 distinct lattice points");
    assert_eq!(angles(c).await, [30.0, 20.0], "the CLI's default view");
    let p = pixels(c).await;
    let all = p["width"].as_f64().unwrap() * p["height"].as_f64().unwrap();
    let n = p["count"].as_f64().unwrap();
    assert!(n > 3000.0 && n < all / 4.0, "{p}");
    shot(c, "3d-01-hilbert").await;
    p
}

async fn orbit_zoom_and_fit(c: &Client, first: &Value) {
    let (x, y) = centre(c).await;
    let path = [(x, y), (x + 60.0, y + 25.0), (x + 120.0, y + 50.0)];
    press_along(c, &path, 100).await;
    // 0.4 degrees a pixel: 120 px across turns AZ by -48, 50 px down
    // raises EL by 20.
    assert_eq!(angles(c).await, [-18.0, 40.0]);
    let turned = pixels(c).await;
    assert_ne!(turned["sum"], first["sum"], "the picture turned");
    assert!(turned["count"].as_f64().unwrap() > 3000.0, "{turned}");
    shot(c, "3d-02-orbited").await;
    wheel(c, (x, y), -240).await;
    tokio::time::sleep(Duration::from_millis(200)).await;
    let zoomed = pixels(c).await;
    assert_ne!(zoomed["sum"], turned["sum"], "the wheel zooms");
    // Fit: the first view again, pixel for pixel.
    click(c, "#fit").await;
    assert_eq!(angles(c).await, [30.0, 20.0]);
    assert_eq!(pixels(c).await, *first);
    // The keyboard, the view focused: right twice turns AZ by -5 each,
    // Shift+up raises EL by 15, + zooms in, 0 fits again.
    let view = c.find(fantoccini::Locator::Css("#view3d")).await.unwrap();
    view.send_keys("\u{E014}\u{E014}").await.unwrap();
    view.send_keys("\u{E008}\u{E013}\u{E008}").await.unwrap();
    assert_eq!(angles(c).await, [20.0, 35.0]);
    let keyed = pixels(c).await;
    assert_ne!(keyed["sum"], first["sum"], "the keys turned the picture");
    view.send_keys("+").await.unwrap();
    assert_ne!(pixels(c).await["sum"], keyed["sum"], "+ zooms");
    let label = text_of(c, "#view3d-label").await;
    assert!(label.contains("arrow keys"), "{label}");
    view.send_keys("0").await.unwrap();
    assert_eq!(angles(c).await, [30.0, 20.0]);
    assert_eq!(pixels(c).await, *first);
}

/// Puts the caret over `from` in the text and types `to` in its place.
async fn replace(c: &Client, from: &str, to: &str) {
    let src = c.find(fantoccini::Locator::Css("#source")).await.unwrap();
    src.click().await.unwrap();
    let script = format!(
        "const s = document.getElementById('source'); const i = s.value.indexOf({from:?});
             s.selectionStart = i; s.selectionEnd = i + {};",
        from.chars().count()
    );
    js(c, &script).await;
    src.send_keys(to).await.unwrap();
}

async fn an_edit_regrows(c: &Client, first: &Value) {
    replace(c, "generations 2", "generations 1").await;
    let now = settled_until(c, 50, 100, |v| v["stems"] == json!(7)).await;
    // Depth 1: 8 points, 7 steps.
    assert_eq!(now["stems"], 7, "{now}");
    let numbers = js(c, "return window.stlc.state.answer.space.stems.length").await;
    assert_eq!(numbers, 7 * 8);
    let p = pixels(c).await;
    assert_ne!(p["sum"], first["sum"]);
    assert!(p["count"].as_f64().unwrap() > 500.0, "{p}");
    shot(c, "3d-03-depth-1").await;
}

async fn a_reload_keeps_the_text(c: &Client, file: &std::path::Path) {
    click(c, "[data-testid=save]").await;
    let saved = file_until(file, 100, |t| t.contains("generations 1")).await;
    assert!(saved.contains("generations 1"));
    let after = reload(c).await;
    let text = after["text"].as_str().unwrap();
    assert!(text.contains("generations 1"), "{after}");
    assert_eq!(after["stems"], 7);
    assert!(pixels(c).await["count"].as_f64().unwrap() > 500.0);
}

/// The page's camera at 30,20 projects the bush's stems where `stlc render
/// --view 30,20` draws them, up to the picture's scale and offset: every
/// end the page projects is an end of a line in the CLI's SVG and back,
/// within 0.05 px: the answer's three decimals of a unit are up to 0.02
/// px at this picture's 29 px a unit, the SVG's two decimals 0.005 px (a
/// view a degree off moves the ends by pixels).
async fn the_camera_is_the_clis(c: &Client) {
    let opened = super::browser_web::open_example(c, "plant3d-bare.lsys").await;
    assert_eq!(opened["ok"], true);
    let script = "const done = arguments[arguments.length - 1];
             import('/view3d.js').then((m) => {
               const [r, d] = m.camera(30, 20);
               const s = window.stlc.state.answer.space.stems;
               const out = [];
               for (let i = 0; i < s.length; i += 8) {
                 for (const o of [i, i + 3]) {
                   out.push([r[0] * s[o] + r[1] * s[o + 1] + r[2] * s[o + 2], d[0] * s[o] + d[1] * s[o + 1] + d[2] * s[o + 2]]);
                 }
               }
               done(out);
             });";
    let page = js_async(c, script, vec![]).await;
    let page: Vec<(f64, f64)> = page
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    let svg = cli_line("render examples/plant3d-bare.lsys -f svg");
    let svg = String::from_utf8(svg).unwrap();
    let (_, path) = svg.split_once(" d=\"").unwrap();
    let d = path.split_once('"').unwrap().0;
    let numbers: Vec<f64> = d
        .split([' ', 'M', 'L'])
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect();
    let cli_points: Vec<(f64, f64)> = numbers.chunks(2).map(|p| (p[0], p[1])).collect();
    // (A line that goes on from the last end writes only its `L`: the
    // CLI's points are the ends without repeats.)
    assert!(cli_points.len() > 2000, "{}", cli_points.len());
    let bbox = |v: &[(f64, f64)]| {
        let far = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        v.iter().fold(far, |b, p| {
            (b.0.min(p.0), b.1.min(p.1), b.2.max(p.0), b.3.max(p.1))
        })
    };
    let (a, b) = (bbox(&page), bbox(&cli_points));
    let scale = (b.2 - b.0) / (a.2 - a.0);
    let height = (a.3 - a.1) * scale;
    assert!((height - (b.3 - b.1)).abs() < 0.02, "{height} {b:?}");
    let mapped: Vec<(f64, f64)> = page
        .iter()
        .map(|p| ((p.0 - a.0) * scale + b.0, (p.1 - a.1) * scale + b.1))
        .collect();
    let near =
        |p: &(f64, f64), q: &(f64, f64)| (p.0 - q.0).abs() < 0.05 && (p.1 - q.1).abs() < 0.05;
    for q in &mapped {
        let found = cli_points.iter().any(|c| near(c, q));
        assert!(found, "{q:?} is not an end in the CLI's picture");
    }
    for c in &cli_points {
        let found = mapped.iter().any(|q| near(c, q));
        assert!(found, "{c:?} is not an end the page draws");
    }
    shot(c, "3d-07-bush").await;
}

/// The volumes (one of each kind) and the replay, from an answer made
/// here: two stems, decisions 1 and 2, inside a translucent box.
async fn volumes_and_replay(c: &Client) {
    let probe = r##"const app = window.stlc;
        const ellipse = {type: 'Ellipse', x: -40, y: -160, w: 80, h: 100};
        const answer = Object.assign({}, app.state.answer, {
          stroke: '#5a3a1a',
          space: {
            stems: [0, 0, 0, 0, -60, 0, 2, 1, 0, -60, 0, 30, -110, 10, 2, 2],
            decisions: 2, width_in_pixels: false, background: '#ffffff', view: [30, 20], axis: [0, 0],
            volumes: [
              {type: 'Box', corner: [-100, -200, -50], size: [200, 200, 100], color: '#c0c0c0'},
              {type: 'Sphere', centre: [60, -150, 0], r: 25, color: '#0000ff'},
              {type: 'Ellipsoid', centre: [-60, -150, 0], radii: [20, 30, 15], color: '#ff0000'},
              {type: 'Cylinder', base: [0, 0, 0], r: 8, h: 60, color: '#808000'},
              {type: 'Extrude', shape: {type: 'Polygon', points: [[60, -20], [90, -20], [75, -60]]}, z1: -10, z2: 10, color: '#800080'},
              {type: 'Revolve', shape: ellipse, color: '#008000'},
              {type: 'Sphere', centre: [0, -110, 0], r: 15, color: '#ffffff'},
            ],
          },
        });
        app.state.answer = answer;
        app.state.answerText = app.editor.text();
        app.state.refit = true;
        // As session.js applies an answer: the slider at its end, then the view.
        app.replay.reset(2);
        app.view.draw();
        return app.view3d.pixels();"##;
    let shown = js(c, probe).await;
    assert!(shown["count"].as_f64().unwrap() > 20000.0, "{shown}");
    shot(c, "3d-04-volumes").await;
    let one = replay_to(c, 1).await;
    assert_eq!(one[0], "decision 1 of 2 · 1 stems");
    let none = replay_to(c, 0).await;
    assert_eq!(none[0], "decision 0 of 2 · 0 stems");
    let two = replay_to(c, 2).await;
    assert_eq!(two[0], "decision 2 of 2 · 2 stems");
    assert_eq!(two[1], shown, "the whole tree again");
    // Each decision adds its stem over the volumes: another picture.
    let sum = |v: &Value| v[1]["sum"].clone();
    assert_ne!(sum(&none), sum(&one));
    assert_ne!(sum(&one), sum(&two));
    replay_to(c, 1).await;
    shot(c, "3d-05-replay-1-of-2").await;
    // A Revolve of a shape off the axis is a torus (its hole shown): its
    // vertices lie between the shape's nearest and farthest x, 40 and 80;
    // one across the axis is its outer edge turned, from the axis (0) to
    // 40.
    let probe = r##"return import('/meshes.js').then(({ volumeMesh }) => {
          const r = (shape) => {
            const { pos } = volumeMesh({type: 'Revolve', shape, color: '#008000'}, [0, 0]);
            let lo = Infinity; let hi = 0;
            for (let i = 0; i < pos.length; i += 3) {
              const d = Math.hypot(pos[i], pos[i + 2]);
              lo = Math.min(lo, d); hi = Math.max(hi, d);
            }
            return [lo, hi];
          };
          return [r({type: 'Ellipse', x: 40, y: -100, w: 40, h: 60}),
                  r({type: 'Ellipse', x: -40, y: -100, w: 80, h: 60})];
        });"##;
    let radii = js(c, probe).await;
    let r = |i: usize, j: usize| radii[i][j].as_f64().unwrap();
    let torus = (r(0, 0) - 40.0).abs() < 1e-6 && (r(0, 1) - 80.0).abs() < 1e-6;
    assert!(torus, "{radii}");
    assert!(r(1, 0) < 1e-9 && (r(1, 1) - 40.0).abs() < 0.1, "{radii}");
}

/// The static site (web/, the WebAssembly engine) shows a 3D example in
/// the same 3D view: its stems as many as `stlc stats` counts.
#[test]
fn the_static_site_shows_a_3d_file_in_chromium() {
    super::browser_web::on_site(async |c, _, _| {
        let opened = super::browser_web::open_example(c, "plant3d-bare.lsys").await;
        assert_eq!(opened["ok"], true, "{opened}");
        let stats = stlc_stdout(&["stats", "--json", "examples/plant3d-bare.lsys"]);
        let stats: Value = serde_json::from_slice(&stats).unwrap();
        let segments: usize = stats["segments"].as_str().unwrap().parse().unwrap();
        let probe = "const v = document.getElementById('view3d');
             return {canvas: !v.hidden, stems: window.stlc.state.answer.space.stems.length};";
        let shown = js(c, probe).await;
        assert_eq!(shown["canvas"], true, "{shown}");
        assert_eq!(shown["stems"], json!(8 * segments));
        let p = pixels(c).await;
        assert!(p["count"].as_f64().unwrap() > 3000.0, "{p}");
        shot(c, "3d-06-static-site").await;
    });
}

/// The issue's oak (examples/oak3d.od) grows in its volumes in the editor
/// and replays: its stems as many as `stlc check` says it grows, each
/// decision adding one application of `R1: [+F][-F][&F]` (three stems)
/// to the seed's ten, the last decision the whole tree again.
#[test]
fn the_3d_oak_grows_and_replays_in_chromium() {
    let check = String::from_utf8(stlc_stdout(&["check", "examples/oak3d.od"])).unwrap();
    // "grows       5656 stems (bfs)" and "1882 fits".
    let words: Vec<&str> = check.split_whitespace().collect();
    let at = |word: &str| {
        words
            .iter()
            .position(|w| w.trim_end_matches([',', ';']) == word)
    };
    let (grows, fits) = (
        words[at("grows").unwrap() + 1],
        words[at("fits").unwrap() - 1],
    );
    let (grows, fits): (usize, usize) = (grows.parse().unwrap(), fits.parse().unwrap());
    assert_eq!(grows, 10 + 3 * fits, "{check}");
    on_served_file("oak3d.od", &example("oak3d.od"), async |c, _| {
        settled_ok(c).await;
        let probe = "const s = window.stlc.state.answer.space;
             return {stems: s.stems.length / 8, decisions: s.decisions, volumes: s.volumes.map((v) => v.type),
                     shown: !document.getElementById('view3d').hidden};";
        let space = js(c, probe).await;
        assert_eq!(space["stems"], json!(grows));
        assert_eq!(space["decisions"], json!(fits));
        assert_eq!(space["volumes"], json!(["Cylinder", "Revolve"]));
        assert_eq!(space["shown"], true);
        let whole = pixels(c).await;
        shot(c, "3d-08-oak").await;
        // Counts are shown with their digits grouped by threes.
        let grouped = |n: usize| crate::support::grouped(n as u64);
        let all_of = grouped(fits);
        let seed = replay_to(c, 0).await;
        assert_eq!(seed[0], format!("decision 0 of {all_of} · 10 stems"));
        let one = replay_to(c, 1).await;
        assert_eq!(one[0], format!("decision 1 of {all_of} · 13 stems"));
        assert_ne!(one[1]["sum"], seed[1]["sum"]);
        let half = replay_to(c, fits / 2).await;
        let (k, n) = (grouped(fits / 2), grouped(10 + 3 * (fits / 2)));
        assert_eq!(half[0], format!("decision {k} of {all_of} · {n} stems"));
        shot(c, "3d-09-oak-half-grown").await;
        // The last decision's stems without the leaves, then the whole tree
        // with them: the canvas's dark green (leaves in the ramp's end
        // colour, #3b5e2b, lit) and bark brown (the ramp's near end,
        // #5b3a1e) pixels counted.
        let census = "const v = document.getElementById('view3d');
             window.stlc.view3d.pixels();
             const t = document.createElement('canvas'); [t.width, t.height] = [v.width, v.height];
             const x = t.getContext('2d'); x.drawImage(v, 0, 0);
             const d = x.getImageData(0, 0, v.width, v.height).data;
             let [leaf, bark] = [0, 0];
             for (let i = 0; i < d.length; i += 4) {
               const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
               if (g > r + 15 && g > b + 15 && g < 140) leaf++;
               if (r > g + 12 && g > b + 8 && r < 160) bark++;
             }
             return [leaf, bark];";
        replay_to(c, fits - 1).await;
        let bare = js(c, census).await;
        let all = replay_to(c, fits).await;
        assert_eq!(all[1], whole, "the whole tree again");
        let leafy = js(c, census).await;
        // Measured 23,672 and 1,818 bare, 42,963 and 1,578 leafy at 1280 x
        // 720: with every stem in one colour (before the ramp) there was no
        // dark green at all, and without leaves no more than the stems'.
        let n = |v: &Value, i: usize| v[i].as_u64().unwrap();
        let (green, green_leafy) = (n(&bare, 0), n(&leafy, 0));
        let deep = "the ramp's deep orders are dark green";
        assert!(green > 5_000, "{deep}: {bare}");
        let more = green_leafy > green * 3 / 2;
        assert!(more, "the leaves add green: {bare} {leafy}");
        let brown = n(&bare, 1) > 500 && n(&leafy, 1) > 500;
        assert!(brown, "the trunk's bark is brown: {leafy}");
    });
}

/// The replay's slider moved to decision `k` as a user moves it: the
/// label then, and the 3D canvas's pixels.
async fn replay_to(c: &Client, k: usize) -> Value {
    let script = "const s = document.getElementById('step'); s.value = arguments[0];
                  s.dispatchEvent(new Event('input'));
                  return [document.getElementById('step-label').textContent, window.stlc.view3d.pixels()];";
    super::browser_steps::js_with(c, script, &[json!(k)]).await
}
