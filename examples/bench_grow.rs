//! Growth benchmark: time against the number of stems grown.
//!
//! ```text
//! cargo build --release --example bench_grow
//! /usr/bin/time -v target/release/examples/bench_grow bfs rstar 1000000
//! ```
//!
//! Arguments: strategy (`bfs`|`dfs`), occupancy index (`rstar`|`spade`), and
//! the number of stems to grow (`--max-stems`; growth stops there with a
//! warning), optionally the side of the square layout (default 4000). The tree: `Seed = FR1`, `R1 = [-F][F][+F]`, `L=1`, `A=30`,
//! default clearance (0.1), in a 4000 x 4000 rectangle with the root at the
//! middle of the bottom edge: far more room than 10^6 stems take, so every
//! run stops at the limit and the number of stems is exactly the one asked
//! for (up to the last application's size).

use std::time::Instant;

use stlc::color::Rgb;
use stlc::grow::occupancy::Backend;
use stlc::grow::{GrowOptions, grow_with};
use stlc::interpret::Strategy;
use stlc::limits::Limits;
use stlc::progress::NoProgress;
use stlc::syntax::ast::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let strategy = match args.get(1).map(String::as_str) {
        Some("dfs") => Strategy::Dfs,
        _ => Strategy::Bfs,
    };
    let backend = match args.get(2).map(String::as_str) {
        Some("spade") => Backend::Spade,
        _ => Backend::Rstar,
    };
    let n: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let side: f64 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(4000.0);
    let loc = Loc::default;
    let branch = |t: &str| {
        BodyItem::Branch(Branch {
            pieces: vec![Piece::Draw(DrawRun {
                text: t.into(),
                loc: loc(),
            })],
            successor: None,
            loc: loc(),
        })
    };
    let od = Description {
        format: Format::Od,
        name: "Bench".into(),
        name_loc: loc(),
        root: (side / 2.0, side - 1.0),
        root_loc: loc(),
        params: StemParams {
            length: 1.0,
            length_dec: 0.0,
            width: 1.0,
            width_dec: 0.0,
            angle: None,
            clearance: None,
            loc: loc(),
        },
        rules: vec![RuleDef {
            name: "R1".into(),
            name_loc: loc(),
            body: Body {
                items: vec![branch("-F"), branch("F"), branch("+F")],
            },
            loc: loc(),
        }],
        seed: None,
        layout: Some(Layout {
            shapes: vec![LayoutShape {
                color: Rgb::new(0, 128, 0),
                color_text: "clGreen".into(),
                shape: Shape::Rect {
                    x: 0.0,
                    y: 0.0,
                    w: side,
                    h: side,
                },
                spelling: Spelling::StartSize,
                angled: false,
                loc: loc(),
            }],
            loc: loc(),
        }),
    };
    let opts = GrowOptions {
        strategy,
        clearance: None,
        limits: Limits {
            max_stems: n,
            // Deep depth-first vines: let them grow as deep as they go.
            max_depth: u32::MAX,
            ..Limits::default()
        },
        max_stems_explicit: true,
    };
    let t = Instant::now();
    let g = grow_with(&od, &opts, backend, &mut NoProgress).expect("growth");
    let secs = t.elapsed().as_secs_f64();
    println!(
        "{strategy:?} {backend:?} stems={} time={secs:.3}s per_stem={:.2}us warnings={}",
        g.stems,
        secs * 1e6 / g.stems as f64,
        g.warnings.len()
    );
    // A deep depth-first result would overflow the stack when dropped (the
    // syntax tree's derived Drop recurses); the process ends here anyway.
    std::mem::forget(g);
}
