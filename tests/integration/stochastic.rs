//! Stochastic `.lsys` rules (section 9 of the language notes): choices by
//! seed and place, dfs equal to bfs, the `seed` key and `--seed`, `stats`
//! counted or expected, diagnostics.

use proptest::prelude::*;
use stlc::choice::{Alternatives, Key};
use stlc::diag::ErrorKind::{self, Lsys, Rule};
use stlc::diag::LsysError::{DuplicateProduction, NotWholeNumber, Param, UnreadableProbability};
use stlc::diag::RuleError::{BadProbability, MissingProbability, ProbabilitySum};
use stlc::interpret::Derivation::{self, Bfs, Dfs};
use stlc::interpret::expected::{StochasticStats, stochastic_stats};
use stlc::limits::Limits;
use stlc::model::lsys::LSystem;
use stlc::syntax::lsys::parse;

use crate::lsys::{expanded_of, segments_of as segments, sys};
use crate::support::stlc_stdout as render;
use crate::support::{limits_with, manifest_path, outcome, stlc_line, stlc_piped};

fn word(s: &LSystem, depth: u32, strategy: Derivation) -> String {
    expanded_of(s, depth, strategy).trim_end().to_string()
}

/// Fig. 1.27 with `seed`.
fn fig_1_27(seed: u64) -> LSystem {
    let mut s = sys(FIG_1_27);
    s.seed = seed;
    s
}

/// The expected stats of `s` at `depth`, over a budget of 10 symbols.
fn expected(s: &LSystem, depth: u32) -> stlc::interpret::expected::Expected {
    let tiny = limits_with(|l| l.max_symbols = 10);
    let StochasticStats::Expected(e) = stochastic_stats(s, depth, &tiny).unwrap() else {
        panic!("over the budget, the values are expected");
    };
    e
}

const FIG_1_27: &str = "axiom F\nangle 25.7\n\
    rule F (0.34) -> F[+F]F[-F]F\nrule F (0.33) -> F[+F]F\nrule F (0.33) -> F[-F]F\n";

/// The documented key function: the axiom's `i`-th symbol has key
/// `Key::root(seed).child(i)`, so at depth 1 the `i`-th successor is the
/// table's pick for that key, for a long axiom of `A`s.
#[test]
fn the_choice_is_the_documented_function_of_seed_and_place() {
    let n = 500;
    let src = format!(
        "axiom {}\nangle 90\nrule A (0.5) -> x\nrule A (0.3) -> y\nrule A (0.2) -> z\nseed 11\n",
        "A".repeat(n)
    );
    let got = word(&sys(&src), 1, Dfs);
    let table = Alternatives::new(&[0.5, 0.3, 0.2]).unwrap();
    let want: String = (0..n as u64)
        .map(|i| ['x', 'y', 'z'][table.pick(Key::root(11).child(i))])
        .collect();
    assert_eq!(got, want);
}

/// Over 3000 occurrences the choices follow the probabilities (each count
/// within 4 standard deviations of `n p`), at depth 1 and, through the
/// keys of successors, at depth 2.
#[test]
fn choices_follow_the_probabilities() {
    let n = 3000usize;
    for (axiom, depth) in [("A".repeat(n), 1), ("B".repeat(n / 3), 2)] {
        let src = format!(
            "axiom {axiom}\nangle 90\nrule B -> AAA\n\
             rule A (0.6) -> x\nrule A (0.3) -> y\nrule A (0.1) -> z\n"
        );
        let w = word(&sys(&src), depth, Bfs);
        assert_eq!(w.len(), n);
        for (c, p) in [('x', 0.6), ('y', 0.3), ('z', 0.1)] {
            let k = w.chars().filter(|&x| x == c).count() as f64;
            let (mean, sd) = (n as f64 * p, (n as f64 * p * (1.0 - p)).sqrt());
            assert!((k - mean).abs() < 4.0 * sd, "{c}: {k} vs {mean} ± {sd}");
        }
    }
}

