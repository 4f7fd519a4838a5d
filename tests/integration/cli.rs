//! The `stlc` binary as a user runs it: stdin/stdout, exit codes, messages,
//! and the files on disk before and after. A command whose whole story is
//! what it prints and its exit status is a literate case in `tests/cmd/`
//! (`cli_cases.rs`); what stays here needs standard input, generated input,
//! pixels, goldens or the file system checked around the command.

use std::fs;
use std::io::{Read, Write};
use std::path::Path;
use std::process::{Command as StdCommand, Stdio};

use predicates::prelude::*;

use crate::support::{
    assert_golden, files_in, manifest_path, outcome, png_at, stlc_line, stlc_piped,
};

/// `F -> F+F` at 90 degrees: depth 2 is `F+F+F+F`, a unit square traced
/// anticlockwise on screen from the origin: up, left, down, right.
const SQUARE: &str = "# a square\ngenerations 2\nangle 90\naxiom F\nrule F F+F\n";

/// A BED by hand: the paper's worked example (003, section IV.1.4).
const WORKED_BED: &str = "Worked\n(50, 100)\nL=10(0) B=1(0)\nRULE\nR1: [F][+F][-F]\nR2: [++F][-F]\nSEED\nR1{R1{,,},R2{,},R1{,,}}\nENDSEED\n";

/// The crate's root, for paths written into a command line.
const ROOT: &str = env!("CARGO_MANIFEST_DIR");

#[test]
fn stdin_and_stdout_with_dash() {
    assert_eq!(stlc_piped("expand - --from lsys", SQUARE), b"F+F+F+F\n");
    // Unnamed input is recognised by its first key.
    assert_eq!(stlc_piped("expand -", SQUARE), b"F+F+F+F\n");
    let out = stlc_piped("render - --from lsys -f svg -o -", SQUARE);
    let svg = String::from_utf8(out).unwrap();
    assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"), "{svg}");
    assert!(svg.trim_end().ends_with("</svg>"));
}

#[test]
fn stats_at_depth_57_is_exact() {
    // F -> F[+F]F[-F]F: each F becomes 11 symbols (5 F, 6 others), so
    // L(n) = 5 L(n-1) + 6, L(0) = 1: L(n) = (5^(n+1) - 3) / 2.
    let lsys = "angle 25.7\naxiom F\nrule F F[+F]F[-F]F\n";
    let out = stlc_piped("stats - --from lsys --depth 57 --json", lsys);
    let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
    let five57 = num_bigint::BigUint::from(5u32).pow(57);
    let length = (five57.clone() * 5u32 - 3u32) / 2u32;
    assert_eq!(v["length"], length.to_string());
    assert_eq!(length.to_string().len(), 41);
    assert_eq!(v["segments"], five57.to_string());
    // 10^40 symbols: bbox and end come from the memoized geometry. The
    // trunk is 3^57 unit steps straight up, and nothing is higher.
    let three57 = 3f64.powi(57);
    assert_eq!(v["bbox"][1].as_f64(), Some(-three57), "{}", v["bbox"]);
    assert_eq!(v["bbox"][3].as_f64(), Some(0.0));
    assert_eq!(v["end"][0].as_f64(), Some(0.0));
    assert_eq!(v["end"][1].as_f64(), Some(-three57));
}

