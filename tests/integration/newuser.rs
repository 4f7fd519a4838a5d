//! What a new user tripped over (issue 10), each as the user met it, through
//! the real binary: one growth default, an honest `check`, no clobbered
//! input, interrupts, flags that do not apply, thick strokes.

use std::fs;
use std::path::Path;

use crate::support::{files_in, outcome, stlc, stlc_line};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn example(name: &str) -> String {
    format!("{ROOT}/examples/{name}")
}

/// Runs stlc with `args`, returning (exit code, stdout, stderr).
fn run(args: &[&str]) -> (i32, Vec<u8>, String) {
    outcome(stlc().args(args))
}

/// Runs `stlc LINE`, returning (exit code, stdout, stderr).
fn run_line(line: &str) -> (i32, Vec<u8>, String) {
    outcome(&mut stlc_line(line))
}

fn path(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

// ------------------------------------------------------ growth default --

/// `render tree.od` equals `render` of `compile tree.od`, byte for byte,
/// for the default growth order and for each one named; the same for
/// `expand`. Every example OD.
#[test]
fn rendering_or_expanding_an_od_equals_doing_it_to_its_compiled_bed() {
    let dir = tempfile::tempdir().unwrap();
    for od in [
        "2dtree.od",
        "fig9.od",
        "holes.od",
        "polygon.od",
        "decrement.od",
    ] {
        for growth in [None, Some("bfs"), Some("dfs")] {
            let bed = dir.path().join("t.bed");
            let od_path = example(od);
            let flags = growth.map(|g| format!("--growth {g}")).unwrap_or_default();
            let compile = format!("compile {od_path} {flags} -o {}", bed.display());
            assert_eq!(run_line(&compile).0, 0, "{od} {growth:?}");
            for (what, ext) in [("render", "png"), ("render", "svg"), ("expand", "txt")] {
                let a = dir.path().join(format!("a.{ext}"));
                let b = dir.path().join(format!("b.{ext}"));
                let from_od = format!("{what} {od_path} {flags} -o {}", a.display());
                assert_eq!(run_line(&from_od).0, 0, "{what} {od} {growth:?}");
                assert_eq!(run(&[what, path(&bed), "-o", path(&b)]).0, 0);
                let same = fs::read(&a).unwrap() == fs::read(&b).unwrap();
                assert!(same, "{what} {od} {growth:?}: the OD and its BED differ");
            }
        }
    }
}

/// The default growth order is bfs everywhere: `compile` without a flag
/// writes the bfs golden, and `--strategy` on `compile` still means the
/// growth order (scripts use it).
#[test]
fn the_default_growth_order_is_bfs_and_compile_keeps_strategy_as_its_alias() {
    let golden =
        |g: &str| fs::read_to_string(format!("{ROOT}/tests/cases/grow/fig9.{g}.bed")).unwrap();
    let fig9 = example("fig9.od");
    let (code, out, _) = run(&["compile", &fig9, "-o", "-"]);
    assert_eq!(code, 0);
    assert_eq!(String::from_utf8(out).unwrap(), golden("bfs"));
    for flag in ["--growth", "--strategy", "-s"] {
        let (code, out, err) = run(&["compile", &fig9, flag, "dfs", "-o", "-"]);
        assert_eq!(code, 0, "{flag}: {err}");
        assert_eq!(String::from_utf8(out).unwrap(), golden("dfs"), "{flag}");
    }
    // Both at once is a contradiction clap refuses.
    let (code, _, _) = run(&["compile", &fig9, "--growth", "dfs", "--strategy", "bfs"]);
    assert_eq!(code, 2);
}

// ---------------------------------------------------------------- check --

/// `check` says no (exit 1) exactly where `compile` does: unbounded growth,
/// a root outside the layout, a layout whose only polygon has no area.
#[test]
fn check_refuses_what_compile_refuses() {
    let dir = tempfile::tempdir().unwrap();
    let unbounded = "U\n(0, 0)\nL=10(0) B=1(0)\nRULE\nR1: [+F R2][-F R1]\nR2: [F R1]\n";
    let outside = "O\n(500, 500)\nRULE\nR1: [+F][-F]\nLAYOUT\n(clGreen) Rectangle (0,0), 100, 100\nENDLAYOUT\n";
    let collinear = "C\n(5, 5)\nRULE\nR1: [+F][-F]\nLAYOUT\n(clGreen) Polygon (0,0), (5,5), (10,10)\nENDLAYOUT\n";
    let cases = [
        ("unbounded.od", unbounded, "no bound"),
        ("outside.od", outside, "outside"),
        ("collinear.od", collinear, ""),
    ];
    for (name, text, needle) in cases {
        let p = dir.path().join(name);
        fs::write(&p, text).unwrap();
        let (compile_code, _, compile_err) = run(&["compile", path(&p), "-o", "-"]);
        let (check_code, out, check_err) = run(&["check", path(&p)]);
        assert_eq!(compile_code, 1, "{name}: {compile_err}");
        let said = String::from_utf8_lossy(&out);
        assert_eq!(check_code, 1, "{name}: check said {said}");
        assert!(check_err.contains(needle), "{name}: {check_err}");
        assert_eq!(check_err, compile_err, "{name}: the same diagnostic");
    }
}

/// `check` of an OD grows it and reports the stems compile would write;
/// of a BED, the stems from its measure, which equal the stems drawn.
#[test]
fn check_reports_the_stems_compile_grows_and_a_bed_draws() {
    let dir = tempfile::tempdir().unwrap();
    let bed = dir.path().join("t.bed");
    let od = example("2dtree.od");
    assert_eq!(run(&["compile", &od, "-o", path(&bed)]).0, 0);
    // The BED's stems, counted independently: every `F` of its expansion.
    let (_, word, _) = run(&["expand", path(&bed)]);
    let drawn = word.iter().filter(|&&b| b == b'F').count();
    let (code, out, _) = run(&["check", &od]);
    assert_eq!(code, 0);
    let out = String::from_utf8(out).unwrap();
    let grows = format!("grows       {drawn} stems (bfs)");
    assert!(out.contains(&grows), "{out}");
    let (_, out, _) = run(&["check", path(&bed)]);
    let out = String::from_utf8(out).unwrap();
    assert!(out.contains(&format!("stems       {drawn}\n")), "{out}");
}

// ------------------------------------------------------ clobbered input --

/// An output that is the input file is refused before any work (exit 1),
/// naming both, and the input is left as it was: the same path, another
/// spelling of it, and a symbolic link to it.
#[test]
fn the_input_is_never_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    let od = dir.path().join("g.od");
    let text = fs::read(example("2dtree.od")).unwrap();
    fs::write(&od, &text).unwrap();
    let bed = dir.path().join("h.bed");
    assert_eq!(run(&["compile", path(&od), "-o", path(&bed)]).0, 0);
    let bed_text = fs::read(&bed).unwrap();
    let link = dir.path().join("link.od");
    std::os::unix::fs::symlink(&od, &link).unwrap();
    let dotted = format!("{}/./g.od", path(dir.path()));
    for args in [
        vec!["compile", path(&od), "-o", path(&od)],
        vec!["compile", path(&od), "-o", &dotted],
        vec!["compile", path(&od), "-o", path(&link)],
        vec!["expand", path(&od), "-o", path(&od)],
    ] {
        let (code, _, err) = run(&args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(err.contains("refusing to write over the input"), "{err}");
        assert_eq!(fs::read(&od).unwrap(), text, "{args:?}");
    }
    let (code, _, err) = run(&["render", path(&bed), "-o", path(&bed), "-f", "png"]);
    // `h.bed` is no image name: that alone is refused first, as a usage error.
    assert_eq!(code, 2, "{err}");
    let same = dir.path().join("same");
    fs::copy(&bed, &same).unwrap();
    let (code, _, err) = run(&["render", path(&same), "--from", "bed", "-o", path(&same)]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("is the same file as"), "{err}");
    assert_eq!(fs::read(&same).unwrap(), bed_text);
}

// ---------------------------------------------------------- interrupts --

/// SIGTERM and SIGINT during a long render: exit 143 and 130, the old
/// output untouched, no temporary file left.
#[test]
fn an_interrupt_removes_the_temporary_file_and_keeps_the_target() {
    use std::process::{Command as Std, Stdio};
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.png");
    let bin = assert_cmd::cargo::cargo_bin("stlc");
    for (signal, code) in [("-TERM", 143), ("-INT", 130)] {
        fs::write(&out, b"old").unwrap();
        // A render long enough to be interrupted: depth 11 takes seconds.
        let mut child = Std::new(&bin)
            .args(["render", &example("abop-1.24a.lsys"), "--depth", "11", "-o"])
            .arg(&out)
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        // Wait until the temporary file exists: the work is under way.
        let mut waited = 0;
        while fs::read_dir(dir.path()).unwrap().count() < 2 && waited < 2_000 {
            std::thread::sleep(std::time::Duration::from_millis(5));
            waited += 1;
        }
        let killed = Std::new("kill")
            .args([signal, &child.id().to_string()])
            .status();
        assert!(killed.unwrap().success());
        let status = child.wait().unwrap();
        assert_eq!(status.code(), Some(code), "{signal}");
        assert_eq!(fs::read(&out).unwrap(), b"old");
        let left = "a file was left behind";
        assert_eq!(files_in(dir.path()), ["t.png"], "{signal}: {left}");
    }
}

/// An output in a directory that does not exist: the message names the
/// user's path, never the temporary one.
#[test]
fn errors_name_the_users_path_not_the_temporary_one() {
    let koch = example("koch-snowflake.lsys");
    let (code, _, err) = run_line(&format!("render {koch} -o /nonexistent/dir/x.png"));
    assert_eq!(code, 1);
    assert!(err.contains("`/nonexistent/dir/x.png`"), "{err}");
    assert!(!err.contains(".stlc-") && !err.contains(".tmp"), "{err}");
}

// --------------------------------------------------------------- flags --

/// Flags that contradict each other are usage errors (exit 2) before any
/// work; flags that do nothing for this input are warnings (exit 0).
#[test]
fn no_flag_is_ignored_without_a_word() {
    let dir = tempfile::tempdir().unwrap();
    let o = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    let od = example("2dtree.od");
    let koch = example("koch-snowflake.lsys");
    let decrement = example("decrement.od");
    let (png, svg, jpg) = (o("x.png"), o("x.svg"), o("x.jpg"));
    let jpg_refused = "`.jpg` is not an image format";
    for (line, needle) in [
        (format!("render {od} -f svg -o {png}"), "contradicts"),
        (format!("render {od} -f png -o {svg}"), "contradicts"),
        (format!("render {od} -o {jpg}"), jpg_refused),
    ] {
        let (code, _, err) = run_line(&line);
        assert_eq!(code, 2, "{line}: {err}");
        assert!(err.contains(needle), "{err}");
        assert!(!dir.path().join("x.png").exists());
    }
    // `render -` without -o: a usage error too.
    let text = fs::read(&koch).unwrap();
    let (code, _, _) = outcome(stlc().args(["render", "-"]).write_stdin(text));
    assert_eq!(code, 2);
    let (a, b, c, d, e) = (o("a.png"), o("b.png"), o("c.png"), o("d.png"), o("e.txt"));
    let layout = "--show-layout";
    for (line, flag) in [
        (format!("render {od} --depth 3 -o {a}"), "--depth"),
        (format!("render {koch} {layout} -o {b}"), layout),
        (format!("render {decrement} {layout} -o {c}"), layout),
        (format!("render {koch} --growth dfs -o {d}"), "--growth"),
        (format!("expand {koch} --clearance 1 -o {e}"), "--clearance"),
        (format!("check {koch} --max-stems 5"), "--max-stems"),
    ] {
        let (code, _, err) = run_line(&line);
        assert_eq!(code, 0, "{line}: {err}");
        let ignored = format!("{flag} was ignored");
        assert!(err.contains(&ignored), "{line}: {err}");
    }
    // --quiet silences the warnings.
    let (code, _, err) = run(&["render", &od, "--depth", "3", "-q", "-o", &o("f.png")]);
    assert_eq!((code, err.as_str()), (0, ""));
}

/// `L` and `R` in an `.lsys` without rules of their own turn nothing: a
/// rule copied from the STL paper gets a warning pointing at it; the
/// Hilbert curve, whose `L` and `R` have rules, gets none. A derivation
/// that draws nothing writes its (blank) picture with a warning.
#[test]
fn inert_turns_and_empty_pictures_are_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let lr = dir.path().join("lr.lsys");
    let text = "axiom F\nrule F F[RF]F[LF]F\nangle 30\ngenerations 2\n";
    fs::write(&lr, text).unwrap();
    let png = dir.path().join("lr.png");
    let (code, _, err) = run(&["render", path(&lr), "-o", path(&png)]);
    assert_eq!(code, 0);
    assert!(err.contains("`L` does not turn in an .lsys file"), "{err}");
    assert!(err.contains("`R` does not turn in an .lsys file"), "{err}");
    assert!(err.contains("lr.lsys:2:"), "points at the rule: {err}");
    let (code, _, err) = run(&["render", &example("hilbert.lsys"), "-o", path(&png)]);
    assert_eq!((code, err.as_str()), (0, ""));
    let empty = dir.path().join("empty.lsys");
    fs::write(&empty, "axiom X\nangle 30\ngenerations 3\n").unwrap();
    let (code, _, err) = run(&["render", path(&empty), "-o", path(&png)]);
    assert_eq!(code, 0);
    assert!(err.contains("the picture is empty"), "{err}");
    assert!(png.exists());
}

