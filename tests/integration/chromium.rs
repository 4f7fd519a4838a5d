//! The harness the browser tests share: a chromedriver and a headless
//! Chromium started for a test's temporary directory, and the steps a
//! user takes (click, drag, open a file, download) with the checks that
//! hold the page to the CLI (the CLI's bytes, byte equality). Skips with
//! a message where `chromium` or `chromedriver` is not installed
//! (`.ci/run` installs Debian's packages), except under CI (`CI` set),
//! where that fails. Screenshots go to `tests/store/browser/`.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use fantoccini::actions::{
    Actions, InputSource, KeyAction, KeyActions, MOUSE_BUTTON_LEFT, MouseActions, PointerAction,
    WheelAction, WheelActions,
};
use fantoccini::{Client, ClientBuilder, Locator};
use serde_json::{Value, json};

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
pub(super) struct Driver {
    child: Child,
    port: u16,
}

/// A port free on loopback now.
pub(super) fn free_port() -> u16 {
    let listener = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    listener.local_addr().unwrap().port()
}

/// Waits (at most 10 s) until something listens on loopback `port`.
pub(super) fn wait_for_port(port: u16) {
    for _ in 0..200 {
        if std::net::TcpStream::connect(("127.0.0.1", port)).is_ok() {
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

impl Driver {
    pub(super) fn start(driver: &Path, tmp: &Path) -> Driver {
        // A free port, chosen here: chromedriver's own messages are not
        // parsed (they go nowhere, so it never blocks on a full pipe).
        let port = free_port();
        let child = Command::new(driver)
            .arg(format!("--port={port}"))
            .env("TMPDIR", tmp)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .process_group(0)
            .spawn()
            .expect("start chromedriver");
        wait_for_port(port);
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

pub(super) async fn js(c: &Client, script: &str) -> Value {
    c.execute(script, vec![]).await.expect(script)
}

/// What the asynchronous `script` hands its last argument (`done`), run
/// with `args` before it.
pub(super) async fn js_async(c: &Client, script: &str, args: Vec<Value>) -> Value {
    c.execute_async(script, args).await.expect(script)
}

/// Waits until the page shows the answer to the text in its editor.
pub(super) async fn settled(c: &Client) -> Value {
    for _ in 0..400 {
        let probe = "const s = window.stlc && window.stlc.state; const t = document.getElementById('source').value;
             if (!s || s.inFlight || s.answerText !== t) return null;
             return {ok: s.answer.ok, stems: Number(s.answer.stems || 0),
                     growth: s.answer.growth ? s.answer.growth.stems : [],
                     text: t};";
        let v = js(c, probe).await;
        if !v.is_null() {
            // The debounce may still hold an edit: settle twice in a row.
            tokio::time::sleep(Duration::from_millis(300)).await;
            let again = js(c, "return window.stlc.state.answerText === document.getElementById('source').value && !window.stlc.state.inFlight").await;
            if again == json!(true) {
                return v;
            }
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    panic!("the page never showed the answer to its text");
}

/// The page's settled state once `done` holds of it, looked at up to
/// `tries` more times `ms` apart; the last one seen if it never does (the
/// caller's assertion says what was wanted).
pub(super) async fn settled_until(
    c: &Client,
    tries: u32,
    ms: u64,
    done: impl Fn(&Value) -> bool,
) -> Value {
    poll(tries + 1, ms, async || settled(c).await, done).await
}

/// What `get` gives once `done` holds of it, asked up to `tries` times
/// `ms` apart; the last value if it never does.
pub(super) async fn poll<T>(
    tries: u32,
    ms: u64,
    mut get: impl AsyncFnMut() -> T,
    done: impl Fn(&T) -> bool,
) -> T {
    let mut v = get().await;
    for _ in 1..tries {
        if done(&v) {
            break;
        }
        tokio::time::sleep(Duration::from_millis(ms)).await;
        v = get().await;
    }
    v
}

/// The page's answer once its text is `want` and drawn without error;
/// the panic names `what` (the edit that should have made it) otherwise.
pub(super) async fn answered(c: &Client, want: &str, what: &str) -> Value {
    let good = |v: &Value| v["text"] == json!(want) && v["ok"] == json!(true);
    let v = settled_until(c, 200, 50, good).await;
    let text = &v["text"];
    assert!(good(&v), "the page never showed the text {what}: {text}");
    v
}

/// Waits (at most 10 s) until `script` returns true; on a timeout, a
/// screenshot `timeout-<what>` and a panic naming `what`.
pub(super) async fn until(c: &Client, script: &str, what: &str) {
    if js_until(c, script, 100, 100, |v| v == &json!(true)).await != json!(true) {
        shot(c, &format!("timeout-{}", what.replace(' ', "-"))).await;
        panic!("timed out waiting until {what}");
    }
}

/// What `script` returns once `done` holds of it, run up to `tries` times
/// `ms` apart; the last value if it never does.
pub(super) async fn js_until(
    c: &Client,
    script: &str,
    tries: u32,
    ms: u64,
    done: impl Fn(&Value) -> bool,
) -> Value {
    poll(tries, ms, async || js(c, script).await, done).await
}

/// The text of the file at `path` once `done` holds of it, read up to
/// `tries` times 50 ms apart (the page's save may still be under way); the
/// last text read if it never does.
pub(super) async fn file_until(path: &Path, tries: u32, done: impl Fn(&str) -> bool) -> String {
    let read = async || std::fs::read_to_string(path).unwrap();
    poll(tries, 50, read, |t: &String| done(t)).await
}

/// The viewport position of canvas point `(x, y)` in the preview.
pub(super) async fn screen_of(c: &Client, x: f64, y: f64) -> (f64, f64) {
    let script = format!(
        "const m = document.getElementById('preview').getScreenCTM();
             return [m.a * {x} + m.e, m.d * {y} + m.f];"
    );
    let v = js(c, &script).await;
    (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}

pub(super) async fn shot(c: &Client, name: &str) {
    let dir = manifest_path("tests/store/browser");
    std::fs::create_dir_all(&dir).unwrap();
    let png = c.screenshot().await.unwrap();
    std::fs::write(dir.join(format!("{name}.png")), png).unwrap();
}

/// A browser to test in: chromedriver started in `tmp/chrome` (downloads
/// and profile there), and a runtime to drive it from; `None` (after
/// saying why) where Chromium is not installed and `CI` is not set.
pub(super) struct Browser {
    pub rt: tokio::runtime::Runtime,
    pub driver: Driver,
    pub chromium: PathBuf,
    pub tmp: PathBuf,
}

impl Browser {
    pub(super) fn start(tmp: &Path) -> Option<Browser> {
        let (chromium, driver) = installed()?;
        let chrome_tmp = tmp.join("chrome");
        std::fs::create_dir_all(&chrome_tmp).unwrap();
        let driver = Driver::start(&driver, &chrome_tmp);
        let rt = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .unwrap();
        Some(Browser {
            rt,
            driver,
            chromium,
            tmp: chrome_tmp,
        })
    }

    /// A WebDriver session.
    pub(super) async fn connect(&self) -> Client {
        connect(&self.driver, &self.chromium, &self.tmp).await
    }
}

/// chromium and chromedriver, or `None` after saying why the test skips.
/// Under CI (the variable `CI` set and not empty, as `.ci/run` sets it) a
/// missing browser is a failure, not a skip: the install failed.
pub(super) fn installed() -> Option<(PathBuf, PathBuf)> {
    let (Some(chromium), Some(driver)) = (which("chromium"), which("chromedriver")) else {
        let why = "chromium and chromedriver are not installed \
                   (apt-get install chromium chromium-driver; .ci/run does)";
        if std::env::var_os("CI").is_some_and(|v| !v.is_empty()) {
            panic!("CI is set, so the browser test must run, but {why}");
        }
        eprintln!("SKIPPED the browser test: {why}");
        return None;
    };
    Some((chromium, driver))
}

/// A WebDriver session in a headless Chromium whose downloads go to
/// `tmp/downloads`.
pub(super) async fn connect(driver: &Driver, chromium: &Path, tmp: &Path) -> Client {
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
            "prefs": {
                "download.default_directory": tmp.join("downloads"),
                "download.prompt_for_download": false,
            },
        }),
    );
    // Starting Chromium can be slow on a busy machine (a cold start while
    // other tests compile or run): a failed session start is retried, and
    // the last error is the one reported.
    let url = format!("http://127.0.0.1:{}", driver.port);
    let mut last = None;
    for attempt in 1..=3 {
        let connector = hyper_util::client::legacy::connect::HttpConnector::new();
        match ClientBuilder::new(connector)
            .capabilities(caps.clone())
            .connect(&url)
            .await
        {
            Ok(c) => return c,
            Err(e) => {
                eprintln!("WebDriver session, attempt {attempt} of 3: {e}");
                last = Some(e);
                tokio::time::sleep(Duration::from_secs(2)).await;
            }
        }
    }
    panic!("no WebDriver session: {:?}", last);
}

/// The mouse pressed at viewport point `path[0]`, moved through the rest
/// of `path` (each move taking `ms`) and released.
fn mouse_along(path: &[(f64, f64)], ms: u64) -> MouseActions {
    let (x, y) = path[0];
    let mut mouse = MouseActions::new("mouse".into())
        .then(PointerAction::MoveTo {
            duration: None,
            x,
            y,
        })
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        });
    for &(x, y) in &path[1..] {
        let duration = Some(Duration::from_millis(ms));
        mouse = mouse.then(PointerAction::MoveTo { duration, x, y });
    }
    mouse.then(PointerAction::Up {
        button: MOUSE_BUTTON_LEFT,
    })
}

/// Presses at viewport point `path[0]`, moves through the rest of `path`
/// (each move taking `ms`) and releases.
pub(super) async fn press_along(c: &Client, path: &[(f64, f64)], ms: u64) {
    c.perform_actions(mouse_along(path, ms)).await.unwrap();
}

/// [`press_along`] with Shift held from the first move until after the
/// release.
pub(super) async fn press_along_shifted(c: &Client, path: &[(f64, f64)], ms: u64) {
    let mut keys = KeyActions::new("keyboard".into()).then(KeyAction::Down { value: SHIFT });
    // One pause a mouse action after the first: the release comes first.
    for _ in 0..path.len() + 1 {
        keys = keys.then(KeyAction::Pause {
            duration: Duration::ZERO,
        });
    }
    let keys = keys.then(KeyAction::Up { value: SHIFT });
    let both = Actions::from(keys).and(mouse_along(path, ms));
    c.perform_actions(both).await.unwrap();
}

/// Presses at canvas point `a`, moves to `b` (by way of their midpoint)
/// and releases.
pub(super) async fn drag(c: &Client, a: (f64, f64), b: (f64, f64)) {
    let (x0, y0) = screen_of(c, a.0, a.1).await;
    let (x1, y1) = screen_of(c, b.0, b.1).await;
    let mid = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    press_along(c, &[(x0, y0), mid, (x1, y1)], 80).await;
}

/// Clicks at canvas point `a`.
pub(super) async fn click_at(c: &Client, a: (f64, f64)) {
    press_along(c, &[screen_of(c, a.0, a.1).await], 0).await;
}

/// The mouse wheel turned by `dy` (120 a notch; > 0: towards the user,
/// zoom out) at viewport point `(x, y)`.
pub(super) async fn wheel(c: &Client, (x, y): (f64, f64), dy: i64) {
    let w = WheelActions::new("wheel".into()).then(WheelAction::Scroll {
        duration: None,
        x: x.round() as i64,
        y: y.round() as i64,
        delta_x: 0,
        delta_y: dy,
    });
    c.perform_actions(w).await.unwrap();
}

/// WebDriver's codes of keys without a character.
pub(super) const SHIFT: char = '\u{E008}';
pub(super) const CONTROL: char = '\u{E009}';

/// Presses `key` with the keys `held` held down (in that order, let go in
/// the other).
pub(super) async fn chord(c: &Client, held: &[char], key: char) {
    let mut keys = KeyActions::new("keyboard".into());
    for &value in held {
        keys = keys.then(KeyAction::Down { value });
    }
    keys = keys
        .then(KeyAction::Down { value: key })
        .then(KeyAction::Up { value: key });
    for &value in held.iter().rev() {
        keys = keys.then(KeyAction::Up { value });
    }
    c.perform_actions(keys).await.unwrap();
}

pub(super) async fn click(c: &Client, css: &str) {
    let element = c.find(Locator::Css(css)).await.unwrap();
    element.click().await.unwrap();
}

/// What `stlc ARGS -o -` writes.
pub(super) fn cli(args: &[&str]) -> Vec<u8> {
    let mut all = args.to_vec();
    all.extend(["-o", "-"]);
    crate::support::stlc_stdout(&all)
}

/// What `stlc LINE -o -` writes (the words of `line` as in
/// [`crate::support::stlc_line`]).
pub(super) fn cli_line(line: &str) -> Vec<u8> {
    crate::support::stlc_piped(&format!("{line} -o -"), "")
}

/// The SVG `stlc render --show-layout -f svg` writes of `text`, saved as
/// `name` (its extension says its kind) in a folder of its own.
pub(super) fn cli_svg_of(name: &str, text: &str) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join(name);
    std::fs::write(&file, text).unwrap();
    cli_line(&format!("render {} --show-layout -f svg", file.display()))
}

/// The bytes of `dir/name` once Chromium has finished downloading it.
pub(super) async fn downloaded(dir: &Path, name: &str) -> Vec<u8> {
    let path = dir.join(name);
    let partial = dir.join(format!("{name}.crdownload"));
    let whole = async || path.is_file() && !partial.exists();
    let done = poll(200, 50, whole, |&whole| whole).await;
    assert!(done, "{} was never downloaded", path.display());
    std::fs::read(&path).unwrap()
}

/// Opens `file` through the page's Open… control (its file input), and
/// waits until the page has read it into the editor.
pub(super) async fn open(c: &Client, file: &Path) {
    let input = c.find(Locator::Id("open-file")).await.unwrap();
    input.send_keys(file.to_str().unwrap()).await.unwrap();
    let text = std::fs::read_to_string(file).unwrap();
    let script = "return document.getElementById('source').value === arguments[0]";
    let read = async || c.execute(script, vec![json!(text)]).await.unwrap();
    let read = poll(200, 50, read, |v| v == &json!(true)).await;
    assert_eq!(read, json!(true), "the page never read {}", file.display());
}

/// Asserts `got` is `want`, saying where they part (not all the bytes).
pub(super) fn same_bytes(got: &[u8], want: &[u8], what: &str) {
    if got != want {
        let at = got.iter().zip(want).take_while(|(a, b)| a == b).count();
        let show = |b: &[u8]| {
            String::from_utf8_lossy(&b[at.saturating_sub(40)..(at + 40).min(b.len())]).into_owned()
        };
        panic!(
            "{what}: {} bytes, the CLI's {}; they part at byte {at}: {:?} / {:?}",
            got.len(),
            want.len(),
            show(got),
            show(want)
        );
    }
}

/// What a test of `stlc serve`'s page has to hand.
pub(super) struct Served<'a> {
    pub server: &'a super::serve::Server,
    /// The file served, in the temporary directory `dir` (`dir` itself
    /// where no file is served).
    pub file: &'a Path,
    pub dir: &'a Path,
    /// Where Chromium's downloads go.
    pub downloads: PathBuf,
}

/// Opens `stlc serve`'s page (no file) in a fresh Chromium, waits for its
/// first answer and runs `f` on it; returns at once where Chromium is
/// missing (after [`Browser::start`] says so).
pub(super) fn on_served_page(f: impl AsyncFnOnce(&Client, &Served)) {
    on_served(None, f);
}

/// [`on_served_page`] for a file `name` holding `text`, written in the
/// temporary directory and served.
pub(super) fn on_served_file(name: &str, text: &str, f: impl AsyncFnOnce(&Client, &Served)) {
    on_served(Some((name, text)), f);
}

fn on_served(file: Option<(&str, &str)>, f: impl AsyncFnOnce(&Client, &Served)) {
    let tmp = tempfile::tempdir().unwrap();
    let Some(browser) = Browser::start(tmp.path()) else {
        return;
    };
    let file = file.map(|(name, text)| {
        let path = tmp.path().join(name);
        std::fs::write(&path, text).unwrap();
        path
    });
    let args: Vec<&str> = file.iter().map(|p| p.to_str().unwrap()).collect();
    let server = super::serve::Server::start(&args);
    let downloads = browser.tmp.join("downloads");
    browser.rt.block_on(async {
        let c = browser.connect().await;
        c.goto(&server.url).await.unwrap();
        settled(&c).await;
        let file = file.as_deref().unwrap_or(tmp.path());
        let served = Served {
            server: &server,
            file,
            dir: tmp.path(),
            downloads,
        };
        f(&c, &served).await;
        let _ = c.close().await;
    });
}
