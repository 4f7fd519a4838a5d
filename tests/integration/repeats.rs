//! `[I n X]`, X a rule, has one expander (`model::walk::Levels`): the
//! measured size of a BED (`Bed::size`), its expansion (`dfs` and `bfs`
//! segments) and growth of the same seed from an OD agree with each other
//! and with counts worked out by hand, for every n. `n = 0` (which the
//! parser refuses) is built in code: it applies nothing.

use stlc::bed::Bed;
use stlc::grow::GrowthOrder;
use stlc::interpret::Derivation::{self, Bfs, Dfs};
use stlc::interpret::bed::draw_into;
use stlc::model::*;
use stlc::progress::NoProgress;
use stlc::syntax::stl::parse;
use stlc::turtle::{Recorder, Segment};
use stlc::{Limits, bed::Size};

/// `F [I n R1]` with `R1: F[+F][-F]`, no layout, thin stems, no
/// clearance, and right angles with lengths falling fast enough (an H-tree)
/// that growth has room for all 7 levels. `n = 0` is read as 1 and then
/// rewritten in the model.
fn desc(n: u32, format: Format) -> Description {
    let text = format!(
        "T (0, 0) L=100(14) B=0.0001(0) A=90 C=0\nRULE\nR1: F[+F][-F]\nSEED\nF [I {} R1]\nENDSEED\n",
        n.max(1)
    );
    let mut d = parse(&text, format, &Limits::default()).unwrap_or_else(|e| panic!("{e}"));
    if n == 0 {
        let seed = d.seed.as_mut().unwrap();
        let SeedItem::Repeat(r) = &mut seed.items[1] else {
            panic!("the seed's second item is the repeat")
        };
        r.count = 0;
    }
    d
}

/// Worked out by hand: one `R1` is `Enter F [ + F ] [ - F ] Leave`, 11
/// symbols and 3 stems; `[I n R1]` applies it `2^n - 1` times (one at the
/// top, two below each); the seed's `F` adds one of each.
fn by_hand(n: u32) -> Size {
    let applications = (1u64 << n) - 1;
    Size {
        symbols: 1 + 11 * applications,
        stems: 1 + 3 * applications,
    }
}

fn segments(bed: &Bed, d: Derivation) -> Vec<Segment> {
    let limits = Limits::default();
    let drawn = draw_into(bed, d, &limits, Recorder::default(), &mut NoProgress);
    drawn.unwrap_or_else(|e| panic!("{e}")).segments
}

#[test]
fn measure_expansion_and_growth_agree_for_every_count() {
    for n in [0, 1, 2, 7] {
        let want = by_hand(n);
        let bed = Bed::new(desc(n, Format::Bed), &Limits::default()).unwrap();
        assert_eq!(bed.size(), want, "measured, n = {n}");
        let drawn = segments(&bed, Dfs);
        assert_eq!(drawn.len() as u64, want.stems, "dfs segments, n = {n}");
        assert_eq!(segments(&bed, Bfs), drawn, "bfs, n = {n}");
        for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
            let o = crate::support::opts(growth);
            let g = crate::grow::grown(&desc(n, Format::Od), o);
            assert_eq!(g.stems, want.stems, "grown stems, n = {n}, {growth:?}");
            assert_eq!(g.bed.size(), want, "the grown BED, n = {n}, {growth:?}");
            let grown = segments(&g.bed, Dfs);
            assert_eq!(
                grown, drawn,
                "the grown BED's segments, n = {n}, {growth:?}"
            );
        }
    }
}

/// `[I 0 R1]` in a slot is an empty slot, measured and drawn alike.
#[test]
fn a_zero_count_in_a_slot_is_an_empty_slot() {
    let mut d = desc(1, Format::Bed);
    let seed = d.seed.as_mut().unwrap();
    let mut terms = Terms::new();
    let (count, rule, loc) = (0, RuleId(0), Loc::default());
    let zero = terms.repeat(Repeat { count, rule, loc });
    let with_zero = terms.push(RuleId(0), false, 0..0, &[Some(zero), None]);
    seed.items[1] = SeedItem::Term(with_zero);
    seed.terms = terms;
    let bed = Bed::new(d, &Limits::default()).unwrap();
    // `F` and one `R1`, as `F [I 1 R1]`.
    assert_eq!(bed.size(), by_hand(1));
    let one = Bed::new(desc(1, Format::Bed), &Limits::default()).unwrap();
    let one = segments(&one, Dfs);
    assert_eq!(segments(&bed, Dfs), one);
    assert_eq!(segments(&bed, Bfs), one);
}
