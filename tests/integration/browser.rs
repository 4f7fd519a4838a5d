//! `stlc serve` in a real headless Chromium, driven over WebDriver
//! (chromedriver, fantoccini): type an OD, draw a rectangle with the
//! mouse, switch bfs/dfs, type an error, replay growth, save. Skips with a
//! message where `chromium` or `chromedriver` is not installed (`.ci/run`
//! installs Debian's packages). Screenshots go to `tests/store/browser/`.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use fantoccini::actions::{InputSource, MOUSE_BUTTON_LEFT, MouseActions, PointerAction};
use fantoccini::{Client, ClientBuilder, Locator};
use serde_json::{Value, json};

use super::serve::Server;
use crate::support::manifest_path;

/// A program on the PATH.
fn which(name: &str) -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join(name))
            .find(|p| p.is_file())
    })
}

/// chromedriver in its own process group, ended with the group (so a
/// Chromium it started goes too).
struct Driver {
    child: Child,
    port: u16,
}

impl Driver {
    fn start(driver: &Path, tmp: &Path) -> Driver {
        // A free port, chosen here: chromedriver's own messages are not
        // parsed (they go nowhere, so it never blocks on a full pipe).
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .unwrap()
            .port();
        let child = Command::new(driver)
            .arg(format!("--port={port}"))
            .env("TMPDIR", tmp)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .process_group(0)
            .spawn()
            .expect("start chromedriver");
        for _ in 0..200 {
            if std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() {
                break;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        Driver { child, port }
    }
}

impl Drop for Driver {
    fn drop(&mut self) {
        // The whole group: chromedriver and any Chromium it left.
        let _ = Command::new("kill")
            .args(["-TERM", "--", &format!("-{}", self.child.id())])
            .status();
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

async fn js(c: &Client, script: &str) -> Value {
    c.execute(script, vec![]).await.expect(script)
}

/// Waits until the page shows the answer to the text in its editor.
async fn settled(c: &Client) -> Value {
    for _ in 0..400 {
        let v = js(
            c,
            "const s = window.stlc; const t = document.getElementById('source').value;
             if (!s || s.inFlight || s.answerText !== t) return null;
             return {ok: s.answer.ok, stems: s.answer.stems || 0,
                     growth: s.answer.growth ? s.answer.growth.stems : [],
                     text: t};",
        )
        .await;
        if !v.is_null() {
            // The debounce may still hold an edit: settle twice in a row.
            tokio::time::sleep(Duration::from_millis(300)).await;
            let again = js(c, "return window.stlc.answerText === document.getElementById('source').value && !window.stlc.inFlight").await;
            if again == json!(true) {
                return v;
            }
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    panic!("the page never showed the answer to its text");
}

/// The viewport position of canvas point `(x, y)` in the preview.
async fn screen_of(c: &Client, x: f64, y: f64) -> (f64, f64) {
    let v = js(
        c,
        &format!(
            "const m = document.getElementById('preview').getScreenCTM();
             return [m.a * {x} + m.e, m.d * {y} + m.f];"
        ),
    )
    .await;
    (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}

async fn shot(c: &Client, name: &str) {
    let dir = manifest_path("tests/store/browser");
    std::fs::create_dir_all(&dir).unwrap();
    let png = c.screenshot().await.unwrap();
    std::fs::write(dir.join(format!("{name}.png")), png).unwrap();
}

const TYPED: &str = "Typed (100, 190)\nL=9(0) B=1.5(0) A=30 C=2\nRULE\nR1: [-F][+F]\nSEED\nFR1\nENDSEED\nLAYOUT\n(clGreen) Rectangle (70, 120), 60, 75\nENDLAYOUT\n";

#[test]
fn the_page_grows_draws_replays_and_saves_in_chromium() {
    let (Some(chromium), Some(driver)) = (which("chromium"), which("chromedriver")) else {
        eprintln!(
            "SKIPPED the browser test: chromium and chromedriver are not installed \
             (apt-get install chromium chromium-driver; .ci/run does)"
        );
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("tree.od");
    std::fs::copy(manifest_path("examples/fig9.od"), &file).unwrap();
    let server = Server::start(&[file.to_str().unwrap()]);
    let chrome_tmp = tmp.path().join("chrome");
    std::fs::create_dir_all(&chrome_tmp).unwrap();
    let driver = Driver::start(&driver, &chrome_tmp);
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(drive(&server, &driver, &chromium, &chrome_tmp, &file));
}

async fn drive(server: &Server, driver: &Driver, chromium: &Path, tmp: &Path, file: &Path) {
    let mut caps = serde_json::Map::new();
    caps.insert(
        "goog:chromeOptions".into(),
        json!({
            "binary": chromium,
            "args": [
                "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--disable-background-networking", "--disable-component-update",
                "--disable-sync", "--disable-quic", "--no-first-run",
                "--window-size=1280,860",
                format!("--user-data-dir={}", tmp.join("profile").display()),
            ],
        }),
    );
    let connector = hyper_util::client::legacy::connect::HttpConnector::new();
    let c = ClientBuilder::new(connector)
        .capabilities(caps)
        .connect(&format!("http://127.0.0.1:{}", driver.port))
        .await
        .expect("a WebDriver session");
    steps(&c, server, file).await;
    acceptance(&c).await;
    let _ = c.close().await;
}

/// The acceptance, on the paper's 2DTree: open it, draw a white
/// hole with the mouse, switch to dfs, replay, save.
async fn acceptance(c: &Client) {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("2dtree.od");
    std::fs::copy(manifest_path("examples/2dtree.od"), &file).unwrap();
    let server = Server::start(&[file.to_str().unwrap()]);
    c.goto(&format!("http://{}/", server.addr)).await.unwrap();
    let opened = settled(c).await;
    assert_eq!(opened["ok"], true, "{opened}");
    let before = opened["stems"].as_u64().unwrap();
    click(c, "[data-tool=Ellipse]").await;
    click(c, "#colour option[value=clWhite]").await;
    drag(c, (100.0, 60.0), (160.0, 110.0)).await;
    let holed = settled(c).await;
    assert_eq!(holed["ok"], true, "{holed}");
    let text = holed["text"].as_str().unwrap();
    let lines = layout_lines(text);
    // The paper's inline layout, rewritten one shape a line, same shapes.
    assert_eq!(
        lines,
        [
            "(clGreen) RoundRect (0, 0), 180, 192, 3.5",
            "(clWhite) RoundRect (40, 15), 15, 15, 2",
            "(clWhite) RoundRect (35, 30), 41, 95, 2.5",
            "(clWhite) Ellipse (100, 60), 60, 50",
        ],
        "{text}"
    );
    let after = holed["stems"].as_u64().unwrap();
    assert!(
        after < before,
        "the hole takes stems away: {before} -> {after}"
    );
    // No stem ends inside the hole (an ellipse centred at (130, 85)).
    let g: Vec<f64> = holed["growth"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let inside = |x: f64, y: f64| ((x - 130.0) / 30.0).powi(2) + ((y - 85.0) / 25.0).powi(2) < 0.95;
    assert!(
        !g.chunks(6).any(|s| inside(s[2], s[3])),
        "a stem grew in the hole"
    );
    click(c, "#strategy option[value=dfs]").await;
    let mut dfs = settled(c).await;
    for _ in 0..20 {
        if dfs["growth"] != holed["growth"] {
            break;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
        dfs = settled(c).await;
    }
    assert_ne!(dfs["growth"], holed["growth"]);
    click(c, "#play").await;
    for _ in 0..600 {
        if js(c, "return window.stlc.replayTimer === null").await == json!(true) {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    shot(c, "11-acceptance").await;
    click(c, "#save").await;
    let mut on_disk = String::new();
    for _ in 0..100 {
        on_disk = std::fs::read_to_string(&file).unwrap();
        if on_disk == text {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert_eq!(on_disk, text);

    // Export: the page offers the CLI's PNG and BED for the same options.
    let od = tmp.path().join("saved.od");
    std::fs::write(&od, text).unwrap();
    for (button, args) in [
        (
            "#export-png",
            vec!["render", "-f", "png", "--show-layout", "--growth", "dfs"],
        ),
        ("#export-bed", vec!["compile", "--growth", "dfs"]),
    ] {
        js(c, "window.stlc.lastDownload = null; return 0;").await;
        click(c, button).await;
        let mut offered = Value::Null;
        for _ in 0..200 {
            offered = js(c, "return window.stlc.lastDownload").await;
            if !offered.is_null() {
                break;
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
        let out = std::process::Command::new(assert_cmd::cargo::cargo_bin("stlc"))
            .args(&args[..1])
            .arg(&od)
            .args(&args[1..])
            .args(["-o", "-"])
            .output()
            .unwrap();
        assert!(out.status.success());
        assert_eq!(offered["size"], out.stdout.len(), "{button}: {offered}");
        let ext = if button.ends_with("png") {
            ".png"
        } else {
            ".bed"
        };
        assert!(
            offered["name"].as_str().unwrap().ends_with(ext),
            "{offered}"
        );
    }
}

async fn steps(c: &Client, server: &Server, file: &Path) {
    c.goto(&format!("http://{}/", server.addr)).await.unwrap();
    let first = settled(c).await;
    assert_eq!(first["ok"], true, "{first}");
    assert!(first["text"].as_str().unwrap().contains("Fig9"));
    shot(c, "1-opened").await;

    // Type an OD.
    let source = c.find(Locator::Id("source")).await.unwrap();
    source.clear().await.unwrap();
    source.send_keys(TYPED).await.unwrap();
    let typed = settled(c).await;
    assert_eq!(typed["text"], TYPED);
    assert_eq!(typed["ok"], true, "{typed}");
    let small = typed["stems"].as_u64().unwrap();
    assert!(small > 3, "{typed}");
    shot(c, "2-typed").await;

    // Draw a rectangle with the mouse: the LAYOUT text gains it, and the
    // tree regrows into it (stems beyond the first rectangle).
    c.find(Locator::Css("[data-tool=Rectangle]"))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
    let (x0, y0) = screen_of(c, 20.0, 20.0).await;
    let (x1, y1) = screen_of(c, 180.0, 160.0).await;
    let drag = MouseActions::new("mouse".into())
        .then(PointerAction::MoveTo {
            duration: None,
            x: x0,
            y: y0,
        })
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        })
        .then(PointerAction::MoveTo {
            duration: Some(Duration::from_millis(100)),
            x: (x0 + x1) / 2.0,
            y: (y0 + y1) / 2.0,
        })
        .then(PointerAction::MoveTo {
            duration: Some(Duration::from_millis(100)),
            x: x1,
            y: y1,
        })
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
    c.perform_actions(drag).await.unwrap();
    let drawn = settled(c).await;
    let text = drawn["text"].as_str().unwrap();
    let layout: Vec<&str> = text
        .lines()
        .skip_while(|l| *l != "LAYOUT")
        .take_while(|l| *l != "ENDLAYOUT")
        .collect();
    assert_eq!(layout.len(), 3, "{text}");
    assert_eq!(layout[1], "(clGreen) Rectangle (70, 120), 60, 75");
    let new = layout[2];
    assert!(new.starts_with("(clGreen) Rectangle ("), "{new}");
    let nums: Vec<f64> = new
        .trim_start_matches("(clGreen) Rectangle ")
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    let near = |a: f64, b: f64| (a - b).abs() <= 1.0;
    assert!(
        near(nums[0], 20.0) && near(nums[1], 20.0) && near(nums[2], 160.0) && near(nums[3], 140.0),
        "{new}"
    );
    assert_eq!(drawn["ok"], true, "{drawn}");
    let grown = drawn["stems"].as_u64().unwrap();
    assert!(grown > small, "{small} -> {grown}");
    let g: Vec<f64> = drawn["growth"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let outside_first = g.chunks(6).any(|s| s[3] < 119.0);
    assert!(outside_first, "no stem grew into the drawn rectangle");
    shot(c, "3-drawn").await;

    // dfs grows another tree from the same outline.
    c.find(Locator::Css("#strategy option[value=dfs]"))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
    let mut dfs = settled(c).await;
    for _ in 0..20 {
        if dfs["growth"] != drawn["growth"] {
            break;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
        dfs = settled(c).await;
    }
    assert_eq!(dfs["ok"], true);
    assert_ne!(
        dfs["growth"], drawn["growth"],
        "bfs and dfs gave the same tree"
    );
    shot(c, "4-dfs").await;

    // Replay: midway only part of the tree is drawn.
    let max: u64 = js(c, "return Number(document.getElementById('step').max)")
        .await
        .as_u64()
        .unwrap();
    assert!(max > 10, "{max}");
    c.find(Locator::Id("play"))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
    // The replay takes about four seconds: look once it is under way.
    let mut mid = Value::Null;
    for _ in 0..200 {
        tokio::time::sleep(Duration::from_millis(50)).await;
        mid = js(
            c,
            "return {v: Number(document.getElementById('step').value),
                     replaying: document.getElementById('preview').classList.contains('replaying'),
                     label: document.getElementById('step-label').textContent};",
        )
        .await;
        if mid["v"].as_u64().unwrap() > max / 4 {
            break;
        }
    }
    let v = mid["v"].as_u64().unwrap();
    assert!(v > 0 && v < max, "{mid}");
    assert_eq!(mid["replaying"], true, "{mid}");
    shot(c, "5-replay").await;
    for _ in 0..600 {
        let done = js(c, "return window.stlc.replayTimer === null").await;
        if done == json!(true) {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    let end = js(c, "return Number(document.getElementById('step').value)").await;
    assert_eq!(end.as_u64().unwrap(), max);

    // An error: its diagnostic is listed and marked at its line.
    let good = dfs["text"].as_str().unwrap().to_string();
    let error_line = good.lines().count() + 1;
    js(c, "const s = document.getElementById('source'); s.focus(); s.setSelectionRange(s.value.length, s.value.length); return 0;").await;
    source.send_keys("JUNK(").await.unwrap();
    let bad = settled(c).await;
    assert_eq!(bad["ok"], false, "{bad}");
    let listed = js(
        c,
        "const li = document.querySelector('[data-testid=diagnostics] li.error');
         const mark = document.querySelector('#gutter span.error');
         return {line: li && li.dataset.line, text: li && li.textContent,
                 mark: mark && mark.textContent};",
    )
    .await;
    assert_eq!(listed["line"], error_line.to_string(), "{listed}");
    assert_eq!(listed["mark"], error_line.to_string(), "{listed}");
    shot(c, "6-error").await;
    for _ in 0..5 {
        source.send_keys("\u{E003}").await.unwrap(); // Backspace
    }
    let fixed = settled(c).await;
    assert_eq!(fixed["ok"], true, "{fixed}");
    assert_eq!(fixed["text"], good.as_str());

    // Save writes the editor's text to the file.
    c.find(Locator::Id("save"))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
    let mut on_disk = String::new();
    for _ in 0..100 {
        on_disk = std::fs::read_to_string(file).unwrap();
        if on_disk == good {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert_eq!(on_disk, good);
    // The page says so once the answer is back (the file is written first).
    let mut status = Value::Null;
    for _ in 0..100 {
        status = js(c, "return document.getElementById('saved').textContent").await;
        if status.as_str().unwrap().starts_with("Saved") {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert!(status.as_str().unwrap().starts_with("Saved"), "{status}");
    shot(c, "7-saved").await;

    tools(c, &good).await;
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

/// Presses at canvas point `a`, moves to `b` and releases.
async fn drag(c: &Client, a: (f64, f64), b: (f64, f64)) {
    let (x0, y0) = screen_of(c, a.0, a.1).await;
    let (x1, y1) = screen_of(c, b.0, b.1).await;
    let mouse = MouseActions::new("mouse".into())
        .then(PointerAction::MoveTo {
            duration: None,
            x: x0,
            y: y0,
        })
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        })
        .then(PointerAction::MoveTo {
            duration: Some(Duration::from_millis(80)),
            x: (x0 + x1) / 2.0,
            y: (y0 + y1) / 2.0,
        })
        .then(PointerAction::MoveTo {
            duration: Some(Duration::from_millis(80)),
            x: x1,
            y: y1,
        })
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
    c.perform_actions(mouse).await.unwrap();
}

/// Clicks at canvas point `a`.
async fn click_at(c: &Client, a: (f64, f64)) {
    let (x, y) = screen_of(c, a.0, a.1).await;
    let mouse = MouseActions::new("mouse".into())
        .then(PointerAction::MoveTo {
            duration: None,
            x,
            y,
        })
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        })
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
    c.perform_actions(mouse).await.unwrap();
}

async fn click(c: &Client, css: &str) {
    c.find(Locator::Css(css))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
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
    let holed = settled(c).await;
    let lines = layout_lines(holed["text"].as_str().unwrap());
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert_eq!(lines[2], "(clWhite) Ellipse (60, 40), 80, 60");
    let stems1 = holed["stems"].as_u64().unwrap();
    assert!(
        stems1 < stems0,
        "a hole grows fewer stems: {stems0} -> {stems1}"
    );
    shot(c, "8-hole").await;

    // Select it by its outline and move it 10 units right and down.
    click(c, "[data-tool=select]").await;
    drag(c, (100.0, 70.0), (110.0, 80.0)).await;
    let moved = settled(c).await;
    let lines = layout_lines(moved["text"].as_str().unwrap());
    assert_eq!(lines[2], "(clWhite) Ellipse (70, 50), 80, 60", "{lines:?}");

    // Resize by its bottom-right handle.
    drag(c, (150.0, 110.0), (160.0, 120.0)).await;
    let resized = settled(c).await;
    let lines = layout_lines(resized["text"].as_str().unwrap());
    assert_eq!(lines[2], "(clWhite) Ellipse (70, 50), 90, 70", "{lines:?}");

    // Lower it below the second rectangle: paint order in the text.
    click(c, "#lower").await;
    let lowered = settled(c).await;
    let lines = layout_lines(lowered["text"].as_str().unwrap());
    assert_eq!(lines[1], "(clWhite) Ellipse (70, 50), 90, 70", "{lines:?}");
    assert_eq!(lines[2], before[1]);
    // Painted before the big green rectangle, the hole is painted over.
    assert_eq!(lowered["stems"].as_u64().unwrap(), stems0, "{lines:?}");

    // Delete it.
    click(c, "#delete").await;
    let deleted = settled(c).await;
    assert_eq!(layout_lines(deleted["text"].as_str().unwrap()), before);

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
    let poly = settled(c).await;
    let lines = layout_lines(poly["text"].as_str().unwrap());
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert_eq!(
        lines[2],
        "(clGreen) Polygon (150, 170), (190, 170), (190, 195)"
    );
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
    assert!(
        (zoomed - fitted / 1.25).abs() < 1e-3,
        "{fitted} -> {zoomed}"
    );
    click(c, "#fit").await;
    assert!((js(c, width).await.as_f64().unwrap() - fitted).abs() < 1e-3);

    // Tree Renderer: an L-system at a depth.
    click(c, "#kind option[value=lsys]").await;
    let depth = c.find(Locator::Id("depth")).await.unwrap();
    depth.send_keys("2").await.unwrap();
    let source = c.find(Locator::Id("source")).await.unwrap();
    source.clear().await.unwrap();
    source
        .send_keys("axiom F++F++F\nangle 60\nrule F F-F++F-F\n")
        .await
        .unwrap();
    let koch = settled(c).await;
    assert_eq!(koch["ok"], true, "{koch}");
    // Depth 2 of the Koch snowflake: 3 * 4^2 segments.
    assert_eq!(koch["stems"], 48, "{koch}");
    let drawn = js(
        c,
        "return document.querySelectorAll('#preview .lib path').length",
    )
    .await;
    assert!(drawn.as_u64().unwrap() >= 1, "{drawn}");
    shot(c, "10-renderer").await;
}
