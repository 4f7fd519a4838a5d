//! `stlc serve` in a real headless Chromium (the harness, and when it
//! skips: chromium.rs): type an OD, draw a rectangle with the mouse,
//! switch bfs/dfs, type an error, replay growth, save.

use std::path::Path;

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser_steps::{
    answer_svg, caret_to_end, js_with, listed_error, retype, set_value, settled_failed, settled_ok,
    text_of, type_into, value_of,
};
use super::chromium::{
    CONTROL, SHIFT, Served, chord, cli, cli_line, click, click_at, downloaded, drag, file_until,
    js, js_until, on_served_file, open, poll, press_along, same_bytes, screen_of, settled,
    settled_until, shot, wheel,
};
use super::serve::{Server, example};
use crate::support::{manifest_path, numbers};

const KOCH: &str = "axiom F++F++F\nangle 60\nrule F F-F++F-F\n";

const TYPED: &str = "Typed (100, 190)\nL=9(0) B=1.5(0) A=30 C=2\nRULE\nR1: [-F][+F]\nSEED\nFR1\nENDSEED\nLAYOUT\n(clGreen) Rectangle (70, 120), 60, 75\nENDLAYOUT\n";

#[test]
fn the_page_grows_draws_replays_and_saves_in_chromium() {
    on_served_file("tree.od", &example("fig9.od"), async |c, served| {
        steps(c, served.file).await;
        acceptance(c).await;
    });
}

/// The acceptance, on the paper's 2DTree: open it, draw a white
/// hole with the mouse, switch to dfs, replay, save.
async fn acceptance(c: &Client) {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("2dtree.od");
    std::fs::copy(manifest_path("examples/2dtree.od"), &file).unwrap();
    let server = Server::start(&[file.to_str().unwrap()]);
    c.goto(&server.url).await.unwrap();
    let opened = settled_ok(c).await;
    let before = opened["stems"].as_u64().unwrap();
    click(c, "[data-tool=Ellipse]").await;
    click(c, "#colour option[value=clWhite]").await;
    drag(c, (100.0, 60.0), (160.0, 110.0)).await;
    let holed = settled_ok(c).await;
    let text = holed["text"].as_str().unwrap();
    // The paper's inline layout stays as it is; the new shape is a line
    // before ENDLAYOUT, spelt as the paper spells its shapes.
    let hole = "\n(clWhite)< Ellipse (100,60,160,110)>\nENDLAYOUT";
    let want = example("2dtree.od").replace("\nENDLAYOUT", hole);
    assert_eq!(text, want, "{text}");
    let after = holed["stems"].as_u64().unwrap();
    let fewer = format!("the hole takes stems away: {before} -> {after}");
    assert!(after < before, "{fewer}");
    // No stem ends inside the hole (an ellipse centred at (130, 85)).
    let g = numbers(&holed["growth"]);
    let inside = |x: f64, y: f64| ((x - 130.0) / 30.0).powi(2) + ((y - 85.0) / 25.0).powi(2) < 0.95;
    let in_hole = g.chunks(6).any(|s| inside(s[2], s[3]));
    assert!(!in_hole, "a stem grew in the hole");
    click(c, "#growth option[value=dfs]").await;
    let dfs = settled_until(c, 20, 100, |v| v["growth"] != holed["growth"]).await;
    assert_ne!(dfs["growth"], holed["growth"]);
    // The growth order is kept in the file: `O=dfs` joins the header, and
    // nothing else in the text changes.
    let text = dfs["text"].as_str().unwrap();
    let want = holed["text"]
        .as_str()
        .unwrap()
        .replace("B=1(0)RULE", "B=1(0) O=dfs RULE");
    assert_eq!(text, want, "{text}");
    click(c, "#play").await;
    replay_ended(c).await;
    shot(c, "11-acceptance").await;
    click(c, "#save").await;
    let on_disk = file_until(&file, 100, |t| t == text).await;
    assert_eq!(on_disk, text);

    // Export: the page offers the CLI's PNG and BED for the same options.
    let od = tmp.path().join("saved.od");
    std::fs::write(&od, text).unwrap();
    for (button, command, ext) in [
        ("#export-png", "render -f png --show-layout", ".png"),
        ("#export-bed", "compile", ".bed"),
    ] {
        js(c, "window.stlc.state.lastDownload = null; return 0;").await;
        click(c, button).await;
        let last = "return window.stlc.state.lastDownload";
        let offered = js_until(c, last, 200, 50, |v| !v.is_null()).await;
        let out = cli_line(&format!("{command} {} --growth dfs", od.display()));
        assert_eq!(offered["size"], out.len(), "{button}: {offered}");
        let name = offered["name"].as_str().unwrap();
        assert!(name.ends_with(ext), "{offered}");
    }
}

