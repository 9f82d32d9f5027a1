//! The certified exact path when a single 61-bit prime is not enough: coefficient growth,
//! multi-modular lifting, the rational fallback, and the proof that says which was used.

mod common;

use common::{SplitMix, frac, int, row};
use gcs_rank::{
    BigRational, EchelonOptions, KernelHint, ModP, Proof, RowAnalysis, SECOND_PRIME, SparseRow,
    THIRD_PRIME, analyse_rows, analyse_rows_exact, certify_rows,
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
fn coefficients_beyond_three_primes_are_lifted_through_as_many_as_they_need() {
    // 21 rows in 20 columns with entries up to 999: coefficients of about 200 bits, beyond the
    // 93 bits that three primes can reconstruct. Further primes (below 2^62) are used until
    // the reconstruction passes the exact check; no rational elimination.
    let rows = square_plus_one(20, 999, 5);
    let expected = reference(20, &rows);
    let bits = coefficient_bits(&expected, 20);
    assert!(bits > 93, "{bits}");
    let (analysis, proof) = analyse_rows_exact(20, &rows, true).unwrap();
    let Proof::MultiModularCertified { primes } = &proof else { panic!("{proof:?}") };
    // Each prime brings about 30 bits of numerator and denominator: not many more than needed.
    assert!(primes.len() > 3 && primes.len() as u64 <= bits / 30 + 3, "{} primes", primes.len());
    assert_eq!(primes[..3], [ModP::PRIME, SECOND_PRIME, THIRD_PRIME]);
    assert!(primes[3..].iter().all(|p| *p < 1 << 62 && *p > 1 << 61));
    assert_eq!(proof.name(), "multimodular");
    assert_eq!(analysis, expected);
    assert_eq!(analysis.rank, 20);
    assert_eq!(analysis.dependent_rows(), vec![20]);
}

/// Points of the plane, exact.
type Points = Vec<(BigRational, BigRational)>;

/// The rigidity matrix of a 2D bar framework: rows `(p_u − p_v, p_v − p_u)` at the points.
fn rigidity_rows(
    points: &[(BigRational, BigRational)],
    edges: &[(usize, usize)],
) -> Vec<SparseRow<BigRational>> {
    edges
        .iter()
        .map(|&(u, v)| {
            let dx = &points[u].0 - &points[v].0;
            let dy = &points[u].1 - &points[v].1;
            SparseRow::from_entries(vec![
                (2 * u, dx.clone()),
                (2 * u + 1, dy.clone()),
                (2 * v, -dx),
                (2 * v + 1, -dy),
            ])
        })
        .collect()
}

/// The planar displacements at `points`: two translations and the rotation about the origin.
fn displacements(points: &[(BigRational, BigRational)]) -> KernelHint {
    let n = points.len();
    let mut t = vec![vec![int(0); 2 * n]; 3];
    for (i, (x, y)) in points.iter().enumerate() {
        t[0][2 * i] = int(1);
        t[1][2 * i + 1] = int(1);
        t[2][2 * i] = -y.clone();
        t[2][2 * i + 1] = x.clone();
    }
    KernelHint { vectors: t, groups: (0..2 * n).map(|c| c / 2).collect(), free_rows: 0 }
}

/// A wheel (hub 0, rim 1..n: itself a rigidity circuit, its last rim bar redundant) with one
/// extra chord, redundant too; points with 10-digit decimal coordinates, as a CAD program
/// writes them.
fn wheel_with_chord(n: usize, seed: u64) -> (Points, Vec<(usize, usize)>) {
    let mut rng = SplitMix(seed);
    let mut coordinate = || frac(rng.nonzero(999_999_999), 10_000_000);
    let points: Vec<_> = (0..=n).map(|_| (coordinate(), coordinate())).collect();
    let mut edges: Vec<(usize, usize)> = (1..=n).map(|i| (0, i)).collect();
    edges.extend((1..n).map(|i| (i, i + 1)));
    edges.push((n, 1));
    edges.push((1, n / 2 + 1));
    (points, edges)
}

#[test]
fn a_rigid_circuit_is_certified_by_the_displacements_without_its_coefficients() {
    let (points, edges) = wheel_with_chord(40, 3);
    let rows = rigidity_rows(&points, &edges);
    let ncols = 2 * points.len();
    let expected = reference(ncols, &rows);
    let last = rows.len() - 1;
    // The coefficients (a self-stress of the wheel the chord closes) are beyond three primes.
    assert!(coefficient_bits(&expected, last) > 93, "{}", coefficient_bits(&expected, last));
    let hint = displacements(&points);
    let certified = certify_rows(ncols, &rows, Some(&hint)).unwrap();
    assert_eq!(
        certified.proof,
        Proof::KernelCertified { prime: ModP::PRIME, kernel: 2, primes: vec![ModP::PRIME] }
    );
    assert_eq!(certified.proof.name(), "kernel");
    assert_eq!(certified.rank, expected.rank);
    let circuits: Vec<Option<Vec<usize>>> = expected
        .outcomes
        .iter()
        .map(|o| o.combination().map(|c| c.iter().map(|(id, _)| *id).collect()))
        .collect();
    assert_eq!(certified.circuits, circuits);
    // The wheel's circuit is every bar before its last; the chord's, the half wheel it closes.
    assert_eq!(certified.circuits[last - 1].as_ref().map(Vec::len), Some(last - 1));
    assert!(certified.circuits[last].as_ref().is_some_and(|c| c.len() > 20 && c.len() < last - 1));
    // Without the hint the same dependency is lifted through many primes: still exact.
    let lifted = certify_rows(ncols, &rows, None).unwrap();
    assert!(
        matches!(lifted.proof, Proof::MultiModularCertified { ref primes } if primes.len() > 3)
    );
    assert_eq!(lifted.circuits, circuits);
}

#[test]
fn a_flexible_circuit_is_not_certified_by_the_displacements() {
    // Four collinear-free points: bars 01, 12, 23, 30 (a four-bar linkage, flexible) and 02 —
    // rigid now — then 13: redundant, circuit = all five bars (K4). Then a separate bar pair
    // 45, 45' (the same bar twice: its circuit is one bar, lifted with one prime).
    let points: Vec<(BigRational, BigRational)> =
        [(0, 0), (7, 1), (8, 6), (1, 5), (20, 3), (25, 9)]
            .iter()
            .map(|&(x, y)| (int(x), int(y)))
            .collect();
    let edges = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2), (1, 3), (4, 5), (4, 5)];
    let rows = rigidity_rows(&points, &edges);
    let hint = displacements(&points);
    let certified = certify_rows(12, &rows, Some(&hint)).unwrap();
    // Both dependencies have small coefficients: one prime, no kernel certificate needed.
    assert_eq!(certified.proof, Proof::ModularCertified { prime: ModP::PRIME });
    assert_eq!(certified.circuits[5], Some(vec![0, 1, 2, 3, 4]));
    assert_eq!(certified.circuits[7], Some(vec![6]));
    // A hint whose vectors the rows do not annihilate proves nothing: a dilation changes
    // every bar. The large circuit of a wheel is then lifted through further primes.
    let (points, edges) = wheel_with_chord(12, 9);
    let rows = rigidity_rows(&points, &edges);
    let mut dilation = displacements(&points);
    dilation.vectors =
        vec![points.iter().flat_map(|(x, y)| [x.clone(), y.clone()]).collect::<Vec<_>>()];
    let certified = certify_rows(2 * points.len(), &rows, Some(&dilation)).unwrap();
    assert!(
        matches!(certified.proof, Proof::MultiModularCertified { .. }),
        "{:?}",
        certified.proof
    );
    let expected = reference(2 * points.len(), &rows);
    assert_eq!(certified.rank, expected.rank);
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

