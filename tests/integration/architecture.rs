//! The shape docs/architecture.md promises, checked on the source: which
//! stage may import which, and files of one idea each.

use std::path::{Path, PathBuf};

use crate::support;

/// Every `.rs` file under `dir`, sorted.
pub(crate) fn rust_files(dir: &Path) -> Vec<PathBuf> {
    files_with(dir, &["rs"])
}

/// Every file under `dir` whose extension is one of `exts`, sorted.
pub(crate) fn files_with(dir: &Path, exts: &[&str]) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path
                .extension()
                .is_some_and(|e| exts.iter().any(|x| e == *x))
            {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// The number of lines of the file at `path`.
fn lines_of(path: &Path) -> usize {
    std::fs::read_to_string(path).unwrap().lines().count()
}

/// The stages `text` imports from the crate: `crate::x` paths and the
/// first segment of each item in a `use crate::{...}` group, in code (a
/// link in a comment is no dependency).
fn imported_stages(text: &str) -> Vec<String> {
    imported_paths(text, "crate::")
        .into_iter()
        .map(|p| p.split("::").next().unwrap_or("").to_string())
        .collect()
}

/// The paths `text` imports under `root` (`crate::` or `stlc::`), without
/// the root: `render::Fill` for `crate::render::Fill`, each item of a
/// group on its own (`{diag::X, grow}`: `diag::X`, `grow`), in code.
fn imported_paths(text: &str, root: &str) -> Vec<String> {
    let code: String = text
        .lines()
        .filter(|line| !line.trim_start().starts_with("//"))
        .map(|line| format!("{line}\n"))
        .collect();
    let mut paths = Vec::new();
    let mut rest = code.as_str();
    while let Some(at) = rest.find(root) {
        // `stlc::` inside another path (`my_stlc::`) is not the crate.
        let whole = at == 0 || !rest[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_');
        rest = &rest[at + root.len()..];
        if !whole {
            continue;
        }
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let item: String = item.chars().filter(|c| !c.is_whitespace()).collect();
                if !item.is_empty() {
                    paths.push(item);
                }
            }
        } else {
            let path: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            paths.push(path.trim_end_matches(':').to_string());
        }
    }
    paths
}

#[test]
fn the_import_reader_sees_plain_paths_and_groups() {
    let text = "use crate::render::Fill;\n/// [`crate::turtle`]\n\
                use crate::{diag::X, grow};\nlet a = crate::num::fixed(1);";
    assert_eq!(imported_stages(text), ["render", "diag", "grow", "num"]);
}

#[test]
fn the_path_reader_sees_library_paths_in_the_binary() {
    let text = "use stlc::pipeline::{self, Request};\nuse stlc::{diag::X, model};\n\
                let a = stlc::render::x(); let b = my_stlc::grow::y();";
    assert_eq!(
        imported_paths(text, "stlc::"),
        ["pipeline", "diag::X", "model", "render::x"]
    );
}

