//! The docs name what exists, and what exists is named in the docs: the
//! page's modules in docs/serve.md's module table and docs/web.md's site
//! table, the API's request fields and answer fields in docs/serve.md. A
//! module added, moved or removed, or a field renamed, fails here until the
//! docs say so.

use std::collections::BTreeSet;
use std::path::PathBuf;

use stlc::api::{self, Page, Settings};
use stlc::pipeline::{ImageFormat, NoProgress};

use crate::support::manifest_path;

/// The names in backticks of the first cell of each row of the table whose
/// header row starts with `| {first} |`.
fn table_names(doc: &str, first: &str) -> BTreeSet<String> {
    let text = std::fs::read_to_string(manifest_path(doc)).unwrap();
    let header = format!("| {first} |");
    let start = text
        .find(&header)
        .unwrap_or_else(|| panic!("{doc}: no table `{header}`"));
    let mut names = BTreeSet::new();
    for line in text[start..].lines().skip(2) {
        let Some(row) = line.strip_prefix("| ") else {
            break;
        };
        names.append(&mut backticked(row.split(" |").next().unwrap_or("")));
    }
    names
}

/// The files under `dir` with one of `exts`, as paths relative to it.
fn files(dir: &str, exts: &[&str]) -> BTreeSet<String> {
    let root = manifest_path(dir);
    let found = crate::architecture::files_with(&root, exts).into_iter();
    let relative = |p: PathBuf| {
        p.strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/")
    };
    found.map(relative).collect()
}

#[test]
fn every_page_module_is_in_the_serve_docs_and_every_named_one_exists() {
    let named = table_names("docs/serve.md", "module");
    let modules = files("src/serve/page", &["js"]);
    assert!(modules.len() >= 20, "{modules:?}");
    let undocumented: Vec<_> = modules.difference(&named).collect();
    let missing: Vec<_> = named.difference(&modules).collect();
    assert!(
        undocumented.is_empty(),
        "page modules without a row in docs/serve.md: {undocumented:?}"
    );
    assert!(
        missing.is_empty(),
        "docs/serve.md names modules that do not exist: {missing:?}"
    );
}

#[test]
fn every_web_page_file_is_in_the_web_docs_and_every_named_one_exists() {
    let named = table_names("docs/web.md", "file");
    let own = files("web/page", &["js", "html"]);
    let undocumented: Vec<_> = own.difference(&named).collect();
    assert!(
        undocumented.is_empty(),
        "web/page files without a row in docs/web.md: {undocumented:?}"
    );
    let shared = files("src/serve/page", &["js", "html"]);
    for name in &named {
        // What the build makes (the module, the folders of examples).
        let built = name == "stlc.wasm" || name.ends_with('/');
        assert!(
            built || own.contains(name) || shared.contains(name),
            "docs/web.md names `{name}`, which is neither in web/page nor src/serve/page"
        );
    }
}

