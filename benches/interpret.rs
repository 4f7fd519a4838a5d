//! Criterion benchmarks of classic L-system interpretation:
//! `F -> F[+F]F[-F]F` (angle 25.7), dfs against bfs, bounding pass, and
//! `stats` at depth 57. `cargo bench --bench interpret`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use stlc::interpret::Derivation;
use stlc::interpret::lsys::{draw_into, exact_lengths};
use stlc::interpret::stats::stats;
use stlc::limits::Limits;
use stlc::progress::NoProgress;
use stlc::syntax::lsys::parse;
use stlc::turtle::Bounds;

const TREE1: &str = "axiom F\nrule F F[+F]F[-F]F\nangle 25.7\n";

fn bounding_pass(c: &mut Criterion) {
    let limits = Limits::default();
    let sys = parse(TREE1, &limits).unwrap();
    let mut group = c.benchmark_group("bounds");
    group.sample_size(10);
    for depth in [6u32, 8, 9] {
        let symbols = u64::try_from(&exact_lengths(&sys, depth)[depth as usize]).unwrap();
        group.throughput(Throughput::Elements(symbols));
        for (name, strategy) in [("dfs", Derivation::Dfs), ("bfs", Derivation::Bfs)] {
            group.bench_with_input(BenchmarkId::new(name, depth), &depth, |b, &d| {
                b.iter(|| {
                    let mut bounds = Bounds::default();
                    draw_into(&sys, d, strategy, &limits, &mut bounds, &mut NoProgress).unwrap();
                    black_box(bounds.count)
                })
            });
        }
    }
    group.finish();
}

fn stats_57(c: &mut Criterion) {
    let limits = Limits::default();
    let sys = parse(TREE1, &limits).unwrap();
    c.bench_function("stats depth 57", |b| {
        b.iter(|| black_box(stats(&sys, 57, &limits).unwrap()))
    });
}

criterion_group!(benches, bounding_pass, stats_57);
criterion_main!(benches);
