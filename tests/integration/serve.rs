//! `stlc serve`: the HTTP API against the CLI's own bytes, and the
//! security rules (Host, Origin, sizes, malformed HTTP, the Save token).
//! The server runs as the real binary on port 0; requests are raw HTTP
//! over a `TcpStream`, so malformed ones can be sent as they are.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use serde_json::{Value, json};

use crate::support::{manifest_path, numbers, outcome, stlc_line};

/// A running `stlc serve`, stopped with Ctrl-C (SIGINT) when dropped.
pub struct Server {
    child: Child,
    /// `127.0.0.1:PORT`.
    pub addr: String,
    /// The link it printed: `http://127.0.0.1:PORT/#token=T`.
    pub url: String,
    /// Its per-run token.
    pub token: String,
}

/// The token of each server started, by address: [`request`] sends it in
/// the header the page sends it in.
static TOKENS: std::sync::Mutex<std::collections::BTreeMap<String, String>> =
    std::sync::Mutex::new(std::collections::BTreeMap::new());

/// The `X-Stlc-Token` header line of the server at `addr` (empty if
/// unknown): what the page sends on every API call.
pub fn key(addr: &str) -> String {
    let tokens = TOKENS.lock().unwrap();
    match tokens.get(addr) {
        Some(t) => format!("X-Stlc-Token: {t}\r\n"),
        None => String::new(),
    }
}

impl Server {
    /// Starts `stlc serve ARGS --port 0` and reads the URL it prints.
    pub fn start(args: &[&str]) -> Server {
        Server::start_binary(&assert_cmd::cargo::cargo_bin("stlc"), args)
    }

    /// Starts `BINARY serve ARGS --port 0` (another build of stlc).
    pub fn start_binary(binary: &std::path::Path, args: &[&str]) -> Server {
        let mut child = Command::new(binary)
            .arg("serve")
            .args(args)
            .args(["--port", "0"])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start stlc serve");
        let mut out = BufReader::new(child.stdout.take().unwrap());
        let mut line = String::new();
        out.read_line(&mut line).unwrap();
        let url = line.trim().to_string();
        let (addr, token) = url
            .strip_prefix("http://")
            .and_then(|r| r.split_once("/#token="))
            .unwrap_or_else(|| panic!("first line is not the URL: {line:?}"));
        let (addr, token) = (addr.to_string(), token.to_string());
        assert!(addr.starts_with("127.0.0.1:"), "{addr}");
        assert_eq!(token.len(), 32, "{token}");
        TOKENS.lock().unwrap().insert(addr.clone(), token.clone());
        // Keep reading, so the server never writes into a closed pipe.
        std::thread::spawn(move || std::io::copy(&mut out, &mut std::io::sink()));
        Server {
            child,
            addr,
            url,
            token,
        }
    }

    /// CPU time the server has used so far (user + system), in clock
    /// ticks, from /proc.
    pub fn cpu_ticks(&self) -> u64 {
        let stat = std::fs::read_to_string(format!("/proc/{}/stat", self.child.id())).unwrap();
        // The fields after the command name (which may hold spaces).
        let rest = &stat[stat.rfind(')').unwrap() + 2..];
        let f: Vec<&str> = rest.split(' ').collect();
        f[11].parse::<u64>().unwrap() + f[12].parse::<u64>().unwrap()
    }

    /// A figure of the server's `/proc` status, kB: `VmRSS:` its resident
    /// size now, `VmHWM:` its peak.
    pub fn status_kb(&self, key: &str) -> u64 {
        let status = std::fs::read_to_string(format!("/proc/{}/status", self.pid())).unwrap();
        let figure = status.lines().find_map(|l| l.strip_prefix(key)).unwrap();
        figure.trim().trim_end_matches("kB").trim().parse().unwrap()
    }

    /// The server's process id.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Whether the server is still running.
    pub fn alive(&mut self) -> bool {
        matches!(self.child.try_wait(), Ok(None))
    }

    /// Kills the server at once (SIGKILL), as a crash or a power cut would.
    pub fn kill(mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
        std::mem::forget(self);
    }

    pub fn port(&self) -> &str {
        self.addr.rsplit(':').next().unwrap()
    }

    /// Sends SIGINT (what Ctrl-C sends) and waits for the exit status.
    pub fn interrupt(mut self) -> std::process::ExitStatus {
        let status = interrupt(&mut self.child);
        std::mem::forget(self);
        status
    }
}