/// A stochastic system made of random rules over `A B F + - [ ]`.
fn arb_system() -> impl Strategy<Value = String> {
    let succ =
        proptest::string::string_regex("[ABF+\\-]{0,4}(\\[[ABF+\\-]{1,3}\\])?[ABF]{0,2}").unwrap();
    (
        proptest::collection::vec(succ, 2..5),
        proptest::collection::vec(1u32..10, 2..5),
        "[AB]{1,3}",
        0u64..1000,
    )
        .prop_map(|(succs, weights, axiom, seed)| {
            let k = succs.len().min(weights.len());
            let total: u32 = weights[..k].iter().sum();
            let mut src = format!("axiom {axiom}\nangle 30\nseed {seed}\nrule B -> A[+B]F\n");
            // Probabilities that sum to 1 exactly: the last takes the rest.
            let mut acc = 0.0;
            for i in 0..k {
                let p = if i + 1 == k {
                    1.0 - acc
                } else {
                    f64::from(weights[i]) / f64::from(total)
                };
                acc += p;
                src.push_str(&format!("rule A ({p}) -> {}\n", succs[i]));
            }
            src
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// dfs and bfs derive the same word and draw the same segments.
    #[test]
    fn dfs_and_bfs_agree_on_stochastic_systems(src in arb_system(), depth in 0u32..6) {
        let s = sys(&src);
        prop_assert_eq!(word(&s, depth, Dfs), word(&s, depth, Bfs));
        prop_assert_eq!(segments(&s, depth, Dfs), segments(&s, depth, Bfs));
    }
}

/// Same seed, same bytes; another seed, another plant; `--seed` overrides
/// the file's `seed` key; `--exact` (no level of detail) draws the same.
#[test]
fn the_seed_selects_the_plant() {
    let file = manifest_path("examples/abop-1.27.lsys");
    let f = file.to_str().unwrap();
    let png = |extra: &str| stlc_piped(&format!("render {f} -o - --size 120x120 {extra}"), "");
    let one = png("--seed 1");
    assert_eq!(one, png("--seed 1"));
    assert_ne!(one, png("--seed 2"));
    assert_eq!(one, png("--seed 1 --exact"));
    assert_eq!(one, png("--seed 1 --strategy bfs"));
    // The seed key, and the flag over it.
    let dir = tempfile::tempdir().unwrap();
    let keyed = dir.path().join("keyed.lsys");
    std::fs::write(&keyed, format!("{FIG_1_27}generations 4\nseed 5\n")).unwrap();
    let k = keyed.to_str().unwrap();
    let five = render(&["expand", k]);
    assert_eq!(five, render(&["expand", k, "--seed", "5"]));
    assert_ne!(five, render(&["expand", k, "--seed", "6"]));
    assert_eq!(five, render(&["expand", k, "--strategy", "bfs"]));
}

/// A deterministic system derives the same word whatever the seed.
#[test]
fn a_deterministic_system_ignores_the_seed() {
    let mut s = sys("axiom F\nangle 25.7\nrule F -> F[+F]F[-F]F\n");
    let w = word(&s, 3, Dfs);
    s.seed = 12345;
    assert_eq!(w, word(&s, 3, Dfs));
}

// ------------------------------------------------------------ stats

/// Counted stats are this seed's word: the counts of the expanded word.
#[test]
fn counted_stats_are_the_words_counts() {
    let s = sys(FIG_1_27);
    let StochasticStats::Counted(st) = stochastic_stats(&s, 4, &Limits::default()).unwrap() else {
        panic!("a short word is counted");
    };
    let w = word(&s, 4, Dfs);
    assert_eq!(st.length, w.len().into());
    for (c, n) in &st.symbols {
        assert_eq!(*n, w.chars().filter(|x| x == c).count().into(), "{c}");
    }
    assert_eq!(st.seed, Some(0));
}

/// Over the budget the expected values come from the mean production
/// matrix: for Fig. 1.27 each F becomes 0.34 x 5 + 0.66 x 3 = 3.68 F on
/// average, so depth r has 3.68^r F expected; `[` follows 0.34 x 2 + 0.66
/// per F of the level above. A second method, the mean over 400 seeds at
/// depth 3, agrees within 4 standard errors.
#[test]
fn expected_stats_follow_the_mean_matrix() {
    let e = expected(&sys(FIG_1_27), 12);
    let f12 = 3.68f64.powi(12);
    let segments = e.segments;
    assert!((segments - f12).abs() < 1e-6 * f12, "{segments} vs {f12}");
    let brackets: f64 = (0..12).map(|r| 3.68f64.powi(r) * 1.34).sum();
    assert!((e.symbols[&'['] - brackets).abs() < 1e-6 * brackets);
    let json = StochasticStats::Expected(e.clone()).to_json();
    assert!(json.starts_with("{\"expected\": true, "), "{json}");
    assert!(StochasticStats::Expected(e).to_text().contains("expected"));
    // Mean over seeds at depth 3.
    let n = 400;
    let counts: Vec<f64> = (0..n)
        .map(|seed| word(&fig_1_27(seed), 3, Dfs).matches('F').count() as f64)
        .collect();
    let mean = counts.iter().sum::<f64>() / n as f64;
    let var = counts.iter().map(|c| (c - mean).powi(2)).sum::<f64>() / (n as f64 - 1.0);
    let se = (var / n as f64).sqrt();
    let want = 3.68f64.powi(3);
    assert!((mean - want).abs() < 4.0 * se, "{mean} vs {want} ± {se}");
}

/// The shortest and longest word lengths of Fig. 1.27 at depth `r`, by
/// the closed forms of the recurrences L(r) = 3 L(r-1) + 3 and H(r) =
/// 5 H(r-1) + 6 (see below): L(r) = (5 x 3^r - 3) / 2, H(r) = (5 x 5^r -
/// 3) / 2.
fn fig_1_27_bounds(r: u32) -> (num_bigint::BigUint, num_bigint::BigUint) {
    use num_bigint::BigUint;
    let closed = |b: u32| (BigUint::from(5u32) * BigUint::from(b).pow(r) - 3u32) / 2u32;
    (closed(3), closed(5))
}

/// Past `u64` the shortest and longest words any seed can derive are
/// still exact in `stats`, text and JSON (they used to saturate, and
/// JSON wrote 2^64 - 1 as if it were the length).
#[test]
fn expected_stats_give_exact_bounds_at_any_depth() {
    assert_eq!(fig_1_27_bounds(3).0, 66u32.into());
    assert_eq!(fig_1_27_bounds(3).1, 311u32.into());
    let s = sys(FIG_1_27);
    for depth in [3, 40, 100, 1000] {
        let e = expected(&s, depth);
        let (lo, hi) = fig_1_27_bounds(depth);
        assert_eq!(e.bounds, (lo.clone(), hi.clone()), "depth {depth}");
        let json = StochasticStats::Expected(e.clone()).to_json();
        let bounds = format!("\"bounds\": [\"{lo}\", \"{hi}\"]");
        assert!(json.contains(&bounds), "{json}");
        let text = StochasticStats::Expected(e).to_text();
        assert!(text.contains(&format!("any seed: {lo} .. {hi}")), "{text}");
    }
}

// ------------------------------------------------------------ errors

/// The shortest word of Fig. 1.27 takes `F[+F]F` (six symbols, three `F`)
/// everywhere: L(d) = 3 + 3 L(d-1), L(0) = 1, so L(3) = 66; the longest
/// takes `F[+F]F[-F]F` (eleven, five `F`): H(d) = 6 + 5 H(d-1), H(3) =
/// 311. Under a limit below 66 no seed's word
/// fits, and the refusal comes before a symbol is derived (nothing is
/// written), for dfs and bfs; past `u64` (depth 100) the message gives the
/// exact bound, L(100) from the closed form below.
#[test]
fn a_depth_no_choice_can_fit_is_refused_at_once() {
    let s = sys(FIG_1_27);
    let refuse = |depth: u32, limit: u64, strategy: Derivation| {
        let mut out = Vec::new();
        let e = expand_within(&s, depth, strategy, limit, &mut out).unwrap_err();
        assert!(out.is_empty(), "wrote {} bytes first", out.len());
        let ErrorKind::Limit {
            value, limit: l, ..
        } = &e.0[0].kind
        else {
            panic!("{:?}", e.0[0].kind)
        };
        // A stochastic expansion gets a tenth of --max-symbols.
        assert_eq!(*l, limit / 10);
        value.clone()
    };
    for strategy in [Dfs, Bfs] {
        assert_eq!(refuse(3, 650, strategy), "at least 66");
        let wanted = format!("at least {}", fig_1_27_bounds(100).0);
        assert_eq!(refuse(100, 1_000_000, strategy), wanted);
    }
    // Under a limit between the bounds some seeds fit and some do not: a
    // word over it is refused before anything is written all the same.
    let mut over = 0;
    for seed in 0..20 {
        // A tenth of 1,200: 120 symbols.
        let mut out = Vec::new();
        if expand_within(&fig_1_27(seed), 3, Dfs, 1_200, &mut out).is_err() {
            over += 1;
            let n = out.len();
            assert!(n == 0, "seed {seed}: wrote {n} bytes first");
        } else {
            assert!(out.len() <= 121, "seed {seed}: {}", out.len());
        }
    }
    assert!(over > 0 && over < 20, "{over} of 20 seeds over 120 symbols");
    // Every seed's word lies within the bounds, and they vary.
    let lens: Vec<usize> = (0..50)
        .map(|seed| word(&fig_1_27(seed), 3, Dfs).len())
        .collect();
    assert!(lens.iter().all(|l| (66..=311).contains(l)), "{lens:?}");
    assert!(lens.iter().any(|&l| l != lens[0]), "{lens:?}");
}

/// `s` expanded to `depth` into `out` with `--max-symbols max_symbols`.
fn expand_within(
    s: &LSystem,
    depth: u32,
    strategy: Derivation,
    max_symbols: u64,
    out: &mut Vec<u8>,
) -> Result<(), stlc::Diagnostics> {
    let limits = limits_with(|l| l.max_symbols = max_symbols);
    let progress = &mut stlc::progress::NoProgress;
    stlc::interpret::lsys::expand(s, depth, strategy, &limits, out, progress)
}

fn first_error(src: &str) -> (ErrorKind, std::ops::Range<usize>) {
    let e = parse(src, &Limits::default()).unwrap_err();
    let d = e.iter().next().unwrap();
    assert!(d.help.is_some());
    (d.kind.clone(), d.span.clone().unwrap())
}

#[test]
fn probabilities_are_checked() {
    let src = "axiom F\nangle 30\nrule F (0.5) -> F+F\nrule F (0.4) -> F-F\n";
    let (kind, span) = first_error(src);
    assert!(
        matches!(&kind, Rule(ProbabilitySum { name, sum }) if name == "F" && (sum - 0.9).abs() < 1e-12),
        "{kind:?}"
    );
    assert_eq!(&src[span], "rule F (0.5) -> F+F");
    assert!(kind.to_string().contains("sum to 0.9"), "{kind}");

    let src = "axiom F\nangle 30\nrule F (1) -> F+F\nrule F -> F-F\n";
    let (kind, span) = first_error(src);
    assert!(matches!(&kind, Rule(MissingProbability { name }) if name == "F"));
    assert_eq!(&src[span], "rule F -> F-F");

    // Only that: the sum of the rules that have one (0.5) is no news.
    let src = "axiom F\nangle 30\nrule F (0.5) -> F+F\nrule F -> F-F\n";
    let e = parse(src, &Limits::default()).unwrap_err();
    assert_eq!(e.0.len(), 1, "{e}");
    assert!(matches!(&e.0[0].kind, Rule(MissingProbability { .. })));
    // One rule with a probability other than 1: it needs none.
    let src = "axiom F\nangle 30\nrule F (0.5) -> F+F\n";
    let e = parse(src, &Limits::default()).unwrap_err();
    assert!(matches!(&e.0[0].kind, Rule(ProbabilitySum { .. })));
    let help = e.0[0].help_text().unwrap();
    let holds = help.contains("needs no probability: write `rule F -> ...`");
    assert!(holds, "{help}");

    let src = "axiom F\nangle 30\nrule F (1) -> F+F\nrule F (0) -> F-F\n";
    let (kind, span) = first_error(src);
    assert!(matches!(&kind, Rule(BadProbability { value, .. }) if *value == 0.0));
    assert_eq!(&src[span], "rule F (0) -> F-F");

    let src = "axiom F\nangle 30\nrule F -> F+F\nrule F -> F-F\n";
    let duplicate = Lsys(DuplicateProduction { symbol: 'F' });
    assert_eq!(first_error(src).0, duplicate);

    let src = "axiom F\nangle 30\nrule F (1) -> F+F\nrule F (1e400) -> F-F\n";
    let (kind, _) = first_error(src);
    assert!(matches!(&kind, Rule(BadProbability { value, .. }) if value.is_infinite()));
    let holds = kind.to_string().contains("not a finite number above 0");
    assert!(holds, "{kind}");

    // A parenthesis where the probability goes that is no decimal number
    // would otherwise start the successor `(1/3)->F+F`.
    for (line, text) in [
        ("rule F (1/3) -> F+F", "(1/3)"),
        ("rule F (50%) = F+F", "(50%)"),
        ("rule F (nan)->F+F", "(nan)"),
    ] {
        let src = format!("axiom F\nangle 30\n{line}\n");
        let (kind, span) = first_error(&src);
        let unreadable = Lsys(UnreadableProbability { text: text.into() });
        assert_eq!(kind, unreadable, "{line}");
        assert_eq!(&src[span], text);
    }
    // `F(0.5)` in a rule head names F's parameters (issue 32, docs/lsys.md):
    // a number there is no name, and the help says where a probability goes.
    let src = "axiom F\nangle 30\nrule F(0.5) -> F+F\n";
    let e = parse(src, &Limits::default()).unwrap_err();
    let d = e.iter().next().unwrap();
    assert!(matches!(d.kind, Lsys(Param { .. })));
    assert_eq!(d.kind.to_string(), "`0.5` is not a formal parameter");
    assert_eq!(&src[d.span.clone().unwrap()], "0.5");
    let help = d.help_text().unwrap();
    assert!(help.contains("rule F (0.5)"), "{help}");

    let src = "axiom F\nangle 30\nseed -3\n";
    let (kind, span) = first_error(src);
    let whole = matches!(kind, Lsys(NotWholeNumber { key: "seed", .. }));
    assert!(whole, "{kind:?}");
    assert_eq!(&src[span], "-3");
}

/// The forms of a stochastic rule: with or without an arrow, a rule of one
/// alternative with `(1)`, the largest seed; `(` stays a symbol elsewhere.
#[test]
fn stochastic_rule_forms() {
    let s =
        sys("axiom F\nangle 30\nrule F (0.5) F+F\nrule F (0.5) = F-F\nseed 18446744073709551615\n");
    assert_eq!(s.rules[&'F'].len(), 2);
    assert_eq!(s.seed, u64::MAX);
    let s = sys("axiom F\nangle 30\nrule F (1) -> FF\n");
    assert!(s.is_stochastic());
    assert_eq!(word(&s, 2, Dfs), "FFFF");
    let s = sys("axiom F\nangle 30\nrule F (F)\n");
    assert!(!s.is_stochastic());
    assert_eq!(word(&s, 1, Dfs), "(F)");
    // Without an arrow after it, a parenthesis is symbols of the successor.
    let s = sys("axiom F\nangle 30\nrule F (x)F\n");
    assert_eq!(word(&s, 1, Dfs), "(x)F");
}

/// A stochastic derivation may visit a tenth of `--max-symbols` (each of
/// its symbols costs about ten of a deterministic one's), so the limit
/// means about the same time: a word whose shortest choice is over the
/// tenth is refused at once, one that grows past it while deriving stops
/// there, and both say why the limit is a tenth.
#[test]
fn a_stochastic_derivation_gets_a_tenth_of_the_symbol_limit() {
    let dir = tempfile::tempdir().unwrap();
    let run = |text: &str, flags: &str| {
        let png = dir.path().join("s.png");
        let line = format!("render - --from lsys -o {} {flags}", png.display());
        let (code, _, err) = outcome(stlc_line(&line).write_stdin(text));
        (Some(code), err)
    };
    // Every choice doubles: 2^20 symbols, over a tenth of 10^6 at once.
    let doubling = "generations 20\naxiom X\nangle 30\nrule X (0.5) -> XX\nrule X (0.5) -> XX\n";
    let (code, err) = run(doubling, "--max-symbols 1000000");
    assert_eq!(code, Some(1), "{err}");
    let says = |words: &str| err.contains(words);
    let holds = says("at least 1048576 exceeds the limit of 100000");
    assert!(holds, "{err}");
    let holds = says("a tenth of --max-symbols (100000 of 1000000)");
    assert!(holds, "{err}");
    // Twenty times the limit lets it through: 2^20 < 2 x 10^6.
    let (code, err) = run(doubling, "--max-symbols 20000000");
    assert_eq!(code, Some(0), "{err}");
    // The shortest word is one symbol, the longest 2^30: counted while
    // deriving, it stops at the tenth.
    let growing =
        "generations 30\naxiom X\nangle 30\nrule X (0.5) -> X\nrule X (0.5) -> XX\nseed 3\n";
    let (code, err) = run(growing, "--max-symbols 1000000");
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains("more than 100000"), "{err}");
    assert!(err.contains("a tenth of --max-symbols"), "{err}");
}

/// A tiny probability is never printed as 0: `check` writes it in
/// scientific notation where six decimals would show nothing.
#[test]
fn a_tiny_probability_is_not_printed_as_zero() {
    let text = "generations 2\naxiom F\nangle 30\nrule F (1e-300) -> F[+F]\nrule F (1) -> F[-F]\n";
    let out = stlc_piped("check - --from lsys", text);
    let text = String::from_utf8_lossy(&out);
    assert!(text.contains("(probability 1e-300)"), "{text}");
    assert!(text.contains("(probability 1)"), "{text}");
    assert!(!text.contains("probability 0"), "{text}");
}

/// An `--exact` SVG (a line a segment) that even a stochastic system's
/// fewest segments overflow is refused before any derivation: abop-1.27
/// (each F becomes 5, 3 or 3 F) draws at least 3^16 = 43,046,721 segments
/// at depth 16, over the 10^7 an SVG may hold; at depth 14 (at least
/// 4,782,969) it is not refused on that ground before deriving. (Without
/// `--exact` the SVG is merged and its lines are counted as written.)
#[test]
fn an_svg_the_fewest_segments_overflow_is_refused_before_deriving() {
    let dir = tempfile::tempdir().unwrap();
    let fig = manifest_path("examples/abop-1.27.lsys");
    let render = |flags: &str, out: &str| {
        let out = dir.path().join(out);
        let (fig, out) = (fig.display(), out.display());
        let line = format!("render {fig} --exact {flags} -o {out}");
        outcome(&mut stlc_line(&line))
    };
    let (code, _, err) = render("--depth 16", "a.svg");
    assert_eq!(code, 1);
    let refused = err.contains("segments in the SVG: more than 10000000");
    assert!(refused, "{err}");
    assert!(!dir.path().join("a.svg").exists());
    // A smaller limit refuses a smaller depth the same way: 3^6 = 729.
    let (code, _, _) = render("--depth 6 --max-svg-segments 700", "b.svg");
    assert_eq!(code, 1);
    // 3^5 = 243 at the fewest: derived, then counted (this seed draws 491).
    let (code, _, err) = render("--depth 5 --max-svg-segments 700", "c.svg");
    assert_eq!(code, 0, "{err}");
}
