//! Bytes -> `precheck` -> the `.od`/`.bed` parser, both formats. For a BED
//! that parses: `bed::validate` and `Bed::new` (they agree, and the measured
//! stems are the segments drawn), the canonical writer and its round trip
//! (`parse(write(x)) == x` when every number of `x` is written exactly;
//! `write` a fixed point always), and drawing it with both derivations into
//! bounding turtles under small limits (they must agree bit for bit).

use stlc::bed::{Bed, validate, write::write};
use stlc::diag::{BedError, Diagnostics, ErrorKind};
use stlc::interpret::{Derivation, bed};
use stlc::limits::Limits;
use stlc::model::{Description, Format, Shape};
use stlc::progress::NoProgress;
use stlc::syntax::{precheck, stl};
use stlc::turtle::{Bounds, Counter};

/// The defaults, tightened so every input runs in milliseconds.
const LIMITS: Limits = Limits {
    max_input_bytes: 1 << 16,
    max_nesting: 1_000,
    max_depth: 16,
    max_repeat: 16,
    max_symbols: 100_000,
    max_word: 100_000,
    max_stems: 10_000,
    max_rule_parts: 1_000,
    max_layout_shapes: 100,
    ..Limits::DEFAULT
};

/// Every number the writer prints for `d`, as it computes them.
fn numbers(d: &Description) -> Vec<f64> {
    let p = &d.params;
    let mut v = vec![
        d.root.0,
        d.root.1,
        p.length.base,
        p.length.decrement,
        p.width.base,
        p.width.decrement,
    ];
    v.extend(p.angle);
    v.extend(p.clearance);
    for s in d.layout.iter().flat_map(|l| &l.shapes) {
        match &s.shape {
            Shape::Rect { x, y, w, h } | Shape::Ellipse { x, y, w, h } => {
                v.extend([*x, *y, *w, *h, x + w, y + h]);
            }
            Shape::RoundRect { x, y, w, h, rx, ry } => {
                v.extend([*x, *y, *w, *h, x + w, y + h, 2.0 * rx, 2.0 * ry]);
            }
            Shape::Polygon(pts) => v.extend(pts.iter().flat_map(|&(x, y)| [x, y])),
        }
    }
    v
}

/// Numbers that survive printing with three decimals, and arithmetic on
/// them, exactly: multiples of 1/2 well inside f64's integer range.
fn exact(d: &Description) -> bool {
    numbers(d)
        .iter()
        .all(|&v| (2.0 * v).fract() == 0.0 && v.abs() < (1u64 << 40) as f64)
}

fn check_spans(e: &Diagnostics, text: &str) {
    assert!(e.has_errors(), "an Err without an error: {e:?}");
    for d in e.iter() {
        for s in d.span.iter().chain(d.labels.iter().map(|l| &l.span)) {
            assert!(
                s.start <= s.end && s.end <= text.len(),
                "span {s:?} outside the text"
            );
            assert!(text.is_char_boundary(s.start) && text.is_char_boundary(s.end));
        }
    }
}

fn roundtrip(x: &Description, format: Format) {
    let w = write(x);
    let y = match stl::parse(&w, format, &LIMITS) {
        Ok(y) => y,
        Err(e) => panic!("the writer's output does not parse back:\n{w}\n{e}"),
    };
    if exact(x) {
        assert_eq!(&y, x, "parse(write(x)) != x; written:\n{w}");
    }
    let w2 = write(&y);
    assert_eq!(w, w2, "write is not a fixed point");
}

fn bits(b: &Bounds) -> Option<[u64; 4]> {
    b.bbox()
        .map(|b| [b.min_x, b.min_y, b.max_x, b.max_y].map(f64::to_bits))
}

/// One input: returns normally, or panics on a broken promise.
pub fn run(data: &[u8]) {
    let Ok(text) = precheck(data, &LIMITS) else {
        return;
    };
    match stl::parse(text, Format::Od, &LIMITS) {
        Ok(od) => roundtrip(&od, Format::Od),
        Err(e) => check_spans(&e, text),
    }
    let x = match stl::parse(text, Format::Bed, &LIMITS) {
        Ok(x) => x,
        Err(e) => return check_spans(&e, text),
    };
    roundtrip(&x, Format::Bed);
    let valid = validate(&x, &LIMITS);
    let bed = Bed::new(x, &LIMITS);
    assert_eq!(
        valid,
        bed.as_ref().map(Bed::size).map_err(Clone::clone),
        "validate and Bed::new disagree"
    );
    let bed = match bed {
        Ok(bed) => bed,
        Err(e) => {
            // The parser resolved names and slot counts: what is left are
            // orders and counts and sizes against the limits.
            for d in e.iter() {
                assert!(
                    matches!(
                        d.kind,
                        ErrorKind::Limit { .. } | ErrorKind::Bed(BedError::OrderTooDeep { .. })
                    ),
                    "unexpected validation error of a parsed BED: {d}"
                );
            }
            return;
        }
    };
    let mut count = Counter::default();
    bed::draw(&bed, Derivation::Dfs, &LIMITS, &mut count, &mut NoProgress).expect("validated");
    assert_eq!(
        count.0,
        bed.size().stems,
        "the measured stems and the drawn segments differ"
    );
    let dfs = bed::draw_into(
        &bed,
        Derivation::Dfs,
        &LIMITS,
        Bounds::default(),
        &mut NoProgress,
    )
    .expect("validated");
    match bed::draw_into(
        &bed,
        Derivation::Bfs,
        &LIMITS,
        Bounds::default(),
        &mut NoProgress,
    ) {
        Ok(bfs) => {
            assert_eq!(
                dfs.count, bfs.count,
                "dfs and bfs draw different segment counts"
            );
            assert_eq!(bits(&dfs), bits(&bfs), "dfs and bfs draw different boxes");
        }
        Err(e) => assert!(
            matches!(e.first_kind(), Some(ErrorKind::Limit { .. })),
            "bfs failed where dfs did not: {e}"
        ),
    }
    assert_eq!(count.0, dfs.count);
}