fn interrupt(child: &mut Child) -> std::process::ExitStatus {
    let _ = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    for _ in 0..100 {
        if let Ok(Some(s)) = child.try_wait() {
            return s;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    child.wait().unwrap()
}

impl Drop for Server {
    fn drop(&mut self) {
        interrupt(&mut self.child);
    }
}

/// An answer: status, head (lower-cased), body.
pub struct Answer {
    pub status: u16,
    pub head: String,
    pub body: Vec<u8>,
}

impl Answer {
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&self.body)))
    }
}

/// Sends `raw` as it is and reads the answer until the server closes.
pub fn raw(addr: &str, raw: &[u8]) -> Answer {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(300))).unwrap();
    let _ = s.write_all(raw);
    let mut buf = Vec::new();
    let _ = s.read_to_end(&mut buf);
    let split = buf
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("no HTTP answer: {:?}", String::from_utf8_lossy(&buf)));
    let head = String::from_utf8_lossy(&buf[..split]).to_ascii_lowercase();
    let status = head.split(' ').nth(1).unwrap().parse().unwrap();
    let mut body = buf[split + 4..].to_vec();
    if head.contains("transfer-encoding: chunked") {
        body = unchunk(&body);
    }
    Answer { status, head, body }
}

fn unchunk(mut b: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let nl = b.windows(2).position(|w| w == b"\r\n").unwrap();
        let n = usize::from_str_radix(std::str::from_utf8(&b[..nl]).unwrap().trim(), 16).unwrap();
        if n == 0 {
            return out;
        }
        out.extend_from_slice(&b[nl + 2..nl + 2 + n]);
        b = &b[nl + 2 + n + 2..];
    }
}

/// A request with the usual headers and `Connection: close`.
pub fn request(
    addr: &str,
    method: &str,
    path: &str,
    extra: &[(&str, &str)],
    body: &[u8],
) -> Answer {
    // A request that names its own key (or a wrong one) sends only that.
    let own = extra.iter().any(|(k, _)| {
        k.eq_ignore_ascii_case("x-stlc-token") || k.eq_ignore_ascii_case("authorization")
    });
    let mut head = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Length: {}\r\n{}",
        body.len(),
        if own { String::new() } else { key(addr) }
    );
    for (k, v) in extra {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    let mut all = head.into_bytes();
    all.extend_from_slice(body);
    raw(addr, &all)
}

/// `POST path` with the JSON `body` and the `extra` headers.
pub fn post(addr: &str, path: &str, extra: &[(&str, &str)], body: &Value) -> Answer {
    request(addr, "POST", path, extra, body.to_string().as_bytes())
}

/// `stlc serve FILE ARGS` of a file `name` holding `text` in a temporary
/// directory: the directory (removed when dropped), the file, the server.
pub fn serve_file(name: &str, text: &str, args: &[&str]) -> (tempfile::TempDir, PathBuf, Server) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join(name);
    std::fs::write(&file, text).unwrap();
    let server = Server::start(&[&[file.to_str().unwrap()], args].concat());
    (dir, file, server)
}

/// The head of a `POST path` of `len` bytes with the page's key, and no
/// `Connection: close` (the connection stays open).
pub fn post_head(addr: &str, path: &str, len: usize) -> String {
    let key = key(addr);
    format!("POST {path} HTTP/1.1\r\nHost: {addr}\r\nContent-Length: {len}\r\n{key}\r\n")
}

/// A connection on which `body` is posted to `/api/render` with the page's
/// key (kept open: the caller reads the answer, or does not).
pub fn send_render(addr: &str, body: &str) -> TcpStream {
    let head = post_head(addr, "/api/render", body.len());
    let mut s = TcpStream::connect(addr).unwrap();
    s.write_all(head.as_bytes()).unwrap();
    s.write_all(body.as_bytes()).unwrap();
    s
}

/// `GET path`.
pub fn get(addr: &str, path: &str) -> Answer {
    request(addr, "GET", path, &[], b"")
}

/// `POST /api/render` with `body`; the answer's JSON.
pub fn render(addr: &str, body: &Value) -> Value {
    let a = post(addr, "/api/render", &[], body);
    assert_eq!(a.status, 200, "{}", String::from_utf8_lossy(&a.body));
    a.json()
}

