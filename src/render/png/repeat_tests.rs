//! Skipping repeated strokes changes no byte: the gallery's `--exact` and
//! level of detail PNGs drawn with every stroke, and with the skips.

use super::DRAW_ALL;
use crate::pipeline::{ImageFormat, Request};
use crate::progress::NoProgress;
use crate::render::png::PngTurtle;
use crate::render::{Fit, RenderOptions, Style, Width};
use crate::turtle::{Point, Segment, Turtle};

/// A picture's size in pixels, `None` for the default.
type Size = Option<(u32, u32)>;

/// The PNG of `text` with `exact`, `size` and `depth`, with the skips
/// (`all` false) or drawing everything.
fn png(
    text: &str,
    exact: bool,
    size: Option<(u32, u32)>,
    depth: Option<u32>,
    all: bool,
) -> Vec<u8> {
    DRAW_ALL.with(|d| d.set(all));
    let mut req = Request::new(text.as_bytes().to_vec());
    req.name = Some("x.lsys".into());
    req.depth = depth;
    req.image = RenderOptions {
        exact,
        threads: 1,
        ..RenderOptions::new(ImageFormat::Png, size)
    };
    let mut out = Vec::new();
    let drawn = req.render(&mut out, &mut NoProgress);
    DRAW_ALL.with(|d| d.set(false));
    drawn.unwrap();
    out
}

fn example(name: &str) -> String {
    let path = format!("{}/examples/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap()
}

/// The gallery's pictures at `size` (the default, or 2048 pixels square),
/// `--exact` and with the level of detail, drawn with every stroke and
/// with the skips: the same bytes. Deep enough that strokes pile up
/// (overdraw); 1.24a at depth 9 is past a million segments, so it is
/// painted in bands.
fn gallery_is_the_same_with_and_without_the_skips(size: Size) {
    let cases: &[(&str, u32)] = &[
        ("abop-1.24a.lsys", 6),
        ("abop-1.24b.lsys", 7),
        ("abop-1.24c.lsys", 6),
        ("abop-1.24d.lsys", 7),
        ("abop-1.24e.lsys", 6),
        ("abop-1.24f.lsys", 6),
        ("abop-1.27.lsys", 6),
        ("hilbert.lsys", 6),
        ("sierpinski-arrowhead.lsys", 7),
        ("koch-snowflake.lsys", 5),
        // Thin 3D stems: hairlines under a pixel, in a translucent paint.
        ("abop-2.8b.lsys", 4),
    ];
    let mut runs: Vec<(&str, u32, bool)> = Vec::new();
    for &(name, depth) in cases {
        runs.extend([(name, depth, true), (name, depth, false)]);
    }
    // Past a million segments: `--exact` at the default size, the level
    // of detail at 2048.
    runs.push(("abop-1.24a.lsys", 9, size.is_none()));
    for (name, depth, exact) in runs {
        let text = example(name);
        let with = png(&text, exact, size, Some(depth), false);
        let without = png(&text, exact, size, Some(depth), true);
        let what = format!("{name} depth {depth} exact {exact} size {size:?}");
        assert!(with == without, "{what}: the skips changed the picture");
    }
}

#[test]
fn the_gallery_is_the_same_with_and_without_the_skips() {
    gallery_is_the_same_with_and_without_the_skips(None);
}

#[test]
fn the_gallery_at_2048_pixels_is_the_same_with_and_without_the_skips() {
    gallery_is_the_same_with_and_without_the_skips(Some((2048, 2048)));
}

#[test]
fn a_square_drawn_over_and_over_is_the_same_and_costs_a_few_strokes() {
    // 20,000 `F+` at 90 degrees: 5,000 times round one square, in
    // batches that are all the same path. (benches/pixels.sh times 2
    // million.)
    let text = format!("axiom {}\nangle 90\n", "F+".repeat(20_000));
    let with = png(&text, true, None, Some(0), false);
    let without = png(&text, true, None, Some(0), true);
    assert!(with == without, "the skips changed the picture");
}

/// A turtle on a 64 x 64 raster, one pixel a canvas unit, hairlines.
fn turtle() -> PngTurtle {
    let style = Style {
        stroke: crate::color::Rgb { r: 0, g: 0, b: 0 },
        background: Some(crate::color::Rgb {
            r: 255,
            g: 255,
            b: 255,
        }),
        width: Width::Pixels(1.0),
    };
    let fit = Fit {
        width: 64,
        height: 64,
        scale: 1.0,
        dx: 0.0,
        dy: 0.0,
    };
    PngTurtle::new(fit, &style).unwrap()
}

/// Strokes the square 8.5-40.5 `times` times round, a batch at a time.
fn square(t: &mut PngTurtle, times: usize) {
    let c = [(8.5, 8.5), (40.5, 8.5), (40.5, 40.5), (8.5, 40.5)];
    for i in 0..times * 4 {
        let (a, b) = (c[i % 4], c[(i + 1) % 4]);
        t.segment(Segment {
            from: Point::new(a.0, a.1),
            to: Point::new(b.0, b.1),
            order: 0,
        });
        if i % 4 == 3 {
            t.flush();
        }
    }
}

#[test]
fn a_repeated_stroke_that_changed_nothing_is_skipped() {
    let mut t = turtle();
    square(&mut t, 300);
    let skipped = t.repeats[0].skipped;
    DRAW_ALL.with(|d| d.set(true));
    let mut all = turtle();
    square(&mut all, 300);
    DRAW_ALL.with(|d| d.set(false));
    assert_eq!(all.repeats[0].skipped, 0);
    // The square takes all the ink it will within a few strokes; every
    // later batch is a repeat that changes nothing.
    assert!(skipped > 250, "{skipped} repeats skipped");
    assert!(t.finish().unwrap() == all.finish().unwrap());
}
