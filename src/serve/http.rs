//! The HTTP edge's pieces: answers with the headers every answer carries,
//! the one guard for `Host` and `Origin`, bounded bodies, query strings,
//! and the per-run secret.

use std::time::Duration;

use http_body_util::{BodyExt, Full, Limited};
use hyper::body::{Bytes, Incoming};
use hyper::header::{CONTENT_LENGTH, CONTENT_TYPE, HOST, HeaderValue, ORIGIN};
use hyper::{Method, Request, Response, StatusCode};
use serde::Serialize;

/// An answer.
pub type Answer = Response<Full<Bytes>>;

/// Time a client has to send a request body.
const BODY_TIMEOUT: Duration = Duration::from_secs(30);

/// A response with the headers every answer carries.
pub fn answer(status: StatusCode, media: &str, body: impl Into<Bytes>) -> Answer {
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

/// `value` as a JSON answer.
pub fn json(status: StatusCode, value: &impl Serialize) -> Answer {
    match serde_json::to_vec(value) {
        Ok(body) => answer(status, "application/json", body),
        Err(_) => error(StatusCode::INTERNAL_SERVER_ERROR, "cannot write the answer"),
    }
}

/// `{"ok": false, "error": message}`.
pub fn error(status: StatusCode, message: &str) -> Answer {
    #[derive(Serialize)]
    struct Error<'a> {
        ok: bool,
        error: &'a str,
    }
    match serde_json::to_vec(&Error {
        ok: false,
        error: message,
    }) {
        Ok(body) => answer(status, "application/json", body),
        Err(_) => answer(status, "text/plain", message.to_string()),
    }
}

/// Who may ask: the `Host` values and (for writes) the `Origin` values
/// this server answers to.
pub struct Guard {
    hosts: [String; 2],
    origins: [String; 2],
}

impl Guard {
    /// The guard of a server on `port` of the loopback interface.
    pub fn new(port: u16) -> Self {
        Guard {
            hosts: [format!("127.0.0.1:{port}"), format!("localhost:{port}")],
            origins: [
                format!("http://127.0.0.1:{port}"),
                format!("http://localhost:{port}"),
            ],
        }
    }

    /// Refuses a request that names another host (DNS rebinding: exactly
    /// one `Host`, ours; a request line with an absolute URL must name it
    /// too) and a POST from another site (at most one `Origin`, ours, or
    /// none, as a script's).
    pub fn check(&self, req: &Request<Incoming>) -> Result<(), Refused> {
        let foreign = || {
            Refused(
                StatusCode::FORBIDDEN,
                "this server answers only to 127.0.0.1 or localhost on its own port",
            )
        };
        let mut hosts = req.headers().get_all(HOST).iter();
        let host = match (hosts.next(), hosts.next()) {
            (Some(h), None) => h.to_str().ok(),
            (Some(_), Some(_)) => {
                return Err(Refused(
                    StatusCode::BAD_REQUEST,
                    "more than one Host header",
                ));
            }
            (None, _) => None,
        };
        if !host.is_some_and(|h| self.hosts.iter().any(|a| a == h)) {
            return Err(foreign());
        }
        if let Some(authority) = req.uri().authority()
            && !self.hosts.iter().any(|a| a == authority.as_str())
        {
            return Err(foreign());
        }
        if req.method() == Method::POST {
            let mut origins = req.headers().get_all(ORIGIN).iter();
            match (origins.next(), origins.next()) {
                (_, Some(_)) => {
                    return Err(Refused(
                        StatusCode::BAD_REQUEST,
                        "more than one Origin header",
                    ));
                }
                (Some(o), None) => {
                    let o = o.to_str().unwrap_or("");
                    if !self.origins.iter().any(|a| a == o) {
                        return Err(Refused(
                            StatusCode::FORBIDDEN,
                            "requests from other sites are refused",
                        ));
                    }
                }
                (None, None) => {}
            }
        }
        Ok(())
    }
}

/// A request the guard refused: the status and why.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Refused(pub StatusCode, pub &'static str);

impl Refused {
    /// The answer that says so.
    pub fn answer(self) -> Answer {
        error(self.0, self.1)
    }
}

/// 503 for heavy work past the queue for the heavy slots, with
/// `Retry-After: seconds`.
pub fn busy(seconds: u64) -> Answer {
    let mut a = error(
        StatusCode::SERVICE_UNAVAILABLE,
        &format!(
            "the server is busy with other heavy work (its queue is full): try again in {seconds} s"
        ),
    );
    a.headers_mut()
        .insert(hyper::header::RETRY_AFTER, HeaderValue::from(seconds));
    a
}

