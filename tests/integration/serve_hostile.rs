//! `stlc serve` against hostile local clients and heavy load
//! (docs/serve.md, "Security model" and "Heavy work"): abandoned and
//! overlong work, the owner's key, light work beside heavy work, clients
//! that never read or send slowly, and the served file replaced by what
//! cannot be read. The server and its helpers are serve.rs's.

use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

use serde_json::json;

use super::serve::*;
use crate::support::manifest_path;

/// Work stops when nobody waits for it: a heavy render ([`HEAVY`] at
/// depth 12, as an SVG: many seconds of work) whose client closes its
/// connection after 0.3 s uses no more CPU a second later; and work past
/// `--time-budget` stops with a diagnostic that names the budget.
#[test]
fn abandoned_and_overlong_work_stops() {
    let server = Server::start(&["--time-budget", "2"]);
    let addr = &server.addr;
    let heavy = json!({"source": HEAVY, "kind": "lsys", "depth": 12});
    let started = std::time::Instant::now();
    let a = render(addr, &heavy);
    let took = started.elapsed();
    assert_eq!(a["ok"], false, "{a}");
    let message = a["diagnostics"][0]["message"].as_str().unwrap();
    assert!(message.contains("time budget of 2 s"), "{message}");
    assert!(took < Duration::from_secs(10), "{took:?}");

    let s = send_render(addr, &heavy.to_string());
    std::thread::sleep(Duration::from_millis(300));
    drop(s);
    // Within a second of the disconnect the work has stopped: the CPU
    // time no longer rises (a tick is 10 ms; allow a few for the server's
    // own bookkeeping).
    std::thread::sleep(Duration::from_millis(1000));
    let t1 = server.cpu_ticks();
    std::thread::sleep(Duration::from_millis(1000));
    let t2 = server.cpu_ticks();
    let went_on = format!("the abandoned work went on: {t1} -> {t2} ticks");
    assert!(t2 - t1 <= 5, "{went_on}");
    // And the server still answers.
    render_ok(addr, &json!({"source": example("fig9.od")}));
}

/// Only the owner (issue 23, problem 1; issue 36, problem 1): the printed
/// link carries the token in its fragment, which a browser never sends;
/// `GET /` and the page's scripts are public code, naming no file and no
/// token; every API call, reads included, needs the token in a header. No
/// cookie carries anything that grants access (a browser sends the
/// cookies of 127.0.0.1 to every port): none is set, and the right token
/// in this port's old cookie opens nothing.
#[test]
fn only_the_owner_reaches_the_file() {
    let (_dir, file, server) = serve_file("mine.od", &example("fig9.od"), &[]);
    let addr = &server.addr;
    let port = server.port().to_string();
    let fragment = format!("http://{addr}/#token={}", server.token);
    assert_eq!(server.url, fragment, "the token in the fragment");
    let stranger = |method: &str, path: &str, extra: &str, body: &str| {
        let n = body.len();
        let head = format!(
            "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Length: {n}\r\n{extra}\r\n"
        );
        raw(addr, (head + body).as_bytes())
    };
    let secret = |a: &Answer| {
        let text = String::from_utf8_lossy(&a.body);
        let named = ["Fig9", "mine.od", &server.token]
            .iter()
            .any(|s| text.contains(s));
        named || a.head.contains("set-cookie")
    };
    // The page and its code: public, the same for anyone, naming nothing.
    for path in [
        "/",
        "/?token=0123",
        "/app.js",
        "/style.css",
        "/engine/http.js",
    ] {
        let a = stranger("GET", path, "", "");
        assert_eq!(a.status, 200, "{path}");
        assert!(!secret(&a), "{path}: {}", a.head);
    }
    let old_cookie = format!("Cookie: stlc-{port}={}\r\n", server.token);
    let render = json!({"source": "x"}).to_string();
    for extra in [
        "",
        old_cookie.as_str(),
        "Cookie: stlc-1=wrong\r\n",
        "Authorization: Bearer 00000000000000000000000000000000\r\n",
        "X-Stlc-Token: 00000000000000000000000000000000\r\n",
    ] {
        for (method, path, body) in [
            ("GET", "/api/file", ""),
            ("GET", "/api/file?known=x", ""),
            ("GET", "/api/examples", ""),
            ("POST", "/api/render", render.as_str()),
            ("POST", "/api/export?format=bed", render.as_str()),
            ("POST", "/api/words", render.as_str()),
            ("POST", "/api/save", render.as_str()),
        ] {
            let a = stranger(method, path, extra, body);
            assert_eq!(a.status, 401, "{method} {path} {extra}");
            assert!(!secret(&a), "{path}");
            let said = String::from_utf8_lossy(&a.body);
            let open_the_link = said.contains("open the link printed in its terminal");
            assert!(open_the_link, "{path}");
        }
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), example("fig9.od"));
    // The page's header, and a script's.
    let save = json!({"source": "x"}).to_string();
    for extra in [
        format!("X-Stlc-Token: {}\r\n", server.token),
        format!("Authorization: Bearer {}\r\n", server.token),
    ] {
        let opened = stranger("GET", "/api/file", &extra, "");
        assert_eq!(opened.status, 200, "{extra}");
        assert_eq!(opened.json()["text"], example("fig9.od"));
        assert!(!opened.head.contains("set-cookie"));
    }
    let bearer = format!("Authorization: Bearer {}\r\n", server.token);
    assert_eq!(stranger("POST", "/api/save", &bearer, &save).status, 200);
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "x");
}

