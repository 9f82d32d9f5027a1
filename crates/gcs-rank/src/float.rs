//! Batch float rank with faer's column-pivoted QR.

use faer::Mat;

use crate::SparseRow;

/// The numerical rank of the rows by column-pivoted Householder QR (faer): the number of
/// diagonal entries of `R` with `|R_ii| > tolerance · |R_00|`.
///
/// Dense (`O(m·n·min(m, n))` time, `m·n` memory): for cross-checks and moderate sizes. Entries at
/// or beyond `ncols` extend the matrix. A matrix with no rows or no columns, or whose entries
/// are all zero, has rank 0. With non-finite entries the answer is unspecified (but the call
/// returns).
///
/// # Example
/// ```
/// use gcs_rank::{SparseRow, float_rank_qr};
///
/// let rows = [
///     SparseRow::from_entries(vec![(0, 1.0), (1, 2.0)]),
///     SparseRow::from_entries(vec![(0, 2.0), (1, 4.0)]),
/// ];
/// assert_eq!(float_rank_qr(2, &rows, 1e-12), 1);
/// ```
pub fn float_rank_qr(ncols: usize, rows: &[SparseRow<f64>], tolerance: f64) -> usize {
    let ncols = rows.iter().filter_map(|r| r.max_col()).map(|c| c + 1).fold(ncols, usize::max);
    let nrows = rows.len();
    if nrows == 0 || ncols == 0 {
        return 0;
    }
    let mut dense = Mat::<f64>::zeros(nrows, ncols);
    for (i, row) in rows.iter().enumerate() {
        for (col, value) in row.entries() {
            dense[(i, *col)] = *value;
        }
    }
    let qr = dense.col_piv_qr();
    let r = qr.thin_R();
    let size = nrows.min(ncols);
    let r00 = r[(0, 0)].abs();
    if r00 == 0.0 || !r00.is_finite() {
        return 0;
    }
    (0..size).filter(|&i| r[(i, i)].abs() > tolerance * r00).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn awkward_shapes() {
        assert_eq!(float_rank_qr(0, &[], 1e-12), 0);
        assert_eq!(float_rank_qr(5, &[], 1e-12), 0);
        assert_eq!(float_rank_qr(3, &[SparseRow::new(), SparseRow::new()], 1e-12), 0);
        let one = [SparseRow::from_entries(vec![(0, -3.0)])];
        assert_eq!(float_rank_qr(1, &one, 1e-12), 1);
        // a column beyond ncols extends the matrix
        let wide = [SparseRow::from_entries(vec![(7, 1.0)])];
        assert_eq!(float_rank_qr(2, &wide, 1e-12), 1);
    }

    #[test]
    fn non_finite_entries_do_not_panic() {
        let rows = [
            SparseRow::from_entries(vec![(0, f64::NAN), (1, 1.0)]),
            SparseRow::from_entries(vec![(0, f64::INFINITY)]),
        ];
        let rank = float_rank_qr(2, &rows, 1e-12);
        assert!(rank <= 2);
    }
}
