//! Criterion benchmarks of the (2,3) pebble game (`gcs_decompose::pebble_game`: rank, the
//! fundamental circuit of every redundant bar, the maximal rigid components) on random Laman
//! frameworks (`laman_edges`, Henneberg moves, half of type II) with one extra bar, 1,000 to
//! 100,000 points — the graphs of `gcs generate laman-sketch N`. `BENCHMARKS.md` times PyRigi's
//! `is_rigid` and `rigid_components` on the same graphs (`benches/pyrigi_rigidity.py`).
//!
//! `GCS_BENCH_PROBE=1 cargo bench --bench pebble` times each size once instead (a Markdown
//! table), up to 1,000,000 points.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, SamplingMode};
use gcs_decompose::pebble_game;
use gcs_model::generate::laman_edges;
use gcs_model::rng::SplitMix64;

/// A random Laman graph on `n` points with one extra bar between two far apart vertices.
fn graph(n: usize) -> Vec<(usize, usize)> {
    let mut rng = SplitMix64::new(1);
    let mut edges = laman_edges(n, 0.5, &mut rng);
    edges.push((0, n - 1));
    edges
}

#[allow(clippy::print_stdout)]
fn bench(c: &mut Criterion) {
    if std::env::var_os("GCS_BENCH_PROBE").is_some() {
        println!("| points | bars | rank | redundant | components | pebble game |");
        println!("|---:|---:|---:|---:|---:|---:|");
        for n in [1_000, 10_000, 100_000, 1_000_000] {
            let edges = graph(n);
            let start = Instant::now();
            let r = pebble_game(n, &edges);
            let t = start.elapsed();
            let redundant = r.circuits.iter().filter(|c| c.is_some()).count();
            println!(
                "| {n} | {} | {} | {redundant} | {} | {:.4} s |",
                edges.len(),
                r.rank,
                r.components.len(),
                t.as_secs_f64()
            );
        }
        return;
    }
    let mut group = c.benchmark_group("pebble_game");
    group
        .sampling_mode(SamplingMode::Flat)
        .sample_size(10)
        .measurement_time(Duration::from_secs(5));
    for n in [1_000, 10_000, 100_000] {
        let edges = graph(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &edges, |b, e| {
            b.iter(|| black_box(pebble_game(n, e)))
        });
    }
    group.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
