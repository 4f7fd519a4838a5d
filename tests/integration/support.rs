//! Golden files, compared one way everywhere: text with a line diff on
//! failure, PNG within 1 per channel.
//!
//! Goldens live under `tests/cases/`. After an intended change, run
//! `STLC_BLESS=1 cargo test --test integration` to rewrite the goldens that
//! differ, then read `git diff tests/cases` before committing. Blessing is
//! refused where the `CI` variable is set: CI compares, it never writes.
//! A mismatch leaves the live output (and, for an image, a picture of the
//! differences) under `tests/store/` (git-ignored), at the golden's path
//! below `tests/cases/` with `.live` (or `.diff`) before the extension.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use tiny_skia::Pixmap;

/// `rel` below the crate's root.
pub fn manifest_path(rel: impl AsRef<Path>) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
}

/// Whether goldens are being rewritten (`STLC_BLESS=1`). Panics when `CI`
/// is set too, so a CI run can never pass by accepting its own output.
pub fn blessing() -> bool {
    let bless = std::env::var_os("STLC_BLESS").is_some_and(|v| v == "1");
    assert!(
        !(bless && std::env::var_os("CI").is_some()),
        "STLC_BLESS=1 is refused where CI is set: CI compares goldens, it never writes them"
    );
    bless
}

/// Compares `actual` with the text golden at `golden` (relative to the
/// crate's root, or absolute). With `STLC_BLESS=1` the golden is rewritten
/// when it differs instead. On a mismatch, fails with a line diff and
/// writes `actual` under `tests/store/`.
pub fn assert_golden(golden: impl AsRef<Path>, actual: &str) {
    let golden = manifest_path(golden);
    if blessing() {
        if fs::read(&golden).ok().as_deref() != Some(actual.as_bytes()) {
            write_atomically(&golden, actual.as_bytes());
        }
        return;
    }
    let expected = match fs::read_to_string(&golden) {
        Ok(text) => text,
        Err(e) => panic!(
            "cannot read the golden {}: {e} (STLC_BLESS=1 writes it)",
            golden.display()
        ),
    };
    if expected != actual {
        let live = store_path(&golden, "live");
        fs::create_dir_all(live.parent().unwrap()).unwrap();
        fs::write(&live, actual).unwrap();
        panic!(
            "{}\nlive output in {} (STLC_BLESS=1 to accept, then read git diff)",
            text_diff(&golden.display().to_string(), &expected, actual),
            live.display()
        );
    }
}

/// Fails with a line diff of `expected` and `actual` unless they are equal;
/// `what` names the text in the message.
pub fn assert_same_text(what: &str, expected: &str, actual: &str) {
    if expected != actual {
        panic!("{}", text_diff(what, expected, actual));
    }
}

/// Compares `live` with the PNG golden at `golden` (relative to the crate's
/// root, or absolute): same size, and every channel of every pixel
/// (demultiplied RGBA) within 1. With `STLC_BLESS=1` the golden is
/// rewritten when it is off instead. On a mismatch, writes the live image
/// and, when the sizes agree, a difference image (pixels off by more than 1
/// in red over a faded reference) under `tests/store/`.
pub fn assert_golden_png(golden: impl AsRef<Path>, live: &Pixmap) {
    let golden = manifest_path(golden);
    let reference = Pixmap::load_png(&golden);
    if blessing() {
        if !reference.is_ok_and(|r| png_difference(&r, live).is_none()) {
            let bytes = live.encode_png().expect("encode the live image");
            write_atomically(&golden, &bytes);
        }
        return;
    }
    let reference = match reference {
        Ok(r) => r,
        Err(e) => panic!(
            "cannot read the golden {}: {e} (STLC_BLESS=1 writes it)",
            golden.display()
        ),
    };
    let Some(problem) = png_difference(&reference, live) else {
        return;
    };
    let live_path = store_path(&golden, "live");
    fs::create_dir_all(live_path.parent().unwrap()).unwrap();
    live.save_png(&live_path).unwrap();
    let mut stored = live_path.display().to_string();
    if let Some(diff) = diff_image(&reference, live) {
        let diff_path = store_path(&golden, "diff");
        diff.save_png(&diff_path).unwrap();
        write!(stored, " and {}", diff_path.display()).unwrap();
    }
    panic!(
        "{}: {problem}; live output in {stored} (STLC_BLESS=1 to accept)",
        golden.display()
    );
}

