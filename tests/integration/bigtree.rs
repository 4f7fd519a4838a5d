//! Big grown trees in the editor (docs/serve.md, "Big trees"): past
//! 10,000 stems the render answer's SVG leaves the tree out, a client that
//! asks gets the stems as a compact binary body (the same answer, number
//! for number), and the page draws the tree on a canvas from them, replay
//! included; small trees keep their SVG `<path>`s.

use std::time::Duration;

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser_3d::unpack;
use super::browser_steps::set_value;
use super::chromium::{Browser, click, js, js_async, js_until, shot};
use super::serve::{Server, post, render};
use crate::support::{numbers, segment_distance};

/// An .od that grows `1 + 3k` stems for `M=1+3k` in a 1200 x 1200 square:
/// one stem from the root, then `[-F][F][+F]` at every tip, bfs, until the
/// next application would pass `M`. Its stems shorten from 2.5 units by
/// 0.01 an order: in the page's view of about 0.45 pixels a unit, the
/// first orders are strokes over a pixel long, the rest dots.
fn big(m: u64) -> String {
    format!(
        "Big\n(600, 1199)\nL=2.5(0.01) B=0.1(0) M={m}\nRULE\nR1: [-F][F][+F]\nLAYOUT\n(clGreen) Rectangle (0,0), 1200, 1200\nENDLAYOUT\n"
    )
}

fn stems(a: &Value) -> u64 {
    a["stems"].as_str().unwrap().parse().unwrap()
}

pub(super) const COMPACT: (&str, &str) = ("Accept", "application/x-stlc-render, application/json");

