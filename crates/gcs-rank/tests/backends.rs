//! One harness, many code paths: every matrix goes through every backend (rational, `Rat`, rug
//! with the feature, two prime fields, f64 with a tolerance, the certified exact path, faer's QR),
//! which must agree on the rank, on which rows are dependent and, for the exact backends, on
//! the combinations.

mod common;

use common::{blocks, frac, int, kite, product, random_sparse, row, to_field};
use gcs_rank::{
    BigRational, Echelon, EchelonOptions, Field, Insertion, ModP, ModPrime, Proof, Rat,
    RowAnalysis, SECOND_PRIME, SparseRow, analyse_rows, analyse_rows_exact, analyse_rows_plain,
    float_rank_qr,
};
use num_traits::ToPrimitive;

/// Checks that `other` has the reference's outcomes, pivots and (mapped) combinations.
fn same_outcomes<F: Field>(
    case: &str,
    backend: &str,
    reference: &RowAnalysis<BigRational>,
    other: &RowAnalysis<F>,
    image: impl Fn(&BigRational) -> F,
) {
    assert_eq!(other.rank, reference.rank, "{case}/{backend}: rank");
    assert_eq!(other.outcomes.len(), reference.outcomes.len(), "{case}/{backend}: outcomes");
    for (i, (a, b)) in reference.outcomes.iter().zip(&other.outcomes).enumerate() {
        match (a, b) {
            (Insertion::Independent { pivot: p }, Insertion::Independent { pivot: q }) => {
                assert_eq!(p, q, "{case}/{backend}: pivot of row {i}");
            }
            (
                Insertion::Dependent { combination: Some(ca) },
                Insertion::Dependent { combination: Some(cb) },
            ) => {
                let mapped: Vec<(usize, F)> = ca
                    .iter()
                    .map(|(id, q)| (*id, image(q)))
                    .filter(|(_, v)| !v.is_zero())
                    .collect();
                assert_eq!(&mapped, cb, "{case}/{backend}: combination of row {i}");
            }
            _ => panic!("{case}/{backend}: row {i} is {a:?} in the reference, {b:?} here"),
        }
    }
}

/// Float outcomes: the same rank and dependent rows; combinations close to the exact ones.
fn float_agrees(case: &str, reference: &RowAnalysis<BigRational>, float: &RowAnalysis<f64>) {
    assert_eq!(float.rank, reference.rank, "{case}/float: rank");
    assert_eq!(float.dependent_rows(), reference.dependent_rows(), "{case}/float: dependent rows");
    for (i, (a, b)) in reference.outcomes.iter().zip(&float.outcomes).enumerate() {
        let (Some(exact), Some(approx)) = (a.combination(), b.combination()) else { continue };
        let exact_at = |id: usize| {
            exact.iter().find(|(j, _)| *j == id).map_or(0.0, |(_, q)| q.to_f64().unwrap())
        };
        let approx_at = |id: usize| approx.iter().find(|(j, _)| *j == id).map_or(0.0, |(_, v)| *v);
        for id in exact.iter().map(|(j, _)| *j).chain(approx.iter().map(|(j, _)| *j)) {
            let (e, f) = (exact_at(id), approx_at(id));
            assert!(
                approx::relative_eq!(e, f, epsilon = 1e-6, max_relative = 1e-6),
                "{case}/float: row {i}, coefficient of row {id}: {f} vs exact {e}"
            );
        }
    }
}

