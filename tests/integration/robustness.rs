//! Hostile input at the library level: deep nesting, huge counts, numbers
//! that are not numbers, degenerate shapes, huge and binary inputs, and the
//! regressions found by fuzzing (`fuzz/`, `docs/fuzzing.md`).
//!
//! Every case must end in a clean [`Diagnostics`] with the right
//! [`ErrorKind`] (or the right drawing). No test here measures time: where
//! work could run away, a test asserts how much was done (segments drawn,
//! symbols announced to the progress sink, an exact count no walk could
//! reach) or that the refusal came before any of it. Parsing runs on a
//! thread with an ordinary 2 MiB stack: the CLI's big worker stack is not
//! what keeps these from overflowing.

use crate::stl::bed;
use crate::support::{limits_with, od};
use stlc::bed::validate;
use stlc::bed::write::write;
use stlc::diag::BedError::OrderTooDeep;
use stlc::diag::Diagnostics;
use stlc::diag::ErrorKind::{self, Bed, Grow, Input, Layout, Lsys, Stl};
use stlc::diag::GrowError::RootOutside;
use stlc::diag::InputError::{
    InputTooLarge, NestingTooDeep, NotFinite, NotUtf8, Syntax, Unbalanced,
};
use stlc::diag::LayoutError::{EmptyRegion, ShapeSizeNotPositive, TooFewPoints};
use stlc::diag::LsysError::{MalformedNumber, MissingKey, NotPositive, NumberTooLarge, UnknownKey};
use stlc::diag::StlError::{NegativeDecrement, StemSizeNotPositive};
use stlc::interpret::Derivation::{self, Bfs, Dfs};
use stlc::limits::Limits;
use stlc::model::{Description, Format, Shape};
use stlc::progress::{NoProgress, Progress};
use stlc::syntax::{lsys, precheck, stl};
use stlc::turtle::{Bounds, Counter, Recorder, Turtle};

/// Asserts that the first error of the diagnostics `$e` matches `$kind`.
macro_rules! assert_first {
    ($e:expr, $kind:pat, $($message:tt)+) => {
        assert!(matches!($e.first_kind(), Some($kind)), $($message)+)
    };
}

/// The stack of an ordinary spawned thread.
const SMALL_STACK: usize = 2 << 20;

/// Runs `f` on a thread with a 2 MiB stack and returns its result.
fn small_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(SMALL_STACK)
        .spawn(f)
        .expect("spawn")
        .join()
        .expect("no panic and no stack overflow")
}

/// The work a drawing announced to its progress sink: the total of the
/// last `start` (`None`: no work was started) and the last `done`.
#[derive(Debug, Default, PartialEq)]
struct Tally {
    total: Option<u64>,
    done: u64,
}

impl Progress for Tally {
    fn start(&mut self, _what: &str, total: u64) {
        self.total = Some(total);
    }
    fn update(&mut self, done: u64) {
        self.done = done;
    }
    fn finish(&mut self) {}
}

fn lsys_err(src: String, limits: Limits) -> Diagnostics {
    small_stack(move || lsys::parse(&src, &limits).expect_err("parsed, expected an error"))
}

fn stl_err(src: String, format: Format, limits: Limits) -> Diagnostics {
    small_stack(move || stl::parse(&src, format, &limits).expect_err("parsed, expected an error"))
}

/// [`stl_err`] of a BED under the default limits.
fn bed_err(src: impl Into<String>) -> Diagnostics {
    stl_err(src.into(), Format::Bed, Limits::default())
}

/// The value of the limit error `e` begins with.
fn limit_value(e: &Diagnostics) -> &str {
    let ErrorKind::Limit { value, .. } = &e.0[0].kind else {
        panic!("not a limit error: {e}")
    };
    value
}

/// A limit error whose message names `what`.
fn is_limit(e: &Diagnostics, what: &str) -> bool {
    matches!(e.first_kind(), Some(k @ ErrorKind::Limit { .. }) if k.to_string().contains(what))
}