async fn steps(c: &Client, file: &Path) {
    let first = settled_ok(c).await;
    assert!(first["text"].as_str().unwrap().contains("Fig9"));
    shot(c, "1-opened").await;

    // Type an OD.
    retype(c, TYPED).await;
    let typed = settled_ok(c).await;
    assert_eq!(typed["text"], TYPED);
    let small = typed["stems"].as_u64().unwrap();
    assert!(small > 3, "{typed}");
    shot(c, "2-typed").await;

    // Draw a rectangle with the mouse: the LAYOUT text gains it, and the
    // tree regrows into it (stems beyond the first rectangle).
    click(c, "[data-tool=Rectangle]").await;
    drag(c, (20.0, 20.0), (180.0, 160.0)).await;
    let drawn = settled(c).await;
    let text = drawn["text"].as_str().unwrap();
    let layout = layout_lines(text);
    assert_eq!(layout.len(), 2, "{text}");
    assert_eq!(layout[0], "(clGreen) Rectangle (70, 120), 60, 75");
    let new = &layout[1];
    assert!(new.starts_with("(clGreen) Rectangle ("), "{new}");
    let nums = numbers_in(new.trim_start_matches("(clGreen) Rectangle "));
    let at = |i: usize, want: f64| (nums[i] - want).abs() <= 1.0;
    let corners = at(0, 20.0) && at(1, 20.0) && at(2, 160.0) && at(3, 140.0);
    assert!(corners, "{new}");
    assert_eq!(drawn["ok"], true, "{drawn}");
    let grown = drawn["stems"].as_u64().unwrap();
    assert!(grown > small, "{small} -> {grown}");
    let g = numbers(&drawn["growth"]);
    let outside_first = g.chunks(6).any(|s| s[3] < 119.0);
    assert!(outside_first, "no stem grew into the drawn rectangle");
    shot(c, "3-drawn").await;

    // dfs grows another tree from the same outline.
    click(c, "#growth option[value=dfs]").await;
    let dfs = settled_until(c, 20, 100, |v| v["growth"] != drawn["growth"]).await;
    assert_eq!(dfs["ok"], true);
    let same = "bfs and dfs gave the same tree";
    assert_ne!(dfs["growth"], drawn["growth"], "{same}");
    shot(c, "4-dfs").await;

    // Replay: midway only part of the tree is drawn.
    let max = js(c, "return Number(document.getElementById('step').max)").await;
    let max = max.as_u64().unwrap();
    assert!(max > 10, "{max}");
    click(c, "#play").await;
    // The replay takes about four seconds: look once it is under way.
    let now = "return {v: Number(document.getElementById('step').value),
                       replaying: document.getElementById('preview').classList.contains('replaying'),
                       label: document.getElementById('step-label').textContent};";
    let mid = js_until(c, now, 200, 50, |m| m["v"].as_u64().unwrap() > max / 4).await;
    let v = mid["v"].as_u64().unwrap();
    assert!(v > 0 && v < max, "{mid}");
    assert_eq!(mid["replaying"], true, "{mid}");
    shot(c, "5-replay").await;
    replay_ended(c).await;
    assert_eq!(value_of(c, "#step").await, max.to_string());

    // An error: its diagnostic is listed and marked at its line.
    let good = dfs["text"].as_str().unwrap().to_string();
    let error_line = good.lines().count() + 1;
    caret_to_end(c).await;
    type_into(c, "source", "JUNK(").await;
    settled_failed(c).await;
    let listed = listed_error(c).await;
    assert_eq!(listed["line"], error_line.to_string(), "{listed}");
    assert_eq!(listed["mark"], error_line.to_string(), "{listed}");
    shot(c, "6-error").await;
    for _ in 0..5 {
        type_into(c, "source", "\u{E003}").await; // Backspace
    }
    let fixed = settled_ok(c).await;
    assert_eq!(fixed["text"], good.as_str());

    // Save writes the editor's text to the file.
    click(c, "#save").await;
    let on_disk = file_until(file, 100, |t| t == good).await;
    assert_eq!(on_disk, good);
    // The page says so once the answer is back (the file is written first).
    let saved = "return document.getElementById('saved').textContent";
    let said_saved = |v: &Value| v.as_str().unwrap().starts_with("Saved");
    let status = js_until(c, saved, 100, 50, said_saved).await;
    assert!(status.as_str().unwrap().starts_with("Saved"), "{status}");
    shot(c, "7-saved").await;

    tools(c, &good).await;
}

