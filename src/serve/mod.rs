//! `stlc serve`: the Tree Maker and Tree Renderer in a web browser
//! (binary only). An HTTP server on 127.0.0.1 serves one embedded page
//! and a small JSON API ([`api`]) that calls the library's pipeline.
//!
//! Security model (docs/serve.md): the server listens on the loopback
//! interface only; a request whose `Host` is not `127.0.0.1:PORT` or
//! `localhost:PORT` is refused (DNS rebinding), as is a POST whose `Origin`
//! is another site's; no path or file name ever comes from a request (Save
//! writes the one file named on the command line, and only with the
//! per-run random token the page carries); request heads, bodies and the
//! work of each request are bounded (the `--max-*` limits), heads and bodies
//! must arrive in time, and the pipeline runs on a small pool of threads
//! apart from the connections, so one slow request never stops the others.

mod api;
mod assets;

use std::convert::Infallible;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use http_body_util::{BodyExt, Full, Limited};
use hyper::body::{Bytes, Incoming};
use hyper::header::{CONTENT_LENGTH, CONTENT_TYPE, HOST, HeaderValue, ORIGIN};
use hyper::{Method, Request, Response, StatusCode};
use hyper_util::rt::{TokioIo, TokioTimer};
use serde_json::{Value, json};

use crate::cli::args::ServeArgs;
use crate::frontend::io::{Input, Output};
use crate::frontend::report;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use stlc::pipeline;
use stlc::syntax::InputKind;

/// Set once the server runs: Ctrl-C then stops it with exit status 0.
pub static SERVING: AtomicBool = AtomicBool::new(false);

/// The page, embedded: no request leaves the machine.
const PAGE: &str = include_str!("page/index.html");

/// The example opened when no file is named.
const EXAMPLE: &str = include_str!("../../examples/2dtree.od");

/// Largest request head (request line and headers), bytes.
const MAX_HEAD: usize = 16 * 1024;

/// Connections served at once; more wait to be accepted.
const MAX_CONNECTIONS: usize = 64;

/// Threads that run the pipeline; more requests wait for one.
const WORKERS: usize = 4;

/// Time a client has to send a request head, and a body.
const HEAD_TIMEOUT: Duration = Duration::from_secs(10);
const BODY_TIMEOUT: Duration = Duration::from_secs(30);

/// Stack of the pipeline threads (as the CLI's worker: a second line of
/// defence; no pass recurses on input depth). Pages are committed only
/// when touched.
const WORKER_STACK: usize = 256 << 20;

/// What every request sees.
struct State {
    settings: api::Settings,
    /// The file Save writes, if one was named.
    file: Option<PathBuf>,
    /// The text opened, its kind and name.
    opened: (String, InputKind, String),
    /// The per-run secret Save requires.
    token: String,
    /// The `Host` values accepted.
    hosts: [String; 2],
    /// The `Origin` values accepted.
    origins: [String; 2],
}

