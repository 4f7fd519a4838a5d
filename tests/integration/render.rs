//! Rendering: PNG and SVG backends, fitting, widths, underlay.
//!
//! Drawings come from hand-written op strings run through the shared
//! interpreter, so every expected pixel and coordinate here is worked out
//! from the geometry, not read back from the renderer. References live in
//! `tests/cases/render/`, compared by [`crate::support`].

use stlc::color::Rgb;
use stlc::diag::RenderError::ImageSize;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, RenderError};
use stlc::num::Linear;
use stlc::progress::{NoProgress, Progress};
use stlc::render::{self, DEFAULT_SIDE, Fit, ImageFormat, PngTurtle, RenderOptions, Style, Width};
use stlc::turtle::{BBox, Fill, Interp, Op, Point, Segment, Turtle};
use tiny_skia::Pixmap;

use crate::support::{assert_golden, assert_golden_png, segment_distance};

// ---------------------------------------------------------------------------
// Helpers

/// Ops of a drawing string: the STL alphabet, plus `{` / `}` for entering
/// and leaving a rule application (one order deeper).
fn ops(text: &str) -> Vec<Op> {
    text.chars()
        .filter_map(|c| match c {
            '{' => Some(Op::Enter),
            '}' => Some(Op::Leave),
            c => Op::of_stl(c),
        })
        .collect()
}

/// Runs `ops` from the origin with unit-length stems (minus `decrement` per
/// order).
fn run(ops: &[Op], angle: f64, decrement: f64, turtle: &mut dyn Turtle) {
    let length = Linear::new(1.0, decrement);
    let mut interp = Interp::new(turtle, Point::new(0.0, 0.0), angle, length);
    for &op in ops {
        interp.apply(op);
    }
}

fn style(width: Width, background: Option<Rgb>) -> Style {
    Style {
        stroke: Rgb::BLACK,
        background,
        width,
    }
}

/// Renders `text` (see [`ops`]) and returns the bytes.
fn render_ops(
    text: &str,
    angle: f64,
    style: &Style,
    format: ImageFormat,
    size: Option<(u32, u32)>,
) -> Vec<u8> {
    render_full(text, angle, 0.0, None, &[], style, format, size).unwrap()
}

/// The SVG text of `text` (see [`ops`]).
fn svg_of(text: &str, angle: f64, style: &Style, size: Option<(u32, u32)>) -> String {
    String::from_utf8(render_ops(text, angle, style, ImageFormat::Svg, size)).unwrap()
}

/// The PNG of `text` (see [`ops`]), decoded.
fn png_of(text: &str, angle: f64, style: &Style, size: Option<(u32, u32)>) -> Pixmap {
    decode(&render_ops(text, angle, style, ImageFormat::Png, size))
}

/// The PNG of `text` at 90 degrees, with `decrement` and `view`, decoded.
fn png_full(
    text: &str,
    decrement: f64,
    view: Option<BBox>,
    style: &Style,
    size: Option<(u32, u32)>,
) -> Pixmap {
    let png = ImageFormat::Png;
    decode(&render_full(text, 90.0, decrement, view, &[], style, png, size).unwrap())
}

#[allow(clippy::too_many_arguments)]
fn render_full(
    text: &str,
    angle: f64,
    decrement: f64,
    view: Option<BBox>,
    underlay: &[Fill],
    style: &Style,
    format: ImageFormat,
    size: Option<(u32, u32)>,
) -> Result<Vec<u8>, Diagnostics> {
    let ops = ops(text);
    let mut drawing = |t: &mut dyn Turtle, _p: &mut dyn Progress| {
        run(&ops, angle, decrement, t);
        Ok(())
    };
    let (mut out, opts) = (Vec::new(), RenderOptions::new(format, size));
    let quiet = &mut NoProgress;
    render::render(&mut drawing, view, underlay, style, &opts, &mut out, quiet)?;
    Ok(out)
}

