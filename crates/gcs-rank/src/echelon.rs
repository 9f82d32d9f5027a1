//! Incremental reduced row echelon form (witness paper §3.1) with pivot exchange (§4).

use crate::Field;
use crate::error::RankError;
use crate::sparse::{Entries, SparseRow, linear_combination, sub_scaled};

/// Marks a column without a pivot row.
const NONE: usize = usize::MAX;

/// Threshold of the float path's partial pivoting: a candidate pivot must be at least this
/// fraction of the largest candidate in magnitude.
const PIVOT_THRESHOLD: f64 = 0.1;

/// Options of an [`Echelon`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EchelonOptions {
    /// Record, for every stored row, its expression over the inserted rows, so that a dependent
    /// row reports the combination of earlier rows that produces it.
    pub track_combinations: bool,
    /// `Some(t)`: an entry is negligible when `|x| <= t * scale(row)`, where the scale is the
    /// largest `|entry|` of the row as inserted (carried along as the row is normalised);
    /// negligible entries are dropped. `None`: the exact [`Field::is_zero`] test.
    ///
    /// Pivoting does not depend on this option but on the field: exact fields choose pivots by
    /// column priority alone, `f64` by threshold partial pivoting (see
    /// [`Echelon::set_priority`]).
    pub tolerance: Option<f64>,
}

impl EchelonOptions {
    /// Exact zero test, combinations tracked.
    pub fn tracked() -> Self {
        EchelonOptions { track_combinations: true, tolerance: None }
    }

    /// Relative tolerance `tolerance` (for `f64`), combinations tracked.
    pub fn float(tolerance: f64) -> Self {
        EchelonOptions { track_combinations: true, tolerance: Some(tolerance) }
    }
}

/// What inserting a row into an [`Echelon`] found.
#[derive(Clone, Debug, PartialEq)]
pub enum Insertion<F> {
    /// The row was independent of the rows before it; it created a pivot in this column.
    Independent {
        /// The new pivot column.
        pivot: usize,
    },
    /// The row is a combination of earlier inserted rows: `row = Σ coef · row[id]`. Ids are the
    /// insertion ids (0, 1, 2, … in insertion order, counting every insert call). Empty when
    /// the row was zero. `combination` is `None` when combinations are not tracked.
    ///
    /// Only rows that were independent when inserted appear, so the combination is the unique
    /// expression of the row in that basis of the span of the earlier rows: its support is the
    /// fundamental circuit of the row.
    Dependent {
        /// `(insertion id, coefficient)` entries, sorted by id.
        combination: Option<Vec<(usize, F)>>,
    },
}

impl<F> Insertion<F> {
    /// Whether the row created a pivot.
    pub fn is_independent(&self) -> bool {
        matches!(self, Insertion::Independent { .. })
    }

    /// The pivot column of an independent row.
    pub fn pivot(&self) -> Option<usize> {
        match self {
            Insertion::Independent { pivot } => Some(*pivot),
            Insertion::Dependent { .. } => None,
        }
    }

    /// The combination of a dependent row, when tracked.
    pub fn combination(&self) -> Option<&[(usize, F)]> {
        match self {
            Insertion::Dependent { combination } => combination.as_deref(),
            Insertion::Independent { .. } => None,
        }
    }
}

/// One stored row of the form.
#[derive(Clone, Debug)]
struct Stored<F> {
    pivot: usize,
    /// The reduced row: 1 in the pivot column, zero in every other pivot column.
    row: SparseRow<F>,
    /// `row` as a combination of inserted rows (empty when not tracked).
    comb: SparseRow<F>,
    /// Magnitude reference of the float tolerance, in the row's current normalisation.
    scale: f64,
}