/// The page's settled answer and the layout lines of its text.
async fn settled_layout(c: &Client) -> (Value, Vec<String>) {
    let v = settled(c).await;
    let lines = layout_lines(v["text"].as_str().unwrap());
    (v, lines)
}

/// The layout lines of `text`, between `LAYOUT` and `ENDLAYOUT`.
fn layout_lines(text: &str) -> Vec<String> {
    text.lines()
        .skip_while(|l| *l != "LAYOUT")
        .skip(1)
        .take_while(|l| *l != "ENDLAYOUT")
        .map(str::to_string)
        .collect()
}

/// The other tools: a white ellipse erases (fewer stems), moving it
/// rewrites its line, a polygon by clicks, reordering, deleting, and
/// dragging the root; each edit shows in the LAYOUT text.
async fn tools(c: &Client, start: &str) {
    let before = layout_lines(start);
    assert_eq!(before.len(), 2, "{before:?}");
    let stems0 = settled(c).await["stems"].as_u64().unwrap();

    // A white ellipse: a hole in the outline.
    // Picking a drawing tool drops the selection, so the paint colour
    // chosen next is for the new shape only.
    click(c, "[data-tool=Ellipse]").await;
    click(c, "#colour option[value=clWhite]").await;
    drag(c, (60.0, 40.0), (140.0, 100.0)).await;
    let (holed, lines) = settled_layout(c).await;
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert_eq!(lines[2], "(clWhite) Ellipse (60, 40), 80, 60");
    let stems1 = holed["stems"].as_u64().unwrap();
    let fewer = format!("a hole grows fewer stems: {stems0} -> {stems1}");
    assert!(stems1 < stems0, "{fewer}");
    shot(c, "8-hole").await;

    // Select it by its outline and move it 10 units right and down.
    click(c, "[data-tool=select]").await;
    drag(c, (100.0, 70.0), (110.0, 80.0)).await;
    let lines = settled_layout(c).await.1;
    assert_eq!(lines[2], "(clWhite) Ellipse (70, 50), 80, 60", "{lines:?}");

    // Resize by its bottom-right handle.
    drag(c, (150.0, 110.0), (160.0, 120.0)).await;
    let lines = settled_layout(c).await.1;
    assert_eq!(lines[2], "(clWhite) Ellipse (70, 50), 90, 70", "{lines:?}");

    // Lower it below the second rectangle: paint order in the text.
    click(c, "#lower").await;
    let (lowered, lines) = settled_layout(c).await;
    assert_eq!(lines[1], "(clWhite) Ellipse (70, 50), 90, 70", "{lines:?}");
    assert_eq!(lines[2], before[1]);
    // Painted before the big green rectangle, the hole is painted over.
    assert_eq!(lowered["stems"].as_u64().unwrap(), stems0, "{lines:?}");

    // Delete it.
    click(c, "#delete").await;
    assert_eq!(settled_layout(c).await.1, before);

    // A polygon by clicks, closed on its first point.
    click(c, "[data-tool=Polygon]").await;
    click(c, "#colour option[value=clGreen]").await;
    for p in [
        (150.0, 170.0),
        (190.0, 170.0),
        (190.0, 195.0),
        (150.0, 170.0),
    ] {
        click_at(c, p).await;
    }
    let lines = settled_layout(c).await.1;
    assert_eq!(lines.len(), 3, "{lines:?}");
    let polygon = "(clGreen) Polygon (150, 170), (190, 170), (190, 195)";
    assert_eq!(lines[2], polygon);
    shot(c, "9-polygon").await;

    // Drag the root: its `(x, y)` in the text follows.
    click(c, "[data-tool=select]").await;
    drag(c, (100.0, 190.0), (90.0, 185.0)).await;
    let rooted = settled(c).await;
    let text = rooted["text"].as_str().unwrap();
    assert!(text.starts_with("Typed (90, 185)\n"), "{text}");
    assert_eq!(rooted["ok"], true, "{rooted}");

    // Fit, zoom in, Fit: the view shrinks, then comes back.
    let width = "return document.getElementById('preview').viewBox.baseVal.width";
    click(c, "#fit").await;
    let fitted = js(c, width).await.as_f64().unwrap();
    // The layout's canvas: the drawn rectangle and the polygon, plus margins.
    assert!(fitted > 170.0 && fitted < 200.0, "{fitted}");
    click(c, "#zoom-in").await;
    let zoomed = js(c, width).await.as_f64().unwrap();
    // (SVG keeps the box in single precision.)
    let by_a_step = (zoomed - fitted / 1.25).abs() < 1e-3;
    assert!(by_a_step, "{fitted} -> {zoomed}");
    click(c, "#fit").await;
    assert!((js(c, width).await.as_f64().unwrap() - fitted).abs() < 1e-3);

    // Tree Renderer: an L-system at a depth.
    click(c, "#kind option[value=lsys]").await;
    retype(c, KOCH).await;
    // The depth control writes the file's `generations` line.
    type_into(c, "depth", "2").await;
    let text = value_of(c, "#source").await;
    assert!(text.ends_with("generations 2\n"), "{text}");
    let koch = settled_ok(c).await;
    // Depth 2 of the Koch snowflake: 3 * 4^2 segments.
    assert_eq!(koch["stems"], 48, "{koch}");
    let drawn = super::browser_steps::count(c, "#preview .lib path").await;
    assert!(drawn >= 1, "{drawn}");
    shot(c, "10-renderer").await;
}

