//! Golden BED files: every `.od` in `examples/` and `tests/cases/grow/` is
//! compiled under both growth strategies and compared with
//! `tests/cases/grow/<name>.<strategy>.bed` (see [`crate::support`] for
//! `STLC_BLESS=1` and what a mismatch leaves behind).

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use stlc::Limits;
use stlc::grow::GrowthOrder;
use stlc::grow::grow;
use stlc::interpret::bed::draw_into;
use stlc::model::Format;
use stlc::progress::NoProgress;
use stlc::syntax::stl;
use stlc::turtle::Counter;

use crate::support::{assert_golden, assert_same_text, blessing, files_with, manifest_path};

/// All outline descriptions with goldens, sorted by name.
fn cases() -> Vec<PathBuf> {
    let mut v = files_with("examples", "od");
    v.extend(files_with("tests/cases/grow", "od"));
    v.sort();
    v
}

fn compile(od_path: &Path, strategy: GrowthOrder) -> (String, u64) {
    let text = fs::read_to_string(od_path).unwrap();
    let od = stl::parse(&text, Format::Od, &Limits::default())
        .unwrap_or_else(|e| panic!("{}: {e}", od_path.display()));
    let grown = grow(&od, &crate::support::opts(strategy), &mut NoProgress).unwrap();
    let text = stlc::bed::write::write(grown.bed.description());
    (text, grown.stems)
}

/// The `.bed` goldens on disk, by file name.
fn golden_files() -> BTreeSet<String> {
    fs::read_dir(manifest_path("tests/cases/grow"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".bed"))
        .collect()
}

#[test]
fn compiled_beds_match_their_goldens() {
    let mut checked = BTreeSet::new();
    for od in cases() {
        let stem = od.file_stem().unwrap().to_string_lossy().into_owned();
        for (strategy, tag) in [(GrowthOrder::Bfs, "bfs"), (GrowthOrder::Dfs, "dfs")] {
            let name = format!("{stem}.{tag}.bed");
            let (actual, _) = compile(&od, strategy);
            assert_golden(format!("tests/cases/grow/{name}"), &actual);
            checked.insert(name);
        }
    }
    // tiny + the thirteen example outlines (three of them 3D), two
    // strategies each; and no golden is left over from a case that is gone
    // (it would never be checked).
    assert_eq!(checked.len(), 28, "{checked:?}");
    let orphans: Vec<String> = golden_files().difference(&checked).cloned().collect();
    assert!(
        orphans.is_empty(),
        "goldens in tests/cases/grow that no case produces: {orphans:?}"
    );
}

#[test]
fn every_golden_reparses_and_rewrites_unchanged_and_draws_its_stems() {
    if blessing() {
        return; // the goldens are being rewritten by the test above
    }
    for od in cases() {
        let stem = od.file_stem().unwrap().to_string_lossy().into_owned();
        for (order, tag) in [(GrowthOrder::Bfs, "bfs"), (GrowthOrder::Dfs, "dfs")] {
            let golden = manifest_path(format!("tests/cases/grow/{stem}.{tag}.bed"));
            let text = fs::read_to_string(&golden).unwrap();
            let bed = stl::parse(&text, Format::Bed, &Limits::default())
                .unwrap_or_else(|e| panic!("{}: {e}", golden.display()));
            stlc::bed::validate(&bed, &Limits::default()).unwrap();
            let rewritten = stlc::bed::write::write(&bed);
            assert_same_text(&golden.display().to_string(), &text, &rewritten);
            // The BED draws exactly the stems the grower counted.
            let (_, stems) = compile(&od, order);
            let (limits, dfs) = (Limits::default(), stlc::interpret::Derivation::Dfs);
            let bed = stlc::bed::Bed::new(bed.clone(), &limits).unwrap();
            let drawn = draw_into(&bed, dfs, &limits, Counter::default(), &mut NoProgress).unwrap();
            assert_eq!(drawn.0, stems, "{stem}.{tag}");
        }
    }
}

#[test]
fn figures_9_and_10_differ_by_strategy() {
    let od = manifest_path("examples/fig9.od");
    let [bfs, dfs] = [GrowthOrder::Bfs, GrowthOrder::Dfs].map(|o| compile(&od, o).0);
    assert_ne!(bfs, dfs);
}
