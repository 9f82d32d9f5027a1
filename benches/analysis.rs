//! Criterion benchmarks of the whole witness analysis — `gcs_analysis::analyze` on an
//! in-memory `System` (witness search, Jacobian assembly, elimination, trivial motions,
//! clusters; parsing excluded) — on generated families of growing size, every backend side by
//! side:
//!
//! - `rectangles`: grids of fixed CAD rectangles (`generate::rectangles`), 100, 1000, 10000;
//! - `grid`: connected CAD plates (`generate::grid`: n × n cells sharing sides, a hole in each),
//!   n = 16, 50, 158: about 1,000, 10,000 and 100,000 entities (issue 15's connected sketches);
//! - `laman`: random 2D Laman frameworks (`generate::laman`), 50, 200, 800 points;
//! - `laman_sketch`: the same as a CAD program writes them (`generate::laman_sketch`): 10-digit
//!   decimal coordinates and one redundant distance whose circuit spans most of the framework,
//!   100, 300, 1000 points (issue 10: exact within 2× of modp), and 10,000 in modp and exact
//!   (issue 15's target: under 1 s);
//! - `sphere`: random 3D triangulated spheres (`generate::triangulated_sphere`), 50, 200;
//! - `parse`: `System::from_ron_str` on the 10,000-rectangle model, on its own.
//!
//! Cases where one analysis takes more than a few seconds are left out ([`measured`]); the
//! probe mode (`GCS_BENCH_PROBE=1`) times every case once instead, and `BENCHMARKS.md` has
//! both. The rug backend is included when gcs-analysis has its `rug` feature.
//!
//! Run: `cargo bench --bench analysis` (with GMP: `cargo bench --bench analysis --features
//! gcs-analysis/rug`); one family: `cargo bench --bench analysis -- rectangles`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode};
use gcs_analysis::{AnalysisOptions, Backend, analyze};
use gcs_model::System;
use gcs_model::generate::{grid, laman, laman_sketch, rectangles, triangulated_sphere};

const SEED: u64 = 2024;

/// The families and their sizes.
const FAMILIES: [(&str, &[usize]); 5] = [
    ("rectangles", &[100, 1000, 10_000]),
    ("grid", &[16, 50, 158]),
    ("laman", &[50, 200, 800]),
    ("laman_sketch", &[100, 300, 1000, 10_000]),
    ("sphere", &[50, 200]),
];

/// Whether the criterion run measures a case. The cases left out take from several seconds
/// to minutes for one analysis, which a run of a few minutes cannot afford ten times; their
/// single-run times (`GCS_BENCH_PROBE=1`) are in `BENCHMARKS.md`.
fn measured(family: &str, backend: Backend, n: usize) -> bool {
    match (family, backend.name()) {
        // Rational elimination with tracked combinations grows like the dense inverse.
        ("laman", "rational" | "rug") => n <= 50,
        // Rational elimination at 10-digit coordinates: minutes from 50 points on.
        ("laman_sketch", "rational" | "rug") => false,
        // 10,000 points: the two backends of the target, modp and exact.
        ("laman_sketch", "float") => n <= 1000,
        ("sphere", "rational") => false,
        // The largest plate: the two backends of the target, modp and exact.
        ("grid", "rational" | "rug" | "float") => n <= 50,
        ("sphere", "rug") => n <= 50,
        _ => true,
    }
}

fn backends() -> Vec<Backend> {
    let mut out =
        vec![Backend::ModP, Backend::Exact, Backend::Rational, Backend::Float { tolerance: 1e-9 }];
    if Backend::Rug.available() {
        out.push(Backend::Rug);
    }
    out
}

fn system(family: &str, n: usize) -> System {
    match family {
        "rectangles" => rectangles(n),
        "grid" => grid(n),
        "laman" => laman(n, SEED),
        "laman_sketch" => laman_sketch(n, SEED),
        "sphere" => triangulated_sphere(n, SEED),
        _ => unreachable!("unknown family {family}"),
    }
}

fn bench_analysis(c: &mut Criterion) {
    for (family, sizes) in FAMILIES {
        let mut group = c.benchmark_group(family);
        group.sample_size(10);
        group.sampling_mode(SamplingMode::Flat);
        group.warm_up_time(Duration::from_millis(500));
        group.measurement_time(Duration::from_secs(2));
        for &n in sizes {
            let s = system(family, n);
            for backend in backends() {
                if !measured(family, backend, n) {
                    continue;
                }
                let options = AnalysisOptions { backend, ..AnalysisOptions::default() };
                group.bench_with_input(BenchmarkId::new(backend.name(), n), &s, |b, s| {
                    b.iter(|| black_box(analyze(s, &options).expect("generated models analyse")))
                });
            }
        }
        group.finish();
    }
}

fn bench_parse(c: &mut Criterion) {
    let text = rectangles(10_000).to_ron();
    let mut group = c.benchmark_group("parse");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group.bench_function(BenchmarkId::new("from_ron_str", 10_000), |b| {
        b.iter(|| black_box(System::from_ron_str(&text, None).expect("valid")))
    });
    group.finish();
}

/// `GCS_BENCH_PROBE=1 cargo bench --bench analysis`: one timed analysis per family, size and
/// backend, [`measured`] or not (a backend goes on to the next size only while one analysis
/// takes less than 1.5 s), printed as a Markdown table; no criterion statistics.
#[allow(clippy::print_stdout)]
fn probe() {
    println!("| family | size | backend | one analysis |\n|---|---|---|---|");
    for (family, sizes) in FAMILIES {
        for backend in backends() {
            // Rational elimination at decimal coordinates: minutes at the smallest size.
            if family == "laman_sketch" && matches!(backend, Backend::Rational | Backend::Rug) {
                continue;
            }
            for &n in sizes {
                let s = system(family, n);
                let options = AnalysisOptions { backend, ..AnalysisOptions::default() };
                let start = std::time::Instant::now();
                black_box(analyze(&s, &options).expect("generated models analyse"));
                let t = start.elapsed();
                println!("| {family} | {n} | {} | {:.3} s |", backend.name(), t.as_secs_f64());
                if t > Duration::from_millis(1500) {
                    break;
                }
            }
        }
    }
    let text = rectangles(10_000).to_ron();
    let start = std::time::Instant::now();
    black_box(System::from_ron_str(&text, None).expect("valid"));
    println!("| parse | 10000 | from_ron_str | {:.3} s |", start.elapsed().as_secs_f64());
}

// What `criterion_group!`/`criterion_main!` expand to, written out (the macros generate an
// undocumented public function, which the workspace lints flag).
fn main() {
    if std::env::var_os("GCS_BENCH_PROBE").is_some() {
        probe();
        return;
    }
    let mut c = Criterion::default().configure_from_args();
    bench_analysis(&mut c);
    bench_parse(&mut c);
    c.final_summary();
}
