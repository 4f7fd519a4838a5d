//! The routes: one handler each, behind the one guard.
//!
//! | route | handler |
//! | --- | --- |
//! | `GET /` | [`page`]: the editor, with the per-run token |
//! | `GET /<asset>` | [`asset`]: the page's scripts and style |
//! | `GET /api/file` | [`file`]: the text opened |
//! | `POST /api/render` | [`render`]: the picture, BED and growth order as JSON |
//! | `POST /api/export?format=png\|svg\|bed\|glb` | [`export`]: the file's bytes |
//! | `POST /api/save` | [`save`]: the text written back (token required) |

use std::sync::Arc;

use hyper::body::Incoming;
use hyper::{Method, Request, StatusCode};
use serde::Serialize;

use super::assets;
use super::compact;
use super::document::Refused;
use super::http::{self, Answer};
use super::memory::{self, Reservation};
use super::state::State;
use super::templates;
use super::work::{self, Ended, Stopped};
use stlc::api::{self, Body, Failed, Format, Kind};
use stlc::diag::Diagnostic;
use stlc::pipeline::ImageFormat;

/// Answers one request.
pub async fn route(state: Arc<State>, req: Request<Incoming>) -> Answer {
    if let Err(refused) = state.guard.check(&req) {
        return refused.answer();
    }
    // Only the owner: every API call, reads included, carries the key in
    // a header (the page has it from the printed link's fragment); the
    // page and its scripts are public code and name no file.
    if req.uri().path().starts_with("/api/") && !state.key.admits(&req) {
        return http::locked();
    }
    let method = req.method().clone();
    let path = req.uri().path().to_string();
    let expected = match path.as_str() {
        "/" | "/api/file" | "/api/examples" => Method::GET,
        "/api/render" | "/api/export" | "/api/save" | "/api/words" => Method::POST,
        p if assets::find(p).is_some() => Method::GET,
        _ => return http::error(StatusCode::NOT_FOUND, "not found"),
    };
    if method != expected {
        return http::error(StatusCode::METHOD_NOT_ALLOWED, "wrong method");
    }
    match path.as_str() {
        "/" => page(),
        "/api/file" => file(state, req).await,
        "/api/examples" => examples(),
        "/api/render" => render(state, req).await,
        "/api/export" => export(state, req).await,
        "/api/save" => save(state, req).await,
        "/api/words" => words(state, req).await,
        p => asset(p),
    }
}

/// `GET /`: the page (public code: no key, no file name).
fn page() -> Answer {
    http::answer(StatusCode::OK, "text/html; charset=utf-8", assets::PAGE)
}

/// `GET /<asset>`: an embedded script or style sheet.
fn asset(path: &str) -> Answer {
    match assets::find(path) {
        Some(a) => http::answer(StatusCode::OK, a.media, a.body),
        None => http::error(StatusCode::NOT_FOUND, "not found"),
    }
}

/// `GET /api/file`: the file as it is now: `{"text", "version", "kind",
/// "name", "path", "can_save"}`; `version` is `null` for a file that does
/// not exist yet (its text is a template; Save creates it). With
/// `?known=V` (a page watching the file) and the file still at version V:
/// `{"version": V, "unchanged": true}`, told from its metadata when it can
/// be, without reading or sending the text. The file is read on the pool,
/// not on the connections' threads.
async fn file(state: Arc<State>, req: Request<Incoming>) -> Answer {
    #[derive(Serialize)]
    struct Opened {
        text: String,
        version: Option<String>,
        kind: Kind,
        name: String,
        path: String,
        can_save: bool,
    }
    #[derive(Serialize)]
    struct Unchanged {
        version: String,
        unchanged: bool,
    }
    let known = http::query_param(req.uri().query(), "known");
    let done = blocking(move || -> Result<Answer, stlc::diag::Diagnostics> {
        let doc = &state.doc;
        if let Some(k) = &known
            && doc.unchanged_since(k)
        {
            return Ok(http::json(
                StatusCode::OK,
                &Unchanged {
                    version: k.clone(),
                    unchanged: true,
                },
            ));
        }
        let now = doc.current()?;
        if let (Some(k), Some(v)) = (&known, &now.version)
            && k == v
        {
            return Ok(http::json(
                StatusCode::OK,
                &Unchanged {
                    version: v.clone(),
                    unchanged: true,
                },
            ));
        }
        Ok(http::json(
            StatusCode::OK,
            &Opened {
                text: now.text,
                version: now.version,
                kind: doc.kind.into(),
                name: doc.name.clone(),
                path: doc.key(),
                can_save: doc.can_save(),
            },
        ))
    })
    .await;
    match done {
        Some(Ok(answer)) => answer,
        Some(Err(d)) => http::error(
            StatusCode::INTERNAL_SERVER_ERROR,
            &d.iter()
                .map(|d| d.kind.to_string())
                .collect::<Vec<_>>()
                .join("; "),
        ),
        None => crashed(),
    }
}

