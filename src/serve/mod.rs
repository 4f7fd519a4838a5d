//! `stlc serve`: the Tree Maker and Tree Renderer in a web browser
//! (binary only). An HTTP server on 127.0.0.1 serves one embedded page
//! and a small JSON API ([`api`]) that calls the library's pipeline.
//!
//! Security model (docs/serve.md): only its owner can reach it: the link
//! it prints carries a per-run secret in its fragment (never sent to a
//! server), which the page keeps in its tab's sessionStorage and sends in
//! a header on every API call; no cookie carries it (cookies go to every
//! port of 127.0.0.1). The page itself is public code and names no file;
//! another local account, or another local port, learns nothing else and
//! changes nothing. It listens on the loopback
//! interface only; a request whose `Host` is not `127.0.0.1:PORT` or
//! `localhost:PORT` is refused (DNS rebinding), as is a POST whose `Origin`
//! is another site's; no path or file name ever comes from a request (Save
//! writes the one file named on the command line, and only with the
//! per-run random token the page carries); request heads, bodies and the
//! work of each request are bounded (the `--max-*` limits), heads and bodies
//! must arrive in time, and the pipeline runs on a small pool of threads
//! apart from the connections, so one slow request never stops the others.

mod assets;
mod compact;
mod conns;
mod document;
mod examples;
mod http;
mod memory;
mod routes;
mod stall;
mod state;
mod templates;
mod work;

use std::convert::Infallible;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

use hyper_util::rt::{TokioIo, TokioTimer};

use crate::frontend::io::Input;
use crate::frontend::{interrupt, report};
use state::State;
use stlc::api;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use stlc::pipeline::{self, InputKind, Limits};

/// What `stlc serve` is started with (the CLI builds it from its flags).
#[derive(Debug, Clone)]
pub struct Config {
    /// The file to open and save; `None`: an example, and Save downloads.
    pub file: Option<String>,
    /// Port on 127.0.0.1; 0 picks a free one.
    pub port: u16,
    /// The `--max-*` limits every request works within.
    pub limits: Limits,
    /// `--max-stems`, if given: a page's max stems above it is refused.
    pub max_stems: Option<u64>,
    /// `--max-svg-segments`.
    pub max_svg_segments: u64,
    /// `--time-budget`: how long one request's work may run.
    pub time_budget: Duration,
    /// `--memory-budget`, bytes: the most heap the server holds
    /// (`memory`).
    pub memory_budget: u64,
}

/// The example opened when no file is named.
const EXAMPLE: &str = include_str!("../../examples/2dtree.od");

/// Largest request head (request line and headers), bytes.
const MAX_HEAD: usize = 16 * 1024;

/// Threads that run the pipeline: as many as requests can be in flight
/// (one a connection, `conns::MAX_CONNECTIONS`), so a light request never
/// waits for a thread. Of these, [`HEAVY`] may run heavy work (past
/// `work::LIGHT`) at a time; heavy work waiting for its turn holds none.
/// A thread's stack is committed only where touched, and an idle thread
/// ends after 10 s.
const WORKERS: usize = conns::MAX_CONNECTIONS;

/// Heavy works that run at once (the machine's two cores' worth).
const HEAVY: usize = 2;

/// Heavy works that may wait for a slot (on no thread); more are refused
/// with 503 and `Retry-After`.
const HEAVY_QUEUE: usize = 16;

/// Time a client has to send a request head.
const HEAD_TIMEOUT: Duration = Duration::from_secs(10);

/// Stack of the pipeline threads (as the CLI's worker: a second line of
/// defence; no pass recurses on input depth). Pages are committed only
/// when touched.
const WORKER_STACK: usize = 64 << 20;

/// Runs `stlc serve` until Ctrl-C; returns the exit code.
pub fn run(config: &Config, color: bool) -> ExitCode {
    memory::tune_allocator();
    match serve(config) {
        Ok(()) => ExitCode::SUCCESS,
        Err(diags) => {
            let mut stderr = std::io::stderr().lock();
            for d in diags.iter() {
                report::write(&mut stderr, d, None, color);
            }
            ExitCode::FAILURE
        }
    }
}

