//! What a browser test reads off the page and the small steps it takes
//! there, one name each: a control's value or text, the editor's text
//! typed, set or rewritten, a field set as typing sets it, the error the
//! diagnostics list, a reload. The harness (Chromium, waits, mouse) is
//! `chromium.rs`.

use std::time::Duration;

use fantoccini::{Client, Locator};
use serde_json::{Value, json};

use super::chromium::{js, settled, settled_until, until};

/// What `script` returns, run with `args` as its `arguments`.
pub(super) async fn js_with(c: &Client, script: &str, args: &[Value]) -> Value {
    c.execute(script, args.to_vec()).await.expect(script)
}

/// The text of the element `css` selects (which must exist).
pub(super) async fn text_of(c: &Client, css: &str) -> String {
    let script = "const e = document.querySelector(arguments[0]); return e && e.textContent";
    let v = js_with(c, script, &[json!(css)]).await;
    let text = v.as_str().unwrap_or_else(|| panic!("no element {css}"));
    text.to_string()
}

/// The texts of the elements `css` selects, in document order.
pub(super) async fn texts_of(c: &Client, css: &str) -> Vec<String> {
    let script = "return [...document.querySelectorAll(arguments[0])].map((e) => e.textContent)";
    let v = js_with(c, script, &[json!(css)]).await;
    let texts = v.as_array().unwrap().iter();
    texts.map(|t| t.as_str().unwrap().to_string()).collect()
}

/// How many elements `css` selects.
pub(super) async fn count(c: &Client, css: &str) -> u64 {
    let script = "return document.querySelectorAll(arguments[0]).length";
    js_with(c, script, &[json!(css)]).await.as_u64().unwrap()
}

/// The value of the control `css` selects.
pub(super) async fn value_of(c: &Client, css: &str) -> String {
    let script = "return document.querySelector(arguments[0]).value";
    let v = js_with(c, script, &[json!(css)]).await;
    v.as_str().unwrap().to_string()
}

/// The SVG of the answer the page shows.
pub(super) async fn answer_svg(c: &Client) -> String {
    let v = js(c, "return window.stlc.state.answer.svg").await;
    v.as_str().unwrap().to_string()
}

/// Asserts the page shows `want`'s SVG (the CLI's bytes), saying where
/// they part otherwise; `what` names the picture.
pub(super) async fn shows_svg(c: &Client, want: &[u8], what: &str) {
    super::chromium::same_bytes(answer_svg(c).await.as_bytes(), want, what);
}

/// Chooses `label` in the New menu as a user does (a `change` event).
pub(super) async fn choose_new(c: &Client, label: &str) {
    let script = "const m = document.getElementById('new');
                  const o = [...m.options].find((o) => o.textContent === arguments[0]);
                  m.value = o.value; m.dispatchEvent(new Event('change')); return 0;";
    js_with(c, script, &[json!(label)]).await;
}

/// The editor's text.
pub(super) async fn editor_text(c: &Client) -> String {
    value_of(c, "#source").await
}

/// Sets the control `css` selects to `value` and tells the page, as typing
/// does (an `input` event).
pub(super) async fn set_value(c: &Client, css: &str, value: &str) {
    let script = "const e = document.querySelector(arguments[0]); e.value = arguments[1];
                  e.dispatchEvent(new Event('input')); return 0;";
    js_with(c, script, &[json!(css), json!(value)]).await;
}

/// Sets the control `css` selects to `value` without telling the page (no
/// event: the page reads it when it next looks).
pub(super) async fn assign_value(c: &Client, css: &str, value: &str) {
    let script = "document.querySelector(arguments[0]).value = arguments[1]; return 0;";
    js_with(c, script, &[json!(css), json!(value)]).await;
}

/// Ticks (`on`) or clears the checkbox `css` selects and tells the page
/// (an `input` event).
pub(super) async fn set_checked(c: &Client, css: &str, on: bool) {
    let script = "const e = document.querySelector(arguments[0]); e.checked = arguments[1];
                  e.dispatchEvent(new Event('input')); return 0;";
    js_with(c, script, &[json!(css), json!(on)]).await;
}

/// Types `keys` (WebDriver keys) into the element with the id `id`.
pub(super) async fn type_into(c: &Client, id: &str, keys: &str) {
    let field = c.find(Locator::Id(id)).await.unwrap();
    field.send_keys(keys).await.unwrap();
}

/// Empties the editor and types `keys` into it.
pub(super) async fn retype(c: &Client, keys: &str) {
    let source = c.find(Locator::Id("source")).await.unwrap();
    source.clear().await.unwrap();
    source.send_keys(keys).await.unwrap();
}

/// Focuses the editor with the caret at the end of its text.
pub(super) async fn caret_to_end(c: &Client) {
    let probe = "const s = document.getElementById('source'); s.focus();
         s.setSelectionRange(s.value.length, s.value.length); return 0;";
    js(c, probe).await;
}

/// The page's settled answer, which must be drawn without error.
pub(super) async fn settled_ok(c: &Client) -> Value {
    let v = settled(c).await;
    assert_eq!(v["ok"], true, "{v}");
    v
}

/// The page's settled answer, which must have failed.
pub(super) async fn settled_failed(c: &Client) -> Value {
    let v = settled(c).await;
    assert_eq!(v["ok"], false, "{v}");
    v
}

/// The editor's text replaced by `text` through the editor's own
/// `rewrite` (one step of its history).
pub(super) async fn rewrite(c: &Client, text: &str) {
    let script = "window.stlc.editor.rewrite(arguments[0])";
    js_with(c, script, &[json!(text)]).await;
}

/// [`rewrite`], then the page's answer once its text is `text` (looked at
/// up to 600 times 50 ms apart; asserted).
pub(super) async fn rewritten(c: &Client, text: &str) -> Value {
    rewrite(c, text).await;
    let v = settled_until(c, 600, 50, |v| v["text"] == json!(text)).await;
    assert_eq!(v["text"], json!(text));
    v
}

/// The first error the diagnostics list: its line, its text, the line
/// marked in the gutter, and whether a picture is shown.
pub(super) async fn listed_error(c: &Client) -> Value {
    let probe = "const li = document.querySelector('[data-testid=diagnostics] li.error');
         const mark = document.querySelector('#gutter span.error');
         return {line: li && li.dataset.line, text: li && li.textContent,
                 mark: mark && mark.textContent,
                 picture: document.querySelector('#preview .lib') !== null};";
    js(c, probe).await
}

/// Waits (at most 10 s) until the element with the id `id` is shown (not
/// hidden); the panic names `what`.
pub(super) async fn until_shown(c: &Client, id: &str, what: &str) {
    let shown = format!("return !document.getElementById('{id}').hidden");
    until(c, &shown, what).await;
}

/// Reloads, accepting the "leave with unsaved edits?" question if one is
/// shown, and returns the answer once the page shows one again.
pub(super) async fn reload(c: &Client) -> Value {
    let _ = js(c, "setTimeout(() => location.reload(), 0); return true").await;
    tokio::time::sleep(Duration::from_millis(300)).await;
    let _ = c.accept_alert().await;
    let script = "return !!(window.stlc && window.stlc.state.doc && window.stlc.state.answer)";
    until(c, script, "the page loaded").await;
    settled(c).await
}
