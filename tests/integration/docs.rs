//! Every example in the documentation works: each fenced block marked as a
//! file (` ```od `, ` ```bed `, ` ```lsys `) in README.md and docs/*.md is
//! loaded through the library pipeline and checked as `stlc check` does
//! (an OD grows, a BED validates and measures, an L-system parses); a BED or
//! L-system must also draw at least one stem.

use std::fs;

use stlc::grow::GrowOptions;
use stlc::pipeline::{self, Loaded, SceneRequest};
use stlc::progress::NoProgress;
use stlc::syntax::InputKind;

/// (file, first line of the block, kind, text) of every file block.
fn blocks() -> Vec<(String, usize, InputKind, String)> {
    let root = env!("CARGO_MANIFEST_DIR");
    let mut files = vec![format!("{root}/README.md")];
    let docs = crate::support::files_with("docs", "md");
    files.extend(docs.iter().map(|p| p.to_string_lossy().into_owned()));
    let mut out = Vec::new();
    for file in files {
        let text = fs::read_to_string(&file).unwrap();
        let mut current: Option<(usize, InputKind, String)> = None;
        for (n, line) in text.lines().enumerate() {
            let fence = line.trim();
            match current.as_mut() {
                Some((start, kind, body)) if fence.starts_with("```") => {
                    out.push((file.clone(), *start, *kind, std::mem::take(body)));
                    current = None;
                }
                Some((_, _, body)) => body.push_str(&format!("{line}\n")),
                None => {
                    let kind = match fence {
                        "```od" => Some(InputKind::Od),
                        "```bed" => Some(InputKind::Bed),
                        "```lsys" => Some(InputKind::Lsys),
                        _ => None,
                    };
                    current = kind.map(|k| (n + 1, k, String::new()));
                }
            }
        }
        assert!(current.is_none(), "{file}: a block is not closed");
    }
    out
}

#[test]
fn every_file_example_in_the_docs_loads_checks_and_draws() {
    let blocks = blocks();
    // The language reference, the .lsys page and the tutorial have examples.
    for kind in [InputKind::Od, InputKind::Bed, InputKind::Lsys] {
        assert!(blocks.iter().any(|b| b.2 == kind), "no {kind:?} example");
    }
    for (file, line, kind, text) in blocks {
        let at = format!("{file}:{line}");
        let opts = GrowOptions::default();
        let loaded = pipeline::load(text.as_bytes(), kind, &opts.limits)
            .unwrap_or_else(|e| panic!("{at}: {e}"));
        let checked = pipeline::check(&loaded, &opts).unwrap_or_else(|e| panic!("{at}: {e}"));
        assert!(checked.summary.contains(": ok"), "{at}");
        if matches!(loaded, Loaded::Od(_)) {
            continue;
        }
        let req = SceneRequest {
            grow: opts,
            derivation: Default::default(),
            depth: None,
            limits: opts.limits,
        };
        let scene =
            pipeline::scene(loaded, &req, &mut NoProgress).unwrap_or_else(|e| panic!("{at}: {e}"));
        let mut count = stlc::turtle::Counter::default();
        scene.draw(&mut count, &mut NoProgress).unwrap();
        assert!(count.0 > 0, "{at}: draws nothing");
    }
}

/// The tutorial shows each step's file as it is in examples/tutorial/
/// (comment lines aside), so the commands under the blocks draw what the
/// blocks say.
#[test]
fn the_tutorial_blocks_are_its_example_files() {
    let root = env!("CARGO_MANIFEST_DIR");
    let tutorial = fs::read_to_string(format!("{root}/docs/tutorial.md")).unwrap();
    let shown: Vec<String> = blocks()
        .into_iter()
        .filter(|b| b.0.ends_with("tutorial.md"))
        .map(|b| b.3)
        .collect();
    let mut steps: Vec<_> = fs::read_dir(format!("{root}/examples/tutorial"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    steps.sort();
    assert!(steps.len() >= 5, "{steps:?}");
    for step in steps {
        let text: String = fs::read_to_string(&step)
            .unwrap()
            .lines()
            .filter(|l| !l.starts_with('#'))
            .map(|l| format!("{l}\n"))
            .collect();
        assert!(
            shown.contains(&text),
            "{} is not shown as it is in docs/tutorial.md",
            step.display()
        );
        let name = step.file_name().unwrap().to_string_lossy().into_owned();
        assert!(tutorial.contains(&name), "the tutorial never runs {name}");
    }
}
