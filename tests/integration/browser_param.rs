//! The book's L-systems in the editor and on the web (issue 32, item 5),
//! in a real Chromium: each `define` is a slider that rewrites only its
//! number; a diagnostic underlines the expression it is about; the static
//! site's engine expands and reports `stats` of every parametric example
//! with the CLI's bytes and its words view shows modules with their
//! parameters; `<stl-tree>` draws one and a share link carries it.
//! Screenshots go to `tests/store/browser/`.

use fantoccini::Client;
use serde_json::{Value, json};

use super::browser_steps::{set_value, settled_failed, shows_svg, texts_of};
use super::browser_web::{
    engine_export, on_site, open_example, opens_in_a_fresh_profile, share_link,
};
use super::chromium::{
    cli, cli_line, cli_svg_of, click, js, js_async, on_served_file, on_served_page, same_bytes,
    settled_until, shot, until,
};
use super::param_frontends::{parametric_examples, same_words};
use super::serve::example;

/// Opens the Numbers panel and moves the slider `key` to `value`, as a
/// drag does (an `input` event); the page's answer to the new text.
async fn slide(c: &Client, key: &str, value: &str) -> Value {
    if js(c, "return document.getElementById('scrub').open").await != json!(true) {
        click(c, "#scrub summary").await;
    }
    let input = format!("#scrub-list input[data-key=\"{key}\"]");
    let script = &format!("return document.querySelector('{input}') !== null");
    until(c, script, "the slider").await;
    set_value(c, &input, value).await;
    let line_end = format!(" {value}\n");
    let moved = |v: &Value| v["text"].as_str().unwrap().contains(&line_end);
    settled_until(c, 100, 50, moved).await
}

/// The willow's four `define`s are sliders beside `angle`; moving
/// `spread` from 30 to 45 rewrites that number only, and the picture is
/// the CLI's for the new text.
#[test]
fn each_define_is_a_slider_that_rewrites_only_its_number_in_chromium() {
    on_served_page(async |c, _| {
        open_example(c, "param-willow.lsys").await;
        let after = slide(c, "define-spread", "45").await;
        let keys = "return [...document.querySelectorAll('#scrub-list input')].map((i) => i.dataset.key).join()";
        let want = "angle,define-shrink,define-side,define-spread,define-twig";
        assert_eq!(js(c, keys).await, json!(want));
        let text = example("param-willow.lsys").replace("define spread 30\n", "define spread 45\n");
        assert_eq!(after["ok"], true, "{after}");
        assert_eq!(after["text"], json!(text));
        let cli = cli_svg_of("edited.lsys", &text);
        shows_svg(c, &cli, "the willow with spread 45").await;
        shot(c, "param-01-define-sliders").await;
    });
}

/// A parameter that divides by zero at generation 3 is underlined at the
/// expression that made it, and clicking its diagnostic selects it.
#[test]
fn a_diagnostic_underlines_the_expression_it_is_about_in_chromium() {
    let text = "generations 5\nangle 9\naxiom A(3)\nrule A(x) -> F(1)A(x-1)B(1/(x-1))\n";
    on_served_file("zero.lsys", text, async |c, _| {
        settled_failed(c).await;
        let marks = "return [...document.querySelectorAll('#underlines mark.error')].map((m) => m.textContent)";
        until(c, &format!("{marks}.length === 1"), "the underline").await;
        assert_eq!(js(c, marks).await, json!(["1/(x-1)"]));
        click(c, "#diagnostics li.error").await;
        let probe = "const s = document.getElementById('source'); return s.value.slice(s.selectionStart, s.selectionEnd)";
        let selected = js(c, probe).await;
        assert_eq!(selected, json!("1/(x-1)"));
        shot(c, "param-02-underlined-expression").await;
    });
}