/// The per-run secret and how a request proves it knows it: the token in
/// a header, `X-Stlc-Token: T` (the page, which has it from the printed
/// link's fragment) or `Authorization: Bearer T` (scripts). No cookie
/// carries it: a browser sends the cookies of 127.0.0.1 to every port, so
/// any other local listener the browser visits would receive it.
pub struct Key {
    token: String,
}

impl Key {
    /// The key `token`.
    pub fn new(token: String) -> Self {
        Key { token }
    }

    /// The secret.
    pub fn token(&self) -> &str {
        &self.token
    }

    /// Whether `req` carries the token in a header.
    pub fn admits(&self, req: &Request<Incoming>) -> bool {
        let h = req.headers();
        let bearer = h
            .get_all(hyper::header::AUTHORIZATION)
            .iter()
            .filter_map(|v| v.to_str().ok()?.strip_prefix("Bearer "));
        let named = h
            .get_all("x-stlc-token")
            .iter()
            .filter_map(|v| v.to_str().ok());
        bearer
            .chain(named)
            .any(|t| same_secret(t.trim(), &self.token))
    }
}

/// The answer to an API call without the key.
pub fn locked() -> Answer {
    error(
        StatusCode::UNAUTHORIZED,
        "this stlc serve answers only its owner: open the link printed in its terminal (http://127.0.0.1:PORT/#token=...) in this tab, or send its token (X-Stlc-Token: TOKEN)",
    )
}

/// The value of `name` in a query string (`a=1&format=svg`), decoded.
pub fn query_param(query: Option<&str>, name: &str) -> Option<String> {
    form_urlencoded::parse(query?.as_bytes())
        .find(|(k, _)| k == name)
        .map(|(_, v)| v.into_owned())
}

/// Reads a body of at most `limit` bytes in [`BODY_TIMEOUT`]: 413 over the
/// limit, 408 too slow, 400 broken.
pub async fn read_body(req: Request<Incoming>, limit: u64) -> Result<Bytes, Answer> {
    let too_large = || {
        error(
            StatusCode::PAYLOAD_TOO_LARGE,
            "the request is larger than --max-input",
        )
    };
    let declared = declared_length(&req);
    if declared.is_some_and(|n| n > limit) {
        return Err(too_large());
    }
    let limit = usize::try_from(limit).unwrap_or(usize::MAX);
    let collected =
        tokio::time::timeout(BODY_TIMEOUT, Limited::new(req.into_body(), limit).collect());
    match collected.await {
        Err(_) => Err(error(
            StatusCode::REQUEST_TIMEOUT,
            "the body came too slowly",
        )),
        Ok(Err(e)) if e.is::<http_body_util::LengthLimitError>() => Err(too_large()),
        Ok(Err(_)) => Err(error(StatusCode::BAD_REQUEST, "the body could not be read")),
        Ok(Ok(c)) => Ok(c.to_bytes()),
    }
}

/// Compares secrets in time independent of where they differ.
pub fn same_secret(a: &str, b: &str) -> bool {
    a.len() == b.len()
        && a.bytes()
            .zip(b.bytes())
            .fold(0u8, |acc, (x, y)| acc | (x ^ y))
            == 0
}

/// The body length a request declares (`Content-Length`), if it does.
pub fn declared_length(req: &Request<Incoming>) -> Option<u64> {
    req.headers()
        .get(CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok())
}

/// 128 bits from the operating system's random source, as hex.
pub fn random_token() -> Result<String, getrandom::Error> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes)?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_parameters_are_found_wherever_they_stand_and_decoded() {
        assert_eq!(
            query_param(Some("format=svg"), "format").as_deref(),
            Some("svg")
        );
        assert_eq!(
            query_param(Some("x=1&format=svg"), "format").as_deref(),
            Some("svg")
        );
        assert_eq!(
            query_param(Some("format=p%6Eg&x"), "format").as_deref(),
            Some("png")
        );
        assert_eq!(query_param(Some("xformat=svg"), "format"), None);
        assert_eq!(query_param(None, "format"), None);
    }

    #[test]
    fn tokens_are_128_random_bits() {
        let a = random_token().unwrap();
        let b = random_token().unwrap();
        assert_eq!(a.len(), 32);
        assert!(a.bytes().all(|c| c.is_ascii_hexdigit()));
        assert_ne!(a, b);
        assert!(same_secret(&a, &a.clone()));
        assert!(!same_secret(&a, &b));
    }
}