#[test]
fn render_png_and_svg_files() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("sq.lsys");
    fs::write(&f, SQUARE).unwrap();
    // Default output: beside the input, .png.
    stlc_line(&format!("render {}", f.display()))
        .assert()
        .success();
    let png = fs::read(dir.path().join("sq.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let pix = tiny_skia::Pixmap::decode_png(&png).unwrap();
    // A square fits a square picture: 800 x 800 by default.
    assert_eq!((pix.width(), pix.height()), (800, 800));

    let svg = dir.path().join("out.svg");
    let line = format!("render {} -o {} --size 200x100", f.display(), svg.display());
    stlc_line(&line).assert().success();
    let text = fs::read_to_string(&svg).unwrap();
    let sized = text.contains("width=\"200\"") && text.contains("height=\"100\"");
    assert!(sized, "{text}");
    assert_eq!(files_in(dir.path()), ["out.svg", "sq.lsys", "sq.png"]);
    // A BED from standard input to a file named .svg: the name says SVG.
    let out = dir.path().join("w.svg");
    let line = format!("render - --from bed -o {}", out.display());
    stlc_line(&line).write_stdin(WORKED_BED).assert().success();
    let text = fs::read_to_string(&out).unwrap();
    assert!(text.contains("<path"), "{text}");
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
    let mut stdin = child.stdin.take().unwrap();
    stdin.write_all(SQUARE.as_bytes()).unwrap();
    drop(stdin);
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 16];
    stdout.read_exact(&mut first).unwrap();
    assert_eq!(&first, b"F+F+F+F+F+F+F+F+");
    drop(stdout);
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "{:?}", out.status);
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
}

// ------------------------------------------------- limits and hostile input --

/// Runs `stlc LINE` with `stdin`; returns (exit code, stderr).
fn run_stdin(line: &str, stdin: impl Into<Vec<u8>>) -> (i32, String) {
    let (code, _, err) = outcome(stlc_line(line).write_stdin(stdin));
    (code, err)
}

/// `stlc LINE` with `stdin` fails (exit 1) saying each of `said`.
fn refused(line: &str, stdin: impl Into<Vec<u8>>, said: &[&str]) {
    let (code, err) = run_stdin(line, stdin);
    assert_eq!(code, 1, "{line}: {err}");
    for s in said {
        assert!(err.contains(s), "{err}");
    }
}