#[test]
fn past_10000_stems_the_svg_leaves_the_tree_out_and_the_stems_come_compact() {
    let server = Server::start(&[]);
    // 10,000 stems: today's answer, the tree in its SVG, JSON even to a
    // client that takes the compact body.
    let small = json!({"source": big(10_000), "kind": "od"});
    let a = render(&server.addr, &small);
    assert_eq!(stems(&a), 10_000);
    assert_eq!(a["tree_in_svg"], true);
    assert_eq!(a["stroke"], "#4a2c12");
    let svg = a["svg"].as_str().unwrap();
    assert!(svg.contains(r##"fill="none" stroke="#4a2c12""##));
    let asked = post(&server.addr, "/api/render", &[COMPACT], &small);
    let head = &asked.head;
    assert!(head.contains("content-type: application/json"), "{head}");
    assert_eq!(asked.json(), a);

    // 10,003 stems: the SVG has the layout, not the tree.
    let body = json!({"source": big(10_003), "kind": "od"});
    let a = render(&server.addr, &body);
    assert_eq!(stems(&a), 10_003);
    assert_eq!(a["tree_in_svg"], false);
    assert_eq!(a["stroke"], "#4a2c12");
    let svg = a["svg"].as_str().unwrap();
    assert!(!svg.contains("stroke="), "no stem in the SVG");
    assert!(svg.contains(r##"fill="#008000""##), "the layout is there");
    assert_eq!(a["growth"]["stems"].as_array().unwrap().len(), 6 * 10_003);
    // Its BED is left out too (megabytes); the export writes it.
    assert_eq!(a["bed"], Value::Null);
    let bed = post(&server.addr, "/api/export?format=bed", &[], &body);
    let bed = String::from_utf8(bed.body).unwrap();
    assert!(bed.starts_with("Big"), "{}", &bed[..bed.len().min(200)]);
    // The seed's F, then three stems an application of R1.
    assert_eq!(bed.matches("R1{").count(), 3_334);
    // The export is the CLI's picture: every stem in it.
    let export = post(&server.addr, "/api/export?format=svg", &[], &body);
    let exported = String::from_utf8(export.body).unwrap();
    assert!(exported.contains(r##"fill="none" stroke="#4a2c12""##));
    let (whole, shown) = (exported.len(), svg.len());
    assert!(whole > 10 * shown, "{whole} {shown}");

    // The compact body is the JSON answer, number for number.
    let compact = post(&server.addr, "/api/render", &[COMPACT], &body);
    assert_eq!(compact.status, 200);
    let head = &compact.head;
    let ok = head.contains("content-type: application/x-stlc-render");
    assert!(ok, "{head}");
    assert_eq!(unpack(&compact.body), a);
    assert!(compact.body.len() < a.to_string().len() * 2 / 3);
}

/// Waits until the page shows the answer to its text and its tree canvas
/// (if any) is drawn: the stems on it.
async fn drawn(c: &Client) -> u64 {
    for _ in 0..1200 {
        let script = "const s = window.stlc && window.stlc.state;
             return !!s && !s.inFlight && s.answerText === document.getElementById('source').value;";
        let ready = js(c, script).await;
        if ready == json!(true) {
            tokio::time::sleep(Duration::from_millis(300)).await;
            let probe = "const done = arguments[arguments.length - 1];
                 const t = window.stlc.view.tree;
                 t.settled().then(() => requestAnimationFrame(() => done(t.drawn())));";
            let n = js_async(c, probe, vec![]).await;
            let script = "return !window.stlc.state.inFlight && window.stlc.state.answerText === document.getElementById('source').value";
            let again = js(c, script).await;
            if again == json!(true) {
                return n.as_u64().unwrap();
            }
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    panic!("the page never drew the answer to its text");
}

/// The tree's alpha (its strokes' canvas and its dots' canvas over it) at
/// each canvas point (canvas units) in `points`, the number of inked
/// pixels, and the mean colour of the pixels inked at least half.
async fn ink(c: &Client, points: &[(f64, f64)]) -> (Vec<u8>, u64, [f64; 3]) {
    let script = format!(
            "const strokes = document.querySelector('#preview [data-testid=tree-canvas]');
             const dots = document.querySelector('#preview [data-testid=tree-dots]');
             const cv = document.createElement('canvas');
             [cv.width, cv.height] = [strokes.width, strokes.height];
             const cx = cv.getContext('2d');
             cx.drawImage(strokes, 0, 0);
             cx.drawImage(dots, 0, 0);
             const fo = strokes.closest('foreignObject');
             const [x0, y0, w] = ['x', 'y', 'width'].map((a) => Number(fo.getAttribute(a)));
             const k = cv.width / w;
             const d = cx.getImageData(0, 0, cv.width, cv.height).data;
             let inked = 0; const rgb = [0, 0, 0]; let strong = 0;
             for (let i = 3; i < d.length; i += 4) {{
               if (d[i] > 0) inked++;
               if (d[i] >= 128) {{ strong++; rgb[0] += d[i - 3]; rgb[1] += d[i - 2]; rgb[2] += d[i - 1]; }}
             }}
             const alpha = {points:?}.map(([x, y]) => {{
               // The pixel the point falls in, and its neighbours: a
               // hairline's coverage may sit in the next pixel.
               const [px, py] = [Math.floor((x - x0) * k), Math.floor((y - y0) * k)];
               let a = 0;
               for (let dy = -1; dy <= 1; dy++) for (let dx = -1; dx <= 1; dx++) {{
                 const [u, v] = [px + dx, py + dy];
                 if (u >= 0 && v >= 0 && u < cv.width && v < cv.height) a = Math.max(a, d[(v * cv.width + u) * 4 + 3]);
               }}
               return a;
             }});
             return {{alpha, inked, rgb: rgb.map((c) => c / Math.max(strong, 1))}};",
            points = points.iter().map(|&(x, y)| [x, y]).collect::<Vec<_>>()
    );
    let v = js(c, &script).await;
    let alpha = v["alpha"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_u64().unwrap() as u8)
        .collect();
    let rgb = v["rgb"].as_array().unwrap();
    let rgb = [0, 1, 2].map(|i| rgb[i].as_f64().unwrap());
    (alpha, v["inked"].as_u64().unwrap(), rgb)
}

/// The tree's canvas: the box it covers (canvas units), its pixels a
/// unit, its screen rectangle and the library's picture's, and how many
/// tree canvases the preview holds.
async fn canvas_box(c: &Client) -> Value {
    let script = "const cv = document.querySelector('#preview [data-testid=tree-canvas]');
         const fo = cv.closest('foreignObject');
         const box = ['x', 'y', 'width', 'height'].map((a) => Number(fo.getAttribute(a)));
         const r = (e) => { const b = e.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom]; };
         return {box: [box[0], box[1], box[0] + box[2], box[1] + box[3]], k: cv.width / box[2],
                 fo: r(fo), lib: r(document.querySelector('#preview .lib svg')),
                 canvases: document.querySelectorAll('#preview foreignObject.tree').length};";
    js(c, script).await
}

/// One stem: from, to, decision.
type Stem = ((f64, f64), (f64, f64), u64);

fn stem_list(a: &Value) -> Vec<Stem> {
    let g: Vec<f64> = numbers(&a["growth"]["stems"]);
    g.chunks(6)
        .map(|s| ((s[0], s[1]), (s[2], s[3]), s[5] as u64))
        .collect()
}

/// Points of a 25 x 25 grid over the layout farther than 8 units (over 3
/// pixels) from every stem in `stems`: where the canvas must have no ink.
fn bare(stems: &[Stem]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 0..25 {
        for j in 0..25 {
            let p = (24.0 + 48.0 * f64::from(i), 24.0 + 48.0 * f64::from(j));
            if stems
                .iter()
                .all(|&(a, b, _)| segment_distance(p, a, b) > 8.0)
            {
                out.push(p);
            }
        }
    }
    out
}

/// Midpoints of every 97th stem of `stems`.
fn midpoints(stems: &[Stem]) -> Vec<(f64, f64)> {
    stems
        .iter()
        .step_by(97)
        .map(|&(a, b, _)| ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0))
        .collect()
}

#[test]
fn a_big_tree_draws_on_a_canvas_and_replays_in_chromium() {
    let tmp = tempfile::tempdir().unwrap();
    let Some(browser) = Browser::start(tmp.path()) else {
        return;
    };
    let text = big(30_001);
    let file = tmp.path().join("big.od");
    std::fs::write(&file, &text).unwrap();
    let server = Server::start(&[file.to_str().unwrap()]);
    // The stems as the JSON API gives them: where the canvas must be inked.
    let answer = render(&server.addr, &json!({"source": text, "kind": "od"}));
    assert_eq!(stems(&answer), 30_001);
    let all = stem_list(&answer);
    let last = all.last().unwrap().2;
    browser.rt.block_on(async {
        let c = browser.connect().await;
        c.goto(&server.url).await.unwrap();
        assert_eq!(drawn(&c).await, 30_001, "every stem on the canvas");
        shot(&c, "bigtree").await;
        let script = "const a = window.stlc.state.answer;
             const inked = (id) => {
               const c = document.querySelector(`#preview [data-testid=${id}]`);
               const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
               let n = 0;
               for (let i = 3; i < d.length; i += 4) if (d[i]) n++;
               return n;
             };
             return {strokes: inked('tree-canvas'), dots: inked('tree-dots'), compact: a.growth.stems instanceof Float64Array, n: a.growth.stems.length,
                     paths: document.querySelectorAll('#preview .lib path[fill=\"none\"]').length,
                     layout: document.querySelectorAll('#preview .lib path[fill=\"#008000\"]').length,
                     canvases: document.querySelectorAll('#preview canvas').length,
                     bed: a.bed, label: document.getElementById('step-label').textContent};";
        let page = js(&c, script).await;
        assert_eq!(page["compact"], true, "{page}");
        assert_eq!(page["n"], 6 * 30_001);
        assert_eq!(page["paths"], 0, "no stem in the SVG");
        assert_eq!(page["layout"], 1, "the layout under it");
        assert_eq!(page["canvases"], 2, "strokes and dots");
        // The first orders' stems are over a pixel long, the rest under.
        assert!(page["strokes"].as_u64().unwrap() > 100, "{page}");
        assert!(page["dots"].as_u64().unwrap() > 100, "{page}");
        assert_eq!(page["bed"], Value::Null);
        let all_of = crate::support::grouped(last);
        let label = format!("decision {all_of} of {all_of} · 30,001 stems");
        assert_eq!(page["label"], label);

        // Ink on every 97th stem's midpoint, none far from all stems, in
        // the stroke's colour.
        let marks = midpoints(&all);
        let empty = bare(&all);
        assert!(empty.len() > 20, "{} bare points", empty.len());
        let probe: Vec<(f64, f64)> = marks.iter().chain(&empty).copied().collect();
        let (alpha, _, rgb) = ink(&c, &probe).await;
        let (on, off) = alpha.split_at(marks.len());
        assert!(on.iter().all(|&a| a > 0), "a stem without ink: {on:?}");
        assert!(off.iter().all(|&a| a == 0), "ink far from every stem: {off:?}");
        let brown = [0x4a, 0x2c, 0x12].map(f64::from);
        let ok = (0..3).all(|i| (rgb[i] - brown[i]).abs() < 4.0);
        assert!(ok, "{rgb:?} is not the stroke #4a2c12");

        // Zoomed in, a sharper canvas of the part in view replaces the
        // whole one once the view rests: inside the library's picture of
        // the layout, inked at the stems there; after Fit, the whole again.
        let fitted = canvas_box(&c).await;
        for _ in 0..3 {
            click(&c, "#zoom-in").await;
        }
        // The tree's base in the middle.
        let script = "const v = window.stlc.state.view;
             window.stlc.view.pan(v, (v[0] + v[2]) / 2 - 600, (v[1] + v[3]) / 2 - 1100); return 0;";
        js(&c, script).await;
        tokio::time::sleep(Duration::from_millis(400)).await;
        assert_eq!(drawn(&c).await, 30_001);
        let zoomed = canvas_box(&c).await;
        assert_eq!(zoomed["canvases"], 1, "the old canvas went: {zoomed}");
        let scale = |b: &Value| b["k"].as_f64().unwrap();
        assert!(scale(&zoomed) > 1.8 * scale(&fitted), "{fitted} {zoomed}");
        let (fo, lib) = (&zoomed["fo"], &zoomed["lib"]);
        for i in 0..2 {
            assert!(fo[i].as_f64().unwrap() >= lib[i].as_f64().unwrap() - 1.0, "{zoomed}");
            assert!(fo[i + 2].as_f64().unwrap() <= lib[i + 2].as_f64().unwrap() + 1.0, "{zoomed}");
        }
        let b: Vec<f64> = (0..4).map(|i| zoomed["box"][i].as_f64().unwrap()).collect();
        let inside: Vec<(f64, f64)> = midpoints(&all)
            .into_iter()
            .filter(|&(x, y)| x > b[0] + 2.0 && y > b[1] + 2.0 && x < b[2] - 2.0 && y < b[3] - 2.0)
            .collect();
        assert!(inside.len() > 20, "{} stems in view", inside.len());
        let (alpha, _, _) = ink(&c, &inside).await;
        assert!(alpha.iter().all(|&a| a > 0), "a stem in view without ink");
        shot(&c, "bigtree-zoomed").await;
        click(&c, "#fit").await;
        tokio::time::sleep(Duration::from_millis(400)).await;
        assert_eq!(drawn(&c).await, 30_001);
        let refitted = canvas_box(&c).await;
        assert_eq!(refitted["box"], fitted["box"]);
        // (The first canvas was made as the page was laid out: its
        // resolution may differ by a little; this one is the reference.)
        let (_, inked, _) = ink(&c, &[]).await;
        for i in 0..4 {
            let a = refitted["fo"][i].as_f64().unwrap();
            let b = refitted["lib"][i].as_f64().unwrap();
            assert!((a - b).abs() < 1.0, "{refitted}");
        }

        // Replay to a decision halfway: the stems up to it, no more.
        let k = last / 2;
        set_value(&c, "#step", &k.to_string()).await;
        let early: Vec<Stem> = all.iter().copied().filter(|s| s.2 <= k).collect();
        let later: Vec<Stem> = all.iter().copied().filter(|s| s.2 > k).collect();
        assert_eq!(drawn(&c).await, early.len() as u64);
        shot(&c, "bigtree-replay-half").await;
        let (alpha, half_inked, _) = ink(&c, &[midpoints(&early), bare(&early)].concat()).await;
        let (on, off) = alpha.split_at(midpoints(&early).len());
        assert!(on.iter().all(|&a| a > 0), "an early stem without ink");
        assert!(off.iter().all(|&a| a == 0), "ink of a later stem");
        assert!(bare(&early).len() > bare(&all).len(), "the later stems cover more");
        assert!(half_inked < inked, "{half_inked} {inked}");
        assert!(!later.is_empty());

        // Play on to the end, in a second: the whole tree again.
        js(&c, "document.getElementById('replay-speed').value = '1s'; return 0;").await;
        click(&c, "#play").await;
        let at = "return Number(document.getElementById('step').value)";
        js_until(&c, at, 200, 50, |v| v.as_u64() == Some(last)).await;
        assert_eq!(drawn(&c).await, 30_001);
        let (_, replayed, _) = ink(&c, &[]).await;
        assert_eq!(replayed, inked, "the replay ends on the same picture");

        // A small tree: the SVG's paths, no canvas.
        set_value(&c, "#source", &super::serve::example("fig9.od")).await;
        drawn(&c).await;
        let script = "return {paths: document.querySelectorAll('#preview .lib path[fill=\"none\"]').length,
                     canvases: document.querySelectorAll('#preview canvas').length,
                     svg: window.stlc.state.answer.tree_in_svg};";
        let page = js(&c, script).await;
        assert!(page["paths"].as_u64().unwrap() > 0, "{page}");
        assert_eq!(page["canvases"], 0);
        assert_eq!(page["svg"], true);
        shot(&c, "bigtree-small-after").await;
        let _ = c.close().await;
    });
}