/// Incremental reduced row echelon form (witness paper §3.1): rows are inserted one at a time;
/// the structure stays in RREF (every pivot column is zero in all other stored rows).
///
/// Each insertion reduces the new row against the stored rows that have a pivot where it has an
/// entry (the remainder lies on free columns), reports it dependent when nothing remains, and
/// otherwise picks a pivot, normalises the row and eliminates the pivot column from the stored
/// rows that contain it, found through a column → rows index. Rows stay sparse over the free
/// columns; the work is proportional to the entries touched, not to the matrix size.
///
/// Columns past [`Echelon::ncols`] in an inserted row extend the matrix (see
/// [`Echelon::insert`]); [`Echelon::try_insert`] rejects them instead.
///
/// # Example
/// ```
/// use gcs_rank::{Echelon, EchelonOptions, Insertion, SparseRow};
///
/// let mut echelon = Echelon::<f64>::new(3, EchelonOptions::float(1e-12));
/// echelon.insert(SparseRow::from_entries(vec![(0, 1.0), (1, 2.0)]));
/// echelon.insert(SparseRow::from_entries(vec![(1, 1.0), (2, 1.0)]));
/// let outcome = echelon.insert(SparseRow::from_entries(vec![(0, 1.0), (1, 3.0), (2, 1.0)]));
/// assert_eq!(outcome, Insertion::Dependent { combination: Some(vec![(0, 1.0), (1, 1.0)]) });
/// assert_eq!(echelon.rank(), 2);
/// ```
#[derive(Clone, Debug)]
pub struct Echelon<F> {
    ncols: usize,
    options: EchelonOptions,
    priority: Vec<usize>,
    rows: Vec<Stored<F>>,
    /// Column → index in `rows` of its pivot row, or `NONE`.
    pivot_of: Vec<usize>,
    /// Column → stored rows that may have an entry there. Lazy: a row that lost the entry by
    /// cancellation may stay listed (and be listed twice); readers check and deduplicate. The
    /// list of a pivot column is exactly its pivot row.
    col_rows: Vec<Vec<usize>>,
    inserted: usize,
    /// With a tolerance: the scale of every inserted row, by insertion id.
    scales: Vec<f64>,
    /// With a tolerance: the decision margin of every insertion ([`Echelon::margin`]).
    margins: Vec<f64>,
}

/// How far a decision of the float path is from the tolerance it was taken at: decisions with
/// a margin below this are within its ambiguity band ([`Echelon::margin`]).
pub const AMBIGUITY_BAND: f64 = 100.0;

/// Sorted, deduplicated copy of a lazy row list.
fn dedup_rows(list: &[usize]) -> Vec<usize> {
    let mut rows = list.to_vec();
    rows.sort_unstable();
    rows.dedup();
    rows
}

impl<F: Field> Echelon<F> {
    /// An empty form over `ncols` columns, priority = column index.
    pub fn new(ncols: usize, options: EchelonOptions) -> Self {
        Echelon {
            ncols,
            options,
            priority: (0..ncols).collect(),
            rows: Vec::new(),
            pivot_of: vec![NONE; ncols],
            col_rows: vec![Vec::new(); ncols],
            inserted: 0,
            scales: Vec::new(),
            margins: Vec::new(),
        }
    }

    /// With a tolerance `t` (the float path): how far the decision on insertion `id` is from
    /// the tolerance, a factor ≥ 1 when robust, below [`AMBIGUITY_BAND`] when a tolerance
    /// within that factor of `t` could have decided otherwise. For a dependent row it is
    /// `t·s / m`, with `s` its scale and `m` the largest entry the reduction left (and dropped
    /// as negligible): infinite when nothing was left. For an independent row it is
    /// `m / (t·a)`, with `m` the largest entry of its remainder and `a` the amplification of
    /// the reduction — `Σ |c_j| s_j` over the combination `Σ c_j row_j` the remainder is —
    /// which bounds the size of what rounding can leave behind: a remainder small against it
    /// may be cancellation noise, however large against the row itself. Requires tracked
    /// combinations for the amplification (without them, `a = s`). `None` without a tolerance
    /// or for an id not inserted.
    pub fn margin(&self, id: usize) -> Option<f64> {
        self.options.tolerance?;
        self.margins.get(id).copied()
    }

    /// The number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// The rank of the inserted rows (the number of stored rows).
    pub fn rank(&self) -> usize {
        self.rows.len()
    }

    /// The number of insert calls so far (the next insertion id).
    pub fn inserted(&self) -> usize {
        self.inserted
    }

    /// The options the form was created with.
    pub fn options(&self) -> &EchelonOptions {
        &self.options
    }

    /// The current column priorities (smaller is chosen first).
    pub fn priority(&self) -> &[usize] {
        &self.priority
    }

    fn grow(&mut self, ncols: usize) {
        if ncols > self.ncols {
            self.priority.extend(self.ncols..ncols);
            self.pivot_of.resize(ncols, NONE);
            self.col_rows.resize(ncols, Vec::new());
            self.ncols = ncols;
        }
    }

