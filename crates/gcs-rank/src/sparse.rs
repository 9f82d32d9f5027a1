//! Sparse rows and the two sparse kernels the elimination is built from.

use crate::Field;
use crate::error::RankError;

/// The entries of a sparse vector: `(column, value)` sorted by column.
pub(crate) type Entries<F> = Vec<(usize, F)>;

/// A sparse row vector: `(column, value)` entries sorted by column, with no explicit zeros and
/// no repeated column.
///
/// The same type holds Jacobian rows (indexed by unknowns), reduced rows, kernel vectors and
/// combinations (indexed by insertion ids).
#[derive(Clone, Debug, PartialEq)]
pub struct SparseRow<F> {
    entries: Vec<(usize, F)>,
}

impl<F> Default for SparseRow<F> {
    fn default() -> Self {
        SparseRow { entries: Vec::new() }
    }
}

impl<F: Field> SparseRow<F> {
    /// The zero row.
    pub fn new() -> Self {
        Self::default()
    }

    /// A row from entries in any order: sorts them by column, adds the values given for the
    /// same column (in the order given) and drops the entries that are (or sum to) exactly zero.
    pub fn from_entries(mut entries: Vec<(usize, F)>) -> Self {
        entries.sort_by_key(|&(col, _)| col);
        let mut merged: Vec<(usize, F)> = Vec::with_capacity(entries.len());
        for (col, value) in entries {
            match merged.last_mut() {
                Some((last, sum)) if *last == col => *sum = sum.add(&value),
                _ => merged.push((col, value)),
            }
        }
        merged.retain(|(_, value)| !value.is_zero());
        SparseRow { entries: merged }
    }

    /// Wraps entries that are already sorted by strictly increasing column and nonzero.
    pub(crate) fn from_sorted(entries: Vec<(usize, F)>) -> Self {
        debug_assert!(entries.windows(2).all(|w| w[0].0 < w[1].0));
        debug_assert!(entries.iter().all(|(_, v)| !v.is_zero()));
        SparseRow { entries }
    }

    /// The entries, sorted by column, all nonzero.
    pub fn entries(&self) -> &[(usize, F)] {
        &self.entries
    }

    /// The entries, sorted by column, all nonzero.
    pub fn into_entries(self) -> Vec<(usize, F)> {
        self.entries
    }

    /// The value in column `col`, `None` when it is zero.
    pub fn get(&self, col: usize) -> Option<&F> {
        self.entries.binary_search_by_key(&col, |&(c, _)| c).ok().map(|i| &self.entries[i].1)
    }

    /// The number of nonzero entries.
    pub fn nnz(&self) -> usize {
        self.entries.len()
    }

    /// Whether every entry is zero.
    pub fn is_zero(&self) -> bool {
        self.entries.is_empty()
    }

    /// The largest column with a nonzero entry, `None` for the zero row.
    pub fn max_col(&self) -> Option<usize> {
        self.entries.last().map(|&(col, _)| col)
    }

    /// The row in another field, entry by entry. Entries that map to zero (a multiple of the
    /// prime in a prime field, an underflow in `f64`) are dropped.
    ///
    /// # Errors
    /// The first error returned by `f`.
    pub fn map<G: Field>(
        &self,
        f: impl Fn(&F) -> Result<G, RankError>,
    ) -> Result<SparseRow<G>, RankError> {
        let mut entries = Vec::with_capacity(self.entries.len());
        for (col, value) in &self.entries {
            let image = f(value)?;
            if !image.is_zero() {
                entries.push((*col, image));
            }
        }
        Ok(SparseRow { entries })
    }

    /// The row multiplied by `factor`.
    pub fn scaled(&self, factor: &F) -> SparseRow<F> {
        if factor.is_zero() {
            return SparseRow::new();
        }
        // In f64 a product of nonzeros can underflow to zero.
        let entries = self
            .entries
            .iter()
            .map(|(col, value)| (*col, value.mul(factor)))
            .filter(|(_, value)| !value.is_zero())
            .collect();
        SparseRow { entries }
    }

    /// The dense vector of length `ncols`; entries at or beyond `ncols` are left out.
    pub fn to_dense(&self, ncols: usize) -> Vec<F> {
        let mut dense = vec![F::zero(); ncols];
        for (col, value) in &self.entries {
            if let Some(slot) = dense.get_mut(*col) {
                *slot = value.clone();
            }
        }
        dense
    }

    /// `Σ self[c] · dense[c]`; entries at or beyond `dense.len()` count as zero.
    pub fn dot_dense(&self, dense: &[F]) -> F {
        let mut sum = F::zero();
        for (col, value) in &self.entries {
            if let Some(x) = dense.get(*col) {
                sum.sub_mul_assign(value, &x.neg());
            }
        }
        sum
    }

