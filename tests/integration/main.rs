//! One integration-test binary; each area is a module.

mod architecture;
mod bigtree;
mod browser;
mod browser_3d;
mod browser_colours;
mod browser_draw;
mod browser_edits;
mod browser_key;
mod browser_leaves;
mod browser_mesh;
mod browser_page;
mod browser_param;
mod browser_space;
mod browser_steps;
mod browser_thumbs;
mod browser_web;
mod chromium;
mod cli;
mod cli_cases;
mod diagnostics;
mod docs;
mod docs_drift;
mod explain;
mod fuzz_corpus;
mod geometry;
mod golden;
mod grow;
mod grow3d;
mod grow_space;
mod import_graph;
mod leaves;
mod lod;
mod lsys;
mod lsys3d;
mod mesh_origin;
mod newuser;
mod od_variation;
mod organs;
mod paint_lod;
mod param;
mod param_frontends;
mod param_lod;
mod render;
mod repeats;
mod robustness;
mod serve;
mod serve_hostile;
mod soak;
mod solid;
mod solid_formats;
mod stl;
mod stochastic;
mod support;
mod tree3d;
mod web_build;

use std::collections::BTreeSet;

/// Every `.rs` file beside this one is declared above: a file left out
/// would never be compiled, and its tests would pass by not running.
#[test]
fn no_forgotten_test_files() {
    let declared: BTreeSet<&str> = include_str!("main.rs")
        .lines()
        .filter_map(|line| line.strip_prefix("mod ")?.strip_suffix(';'))
        .collect();
    let dir = support::manifest_path("tests/integration");
    let on_disk: BTreeSet<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.is_file() && path.extension().is_some_and(|e| e == "rs"))
        .map(|path| path.file_stem().unwrap().to_string_lossy().into_owned())
        .filter(|name| name != "main")
        .collect();
    let forgotten: Vec<&String> = on_disk
        .iter()
        .filter(|name| !declared.contains(name.as_str()))
        .collect();
    assert!(
        forgotten.is_empty(),
        "tests/integration has files main.rs does not declare as `mod`: {forgotten:?}"
    );
    // The list above was read, not empty by a parsing slip.
    assert!(
        declared.contains("support") && declared.len() >= 9,
        "{declared:?}"
    );
}