/// Waits (up to 30 s) until the replay has ended.
async fn replay_ended(c: &Client) {
    let replayed = "return window.stlc.state.replayTimer === null";
    js_until(c, replayed, 600, 50, |v| v == &json!(true)).await;
}

/// The BED of the page's answer once it is `want` (the page may still be
/// answering an earlier edit), or the last one seen.
async fn answer_bed(c: &Client, want: &str) -> String {
    let bed = async || {
        settled(c).await;
        let bed = js(c, "return window.stlc.state.answer.bed").await;
        bed.as_str().unwrap_or_default().to_string()
    };
    poll(40, 50, bed, |b| b == want).await
}

/// The preview's view box: `[x, y, width, height]` in canvas units.
async fn view_box(c: &Client) -> Vec<f64> {
    let script = "const b = document.getElementById('preview').viewBox.baseVal;
         return [b.x, b.y, b.width, b.height];";
    let v = js(c, script).await;
    numbers(&v)
}

/// The box Fit shows, as a view box.
async fn fit_box(c: &Client) -> Vec<f64> {
    let fit = "const f = window.stlc.state.fitView; return [f[0], f[1], f[2] - f[0], f[3] - f[1]];";
    let v = js(c, fit).await;
    numbers(&v)
}

fn same_box(a: &[f64], b: &[f64]) -> bool {
    // (SVG keeps the box in single precision.)
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-3)
}

/// The numbers in `line` (a shape's, after its name), in order.
fn numbers_in(line: &str) -> Vec<f64> {
    line.split(|ch: char| !(ch.is_ascii_digit() || ch == '.'))
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect()
}

#[test]
fn the_page_opens_exports_zooms_edits_and_undoes_in_chromium() {
    on_served_file("start.od", TYPED, async |c, served| {
        renderer(c, served).await;
        editing(c, served).await;
        columns(c, served.dir).await;
    });
}