// ------------------------------------------------------- thick strokes --

/// 50,000 copies of one thick stem draw the picture one copy draws, byte
/// for byte (a path unions its strokes; repeats are drawn once).
#[test]
fn many_copies_of_a_thick_stem_draw_what_one_draws() {
    let dir = tempfile::tempdir().unwrap();
    let bed = |n: usize| {
        let seed = "R1{,}\n".repeat(n);
        format!("T\n(100, 100)\nL=10(0) B=3(0)\nRULE\nR1: [+F][-F]\nSEED\n{seed}ENDSEED\n")
    };
    let (one, many) = (dir.path().join("one.bed"), dir.path().join("many.bed"));
    fs::write(&one, bed(1)).unwrap();
    fs::write(&many, bed(50_000)).unwrap();
    let (a, b) = (dir.path().join("one.png"), dir.path().join("many.png"));
    assert_eq!(run(&["render", path(&one), "-o", path(&a)]).0, 0);
    assert_eq!(run(&["render", path(&many), "-o", path(&b)]).0, 0);
    assert!(fs::read(&a).unwrap() == fs::read(&b).unwrap());
}

// ------------------------------------------------------ header colours --

/// `S=` and `G=` in the header give the tree's stroke and background; the
/// BED keeps them as written; `--stroke` and `--background` override them.
#[test]
fn a_description_can_store_its_stroke_and_background() {
    let dir = tempfile::tempdir().unwrap();
    let od = dir.path().join("c.od");
    let text = "C\n(0, 0)\nL=10(0) B=2(0) S=clMaroon G=#ffffe0\nRULE\nR1: [+F][-F]\nSEED\nF [I 3 R1]\nENDSEED\n";
    fs::write(&od, text).unwrap();
    let (code, bed, _) = run(&["compile", path(&od), "-o", "-"]);
    assert_eq!(code, 0);
    let bed = String::from_utf8(bed).unwrap();
    let header = "L=10(0) B=2(0) C=1 S=clMaroon G=#ffffe0\n";
    assert!(bed.contains(header), "{bed}");
    let svg = |extra: &str| {
        let line = format!("render {} -f svg -o - {extra}", od.display());
        String::from_utf8(run_line(&line).1).unwrap()
    };
    let own = svg("");
    assert!(own.contains("fill=\"#ffffe0\""), "{own}");
    assert!(own.contains("stroke=\"#800000\""), "clMaroon: {own}");
    let over = svg("--stroke #123456 --background none");
    let stroke = over.contains("stroke=\"#123456\"");
    assert!(stroke && !over.contains("<rect"), "{over}");
    // A number where a colour goes, and the other way round, are errors
    // at the value.
    let bad = dir.path().join("bad.od");
    fs::write(&bad, "C\n(0, 0)\nL=clRed S=12\nRULE\nR1: [+F][-F]\n").unwrap();
    let (code, _, err) = run(&["check", "--color", "never", path(&bad)]);
    assert_eq!(code, 1);
    let number = err.contains("`L` takes a number");
    assert!(number && err.contains("`S` takes a colour"), "{err}");
}