/// The static site's engine (WebAssembly) writes the CLI's SVG, words and
/// `stats --json` for every parametric example (its PNGs are held to the
/// CLI's in browser_web.rs's every_example), and the page's words view
/// shows the willow's modules with their parameters.
#[test]
fn the_web_engine_draws_expands_and_reports_stats_of_every_parametric_example_in_chromium() {
    on_site(async |c, _, _| {
        let c = c.clone();
        for name in parametric_examples() {
            let path = format!("examples/{name}");
            let request = json!({"source": example(&name), "kind": "lsys", "show_layout": true});
            let svg = engine_export(&c, &request, "svg").await.unwrap();
            let want = cli(&["render", &path, "--show-layout", "-f", "svg"]);
            same_bytes(&svg, &want, &name);
            let probe = "const [request, done] = arguments;
                     window.stlc.engine.words(request).then(done, (e) => done(String(e)));";
            let words = js_async(&c, probe, vec![request]).await;
            same_words(&name, &words);
        }
        // The words view: the axiom A(10,0), then the first rule applied
        // (l = 10 >= twig: F(10), two side branches of 10 x 0.62 and
        // 10 x 0.62 x 0.9, the axis 10 x 0.82; ten modules).
        open_example(&c, "param-willow.lsys").await;
        click(&c, "#words summary").await;
        let items = "document.querySelectorAll('#word-list li').length >= 2";
        until(&c, &format!("return {items}"), "the words").await;
        let shown = texts_of(&c, "#word-list li").await;
        assert_eq!(shown[0], "A(10,0) (1)");
        let first = "F(10)[+(30)A(6.2,1)][-(30)A(5.58,1)]A(8.2,0) (10)";
        assert_eq!(shown[1], first);
        shot(&c, "param-03-web-words").await;
    });
}

/// `<stl-tree>` draws a parametric text written inline (its `<`, `>=`
/// and `&` stay as written in a `<script type="text/stl">`) and one at
/// `src=`, as `stlc render -f svg` draws them.
#[test]
fn stl_tree_draws_parametric_trees_as_the_cli_in_chromium() {
    on_site(async |c, server, _| {
        let willow = example("param-willow.lsys");
        let page = format!(
            "<!doctype html><meta charset=utf-8><script type=module src=stl-tree.js></script>\n\
             <stl-tree id=willow><script type=\"text/stl\">\n{willow}</script></stl-tree>\n\
             <stl-tree id=honda src=\"examples/abop-2.6a.lsys\" depth=6></stl-tree>\n"
        );
        let files = [("param-elements-test.html", page)];
        let states = super::browser_page::elements(c, server, &files).await;
        assert_eq!(states, json!(["drawn", "drawn"]), "both drawn");
        for (id, line) in [
            ("willow", "render examples/param-willow.lsys"),
            ("honda", "render examples/abop-2.6a.lsys --depth 6"),
        ] {
            let svg = js(c, &format!("return document.getElementById('{id}').svg")).await;
            let cli = cli_line(&format!("{line} -f svg"));
            same_bytes(svg.as_str().unwrap().as_bytes(), &cli, id);
        }
        shot(c, "param-04-stl-tree").await;
    });
}

/// A share link carries a parametric tree with a `define` moved: opened
/// in a fresh profile it shows the same text and the CLI's SVG of it.
#[test]
fn a_share_link_carries_a_parametric_tree_in_chromium() {
    let text = example("param-willow.lsys").replace("define shrink 0.82\n", "define shrink 0.75\n");
    let mut link = String::new();
    let Some(_site) = on_site(async |c, server, _| {
        open_example(c, "param-willow.lsys").await;
        let v = slide(c, "define-shrink", "0.75").await;
        assert_eq!(v["text"], json!(text));
        link = share_link(c).await;
        let base = format!("{}#k=lsys&n=param-willow.lsys&s=", server.url);
        assert!(link.starts_with(&base), "{link}");
    }) else {
        return;
    };
    let want = cli_svg_of("willow.lsys", &text);
    opens_in_a_fresh_profile(&link, &text, &want, "param-05-shared");
}