/// [`render`], for an answer that must be drawn (`ok`).
pub fn render_ok(addr: &str, body: &Value) -> Value {
    let a = render(addr, body);
    assert_eq!(a["ok"], true, "{a}");
    a
}

/// The answer's stem count: decimal digits, exact.
fn stems(a: &Value) -> u64 {
    assert_eq!(a["stems_exact"], true, "{a}");
    a["stems"].as_str().unwrap().parse().unwrap()
}

pub fn example(name: &str) -> String {
    std::fs::read_to_string(manifest_path("examples").join(name)).unwrap()
}

/// A stochastic system with no level of detail (its alternatives turn
/// differently: docs/rendering.md), so derived symbol by symbol: at depth
/// 12 about 3 x 10^8 symbols, many seconds of work, drawing one segment
/// (so an SVG is not refused for its size). ABOP 1.27 at depth 14 was
/// that before issue 24; it now draws at a level of detail at once.
pub const HEAVY: &str = "axiom FX\nrule X (0.5) -> XXXXX+\nrule X (0.5) -> XXXXX-\nangle 30\n";

/// What `stlc LINE` writes to standard output.
fn cli(line: &str) -> Vec<u8> {
    crate::support::stlc_piped(line, "")
}

/// What `stlc LINE` writes to standard output, as text.
fn cli_text(line: &str) -> String {
    String::from_utf8(cli(line)).unwrap()
}

/// The BED and SVG of an .od are byte for byte what `stlc compile` and
/// `stlc render -f svg --show-layout` write with the same options, in both
/// growth orders and space-first, with a clearance and a stem limit, and
/// space-first with a seed in the file.
#[test]
fn render_answers_the_cli_bytes_for_an_od() {
    let server = Server::start(&[]);
    for name in ["2dtree.od", "fig9.od", "holes.od"] {
        let path = manifest_path("examples").join(name);
        let path = path.to_str().unwrap();
        let limited = "--clearance 0.5 --max-stems 120";
        for (strategy, extra) in [("bfs", ""), ("dfs", ""), ("dfs", limited), ("space", "")] {
            let mut body = json!({"source": example(name), "kind": "od", "growth": strategy});
            if !extra.is_empty() {
                body["clearance"] = json!(0.5);
                body["max_stems"] = json!(120);
            }
            let a = render_ok(&server.addr, &body);
            let bed = cli_text(&format!("compile {path} -o - --growth {strategy} {extra}"));
            crate::support::assert_same_text(name, &bed, a["bed"].as_str().unwrap());
            let svg = cli_text(&format!(
                "render {path} -f svg -o - --show-layout --growth {strategy} {extra}"
            ));
            crate::support::assert_same_text(name, &svg, a["svg"].as_str().unwrap());
            // The stems counted are the stems in the growth order.
            let order = a["growth"]["stems"].as_array().unwrap();
            assert_eq!(order.len() as u64 / 6, stems(&a));
            if !extra.is_empty() {
                assert!(stems(&a) <= 120);
            }
        }
    }
    // Space-first with a seed in the file (`V=`, which moves the
    // attraction points): two seeds, each the CLI's, two different trees.
    let dir = tempfile::tempdir().unwrap();
    let mut beds = Vec::new();
    for seed in [3, 8] {
        let text = example("holes.od").replace("C=1.5\n", &format!("C=1.5 O=space V={seed}\n"));
        assert!(text.contains("V="), "the header line is where it was");
        let path = dir.path().join(format!("holes-v{seed}.od"));
        std::fs::write(&path, &text).unwrap();
        let body = json!({"source": text, "kind": "od", "growth": "space"});
        let a = render_ok(&server.addr, &body);
        let bed = cli_text(&format!("compile {} -o - --growth space", path.display()));
        crate::support::assert_same_text("holes.od", &bed, a["bed"].as_str().unwrap());
        beds.push(bed);
    }
    assert_ne!(beds[0], beds[1], "the seed moves the points and the tree");
}