/// `--seed` where nothing chooses (a BED, a deterministic L-system, an OD
/// without alternatives) is a warning that says why every seed gives the
/// same tree; where something chooses, there is none.
#[test]
fn a_seed_that_changes_nothing_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| path(&dir.path().join(name)).to_string();
    let bed = format!("{ROOT}/tests/cases/grow/alternatives.dfs.bed");
    let koch = example("koch-snowflake.lsys");
    let tree = example("2dtree.od");
    let (a, b) = (out("a.png"), out("b.bed"));
    let no_alternatives = "this description has no alternatives";
    let bed_reason = "a .bed has its choices written out";
    let lsys_reason = "this L-system has no stochastic rules";
    for (line, reason) in [
        (format!("render {bed} --seed 3 -o {a}"), bed_reason),
        (format!("stats {koch} --seed 3"), lsys_reason),
        (format!("compile {tree} --seed 3 -o {b}"), no_alternatives),
        (format!("check {tree} --seed 3"), no_alternatives),
    ] {
        let (code, _, err) = run_line(&line);
        assert_eq!(code, 0, "{line}: {err}");
        let ignored = err.contains("--seed was ignored");
        assert!(ignored && err.contains(reason), "{line}: {err}");
    }
    let plant = example("abop-1.27.lsys");
    let grove = example("grove.od");
    for line in [
        format!("render {plant} --seed 3 -o {}", out("c.png")),
        format!("stats {plant} --seed 3"),
        format!("compile {grove} --seed 3 -o {}", out("d.bed")),
    ] {
        let (code, _, err) = run_line(&line);
        assert_eq!((code, err.as_str()), (0, ""), "{line}");
    }
}