    /// Inserts a row, reporting whether it is independent of the rows inserted before.
    ///
    /// A row with entries at or beyond [`Echelon::ncols`] first extends the matrix with zero
    /// columns up to its last entry (new columns get priority = their index); use
    /// [`Echelon::try_insert`] to treat that as an error.
    ///
    /// Complexity: the reduction costs `O(K log K)` for the `K` stored entries of the pivot rows
    /// it uses; a new pivot then costs one merge per stored row having an entry in its column.
    pub fn insert(&mut self, row: SparseRow<F>) -> Insertion<F> {
        let id = self.inserted;
        self.inserted += 1;
        if let Some(max) = row.max_col() {
            self.grow(max + 1);
        }
        let scale = self.row_scale(&row);
        let threshold = self.options.tolerance.map(|t| t * scale);
        // Entries are dropped below the ambiguity band; the decision is taken at the threshold.
        let floor = threshold.map(|th| th / AMBIGUITY_BAND);
        let negligible = |x: &F| floor.is_some_and(|f| x.magnitude() <= f);
        if self.options.tolerance.is_some() {
            self.scales.push(scale);
        }

        // Split the row into its entries on pivot columns (the coefficients of the pivot rows
        // to subtract) and the rest (moved, not cloned, into the remainder).
        let (on_pivots, rest): (Entries<F>, Entries<F>) =
            row.into_entries().into_iter().partition(|(col, _)| self.pivot_of[*col] != NONE);
        let used: Vec<(&F, usize)> =
            on_pivots.iter().map(|(col, value)| (value, self.pivot_of[*col])).collect();
        let terms: Vec<(&F, &[(usize, F)])> =
            used.iter().map(|&(coef, r)| (coef, self.rows[r].row.entries())).collect();
        let pivot_of = &self.pivot_of;
        let mut reduced = linear_combination(rest, &terms, |c| pivot_of[c] != NONE, negligible);
        // The largest entry left, then those within the band dropped too (float path).
        let left = reduced.iter().map(|(_, v)| v.magnitude()).fold(0.0, f64::max);
        if let Some(th) = threshold {
            reduced.retain(|(_, v)| v.magnitude() > th);
        }

        // -Σ coef · comb(pivot row): the negated expression of the eliminated part.
        let comb_neg = if self.options.track_combinations {
            let comb_terms: Vec<(&F, &[(usize, F)])> =
                used.iter().map(|&(coef, r)| (coef, self.rows[r].comb.entries())).collect();
            linear_combination(Vec::new(), &comb_terms, |_| false, |_| false)
        } else {
            Vec::new()
        };

        if reduced.is_empty() {
            if let Some(th) = threshold {
                self.margins.push(if left > 0.0 { th / left } else { f64::INFINITY });
            }
            let combination = self
                .options
                .track_combinations
                .then(|| comb_neg.into_iter().map(|(i, v)| (i, v.neg())).collect());
            return Insertion::Dependent { combination };
        }
        if let Some(t) = self.options.tolerance {
            // Amplification: the row itself and Σ |c_j| s_j over the rows it was reduced with.
            let amplification = scale
                + comb_neg
                    .iter()
                    .map(|(i, v)| v.magnitude() * self.scales.get(*i).copied().unwrap_or(0.0))
                    .sum::<f64>();
            self.margins.push(left / (t * amplification.max(f64::MIN_POSITIVE)));
        }

        let candidates: Vec<&(usize, F)> = reduced.iter().collect();
        let Some(k) = self.choose_pivot(&candidates) else {
            // Unreachable: `reduced` is nonempty. Reported as dependent rather than panicking.
            return Insertion::Dependent { combination: None };
        };
        let (pivot, pivot_value) = (reduced[k].0, reduced[k].1.clone());
        let inv = pivot_value.inv().expect("a reduced entry is nonzero");
        let new_row = normalise(reduced, pivot, &inv);
        let new_comb = if self.options.track_combinations {
            let mut comb = comb_neg;
            comb.push((id, F::one()));
            SparseRow::from_sorted(comb).scaled(&inv)
        } else {
            SparseRow::new()
        };
        let new_scale = scale / pivot_value.magnitude();
        let r_new = self.rows.len();
        let grown = self.eliminate(pivot, r_new, &new_row, &new_comb);
        for (col, _) in new_row.entries() {
            if *col != pivot {
                self.col_rows[*col].push(r_new);
            }
        }
        self.col_rows[pivot] = vec![r_new];
        self.pivot_of[pivot] = r_new;
        self.rows.push(Stored { pivot, row: new_row, comb: new_comb, scale: new_scale });
        self.compact(grown);
        Insertion::Independent { pivot }
    }