    /// `Σ self[c] · other[c]`.
    pub fn dot(&self, other: &SparseRow<F>) -> F {
        let mut sum = F::zero();
        let (mut i, mut j) = (0, 0);
        while i < self.entries.len() && j < other.entries.len() {
            let (a, b) = (&self.entries[i], &other.entries[j]);
            match a.0.cmp(&b.0) {
                std::cmp::Ordering::Less => i += 1,
                std::cmp::Ordering::Greater => j += 1,
                std::cmp::Ordering::Equal => {
                    sum.sub_mul_assign(&a.1, &b.1.neg());
                    i += 1;
                    j += 1;
                }
            }
        }
        sum
    }

    /// `Σ coefficient · rows[id]` over the `(id, coefficient)` entries of `self`: the vector
    /// that a combination over inserted rows stands for. Ids without a row count as zero.
    pub fn combine_rows(&self, rows: &[SparseRow<F>]) -> SparseRow<F> {
        let terms: Vec<(&F, &[(usize, F)])> = self
            .entries
            .iter()
            .filter_map(|(id, coef)| rows.get(*id).map(|row| (coef, row.entries())))
            .collect();
        let negated = linear_combination(Vec::new(), &terms, |_| false, |x: &F| x.is_zero());
        SparseRow { entries: negated.into_iter().map(|(c, v)| (c, v.neg())).collect() }
    }
}

impl<F: Field> FromIterator<(usize, F)> for SparseRow<F> {
    fn from_iter<I: IntoIterator<Item = (usize, F)>>(iter: I) -> Self {
        Self::from_entries(iter.into_iter().collect())
    }
}

/// `base − Σ coef · term` over the columns for which `skip` is false, dropping the results for
/// which `negligible` holds. All inputs are sorted sparse vectors.
///
/// The products are gathered by column and accumulated with [`Field::sub_mul_assign`], so that
/// exact fields never build the intermediate products as separate values. Cost:
/// `O(K log K)` with `K` the total number of term entries.
pub(crate) fn linear_combination<F: Field>(
    base: Vec<(usize, F)>,
    terms: &[(&F, &[(usize, F)])],
    skip: impl Fn(usize) -> bool,
    negligible: impl Fn(&F) -> bool,
) -> Vec<(usize, F)> {
    let mut items: Vec<(usize, u32, u32)> = Vec::new();
    for (t, (_, entries)) in terms.iter().enumerate() {
        for (k, (col, _)) in entries.iter().enumerate() {
            if !skip(*col) {
                items.push((*col, t as u32, k as u32));
            }
        }
    }
    items.sort_unstable();
    let mut out = Vec::with_capacity(items.len() + base.len());
    let mut base = base.into_iter().filter(|(col, _)| !skip(*col)).peekable();
    let mut i = 0;
    loop {
        let next_item = items.get(i).map(|it| it.0);
        let next_base = base.peek().map(|e| e.0);
        let col = match (next_item, next_base) {
            (None, None) => break,
            (Some(x), None) | (None, Some(x)) => x,
            (Some(x), Some(y)) => x.min(y),
        };
        let mut acc = match base.next_if(|(c, _)| *c == col) {
            Some((_, value)) => value,
            None => F::zero(),
        };
        while i < items.len() && items[i].0 == col {
            let (_, t, k) = items[i];
            let (coef, entries) = terms[t as usize];
            acc.sub_mul_assign(coef, &entries[k as usize].1);
            i += 1;
        }
        if !acc.is_zero() && !negligible(&acc) {
            out.push((col, acc));
        }
    }
    out
}