/// The growth order: the seed's stems come first (decision 0, the first
/// one from the root); decisions never go back; and every stem of a
/// decision starts where an earlier stem (or its own decision's earlier
/// stem) ends: a replay always adds to the tree already drawn. bfs and dfs
/// decide fig9 in different orders but place the same number of stems
/// only if the trees agree, which they do not.
#[test]
fn the_growth_order_replays_a_connected_tree() {
    let server = Server::start(&[]);
    let mut orders = Vec::new();
    for strategy in ["bfs", "dfs", "space"] {
        let body = json!({"source": example("fig9.od"), "growth": strategy});
        let a = render(&server.addr, &body);
        let g = numbers(&a["growth"]["stems"]);
        assert!(g.len() >= 6 * 50, "{}", g.len());
        let root = "the first stem starts at the root";
        assert_eq!((g[0], g[1]), (100.0, 196.0), "{root}");
        assert_eq!(g[5], 0.0, "the seed's F is decision 0");
        let mut ends: Vec<(f64, f64)> = vec![(100.0, 196.0)];
        let mut last = 0.0;
        for s in g.chunks(6) {
            assert!(s[5] >= last, "decisions go forward");
            last = s[5];
            let near = |p: &(f64, f64)| (p.0 - s[0]).abs() < 0.01 && (p.1 - s[1]).abs() < 0.01;
            assert!(ends.iter().any(near), "stem {s:?} starts at no earlier end");
            ends.push((s[2], s[3]));
        }
        assert_eq!(a["growth"]["decisions"].as_f64().unwrap(), last);
        orders.push(g);
    }
    assert_ne!(orders[0], orders[1], "bfs and dfs grow fig9 differently");
    assert_ne!(orders[0], orders[2], "bfs and space grow fig9 differently");
}

/// An L-system with a depth and a BED are drawn as `stlc render` draws
/// them; the PNG export is the CLI's PNG.
#[test]
fn lsys_bed_and_png_export_are_the_cli_bytes() {
    let server = Server::start(&[]);
    let koch = json!({"source": example("koch-snowflake.lsys"), "kind": "lsys", "depth": 2});
    let a = render_ok(&server.addr, &koch);
    let svg = cli("render examples/koch-snowflake.lsys -f svg -o - --depth 2");
    assert_eq!(a["svg"].as_str().unwrap().as_bytes(), &svg[..]);
    assert!(a["bed"].is_null());

    let bed = json!({"source": example("paper-worked.bed"), "kind": "bed"});
    let a = render(&server.addr, &bed);
    let svg = cli("render examples/paper-worked.bed -f svg -o - --show-layout");
    assert_eq!(a["svg"].as_str().unwrap().as_bytes(), &svg[..]);

    let body = json!({"source": example("holes.od"), "growth": "dfs"});
    let png = post(&server.addr, "/api/export?format=png", &[], &body);
    assert!(png.head.contains("content-type: image/png"), "{}", png.head);
    let cli_png = cli("render examples/holes.od -f png -o - --show-layout --growth dfs");
    assert!(png.body == cli_png, "the exported PNG is not the CLI's");
    let bed = post(&server.addr, "/api/export?format=bed", &[], &body);
    assert!(bed.body == cli("compile examples/holes.od -o - --growth dfs"));
}

/// An input error answers 200 with diagnostics at 1-based lines and
/// columns: here an unknown colour, at column 2 (after `(`) of its line.
#[test]
fn input_errors_answer_diagnostics_with_lines_and_columns() {
    let server = Server::start(&[]);
    let text = example("holes.od").replace("(clWhite) Ellipse (40", "(clWhiet) Ellipse (40");
    let line = text.lines().position(|l| l.contains("clWhiet")).unwrap() + 1;
    assert!(line > 10, "{line}");
    let a = render(&server.addr, &json!({"source": text, "kind": "od"}));
    assert_eq!(a["ok"], false, "{a}");
    let d = &a["diagnostics"][0];
    assert_eq!(d["line"], line, "{d}");
    assert_eq!(d["column"], 2, "{d}");
    assert_eq!(d["end_line"], line, "{d}");
    assert_eq!(d["end_column"], 9, "{d}");
    assert!(d["message"].as_str().unwrap().contains("clWhiet"), "{d}");
    assert!(d["help"].as_str().unwrap().contains("clWhite"), "{d}");

    // Growth that nothing bounds is refused, not run for ever.
    let unbounded = json!({"source": "T (0, 0) L=10(0) RULE R1: F[+R1][-R1]", "kind": "od"});
    let a = render(&server.addr, &unbounded);
    assert_eq!(a["ok"], false, "{a}");
    // A stem limit above the server's own is refused.
    let server = Server::start(&["--max-stems", "100"]);
    let over = json!({"source": example("fig9.od"), "max_stems": 101});
    let a = render(&server.addr, &over);
    assert_eq!(a["ok"], false, "{a}");
    let under = json!({"source": example("fig9.od"), "max_stems": 40});
    let a = render_ok(&server.addr, &under);
    assert!(stems(&a) <= 40);
    let warned = a["warnings"][0]["message"].as_str().unwrap();
    assert!(warned.contains("40"), "{a}");
}

