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
//!
//! The leading column is the first in a fill-reducing column order ([`Order`]), not the first
//! by index: the rows of a connected framework in file order would otherwise fill in to a
//! dense triangle (a random Laman framework of 5,000 points: 6.8 s in index order, 0.44 s in
//! this one). Which rows are dependent on the rows before them, and their combinations, do not
//! depend on the column order; pivot columns do.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

use crate::sparse::{SparseRow, sub_scaled};
use crate::{Field, Insertion, RowAnalysis};

/// The rank of `rows` (over `ncols` columns) and, per row in order, its pivot column when it is
/// independent of the rows before it, `None` when it is dependent on them.
///
/// Exact fields only: a value is zero when [`Field::is_zero`] says so (no tolerance). Columns
/// at or beyond `ncols` are ignored.
pub fn echelon_rank<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
) -> (usize, Vec<Option<usize>>) {
    let rows = within(ncols, rows);
    let mut lu = Plain::new(ncols, &rows, false);
    let outcomes = rows.into_iter().enumerate().map(|(id, row)| lu.insert(id, row).ok()).collect();
    (lu.stored.len(), outcomes)
}

/// The outcomes [`analyse_rows`](crate::analyse_rows) gives with tracked combinations, found in
/// plain row echelon form: the rank, and per row whether it is independent of the rows before it
/// (with its pivot column) or dependent on them, with the combination of earlier rows that
/// produces it (`(row index, coefficient)`, sorted by index).
///
/// The reduced form tracks, for every stored row, its expression over the inserted rows: on a
/// connected rigid framework those expressions fill in to the dense inverse of the basis, which
/// is most of the cost of a redundancy analysis. Here the stored rows are the `U` of an LU
/// factorisation (each reduced only against the pivot rows of its leading columns) and keep the
/// multipliers of their own reduction (the `L`); the combination of a dependent row is then found
/// by one backward substitution through the multipliers it reaches. Since only rows independent
/// of the rows before them form the basis, that combination is the unique expression of the row
/// in that basis: the same as the reduced form's. Pivot columns are leading columns in the
/// fill-reducing order ([`Order`]), which may differ from the reduced form's choice.
///
/// Exact fields only (no tolerance). Rows with entries at or beyond `ncols` extend the matrix.
///
/// # Complexity
/// The elimination's, that of an LU factorisation in the columns' order; then, per dependent
/// row, the multipliers reachable from its reduction.
pub fn analyse_rows_plain<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
) -> RowAnalysis<F> {
    let rows: Vec<Vec<(usize, F)>> = rows
        .into_iter()
        .map(|row| row.into_entries().into_iter().filter(|(_, v)| !v.is_zero()).collect())
        .collect();
    // Columns past `ncols` extend the matrix.
    let width = rows.iter().filter_map(|r| r.last()).map(|e| e.0 + 1).fold(ncols, usize::max);
    let mut lu = Plain::new(width, &rows, true);
    let mut outcomes = Vec::with_capacity(rows.len());
    for (id, row) in rows.into_iter().enumerate() {
        outcomes.push(match lu.insert(id, row) {
            Ok(pivot) => Insertion::Independent { pivot },
            Err(used) => Insertion::Dependent { combination: Some(lu.expand(used)) },
        });
    }
    RowAnalysis { rank: lu.stored.len(), outcomes }
}