#[test]
fn each_limit_names_the_flag_that_raises_it() {
    // Nesting, in each format.
    let n = 100_000;
    let deep = format!("angle 90\naxiom {}F{}\n", "[".repeat(n), "]".repeat(n));
    refused("check - --from lsys", deep, &["--max-nesting"]);
    let deep_bed = format!(
        "T (0,0) RULE R1: [F] SEED {}{} ENDSEED",
        "R1{".repeat(n),
        "}".repeat(n)
    );
    refused("check - --from bed", deep_bed, &["--max-nesting"]);
    // A RULE section of 200,001 parts (one rule of 200,000 branches) is
    // refused before parsing; under a raised limit it reads.
    let wide = format!("T (0,0) RULE R1: {} SEED F ENDSEED", "[+F]".repeat(200_000));
    let said = ["200001 exceeds the limit of 100000", "--max-rule-parts"];
    refused("check - --from bed", wide.clone(), &said);
    let (code, err) = run_stdin("check - --from bed --max-rule-parts 200001", wide);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn the_readme_commands_run() {
    let readme = fs::read_to_string(manifest_path("README.md")).unwrap();
    // The first screen names an example that exists and the test command.
    assert!(readme.contains("cargo test"));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("2dtree.png");
    assert!(readme.contains("render examples/2dtree.od --show-layout"));
    let line = format!("render {ROOT}/examples/2dtree.od --show-layout -o");
    stlc_line(&line).arg(&out).assert().success();
    let pix = png_at(&out);
    // The layout is 180 x 192 canvas units; with a margin of 4% of 192
    // plus half a stem (B=1) on every side, 8.18 units, it is 196.36 x
    // 208.36: round(800 x 196.36 / 208.36) = 754 x 800 pixels.
    assert_eq!((pix.width(), pix.height()), (754, 800));
}

/// The grown tiny tree (tests/cases/grow/tiny.bfs.bed) over its layout,
/// checked by hand: the layout box x -15..15, y -25..5 with a margin of
/// 4% of 30 plus half a stem (B=1), 1.7 units, is 33.4 units square and
/// fills 120 px, so the scale is s = 120 / 33.4 = 3.593; the box's centre
/// (0, -10) is pixel (60, 60), the root (0, 0) is (60, 60 + 10 s) =
/// (60, 95.93), stems are 3.59 px wide, the four tips are (24.07, 95.93),
/// (24.07, 24.07), (95.93, 24.07), (95.93, 95.93), and the box spans
/// 60 -/+ 15 s = 6.11 .. 113.89: the margin outside it is background.
#[test]
fn a_bed_with_a_layout_renders_its_golden_svg() {
    let line = |f: &str| {
        format!(
            "render {ROOT}/tests/cases/grow/tiny.bfs.bed --show-layout --size 120x120 -f {f} -o -"
        )
    };
    let svg = String::from_utf8(stlc_piped(&line("svg"), "")).unwrap();
    assert_golden("tests/cases/render/tiny-layout.svg", &svg);
    // The PNG agrees: stem pixels are bark brown, the layout green, the
    // margin around the layout white.
    let pix = tiny_skia::Pixmap::decode_png(&stlc_piped(&line("png"), "")).unwrap();
    let at = |x: u32, y: u32| {
        let p = pix.pixel(x, y).unwrap();
        (p.red(), p.green(), p.blue())
    };
    assert_eq!(at(60, 80), (0x4a, 0x2c, 0x12)); // on the seed stem
    assert_eq!(at(24, 40), (0x4a, 0x2c, 0x12)); // on a level-2 stem
    assert_eq!(at(40, 100), (0, 128, 0)); // between stems: layout green
    assert_eq!(at(3, 3), (255, 255, 255)); // the margin: background
}

#[test]
fn a_full_disk_on_stdout_is_an_error_not_a_panic() {
    // Only the real device: where /dev is a plain directory, creating
    // "/dev/full" would make an ordinary file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let is_device = fs::metadata("/dev/full").is_ok_and(|m| m.file_type().is_char_device());
        if !is_device {
            return; // no /dev/full on this system
        }
    }
    let Ok(full) = fs::OpenOptions::new().write(true).open("/dev/full") else {
        return;
    };
    let bin = assert_cmd::cargo::cargo_bin("stlc");
    let out = StdCommand::new(bin)
        .args(["expand", "-", "--from", "lsys", "--depth", "12"])
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(full)
        .stderr(Stdio::piped())
        .spawn()
        .and_then(|mut c| {
            c.stdin.take().unwrap().write_all(SQUARE.as_bytes())?;
            c.wait_with_output()
        })
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("No space left"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// `stlc compile` as a user runs it: to a named file, to the default name
/// beside the input, to stdout; each strategy gives its golden BED (the
/// goldens in tests/cases/grow were checked by hand and by the invariant
/// tests in grow.rs).
#[test]
fn compile_writes_the_golden_bed_to_a_file_a_default_name_and_stdout() {
    let golden = |s: &str| format!("tests/cases/grow/fig9.{s}.bed");
    let dir = tempfile::tempdir().unwrap();
    let od = dir.path().join("fig9.od");
    fs::copy(manifest_path("examples/fig9.od"), &od).unwrap();
    // Named output, default strategy bfs.
    let out = dir.path().join("grown.bed");
    let line = format!("compile {} -o {}", od.display(), out.display());
    stlc_line(&line).assert().success().stdout("");
    assert_golden(golden("bfs"), &fs::read_to_string(&out).unwrap());
    // No -o: the input's name with .bed, beside it.
    let line = format!("compile {} --strategy dfs", od.display());
    stlc_line(&line).assert().success();
    let beside = fs::read_to_string(dir.path().join("fig9.bed")).unwrap();
    assert_golden(golden("dfs"), &beside);
    assert_eq!(files_in(dir.path()), ["fig9.bed", "fig9.od", "grown.bed"]);
    // Standard input to standard output.
    let piped = stlc_piped("compile - --strategy dfs", fs::read(&od).unwrap());
    assert_golden(golden("dfs"), &String::from_utf8(piped).unwrap());
    // bfs and dfs grow different trees here (Figures 9 and 10), so the
    // comparisons above tell whether --strategy reached the grower.
    let read = |s: &str| fs::read(manifest_path(golden(s))).unwrap();
    assert_ne!(read("bfs"), read("dfs"));
}

/// Growing and drawing in one step draws exactly what compiling and then
/// rendering the BED draws (same pixels), for each strategy.
#[test]
fn render_of_an_od_equals_render_of_its_compiled_bed() {
    let dir = tempfile::tempdir().unwrap();
    for strategy in ["bfs", "dfs"] {
        let sized = "--show-layout --size 200x200 -o";
        let from_od = dir.path().join(format!("od-{strategy}.png"));
        let od = format!("render {ROOT}/examples/fig9.od --growth {strategy} {sized}");
        stlc_line(&od).arg(&from_od).assert().success();
        let from_bed = dir.path().join(format!("bed-{strategy}.png"));
        let bed = format!("render {ROOT}/tests/cases/grow/fig9.{strategy}.bed {sized}");
        stlc_line(&bed).arg(&from_bed).assert().success();
        let (a, b) = (png_at(&from_od), png_at(&from_bed));
        assert_eq!((a.width(), a.height()), (b.width(), b.height()));
        assert!(a.data() == b.data(), "{strategy}: pixels differ");
    }
}

/// Every command that writes a file, failing for each class of reason
/// (bad input, limit, growth refused, bad option value), leaves an existing
/// output byte for byte as it was, no temporary file beside it, exit 1 or 2
/// and a message on stderr.
#[test]
fn every_writing_command_keeps_the_old_output_on_every_failure_class() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_owned()
    };
    let bad_lsys = write("bad.lsys", "angle 90\naxiom F]\n");
    let bad_rule = write("rule.lsys", "angle 90\naxiom F\nrule F F[+F\n");
    let square = write("sq.lsys", SQUARE);
    let bad_od = write("bad.od", "T\n(0, 0)\nRULE\nR1: [+F][-F\n");
    let unbounded = write("u.od", "U\n(0, 0)\nL=10(0) B=1(0)\nRULE\nR1: [+F][-F]\n");
    let u = &unbounded;
    let outside = "O\n(500, 500)\nRULE\nR1: [+F][-F]\nSEED\nFR1\nENDSEED\nLAYOUT\nRectangle (0,0), 100, 100 clGreen\nENDLAYOUT\n";
    let outside = write("out.od", outside);
    let bad_bed = write("bad.bed", "T (0,0) RULE R1: [F] SEED R7{} ENDSEED");
    let deep_stdin = "render - --from lsys --depth 1000000";
    let small_input = "--max-stems 5 --clearance=0 --max-input 10";
    // The line at fault is named, and the bracket; a limit is refused
    // before anything is drawn (from standard input too).
    let cases = [
        (format!("render {bad_rule} --depth 2"), 1, "rule.lsys:3:"),
        (format!("render {bad_rule} --depth 2"), 1, "["),
        (deep_stdin.into(), 1, "--max-depth"),
        (format!("render {bad_lsys}"), 1, "unbalanced"),
        (format!("render {square} --depth 1000000"), 1, "--max-depth"),
        (format!("render {square} --size 0x0"), 2, "size"),
        (format!("render {bad_bed}"), 1, "R7"),
        (format!("render {outside}"), 1, "root"),
        (format!("compile {bad_od}"), 1, "bad.od"),
        (format!("compile {unbounded}"), 1, "--max-stems"),
        (format!("compile {outside}"), 1, "root"),
        (format!("compile {u} --clearance -1"), 2, "clearance"),
        (format!("compile {u} --clearance nan"), 2, "clearance"),
        (format!("compile {u} {small_input}"), 1, "--max-input"),
        (format!("compile {square}"), 1, "lsys"),
        (format!("expand {bad_lsys}"), 1, "unbalanced"),
        (format!("expand {square} --depth 1000000"), 1, "--max-depth"),
        (format!("expand {bad_bed}"), 1, "R7"),
    ];
    for (line, code, needle) in cases {
        // `render` refuses an output extension that is not an image format.
        let name = if line.starts_with("render") {
            "previous.png"
        } else {
            "previous.out"
        };
        let out = dir.path().join(name);
        fs::write(&out, b"previous bytes").unwrap();
        let before = files_in(dir.path());
        let mut command = stlc_line(&line);
        if line.contains(" - ") {
            command.write_stdin(SQUARE);
        }
        let (got, _, err) = outcome(command.arg("-o").arg(&out));
        assert_eq!(got, code, "{line}: {err}");
        let says = err.to_lowercase().contains(&needle.to_lowercase());
        assert!(says, "{line}: {err}");
        assert!(!err.contains("panicked"), "{line}: {err}");
        assert_eq!(fs::read(&out).unwrap(), b"previous bytes", "{line}");
        assert_eq!(files_in(dir.path()), before, "{line} left a file");
    }
}

