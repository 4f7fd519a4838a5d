//! A 3D view of a system that paints, past what the exact view affords:
//! stand-ins carry the colours inside them (docs/3d.md, *Colours and
//! organs inside stand-ins*), and below that size the view is the exact
//! one.

use crate::support::{manifest_path, outcome, png_at, stlc_line};

/// Pixels within 40 of `rgb` in every channel, and inked pixels (a
/// channel under 200).
fn near(png: &tiny_skia::Pixmap, rgb: [u8; 3]) -> (usize, usize) {
    let (mut near, mut inked) = (0, 0);
    for p in png.pixels() {
        let c = p.demultiply();
        let px = [c.red(), c.green(), c.blue()];
        inked += usize::from(px.iter().any(|&v| v < 200));
        near += usize::from(px.iter().zip(rgb).all(|(&a, b)| a.abs_diff(b) <= 40));
    }
    (near, inked)
}

#[test]
fn fig_1_26_at_depth_16_is_drawn_with_its_flowers_and_stems_in_their_colours() {
    // Depth 16: some 10^9 modules and 10^8 stems, over the exact view's
    // 10^7 (its --exact is refused, after some 40 s of counting).
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("deep.png");
    let input = manifest_path("examples/abop-1.26.lsys");
    let (input, to) = (input.display(), out.display());
    let line = format!("render {input} --depth 16 --size 300x300 -o {to}");
    let (code, _, err) = outcome(&mut stlc_line(&line));
    assert_eq!(code, 0, "{err}");
    let png = png_at(&out);
    // The stems' green (#2f5d1e), and the flowers: stamens' yellow
    // (#f2c230) over their pedicels' green, a colour between the two
    // (nearer the yellow) where they are stand-ins. Without colours in
    // the stand-ins the crown would be one palette colour or the ink.
    let (green, inked) = near(&png, [0x2f, 0x5d, 0x1e]);
    let flowers = png
        .pixels()
        .iter()
        .filter(|p| {
            let c = p.demultiply();
            (0x90..=0xf2).contains(&c.red())
                && (0x5d..=0xc2).contains(&c.green())
                && (0x1e..=0x30).contains(&c.blue())
        })
        .count();
    assert!(inked > 2000, "{inked} inked");
    assert!(
        green > inked / 10 && flowers > inked / 10,
        "{green} green, {flowers} flowers of {inked}"
    );
}

#[test]
fn below_its_budget_a_painting_view_is_the_exact_one() {
    let dir = tempfile::tempdir().unwrap();
    let input = manifest_path("examples/plant3d.lsys");
    let mut pictures = Vec::new();
    for exact in ["", "--exact"] {
        let out = dir.path().join(format!("p{}.png", exact.len()));
        let (input, to) = (input.display(), out.display());
        let line = format!("render {input} --depth 9 --size 200x200 {exact} -o {to}");
        stlc_line(&line).assert().success();
        pictures.push(std::fs::read(&out).unwrap());
    }
    assert!(pictures[0] == pictures[1], "the same bytes");
}