/// A random vector `ω` of the left kernel `{ω : ωᵀA = 0}` of the matrix whose rows are `rows`
/// (over `ncols` columns), for exact fields; with the rank of `A`.
///
/// The rows are brought to plain row echelon form as in [`analyse_rows_plain`]; each row `r`
/// dependent on the rows before it gives the left-kernel vector `e_r − Σ c_i e_i` of its
/// combination, and these `m − rank` vectors are a basis of the left kernel (each has its own
/// `e_r`). `ω` is their combination with coefficients from `draw`, in row order: a linear
/// bijection, so uniform draws give a vector uniform over the left kernel. One backward
/// substitution through the multipliers serves all of them together.
///
/// # Complexity
/// The elimination's, then one pass over the multipliers reachable from the dependent rows.
///
/// # Example
/// ```
/// use gcs_rank::{Field, ModP, SparseRow, random_left_kernel_vector};
/// // Three rows of rank 2 over two columns.
/// let rows = [(0, 1), (1, 1), (0, 1)].map(|(c, v)| SparseRow::from_entries(vec![(c, ModP::from_i64(v))]));
/// let (rank, w) = random_left_kernel_vector(2, rows, || ModP::from_i64(5));
/// assert_eq!(rank, 2);
/// assert_eq!(w, vec![ModP::from_i64(5).neg(), ModP::from_i64(0), ModP::from_i64(5)]);
/// ```
pub fn random_left_kernel_vector<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
    mut draw: impl FnMut() -> F,
) -> (usize, Vec<F>) {
    let rows = within(ncols, rows);
    let m = rows.len();
    let mut lu = Plain::new(ncols, &rows, true);
    let mut omega = vec![F::zero(); m];
    let mut pending: Vec<(usize, F)> = Vec::new();
    for (id, row) in rows.into_iter().enumerate() {
        if let Err(used) = lu.insert(id, row) {
            // e_r − Σ c·(the stored rows it was reduced with), times a random t.
            let t = draw();
            pending.extend(used.into_iter().map(|(k, c)| (k, c.mul(&t))));
            omega[id] = t;
        }
    }
    for (id, c) in lu.expand(pending) {
        omega[id] = omega[id].sub(&c);
    }
    (lu.stored.len(), omega)
}

/// A random vector of the right kernel `{v : A v = 0}` of the matrix whose rows are `rows`
/// (over `ncols` columns), for exact fields; with the rank of `A`.
///
/// The rows are brought to plain row echelon form as in [`echelon_rank`] (no back-reduction,
/// so the fill-in is that of an LU factorisation, not of the reduced form); every free column
/// then takes a value from `draw`, in decreasing order of the fill-reducing column order
/// ([`Order`]), and every pivot column the value
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
    let rows = within(ncols, rows);
    let mut lu = Plain::new(ncols, &rows, false);
    for (id, row) in rows.into_iter().enumerate() {
        let _ = lu.insert(id, row);
    }
    // In the order's numbering, then back.
    let mut w = vec![F::zero(); ncols];
    for c in (0..ncols).rev() {
        w[c] = match lu.pivot_of[c] {
            // Leading 1 at c, every other entry to its right, already known.
            k if k != NONE => {
                let mut x = F::zero();
                for (j, a) in lu.row(k).iter().skip(1) {
                    x.sub_mul_assign(a, &w[*j]);
                }
                x
            }
            _ => draw(),
        };
    }
    let mut v = vec![F::zero(); ncols];
    for (k, value) in w.into_iter().enumerate() {
        v[lu.order.column(k)] = value;
    }
    (lu.stored.len(), v)
}

/// The rows' nonzero entries in columns below `ncols`.
fn within<F: Field>(
    ncols: usize,
    rows: impl IntoIterator<Item = SparseRow<F>>,
) -> Vec<Vec<(usize, F)>> {
    rows.into_iter()
        .map(|row| {
            row.into_entries().into_iter().filter(|(c, v)| *c < ncols && !v.is_zero()).collect()
        })
        .collect()
}

/// Marks a position without a pivot row.
const NONE: usize = usize::MAX;

/// Plain row echelon form in a fill-reducing column order: the `U` of an LU factorisation,
/// with the `L` (each stored row's multipliers) when tracked.
struct Plain<F> {
    order: Order,
    /// Position in the order → index in `stored` of its pivot row, or `NONE`.
    pivot_of: Vec<usize>,
    stored: Vec<Stored<F>>,
    /// The stored rows' entries, one after another (a row's are `entries[span[k].0..span[k].1]`):
    /// one allocation in the order the rows were stored, and a reduction step reads its pivot
    /// row with one lookup in `span` instead of two pointer chases to a `Vec` of its own.
    entries: Vec<(usize, F)>,
    span: Vec<(usize, usize)>,
    track: bool,
    fill: Vec<usize>,
    /// The dense form of the row being reduced, for rows whose reduction fills in.
    dense: Accumulator<F>,
    switch: Switch,
    /// How many rows moved to the accumulator.
    dense_rows: usize,
}