/// Runs one matrix through every backend and returns the rational reference analysis.
fn check_case(
    case: &str,
    ncols: usize,
    rows: &[SparseRow<BigRational>],
    expected_rank: usize,
) -> RowAnalysis<BigRational> {
    let reference = analyse_rows(ncols, rows.iter().cloned(), EchelonOptions::tracked());
    assert_eq!(reference.rank, expected_rank, "{case}: rank");

    // The reference is right: every combination reproduces its row, over earlier independent
    // rows only.
    for (i, outcome) in reference.outcomes.iter().enumerate() {
        if let Insertion::Dependent { combination } = outcome {
            let combination = combination.as_ref().expect("tracked");
            assert!(
                combination
                    .iter()
                    .all(|(id, _)| *id < i && reference.outcomes[*id].is_independent()),
                "{case}: combination of row {i} uses a later or dependent row"
            );
            let rebuilt = SparseRow::from_entries(combination.clone()).combine_rows(rows);
            assert_eq!(rebuilt, rows[i], "{case}: combination of row {i}");
        }
    }

    // Kernel: annihilated by every row, rank + nullity = ncols.
    let mut echelon = Echelon::new(ncols, EchelonOptions::default());
    for r in rows {
        echelon.insert(r.clone());
    }
    let kernel = echelon.kernel_basis();
    assert_eq!(kernel.len() + echelon.rank(), ncols, "{case}: rank-nullity");
    for (k, v) in kernel.iter().enumerate() {
        for (i, r) in rows.iter().enumerate() {
            assert!(Field::is_zero(&r.dot(v)), "{case}: row {i} · kernel vector {k} ≠ 0");
        }
    }

    let rat = analyse_rows::<Rat>(ncols, to_field(rows), EchelonOptions::tracked());
    same_outcomes(case, "rat", &reference, &rat, |q| Rat::from(q));
    let mut rat_echelon = Echelon::<Rat>::new(ncols, EchelonOptions::default());
    for r in to_field::<Rat>(rows) {
        rat_echelon.insert(r);
    }
    let rat_kernel: Vec<SparseRow<BigRational>> =
        rat_echelon.kernel_basis().iter().map(|v| v.map(BigRational::from_rat).unwrap()).collect();
    assert_eq!(rat_kernel, kernel, "{case}/rat: kernel");

    let modp = analyse_rows::<ModP>(ncols, to_field(rows), EchelonOptions::tracked());
    same_outcomes(case, "modp", &reference, &modp, |q| ModP::from_rational(q).unwrap());
    type Second = ModPrime<SECOND_PRIME>;
    let second = analyse_rows::<Second>(ncols, to_field(rows), EchelonOptions::tracked());
    same_outcomes(case, "modp2", &reference, &second, |q| Second::from_rational(q).unwrap());

    #[cfg(feature = "rug")]
    {
        let rug = analyse_rows::<rug::Rational>(ncols, to_field(rows), EchelonOptions::tracked());
        same_outcomes(case, "rug", &reference, &rug, gcs_rank::big_to_rug);
    }

    // The certified path eliminates in plain row echelon form: the reference's dependencies and
    // combinations, with the plain form's pivots.
    let (exact, proof) = analyse_rows_exact(ncols, rows, true).unwrap();
    let plain = analyse_rows_plain(ncols, rows.iter().cloned());
    assert_eq!(exact, plain, "{case}: analyse_rows_exact");
    assert_eq!(exact.rank, reference.rank, "{case}: plain rank");
    for (i, (a, b)) in reference.outcomes.iter().zip(&plain.outcomes).enumerate() {
        assert_eq!(a.is_independent(), b.is_independent(), "{case}: plain, row {i}");
        assert_eq!(a.combination(), b.combination(), "{case}: plain, row {i}");
    }
    assert_eq!(proof, Proof::ModularCertified { prime: ModP::PRIME }, "{case}: proof");
    let (untracked, _) = analyse_rows_exact(ncols, rows, false).unwrap();
    assert_eq!(untracked.dependent_rows(), reference.dependent_rows(), "{case}: untracked");
    assert!(untracked.outcomes.iter().all(|o| o.combination().is_none()), "{case}: untracked");

    let float_rows: Vec<SparseRow<f64>> = to_field(rows);
    let float = analyse_rows(ncols, float_rows.iter().cloned(), EchelonOptions::float(1e-9));
    float_agrees(case, &reference, &float);
    assert_eq!(float_rank_qr(ncols, &float_rows, 1e-9), reference.rank, "{case}: faer QR");
    reference
}

#[test]
fn empty_matrices() {
    check_case("0 rows", 3, &[], 0);
    check_case("0 rows, 0 columns", 0, &[], 0);
    let analysis = check_case("zero rows, 0 columns", 0, &[SparseRow::new(), SparseRow::new()], 0);
    assert_eq!(analysis.dependent_rows(), vec![0, 1]);
    assert_eq!(analysis.outcomes[0].combination(), Some(&[][..]));
}

#[test]
fn one_by_one() {
    check_case("1x1", 1, &[row(&[(0, 7)])], 1);
    check_case("1x1 zero", 1, &[SparseRow::new()], 0);
}

