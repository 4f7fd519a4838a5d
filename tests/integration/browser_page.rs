//! The static Tree Maker's own behaviour (docs/web.md) in Chromium, one
//! behaviour a test, on browser_web.rs's site and helpers: share links
//! that inflate past the input limit, and the trip-ups of new users.
//! Screenshots go to `tests/store/browser/`.

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser::{js, settled, shot};
use super::browser_web::{Static, start};
use crate::browser::Browser;

/// The site, a browser on it showing its first picture, and `body` run
/// with the session; skips (returns) where the site or Chromium is
/// missing, as browser_web.rs's tests do.
fn on_site<F>(body: F)
where
    F: AsyncFnOnce(&Client, &Static, &Browser),
{
    let tmp = tempfile::tempdir().unwrap();
    let Some((_, server, browser)) = start(tmp.path()) else {
        return;
    };
    browser.rt.block_on(async {
        let c = browser.connect().await;
        c.goto(&server.url).await.unwrap();
        settled(&c).await;
        body(&c, &server, &browser).await;
        let _ = c.close().await;
    });
}

/// A share-link fragment whose text is `mib` MiB of zero bytes (valid
/// UTF-8), deflated in the page (1 MiB chunks streamed through
/// CompressionStream, so the page never holds the whole text).
async fn bomb_fragment(c: &Client, mib: u32) -> String {
    let v = c
        .execute_async(
            "const [mib, done] = arguments;
             const zeros = new Uint8Array(1 << 20);
             let n = 0;
             const src = new ReadableStream({ pull(ctl) { if (n++ < mib) ctl.enqueue(zeros); else ctl.close(); } });
             new Response(src.pipeThrough(new CompressionStream('deflate-raw'))).arrayBuffer().then((buf) => {
               const b = new Uint8Array(buf);
               let s = '';
               for (let i = 0; i < b.length; i += 0x8000) s += String.fromCharCode(...b.subarray(i, i + 0x8000));
               done('#k=od&n=bomb.od&s=' + btoa(s).replace(/\\+/g, '-').replace(/\\//g, '_').replace(/=+$/, ''));
             }, (e) => done(String(e)));",
            vec![json!(mib)],
        )
        .await
        .unwrap();
    v.as_str().unwrap().to_string()
}

/// Issue 36, 6: a share link of 3 x 10^8 bytes (286 MiB of text in under
/// 400 KB of link) crashed the tab, inflated with no cap. It inflates to
/// at most the input limit (64 MiB) and the page says the link is too
/// large, in the editor, and goes on working.
#[test]
fn a_share_link_that_inflates_past_the_input_limit_is_refused_in_chromium() {
    on_site(async |c, server, _| {
        let fragment = bomb_fragment(c, 286).await;
        assert!(fragment.starts_with("#k=od&n=bomb.od&s="), "{fragment}");
        assert!(fragment.len() < 400_000, "{} characters", fragment.len());
        // Opened afresh, as a link is.
        c.goto("about:blank").await.unwrap();
        c.goto(&format!("{}{fragment}", server.url)).await.unwrap();
        let v: Value = settled(c).await;
        let text = v["text"].as_str().unwrap();
        assert!(
            text.starts_with("# This share link's text is too large")
                && text.contains("the input limit of 67108864 bytes (64 MiB)"),
            "{text}"
        );
        assert_eq!(js(c, "return document.title.length > 0").await, json!(true));
        shot(c, "page-share-too-large").await;
    });
}

/// Sets the Export panel's inputs (`[id, value]`), as typing does, and
/// returns the command the panel shows once it has caught up (with
/// `want` in it).
async fn export_command(c: &Client, inputs: &[(&str, &str)], want: &str) -> String {
    if js(c, "return document.getElementById('export-options').open").await != json!(true) {
        super::browser::click(c, "#export-options summary").await;
    }
    for (id, value) in inputs {
        c.execute(
            "const [id, v] = arguments; const e = document.getElementById(id);
             e.value = v; e.dispatchEvent(new Event('input'));",
            vec![json!(id), json!(value)],
        )
        .await
        .unwrap();
    }
    let mut shown = String::new();
    for _ in 0..200 {
        shown = js(
            c,
            "return document.getElementById('export-cli').textContent",
        )
        .await
        .as_str()
        .unwrap()
        .to_string();
        if shown.contains(want) {
            return shown;
        }
        tokio::time::sleep(std::time::Duration::from_millis(50)).await;
    }
    panic!("the Export panel never showed `{want}`: {shown}");
}

/// Issue 36, 11: "4000 x auto", as the placeholders invite, exported the
/// default size and showed no `--size`. A width alone exports at that
/// width with the height from the picture's aspect (successors.od is
/// 800 x 653 at the default size: 1600 wide is 1306 high), the command
/// shown has that `--size` and writes the same bytes; a height alone
/// likewise.
#[test]
fn an_export_with_only_a_width_keeps_the_aspect_in_chromium() {
    on_site(async |c, _, browser| {
        let v = super::browser_web::open_example(c, "successors.od").await;
        assert_eq!(v["ok"], json!(true));
        let svg = js(c, "return window.stlc.state.answer.svg.slice(0, 120)").await;
        assert!(
            svg.as_str()
                .unwrap()
                .contains("width=\"800\" height=\"653\""),
            "{svg}"
        );
        let want = "stlc render successors.od --size 1600x1306 --show-layout -o successors.png";
        let shown = export_command(c, &[("export-w", "1600"), ("export-h", "")], want).await;
        shot(c, "page-export-width-only").await;
        assert!(
            shown.contains("--size 1600x1306 --show-layout -o successors.svg"),
            "{shown}"
        );
        super::browser::click(c, "#export-png").await;
        let got =
            super::browser::downloaded(&browser.tmp.join("downloads"), "successors.png").await;
        let od = crate::support::manifest_path("examples/successors.od");
        let cli = super::browser::cli(&[
            "render",
            od.to_str().unwrap(),
            "--size",
            "1600x1306",
            "--show-layout",
        ]);
        super::browser::same_bytes(&got, &cli, "the width-only export");
        // A height alone: the width from the aspect (653 high is 800 wide).
        export_command(
            c,
            &[("export-w", ""), ("export-h", "653")],
            "--size 800x653 --show-layout",
        )
        .await;
    });
}
