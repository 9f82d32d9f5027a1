//! Rough timings of every backend:
//! `cargo run --release -p gcs-rank --example timing [--features rug] [-- PER_ROW]`.
//!
//! Fast runs are repeated and the best time is printed; slow ones run once.
#![allow(clippy::print_stdout)]

#[path = "../tests/common/mod.rs"]
mod common;

use std::hint::black_box;
use std::time::{Duration, Instant};

use gcs_rank::{
    BigRational, EchelonOptions, Field, ModP, Rat, SparseRow, analyse_rows, analyse_rows_exact,
    float_rank_qr,
};

/// Best wall time of `f` over up to five runs (fewer when one run takes over a second).
fn best<T>(mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut best = Duration::MAX;
    let mut out = None;
    for _ in 0..5 {
        let start = Instant::now();
        let value = f();
        let elapsed = start.elapsed();
        best = best.min(elapsed);
        out = Some(value);
        if elapsed > Duration::from_secs(1) {
            break;
        }
    }
    (best, out.expect("at least one run"))
}

fn ms(d: Duration) -> String {
    format!("{:>10.3} ms", d.as_secs_f64() * 1e3)
}

/// Times `analyse_rows` over `F` without and with combinations; returns the rank.
fn backend<F: Field>(label: &str, ncols: usize, rows: &[SparseRow<BigRational>]) -> usize {
    let images: Vec<SparseRow<F>> = common::to_field(rows);
    let tolerance = if F::EXACT { None } else { Some(1e-9) };
    let run = |track_combinations| {
        let options = EchelonOptions { track_combinations, tolerance };
        best(|| analyse_rows(ncols, images.iter().cloned(), options.clone()))
    };
    let (plain, analysis) = run(false);
    let (tracked, _) = run(true);
    println!("  {label:<34} {}   {}", ms(plain), ms(tracked));
    analysis.rank
}

/// Times `analyse_rows` over `F` with combinations.
fn tracked<F: Field>(label: &str, ncols: usize, rows: &[SparseRow<BigRational>]) {
    let images: Vec<SparseRow<F>> = common::to_field(rows);
    let (t, analysis) =
        best(|| analyse_rows(ncols, images.iter().cloned(), EchelonOptions::tracked()));
    println!("  {label:<34} {}   rank {}", ms(t), analysis.rank);
}

/// Small fractions like the coordinates of a sketched witness: `n/d`, `|n| ≤ 20`, `d ≤ 12`.
fn small_fractions<F: Field>(count: usize, seed: u64) -> Vec<F> {
    let mut rng = common::SplitMix(seed);
    (0..count)
        .map(|_| {
            let n = rng.below(41) as i64 - 20;
            let d = rng.below(12) as i64 + 1;
            F::from_rational(&common::frac(n, d)).expect("exact")
        })
        .collect()
}

/// `OPS / 2` steps of `acc = acc + a·b` over small fractions (one product, one sum each).
fn mixed_add_mul<F: Field>(pool: &[F]) -> F {
    let mut acc = F::zero();
    for i in 0..OPS / 2 {
        let product = pool[i % pool.len()].mul(&pool[(7 * i + 3) % pool.len()]);
        acc = acc.add(&product);
    }
    acc
}

/// `OPS / 16` dot products of length 8 (8 products, 8 sums each) accumulated with
/// `sub_mul_assign`, the shape of a dual-number gradient or an elimination step.
fn dot_products<F: Field>(pool: &[F]) -> F {
    let mut total = F::zero();
    let n = pool.len() - 16;
    for i in 0..OPS / 16 {
        let (x, y) = (&pool[i % n..i % n + 8], &pool[(5 * i + 1) % n..(5 * i + 1) % n + 8]);
        let mut dot = F::zero();
        for (a, b) in x.iter().zip(y) {
            dot.sub_mul_assign(a, b);
        }
        total = total.add(&dot);
    }
    total
}

/// Number of field operations in each micro-benchmark.
const OPS: usize = 1_000_000;

