//! Rank in plain row echelon form, for exact fields: when only the rank (and which rows are
//! independent) is wanted.
//!
//! [`Echelon`](crate::Echelon) keeps the reduced form (every pivot column cleared in every
//! other row), which circuits, kernels and pivot exchanges need. For the rank alone that
//! back-substitution is wasted work, and on flexible systems it is most of the work: on an
//! articulated chain every pivot row ends up expressed over all the hinge parameters before
//! it. Here each row is only reduced against the pivot rows of its leading column, until it
//! vanishes (dependent) or leads with a new pivot column (independent); stored rows are never
//! touched again.

use crate::Field;
use crate::sparse::{SparseRow, sub_scaled};

/// The rank of `rows` (over `ncols` columns) and, per row in order, its pivot column when it is
/// independent of the rows before it, `None` when it is dependent on them.
///
/// Exact fields only: a value is zero when [`Field::is_zero`] says so (no tolerance). Columns
/// at or beyond `ncols` are ignored.
pub fn echelon_rank<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
) -> (usize, Vec<Option<usize>>) {
    // Normalised pivot rows (leading entry 1), by leading column.
    let mut pivot_rows: Vec<Option<Vec<(usize, F)>>> = vec![None; ncols];
    let mut outcomes = Vec::new();
    let mut rank = 0;
    let mut fill = Vec::new();
    for row in rows {
        let mut entries: Vec<(usize, F)> =
            row.into_entries().into_iter().filter(|(c, v)| *c < ncols && !v.is_zero()).collect();
        let pivot = loop {
            let Some((lead, value)) = entries.first().map(|(c, v)| (*c, v.clone())) else {
                break None;
            };
            match &pivot_rows[lead] {
                Some(p) => {
                    fill.clear();
                    sub_scaled(&mut entries, &value, p, Some(lead), |_| false, &mut fill);
                }
                None => {
                    let Some(inv) = value.inv() else { break None };
                    for (_, v) in &mut entries {
                        *v = v.mul(&inv);
                    }
                    pivot_rows[lead] = Some(entries);
                    rank += 1;
                    break Some(lead);
                }
            }
        };
        outcomes.push(pivot);
    }
    (rank, outcomes)
}