/// On a terminal (a pseudo-terminal from util-linux `script`, skipped where
/// there is none) the bar appears, names its passes and reaches 100 %; with
/// `--quiet`, or with stderr not a terminal, nothing is printed.
///
/// Each run draws a different depth, so its word length (the bar's total)
/// marks its own output: on this sandbox a `script` log can also hold output
/// of an earlier pseudo-terminal session.
#[test]
fn the_progress_bar_shows_on_a_terminal_only() {
    let dir = tempfile::tempdir().unwrap();
    // `script` needs a pseudo-terminal; a container without /dev/ptmx or
    // /dev/pts has none, and the test has nothing to look at there.
    let has_pty = StdCommand::new("script")
        .args(["-qfec", "true"])
        .arg(dir.path().join("probe.log"))
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !has_pty {
        return;
    }
    let bin = assert_cmd::cargo::cargo_bin("stlc");
    let root = env!("CARGO_MANIFEST_DIR");
    let run = |depth: u32, extra: &str| {
        let log = dir.path().join(format!("tty{depth}.log"));
        let (bin, dir) = (bin.display(), dir.path().display());
        let cmd = format!(
            "{bin} render {root}/examples/abop-1.24a.lsys --depth {depth} -o {dir}/x.png {extra}"
        );
        let st = StdCommand::new("script")
            .args(["-qfec", &cmd])
            .arg(&log)
            .env("STLC_PROGRESS_DELAY_MS", "0")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .status()
            .unwrap();
        assert!(st.success());
        fs::read_to_string(&log).unwrap()
    };
    // Word lengths (5^(n+1) - 3) / 2: depth 6 is 39,061, depth 7 195,311.
    let quiet = run(6, "--quiet");
    assert!(!quiet.contains("39,061"), "{quiet}");
    // --exact: a bounding pass, then every symbol drawn.
    let shown = run(7, "--exact");
    assert!(shown.contains("measuring: symbols"), "{shown}");
    assert!(shown.contains("drawing: symbols"), "{shown}");
    assert!(shown.contains("195,311/195,311"), "{shown}");
    // The default level of detail fits from the memo (no measuring pass);
    // at depth 7 nothing is under half a pixel, so every symbol is drawn.
    let lod = run(7, "");
    assert!(!lod.contains("measuring"), "{lod}");
    assert!(lod.contains("195,311/195,311"), "{lod}");
    // Not a terminal: stderr stays empty even with no delay.
    let line = format!("render {root}/examples/abop-1.24a.lsys --depth 7 -f svg -o -");
    let (code, _, err) = outcome(stlc_line(&line).env("STLC_PROGRESS_DELAY_MS", "0"));
    assert_eq!(code, 0);
    assert!(err.is_empty(), "{err}");
}