    /// Like [`Echelon::insert`], but a row with an entry at or beyond [`Echelon::ncols`] is an
    /// error and leaves the form (and the insertion count) unchanged.
    ///
    /// # Errors
    /// [`RankError::ColumnOutOfRange`].
    pub fn try_insert(&mut self, row: SparseRow<F>) -> Result<Insertion<F>, RankError> {
        match row.max_col() {
            Some(col) if col >= self.ncols => {
                Err(RankError::ColumnOutOfRange { col, ncols: self.ncols })
            }
            _ => Ok(self.insert(row)),
        }
    }

    /// The largest magnitude of a row (only needed with a tolerance).
    fn row_scale(&self, row: &SparseRow<F>) -> f64 {
        if self.options.tolerance.is_none() {
            return 0.0;
        }
        row.entries().iter().map(|(_, v)| v.magnitude()).fold(0.0, f64::max)
    }

    /// Index in `candidates` of the pivot: the smallest (priority, column), among the entries
    /// within [`PIVOT_THRESHOLD`] of the largest magnitude in an inexact field.
    fn choose_pivot(&self, candidates: &[&(usize, F)]) -> Option<usize> {
        let floor = if !F::EXACT {
            let largest = candidates.iter().map(|(_, v)| v.magnitude()).fold(0.0, f64::max);
            PIVOT_THRESHOLD * largest
        } else {
            0.0
        };
        candidates
            .iter()
            .enumerate()
            .filter(|(_, (_, v))| floor == 0.0 || v.magnitude() >= floor)
            .min_by_key(|(_, (col, _))| (self.priority[*col], *col))
            .map(|(k, _)| k)
    }

    /// Eliminates column `pivot` from every stored row other than `skip` that has an entry
    /// there, using `source` (with 1 in that column) and its combination `source_comb`.
    /// Returns the columns whose row lists grew.
    fn eliminate(
        &mut self,
        pivot: usize,
        skip: usize,
        source: &SparseRow<F>,
        source_comb: &SparseRow<F>,
    ) -> Vec<usize> {
        let tolerance = self.options.tolerance;
        let track = self.options.track_combinations;
        let mut fill = Vec::new();
        let mut grown = Vec::new();
        for r in dedup_rows(&self.col_rows[pivot]) {
            if r == skip {
                continue;
            }
            let stored = &mut self.rows[r];
            let Some(v) = stored.row.get(pivot).cloned() else { continue };
            let threshold = tolerance.map(|t| t * stored.scale);
            let negligible = |x: &F| threshold.is_some_and(|th| x.magnitude() <= th);
            fill.clear();
            let mut row = std::mem::take(&mut stored.row).into_entries();
            sub_scaled(&mut row, &v, source.entries(), Some(pivot), negligible, &mut fill);
            stored.row = SparseRow::from_sorted(row);
            if track {
                let mut comb = std::mem::take(&mut stored.comb).into_entries();
                sub_scaled(&mut comb, &v, source_comb.entries(), None, |_| false, &mut Vec::new());
                stored.comb = SparseRow::from_sorted(comb);
            }
            for &col in &fill {
                self.col_rows[col].push(r);
            }
            grown.extend_from_slice(&fill);
        }
        grown
    }

    /// Rebuilds the lazy row lists of `cols` that have grown past twice the rank (stale and
    /// repeated entries accumulate with cancellations and pivot exchanges), keeping list sizes
    /// within a constant factor of the true ones at amortised constant cost per push. Every
    /// stored row must be in place.
    fn compact(&mut self, cols: impl IntoIterator<Item = usize>) {
        let limit = 2 * self.rows.len() + 8;
        for col in cols {
            if self.col_rows[col].len() > limit {
                let mut list = dedup_rows(&self.col_rows[col]);
                list.retain(|&r| self.rows[r].row.get(col).is_some());
                self.col_rows[col] = list;
            }
        }
    }