/// `b^e mod m`.
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

/// Miller–Rabin with the first twelve prime bases: deterministic below 3.3·10^24.
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

#[test]
fn the_extra_primes_are_prime_and_large() {
    for p in [ModP::PRIME, SECOND_PRIME, THIRD_PRIME] {
        assert!(is_prime(p), "{p}");
        assert!(p > 1 << 60);
    }
}

/// The witness primes are primes `≡ 3 (mod 4)` (a square root is one power: `a^((p+1)/4)`),
/// the first is ModP's, and the second has every prime up to 23 as a square (√3, which 2^61 − 1
/// lacks, for an equilateral triangle); arithmetic in `ModQ` follows the prime set around it.
#[test]
fn witness_primes_are_what_the_modular_witness_needs() {
    use gcs_rank::{Field, ModQ, WITNESS_PRIMES, with_modulus};
    assert_eq!(WITNESS_PRIMES[0], ModP::PRIME);
    for p in WITNESS_PRIMES {
        assert!(is_prime(p) && p % 4 == 3, "{p}");
    }
    let square = |a: u128, p: u64| pow_mod(a, (p as u128 - 1) / 2, p as u128) == 1;
    assert!(!square(3, ModP::PRIME), "3 is no square modulo 2^61 - 1");
    for a in [2, 3, 5, 7, 11, 13, 17, 19, 23] {
        assert!(square(a, WITNESS_PRIMES[1]), "{a}");
    }
    with_modulus(WITNESS_PRIMES[1], || {
        let three = ModQ::new(3);
        let root =
            ModQ::new(
                pow_mod(3, (WITNESS_PRIMES[1] as u128 + 1) / 4, WITNESS_PRIMES[1] as u128) as u64
            );
        assert_eq!(Field::mul(&root, &root), three);
        assert_eq!(
            Field::mul(&ModQ::new(WITNESS_PRIMES[1] - 1), &ModQ::new(2)).value(),
            WITNESS_PRIMES[1] - 2
        );
    });
    assert_eq!(gcs_rank::modulus(), ModP::PRIME, "the modulus is restored");
}

/// The turn prime is a prime `≡ 3 (mod 4)` with `p + 1` a multiple of every `N ≤ 36`, so that
/// the unit circle modulo it has a turn of order `N` for each.
#[test]
fn the_turn_prime_carries_every_turn_up_to_36() {
    use gcs_rank::{TURN_PERIOD, TURN_PRIME};
    assert!(is_prime(TURN_PRIME) && TURN_PRIME % 4 == 3 && TURN_PRIME > 1 << 60);
    for n in 1..=36 {
        assert_eq!(TURN_PERIOD % n, 0, "{n}");
    }
    assert_eq!((TURN_PRIME + 1) % TURN_PERIOD, 0);
}