/// The `--exact` SVG of `text`: every segment written.
fn exact_svg(text: &str, angle: f64, style: &Style, size: Option<(u32, u32)>) -> String {
    let ops = ops(text);
    let mut drawing = |t: &mut dyn Turtle, _p: &mut dyn Progress| {
        run(&ops, angle, 0.0, t);
        Ok(())
    };
    let (mut out, mut opts) = (Vec::new(), RenderOptions::new(ImageFormat::Svg, size));
    opts.exact = true;
    let quiet = &mut NoProgress;
    render::render(&mut drawing, None, &[], style, &opts, &mut out, quiet).unwrap();
    String::from_utf8(out).unwrap()
}

/// `drawing` rendered in `format` at `size` with 1 px black stems, no view,
/// underlay or background, into `out`.
fn render_plain(
    drawing: &mut render::Drawing<'_>,
    format: ImageFormat,
    size: Option<(u32, u32)>,
    out: &mut dyn std::io::Write,
) -> Result<Option<u64>, Diagnostics> {
    let st = style(Width::Pixels(1.0), None);
    let opts = RenderOptions::new(format, size);
    render::render(drawing, None, &[], &st, &opts, out, &mut NoProgress)
}

fn decode(png: &[u8]) -> Pixmap {
    Pixmap::decode_png(png).expect("a valid PNG")
}

/// Demultiplied RGBA of one pixel.
pub fn rgba(p: &Pixmap, x: u32, y: u32) -> [u8; 4] {
    let c = p.pixel(x, y).unwrap().demultiply();
    [c.red(), c.green(), c.blue(), c.alpha()]
}

/// Dark: an opaque pixel much closer to black than to white.
fn is_dark(p: &Pixmap, x: u32, y: u32) -> bool {
    let [r, g, b, a] = rgba(p, x, y);
    a > 200 && u32::from(r) + u32::from(g) + u32::from(b) < 3 * 100
}

/// The stroked polylines of an SVG written by stlc: each `<path
/// fill="none" ...>`'s `d` as segments, in output pixels, with its width.
fn svg_strokes(svg: &str) -> Vec<(f64, Vec<(Point, Point)>)> {
    let attr = |line: &str, name: &str| -> String {
        let start = line.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        let end = start + line[start..].find('"').unwrap();
        line[start..end].to_string()
    };
    svg.lines()
        .filter(|l| l.starts_with("<path fill=\"none\""))
        .map(|l| {
            let width: f64 = attr(l, "stroke-width").parse().unwrap();
            let d = attr(l, "d");
            let mut segs = Vec::new();
            let mut at = Point::default();
            let mut letters = d.chars().filter(|c| *c == 'M' || *c == 'L');
            for coords in d.split(['M', 'L']).skip(1) {
                let mut v = coords.split_whitespace().map(|n| n.parse().unwrap());
                let p = Point::new(v.next().unwrap(), v.next().unwrap());
                if letters.next() == Some('L') {
                    segs.push((at, p));
                }
                at = p;
            }
            (width, segs)
        })
        .collect()
}

/// The distance from `p` to the nearest of `lines`.
fn distance_to_nearest(p: Point, lines: &[(Point, Point)]) -> f64 {
    let d = |&(a, b): &(Point, Point)| segment_distance((p.x, p.y), (a.x, a.y), (b.x, b.y));
    lines.iter().map(d).fold(f64::INFINITY, f64::min)
}

/// A small branching tree: trunk, two branches of order 1 each carrying two
/// twigs of order 2 (the `{ }` mark rule applications).
const TREE: &str = "FF[+{FF[+{F}][-{F}]}][-{FF[+{F}][-{F}]}]";

// ---------------------------------------------------------------------------
// SVG

#[test]
fn unit_square_svg_matches_its_golden() {
    // At 90 degrees, FF+... draws (0,0) -> (0,-1) -> (-1,-1) -> (-1,0) ->
    // (0,0). Into 100x100 with 2 px strokes: margin 4 + 1 = 5, scale 90,
    // the centre (-0.5,-0.5) at (50,50): corners at 5 and 95.
    let st = style(Width::Pixels(2.0), Some(Rgb::WHITE));
    let svg = svg_of("F+F+F+F", 90.0, &st, Some((100, 100)));
    assert!(svg.contains(" d=\"M95.00 95.00 L95.00 5.00 L5.00 5.00 L5.00 95.00 L95.00 95.00\""));
    assert_golden("tests/cases/render/square.svg", &svg);
}