/// Light work never waits behind heavy work (issue 23, problem 8): with
/// eight heavy renders in flight ([`HEAVY`] at depth 12, each to its time
/// budget), a light render (four strokes) is answered before any of them ends.
#[test]
fn a_light_render_is_answered_while_heavy_ones_run() {
    let server = Server::start(&["--time-budget", "20"]);
    let addr = server.addr.clone();
    let streams = heavy_renders(&addr, 8);
    // Let them start and pass the light time.
    std::thread::sleep(Duration::from_millis(800));
    let mut times = Vec::new();
    for _ in 0..3 {
        let t0 = std::time::Instant::now();
        render_ok(&addr, &json!({"source": SQUARE, "kind": "lsys"}));
        times.push(t0.elapsed());
    }
    // Answered while every heavy render still runs (each to its 20 s
    // budget): a comparison, not a time, so a loaded machine that slows
    // both does not fail it.
    for mut s in streams {
        s.set_read_timeout(Some(Duration::from_millis(100)))
            .unwrap();
        let mut buf = [0u8; 64];
        let n = s.read(&mut buf).unwrap_or(0);
        let said = String::from_utf8_lossy(&buf[..n]);
        let ended = "a heavy render ended before the light ones were answered";
        assert_eq!(n, 0, "{ended} ({times:?}): {said}");
    }
}

/// A client that pipelines requests and never reads its answers is dropped
/// once a write makes no progress for 10 s (issue 23, problem 2): reading
/// afterwards gets far fewer than all the answers, then the end.
#[test]
fn a_client_that_never_reads_is_dropped() {
    let server = Server::start(&[]);
    let addr = &server.addr;
    let body = json!({"source": example("hilbert.lsys"), "kind": "lsys", "depth": 9}).to_string();
    let one = request(addr, "POST", "/api/render", &[], body.as_bytes());
    assert_eq!(one.status, 200);
    // A merged SVG of a picture's worth of lines (Hilbert's are 1.4 px).
    let size = one.body.len();
    assert!(size > 1_000_000, "{size}");
    let n = 40;
    let mut s = TcpStream::connect(addr).unwrap();
    let head = post_head(addr, "/api/render", body.len());
    for _ in 0..n {
        s.write_all(head.as_bytes()).unwrap();
        s.write_all(body.as_bytes()).unwrap();
    }
    std::thread::sleep(Duration::from_secs(14));
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let mut got = Vec::new();
    let _ = s.read_to_end(&mut got);
    let (came, all) = (got.len(), n * size);
    let kept = format!("{came} of {all} bytes came: the connection was kept");
    assert!(got.len() < n * size / 2, "{kept}");
    // The server still answers others.
    render_ok(addr, &json!({"source": example("fig9.od")}));
}