/// `target −= v · source`, with column `cancel` (where the result is known to vanish) removed
/// outright. Results for which `negligible` holds are dropped; every column that is in the
/// result but was not in `target` is appended to `fill`.
///
/// When `source` brings no new column the update is in place; otherwise the entries of `target`
/// are moved (never cloned) into a merged vector.
pub(crate) fn sub_scaled<F: Field>(
    target: &mut Vec<(usize, F)>,
    v: &F,
    source: &[(usize, F)],
    cancel: Option<usize>,
    negligible: impl Fn(&F) -> bool,
    fill: &mut Vec<usize>,
) {
    let keep =
        |col: usize, value: &F| Some(col) != cancel && !value.is_zero() && !negligible(value);
    if covers(target, source, cancel) {
        let mut i = 0;
        for (col, value) in source {
            if Some(*col) == cancel {
                continue;
            }
            while target[i].0 < *col {
                i += 1;
            }
            target[i].1.sub_mul_assign(v, value);
        }
        target.retain(|(col, value)| keep(*col, value));
        return;
    }
    let old = std::mem::take(target);
    let mut out = Vec::with_capacity(old.len() + source.len());
    let mut source = source.iter().peekable();
    for (col, mut value) in old {
        while let Some((s_col, s_value)) = source.next_if(|(c, _)| *c < col) {
            let mut x = F::zero();
            x.sub_mul_assign(v, s_value);
            if keep(*s_col, &x) {
                fill.push(*s_col);
                out.push((*s_col, x));
            }
        }
        if let Some((_, s_value)) = source.next_if(|(c, _)| *c == col) {
            value.sub_mul_assign(v, s_value);
        }
        if keep(col, &value) {
            out.push((col, value));
        }
    }
    for (s_col, s_value) in source {
        let mut x = F::zero();
        x.sub_mul_assign(v, s_value);
        if keep(*s_col, &x) {
            fill.push(*s_col);
            out.push((*s_col, x));
        }
    }
    *target = out;
}

/// Whether every column of `source` other than `cancel` is a column of `target`.
fn covers<F>(target: &[(usize, F)], source: &[(usize, F)], cancel: Option<usize>) -> bool {
    if source.len() > target.len() + usize::from(cancel.is_some()) {
        return false;
    }
    let mut i = 0;
    for (col, _) in source {
        if Some(*col) == cancel {
            continue;
        }
        while i < target.len() && target[i].0 < *col {
            i += 1;
        }
        if i == target.len() || target[i].0 != *col {
            return false;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_entries_sorts_merges_and_drops_zeros() {
        let row = SparseRow::from_entries(vec![(5, 2.0), (1, 1.0), (5, -2.0), (3, 0.0), (1, 0.5)]);
        assert_eq!(row.entries(), &[(1, 1.5)]);
        assert_eq!(row.get(1), Some(&1.5));
        assert_eq!(row.get(5), None);
        assert_eq!(row.nnz(), 1);
        assert!(!row.is_zero());
        assert!(SparseRow::<f64>::from_entries(vec![(2, 1.0), (2, -1.0)]).is_zero());
    }

    #[test]
    fn map_drops_entries_that_vanish() {
        let row = SparseRow::from_entries(vec![(0, 1.0), (2, 4.0)]);
        let mapped: SparseRow<f64> = row.map(|x| Ok(if *x > 2.0 { 0.0 } else { x * 3.0 })).unwrap();
        assert_eq!(mapped.entries(), &[(0, 3.0)]);
    }

    #[test]
    fn kernels_agree_with_dense_arithmetic() {
        let a = [(0, 1.0), (2, 2.0), (3, 1.0)];
        let b = [(1, 5.0), (2, 1.0)];
        let mut fill = Vec::new();
        let mut merged = a.to_vec();
        sub_scaled(&mut merged, &2.0, &b, None, |_| false, &mut fill);
        assert_eq!(merged, vec![(0, 1.0), (1, -10.0), (3, 1.0)]);
        assert_eq!(fill, vec![1]);
        // in place (no new column), with a cancelled column
        let mut in_place = vec![(0, 1.0), (1, 3.0), (2, 2.0), (3, 1.0)];
        fill.clear();
        sub_scaled(&mut in_place, &2.0, &b, Some(2), |_| false, &mut fill);
        assert_eq!(in_place, vec![(0, 1.0), (1, -7.0), (3, 1.0)]);
        assert!(fill.is_empty());
        // the cancelled column is dropped even when it brings fill
        let mut fresh = vec![(3, 1.0)];
        sub_scaled(&mut fresh, &1.0, &[(0, 1.0), (3, 1.0)], Some(3), |_| false, &mut fill);
        assert_eq!(fresh, vec![(0, -1.0)]);
        assert_eq!(fill, vec![0]);
        let combo = linear_combination(
            a.to_vec(),
            &[(&1.0, &b[..]), (&-1.0, &a[..])],
            |c| c == 3,
            |_| false,
        );
        assert_eq!(combo, vec![(0, 2.0), (1, -5.0), (2, 3.0)]);
        let row = SparseRow::from_entries(a.to_vec());
        assert_eq!(row.dot_dense(&[1.0, 1.0, 1.0]), 3.0);
        assert_eq!(row.to_dense(3), vec![1.0, 0.0, 2.0]);
        assert_eq!(row.max_col(), Some(3));
        assert_eq!(row.scaled(&0.0), SparseRow::new());
        assert_eq!(row.dot(&SparseRow::from_entries(b.to_vec())), 2.0);
    }
}
