//! Criterion benchmarks of the rigid subsystems (witness paper §4–§5) on generated families of
//! growing size:
//!
//! - cluster finding with the four methods of `gcs_analysis::ClusterMethod` — the paper's
//!   Algorithm 1 (one elimination per reference), Algorithm 2 (one elimination, pivot exchanges
//!   per reference), the kernel restriction (one elimination, no exchange) and the open-chain
//!   shortcut (one small elimination per block; the kernel method where it does not apply) —
//!   on articulated chains of triangles (as many clusters as triangles, an open chain) and
//!   Laman frameworks with bars removed (not an open chain: the shortcut's overhead);
//! - W-decomposition (Algorithm 3) of rigid systems: triangulated strips (up to 1,000 points,
//!   the target size) and random Laman frameworks, with the default removal heuristic,
//!   and on the small sizes with file order to show what the heuristic saves.
//!
//! Each measurement is the whole `analyze` (witness, rank, clusters, and the decomposition when
//! asked) on an in-memory system, modulo the prime for clusters and decomposition.
//!
//! Run: `cargo bench --bench decompose` (add `-- --quick` for a short run).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion};
use gcs_analysis::{AnalysisOptions, Backend, ClusterMethod, RemovalOrder, analyze};
use gcs_model::Dim;
use gcs_model::System;
use gcs_model::generate::{framework, laman_edges, random_coords, strip, triangle_chain};
use gcs_model::rng::SplitMix64;

const SEED: u64 = 7;

fn group<'a>(
    c: &'a mut Criterion,
    name: &str,
) -> criterion::BenchmarkGroup<'a, criterion::measurement::WallTime> {
    let mut g = c.benchmark_group(name);
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(300));
    g.measurement_time(Duration::from_secs(2));
    g
}

/// A random Laman framework on `n` points with `k` bars removed: flexible, several clusters.
fn loose_laman(n: usize, k: usize) -> System {
    let mut rng = SplitMix64::new(SEED);
    let mut edges = laman_edges(n, 0.5, &mut rng);
    for _ in 0..k {
        let i = rng.below(edges.len() as u64) as usize;
        edges.remove(i);
    }
    let coords = random_coords(n, Dim::Two, 1000, &mut rng);
    framework(&format!("loose-laman-{n}"), Dim::Two, &coords, &edges)
}

fn options(method: ClusterMethod, decompose: bool, order: RemovalOrder) -> AnalysisOptions {
    AnalysisOptions {
        backend: Backend::ModP,
        cluster_method: method,
        decompose,
        removal_order: order,
        ..AnalysisOptions::default()
    }
}

fn clusters(c: &mut Criterion) {
    let mut g = group(c, "clusters");
    let mut cases: Vec<(String, System)> = Vec::new();
    for n in [25, 50, 100, 200] {
        cases.push((format!("chain/{n}"), triangle_chain(n, SEED)));
    }
    for n in [50, 100, 200] {
        cases.push((format!("loose-laman/{n}"), loose_laman(n, n / 10)));
    }
    for (name, system) in &cases {
        for (label, method) in [
            ("kernel", ClusterMethod::Kernel),
            ("alg2-exchange", ClusterMethod::Exchange),
            ("alg1-eliminate", ClusterMethod::Eliminate),
            ("open-chain", ClusterMethod::OpenChain),
        ] {
            // Algorithm 1 eliminates once per cluster: quadratic; keep it to moderate sizes.
            if method == ClusterMethod::Eliminate && system.entities().len() > 250 {
                continue;
            }
            let o = options(method, false, RemovalOrder::default());
            g.bench_with_input(BenchmarkId::new(label, name), system, |b, s| {
                b.iter(|| black_box(analyze(s, &o).map(|a| a.clusters.len()).unwrap_or(0)))
            });
        }
    }
    g.finish();
}

fn decomposition(c: &mut Criterion) {
    let mut g = group(c, "w-decomposition");
    for n in [50, 100, 250, 500] {
        let s = strip(n, SEED);
        let o = options(ClusterMethod::Kernel, true, RemovalOrder::FewShortCycles);
        g.bench_with_input(BenchmarkId::new("strip", 2 * n), &s, |b, s| {
            b.iter(|| black_box(analyze(s, &o).map(|a| a.decomposition_statistics).ok()))
        });
    }
    for n in [25, 50, 100] {
        let s = gcs_model::generate::laman(n, SEED);
        for (label, order) in
            [("laman", RemovalOrder::FewShortCycles), ("laman-file-order", RemovalOrder::FileOrder)]
        {
            if order == RemovalOrder::FileOrder && n > 50 {
                continue;
            }
            let o = options(ClusterMethod::Kernel, true, order);
            g.bench_with_input(BenchmarkId::new(label, n), &s, |b, s| {
                b.iter(|| black_box(analyze(s, &o).map(|a| a.decomposition_statistics).ok()))
            });
        }
    }
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    clusters(&mut c);
    decomposition(&mut c);
    c.final_summary();
}