/// Demultiplied RGBA of the pixel at `(x, y)`.
fn rgba(p: &Pixmap, x: u32, y: u32) -> [u8; 4] {
    let c = p.pixel(x, y).unwrap().demultiply();
    [c.red(), c.green(), c.blue(), c.alpha()]
}

/// Whether two pixels differ by more than 1 in some channel.
fn off(a: [u8; 4], b: [u8; 4]) -> bool {
    a.iter().zip(b).any(|(a, b)| a.abs_diff(b) > 1)
}

/// What is wrong with `live` against `reference`, or `None` when it
/// matches within the tolerance.
fn png_difference(reference: &Pixmap, live: &Pixmap) -> Option<String> {
    let (w, h) = (reference.width(), reference.height());
    if (w, h) != (live.width(), live.height()) {
        return Some(format!(
            "size {}x{}, golden {w}x{h}",
            live.width(),
            live.height()
        ));
    }
    let mut count = 0u64;
    let mut first = None;
    for y in 0..h {
        for x in 0..w {
            let (a, b) = (rgba(reference, x, y), rgba(live, x, y));
            if off(a, b) {
                count += 1;
                first.get_or_insert((x, y, a, b));
            }
        }
    }
    let (x, y, a, b) = first?;
    Some(format!(
        "{count} pixels differ by more than 1 in a channel; the first at ({x}, {y}): \
         golden RGBA {a:?}, live {b:?}"
    ))
}

/// Red where the images differ by more than 1, the reference faded to
/// light grey elsewhere; `None` when the sizes differ.
fn diff_image(reference: &Pixmap, live: &Pixmap) -> Option<Pixmap> {
    let (w, h) = (reference.width(), reference.height());
    if (w, h) != (live.width(), live.height()) {
        return None;
    }
    let mut diff = Pixmap::new(w, h)?;
    for y in 0..h {
        for x in 0..w {
            let (a, b) = (rgba(reference, x, y), rgba(live, x, y));
            let colour = if off(a, b) {
                tiny_skia::ColorU8::from_rgba(255, 0, 0, 255)
            } else {
                // Luma of the reference over white, faded to a quarter.
                let luma = (u32::from(a[0]) * 3 + u32::from(a[1]) * 6 + u32::from(a[2])) / 10;
                let over_white = (luma * u32::from(a[3]) + 255 * (255 - u32::from(a[3]))) / 255;
                let grey = (192 + over_white / 4) as u8;
                tiny_skia::ColorU8::from_rgba(grey, grey, grey, 255)
            };
            let i = (y * w + x) as usize;
            diff.pixels_mut()[i] = colour.premultiply();
        }
    }
    Some(diff)
}

/// Where a mismatch's `tag` file ("live", "diff") for `golden` goes: its
/// path below `tests/cases/` (or its file name) under `tests/store/`, with
/// `.tag` before the extension.
fn store_path(golden: &Path, tag: &str) -> PathBuf {
    let cases = manifest_path("tests/cases");
    let rel = golden
        .strip_prefix(&cases)
        .map(Path::to_path_buf)
        .unwrap_or_else(|_| PathBuf::from(golden.file_name().unwrap()));
    let stem = rel.file_stem().unwrap().to_string_lossy();
    let name = match rel.extension() {
        Some(ext) => format!("{stem}.{tag}.{}", ext.to_string_lossy()),
        None => format!("{stem}.{tag}"),
    };
    manifest_path("tests/store").join(rel.with_file_name(name))
}

