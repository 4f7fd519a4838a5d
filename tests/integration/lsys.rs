//! Classic L-systems: parsing, derivation (dfs and bfs), expand and stats,
//! checked against independently known values.

use crate::support::{limit_kind, limits_with};
use num_bigint::BigUint;
use proptest::prelude::*;
use stlc::diag::ErrorKind::{Input, Lsys};
use stlc::diag::InputError::{Unbalanced, UnknownColour};
use stlc::diag::LsysError::*;
use stlc::diag::{ErrorKind, InputError};
use stlc::interpret::Derivation::{self, Bfs, Dfs};
use stlc::interpret::lsys::{draw_into, exact_lengths, expand};
use stlc::interpret::stats::{stats, stats_with_budget};
use stlc::limits::{Bound, Limits};
use stlc::model::lsys::{Background, LSystem};
use stlc::progress::NoProgress;
use stlc::syntax::lsys::parse;
use stlc::turtle::{Point, Recorder, Segment};

/// `src` read as an `.lsys` with the default limits; its diagnostics and
/// the text on failure.
pub fn sys(src: &str) -> LSystem {
    parse(src, &Limits::default()).unwrap_or_else(|e| panic!("{e}\n{src}"))
}

/// The segments `src` draws at `depth`, with the default limits.
pub fn segments(src: &str, depth: u32, strategy: Derivation) -> Vec<Segment> {
    segments_of(&sys(src), depth, strategy)
}

/// The segments `s` draws at `depth`, with the default limits.
pub fn segments_of(s: &LSystem, depth: u32, strategy: Derivation) -> Vec<Segment> {
    recorded_of(s, depth, strategy).segments
}

/// What the turtle hands a backend for `s` at `depth` (segments,
/// polygons), with the default limits.
pub fn recorded_of(s: &LSystem, depth: u32, strategy: Derivation) -> Recorder {
    let mut rec = Recorder::default();
    let limits = Limits::default();
    draw_into(s, depth, strategy, &limits, &mut rec, &mut NoProgress).unwrap();
    rec
}

fn expanded(src: &str, depth: u32, strategy: Derivation) -> String {
    expanded_of(&sys(src), depth, strategy)
}

/// The word `s` derives at `depth` (newline included), default limits.
pub fn expanded_of(s: &LSystem, depth: u32, strategy: Derivation) -> String {
    let (mut out, limits) = (Vec::new(), Limits::default());
    expand(s, depth, strategy, &limits, &mut out, &mut NoProgress).unwrap();
    String::from_utf8(out).unwrap()
}

fn big(n: u64) -> BigUint {
    BigUint::from(n)
}

const TREE1: &str = "axiom F\nrule F F[+F]F[-F]F\nangle 25.7\n";

// ------------------------------------------------------------------ parse --

#[test]
fn parses_every_key() {
    let s = sys("# a comment\n\
         generations 4   # trailing comment\n\
         axiom F [+F]\n\
         rule F -> FF\n\
         rule X = F[+X]\n\
         rule Y YF\n\
         angle -22.5\n\
         length 2.5\n\
         width .5\n\
         color #ff8000\n\
         background none\n");
    assert_eq!(s.generations, Some(4));
    assert_eq!(s.axiom, vec!['F', '[', '+', 'F', ']']);
    assert_eq!(s.successor('F'), Some(&['F', 'F'][..]));
    assert_eq!(s.successor('X'), Some(&['F', '[', '+', 'X', ']'][..]));
    assert_eq!(s.successor('Y'), Some(&['Y', 'F'][..]));
    assert_eq!(s.angle, -22.5);
    assert_eq!(s.length, 2.5);
    assert_eq!(s.width, 0.5);
    assert_eq!(s.color, Some(stlc::color::Rgb::new(255, 128, 0)));
    assert_eq!(s.background, Background::None);
}

#[test]
fn defaults_and_optional_generations() {
    let s = sys("axiom F\nangle 90");
    assert_eq!(s.generations, None);
    assert_eq!(s.length, 1.0);
    assert_eq!(s.width, 1.0);
    assert_eq!(s.color, None);
    assert_eq!(s.background, Background::White);
    let s = sys("axiom F\r\nangle 90\r\nbackground clGreen\r\nrule F->F+F");
    let wanted = Background::Color(stlc::color::Rgb::new(0, 128, 0));
    assert_eq!(s.background, wanted);
    assert_eq!(s.successor('F'), Some(&['F', '+', 'F'][..]));
}