const N: usize = 100_000;
const HEAD: &str = "T (0, 0) L=10(0) B=1(0) RULE ";

/// A BED whose seed is `seed`, its rule `R1: [F]`.
fn seeded(seed: String) -> String {
    format!("{HEAD} R1: [F] SEED {seed} ENDSEED")
}

/// `open` `n` times, then `inner`, then `close` `n` times.
fn nest(n: usize, open: &str, inner: &str, close: &str) -> String {
    format!("{}{inner}{}", open.repeat(n), close.repeat(n))
}

/// The error of nesting past `limit` levels.
fn too_deep(limit: usize) -> ErrorKind {
    Input(NestingTooDeep { limit })
}

/// The default limits with nesting allowed to a million levels.
fn deep_limits() -> Limits {
    limits_with(|l| l.max_nesting = 1_000_000)
}

/// `d` read as a BED and drawn in `order` into `turtle`.
fn draw_bed(
    d: &Description,
    order: Derivation,
    limits: &Limits,
    turtle: &mut impl Turtle,
    progress: &mut impl Progress,
) -> Result<(), Diagnostics> {
    stlc::bed::Bed::new(d.clone(), limits)
        .and_then(|bed| stlc::interpret::bed::draw(&bed, order, limits, turtle, progress))
}

// --------------------------------------------------------------- nesting --

#[test]
fn lsys_axiom_nested_a_hundred_thousand_deep_is_refused_at_the_limit() {
    let src = format!("axiom {}\nangle 90\n", nest(N, "[", "F", "]"));
    let e = lsys_err(src, Limits::default());
    assert_eq!(e.first_kind(), Some(&too_deep(10_000)));
    // The 10 001st `[`, after `axiom `.
    assert_eq!(e.0[0].span, Some(6 + 10_000..6 + 10_001));
}

#[test]
fn lsys_successor_nested_a_hundred_thousand_deep_is_refused() {
    let src = format!("axiom F\nangle 90\nrule F {}\n", nest(N, "[", "F", "]"));
    let e = lsys_err(src, Limits::default());
    assert_eq!(e.first_kind(), Some(&too_deep(10_000)));
}

#[test]
fn deep_lsys_brackets_within_a_raised_limit_parse_and_draw_without_recursion() {
    // With the limit raised, nothing recursive is left to overflow: the
    // grammar reads a word flat and both strategies use explicit stacks.
    let limits = deep_limits();
    let (axiom, successor) = (nest(N, "[", "F", "]"), nest(N, "[", "+F", "]"));
    let src = format!("axiom {axiom}\nangle 90\nrule F F{successor}\n");
    let counts = small_stack(move || {
        let sys = lsys::parse(&src, &limits).expect("parses");
        [Dfs, Bfs].map(|s| {
            let mut c = Counter::default();
            let mut tally = Tally::default();
            stlc::interpret::lsys::draw(&sys, 1, s, &limits, &mut c, &mut tally).expect("draws");
            (c.0, tally)
        })
    });
    // F -> F[...+F...]: two segments, and a word of 4N + 3 symbols (the
    // axiom's 2N brackets around the successor's 2N + 3) announced and
    // finished.
    let word = 4 * N as u64 + 3;
    for (segments, tally) in counts {
        assert_eq!(segments, 2);
        assert_eq!((tally.total, tally.done), (Some(word), word));
    }
    // An unbalanced one is still pointed at, at its opening bracket.
    let src = format!("axiom F{}\nangle 90\n", "[".repeat(N));
    let e = lsys_err(src, limits);
    let want = Some(&Input(Unbalanced('[')));
    assert_eq!(e.first_kind(), want);
}

#[test]
fn stl_brackets_braces_and_repeats_a_hundred_thousand_deep_are_refused() {
    let cases = [
        format!("{HEAD} R1: {}", nest(N, "[", "F", "]")),
        seeded(nest(N, "R1{", "", "}")),
        seeded(nest(N, "{", "", "}")),
        seeded(nest(N, "[I 2 ", "R1", "]")),
        seeded(nest(N, "[", "F", "]")),
    ];
    for src in cases {
        for format in [Format::Od, Format::Bed] {
            let e = stl_err(src.clone(), format, Limits::default());
            assert_eq!(e.first_kind(), Some(&too_deep(10_000)), "{}", &src[..60]);
        }
    }
}