#[test]
fn svg_is_well_formed_and_byte_deterministic() {
    let st = style(Width::Canvas(Linear::new(0.3, 0.1)), Some(Rgb::WHITE));
    let a = render_full(TREE, 30.0, 0.2, None, &[], &st, ImageFormat::Svg, None).unwrap();
    let b = render_full(TREE, 30.0, 0.2, None, &[], &st, ImageFormat::Svg, None).unwrap();
    assert_eq!(a, b);
    let text = String::from_utf8(a).unwrap();
    assert!(text.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\""));
    assert!(text.ends_with("</svg>\n"));
    assert!(!text.contains('\r') && !text.contains("-0.00") && !text.contains("NaN"));
    // Three widths (orders 0, 1, 2), each in its own path element, thinning.
    let widths: Vec<f64> = svg_strokes(&text).iter().map(|(w, _)| *w).collect();
    assert!(widths.len() >= 3, "{widths:?}");
    let mut distinct = widths.clone();
    distinct.dedup();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup();
    assert_eq!(distinct.len(), 3, "{widths:?}");
}

#[test]
fn svg_background_is_absent_when_transparent() {
    let st = style(Width::Pixels(1.0), None);
    let svg = svg_of("F", 90.0, &st, None);
    assert!(!svg.contains("<rect"), "{svg}");
    let st = style(Width::Pixels(1.0), Some(Rgb::new(1, 2, 3)));
    let svg = svg_of("F", 90.0, &st, None);
    assert!(svg.contains("fill=\"#010203\""));
}

// ---------------------------------------------------------------------------
// PNG

#[test]
fn thick_horizontal_line_is_dark_in_the_middle_and_white_far_away() {
    // Heading right, one stem: (0,0) -> (1,0). Into 100x50 with 10 px
    // strokes: margin 4 + 5 = 9 px, scale 82: the line runs from x = 9 to
    // x = 91 at y = 25, 10 px thick, round caps reaching x = 4 and 96.
    let st = style(Width::Pixels(10.0), Some(Rgb::WHITE));
    let p = png_of("-F", 90.0, &st, Some((100, 50)));
    assert_eq!((p.width(), p.height()), (100, 50));
    for x in [10, 50, 90] {
        assert_eq!(rgba(&p, x, 25), [0, 0, 0, 255], "x = {x}");
        assert_eq!(rgba(&p, x, 22), [0, 0, 0, 255], "x = {x}");
    }
    for (x, y) in [(50, 2), (50, 47), (1, 25), (98, 25), (50, 35)] {
        assert_eq!(rgba(&p, x, y), [255, 255, 255, 255], "({x}, {y})");
    }
}

#[test]
fn no_background_means_transparent() {
    let st = style(Width::Pixels(10.0), None);
    let p = png_of("-F", 90.0, &st, Some((100, 50)));
    assert_eq!(rgba(&p, 50, 2)[3], 0);
    assert_eq!(rgba(&p, 50, 25), [0, 0, 0, 255]);
}

#[test]
fn default_size_is_800_on_the_long_side() {
    // The tree is taller than wide: height 800.
    let p = png_of(TREE, 30.0, &style(Width::Pixels(2.0), None), None);
    assert_eq!(p.height(), DEFAULT_SIDE);
    assert!(p.width() < DEFAULT_SIDE && p.width() > 100, "{}", p.width());
}

