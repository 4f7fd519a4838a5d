//! Drawing like a painting program, in a real Chromium: the paint colour is
//! for the next shape only (a green pentagon stays green when white is
//! picked for a diamond), Recolour is its own action, the empty canvas shows
//! a grid; a click picks the smallest shape under the pointer; a drawing
//! edit rewrites only its shape's text, keeping comments and the paper's
//! one-line spelling byte for byte; arrows nudge by 1 (Shift: 10), Ctrl-D
//! duplicates, Delete removes just that shape's text, Shift draws a circle
//! and 45-degree polygon edges.

use std::time::Duration;

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser_steps::{count, settled_ok, texts_of};
use super::chromium::{
    CONTROL, SHIFT, chord, click, click_at, js, on_served_file, press_along, press_along_shifted,
    screen_of, settled, shot,
};
use super::serve::Server;
use crate::support::numbers;

/// No LAYOUT yet: the tree is bounded by its length decrement.
const EMPTY: &str =
    "Draw (100, 150)\nL=8(2) B=1(0) A=30 C=2\nRULE\nR1: [-F R1][+F R1]\nSEED\nFR1\nENDSEED\n";

/// The paper's one-line 2DTree, with comments inside LAYOUT and a shape in
/// Table 1's spelling on its own line.
const ONE_LINE: &str = "# the paper's 2DTree, as printed\n2DTree (76, 150)L=10(0) B=1(0)RULE R1: [+F][-F] LAYOUT (clGreen)< RoundRect (0,0,180,192,7,7)> (clWhite)< RoundRect (55,30,40,15,4,4)> (clWhite)< RoundRect (35,125,76,30,5,5)> # the paper's line\n# a comment inside LAYOUT\n(clgreen) Ellipse (120, 150), 30, 20  # a pond, Table 1's spelling, its colour in lower case\n\nENDLAYOUT\n";

#[test]
fn drawing_edits_touch_only_their_shape_in_chromium() {
    on_served_file("draw.od", EMPTY, async |c, served| {
        paint_colour_is_for_the_next_shape(c).await;
        let one_line = served.dir.join("one-line.od");
        std::fs::write(&one_line, ONE_LINE).unwrap();
        let server = Server::start(&[one_line.to_str().unwrap()]);
        c.goto(&server.url).await.unwrap();
        edits_keep_the_rest_of_the_text(c).await;
    });
}

const RIGHT: char = '\u{E014}';
const DOWN: char = '\u{E015}';
const DELETE: char = '\u{E017}';

/// The editor's text once the page shows its answer.
async fn text(c: &Client) -> String {
    settled(c).await["text"].as_str().unwrap().to_string()
}

async fn selected(c: &Client) -> Value {
    js(c, "return window.stlc.state.selected").await
}