#[test]
fn stl_nesting_beyond_the_limit_in_a_raised_limit_is_a_clean_error_or_a_tree() {
    // Raised limit: what the parser itself does with 10^5 levels, on a
    // small stack. Brackets in a body are drawing; a seed of bare braces
    // or of `[I 2` around a rule is malformed and must say so.
    let limits = deep_limits();
    let body = format!("{HEAD} R1: [{}] SEED R1 ENDSEED", nest(N, "[", "F", "]"));
    let count = small_stack(move || {
        let d = stl::parse(&body, Format::Bed, &limits).expect("a deep branch parses");
        let mut c = Counter::default();
        draw_bed(&d, Dfs, &limits, &mut c, &mut NoProgress).expect("draws");
        c.0
    });
    assert_eq!(count, 1);
    let braces = seeded(nest(N, "{", "", "}"));
    // Pointed at the first brace, which follows no rule name.
    let at = braces.find('{').unwrap();
    let e = stl_err(braces, Format::Bed, limits);
    assert_eq!(e.0[0].span, Some(at..at + 1), "{e}");
    let repeats = seeded(nest(N, "[I 2 ", "R1", "]"));
    let at = repeats.find("[I").unwrap();
    let e = stl_err(repeats, Format::Bed, limits);
    let wanted = Some(&Input(Unbalanced('[')));
    assert_eq!(e.first_kind(), wanted, "{e}");
    assert_eq!(e.0[0].span, Some(at..at + 1));
}

/// A seed term `R1{R1{...}}` is a tree of nested values as deep as the
/// input. Every pass over it uses an explicit stack: pest, the parser's own
/// passes, validation, the writer, both drawing strategies, and `Term`'s
/// hand-written `Clone`, `PartialEq`, `Drop` and depth-capped `Debug` (derived ones recursed about
/// 1 KiB of stack per level in a debug build: 1 000 levels fitted a 2 MiB
/// stack, 2 000 did not). So terms nested to just under the default
/// `max_nesting` (10 000) go through everything on an ordinary 2 MiB thread.
#[test]
fn terms_nested_to_the_default_limit_work_on_an_ordinary_thread_stack() {
    let n = 9_900;
    let src = seeded(nest(n, "R1{", "", "}"));
    let (count, text_len) = small_stack(move || {
        let limits = Limits::default();
        let d = stl::parse(&src, Format::Bed, &limits).expect("parses");
        validate(&d, &limits).expect("valid");
        let text = write(&d);
        let mut c = Counter::default();
        draw_bed(&d, Dfs, &limits, &mut c, &mut NoProgress).expect("draws");
        let mut b = Counter::default();
        draw_bed(&d, Bfs, &limits, &mut b, &mut NoProgress).expect("draws");
        assert_eq!(b.0, c.0);
        let back = stl::parse(&text, Format::Bed, &limits).expect("reparses");
        assert!(back == d, "round trip");
        // Clone, compare, and tell a difference at the deepest level.
        let copy = d.clone();
        assert!(copy == d);
        // (Locations do not take part in equality: only the innermost slot,
        // a repeat instead of empty, differs.)
        let deeper = seeded(nest(n - 1, "R1{", "[I 2 R1]", "}"));
        let deeper = stl::parse(&deeper, Format::Bed, &limits).expect("parses");
        assert!(deeper != d, "the innermost slot differs");
        // `{:?}` of the description shows the arena's size, not its terms.
        let shown = format!("{d:#?}");
        assert!(shown.contains(&format!("terms: {n}")), "{shown}");
        drop((d, copy, back, deeper));
        (c.0, text.len())
    });
    assert_eq!(count, n as u64);
    // Indentation stops at MAX_INDENT_DEPTH, so the text stays linear in
    // the depth and reads back under the default input limit.
    let indent = 2 * stlc::bed::write::MAX_INDENT_DEPTH;
    assert!(text_len < n * 2 * (indent + 4) + 200, "{text_len}");
}