/// `GET /api/examples`: `[{"name", "kind", "text"}]`: the templates a new
/// file starts from (`new.od`, `new.lsys`), then every example, for the
/// page's New menu.
fn examples() -> Answer {
    #[derive(Serialize)]
    struct Example {
        name: &'static str,
        kind: Kind,
        text: &'static str,
    }
    let templates = [("new.od", templates::OD), ("new.lsys", templates::LSYS)];
    let list: Vec<Example> = templates
        .iter()
        .chain(super::examples::EXAMPLES)
        .map(|&(name, text)| Example {
            name,
            kind: stlc::pipeline::InputKind::from_path(std::path::Path::new(name))
                .unwrap_or(stlc::pipeline::InputKind::Od)
                .into(),
            text,
        })
        .collect();
    http::json(StatusCode::OK, &list)
}

/// Reads and parses a request body: the answer to send instead if it is
/// too large, too slow or not what the API takes.
async fn body(state: &State, req: Request<Incoming>) -> Result<Body, Answer> {
    let bytes = http::read_body(req, state.settings.limits.max_input_bytes).await?;
    api::parse(&bytes).map_err(|api::BadRequest(m)| http::error(StatusCode::BAD_REQUEST, &m))
}

/// Memory for a request's work, reserved before its body is read (from
/// its declared length; an undeclared one may be as long as
/// `--max-input`): the answer to send instead if there is none.
async fn admit(state: &State, req: &Request<Incoming>) -> Result<Reservation, Answer> {
    let max = state.settings.limits.max_input_bytes;
    let len = http::declared_length(req).unwrap_or(max).min(max);
    reserve(state, memory::need(len)).await
}

/// Reserves `need` bytes of the memory budget, or says why not.
async fn reserve(state: &State, need: u64) -> Result<Reservation, Answer> {
    state
        .memory
        .admit(need, memory::ADMIT_WAIT)
        .await
        .map_err(refused)
}

/// The answer to a request the memory budget has no room for.
fn refused(r: memory::Refused) -> Answer {
    http::error(StatusCode::SERVICE_UNAVAILABLE, &memory::refusal(r))
}

/// What a call on a request's body ended in: its memory reserved, its
/// body read, the call run on the pool within the time budget, the heavy
/// slots and the memory budget (`work`, `memory`). `png` says whether the
/// call paints a PNG (its pixels reserved once the body says its size).
async fn call<T: Send + 'static>(
    state: Arc<State>,
    req: Request<Incoming>,
    png: bool,
    // Run again from the start if heavy work waited for a slot (`work`).
    call: impl Fn(&Body, &api::Settings, &mut dyn stlc::pipeline::Progress) -> T + Send + Sync + 'static,
) -> Result<Ended<T>, Answer> {
    let reserved = admit(&state, &req).await?;
    let body = body(&state, req).await?;
    // A big PNG's pixels, reserved once the body says its size.
    let pixels = match (png, body.size) {
        (true, Some([w, h])) => Some(reserve(&state, memory::png_need(w, h)).await?),
        _ => None,
    };
    let (budget, slots) = (state.settings.time_budget, state.heavy.clone());
    let memory = Some(state.memory.clone());
    let heavy = body.source.len() > work::BIG_INPUT || pixels.is_some();
    Ok(work::run(budget, slots, memory, heavy, move |w| {
        let _held = (&reserved, &pixels);
        call(&body, &state.settings, w)
    })
    .await)
}

/// `POST /api/render`: the answer as JSON (HTTP 200 once the request itself
/// is well formed, the input's errors as diagnostics); a big grown tree
/// is left out of the SVG, and its stems come as a compact body to a
/// client that accepts one (`compact`).
async fn render(state: Arc<State>, req: Request<Incoming>) -> Answer {
    let accept = req.headers().get(hyper::header::ACCEPT);
    let compact = compact::accepted(accept.and_then(|v| v.to_str().ok()));
    let big = Some(compact::BIG_TREE_STEMS);
    let done = match call(state, req, false, move |b, s, w| {
        api::render(b, s, ImageFormat::Svg, big, w)
    })
    .await
    {
        Ok(d) => d,
        Err(a) => return a,
    };
    match done {
        Ended::Done(Ok((answer, _))) if compact && !answer.tree_in_svg => {
            match compact::body(answer) {
                Ok(bytes) => http::answer(StatusCode::OK, compact::MEDIA, bytes),
                Err(answer) => http::json(StatusCode::OK, &answer),
            }
        }
        Ended::Done(Ok((answer, _))) => http::json(StatusCode::OK, &answer),
        Ended::Done(Err(failed)) => http::json(StatusCode::OK, &failed),
        Ended::Stopped(why) => stopped(why),
        Ended::Crashed => crashed(),
    }
}