#[test]
fn canvas_widths_thin_with_order() {
    // A vertical trunk of order 0 then, after moving right, a vertical stem
    // of order 2 (decrement 1 of base 3: 3 and 1 canvas units). Scale is
    // fixed by the 100-pixel view: 10 px per unit, so 30 px and 10 px.
    let mut view = BBox::at(Point::new(-2.0, -8.0));
    view.add(Point::new(8.0, 2.0));
    let st = style(Width::Canvas(Linear::new(3.0, 1.0)), Some(Rgb::WHITE));
    let p = png_full("FF-fff+{{F}}", 0.0, Some(view), &st, Some((100, 100)));
    let dark_run = |y: u32, x0: u32, x1: u32| (x0..x1).filter(|&x| is_dark(&p, x, y)).count();
    // Trunk at x = 20 px (canvas 0), row y = 70 (canvas -1).
    let trunk = dark_run(70, 0, 40);
    // Stem of order 2 at x = 50 px (canvas 3), rows 60..50 (canvas -2..-3),
    // clear of the trunk's round cap (radius 15 px around (20, 60)).
    let twig = dark_run(55, 40, 70);
    assert!((29..=31).contains(&trunk), "trunk {trunk} px");
    assert!((9..=11).contains(&twig), "twig {twig} px");
}

#[test]
fn widths_below_zero_still_draw_hairlines() {
    let st = style(Width::Canvas(Linear::new(1.0, 2.0)), Some(Rgb::WHITE));
    let p = png_full("{{-F}}", 0.0, None, &st, Some((50, 50)));
    // Widest stroke 1 unit (order 0 never drawn): the 1-unit line is fitted
    // at (50 - 2 * 4.25) / 2 = 20.75 px per unit, centred on row 25.
    let touched = (0..50)
        .filter(|&x| rgba(&p, x, 24)[0] < 255 || rgba(&p, x, 25)[0] < 255)
        .count();
    assert!((19..=23).contains(&touched), "{touched}");
}

#[test]
fn tree_png_matches_its_reference() {
    let st = style(Width::Canvas(Linear::new(0.12, 0.04)), Some(Rgb::WHITE));
    let (png, size) = (ImageFormat::Png, Some((120, 160)));
    let png = render_full(TREE, 30.0, 0.25, None, &[], &st, png, size).unwrap();
    assert_golden_png("tests/cases/render/tree.png", &decode(&png));
}

#[test]
fn png_is_byte_deterministic() {
    let st = style(Width::Pixels(1.5), Some(Rgb::WHITE));
    let a = render_ops(TREE, 25.7, &st, ImageFormat::Png, Some((64, 64)));
    let b = render_ops(TREE, 25.7, &st, ImageFormat::Png, Some((64, 64)));
    assert_eq!(a, b);
}

// ---------------------------------------------------------------------------
// Underlay

#[test]
fn underlay_is_even_odd_and_under_the_strokes() {
    // A 10x10 green square with a 4x4 hole, shown exactly (view 0..10 on
    // 100x100: 10 px per unit), and a vertical stem from (1,9) up to (1,8).
    let ring = |x0: f64, y0: f64, s: f64| {
        let corners = [(0.0, 0.0), (s, 0.0), (s, s), (0.0, s)];
        corners
            .map(|(dx, dy)| Point::new(x0 + dx, y0 + dy))
            .to_vec()
    };
    let green = Rgb::new(0, 128, 0);
    let underlay = [Fill {
        color: green,
        rings: vec![ring(0.0, 0.0, 10.0), ring(3.0, 3.0, 4.0)],
    }];
    let mut view = BBox::at(Point::new(0.0, 0.0));
    view.add(Point::new(10.0, 10.0));
    let st = style(Width::Pixels(4.0), Some(Rgb::WHITE));
    let mut outputs = Vec::new();
    for format in [ImageFormat::Png, ImageFormat::Svg] {
        let mut drawing = |t: &mut dyn Turtle, _: &mut dyn Progress| {
            let mut interp = Interp::new(t, Point::new(1.0, 9.0), 90.0, Linear::constant(1.0));
            ops("F").into_iter().for_each(|op| interp.apply(op));
            Ok(())
        };
        let (mut out, opts) = (Vec::new(), RenderOptions::new(format, Some((100, 100))));
        let view = Some(view);
        let quiet = &mut NoProgress;
        render::render(&mut drawing, view, &underlay, &st, &opts, &mut out, quiet).unwrap();
        outputs.push(out);
    }
    let p = decode(&outputs[0]);
    assert_eq!(rgba(&p, 50, 50), [255, 255, 255, 255], "the hole");
    assert_eq!(rgba(&p, 20, 50), [0, 128, 0, 255], "the ring");
    assert_eq!(rgba(&p, 10, 85), [0, 0, 0, 255], "the stem on top");
    let svg = String::from_utf8(outputs[1].clone()).unwrap();
    let fill = svg.find("fill-rule=\"evenodd\"").unwrap();
    let stroke = svg.find("<path fill=\"none\"").unwrap();
    assert!(fill < stroke, "underlay first");
    assert!(svg.contains(
        "<path fill=\"#008000\" fill-rule=\"evenodd\" d=\"M0.00 0.00 L100.00 0.00 \
         L100.00 100.00 L0.00 100.00 Z M30.00 30.00 L70.00 30.00 L70.00 70.00 L30.00 70.00 Z\"/>"
    ));
}

