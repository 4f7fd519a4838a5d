//! Coverage of space-first growth against bfs and dfs (issue 34):
//!
//! ```text
//! cargo build --release --example bench_space
//! target/release/examples/bench_space examples/holes.od benches/space/box-hole.od
//! ```
//!
//! For each `.od` (2D or 3D, with a LAYOUT): grows it bfs unbounded, then
//! bfs, dfs and space-first with a budget of a third of those stems
//! (`--max-stems`), and measures on a grid over the region (200 x 200
//! cells of its box in 2D, 40^3 in 3D, the cells' centres the region holds)
//! the share of the grid within 2 L of a stem (L: the seed's segment
//! length) and the mean distance from a grid point to the nearest stem's
//! centre line. Prints one Markdown table row per file and order.

use stlc::grow::grow3::region::Region3;
use stlc::grow::region::Region;
use stlc::grow::{GrowOptions, GrowthOrder, PlacedStem, grow_traced};
use stlc::limits::Limits;
use stlc::model::{Description, Format};
use stlc::progress::NoProgress;
use stlc::turtle::Point;

/// The squared distance from `p` to the stem's centre line.
fn dist2(p: [f64; 3], s: &PlacedStem) -> f64 {
    let a = [s.from.x, s.from.y, s.z[0]];
    let b = [s.to.x, s.to.y, s.z[1]];
    let d: [f64; 3] = std::array::from_fn(|i| b[i] - a[i]);
    let l2: f64 = d.iter().map(|c| c * c).sum();
    let t = if l2 > 0.0 {
        ((0..3).map(|i| (p[i] - a[i]) * d[i]).sum::<f64>() / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (0..3).map(|i| (p[i] - a[i] - t * d[i]).powi(2)).sum()
}

/// The grid points the region holds.
fn grid(od: &Description) -> Vec<[f64; 3]> {
    let layout = od.layout.as_ref().expect("a LAYOUT");
    let mut out = Vec::new();
    if od.is_3d() {
        let r = Region3::from_layout(layout, [od.root.0, od.root_z.unwrap_or(0.0)], 1_000_000)
            .expect("the region");
        let (lo, hi) = r.bounds();
        let n = 40;
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let p = [i, j, k].map(|c| c as f64);
                    let p =
                        std::array::from_fn(|d| lo[d] + (p[d] + 0.5) * (hi[d] - lo[d]) / n as f64);
                    if r.covers_point(p) {
                        out.push(p);
                    }
                }
            }
        }
    } else {
        let r = Region::from_layout(layout, 1_000_000).expect("the region");
        let b = r.bbox();
        let n = 200;
        for i in 0..n {
            for j in 0..n {
                let x = b.min_x + (i as f64 + 0.5) * (b.max_x - b.min_x) / n as f64;
                let y = b.min_y + (j as f64 + 0.5) * (b.max_y - b.min_y) / n as f64;
                if r.covers_point(Point::new(x, y)) {
                    out.push([x, y, 0.0]);
                }
            }
        }
    }
    out
}

fn main() {
    println!("| file | order | stems | within 2L | mean distance (L) |");
    println!("| --- | --- | ---: | ---: | ---: |");
    for path in std::env::args().skip(1) {
        let text = std::fs::read_to_string(&path).expect("readable");
        let od = stlc::syntax::stl::parse(&text, Format::Od, &Limits::default()).expect("an OD");
        let l = od.params.length.base;
        let opts = |growth, max_stems| GrowOptions {
            growth,
            limits: Limits {
                max_stems,
                ..Limits::default()
            },
            max_stems_explicit: true,
            seed: od.params.design.seed.unwrap_or(0),
            ..GrowOptions::default()
        };
        let all = grow_traced(&od, &opts(GrowthOrder::Bfs, 10_000_000), &mut NoProgress)
            .expect("growth")
            .1
            .len() as u64;
        let pts = grid(&od);
        let name = std::path::Path::new(&path)
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        for growth in [GrowthOrder::Bfs, GrowthOrder::Dfs, GrowthOrder::Space] {
            let (_, stems) =
                grow_traced(&od, &opts(growth, all / 3), &mut NoProgress).expect("growth");
            let (mut near, mut sum) = (0usize, 0.0);
            for &p in &pts {
                let d = stems
                    .iter()
                    .map(|s| dist2(p, s))
                    .fold(f64::INFINITY, f64::min)
                    .sqrt();
                near += usize::from(d <= 2.0 * l);
                sum += d;
            }
            println!(
                "| {name} | {growth} | {} of {all} | {:.1} % | {:.2} |",
                stems.len(),
                100.0 * near as f64 / pts.len() as f64,
                sum / pts.len() as f64 / l
            );
        }
    }
}