/// An SVG holds every segment, so it has a segment limit; it is checked
/// before a byte is written, with or without a layout fixing the view. A
/// PNG has no such limit. Counts by hand: `F -> F[+F]F[-F]F` at depth 4
/// draws 5^4 = 625 segments; the grown tiny tree draws 7 stems (1 + 2 + 4).
#[test]
fn an_svg_over_its_segment_limit_is_refused_before_a_byte_is_written() {
    let tree = format!("{ROOT}/examples/abop-1.24a.lsys");
    let tiny = format!("{ROOT}/tests/cases/grow/tiny.bfs.bed");
    for (input, depth, count) in [(&tree, "4", 625u64), (&tiny, "1", 7)] {
        let svg = format!("render {input} --depth {depth} -f svg -o - --show-layout");
        let over = format!("{svg} --max-svg-segments {}", count - 1);
        let (code, out, err) = outcome(&mut stlc_line(&over));
        assert_eq!(code, 1, "{err}");
        assert!(out.is_empty(), "{input}: wrote before refusing");
        let exceeds = format!("{count} exceeds the limit of {}", count - 1);
        let flag = err.contains("--max-svg-segments");
        assert!(err.contains(&exceeds) && flag, "{err}");
        let at = stlc_piped(&format!("{svg} --max-svg-segments {count}"), "");
        let svg = String::from_utf8(at).unwrap();
        // Every segment is written: one ` L` each (plus the three of the
        // layout rectangle under the tiny tree).
        let under_tiny = u64::from(input == &tiny) * 3;
        assert_eq!(svg.matches(" L").count() as u64, count + under_tiny);
        let png = format!("render {input} --depth {depth} -f png -o - --max-svg-segments 1");
        stlc_line(&png).assert().success();
    }
}