/// The `.lsys` error `$variant` of the key `$key` whose value is `$text`.
macro_rules! keyed {
    ($variant:ident, $key:expr, $text:expr) => {
        Lsys($variant {
            key: $key,
            text: $text.into(),
        })
    };
}

/// Parses `src` and returns (kind, span) of every diagnostic.
fn errors(src: &str, limits: &Limits) -> Vec<(ErrorKind, std::ops::Range<usize>)> {
    let err = parse(src, limits).unwrap_err();
    err.iter()
        .map(|d| {
            assert!(d.help.is_some(), "no help on {d}");
            (d.kind.clone(), d.span.clone().expect("a span"))
        })
        .collect()
}

#[test]
fn unknown_key_suggests_the_nearest() {
    let src = "axiom F\nangel 30\n";
    let err = parse(src, &Limits::default()).unwrap_err();
    // Unknown key, and the angle is then missing: both reported.
    assert_eq!(err.0.len(), 2);
    let d = &err.0[0];
    let key = "angel".into();
    assert_eq!(d.kind, Lsys(UnknownKey { key }));
    assert_eq!(d.span, Some(8..13));
    assert_eq!(d.help_text().as_deref(), Some("did you mean `angle`?"));
    assert_eq!(err.0[1].kind, Lsys(MissingKey { key: "angle" }));
}

#[test]
fn missing_axiom_and_angle_are_both_reported() {
    let src = "generations 3\nrule F FF\n";
    let e = errors(src, &Limits::default());
    let missing = |key| (Lsys(MissingKey { key }), 24..24);
    assert_eq!(e, vec![missing("axiom"), missing("angle")]);
}

#[test]
fn two_rules_for_one_symbol_label_both() {
    let src = "axiom F\nangle 90\nrule F FF\nrule F F+F\n";
    let err = parse(src, &Limits::default()).unwrap_err();
    assert_eq!(err.0.len(), 1);
    let d = &err.0[0];
    assert_eq!(d.kind, Lsys(DuplicateProduction { symbol: 'F' }));
    assert_eq!(d.span, Some(27..37)); // the second rule line
    assert_eq!(d.labels.len(), 1);
    assert_eq!(d.labels[0].span, 17..26); // the first
}

#[test]
fn unbalanced_brackets_point_at_the_unmatched_one() {
    // axiom: `[` at byte 7 never closed; successor: `]` at byte 29 closes nothing.
    let src = "axiom [F[F]\nangle 90\nrule F F]F\n";
    assert_eq!(&src[6..7], "[");
    assert_eq!(&src[29..30], "]");
    let e = errors(src, &Limits::default());
    let unbalanced = |c, at| (Input(Unbalanced(c)), at);
    assert_eq!(e, vec![unbalanced('[', 6..7), unbalanced(']', 29..30)]);
}

#[test]
fn malformed_and_invalid_numbers() {
    let src = "axiom F\nangle 2x5\nlength -1\nwidth 1e999\ngenerations 2.5\n";
    let e = errors(src, &Limits::default());
    assert_eq!(e.len(), 4);
    let malformed = (Lsys(MalformedNumber { text: "2x5".into() }), 14..17);
    let not_positive = (keyed!(NotPositive, "length", "-1"), 25..27);
    let too_large = (keyed!(NumberTooLarge, "width", "1e999"), 34..39);
    let not_whole = (keyed!(NotWholeNumber, "generations", "2.5"), 52..55);
    assert_eq!(e, [malformed, not_positive, too_large, not_whole]);
    let e = errors("axiom F\nangle nan\n", &Limits::default());
    let wanted = vec![(Lsys(MalformedNumber { text: "nan".into() }), 14..17)];
    assert_eq!(e, wanted);
}

#[test]
fn generations_above_max_depth_name_the_flag() {
    let limits = limits_with(|l| l.max_depth = 10);
    let err = parse("generations 11\naxiom F\nangle 90\n", &limits).unwrap_err();
    let d = &err.0[0];
    let wanted = limit_kind(Bound::Depth, Some("generations"), "11", 10);
    assert_eq!(d.kind, wanted);
    assert_eq!(d.span, Some(12..14));
    assert!(d.help_text().unwrap().contains("--max-depth"));
}

