//! The PNG backend's unit tests: folding, blots, covering strokes, batches.

use super::*;
use crate::render::Style;

fn turtle() -> PngTurtle {
    wide_turtle(1.0)
}

/// Draws a connected run through `points` (output pixels, scale 1).
fn run(t: &mut PngTurtle, points: &[Point]) {
    for w in points.windows(2) {
        t.segment(Segment {
            from: w[0],
            to: w[1],
            order: 0,
        });
    }
    t.end_subpath();
}

#[test]
fn a_run_of_sub_pixel_segments_folds_to_its_exact_end() {
    // 100 steps of 0.001 px zigzagging right: 0.1 px in all, one line.
    let points: Vec<Point> = (0..=100)
        .map(|i| Point::new(10.0 + f64::from(i) * 0.001, 10.0 + f64::from(i % 2) * 0.01))
        .collect();
    let mut t = turtle();
    run(&mut t, &points);
    assert_eq!(t.batch.len(), 2, "move and one line");
    let end = t.batch.last_point().unwrap();
    assert_eq!((end.x, end.y), (10.1, 10.0));
}

#[test]
fn segments_of_the_tolerance_or_longer_are_all_kept() {
    let points: Vec<Point> = (0..=40)
        .map(|i| Point::new(10.0 + f64::from(i) * FOLD_PX, 20.0 + f64::from(i % 2)))
        .collect();
    let mut t = turtle();
    run(&mut t, &points);
    assert_eq!(t.batch.len(), points.len());
}

#[test]
fn a_long_run_keeps_a_vertex_per_tolerance_and_its_end() {
    // 1000 steps of 0.01 px along a line: 10 px, a vertex every
    // 0.25 px (25 steps; float sums may need one more step).
    let points: Vec<Point> = (0..=1000)
        .map(|i| Point::new(5.0 + f64::from(i) * 0.01, 50.0))
        .collect();
    let mut t = turtle();
    run(&mut t, &points);
    assert!((40..=42).contains(&t.batch.len()), "{}", t.batch.len());
    let end = t.batch.last_point().unwrap();
    assert_eq!((end.x, end.y), (15.0, 50.0));
}

/// A connected run's stand-in is folded as the run it stands for: the
/// 10 px chord of 1000 segments of 0.01 px gets a vertex every 0.25 px
/// (39 inside, the move and the end: 41 points, as the run itself gets
/// 40 to 42 above); of 10 segments of 1 px, one at every segment end
/// (11 points, as 10 segments); and the end is exact.
#[test]
fn a_runs_stand_in_is_folded_as_the_run() {
    let chord = stem(5.0, 50.0, 15.0, 50.0);
    for (segments, points) in [(1000.0, 41), (10.0, 11)] {
        let mut t = turtle();
        t.run(chord, segments);
        t.end_subpath();
        assert_eq!(t.batch.len(), points, "{segments} segments");
        let end = t.batch.last_point().unwrap();
        assert_eq!((end.x, end.y), (15.0, 50.0));
    }
    let mut exact = turtle();
    let ten: Vec<Point> = (0..=10)
        .map(|i| Point::new(5.0 + f64::from(i), 50.0))
        .collect();
    run(&mut exact, &ten);
    assert_eq!(exact.batch.len(), 11);
}

/// `--exact` strokes every BATCH_SEGMENTS segments as a path and starts
/// the next with a new run; a stand-in's run breaks where that happens:
/// after runs of 1000 segments, at the fifth (4096 crossed), not before.
#[test]
fn a_runs_stand_in_breaks_where_the_exact_drawing_starts_a_path() {
    let mut t = turtle();
    for i in 0..5 {
        let x = 5.0 + f64::from(i) * 0.1;
        t.run(stem(x, 50.0, x + 0.1, 50.0), 1000.0);
        assert_eq!(t.last_to.is_none(), i == 4, "run {i}");
    }
}

#[test]
fn runs_do_not_fold_across_a_jump() {
    // Two 0.1 px runs 0.05 px apart: two subpaths, both drawn.
    let mut t = turtle();
    run(&mut t, &[Point::new(10.0, 10.0), Point::new(10.1, 10.0)]);
    run(&mut t, &[Point::new(10.15, 10.0), Point::new(10.25, 10.0)]);
    assert_eq!(t.batch.len(), 4);
}

