//! Rendered diagnostics, as a user sees them on stderr (colour off): one
//! snapshot per file in `tests/cases/errors/`. `.od` files that parse are
//! compiled, so growth errors (root outside, unbounded) are covered too.
//!
//! Review changes with `cargo insta review` (or `INSTA_UPDATE=always`, then
//! read `git diff`); CI never writes snapshots.

use std::fs;
use std::path::PathBuf;

use assert_cmd::Command;

fn errors_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/cases/errors")
}

#[test]
fn every_error_case_renders_a_pointed_report() {
    let mut names: Vec<String> = fs::read_dir(errors_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert!(names.len() >= 12, "{names:?}");
    for name in names {
        let args: Vec<&str> = if name.ends_with(".od") {
            vec!["compile", &name, "-o", "-", "--color", "never"]
        } else {
            vec!["check", &name, "--color", "never"]
        };
        let out = Command::cargo_bin("stlc")
            .unwrap()
            .current_dir(errors_dir())
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(1), "{name} should fail with exit 1");
        assert!(out.stdout.is_empty(), "{name}: nothing on stdout");
        let stderr = String::from_utf8(out.stderr).unwrap();
        // Every report names the file and says how to fix it.
        assert!(stderr.contains(&name), "{name}: {stderr}");
        assert!(stderr.to_lowercase().contains("help"), "{name}: {stderr}");
        insta::assert_snapshot!(name.replace('.', "_"), stderr);
    }
}