/// The request body's fields: those serde names when it refuses an
/// unknown one (`expected one of `source`, `kind`, ...`).
fn body_fields() -> BTreeSet<String> {
    let api::BadRequest(m) = api::parse(br#"{"source": "x", "no such field": 1}"#).unwrap_err();
    let list = &m[m.find("expected one of").expect(&m)..];
    backticked(list)
}

/// The names in backticks in `text`.
fn backticked(text: &str) -> BTreeSet<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The names listed between `open` and `close` after `lead` in
/// docs/serve.md: those in backticks, or else each comma-separated item up
/// to its `:` (`{ok: true, svg, ...}`).
fn documented(lead: &str, open: char, close: char) -> BTreeSet<String> {
    let text = std::fs::read_to_string(manifest_path("docs/serve.md")).unwrap();
    let at = text
        .find(lead)
        .unwrap_or_else(|| panic!("docs/serve.md: no `{lead}`"));
    let rest = &text[at + lead.len()..];
    let rest = &rest[rest.find(open).unwrap() + 1..];
    let list = &rest[..rest.find(close).unwrap()];
    if list.contains('`') {
        return backticked(list);
    }
    list.split(',')
        .map(|f| {
            f.trim()
                .trim_matches('`')
                .split(':')
                .next()
                .unwrap()
                .trim()
                .to_string()
        })
        .filter(|f| !f.is_empty())
        .collect()
}

#[test]
fn the_api_fields_in_the_serve_docs_are_the_api_s() {
    // The request: every field the API reads, and no other.
    let mut fields = body_fields();
    let read = fields.contains("source") && fields.contains("growth");
    assert!(read, "{fields:?}");
    // `strategy` is `growth`'s old name, still read: the docs say so in
    // prose, not as a field of its own.
    assert!(fields.remove("strategy"), "{fields:?}");
    let serve = std::fs::read_to_string(manifest_path("docs/serve.md")).unwrap();
    assert!(serve.contains("`strategy`, its old name, is still read"));
    let named = documented(
        "| `render(request)` | `POST /api/render`'s JSON for `request`",
        '(',
        ')',
    );
    let row = "docs/serve.md's render(request) row against the API's body";
    assert_eq!(named, fields, "{row}");
    // The answer: the keys of a real render answer (an .od has a root and
    // a layout; a 3D input's `space` is named as the answer says it is).
    let tree = std::fs::read_to_string(manifest_path("examples/2dtree.od")).unwrap();
    let body = api::parse(serde_json::json!({ "source": tree }).to_string().as_bytes()).unwrap();
    let s = Settings::defaults(Page::Served);
    let (answer, _) = api::render(&body, &s, ImageFormat::Svg, None, &mut NoProgress).unwrap();
    let mut keys: BTreeSet<String> = serde_json::to_value(&answer)
        .unwrap()
        .as_object()
        .unwrap()
        .keys()
        .cloned()
        .collect();
    keys.insert("space".into());
    let named = documented("| `render(request)` |", '{', '}');
    let answer = "docs/serve.md's render answer against the API's";
    assert_eq!(named, keys, "{answer}");
}

/// The `@property` names of the JSDoc `@typedef` named `name` in the
/// page's engine (src/serve/page/engine/index.js), `[optional]` ones
/// without their brackets.
fn typedef_properties(name: &str) -> BTreeSet<String> {
    let js = std::fs::read_to_string(manifest_path("src/serve/page/engine/index.js")).unwrap();
    let block = js
        .split("/**")
        .find(|b| b.contains(&format!("@typedef {{object}} {name}\n")))
        .unwrap_or_else(|| panic!("engine/index.js: no typedef {name}"));
    let block = &block[..block.find("*/").unwrap()];
    block
        .lines()
        .filter_map(|l| l.split("@property ").nth(1))
        .map(|p| {
            // `{type} name description`: the type may hold spaces and
            // braces, so skip to the brace that closes the first.
            let mut depth = 0;
            let end = p
                .char_indices()
                .find(|&(_, c)| {
                    depth += match c {
                        '{' => 1,
                        '}' => -1,
                        _ => 0,
                    };
                    depth == 0
                })
                .unwrap()
                .0;
            let name = p[end + 1..].split_whitespace().next().unwrap();
            name.trim_matches(|c| c == '[' || c == ']').to_string()
        })
        .collect()
}

#[test]
fn the_page_s_typedefs_are_the_api_s() {
    // The request the page sends: every field the API reads (`strategy`,
    // the old name, only in prose), and no field the API would refuse.
    let mut fields = body_fields();
    fields.remove("strategy");
    let request = "engine/index.js's RenderRequest against the API's body";
    assert_eq!(typedef_properties("RenderRequest"), fields, "{request}");
    // A diagnostic as the API writes it: the keys of a real one.
    let body = api::parse(br#"{"source": "T (0,0) L=1(0) RULE R1: [F R9]"}"#).unwrap();
    let s = Settings::defaults(Page::Served);
    let failed = match api::render(&body, &s, ImageFormat::Svg, None, &mut NoProgress) {
        Err(f) => f,
        Ok(_) => panic!("an unknown rule renders"),
    };
    let value = serde_json::to_value(&failed).unwrap();
    let diagnostic: BTreeSet<String> = value["diagnostics"][0]
        .as_object()
        .unwrap_or_else(|| panic!("{value}"))
        .keys()
        .cloned()
        .collect();
    let what = "engine/index.js's Diagnostic against the API's";
    assert_eq!(typedef_properties("Diagnostic"), diagnostic, "{what}");
}
