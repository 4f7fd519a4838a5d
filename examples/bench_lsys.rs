//! Benchmark driver for classic L-systems (used by `benches/lsys-scale.sh`).
//!
//! ```text
//! cargo run --release --example bench_lsys -- MODE STRATEGY DEPTH [FILE]
//! ```
//! MODE: `bounds` (the bounding pass: every segment into a box, what
//! `stats` and the renderer's first pass do), `count` (segments counted
//! only), `stats` (the library's `stats`), `expand` (the word to /dev/null).
//! STRATEGY: `dfs` or `bfs`. Without FILE, `F -> F[+F]F[-F]F` at 25.7 degrees.
//! Prints one line: mode, strategy, depth, symbols, seconds, M symbols/s.

use std::time::Instant;

use stlc::interpret::Derivation;
use stlc::interpret::lsys::{draw_into, exact_lengths, expand};
use stlc::interpret::stats::stats;
use stlc::limits::Limits;
use stlc::progress::NoProgress;
use stlc::syntax::lsys::parse;
use stlc::turtle::{Bounds, Counter};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mode = args.first().map_or("bounds", String::as_str);
    let strategy = match args.get(1).map_or("dfs", String::as_str) {
        "bfs" => Derivation::Bfs,
        _ => Derivation::Dfs,
    };
    let depth: u32 = args.get(2).map_or(Ok(8), |d| d.parse())?;
    let src = match args.get(3) {
        Some(path) => std::fs::read_to_string(path)?,
        None => "axiom F\nrule F F[+F]F[-F]F\nangle 25.7\n".to_string(),
    };
    let limits = Limits {
        max_symbols: u64::MAX / 2,
        max_word: 4_000_000_000,
        ..Limits::default()
    };
    let sys = parse(&src, &limits)?;
    let symbols = exact_lengths(&sys, depth)[depth as usize].to_string();
    let t = Instant::now();
    let what = match mode {
        "count" => {
            let mut c = Counter::default();
            draw_into(&sys, depth, strategy, &limits, &mut c, &mut NoProgress)?;
            format!("segments={}", c.0)
        }
        "stats" => {
            let st = stats(&sys, depth, &limits)?;
            format!("bbox={:?}", st.bbox)
        }
        "expand" => {
            let mut sink = std::io::sink();
            expand(&sys, depth, strategy, &limits, &mut sink, &mut NoProgress)?;
            String::new()
        }
        _ => {
            let mut b = Bounds::default();
            draw_into(&sys, depth, strategy, &limits, &mut b, &mut NoProgress)?;
            format!("segments={}", b.count)
        }
    };
    let secs = t.elapsed().as_secs_f64();
    let rate = symbols.parse::<f64>().unwrap_or(f64::NAN) / secs / 1e6;
    println!(
        "{mode} {} depth={depth} symbols={symbols} secs={secs:.6} Msym/s={rate:.1} {what}",
        if strategy == Derivation::Bfs {
            "bfs"
        } else {
            "dfs"
        }
    );
    Ok(())
}