/// Replaces `path` with `bytes` by renaming a finished file over it, so a
/// test reading the golden while another blesses it never sees half a file.
fn write_atomically(path: &Path, bytes: &[u8]) {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let tmp = path.with_file_name(format!(
        ".{}.bless-{}-{}",
        path.file_name().unwrap().to_string_lossy(),
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    fs::write(&tmp, bytes).unwrap_or_else(|e| panic!("writing {}: {e}", tmp.display()));
    fs::rename(&tmp, path).unwrap_or_else(|e| panic!("renaming onto {}: {e}", path.display()));
}

/// Lines shown on each side of a diff before the rest is counted instead.
const MAX_DIFF_LINES: usize = 20;
/// Characters of a long line shown around its first difference.
const LINE_WINDOW: usize = 160;

/// A readable account of how `actual` differs from `expected`: the changed
/// block between their common first and last lines, as `-` (golden) and
/// `+` (now) lines with two lines of context, and for a changed line the
/// column where it first differs.
fn text_diff(what: &str, expected: &str, actual: &str) -> String {
    // Lines keep their endings, so a missing final newline or a `\r` is a
    // difference the diff shows rather than two equal-looking texts.
    let e: Vec<&str> = expected.split_inclusive('\n').collect();
    let a: Vec<&str> = actual.split_inclusive('\n').collect();
    let prefix = e.iter().zip(&a).take_while(|(x, y)| x == y).count();
    let suffix = e[prefix..]
        .iter()
        .rev()
        .zip(a[prefix..].iter().rev())
        .take_while(|(x, y)| x == y)
        .count();
    let (old, new) = (&e[prefix..e.len() - suffix], &a[prefix..a.len() - suffix]);
    let mut out = format!(
        "{what}: differs from the golden at line {} (golden {} lines, now {})\n",
        prefix + 1,
        e.len(),
        a.len()
    );
    let col = match (old.first(), new.first()) {
        (Some(x), Some(y)) => {
            let c = x.chars().zip(y.chars()).take_while(|(p, q)| p == q).count();
            writeln!(out, "first difference at column {}", c + 1).unwrap();
            c
        }
        _ => 0,
    };
    for line in &e[prefix.saturating_sub(2)..prefix] {
        writeln!(out, "  {}", shown(line, col)).unwrap();
    }
    for (sign, lines) in [('-', old), ('+', new)] {
        for line in lines.iter().take(MAX_DIFF_LINES) {
            writeln!(out, "{sign} {}", shown(line, col)).unwrap();
        }
        if lines.len() > MAX_DIFF_LINES {
            writeln!(
                out,
                "{sign} ... {} more lines",
                lines.len() - MAX_DIFF_LINES
            )
            .unwrap();
        }
    }
    for line in e[e.len() - suffix..].iter().take(2) {
        writeln!(out, "  {}", shown(line, col)).unwrap();
    }
    out
}

/// One line for a diff: without its `\n`, escaped if it holds other
/// control characters (or lacks the `\n`), and cut to a window around
/// column `col` when long.
fn shown(line: &str, col: usize) -> String {
    let body = line.strip_suffix('\n');
    let text = body.unwrap_or(line);
    let chars: Vec<char> = text.chars().collect();
    let cut = if chars.len() > LINE_WINDOW {
        let start = col
            .saturating_sub(LINE_WINDOW / 2)
            .min(chars.len() - LINE_WINDOW);
        let end = start + LINE_WINDOW;
        format!(
            "{}{}{}",
            if start > 0 { "…" } else { "" },
            chars[start..end].iter().collect::<String>(),
            if end < chars.len() { "…" } else { "" }
        )
    } else {
        text.to_string()
    };
    if body.is_none() || cut.chars().any(char::is_control) {
        format!(
            "{cut:?}{}",
            if body.is_none() { " (no newline)" } else { "" }
        )
    } else {
        cut
    }
}

#[test]
fn a_text_diff_shows_the_changed_lines_with_context_and_column() {
    let golden = "a\nb\nc\nd\ne\n";
    let now = "a\nb\nC\nd\ne\n";
    assert_eq!(
        text_diff("g", golden, now),
        "g: differs from the golden at line 3 (golden 5 lines, now 5)\n\
         first difference at column 1\n  a\n  b\n- c\n+ C\n  d\n  e\n"
    );
    // An inserted line, and a missing final newline.
    assert_eq!(
        text_diff("g", "a\nb\n", "a\nx\nb\n"),
        "g: differs from the golden at line 2 (golden 2 lines, now 3)\n  a\n+ x\n  b\n"
    );
    assert_eq!(
        text_diff("g", "a\nb\n", "a\nb"),
        "g: differs from the golden at line 2 (golden 2 lines, now 2)\n\
         first difference at column 2\n  a\n- b\n+ \"b\" (no newline)\n"
    );
}

#[test]
fn a_long_line_is_shown_around_its_first_difference() {
    let golden = format!("{}X{}\n", "a".repeat(500), "b".repeat(500));
    let now = format!("{}Y{}\n", "a".repeat(500), "b".repeat(500));
    let diff = text_diff("g", &golden, &now);
    assert!(diff.contains("first difference at column 501"), "{diff}");
    let minus = diff.lines().find(|l| l.starts_with("- ")).unwrap();
    assert_eq!(minus, format!("- …{}X{}…", "a".repeat(80), "b".repeat(79)));
}

#[test]
fn store_paths_mirror_the_golden_below_tests_cases() {
    assert_eq!(
        store_path(&manifest_path("tests/cases/grow/fig9.bfs.bed"), "live"),
        manifest_path("tests/store/grow/fig9.bfs.live.bed")
    );
    assert_eq!(
        store_path(&manifest_path("tests/cases/render/tree.png"), "diff"),
        manifest_path("tests/store/render/tree.diff.png")
    );
}

#[test]
fn an_image_off_by_one_matches_and_off_by_two_does_not() {
    let mut reference = Pixmap::new(3, 2).unwrap();
    reference.fill(tiny_skia::Color::from_rgba8(100, 100, 100, 255));
    let mut live = reference.clone();
    live.pixels_mut()[4] = tiny_skia::ColorU8::from_rgba(101, 99, 100, 255).premultiply();
    assert_eq!(png_difference(&reference, &live), None);
    live.pixels_mut()[4] = tiny_skia::ColorU8::from_rgba(102, 100, 100, 255).premultiply();
    assert_eq!(
        png_difference(&reference, &live).unwrap(),
        "1 pixels differ by more than 1 in a channel; the first at (1, 1): \
         golden RGBA [100, 100, 100, 255], live [102, 100, 100, 255]"
    );
    let diff = diff_image(&reference, &live).unwrap();
    assert_eq!(rgba(&diff, 1, 1), [255, 0, 0, 255]);
    // Grey 100 over nothing: 192 + 100 / 4.
    assert_eq!(rgba(&diff, 0, 0), [217, 217, 217, 255]);
    assert!(png_difference(&reference, &Pixmap::new(2, 3).unwrap()).is_some());
}

/// The `stlc` binary as a user runs it, without colours (`NO_COLOR`), so
/// its messages compare as plain text.
pub fn stlc() -> assert_cmd::Command {
    let mut c = assert_cmd::Command::cargo_bin("stlc").expect("binary");
    c.env("NO_COLOR", "1");
    c
}

/// What the `stlc` binary writes to standard output for `args`; its
/// standard error in the panic if it fails.
pub fn stlc_stdout(args: &[&str]) -> Vec<u8> {
    let (code, out, err) = outcome(stlc().args(args));
    assert_eq!(code, 0, "stlc {args:?}: {err}");
    out
}

/// `stlc` with the words of `line` as its arguments. The paths written
/// into a line are the crate's and temporary directories', and the words
/// are flags and values: none holds white space (asserted, so a checkout
/// under a path with a space fails here, not somewhere stranger).
pub fn stlc_line(line: &str) -> assert_cmd::Command {
    let mut c = stlc();
    for word in line.split_whitespace() {
        c.arg(word);
    }
    assert!(
        !manifest_path("").display().to_string().contains(' '),
        "stlc_line splits at spaces and the crate's path holds one"
    );
    c
}

/// What `stlc line` writes to standard output given `stdin`; it must
/// succeed (its standard error in the panic otherwise).
pub fn stlc_piped(line: &str, stdin: impl Into<Vec<u8>>) -> Vec<u8> {
    let out = stlc_line(line).write_stdin(stdin).output().unwrap();
    assert!(
        out.status.success(),
        "stlc {line}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// `cmd` run: its exit code (-1 for a signal), standard output and
/// standard error as text.
pub fn outcome(cmd: &mut assert_cmd::Command) -> (i32, Vec<u8>, String) {
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    (out.status.code().unwrap_or(-1), out.stdout, err)
}

/// The numbers of a JSON array (`bbox`, `end`, a view box).
pub fn numbers(v: &serde_json::Value) -> Vec<f64> {
    let all = v.as_array().unwrap_or_else(|| panic!("not an array: {v}"));
    all.iter().map(|x| x.as_f64().unwrap()).collect()
}

/// The PNG file at `path`, decoded.
pub fn png_at(path: impl AsRef<Path>) -> Pixmap {
    Pixmap::decode_png(&fs::read(path).unwrap()).unwrap()
}

/// `n` with its digits grouped by threes, as the editor shows counts
/// (`30,001`).
pub fn grouped(n: u64) -> String {
    let d = n.to_string();
    let mut out = String::new();
    for (i, ch) in d.chars().enumerate() {
        if i > 0 && (d.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

/// `text` read as an Outline Description with the default limits; its
/// diagnostics and the text on failure.
pub fn od(text: &str) -> stlc::model::Description {
    stlc::syntax::stl::parse(text, stlc::model::Format::Od, &stlc::Limits::default())
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The default growth options in the order `growth`.
pub fn opts(growth: stlc::grow::GrowthOrder) -> stlc::grow::GrowOptions {
    stlc::grow::GrowOptions {
        growth,
        ..stlc::grow::GrowOptions::default()
    }
}

/// Calls `each(i, j)`, `i < j`, for the pairs of spans `(lo, hi)` (one
/// axis of each item's box) that come within `reach` of each other: sweep
/// and prune, in no particular order. Items farther apart than `reach` on
/// one axis are farther apart than `reach`, so a pairwise distance check
/// needs only these; the brute-force checks of growth stay exact at a
/// fraction of all pairs.
pub fn near_pairs(spans: &[(f64, f64)], reach: f64, mut each: impl FnMut(usize, usize)) {
    let mut by_lo: Vec<usize> = (0..spans.len()).collect();
    by_lo.sort_by(|&a, &b| spans[a].0.total_cmp(&spans[b].0));
    for (k, &a) in by_lo.iter().enumerate() {
        let end = spans[a].1 + reach;
        for &b in &by_lo[k + 1..] {
            if spans[b].0 > end {
                break;
            }
            each(a.min(b), a.max(b));
        }
    }
}

/// [`near_pairs`] finds exactly the pairs of all pairs whose spans come
/// within the reach, on random spans (a fixed linear congruential stream).
#[test]
fn near_pairs_are_the_brute_force_pairs_within_reach() {
    let mut x: u64 = 12345;
    let mut next = || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let spans: Vec<(f64, f64)> = (0..300)
        .map(|_| {
            let lo = next() * 100.0;
            (lo, lo + next() * 3.0)
        })
        .collect();
    for reach in [0.0, 0.5, 2.0] {
        let mut brute = Vec::new();
        for i in 0..spans.len() {
            for j in i + 1..spans.len() {
                let gap = (spans[j].0 - spans[i].1).max(spans[i].0 - spans[j].1);
                if gap <= reach {
                    brute.push((i, j));
                }
            }
        }
        assert!(brute.len() > 100 && brute.len() < 20_000, "{}", brute.len());
        let mut found = Vec::new();
        near_pairs(&spans, reach, |i, j| found.push((i, j)));
        found.sort_unstable();
        assert_eq!(found, brute, "reach {reach}");
    }
}

/// Whether npm's Khronos glTF validator is installed (`npm ci`). Without it
/// a test fails under CI and is skipped, saying so, elsewhere: `false` then.
pub fn gltf_validator_present() -> bool {
    if manifest_path("node_modules/gltf-validator").is_dir() {
        return true;
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "node_modules/gltf-validator is missing: run `npm ci`"
    );
    eprintln!("skipped: node_modules/gltf-validator is missing (run `npm ci`)");
    false
}

/// What `tests/js/gltf-validate.mjs` says of `files`, a line a file; it
/// must succeed (its output in the panic otherwise).
pub fn gltf_validate(files: &[PathBuf]) -> String {
    let root = manifest_path("");
    let run = std::process::Command::new("node")
        .arg(root.join("tests/js/gltf-validate.mjs"))
        .args(files)
        .current_dir(&root)
        .output()
        .expect("node runs");
    let said = String::from_utf8_lossy(&run.stdout).into_owned();
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{said}{err}");
    said
}

/// The names of the entries of `dir`, sorted.
pub fn files_in(dir: impl AsRef<Path>) -> Vec<String> {
    let entries = fs::read_dir(dir).unwrap();
    let mut names: Vec<String> = entries
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The kind of a limit error, written out field by field: `bound` with
/// `value` (as the message writes it) over `limit`, `what` measured where
/// the bound's own words are not precise enough.
pub fn limit_kind(
    bound: stlc::Bound,
    what: Option<&str>,
    value: &str,
    limit: u64,
) -> stlc::ErrorKind {
    let (what, value) = (what.map(str::to_string), value.to_string());
    stlc::ErrorKind::Limit {
        bound,
        what,
        value,
        limit,
    }
}

/// The default limits with `set` applied (`limits_with(|l| l.max_word = 100)`).
pub fn limits_with(set: impl FnOnce(&mut stlc::Limits)) -> stlc::Limits {
    let mut limits = stlc::Limits::default();
    set(&mut limits);
    limits
}

/// A layout volume: a sphere.
pub fn sphere(centre: [f64; 3], r: f64) -> stlc::model::Solid {
    stlc::model::Solid::Sphere { centre, r }
}

/// A layout volume: a box from `corner`, `size` along each axis.
pub fn cuboid(corner: [f64; 3], size: [f64; 3]) -> stlc::model::Solid {
    stlc::model::Solid::Box { corner, size }
}

/// A layout volume: a vertical cylinder standing on `base`.
pub fn cylinder(base: [f64; 3], r: f64, h: f64) -> stlc::model::Solid {
    stlc::model::Solid::Cylinder { base, r, h }
}

/// A layout volume: an ellipsoid.
pub fn ellipsoid(centre: [f64; 3], radii: [f64; 3]) -> stlc::model::Solid {
    stlc::model::Solid::Ellipsoid { centre, radii }
}

/// The text of `examples/name`.
pub fn example_text(name: &str) -> String {
    fs::read_to_string(manifest_path("examples").join(name)).unwrap()
}

/// The distance from `p` to the segment `a`-`b` (to `a` when they
/// coincide).
pub fn segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((p.0 - a.0 - t * dx).powi(2) + (p.1 - a.1 - t * dy).powi(2)).sqrt()
}

/// The files of the crate's folder `dir` whose names end in `.ext`,
/// sorted.
pub fn files_with(dir: &str, ext: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = fs::read_dir(manifest_path(dir))
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    files.sort();
    files
}
