//! The leaf control in a real Chromium (issue 33, item 6): on the leafy
//! `examples/oak3d.od` it lists `none` and the surfaces of the file's
//! `SURFACES` block; choosing `none` removes only the header's `P=L`,
//! choosing `L` writes it back, and each picture (the page's SVG export at
//! the 3D view's angles, the layout shown) is the CLI's for the new
//! text at those angles. Screenshots go to `tests/store/browser/leaves-*.png`.

use serde_json::{Value, json};

use super::browser_web::open_example;
use super::chromium::{answered, cli_line, js, on_served_page, same_bytes, shot};
use super::serve::example;

/// Chooses `name` in the leaf list as a user does (a `change` event); the
/// page's answer once its text is `want`.
async fn choose(c: &fantoccini::Client, name: &str, want: &str) -> Value {
    let script = format!(
        "const s = document.getElementById('leaf'); s.value = {name:?};
             s.dispatchEvent(new Event('change')); return 0;"
    );
    js(c, &script).await;
    answered(c, want, &format!("with leaf {name}")).await
}

/// The page's SVG export of its text at the 3D view's angles, and the
/// CLI's SVG of `text` at those angles.
async fn page_and_cli_svg(c: &fantoccini::Client, text: &str) -> (Vec<u8>, Vec<u8>) {
    let script = "const a = window.stlc;
         const view = a.view3d.angles();
         const e = await a.engine.export({source: a.editor.text(), kind: 'od', view}, 'svg');
         return [view, e.ok ? await e.blob.text() : ''];";
    let got = js(c, script).await;
    let view = format!("{},{}", got[0][0], got[0][1]);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("oak3d.od");
    std::fs::write(&file, text).unwrap();
    let want = cli_line(&format!(
        "render {} --view {view} --show-layout -f svg",
        file.display()
    ));
    (got[1].as_str().unwrap().as_bytes().to_vec(), want)
}

/// The leaf list's options and its value.
async fn leaf_list(c: &fantoccini::Client) -> Value {
    let script = "const s = document.getElementById('leaf');
         return [[...s.options].map((o) => o.value), s.value]";
    js(c, script).await
}

#[test]
fn the_leaf_control_rewrites_only_p_in_chromium() {
    on_served_page(async |c, _| {
        open_example(c, "oak3d.od").await;
        let leafy = example("oak3d.od");
        assert_eq!(leaf_list(c).await, json!([["none", "L"], "L"]));
        let shown = "return document.getElementById('leaf').offsetParent !== null";
        let for_an_od = "the leaf control is shown for an OD";
        assert!(js(c, shown).await == json!(true), "{for_an_od}");

        // none: the header line loses ` P=L`, nothing else changes.
        let header = "L=12(0.5) B=3(0.2) A=28 C=2 D=137.5 S=#5b3a1e..#3b5e2b P=L";
        assert!(leafy.contains(header));
        let bare = leafy.replace(header, header.strip_suffix(" P=L").unwrap());
        choose(c, "none", &bare).await;
        assert_eq!(leaf_list(c).await, json!([["none", "L"], "none"]));
        let (page, bare_svg) = page_and_cli_svg(c, &bare).await;
        same_bytes(&page, &bare_svg, "bare oak3d");
        shot(c, "leaves-01-none").await;

        // L again: the key comes back where it was, the text is the file's.
        choose(c, "L", &leafy).await;
        let (page, leafy_svg) = page_and_cli_svg(c, &leafy).await;
        same_bytes(&page, &leafy_svg, "leafy oak3d");
        // The leaves are in the picture: it has more to draw than the bare
        // oak's (same angles, the default ones: nothing turned the view).
        assert!(leafy_svg.len() > bare_svg.len() + 1000);
        shot(c, "leaves-02-leafy").await;

        // An .lsys has no leaf control.
        open_example(c, "abop-1.26.lsys").await;
        let hidden = "return document.getElementById('leaf').offsetParent === null";
        assert_eq!(js(c, hidden).await, json!(true));
    });
}