// ---------------------------------------------------------------------------
// PNG and SVG agree

#[test]
fn png_and_svg_agree() {
    let st = style(Width::Pixels(3.0), Some(Rgb::WHITE));
    let size = Some((150, 200));
    let png = png_of(TREE, 30.0, &st, size);
    // `--exact`: a line a segment.
    let svg = exact_svg(TREE, 30.0, &st, size);
    assert!(svg.contains(" width=\"150\" height=\"200\" viewBox=\"0 0 150 200\""));
    assert_eq!((png.width(), png.height()), (150, 200));

    let strokes = svg_strokes(&svg);
    let segs: Vec<(Point, Point)> = strokes.into_iter().flat_map(|s| s.1).collect();
    assert_eq!(segs.len(), TREE.matches('F').count());
    // Merged (the default): collinear runs are one line, fewer lines,
    // and every segment's points lie on one of them.
    let merged = svg_of(TREE, 30.0, &st, size);
    let lines: Vec<(Point, Point)> = svg_strokes(&merged).into_iter().flat_map(|s| s.1).collect();
    assert!(lines.len() < segs.len(), "{} lines", lines.len());
    for &(a, b) in &segs {
        for t in [0.0, 0.5, 1.0] {
            let p = Point::new(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            let d = distance_to_nearest(p, &lines);
            assert!(d < 0.01, "{p:?} is {d} px from every merged line");
        }
    }
    // Every dark pixel lies within half a stroke (plus a pixel of
    // anti-aliasing) of the SVG's geometry ...
    for y in 0..png.height() {
        for x in 0..png.width() {
            if is_dark(&png, x, y) {
                let c = Point::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let d = distance_to_nearest(c, &segs);
                let ok = d <= 1.5 + 1.0;
                assert!(ok, "dark pixel ({x}, {y}) is {d} px from every path");
            }
        }
    }
    // ... and the PNG is dark all along it.
    for &(a, b) in &segs {
        for i in 0..=10 {
            let t = f64::from(i) / 10.0;
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            let ok = is_dark(&png, x as u32, y as u32);
            assert!(ok, "({x}, {y}) on the path is not dark");
        }
    }
}

// ---------------------------------------------------------------------------
// Edge cases and errors

#[test]
fn empty_and_single_point_drawings_give_valid_images() {
    let st = style(Width::Canvas(Linear::new(1.0, 0.0)), Some(Rgb::WHITE));
    // Nothing drawn: no ops, a move only, turns only.
    for text in ["", "f", "+-"] {
        for format in [ImageFormat::Png, ImageFormat::Svg] {
            let out = render_full(text, 90.0, 0.0, None, &[], &st, format, None).unwrap();
            if format == ImageFormat::Png {
                let p = decode(&out);
                assert_eq!((p.width(), p.height()), (DEFAULT_SIDE, DEFAULT_SIDE));
            } else {
                assert!(String::from_utf8(out).unwrap().ends_with("</svg>\n"));
            }
        }
    }
    // One point drawn: a zero-length stem, fitted without NaN.
    let st = style(Width::Pixels(6.0), Some(Rgb::WHITE));
    let out = render_full("{F}", 90.0, 1.0, None, &[], &st, ImageFormat::Svg, None).unwrap();
    let svg = String::from_utf8(out).unwrap();
    assert!(svg.contains("d=\"M400.00 400.00 L400.00 400.00\""), "{svg}");
    // PNG draws it as a round dot too, like SVG viewers do.
    let out = render_full("{F}", 90.0, 1.0, None, &[], &st, ImageFormat::Png, None).unwrap();
    let p = decode(&out);
    assert!(is_dark(&p, 400, 400) && is_dark(&p, 398, 401));
    assert_eq!(rgba(&p, 410, 400), [255, 255, 255, 255]);
}

#[test]
fn absurd_sizes_are_refused_before_drawing() {
    for size in [(0, 100), (100, 0), (16_385, 100)] {
        let mut called = false;
        let mut drawing = |_: &mut dyn Turtle, _: &mut dyn Progress| {
            called = true;
            Ok(())
        };
        let mut out = Vec::new();
        let err = render_plain(&mut drawing, ImageFormat::Png, Some(size), &mut out).unwrap_err();
        let size = matches!(err.first_kind(), Some(ErrorKind::Render(ImageSize { .. })));
        assert!(size, "{err}");
        assert!(err.to_string().contains("--size"), "{err}");
        assert!(!called && out.is_empty());
    }
}

#[test]
fn drawing_errors_pass_through_and_nothing_is_written() {
    let mut runs = 0;
    let mut drawing = |t: &mut dyn Turtle, _: &mut dyn Progress| {
        runs += 1;
        if runs == 2 {
            return Err(Diagnostic::error(RenderError::DrawingNotFinite).into());
        }
        t.segment(Segment {
            from: Point::new(0.0, 0.0),
            to: Point::new(1.0, 1.0),
            order: 0,
        });
        Ok(())
    };
    let mut out = Vec::new();
    let err = render_plain(&mut drawing, ImageFormat::Png, None, &mut out).unwrap_err();
    let not_finite = ErrorKind::Render(RenderError::DrawingNotFinite);
    assert_eq!(err.first_kind(), Some(&not_finite));
    assert!(out.is_empty());
}

/// A writer whose every write fails with the error `0` makes.
pub struct Failing(pub fn() -> std::io::Error);

impl std::io::Write for Failing {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err((self.0)())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[test]
fn write_errors_become_io_diagnostics() {
    for format in [ImageFormat::Png, ImageFormat::Svg] {
        let ops = ops("FF");
        let mut drawing = |t: &mut dyn Turtle, _: &mut dyn Progress| {
            run(&ops, 90.0, 0.0, t);
            Ok(())
        };
        let mut full = Failing(|| std::io::Error::other("disk full"));
        let err = render_plain(&mut drawing, format, None, &mut full).unwrap_err();
        let full =
            matches!(err.first_kind(), Some(ErrorKind::Io { error, .. }) if error == "disk full");
        assert!(full, "{err}");
    }
}

// ---------------------------------------------------------------------------
// Streaming

#[test]
fn a_million_tiny_segments_stream_through_the_png_backend() {
    // A zigzag of 10^6 segments of a fifth of a pixel, drawn straight into
    // the backend: nothing holds them (batches of a few thousand).
    let fit = Fit {
        width: 200,
        height: 200,
        scale: 1.0,
        dx: 0.0,
        dy: 0.0,
    };
    let mut turtle = PngTurtle::new(fit, &style(Width::Pixels(1.0), Some(Rgb::WHITE))).unwrap();
    let point = |i: u32| {
        // Even rows run right, odd rows back left.
        let (row, col) = (i / 1000, i % 1000);
        let x = col.abs_diff(1000 * (row % 2));
        Point::new(f64::from(x) * 0.19, f64::from(row) * 0.19)
    };
    for i in 0..1_000_000 {
        let (from, to, order) = (point(i), point(i + 1), 0);
        turtle.segment(Segment { from, to, order });
    }
    let p = turtle.into_raster().unwrap();
    assert!(is_dark(&p, 100, 100));
}

// ---------------------------------------------------------------------------
// Bands and threads

/// The PNG `stlc render` writes for `args` (one line) with `--threads threads`.
fn threads_png(args: &str, threads: &str) -> Vec<u8> {
    let line = format!("render {args} -f png -o - -q --threads {threads}");
    crate::support::stlc_stdout(&line.split_whitespace().collect::<Vec<_>>())
}

/// Pixels darker than `level` in the red channel.
fn inked(png: &[u8], level: u8) -> usize {
    let p = decode(png);
    p.pixels().iter().filter(|p| p.red() < level).count()
}

/// Big drawings (2^20 segments or more) are painted in bands; one thread
/// and two write the same bytes: a deterministic system drawn exactly
/// (5^9 = 1,953,125 segments), a stochastic one (1,204,285 segments at
/// depth 11, `stlc stats`), and a level-of-detail drawing at depth 20.
#[test]
fn a_big_png_is_the_same_bytes_with_one_thread_or_two() {
    let root = env!("CARGO_MANIFEST_DIR");
    let tree = format!("{root}/examples/abop-1.24a.lsys");
    let plant = format!("{root}/examples/abop-1.27.lsys");
    for args in [
        format!("{tree} --exact --depth 9 --size 300x600"),
        format!("{plant} --exact --depth 11 --size 400x400"),
        format!("{tree} --depth 20 --size 300x600"),
    ] {
        let one = threads_png(&args, "1");
        let two = threads_png(&args, "2");
        assert!(one == two, "{args:?}");
        // A picture, not a blank: thousands of green pixels (clGreen
        // strokes have no red).
        assert!(inked(&one, 128) > 2_000, "{args:?}: {}", inked(&one, 128));
    }
}

/// A grown tree drawn over its layout in bands (as a tree of 2^20 stems
/// would be: the count is the frame's): the same bytes with one, two and
/// three threads, and the picture of one raster but for anti-aliasing at
/// the bands' edges.
#[test]
fn a_tree_over_its_layout_in_bands_is_the_same_with_any_threads() {
    use stlc::grow::GrowOptions;
    use stlc::pipeline::{self, Look, SceneRequest, ShowLayout};
    use stlc::syntax::InputKind;
    let root = env!("CARGO_MANIFEST_DIR");
    let text = std::fs::read(format!("{root}/examples/2dtree.od")).unwrap();
    let opts = GrowOptions::default();
    let loaded = pipeline::load(&text, InputKind::Od, &opts.limits).unwrap();
    let pipeline::Loaded::Od(desc) = &loaded else {
        panic!("an .od");
    };
    let layout = desc.layout.clone().unwrap();
    let req = SceneRequest {
        grow: opts,
        derivation: Default::default(),
        depth: None,
        limits: opts.limits,
    };
    let scene = pipeline::scene(loaded, &req, &mut NoProgress).unwrap();
    let look = Look {
        show_layout: ShowLayout::Yes,
        ..Look::default()
    };
    let st = pipeline::style(&scene, &look);
    let view = stlc::rings::layout_bbox(&layout).unwrap();
    let fills = stlc::rings::fills(&layout);
    let png = |segments: u64, threads: usize| {
        let mut drawing = |t: &mut dyn Turtle, p: &mut dyn Progress| scene.draw(t, p);
        let mut opts = RenderOptions::new(ImageFormat::Png, Some((500, 700)));
        let mut out = Vec::new();
        opts.threads = threads;
        let segments = Some(segments);
        let frame = render::Frame::View { view, segments };
        let quiet = &mut NoProgress;
        render::render_framed(&mut drawing, frame, &fills, &st, &opts, &mut out, quiet).unwrap();
        decode(&out)
    };
    let banded = png(render::BANDED_SEGMENTS, 1);
    for threads in [2, 3] {
        assert!(banded == png(render::BANDED_SEGMENTS, threads), "{threads}");
    }
    let whole = png(1, 2);
    assert!(banded != whole, "banded: not one raster's bytes");
    let pairs = banded.pixels().iter().zip(whole.pixels());
    let differing = pairs.filter(|(a, b)| a != b).count();
    assert!(differing < 500, "{differing} of 350,000 pixels differ");
    // The layout and the tree are painted: not a white page.
    let white =
        |p: &&tiny_skia::PremultipliedColorU8| (p.red(), p.green(), p.blue()) == (255, 255, 255);
    let painted = banded.pixels().iter().filter(|p| !white(p)).count();
    assert!(painted > 10_000, "{painted}");
}
