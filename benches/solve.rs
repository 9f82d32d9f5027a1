//! Criterion benchmarks of the solver (issue 13): `gcs_solve::solve` on a system already
//! analysed (the analysis is outside the timing), on random Laman sketches built from a known
//! realization and drawn with 5% jitter (`generate::laman_drawn`, one redundant distance), and
//! on CAD-like sketches (`generate::rectangles_drawn`: fixed rectangles with horizontal,
//! vertical and two dimensions each, every free corner drawn up to 0.5 off its place; solved
//! in closed form, and with the whole system numerical for comparison).
//!
//! `benches/solve.sh` runs the same generator through `examples/drawn.rs` at 100 to 10,000
//! points with 5% and 20% jitter and prints time, status and the triangles that kept their
//! orientation (the table in BENCHMARKS.md).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode};
use gcs_analysis::{AnalysisOptions, analyze};
use gcs_solve::{SolveOptions, solve};

fn options() -> AnalysisOptions {
    AnalysisOptions { sketch: false, global_rigidity: false, ..AnalysisOptions::default() }
}

fn main() {
    let mut c = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    {
        let mut group = c.benchmark_group("solve-laman-drawn-5pct");
        group.sampling_mode(SamplingMode::Flat);
        for n in [100, 300, 1000] {
            let (system, _) = gcs_model::generate::laman_drawn(n, 1, 0.05);
            let analysis = analyze(&system, &options()).expect("analysis");
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
                b.iter(|| black_box(solve(&system, &analysis, &SolveOptions::default())))
            });
        }
        group.finish();
    }
    {
        let mut group = c.benchmark_group("solve-rectangles");
        group.sampling_mode(SamplingMode::Flat);
        let numeric = SolveOptions { constructive: false, ..SolveOptions::default() };
        for n in [100, 1000, 2500] {
            let system = gcs_model::generate::rectangles_drawn(n, 0.5, 7);
            let analysis = analyze(&system, &options()).expect("analysis");
            group.bench_with_input(BenchmarkId::new("closed-form", n), &n, |b, _| {
                b.iter(|| black_box(solve(&system, &analysis, &SolveOptions::default())))
            });
            group.bench_with_input(BenchmarkId::new("numeric", n), &n, |b, _| {
                b.iter(|| black_box(solve(&system, &analysis, &numeric)))
            });
        }
        group.finish();
    }
    {
        // Enumeration of every realization (`--all`): the core by homotopy continuation (a
        // 6-point core of 70 paths, an 8-point core of 924), the closed-form points on both
        // sides.
        let mut group = c.benchmark_group("enumerate-laman-core");
        group.sampling_mode(SamplingMode::Flat).sample_size(10);
        let all = SolveOptions { all: Some(10_000), ..SolveOptions::default() };
        for n in [7, 8] {
            let (system, _) = gcs_model::generate::laman_drawn(n, 1, 0.0);
            let analysis = analyze(&system, &options()).expect("analysis");
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
                b.iter(|| black_box(solve(&system, &analysis, &all)))
            });
        }
        group.finish();
    }
    {
        // The core's DR-plan node by node: chains of m K3,3 joined by three distances (2m − 1
        // nodes: m K3,3 of 70 paths each, m − 1 assemblies of 6), every node's candidates at
        // the drawing's choices (one realization listed).
        let mut group = c.benchmark_group("enumerate-k33-chain-nodes");
        group.sampling_mode(SamplingMode::Flat).sample_size(10);
        let one = SolveOptions { all: Some(1), ..SolveOptions::default() };
        for m in [1, 2, 4] {
            let system = gcs_model::generate::k33_chain(m, 1);
            let analysis = analyze(&system, &options()).expect("analysis");
            group.bench_with_input(BenchmarkId::from_parameter(m), &m, |b, _| {
                b.iter(|| black_box(solve(&system, &analysis, &one)))
            });
        }
        group.finish();
    }
    c.final_summary();
}