#[test]
fn duplicate_key_bad_colour_and_long_predecessor() {
    let src = "axiom F\nangle 90\nangle 60\ncolor clGren\nrule FF F\n";
    let (text, predecessor, symbols) = ("clGren".into(), "FF".into(), 2);
    let long = Lsys(LongPredecessor {
        predecessor,
        symbols,
    });
    let long = (long, 44..46);
    let duplicate = (Lsys(DuplicateKey { key: "angle" }), 17..22);
    let colour = (Input(UnknownColour { text }), 32..38);
    assert_eq!(errors(src, &Limits::default()), [duplicate, colour, long]);
}

#[test]
fn syntax_errors_read_like_the_file_not_the_grammar() {
    let err = parse("axiom F\nangle\n", &Limits::default()).unwrap_err();
    let d = &err.0[0];
    let wanted = ErrorKind::Input(InputError::Syntax("expected a number".into()));
    assert_eq!(d.kind, wanted);
    assert_eq!(d.span, Some(13..13));
    let err = parse("axiom F\nangle 90\nrule X\n", &Limits::default()).unwrap_err();
    let ErrorKind::Input(InputError::Syntax(m)) = &err.0[0].kind else {
        panic!("{err}")
    };
    assert_eq!(m, "expected `->`, `=` or a space before the successor");
    assert_eq!(err.0[0].span, Some(23..23));
    let err = parse("axiom F\n5 F\nangle 90\n", &Limits::default()).unwrap_err();
    let line = "expected a line `key value` or a `#` comment".into();
    assert_eq!(err.0[0].kind, ErrorKind::Input(InputError::Syntax(line)));
    assert_eq!(err.0[0].span, Some(8..8));
    assert!(err.0[0].help.is_some());
}

// -------------------------------------------------------------- derivation --

#[test]
fn parallel_rewriting_gives_fibonacci_lengths() {
    // A -> AB, B -> A: |W_n| = Fib(n + 2) only if every symbol is rewritten at once.
    let src = "axiom A\nrule A AB\nrule B A\nangle 90\n";
    let (mut a, mut b) = (1u64, 2u64); // Fib(2), Fib(3)
    let lengths = exact_lengths(&sys(src), 40);
    for (n, len) in lengths.iter().enumerate() {
        assert_eq!(*len, big(a), "depth {n}");
        (a, b) = (b, a + b);
    }
    assert_eq!(expanded(src, 4, Dfs), "ABAABABA\n");
    assert_eq!(expanded(src, 4, Bfs), "ABAABABA\n");
    for depth in 0..12 {
        let dfs = expanded(src, depth, Dfs);
        assert_eq!(BigUint::from(dfs.len() - 1), lengths[depth as usize]);
        assert_eq!(dfs, expanded(src, depth, Bfs));
    }
}

#[test]
fn expand_by_hand() {
    // Hand derivation: F+X -> (FF)+(F-X) -> (FFFF)+(FF-F-X).
    let src = "axiom F+X\nrule F FF\nrule X F-X\nangle 90\n";
    assert_eq!(expanded(src, 0, Dfs), "F+X\n");
    assert_eq!(expanded(src, 1, Dfs), "FF+F-X\n");
    assert_eq!(expanded(src, 2, Dfs), "FFFF+FF-F-X\n");
    assert_eq!(expanded(src, 2, Bfs), "FFFF+FF-F-X\n");
}

/// A segment of order 0 from `a` to `b`.
fn seg(a: (f64, f64), b: (f64, f64)) -> Segment {
    let (from, to) = (Point::new(a.0, a.1), Point::new(b.0, b.1));
    Segment { from, to, order: 0 }
}