/// `stlc render INPUT -o OUT`.
fn render_to(input: &Path, out: impl AsRef<std::ffi::OsStr>) -> assert_cmd::assert::Assert {
    stlc_line(&format!("render {} -o", input.display()))
        .arg(out)
        .assert()
}

/// `-o` at something that is not a regular file: a named pipe and a null
/// device are written into and stay what they were (renaming a finished
/// file over them, as for a regular file, would replace the pipe or the
/// device with a file: `-o /dev/null` as root would remove the machine's
/// null device). A symbolic link stays a link and the file it names is
/// replaced; a dangling link creates that file; a loop of links is an error.
#[cfg(unix)]
#[test]
fn outputs_that_are_pipes_devices_or_links_stay_what_they_are() {
    use std::os::unix::fs::FileTypeExt;
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name);
    let square = p("square.lsys");
    fs::write(&square, SQUARE).unwrap();
    let svg = stlc_piped(&format!("render {} -o - -f svg", square.display()), "");
    assert!(svg.starts_with(b"<svg") || svg.starts_with(b"<?xml"));

    // A named pipe, read by another thread while stlc writes.
    let fifo = p("pipe.svg");
    let made = StdCommand::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        // A second name for the pipe, to release the reader should stlc
        // have replaced the pipe instead of writing into it.
        fs::hard_link(&fifo, p("pipe.alias")).unwrap();
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || fs::read(fifo).unwrap())
        };
        render_to(&square, &fifo).success();
        let still_a_pipe = fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo();
        if !still_a_pipe {
            drop(fs::OpenOptions::new().write(true).open(p("pipe.alias")));
        }
        assert!(still_a_pipe, "the pipe was replaced by a file");
        assert_eq!(reader.join().unwrap(), svg, "the pipe carried the SVG");
    }

    // A private null device (only where mknod is allowed, i.e. as root).
    let null = p("null.png");
    let made = StdCommand::new("mknod")
        .args(["-m", "666"])
        .arg(&null)
        .args(["c", "1", "3"])
        .stderr(Stdio::null())
        .status();
    if made.is_ok_and(|s| s.success()) {
        render_to(&square, &null).success();
        let ft = fs::symlink_metadata(&null).unwrap().file_type();
        assert!(ft.is_char_device(), "still the null device");
    }

    // A link to an existing file.
    let real = p("real.svg");
    fs::write(&real, "old").unwrap();
    std::os::unix::fs::symlink("real.svg", p("link.svg")).unwrap();
    render_to(&square, p("link.svg")).success();
    let link = fs::symlink_metadata(p("link.svg")).unwrap();
    assert!(link.file_type().is_symlink());
    assert_eq!(fs::read(&real).unwrap(), svg);

    // A dangling link: the file it names is created.
    std::os::unix::fs::symlink("made.svg", p("dangling.svg")).unwrap();
    render_to(&square, p("dangling.svg")).success();
    assert_eq!(fs::read(p("made.svg")).unwrap(), svg);

    // A loop: an error, nothing written.
    std::os::unix::fs::symlink("b.svg", p("a.svg")).unwrap();
    std::os::unix::fs::symlink("a.svg", p("b.svg")).unwrap();
    let before = files_in(dir.path());
    render_to(&square, p("a.svg"))
        .code(1)
        .stderr(predicate::str::contains("symbolic links"));
    assert_eq!(files_in(dir.path()), before, "no temporary file left");
}