async fn paint_colour_is_for_the_next_shape(c: &Client) {
    settled_ok(c).await;
    // The empty canvas: a grid with its coordinates.
    let lines = count(c, "#preview .grid line").await;
    assert!(lines >= 6, "{lines} grid lines");
    let labels = texts_of(c, "#preview .grid text").await;
    assert!(labels.iter().any(|l| l == "100"), "{labels:?}");
    shot(c, "draw-1-empty-grid").await;

    // Room around the root to draw in: zoom out until it is in view.
    let (rx, ry, r) = (100.0, 150.0, 30.0);
    for _ in 0..12 {
        let v = numbers(&js(c, "return window.stlc.state.view").await);
        if v[0] < rx - 1.2 * r && v[2] > rx + 1.2 * r && v[1] < ry - 1.5 * r && v[3] > ry + r {
            break;
        }
        click(c, "#zoom-out").await;
    }
    let at = |k: f64, radius: f64, cy: f64| {
        let a = (k * 72.0 - 90.0).to_radians();
        let (x, y) = (rx + radius * libm::cos(a), cy + radius * libm::sin(a));
        (x.round(), y.round())
    };
    // A green pentagon around the root, by clicks, closed on its first point.
    click(c, "[data-tool=Polygon]").await;
    click(c, "#colour option[value=clGreen]").await;
    let pentagon: Vec<(f64, f64)> = (0..5).map(|k| at(k as f64, r, ry - r / 3.0)).collect();
    for &p in pentagon.iter().chain(std::iter::once(&pentagon[0])) {
        click_at(c, p).await;
    }
    let green = text(c).await;
    let line = |pts: &[(f64, f64)], colour: &str| {
        let pts: Vec<String> = pts.iter().map(|(x, y)| format!("({x}, {y})")).collect();
        format!("({colour}) Polygon {}", pts.join(", "))
    };
    let pentagon_line = line(&pentagon, "clGreen");
    let want = format!("{EMPTY}LAYOUT\n{pentagon_line}\nENDLAYOUT\n");
    assert_eq!(green, want);
    let grown = settled_ok(c).await;
    assert!(grown["stems"].as_u64().unwrap() > 1, "{grown}");
    // The pentagon drawn is selected; picking white changes no shape.
    assert_eq!(selected(c).await, 0);
    click(c, "#colour option[value=clWhite]").await;
    tokio::time::sleep(Duration::from_millis(200)).await;
    assert_eq!(text(c).await, green, "picking a colour recoloured a shape");
    // A white diamond beside the stem: the pentagon stays green, the tree
    // still grows.
    let d = r / 4.0;
    let (cx, cy) = ((rx + r / 2.5).round(), (ry - r / 2.0).round());
    let diamond = [(cx, cy - d), (cx + d, cy), (cx, cy + d), (cx - d, cy)];
    for p in diamond.iter().chain(std::iter::once(&diamond[0])) {
        click_at(c, (p.0.round(), p.1.round())).await;
    }
    let both = settled_ok(c).await;
    let both_text = both["text"].as_str().unwrap().to_string();
    let diamond: Vec<(f64, f64)> = diamond.iter().map(|p| (p.0.round(), p.1.round())).collect();
    let diamond_line = line(&diamond, "clWhite");
    let want = format!("{EMPTY}LAYOUT\n{pentagon_line}\n{diamond_line}\nENDLAYOUT\n");
    assert_eq!(both_text, want);
    assert!(both["stems"].as_u64().unwrap() > 1, "{both}");
    let names = "return window.stlc.state.answer.layout.shapes.map((s) => s.name)";
    let colours = js(c, names).await;
    assert_eq!(colours, json!(["clGreen", "clWhite"]));
    shot(c, "draw-2-green-pentagon-white-diamond").await;

    // Recolour is its own action: select the diamond, pick red, Recolour.
    click(c, "[data-tool=select]").await;
    click_at(c, (cx, cy)).await;
    assert_eq!(selected(c).await, 1);
    click(c, "#colour option[value=clRed]").await;
    tokio::time::sleep(Duration::from_millis(200)).await;
    assert_eq!(text(c).await, both_text);
    click(c, "#recolour").await;
    let red = text(c).await;
    let want = both_text.replace("(clWhite) Polygon", "(clRed) Polygon");
    assert_eq!(red, want);

    // Shift while clicking a polygon's points: edges at 0 and 45 degrees.
    click(c, "[data-tool=Polygon]").await;
    click_at(c, (90.0, 145.0)).await;
    shift_click(c, (105.0, 143.0)).await;
    shift_click(c, (110.0, 152.0)).await;
    click_at(c, (90.0, 145.0)).await;
    let polygon = "\n(clRed) Polygon (90, 145), (105, 145), (111, 151)\nENDLAYOUT";
    assert_eq!(text(c).await, red.replace("\nENDLAYOUT", polygon));
}

/// Clicks at canvas point `p` with Shift held.
async fn shift_click(c: &Client, p: (f64, f64)) {
    press_along_shifted(c, &[screen_of(c, p.0, p.1).await], 0).await;
}