/// Slowloris (issue 23, problem 7): 300 connections that send their head a
/// byte at a time and never finish do not keep the page from loading: past
/// the connection count the idlest makes room, so `GET /` and a light
/// render are answered well inside the heads' 10 s timeout.
#[test]
fn slow_heads_cannot_fill_the_server() {
    let server = Server::start(&[]);
    let addr = server.addr.clone();
    let mut slow: Vec<TcpStream> = Vec::new();
    for _ in 0..300 {
        let mut s = TcpStream::connect(&addr).unwrap();
        s.write_all(b"GET / HTTP/1.1\r\nHo").unwrap();
        slow.push(s);
    }
    let mut times = Vec::new();
    for _ in 0..3 {
        for s in slow.iter_mut() {
            let _ = s.write_all(b"s");
        }
        let t0 = std::time::Instant::now();
        let page = get(&addr, "/");
        render_ok(&addr, &json!({"source": example("fig9.od")}));
        times.push(t0.elapsed());
        assert_eq!(page.status, 200);
    }
    // Before, the 64 connection slots were full and the page waited for
    // the slow heads' 10 s timeout.
    // Half the heads' timeout: what the page waited before, twice over.
    times.sort();
    assert!(times[1] < Duration::from_secs(5), "{times:?}");
    drop(slow);
}

/// The served file is read with bounds (issue 36, problems 2 and 3): with
/// a named pipe in its place, 20 `GET /api/file` are each answered at
/// once with what is wrong (before, each held a pool thread for good, and
/// a small render then timed out); a link to `/dev/zero` and a 10 GB
/// sparse file are refused without reading them, and the server's
/// resident size stays small.
#[test]
fn the_served_file_is_read_with_bounds() {
    let (_dir, file, server) = serve_file("tree.od", &example("fig9.od"), &[]);
    let addr = server.addr.clone();
    std::fs::remove_file(&file).unwrap();
    let made = Command::new("mkfifo").arg(&file).status().unwrap();
    assert!(made.success());
    let t0 = std::time::Instant::now();
    let asks: Vec<_> = (0..20)
        .map(|_| {
            let addr = addr.clone();
            std::thread::spawn(move || get(&addr, "/api/file"))
        })
        .collect();
    for a in asks {
        let a = a.join().unwrap();
        assert_eq!(a.status, 500);
        let e = a.json()["error"].as_str().unwrap().to_string();
        assert!(e.contains("a named pipe, not a regular file"), "{e}");
    }
    render_ok(&addr, &json!({"source": example("fig9.od")}));
    assert!(t0.elapsed() < Duration::from_secs(10), "{:?}", t0.elapsed());
    std::fs::remove_file(&file).unwrap();

    std::os::unix::fs::symlink("/dev/zero", &file).unwrap();
    let error = || get(&addr, "/api/file").json()["error"].to_string();
    let e = error();
    assert!(e.contains("a device, not a regular file"), "{e}");
    std::fs::remove_file(&file).unwrap();
    std::fs::File::create(&file)
        .unwrap()
        .set_len(10 << 30)
        .unwrap();
    let e = error();
    assert!(e.contains("more than --max-input"), "{e}");
    let rss = server.status_kb("VmRSS:");
    assert!(rss < 200_000, "{rss} kB resident");
}

/// `n` heavy renders ([`HEAVY`] at depth 12, many seconds each) sent on
/// their own connections, whose answers are read (or not) by the caller.
fn heavy_renders(addr: &str, n: usize) -> Vec<TcpStream> {
    let heavy = json!({"source": HEAVY, "kind": "lsys", "depth": 12}).to_string();
    let streams = (0..n).map(|_| send_render(addr, &heavy));
    let read_within = |s: TcpStream| {
        s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
        s
    };
    streams.map(read_within).collect()
}

/// A light render: four unit strokes (a debug build draws it in a few
/// milliseconds of processor, far under the server's fresh allowance
/// however loaded the machine; fig9, at 30 ms, came near it).
const SQUARE: &str = "axiom F\nrule F -> F+F\nangle 90\ngenerations 2\n";