/// DNS rebinding and cross-site requests: a foreign or missing Host is
/// refused on every path, `localhost:PORT` is accepted; a POST from a
/// foreign Origin is refused, from the page's own accepted.
#[test]
fn foreign_hosts_and_origins_are_refused() {
    let server = Server::start(&[]);
    let addr = &server.addr;
    let port = server.port();
    let at_host = |host: &str| {
        let key = key(addr);
        let head = format!("GET / HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n{key}\r\n");
        raw(addr, head.as_bytes())
    };
    assert_eq!(at_host(addr).status, 200);
    assert_eq!(at_host(&format!("localhost:{port}")).status, 200);
    for host in [
        "evil.example".to_string(),
        format!("evil.example:{port}"),
        "127.0.0.1".to_string(),
        format!("127.0.0.1:{port}.evil.example"),
    ] {
        assert_eq!(at_host(&host).status, 403, "{host}");
    }
    let no_host = raw(addr, b"GET /api/file HTTP/1.0\r\n\r\n");
    assert_eq!(no_host.status, 403);
    let body = json!({"source": example("fig9.od")}).to_string();
    for (origin, status) in [
        ("http://evil.example".to_string(), 403),
        (format!("http://localhost:{port}.evil.example"), 403),
        ("null".to_string(), 403),
        (format!("http://127.0.0.1:{port}"), 200),
        (format!("http://localhost:{port}"), 200),
    ] {
        let from = [("Origin", origin.as_str())];
        let a = request(addr, "POST", "/api/render", &from, body.as_bytes());
        assert_eq!(a.status, status, "{origin}");
    }
    // No file path is read from a request: paths other than the page's
    // are not found.
    for path in [
        "/../Cargo.toml",
        "/examples/fig9.od",
        "/api/file?path=/etc/passwd",
    ] {
        let a = get(addr, path);
        let passwd = String::from_utf8_lossy(&a.body).contains("root:");
        let status = a.status;
        let hidden = status == 404 || (status == 200 && !passwd);
        assert!(hidden, "{path}: {status}");
    }
}

/// Sizes: a body over --max-input is 413 (declared or chunked), malformed
/// JSON is 400, a huge head is refused; garbage never stops the server;
/// idle connections do not keep others waiting.
#[test]
fn oversize_malformed_and_idle_requests_never_stop_the_server() {
    let server = Server::start(&["--max-input", "2000"]);
    let addr = &server.addr;
    let big = json!({"source": "x".repeat(3000)}).to_string();
    let a = request(addr, "POST", "/api/render", &[], big.as_bytes());
    assert_eq!(a.status, 413);
    // Chunked, with no length declared.
    let mut chunked = format!(
        "POST /api/render HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nTransfer-Encoding: chunked\r\n{}\r\n",
        key(addr)
    )
    .into_bytes();
    for _ in 0..3 {
        chunked.extend_from_slice(format!("3e8\r\n{}\r\n", "y".repeat(1000)).as_bytes());
    }
    chunked.extend_from_slice(b"0\r\n\r\n");
    assert_eq!(raw(addr, &chunked).status, 413);
    for bad in [
        &b"{"[..],
        b"not json",
        b"[]",
        b"{\"source\": 1}",
        b"\xff\xfe",
    ] {
        assert_eq!(request(addr, "POST", "/api/render", &[], bad).status, 400);
    }
    // A head over the limit: refused (431) or the connection closed.
    let huge = format!(
        "GET / HTTP/1.1\r\nHost: {addr}\r\nX-Big: {}\r\n\r\n",
        "z".repeat(100_000)
    );
    let mut s = TcpStream::connect(addr).unwrap();
    let _ = s.write_all(huge.as_bytes());
    let mut buf = Vec::new();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let _ = s.read_to_end(&mut buf);
    let answer = String::from_utf8_lossy(&buf);
    assert!(!answer.contains(" 200 "), "{answer}");
    // Garbage, a half request, idle connections.
    for junk in [
        &b"\x00\x01\x02\r\n\r\n"[..],
        b"GET\r\n\r\n",
        b"POST /api/render HTTP/1.1\r\nContent-Length: -5\r\n\r\n",
        b"GET / HTTP/9.9\r\n\r\n",
    ] {
        let mut s = TcpStream::connect(addr).unwrap();
        let _ = s.write_all(junk);
        s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
        let _ = s.read_to_end(&mut Vec::new());
    }
    let idle: Vec<TcpStream> = (0..20).map(|_| TcpStream::connect(addr).unwrap()).collect();
    render_ok(addr, &json!({"source": example("fig9.od")}));
    drop(idle);
}