// ---------------------------------------------------------------- counts --

#[test]
fn generations_in_the_millions_are_refused_with_limit() {
    let src = "generations 5000000\naxiom F\nangle 90\n";
    let e = lsys_err(src.into(), Limits::default());
    assert!(is_limit(&e, "generations"), "{e}");
    let d = &e.0[0];
    assert_eq!(d.span, Some(12..19));
    // A number too large for any integer type is a limit too, not a crash.
    let src = "generations 99999999999999999999999999\naxiom F\nangle 90\n";
    let e = lsys_err(src.into(), Limits::default());
    assert!(is_limit(&e, "generations"), "{e}");
}

#[test]
fn self_resemblance_counts_in_the_millions_are_refused_with_limit() {
    let src = format!("{HEAD} R1: [F] SEED [I 3000000 R1] ENDSEED");
    let at = src.find("3000000").unwrap();
    for format in [Format::Od, Format::Bed] {
        let e = stl_err(src.clone(), format, Limits::default());
        assert!(is_limit(&e, "self-resemblance count"), "{e}");
        assert_eq!(e.0[0].span, Some(at..at + 7));
    }
    // In a fixed figure, and beyond u32.
    let src = format!("{HEAD} R1: [F[I 99999999999999 F+F]]");
    let e = bed_err(src);
    assert!(is_limit(&e, "self-resemblance count"), "{e}");
}

#[test]
fn an_expansion_beyond_the_symbol_budget_is_refused_before_drawing() {
    // 2^40 stems from [I 40 R1] with two branches: within max_repeat,
    // beyond max_symbols.
    let d = bed(&format!("{HEAD} R1: [+F][-F] SEED [I 40 R1] ENDSEED"));
    let (e, drawn, tally) = small_stack(move || {
        let (mut c, mut tally) = (Counter::default(), Tally::default());
        let e = draw_bed(&d, Dfs, &Limits::default(), &mut c, &mut tally).unwrap_err();
        (e, c.0, tally)
    });
    assert!(is_limit(&e, "symbols in the expansion"), "{e}");
    // The exact size, some 10^13 symbols, was counted, not walked: nothing
    // was drawn and no pass over the symbols began.
    assert_eq!(limit_value(&e), (10 * ((1u64 << 40) - 1)).to_string());
    assert_eq!((drawn, tally), (0, Tally::default()));
}

/// `src` parsed and drawn to depth 10,000 on a small stack, which must
/// fail: the error, the segments drawn and the work announced.
fn drawn_to_depth_10000(src: String) -> (Diagnostics, u64, Tally) {
    small_stack(move || {
        let limits = Limits::default();
        let sys = lsys::parse(&src, &limits).expect("parses");
        let (mut c, mut tally) = (Counter::default(), Tally::default());
        let e = stlc::interpret::lsys::draw(&sys, 10_000, Dfs, &limits, &mut c, &mut tally)
            .unwrap_err();
        (e, c.0, tally)
    })
}

#[test]
fn a_derivation_beyond_the_budget_is_refused_with_its_exact_length() {
    let (e, drawn, tally) = drawn_to_depth_10000("axiom F\nrule F FF\nangle 90\n".into());
    // Refused before a symbol was derived.
    assert_eq!((drawn, tally), (0, Tally::default()));
    assert!(is_limit(&e, "derived word length at depth 10000"), "{e}");
    // 2^10000 has 3011 digits.
    assert_eq!(limit_value(&e).len(), 3011);
    let exact = num_bigint::BigUint::from(2u32).pow(10_000);
    assert_eq!(limit_value(&e), exact.to_string());
}