/// One stored row: `row = inv · (input[id] − Σ m · stored[k].row)` over `multipliers` (kept
/// only when tracked); the row's entries ([`Plain::row`]) in the order's numbering, leading 1.
struct Stored<F> {
    id: usize,
    inv: F,
    multipliers: Vec<(usize, F)>,
}

/// When the reduction of a row moves from its sorted sparse form to the [`Accumulator`].
#[derive(Clone, Copy, Debug)]
enum Switch {
    /// By the cost model of [`Plain::insert`] (the only policy outside tests).
    Cost,
    /// Never: the sparse form throughout.
    #[cfg(test)]
    Never,
    /// Before the given reduction step (0: from the start; steps are counted by the tracked
    /// multipliers, so only with `track`).
    #[cfg(test)]
    AfterSteps(usize),
}

impl<F: Field> Plain<F> {
    fn new(ncols: usize, rows: &[Vec<(usize, F)>], track: bool) -> Self {
        Plain {
            order: Order::new(ncols, rows),
            pivot_of: vec![NONE; ncols],
            stored: Vec::new(),
            entries: Vec::new(),
            span: Vec::new(),
            track,
            fill: Vec::new(),
            dense: Accumulator::default(),
            switch: Switch::Cost,
            dense_rows: 0,
        }
    }

    /// Reduces input row `id` (entries in columns below the width): `Ok(pivot column)` when it
    /// is independent of the rows before it, `Err(Σ c · stored[k])` — the stored rows it is the
    /// combination of, empty when not tracked — when dependent.
    ///
    /// The row is reduced by its leading entry, step by step, first in its sorted sparse form:
    /// a step merges it with a pivot row, at a cost of about both their lengths. A row that
    /// fills in (on a connected framework a working row grows to a thousand entries while its
    /// stored remainder keeps a few dozen) moves to the dense [`Accumulator`], where a step
    /// costs the pivot row's length alone, and the scans for leading entries plus the final
    /// gather read about `2 · (width − lead) / 64` words of its bitset. The switch is the ski
    /// rental rule: merge until the merging done on this row costs as much as moving would
    /// (the working row's length plus those words), then move; so no row costs more than
    /// about twice the cheaper of the two forms. The two forms do the same operations on the
    /// same entries in the same order: the outcome, the stored row and the multipliers do not
    /// depend on where (or whether) the row switches.
    fn insert(&mut self, id: usize, row: Vec<(usize, F)>) -> Result<usize, Vec<(usize, F)>> {
        let mut entries = self.order.apply(row);
        let mut used: Vec<(usize, F)> = Vec::new();
        let width = self.pivot_of.len();
        let mut rent = 0;
        loop {
            let Some((lead, value)) = entries.first().map(|(c, v)| (*c, v.clone())) else {
                return Err(used);
            };
            let k = self.pivot_of[lead];
            if k == NONE {
                return self.store(id, lead, entries, value, used);
            }
            let dense = match self.switch {
                Switch::Cost => rent >= entries.len() + 2 * (width - lead) / 64,
                #[cfg(test)]
                Switch::Never => false,
                #[cfg(test)]
                Switch::AfterSteps(n) => used.len() >= n,
            };
            if dense {
                return self.insert_dense(id, entries, used);
            }
            let (from, to) = self.span[k];
            let pivot_row = &self.entries[from..to];
            rent += entries.len() + pivot_row.len();
            self.fill.clear();
            sub_scaled(&mut entries, &value, pivot_row, Some(lead), |_| false, &mut self.fill);
            if self.track {
                used.push((k, value));
            }
        }
    }

