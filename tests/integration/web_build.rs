//! `sh web/build.sh [FOLDER]` (docs/web.md): it builds into a fresh folder
//! and swaps it in, so builds one after the other, or two at once, all
//! succeed and leave one whole site. The old script emptied and refilled
//! the folder in place: a second build running beside the first failed
//! with "cp: cannot create regular file 'target/site/examples/'".

use std::process::{Command, Stdio};

use super::browser_web::{examples, wasm_target};
use crate::support::manifest_path;

/// `sh web/build.sh folder`, from the crate's root.
fn build(folder: &std::path::Path) -> std::process::Child {
    Command::new("sh")
        .arg("web/build.sh")
        .arg(folder)
        .current_dir(manifest_path(""))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Waits for the build `child`, which must succeed (`what` it was in the panic).
fn succeeded(child: std::process::Child, what: &str) {
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{what} failed: {err}");
}

#[test]
fn two_builds_at_once_then_a_third_all_succeed_and_leave_one_whole_site() {
    if !wasm_target() {
        return;
    }
    // Beside target/site (the same file system, so the swap is a rename),
    // its own name so the other web tests' site is left alone.
    let parent = manifest_path("target/web-build-test");
    std::fs::create_dir_all(&parent).unwrap();
    let parent = tempfile::tempdir_in(&parent).unwrap();
    let site = parent.path().join("site");

    let first = build(&site);
    let second = build(&site);
    succeeded(first, "the first of two builds at once");
    succeeded(second, "the second of two builds at once");
    succeeded(build(&site), "a third build after them");

    // One whole site: the page, the module, every example and their list.
    let index = std::fs::read_to_string(site.join("index.html")).unwrap();
    assert!(index.contains("src=\"entry.js\""), "{index}");
    // The static site's entry, not the served page's: the HTML names one
    // entry and the build ships the WebAssembly one in its place.
    let entry = std::fs::read_to_string(site.join("entry.js")).unwrap();
    assert!(entry.contains("useEngine(createWasmEngine)"), "{entry}");
    let page = std::fs::read_to_string(manifest_path("src/serve/page/index.html")).unwrap();
    assert_eq!(index, page, "the page is copied, not rewritten");
    let wasm = std::fs::read(site.join("stlc.wasm")).unwrap();
    assert_eq!(&wasm[..4], b"\0asm");
    let list = std::fs::read_to_string(site.join("examples/index.json")).unwrap();
    for name in examples() {
        let (file, listed) = (site.join("examples").join(&name), format!("\"{name}\""));
        assert!(file.is_file(), "{name} is missing");
        assert!(list.contains(&listed), "{name} is not in {list}");
    }
    // Nothing left beside it: no half-built or set-aside folders.
    assert_eq!(crate::support::files_in(parent.path()), ["site"]);
}