#[test]
fn a_wide_alphabet_at_the_depth_limit_is_refused_with_its_exact_length() {
    // 60 000 distinct symbols and depth 10 000: a length table of every
    // (symbol, depth) pair would be 4.8 GB. Only `F` has a rule, so only
    // its lengths are carried from level to level.
    // (U+FEFF, the byte-order mark, is blank space to the parser.)
    let chars = (0x4e00u32..0x4e00 + 60_000).filter_map(char::from_u32);
    let alphabet: String = chars.filter(|&c| c != '\u{feff}').collect();
    let inert = alphabet.chars().count();
    let src = format!("axiom F{alphabet}\nrule F FF\nangle 90\n");
    let (e, drawn, tally) = drawn_to_depth_10000(src);
    assert!(is_limit(&e, "derived word length at depth 10000"), "{e}");
    // 2^10000 copies of F and the inert symbols once each.
    let exact = num_bigint::BigUint::from(2u32).pow(10_000) + inert;
    assert_eq!(limit_value(&e), exact.to_string());
    assert_eq!((drawn, tally), (0, Tally::default()));
}

// --------------------------------------------------------------- numbers --

#[test]
fn lsys_numbers_that_overflow_or_are_not_numbers_are_refused() {
    for (line, needle) in [
        ("angle 1e999", "1e999"),
        ("angle NaN", "NaN"),
        ("angle inf", "inf"),
        ("angle -inf", "-inf"),
        ("angle 1e", "1e"),
    ] {
        let src = format!("axiom F\n{line}\n");
        let at = src.find(needle).unwrap();
        let e = lsys_err(src.clone(), Limits::default());
        assert_first!(
            e,
            Lsys(NumberTooLarge { .. } | MalformedNumber { .. }),
            "{line}: {e}"
        );
        assert_eq!(e.0[0].span, Some(at..at + needle.len()), "{line}");
    }
    for line in ["length 0", "length -1", "width -2", "length 1e999"] {
        let src = format!("axiom F\nangle 90\n{line}\n");
        let e = lsys_err(src, Limits::default());
        assert_first!(
            e,
            Lsys(NotPositive { .. } | NumberTooLarge { .. }),
            "{line}: {e}"
        );
    }
}

#[test]
fn stl_numbers_that_overflow_are_refused() {
    let layout = format!("{HEAD} R1: [F] LAYOUT (clGreen) Rectangle (0,0), 1e309, 5 ENDLAYOUT");
    for (src, needle) in [
        ("T (1e999, 0) L=10(0) B=1(0) RULE R1: [F]", "1e999"),
        ("T (0, 0) L=1e400(0) B=1(0) RULE R1: [F]", "1e400"),
        ("T (0, 0) L=10(0) B=1(0) A=-1e999 RULE R1: [F]", "-1e999"),
        (&layout, "1e309"),
    ] {
        let at = src.find(needle).unwrap();
        let e = bed_err(src);
        assert_first!(e, Input(NotFinite { .. }), "{src}: {e}");
        assert_eq!(e.0[0].span, Some(at..at + needle.len()), "{src}");
    }
    // `NaN` and `inf` are not numbers in the grammar at all.
    for src in [
        "T (NaN, 0) L=10(0) B=1(0) RULE R1: [F]",
        "T (0, 0) L=inf(0) B=1(0) RULE R1: [F]",
    ] {
        let e = bed_err(src);
        assert_first!(e, Input(Syntax(_)), "{src}: {e}");
    }
}

