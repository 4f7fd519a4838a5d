//! `.od`/`.bed`: parsing, diagnostics, the canonical writer and expansion.
//!
//! Expected values are worked by hand (the paper's expansions, coordinates
//! of a turtle turning by right angles), never copied from the output.

use crate::support::{cuboid, cylinder, ellipsoid, limit_kind, limits_with, od, sphere};
use proptest::prelude::*;
use stlc::bed::Bed;
use stlc::bed::validate;
use stlc::bed::write::write;
use stlc::color::Rgb;
use stlc::diag::{BedError, Diagnostics, ErrorKind, InputError, LayoutError, RuleError, StlError};
use stlc::interpret::Derivation::{self, Bfs, Dfs};
use stlc::interpret::bed::{draw_into, expand};
use stlc::limits::{Bound, Limits};
use stlc::model::{
    Body, BodyItem, Branch, Description, DrawRun, Fixed, Format, Layout, LayoutShape, LayoutSolid,
    Loc, Piece, Repeat, RuleDef, RuleId, RuleRef, Seed, SeedItem, Shape, Solid, Spelling,
    StemParams, TermId, Terms,
};
use stlc::num::Linear;
use stlc::progress::NoProgress;
use stlc::syntax::stl::parse;
use stlc::turtle::turtle3::Segment3;
use stlc::turtle::{Point, Recorder, Segment};

const TREE_2D: &str = "2DTree (76, 150)L=10(0) B=1(0)RULE R1: [+F][-F] LAYOUT (clGreen)< RoundRect (0,0,180,192,7,7)> (clWhite)< RoundRect (55,30,40,15,4,4)> (clWhite)< RoundRect (35,125,76,30,5,5)> ENDLAYOUT";