/// A random vector of the right kernel `{v : A v = 0}` of the matrix whose rows are `rows`
/// (over `ncols` columns), for exact fields; with the rank of `A`.
///
/// The rows are brought to plain row echelon form as in [`echelon_rank`] (no back-reduction,
/// so the fill-in is that of an LU factorisation, not of the reduced form); every free column
/// then takes a value from `draw`, in decreasing column order, and every pivot column the value
/// back-substitution gives it. The map from the free values to the kernel is a linear bijection,
/// so uniform draws give a vector uniform over the kernel. Columns at or beyond `ncols` are
/// ignored.
///
/// # Complexity
/// The elimination's, then one pass over the stored entries.
///
/// # Example
/// ```
/// use gcs_rank::{Field, ModP, SparseRow, random_kernel_vector};
/// // x0 + x1 + x2 = 0: a plane of solutions.
/// let row = SparseRow::from_entries(vec![(0, ModP::one()), (1, ModP::one()), (2, ModP::one())]);
/// let mut k = 0;
/// let (rank, v) = random_kernel_vector(3, [row.clone()], || { k += 1; ModP::from_i64(k) });
/// assert_eq!(rank, 1);
/// assert!(row.dot_dense(&v).is_zero());
/// ```
pub fn random_kernel_vector<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
    mut draw: impl FnMut() -> F,
) -> (usize, Vec<F>) {
    let mut pivot_rows: Vec<Option<Vec<(usize, F)>>> = vec![None; ncols];
    let mut rank = 0;
    let mut fill = Vec::new();
    for row in rows {
        let mut entries: Vec<(usize, F)> =
            row.into_entries().into_iter().filter(|(c, v)| *c < ncols && !v.is_zero()).collect();
        while let Some((lead, value)) = entries.first().map(|(c, v)| (*c, v.clone())) {
            match &pivot_rows[lead] {
                Some(p) => {
                    fill.clear();
                    sub_scaled(&mut entries, &value, p, Some(lead), |_| false, &mut fill);
                }
                None => {
                    let Some(inv) = value.inv() else { break };
                    for (_, v) in &mut entries {
                        *v = v.mul(&inv);
                    }
                    pivot_rows[lead] = Some(entries);
                    rank += 1;
                    break;
                }
            }
        }
    }
    let mut v = vec![F::zero(); ncols];
    for c in (0..ncols).rev() {
        v[c] = match &pivot_rows[c] {
            // Leading 1 at c, every other entry to its right, already known.
            Some(p) => {
                let mut x = F::zero();
                for (j, a) in p.iter().skip(1) {
                    x.sub_mul_assign(a, &v[*j]);
                }
                x
            }
            None => draw(),
        };
    }
    (rank, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Echelon, EchelonOptions, ModP};

    fn row(entries: &[(usize, u64)]) -> SparseRow<ModP> {
        SparseRow::from_entries(entries.iter().map(|(c, v)| (*c, ModP::new(*v))).collect())
    }

    #[test]
    fn a_random_kernel_vector_is_in_the_kernel_and_spans_it() {
        // Rank 2 on 4 columns: two draws give independent kernel vectors.
        let rows = vec![
            row(&[(0, 1), (1, 2), (3, 5)]),
            row(&[(1, 1), (2, 3)]),
            row(&[(0, 1), (1, 3), (2, 3), (3, 5)]),
        ];
        let mut k = 0u64;
        let mut draw = || {
            k += 7;
            ModP::new(k * k + 1)
        };
        let (rank, a) = random_kernel_vector(4, rows.clone(), &mut draw);
        let (_, b) = random_kernel_vector(4, rows.clone(), &mut draw);
        assert_eq!(rank, 2);
        for r in &rows {
            assert!(r.dot_dense(&a).is_zero() && r.dot_dense(&b).is_zero());
        }
        let (both, _) = echelon_rank(
            4,
            [
                SparseRow::from_entries(a.into_iter().enumerate().collect()),
                SparseRow::from_entries(b.into_iter().enumerate().collect()),
            ],
        );
        assert_eq!(both, 2);
    }

    #[test]
    fn dependent_rows_are_found_in_order() {
        let rows = vec![
            row(&[(0, 1), (1, 2)]),
            row(&[(1, 1), (2, 3)]),
            row(&[(0, 2), (1, 5), (2, 3)]), // r0·2 + r1
            row(&[]),
            row(&[(2, 7)]),
            row(&[(0, 1), (3, 1)]),
        ];
        let (rank, pivots) = echelon_rank(4, rows);
        assert_eq!(rank, 4);
        assert_eq!(pivots, [Some(0), Some(1), None, None, Some(2), Some(3)]);
    }

    #[test]
    fn the_same_rank_and_dependent_rows_as_the_reduced_form() {
        // A long chain of overlapping rows with a few planted dependencies.
        let mut rows = Vec::new();
        let mut state = 12345u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            state >> 33
        };
        for i in 0..300 {
            let n = 40;
            let (a, b, c) =
                ((i * 7) % n, (i * 7 + 1 + (next() as usize) % 5) % n, next() as usize % n);
            rows.push(row(&[(a, 1 + next() % 97), (b, 1 + next() % 97), (c, 1 + next() % 97)]));
        }
        let mut e = Echelon::new(40, EchelonOptions::default());
        let expected: Vec<bool> =
            rows.iter().map(|r| e.insert(r.clone()).is_independent()).collect();
        let (rank, pivots) = echelon_rank(40, rows);
        assert_eq!(rank, e.rank());
        assert_eq!(pivots.iter().map(Option::is_some).collect::<Vec<_>>(), expected);
    }
}