/// A blot is a capsule painted by distance: full ink within its
/// radius less half a pixel, half at its radius, none a pixel out;
/// two blots accumulate. A sparse stand-in is an ordinary segment.
#[test]
fn blots_paint_by_distance_and_accumulate() {
    // Stems 1 px, so blots are 2 px wide: radius 1 around (10.5, 10.5).
    let mut t = turtle();
    let dot = stem(10.5, 10.5, 10.5, 10.5);
    t.stand_in(&StandIn::blot(dot, 5.0));
    let p = t.into_raster().unwrap();
    let at = |p: &Pixmap, x, y| p.pixel(x, y).unwrap().red();
    assert_eq!(at(&p, 10, 10), 0, "centre: full ink");
    // Centre 1 px away: coverage 0.5, 255 * (1 - 128/255) rounded.
    assert_eq!(at(&p, 11, 10), 127);
    assert_eq!(at(&p, 10, 9), 127);
    assert_eq!(at(&p, 12, 10), 255, "1.5 px out: untouched");
    let mut twice = turtle();
    twice.stand_in(&StandIn::blot(dot, 5.0));
    twice.stand_in(&StandIn::blot(dot, 5.0));
    assert_eq!(
        at(&twice.into_raster().unwrap(), 11, 10),
        63,
        "source-over twice"
    );
    // Density under BLOT_DENSITY: a 1 px hairline segment, not a blot.
    let mut sparse = turtle();
    sparse.stand_in(&StandIn::blot(stem(20.0, 10.5, 40.0, 10.5), 1.0));
    assert_eq!(sparse.paths, 0);
    sparse.flush();
    assert_eq!(sparse.paths, 1);
    let p = sparse.into_raster().unwrap();
    assert!(at(&p, 30, 10) < 128 && at(&p, 30, 12) == 255);
}

fn wide_turtle(width: f64) -> PngTurtle {
    let fit = Fit {
        width: 100,
        height: 100,
        scale: 1.0,
        dx: 0.0,
        dy: 0.0,
    };
    let style = Style {
        stroke: Rgb::BLACK,
        background: Some(Rgb::WHITE),
        width: Width::Pixels(width),
    };
    PngTurtle::new(fit, &style).unwrap()
}

fn stem(ax: f64, ay: f64, bx: f64, by: f64) -> Segment {
    Segment {
        from: Point::new(ax, ay),
        to: Point::new(bx, by),
        order: 0,
    }
}

/// A stroke wider than the picture many times over (tiny-skia 0.12
/// panics near 10^10 px) paints every pixel the stroke colour, with no
/// path stroked, and later strokes change nothing. One whose half
/// width falls short of the farthest corner is a real stroke: a 100 x
/// 100 raster's farthest corner from the point (50, 50) is 70.7 px away.
#[test]
fn a_stroke_wider_than_the_picture_covers_it_without_the_rasteriser() {
    let all =
        |p: &Pixmap, v: u8| (0..100).all(|y| (0..100).all(|x| p.pixel(x, y).unwrap().red() == v));
    for width in [1.0e10, 1.0e300, 142.0] {
        let mut t = wide_turtle(width);
        t.segment(stem(50.0, 50.0, 50.0, 50.0));
        t.segment(stem(10.0, 10.0, 20.0, 20.0));
        assert_eq!(t.paths, 0, "{width}");
        assert!(t.covered);
        assert!(
            all(&t.into_raster().unwrap(), 0),
            "{width}: all stroke colour"
        );
    }
    let mut t = wide_turtle(140.0);
    t.segment(stem(50.0, 50.0, 50.0, 50.0));
    assert!(!t.covered, "70 < 70.7: a stroke");
    t.flush();
    assert_eq!(t.paths, 1);
    let mut t = wide_turtle(130.0);
    t.segment(stem(50.0, 50.0, 50.0, 50.0));
    let p = t.into_raster().unwrap();
    // The corner pixel's centre is 70.0 px from (50, 50), 5 px out.
    assert_eq!(p.pixel(0, 0).unwrap().red(), 255);
    assert_eq!(p.pixel(50, 50).unwrap().red(), 0);
    // Far outside the picture, too far to reach it even 10^10 px wide:
    // drawn at the widest the rasteriser takes, and nothing panics.
    let mut t = wide_turtle(1.0e10);
    t.segment(stem(1.0e11, 0.0, 1.0e11, 10.0));
    assert!(!t.covered);
    assert!(all(&t.into_raster().unwrap(), 255));
}

