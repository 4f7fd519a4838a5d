//! The New menu's thumbnails in a real Chromium (issue 33, item 6): the
//! Examples panel shows each template and example as a 96 x 96 picture
//! drawn by the page's engine, the CLI's PNG at `--size 96x96`; a click
//! opens that example. Screenshots go to `tests/store/browser/thumbs-*.png`.

use fantoccini::Client;
use serde_json::json;

use super::browser_web::{engine_export, examples, on_site};
use super::chromium::{
    cli_line, click, js, js_until, on_served_page, same_bytes, settled_until, shot,
};
use super::serve::example;

/// The PNG `stlc render examples/NAME --size 96x96 --show-layout` writes.
fn cli_thumb(name: &str) -> Vec<u8> {
    cli_line(&format!(
        "render examples/{name} --size 96x96 --show-layout -f png"
    ))
}

/// Waits (at most 60 s) until the thumbnail of `name` shows a 96 x 96
/// picture; then the engine's PNG for the request the thumbnail makes
/// (the page's CSP lets it show a blob URL, not read one back).
async fn thumb(c: &Client, name: &str) -> Vec<u8> {
    let shown = format!(
        "const url = window.stlc.state.thumbnails.get({name:?});
         const img = document.querySelector('[data-testid=\"thumb-{name}\"] img');
         return !!url && img.src === url && img.complete && img.naturalWidth === 96 && img.naturalHeight === 96;"
    );
    let drawn = js_until(c, &shown, 600, 100, |v| v == &json!(true)).await;
    if drawn != json!(true) {
        shot(c, "thumbs-timeout").await;
        panic!("the thumbnail of {name} was never drawn");
    }
    let kind = name.rsplit('.').next().unwrap();
    let request = json!({"source": example(name), "kind": kind, "size": [96, 96]});
    engine_export(c, &request, "png").await.unwrap()
}

/// Opens the panel: a tile per template and example, in the New menu's
/// order; the first ones drawn are the CLI's PNGs; a click opens one.
async fn thumbnails_open_examples(c: &Client, what: &str) {
    click(c, "#new-gallery summary").await;
    // The list comes from the engine: tiles once it is read.
    let tiles =
        "return [...document.querySelectorAll('#new-grid .thumb')].map((b) => b.dataset.testid)";
    let names = js_until(c, tiles, 200, 50, |v| v != &json!([])).await;
    let mut want = vec!["thumb-new.od".to_string(), "thumb-new.lsys".to_string()];
    want.extend(examples().iter().map(|n| format!("thumb-{n}")));
    assert_eq!(names, json!(want));
    for name in ["2dtree.od", "abop-1.24a.lsys"] {
        same_bytes(&thumb(c, name).await, &cli_thumb(name), name);
    }
    shot(c, &format!("thumbs-01-{what}")).await;
    click(c, "[data-testid='thumb-koch-snowflake.lsys']").await;
    let want = example("koch-snowflake.lsys");
    let opened = settled_until(c, 100, 50, |v| v["text"] == json!(want)).await;
    assert_eq!(opened["text"], json!(want));
    let open = js(c, "return document.getElementById('new-gallery').open").await;
    assert_eq!(open, json!(false));
}

#[test]
fn the_examples_panel_shows_the_cli_thumbnails_and_opens_one_in_chromium() {
    on_served_page(async |c, _| {
        thumbnails_open_examples(c, "serve").await;
    });
}

#[test]
fn the_static_site_shows_the_same_thumbnails_in_chromium() {
    on_site(async |c, _, _| thumbnails_open_examples(c, "web").await);
}