/// Save: refused without the page's token or with a wrong one; with it,
/// the named file is written (atomically, by the CLI's writer); with no
/// file named, there is nothing to write (the page downloads).
#[test]
fn save_needs_the_token_and_writes_only_the_named_file() {
    let (dir, file, server) = serve_file("tree.od", &example("fig9.od"), &[]);
    let addr = &server.addr;
    let token = server.token.clone();
    let opened = get(addr, "/api/file").json();
    assert_eq!(opened["text"], example("fig9.od"));
    assert_eq!(opened["can_save"], true);
    let body = json!({"source": "Changed (1, 2)\nRULE\nR1: F\n"}).to_string();
    for bad in [String::new(), "0".repeat(32), format!("{token}0")] {
        let headers = [("X-Stlc-Token", bad.as_str())];
        let a = request(addr, "POST", "/api/save", &headers, body.as_bytes());
        assert_eq!(a.status, 401);
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), example("fig9.od"));
    let key = [("X-Stlc-Token", token.as_str())];
    let a = request(addr, "POST", "/api/save", &key, body.as_bytes());
    assert_eq!(a.status, 200, "{}", String::from_utf8_lossy(&a.body));
    let saved = std::fs::read_to_string(&file).unwrap();
    assert_eq!(saved, "Changed (1, 2)\nRULE\nR1: F\n");
    // Nothing but the file: no temporary left beside it.
    assert_eq!(crate::support::files_in(dir.path()), ["tree.od"]);

    let example_server = Server::start(&[]);
    let token = &example_server.token;
    let headers = [("X-Stlc-Token", token.as_str())];
    let to = &example_server.addr;
    let a = request(to, "POST", "/api/save", &headers, body.as_bytes());
    assert_eq!(a.status, 409);
    assert_ne!(token, &server.token, "each run has its own token");
}

/// Ctrl-C stops the server with exit status 0; a new file in a missing
/// folder, or one whose name says no kind, is an error
/// before anything is served.
#[test]
fn ctrl_c_stops_cleanly_and_a_file_that_cannot_be_made_is_an_error() {
    let server = Server::start(&[]);
    assert_eq!(get(&server.addr, "/").status, 200);
    let status = server.interrupt();
    assert!(status.success(), "{status:?}");
    let (code, out, err) = outcome(&mut stlc_line("serve no/such/file.od --port 0"));
    assert_eq!(code, 1);
    assert!(out.is_empty());
    let named = err.contains("no/such/file.od");
    assert!(named && err.contains("does not exist"), "{err}");
    // A new file whose name says no kind: nothing to start from.
    let dir = tempfile::tempdir().unwrap();
    let odd = dir.path().join("new.xyz");
    let line = format!("serve {} --port 0", odd.display());
    let (code, _, err) = outcome(&mut stlc_line(&line));
    assert_eq!(code, 1);
    assert!(err.contains(".od, .bed or .lsys"), "{err}");
}

