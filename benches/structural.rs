//! Criterion benchmarks of the structural methods (gcs-rigidity) on generated families of
//! growing size: Dense and Over-Rigid (rule DOR, and exact DOR at a witness) on random Laman
//! frameworks (2D) and triangulated spheres (3D), the Dulmage–Mendelsohn decomposition on CAD
//! rectangles and Laman frameworks, and Dense with a fresh maximum flow per `Distribute` call
//! (the flow paper's accounting) to show what the incremental flow saves; the cost of one fresh
//! network and maximum flow (`network_build`) prices what every other call would cost without
//! the incremental flow.
//!
//! Run: `cargo bench --bench structural` (add `-- --quick` for a short run).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion};
use gcs_model::System;
use gcs_model::generate::{laman, rectangles, triangulated_sphere};
use gcs_rigidity::{
    Network, RuleDor, WitnessDor, dense_analysis, dm_decomposition, over_rigid_analysis,
};

const SIZES: [usize; 4] = [50, 100, 200, 400];
const SEED: u64 = 2024;

fn configure<'a>(
    c: &'a mut Criterion,
    name: &str,
) -> criterion::BenchmarkGroup<'a, criterion::measurement::WallTime> {
    let mut group = c.benchmark_group(name);
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(1));
    group
}

fn families() -> Vec<(&'static str, usize, System)> {
    let mut out = Vec::new();
    for n in SIZES {
        out.push(("laman", n, laman(n, SEED)));
    }
    for n in SIZES {
        out.push(("sphere", n, triangulated_sphere(n, SEED)));
    }
    out
}

fn bench_dense(c: &mut Criterion) {
    let mut group = configure(c, "dense");
    for (family, n, system) in families() {
        group.bench_with_input(BenchmarkId::new(family, n), &system, |b, s| {
            b.iter(|| black_box(dense_analysis(s)))
        });
    }
    group.finish();
}

/// Dense as the paper counts it: a new network and maximum flow for every overloaded
/// constraint (no flow reuse). 2D only: in 3D Dense stops at the first bar.
fn bench_dense_fresh_flow(c: &mut Criterion) {
    let mut group = configure(c, "dense_fresh_flow");
    for n in [50, 100, 200] {
        let system = laman(n, SEED);
        group.bench_with_input(BenchmarkId::new("laman", n), &system, |b, s| {
            b.iter(|| {
                let k = s.dim().displacements();
                let mut found = None;
                for c in s.constraint_indices() {
                    let mut net = Network::new(s);
                    if let Ok(Some(sub)) = net.distribute_on_constraint(c, k) {
                        found = Some(sub);
                        break;
                    }
                }
                black_box(found)
            })
        });
    }
    group.finish();
}

fn bench_over_rigid(c: &mut Criterion) {
    let mut group = configure(c, "over_rigid_rules");
    for (family, n, system) in families() {
        group.bench_with_input(BenchmarkId::new(family, n), &system, |b, s| {
            b.iter(|| black_box(over_rigid_analysis(s, &RuleDor::for_system(s))))
        });
    }
    group.finish();
}

/// Over-Rigid with the exact DOR at a witness (the oracle is built once, outside the loop;
/// `witness_dor_build` measures building it: the witness search and the generators).
fn bench_over_rigid_witness(c: &mut Criterion) {
    let families = families();
    let oracles: Vec<WitnessDor> = families
        .iter()
        .map(|(_, _, s)| WitnessDor::find(s, 1).expect("the generated families have a witness"))
        .collect();
    let mut group = configure(c, "over_rigid_witness");
    for ((family, n, system), oracle) in families.iter().zip(&oracles) {
        group.bench_with_input(BenchmarkId::new(*family, n), system, |b, s| {
            b.iter(|| black_box(over_rigid_analysis(s, oracle)))
        });
    }
    group.finish();
    let mut group = configure(c, "witness_dor_build");
    for (family, n, system) in &families {
        group.bench_with_input(BenchmarkId::new(*family, n), system, |b, s| {
            b.iter(|| black_box(WitnessDor::find(s, 1)))
        });
    }
    group.finish();
}

/// One object–constraint network with its maximum flow from scratch: what each `Distribute`
/// call would cost without the incremental flow.
fn bench_network_build(c: &mut Criterion) {
    let mut group = configure(c, "network_build");
    for (family, n, system) in families() {
        group.bench_with_input(BenchmarkId::new(family, n), &system, |b, s| {
            b.iter(|| black_box(Network::new(s)))
        });
    }
    group.finish();
}

fn bench_dm(c: &mut Criterion) {
    let mut group = configure(c, "dulmage_mendelsohn");
    for n in SIZES {
        // Eight entities (four points, four segments) per rectangle.
        let system = rectangles(n / 8);
        group.bench_with_input(BenchmarkId::new("rectangles", n), &system, |b, s| {
            b.iter(|| black_box(dm_decomposition(s)))
        });
    }
    for n in SIZES {
        let system = laman(n, SEED);
        group.bench_with_input(BenchmarkId::new("laman", n), &system, |b, s| {
            b.iter(|| black_box(dm_decomposition(s)))
        });
    }
    group.finish();
}

// What `criterion_group!`/`criterion_main!` expand to, written out (the macros generate an
// undocumented public function, which the workspace lints flag).
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_dense(&mut c);
    bench_dense_fresh_flow(&mut c);
    bench_over_rigid(&mut c);
    bench_over_rigid_witness(&mut c);
    bench_network_build(&mut c);
    bench_dm(&mut c);
    c.final_summary();
}
