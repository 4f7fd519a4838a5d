//! Bytes -> `.od` parser -> the grower (both growth orders, tight limits) ->
//! the canonical writer. What grows must be a BED that reads back, passes
//! `Bed::new` (or meets only the symbol budget) and draws.

use stlc::bed::{Bed, write::write};
use stlc::diag::{BedError, ErrorKind, GrowError, LayoutError};
use stlc::grow::{GrowOptions, GrowthOrder, grow};
use stlc::interpret::{Derivation, bed};
use stlc::limits::Limits;
use stlc::model::Format;
use stlc::progress::NoProgress;
use stlc::syntax::{precheck, stl};
use stlc::turtle::Counter;

/// Every limit tightened, so every input runs in milliseconds.
const LIMITS: Limits = Limits {
    max_input_bytes: 1 << 16,
    max_nesting: 1_000,
    max_depth: 16,
    max_repeat: 16,
    max_symbols: 100_000,
    max_word: 100_000,
    max_stems: 300,
    max_layout_vertices: 2_000,
    max_rule_parts: 1_000,
    max_layout_shapes: 100,
};

/// The errors growth may give for an OD the parser accepted. Not among
/// them: `UnboundedGrowth` (`max_stems` is given explicitly, which bounds
/// any growth), `BadClearance` (the parser admits only finite `C >= 0` and
/// finite `L`), `UndeclaredRule`, `UnknownRule` and `SlotCount` (the parser
/// resolved names and slot counts).
fn acceptable_growth_error(kind: &ErrorKind) -> bool {
    matches!(
        kind,
        // A budget: seed stems, layout vertices, symbols of the grown BED.
        ErrorKind::Limit { .. }
            // No SEED and no rule.
            | ErrorKind::Grow(GrowError::NothingToGrow)
            // The layout: the root outside it, no area left, or shapes
            // whose corners overflow (`x + w` infinite).
            | ErrorKind::Grow(GrowError::RootOutside { .. })
            | ErrorKind::Layout(LayoutError::EmptyRegion)
            | ErrorKind::Layout(LayoutError::LayoutNotFinite)
            // A term written out in the seed at an order where stems have
            // no length or width (`Bed::new` of the grown BED).
            | ErrorKind::Bed(BedError::OrderTooDeep { .. })
    )
}

/// One input: returns normally, or panics on a broken promise.
pub fn run(data: &[u8]) {
    let Ok(text) = precheck(data, &LIMITS) else {
        return;
    };
    let Ok(od) = stl::parse(text, Format::Od, &LIMITS) else {
        return;
    };
    for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs] {
        let opts = GrowOptions {
            growth,
            clearance: None,
            limits: LIMITS,
            max_stems_explicit: true,
            // Alternatives choose by seed: vary it with the input.
            seed: data.len() as u64,
        };
        let grown = match grow(&od, &opts, &mut NoProgress) {
            Ok(g) => g,
            Err(e) => {
                for d in e.iter().filter(|d| d.is_error()) {
                    assert!(
                        acceptable_growth_error(&d.kind),
                        "unexpected growth error: {d}"
                    );
                }
                continue;
            }
        };
        assert!(grown.stems <= LIMITS.max_stems, "{} stems", grown.stems);
        let w = write(grown.bed.description());
        let back = match stl::parse(&w, Format::Bed, &LIMITS) {
            Ok(b) => b,
            Err(e) => panic!("the grown BED does not read back:\n{w}\n{e}"),
        };
        let back = match Bed::new(back, &LIMITS) {
            Ok(b) => b,
            Err(e) => {
                // Only the symbol budget may refuse a grown tree (fixed
                // figures in rules can be large); never names, slots or
                // orders.
                assert!(
                    e.iter().all(|d| matches!(d.kind, ErrorKind::Limit { .. })),
                    "grown BED invalid:\n{w}\n{e}"
                );
                continue;
            }
        };
        let c = bed::draw_into(
            &back,
            Derivation::Dfs,
            &LIMITS,
            Counter::default(),
            &mut NoProgress,
        )
        .expect("validated");
        assert_eq!(
            c.0,
            back.size().stems,
            "the measured stems and the drawn segments differ:\n{w}"
        );
    }
}