#[test]
fn zero_and_negative_sizes_are_refused() {
    for (src, needle) in [
        ("T (0, 0) L=0(0) B=1(0) RULE R1: [F]", "0(0)"),
        ("T (0, 0) L=10(0) B=-1(0) RULE R1: [F]", "-1(0)"),
        ("T (0, 0) L=10(-1) B=1(0) RULE R1: [F]", "-1)"),
    ] {
        let e = bed_err(src);
        assert_first!(
            e,
            Stl(StemSizeNotPositive { .. } | NegativeDecrement { .. }),
            "{src}: {e}"
        );
        let at = src.find(needle).unwrap();
        let span = e.0[0].span.clone().unwrap();
        assert_eq!(span.start, at, "{src}");
    }
    for shape in [
        "Rectangle (0,0), 0, 10",
        "Rectangle (0,0), 10, -10",
        "Ellipse (5,5,5,9)",
        "RoundRect (0,0), 10, 10, -1",
        "RoundRect (0,0,10,10,0,4)",
        "Polygon (0,0), (1,1)",
    ] {
        let src = format!("{HEAD} R1: [F] LAYOUT (clGreen) {shape} ENDLAYOUT");
        let e = stl_err(src, Format::Od, Limits::default());
        assert_first!(
            e,
            Layout(ShapeSizeNotPositive { .. } | TooFewPoints { .. }),
            "{shape}: {e}"
        );
    }
    // A decrement that runs the length out: the order where it happens.
    let d = bed("T (0, 0) L=10(5) B=1(0) RULE R1: [F] SEED R1{R1{R1{}}} ENDSEED");
    let e = validate(&d, &Limits::default()).unwrap_err();
    assert_first!(e, Bed(OrderTooDeep { order: 2, .. }), "{e}");
}

// ---------------------------------------------------------------- layout --

#[test]
fn a_self_intersecting_polygon_is_read_and_written_back_as_given() {
    // A bow tie: its edges cross at (5, 5). The region is the grower's
    // business; the parser keeps the points in order and the writer too.
    let src =
        format!("{HEAD} R1: [F] LAYOUT (clGreen) Polygon (0,0), (10,10), (10,0), (0,10) ENDLAYOUT");
    let d = bed(&src);
    let shapes = &d.layout.as_ref().unwrap().shapes;
    let want = Shape::Polygon(vec![(0.0, 0.0), (10.0, 10.0), (10.0, 0.0), (0.0, 10.0)]);
    assert_eq!(shapes[0].shape, want);
    assert_eq!(bed(&write(&d)), d);
}

#[test]
fn a_layout_whose_shapes_cancel_is_read_and_drawn() {
    // A green square erased by a white one: the painting is empty. Reading
    // and drawing the BED do not depend on the region.
    let src = format!(
        "{HEAD} R1: [F] SEED F ENDSEED LAYOUT (clGreen) Rectangle (0,0), 10, 10 \
         (clWhite) Rectangle (0,0), 10, 10 ENDLAYOUT"
    );
    let d = bed(&src);
    assert_eq!(d.layout.as_ref().unwrap().shapes.len(), 2);
    let mut b = Bounds::default();
    let limits = Limits::default();
    draw_bed(&d, Dfs, &limits, &mut b, &mut NoProgress).unwrap();
    assert_eq!(b.count, 1);
}

// ------------------------------------------------------ size and garbage --

#[test]
fn a_hundred_megabyte_input_is_refused_by_its_size_before_its_bytes_are_read() {
    // Not UTF-8 from the first byte on: any look at the content would
    // report that instead, so the size alone refused it.
    let big = vec![0xff; 100 << 20];
    let e = precheck(&big, &Limits::default()).unwrap_err();
    let (size, limit) = (100 << 20, 64 << 20);
    let too_large = Input(InputTooLarge { size, limit });
    assert_eq!(e.first_kind(), Some(&too_large));
}

/// A deterministic stream of bytes (xorshift64*).
fn garbage(len: usize, mut seed: u64) -> Vec<u8> {
    (0..len)
        .map(|_| {
            seed ^= seed >> 12;
            seed ^= seed << 25;
            seed ^= seed >> 27;
            (seed.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 56) as u8
        })
        .collect()
}