/// A new output file gets the mode any new file gets here (0666 less the
/// umask, as `File::create` does), not a temporary file's 0600; a replaced
/// file keeps its own mode.
#[cfg(unix)]
#[test]
fn output_files_get_the_usual_mode_and_replaced_files_keep_theirs() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name);
    let square = p("square.lsys");
    fs::write(&square, SQUARE).unwrap();
    let mode = |path: &Path| fs::metadata(path).unwrap().permissions().mode() & 0o777;
    fs::File::create(p("plain")).unwrap();
    for (command, out) in [
        ("render", "new.png"),
        ("render", "new.svg"),
        ("expand", "new.txt"),
    ] {
        let line = format!("{command} square.lsys -o {out}");
        stlc_line(&line).current_dir(dir.path()).assert().success();
        assert_eq!(mode(&p(out)), mode(&p("plain")), "{out}");
    }
    let kept = p("kept.png");
    fs::write(&kept, "old").unwrap();
    fs::set_permissions(&kept, fs::Permissions::from_mode(0o640)).unwrap();
    render_to(&square, &kept).success();
    assert_eq!(mode(&kept), 0o640);
    assert!(fs::read(&kept).unwrap().starts_with(b"\x89PNG"));
}

/// One meaning per flag: `--derivation` (old name `--strategy`, `-s`) is
/// the derivation order on render; on an .od without `--growth` it warns
/// that it cannot change the tree (the picture is the default growth's);
/// on compile `--strategy` is still the growth order, with a warning
/// naming `--growth`.
#[test]
fn strategy_means_one_thing_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let od = format!("{ROOT}/examples/fig9.od");
    let png = |flags: &str, name: &str| {
        let out = dir.path().join(name);
        let line = format!("render {od} --size 120x120 -o {} {flags}", out.display());
        let (code, _, err) = outcome(&mut stlc_line(&line));
        assert_eq!(code, 0, "{err}");
        (std::fs::read(&out).unwrap(), err)
    };
    let (plain, quiet) = png("", "plain.png");
    assert!(quiet.is_empty(), "{quiet}");
    let (old, warned) = png("--strategy dfs", "old.png");
    let (new, warned_too) = png("--derivation dfs", "new.png");
    assert_eq!(old, plain, "the derivation order does not change the tree");
    assert_eq!(new, plain);
    for w in [&warned, &warned_too] {
        let both = w.contains("--derivation") && w.contains("--growth dfs");
        assert!(both, "{w}");
    }
    let (grown, with_growth) = png("--strategy dfs --growth dfs", "grown.png");
    assert_ne!(grown, plain, "--growth dfs grows another tree");
    assert!(with_growth.is_empty(), "{with_growth}");
    let (code, out, err) = outcome(&mut stlc_line(&format!("compile {od} --strategy dfs -o -")));
    assert_eq!(code, 0, "{err}");
    let golden = std::fs::read(manifest_path("tests/cases/grow/fig9.dfs.bed")).unwrap();
    let depth_first = "compile --strategy dfs still grows depth-first";
    assert_eq!(out, golden, "{depth_first}");
    assert!(err.contains("its name is --growth"), "{err}");
}

/// stlc runs under a 1 GB address-space limit (an address-space limit
/// counts the worker's stack reservation): `check` and `render` succeed.
#[test]
fn it_runs_under_a_one_gigabyte_address_space_limit() {
    let bin = assert_cmd::cargo::cargo_bin("stlc");
    let od = format!("{ROOT}/examples/2dtree.od");
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("t.png");
    let (bin, png_at) = (bin.display(), png.display());
    let script = format!(
        "ulimit -v 1000000 && '{bin}' check '{od}' >/dev/null && '{bin}' render '{od}' -o '{png_at}'"
    );
    let out = StdCommand::new("sh")
        .args(["-c", &script])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
}

