//! Matrices shared by the integration tests and `examples/timing.rs`.
#![allow(dead_code, unreachable_pub)]

use gcs_rank::{BigRational, Field, SparseRow};
use num_bigint::BigInt;

/// A small deterministic generator (SplitMix64), so that the matrices are the same everywhere.
pub struct SplitMix(pub u64);

impl SplitMix {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, n)` (n > 0).
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }

    /// Uniform nonzero integer in `[-k, k]`.
    pub fn nonzero(&mut self, k: i64) -> i64 {
        let v = self.below(k as u64) as i64 + 1;
        if self.below(2) == 0 { v } else { -v }
    }
}

pub fn int(v: i64) -> BigRational {
    BigRational::from_i64(v)
}

pub fn frac(n: i64, d: i64) -> BigRational {
    BigRational::new(BigInt::from(n), BigInt::from(d))
}

pub fn row(entries: &[(usize, i64)]) -> SparseRow<BigRational> {
    SparseRow::from_entries(entries.iter().map(|&(c, v)| (c, int(v))).collect())
}

/// `Σ coef · rows[id]` over integer coefficients.
pub fn combine(rows: &[SparseRow<BigRational>], coefs: &[(usize, i64)]) -> SparseRow<BigRational> {
    let combination = SparseRow::from_entries(coefs.iter().map(|&(i, c)| (i, int(c))).collect());
    combination.combine_rows(rows)
}

/// `n × n` sparse integer matrix: each row has `per_row` entries in `[-9, 9]` at random
/// columns, and every `every`-th row (after the first few) is replaced by a combination of two
/// or three earlier rows with small coefficients (a planted dependency).
pub fn random_sparse(
    n: usize,
    per_row: usize,
    every: usize,
    seed: u64,
) -> Vec<SparseRow<BigRational>> {
    let mut rng = SplitMix(seed);
    let mut rows: Vec<SparseRow<BigRational>> = Vec::with_capacity(n);
    for i in 0..n {
        if i >= 4 && every > 0 && i % every == 0 {
            let k = 2 + rng.below(2) as usize;
            let coefs: Vec<(usize, i64)> =
                (0..k).map(|_| (rng.below(i as u64) as usize, rng.nonzero(3))).collect();
            rows.push(combine(&rows, &coefs));
        } else {
            let entries: Vec<(usize, i64)> =
                (0..per_row).map(|_| (rng.below(n as u64) as usize, rng.nonzero(9))).collect();
            rows.push(row(&entries));
        }
    }
    rows
}

/// Rank-deficient product `A·B` with `A` of size `m × k` and `B` of size `k × n`, integer entries
/// in `[-5, 5]`: rank at most `k`.
pub fn product(m: usize, k: usize, n: usize, seed: u64) -> Vec<SparseRow<BigRational>> {
    let mut rng = SplitMix(seed);
    let a: Vec<Vec<i64>> =
        (0..m).map(|_| (0..k).map(|_| rng.below(11) as i64 - 5).collect()).collect();
    let b: Vec<Vec<i64>> =
        (0..k).map(|_| (0..n).map(|_| rng.below(11) as i64 - 5).collect()).collect();
    a.iter()
        .map(|ai| {
            let entries: Vec<(usize, i64)> =
                (0..n).map(|j| (j, (0..k).map(|t| ai[t] * b[t][j]).sum::<i64>())).collect();
            row(&entries)
        })
        .collect()
}

/// The kite of the witness paper (fig. 4): the Jacobian rows of dist(p1,p2), dist(p1,p3),
/// dist(p2,p4), dist(p3,p4), dist(p2,p3), dist(p1,p4) at p1=(2,7), p2=(5,6), p3=(1,1),
/// p4=(6,3), columns x1 y1 x2 y2 x3 y3 x4 y4 (the factor 2 of the squared distance dropped).
pub fn kite() -> Vec<SparseRow<BigRational>> {
    let p = [(2i64, 7i64), (5, 6), (1, 1), (6, 3)];
    [(0usize, 1usize), (0, 2), (1, 3), (2, 3), (1, 2), (0, 3)]
        .iter()
        .map(|&(i, j)| {
            let (dx, dy) = (p[i].0 - p[j].0, p[i].1 - p[j].1);
            row(&[(2 * i, dx), (2 * i + 1, dy), (2 * j, -dx), (2 * j + 1, -dy)])
        })
        .collect()
}

/// `blocks` independent dense `size × size` blocks on the diagonal (random integers in
/// `[-9, 9]`), with every block's last row replaced by the sum of its first two rows.
pub fn blocks(blocks: usize, size: usize, seed: u64) -> (usize, Vec<SparseRow<BigRational>>) {
    let mut rng = SplitMix(seed);
    let mut rows = Vec::with_capacity(blocks * size);
    for b in 0..blocks {
        let base = b * size;
        let first = rows.len();
        for r in 0..size {
            if r == size - 1 && size >= 3 {
                let coefs = [(first, 1), (first + 1, 1)];
                rows.push(combine(&rows, &coefs));
            } else {
                let entries: Vec<(usize, i64)> =
                    (0..size).map(|c| (base + c, rng.below(19) as i64 - 9)).collect();
                rows.push(row(&entries));
            }
        }
    }
    (blocks * size, rows)
}

/// Converts rows to another field.
pub fn to_field<F: Field>(rows: &[SparseRow<BigRational>]) -> Vec<SparseRow<F>> {
    rows.iter().map(|r| r.map(F::from_rational).expect("representable")).collect()
}