    /// Sets the column priorities: when a new row has several candidate pivot columns, the one
    /// with the smallest priority is chosen (ties: the smaller column). On the float path the
    /// choice is among the entries with `|x| >= 0.1 · max |x|` (threshold partial pivoting).
    ///
    /// `priority[c]` is the priority of column `c`; columns past the end of `priority` get
    /// `usize::MAX` (chosen last) and extra entries are ignored. Only later pivot choices are
    /// affected; use [`Echelon::make_free`] to move existing pivots.
    pub fn set_priority(&mut self, priority: Vec<usize>) {
        for (col, slot) in self.priority.iter_mut().enumerate() {
            *slot = priority.get(col).copied().unwrap_or(usize::MAX);
        }
    }

    /// Whether column `col` has a pivot row.
    pub fn is_pivot(&self, col: usize) -> bool {
        self.pivot_of.get(col).is_some_and(|&r| r != NONE)
    }

    /// The pivot columns, in increasing column order.
    pub fn pivot_columns(&self) -> Vec<usize> {
        (0..self.ncols).filter(|&c| self.pivot_of[c] != NONE).collect()
    }

    /// The free (non-pivot) columns, in increasing column order.
    pub fn free_columns(&self) -> Vec<usize> {
        (0..self.ncols).filter(|&c| self.pivot_of[c] == NONE).collect()
    }

    /// The stored reduced row whose pivot is `col` (normalised so that its pivot entry is 1).
    pub fn pivot_row(&self, col: usize) -> Option<&SparseRow<F>> {
        self.stored(col).map(|s| &s.row)
    }

    /// The stored row whose pivot is `col`, as a combination of inserted rows
    /// (`(insertion id, coefficient)` entries); `None` when `col` is not a pivot or
    /// combinations are not tracked.
    pub fn pivot_combination(&self, col: usize) -> Option<&SparseRow<F>> {
        if !self.options.track_combinations {
            return None;
        }
        self.stored(col).map(|s| &s.comb)
    }

    fn stored(&self, col: usize) -> Option<&Stored<F>> {
        match self.pivot_of.get(col) {
            Some(&r) if r != NONE => Some(&self.rows[r]),
            _ => None,
        }
    }

    /// Reduces a vector against the current form without inserting it: the remainder lies on
    /// free columns (and on columns past [`Echelon::ncols`], which are kept). With a tolerance,
    /// entries negligible relative to the largest entry of `row` are dropped.
    pub fn reduce(&self, row: &SparseRow<F>) -> SparseRow<F> {
        let threshold = self.options.tolerance.map(|t| t * self.row_scale(row));
        let negligible = |x: &F| threshold.is_some_and(|th| x.magnitude() <= th);
        let is_pivot = |c: usize| self.pivot_of.get(c).is_some_and(|&r| r != NONE);
        let terms: Vec<(&F, &[(usize, F)])> = row
            .entries()
            .iter()
            .filter(|(col, _)| is_pivot(*col))
            .map(|(col, value)| (value, self.rows[self.pivot_of[*col]].row.entries()))
            .collect();
        SparseRow::from_sorted(linear_combination(
            row.entries().to_vec(),
            &terms,
            is_pivot,
            negligible,
        ))
    }

    /// Basis of the right kernel `{v : A v = 0}`, one vector per free column `f` in increasing
    /// order: `v = e_f − Σ_i a_{i,f} e_{pivot_i}`.
    pub fn kernel_basis(&self) -> Vec<SparseRow<F>> {
        let mut basis = Vec::new();
        for f in 0..self.ncols {
            if self.pivot_of[f] != NONE {
                continue;
            }
            let mut entries = vec![(f, F::one())];
            for r in dedup_rows(&self.col_rows[f]) {
                if let Some(a) = self.rows[r].row.get(f) {
                    entries.push((self.rows[r].pivot, a.neg()));
                }
            }
            basis.push(SparseRow::from_entries(entries));
        }
        basis
    }