#[test]
fn segments_by_hand() {
    // `F+F` at 90 degrees: up one, turn left, then one step left (canvas: y down).
    let segs = segments("axiom F+F\nangle 90\nlength 2\n", 0, Dfs);
    let p = Point::new;
    let wanted = [seg((0.0, 0.0), (0.0, -2.0)), seg((0.0, -2.0), (-2.0, -2.0))];
    assert_eq!(segs, wanted);
    // `heading 0`: the same word starts to the right, then turns up.
    let segs = segments("axiom F+F\nangle 90\nheading 0\n", 0, Bfs);
    let wanted = [seg((0.0, 0.0), (1.0, 0.0)), seg((1.0, 0.0), (1.0, -1.0))];
    assert_eq!(segs, wanted);
    // `heading 180` with `|`: left, then turned around, back right.
    let segs = segments("axiom F|F\nangle 90\nheading 180\n", 0, Dfs);
    let ends: Vec<Point> = segs.iter().map(|s| s.to).collect();
    assert_eq!(ends, [p(-1.0, 0.0), p(0.0, 0.0)]);
    // `F[-F]|F` one level down from `X`: a right branch, then back down.
    let segs = segments("axiom X\nrule X F[-F]|F\nangle 90\n", 1, Dfs);
    let (up, right) = (seg((0.0, 0.0), (0.0, -1.0)), seg((0.0, -1.0), (1.0, -1.0)));
    assert_eq!(segs, [up, right, seg((0.0, -1.0), (0.0, 0.0))]);
}

#[test]
fn bracketed_tree_closed_forms() {
    // F -> F[+F]F[-F]F: each F becomes 5 F and 6 other symbols, so
    // F count 5^n and length 1 + 10 * (5^n - 1) / 4 = (5^(n+1) - 3) / 2.
    let s = sys(TREE1);
    // A small traversal budget: counts are exact whether or not it runs.
    let limits = limits_with(|l| l.max_symbols = 100_000);
    for n in 0..=20u32 {
        let st = stats(&s, n, &limits).unwrap();
        // The memoized geometry gives the box at every depth; the trunk is
        // 3^n steps straight up.
        assert_eq!(st.bbox.map(|b| b[1]), Some(-(3f64.powi(n as i32))));
        assert_eq!(st.segments, big(5u64.pow(n)));
        assert_eq!(st.length, big((5u64.pow(n + 1) - 3) / 2));
        assert_eq!(st.symbols[&'+'], big((5u64.pow(n) - 1) / 4));
    }
}

#[test]
fn table_3_of_000_corrected() {
    // 000's Table 3 prints 11, 61, 311, 1,562, 7,813, 39,080 for its levels
    // 0..5 (rewriting steps 1..6). The true lengths, by brute-force bfs
    // expansion and by the closed form (5^(n+1) - 3) / 2:
    let truth = [11u64, 61, 311, 1561, 7811, 39061];
    for (level, &want) in truth.iter().enumerate() {
        let n = level as u32 + 1;
        assert_eq!((5u64.pow(n + 1) - 3) / 2, want);
        let word = expanded(TREE1, n, Bfs);
        assert_eq!(word.len() as u64 - 1, want, "level {level}");
        let st = stats(&sys(TREE1), n, &Limits::default()).unwrap();
        assert_eq!(st.length, big(want));
    }
}

#[test]
fn stats_at_depth_57_is_exact() {
    let want = (BigUint::from(5u32).pow(58) - 3u32) / 2u32;
    let st = stats(&sys(TREE1), 57, &Limits::default()).unwrap();
    assert_eq!(st.length, want);
    assert_eq!(st.length.to_string().len(), 41);
    assert_eq!(st.segments, BigUint::from(5u32).pow(57));
    assert_eq!(st.symbols[&'['], BigUint::from(5u32).pow(57) / 2u32); // (5^57 - 1) / 2
    // 10^40 symbols, but the box and end come from the memoized geometry
    // (checked against an independent recursion in geometry.rs).
    let three57 = 3f64.powi(57);
    assert_eq!(st.bbox.map(|b| (b[1], b[3])), Some((-three57, 0.0)));
    assert_eq!(st.end, Some([0.0, -three57]));
    let json = st.to_json();
    assert!(json.contains(&format!("\"length\": \"{want}\"")), "{json}");
    // A skipped geometry (budget 0) is still written as null.
    let skipped = stats_with_budget(&sys(TREE1), 57, &Limits::default(), 0).unwrap();
    assert!(skipped.to_json().contains("\"bbox\": null, \"end\": null"));
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-6
}

