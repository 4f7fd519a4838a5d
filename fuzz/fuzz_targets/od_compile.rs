//! Bytes -> `.od` parser -> the grower (both strategies, tight limits) ->
//! the canonical writer. What grows must be a BED that reads back, passes
//! `bed::validate` (or meet only the symbol budget) and draw.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stlc::bed::{validate, write::write};
use stlc::diag::ErrorKind;
use stlc::grow::{GrowOptions, grow};
use stlc::interpret::{Strategy, bed};
use stlc::limits::Limits;
use stlc::progress::NoProgress;
use stlc::model::Format;
use stlc::syntax::{precheck, stl};
use stlc::turtle::Counter;

const LIMITS: Limits = Limits {
    max_input_bytes: 1 << 16,
    max_nesting: 1_000,
    max_depth: 16,
    max_repeat: 16,
    max_symbols: 100_000,
    max_word: 100_000,
    max_stems: 300,
    max_layout_vertices: 2_000,
};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = precheck(data, &LIMITS) else {
        return;
    };
    let Ok(od) = stl::parse(text, Format::Od, &LIMITS) else {
        return;
    };
    for strategy in [Strategy::Bfs, Strategy::Dfs] {
        let opts = GrowOptions {
            strategy,
            clearance: None,
            limits: LIMITS,
            max_stems_explicit: true,
        };
        let grown = match grow(&od, &opts, &mut NoProgress) {
            Ok(g) => g,
            Err(e) => {
                for d in e.iter().filter(|d| d.is_error()) {
                    assert!(
                        matches!(
                            d.kind,
                            ErrorKind::Grow(_) | ErrorKind::Limit { .. } | ErrorKind::Stl(_)
                        ),
                        "unexpected growth error: {d}"
                    );
                }
                continue;
            }
        };
        assert!(grown.stems <= LIMITS.max_stems, "{} stems", grown.stems);
        let w = write(&grown.bed);
        let back = match stl::parse(&w, Format::Bed, &LIMITS) {
            Ok(b) => b,
            Err(e) => panic!("the grown BED does not read back:\n{w}\n{e}"),
        };
        if let Err(e) = validate(&back, &LIMITS) {
            // Only the symbol budget may refuse a grown tree (fixed figures
            // in rules can be large); never names, slots or orders.
            assert!(
                e.iter().all(|d| matches!(d.kind, ErrorKind::Limit { .. })),
                "grown BED invalid:\n{w}\n{e}"
            );
            continue;
        }
        let mut c = Counter::default();
        bed::draw(&back, Strategy::Dfs, &LIMITS, &mut c, &mut NoProgress).expect("validated");
    }
});