    /// Pivot exchange ("anchoring a reference", witness paper §4): makes column `col` free.
    ///
    /// If the stored row pivoted on `col` has a nonzero entry in some free column not marked in
    /// `keep_free` (missing entries of `keep_free` count as unmarked), that column becomes the
    /// pivot instead (the one of smallest priority; on the float path among the entries within
    /// the pivoting threshold) and the form is restored to RREF; tracked combinations stay
    /// exact expressions over the inserted rows.
    ///
    /// Returns `Ok(true)` if `col` is now free (or already was), `Ok(false)` if it cannot be
    /// freed: its row only involves columns in `keep_free`, so `col` is determined by them.
    ///
    /// # Errors
    /// [`RankError::ColumnOutOfRange`] when `col >= ncols`.
    pub fn make_free(&mut self, col: usize, keep_free: &[bool]) -> Result<bool, RankError> {
        if col >= self.ncols {
            return Err(RankError::ColumnOutOfRange { col, ncols: self.ncols });
        }
        let r = self.pivot_of[col];
        if r == NONE {
            return Ok(true);
        }
        let candidates: Vec<&(usize, F)> = self.rows[r]
            .row
            .entries()
            .iter()
            .filter(|(c, _)| *c != col && !keep_free.get(*c).copied().unwrap_or(false))
            .collect();
        let Some(k) = self.choose_pivot(&candidates) else {
            return Ok(false);
        };
        let (new_pivot, value) = (candidates[k].0, candidates[k].1.clone());
        let inv = value.inv().expect("a stored entry is nonzero");
        // Take the row out while the others are reduced against it.
        let stored = &mut self.rows[r];
        let source = normalise(std::mem::take(&mut stored.row).into_entries(), new_pivot, &inv);
        let source_comb = std::mem::take(&mut stored.comb).scaled(&inv);
        stored.scale /= value.magnitude();
        stored.pivot = new_pivot;
        let grown = self.eliminate(new_pivot, r, &source, &source_comb);
        self.rows[r].row = source;
        self.rows[r].comb = source_comb;
        self.pivot_of[col] = NONE;
        self.pivot_of[new_pivot] = r;
        self.col_rows[new_pivot] = vec![r];
        // The old pivot column is now a free column of row r; its list held exactly r, and
        // the elimination added the rows it filled.
        self.compact(grown);
        Ok(true)
    }

    /// The RREF as `(pivot column, row)` pairs sorted by pivot priority (ties: column).
    pub fn rref(&self) -> Vec<(usize, SparseRow<F>)> {
        let mut out: Vec<(usize, SparseRow<F>)> =
            self.rows.iter().map(|s| (s.pivot, s.row.clone())).collect();
        out.sort_by_key(|(pivot, _)| (self.priority[*pivot], *pivot));
        out
    }
}

/// `entries · inv` with the pivot entry set to exactly one.
fn normalise<F: Field>(entries: Vec<(usize, F)>, pivot: usize, inv: &F) -> SparseRow<F> {
    let scaled = entries
        .into_iter()
        .map(|(col, value)| if col == pivot { (col, F::one()) } else { (col, value.mul(inv)) })
        .filter(|(_, value)| !value.is_zero())
        .collect();
    SparseRow::from_sorted(scaled)
}

/// Whole-matrix analysis in insertion order: the rank and the outcome of every row.
#[derive(Clone, Debug, PartialEq)]
pub struct RowAnalysis<F> {
    /// The rank of the rows.
    pub rank: usize,
    /// One outcome per row, in order.
    pub outcomes: Vec<Insertion<F>>,
}

impl<F> RowAnalysis<F> {
    /// Indices of the rows that were independent of the rows before them.
    pub fn independent_rows(&self) -> Vec<usize> {
        (0..self.outcomes.len()).filter(|&i| self.outcomes[i].is_independent()).collect()
    }

    /// Indices of the rows that are combinations of the rows before them (the redundant ones).
    pub fn dependent_rows(&self) -> Vec<usize> {
        (0..self.outcomes.len()).filter(|&i| !self.outcomes[i].is_independent()).collect()
    }
}

/// [`analyse_rows`], with the decision margin of every row ([`Echelon::margin`]; empty without
/// a tolerance).
pub fn analyse_rows_with_margins<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
    options: EchelonOptions,
) -> (RowAnalysis<F>, Vec<f64>) {
    let mut echelon = Echelon::new(ncols, options);
    let outcomes: Vec<Insertion<F>> = rows.into_iter().map(|row| echelon.insert(row)).collect();
    let margins = (0..outcomes.len()).filter_map(|i| echelon.margin(i)).collect();
    (RowAnalysis { rank: echelon.rank(), outcomes }, margins)
}