/// One path unions its strokes, so the same wide stem drawn 10,000 times
/// (more than a batch) paints exactly what drawing it once paints, and
/// is stroked once.
#[test]
fn a_repeated_wide_stem_paints_what_one_paints_and_is_stroked_once() {
    let mut once = wide_turtle(12.0);
    once.segment(stem(20.0, 80.0, 70.0, 30.0));
    let mut many = wide_turtle(12.0);
    for _ in 0..10_000 {
        many.segment(stem(20.0, 80.0, 70.0, 30.0));
        many.segment(stem(70.0, 30.0, 60.0, 10.0));
    }
    many.flush();
    assert_eq!(many.paths, 1);
    let mut twice = wide_turtle(12.0);
    twice.segment(stem(20.0, 80.0, 70.0, 30.0));
    twice.segment(stem(70.0, 30.0, 60.0, 10.0));
    assert_eq!(many.into_raster().unwrap(), twice.into_raster().unwrap());
    assert_ne!(
        once.into_raster().unwrap().data(),
        wide_turtle(12.0).into_raster().unwrap().data()
    );
}

/// Overlapping wide strokes are split into paths of at most
/// INK_PER_BATCH images' worth of ink: 100 x 100 px allows 20,000 px;
/// each 90 px stroke 10 px wide counts 10 x (90 + 10) = 1,000, so 20 go
/// in a path and 100 distinct strokes make 5 paths.
#[test]
fn overlapping_wide_strokes_are_drawn_in_paths_of_bounded_ink() {
    let mut t = wide_turtle(10.0);
    for i in 0..100 {
        let x = 5.0 + f64::from(i) * 0.5;
        t.segment(stem(x, 5.0, x, 95.0));
    }
    t.flush();
    assert_eq!(t.paths, 5);
    // Hairlines never count as wide: 100 of them go in one path.
    let mut h = turtle();
    for i in 0..100 {
        let x = 5.0 + f64::from(i) * 0.5;
        h.segment(stem(x, 5.0, x, 95.0));
    }
    h.flush();
    assert_eq!(h.paths, 1);
}

// ---------------------------------------------------------------------------
// Bands

/// A drawing that reaches every band of a 150 x 300 picture (five bands,
/// the last 44 rows): a layout fill, long and short hairlines across band
/// edges, wide strokes, blots (a level of detail) and one stroke width
/// change after another.
fn busy(t: &mut PngTurtle) {
    t.fill(&Fill {
        color: Rgb::new(200, 230, 200),
        rings: vec![vec![
            Point::new(10.0, 5.0),
            Point::new(140.0, 60.0),
            Point::new(120.0, 290.0),
            Point::new(5.0, 200.0),
        ]],
    });
    t.set_detail(Some(0.5));
    for i in 0..200 {
        let f = f64::from(i);
        let x = 5.0 + (f * 37.0) % 140.0;
        let y = (f * 53.0) % 300.0;
        t.segment(stem(x, y, x + 3.0 - f % 7.0, y + 9.0 - f % 19.0));
        t.segment(stem(x + 3.0 - f % 7.0, y + 9.0 - f % 19.0, x, y + 0.3));
        if i % 10 == 0 {
            t.stand_in(&StandIn::blot(stem(x, y, x + 0.4, y + 0.2), 5.0));
        }
    }
    for i in 0..40 {
        let x = 3.0 + 3.7 * f64::from(i);
        t.segment(stem(x, 0.0, 150.0 - x, 300.0));
    }
}

fn busy_fit() -> Fit {
    Fit {
        width: 150,
        height: 300,
        scale: 1.0,
        dx: 0.0,
        dy: 0.0,
    }
}

fn busy_style(width: f64) -> Style {
    Style {
        stroke: Rgb::new(20, 90, 20),
        background: Some(Rgb::WHITE),
        width: Width::Pixels(width),
    }
}

