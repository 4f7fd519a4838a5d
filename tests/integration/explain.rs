//! Growth explains itself: each rule's tries, fits and misses by reason,
//! and the warning for a rule tried and never fitted, with its first
//! failure's numbers, in every front end.

use crate::support::{od, opts, outcome, stlc_line};
use stlc::diag::{Diagnostic, ErrorKind, GrowError, Kin, Misfit, MissReason};
use stlc::grow::explain::RuleTally;
use stlc::grow::{GrowOptions, GrowthOrder, grow};
use stlc::pipeline::Request;
use stlc::progress::NoProgress;

/// Problem 8 of issue 22: `F[+F][-F][F]` at `A=25` with thick stems. The
/// straight branch `[F]` (stem 4) and the left one `[+F]` (stem 2) start
/// at the trunk's tip 25 degrees apart, so their far ends are `l sin 25`
/// from the other stem, less than the clearance plus their widths: the
/// rule never grows, and the seed (9 stems) is all there is.
fn problem_8(angle: u32) -> String {
    format!(
        "Problem8
(150, 290)
L=9(0.3) B=3(0.3) A={angle} C=1.5
RULE
R1: F[+F][-F][F]
SEED
FFFFFFFFF R1
ENDSEED
LAYOUT
(clGreen) Rectangle (0, 0), 300, 300
ENDLAYOUT
"
    )
}

/// The distance found and the distance needed, from the geometry alone:
/// at order 1 the stems are `9 - 0.3` long and `3 - 0.3` wide; two
/// branches of one tip `A` apart, both `l` long, have each far end
/// `l sin A` from the other (its foot falls inside the other stem, since
/// `l cos A < l`); the centre lines need `C` plus half of each width.
fn problem_8_numbers() -> (f64, f64) {
    let l = 9.0 - 0.3;
    let w = 3.0 - 0.3;
    let found = l * libm::sin(25f64.to_radians());
    let needed = 1.5 + w / 2.0 + w / 2.0;
    (found, needed)
}

fn never_fitted(warnings: &[Diagnostic]) -> Vec<&Diagnostic> {
    warnings
        .iter()
        .filter(|w| matches!(w.kind, ErrorKind::Grow(GrowError::NeverFitted { .. })))
        .collect()
}

/// A clearance miss's stem, kin, other stem, found, needed and clearance.
fn too_close(why: Misfit) -> (u32, Kin, Option<u32>, f64, f64, f64) {
    let Misfit::TooClose {
        stem,
        kin,
        other,
        found,
        needed,
        clearance,
    } = why
    else {
        panic!("not a clearance miss: {why:?}");
    };
    (stem, kin, other, found, needed, clearance)
}

/// The warning of problem 8: which stems, how far apart, how far they
/// need to be, where the rule is, and what to change.
fn assert_problem_8_warning(warnings: &[Diagnostic], text: &str) {
    let (found, needed) = problem_8_numbers();
    let ws = never_fitted(warnings);
    assert_eq!(ws.len(), 1, "{warnings:?}");
    let w = ws[0];
    assert!(!w.is_error());
    let ErrorKind::Grow(GrowError::NeverFitted { rule, tries, why }) = &w.kind else {
        unreachable!()
    };
    assert_eq!((rule.as_str(), *tries), ("R1", 1));
    let (stem, kin, other, f, n, clearance) = too_close(*why);
    let want = (4, Kin::Sibling, Some(2), 1.5);
    assert_eq!((stem, kin, other, clearance), want);
    assert!((f - found).abs() < 1e-9, "found {f}, expected {found}");
    assert!((n - needed).abs() < 1e-9, "needed {n}, expected {needed}");
    let message = w.kind.to_string();
    assert!(
        message.contains(&format!("within {found:.3} of stem 2, its sibling"))
            && message.contains(&format!("where {needed:.1} is needed")),
        "{message}"
    );
    let rule_at = text.find("R1: F[+F][-F][F]").unwrap();
    assert_eq!(w.span, Some(rule_at..rule_at + "R1: F[+F][-F][F]".len()));
    assert!(w.help_text().unwrap().contains("raise `A`"), "{w:?}");
}