/// Runs `stlc serve` until Ctrl-C; returns the exit code.
pub fn run(a: &ServeArgs, _quiet: bool, color: bool) -> ExitCode {
    match serve(a) {
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

fn serve(a: &ServeArgs) -> Result<(), Diagnostics> {
    let limits = a.derive_limits.limits(&a.limits, a.max_stems);
    let (file, opened) = match &a.file {
        Some(name) => {
            let input = Input::parse(name);
            let Input::Path(path) = input.clone() else {
                return Err(Diagnostic::error(ErrorKind::Io {
                    doing: "cannot serve standard input".into(),
                    error: "Save needs a file to write back".into(),
                })
                .with_help("name a file, or leave it out to start from an example")
                .into());
            };
            let bytes = input.read(limits.max_input_bytes)?;
            let kind = pipeline::detect_kind(Some(&path), &bytes)?;
            let text = String::from_utf8(bytes).map_err(|_| {
                Diagnostic::error(ErrorKind::Io {
                    doing: format!("cannot open `{}` in the editor", path.display()),
                    error: "it is not UTF-8 text".into(),
                })
            })?;
            (Some(path), (text, kind, name.clone()))
        }
        None => (
            None,
            (EXAMPLE.to_string(), InputKind::Od, "2dtree.od".into()),
        ),
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
            max_stems_explicit: a.max_stems.is_some(),
            max_svg_segments: a.max_svg_segments,
        },
        file,
        opened,
        token: random_token(),
        hosts: [format!("127.0.0.1:{port}"), format!("localhost:{port}")],
        origins: [
            format!("http://127.0.0.1:{port}"),
            format!("http://localhost:{port}"),
        ],
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
        writeln!(out, "http://127.0.0.1:{port}/")
            .and_then(|()| out.flush())
            .map_err(|e| io_error(&e, "cannot write to standard output"))?;
    }
    SERVING.store(true, std::sync::atomic::Ordering::SeqCst);
    runtime.block_on(accept_loop(listener, state))
}

/// Accepts connections for ever, at most [`MAX_CONNECTIONS`] at once.
async fn accept_loop(
    listener: std::net::TcpListener,
    state: Arc<State>,
) -> Result<(), Diagnostics> {
    let listener =
        tokio::net::TcpListener::from_std(listener).map_err(|e| io_error(&e, "cannot listen"))?;
    let slots = Arc::new(tokio::sync::Semaphore::new(MAX_CONNECTIONS));
    loop {
        let Ok(permit) = slots.clone().acquire_owned().await else {
            return Ok(());
        };
        let stream = match listener.accept().await {
            Ok((stream, _)) => stream,
            // Out of file descriptors and the like: wait, then go on.
            Err(_) => {
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        let state = state.clone();
        tokio::spawn(async move {
            let _permit = permit;
            let service = hyper::service::service_fn(move |req| handle(state.clone(), req));
            let _ = hyper::server::conn::http1::Builder::new()
                .timer(TokioTimer::new())
                .header_read_timeout(HEAD_TIMEOUT)
                .max_buf_size(MAX_HEAD)
                .serve_connection(TokioIo::new(stream), service)
                .await;
        });
    }
}

type Answer = Response<Full<Bytes>>;

/// A response with the headers every answer carries.
fn answer(status: StatusCode, media: &str, body: impl Into<Bytes>) -> Answer {
    let mut r = Response::new(Full::new(body.into()));
    *r.status_mut() = status;
    let h = r.headers_mut();
    if let Ok(v) = HeaderValue::from_str(media) {
        h.insert(CONTENT_TYPE, v);
    }
    h.insert("cache-control", HeaderValue::from_static("no-store"));
    h.insert(
        "x-content-type-options",
        HeaderValue::from_static("nosniff"),
    );
    h.insert(
        "content-security-policy",
        HeaderValue::from_static(
            "default-src 'self'; img-src 'self' data: blob:; style-src 'self' 'unsafe-inline'; \
             frame-ancestors 'none'",
        ),
    );
    r
}

fn json_answer(status: StatusCode, v: &Value) -> Answer {
    answer(status, "application/json", v.to_string())
}

fn error_answer(status: StatusCode, message: &str) -> Answer {
    json_answer(status, &json!({"ok": false, "error": message}))
}

async fn handle(state: Arc<State>, req: Request<Incoming>) -> Result<Answer, Infallible> {
    Ok(route(&state, req).await)
}

async fn route(state: &Arc<State>, req: Request<Incoming>) -> Answer {
    let host = req.headers().get(HOST).and_then(|h| h.to_str().ok());
    if !host.is_some_and(|h| state.hosts.iter().any(|a| a == h)) {
        return error_answer(
            StatusCode::FORBIDDEN,
            "this server answers only to 127.0.0.1 or localhost on its own port",
        );
    }
    let method = req.method().clone();
    let path = req.uri().path().to_string();
    if method == Method::POST {
        let origin = req.headers().get(ORIGIN).map(|o| o.to_str().unwrap_or(""));
        if let Some(o) = origin
            && !state.origins.iter().any(|a| a == o)
        {
            return error_answer(
                StatusCode::FORBIDDEN,
                "requests from other sites are refused",
            );
        }
    }
    match (&method, path.as_str()) {
        (&Method::GET, "/") => answer(
            StatusCode::OK,
            "text/html; charset=utf-8",
            PAGE.replace("{{TOKEN}}", &state.token),
        ),
        (&Method::GET, p) if let Some(a) = assets::find(p) => {
            answer(StatusCode::OK, a.media, a.body)
        }
        (&Method::GET, "/api/file") => {
            let (text, kind, name) = &state.opened;
            json_answer(
                StatusCode::OK,
                &json!({
                    "text": text,
                    "kind": kind_name(*kind),
                    "name": name,
                    "can_save": state.file.is_some(),
                }),
            )
        }
        (&Method::POST, "/api/render" | "/api/export" | "/api/save") => {
            let token_ok = req
                .headers()
                .get("x-stlc-token")
                .and_then(|t| t.to_str().ok())
                .is_some_and(|t| same_secret(t, &state.token));
            let format = req
                .uri()
                .query()
                .and_then(|q| q.strip_prefix("format="))
                .map(str::to_string);
            let body = match read_body(req, state.settings.limits.max_input_bytes).await {
                Ok(b) => b,
                Err(a) => return a,
            };
            let (request, _) = match api::parse_request(&body) {
                Ok(r) => r,
                Err(api::BadRequest(m)) => return error_answer(StatusCode::BAD_REQUEST, &m),
            };
            let state = state.clone();
            match path.as_str() {
                "/api/render" => {
                    let v = blocking(move || api::render(&request, &state.settings)).await;
                    match v {
                        Some(v) => json_answer(StatusCode::OK, &v),
                        None => error_answer(
                            StatusCode::INTERNAL_SERVER_ERROR,
                            "stlc crashed; this is a bug",
                        ),
                    }
                }
                "/api/export" => {
                    let Some(format) =
                        format.filter(|f| ["png", "svg", "bed"].contains(&f.as_str()))
                    else {
                        return error_answer(
                            StatusCode::BAD_REQUEST,
                            "say ?format=png, ?format=svg or ?format=bed",
                        );
                    };
                    let r = blocking(move || api::export(&request, &state.settings, &format)).await;
                    match r {
                        Some(Ok((bytes, media))) => answer(StatusCode::OK, media, bytes),
                        Some(Err(v)) => json_answer(StatusCode::OK, &v),
                        None => error_answer(
                            StatusCode::INTERNAL_SERVER_ERROR,
                            "stlc crashed; this is a bug",
                        ),
                    }
                }
                _ => {
                    if !token_ok {
                        return error_answer(
                            StatusCode::FORBIDDEN,
                            "saving needs the page's token",
                        );
                    }
                    let Some(file) = state.file.clone() else {
                        return error_answer(
                            StatusCode::CONFLICT,
                            "no file was named on the command line: the page downloads instead",
                        );
                    };
                    let text = request.source;
                    let r = blocking(move || {
                        Output::Path(file).write_with(|w| {
                            w.write_all(text.as_bytes())
                                .map_err(|e| io_error(&e, "cannot write the file").into())
                        })
                    })
                    .await;
                    match r {
                        Some(Ok(())) => json_answer(StatusCode::OK, &json!({"ok": true})),
                        Some(Err(d)) => {
                            let list: Vec<Diagnostic> = d.iter().cloned().collect();
                            json_answer(
                                StatusCode::OK,
                                &json!({"ok": false, "diagnostics": api::diagnostics_json("", &list)}),
                            )
                        }
                        None => error_answer(
                            StatusCode::INTERNAL_SERVER_ERROR,
                            "stlc crashed; this is a bug",
                        ),
                    }
                }
            }
        }
        (_, "/" | "/api/file" | "/api/render" | "/api/export" | "/api/save") => {
            error_answer(StatusCode::METHOD_NOT_ALLOWED, "wrong method")
        }
        (_, p) if assets::find(p).is_some() => {
            error_answer(StatusCode::METHOD_NOT_ALLOWED, "wrong method")
        }
        _ => error_answer(StatusCode::NOT_FOUND, "not found"),
    }
}

/// Runs pipeline work on the pool of [`WORKERS`] threads; `None` if it
/// panicked (a bug; the server goes on).
async fn blocking<T: Send + 'static>(work: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    tokio::task::spawn_blocking(work).await.ok()
}

/// Reads a body of at most `limit` bytes in [`BODY_TIMEOUT`]: 413 over the
/// limit, 408 too slow, 400 broken.
async fn read_body(req: Request<Incoming>, limit: u64) -> Result<Bytes, Answer> {
    let too_large = || {
        error_answer(
            StatusCode::PAYLOAD_TOO_LARGE,
            "the request is larger than --max-input",
        )
    };
    let declared = req
        .headers()
        .get(CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok());
    if declared.is_some_and(|n| n > limit) {
        return Err(too_large());
    }
    let limit = usize::try_from(limit).unwrap_or(usize::MAX);
    let collected =
        tokio::time::timeout(BODY_TIMEOUT, Limited::new(req.into_body(), limit).collect());
    match collected.await {
        Err(_) => Err(error_answer(
            StatusCode::REQUEST_TIMEOUT,
            "the body came too slowly",
        )),
        Ok(Err(e)) if e.is::<http_body_util::LengthLimitError>() => Err(too_large()),
        Ok(Err(_)) => Err(error_answer(
            StatusCode::BAD_REQUEST,
            "the body could not be read",
        )),
        Ok(Ok(c)) => Ok(c.to_bytes()),
    }
}

fn kind_name(k: InputKind) -> &'static str {
    match k {
        InputKind::Od => "od",
        InputKind::Bed => "bed",
        InputKind::Lsys => "lsys",
    }
}

/// Compares secrets in time independent of where they differ.
fn same_secret(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

/// 128 random bits as hex: from the system's random source, or (where
/// there is none to read) from std's randomly keyed hashers.
fn random_token() -> String {
    let mut bytes = [0u8; 16];
    let read = std::fs::File::open("/dev/urandom")
        .and_then(|mut f| std::io::Read::read_exact(&mut f, &mut bytes));
    if read.is_err() {
        use std::hash::{BuildHasher, Hasher};
        for chunk in bytes.chunks_mut(8) {
            let mut h = std::collections::hash_map::RandomState::new().build_hasher();
            h.write_u128(
                std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_nanos()),
            );
            chunk.copy_from_slice(&h.finish().to_le_bytes());
        }
    }
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}