/// The bands' pixels are a function of the bands, not of the threads: one
/// thread (no thread started), two, three, and more threads than bands
/// paint the same bytes; and they are a drawing, not a blank.
#[test]
fn banded_pixels_are_the_same_with_any_number_of_threads() {
    for width in [1.0, 0.5, 3.0, 12.0] {
        let style = busy_style(width);
        let one = draw_in_threads(busy_fit(), &style, 1, |t| {
            busy(t);
            Ok(())
        })
        .unwrap();
        let inked = one.pixels().iter().filter(|p| p.green() < 200).count();
        assert!(inked > 2_000, "{width}: {inked} inked pixels");
        for threads in [2, 3, 8] {
            let many = draw_in_threads(busy_fit(), &style, threads, |t| {
                busy(t);
                Ok(())
            })
            .unwrap();
            assert!(one == many, "width {width}, {threads} threads");
        }
        // Against one raster: the same drawing but for the anti-aliasing
        // of lines across a band's edge.
        let mut whole = PngTurtle::new(busy_fit(), &style).unwrap();
        busy(&mut whole);
        let whole = whole.into_raster().unwrap();
        let diff: u64 = one
            .data()
            .iter()
            .zip(whole.data())
            .map(|(a, b)| u64::from(a.abs_diff(*b)))
            .sum();
        let mean = diff as f64 / one.data().len() as f64;
        assert!(mean < 1.0, "width {width}: mean {mean}/255 a channel");
    }
}

/// Blots are painted by distance, each pixel from its own centre, so a
/// banded raster's blots are exactly one raster's; so is a cover.
#[test]
fn banded_blots_and_covers_are_exactly_one_rasters() {
    let draw = |t: &mut PngTurtle| {
        for i in 0..100 {
            let f = f64::from(i);
            let (x, y) = (7.0 + (f * 13.0) % 130.0, (f * 31.0) % 300.0);
            t.stand_in(&StandIn::blot(stem(x, y, x + 2.0, y + 1.5), 3.0));
        }
    };
    let style = busy_style(2.0);
    let mut whole = PngTurtle::new(busy_fit(), &style).unwrap();
    draw(&mut whole);
    let banded = draw_in_threads(busy_fit(), &style, 2, |t| {
        draw(t);
        Ok(())
    })
    .unwrap();
    assert!(whole.into_raster().unwrap() == banded);
    let covered = draw_in_threads(busy_fit(), &busy_style(1e9), 2, |t| {
        t.segment(stem(75.0, 150.0, 75.0, 150.0));
        t.segment(stem(1.0, 1.0, 2.0, 2.0));
        Ok(())
    })
    .unwrap();
    assert!(covered.pixels().iter().all(|p| p.green() == 90));
}

/// A subpath goes to the bands whose rows it reaches, anti-aliasing and
/// caps included (half the width and 2 px), moved up by the band's top.
#[test]
fn subpaths_are_routed_to_the_bands_they_reach() {
    let mut r = bands::Router::new(300);
    let sub = |r: &mut bands::Router, pts: &[(f32, f32)], width: f32| {
        for &(x, y) in pts {
            r.point(x, y);
        }
        r.end(width);
    };
    sub(&mut r, &[(1.0, 10.0), (2.0, 20.0)], 1.0); // band 0 only
    sub(&mut r, &[(3.0, 61.0), (4.0, 62.0)], 1.0); // 62 + 2.5 reaches band 1
    sub(&mut r, &[(5.0, 70.0), (6.0, 200.0)], 1.0); // bands 1, 2, 3
    sub(&mut r, &[(7.0, 299.0), (8.0, 299.5)], 1.0); // the last band, 4
    let paths = r.take();
    let bands: Vec<usize> = paths.iter().map(|(b, _)| *b).collect();
    assert_eq!(bands, [0, 1, 2, 3, 4]);
    let points =
        |b: usize| -> Vec<(f32, f32)> { paths[b].1.points().iter().map(|p| (p.x, p.y)).collect() };
    assert_eq!(
        points(0),
        [(1.0, 10.0), (2.0, 20.0), (3.0, 61.0), (4.0, 62.0)]
    );
    assert_eq!(
        points(1),
        [(3.0, -3.0), (4.0, -2.0), (5.0, 6.0), (6.0, 136.0)]
    );
    assert_eq!(points(3), [(5.0, -122.0), (6.0, 8.0)]);
    assert_eq!(points(4), [(7.0, 43.0), (8.0, 43.5)]);
    assert!(r.take().is_empty(), "taken: the next batch starts empty");
}