#[test]
fn problem_8_warns_of_the_sibling_distance_in_every_front_end() {
    let text = problem_8(25);
    let (found, needed) = problem_8_numbers();
    // The numbers the test expects: 3.677 found, 4.2 needed.
    assert_eq!(format!("{found:.3} {needed:.1}"), "3.677 4.2");

    let mut request = Request::new(text.clone().into_bytes());
    request.kind = Some(stlc::pipeline::InputKind::Od);
    let (compiled, warnings) = request.compile(&mut NoProgress).unwrap();
    assert_eq!(compiled.grown.stems, 9, "the seed alone");
    assert_problem_8_warning(&warnings, &text);
    // The page renders through `Request::render`.
    let drawn = request.render(&mut Vec::new(), &mut NoProgress).unwrap();
    assert_problem_8_warning(&drawn.warnings, &text);
    let checked = request.check().unwrap();
    assert_problem_8_warning(&checked.warnings, &text);
    let line = "  rule R1     1 try, 0 fits; most misses: too close to a sibling stem (1 of 1)\n";
    assert!(checked.summary.contains(line), "{}", checked.summary);

    // `stlc check` prints the line and the warning, pointing at the rule.
    let (code, out, err) = outcome(stlc_line("check - --from od").write_stdin(text));
    assert_eq!(code, 0, "{err}");
    let out = String::from_utf8(out).unwrap();
    assert!(out.contains(line.trim_start()), "{out}");
    let within = format!("came within {found:.3} of stem 2, its sibling");
    let needed = format!("where {needed:.1} is needed");
    for part in [
        "rule `R1` never grew",
        &within,
        &needed,
        "R1: F[+F][-F][F]",
        "raise `A`",
    ] {
        assert!(err.contains(part), "{part}: {err}");
    }
}

#[test]
fn problem_8_with_a_wider_angle_grows_and_warns_of_nothing() {
    // At 35 degrees the far ends are 8.7 sin 35 = 4.99 apart: enough.
    let d = od(&problem_8(35));
    for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        let g = grow(&d, &opts(growth), &mut NoProgress).unwrap();
        assert!(g.stems > 100, "{growth:?}: {}", g.stems);
        assert!(never_fitted(&g.warnings).is_empty(), "{:?}", g.warnings);
        let t = &g.tallies[0];
        assert!(t.fits > 0 && t.tries > t.fits, "{t:?}");
        // Every application draws 4 stems; the seed 9.
        assert_eq!(g.stems, 9 + 4 * t.fits);
    }
}

/// `R1: [F]` grows one stem straight up at each tip. The seed's `F` ends
/// at y = 85; R1's stems end at 75, 65, ..., 5, all inside the 100-high
/// rectangle (the top edge at y = 0, the stems 0.05 wide each side); the
/// ninth would end at -5, outside. So: 9 tries, 8 fits, one miss, outside
/// the layout, at the try's first (only) stem.
#[test]
fn counts_match_a_layout_that_admits_exactly_eight_applications() {
    let d = od("Column
(10, 95)
L=10(0) B=0.1(0) A=30 C=0
RULE
R1: [F]
SEED
F R1
ENDSEED
LAYOUT
(clGreen) Rectangle (0, 0), 20, 100
ENDLAYOUT
");
    for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        let g = grow(&d, &opts(growth), &mut NoProgress).unwrap();
        assert_eq!(g.stems, 9, "{growth:?}");
        let mut misses = [0; MissReason::COUNT];
        misses[MissReason::Outside.index()] = 1;
        assert_eq!(
            g.tallies,
            vec![RuleTally {
                tries: 9,
                fits: 8,
                misses,
                first_miss: Some(Misfit::Outside { stem: 1 }),
                claimed: 0,
                killed: 0,
            }],
            "{growth:?}"
        );
        // It fitted: no warning.
        assert!(g.warnings.is_empty(), "{:?}", g.warnings);
    }
}

/// A clearance miss of a try's one stem against a stem already there,
/// its distances to rounding (the turtle's directions come from `libm`).
fn assert_too_close(why: Misfit, kin: Kin, found: f64, needed: f64) {
    let (stem, k, other, f, n, clearance) = too_close(why);
    assert_eq!((stem, k, other, clearance), (1, kin, None, 1.0), "{why:?}");
    let near = (f - found).abs() < 1e-9 && (n - needed).abs() < 1e-9;
    assert!(near, "{why:?}");
}

