//! Per-pixel difference of two PNGs of the same size (the level-of-detail
//! figures in docs/rendering.md), and side-by-side pictures.
//!
//! ```sh
//! cargo run --release --example pixdiff -- A.png B.png
//! #   mean 0.41/255 max 96/255 differing 3012 (>16: 512, >64: 20) of 262144 inked 9233 9761
//! cargo run --release --example pixdiff -- A.png B.png side.png [ZOOM X Y W H]
//! ```
//!
//! The difference of a pixel is the largest of its channels' absolute
//! differences; the mean is over every pixel; "inked" counts each
//! image's pixels at least half inked (over 127 from the background). With a third argument, writes
//! A and B side by side (optionally the `W` x `H` crop at `X`, `Y` of each,
//! magnified `ZOOM` times, nearest neighbour) with a grey rule between.

use tiny_skia::Pixmap;

fn load(path: &str) -> Pixmap {
    Pixmap::load_png(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (a, b) = (load(&args[0]), load(&args[1]));
    assert_eq!(
        (a.width(), a.height()),
        (b.width(), b.height()),
        "sizes differ"
    );
    let (mut sum, mut max, mut differing, mut over16, mut over64) = (0u64, 0u8, 0u64, 0u64, 0u64);
    for (p, q) in a.pixels().iter().zip(b.pixels()) {
        let d = [
            p.red().abs_diff(q.red()),
            p.green().abs_diff(q.green()),
            p.blue().abs_diff(q.blue()),
            p.alpha().abs_diff(q.alpha()),
        ]
        .into_iter()
        .max()
        .unwrap_or(0);
        sum += u64::from(d);
        max = max.max(d);
        differing += u64::from(d > 0);
        over16 += u64::from(d > 16);
        over64 += u64::from(d > 64);
    }
    let n = a.pixels().len() as u64;
    println!(
        "mean {:.3}/255 max {max}/255 differing {differing} (>16: {over16}, >64: {over64}) of {n} inked {} {}",
        sum as f64 / n as f64,
        inked(&a),
        inked(&b)
    );
    if let Some(out) = args.get(2) {
        let num = |i: usize, d: u32| args.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
        let zoom = num(3, 1);
        let (x0, y0) = (num(4, 0), num(5, 0));
        let w = num(6, a.width() - x0).min(a.width() - x0);
        let h = num(7, a.height() - y0).min(a.height() - y0);
        let gap = 4;
        let mut side = Pixmap::new(2 * w * zoom + gap, h * zoom).expect("size");
        side.fill(tiny_skia::Color::from_rgba8(160, 160, 160, 255));
        for (i, src) in [&a, &b].into_iter().enumerate() {
            let ox = i as u32 * (w * zoom + gap);
            for y in 0..h * zoom {
                for x in 0..w * zoom {
                    let p = src.pixel(x0 + x / zoom, y0 + y / zoom).expect("inside");
                    let at = ((y * side.width()) + ox + x) as usize;
                    side.pixels_mut()[at] = p;
                }
            }
        }
        side.save_png(out).expect("write");
    }
}

/// Pixels at least half inked: the largest channel difference from the
/// background (the top-left pixel) over 127.
fn inked(p: &Pixmap) -> u64 {
    let bg = p.pixels()[0];
    let diff = |q: &tiny_skia::PremultipliedColorU8| {
        [
            q.red().abs_diff(bg.red()),
            q.green().abs_diff(bg.green()),
            q.blue().abs_diff(bg.blue()),
            q.alpha().abs_diff(bg.alpha()),
        ]
        .into_iter()
        .max()
        .unwrap_or(0)
    };
    p.pixels().iter().filter(|q| diff(q) > 127).count() as u64
}