/// Memory is given back (issue 36, problem 5): after two 200,000-stem
/// growths at once (measured: 98 MB above the fresh size at their peak, 14
/// MB above it idle) the idle server's resident size returns to within
/// 25 MB of its fresh size (before, the allocator kept what they freed:
/// 8 x 3 such growths left it 51 MB above; benches/light_lane.py is the
/// soak). The growths must first have raised it by 40 MB or more, so that
/// there was something to give back.
#[test]
fn memory_freed_after_a_burst_goes_back_to_the_system() {
    // Two growths run at once (the heavy slots): a time budget a loaded
    // CI machine cannot run past.
    let server = Server::start(&["--time-budget", "300"]);
    let addr = server.addr.clone();
    let big = std::fs::read_to_string(manifest_path("benches/bigtree.od")).unwrap();
    let fresh = server.status_kb("VmRSS:");
    let peak = AtomicU64::new(fresh);
    let growths: Vec<_> = (0..2)
        .map(|_| {
            let (addr, big) = (addr.clone(), big.clone());
            // A growth the server is too busy for now (503, with the rest
            // of the suite running beside it) is asked again.
            std::thread::spawn(move || {
                let mut answer = json!(null);
                for _ in 0..10 {
                    let body = json!({ "source": big }).to_string();
                    let a = request(&addr, "POST", "/api/render", &[], body.as_bytes());
                    answer = a.json();
                    if a.status == 200 && answer["ok"] == true {
                        break;
                    }
                    std::thread::sleep(Duration::from_secs(1));
                }
                answer
            })
        })
        .collect();
    while growths.iter().any(|g| !g.is_finished()) {
        peak.fetch_max(server.status_kb("VmRSS:"), Ordering::Relaxed);
        std::thread::sleep(Duration::from_millis(50));
    }
    for g in growths {
        let answer = g.join().unwrap();
        assert_eq!(answer["ok"], true, "{answer}");
    }
    let peak = peak.load(Ordering::Relaxed);
    // The server looks every 2 s whether it is idle.
    std::thread::sleep(Duration::from_secs(5));
    let idle = server.status_kb("VmRSS:");
    let seen = format!("fresh {fresh} kB, peak {peak} kB");
    assert!(peak > fresh + 40_000, "{seen}: too little to give back");
    let kept = format!("{seen}, idle {idle} kB: not given back");
    assert!(idle < fresh + 25_000, "{kept}");
}

/// A light lane heavy work cannot starve (issue 36, problem 4): with 40
/// heavy renders in flight (before, heavy work waiting for its 2 slots held
/// every pool thread, and `/api/file` and a small render waited for one:
/// 58 s), `GET /api/file` and a light render are answered before any heavy
/// render ends (they run to their 30 s budget); heavy work past a bounded
/// queue is refused with 503 and `Retry-After`.
#[test]
fn light_work_is_answered_while_forty_heavy_ones_wait() {
    let (_dir, _, server) = serve_file("tree.od", &example("fig9.od"), &["--time-budget", "30"]);
    let addr = server.addr.clone();
    let streams = heavy_renders(&addr, 40);
    // Let them start and be sorted: 2 running, 16 waiting, the rest
    // refused (each after using 50 ms of processor: the burst of 40
    // starting at once is not what is measured here).
    std::thread::sleep(Duration::from_secs(3));
    let mut times = Vec::new();
    for _ in 0..5 {
        let t0 = std::time::Instant::now();
        let opened = get(&addr, "/api/file");
        render_ok(&addr, &json!({"source": SQUARE, "kind": "lsys"}));
        times.push(t0.elapsed());
        assert_eq!(opened.status, 200);
    }
    // Before, a light request waited for a heavy one to end (58 s once);
    // now all five are answered while the two running heavy renders are
    // still inside their 30 s budget: no heavy answer has come yet. (A
    // comparison of the two, not a time: a loaded machine slows both.
    // benches/light_lane.py measures the times: p99 under 1 s in the
    // release build with 120 heavy clients.)
    // Past the queue: 503 with Retry-After. Each of the 40 is sorted after
    // its fresh allowance of processor, which a loaded machine stretches:
    // the streams are read in turns until the 22 past the 2 slots and the
    // 16 places have their answer, or 20 s have gone (the running ones'
    // budget is 30 s).
    let (mut finished, mut busy) = (0, 0);
    let mut open: Vec<TcpStream> = streams;
    let deadline = std::time::Instant::now() + Duration::from_secs(20);
    while busy < 40 - 2 - 16 && std::time::Instant::now() < deadline {
        let mut still = Vec::new();
        for mut s in open {
            s.set_read_timeout(Some(Duration::from_millis(20))).unwrap();
            let mut buf = [0u8; 4096];
            match s.read(&mut buf) {
                Ok(n) if n > 0 => {
                    let head = String::from_utf8_lossy(&buf[..n]).to_ascii_lowercase();
                    if head.starts_with("http/1.1 503") {
                        assert!(head.contains("retry-after: "), "{head}");
                        busy += 1;
                    } else {
                        finished += 1;
                    }
                }
                _ => still.push(s),
            }
        }
        open = still;
    }
    let ended = "a heavy render ended before the light requests were answered";
    assert_eq!(finished, 0, "{ended} ({times:?})");
    assert_eq!(busy, 40 - 2 - 16, "{busy} of 40 were told to come back");
}
