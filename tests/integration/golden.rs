//! Golden BED files: every `.od` in `examples/` and `tests/cases/grow/` is
//! compiled under both growth strategies and compared with
//! `tests/cases/grow/<name>.<strategy>.bed`.
//!
//! Regenerate after an intended change with
//! `STLC_BLESS=1 cargo test --test integration golden`, then read the diff
//! (`git diff tests/cases/grow`) before committing. CI never writes.

use std::fs;
use std::path::{Path, PathBuf};

use stlc::Limits;
use stlc::grow::GrowthOrder;
use stlc::grow::{GrowOptions, grow};
use stlc::model::Format;
use stlc::progress::NoProgress;
use stlc::syntax::stl;
use stlc::turtle::Counter;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// All outline descriptions with goldens, sorted by name.
fn cases() -> Vec<PathBuf> {
    let mut v = Vec::new();
    for dir in ["examples", "tests/cases/grow"] {
        for e in fs::read_dir(root().join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "od") {
                v.push(p);
            }
        }
    }
    v.sort();
    v
}

fn compile(od_path: &Path, strategy: GrowthOrder) -> (String, u64) {
    let text = fs::read_to_string(od_path).unwrap();
    let od = stl::parse(&text, Format::Od, &Limits::default())
        .unwrap_or_else(|e| panic!("{}: {e}", od_path.display()));
    let opts = GrowOptions {
        growth: strategy,
        ..GrowOptions::default()
    };
    let grown = grow(&od, &opts, &mut NoProgress).unwrap();
    (
        stlc::bed::write::write(grown.bed.description()),
        grown.stems,
    )
}

/// Fails with the first differing line and some context, not two walls of text.
fn assert_same_text(name: &str, expected: &str, actual: &str) {
    if expected == actual {
        return;
    }
    let (e, a): (Vec<_>, Vec<_>) = (expected.lines().collect(), actual.lines().collect());
    let i = e
        .iter()
        .zip(&a)
        .position(|(x, y)| x != y)
        .unwrap_or(e.len().min(a.len()));
    let ctx = |v: &[&str]| v[i.saturating_sub(3)..(i + 4).min(v.len())].join("\n");
    panic!(
        "{name}: output differs from the golden at line {} (golden {} lines, now {})\n--- golden\n{}\n--- now\n{}\n\
         (regenerate with STLC_BLESS=1 cargo test --test integration golden, then read git diff)",
        i + 1,
        e.len(),
        a.len(),
        ctx(&e),
        ctx(&a)
    );
}

#[test]
fn compiled_beds_match_their_goldens() {
    let bless = std::env::var_os("STLC_BLESS").is_some();
    let mut checked = 0;
    for od in cases() {
        let stem = od.file_stem().unwrap().to_string_lossy().into_owned();
        for (strategy, tag) in [(GrowthOrder::Bfs, "bfs"), (GrowthOrder::Dfs, "dfs")] {
            let golden = root().join(format!("tests/cases/grow/{stem}.{tag}.bed"));
            let (actual, _) = compile(&od, strategy);
            if bless {
                fs::write(&golden, &actual).unwrap();
            }
            let expected = fs::read_to_string(&golden)
                .unwrap_or_else(|_| panic!("missing golden {}", golden.display()));
            assert_same_text(&format!("{stem}.{tag}"), &expected, &actual);
            checked += 1;
        }
    }
    // tiny + the five example outlines, two strategies each.
    assert!(checked >= 12, "only {checked} goldens checked");
}

#[test]
fn every_golden_reparses_and_rewrites_unchanged_and_draws_its_stems() {
    if std::env::var_os("STLC_BLESS").is_some() {
        return; // the goldens are being rewritten by the test above
    }
    for od in cases() {
        let stem = od.file_stem().unwrap().to_string_lossy().into_owned();
        for tag in ["bfs", "dfs"] {
            let golden = root().join(format!("tests/cases/grow/{stem}.{tag}.bed"));
            let text = fs::read_to_string(&golden).unwrap();
            let bed = stl::parse(&text, Format::Bed, &Limits::default())
                .unwrap_or_else(|e| panic!("{}: {e}", golden.display()));
            stlc::bed::validate(&bed, &Limits::default()).unwrap();
            assert_same_text(
                &golden.display().to_string(),
                &text,
                &stlc::bed::write::write(&bed),
            );
            // The BED draws exactly the stems the grower counted.
            let (_, stems) = compile(
                &od,
                if tag == "bfs" {
                    GrowthOrder::Bfs
                } else {
                    GrowthOrder::Dfs
                },
            );
            let drawn = stlc::bed::Bed::new(bed.clone(), &Limits::default())
                .and_then(|bed| {
                    stlc::interpret::bed::draw_into(
                        &bed,
                        stlc::interpret::Derivation::Dfs,
                        &Limits::default(),
                        Counter::default(),
                        &mut NoProgress,
                    )
                })
                .unwrap();
            assert_eq!(drawn.0, stems, "{stem}.{tag}");
        }
    }
}

#[test]
fn compiling_twice_gives_identical_bytes() {
    let od = root().join("examples/fig9.od");
    for s in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        assert_eq!(compile(&od, s).0, compile(&od, s).0);
    }
}

#[test]
fn figures_9_and_10_differ_by_strategy() {
    let od = root().join("examples/fig9.od");
    assert_ne!(
        compile(&od, GrowthOrder::Bfs).0,
        compile(&od, GrowthOrder::Dfs).0
    );
}