fn serve(a: &Config) -> Result<(), Diagnostics> {
    let limits = a.limits;
    let memory = Arc::new(memory::Memory::new(
        a.memory_budget,
        Some(crate::frontend::heap::live_bytes),
    ));
    let doc = match &a.file {
        Some(name) => open(name, limits.max_input_bytes, &memory)?,
        None => {
            document::Document::example(EXAMPLE, "2dtree.od", InputKind::Od, limits.max_input_bytes)
        }
    };
    let listener = std::net::TcpListener::bind(("127.0.0.1", a.port))
        .and_then(|l| l.set_nonblocking(true).map(|()| l))
        .map_err(|e| io_error(&e, &format!("cannot listen on 127.0.0.1:{}", a.port)))?;
    let port = listener
        .local_addr()
        .map_err(|e| io_error(&e, "cannot read the port listened on"))?
        .port();
    let state = Arc::new(State {
        settings: api::Settings {
            limits,
            max_stems: a.max_stems,
            max_svg_segments: a.max_svg_segments,
            time_budget: a.time_budget,
            page: api::Page::Served,
        },
        doc,
        key: http::Key::new(http::random_token().map_err(|e| {
            io_error(
                &std::io::Error::other(e),
                "cannot read the system's random source",
            )
        })?),
        guard: http::Guard::new(port),
        heavy: Arc::new(work::Slots::new(HEAVY, HEAVY_QUEUE)),
        memory,
    });
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .max_blocking_threads(WORKERS)
        .thread_stack_size(WORKER_STACK)
        .enable_all()
        .build()
        .map_err(|e| io_error(&e, "cannot start the server's threads"))?;
    {
        let mut out = std::io::stdout().lock();
        // The token in the fragment: the browser never sends it (docs/serve.md).
        writeln!(out, "http://127.0.0.1:{port}/#token={}", state.key.token())
            .and_then(|()| out.flush())
            .map_err(|e| io_error(&e, "cannot write to standard output"))?;
    }
    interrupt::stop_is_success();
    work::quiet_stops();
    runtime.spawn(memory::give_back_when_idle(state.memory.clone()));
    runtime.block_on(accept_loop(listener, state))
}

/// The file named on the command line: one that exists must be UTF-8 text
/// of a known kind; one that does not yet starts from a template of the
/// kind its extension names, and the first Save creates it.
fn open(
    name: &str,
    max_bytes: u64,
    memory: &Arc<memory::Memory>,
) -> Result<document::Document, Diagnostics> {
    let Input::Path(path) = Input::parse(name) else {
        return Err(Diagnostic::error(ErrorKind::Io {
            doing: "cannot serve standard input".into(),
            error: "Save needs a file to write back".into(),
        })
        .with_help("name a file, or leave it out to start from an example")
        .into());
    };
    // A save killed midway (SIGKILL) left its temporary file beside the
    // file: remove those of processes that are gone.
    let folder = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => std::path::Path::new("."),
    };
    crate::frontend::io::sweep_stale_temps(folder);
    // Read as every request reads it: a named pipe or device is refused,
    // not waited on.
    let kind = if let Some(served) = document::read_served(&path, max_bytes, None)? {
        pipeline::detect_kind(Some(&path), &served.bytes)?
    } else {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !dir.is_dir() {
            return Err(Diagnostic::error(ErrorKind::Io {
                doing: format!("cannot start `{}`", path.display()),
                error: format!("the folder `{}` does not exist", dir.display()),
            })
            .with_help("create the folder first, or name a file in an existing one")
            .into());
        }
        InputKind::from_path(&path).ok_or_else(|| {
            Diagnostics::from(
                Diagnostic::error(ErrorKind::Io {
                    doing: format!("cannot start `{}`", path.display()),
                    error: "it does not exist, and its name says no kind".into(),
                })
                .with_help("name a new file .od, .bed or .lsys: it starts from a template"),
            )
        })?
    };
    let template = match kind {
        InputKind::Od => templates::OD,
        InputKind::Bed => templates::BED,
        InputKind::Lsys => templates::LSYS,
    };
    document::Document::file(path, name, kind, template, max_bytes, Some(memory.clone()))
}

/// Accepts connections for ever; past `conns::MAX_CONNECTIONS` the
/// idlest one makes room for each new one.
async fn accept_loop(
    listener: std::net::TcpListener,
    state: Arc<State>,
) -> Result<(), Diagnostics> {
    let listener =
        tokio::net::TcpListener::from_std(listener).map_err(|e| io_error(&e, "cannot listen"))?;
    let conns = conns::Conns::default();
    loop {
        let stream = match listener.accept().await {
            Ok((stream, _)) => stream,
            // Out of file descriptors and the like: wait, then go on.
            Err(_) => {
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        let state = state.clone();
        let ticket = conns.open();
        let mine = ticket.clone();
        let task = tokio::spawn(async move {
            let on_request = mine.clone();
            let service = hyper::service::service_fn(move |req| {
                let busy = on_request.busy();
                let state = state.clone();
                async move {
                    let answer = handle(state, req).await;
                    drop(busy);
                    answer
                }
            });
            let _ = hyper::server::conn::http1::Builder::new()
                .timer(TokioTimer::new())
                .header_read_timeout(HEAD_TIMEOUT)
                .max_buf_size(MAX_HEAD)
                .serve_connection(
                    TokioIo::new(stall::Stall::new(stream, stall::WRITE_STALL)),
                    service,
                )
                .await;
            mine.close();
        });
        ticket.set_abort(task.abort_handle());
    }
}

async fn handle(
    state: Arc<State>,
    req: hyper::Request<hyper::body::Incoming>,
) -> Result<http::Answer, Infallible> {
    Ok(routes::route(state, req).await)
}