    /// [`Plain::insert`] continued in the dense accumulator, from the working row `entries`
    /// (sorted, nonzero, not empty) and the stored rows `used` so far.
    fn insert_dense(
        &mut self,
        id: usize,
        entries: Vec<(usize, F)>,
        mut used: Vec<(usize, F)>,
    ) -> Result<usize, Vec<(usize, F)>> {
        self.dense_rows += 1;
        let acc = &mut self.dense;
        acc.fit(self.pivot_of.len());
        let mut from = entries.first().map_or(0, |e| e.0);
        for (c, v) in entries {
            acc.set(c, v);
        }
        while let Some(lead) = acc.next(from) {
            from = lead;
            let value = acc.take(lead);
            let k = self.pivot_of[lead];
            if k == NONE {
                let mut entries = vec![(lead, value.clone())];
                acc.drain(lead + 1, &mut entries);
                return self.store(id, lead, entries, value, used);
            }
            // The next step's pivot row is most often that of the next position marked now
            // (fill from this step lands before it less often): its first entry is read ahead,
            // so that fetching it from memory overlaps this step's arithmetic.
            if let Some(next) = acc.peek_after(lead)
                && let Some(&(start, _)) = self.span.get(self.pivot_of[next])
            {
                std::hint::black_box(self.entries.get(start).map(|e| e.0));
            }
            // The pivot row leads with its pivot column, which `take` has already cleared.
            let neg = value.neg();
            let (start, end) = self.span[k];
            for (j, s) in &self.entries[start + 1..end] {
                acc.sub_mul(*j, &value, &neg, s);
            }
            if self.track {
                used.push((k, value));
            }
        }
        Err(used)
    }

    /// Stores the remainder `entries` (leading `value` at position `lead`, no pivot there yet)
    /// scaled to a leading 1, with its multipliers: `Ok(its pivot column)`.
    fn store(
        &mut self,
        id: usize,
        lead: usize,
        mut entries: Vec<(usize, F)>,
        value: F,
        used: Vec<(usize, F)>,
    ) -> Result<usize, Vec<(usize, F)>> {
        let Some(inv) = value.inv() else {
            // Unreachable for a field: a nonzero entry has an inverse.
            return Err(used);
        };
        for (_, v) in &mut entries {
            *v = v.mul(&inv);
        }
        self.pivot_of[lead] = self.stored.len();
        let from = self.entries.len();
        self.entries.extend(entries);
        self.span.push((from, self.entries.len()));
        self.stored.push(Stored { id, inv, multipliers: used });
        Ok(self.order.column(lead))
    }

    /// The entries of stored row `k`.
    fn row(&self, k: usize) -> &[(usize, F)] {
        let (from, to) = self.span[k];
        &self.entries[from..to]
    }

    /// `Σ c · stored[k].row` over `used`, as a combination of input rows (sorted by id, zeros
    /// left out): stored rows are replaced by their definitions, latest first (a row's
    /// multipliers refer to earlier rows).
    fn expand(&self, used: Vec<(usize, F)>) -> Vec<(usize, F)> {
        let mut pending: BTreeMap<usize, F> = BTreeMap::new();
        for (k, c) in used {
            let slot = pending.entry(k).or_insert_with(F::zero);
            *slot = slot.add(&c);
        }
        let mut out = Vec::new();
        while let Some((k, c)) = pending.pop_last() {
            if c.is_zero() {
                continue;
            }
            let s = &self.stored[k];
            let scaled = c.mul(&s.inv);
            for (j, m) in &s.multipliers {
                pending.entry(*j).or_insert_with(F::zero).sub_mul_assign(&scaled, m);
            }
            out.push((s.id, scaled));
        }
        out.sort_unstable_by_key(|e| e.0);
        out
    }
}

/// A fill-reducing column order for plain row echelon form: the smallest-last (degeneracy)
/// order of the column graph (two columns adjacent when some row has entries in both) —
/// repeatedly the column with the fewest neighbours left, ties to the smaller index.
///
/// On a framework this peels the vertices of lowest degree first (the reverse of a Henneberg
/// construction, whose vertices have two or three bars when added), so that most pivot rows
/// are found before the rows around them fill in; on trees of bodies it eliminates from the
/// leaves, without fill. Rows longer than [`Order::LONG_ROW`] add no edges (a clique of their
/// width would cost more than it tells). The identity for fewer than [`Order::MIN_COLUMNS`]
/// columns.
struct Order {
    /// `new[c]`: the position of column `c` in the order; `old[k]`: the column at position `k`.
    /// Both empty for the identity.
    new: Vec<usize>,
    old: Vec<usize>,
}

impl Order {
    const MIN_COLUMNS: usize = 32;
    const LONG_ROW: usize = 64;

