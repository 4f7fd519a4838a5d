//! The static Tree Maker (`target/site`, built by the first line under the
//! README's `## On the web`) in a real headless Chromium, served by
//! `python3 -m http.server` on loopback: the pipeline runs in the page
//! (WebAssembly in a Web Worker), and its pictures and exports are the
//! CLI's bytes. Skips with a message where the wasm32-unknown-unknown
//! target or python3 is missing; Chromium as chromium.rs says.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::OnceLock;
use std::time::Duration;

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser_steps::{answer_svg, rewritten, settled_ok, shows_svg, type_into};
use super::chromium::{
    Browser, cli, cli_line, cli_svg_of, click, downloaded, drag, free_port, js, js_async, js_until,
    open, same_bytes, settled, settled_until, shot, wait_for_port,
};
use super::serve::example;
use crate::support::manifest_path;

/// The first line of the first code block under `## On the web` in the
/// README: the documented build command.
pub(super) fn build_command() -> String {
    let readme = std::fs::read_to_string(manifest_path("README.md")).unwrap();
    let section = readme.split("\n## On the web\n").nth(1);
    let section = section.expect("the README has a `## On the web` section");
    let block = section.split("```sh\n").nth(1);
    let block = block.expect("a ```sh block under `## On the web`");
    block.lines().next().unwrap().to_string()
}

/// `target/site`, built once per test run by the README's command; `None`
/// (after saying why, loudly) where the wasm target is not installed.
pub(super) fn site() -> Option<&'static Path> {
    static SITE: OnceLock<Option<PathBuf>> = OnceLock::new();
    SITE.get_or_init(|| {
        if !wasm_target() {
            return None;
        }
        let line = build_command();
        let out = Command::new("sh")
            .args(["-c", &line])
            .current_dir(manifest_path(""))
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "`{line}` failed: {err}");
        Some(manifest_path("target/site"))
    })
    .as_deref()
}