#[test]
fn koch_snowflake_segments_end_and_box() {
    // 3 * 4^n segments; the curve closes on itself; the triangle of side
    // 3^n (unit steps) has its apex at the origin's top: height 3^n * sqrt(3)/2.
    let src = "axiom F--F--F\nrule F F+F--F+F\nangle 60\n";
    for n in 0..=5u32 {
        let st = stats(&sys(src), n, &Limits::default()).unwrap();
        assert_eq!(st.segments, big(3 * 4u64.pow(n)));
        let [ex, ey] = st.end.unwrap();
        assert!(close(ex, 0.0) && close(ey, 0.0), "end {ex} {ey}");
        // Depth 0: up 1, then down-right, then back: box x 0..sqrt(3)/2, y -1..0.
        if n == 0 {
            let b = st.bbox.unwrap();
            assert!(close(b[0], 0.0) && close(b[1], -1.0), "{b:?}");
            assert!(close(b[2], 3f64.sqrt() / 2.0) && close(b[3], 0.0), "{b:?}");
        }
    }
    // Heading after the word: every `F+F--F+F` turns 0, the axiom -4 * 60:
    // 90 - 240 = -150 = 210 degrees. Check with one extra F at the end.
    let src = "axiom F--F--FA\nrule F F+F--F+F\nrule A F\nangle 60\n";
    let segs = segments(src, 3, Dfs);
    let last = segs.last().unwrap();
    let (dx, dy) = (last.to.x - last.from.x, last.to.y - last.from.y);
    let a210 = 210f64.to_radians();
    let ok = close(dx, libm::cos(a210)) && close(dy, -libm::sin(a210));
    assert!(ok, "{dx} {dy}");
}

#[test]
fn sierpinski_arrowhead_counts() {
    for (axiom, extra) in [("X", 0i64), ("YF", 1)] {
        let src = format!("axiom {axiom}\nrule X YF+XF+Y\nrule Y XF-YF-X\nangle 60\n");
        for n in 0..=9u32 {
            let st = stats(&sys(&src), n, &Limits::default()).unwrap();
            let count = big((3i64.pow(n) - 1 + extra) as u64);
            assert_eq!(st.segments, count, "{axiom} {n}");
            if n <= 6 {
                assert_eq!(segments(&src, n, Dfs).len() as i64, 3i64.pow(n) - 1 + extra);
            }
        }
    }
}

#[test]
fn bfs_refuses_over_the_word_budget() {
    let limits = limits_with(|l| l.max_word = 1000);
    let s = sys(TREE1);
    let mut rec = Recorder::default();
    // Depth 4: 1561 symbols > 1000.
    let err = draw_into(&s, 4, Bfs, &limits, &mut rec, &mut NoProgress).unwrap_err();
    let word = limit_kind(Bound::Word, Some("bfs word at level 4"), "1561", 1000);
    assert_eq!(err.first_kind(), Some(&word));
    assert!(err.0[0].help_text().unwrap().contains("--max-word"));
    assert!(rec.segments.is_empty());
    // dfs holds no word: fine.
    draw_into(&s, 4, Dfs, &limits, &mut rec, &mut NoProgress).unwrap();
    assert_eq!(rec.segments.len(), 625);
    // Depth 57 with bfs: refused with the exact length, no attempt to allocate.
    let limits = Limits::default();
    let err = draw_into(&s, 57, Bfs, &limits, &mut rec, &mut NoProgress).unwrap_err();
    let ErrorKind::Limit { value, .. } = err.first_kind().unwrap() else {
        panic!("{err}")
    };
    let wanted = ((BigUint::from(5u32).pow(58) - 3u32) / 2u32).to_string();
    assert_eq!(*value, wanted);
}