/// Front ends speak only the pipeline's language (docs/architecture.md):
/// `cli`, `serve`, `frontend` and `web` import from the library only `pipeline`,
/// `api` and `diag`; from the binary only `frontend` and themselves;
/// `serve` nothing from `cli`, and `cli` from `serve` only its entry point
/// and its config.
#[test]
fn front_ends_import_only_the_pipeline_and_not_each_other() {
    let own: [(&str, &[&str]); 4] = [
        ("src/cli", &["cli", "frontend", "serve"]),
        ("src/serve", &["serve", "frontend"]),
        ("src/frontend", &["frontend"]),
        // The web front end (its own crate): its one module of calls.
        ("web/src", &["calls"]),
    ];
    let mut checked = 0;
    for (dir, binary) in own {
        for path in rust_files(&support::manifest_path(dir)) {
            let (text, file) = (std::fs::read_to_string(&path).unwrap(), path.display());
            for path in imported_paths(&text, "stlc::") {
                let stage = path.split("::").next().unwrap();
                let allowed = ["pipeline", "api", "diag"].contains(&stage);
                assert!(allowed, "{file} imports stlc::{path}");
            }
            for path in imported_paths(&text, "crate::") {
                let stage = path.split("::").next().unwrap();
                assert!(binary.contains(&stage), "{file} imports crate::{path}");
                let entry = ["serve::run", "serve::Config"].contains(&path.as_str());
                let only = "only serve's entry point and config";
                assert!(
                    stage != "serve" || entry,
                    "{file} reaches into crate::{path}: {only}"
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 10, "only {checked} files read");
}

/// Dependencies run one way (docs/architecture.md): syntax, grow and bed
/// never import render; syntax and render never import grow or interpret.
#[test]
fn stages_import_only_downstream() {
    let rules: [(&str, &[&str]); 4] = [
        ("src/syntax", &["render", "grow", "interpret"]),
        ("src/grow", &["render"]),
        ("src/bed", &["render"]),
        ("src/render", &["grow", "interpret"]),
    ];
    let mut checked = 0;
    for (dir, forbidden) in rules {
        for path in rust_files(&support::manifest_path(dir)) {
            let (text, file) = (std::fs::read_to_string(&path).unwrap(), path.display());
            for stage in imported_stages(&text) {
                let upstream = forbidden.contains(&stage.as_str());
                assert!(!upstream, "{file} imports crate::{stage}");
            }
            checked += 1;
        }
    }
    assert!(checked >= 20, "only {checked} files read");
}

/// The model is the bottom stage: it imports only `diag`, `num` and
/// `color` (and itself).
#[test]
fn the_model_imports_only_diag_num_and_color() {
    let files = rust_files(&support::manifest_path("src/model"));
    assert!(files.len() >= 4, "only {} files found", files.len());
    for path in files {
        let (text, file) = (std::fs::read_to_string(&path).unwrap(), path.display());
        for stage in imported_stages(&text) {
            let allowed = ["diag", "num", "color", "model"].contains(&stage.as_str());
            assert!(allowed, "{file} imports crate::{stage}");
        }
    }
}

/// Files of one idea each: none in src/ over 650 lines.
#[test]
fn no_source_file_is_over_650_lines() {
    let files = rust_files(&support::manifest_path("src"));
    assert!(files.len() >= 40, "only {} files found", files.len());
    for file in files {
        let lines = lines_of(&file);
        assert!(lines <= 650, "{} has {lines} lines", file.display());
    }
}

/// Test files of more lines than this are a sign that one holds several
/// behaviours: split where the behaviour changes.
const TEST_FILE_LINES: usize = 1000;

/// Test files over [`TEST_FILE_LINES`] when the ceiling came, with the
/// lines they had then: each may shrink, not grow, and leaves the list
/// once under the ceiling (the test says so).
const TEST_FILES_OVER: &[(&str, usize)] = &[("stl.rs", 1074)];

/// Ceilings for tests and the page's JavaScript, as src/ has its 650
/// lines: a test file at most [`TEST_FILE_LINES`] (those listed in
/// [`TEST_FILES_OVER`] at most what they had), a JavaScript module at
/// most 400 lines, in the page, the static site and the page's Node tests.
#[test]
fn test_files_and_javascript_have_ceilings() {
    let tests = rust_files(&support::manifest_path("tests/integration"));
    assert!(tests.len() >= 30, "only {} test files found", tests.len());
    for file in tests {
        let lines = lines_of(&file);
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        match TEST_FILES_OVER.iter().find(|(n, _)| *n == name) {
            Some((_, had)) => {
                assert!(
                    lines <= *had,
                    "{name} has {lines} lines, more than its {had}: split it"
                );
                assert!(
                    lines > TEST_FILE_LINES,
                    "{name} is under {TEST_FILE_LINES} lines now: strike it from TEST_FILES_OVER"
                );
            }
            None => assert!(
                lines <= TEST_FILE_LINES,
                "{name} has {lines} lines (at most {TEST_FILE_LINES}): split it where the behaviour changes"
            ),
        }
    }
    let mut scripts = 0;
    for dir in ["src/serve/page", "web/page", "tests/page"] {
        for path in files_with(&support::manifest_path(dir), &["js"]) {
            let lines = lines_of(&path);
            let file = path.display();
            assert!(lines <= 400, "{file} has {lines} lines (at most 400)");
            scripts += 1;
        }
    }
    assert!(scripts >= 30, "only {scripts} scripts found");
}

/// The files grammar.pest's comments and docs/architecture.md name exist:
/// a moved file leaves no stale name behind.
#[test]
fn files_named_in_the_grammar_and_the_architecture_exist() {
    let mut named = 0;
    for doc in ["grammar.pest", "docs/architecture.md"] {
        let text = std::fs::read_to_string(support::manifest_path(doc)).unwrap();
        let mut rest = text.as_str();
        while let Some(at) = rest.find("src/") {
            let path: String = rest[at..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || "/_.-".contains(*c))
                .collect();
            let path = path.trim_end_matches('.');
            rest = &rest[at + path.len()..];
            let exists = support::manifest_path(path).exists();
            assert!(exists, "{doc} names {path}, which does not exist");
            named += 1;
        }
    }
    assert!(named >= 8, "only {named} paths found");
}

/// lib.rs is the map: every module it declares has its line in the
/// crate's docs (`//! - [`name`]: ...`).
#[test]
fn lib_rs_lists_every_module() {
    let lib = std::fs::read_to_string(support::manifest_path("src/lib.rs")).unwrap();
    let modules: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod ")?.strip_suffix(';'))
        .collect();
    assert!(modules.len() >= 12, "{modules:?}");
    for m in modules {
        let (line, or) = (format!("//! - [`{m}`]:"), format!("//! - [`{m}`] ("));
        let listed = lib.contains(&line) || lib.contains(&or);
        assert!(listed, "lib.rs's docs have no line for `{m}`");
    }
}