/// Whether the wasm32-unknown-unknown target is installed (after saying
/// loudly that the web tests skip, where it is not).
pub(super) fn wasm_target() -> bool {
    let sysroot = Command::new("rustc").args(["--print", "sysroot"]).output();
    let sysroot = String::from_utf8(sysroot.expect("rustc --print sysroot").stdout).unwrap();
    let target = Path::new(sysroot.trim()).join("lib/rustlib/wasm32-unknown-unknown");
    if !target.is_dir() {
        eprintln!(
            "SKIPPED the web tests: the wasm32-unknown-unknown target is not installed \
             (rustup target add wasm32-unknown-unknown; .ci/run does where it can)"
        );
    }
    target.is_dir()
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
        let port = free_port();
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
        wait_for_port(port);
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
pub(super) async fn engine_export(
    c: &Client,
    request: &Value,
    format: &str,
) -> Result<Vec<u8>, Value> {
    let script = "const [request, format, done] = arguments;
             window.stlc.engine.export(request, format).then(async (a) => {
               if (!a.ok) { done({failed: a}); return; }
               const b = new Uint8Array(await a.blob.arrayBuffer());
               let s = '';
               for (let i = 0; i < b.length; i += 0x8000) s += String.fromCharCode(...b.subarray(i, i + 0x8000));
               done({bytes: s});
             }, (e) => done({failed: String(e)}));";
    let v = js_async(c, script, vec![request.clone(), json!(format)]).await;
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
    on_site(async |c, _, browser| {
        let downloads = browser.tmp.join("downloads");
        let first = settled_ok(c).await;
        // The page opens on the paper's 2DTree, drawn as `stlc render
        // --show-layout -f svg` draws it.
        let paper = example("2dtree.od");
        assert_eq!(first["text"], paper);
        let cli_svg = cli(&["render", "examples/2dtree.od", "--show-layout", "-f", "svg"]);
        shows_svg(c, &cli_svg, "the first picture").await;
        shot(c, "web-01-2dtree").await;

        // A white rectangle drawn with the mouse: the text gets its line,
        // the tree regrows around it, and the BED is `stlc compile`'s for
        // the new text.
        let before = first["stems"].as_u64().unwrap();
        click(c, "[data-tool=Rectangle]").await;
        click(c, "#colour option[value=clWhite]").await;
        drag(c, (100.0, 60.0), (160.0, 110.0)).await;
        let holed = settled_ok(c).await;
        let text = holed["text"].as_str().unwrap().to_string();
        let hole = "\n(clWhite)< Rectangle (100,60,160,110)>\nENDLAYOUT";
        assert_eq!(text, paper.replace("\nENDLAYOUT", hole));
        let after = holed["stems"].as_u64().unwrap();
        let fewer = format!("the hole takes stems away: {before} -> {after}");
        assert!(after < before, "{fewer}");
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("2dtree.od");
        std::fs::write(&file, &text).unwrap();
        let path = file.to_str().unwrap();
        let bed = js(c, "return window.stlc.state.answer.bed").await;
        let cli_bed = cli(&["compile", path]);
        let bed = bed.as_str().unwrap().as_bytes();
        same_bytes(bed, &cli_bed, "the regrown BED");
        shot(c, "web-02-rectangle").await;

        // The SVG and BED buttons download the CLI's bytes.
        click(c, "#export-svg").await;
        let cli_svg = cli(&["render", path, "--show-layout", "-f", "svg"]);
        let svg = downloaded(&downloads, "2dtree.svg").await;
        same_bytes(&svg, &cli_svg, "the SVG download");
        click(c, "#export-bed").await;
        let bed = downloaded(&downloads, "2dtree.bed").await;
        same_bytes(&bed, &cli_bed, "the BED download");

        // Unsaved work survives a reload: kept in the browser's storage,
        // offered back (never applied by itself), restored on request.
        let _ = js(c, "setTimeout(() => location.reload(), 0); return true").await;
        tokio::time::sleep(Duration::from_millis(300)).await;
        let _ = c.accept_alert().await;
        let shown = "return !!(window.stlc && window.stlc.state.answer) && !document.getElementById('notice').hidden";
        let offered = js_until(c, shown, 200, 50, |v| v == &json!(true)).await;
        assert_eq!(offered, json!(true), "the unsaved edits are offered back");
        assert_eq!(settled(c).await["text"], json!(paper));
        click(c, "[data-testid=restore-draft]").await;
        assert_eq!(settled(c).await["text"], json!(text));

        // Save downloads the text; Open… reads a file from disk.
        click(c, "[data-testid=save]").await;
        let saved = downloaded(&downloads, "2dtree.od").await;
        same_bytes(&saved, text.as_bytes(), "the saved text");
        let koch = manifest_path("examples/koch-snowflake.lsys");
        open(c, &koch).await;
        settled_ok(c).await;
        let cli_svg = cli_line(&format!("render {} --show-layout -f svg", koch.display()));
        shows_svg(c, &cli_svg, "the opened file's picture").await;
        // Words, generation by generation, from the module: the Koch
        // snowflake's axiom `F--F--F` (7 symbols) and first word: each F
        // becomes `F+F--F+F`, 3 x 8 + 4 = 28 symbols.
        js(c, "document.getElementById('words').open = true").await;
        let listed =
            "return [...document.querySelectorAll('#word-list li')].map((l) => l.textContent)";
        let two = |v: &Value| v.as_array().is_some_and(|w| w.len() >= 2);
        let words = js_until(c, listed, 100, 50, two).await;
        assert_eq!(words[0], json!("F--F--F (7)"), "{words}");
        let first = json!("F+F--F+F--F+F--F+F--F+F--F+F (28)");
        assert_eq!(words[1], first, "{words}");
        shot(c, "web-03-words").await;

        every_example(c).await;
        newer_edit_ends_older_work(c).await;
    });
}

/// Every example, each growth order of an OD: the engine's SVG and BED
/// exports (the request the page's buttons send) are the CLI's bytes, its
/// PNG within 1 of 255 per channel.
async fn every_example(c: &Client) {
    let mut worst = 0;
    for name in examples() {
        let path = format!("examples/{name}");
        let source = example(&name);
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
                request["growth"] = json!(o);
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
/// an AbortError) and the newer one answers (the long work: a stochastic
/// system with no level of detail at depth 14, many seconds; at depth 2
/// it draws 1 + (4^2 - 1) / 3 = 6 segments).
async fn newer_edit_ends_older_work(c: &Client) {
    let source = manifest_path("tests/cases/render/slow-stochastic.lsys");
    let source = std::fs::read_to_string(source).unwrap();
    let script = "const [source, done] = arguments;
             const engine = window.stlc.engine;
             const old = new AbortController();
             const slow = engine.render({source, kind: 'lsys', depth: 14}, {signal: old.signal})
               .then(() => 'answered', (e) => e.name);
             setTimeout(async () => {
               old.abort();
               const fast = await engine.render({source, kind: 'lsys', depth: 2});
               done({slow: await slow, fast: fast.ok, stems: fast.stems});
             }, 200);";
    let v = js_async(c, script, vec![json!(source)]).await;
    assert_eq!(v["slow"], "AbortError", "{v}");
    assert_eq!(v["fast"], true, "{v}");
    assert_eq!(v["stems"], "6", "{v}");
}

/// The page's share link for its document as it is now.
pub(super) async fn share_link(c: &Client) -> String {
    let script =
        "const done = arguments[0]; window.stlc.shareLink().then(done, (e) => done(String(e)));";
    let v = js_async(c, script, vec![]).await;
    v.as_str().unwrap().to_string()
}

/// Opens the example `name` from the New menu and waits for its picture.
pub(super) async fn open_example(c: &Client, name: &str) -> Value {
    let text = example(name);
    super::browser_steps::choose_new(c, name).await;
    let v = settled_until(c, 100, 50, |v| v["text"] == json!(text)).await;
    assert_eq!(v["text"], json!(text), "the page never opened {name}: {v}");
    v
}

/// The site, a browser on it showing its first picture, and `body` run
/// with the session; then the site's server, still serving (for a fresh
/// browser to open a link to it). `None` (skip) where the site or Chromium
/// is missing, as the other tests here do.
pub fn on_site<F>(body: F) -> Option<Static>
where
    F: AsyncFnOnce(&Client, &Static, &Browser),
{
    let tmp = tempfile::tempdir().unwrap();
    let (_, server, browser) = start(tmp.path())?;
    browser.rt.block_on(async {
        let c = browser.connect().await;
        c.goto(&server.url).await.unwrap();
        settled(&c).await;
        body(&c, &server, &browser).await;
        let _ = c.close().await;
    });
    Some(server)
}

/// Opens `link` in a fresh browser profile: the page shows `text` and
/// draws `svg` (the bytes the CLI writes for it); `shot` names its
/// screenshot.
pub fn opens_in_a_fresh_profile(link: &str, text: &str, svg: &[u8], shot_name: &str) {
    let fresh_tmp = tempfile::tempdir().unwrap();
    let Some(fresh) = Browser::start(fresh_tmp.path()) else {
        return;
    };
    fresh.rt.block_on(async {
        let c = fresh.connect().await;
        c.goto(link).await.unwrap();
        assert_eq!(settled(&c).await["text"], json!(text));
        shows_svg(&c, svg, "the SVG from the link").await;
        shot(&c, shot_name).await;
        let _ = c.close().await;
    });
}

/// A share link carries the tree, its growth order and its seed: opened in
/// a fresh browser profile it shows the same text and the same SVG bytes
/// (the CLI's). docs/web.md's table of link lengths is what the page
/// makes for every example.
#[test]
fn a_share_link_restores_the_tree_in_a_fresh_profile_in_chromium() {
    let (mut link, mut text, mut svg) = (String::new(), String::new(), String::new());
    let Some(_site) = on_site(async |c, server, _| {
        open_example(c, "grove.od").await;
        // Depth-first, seed 7: keys the controls write into the text.
        click(c, "#growth option[value=dfs]").await;
        type_into(c, "seed", "7").await;
        let both = |t: &str| t.contains("O=dfs") && t.contains("V=7");
        let v = settled_until(c, 100, 50, |v| both(v["text"].as_str().unwrap())).await;
        text = v["text"].as_str().unwrap().to_string();
        assert!(both(&text), "{text}");
        svg = answer_svg(c).await;
        link = share_link(c).await;
        let base = format!("{}#k=od&n=grove.od&s=", server.url);
        assert!(link.starts_with(&base), "{link}");
        link_lengths(c).await;
    }) else {
        return;
    };
    // The CLI draws the same text alike.
    let cli = cli_svg_of("grove.od", &text);
    same_bytes(svg.as_bytes(), &cli, "the shared grove");
    opens_in_a_fresh_profile(&link, &text, svg.as_bytes(), "web-03-shared");
}

/// docs/web.md's table of share links: for every example, the bytes of
/// its text and the characters its link adds to the page's address, as
/// the page makes them.
async fn link_lengths(c: &Client) {
    let doc = std::fs::read_to_string(manifest_path("docs/web.md")).unwrap();
    let mut rows = Vec::new();
    for name in examples() {
        let text = example(&name);
        let kind = name.rsplit('.').next().unwrap();
        let script = "const [name, kind, text, done] = arguments;
                 import('./share.js').then((m) => m.toFragment({name, kind, text})).then((f) => done(f.length));";
        let v = js_async(c, script, vec![json!(name), json!(kind), json!(text)]).await;
        let (bytes, link) = (text.len(), v.as_u64().unwrap());
        rows.push(format!("| `{name}` | {bytes} | {link} |"));
    }
    let missing: Vec<&String> = rows.iter().filter(|r| !doc.contains(r.as_str())).collect();
    let table = rows.join("\n");
    let lacks = format!("docs/web.md lacks the rows {missing:#?}; the whole table:\n{table}");
    assert!(missing.is_empty(), "{lacks}");
}

/// `<stl-tree>` draws the CLI's SVG for an OD (its text inline, with
/// growth and seed attributes), a BED (`src=`) and an `.lsys` (a depth
/// attribute), and shows the diagnostics of a wrong text; the gallery page
/// draws every example as `stlc render -f svg` does.
#[test]
fn stl_tree_elements_draw_the_cli_svgs_in_chromium() {
    let (grove, koch) = (example("grove.od"), example("koch-snowflake.lsys"));
    let page = format!(
        "<!doctype html><meta charset=utf-8><script type=module src=stl-tree.js></script>\n\
         <stl-tree id=od growth=dfs seed=7><script type=\"text/stl\">\n{grove}</script></stl-tree>\n\
         <stl-tree id=bed src=\"examples/paper-worked.bed\"></stl-tree>\n\
         <stl-tree id=lsys depth=3><script type=\"text/stl\">\n{koch}</script></stl-tree>\n\
         <stl-tree id=bad kind=od><script type=\"text/stl\">\nT (1, 2) L=10(0) B=1(0)\nRULE\nR1: [+F][-F]\nSEED\nR2\nENDSEED\n</script></stl-tree>\n"
    );
    on_site(async |c, server, _| {
        let files = [("elements-test.html", page)];
        let states = super::browser_page::elements(c, server, &files).await;
        assert_eq!(states, json!(["drawn", "drawn", "drawn", "error"]));
        for (id, line) in [
            ("od", "render examples/grove.od --growth dfs --seed 7"),
            ("bed", "render examples/paper-worked.bed"),
            ("lsys", "render examples/koch-snowflake.lsys --depth 3"),
        ] {
            let script = format!(
                "const e = document.getElementById('{id}');
                 return [e.svg, e.querySelector(':scope > svg') !== null];"
            );
            let v = js(c, &script).await;
            assert_eq!(v[1], true, "{id}: no inline <svg> child");
            let cli = cli_line(&format!("{line} -f svg"));
            same_bytes(v[0].as_str().unwrap().as_bytes(), &cli, id);
        }
        let error = super::browser_steps::text_of(c, "#bad pre.stl-tree-error").await;
        let unknown = "line 5, column 1: error: unknown rule `R2` (no rule has this name)";
        assert_eq!(error.lines().next().unwrap(), unknown);
        shot(c, "web-04-elements").await;

        // The gallery: every example, drawn live.
        let states =
            "return [...document.querySelectorAll('stl-tree')].map((e) => e.dataset.state)";
        c.goto(&format!("{}gallery.html", server.url))
            .await
            .unwrap();
        let names = examples();
        js_until(c, states, 600, 50, |s| {
            let s = s.as_array().unwrap();
            s.len() == names.len() && s.iter().all(|x| x == "drawn")
        })
        .await;
        let drawn = js(c, "return [...document.querySelectorAll('stl-tree')].map((e) => [e.getAttribute('src'), e.svg])").await;
        let drawn = drawn.as_array().unwrap();
        assert_eq!(drawn.len(), names.len());
        for (d, name) in drawn.iter().zip(&names) {
            let path = format!("examples/{name}");
            assert_eq!(d[0], json!(path));
            let got = d[1].as_str().unwrap_or_else(|| panic!("{name} not drawn"));
            same_bytes(got.as_bytes(), &cli(&["render", &path, "-f", "svg"]), name);
        }
        shot(c, "web-05-gallery").await;
    });
}

/// The page's own "edit to picture" time (ms) of `runs` edits to the
/// text it shows: each adds a different comment line, so every one is
/// rendered afresh.
async fn edit_times(c: &Client, runs: usize) -> Vec<f64> {
    let base = settled(c).await["text"].as_str().unwrap().to_string();
    let mut times = Vec::new();
    for i in 0..runs {
        rewritten(c, &format!("{base}# edit {i}\n")).await;
        let last = "const t = window.stlc.state.timings; return t[t.length - 1]";
        let t = js(c, last).await;
        times.push(t.as_f64().unwrap());
    }
    times
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Not a test: the measurement `benches/web.sh` runs (docs/web.md). In one
/// browser, side by side: edit to picture on 2dtree, holes and grove in
/// `stlc serve` (STLC_SERVE_BIN, a release build) and in the static site,
/// STLC_WEB_RUNS edits each (default 15), medians; and page load to first
/// picture on the static site (ms from navigation start), first load and
/// the median of ten reloads.
#[test]
#[ignore = "a measurement: benches/web.sh runs it"]
fn measure_the_static_site_against_stlc_serve() {
    let tmp = tempfile::tempdir().unwrap();
    let Some((_, site, browser)) = start(tmp.path()) else {
        return;
    };
    let runs: usize = std::env::var("STLC_WEB_RUNS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(15);
    browser.rt.block_on(async {
        let c = browser.connect().await;
        let mut loads = Vec::new();
        for _ in 0..11 {
            c.goto(&site.url).await.unwrap();
            let mut t = Value::Null;
            while t.is_null() {
                tokio::time::sleep(Duration::from_millis(20)).await;
                t = js(&c, "return window.stlc ? window.stlc.firstPicture ?? null : null").await;
            }
            loads.push(t.as_f64().unwrap());
        }
        println!(
            "page load to first picture (2dtree.od): first {:.0} ms, median of the next 10 {:.0} ms",
            loads[0],
            median(loads[1..].to_vec())
        );
        println!("| example | stlc serve, median ms | static site (wasm), median ms | ratio |");
        println!("| --- | --- | --- | --- |");
        for name in ["2dtree.od", "holes.od", "grove.od"] {
            let path = manifest_path(format!("examples/{name}"));
            let serve = match std::env::var_os("STLC_SERVE_BIN") {
                Some(bin) => super::serve::Server::start_binary(Path::new(&bin), &[path.to_str().unwrap()]),
                None => super::serve::Server::start(&[path.to_str().unwrap()]),
            };
            c.goto(&serve.url).await.unwrap();
            settled(&c).await;
            edit_times(&c, 2).await; // warm-up
            let served = median(edit_times(&c, runs).await);
            c.goto(&site.url).await.unwrap();
            settled(&c).await;
            open_example(&c, name).await;
            edit_times(&c, 2).await;
            let web = median(edit_times(&c, runs).await);
            println!("| `{name}` | {served:.1} | {web:.1} | {:.2} |", web / served);
        }
        let _ = c.close().await;
    });
}