#[test]
fn both_strategies_refuse_over_max_symbols_and_max_depth() {
    let limits = limits_with(|l| (l.max_symbols, l.max_depth) = (311, 20));
    let s = sys(TREE1);
    for strategy in [Dfs, Bfs] {
        let mut rec = Recorder::default();
        assert!(draw_into(&s, 3, strategy, &limits, &mut rec, &mut NoProgress).is_ok());
        let err = draw_into(&s, 4, strategy, &limits, &mut rec, &mut NoProgress).unwrap_err();
        let limit =
            matches!(err.first_kind(), Some(ErrorKind::Limit { value, .. }) if value == "1561");
        assert!(limit, "{err}");
        assert!(err.0[0].help_text().unwrap().contains("--max-symbols"));
        let err = draw_into(&s, 21, strategy, &limits, &mut rec, &mut NoProgress).unwrap_err();
        assert!(err.0[0].help_text().unwrap().contains("--max-depth"));
        let mut out = Vec::new();
        assert!(expand(&s, 4, strategy, &limits, &mut out, &mut NoProgress).is_err());
        assert!(out.is_empty());
    }
    let e = stats(&s, 21, &limits).unwrap_err();
    assert!(matches!(e.first_kind(), Some(ErrorKind::Limit { .. })));
}

#[test]
fn stats_json_shape() {
    // F+F at 90: length 3, box x -1..0, y -1..0, ends at (-1, -1).
    let st = stats(&sys("axiom F+F\nangle 90\n"), 0, &Limits::default()).unwrap();
    let json = "{\"length\": \"3\", \"segments\": \"2\", \
         \"bbox\": [-1.000000, -1.000000, 0.000000, 0.000000], \
         \"end\": [-1.000000, -1.000000], \
         \"symbols\": {\"+\": \"1\", \"F\": \"2\"}}";
    assert_eq!(st.to_json(), json);
    let v: serde_json::Value = serde_json::from_str(&st.to_json()).unwrap();
    assert_eq!(v["length"], "3");
    assert!(st.to_text().contains("length    3"));
}

#[test]
fn broken_pipe_has_its_own_kind() {
    let mut closed = crate::render::Failing(|| std::io::ErrorKind::BrokenPipe.into());
    let (tree, limits) = (sys(TREE1), Limits::default());
    let err = expand(&tree, 8, Dfs, &limits, &mut closed, &mut NoProgress).unwrap_err();
    assert_eq!(err.first_kind(), Some(&ErrorKind::BrokenPipe));
}

// -------------------------------------------------------- dfs == bfs (prop) --

/// A random word over `alphabet` with balanced brackets (as the parser
/// requires of successors).
pub fn word(
    alphabet: &'static [char],
    max: usize,
) -> impl proptest::strategy::Strategy<Value = String> {
    proptest::collection::vec((0..alphabet.len() + 2, any::<bool>()), 0..max).prop_map(move |v| {
        let mut out = String::new();
        let mut open = 0;
        for (i, _) in v {
            if i == alphabet.len() {
                out.push('[');
                open += 1;
            } else if i == alphabet.len() + 1 {
                if open > 0 {
                    out.push(']');
                    open -= 1;
                }
            } else {
                out.push(alphabet[i]);
            }
        }
        out.extend(std::iter::repeat_n(']', open));
        out
    })
}

pub const ALPHABET: &[char] = &['F', 'F', 'f', '+', '-', '|', 'A', 'B', 'X'];

/// A system of random words: the axiom (`F` if empty) and the rules of
/// `F A B +` that are not empty, in that order.
pub fn source(axiom: String, rules: &[String], angle: f64, heading: f64) -> String {
    let axiom = if axiom.is_empty() { "F" } else { &axiom };
    let mut src = format!("axiom {axiom}\nangle {angle}\nheading {heading}\n");
    for (pred, succ) in ['F', 'A', 'B', '+'].iter().zip(rules) {
        if !succ.is_empty() {
            src.push_str(&format!("rule {pred} -> {succ}\n"));
        }
    }
    src
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn dfs_and_bfs_draw_identical_segments(
        axiom in word(ALPHABET, 8),
        rules in proptest::collection::vec(word(ALPHABET, 9), 4),
        angle in prop_oneof![Just(90.0), Just(60.0), Just(25.7), -400.0..400.0f64],
        heading in prop_oneof![Just(90.0), Just(0.0), Just(180.0), -720.0..720.0f64],
        depth in 0u32..=5,
    ) {
        let src = source(axiom, &rules, angle, heading);
        let dfs = segments(&src, depth, Dfs);
        let bfs = segments(&src, depth, Bfs);
        prop_assert_eq!(&dfs, &bfs, "{}", src);
        prop_assert_eq!(expanded(&src, depth, Dfs), expanded(&src, depth, Bfs));
    }
}