async fn edits_keep_the_rest_of_the_text(c: &Client) {
    let first = settled_ok(c).await;
    assert_eq!(first["text"], ONE_LINE);
    // No grid once there are shapes.
    assert_eq!(count(c, "#preview .grid line").await, 0);

    // Inside the small hole (40..55, 15..30), painted over the big green
    // RoundRect: the hole is picked, not the shape behind it; so it is
    // from just outside its edge (2 pixels right of x = 55).
    click(c, "[data-tool=select]").await;
    click_at(c, (47.0, 22.0)).await;
    assert_eq!(selected(c).await, 1);
    click_at(c, (100.0, 100.0)).await;
    assert_eq!(selected(c).await, 0);
    let (ex, ey) = screen_of(c, 55.0, 22.0).await;
    press_along(c, &[(ex + 2.0, ey)], 0).await;
    assert_eq!(selected(c).await, 1);
    shot(c, "draw-3-small-hole-selected").await;

    // Arrow right: one unit; Shift+Down: ten. Only that shape's numbers
    // change (Delphi's corners keep their order); every other byte stays.
    chord(c, &[], RIGHT).await;
    let once = text(c).await;
    let hole = "(55,30,40,15,4,4)";
    assert_eq!(once, ONE_LINE.replace(hole, "(56,30,41,15,4,4)"));
    chord(c, &[SHIFT], DOWN).await;
    let nudged = text(c).await;
    assert_eq!(nudged, ONE_LINE.replace(hole, "(56,40,41,25,4,4)"));

    // The pond dragged 10 right and 5 down with the mouse: its line keeps
    // its spelling and its comment.
    drag_at(c, (135.0, 160.0), (145.0, 165.0)).await;
    let moved = text(c).await;
    let comment = "  # a pond, Table 1's spelling, its colour in lower case\n";
    let pond = format!("(clgreen) Ellipse (130, 155), 30, 20{comment}");
    let was = format!("(clgreen) Ellipse (120, 150), 30, 20{comment}");
    assert_eq!(moved, nudged.replace(&was, &pond));
    assert_eq!(selected(c).await, 3);
    shot(c, "draw-4-one-line-moved").await;

    // Ctrl-D: a copy 10 units off, on the line after the pond's, selected.
    chord(c, &[CONTROL], 'd').await;
    let duplicated = text(c).await;
    let copy = format!("{pond}(clgreen) Ellipse (140, 165), 30, 20\n");
    assert_eq!(duplicated, moved.replace(&pond, &copy));
    assert_eq!(selected(c).await, 4);
    let shapes = js(c, "return window.stlc.state.answer.layout.shapes.length").await;
    assert_eq!(shapes, 5);
    shot(c, "draw-5-duplicated").await;

    // Delete removes just the copy's line.
    chord(c, &[], DELETE).await;
    assert_eq!(text(c).await, moved);

    // A new shape: a line before ENDLAYOUT, spelt as the shape before it
    // (here the pond's Table 1 spelling; in 2dtree.od the paper's, as
    // browser.rs's acceptance checks).
    click(c, "[data-tool=Ellipse]").await;
    click(c, "#colour option[value=clWhite]").await;
    drag_at(c, (100.0, 60.0), (160.0, 110.0)).await;
    let added = text(c).await;
    let ellipse = "\n\n(clWhite) Ellipse (100, 60), 60, 50\nENDLAYOUT";
    assert_eq!(added, moved.replace("\n\nENDLAYOUT", ellipse));
    assert_eq!(settled(c).await["ok"], true);
    shot(c, "draw-6-added-in-file-style").await;

    // Shift held while dragging a box: a circle.
    let a = screen_of(c, 140.0, 20.0).await;
    let b = screen_of(c, 170.0, 35.0).await;
    press_along_shifted(c, &[a, b], 120).await;
    let circle = "\n(clWhite) Ellipse (140, 20), 30, 30\nENDLAYOUT";
    assert_eq!(text(c).await, added.replace("\nENDLAYOUT", circle));
}

/// Presses at canvas point `a`, moves to `b` in one move and releases.
async fn drag_at(c: &Client, a: (f64, f64), b: (f64, f64)) {
    let (a, b) = (screen_of(c, a.0, a.1).await, screen_of(c, b.0, b.1).await);
    press_along(c, &[a, b], 120).await;
}
