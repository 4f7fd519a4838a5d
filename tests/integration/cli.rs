//! The `stlc` binary as a user runs it: every command, stdin/stdout, exit
//! codes, messages, and the files on disk before and after.

use std::fs;
use std::io::{Read, Write};
use std::path::Path;
use std::process::{Command as StdCommand, Stdio};

use assert_cmd::Command;
use predicates::prelude::*;

fn stlc() -> Command {
    let mut c = Command::cargo_bin("stlc").expect("binary");
    c.env("NO_COLOR", "1");
    c
}

/// `F -> F+F` at 90 degrees: depth 2 is `F+F+F+F`, a unit square traced
/// anticlockwise on screen from the origin: up, left, down, right.
const SQUARE: &str = "# a square\ngenerations 2\nangle 90\naxiom F\nrule F F+F\n";

/// A BED by hand: the paper's worked example (003, section IV.1.4).
const WORKED_BED: &str = "Worked\n(50, 100)\nL=10(0) B=1(0)\nRULE\nR1: [F][+F][-F]\nR2: [++F][-F]\nSEED\nR1{R1{,,},R2{,},R1{,,}}\nENDSEED\n";

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn help_teaches_every_command_with_an_example() {
    for cmd in ["render", "compile", "expand", "stats", "check"] {
        stlc()
            .args([cmd, "--help"])
            .assert()
            .success()
            .stdout(predicate::str::contains("Examples:"))
            .stdout(predicate::str::contains("stlc "));
    }
    stlc()
        .arg("--help")
        .assert()
        .success()
        .stdout(predicate::str::contains(".od"))
        .stdout(predicate::str::contains("Exit status"));
}

#[test]
fn usage_errors_exit_2() {
    stlc().assert().code(2);
    stlc().args(["render"]).assert().code(2);
    stlc().args(["frobnicate"]).assert().code(2);
    stlc()
        .args(["render", "x.lsys", "--size", "0x5"])
        .assert()
        .code(2);
}

#[test]
fn expand_streams_the_derived_word() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("sq.lsys");
    fs::write(&f, SQUARE).unwrap();
    for strategy in ["dfs", "bfs"] {
        stlc()
            .args(["expand", f.to_str().unwrap(), "--strategy", strategy])
            .assert()
            .success()
            .stdout("F+F+F+F\n");
    }
    // --depth overrides generations: depth 3 doubles it again.
    stlc()
        .args(["expand", f.to_str().unwrap(), "--depth", "3"])
        .assert()
        .success()
        .stdout("F+F+F+F+F+F+F+F\n");
}

#[test]
fn stdin_and_stdout_with_dash() {
    stlc()
        .args(["expand", "-", "--from", "lsys"])
        .write_stdin(SQUARE)
        .assert()
        .success()
        .stdout("F+F+F+F\n");
    // Unnamed input is recognised by its first key.
    stlc()
        .args(["expand", "-"])
        .write_stdin(SQUARE)
        .assert()
        .success()
        .stdout("F+F+F+F\n");
    let out = stlc()
        .args(["render", "-", "--from", "lsys", "-f", "svg", "-o", "-"])
        .write_stdin(SQUARE)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let svg = String::from_utf8(out).unwrap();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"), "{svg}");
    assert!(svg.trim_end().ends_with("</svg>"));
}

#[test]
fn stats_json_has_exact_counts_and_the_turtle_extent() {
    let out = stlc()
        .args(["stats", "-", "--from", "lsys", "--json"])
        .write_stdin(SQUARE)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(v["length"], "7");
    assert_eq!(v["segments"], "4");
    assert_eq!(v["symbols"]["F"], "4");
    assert_eq!(v["symbols"]["+"], "3");
    // Up, left, down, right from the origin: box [-1,-1,0,0], back home.
    let num = |x: &serde_json::Value| x.as_f64().unwrap();
    let bbox: Vec<f64> = v["bbox"].as_array().unwrap().iter().map(num).collect();
    assert_eq!(bbox, vec![-1.0, -1.0, 0.0, 0.0]);
    let end: Vec<f64> = v["end"].as_array().unwrap().iter().map(num).collect();
    assert!(end[0].abs() < 1e-9 && end[1].abs() < 1e-9, "{end:?}");
}

#[test]
fn stats_at_depth_57_is_exact() {
    // F -> F[+F]F[-F]F: each F becomes 11 symbols (5 F, 6 others), so
    // L(n) = 5 L(n-1) + 6, L(0) = 1: L(n) = (5^(n+1) - 3) / 2.
    let lsys = "angle 25.7\naxiom F\nrule F F[+F]F[-F]F\n";
    let out = stlc()
        .args(["stats", "-", "--from", "lsys", "--depth", "57", "--json"])
        .write_stdin(lsys)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let five57 = num_bigint::BigUint::from(5u32).pow(57);
    let length = (five57.clone() * 5u32 - 3u32) / 2u32;
    assert_eq!(v["length"], length.to_string());
    assert_eq!(length.to_string().len(), 41);
    assert_eq!(v["segments"], five57.to_string());
    assert!(v["bbox"].is_null(), "too long to walk: {}", v["bbox"]);
}