    fn new<F>(ncols: usize, rows: &[Vec<(usize, F)>]) -> Order {
        if ncols < Self::MIN_COLUMNS {
            return Order { new: Vec::new(), old: Vec::new() };
        }
        let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); ncols];
        for row in rows.iter().filter(|r| r.len() <= Self::LONG_ROW) {
            for (i, (a, _)) in row.iter().enumerate() {
                for (b, _) in &row[i + 1..] {
                    adjacent[*a].push(*b);
                    adjacent[*b].push(*a);
                }
            }
        }
        for list in &mut adjacent {
            list.sort_unstable();
            list.dedup();
        }
        let mut degree: Vec<usize> = adjacent.iter().map(Vec::len).collect();
        let mut done = vec![false; ncols];
        let mut heap: BinaryHeap<Reverse<(usize, usize)>> =
            (0..ncols).map(|c| Reverse((degree[c], c))).collect();
        let mut old = Vec::with_capacity(ncols);
        while let Some(Reverse((d, c))) = heap.pop() {
            if done[c] || d != degree[c] {
                continue;
            }
            done[c] = true;
            old.push(c);
            for &a in &adjacent[c] {
                if !done[a] {
                    degree[a] -= 1;
                    heap.push(Reverse((degree[a], a)));
                }
            }
        }
        let mut new = vec![0; ncols];
        for (k, &c) in old.iter().enumerate() {
            new[c] = k;
        }
        Order { new, old }
    }

    /// A row's entries renumbered into the order (columns past the order's keep their index),
    /// sorted.
    fn apply<F>(&self, mut entries: Vec<(usize, F)>) -> Vec<(usize, F)> {
        if !self.new.is_empty() {
            for (c, _) in &mut entries {
                *c = self.new.get(*c).copied().unwrap_or(*c);
            }
            entries.sort_unstable_by_key(|e| e.0);
        }
        entries
    }

    /// The column at position `k` of the order.
    fn column(&self, k: usize) -> usize {
        self.old.get(k).copied().unwrap_or(k)
    }
}

/// A dense working row: `values` over the whole width and a bitset of the positions that may
/// be nonzero, so that leading entries are found word by word and clearing touches only those
/// positions. Empty until a row first needs it; all zero between rows.
struct Accumulator<F> {
    values: Vec<F>,
    bits: Vec<u64>,
}

impl<F> Default for Accumulator<F> {
    fn default() -> Self {
        Accumulator { values: Vec::new(), bits: Vec::new() }
    }
}

impl<F: Field> Accumulator<F> {
    /// Grows to `width` positions.
    fn fit(&mut self, width: usize) {
        if self.values.len() < width {
            self.values.resize(width, F::zero());
            self.bits.resize(width.div_ceil(64), 0);
        }
    }

    fn mark(&mut self, c: usize) {
        self.bits[c / 64] |= 1 << (c % 64);
    }

    /// Position `c` (zero before) set to `v`.
    fn set(&mut self, c: usize, v: F) {
        self.values[c] = v;
        self.mark(c);
    }

    /// `values[c] −= a · b` (`neg_a` is `−a`), left unsettled ([`Field::sub_mul_unsettled`]:
    /// every read below settles the value first).
    #[inline]
    fn sub_mul(&mut self, c: usize, a: &F, neg_a: &F, b: &F) {
        self.values[c].sub_mul_unsettled(a, neg_a, b);
        self.mark(c);
    }

    /// The value at `c`, leaving zero there.
    fn take(&mut self, c: usize) -> F {
        self.bits[c / 64] &= !(1 << (c % 64));
        let mut v = std::mem::replace(&mut self.values[c], F::zero());
        v.settle();
        v
    }

    /// The first position at or after `from` with a nonzero value; the marks of the zeros
    /// passed on the way are cleared.
    fn next(&mut self, from: usize) -> Option<usize> {
        let mut w = from / 64;
        let mut word = self.bits.get(w)? & (!0 << (from % 64));
        loop {
            while word != 0 {
                let c = w * 64 + word.trailing_zeros() as usize;
                self.values[c].settle();
                if !self.values[c].is_zero() {
                    return Some(c);
                }
                word &= word - 1;
                self.bits[w] &= !(1 << (c % 64));
            }
            w += 1;
            word = *self.bits.get(w)?;
        }
    }

