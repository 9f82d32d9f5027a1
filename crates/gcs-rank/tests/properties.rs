//! Property tests on random small rational matrices (fixed seed, small case counts).

mod common;

use common::to_field;
use gcs_rank::{
    BigRational, Echelon, EchelonOptions, Field, Insertion, ModP, Rat, RowAnalysis, SparseRow,
    analyse_rows, analyse_rows_exact, float_rank_qr,
};
use num_bigint::BigInt;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config(cases: u32, seed: u64) -> Config {
    Config { cases, rng_seed: RngSeed::Fixed(seed), failure_persistence: None, ..Config::default() }
}

/// A row is either fresh random entries or a random combination of earlier rows (so that
/// dependencies are common).
#[derive(Clone, Debug)]
enum RowSpec {
    Fresh(Vec<(usize, i64, i64)>),
    Combination(Vec<(u8, i64)>),
}

/// `(ncols, rows)`: up to 7 columns and 9 rows, entries `n/d` with `|n| <= 4`, `d <= 3`.
fn matrix() -> impl Strategy<Value = (usize, Vec<SparseRow<BigRational>>)> {
    (1usize..=7).prop_flat_map(|ncols| {
        let fresh = prop::collection::vec((0..ncols, -4i64..=4, 1i64..=3), 0..=ncols + 1)
            .prop_map(RowSpec::Fresh);
        let combination =
            prop::collection::vec((any::<u8>(), -3i64..=3), 1..=3).prop_map(RowSpec::Combination);
        let spec = prop_oneof![3 => fresh, 2 => combination];
        prop::collection::vec(spec, 0..=9).prop_map(move |specs| (ncols, build(&specs)))
    })
}

fn build(specs: &[RowSpec]) -> Vec<SparseRow<BigRational>> {
    let mut rows: Vec<SparseRow<BigRational>> = Vec::new();
    for spec in specs {
        let row = match spec {
            RowSpec::Fresh(entries) => SparseRow::from_entries(
                entries
                    .iter()
                    .map(|&(c, n, d)| (c, BigRational::new(BigInt::from(n), BigInt::from(d))))
                    .collect(),
            ),
            RowSpec::Combination(_) if rows.is_empty() => SparseRow::new(),
            RowSpec::Combination(terms) => SparseRow::from_entries(
                terms
                    .iter()
                    .map(|&(k, c)| (k as usize % rows.len(), BigRational::from_i64(c)))
                    .collect(),
            )
            .combine_rows(&rows),
        };
        rows.push(row);
    }
    rows
}

fn reference(ncols: usize, rows: &[SparseRow<BigRational>]) -> RowAnalysis<BigRational> {
    analyse_rows(ncols, rows.iter().cloned(), EchelonOptions::tracked())
}

/// Every combination of `analysis` reproduces its row exactly.
fn combinations_reproduce(rows: &[SparseRow<BigRational>], analysis: &RowAnalysis<BigRational>) {
    for (i, outcome) in analysis.outcomes.iter().enumerate() {
        if let Some(c) = outcome.combination() {
            assert_eq!(SparseRow::from_entries(c.to_vec()).combine_rows(rows), rows[i], "row {i}");
        }
    }
}

/// RREF invariants of `echelon` holding the rows `inserted`: pivot entries 1, other pivot
/// columns 0, every stored row equal to its tracked combination, every inserted row in the row
/// space, and the rank unchanged.
fn check_form(echelon: &Echelon<BigRational>, inserted: &[SparseRow<BigRational>], rank: usize) {
    assert_eq!(echelon.rank(), rank);
    let pivots = echelon.pivot_columns();
    assert_eq!(pivots.len(), rank);
    for &c in &pivots {
        let row = echelon.pivot_row(c).unwrap();
        assert_eq!(row.get(c), Some(&<BigRational as Field>::one()));
        for &d in &pivots {
            assert!(d == c || row.get(d).is_none(), "pivot column {d} in the row of {c}");
        }
        let comb = echelon.pivot_combination(c).unwrap();
        assert_eq!(&comb.combine_rows(inserted), row, "combination of the row of {c}");
    }
    for (i, r) in inserted.iter().enumerate() {
        assert!(echelon.reduce(r).is_zero(), "inserted row {i} left the row space");
    }
}

