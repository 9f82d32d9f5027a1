//! The certified exact path when a single 61-bit prime is not enough: coefficient growth,
//! multi-modular lifting, the rational fallback, and the proof that says which was used.

mod common;

use common::{SplitMix, frac, int, row};
use gcs_rank::{
    BigRational, EchelonOptions, ModP, Proof, RowAnalysis, SECOND_PRIME, SparseRow, THIRD_PRIME,
    analyse_rows, analyse_rows_exact,
};
use num_bigint::BigInt;

fn reference(ncols: usize, rows: &[SparseRow<BigRational>]) -> RowAnalysis<BigRational> {
    analyse_rows(ncols, rows.iter().cloned(), EchelonOptions::tracked())
}

/// The largest bit length of a numerator or denominator in the combination of row `i`.
fn coefficient_bits(analysis: &RowAnalysis<BigRational>, i: usize) -> u64 {
    analysis.outcomes[i]
        .combination()
        .unwrap()
        .iter()
        .map(|(_, q)| q.numer().bits().max(q.denom().bits()))
        .max()
        .unwrap_or(0)
}

/// `n` random rows with entries in `[-k, k]` in `n` columns, then one more random row, which
/// is dependent with coefficients that are ratios of `n × n` determinants.
fn square_plus_one(n: usize, k: i64, seed: u64) -> Vec<SparseRow<BigRational>> {
    let mut rng = SplitMix(seed);
    (0..=n)
        .map(|_| {
            let entries: Vec<(usize, i64)> = (0..n).map(|c| (c, rng.nonzero(k))).collect();
            row(&entries)
        })
        .collect()
}

#[test]
fn small_coefficients_are_certified_with_one_prime() {
    let rows = vec![row(&[(0, 1), (1, 2)]), row(&[(1, 3)]), row(&[(0, 2), (1, 7)])];
    let (analysis, proof) = analyse_rows_exact(2, &rows, true).unwrap();
    assert_eq!(proof, Proof::ModularCertified { prime: ModP::PRIME });
    assert_eq!(analysis.outcomes[2].combination(), Some(&[(0, int(2)), (1, int(1))][..]));
}

#[test]
fn planted_large_coefficients_need_a_second_prime() {
    // row 2 = a·row 0 + b·row 1 with a, b of about 40 bits: beyond sqrt(p/2) ≈ 2^30.
    let a = BigRational::new(BigInt::from((1i64 << 40) + 1), BigInt::from(3));
    let b = BigRational::new(BigInt::from(-(1i64 << 45) - 3), BigInt::from(7));
    let e0 = row(&[(0, 1), (2, 5)]);
    let e1 = row(&[(1, 1), (2, -1)]);
    let combined = SparseRow::from_entries(vec![(0, a.clone()), (1, b.clone())]);
    let rows = vec![e0.clone(), e1.clone(), combined.combine_rows(&[e0, e1])];
    let (analysis, proof) = analyse_rows_exact(3, &rows, true).unwrap();
    assert_eq!(proof, Proof::MultiModularCertified { primes: vec![ModP::PRIME, SECOND_PRIME] });
    assert_eq!(analysis.outcomes[2].combination(), Some(&[(0, a), (1, b)][..]));
    assert_eq!(analysis, reference(3, &rows));
}

#[test]
fn planted_larger_coefficients_need_a_third_prime() {
    // about 75 bits: beyond the 61 bits of two primes, within the 93 bits of three
    let a = BigRational::new(BigInt::from(1u8) << 75u32, BigInt::from(11));
    let rows = vec![row(&[(0, 2)]), SparseRow::from_entries(vec![(0, a.clone() * int(2))])];
    let (analysis, proof) = analyse_rows_exact(1, &rows, true).unwrap();
    assert_eq!(
        proof,
        Proof::MultiModularCertified { primes: vec![ModP::PRIME, SECOND_PRIME, THIRD_PRIME] }
    );
    assert_eq!(analysis.outcomes[1].combination(), Some(&[(0, a)][..]));
}