/// Tree Renderer through Open…: a BED (and its SVG export, the CLI's
/// bytes), a broken BED's diagnostic, an L-system at a depth; each new
/// file is shown whole.
async fn renderer(c: &Client, served: &Served<'_>) {
    let (dir, downloads) = (served.dir, &served.downloads);
    settled_ok(c).await;
    let typed_view = view_box(c).await;

    // A BED opened from disk: drawn as `stlc render` draws it, and fitted.
    let fig9 = manifest_path("examples/fig9.od");
    let bed = dir.join("fig9.bed");
    std::fs::write(&bed, cli(&["compile", fig9.to_str().unwrap()])).unwrap();
    open(c, &bed).await;
    let opened = settled_ok(c).await;
    let whole = std::fs::read_to_string(&bed).unwrap();
    assert_eq!(opened["text"].as_str().unwrap(), whole);
    assert_eq!(value_of(c, "#kind").await, "bed");
    // (The BED keeps the OD's LAYOUT, so the page shows it, as
    // `--show-layout` does.)
    let svg = cli_line(&format!("render {} --show-layout -f svg", bed.display()));
    same_bytes(answer_svg(c).await.as_bytes(), &svg, "the page's SVG");
    let fitted = view_box(c).await;
    assert!(same_box(&fitted, &fit_box(c).await), "{fitted:?}");
    assert!(!same_box(&fitted, &typed_view), "{fitted:?} {typed_view:?}");
    shot(c, "12-open-bed").await;

    // SVG export: the file the browser saves is the CLI's.
    click(c, "#export-svg").await;
    same_bytes(&downloaded(downloads, "fig9.svg").await, &svg, "fig9.svg");

    // A broken BED: its diagnostic at its line, the last picture kept.
    let text = std::fs::read_to_string(&bed).unwrap();
    let mut broken: Vec<String> = text.lines().map(str::to_string).collect();
    broken[2] = format!("JUNK {}", broken[2]);
    let bad = dir.join("bad.bed");
    std::fs::write(&bad, broken.join("\n") + "\n").unwrap();
    open(c, &bad).await;
    settled_failed(c).await;
    let listed = listed_error(c).await;
    assert_eq!(listed["line"], "3", "{listed}");
    assert_eq!(listed["mark"], "3", "{listed}");
    let expected = "expected `RULE`, a root `(x, y)` or a stem parameter";
    let said = listed["text"].as_str().unwrap();
    assert!(said.contains(expected), "{listed}");
    // A file just opened that fails shows no picture of the file before
    // it (issue 22, problem 4).
    assert_eq!(listed["picture"], false, "{listed}");
    shot(c, "13-bad-bed").await;

    // An L-system with a depth: the Koch snowflake at depth 3.
    let koch = dir.join("koch.lsys");
    std::fs::write(&koch, KOCH).unwrap();
    open(c, &koch).await;
    assert_eq!(value_of(c, "#kind").await, "lsys");
    type_into(c, "depth", "3").await;
    let drawn = settled_until(c, 40, 50, |v| v["stems"] == 192).await;
    // 3 * 4^3 segments.
    assert_eq!(drawn["stems"], 192, "{drawn}");
    let svg = cli_line(&format!("render {} --depth 3 -f svg", koch.display()));
    same_bytes(answer_svg(c).await.as_bytes(), &svg, "the page's SVG");
    assert!(same_box(&view_box(c).await, &fit_box(c).await));
    shot(c, "14-lsys").await;
    click(c, "#export-svg").await;
    same_bytes(&downloaded(downloads, "koch.svg").await, &svg, "koch.svg");

    // A forest with alternatives: the seed field is `--seed`, "next seed"
    // grows the next variant, and every root shows.
    let grove = dir.join("grove.od");
    std::fs::copy(manifest_path("examples/grove.od"), &grove).unwrap();
    open(c, &grove).await;
    settled(c).await;
    let bed_of = |seed: &str| {
        String::from_utf8(cli(&["compile", grove.to_str().unwrap(), "--seed", seed])).unwrap()
    };
    let grove_is = async |seed: &str, what: &str| {
        let want = bed_of(seed);
        same_bytes(answer_bed(c, &want).await.as_bytes(), want.as_bytes(), what);
    };
    type_into(c, "seed", "7").await;
    grove_is("7", "the grove, seed 7").await;
    let roots = super::browser_steps::count(c, "#preview .other-root").await;
    assert_eq!(roots, 3, "the grove's three further roots");
    shot(c, "15-grove-seed-7").await;
    click(c, "#reseed").await;
    assert_eq!(value_of(c, "#seed").await, "8");
    grove_is("8", "the grove, next seed").await;
    shot(c, "16-grove-seed-8").await;
    // Seeds past 2^53 (where JavaScript numbers stop being exact) reach
    // the server digit for digit; "next seed" counts on exactly.
    set_value(c, "#seed", "18446744073709551614").await;
    click(c, "#reseed").await;
    let top = u64::MAX.to_string();
    assert_eq!(value_of(c, "#seed").await, top);
    grove_is(&top, "the grove, seed 2^64 - 1").await;
    set_value(c, "#seed", "").await;
}

