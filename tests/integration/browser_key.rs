//! The page's key in a real Chromium (issue 36, problem 1): the printed
//! link's fragment `#token=T` is read by the page, kept in the tab's
//! sessionStorage and taken out of the address bar; every API call sends
//! it as `X-Stlc-Token`; no cookie is set; a reload in the same tab keeps
//! working; a new tab opened without the link gets the server's "open the
//! link" message, not the file.

use fantoccini::Client;
use serde_json::{Value, json};

use super::chromium::{js, on_served_file, poll, settled};
use super::serve::example;

/// The page's engine asked for the file, as the page asks: its text, or
/// `error: ` and the message.
const OPEN: &str = "const done = arguments[0];
    window.stlc.engine.open().then((f) => done(f.text), (e) => done('error: ' + e.message));";

#[test]
fn the_key_travels_in_the_fragment_and_a_header_never_a_cookie() {
    on_served_file("mine.od", &example("fig9.od"), async |c, served| {
        let server = served.server;
        let seen = state(c).await;
        assert_eq!(seen["hash"], "", "the token left the address bar: {seen}");
        assert_eq!(seen["href"], format!("http://{}/", server.addr), "{seen}");
        assert_eq!(seen["kept"], server.token.as_str(), "{seen}");
        assert_eq!(seen["cookie"], "", "{seen}");
        assert_eq!(seen["text"], example("fig9.od"), "the file was read");
        // A reload in the same tab: the key from sessionStorage.
        c.refresh().await.unwrap();
        settled(c).await;
        assert_eq!(state(c).await["text"], example("fig9.od"));
        // Every call of the page carries the header: ask as the page asks.
        let asked = c.execute_async(OPEN, vec![]).await.unwrap();
        assert_eq!(asked, json!(example("fig9.od")));
        // A new tab on the bare address: no key, no file.
        let first = c.window().await.unwrap();
        let second = c.new_window(true).await.unwrap();
        c.switch_to_window(second.handle).await.unwrap();
        c.goto(&format!("http://{}/", server.addr)).await.unwrap();
        let ask = async || c.execute_async(OPEN, vec![]).await.unwrap();
        let refused = poll(100, 50, ask, Value::is_string).await;
        let refused = refused.as_str().unwrap_or_default().to_string();
        let open_the_link = refused.contains("open the link printed in its terminal");
        assert!(refused.starts_with("error: ") && open_the_link, "{refused}");
        let shown = js(c, "return document.body.innerText").await.to_string();
        assert!(!shown.contains("Fig9"));
        c.close_window().await.unwrap();
        c.switch_to_window(first).await.unwrap();
    });
}

/// What the tab holds: the address bar's fragment and address,
/// the key kept, the cookies, the editor's text.
async fn state(c: &Client) -> Value {
    let script = "return {hash: location.hash, href: location.href,
                 kept: sessionStorage.getItem('stlc-token'), cookie: document.cookie,
                 text: document.getElementById('source').value};";
    js(c, script).await
}
