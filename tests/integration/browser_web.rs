//! The static Tree Maker (`target/site`, built by the first line under the
//! README's `## On the web`) in a real headless Chromium, served by
//! `python3 -m http.server` on loopback: the pipeline runs in the page
//! (WebAssembly in a Web Worker), and its pictures and exports are the
//! CLI's bytes. Skips with a message where the wasm32-unknown-unknown
//! target or python3 is missing; Chromium as browser.rs does (a failure
//! under CI). Screenshots go to `tests/store/browser/`.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::OnceLock;
use std::time::Duration;

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser::{Browser, cli, click, downloaded, drag, js, same_bytes, settled, shot};
use crate::support::manifest_path;

/// The first line of the first code block under `## On the web` in the
/// README: the documented build command.
pub(super) fn build_command() -> String {
    let readme = std::fs::read_to_string(manifest_path("README.md")).unwrap();
    let section = readme
        .split("\n## On the web\n")
        .nth(1)
        .expect("the README has a `## On the web` section");
    let block = section
        .split("```sh\n")
        .nth(1)
        .expect("a ```sh block under `## On the web`");
    block.lines().next().unwrap().to_string()
}

/// `target/site`, built once per test run by the README's command; `None`
/// (after saying why, loudly) where the wasm target is not installed.
pub(super) fn site() -> Option<&'static Path> {
    static SITE: OnceLock<Option<PathBuf>> = OnceLock::new();
    SITE.get_or_init(|| {
        let sysroot = Command::new("rustc")
            .args(["--print", "sysroot"])
            .output()
            .expect("rustc --print sysroot");
        let sysroot = String::from_utf8(sysroot.stdout).unwrap();
        let target = Path::new(sysroot.trim()).join("lib/rustlib/wasm32-unknown-unknown");
        if !target.is_dir() {
            eprintln!(
                "SKIPPED the web tests: the wasm32-unknown-unknown target is not installed \
                 (rustup target add wasm32-unknown-unknown; .ci/run does where it can)"
            );
            return None;
        }
        let line = build_command();
        let out = Command::new("sh")
            .args(["-c", &line])
            .current_dir(manifest_path(""))
            .stdin(Stdio::null())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "`{line}` failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        Some(manifest_path("target/site"))
    })
    .as_deref()
}

/// `python3 -m http.server` serving a folder on loopback, in its own
/// process group, ended with it.
pub(super) struct Static {
    child: Child,
    pub url: String,
}