/// Every kind of miss, each in a description small enough to work by
/// hand; each rule is tried once (a count of 1, or nothing after it).
#[test]
fn each_reason_is_found_with_its_numbers() {
    let one = |text: &str| {
        let g = grow(&od(text), &opts(GrowthOrder::Bfs), &mut NoProgress).unwrap();
        let t = g.tallies[0].clone();
        assert_eq!((t.tries, t.fits), (1, 0), "{text}");
        assert_eq!(t.misses.iter().sum::<u64>(), 1);
        let why = t.first_miss.unwrap();
        assert_eq!(t.misses[why.reason().index()], 1);
        assert_eq!(never_fitted(&g.warnings).len(), 1, "{:?}", g.warnings);
        why
    };
    // Six turns of 30 degrees fold the branch back down the seed's stem:
    // its far end lands on the root, 0 from the stem it starts from; the
    // stems are 1 wide and C = 1, so 2 is needed.
    let why = one("Back (0, 0) L=10(0) B=1(0) A=30 C=1 RULE R1: [++++++F] SEED F[I 1 R1] ENDSEED");
    assert_too_close(why, Kin::Parent, 0.0, 2.0);
    // The seed draws a stem from (10, -10) down to (10, 0) beside its
    // trunk, without growing; R1's stem from the trunk's tip (0, -10) to
    // the right ends on that stem's start: no joint, distance 0.
    let why =
        one("Other (0, 0) L=10(0) B=1(0) A=90 C=1 RULE R1: [-F] SEED F[-f-F][I 1 R1] ENDSEED");
    assert_too_close(why, Kin::Other, 0.0, 2.0);
    // Width 1 - 1 = 0 at order 1.
    let why = one("Thin (0, 0) L=10(0) B=1(1) RULE R1: [F] SEED F[I 1 R1] ENDSEED");
    let (order, width) = (1, 0.0);
    assert_eq!(why, Misfit::TooThin { order, width });
    // Length 10 - 10 = 0 at order 1 (checked before the width).
    let why = one("Short (0, 0) L=10(10) B=1(1) RULE R1: [F] SEED F[I 1 R1] ENDSEED");
    let (order, length) = (1, 0.0);
    assert_eq!(why, Misfit::TooShort { order, length });
}

/// A limit that stops a try has its own warning: the rule's counts say
/// so, and no second warning repeats it.
#[test]
fn a_limit_is_counted_but_not_warned_twice() {
    let d = od("Capped (0, 0) L=10(0) B=1(0) A=30 C=1 RULE R1: [F] SEED F[I 3 R1] ENDSEED");
    let mut o = GrowOptions::default();
    o.limits.max_depth = 0;
    let g = grow(&d, &o, &mut NoProgress).unwrap();
    assert_eq!(g.tallies[0].first_miss, Some(Misfit::Depth { limit: 0 }));
    assert_eq!(g.warnings.len(), 1, "{:?}", g.warnings);
    let capped = matches!(
        g.warnings[0].kind,
        ErrorKind::Grow(GrowError::DepthCapped { .. })
    );
    assert!(capped);
}

/// The same input gives the same counts, and they add up: every try fits
/// or misses for one reason; in fig9 (`R1 = [-F][+F]`, no counts) every
/// tip of every success is tried once, and the seed's growth point.
#[test]
fn counts_are_deterministic_and_add_up() {
    let root = env!("CARGO_MANIFEST_DIR");
    for file in ["fig9.od", "grove.od", "successors.od", "alternatives.od"] {
        let text = std::fs::read_to_string(format!("{root}/examples/{file}")).unwrap();
        let d = od(&text);
        for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let a = grow(&d, &opts(growth), &mut NoProgress).unwrap();
            let b = grow(&d, &opts(growth), &mut NoProgress).unwrap();
            assert_eq!(a.tallies, b.tallies, "{file} {growth:?}");
            assert_eq!(a.tallies.len(), d.rules.len());
            for t in &a.tallies {
                assert_eq!(t.tries, t.fits + t.misses.iter().sum::<u64>(), "{file}");
                assert_eq!(t.first_miss.is_some(), t.tries > t.fits, "{file}");
            }
            if file == "fig9.od" {
                let t = &a.tallies[0];
                assert_eq!(t.tries, 1 + 2 * t.fits, "{growth:?}");
                assert_eq!(a.stems, 1 + 2 * t.fits);
            }
        }
    }
}