#[test]
fn coefficient_growth_beyond_one_prime_is_lifted_from_several() {
    // Nine random rows in 8 columns with entries up to 99: the ninth row's coefficients are
    // ratios of 8×8 determinants, far beyond the 30 bits one 61-bit prime can reconstruct.
    let rows = square_plus_one(8, 99, 21);
    let expected = reference(8, &rows);
    let bits = coefficient_bits(&expected, 8);
    assert!(bits > 31 && bits < 93, "coefficients of {bits} bits");
    let (analysis, proof) = analyse_rows_exact(8, &rows, true).unwrap();
    assert!(matches!(proof, Proof::MultiModularCertified { .. }), "{proof:?}");
    assert_eq!(analysis, expected);
}

#[test]
fn coefficients_too_large_for_three_primes_fall_back_to_rational() {
    // 21 rows in 20 columns with entries up to 999: coefficients of about 200 bits, beyond the
    // 93 bits that three primes can reconstruct. The answer is still exact.
    let rows = square_plus_one(20, 999, 5);
    let expected = reference(20, &rows);
    assert!(coefficient_bits(&expected, 20) > 93);
    let (analysis, proof) = analyse_rows_exact(20, &rows, true).unwrap();
    assert_eq!(proof, Proof::Rational);
    assert_eq!(proof.name(), "rational");
    assert_eq!(analysis, expected);
    assert_eq!(analysis.rank, 20);
    assert_eq!(analysis.dependent_rows(), vec![20]);
}

#[test]
fn a_prime_dividing_a_denominator_falls_back_to_rational() {
    let p = BigInt::from(ModP::PRIME);
    let tiny = BigRational::new(BigInt::from(1), p);
    let rows = vec![
        SparseRow::from_entries(vec![(0, tiny.clone()), (1, int(1))]),
        SparseRow::from_entries(vec![(0, tiny * int(2)), (1, int(2))]),
    ];
    let (analysis, proof) = analyse_rows_exact(2, &rows, true).unwrap();
    assert_eq!(proof, Proof::Rational);
    assert_eq!(analysis.outcomes[1].combination(), Some(&[(0, int(2))][..]));
}

#[test]
fn fractional_inputs_are_certified() {
    let rows = vec![
        SparseRow::from_entries(vec![(0, frac(1, 3)), (2, frac(-5, 7))]),
        SparseRow::from_entries(vec![(1, frac(2, 9))]),
        SparseRow::from_entries(vec![(0, frac(1, 6)), (1, frac(4, 3)), (2, frac(-5, 14))]),
    ];
    let (analysis, proof) = analyse_rows_exact(3, &rows, true).unwrap();
    assert_eq!(proof, Proof::ModularCertified { prime: ModP::PRIME });
    assert_eq!(analysis.outcomes[2].combination(), Some(&[(0, frac(1, 2)), (1, int(6))][..]));
}

#[test]
fn the_extra_primes_are_prime_and_large() {
    // Miller–Rabin with the first twelve prime bases is deterministic below 3.3·10^24.
    fn pow_mod(mut b: u128, mut e: u128, m: u128) -> u128 {
        let mut r = 1u128;
        b %= m;
        while e > 0 {
            if e & 1 == 1 {
                r = r * b % m;
            }
            b = b * b % m;
            e >>= 1;
        }
        r
    }
    fn is_prime(n: u64) -> bool {
        let n = n as u128;
        let (mut d, mut s) = (n - 1, 0);
        while d % 2 == 0 {
            d /= 2;
            s += 1;
        }
        [2u128, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37].iter().all(|&a| {
            let mut x = pow_mod(a, d, n);
            if x == 1 || x == n - 1 {
                return true;
            }
            for _ in 1..s {
                x = x * x % n;
                if x == n - 1 {
                    return true;
                }
            }
            false
        })
    }
    for p in [ModP::PRIME, SECOND_PRIME, THIRD_PRIME] {
        assert!(is_prime(p), "{p}");
        assert!(p > 1 << 60);
    }
}