/// `src` read as a BED with the default limits; its diagnostics on failure.
pub fn bed(src: &str) -> Description {
    parse(src, Format::Bed, &Limits::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn errors(src: &str) -> Diagnostics {
    parse(src, Format::Bed, &Limits::default()).expect_err("parsed, expected an error")
}

/// The one error of `src`, asserted to be of `kind`: its span and help.
fn refused(src: &str, kind: ErrorKind) -> (std::ops::Range<usize>, String) {
    let e = errors(src);
    assert_eq!(e.0.len(), 1, "{e}");
    let d = &e.0[0];
    assert_eq!(d.kind, kind, "{src}");
    let help = d.help_text().unwrap_or_default();
    (d.span.clone().expect("a span"), help)
}

/// The help of the one error of `src`, asserted to be of `kind` and to
/// point at the first `needle`.
fn refused_at(src: &str, kind: ErrorKind, needle: &str) -> String {
    let (span, help) = refused(src, kind);
    assert_eq!(span, at(src, needle, 0), "{src}");
    help
}

/// Byte range of the `n`th (0-based) occurrence of `needle` in `src`.
fn at(src: &str, needle: &str, n: usize) -> std::ops::Range<usize> {
    let start = src.match_indices(needle).nth(n).expect("needle").0;
    start..start + needle.len()
}

fn expanded(d: &Description, strategy: Derivation) -> String {
    let (mut out, l) = (Vec::new(), Limits::default());
    let bed = Bed::new(d.clone(), &l).unwrap();
    expand(&bed, strategy, &l, &mut out, &mut NoProgress).unwrap();
    String::from_utf8(out).unwrap()
}

/// The expansion of `d`, asserted the same depth-first and breadth-first.
fn expanded_both(d: &Description) -> String {
    let dfs = expanded(d, Dfs);
    assert_eq!(expanded(d, Bfs), dfs, "bfs against dfs");
    dfs
}

type Segments = Result<Vec<Segment>, Diagnostics>;

fn segments(d: &Description, strategy: Derivation) -> Segments {
    segments_within(d, strategy, &Limits::default())
}

fn segments_within(d: &Description, s: Derivation, l: &Limits) -> Segments {
    let bed = Bed::new(d.clone(), l)?;
    draw_into(&bed, s, l, Recorder::default(), &mut NoProgress).map(|r| r.segments)
}

/// A 3D description's stems, drawn by the 3D interpreter.
fn segments3(d: &Description, strategy: Derivation) -> Result<Vec<Segment3>, Diagnostics> {
    let (mut out, l) = (Vec::new(), Limits::default());
    let bed = Bed::new(d.clone(), &l)?;
    stlc::interpret::bed3::draw3(&bed, strategy, &l, &mut |s| out.push(s), &mut NoProgress)?;
    Ok(out)
}

/// A rule's term with `found` slots where the rule has `expected` branches.
fn slot_count(rule: &str, expected: usize, found: usize) -> ErrorKind {
    ErrorKind::Rule(RuleError::SlotCount {
        rule: rule.into(),
        expected,
        found,
    })
}

/// A rounded rectangle's shape.
fn round_rect(x: f64, y: f64, w: f64, h: f64, rx: f64, ry: f64) -> Shape {
    Shape::RoundRect { x, y, w, h, rx, ry }
}

const HEAD: &str = "T (0, 0) L=10(0) B=1(0) RULE ";

// ---------------------------------------------------------------- paper --

#[test]
fn the_papers_2dtree_parses_as_written() {
    let d = od(TREE_2D);
    assert_eq!(d.name, "2DTree");
    assert_eq!(d.root, (76.0, 150.0));
    let (l, w) = (&d.params.length, &d.params.width);
    let stems = (l.base, l.decrement, w.base, w.decrement);
    assert_eq!(stems, (10.0, 0.0, 1.0, 0.0));
    assert_eq!((d.params.angle, d.params.clearance), (None, None));
    assert_eq!(d.rules.len(), 1);
    assert_eq!(d.rules[0].name, "R1");
    assert_eq!(d.rules[0].branch_count(), 2);
    assert!(d.seed.is_none());
    let shapes = &d.layout.as_ref().unwrap().shapes;
    assert_eq!(shapes.len(), 3);
    // Delphi's corner reading: (x1,y1,x2,y2,ellipse w,ellipse h).
    let want = [
        (Rgb::new(0, 128, 0), 0.0, 0.0, 180.0, 192.0, 3.5),
        // (55,30)-(40,15): corners in either order.
        (Rgb::WHITE, 40.0, 15.0, 15.0, 15.0, 2.0),
        // (35,125)-(76,30).
        (Rgb::WHITE, 35.0, 30.0, 41.0, 95.0, 2.5),
    ];
    for (s, (c, x, y, w, h, r)) in shapes.iter().zip(want) {
        assert_eq!(s.color, c);
        assert_eq!(s.spelling, Spelling::Corners);
        assert!(s.angled);
        assert_eq!(s.shape, round_rect(x, y, w, h, r, r));
    }
    assert_eq!(shapes[0].color_text, "clGreen");
    // No seed: `F` then the first rule (Figure 9's `FR1`).
    let seed = d.effective_seed().unwrap();
    assert!(matches!(&seed.items[0], SeedItem::Draw(r) if r.text == "F"));
    assert!(
        matches!(&seed.items[1], SeedItem::Term(t) if seed.term(*t).bare() && seed.term(*t).rule() == RuleId(0))
    );
}

#[test]
fn the_papers_worked_expansion() {
    let d = bed("Rn (0, 0) L=10(0) B=1(0)
        RULE R1 = [F][+F][-F]  R2 = [++F][-F]
        SEED R1{R1{,,},R2{,},R1{,,}} ENDSEED");
    let want = "[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]\n";
    assert_eq!(expanded_both(&d), want);
}

#[test]
fn seed_r1r2r2_is_split_by_longest_match() {
    let d = bed(&format!(
        "{HEAD} R1=[FFF] R2=[F[+F][-F]F] SEED R1R2R2 ENDSEED"
    ));
    let seed = d.seed.as_ref().unwrap();
    assert_eq!(seed.items.len(), 3);
    // In a BED a bare name is the full term with every slot empty.
    for item in &seed.items {
        assert!(matches!(item, SeedItem::Term(t)
            if !seed.term(*t).bare() && seed.term(*t).slot_count() == 1 && seed.term(*t).all_empty()));
    }
    assert_eq!(expanded_both(&d), "[FFF][F[+F][-F]F][F[+F][-F]F]\n");
}

#[test]
fn longest_match_prefers_the_longer_name() {
    let d = bed(&format!("{HEAD} R1=[F] R12=[+F] SEED FR12R1 ENDSEED"));
    let seed = d.seed.as_ref().unwrap();
    let items = &seed.items;
    assert!(matches!(&items[1], SeedItem::Term(t) if seed.term(*t).rule() == RuleId(1)));
    assert!(matches!(&items[2], SeedItem::Term(t) if seed.term(*t).rule() == RuleId(0)));
    assert_eq!(expanded(&d, Dfs), "F[+F][F]\n");
}

#[test]
fn self_resemblance_counts_in_both_forms() {
    // [I 2 R1] = R1{R1{,},R1{,}}
    let d = bed(&format!("{HEAD} R1=[F][+F] SEED [I 2 R1] ENDSEED"));
    assert_eq!(expanded_both(&d), "[F[F][+F]][+F[F][+F]]\n");
    // [I 1 w] is w; [I 2 w] rewrites each F of w by w once.
    let d = bed(&format!(
        "{HEAD} R1=[F] SEED [I 1 F+F] f [I 2 F[+F]F] ENDSEED"
    ));
    let want = "F+Ff F[+F]F[+F[+F]F]F[+F]F\n".replace(' ', "");
    assert_eq!(expanded_both(&d), want);
}

#[test]
fn trunk_and_successor_names_in_bodies() {
    // The successor name draws nothing in a BED; the trunk comes first.
    let d = bed(&format!(
        "{HEAD} R1: F[+F R2][-F] R2: [F] SEED R1{{R2{{}},}} ENDSEED"
    ));
    let b = &d.rules[0].body.items;
    assert!(matches!(&b[0], BodyItem::Draw(r) if r.text == "F"));
    assert!(
        matches!(&b[1], BodyItem::Branch(br) if br.successor.as_ref().map(|s| s.rule) == Some(RuleId(1)))
    );
    assert_eq!(expanded(&d, Dfs), "F[+F[F]][-F]\n");
}

#[test]
fn segments_have_hand_computed_coordinates_and_orders() {
    // A=90 keeps every coordinate exact. L=10(2): order 0 length 10,
    // order 1 length 8, order 2 length 6.
    let d = bed("T (0, 0) L=10(2) B=1(0) A=90 RULE R1: F[+F] SEED F R1{R1{}} ENDSEED");
    let seg = |x0, y0, x1, y1, order| {
        let (from, to) = (Point::new(x0, y0), Point::new(x1, y1));
        Segment { from, to, order }
    };
    let want = vec![
        seg(0.0, 0.0, 0.0, -10.0, 0),       // seed F, up
        seg(0.0, -10.0, 0.0, -18.0, 1),     // R1's trunk
        seg(0.0, -18.0, -8.0, -18.0, 1),    // its branch, turned left
        seg(-8.0, -18.0, -14.0, -18.0, 2),  // the inner R1's trunk, still left
        seg(-14.0, -18.0, -14.0, -12.0, 2), // its branch, turned left again: down
    ];
    assert_eq!(segments(&d, Dfs).unwrap(), want);
    assert_eq!(segments(&d, Bfs).unwrap(), want);
}

#[test]
fn the_root_and_default_angle_are_used() {
    // A defaults to 30: a left turn then F from (100, 50) goes to
    // (100 - 10 sin 30, 50 - 10 cos 30).
    let d = bed("T (100, 50) L=10(0) B=1(0) RULE R1: [+F] SEED R1 ENDSEED");
    let s = segments(&d, Dfs).unwrap();
    assert_eq!(s.len(), 1);
    assert_eq!(s[0].from, Point::new(100.0, 50.0));
    assert!((s[0].to.x - 95.0).abs() < 1e-12);
    assert!((s[0].to.y - (50.0 - 10.0 * 3f64.sqrt() / 2.0)).abs() < 1e-12);
    assert_eq!(s[0].order, 1);
}

#[test]
fn od_bare_references_are_growth_points() {
    let d = od(&format!("{HEAD} R1: [+F][-F] SEED FR1 ENDSEED"));
    let seed = d.seed.as_ref().unwrap();
    assert!(
        matches!(&seed.items[1], SeedItem::Term(t) if seed.term(*t).bare() && seed.term(*t).slot_count() == 2)
    );
}

#[test]
fn both_definition_forms_and_comments() {
    let d = bed(
        "# a comment\nT # name\n(1.5, -2) L=10(0.5) B=2(0.25) A=22.5 C=1\nRULE\nR1: [+F] # colon\nR2=[-F]\nSEED R1{R2{}} ENDSEED\nLAYOUT (#00ff00) Rectangle (0,0), 200, 100 ENDLAYOUT",
    );
    assert_eq!(d.root, (1.5, -2.0));
    assert_eq!(d.params.angle, Some(22.5));
    assert_eq!(d.params.clearance, Some(1.0));
    assert_eq!(d.rules.len(), 2);
    let s = &d.layout.as_ref().unwrap().shapes[0];
    assert_eq!(s.color, Rgb::new(0, 255, 0));
    assert_eq!(s.spelling, Spelling::StartSize);
    let (x, y, w, h) = (0.0, 0.0, 200.0, 100.0);
    assert_eq!(s.shape, Shape::Rect { x, y, w, h });
}

// ---------------------------------------------------------- diagnostics --

/// Mistakes with one error each, pointed at the first occurrence of the
/// text at fault; the help of unknown names suggests the nearest.
#[test]
fn each_mistake_is_reported_at_its_text() {
    let src = format!("{HEAD} R1: [F] R2: [F][F] SEED FR3 ENDSEED");
    let unknown = ErrorKind::Rule(RuleError::UnknownRule { name: "R3".into() });
    assert!(refused_at(&src, unknown, "R3").contains("`R1`"));
    let src = format!("{HEAD} R1: [F][F] SEED F R1{{,,}} ENDSEED");
    assert!(refused_at(&src, slot_count("R1", 2, 3), "R1{,,}").contains("R1{,}"));
    let src = format!("{HEAD} R1: [F] LAYOUT (clRed) Polygon (0,0), (5,5) ENDLAYOUT");
    let few = ErrorKind::Layout(LayoutError::TooFewPoints { points: 2 });
    refused_at(&src, few, "Polygon (0,0), (5,5)");
    let src = format!("{HEAD} R1: [F] LAYOUT (clGren) Rectangle (0,0), 5, 5 ENDLAYOUT");
    let text = "clGren".into();
    let colour = ErrorKind::Input(InputError::UnknownColour { text });
    assert!(refused_at(&src, colour, "clGren").contains("clGreen"));
    let unclosed = |open, close| ErrorKind::Stl(StlError::UnclosedSection { open, close });
    let src = format!("{HEAD} R1: [F] SEED R1 LAYOUT (clGreen) Rectangle (0,0), 5, 5 ENDLAYOUT");
    refused_at(&src, unclosed("SEED", "ENDSEED"), "SEED");
    let src = format!("{HEAD} R1: [F] LAYOUT (clGreen) Rectangle (0,0), 5, 5");
    refused_at(&src, unclosed("LAYOUT", "ENDLAYOUT"), "LAYOUT");
    let src = "T (0, 1e999) L=10(0) B=1(0) RULE R1: [F]";
    let text = "1e999".into();
    let finite = ErrorKind::Input(InputError::NotFinite { text });
    refused_at(src, finite, "1e999");
    let src = format!("{HEAD} R1: [F] SEED [I 10001 R1] ENDSEED");
    let over = limit_kind(Bound::Repeat, None, "10001", 10000);
    assert!(refused_at(&src, over, "10001").contains("--max-depth"));
    let src = format!("{HEAD} R1: [F] SEED F{{}} ENDSEED");
    refused_at(&src, ErrorKind::Stl(StlError::BraceWithoutRule), "{");
}

#[test]
fn unbalanced_brackets_point_at_the_unmatched_one() {
    // The body after `R1: `, the unmatched character and which of its
    // occurrences in the whole text (0-based) is the unmatched one.
    for (body, c, n) in [
        ("[F][+F SEED ENDSEED", '[', 1),
        ("[F]] SEED ENDSEED", ']', 1),
        ("[F] SEED R1{R1{} ENDSEED", '{', 0),
        ("[F] SEED R1{}} ENDSEED", '}', 1),
        ("[F] SEED [+F R1 ENDSEED", '[', 1),
    ] {
        let src = format!("{HEAD} R1: {body}");
        let (span, _) = refused(&src, ErrorKind::Input(InputError::Unbalanced(c)));
        assert_eq!(span, at(&src, &c.to_string(), n), "{src}");
    }
}

#[test]
fn duplicate_rule_labels_both() {
    let src = format!("{HEAD} R1: [F] R1: [+F] SEED R1 ENDSEED");
    let e = errors(&src);
    assert_eq!(e.0.len(), 1, "{e}");
    let wanted = ErrorKind::Rule(RuleError::DuplicateRule { name: "R1".into() });
    assert_eq!(e.0[0].kind, wanted);
    assert_eq!(e.0[0].span, Some(at(&src, "R1", 1)));
    assert_eq!(e.0[0].labels[0].span, at(&src, "R1", 0));
}

#[test]
fn reserved_names_are_refused() {
    for name in ["F", "f", "L", "R", "I", "SEED"] {
        let src = format!("{HEAD} {name}: [F] R1: [F]");
        let reserved = ErrorKind::Rule(RuleError::ReservedName { name: name.into() });
        let (span, _) = refused(&src, reserved);
        let wanted = at(&src, &format!("{name}:"), 0).start..at(&src, ":", 0).start;
        assert_eq!(span, wanted);
    }
}

#[test]
fn rule_names_in_bodies_only_end_branches() {
    // in a branch, in the trunk, in a nested bracket
    for body in ["[R1 +F][-F]", "F R1 [-F]", "[F[+F R1]]"] {
        let src = format!("{HEAD} R1: {body}");
        let (span, _) = refused(&src, ErrorKind::Stl(StlError::NameNotAtBranchEnd));
        assert_eq!(span, at(&src, "R1", 1), "{src}");
    }
}

#[test]
fn sizes_must_be_positive() {
    let stem = |key, what| ErrorKind::Stl(StlError::StemSizeNotPositive { key, what });
    let shape = |shape, what| ErrorKind::Layout(LayoutError::ShapeSizeNotPositive { shape, what });
    let src = "T (0, 0) L=-1(0) B=1(0) RULE R1: [F]";
    refused_at(src, stem("L", "length"), "-1");

    let src = "T (0, 0) L=1(0) B=0(0) RULE R1: [F]";
    let (span, _) = refused(src, stem("B", "broadness"));
    let b = at(src, "B=0", 0).start + 2;
    assert_eq!(span, b..b + 1);

    let src = format!("{HEAD} R1: [F] LAYOUT (clGreen) Rectangle (0,0), 0, 10 ENDLAYOUT");
    let (span, _) = refused(&src, shape("Rectangle", "width"));
    let w = at(&src, "(0,0), 0", 0).end - 1;
    assert_eq!(span, w..w + 1);

    let src = format!("{HEAD} R1: [F] LAYOUT (clGreen) RoundRect (0,0), 5, 10, -2 ENDLAYOUT");
    refused_at(&src, shape("RoundRect", "corner radius"), "-2");
}

#[test]
fn several_errors_are_reported_together() {
    let src = format!(
        "{HEAD} R1: [F][F] F: [F] SEED R1{{,,}} R9 ENDSEED LAYOUT (clBlu) Polygon (0,0) ENDLAYOUT"
    );
    let e = errors(&src);
    let kinds: Vec<ErrorKind> = e.iter().map(|d| d.kind.clone()).collect();
    // The layout is read as it is met, names before bodies, the seed last,
    // in the order its text is read (the seed is tokenised as it is built).
    let blu = "clBlu".into();
    assert_eq!(
        kinds,
        vec![
            ErrorKind::Input(InputError::UnknownColour { text: blu }),
            ErrorKind::Layout(LayoutError::TooFewPoints { points: 1 }),
            ErrorKind::Rule(RuleError::ReservedName { name: "F".into() }),
            slot_count("R1", 2, 3),
            ErrorKind::Rule(RuleError::UnknownRule { name: "R9".into() }),
        ]
    );
}

#[test]
fn syntax_errors_name_what_the_user_types() {
    let src = "T (0,0) RULE R1: SEED R1 ENDSEED";
    let (span, _) = refused(src, ErrorKind::Rule(RuleError::MissingBody));
    let colon = at(src, ":", 0).end;
    assert_eq!(span, colon..colon);
    // pest's own errors are worded in what the user types, too.
    let e = errors("T (0,0) RULE R1: [F] SEED R1 ENDSEED ENDSEED");
    let m = e.0[0].kind.to_string();
    assert!(m.contains("end of input"), "{m}");
    assert!(!m.contains("stl_"), "{m}");
}

#[test]
fn validate_refuses_orders_without_length() {
    // L=10(5): order 2 has length 0.
    let src = "T (0,0) L=10(5) B=1(0) RULE R1: [F] SEED R1{R1{}} ENDSEED";
    let d = bed(src);
    let e = validate(&d, &Limits::default()).unwrap_err();
    let (rule, order, length, width) = ("R1".into(), 2, 0.0, 1.0);
    let deep = ErrorKind::Bed(BedError::OrderTooDeep {
        rule,
        order,
        length,
        width,
    });
    assert_eq!(e.first_kind(), Some(&deep));
    assert_eq!(e.0[0].span, Some(at(src, "R1{}", 0)));
    // ... and so does drawing.
    assert!(segments(&d, Dfs).is_err());
}

#[test]
fn validate_bounds_the_derived_size() {
    let d = bed(&format!("{HEAD} R1: [F][F] SEED [I 40 R1] ENDSEED"));
    let limits = limits_with(|l| l.max_symbols = 1000);
    let e = validate(&d, &limits).unwrap_err();
    assert!(matches!(e.first_kind(), Some(ErrorKind::Limit { .. })));
}

#[test]
fn bfs_refuses_words_over_the_limit() {
    // [I 8 R1], R1 = [F][F]: 2^8 - 1 = 255 applications, far over 100 symbols.
    let d = bed(&format!("{HEAD} R1: [F][F] SEED [I 8 R1] ENDSEED"));
    let limits = limits_with(|l| l.max_word = 100);
    let e = segments_within(&d, Bfs, &limits).unwrap_err();
    assert!(matches!(e.first_kind(), Some(ErrorKind::Limit { .. })));
    let help = e.0[0].help_text().unwrap_or_default();
    assert!(help.contains("--max-word"));
    // dfs needs no word.
    let r = segments_within(&d, Dfs, &limits).unwrap();
    assert_eq!(r.len(), 2 * 255);
}

// --------------------------------------------------------------- writer --

#[test]
fn the_writer_is_canonical() {
    let d = bed(
        "X (1.25,2) L=10(0.5) B=1(0.1) A=30 RULE R1=F[+F R2][-F] R2=[F][+F][-F] \
                 SEED F[+F R1{R2{,R2{,,},},}] R1 ENDSEED \
                 LAYOUT (clGreen)<RoundRect (0,0,180,192,7,7)> (clWhite) Ellipse (1,2), 3, 4 \
                 (#ff0000) Polygon (0,0),(1,0),(0,1) ENDLAYOUT",
    );
    let want = "\
X
(1.25, 2)
L=10(0.5) B=1(0.1) A=30
RULE
R1: F[+F R2][-F]
R2: [F][+F][-F]
SEED
F[+F
R1{
  R2{
    ,
    R2{,,},
  },
}
]
R1{,}
ENDSEED
LAYOUT
(clGreen) <RoundRect (0, 0, 180, 192, 7, 7)>
(clWhite) Ellipse (1, 2), 3, 4
(#ff0000) Polygon (0, 0), (1, 0), (0, 1)
ENDLAYOUT
";
    assert_eq!(write(&d), want);
    assert_eq!(bed(want), d);
}

#[test]
fn drawing_letters_that_spell_a_rule_are_spaced() {
    let d = bed(&format!("{HEAD} FL: [F L] SEED F L FL ENDSEED"));
    assert_eq!(d.rules[0].body.items.len(), 1);
    let text = write(&d);
    assert!(text.contains("FL: [F L]\n"), "{text}");
    assert_eq!(bed(&text), d);
}

// ------------------------------------------------------------------ deep --

/// A BED whose seed nests `n` terms `R1{R1{...}}`.
fn nested(n: usize) -> String {
    let (open, close) = ("R1{".repeat(n), "}".repeat(n));
    format!("{HEAD} R1: [F] SEED {open}{close} ENDSEED")
}

fn big_stack<F: FnOnce() + Send + 'static>(f: F) {
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(f)
        .unwrap()
        .join()
        .unwrap();
}

#[test]
fn five_thousand_nested_terms_parse_write_and_expand() {
    big_stack(|| {
        let n = 5000;
        let src = nested(n);
        let d = bed(&src);
        let text = write(&d);
        // One line per term, indented two spaces per level up to depth 24
        // (then no further): with i(d) = 2 min(d, 24), the opening line of
        // depth d is i(d) + 4 bytes (`R1{` and LF), its closing line
        // i(d) + 2 (`}` and LF), the innermost `R1{}` line i(n-1) + 5.
        let head = "T\n(0, 0)\nL=10(0) B=1(0)\nRULE\nR1: [F]\nSEED\n";
        let i = |d: usize| 2 * d.min(24);
        let seed: usize = (0..n - 1).map(|d| 2 * i(d) + 6).sum::<usize>() + i(n - 1) + 5;
        assert_eq!(text.len(), head.len() + seed + "ENDSEED\n".len());
        assert!(text.starts_with(&format!("{head}R1{{\n  R1{{\n    R1{{\n")));
        assert!(text.ends_with("  }\n}\nENDSEED\n"));
        // Linear in depth, so the deep file reads back too.
        assert_eq!(bed(&text), d);
        let out = expanded(&d, Dfs);
        assert_eq!(out.len(), 3 * n + 1);
        assert!(out.starts_with("[F[F"));
        // bfs rewrites the whole word once per level (quadratic here), so
        // it is compared on the first 500 levels only.
        assert_eq!(segments(&d, Dfs).unwrap().len(), n);
        let small = bed(&nested(500));
        let wanted = segments(&small, Dfs).unwrap();
        assert_eq!(segments(&small, Bfs).unwrap(), wanted);
        drop(d);
    });
}

#[test]
fn nesting_of_a_hundred_thousand_is_refused_before_parsing() {
    let n = 100_000;
    let src = nested(n);
    let e = parse(&src, Format::Bed, &Limits::default()).unwrap_err();
    let too_deep = ErrorKind::Input(InputError::NestingTooDeep { limit: 10_000 });
    assert_eq!(e.first_kind(), Some(&too_deep));
}

// ------------------------------------------------------------ proptests --

/// A small deterministic generator of BEDs (xorshift), so a failing case is
/// reproducible from its seed; the flag makes a 3D BED (its drawing with
/// `& ^ \ /`).
struct Gen(u64, bool);

impl Gen {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn chance(&mut self, percent: u64) -> bool {
        self.below(100) < percent
    }
    fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
        xs[self.below(xs.len() as u64) as usize]
    }
    /// k/1000 in [lo, hi).
    fn milli(&mut self, lo: i64, hi: i64) -> f64 {
        (lo * 1000 + self.below(((hi - lo) * 1000) as u64) as i64) as f64 / 1000.0
    }
    /// k/8 in (0, hi]: exact in binary, so corner sums are exact.
    fn eighth(&mut self, hi: u64) -> f64 {
        (1 + self.below(hi * 8)) as f64 / 8.0
    }
    fn letters(&mut self, max: u64) -> String {
        let symbols: &[&str] = if self.1 {
            &["F", "f", "+", "-", "L", "R", "|", "F", "&", "^", "\\", "/"]
        } else {
            &["F", "f", "+", "-", "L", "R", "|", "F"]
        };
        (0..1 + self.below(max))
            .map(|_| self.pick(symbols))
            .collect()
    }
    /// Drawing with balanced nested brackets.
    fn drawing(&mut self) -> String {
        let mut s = self.letters(3);
        if self.chance(40) {
            s = format!("{s}[{}]{}", self.letters(3), self.letters(2));
        }
        s
    }
    fn fixed(&mut self) -> Fixed {
        let (count, word, loc) = (1 + self.below(3) as u32, self.drawing(), Loc::default());
        Fixed { count, word, loc }
    }
}

fn run(text: String) -> DrawRun {
    let loc = Loc::default();
    DrawRun { text, loc }
}

/// Appends the drawing `$t` to `$items`: to the `$draw` run that ends
/// them (the parser reads adjacent letters as one run), else as a new one.
macro_rules! push_run {
    ($items:expr, $draw:path, $t:expr) => {{
        let t: String = $t;
        match $items.last_mut() {
            Some($draw(r)) => r.text.push_str(&t),
            _ => $items.push($draw(run(t).into())),
        }
    }};
}

fn gen_body(g: &mut Gen, rules: usize) -> Body {
    let mut items: Vec<BodyItem> = Vec::new();
    for _ in 0..1 + g.below(4) {
        match g.below(3) {
            0 => push_run!(items, BodyItem::Draw, g.letters(3)),
            1 => items.push(BodyItem::Fixed(g.fixed())),
            _ => {
                let mut pieces: Vec<Piece> = Vec::new();
                for _ in 0..g.below(3) {
                    if g.chance(70) {
                        push_run!(pieces, Piece::Draw, g.drawing());
                    } else {
                        pieces.push(Piece::Fixed(g.fixed()));
                    }
                }
                let successor = g.chance(30).then(|| RuleRef {
                    rule: RuleId(g.below(rules as u64) as usize),
                    loc: Loc::default(),
                });
                items.push(BodyItem::Branch(Branch {
                    pieces,
                    successor,
                    loc: Loc::default(),
                }));
            }
        }
    }
    Body { items }
}

fn gen_term(g: &mut Gen, terms: &mut Terms, rules: &[RuleDef], depth: u32) -> TermId {
    let rule = g.below(rules.len() as u64) as usize;
    let m = rules[rule].branch_count();
    let slots = (0..m)
        .map(|_| {
            if depth == 0 || g.chance(40) {
                None
            } else if g.chance(20) {
                let count = 1 + g.below(2) as u32;
                let (rule, loc) = (RuleId(g.below(rules.len() as u64) as usize), Loc::default());
                Some(terms.repeat(Repeat { count, rule, loc }))
            } else {
                Some(Terms::slot_of(gen_term(g, terms, rules, depth - 1)))
            }
        })
        .collect::<Vec<_>>();
    terms.push(RuleId(rule), false, 0..0, &slots)
}

fn gen_shape(g: &mut Gen) -> LayoutShape {
    let color_text = g.pick(&["clGreen", "clWhite", "#00ff00", "clRed", "#abc"]);
    let (x, y) = (g.eighth(100) - 50.0, g.eighth(100));
    let (w, h) = (g.eighth(50), g.eighth(50));
    let (shape, spelling) = match g.below(6) {
        0 => (Shape::Rect { x, y, w, h }, Spelling::StartSize),
        1 => (Shape::Rect { x, y, w, h }, Spelling::Corners),
        2 => (Shape::Ellipse { x, y, w, h }, Spelling::Corners),
        3 => {
            let r = g.eighth(5);
            (round_rect(x, y, w, h, r, r), Spelling::StartSize)
        }
        4 => {
            let (rx, ry) = (g.eighth(5), g.eighth(5));
            (round_rect(x, y, w, h, rx, ry), Spelling::Corners)
        }
        _ => {
            let pts = (0..3 + g.below(3))
                .map(|_| (g.eighth(100), g.eighth(100)))
                .collect();
            (Shape::Polygon(pts), Spelling::Points)
        }
    };
    LayoutShape {
        color: Rgb::parse(color_text).unwrap(),
        color_text: color_text.to_string(),
        shape,
        spelling,
        angled: g.chance(50),
        loc: Loc::default(),
    }
}

/// A volume of a 3D layout, sizes in eighths (exact, positive).
fn gen_solid(g: &mut Gen) -> LayoutSolid {
    let color_text = g.pick(&["clGreen", "clWhite", "#00ff00", "clRed", "#abc"]);
    let mut p = || [g.eighth(100) - 50.0, g.eighth(100), g.eighth(40) - 20.0];
    let point = p();
    let solid = match g.below(6) {
        0 => cuboid(point, [g.eighth(50), g.eighth(50), g.eighth(50)]),
        1 => sphere(point, g.eighth(50)),
        2 => ellipsoid(point, [g.eighth(50), g.eighth(50), g.eighth(50)]),
        3 => cylinder(point, g.eighth(20), g.eighth(80)),
        4 => {
            let z1 = g.eighth(40) - 40.0;
            let (shape, z2) = (gen_shape(g).shape, z1 + g.eighth(40));
            Solid::Extrude { shape, z1, z2 }
        }
        _ => Solid::Revolve {
            shape: gen_shape(g).shape,
        },
    };
    LayoutSolid {
        color: Rgb::parse(color_text).unwrap(),
        color_text: color_text.to_string(),
        solid,
        loc: Loc::default(),
    }
}

fn gen_description(seed: u64) -> Description {
    let mut g = Gen(seed | 1, false);
    g.1 = g.chance(40);
    let three = g.1;
    let pool = ["R1", "R2", "Crown", "FL", "Rn_2"];
    let n = 1 + g.below(3) as usize;
    let start = g.below(pool.len() as u64) as usize;
    let names: Vec<&str> = (0..n).map(|i| pool[(start + i) % pool.len()]).collect();
    let rules: Vec<RuleDef> = names
        .iter()
        .map(|name| RuleDef {
            name: name.to_string(),
            name_loc: Loc::default(),
            alternative: None,
            body: gen_body(&mut g, n),
            loc: Loc::default(),
        })
        .collect();
    let mut items: Vec<SeedItem> = Vec::new();
    let mut terms = Terms::new();
    for _ in 0..g.below(5) {
        match g.below(5) {
            0 => push_run!(items, SeedItem::Draw, g.drawing()),
            1 => items.push(SeedItem::Fixed(Box::new(g.fixed()))),
            2 => {
                let (count, loc) = (1 + g.below(3) as u32, Loc::default());
                let rule = RuleId(g.below(n as u64) as usize);
                items.push(SeedItem::Repeat(Box::new(Repeat { count, rule, loc })));
            }
            3 => {
                // A term inside a seed bracket: `[+F`, term, `]`.
                let open = format!("[{}", g.letters(2));
                push_run!(items, SeedItem::Draw, open);
                let t = gen_term(&mut g, &mut terms, &rules, 3);
                items.push(SeedItem::Term(t));
                push_run!(items, SeedItem::Draw, "]".into());
            }
            _ => {
                let t = gen_term(&mut g, &mut terms, &rules, 4);
                items.push(SeedItem::Term(t));
            }
        }
    }
    let layout = g.chance(60).then(|| {
        let (n, t) = (g.below(4), three);
        Layout {
            shapes: (0..n).filter(|_| !t).map(|_| gen_shape(&mut g)).collect(),
            solids: (0..n).filter(|_| t).map(|_| gen_solid(&mut g)).collect(),
            loc: Loc::default(),
        }
    });
    let root_z = three.then(|| g.milli(-100, 100));
    let divergence = (three && g.chance(60)).then(|| g.milli(-360, 360));
    let loc = Loc::default();
    let seed = g.chance(90).then_some(Seed { items, terms, loc });
    // A 3D forest: a second root, with a seed of its own.
    let forest = match (three && g.chance(30), &seed) {
        (true, Some(_)) => vec![stlc::model::Tree {
            root: (g.milli(-100, 100), g.milli(-100, 100)),
            root_z: Some(g.milli(-100, 100)),
            root_loc: Loc::default(),
            seed: Some(Seed {
                items: vec![SeedItem::Draw(Box::new(run(g.drawing())))],
                terms: Terms::new(),
                loc: Loc::default(),
            }),
        }],
        _ => Vec::new(),
    };
    Description {
        format: Format::Bed,
        name: g.pick(&["T", "2DTree", "tree_1"]).to_string(),
        name_loc: Loc::default(),
        root: (g.milli(-100, 100), g.milli(-100, 100)),
        root_z,
        root_loc: Loc::default(),
        params: StemParams {
            length: Linear::new(g.milli(20, 100), g.milli(0, 2)),
            width: Linear::new(g.milli(1, 10), if g.chance(50) { 0.0 } else { 0.125 }),
            angle: g.chance(50).then(|| g.milli(0, 90)),
            clearance: g.chance(50).then(|| g.milli(0, 5)),
            divergence,
            stroke: g
                .chance(30)
                .then(|| colour(Some(Rgb::new(0x80, 0, 0)), g.pick(&["clMaroon", "#800000"]))),
            background: g.chance(30).then(|| match g.chance(50) {
                true => colour(None, "none"),
                false => colour(Some(Rgb::WHITE), "#ffffff"),
            }),
            stroke_end: None,
            leaf: None,
            design: Default::default(),
            loc: Loc::default(),
        },
        rules,
        seed,
        layout,
        forest,
        surfaces: None,
    }
}

/// A colour as written (`text`) and what it paints (`None`: nothing).
fn colour(rgb: Option<Rgb>, text: &str) -> stlc::model::Colour {
    let text = text.to_string();
    stlc::model::Colour { rgb, text }
}

/// The round trip's generator makes 3D descriptions too: roots with z, a
/// forest, `D=`, volumes of every kind and 3D turns in bodies and seeds.
#[test]
fn the_generator_makes_3d_descriptions_with_everything_3d() {
    let (mut roots, mut forests, mut divergences, mut turns) = (0, 0, 0, 0);
    // The kinds of volume met (Box, Sphere, Ellipsoid, Cylinder, Extrude, Revolve).
    let mut kinds = std::collections::HashSet::new();
    for seed in 0..400 {
        let d = gen_description(seed);
        if !d.is_3d() {
            continue;
        }
        roots += 1;
        forests += usize::from(d.forest.iter().any(|t| t.root_z.is_some()));
        divergences += usize::from(d.params.divergence.is_some());
        let text = write(&d);
        turns += usize::from(text.contains('&') || text.contains('\\'));
        for s in d.layout.iter().flat_map(|l| &l.solids) {
            kinds.insert(std::mem::discriminant(&s.solid));
        }
        assert_eq!(bed(&text), d, "{text}");
    }
    assert!(roots > 100 && forests > 10 && divergences > 50 && turns > 50);
    assert_eq!(kinds.len(), 6);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn parse_write_roundtrips(seed in any::<u64>()) {
        let d = gen_description(seed);
        let text = write(&d);
        let back = match parse(&text, Format::Bed, &Limits::default()) {
            Ok(b) => b,
            Err(e) => panic!("{e}\n{text}"),
        };
        prop_assert_eq!(&back, &d, "{}", text);
        prop_assert_eq!(write(&back), text);
    }

    #[test]
    fn dfs_and_bfs_draw_the_same(seed in any::<u64>()) {
        let d = gen_description(seed);
        let a = segments(&d, Dfs);
        let b = segments(&d, Bfs);
        prop_assert_eq!(&a, &b);
        if d.is_3d() {
            prop_assert_eq!(segments3(&d, Dfs), segments3(&d, Bfs));
        }
        if a.is_ok() {
            prop_assert_eq!(expanded(&d, Dfs), expanded(&d, Bfs));
        }
    }
}

#[test]
fn the_example_files_parse_and_expand_as_the_paper_says() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let read = |n: &str| std::fs::read_to_string(dir.join(n)).unwrap();
    let d = bed(&read("paper-worked.bed"));
    let worked = "[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]\n";
    assert_eq!(expanded(&d, Dfs), worked);
    let d = bed(&read("seed-r1r2r2.bed"));
    let worked = "[FFF][F[+F][-F]F][F[+F][-F]F]\n";
    assert_eq!(expanded(&d, Bfs), worked);
    assert_eq!(od(&read("2dtree.od")).layout.unwrap().shapes.len(), 3);
}

// ---------------------------------------------------------------- 3D --

/// Section 11's 3D header and volumes, read as written; both spellings of
/// `Extrude` (plain, the last two numbers z1 and z2, or the shape in angle
/// brackets) are the same volume.
#[test]
fn a_3d_description_reads_roots_divergence_turns_and_volumes() {
    let d = bed(
        "Oak (150, 298, 0) (60, 280, -12.5) L=10(1) B=2(0.2) A=30 D=137.5 \
         RULE R1: [+F&F][-F^F][\\F/F] SEED F R1{,,} ENDSEED SEED F ENDSEED \
         LAYOUT (clGreen) Box (1, 2, 3), 4, 5, 6 \
         (clWhite) Sphere (150, 150, 0), 40 \
         (#00ff00) Ellipsoid (1, 2, 3), 4, 5, 6 \
         (clGreen) Cylinder (150, 298, 0), 10, 60 \
         (clGreen) Extrude Ellipse (50, 40), 200, 180, -30, 30 \
         (clGreen) Extrude <Ellipse (50, 40), 200, 180>, -30, 30 \
         (clGreen) <Revolve <RoundRect (0, 0), 10, 20, 2>> \
         ENDLAYOUT",
    );
    assert_eq!((d.root, d.root_z), ((150.0, 298.0), Some(0.0)));
    assert_eq!(d.forest[0].root_z, Some(-12.5));
    assert_eq!(d.params.divergence, Some(137.5));
    let l = d.layout.as_ref().unwrap();
    assert!(l.shapes.is_empty());
    let solids: Vec<&Solid> = l.solids.iter().map(|s| &s.solid).collect();
    let (x, y, w, h) = (50.0, 40.0, 200.0, 180.0);
    let ellipse = Shape::Ellipse { x, y, w, h };
    let (shape, z1, z2) = (ellipse, -30.0, 30.0);
    let extruded = Solid::Extrude { shape, z1, z2 };
    assert_eq!(
        solids,
        [
            &cuboid([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]),
            &sphere([150.0, 150.0, 0.0], 40.0),
            &ellipsoid([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]),
            &cylinder([150.0, 298.0, 0.0], 10.0, 60.0),
            &extruded,
            &extruded,
            &Solid::Revolve {
                shape: round_rect(0.0, 0.0, 10.0, 20.0, 2.0, 2.0)
            },
        ]
    );
    assert_eq!(l.solids[1].color, Rgb::WHITE);
    let text = write(&d);
    let head = "Oak\n(150, 298, 0) (60, 280, -12.5)\nL=10(1) B=2(0.2) A=30 D=137.5\n";
    assert!(text.starts_with(head), "{text}");
    let holds = text.contains("(clGreen) Extrude <Ellipse (50, 40), 200, 180>, -30, 30\n");
    assert!(holds, "{text}");
    assert!(text.contains("R1: [+F&F][-F^F][\\F/F]\n"), "{text}");
    assert_eq!(bed(&text), d);
}

/// Mixing 2D and 3D: each mistake is reported where it is, and the 2D
/// forms keep working in a 2D file.
#[test]
fn mixing_2d_and_3d_is_reported_where_it_happens() {
    let one = |src: &str| {
        let e = errors(src);
        (e.0[0].kind.clone(), e.0[0].span.clone().unwrap())
    };
    let src = "T (0, 0, 0) (1, 1) RULE R1: [F]";
    let mixed = ErrorKind::Stl(StlError::MixedRoots { first: 3, this: 2 });
    assert_eq!(one(src), (mixed, at(src, "(1, 1)", 0)));
    let src = "T (0, 0) RULE R1: [F/F]";
    let (kind, span) = one(src);
    assert_eq!(span, at(src, "/", 0));
    assert!(matches!(kind, ErrorKind::Stl(StlError::Needs3d { .. })));
    let e = errors(src);
    assert!(e.0[0].help_text().unwrap().contains("`(0, 0, 0)`"));
    // In a seed and in `[I n w]` alike.
    let src = "T (0, 0) RULE R1: [F] SEED [I 2 F^F] ENDSEED";
    assert_eq!(one(src).1, at(src, "^", 0));
    let src = "T (0, 0) D=5 RULE R1: [F]";
    assert_eq!(one(src).1, at(src, "D=5", 0));
    let src = "T (0, 0, 0) RULE R1: [F] LAYOUT (clGreen) Rectangle (0, 0), 5, 5 ENDLAYOUT";
    let e = errors(src);
    let wanted = ErrorKind::Layout(LayoutError::FlatShapeIn3d { shape: "Rectangle" });
    assert_eq!(one(src), (wanted, at(src, "Rectangle (0, 0), 5, 5", 0)));
    let help = e.0[0].help_text().unwrap();
    let both = [
        "`Extrude Rectangle (0, 0), 5, 5, z1, z2`",
        "`Revolve Rectangle (0, 0), 5, 5`",
    ];
    assert!(both.iter().all(|b| help.contains(b)), "{help}");
    let src = "T (0, 0) RULE R1: [F] LAYOUT (clGreen) Sphere (0, 0, 0), 5 ENDLAYOUT";
    let wanted = ErrorKind::Layout(LayoutError::SolidIn2d { shape: "Sphere" });
    assert_eq!(one(src).0, wanted);
    // Sizes and depths.
    let src = "T (0, 0, 0) RULE R1: [F] LAYOUT (clGreen) Box (0, 0, 0), 5, 0, 5 ENDLAYOUT";
    let at = src.find("5, 0, 5").unwrap() + 3;
    let (shape, what) = ("Box", "height");
    let size = ErrorKind::Layout(LayoutError::ShapeSizeNotPositive { shape, what });
    assert_eq!(one(src), (size, at..at + 1));
    let src =
        "T (0, 0, 0) RULE R1: [F] LAYOUT (clGreen) Extrude Ellipse (0, 0), 5, 5, 3, 3 ENDLAYOUT";
    assert_eq!(one(src).0, ErrorKind::Layout(LayoutError::ExtrudeRange));
    for bad in [
        "Sphere (0, 0), 5",
        "Sphere (0, 0, 0), 5, 6",
        "Extrude Ellipse (0, 0), 5, 5",
        "Revolve <Ellipse (0, 0), 5, 5>, 1",
        "Extrude Sphere (0, 0, 0), 5, 1, 2",
        "Box Ellipse (0, 0), 5, 5",
    ] {
        let src = format!("T (0, 0, 0) RULE R1: [F] LAYOUT (clGreen) {bad} ENDLAYOUT");
        let kind = one(&src).0;
        let arguments = matches!(kind, ErrorKind::Layout(LayoutError::ShapeArguments { .. }));
        assert!(arguments, "{bad}");
    }
}