impl Static {
    /// `None` (after saying why) where python3 is missing.
    pub(super) fn start(dir: &Path) -> Option<Static> {
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .unwrap()
            .port();
        let Ok(child) = Command::new("python3")
            .args(["-m", "http.server", "--bind", "127.0.0.1", "--directory"])
            .arg(dir)
            .arg(port.to_string())
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .process_group(0)
            .spawn()
        else {
            eprintln!("SKIPPED the web test: python3 is not installed (it serves the site)");
            return None;
        };
        for _ in 0..200 {
            if std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() {
                break;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        Some(Static {
            child,
            url: format!("http://127.0.0.1:{port}/"),
        })
    }
}

impl Drop for Static {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The site, a server for it and a browser; `None` where one is missing.
pub(super) fn start(tmp: &Path) -> Option<(&'static Path, Static, Browser)> {
    let site = site()?;
    let browser = Browser::start(tmp)?;
    let server = Static::start(site)?;
    Some((site, server, browser))
}

/// Every example file's name, sorted.
pub(super) fn examples() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(manifest_path("examples"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".od") || n.ends_with(".bed") || n.ends_with(".lsys"))
        .collect();
    names.sort();
    names
}

/// What the page's engine exports for `request` in `format`: the bytes,
/// or the failed answer's JSON.
async fn engine_export(c: &Client, request: &Value, format: &str) -> Result<Vec<u8>, Value> {
    let v = c
        .execute_async(
            "const [request, format, done] = arguments;
             window.stlc.engine.export(request, format).then(async (a) => {
               if (!a.ok) { done({failed: a}); return; }
               const b = new Uint8Array(await a.blob.arrayBuffer());
               let s = '';
               for (let i = 0; i < b.length; i += 0x8000) s += String.fromCharCode(...b.subarray(i, i + 0x8000));
               done({bytes: s});
             }, (e) => done({failed: String(e)}));",
            vec![request.clone(), json!(format)],
        )
        .await
        .unwrap();
    match v["bytes"].as_str() {
        // One character a byte (0 to 255).
        Some(s) => Ok(s.chars().map(|ch| ch as u32 as u8).collect()),
        None => Err(v["failed"].clone()),
    }
}

/// The largest difference of one channel of one pixel between two PNGs of
/// the same size.
fn png_difference(a: &[u8], b: &[u8], what: &str) -> u8 {
    let a = tiny_skia::Pixmap::decode_png(a).unwrap();
    let b = tiny_skia::Pixmap::decode_png(b).unwrap();
    assert_eq!((a.width(), a.height()), (b.width(), b.height()), "{what}");
    a.data()
        .iter()
        .zip(b.data())
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0)
}

#[test]
fn the_static_site_draws_regrows_and_exports_the_cli_bytes_in_chromium() {
    let tmp = tempfile::tempdir().unwrap();
    let Some((_, server, browser)) = start(tmp.path()) else {
        return;
    };
    let downloads = browser.tmp.join("downloads");
    browser.rt.block_on(async {
        let c = browser.connect().await;
        c.goto(&server.url).await.unwrap();
        let first = settled(&c).await;
        assert_eq!(first["ok"], true, "{first}");
        // The page opens on the paper's 2DTree, drawn as `stlc render
        // --show-layout -f svg` draws it.
        let paper = std::fs::read_to_string(manifest_path("examples/2dtree.od")).unwrap();
        assert_eq!(first["text"], paper);
        let svg = js(&c, "return window.stlc.state.answer.svg").await;
        same_bytes(
            svg.as_str().unwrap().as_bytes(),
            &cli(&["render", "examples/2dtree.od", "--show-layout", "-f", "svg"]),
            "the first picture",
        );
        shot(&c, "web-01-2dtree").await;

        // A white rectangle drawn with the mouse: the text gets its line,
        // the tree regrows around it, and the BED is `stlc compile`'s for
        // the new text.
        let before = first["stems"].as_u64().unwrap();
        click(&c, "[data-tool=Rectangle]").await;
        click(&c, "#colour option[value=clWhite]").await;
        drag(&c, (100.0, 60.0), (160.0, 110.0)).await;
        let holed = settled(&c).await;
        assert_eq!(holed["ok"], true, "{holed}");
        let text = holed["text"].as_str().unwrap().to_string();
        assert_eq!(
            text,
            paper.replace(
                "\nENDLAYOUT",
                "\n(clWhite)< Rectangle (100,60,160,110)>\nENDLAYOUT"
            )
        );
        let after = holed["stems"].as_u64().unwrap();
        assert!(
            after < before,
            "the hole takes stems away: {before} -> {after}"
        );
        let file = tmp.path().join("2dtree.od");
        std::fs::write(&file, &text).unwrap();
        let path = file.to_str().unwrap();
        let bed = js(&c, "return window.stlc.state.answer.bed").await;
        same_bytes(
            bed.as_str().unwrap().as_bytes(),
            &cli(&["compile", path]),
            "the regrown BED",
        );
        shot(&c, "web-02-rectangle").await;

        // The SVG and BED buttons download the CLI's bytes.
        click(&c, "#export-svg").await;
        same_bytes(
            &downloaded(&downloads, "2dtree.svg").await,
            &cli(&["render", path, "--show-layout", "-f", "svg"]),
            "the SVG download",
        );
        click(&c, "#export-bed").await;
        same_bytes(
            &downloaded(&downloads, "2dtree.bed").await,
            &cli(&["compile", path]),
            "the BED download",
        );

        every_example(&c).await;
        newer_edit_ends_older_work(&c).await;
        let _ = c.close().await;
    });
}

/// Every example, each growth order of an OD: the engine's SVG and BED
/// exports (the request the page's buttons send) are the CLI's bytes, its
/// PNG within 1 of 255 per channel.
async fn every_example(c: &Client) {
    let mut worst = 0;
    for name in examples() {
        let path = format!("examples/{name}");
        let source = std::fs::read_to_string(manifest_path(&path)).unwrap();
        let kind = name.rsplit('.').next().unwrap();
        let orders: &[Option<&str>] = if kind == "od" {
            &[Some("bfs"), Some("dfs")]
        } else {
            &[None]
        };
        for order in orders {
            let mut request = json!({"source": source, "kind": kind, "show_layout": true});
            let mut flags = vec![];
            if let Some(o) = order {
                request["strategy"] = json!(o);
                flags = vec!["--growth", o];
            }
            let what = format!("{name} {order:?}");
            let mut args = vec!["render", &path, "--show-layout", "-f", "svg"];
            args.extend(&flags);
            let svg = engine_export(c, &request, "svg").await;
            same_bytes(&svg.unwrap(), &cli(&args), &format!("{what} SVG"));
            args[4] = "png";
            let png = engine_export(c, &request, "png").await.unwrap();
            let d = png_difference(&png, &cli(&args), &what);
            assert!(d <= 1, "{what}: a pixel differs by {d} of 255");
            worst = worst.max(d);
            let bed = engine_export(c, &request, "bed").await;
            if kind == "od" {
                let mut args = vec!["compile", &path];
                args.extend(&flags);
                same_bytes(&bed.unwrap(), &cli(&args), &format!("{what} BED"));
            } else {
                let failed = bed.unwrap_err();
                assert_eq!(failed["ok"], false, "{what}: {failed}");
            }
        }
    }
    eprintln!("the wasm PNGs differ from the CLI's by at most {worst} of 255 per channel");
}

/// A render a newer one supersedes ends at once (its promise rejects with
/// an AbortError) and the newer one answers.
async fn newer_edit_ends_older_work(c: &Client) {
    let source = std::fs::read_to_string(manifest_path("examples/abop-1.27.lsys")).unwrap();
    let v = c
        .execute_async(
            "const [source, done] = arguments;
             const engine = window.stlc.engine;
             const old = new AbortController();
             const slow = engine.render({source, kind: 'lsys', depth: 14}, {signal: old.signal})
               .then(() => 'answered', (e) => e.name);
             setTimeout(async () => {
               old.abort();
               const fast = await engine.render({source, kind: 'lsys', depth: 2});
               done({slow: await slow, fast: fast.ok, stems: fast.stems});
             }, 200);",
            vec![json!(source)],
        )
        .await
        .unwrap();
    assert_eq!(v["slow"], "AbortError", "{v}");
    assert_eq!(v["fast"], true, "{v}");
}