#[test]
fn binary_garbage_is_refused_cleanly_by_every_parser() {
    for seed in 1..=20u64 {
        let bytes = garbage(4096, seed);
        let lossy = String::from_utf8_lossy(&bytes).into_owned();
        // As bytes: not UTF-8.
        let e = precheck(&bytes, &Limits::default()).unwrap_err();
        assert_first!(e, Input(NotUtf8(_)), "{e}");
        // As text (replacement characters): a syntax error or a limit.
        let e = lsys_err(lossy.clone(), Limits::default());
        assert_first!(
            e,
            Input(Syntax(_) | NestingTooDeep { .. }) | Lsys(UnknownKey { .. } | MissingKey { .. }),
            "{e}"
        );
        for format in [Format::Od, Format::Bed] {
            let e = stl_err(lossy.clone(), format, Limits::default());
            assert_first!(e, Input(Syntax(_) | NestingTooDeep { .. }), "{e}");
        }
    }
}

#[test]
fn invalid_utf8_is_refused_with_its_offset_by_both_parsers_entry() {
    let mut bytes = b"axiom F\nangle 90\n# caf".to_vec();
    bytes.extend_from_slice(&[0xc3, 0x28]);
    let e = precheck(&bytes, &Limits::default()).unwrap_err();
    let want = Some(&Input(NotUtf8(22)));
    assert_eq!(e.first_kind(), want);
    assert_eq!(e.0[0].span, Some(22..22));
    // A UTF-16 file (BOM FF FE) fails at byte 0.
    let e = precheck(b"\xff\xfea\0x\0", &Limits::default()).unwrap_err();
    let want = Some(&Input(NotUtf8(0)));
    assert_eq!(e.first_kind(), want);
}

#[test]
fn empty_and_comment_only_files_of_each_kind_say_what_is_missing() {
    for src in ["", "\n\n  \n", "# nothing but a comment\n# and another"] {
        let e = lsys_err(src.into(), Limits::default());
        let missing: Vec<String> = e.iter().map(|d| d.kind.to_string()).collect();
        let holds = missing.iter().any(|m| m.contains("axiom"));
        assert!(holds, "{src:?}: {missing:?}");
        for format in [Format::Od, Format::Bed] {
            let e = stl_err(src.into(), format, Limits::default());
            assert_first!(e, Input(Syntax(_)), "{src:?}: {e}");
            assert_eq!(e.0.len(), 1);
        }
    }
}

// ----------------------------------------------------------------- grower --

fn grow_err(src: &str) -> Diagnostics {
    let grown = stlc::grow::grow(&od(src), &Default::default(), &mut NoProgress);
    grown.map(|g| g.stems).expect_err(src)
}

#[test]
fn a_layout_whose_shapes_cancel_leaves_nothing_to_grow_in() {
    let src = "T (5, 5) L=1(0) B=1(0) RULE R1: [+F][-F] \
               LAYOUT (clGreen) Rectangle (0,0), 10, 10 (clWhite) Rectangle (0,0), 10, 10 ENDLAYOUT";
    let e = grow_err(src);
    assert_first!(e, Layout(EmptyRegion), "{e}");
    let at = src.find("LAYOUT").unwrap();
    assert_eq!(e.0[0].span.as_ref().map(|s| s.start), Some(at));
}

#[test]
fn a_root_outside_the_layout_is_refused_at_the_root() {
    let src = "T (50, 50) L=1(0) B=1(0) RULE R1: [+F][-F] \
               LAYOUT (clGreen) Rectangle (0,0), 10, 10 ENDLAYOUT";
    let e = grow_err(src);
    assert_first!(e, Grow(RootOutside { .. }), "{e}");
    assert_eq!(e.0[0].span, Some(2..10));
}