#[test]
fn single_row_and_single_column() {
    let wide: Vec<(usize, i64)> = (0..9).map(|c| (c, c as i64 - 4)).collect();
    check_case("1xn", 9, &[row(&wide)], 1);
    let tall: Vec<SparseRow<BigRational>> =
        [3, 0, -6, 5, 0, 1].iter().map(|&v| row(&[(0, v)])).collect();
    let analysis = check_case("nx1", 1, &tall, 1);
    assert_eq!(analysis.dependent_rows(), vec![1, 2, 3, 4, 5]);
    assert_eq!(analysis.outcomes[3].combination(), Some(&[(0, frac(5, 3))][..]));
}

#[test]
fn zero_and_duplicate_rows() {
    let r = row(&[(0, 1), (2, -3), (4, 2)]);
    let s = row(&[(1, 4), (2, 1)]);
    let two_r = r.scaled(&int(2));
    let minus_r = r.scaled(&int(-1));
    let r_plus_s =
        SparseRow::from_entries(r.entries().iter().chain(s.entries()).cloned().collect::<Vec<_>>());
    let rows = vec![
        SparseRow::new(),
        r.clone(),
        SparseRow::new(),
        r.clone(),
        two_r,
        minus_r,
        s,
        r_plus_s,
        SparseRow::new(),
    ];
    let analysis = check_case("zero and duplicate rows", 5, &rows, 2);
    assert_eq!(analysis.dependent_rows(), vec![0, 2, 3, 4, 5, 7, 8]);
    assert_eq!(analysis.outcomes[4].combination(), Some(&[(1, int(2))][..]));
    assert_eq!(analysis.outcomes[7].combination(), Some(&[(1, int(1)), (6, int(1))][..]));
}

#[test]
fn random_sparse_200_with_planted_dependencies() {
    let rows = random_sparse(200, 3, 10, 7);
    let analysis = check_case("random sparse 200x200", 200, &rows, 181);
    let planted: Vec<usize> = (1..20).map(|k| 10 * k).collect();
    assert_eq!(analysis.dependent_rows(), planted);
}

#[test]
fn rank_deficient_products() {
    check_case("product 30x6 * 6x25", 25, &product(30, 6, 25, 3), 6);
    check_case("product 12x11 * 11x12", 12, &product(12, 11, 12, 5), 11);
}

#[test]
fn independent_blocks() {
    let (ncols, rows) = blocks(40, 6, 9);
    let analysis = check_case("40 blocks of 6x6", ncols, &rows, 200);
    let expected: Vec<usize> = (0..40).map(|b| 6 * b + 5).collect();
    assert_eq!(analysis.dependent_rows(), expected);
}

#[test]
fn the_kite() {
    let rows = kite();
    let analysis = check_case("kite", 8, &rows, 5);
    // dist(p1,p4) is redundant, with all five other distances in its circuit.
    assert_eq!(analysis.dependent_rows(), vec![5]);
    let combination = analysis.outcomes[5].combination().unwrap();
    let ids: Vec<usize> = combination.iter().map(|(id, _)| *id).collect();
    assert_eq!(ids, vec![0, 1, 2, 3, 4]);

    // The RREF of the first five rows (pivots x1 y1 x2 y2 x3, free y3 x4 y4), checked against
    // the exact numbers; its first row is x1 − 4/5·y3 − x4 + 4/5·y4 as in the paper.
    let mut echelon = Echelon::new(8, EchelonOptions::tracked());
    for r in &rows[..5] {
        echelon.insert(r.clone());
    }
    assert_eq!(echelon.pivot_columns(), vec![0, 1, 2, 3, 4]);
    assert_eq!(echelon.free_columns(), vec![5, 6, 7]);
    let expected = [
        vec![(0, int(1)), (5, frac(-4, 5)), (6, int(-1)), (7, frac(4, 5))],
        vec![(1, int(1)), (5, frac(-4, 5)), (7, frac(-1, 5))],
        vec![(2, int(1)), (5, frac(-3, 5)), (6, int(-1)), (7, frac(3, 5))],
        vec![(3, int(1)), (5, frac(-1, 5)), (7, frac(-4, 5))],
        vec![(4, int(1)), (5, frac(2, 5)), (6, int(-1)), (7, frac(-2, 5))],
    ];
    let rref = echelon.rref();
    for (k, (pivot, r)) in rref.iter().enumerate() {
        assert_eq!(*pivot, k);
        assert_eq!(r.entries(), &expected[k][..], "RREF row {k}");
    }
    // The three free columns are the displacements: a kernel of dimension 3.
    assert_eq!(echelon.kernel_basis().len(), 3);
}