/// `POST /api/export?format=png|svg|bed|glb`: the file's bytes and media type,
/// or the diagnostics as JSON.
async fn export(state: Arc<State>, req: Request<Incoming>) -> Answer {
    let format = http::query_param(req.uri().query(), "format");
    let Some(format) = format.as_deref().and_then(Format::from_name) else {
        return http::error(
            StatusCode::BAD_REQUEST,
            "say ?format=png, ?format=svg, ?format=bed or ?format=glb",
        );
    };
    let png = format == Format::Png;
    let done = match call(state, req, png, move |b, s, w| api::export(b, s, format, w)).await {
        Ok(d) => d,
        Err(a) => return a,
    };
    match done {
        Ended::Done(Ok(bytes)) => http::answer(StatusCode::OK, format.media(), bytes),
        Ended::Done(Err(failed)) => http::json(StatusCode::OK, &failed),
        Ended::Stopped(why) => stopped(why),
        Ended::Crashed => crashed(),
    }
}

/// `POST /api/words`: an `.lsys`'s word generation by generation (depth 0
/// up to its depth, at most [`api::WORD_DEPTHS`] of them), each cut at
/// [`api::WORD_CHARS`] characters, with its exact length: for teaching.
async fn words(state: Arc<State>, req: Request<Incoming>) -> Answer {
    let done = match call(state, req, false, api::words).await {
        Ok(d) => d,
        Err(a) => return a,
    };
    match done {
        Ended::Done(Ok(answer)) => http::json(StatusCode::OK, &answer),
        Ended::Done(Err(failed)) => http::json(StatusCode::OK, &failed),
        Ended::Stopped(why) => stopped(why),
        Ended::Crashed => crashed(),
    }
}

/// `POST /api/save`: writes the text to the file named on the command
/// line, atomically (the key was checked with every API call's), and only
/// over the version the edit is based on: otherwise 412 with the version
/// there now.
async fn save(state: Arc<State>, req: Request<Incoming>) -> Answer {
    let bytes = match http::read_body(req, state.settings.limits.max_input_bytes).await {
        Ok(b) => b,
        Err(a) => return a,
    };
    let body = match api::parse_save(&bytes) {
        Ok(b) => b,
        Err(api::BadRequest(m)) => return http::error(StatusCode::BAD_REQUEST, &m),
    };
    #[derive(Serialize)]
    struct Saved {
        ok: bool,
        version: Option<String>,
        #[serde(skip_serializing_if = "Option::is_none")]
        error: Option<&'static str>,
    }
    let done = blocking(move || {
        state
            .doc
            .save(&body.source, body.version.as_ref().map(|v| v.as_deref()))
    })
    .await;
    match done {
        Some(Ok(version)) => http::json(
            StatusCode::OK,
            &Saved {
                ok: true,
                version: Some(version),
                error: None,
            },
        ),
        Some(Err(Refused::Changed(now))) => http::json(
            StatusCode::PRECONDITION_FAILED,
            &Saved {
                ok: false,
                version: now,
                error: Some("the file changed since this edit began (another tab or program)"),
            },
        ),
        Some(Err(Refused::NoFile)) => http::error(
            StatusCode::CONFLICT,
            "no file was named on the command line: the page downloads instead",
        ),
        Some(Err(Refused::Failed(d))) => {
            let list: Vec<Diagnostic> = d.iter().cloned().collect();
            http::json(
                StatusCode::OK,
                &Failed {
                    ok: false,
                    diagnostics: api::diagnostics_json("", &list, api::Page::Served),
                },
            )
        }
        None => crashed(),
    }
}

/// The answer for stopped work: past the budget, the diagnostics JSON
/// (HTTP 200, as for any input the work cannot finish); abandoned, a 503
/// nobody reads.
fn stopped(why: Stopped) -> Answer {
    match why {
        Stopped::OverBudget(budget) => http::json(
            StatusCode::OK,
            &Failed::message(
                &format!(
                    "stopped: the work ran past the time budget of {} s",
                    budget.as_secs_f64()
                ),
                "ask for less (a smaller depth, --max-stems, a smaller layout), or start stlc serve with --time-budget SECONDS",
            ),
        ),
        Stopped::OverMemory { live, budget } => http::error(
            StatusCode::SERVICE_UNAVAILABLE,
            &format!(
                "stopped: the server held {} MiB, over its memory budget of {} MiB (--memory-budget); try again in a moment, or ask for less",
                memory::mib(live),
                memory::mib(budget)
            ),
        ),
        Stopped::Abandoned => http::error(
            StatusCode::SERVICE_UNAVAILABLE,
            "stopped: the request was abandoned",
        ),
        Stopped::Busy => http::busy(work::RETRY_AFTER),
    }
}

fn crashed() -> Answer {
    http::error(
        StatusCode::INTERNAL_SERVER_ERROR,
        "stlc crashed; this is a bug",
    )
}

/// Runs pipeline work on the blocking pool; `None` if it panicked (a bug;
/// the server goes on).
async fn blocking<T: Send + 'static>(work: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    tokio::task::spawn_blocking(work).await.ok()
}