/// Inserts `rows` in order into a fresh [`Echelon`] and collects the outcomes.
///
/// Rows with entries at or beyond `ncols` extend the matrix, as in [`Echelon::insert`].
pub fn analyse_rows<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
    options: EchelonOptions,
) -> RowAnalysis<F> {
    let mut echelon = Echelon::new(ncols, options);
    let outcomes: Vec<Insertion<F>> = rows.into_iter().map(|row| echelon.insert(row)).collect();
    RowAnalysis { rank: echelon.rank(), outcomes }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ModP;
    use num_rational::BigRational;

    fn q(v: i64) -> BigRational {
        BigRational::from_i64(v)
    }

    fn row(entries: &[(usize, i64)]) -> SparseRow<BigRational> {
        SparseRow::from_entries(entries.iter().map(|&(c, v)| (c, q(v))).collect())
    }

    #[test]
    fn priorities_choose_the_pivot() {
        let mut echelon = Echelon::<BigRational>::new(4, EchelonOptions::default());
        echelon.set_priority(vec![3, 2, 1, 0]);
        assert_eq!(echelon.insert(row(&[(0, 1), (1, 1), (3, 2)])).pivot(), Some(3));
        echelon.set_priority(vec![5, 0]); // columns 2 and 3 go last
        assert_eq!(echelon.insert(row(&[(0, 1), (1, 4), (2, 1)])).pivot(), Some(1));
        assert_eq!(echelon.priority(), &[5, 0, usize::MAX, usize::MAX]);
        assert_eq!(echelon.pivot_columns(), vec![1, 3]);
        // the RREF is listed by priority
        let order: Vec<usize> = echelon.rref().iter().map(|(p, _)| *p).collect();
        assert_eq!(order, vec![1, 3]);
    }

    #[test]
    fn out_of_range_columns_extend_or_fail() {
        let mut echelon = Echelon::<ModP>::new(2, EchelonOptions::default());
        let wide = SparseRow::from_entries(vec![(4, ModP::new(3))]);
        assert_eq!(
            echelon.try_insert(wide.clone()),
            Err(RankError::ColumnOutOfRange { col: 4, ncols: 2 })
        );
        assert_eq!(echelon.inserted(), 0);
        assert_eq!(echelon.insert(wide), Insertion::Independent { pivot: 4 });
        assert_eq!(echelon.ncols(), 5);
        assert_eq!(echelon.kernel_basis().len(), 4);
        assert_eq!(
            echelon.make_free(9, &[]),
            Err(RankError::ColumnOutOfRange { col: 9, ncols: 5 })
        );
        assert!(!echelon.is_pivot(100));
        assert!(echelon.pivot_row(100).is_none());
    }

    #[test]
    fn make_free_exchanges_pivots_or_reports_determined_columns() {
        let mut echelon = Echelon::<BigRational>::new(4, EchelonOptions::tracked());
        let rows = [row(&[(0, 2), (2, 4)]), row(&[(1, 1), (2, 1), (3, 1)])];
        for r in &rows {
            echelon.insert(r.clone());
        }
        // x0 = -2 x2: with x2 kept free, x0 is determined
        assert_eq!(echelon.make_free(0, &[false, false, true, false]), Ok(false));
        assert!(echelon.is_pivot(0));
        // otherwise x2 takes over the pivot and row 1 is re-reduced
        assert_eq!(echelon.make_free(0, &[]), Ok(true));
        assert_eq!(echelon.pivot_columns(), vec![1, 2]);
        let r2 = echelon.pivot_row(2).unwrap();
        assert_eq!(r2.entries(), &[(0, BigRational::new(1.into(), 2.into())), (2, q(1))]);
        let r1 = echelon.pivot_row(1).unwrap();
        assert_eq!(
            r1.entries(),
            &[(0, BigRational::new((-1).into(), 2.into())), (1, q(1)), (3, q(1))]
        );
        for col in [1, 2] {
            let comb = echelon.pivot_combination(col).unwrap();
            assert_eq!(&comb.combine_rows(&rows), echelon.pivot_row(col).unwrap());
        }
        // an already free column
        assert_eq!(echelon.make_free(3, &[]), Ok(true));
        // a new row after the exchange still gets its combination over inserted rows
        let outcome = echelon.insert(row(&[(0, 2), (1, 3), (2, 7), (3, 3)]));
        assert_eq!(outcome.combination(), Some(&[(0, q(1)), (1, q(3))][..]));
    }

    #[test]
    fn repeated_exchanges_keep_the_row_lists_small() {
        // Each exchange cancels x3 from the second row and the next one brings it back: without
        // compaction the list of column 3 would grow by one entry every two exchanges.
        let rows = [row(&[(0, 1), (2, 1), (3, 1)]), row(&[(1, 1), (2, 1), (3, 1)])];
        let mut echelon = Echelon::<BigRational>::new(4, EchelonOptions::tracked());
        for r in &rows {
            echelon.insert(r.clone());
        }
        for round in 0..100 {
            let col = if round % 2 == 0 { 0 } else { 2 };
            assert_eq!(echelon.make_free(col, &[]), Ok(true));
        }
        assert_eq!(echelon.pivot_columns(), vec![0, 1]);
        for list in &echelon.col_rows {
            assert!(list.len() <= 2 * echelon.rank() + 9, "list of {} rows", list.len());
        }
        for v in echelon.kernel_basis() {
            for r in &rows {
                assert!(Field::is_zero(&r.dot(&v)));
            }
        }
        for col in echelon.pivot_columns() {
            let comb = echelon.pivot_combination(col).unwrap();
            assert_eq!(&comb.combine_rows(&rows), echelon.pivot_row(col).unwrap());
        }
    }

    #[test]
    fn reduce_leaves_the_free_part() {
        let mut echelon = Echelon::<BigRational>::new(3, EchelonOptions::default());
        echelon.insert(row(&[(0, 1), (1, 1)]));
        assert_eq!(echelon.reduce(&row(&[(0, 3), (2, 1)])).entries(), &[(1, q(-3)), (2, q(1))]);
        assert!(echelon.reduce(&row(&[(0, 2), (1, 2)])).is_zero());
        assert!(echelon.pivot_combination(0).is_none(), "not tracked");
    }

    #[test]
    fn float_tolerance_is_relative_to_the_row() {
        let noisy = |scale: f64| {
            vec![
                SparseRow::from_entries(vec![(0, scale), (1, 2.0 * scale)]),
                SparseRow::from_entries(vec![(0, 3.0 * scale), (1, 6.0 * scale * (1.0 + 1e-13))]),
            ]
        };
        for scale in [1e-8, 1.0, 1e8] {
            let loose = analyse_rows(2, noisy(scale), EchelonOptions::float(1e-9));
            assert_eq!(loose.rank, 1, "scale {scale}");
            let combination = loose.outcomes[1].combination().unwrap();
            assert!((combination[0].1 - 3.0).abs() < 1e-9);
            let exact = analyse_rows(2, noisy(scale), EchelonOptions::default());
            assert_eq!(exact.rank, 2, "without a tolerance the noise counts, scale {scale}");
        }
    }

    #[test]
    fn float_pivoting_prefers_large_entries() {
        // column 0 has the best priority but a tiny entry: column 1 (within the threshold of
        // the largest) is chosen, with or without a tolerance
        for options in [EchelonOptions::float(1e-12), EchelonOptions::default()] {
            let mut echelon = Echelon::<f64>::new(3, options);
            let row = SparseRow::from_entries(vec![(0, 1e-6), (1, 0.5), (2, 1.0)]);
            assert_eq!(echelon.insert(row).pivot(), Some(1));
        }
        // exact fields go by priority alone
        let mut exact = Echelon::<BigRational>::new(3, EchelonOptions::default());
        let row =
            SparseRow::from_entries(vec![(0, BigRational::new(1.into(), 1000.into())), (2, q(9))]);
        assert_eq!(exact.insert(row).pivot(), Some(0));
    }

    #[test]
    fn the_form_is_clone() {
        let mut echelon = Echelon::<ModP>::new(2, EchelonOptions::tracked());
        echelon.insert(SparseRow::from_entries(vec![(0, ModP::new(2))]));
        let mut copy = echelon.clone();
        copy.insert(SparseRow::from_entries(vec![(1, ModP::new(2))]));
        assert_eq!((echelon.rank(), copy.rank()), (1, 2));
    }
}
