//! Variation in Outline Descriptions (section 9 of the language notes):
//! rules with alternatives chosen by seed and place, the BED that records
//! the choices, and forests of several roots in one outline.

use stlc::choice::{Alternatives, Key};
use stlc::diag::ErrorKind::{self, Grow, Rule, Stl};
use stlc::diag::GrowError::SharedRoot;
use stlc::diag::RuleError::*;
use stlc::diag::StlError::SeedsPerRoot;
use stlc::grow::{GrowOptions, Grown, GrowthOrder, grow, grow_traced};
use stlc::model::{Description, Format, SeedItem, Slot};
use stlc::progress::NoProgress;
use stlc::syntax::stl::parse;
use stlc::{Diagnostics, Limits};

use crate::grow::span_of;
use crate::support::{example_text, manifest_path, od, opts, outcome, stlc_line};

fn errors(text: &str, format: Format) -> Diagnostics {
    let parsed = parse(text, format, &Limits::default());
    parsed.expect_err(text)
}

/// The first error of `text` read as `format`: its kind and span.
fn first(text: &str, format: Format) -> (ErrorKind, Option<std::ops::Range<usize>>) {
    let d = errors(text, format).0.swap_remove(0);
    (d.kind, d.span)
}

fn grown(d: &Description, growth: GrowthOrder, seed: u64) -> Grown {
    let mut o = opts(growth);
    (o.seed, o.max_stems_explicit) = (seed, true);
    grow(d, &o, &mut NoProgress).unwrap_or_else(|e| panic!("{e}"))
}

/// The BED that grew, as written.
pub fn bed_text(g: &Grown) -> String {
    stlc::bed::write::write(g.bed.description())
}

/// The alternative (1-based) of the term at the first growth point of the
/// first tree's grown seed, `None` if nothing grew there.
fn first_choice(g: &Grown) -> Option<u32> {
    let d = g.bed.description();
    let seed = d.seed.as_ref()?;
    seed.items.iter().find_map(|i| match i {
        SeedItem::Term(t) => Some(d.rule(seed.term(*t).rule()).alternative.as_ref()?.number),
        _ => None,
    })
}

// ------------------------------------------------------------ choices

