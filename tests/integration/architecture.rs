//! The shape docs/architecture.md promises, checked on the source: which
//! stage may import which, and files of one idea each.

use std::path::{Path, PathBuf};

use crate::support;

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// The stages `text` imports from the crate: `crate::x` paths and the
/// first segment of each item in a `use crate::{...}` group, in code (a
/// link in a comment is no dependency).
fn imported_stages(text: &str) -> Vec<String> {
    let code: String = text
        .lines()
        .filter(|line| !line.trim_start().starts_with("//"))
        .map(|line| format!("{line}\n"))
        .collect();
    let mut stages = Vec::new();
    let mut rest = code.as_str();
    while let Some(at) = rest.find("crate::") {
        rest = &rest[at + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let item = item.trim();
                if !item.is_empty() {
                    stages.push(item.split("::").next().unwrap().trim().to_string());
                }
            }
        } else {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            stages.push(name);
        }
    }
    stages
}

#[test]
fn the_import_reader_sees_plain_paths_and_groups() {
    let text = "use crate::render::Fill;\n/// [`crate::turtle`]\n\
                use crate::{diag::X, grow};\nlet a = crate::num::fixed(1);";
    assert_eq!(imported_stages(text), ["render", "diag", "grow", "num"]);
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
        for file in rust_files(&support::manifest_path(dir)) {
            let text = std::fs::read_to_string(&file).unwrap();
            for stage in imported_stages(&text) {
                assert!(
                    !forbidden.contains(&stage.as_str()),
                    "{} imports crate::{stage}",
                    file.display()
                );
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
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for stage in imported_stages(&text) {
            assert!(
                ["diag", "num", "color", "model"].contains(&stage.as_str()),
                "{} imports crate::{stage}",
                file.display()
            );
        }
    }
}

/// Files of one idea each: none in src/ over 650 lines.
#[test]
fn no_source_file_is_over_650_lines() {
    let files = rust_files(&support::manifest_path("src"));
    assert!(files.len() >= 40, "only {} files found", files.len());
    for file in files {
        let lines = std::fs::read_to_string(&file).unwrap().lines().count();
        assert!(lines <= 650, "{} has {lines} lines", file.display());
    }
}
