//! Growth benchmark: time against the number of stems grown.
//!
//! ```text
//! cargo build --release --example bench_grow
//! /usr/bin/time -v target/release/examples/bench_grow bfs rstar 1000000
//! ```
//!
//! Arguments: strategy (`bfs`|`dfs`|`space`), occupancy index (`rstar`,
//! the one left: the spade experiment was removed, docs/dependencies.md),
//! and
//! the number of stems to grow (`--max-stems`; growth stops there with a
//! warning), optionally the side of the square layout (default 4000) and the stroke width B (default 0.1). The tree: `Seed = FR1`, `R1 = [-F][F][+F]`, `L=1`, `B=0.1` (thin: stems keep their distance as drawn), `A=30`,
//! default clearance (0.1), in a 4000 x 4000 rectangle with the root at the
//! middle of the bottom edge: far more room than 10^6 stems take, so every
//! run stops at the limit and the number of stems is exactly the one asked
//! for (up to the last application's size).
//!
//! A sixth argument grows the same tree in space (issue 26): `prism`, the
//! root at z = 0 and the rectangle extruded from z = -side/2 to side/2
//! (a planar tree: the 2D decisions, through the 3D grower), or `cube`,
//! the rectangle's cube as a `Box` with `D=137.5` (the tree spreads around
//! its stems in all three dimensions). `benches/grow3d.sh` runs the three
//! side by side.

use std::time::Instant;

use stlc::grow::occupancy::Backend;
use stlc::grow::{GrowOptions, GrowthOrder, grow_with};
use stlc::limits::Limits;
use stlc::model::{Format, LayoutSolid, Loc, Shape, Solid};
use stlc::progress::NoProgress;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let growth = match args.get(1).map(String::as_str) {
        Some("dfs") => GrowthOrder::Dfs,
        Some("space") => GrowthOrder::Space,
        _ => GrowthOrder::Bfs,
    };
    let backend = match args.get(2).map(String::as_str) {
        Some("spade") => {
            eprintln!(
                "bench_grow: the spade occupancy index was removed (docs/dependencies.md); measure with rstar"
            );
            std::process::exit(2);
        }
        _ => Backend::Rstar,
    };
    let n: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let side: f64 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(4000.0);
    // The stroke width: stems keep the clearance between their drawn edges,
    // so a wider stroke grows a sparser tree.
    let width: f64 = args.get(5).and_then(|s| s.parse().ok()).unwrap_or(0.1);
    let text = format!(
        "Bench\n({}, {})\nL=1(0) B={width}(0)\nRULE\nR1: [-F][F][+F]\nLAYOUT\n(clGreen) Rectangle (0,0), {side}, {side}\nENDLAYOUT\n",
        side / 2.0,
        side - 1.0
    );
    let mut od =
        stlc::syntax::stl::parse(&text, Format::Od, &Limits::default()).expect("the OD parses");
    let space = args.get(6).map(String::as_str).unwrap_or("plane");
    if space != "plane" {
        od.root_z = Some(0.0);
        let solid = if space == "cube" {
            od.params.divergence = Some(137.5);
            Solid::Box {
                corner: [0.0, 0.0, -side / 2.0],
                size: [side; 3],
            }
        } else {
            Solid::Extrude {
                shape: Shape::Rect {
                    x: 0.0,
                    y: 0.0,
                    w: side,
                    h: side,
                },
                z1: -side / 2.0,
                z2: side / 2.0,
            }
        };
        let layout = od.layout.as_mut().expect("a layout");
        layout.solids = vec![LayoutSolid {
            color: layout.shapes[0].color,
            color_text: String::new(),
            solid,
            loc: Loc::default(),
        }];
        layout.shapes.clear();
    }
    let opts = GrowOptions {
        growth,
        clearance: None,
        limits: Limits {
            max_stems: n,
            // Deep depth-first vines: let them grow as deep as they go.
            max_depth: u32::MAX,
            ..Limits::default()
        },
        max_stems_explicit: true,
        seed: 0,
    };
    let t = Instant::now();
    let g = grow_with(&od, &opts, backend, &mut NoProgress).expect("growth");
    let secs = t.elapsed().as_secs_f64();
    println!(
        "{growth:?} {backend:?} {space} stems={} tries={} time={secs:.3}s per_stem={:.2}us warnings={}",
        g.stems,
        g.tallies.iter().map(|t| t.tries).sum::<u64>(),
        secs * 1e6 / g.stems as f64,
        g.warnings.len()
    );
    // A deep depth-first result would overflow the stack when dropped (the
    // syntax tree's derived Drop recurses); the process ends here anyway.
    std::mem::forget(g);
}