/// The documented key function decides: the seed's growth point 0 of root
/// 0 has key `Key::root(seed).child(0).child(0)`, and the alternative grown
/// there is the table's pick for it, for every seed tried.
#[test]
fn the_first_choice_is_the_documented_function_of_seed_and_place() {
    let d = od("T (0,0) L=10(0) B=1(0) RULE
        R1 (0.5): [+F] R1 (0.3): [-F] R1 (0.2): [F] SEED [I 1 R1] ENDSEED");
    let table = Alternatives::new(&[0.5, 0.3, 0.2]).unwrap();
    for seed in 0..200u64 {
        let g = grown(&d, GrowthOrder::Bfs, seed);
        let expected = table.pick(Key::root(seed).child(0).child(0)) as u32 + 1;
        assert_eq!(first_choice(&g), Some(expected), "seed {seed}");
    }
}

/// Over thousands of seeds the choices follow the probabilities: each
/// alternative's count lies within 4 standard deviations of `n p`.
#[test]
fn choices_follow_the_probabilities() {
    let d = od("T (0,0) L=10(0) B=1(0) RULE
        R1 (0.6): [+F] R1 (0.3): [-F] R1 (0.1): [F] SEED [I 1 R1] ENDSEED");
    let n = 3000u64;
    let mut counts = [0u64; 3];
    for seed in 0..n {
        let k = first_choice(&grown(&d, GrowthOrder::Bfs, seed)).unwrap();
        counts[k as usize - 1] += 1;
    }
    for (c, p) in counts.iter().zip([0.6, 0.3, 0.1]) {
        let mean = n as f64 * p;
        let sd = (n as f64 * p * (1.0 - p)).sqrt();
        let holds = (*c as f64 - mean).abs() < 4.0 * sd;
        assert!(holds, "{counts:?}: {c} vs {mean} ± {sd}");
    }
}

/// A picked body that does not fit leaves its slot empty: growth never
/// tries another alternative. The long body cannot fit in the box, so the
/// seed's point is empty exactly when the key picks it.
#[test]
fn a_body_that_does_not_fit_is_not_replaced_by_another() {
    let d = od("T (50,95) L=10(0) B=1(0) RULE
        R1 (0.5): [F] R1 (0.5): [FFFFFFFFFFFF] SEED R1 ENDSEED
        LAYOUT (clGreen) Rectangle (0,0), 100, 100 ENDLAYOUT");
    let table = Alternatives::new(&[0.5, 0.5]).unwrap();
    let (mut empty, mut short) = (0, 0);
    for seed in 0..100u64 {
        let g = grown(&d, GrowthOrder::Dfs, seed);
        let pick = table.pick(Key::root(seed).child(0).child(0));
        match first_choice(&g) {
            None => {
                assert_eq!(pick, 1, "seed {seed}: empty but the short body was picked");
                empty += 1;
            }
            Some(k) => {
                assert_eq!((k, pick), (1, 0), "seed {seed}");
                short += 1;
            }
        }
    }
    assert!(empty > 20 && short > 20, "{empty} empty, {short} short");
}

/// Every application chooses anew: a self-resemblant branch of one
/// alternative grows any alternative, and the BED names each one.
#[test]
fn every_application_chooses_and_the_bed_names_the_choice() {
    let d = od("T (0,0) L=10(0) B=1(0) RULE
        R1 (0.5): [+F] R1 (0.5): [-F] SEED [I 6 R1] ENDSEED");
    let g = grown(&d, GrowthOrder::Bfs, 3);
    let text = bed_text(&g);
    let holds = text.contains("R1.1 (0.5): [+F]\nR1.2 (0.5): [-F]\n");
    assert!(holds, "{text}");
    // One chain of six applications; both alternatives occur (the chance
    // that one seed gives six equal choices is 1/32, and seed 3 does not).
    let (ones, twos) = (text.matches("R1.1{").count(), text.matches("R1.2{").count());
    assert_eq!(ones + twos, 6, "{text}");
    assert!(ones > 0 && twos > 0, "{text}");
    // The chain follows the key path root, child(0), child(0), ...
    let table = Alternatives::new(&[0.5, 0.5]).unwrap();
    let mut key = Key::root(3).child(0).child(0);
    let mut expected = Vec::new();
    for _ in 0..6 {
        expected.push(format!("R1.{}", table.pick(key) + 1));
        key = key.child(0);
    }
    let applied = |l: &&str| l.starts_with("R1.") && l.contains('{');
    let found: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(applied)
        .map(|l| &l[..4])
        .collect();
    assert_eq!(found, expected);
}

/// The BED round-trips: read back, it is the same description; and it
/// renders the same picture whatever `--seed` says.
#[test]
fn a_grown_bed_reads_back_and_needs_no_seed() {
    for file in ["alternatives", "grove"] {
        let d = od(&example_text(&format!("{file}.od")));
        let g = grown(&d, GrowthOrder::Bfs, 5);
        let written = bed_text(&g);
        let back = parse(&written, Format::Bed, &Limits::default()).unwrap();
        let holds = back == *g.bed.description();
        assert!(holds, "{file}: the BED reads back differently");
        assert_eq!(stlc::bed::write::write(&back), written);
    }
}

/// Same seed, same bytes; another seed, another tree.
#[test]
fn the_seed_selects_the_tree() {
    let d = od(&example_text("alternatives.od"));
    for g in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        let a = bed_text(&grown(&d, g, 1));
        assert_eq!(a, bed_text(&grown(&d, g, 1)));
        assert_ne!(a, bed_text(&grown(&d, g, 2)));
    }
}

/// A description without alternatives grows the same tree for any seed.
#[test]
fn without_alternatives_the_seed_changes_nothing() {
    let d = od(&example_text("crown.od"));
    let want = bed_text(&grown(&d, GrowthOrder::Bfs, 99));
    assert_eq!(bed_text(&grown(&d, GrowthOrder::Bfs, 0)), want);
}

// ------------------------------------------------------------ diagnostics

const R: &str = "T (0,0) L=1(0) B=1(0) RULE";

#[test]
fn probabilities_must_sum_to_one() {
    let text = &format!("{R} R1 (0.5): [+F] R1 (0.4): [-F]");
    let (kind, span) = first(text, Format::Od);
    let sum = matches!(&kind, Rule(ProbabilitySum { name, sum }) if name == "R1" && (sum - 0.9).abs() < 1e-12);
    assert!(sum, "{kind:?}");
    assert_eq!(span, Some(span_of(text, "R1")));
    assert!(kind.to_string().contains("0.9"), "{kind}");
}

#[test]
fn a_probability_must_be_above_zero() {
    let text = &format!("{R} R1 (1): [+F] R1 (0): [-F]");
    let (kind, span) = first(text, Format::Od);
    assert!(matches!(&kind, Rule(BadProbability { name, value }) if name == "R1" && *value == 0.0));
    let second = text.rfind("R1").unwrap();
    assert_eq!(span, Some(second..second + 2));
}

#[test]
fn every_alternative_needs_a_probability() {
    let text = &format!("{R} R1 (0.5): [+F] R1: [-F]");
    let e = errors(text, Format::Od);
    assert!(matches!(&e.0[0].kind, Rule(MissingProbability { name }) if name == "R1"));
    let second = text.rfind("R1").unwrap();
    assert_eq!(e.0[0].span, Some(second..second + 2));
    // Only that: the sum of the bodies that have one (0.5) is no news.
    assert_eq!(e.0.len(), 1, "{e}");
    // One body with a probability other than 1: it needs none.
    let e = errors(&format!("{R} R1 (0.5): [+F]"), Format::Od);
    assert!(matches!(&e.0[0].kind, Rule(ProbabilitySum { .. })));
    let help = e.0[0].help_text().unwrap();
    let holds = help.contains("one body needs no probability: write `R1: ...`");
    assert!(holds, "{help}");
    // Two bodies without probabilities stay a duplicate.
    let (kind, _) = first(&format!("{R} R1: [+F] R1: [-F]"), Format::Od);
    assert!(matches!(&kind, Rule(DuplicateRule { .. })));
}

/// The canonical writer keeps an OD an OD: alternatives as several bodies
/// of one name (`R1 (0.6): ...`), which read back as the same description;
/// the BED grown from it names them `R1.1`, `R1.2`.
#[test]
fn an_od_with_alternatives_writes_as_an_od() {
    let text = "T\n(50, 90)\nL=10(0) B=1(0) A=30\nRULE\nR1 (0.6): [+F][-F]\nR1 (0.4): [F]\nSEED\nF R1\nENDSEED\nLAYOUT\n(clGreen) Rectangle (0, 0), 100, 100\nENDLAYOUT\n";
    let d = od(text);
    let written = stlc::bed::write::write(&d);
    assert_eq!(written, text.replace("F R1", "F\nR1"));
    assert_eq!(stlc::bed::write::write(&od(&written)), written);
    let g = grown(&d, GrowthOrder::Bfs, 0);
    let bed = bed_text(&g);
    let holds = bed.contains("R1.1 (0.6): [+F][-F]\nR1.2 (0.4): [F]\n");
    assert!(holds, "{bed}");
}

#[test]
fn a_dot_in_an_od_is_refused() {
    // The name's span: at a rule's definition and at a use in the seed.
    for text in [
        format!("{R} R1.1: [+F]"),
        format!("{R} R1 (1): [+F] SEED F R1.1 ENDSEED"),
    ] {
        let (kind, span) = first(&text, Format::Od);
        let dotted = matches!(&kind, Rule(DottedName { name }) if name == "R1.1");
        assert!(dotted, "{text}");
        assert_eq!(span, Some(span_of(&text, "R1.1")), "{text}");
    }
}

#[test]
fn a_bed_names_alternatives_that_exist() {
    let head = format!("{R} R1.1 (0.5): [+F] R1.2 (0.5): [-F] SEED ");
    let text = format!("{head}R1.3{{}} ENDSEED");
    let (name, number) = ("R1".into(), "3".into());
    let unknown = Rule(UnknownAlternative { name, number });
    let want = (unknown, Some(span_of(&text, "R1.3")));
    assert_eq!(first(&text, Format::Bed), want);
    let (kind, _) = first(&format!("{head}R1{{}} ENDSEED"), Format::Bed);
    assert!(matches!(&kind, Rule(AlternativeNotNamed { name, count: 2 }) if name == "R1"));
    let text = format!("{head}R1.2{{}} ENDSEED");
    assert!(parse(&text, Format::Bed, &Limits::default()).is_ok());
}

/// A BED chooses nothing: a probability only annotates a recorded
/// alternative (`R1.1 (0.5)`); on a rule without a number it is an error
/// (it was read as an alternative numbered 0 and written back as `R1.0`).
#[test]
fn a_bed_probability_belongs_to_an_alternative() {
    let text = &format!("{R} R1 (1): [+F][-F] SEED F R1{{,}} ENDSEED");
    let name = "R1".into();
    let without = Rule(ProbabilityWithoutAlternative { name });
    let want = (without, Some(span_of(text, "R1")));
    assert_eq!(first(text, Format::Bed), want);
    // The same line in an OD is a rule of one alternative.
    let d = od(text.replace("R1{,}", "R1").as_str());
    assert_eq!(d.rules[0].alternative.as_ref().map(|a| a.number), Some(1));
}

#[test]
fn a_bed_repeats_only_rules_without_alternatives() {
    // `[I 2 R1]` unrolls R1 at every tip: with alternatives each level
    // would choose, so a BED (which records choices) refuses it, with or
    // without an alternative's number; an OD's repeat is a growth point.
    let head = format!("{R} R1.1 (0.5): [+F] R1.2 (0.5): [-F] R2: [+F] SEED F ");
    for repeat in ["[I 2 R1]", "[I 2 R1.2]"] {
        let text = format!("{head}{repeat} ENDSEED");
        let name = "R1".into();
        let chooses = Rule(RepeatChooses { name, count: 2 });
        let want = (chooses, Some(span_of(&text, repeat)));
        assert_eq!(first(&text, Format::Bed), want, "{repeat}");
    }
    let text = format!("{head}[I 2 R2] ENDSEED");
    assert!(parse(&text, Format::Bed, &Limits::default()).is_ok());
    let od = format!("{R} R1 (0.5): [+F] R1 (0.5): [-F] SEED F [I 2 R1] ENDSEED");
    assert!(parse(&od, Format::Od, &Limits::default()).is_ok());
}

#[test]
fn a_forest_bed_has_one_seed_per_root() {
    let forest = |roots: &str, seeds: usize| {
        let seeds = "SEED F ENDSEED ".repeat(seeds);
        format!("T {roots} L=1(0) B=1(0) RULE R1: [+F] {seeds}")
    };
    let text = forest("(0,0) (10,0)", 3);
    let (kind, _) = first(&text, Format::Bed);
    assert_eq!(kind, Stl(SeedsPerRoot { roots: 2, seeds: 3 }));
    let d = parse(&forest("(0,0) (10,0)", 2), Format::Bed, &Limits::default()).unwrap();
    assert_eq!(d.forest.len(), 1);
    // Fewer SEEDs than roots: an error at the first root without one (it
    // drew one tree where the file names three).
    let text = forest("(0,0) (10,0) (20,0)", 1);
    let few = Stl(SeedsPerRoot { roots: 3, seeds: 1 });
    let want = (few, Some(span_of(&text, "(10,0)")));
    assert_eq!(first(&text, Format::Bed), want);
    let text = forest("(0,0) (10,0) (20,0)", 2);
    assert_eq!(first(&text, Format::Bed).1, Some(span_of(&text, "(20,0)")));
    // No SEED at all: every root grows the default seed.
    let none = forest("(0,0) (10,0)", 0);
    assert!(parse(&none, Format::Bed, &Limits::default()).is_ok());
    let (kind, _) = first(&forest("(0,0)", 2), Format::Od);
    assert_eq!(kind, Stl(SeedsPerRoot { roots: 1, seeds: 2 }));
}

// ------------------------------------------------------------ forests

/// A root on the point of an earlier one is warned about, pointing at both
/// (its tree grows on top of the other's); distinct roots are not, nor is
/// 0 against -0.
#[test]
fn a_root_on_another_roots_point_is_warned_about() {
    let forest = |roots: &str| {
        format!("T {roots} L=5(0) B=1(0) A=30 RULE R1: [+F][-F] SEED F [I 2 R1] ENDSEED")
    };
    let text = &forest("(10, 0) (30, 0) (10, 0) (0, -0) (0, 0)");
    let g = grown(&od(text), GrowthOrder::Bfs, 0);
    let is_shared = |w: &&stlc::Diagnostic| matches!(w.kind, Grow(SharedRoot { .. }));
    let shared: Vec<_> = g.warnings.iter().filter(is_shared).collect();
    assert_eq!(shared.len(), 1, "the first repeat only: {:?}", g.warnings);
    assert_eq!(shared[0].kind, Grow(SharedRoot { root: 3, first: 1 }));
    let third = text.rfind("(10, 0)").unwrap();
    assert_eq!(shared[0].span, Some(third..third + "(10, 0)".len()));
    assert_eq!(shared[0].labels[0].span, span_of(text, "(10, 0)"));
    let apart = forest("(10, 0) (30, 0)");
    assert!(grown(&od(&apart), GrowthOrder::Bfs, 0).warnings.is_empty());
    let w = grown(&od(&forest("(0, -0) (0, 0)")), GrowthOrder::Bfs, 0).warnings;
    assert_eq!(w[0].kind, Grow(SharedRoot { root: 2, first: 1 }));
}

/// `check` counts a forest's roots and shows the first six: all four of
/// the grove; six of ten, then how many more.
#[test]
fn check_lists_a_forests_roots_briefly() {
    let summary = |text: &str| {
        let (opts, od) = (GrowOptions::default(), stlc::syntax::InputKind::Od);
        let loaded = stlc::pipeline::load(text.as_bytes(), od, &opts.limits).unwrap();
        stlc::pipeline::check(&loaded, &opts).unwrap().summary
    };
    let said = summary(&example_text("grove.od"));
    let four = "  roots       4 (a forest): (50, 290) (110, 290) (170, 290) (235, 290)\n";
    assert!(said.contains(four), "{said}");
    let roots: Vec<String> = (0..10).map(|i| format!("({}, 0)", i * 100)).collect();
    let roots = roots.join(" ");
    let ten = format!("T {roots} L=1(0) B=1(0) RULE R1: [+F] SEED F ENDSEED");
    let s = summary(&ten);
    let line = s.lines().find(|l| l.starts_with("  roots")).unwrap();
    let six = "(0, 0) (100, 0) (200, 0) (300, 0) (400, 0) (500, 0)";
    let want = format!("  roots       10 (a forest): {six} ... and 4 more");
    assert_eq!(line, want);
}

/// Two binary trees far apart, three levels each, lengths 15, 10, 5 and
/// branches 90 degrees apart (no collisions: 1 + 2 + 4 applications and
/// 1 + 2 + 4 + 8 stems a tree).
const FAR_APART: &str =
    "F2 (0,0) (1000,0) L=20(5) B=1(0) A=45 RULE R1: [+F][-F] SEED F [I 3 R1] ENDSEED";

/// Which tree each decision of [`FAR_APART`] grew in, in decision order.
fn decision_trees(growth: GrowthOrder) -> Vec<usize> {
    let d = od(FAR_APART);
    let (_, placed) = grow_traced(&d, &opts(growth), &mut NoProgress).unwrap();
    let tree = |s: &stlc::grow::PlacedStem| (s.decision, usize::from(s.from.x > 500.0));
    let mut trees: Vec<(u64, usize)> = placed.iter().filter(|s| s.decision > 0).map(tree).collect();
    trees.dedup();
    trees.into_iter().map(|(_, t)| t).collect()
}

/// `bfs` interleaves the trees level by level, root order within a level;
/// `dfs` grows the first tree whole, then the second.
#[test]
fn bfs_interleaves_trees_by_level_and_dfs_grows_them_in_root_order() {
    // Levels of 1, 2, 4 applications per tree.
    let bfs = decision_trees(GrowthOrder::Bfs);
    let levels = [1, 2, 4].map(|n| [vec![0; n], vec![1; n]].concat());
    assert_eq!(bfs, levels.concat());
    let dfs = decision_trees(GrowthOrder::Dfs);
    assert_eq!(dfs, [vec![0; 7], vec![1; 7]].concat());
}

/// Each root grows the seed; without alternatives, two trees far apart are
/// the same tree moved; and the BED has one SEED per root.
#[test]
fn each_root_grows_the_seed_and_the_bed_lists_the_roots() {
    let d = od(FAR_APART);
    let g = grown(&d, GrowthOrder::Bfs, 0);
    assert_eq!(g.stems, 2 * (1 + 2 + 4 + 8));
    let text = bed_text(&g);
    assert!(text.starts_with("F2\n(0, 0) (1000, 0)\n"), "{text}");
    assert_eq!(text.matches("\nSEED\n").count(), 2);
    let seeds: Vec<&str> = text.split("SEED\n").collect();
    assert_eq!(seeds[1], seeds[3], "{text}");
}

/// Trees compete for space: two roots close together in a box grow fewer
/// stems than twice one alone, and both grow. (The brute-force
/// invariants of grow.rs hold between the trees of every example forest.)
#[test]
fn trees_share_the_occupancy() {
    let layout = "SEED FF R1 ENDSEED LAYOUT (clGreen) Rectangle (0,0), 200, 200 ENDLAYOUT";
    let roots = |r: &str| od(&format!("A {r} L=10(0) B=1(0) RULE R1: [+F][-F] {layout}"));
    let one = grown(&roots("(50,190)"), GrowthOrder::Bfs, 0).stems;
    let g = grown(&roots("(50,190) (90,190)"), GrowthOrder::Bfs, 0);
    let two = g.stems;
    assert!(two < 2 * one, "{two} stems for two trees, {one} for one");
    let text = bed_text(&g);
    let seeds: Vec<&str> = text.split("SEED\n").collect();
    let grew = |seed: &str| seed.contains("R1{");
    assert!(grew(seeds[1]) && grew(seeds[3]), "{text}");
}

/// Roots of a forest get their own keys: the trees of a forest with
/// alternatives differ from each other.
#[test]
fn trees_of_a_forest_choose_differently() {
    let d = od(
        "F2 (0,0) (1000,0) L=10(0) B=1(0) RULE R1 (0.5): [+F] R1 (0.5): [-F]
        SEED F [I 8 R1] ENDSEED",
    );
    let text = bed_text(&grown(&d, GrowthOrder::Bfs, 0));
    let seeds: Vec<&str> = text.split("SEED\n").collect();
    assert_ne!(seeds[1], seeds[3], "{text}");
}

/// Acceptance: `stlc compile grove.od --seed 7` twice gives the same bytes,
/// `--seed 8` a different grove, and the BED renders alike under any seed
/// and like the OD rendered with the seed it was compiled with.
#[test]
fn compile_grove_with_seeds() {
    let dir = tempfile::tempdir().unwrap();
    let grove = manifest_path("examples/grove.od");
    let compile = |seed: &str, out: &str| {
        let out = dir.path().join(out);
        let (from, to) = (grove.display(), out.display());
        let line = format!("compile {from} --seed {seed} -o {to}");
        stlc_line(&line).assert().success();
        std::fs::read(out).unwrap()
    };
    let a = compile("7", "a.bed");
    assert_eq!(a, compile("7", "b.bed"));
    assert_ne!(a, compile("8", "c.bed"));
    let render = |input: &std::path::Path, seed: &str| {
        let line = format!("render --format svg --seed {seed} -o - {}", input.display());
        outcome(&mut stlc_line(&line)).1
    };
    let bed = dir.path().join("a.bed");
    let from_bed = render(&bed, "1");
    assert!(from_bed.starts_with(b"<svg") || from_bed.starts_with(b"<?xml"));
    assert_eq!(from_bed, render(&bed, "2"));
    assert_eq!(from_bed, render(&grove, "7"));
    assert_ne!(from_bed, render(&grove, "8"));
}

/// Every slot of a grown forest's terms names an alternative of R1.
#[test]
fn grown_terms_name_alternatives() {
    let g = grown(&od(&example_text("grove.od")), GrowthOrder::Dfs, 7);
    let d = g.bed.description();
    let mut seeds = vec![d.seed.as_ref().unwrap()];
    seeds.extend(d.forest.iter().map(|t| t.seed.as_ref().unwrap()));
    assert_eq!(seeds.len(), 4);
    for seed in seeds {
        let mut stack: Vec<_> = seed
            .items
            .iter()
            .filter_map(|i| match i {
                SeedItem::Term(t) => Some(seed.term(*t)),
                _ => None,
            })
            .collect();
        while let Some(t) = stack.pop() {
            assert!(d.rule(t.rule()).alternative.is_some());
            stack.extend(t.slots().flatten().filter_map(|s| match s {
                Slot::Term(c) => Some(c),
                Slot::Repeat(_) => None,
            }));
        }
    }
}