/// Back in Tree Maker: wheel zoom and drag-to-pan move only the view; a
/// RoundRect drawn, Raise, a selected shape recoloured; Ctrl-Z and Ctrl-Y
/// walk those edits back and forth.
async fn editing(c: &Client, served: &Served<'_>) {
    let (dir, downloads) = (served.dir, &served.downloads);
    let od = dir.join("tree.od");
    std::fs::write(&od, TYPED).unwrap();
    open(c, &od).await;
    settled_ok(c).await;
    assert_eq!(value_of(c, "#kind").await, "od");
    let fitted = view_box(c).await;
    assert!(same_box(&fitted, &fit_box(c).await), "{fitted:?}");
    let svg = answer_svg(c).await;
    let lib = "return document.querySelector('#preview .lib').innerHTML";
    let picture = js(c, lib).await;
    let renders = "return window.stlc.state.timings.length";
    let rendered = js(c, renders).await;

    // The wheel zooms out around the pointer: the canvas point under it
    // stays under it, the picture is the same.
    let (px, py) = screen_of(c, 100.0, 150.0).await;
    let mut notches = 0;
    while view_box(c).await[2] < 240.0 {
        wheel(c, (px, py), 120).await;
        notches += 1;
        assert!(notches < 30, "the wheel does not zoom");
    }
    let zoomed = view_box(c).await;
    let ratio = zoomed[2] / fitted[2];
    let steps = libm::log(ratio) / libm::log(1.15);
    assert!((steps - steps.round()).abs() < 1e-3, "{ratio}");
    assert!((zoomed[3] / fitted[3] - ratio).abs() < 1e-3);
    let (qx, qy) = screen_of(c, 100.0, 150.0).await;
    let moved = (qx - px).abs() < 1.0 && (qy - py).abs() < 1.0;
    assert!(moved, "{px},{py} -> {qx},{qy}");
    // The wheel back towards the screen zooms in.
    wheel(c, (px, py), -120).await;
    assert!((view_box(c).await[2] * 1.15 - zoomed[2]).abs() < 1e-2);
    wheel(c, (px, py), 120).await;

    // Dragging empty space pans: the picture moves with the mouse.
    let (sx, sy) = screen_of(c, 30.0, 60.0).await;
    press_along(c, &[(sx, sy), (sx + 60.0, sy + 40.0)], 100).await;
    let (tx, ty) = screen_of(c, 30.0, 60.0).await;
    let moved = (tx - sx - 60.0).abs() < 1.0 && (ty - sy - 40.0).abs() < 1.0;
    assert!(moved, "{sx},{sy} -> {tx},{ty}");
    let panned = view_box(c).await;
    assert!((panned[2] - zoomed[2]).abs() < 1e-3);
    assert_eq!(js(c, lib).await, picture);
    assert_eq!(js(c, renders).await, rendered);
    assert_eq!(answer_svg(c).await, svg);
    shot(c, "15-zoomed-panned").await;

    // A RoundRect drawn beside the rectangle: the canvas grows, the view
    // stays where the user put it.
    click(c, "[data-tool=RoundRect]").await;
    click(c, "#colour option[value=clGreen]").await;
    drag(c, (140.0, 40.0), (190.0, 100.0)).await;
    let drawn = settled_ok(c).await;
    let drawn_text = drawn["text"].as_str().unwrap().to_string();
    let lines = layout_lines(&drawn_text);
    assert_eq!(lines.len(), 2, "{lines:?}");
    assert_eq!(lines[0], "(clGreen) Rectangle (70, 120), 60, 75");
    // The drag lands on whole screen pixels at a zoom of 1.15^k, so each
    // number is the intended one within one canvas unit; the corner radius
    // is an eighth of the shorter side, to 0.1.
    let rr = lines[1].clone();
    let nums = numbers_in(rr.trim_start_matches("(clGreen) RoundRect "));
    assert_eq!(nums.len(), 5, "{rr}");
    for (got, want) in nums.iter().zip([140.0, 40.0, 50.0, 60.0]) {
        assert!((got - want).abs() <= 1.0, "{rr}");
    }
    let radius = (nums[2].min(nums[3]) / 8.0 * 10.0).round() / 10.0;
    assert!((nums[4] - radius).abs() < 1e-9, "{rr}");
    let shape = js(c, "return window.stlc.state.answer.layout.shapes[1]").await;
    assert_eq!(shape["type"], "RoundRect", "{shape}");
    assert_eq!(shape["rx"], nums[4], "{shape}");
    assert_eq!(shape["ry"], nums[4], "{shape}");
    assert!(same_box(&view_box(c).await, &panned));
    assert!(!same_box(&fit_box(c).await, &fitted));

    // Raise the rectangle above the RoundRect.
    click(c, "[data-tool=select]").await;
    click_at(c, (100.0, 140.0)).await;
    assert_eq!(js(c, "return window.stlc.state.selected").await, 0);
    click(c, "#raise").await;
    let raised_text = settled(c).await["text"].as_str().unwrap().to_string();
    let want = [rr.as_str(), "(clGreen) Rectangle (70, 120), 60, 75"];
    assert_eq!(layout_lines(&raised_text), want);

    // Recolour paints the selection with the paint colour.
    click(c, "#colour option[value=clLime]").await;
    click(c, "#recolour").await;
    let lime_text = settled_ok(c).await["text"].as_str().unwrap().to_string();
    let want = [rr.as_str(), "(clLime) Rectangle (70, 120), 60, 75"];
    assert_eq!(layout_lines(&lime_text), want);
    let lime = answer_svg(c).await.to_lowercase().contains("#00ff00");
    assert!(lime, "the lime rectangle is not drawn lime");
    assert!(same_box(&view_box(c).await, &panned));
    shot(c, "16-roundrect-raised-lime").await;

    // Undo walks back through the three edits (and no further: opening a
    // file starts a new history); redo walks forward.
    for want in [&raised_text, &drawn_text, TYPED, TYPED] {
        chord(c, &[CONTROL], 'z').await;
        assert_eq!(settled_ok(c).await["text"].as_str().unwrap(), want);
    }
    let shapes = js(c, "return window.stlc.state.shapes.length").await;
    assert_eq!(shapes, 1);
    chord(c, &[CONTROL], 'y').await;
    assert_eq!(settled(c).await["text"].as_str().unwrap(), drawn_text);
    chord(c, &[CONTROL, SHIFT], 'z').await;
    assert_eq!(settled(c).await["text"].as_str().unwrap(), raised_text);
    assert!(same_box(&view_box(c).await, &panned));
    shot(c, "17-undone").await;

    // Typing is one more step of the same history, undone in the editor.
    caret_to_end(c).await;
    type_into(c, "source", "JUNK(").await;
    let typed = settled_failed(c).await;
    let junk = format!("{raised_text}JUNK(");
    assert_eq!(typed["text"].as_str().unwrap(), junk);
    chord(c, &[CONTROL], 'z').await;
    assert_eq!(settled_ok(c).await["text"].as_str().unwrap(), raised_text);

    // Another description pasted over the whole text is shown whole. (Its
    // text reaches the clipboard by a real Ctrl-C in a scratch textarea.)
    let fig9 = example("fig9.od");
    js_with(
        c,
        "const t = document.createElement('textarea'); t.id = 'scratch';
         t.value = arguments[0]; document.body.appendChild(t);
         t.focus(); t.select(); return 0;",
        &[json!(fig9)],
    )
    .await;
    chord(c, &[CONTROL], 'c').await;
    let script = "document.getElementById('scratch').remove();
         const s = document.getElementById('source'); s.focus(); s.select(); return 0;";
    js(c, script).await;
    chord(c, &[CONTROL], 'v').await;
    let pasted = settled_ok(c).await;
    assert_eq!(pasted["text"].as_str().unwrap(), fig9);
    let shown = view_box(c).await;
    assert!(same_box(&shown, &fit_box(c).await), "{shown:?}");
    assert!(!same_box(&shown, &panned), "{shown:?}");
    shot(c, "18-pasted").await;

    // Tree Maker's SVG export, grown depth-first: `stlc render`'s bytes.
    click(c, "#growth option[value=dfs]").await;
    let dfs = settled_until(c, 20, 100, |v| v["growth"] != pasted["growth"]).await;
    assert_ne!(dfs["growth"], pasted["growth"]);
    let od = dir.join("fig9.od");
    std::fs::write(&od, &fig9).unwrap();
    let command = format!("render {} --show-layout --growth dfs -f svg", od.display());
    let svg = cli_line(&command);
    click(c, "#export-svg").await;
    same_bytes(&downloaded(downloads, "tree.svg").await, &svg, "tree.svg");
}