#[test]
fn every_example_parses_and_draws_the_same_both_ways() {
    let (mut seen, mut three) = (0, 0);
    for path in crate::support::files_with("examples", "lsys") {
        let src = std::fs::read_to_string(&path).unwrap();
        let s = parse(&src, &Limits::default()).unwrap_or_else(|e| panic!("{path:?}: {e}"));
        let depth = s.generations.expect("examples say their depth").min(4);
        let lim = Limits::default();
        if s.is_3d() {
            // 3D (docs/3d.md): the same segments both ways, in 3D.
            use stlc::interpret::lsys::lsys3::draw3;
            let (mut a, mut b) = (Vec::new(), Vec::new());
            draw3(&s, depth, Dfs, &lim, &mut |x| a.push(x), &mut NoProgress).unwrap();
            draw3(&s, depth, Bfs, &lim, &mut |x| b.push(x), &mut NoProgress).unwrap();
            assert!(!a.is_empty(), "{path:?}");
            assert_eq!(a, b, "{path:?}");
            three += 1;
            continue;
        }
        let (mut a, mut b) = (Recorder::default(), Recorder::default());
        draw_into(&s, depth, Dfs, &lim, &mut a, &mut NoProgress).unwrap();
        draw_into(&s, depth, Bfs, &lim, &mut b, &mut NoProgress).unwrap();
        assert!(!a.segments.is_empty(), "{path:?}");
        assert_eq!(a, b, "{path:?}");
        seen += 1;
    }
    // 11 classic 2D and 2 classic 3D systems; the parametric ones of
    // issue 32: ABOP 1.31 a-e, 1.35 and param-willow (2D), 2.6, 2.7 and
    // 2.8 a-d (3D); issue 33's ABOP 1.26 (3D, leaves and flowers), 5.5a
    // (2D, a leaf), 3.2 (3D, leaves and a flower that grow) and
    // plant3d-bare (3D, the skeleton plant3d had been).
    assert_eq!((seen, three), (19, 17));
}

#[test]
fn hilbert_and_stl_fig4_counts() {
    // Hilbert: 4^n - 1 segments (each level: 4 copies joined by 3 F).
    let src = crate::support::example_text("hilbert.lsys");
    for n in 1..=7u32 {
        let st = stats(&sys(&src), n, &Limits::default()).unwrap();
        assert_eq!(st.segments, big(4u64.pow(n) - 1));
        // The curve fills a (2^n - 1) square.
        let b = st.bbox.unwrap();
        let side = f64::from(2u32.pow(n) - 1);
        let ok = close(b[2] - b[0], side) && close(b[3] - b[1], side);
        assert!(ok, "{n} {b:?}");
    }
    // 003 Fig. 4 at depth 1: F[-F]F[+F]F, 30 degrees, by hand.
    let segs = segments("axiom F\nrule F F[-F]F[+F]F\nangle 30\n", 1, Dfs);
    assert_eq!(segs.len(), 5);
    let (s30, c30) = (0.5, 3f64.sqrt() / 2.0);
    let want = [
        ((0.0, 0.0), (0.0, -1.0)),
        ((0.0, -1.0), (s30, -1.0 - c30)), // right branch leans right
        ((0.0, -1.0), (0.0, -2.0)),
        ((0.0, -2.0), (-s30, -2.0 - c30)),
        ((0.0, -2.0), (0.0, -3.0)),
    ];
    for (seg, (f, t)) in segs.iter().zip(want) {
        assert!(close(seg.from.x, f.0) && close(seg.from.y, f.1), "{seg:?}");
        assert!(close(seg.to.x, t.0) && close(seg.to.y, t.1), "{seg:?}");
    }
}

#[test]
fn heading_defaults_to_up_and_is_checked_like_any_number() {
    assert_eq!(sys("axiom F\nangle 90\n").heading, 90.0);
    assert_eq!(sys("axiom F\nangle 90\nheading -45\n").heading, -45.0);
    let src = "axiom F\nangle 90\nheading north\nheading 0\n";
    let e = errors(src, &Limits::default());
    // `north`, after "axiom F\nangle 90\nheading "
    let text = "north".into();
    assert_eq!(e[0], (Lsys(MalformedNumber { text }), 25..30));
    assert_eq!(e[1].0, Lsys(DuplicateKey { key: "heading" }));
}