/// `stlc serve new.od` for a file not there yet starts from a template
/// (`version` null), and the first Save creates it; a save based on an
/// older version is refused with 412 and the version now there, and
/// nothing is written; a save based on that version goes through.
#[test]
fn a_new_file_is_created_and_a_save_over_another_version_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("oak.od");
    let server = Server::start(&[file.to_str().unwrap()]);
    let addr = &server.addr;
    let opened = get(addr, "/api/file").json();
    assert_eq!(opened["version"], Value::Null);
    assert!(opened["text"].as_str().unwrap().contains("RULE"));
    assert!(!file.exists(), "nothing is written before Save");
    // The template grows a tree.
    let a = render_ok(addr, &json!({"source": opened["text"]}));
    assert!(stems(&a) > 50, "{a}");
    let token = server.token.clone();
    let save = |body: Value| post(addr, "/api/save", &[("X-Stlc-Token", &token)], &body);
    let first = save(json!({"source": "one\n", "version": null}));
    let said = String::from_utf8_lossy(&first.body).into_owned();
    assert_eq!(first.status, 200, "{said}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "one\n");
    let v1 = first.json()["version"].as_str().unwrap().to_string();
    assert_eq!(get(addr, "/api/file").json()["version"], v1.as_str());
    // Another program writes; a save based on v1 is refused.
    std::fs::write(&file, "theirs\n").unwrap();
    let now = get(addr, "/api/file").json();
    assert_eq!(now["text"], "theirs\n", "the file is read as it is now");
    let refused = save(json!({"source": "mine\n", "version": v1}));
    assert_eq!(refused.status, 412);
    assert_eq!(refused.json()["version"], now["version"]);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "theirs\n");
    // Keep mine: based on the version there now.
    let kept = save(json!({"source": "mine\n", "version": now["version"]}));
    assert_eq!(kept.status, 200);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine\n");
}

/// A forest with alternatives: the request's seed is the CLI's `--seed`
/// (same BED bytes), another seed grows another grove, and the answer
/// lists the roots after the first for the page to show.
#[test]
fn the_seed_of_a_request_is_the_cli_seed_and_forest_roots_are_listed() {
    let server = Server::start(&[]);
    let path = "examples/grove.od";
    let ask = |seed: u64| {
        let body = json!({"source": example("grove.od"), "growth": "bfs", "seed": seed});
        render(&server.addr, &body)
    };
    let a = ask(7);
    assert_eq!(a["ok"], true, "{a}");
    let bed = cli_text(&format!("compile {path} -o - --seed 7"));
    crate::support::assert_same_text("grove --seed 7", &bed, a["bed"].as_str().unwrap());
    assert_ne!(a["bed"], ask(8)["bed"]);
    let others = a["root"]["others"].as_array().unwrap();
    let at = |r: &Value, k: &str| r[k].as_f64().unwrap();
    let xy: Vec<(f64, f64)> = others.iter().map(|r| (at(r, "x"), at(r, "y"))).collect();
    assert_eq!(xy, [(110.0, 290.0), (170.0, 290.0), (235.0, 290.0)]);
    // A seed as a string of digits (how the page sends it): exact past a
    // JavaScript number's 2^53, the CLI's --seed of the same digits.
    let top = u64::MAX.to_string();
    let body = json!({"source": example("grove.od"), "seed": &top});
    let b = render(&server.addr, &body);
    let bed = cli_text(&format!("compile {path} -o - --seed {top}"));
    crate::support::assert_same_text("grove --seed 2^64-1", &bed, b["bed"].as_str().unwrap());
    let below = cli_text(&format!("compile {path} -o - --seed {}", u64::MAX - 1));
    assert_ne!(below, bed, "neighbouring seeds grow different groves");
    for bad in ["x", "-1", "18446744073709551616", "1.5"] {
        let body = json!({"source": example("grove.od"), "seed": bad}).to_string();
        let answer = request(&server.addr, "POST", "/api/render", &[], body.as_bytes());
        assert_eq!(answer.status, 400, "{bad}");
    }
}