proptest! {
    #![proptest_config(config(256, 0x5eed_0001))]

    #[test]
    fn backends_agree((ncols, rows) in matrix()) {
        let exact = reference(ncols, &rows);
        combinations_reproduce(&rows, &exact);

        let modp = analyse_rows::<ModP>(ncols, to_field(&rows), EchelonOptions::tracked());
        prop_assert_eq!(modp.rank, exact.rank);
        for (a, b) in exact.outcomes.iter().zip(&modp.outcomes) {
            match (a, b) {
                (Insertion::Independent { pivot: p }, Insertion::Independent { pivot: q }) => {
                    prop_assert_eq!(p, q)
                }
                (Insertion::Dependent { combination: Some(x) },
                 Insertion::Dependent { combination: Some(y) }) => {
                    let mapped: Vec<(usize, ModP)> =
                        x.iter().map(|(i, q)| (*i, ModP::from_rational(q).unwrap())).collect();
                    prop_assert_eq!(&mapped, y);
                }
                _ => prop_assert!(false, "outcomes differ: {:?} vs {:?}", a, b),
            }
        }

        #[cfg(feature = "rug")]
        {
            let rug = analyse_rows::<rug::Rational>(ncols, to_field(&rows), EchelonOptions::tracked());
            let back: Vec<Option<Vec<(usize, BigRational)>>> = rug.outcomes.iter()
                .map(|o| o.combination().map(|c| c.iter().map(|(i, q)| (*i, gcs_rank::rug_to_big(q))).collect()))
                .collect();
            let expected: Vec<Option<Vec<(usize, BigRational)>>> =
                exact.outcomes.iter().map(|o| o.combination().map(<[_]>::to_vec)).collect();
            prop_assert_eq!(back, expected);
            prop_assert_eq!(rug.rank, exact.rank);
        }

        let rat = analyse_rows::<Rat>(ncols, to_field(&rows), EchelonOptions::tracked());
        let back: Vec<Option<Vec<(usize, BigRational)>>> = rat.outcomes.iter()
            .map(|o| o.combination().map(|c| c.iter().map(|(i, q)| (*i, q.to_big())).collect()))
            .collect();
        let expected: Vec<Option<Vec<(usize, BigRational)>>> =
            exact.outcomes.iter().map(|o| o.combination().map(<[_]>::to_vec)).collect();
        prop_assert_eq!(back, expected);
        prop_assert_eq!(rat.rank, exact.rank);

        let (certified, _) = analyse_rows_exact(ncols, &rows, true).unwrap();
        prop_assert_eq!(&certified, &exact);

        let float_rows: Vec<SparseRow<f64>> = to_field(&rows);
        let float = analyse_rows(ncols, float_rows.iter().cloned(), EchelonOptions::float(1e-11));
        prop_assert_eq!(float.rank, exact.rank);
        prop_assert_eq!(float.dependent_rows(), exact.dependent_rows());
        prop_assert_eq!(float_rank_qr(ncols, &float_rows, 1e-11), exact.rank);
    }

    #[test]
    fn kernel_is_annihilated_and_rank_plus_nullity_is_ncols((ncols, rows) in matrix()) {
        let mut echelon = Echelon::<BigRational>::new(ncols, EchelonOptions::default());
        for r in &rows {
            echelon.insert(r.clone());
        }
        let kernel = echelon.kernel_basis();
        prop_assert_eq!(echelon.rank() + kernel.len(), ncols);
        for v in &kernel {
            for r in &rows {
                prop_assert!(Field::is_zero(&r.dot(v)));
            }
            // one free column per vector, with coefficient 1: the basis is independent
            let free: Vec<usize> =
                v.entries().iter().map(|(c, _)| *c).filter(|c| !echelon.is_pivot(*c)).collect();
            prop_assert_eq!(free.len(), 1);
            prop_assert_eq!(v.get(free[0]), Some(&<BigRational as Field>::one()));
        }
    }

    #[test]
    fn make_free_keeps_row_space_and_combinations(
        (ncols, rows) in matrix(),
        split in 0usize..=9,
        ops in prop::collection::vec((0usize..7, prop::collection::vec(any::<bool>(), 7)), 0..6),
    ) {
        let expected = reference(ncols, &rows);
        let split = split.min(rows.len());
        let mut echelon = Echelon::new(ncols, EchelonOptions::tracked());
        for r in &rows[..split] {
            echelon.insert(r.clone());
        }
        let rank = echelon.rank();
        for (col, keep) in &ops {
            let col = col % ncols;
            let keep_free = &keep[..ncols];
            let before = echelon.pivot_row(col).cloned();
            let freed = echelon.make_free(col, keep_free).unwrap();
            match before {
                None => prop_assert!(freed),
                Some(row) => {
                    let movable = row.entries().iter().any(|(c, _)| *c != col && !keep_free[*c]);
                    prop_assert_eq!(freed, movable);
                    prop_assert_eq!(echelon.is_pivot(col), !freed);
                }
            }
            check_form(&echelon, &rows[..split], rank);
        }
        // Later insertions see the same dependencies, with correct combinations.
        let mut outcomes: Vec<Insertion<BigRational>> = Vec::new();
        for r in &rows[split..] {
            outcomes.push(echelon.insert(r.clone()));
        }
        for (k, outcome) in outcomes.iter().enumerate() {
            let i = split + k;
            prop_assert_eq!(outcome.is_independent(), expected.outcomes[i].is_independent());
            if let Some(c) = outcome.combination() {
                prop_assert_eq!(&SparseRow::from_entries(c.to_vec()).combine_rows(&rows), &rows[i]);
            }
        }
        check_form(&echelon, &rows, expected.rank);
    }
}