#[test]
fn a_self_intersecting_polygon_layout_grows_inside_its_lobes() {
    // A bow tie crossing at (50, 50); the root sits in its left lobe, the
    // triangle (0, 0), (50, 50), (0, 100): x <= y <= 100 - x. Stems do not
    // shorten, so only the layout stops the growth.
    let src = "T (15, 60) L=5(0) B=1(0) A=20 RULE R1: [+F][-F] SEED F R1 ENDSEED \
               LAYOUT (clGreen) Polygon (0,0), (100,100), (100,0), (0,100) ENDLAYOUT";
    let d = od(src);
    let g = small_stack(move || {
        stlc::grow::grow(&d, &stlc::grow::GrowOptions::default(), &mut NoProgress).expect("grows")
    });
    let mut segs = Recorder::default();
    let limits = Limits::default();
    stlc::interpret::bed::draw(&g.bed, Dfs, &limits, &mut segs, &mut NoProgress).unwrap();
    assert_eq!(segs.segments.len() as u64, g.stems);
    let ends = || segs.segments.iter().flat_map(|s| [s.from, s.to]);
    for p in ends() {
        let (x, y) = (p.x, p.y);
        let inside = x <= y && y <= 100.0 - x;
        assert!(inside, "({x}, {y}) is outside the left lobe");
    }
    // It filled the lobe out to its outer edge, x = 0.
    let min_x = ends().map(|p| p.x).fold(f64::INFINITY, f64::min);
    assert!(min_x < 1.0, "{min_x}");
    // What it grew is a valid BED that reads back.
    let text = write(g.bed.description());
    let back = bed(&text);
    validate(&back, &Limits::default()).expect("valid");
}

/// A runaway layout: a star of 20,000 thin spikes (geo's overlay, past
/// 16,000 edges, fragments its input and spent 10 s on it; 200,000 spikes
/// took minutes), and big ellipses painted one after another. Both are
/// refused by the layout vertex limit, at the shape that passes it, before
/// an overlay of that size runs.
#[test]
fn runaway_layouts_are_refused_at_the_shape_that_passes_the_vertex_limit() {
    let star: Vec<String> = (0..20_000)
        .map(|i| {
            let t = std::f64::consts::TAU * f64::from(i) / 20_000.0;
            let r = if i % 2 == 1 { 400.0 } else { 200.0 };
            let (x, y) = (500.0 + r * libm::cos(t), 500.0 + r * libm::sin(t));
            format!("({x:.3},{y:.3})")
        })
        .collect();
    let star = star.join(",");
    let src = format!(
        "T (500, 500) L=10(0) B=1(0) RULE R1: [-F][+F] LAYOUT (clGreen) Polygon {star} ENDLAYOUT"
    );
    // A polygon of more points than the limit is refused before the parser
    // reads it, pointing at the shape; within a raised limit it parses and
    // the region counts it exactly.
    let e = stl::parse(&src, Format::Od, &Limits::default()).unwrap_err();
    assert!(is_limit(&e, "layout outline vertices"), "{e}");
    let message = e.to_string();
    assert!(message.contains("20000 exceeds the limit of 16000"), "{e}");
    assert_eq!(e.0[0].span.as_ref().map(|s| s.start), src.find("(clGreen)"));
    let limits = limits_with(|l| l.max_layout_vertices = 20_000);
    let d = stl::parse(&src, Format::Od, &limits).expect("within the raised limit it parses");
    let mut o = stlc::grow::GrowOptions::default();
    o.limits.max_layout_vertices = 16_000;
    let e = stlc::grow::grow(&d, &o, &mut NoProgress).unwrap_err();
    assert!(is_limit(&e, "layout outline vertices"), "{e}");
    assert_eq!(e.0[0].span.as_ref().map(|s| s.start), src.find("(clGreen)"));

    // An ellipse of radius 50,000 flattens (within 0.05 units) to 556 steps
    // a quarter, 2,224 vertices. Ellipses side by side, not overlapping,
    // add up: seven make 15,568, the eighth would make 17,792 > 16,000.
    let shapes: String = (0..600)
        .map(|i| format!("(clGreen) Ellipse ({}, 0), 100000, 100000 ", i * 100_001))
        .collect();
    let src =
        format!("T (50000, 50000) L=10(0) B=1(0) RULE R1: [-F][+F] LAYOUT {shapes} ENDLAYOUT");
    let e = grow_err(&src);
    assert!(is_limit(&e, "layout outline vertices"), "{e}");
    assert!(e.to_string().contains("17792"), "{e}");
    let eighth = src.match_indices("(clGreen)").nth(7).unwrap().0;
    assert_eq!(e.0[0].span.as_ref().map(|s| s.start), Some(eighth));
}