/// Times the micro-benchmarks over `F`; returns the two results.
fn micro<F: Field + std::fmt::Display>(label: &str) -> (String, String) {
    let pool: Vec<F> = small_fractions(1021, 3);
    let (t_mixed, mixed) = best(|| mixed_add_mul(black_box(&pool)));
    let (t_dot, dot) = best(|| dot_products(black_box(&pool)));
    let per_op = |d: Duration| d.as_secs_f64() * 1e9 / OPS as f64;
    println!(
        "  {label:<34} {}   {}   ({:.1} / {:.1} ns per operation)",
        ms(t_mixed),
        ms(t_dot),
        per_op(t_mixed),
        per_op(t_dot)
    );
    (mixed.to_string(), dot.to_string())
}

fn main() {
    println!("10^6 operations on small fractions (|n| <= 20, d <= 12)");
    println!("  {:<34} {:>13}   {:>13}", "backend", "acc += a*b", "8-term dots");
    let big = micro::<BigRational>("BigRational");
    let rat = micro::<Rat>("Rat");
    assert_eq!(big, rat, "the two rationals disagree");

    let per_row: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(6);
    let n = 200;
    let rows = common::random_sparse(n, per_row, 10, 7);
    let nnz: usize = rows.iter().map(|r| r.nnz()).sum();
    println!(
        "{n}x{n} sparse integer matrix ({per_row} random entries a row, {nnz} nonzeros), every \
         10th row a planted dependency"
    );
    println!("  {:<34} {:>13}   {:>13}", "backend", "no combos", "combos");
    let r_modp = backend::<ModP>("Echelon<ModP> (2^61-1)", n, &rows);
    let r_float = backend::<f64>("Echelon<f64>, tolerance 1e-9", n, &rows);
    #[cfg(feature = "rug")]
    let r_rug = backend::<rug::Rational>("Echelon<rug::Rational>", n, &rows).to_string();
    #[cfg(not(feature = "rug"))]
    let r_rug = "n/a (feature off)";
    let r_rat = backend::<Rat>("Echelon<Rat>", n, &rows);
    let r_num = backend::<BigRational>("Echelon<BigRational>", n, &rows);
    let float_rows: Vec<SparseRow<f64>> = common::to_field(&rows);
    let (t, r_qr) = best(|| float_rank_qr(n, &float_rows, 1e-9));
    println!("  {:<34} {}", "float_rank_qr (faer col-piv QR)", ms(t));
    let (t_plain, (exact, proof)) = best(|| analyse_rows_exact(n, &rows, false).expect("exact"));
    let (t_tracked, _) = best(|| analyse_rows_exact(n, &rows, true).expect("exact"));
    println!("  {:<34} {}   {}", "analyse_rows_exact", ms(t_plain), ms(t_tracked));
    println!(
        "  ranks: modp {r_modp}, f64 {r_float}, rug {r_rug}, rat {r_rat}, num {r_num}, qr {r_qr}, \
         exact {} ({proof})",
        exact.rank
    );

    let (ncols, block_rows) = common::blocks(12_500, 8, 11);
    println!(
        "{} rows in independent 8x8 blocks ({ncols} columns, last row of each block dependent)",
        block_rows.len()
    );
    let images: Vec<SparseRow<ModP>> = common::to_field(&block_rows);
    for (label, options) in [
        ("Echelon<ModP>, no combos", EchelonOptions::default()),
        ("Echelon<ModP>, combos", EchelonOptions::tracked()),
    ] {
        let (t, analysis) = best(|| analyse_rows(ncols, images.iter().cloned(), options.clone()));
        println!("  {label:<34} {}   rank {}", ms(t), analysis.rank);
    }
    tracked::<Rat>("Echelon<Rat>, combos", ncols, &block_rows);
    tracked::<BigRational>("Echelon<BigRational>, combos", ncols, &block_rows);
    let (t, (exact, proof)) = best(|| analyse_rows_exact(ncols, &block_rows, true).expect("exact"));
    println!("  {:<34} {}   rank {} ({proof})", "analyse_rows_exact, combos", ms(t), exact.rank);
}
