//! The fuzz targets' bodies (`fuzz/bodies/`, what `cargo fuzz run` calls)
//! over their corpora (`fuzz/corpus/<target>/`): every seed input keeps the
//! promises its target checks, and the bodies compile with the library as
//! it is today (the fuzz crate itself is built only with nightly).

#[path = "../../fuzz/bodies/lsys_parse.rs"]
mod lsys_parse;
#[path = "../../fuzz/bodies/lsys_render.rs"]
mod lsys_render;
#[path = "../../fuzz/bodies/od_compile.rs"]
mod od_compile;
#[path = "../../fuzz/bodies/stl_parse.rs"]
mod stl_parse;

use crate::support::manifest_path;

/// Runs `body` over every committed seed of `fuzz/corpus/<target>`
/// (`seed-*`, in name order; what a local fuzzing run adds beside them is
/// not committed and not run); returns how many it ran.
fn corpus(target: &str, body: fn(&[u8])) -> usize {
    let dir = manifest_path("fuzz/corpus").join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.is_file()
                && p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with("seed-"))
        })
        .collect();
    files.sort();
    for f in &files {
        let data = std::fs::read(f).unwrap();
        let outcome = std::panic::catch_unwind(|| body(&data));
        assert!(outcome.is_ok(), "{target}: {} broke a promise", f.display());
    }
    files.len()
}

#[test]
fn every_corpus_input_keeps_its_targets_promises() {
    for (target, body, at_least) in [
        ("lsys_parse", lsys_parse::run as fn(&[u8]), 10),
        ("lsys_render", lsys_render::run, 10),
        ("od_compile", od_compile::run, 5),
        ("stl_parse", stl_parse::run, 10),
    ] {
        let n = corpus(target, body);
        assert!(n >= at_least, "{target}: only {n} corpus inputs");
    }
}
