//! Issue 32's acceptance for the front ends without a browser: every
//! example of the book's L-systems (parameters, conditions, context,
//! tropism) renders, expands and reports `stats` in the editor's server
//! (`stlc serve`'s API, as the page asks it) with the CLI's bytes. The
//! static site's WebAssembly engine is held to the same bytes in
//! browser_param.rs.

use serde_json::{Value, json};
use stlc::api::WORD_CHARS;

use super::serve::{Server, example, post};
use crate::support::{manifest_path, stlc_stdout};

/// The names of issue 32's examples begin so.
const BOOK: [&str; 4] = ["abop-1.31", "abop-1.35", "abop-2.", "param-"];

/// The examples of issue 32 (ABOP Fig. 1.31, 1.35, 2.6-2.8 and our own
/// tree): every parametric or context-sensitive file of `examples/`.
pub(super) fn parametric_examples() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(manifest_path("examples"))
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".lsys") && BOOK.iter().any(|p| n.starts_with(p)))
        .collect();
    names.sort();
    names
}

/// What the CLI's `expand` wrote, as the words view keeps it: the first
/// [`WORD_CHARS`] bytes, without trailing whitespace.
pub(super) fn kept(expanded: &[u8]) -> String {
    let n = expanded.len().min(WORD_CHARS);
    let text = String::from_utf8(expanded[..n].to_vec()).unwrap();
    text.trim_end().to_string()
}

/// The words answer's generations against `stlc expand` and `stlc stats
/// --json` at each depth, for the example `name`.
pub(super) fn same_words(name: &str, words: &Value) {
    let path = format!("examples/{name}");
    let words = words["words"]
        .as_array()
        .unwrap_or_else(|| panic!("{name}: {words}"));
    assert!(words.len() >= 2, "{name}: {words:?}");
    for (d, w) in words.iter().enumerate() {
        let depth = d.to_string();
        assert_eq!(w["depth"], json!(d));
        let expanded = stlc_stdout(&["expand", &path, "--depth", &depth]);
        let word = json!(kept(&expanded));
        assert_eq!(w["word"], word, "{name} word at depth {d}");
        let stats = stlc_stdout(&["stats", &path, "--json", "--depth", &depth]);
        let mine = format!("{}\n", w["stats"].as_str().unwrap());
        let cli = String::from_utf8(stats).unwrap();
        assert_eq!(mine, cli, "{name} stats at depth {d}");
        let parsed: Value = serde_json::from_str(&mine).unwrap();
        assert_eq!(w["length"], parsed["length"], "{name} length at depth {d}");
    }
}

#[test]
fn every_parametric_example_renders_expands_and_reports_stats_as_the_cli_in_serve() {
    let names = parametric_examples();
    // 1.31 a-e, 1.35, 2.6 a-d, 2.7 a-d, 2.8 a-d and the willow.
    assert_eq!(names.len(), 19, "{names:?}");
    let server = Server::start(&[]);
    for name in &names {
        let file = format!("examples/{name}");
        let body = json!({"source": example(name), "kind": "lsys", "show_layout": true});
        for format in ["svg", "png"] {
            let path = format!("/api/export?format={format}");
            let a = post(&server.addr, &path, &[], &body);
            assert_eq!(a.status, 200, "{name} {format}");
            let cli = stlc_stdout(&["render", &file, "--show-layout", "-f", format, "-o", "-"]);
            let not_the_clis = format!("{name}: the served {format} is not the CLI's");
            assert!(a.body == cli, "{not_the_clis}");
        }
        let words = post(&server.addr, "/api/words", &[], &body);
        assert_eq!(words.status, 200, "{name}");
        same_words(name, &words.json());
    }
}

/// The words view of a parametric system shows each module with its
/// parameters (ABOP Fig. 2.6a's first two generations, by hand: `A(1,10)`
/// becomes `!(w)F(l)[&(a0)B(l*r2,w*wr)]/(d)A(l*r1,w*wr)` with l = 1,
/// w = 10, r1 = 0.9, r2 = 0.6, wr = 0.707, a0 = 45, d = 137.5; 10 x 0.707
/// is 7.069999999999999 in f64).
#[test]
fn the_words_view_shows_modules_with_their_parameters() {
    let server = Server::start(&[]);
    let body = json!({"source": example("abop-2.6a.lsys"), "kind": "lsys", "depth": 1});
    let a = post(&server.addr, "/api/words", &[], &body).json();
    assert_eq!(a["words"][0]["word"], "A(1,10)");
    assert_eq!(a["words"][0]["length"], "1");
    assert_eq!(
        a["words"][1]["word"],
        "!(10)F(1)[&(45)B(0.6,7.069999999999999)]/(137.5)A(0.9,7.069999999999999)"
    );
    // ! F [ & B ] / A: eight modules, one drawn step.
    assert_eq!(a["words"][1]["length"], "8");
    let stats: Value = serde_json::from_str(a["words"][1]["stats"].as_str().unwrap()).unwrap();
    assert_eq!(stats["segments"], "1");
}