/// The JavaScript index (UTF-16 units) of byte offset `byte` of `text`.
fn js_index(text: &str, byte: usize) -> u64 {
    text[..byte].encode_utf16().count() as u64
}

/// Clicks the first error in the diagnostics list and returns the
/// editor's selection, `[selectionStart, selectionEnd]`.
async fn click_error(c: &Client) -> Value {
    click(c, "[data-testid=diagnostics] li.error").await;
    let selection =
        "const s = document.getElementById('source'); return [s.selectionStart, s.selectionEnd];";
    js(c, selection).await
}

/// Diagnostics count columns in characters (code points), JavaScript in
/// UTF-16 units: after an emoji, clicking a diagnostic still selects
/// exactly the token it is about.
async fn columns(c: &Client, dir: &Path) {
    // An emoji in a comment on an earlier line, and the error's whole
    // token selected (`clWhiet`, columns 2 to 9).
    let od = dir.join("emoji.od");
    let text = TYPED.replacen(
        "LAYOUT\n",
        "LAYOUT\n# 🌳 tree, a 🌲 comment\n(clWhiet) Ellipse (80, 130), 20, 20\n",
        1,
    );
    std::fs::write(&od, &text).unwrap();
    open(c, &od).await;
    settled_failed(c).await;
    let at = text.find("clWhiet").unwrap();
    let want = json!([js_index(&text, at), js_index(&text, at + "clWhiet".len())]);
    assert_eq!(click_error(c).await, want, "{text}");

    // An emoji before the error on its own line (an L-system's symbol): the
    // unbalanced `]` is column 8, JavaScript index 8 of its line.
    let lsys = dir.join("emoji.lsys");
    let text = "# 🌳 tree\nangle 20\naxiom 🌳]F\n";
    std::fs::write(&lsys, text).unwrap();
    open(c, &lsys).await;
    settled_failed(c).await;
    let listed = text_of(c, "[data-testid=diagnostics] li.error").await;
    assert!(listed.contains("line 3, column 8"), "{listed}");
    let at = text.find(']').unwrap();
    let want = json!([js_index(text, at), js_index(text, at + 1)]);
    assert_eq!(click_error(c).await, want, "{text}");
    let script = "const s = document.getElementById('source');
         return s.value.slice(s.selectionStart, s.selectionEnd);";
    let selected = js(c, script).await;
    assert_eq!(selected, "]");
    shot(c, "20-emoji-column").await;
}