/// Every setting in the file (stl-language.md section 10): `O=`, `V=` and
/// `M=` in an OD's header grow what `--growth`, `--seed` and `--max-stems`
/// grow, and the flags override the file for one run (a BED refusing them,
/// and wrong values, are cases in tests/cmd/growth.md).
#[test]
fn growth_settings_kept_in_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let fig9 = std::fs::read_to_string(manifest_path("examples/fig9.od")).unwrap();
    let with = |keys: &str, name: &str| {
        let header = "L=9(0) B=1.5(0) A=30 C=2";
        let text = fig9.replace(header, &format!("{header} {keys}"));
        assert_ne!(text, fig9, "the header line moved");
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    // (standard output, which must be a success; standard error).
    let compile = |file: &str, flags: &str| {
        let (code, out, err) = outcome(&mut stlc_line(&format!("compile {file} -o - {flags}")));
        assert_eq!(code, 0, "{err}");
        (out, err)
    };
    let bed = |file: &str, flags: &str| compile(file, flags).0;
    let golden =
        |order: &str| std::fs::read(format!("{ROOT}/tests/cases/grow/fig9.{order}.bed")).unwrap();
    let dfs = with("O=dfs", "dfs.od");
    assert_eq!(bed(&dfs, ""), golden("dfs"), "O=dfs grows depth-first");
    let overridden = bed(&dfs, "--growth bfs");
    assert_eq!(overridden, golden("bfs"), "--growth overrides O=");
    // V= and M= grow what --seed and --max-stems grow.
    let grove = std::fs::read_to_string(manifest_path("examples/grove.od")).unwrap();
    let keyed = dir.path().join("grove.od");
    std::fs::write(&keyed, grove.replace("A=25 C=1", "A=25 C=1 V=7 M=500")).unwrap();
    let keyed = keyed.display().to_string();
    let plain = format!("{ROOT}/examples/grove.od");
    assert_eq!(bed(&keyed, ""), bed(&plain, "--seed 7 --max-stems 500"));
    // The warning names the limit in force: M= (the file's design), or
    // --max-stems where it is the lower.
    let by_m = compile(&keyed, "").1;
    assert!(by_m.contains("would pass the file's M=500"), "{by_m}");
    assert!(!by_m.contains("--max-stems"), "{by_m}");
    let by_flag = compile(&keyed, "--max-stems 300").1;
    assert!(by_flag.contains("the stem limit of 300"), "{by_flag}");
    let raise = "raise the limit with --max-stems N";
    assert!(by_flag.contains(raise), "{by_flag}");
    // The flag overrides V= for one run.
    let by_flag = bed(&plain, "--seed 8 --max-stems 500");
    assert_eq!(bed(&keyed, "--seed 8"), by_flag);
    // A BED refusing them, and wrong values: tests/cmd/growth.md.
}

/// Standard input is compared with the output as a named input is (issue
/// 36, problem 8): `stlc compile - -o g.od < g.od`, and `-o /dev/stdin`
/// with standard input redirected from the file, are refused before any
/// work (exit 1), and the hand-written OD is left as it was. Standard
/// input from a pipe is no file: its output is written as before.
#[test]
fn standard_input_is_never_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let od = dir.path().join("g.od");
    let text = fs::read(manifest_path("examples/2dtree.od")).unwrap();
    fs::write(&od, &text).unwrap();
    for output in [od.to_str().unwrap(), "/dev/stdin"] {
        let out = StdCommand::new(assert_cmd::cargo::cargo_bin("stlc"))
            .args(["compile", "-", "--from", "od", "-o", output])
            .env("NO_COLOR", "1")
            .stdin(fs::File::open(&od).unwrap())
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "-o {output}: {err}");
        let refusing = err.contains("refusing to write over the input") && err.contains("<stdin>");
        assert!(refusing, "{err}");
        assert_eq!(fs::read(&od).unwrap(), text, "-o {output}");
    }
    // The same text through a pipe: written.
    let bed = dir.path().join("g.bed");
    stlc_piped(&format!("compile - --from od -o {}", bed.display()), text);
    assert!(fs::read_to_string(&bed).unwrap().contains("SEED"));
}