    /// The first marked position after `c` (its value may be zero), without clearing marks.
    fn peek_after(&self, c: usize) -> Option<usize> {
        let mut w = (c + 1) / 64;
        let mut word = self.bits.get(w)? & (!0 << ((c + 1) % 64));
        while word == 0 {
            w += 1;
            word = *self.bits.get(w)?;
        }
        Some(w * 64 + word.trailing_zeros() as usize)
    }

    /// Appends the nonzero entries to `out`, in order, and clears every position. All marks are
    /// at or after `from` (the reduction has cleared the positions it passed), so the words
    /// before its word are not read.
    fn drain(&mut self, from: usize, out: &mut Vec<(usize, F)>) {
        for w in from / 64..self.bits.len() {
            let mut word = std::mem::take(&mut self.bits[w]);
            while word != 0 {
                let c = w * 64 + word.trailing_zeros() as usize;
                word &= word - 1;
                let mut v = std::mem::replace(&mut self.values[c], F::zero());
                v.settle();
                if !v.is_zero() {
                    out.push((c, v));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Echelon, EchelonOptions, ModP, Rat};

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

    #[test]
    fn plain_dependencies_are_the_reduced_forms() {
        // Random sparse rows over 30 columns, many of them combinations of earlier ones, and
        // rows reaching past `ncols`: the same outcomes, combinations included, as the reduced
        // form with tracked combinations.
        let mut state = 987654321u64;
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            state >> 33
        };
        for trial in 0..20 {
            let ncols = 30;
            let mut rows: Vec<SparseRow<ModP>> = Vec::new();
            for i in 0..60 {
                let r = if i > 3 && next() % 3 == 0 {
                    // A combination of up to three earlier rows.
                    let picks = (0..1 + next() % 3)
                        .map(|_| (next() as usize % rows.len(), ModP::new(1 + next() % 1000)))
                        .collect();
                    SparseRow::from_entries(picks).combine_rows(&rows)
                } else {
                    let width = if trial % 5 == 0 { ncols + 3 } else { ncols };
                    let entries = (0..1 + next() % 4)
                        .map(|_| (next() as usize % width, 1 + next() % 1_000_000))
                        .collect::<Vec<_>>();
                    SparseRow::from_entries(
                        entries.into_iter().map(|(c, v)| (c, ModP::new(v))).collect(),
                    )
                };
                rows.push(r);
            }
            let tracked = crate::analyse_rows(ncols, rows.clone(), EchelonOptions::tracked());
            let plain = analyse_rows_plain(ncols, rows.clone());
            assert_eq!(plain.rank, tracked.rank, "trial {trial}");
            for (i, (a, b)) in plain.outcomes.iter().zip(&tracked.outcomes).enumerate() {
                assert_eq!(a.is_independent(), b.is_independent(), "trial {trial} row {i}");
                assert_eq!(a.combination(), b.combination(), "trial {trial} row {i}");
            }
            assert!(plain.outcomes.iter().any(|o| !o.is_independent()));
        }
    }

    /// Everything a `Plain` elimination leaves behind, row by row: the outcome (a pivot column,
    /// or the expanded combination of a dependent row) and the stored rows with their inverses
    /// and multipliers.
    type Trace<F> =
        (Vec<Result<usize, Vec<(usize, F)>>>, Vec<(Vec<(usize, F)>, usize, F, Vec<(usize, F)>)>);

    fn eliminate<F: Field>(
        ncols: usize,
        rows: &[Vec<(usize, F)>],
        switch: Switch,
    ) -> (Trace<F>, usize) {
        let mut lu = Plain::new(ncols, rows, true);
        lu.switch = switch;
        let outcomes = rows
            .iter()
            .enumerate()
            .map(|(id, r)| lu.insert(id, r.clone()).map_err(|used| lu.expand(used)))
            .collect();
        let stored = lu
            .stored
            .iter()
            .enumerate()
            .map(|(k, s)| (lu.row(k).to_vec(), s.id, s.inv.clone(), s.multipliers.clone()))
            .collect();
        ((outcomes, stored), lu.dense_rows)
    }

    /// Random sparse rows over `ncols` columns, a third of them combinations of up to four
    /// earlier rows (planted dependencies), a few reaching across the whole width.
    fn planted(ncols: usize, nrows: usize, seed: u64) -> Vec<Vec<(usize, ModP)>> {
        let mut state = seed;
        let mut next = move || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            state >> 33
        };
        let mut rows: Vec<SparseRow<ModP>> = Vec::new();
        for i in 0..nrows {
            let r = if i > 3 && next() % 3 == 0 {
                let picks = (0..1 + next() % 4)
                    .map(|_| (next() as usize % rows.len(), ModP::new(1 + next() % 1000)))
                    .collect();
                SparseRow::from_entries(picks).combine_rows(&rows)
            } else {
                let count = if next() % 10 == 0 { ncols / 2 } else { 2 + next() as usize % 4 };
                let entries = (0..count)
                    .map(|_| (next() as usize % ncols, ModP::new(1 + next() % 1_000_000)))
                    .collect();
                SparseRow::from_entries(entries)
            };
            rows.push(r);
        }
        rows.into_iter().map(SparseRow::into_entries).collect()
    }

    #[test]
    fn the_dense_accumulator_changes_nothing() {
        // The same outcomes, pivot columns, combinations, stored rows and multipliers whether
        // rows switch to the dense form never, from the start, mid-way or by the cost model;
        // widths of one to four bitset words, and under the order's threshold.
        for (trial, (ncols, nrows)) in
            [(20, 40), (64, 100), (65, 130), (150, 260), (250, 300)].into_iter().enumerate()
        {
            let rows = planted(ncols, nrows, 1000 + trial as u64);
            let (sparse, none) = eliminate(ncols, &rows, Switch::Never);
            assert_eq!(none, 0);
            assert!(sparse.0.iter().any(Result::is_err), "trial {trial}: no dependency");
            for switch in
                [Switch::AfterSteps(0), Switch::AfterSteps(1), Switch::AfterSteps(3), Switch::Cost]
            {
                let (dense, moved) = eliminate(ncols, &rows, switch);
                assert_eq!(dense.0, sparse.0, "trial {trial}, {switch:?}: outcomes");
                assert_eq!(dense.1, sparse.1, "trial {trial}, {switch:?}: stored rows");
                if !matches!(switch, Switch::Cost) {
                    assert!(moved > 0, "trial {trial}, {switch:?}: nothing switched");
                }
            }
        }
    }

    #[test]
    fn the_dense_accumulator_serves_rationals_too() {
        // The accumulator is generic: exact rationals, switched mid-way, give the outcomes and
        // stored rows of the sparse form.
        let rows: Vec<Vec<(usize, Rat)>> = planted(70, 90, 77)
            .into_iter()
            .map(|r| {
                r.into_iter()
                    .map(|(c, v)| (c, Rat::from_i64(v.value() as i64 % 97 - 48)))
                    .filter(|(_, v)| !v.is_zero())
                    .collect()
            })
            .collect();
        let (sparse, _) = eliminate(70, &rows, Switch::Never);
        let (dense, moved) = eliminate(70, &rows, Switch::AfterSteps(2));
        assert!(moved > 0);
        assert_eq!(dense, sparse);
    }

    #[test]
    fn the_cost_model_switches_rows_that_fill_in() {
        // A path of 2,000 columns, rows x_i − x_{i+1}: short rows, short reductions, no switch.
        let n = 2000;
        let mut rows: Vec<Vec<(usize, ModP)>> =
            (0..n - 1).map(|i| vec![(i, ModP::one()), (i + 1, ModP::one().neg())]).collect();
        let (_, moved) = eliminate(n, &rows, Switch::Cost);
        assert_eq!(moved, 0);
        // A row over every column, then its dependent twin: merging them with the path rows
        // costs their whole length at every step, and they switch.
        let full: Vec<(usize, ModP)> = (0..n).map(|c| (c, ModP::new(c as u64 + 1))).collect();
        rows.push(full.clone());
        rows.push(full.into_iter().map(|(c, v)| (c, v.mul(&ModP::new(3)))).collect());
        let (sparse, _) = eliminate(n, &rows, Switch::Never);
        let (cost, moved) = eliminate(n, &rows, Switch::Cost);
        assert_eq!(moved, 2);
        assert_eq!(cost, sparse);
        assert!(cost.0[n - 1].is_ok());
        assert_eq!(cost.0[n], Err(vec![(n - 1, ModP::new(3))]));
    }
}
