//! Criterion benchmarks of global rigidity (issue 19): the stress-matrix test on a bare graph
//! (`gcs_analysis::global::graph_globally_rigid`: a random configuration and a random stress
//! modulo 2^61 − 1, the ranks of `R` and of the stress matrix) on 2D and 3D frameworks of 100
//! to 1000 points, and the whole `gcs analyze` pipeline (`analyze`, exact backend) on the same
//! frameworks drawn at random integer coordinates.
//!
//! The graphs (`extension_graph`) are generically globally rigid by construction: `K_{d+2}`
//! grown by 1-extensions (remove a random edge `uv`, add a vertex joined to `u`, `v` and `d − 1`
//! other random vertices), which preserve generic global rigidity (Connelly). They have
//! `(d+2)(d+1)/2 + d(n − d − 2)` edges. `BENCHMARKS.md` times PyRigi's `is_globally_rigid` on
//! the same graphs (`benches/pyrigi_global.py` regenerates them from the same SplitMix64).
//!
//! `GCS_BENCH_PROBE=1 cargo bench --bench global` times each case once instead (a Markdown
//! table); `GCS_BENCH_EDGES=DIR` writes each graph's edge list to `DIR/global-<d>d-<n>.txt`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode};
use gcs_analysis::global::graph_globally_rigid;
use gcs_analysis::{AnalysisOptions, analyze};
use gcs_model::generate::{framework, random_coords};
use gcs_model::rng::SplitMix64;
use gcs_model::{Dim, System};

const SEED: u64 = 2024;
const SIZES: [usize; 3] = [100, 300, 1000];

/// A generically globally rigid graph on `n ≥ d + 2` vertices in dimension `d`.
fn extension_graph(n: usize, d: usize, seed: u64) -> Vec<(usize, usize)> {
    let mut rng = SplitMix64::new(seed);
    let mut edges: Vec<(usize, usize)> =
        (0..d + 2).flat_map(|i| (i + 1..d + 2).map(move |j| (i, j))).collect();
    for v in d + 2..n {
        let k = rng.below(edges.len() as u64) as usize;
        let (a, b) = edges.swap_remove(k);
        let mut joined = vec![a, b];
        while joined.len() < d + 1 {
            let c = rng.below(v as u64) as usize;
            if !joined.contains(&c) {
                joined.push(c);
            }
        }
        edges.extend(joined.into_iter().map(|c| (c, v)));
    }
    edges
}

fn dim(d: usize) -> Dim {
    if d == 2 { Dim::Two } else { Dim::Three }
}

fn system(n: usize, d: usize, edges: &[(usize, usize)]) -> System {
    let coords = random_coords(n, dim(d), 1_000_000, &mut SplitMix64::new(SEED + 1));
    framework(&format!("extension-{d}d-{n}"), dim(d), &coords, edges)
}

fn bench(c: &mut Criterion) {
    for d in [2, 3] {
        let mut group = c.benchmark_group(format!("global_{d}d"));
        group.sample_size(10);
        group.sampling_mode(SamplingMode::Flat);
        group.warm_up_time(Duration::from_millis(500));
        group.measurement_time(Duration::from_secs(3));
        for n in SIZES {
            let edges = extension_graph(n, d, SEED);
            group.bench_with_input(BenchmarkId::new("stress_test", n), &edges, |b, e| {
                b.iter(|| {
                    let g = graph_globally_rigid(n, d, e, 1);
                    assert!(g.globally_rigid);
                    black_box(g)
                })
            });
            // The whole analysis (its clusters) takes seconds to minutes past these sizes.
            if n > if d == 2 { 300 } else { 100 } {
                continue;
            }
            let s = system(n, d, &edges);
            let options = AnalysisOptions::default();
            group.bench_with_input(BenchmarkId::new("analyze", n), &s, |b, s| {
                b.iter(|| black_box(analyze(s, &options).expect("analyses")))
            });
        }
        group.finish();
    }
}

#[allow(clippy::print_stdout)]
fn probe() {
    println!("| d | n | edges | stress test | analyze (exact, with it) | analyze without it |");
    println!("|---|---|---|---|---|---|");
    for d in [2, 3] {
        for n in SIZES {
            let edges = extension_graph(n, d, SEED);
            let start = std::time::Instant::now();
            let g = black_box(graph_globally_rigid(n, d, &edges, 1));
            let t = start.elapsed().as_secs_f64();
            assert!(g.globally_rigid);
            let s = system(n, d, &edges);
            let start = std::time::Instant::now();
            let a = black_box(analyze(&s, &AnalysisOptions::default()).expect("analyses"));
            let with = start.elapsed().as_secs_f64();
            assert_eq!(a.global_rigidity.map(|g| g.globally_rigid), Some(true));
            let off = AnalysisOptions { global_rigidity: false, ..AnalysisOptions::default() };
            let start = std::time::Instant::now();
            black_box(analyze(&s, &off).expect("analyses"));
            let without = start.elapsed().as_secs_f64();
            println!("| {d} | {n} | {} | {:.4} s | {with:.3} s | {without:.3} s |", edges.len(), t);
        }
    }
}

fn write_edges(dir: &str) {
    for d in [2, 3] {
        for n in SIZES {
            let text: String =
                extension_graph(n, d, SEED).iter().map(|(a, b)| format!("{a} {b}\n")).collect();
            let path = format!("{dir}/global-{d}d-{n}.txt");
            std::fs::write(&path, text).unwrap_or_else(|e| panic!("{path}: {e}"));
        }
    }
}

// What `criterion_group!`/`criterion_main!` expand to, written out (the macros generate an
// undocumented public function, which the workspace lints flag).
fn main() {
    if let Some(dir) = std::env::var_os("GCS_BENCH_EDGES") {
        write_edges(&dir.to_string_lossy());
        return;
    }
    if std::env::var_os("GCS_BENCH_PROBE").is_some() {
        probe();
        return;
    }
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