#[test]
fn render_png_and_svg_files() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("sq.lsys");
    fs::write(&f, SQUARE).unwrap();
    // Default output: beside the input, .png.
    stlc()
        .args(["render", f.to_str().unwrap()])
        .assert()
        .success();
    let png = fs::read(dir.path().join("sq.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let pix = tiny_skia::Pixmap::decode_png(&png).unwrap();
    // A square fits a square picture: 800 x 800 by default.
    assert_eq!((pix.width(), pix.height()), (800, 800));

    let svg = dir.path().join("out.svg");
    stlc()
        .args([
            "render",
            f.to_str().unwrap(),
            "-o",
            svg.to_str().unwrap(),
            "--size",
            "200x100",
        ])
        .assert()
        .success();
    let text = fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("width=\"200\"") && text.contains("height=\"100\""),
        "{text}"
    );
    assert_eq!(files_in(dir.path()), ["out.svg", "sq.lsys", "sq.png"]);
}

#[test]
fn a_bad_input_points_at_the_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("bad.lsys");
    fs::write(&f, "angle 90\naxiom F\nrule F F[+F\n").unwrap();
    let out = dir.path().join("bad.png");
    fs::write(&out, b"previous picture").unwrap();
    stlc()
        .args([
            "render",
            f.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--depth",
            "2",
        ])
        .assert()
        .code(1)
        .stderr(predicate::str::contains("bad.lsys"))
        .stderr(predicate::str::contains(":3:"))
        .stderr(predicate::str::contains("["));
    // The old output is untouched and no temporary file is left.
    assert_eq!(fs::read(&out).unwrap(), b"previous picture");
    assert_eq!(files_in(dir.path()), ["bad.lsys", "bad.png"]);
}

#[test]
fn missing_file_and_unwritable_directory_are_errors_not_panics() {
    stlc()
        .args(["check", "/nonexistent/tree.od"])
        .assert()
        .code(1)
        .stderr(predicate::str::contains("cannot read"));
    stlc()
        .args([
            "render",
            "-",
            "--from",
            "lsys",
            "-o",
            "/nonexistent/dir/x.png",
        ])
        .write_stdin(SQUARE)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("/nonexistent/dir"))
        .stderr(predicate::str::contains("panicked").not());
}

#[test]
fn a_failed_render_keeps_the_previous_output_and_leaves_no_temp_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tree.png");
    fs::write(&out, b"old").unwrap();
    // Depth far beyond the limit: refused before anything is drawn.
    stlc()
        .args(["render", "-", "--from", "lsys", "--depth", "1000000", "-o"])
        .arg(&out)
        .write_stdin(SQUARE)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("--max-depth"));
    assert_eq!(fs::read(&out).unwrap(), b"old");
    assert_eq!(files_in(dir.path()), ["tree.png"]);
}

#[test]
fn a_broken_pipe_exits_quietly() {
    let bin = assert_cmd::cargo::cargo_bin("stlc");
    let mut child = StdCommand::new(bin)
        .args(["expand", "-", "--from", "lsys", "--depth", "20"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(SQUARE.as_bytes())
        .unwrap();
    let mut first = [0u8; 16];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    assert_eq!(&first, b"F+F+F+F+F+F+F+F+");
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{:?}", out.status);
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
}

#[test]
fn expand_of_a_bed_prints_drawing_components_only() {
    stlc()
        .args(["expand", "-", "--from", "bed"])
        .write_stdin(WORKED_BED)
        .assert()
        .success()
        .stdout("[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]\n");
}

#[test]
fn check_summarises_each_kind() {
    stlc()
        .args(["check", "-", "--from", "bed"])
        .write_stdin(WORKED_BED)
        .assert()
        .success()
        .stdout(predicate::str::contains("R1 (3 branches)"))
        .stdout(predicate::str::contains("R2 (2 branches)"))
        // 3 + (3 + 2 + 3) segments.
        .stdout(predicate::str::contains("stems       11"));
    stlc()
        .args(["check", "-", "--from", "lsys"])
        .write_stdin(SQUARE)
        .assert()
        .success()
        .stdout(predicate::str::contains("F -> F+F"));
}

#[test]
fn compile_and_stats_refuse_the_wrong_kind_with_a_hint() {
    stlc()
        .args(["compile", "-", "--from", "lsys"])
        .write_stdin(SQUARE)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("stlc render"));
    stlc()
        .args(["stats", "-", "--from", "bed"])
        .write_stdin(WORKED_BED)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("stlc check"));
}

#[test]
fn png_to_a_file_named_dash_svg_is_svg() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("w.svg");
    stlc()
        .args(["render", "-", "--from", "bed", "-o"])
        .arg(&out)
        .write_stdin(WORKED_BED)
        .assert()
        .success();
    let text = fs::read_to_string(&out).unwrap();
    assert!(text.contains("<path"), "{text}");
}