/// The typed edge: the query string is parsed wherever `format` stands, a
/// field the API does not know is a 400 that names it, and a request with
/// two `Host` headers, two `Origin` headers, or an absolute URL naming
/// another host is refused.
#[test]
fn the_edge_parses_queries_refuses_unknown_fields_and_doubled_headers() {
    let server = Server::start(&[]);
    let addr = &server.addr;
    let body = json!({"source": example("fig9.od")}).to_string();
    let query = "/api/export?x=1&format=svg";
    let svg = request(addr, "POST", query, &[], body.as_bytes());
    assert_eq!(svg.status, 200);
    let head = &svg.head;
    assert!(head.contains("content-type: image/svg+xml"), "{head}");
    let cli_svg = cli("render examples/fig9.od -f svg -o - --show-layout");
    assert!(svg.body == cli_svg, "the exported SVG is not the CLI's");

    let typo = json!({"source": example("fig9.od"), "clearence": 2}).to_string();
    let a = request(addr, "POST", "/api/render", &[], typo.as_bytes());
    assert_eq!(a.status, 400);
    let error = a.json()["error"].as_str().unwrap().to_string();
    assert!(error.contains("unknown field `clearence`"), "{error}");

    let twice = format!(
        "GET / HTTP/1.1\r\nHost: {addr}\r\nHost: evil.example\r\nConnection: close\r\n\r\n"
    );
    assert_eq!(raw(addr, twice.as_bytes()).status, 400);
    let ours = format!("http://{addr}");
    let two = [("Origin", ours.as_str()), ("Origin", "http://evil.example")];
    let origins = request(addr, "POST", "/api/render", &two, body.as_bytes());
    assert_eq!(origins.status, 400);
    let absolute =
        format!("GET http://evil.example/ HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n");
    assert_eq!(raw(addr, absolute.as_bytes()).status, 403);
    let ours = format!(
        "GET http://{addr}/ HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n{}\r\n",
        key(addr)
    );
    assert_eq!(raw(addr, ours.as_bytes()).status, 200);
}

/// The page's ES modules are all served: from the entry, every
/// `import ... from './x.js'` is fetched as JavaScript; other methods on
/// them are 405, other paths 404.
#[test]
fn the_page_and_every_module_it_imports_are_served() {
    let server = Server::start(&[]);
    let page = get(&server.addr, "/");
    assert_eq!(page.status, 200);
    let html = String::from_utf8(page.body).unwrap();
    let entry = r#"<script type="module" src="entry.js"></script>"#;
    assert!(html.contains(entry), "{html}");
    let css = get(&server.addr, "/style.css");
    assert_eq!(css.status, 200);
    assert!(css.head.contains("content-type: text/css"), "{}", css.head);
    let mut todo = vec!["/entry.js".to_string()];
    let mut seen = Vec::new();
    while let Some(path) = todo.pop() {
        if seen.contains(&path) {
            continue;
        }
        let got = get(&server.addr, &path);
        assert_eq!(got.status, 200, "{path}");
        let head = &got.head;
        let javascript = head.contains("content-type: text/javascript");
        assert!(javascript, "{path}: {head}");
        let dir = &path[..path.rfind('/').unwrap()];
        for line in String::from_utf8(got.body).unwrap().lines() {
            // `import x from './y.js';` or a bare `import './y.js';`.
            let Some(spec) = line
                .strip_prefix("import ")
                .map(|l| l.rsplit_once(" from ").map_or(l, |(_, spec)| spec))
                .filter(|spec| spec.starts_with('\''))
            else {
                continue;
            };
            let spec = spec.trim_end_matches(';').trim_matches('\'');
            let target = match spec.strip_prefix("../") {
                Some(up) => format!("{}/{up}", &dir[..dir.rfind('/').unwrap()]),
                None => format!("{dir}/{}", spec.trim_start_matches("./")),
            };
            todo.push(target);
        }
        seen.push(path);
    }
    assert!(seen.len() >= 5, "{seen:?}");
    assert!(seen.contains(&"/engine/http.js".to_string()), "{seen:?}");
    assert!(seen.contains(&"/app.js".to_string()), "{seen:?}");
    let post = request(&server.addr, "POST", "/engine/http.js", &[], b"");
    assert_eq!(post.status, 405);
    let missing = get(&server.addr, "/engine/none.js");
    assert_eq!(missing.status, 404);
}

/// Counts past 2^53 travel as exact digits: abop-1.24a (F -> F[+F]F[-F]F,
/// five F for one) has 5^30 segments at depth 30, more than a u64 holds.
#[test]
fn counts_past_a_machine_integer_are_exact_digits() {
    let server = Server::start(&[]);
    let at =
        |depth: u32| json!({"source": example("abop-1.24a.lsys"), "kind": "lsys", "depth": depth});
    let a = render_ok(&server.addr, &at(30));
    assert_eq!(a["stems"], "931322574615478515625");
    assert_eq!(a["stems_exact"], true);
    let small = render(&server.addr, &at(3));
    assert_eq!(small["stems"], "125");
}
