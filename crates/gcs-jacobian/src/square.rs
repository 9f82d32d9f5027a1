//! The modular witness's last attempt: a point of the parameter-free constraints modulo the
//! prime, found as the solution of a square system over random free coordinates, its structure
//! read off the numerical projection of the sketch ([`crate::project`]).
//!
//! The constructive placement ([`crate::place`]) decides, entity by entity, which coordinates
//! are free choices and which its constraints determine; where a sketch's loops defeat every
//! order it tries (a linear pattern whose copies are also mirror images, offsets of offsets),
//! it fails although the sketch itself shows that the constraints have real solutions near it.
//! Here the split comes from that solution instead: at the projected point `x*`, the rows of
//! the parameter-free constraints are reduced (floating point, rows scaled to their largest
//! entry), which picks independent rows `R` and as many pivot columns `B`; the other columns
//! `N` are coordinates of the solutions near `x*` (the implicit function theorem: the rows `R`
//! are a regular system in `B` there). Modulo the prime, `N` is given random values and the
//! square system `R` in `B` is solved block by block along its Dulmage–Mendelsohn fine
//! decomposition ([`gcs_rank::bipartite`]): a linear block by elimination, any other at a
//! random point of its solutions ([`crate::polysolve`]), a block without a root again with
//! other random values of the free coordinates it reads first.
//!
//! The floating point only proposes the split; nothing here decides a rank. What is returned is
//! checked exactly modulo the prime: every parameter-free equation vanishes (the rows left out
//! of `R` too), each block's Jacobian is regular at its point — so the point is a regular point
//! of solutions of dimension `|N|`, and, `N` being random, a generic point of them — no entity
//! is degenerate, and points apart near the sketch are apart. A split the sketch's special
//! position misleads (a rank that drops at `x*`) only makes this attempt fail.

use gcs_model::rng::SplitMix64;
use gcs_model::{ConstraintIdx, ConstraintKind, EntityIdx, EntityKind, System};
use gcs_rank::bipartite::{Bipartite, dulmage_mendelsohn};
use gcs_rank::{Field, ModQ, PrimeField};

use crate::dual::Dual;
use crate::laws;
use crate::layout::Layout;
use crate::polysolve::{self, Poly};
use crate::qla::{Num, Q};
use crate::views::Local;

/// A row below this, relative to its largest entry before the reduction, is taken as dependent
/// on the rows before it when the split is chosen (a proposal, checked exactly afterwards).
const DEPENDENT: f64 = 1e-9;

/// A pivot is taken among the entries at least this fraction of the row's largest (threshold
/// pivoting): the last column among them (what a sketch copies is written after its original,
/// and is better determined than free), or, for a second split, the first.
const PIVOT_THRESHOLD: f64 = 0.1;

/// How often a block is tried again with other values of the free coordinates it reads first.
const BLOCK_TRIES: usize = 32;

/// How often the whole construction is started again with other random values.
const ATTEMPTS: usize = 3;

/// Where equations come from.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// A parameter-free constraint's rows.
    Law(ConstraintIdx),
    /// The parallelism a distance between lines (concentricity, between circles) needs.
    Parallel(ConstraintIdx),
    /// An entity's internal relation (the Plücker relation of a 3D line).
    Internal(EntityIdx),
}

/// One equation: its source and its index among the source's rows, and the columns it reads.
struct Row {
    source: usize,
    k: usize,
    cols: Vec<usize>,
}

struct Square<'a> {
    system: &'a System,
    layout: &'a Layout,
    variants: Vec<usize>,
    sources: Vec<Source>,
}

impl Square<'_> {
    /// The rows of source `s` at `x`, with the columns of their gradients.
    fn rows<F: Field>(&self, s: Source, x: &[F]) -> (Vec<Dual<F>>, Vec<usize>) {
        let none = |_: EntityIdx| None;
        match s {
            Source::Law(ci) | Source::Parallel(ci) => {
                let base = self.system.constraint_base_entities(ci);
                let local = Local::new(self.system, self.layout, &base, x);
                let sig = self.system.constraint(ci).signature;
                let law = laws::law(sig, self.variants[ci.index()], &local, &none, false);
                let rows = match s {
                    Source::Law(_) => law.rows,
                    _ => law.parallel.unwrap_or_default(),
                };
                (rows, local.cols)
            }
            Source::Internal(e) => {
                let local = Local::new(self.system, self.layout, &[e], x);
                let rows = match self.layout.repr(e) {
                    Some(repr) => {
                        repr.internal_equations(local.coords(e)).into_iter().take(1).collect()
                    }
                    None => Vec::new(),
                };
                (rows, local.cols)
            }
        }
    }
}

/// A point of the parameter-free constraints modulo the current prime (see the module
/// documentation), from the approximate solution `approx`, with pivots `last` or first in
/// column order (see [`PIVOT_THRESHOLD`]); `None` when none was found.
pub(crate) fn place(
    system: &System,
    layout: &Layout,
    approx: &[f64],
    seed: u64,
    last: bool,
    budget: &mut u64,
) -> Option<Vec<Q>> {
    let ncols = layout.ncols();
    let mut sources = Vec::new();
    let variants = crate::project::variants_at(system, layout, approx);
    let none = |_: EntityIdx| None;
    for ci in system.constraint_indices() {
        let c = system.constraint(ci);
        if c.kind == ConstraintKind::Fix {
            // (Modulo the prime a fixed position is read off the witness, as a dimension is.)
            continue;
        }
        if !c.kind.is_metric() {
            sources.push(Source::Law(ci));
            continue;
        }
        let base = system.constraint_base_entities(ci);
        let local = Local::new(system, layout, &base, approx);
        if laws::law(c.signature, variants[ci.index()], &local, &none, false).parallel.is_some() {
            sources.push(Source::Parallel(ci));
        }
    }
    for e in system.entity_indices() {
        if let Some(repr) = layout.repr(e)
            && repr.internal_rows() > usize::from(repr.homogeneous())
        {
            sources.push(Source::Internal(e));
        }
    }
    let sq = Square { system, layout, variants, sources };
    let mut rng = SplitMix64::new(seed ^ 0x005A_0A2E);

    // The rows at the projection, and the columns each reads (at a random point as well, so
    // that a derivative vanishing at the projection does not hide a column).
    let random: Vec<f64> = (0..ncols).map(|_| (rng.below(2001) as f64 - 1000.0) / 1000.0).collect();
    let mut rows: Vec<Row> = Vec::new();
    let mut gradients: Vec<Vec<(usize, f64)>> = Vec::new();
    for (s, source) in sq.sources.iter().enumerate() {
        let (at, cols) = sq.rows(*source, approx);
        let (elsewhere, _) = sq.rows(*source, &random);
        for (k, (r, q)) in at.iter().zip(&elsewhere).enumerate() {
            let read: Vec<usize> = cols
                .iter()
                .enumerate()
                .filter(|(i, _)| r.grad[*i] != 0.0 || q.grad[*i] != 0.0)
                .map(|(_, c)| *c)
                .collect();
            gradients.push(cols.iter().zip(&r.grad).map(|(c, g)| (*c, *g)).collect());
            rows.push(Row { source: s, k, cols: read });
        }
    }
    if rows.iter().any(|r| r.cols.iter().any(|c| *c >= ncols)) {
        return None;
    }

    // The split: independent rows and their pivot columns, by the reduction at the projection.
    let (independent, pivot_cols) = split(ncols, &gradients, last);
    let mut b_index = vec![usize::MAX; ncols];
    for (i, c) in pivot_cols.iter().enumerate() {
        b_index[*c] = i;
    }
    let graph = Bipartite::new(
        pivot_cols.len(),
        independent
            .iter()
            .map(|r| rows[*r].cols.iter().map(|c| b_index[*c]).filter(|i| *i != usize::MAX)),
    );
    let dm = dulmage_mendelsohn(&graph);

    let covered: usize = dm.blocks.iter().map(|(r, _)| r.len()).sum();
    if covered != independent.len() || dm.matching.size != pivot_cols.len() {
        return None;
    }
    // The rows left out, by the last block among their columns (checked once it is solved;
    // before any block when they read no pivot column).
    let mut block_of_col = vec![None; ncols];
    for (k, (_, bcols)) in dm.blocks.iter().enumerate() {
        for i in bcols {
            block_of_col[pivot_cols[*i]] = Some(k);
        }
    }
    let mut in_r = vec![false; rows.len()];
    for r in &independent {
        in_r[*r] = true;
    }
    let mut checked_after: Vec<Vec<usize>> = vec![Vec::new(); dm.blocks.len() + 1];
    for (r, row) in rows.iter().enumerate() {
        if !in_r[r] {
            let last = row.cols.iter().filter_map(|c| block_of_col[*c]).max();
            checked_after[last.map_or(0, |k| k + 1)].push(r);
        }
    }
    let apart = apart_pairs(system, layout, &sq.sources, approx);

    for _ in 0..ATTEMPTS {
        let mut solver = Solver {
            sq: &sq,
            rows: &rows,
            value: vec![ModQ::zero(); ncols],
            assigned: vec![false; ncols],
            rng: SplitMix64::new(rng.next_u64()),
            apart: &apart,
            hopeless: false,
        };
        let mut ok = solver.check(&checked_after[0], &[]);
        for (k, (brows, bcols)) in dm.blocks.iter().enumerate() {
            if !ok {
                break;
            }
            let block_rows: Vec<usize> = brows.iter().map(|i| independent[*i]).collect();
            let block_cols: Vec<usize> = bcols.iter().map(|i| pivot_cols[*i]).collect();
            ok = solver.block(&block_rows, &block_cols, &checked_after[k + 1], budget);
        }
        if solver.hopeless {
            return None;
        }
        if !ok {
            continue;
        }
        for c in 0..ncols {
            if !solver.assigned[c] {
                solver.assign_random(c);
            }
        }
        let all: Vec<usize> = (0..rows.len()).collect();
        let every: Vec<usize> = (0..ncols).collect();
        if solver.check(&all, &every) {
            return Some(solver.value.into_iter().map(Num::P).collect());
        }
    }
    None
}

/// The independent rows and their pivot columns, by Gaussian elimination of the rows (as
/// `(column, entry)` lists) in order, each scaled to its largest entry (see [`DEPENDENT`],
/// [`PIVOT_THRESHOLD`]).
fn split(ncols: usize, gradients: &[Vec<(usize, f64)>], last: bool) -> (Vec<usize>, Vec<usize>) {
    let mut acc = vec![0.0f64; ncols];
    let mut touched: Vec<usize> = Vec::new();
    let mut mark = vec![false; ncols];
    // The pivot rows, normalised to 1 at their pivot, in the order they were taken.
    let mut pivots: Vec<(usize, Vec<(usize, f64)>)> = Vec::new();
    let mut independent = Vec::new();
    for (r, g) in gradients.iter().enumerate() {
        let largest = g.iter().map(|(_, v)| v.abs()).fold(0.0, f64::max);
        if largest == 0.0 || !largest.is_finite() {
            continue;
        }
        for (c, v) in g {
            if !mark[*c] {
                mark[*c] = true;
                touched.push(*c);
            }
            acc[*c] += v / largest;
        }
        for (pc, prow) in &pivots {
            let f = acc[*pc];
            if f == 0.0 {
                continue;
            }
            for (c, v) in prow {
                if !mark[*c] {
                    mark[*c] = true;
                    touched.push(*c);
                }
                acc[*c] -= f * v;
            }
            acc[*pc] = 0.0;
        }
        let top = touched.iter().map(|c| acc[*c].abs()).fold(0.0, f64::max);
        if top > DEPENDENT {
            let pc = touched
                .iter()
                .copied()
                .filter(|c| acc[*c].abs() >= PIVOT_THRESHOLD * top)
                .max_by_key(|c| if last { *c } else { usize::MAX - *c })
                .unwrap_or(touched[0]);
            let p = acc[pc];
            let mut row: Vec<(usize, f64)> =
                touched.iter().filter(|c| acc[**c] != 0.0).map(|c| (*c, acc[*c] / p)).collect();
            row.sort_unstable_by_key(|(c, _)| *c);
            pivots.push((pc, row));
            independent.push(r);
        }
        for c in touched.drain(..) {
            acc[c] = 0.0;
            mark[c] = false;
        }
    }
    let cols = pivots.into_iter().map(|(c, _)| c).collect();
    (independent, cols)
}

/// The pairs of points a generic point keeps apart: the ends of a segment or an arc, and two
/// points of one equation's source, apart at the projection (relative to its size).
fn apart_pairs(
    system: &System,
    layout: &Layout,
    sources: &[Source],
    approx: &[f64],
) -> Vec<(EntityIdx, EntityIdx)> {
    let size = approx.iter().map(|v| v.abs()).fold(1.0, f64::max);
    let point = |e: EntityIdx| system.entity(e).kind() == EntityKind::Point;
    let far = |a: EntityIdx, b: EntityIdx| {
        let (pa, pb) = (&approx[layout.columns(a)], &approx[layout.columns(b)]);
        pa.iter().zip(pb).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt() > 1e-6 * size
    };
    let mut out = Vec::new();
    let mut push = |a: EntityIdx, b: EntityIdx| {
        if a != b && point(a) && point(b) && far(a, b) {
            out.push((a.min(b), a.max(b)));
        }
    };
    for e in system.entity_indices() {
        if let Some((a, b)) = system.segment_points(e).or_else(|| system.arc_points(e)) {
            push(a, b);
        }
    }
    for s in sources {
        if let Source::Law(ci) = s {
            let base = system.constraint_base_entities(*ci);
            for (i, a) in base.iter().enumerate() {
                for b in &base[i + 1..] {
                    push(*a, *b);
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The values modulo the prime, assigned block by block.
struct Solver<'a> {
    sq: &'a Square<'a>,
    rows: &'a [Row],
    value: Vec<ModQ>,
    assigned: Vec<bool>,
    rng: SplitMix64,
    apart: &'a [(EntityIdx, EntityIdx)],
    /// A block too large to solve was met: other random values do not help.
    hopeless: bool,
}

impl Solver<'_> {
    fn assign_random(&mut self, c: usize) {
        self.value[c] = ModQ::residue(self.rng.next_u64());
        self.assigned[c] = true;
    }

    /// Solves the block `rows` in `cols` (see [`place`]), then checks the rows `then`; the
    /// free coordinates it reads first are drawn (again, when it has no acceptable point).
    fn block(&mut self, rows: &[usize], cols: &[usize], then: &[usize], budget: &mut u64) -> bool {
        let mut fresh: Vec<usize> = Vec::new();
        for r in rows {
            for &c in &self.rows[*r].cols {
                if !self.assigned[c] && !cols.contains(&c) && !fresh.contains(&c) {
                    fresh.push(c);
                }
            }
        }
        for _ in 0..BLOCK_TRIES {
            for &c in &fresh {
                self.assign_random(c);
            }
            for point in self.points(rows, cols, budget) {
                for (c, v) in cols.iter().zip(&point) {
                    self.value[*c] = *v;
                    self.assigned[*c] = true;
                }
                if self.regular(rows, cols) && self.check(then, cols) {
                    return true;
                }
            }
            for &c in cols {
                self.assigned[c] = false;
            }
            if fresh.is_empty() {
                break;
            }
        }
        false
    }

    /// The points of the block's equations the solver finds. The rows linear in the block's
    /// columns are solved first (a point and a basis of their kernel: the linear rows of a
    /// pattern's copies, of mirror images about placed axes); the others, in the kernel's
    /// coordinates, are solved as a polynomial system at a few random points of its solutions
    /// ([`crate::polysolve`]) — none when the kernel is too large.
    fn points(&mut self, rows: &[usize], cols: &[usize], budget: &mut u64) -> Vec<Vec<ModQ>> {
        type P = Poly<ModQ>;
        let n = cols.len();
        // Linear rows: at two random points the Jacobians agree and the values differ by the
        // Jacobian times the step (a polynomial that is not linear passes with probability at
        // most its degree over the prime; every point is checked all the same).
        let x0: Vec<ModQ> = (0..n).map(|_| ModQ::residue(self.rng.next_u64())).collect();
        let dx: Vec<ModQ> = (0..n).map(|_| ModQ::residue(self.rng.next_u64())).collect();
        let x1: Vec<ModQ> = x0.iter().zip(&dx).map(|(a, b)| a.add(b)).collect();
        let (Some(at0), Some(at1)) = (self.rows_at(rows, cols, &x0), self.rows_at(rows, cols, &x1))
        else {
            return Vec::new();
        };
        let mut linear = Vec::new();
        let mut nonlinear = Vec::new();
        for (i, (l0, l1)) in at0.iter().zip(&at1).enumerate() {
            let mut moved = l0[n];
            for (g, d) in l0[..n].iter().zip(&dx) {
                moved = moved.add(&g.mul(d));
            }
            if l0[..n] == l1[..n] && moved == l1[n] {
                // J (x − x0) = −v0.
                let mut line = l0.clone();
                line[n] = line[n].neg();
                linear.push(line);
            } else {
                nonlinear.push(rows[i]);
            }
        }
        let Some((step, kernel)) = affine_solutions(linear, n) else { return Vec::new() };
        let base: Vec<ModQ> = x0.iter().zip(&step).map(|(a, b)| a.add(b)).collect();
        let k = kernel.len();
        if nonlinear.is_empty() {
            return if k == 0 { vec![base] } else { Vec::new() };
        }
        if k > polysolve::MAX_VARS {
            self.hopeless = true;
            return Vec::new();
        }
        // The block's columns as affine forms in the kernel's coordinates.
        let mut coords: Vec<P> = vec![P::zero(); self.value.len()];
        for r in &nonlinear {
            for &c in &self.rows[*r].cols {
                coords[c] = P::constant(self.value[c]);
            }
        }
        for (i, c) in cols.iter().enumerate() {
            let mut form = P::constant(base[i]);
            for (j, v) in kernel.iter().enumerate() {
                if !v[i].is_zero() {
                    form = form.add(&P::var(j).mul(&P::constant(v[i])));
                }
            }
            coords[*c] = form;
        }
        let mut equations: Vec<P> = Vec::with_capacity(nonlinear.len());
        // (Each source evaluated once: its rows in the block are read from it.)
        let mut by_source: Vec<(usize, Vec<Dual<P>>)> = Vec::new();
        for r in &nonlinear {
            let row = &self.rows[*r];
            let i = match by_source.iter().position(|(s, _)| *s == row.source) {
                Some(i) => i,
                None => {
                    let (values, _) = self.sq.rows(self.sq.sources[row.source], &coords);
                    by_source.push((row.source, values));
                    by_source.len() - 1
                }
            };
            match by_source[i].1.get(row.k) {
                Some(d) => equations.push(d.value.clone()),
                None => return Vec::new(),
            }
        }
        // Points kept apart that a solution shows together are kept apart in the next round
        // (`z · Π ℓ = 1`, `ℓ` a random linear form in their difference): folded
        // constructions form parts of the solutions as large as the proper one, or larger, and
        // a random point of the solutions lands on them.
        let layout = self.sq.layout;
        let column = |c: usize| cols.iter().position(|b| *b == c);
        let known = |e: EntityIdx, assigned: &[bool]| {
            layout.columns(e).all(|c| assigned[c] || column(c).is_some())
        };
        let pairs: Vec<(EntityIdx, EntityIdx)> = self
            .apart
            .iter()
            .copied()
            .filter(|(a, b)| {
                let touched = |e: EntityIdx| layout.columns(e).any(|c| column(c).is_some());
                (touched(*a) || touched(*b))
                    && known(*a, &self.assigned)
                    && known(*b, &self.assigned)
            })
            .collect();
        let at = |x: &[ModQ], value: &[ModQ], c: usize| column(c).map_or(value[c], |i| x[i]);
        let mut saturated: Vec<usize> = Vec::new();
        for _round in 0..4 {
            let mut system = equations.clone();
            let mut nv = k;
            if !saturated.is_empty() {
                if k >= polysolve::MAX_VARS {
                    return Vec::new();
                }
                let mut product = P::one();
                for &i in &saturated {
                    let (a, b) = pairs[i];
                    let mut l = P::zero();
                    for (ca, cb) in layout.columns(a).zip(layout.columns(b)) {
                        let r = P::constant(ModQ::residue(self.rng.next_u64()));
                        l = l.add(&coords[ca].sub(&coords[cb]).mul(&r));
                    }
                    product = product.mul(&l);
                }
                system.push(P::var(k).mul(&product).sub(&P::one()));
                nv = k + 1;
            }
            let rng = &mut self.rng;
            let found = polysolve::points(&system, nv, 16, &mut || rng.next_u64(), budget);
            let Ok((ts, _)) = found else { return Vec::new() };
            let points: Vec<Vec<ModQ>> = ts
                .into_iter()
                .map(|t| {
                    let mut x = base.clone();
                    for (tj, v) in t.iter().take(k).zip(&kernel) {
                        for (xi, vi) in x.iter_mut().zip(v) {
                            *xi = xi.add(&tj.mul(vi));
                        }
                    }
                    x
                })
                .collect();
            let mut proper = Vec::new();
            let mut more = false;
            for x in points {
                let together: Vec<usize> = (0..pairs.len())
                    .filter(|i| {
                        let (a, b) = pairs[*i];
                        layout
                            .columns(a)
                            .zip(layout.columns(b))
                            .all(|(ca, cb)| at(&x, &self.value, ca) == at(&x, &self.value, cb))
                    })
                    .collect();
                if together.is_empty() {
                    proper.push(x);
                }
                for i in together {
                    if !saturated.contains(&i) {
                        saturated.push(i);
                        more = true;
                    }
                }
            }
            // (A product of many forms makes the system too large to solve.)
            if !proper.is_empty() || !more || saturated.len() > 8 {
                return proper;
            }
        }
        Vec::new()
    }

    /// The values and the Jacobian (dense, in the block's columns) of the block's rows at the
    /// values with `x` in the block's columns; `None` when a row is missing.
    fn rows_at(&mut self, rows: &[usize], cols: &[usize], x: &[ModQ]) -> Option<Vec<Vec<ModQ>>> {
        for (c, v) in cols.iter().zip(x) {
            self.value[*c] = *v;
        }
        let mut out = Vec::with_capacity(rows.len());
        for r in rows {
            let row = &self.rows[*r];
            let (values, local_cols) = self.sq.rows(self.sq.sources[row.source], &self.value);
            let d = values.get(row.k)?;
            let mut line = vec![ModQ::zero(); cols.len() + 1];
            for (c, g) in local_cols.iter().zip(&d.grad) {
                if let Some(i) = cols.iter().position(|b| b == c) {
                    line[i] = line[i].add(g);
                }
            }
            line[cols.len()] = d.value;
            out.push(line);
        }
        Some(out)
    }

    /// Whether the block's Jacobian is regular at the values.
    fn regular(&self, rows: &[usize], cols: &[usize]) -> bool {
        let mut matrix: Vec<gcs_rank::SparseRow<ModQ>> = Vec::with_capacity(rows.len());
        for r in rows {
            let row = &self.rows[*r];
            let (values, local_cols) = self.sq.rows(self.sq.sources[row.source], &self.value);
            let Some(d) = values.get(row.k) else { return false };
            let entries: Vec<(usize, ModQ)> = local_cols
                .iter()
                .zip(&d.grad)
                .filter_map(|(c, g)| cols.iter().position(|b| b == c).map(|i| (i, *g)))
                .filter(|(_, g)| !g.is_zero())
                .collect();
            matrix.push(gcs_rank::SparseRow::from_entries(entries));
        }
        gcs_rank::echelon_rank(cols.len(), matrix).0 == cols.len()
    }

    /// Whether the rows `check` vanish at the values (drawing the free coordinates they read
    /// that are not drawn yet), and the entities with a column in `cols` are proper and apart
    /// from the points they must be apart from.
    fn check(&mut self, check: &[usize], cols: &[usize]) -> bool {
        let rows = self.rows;
        for r in check {
            let row = &rows[*r];
            for &c in &row.cols {
                if !self.assigned[c] {
                    self.assign_random(c);
                }
            }
            let (values, _) = self.sq.rows(self.sq.sources[row.source], &self.value);
            if values.get(row.k).is_none_or(|d| !d.value.is_zero()) {
                return false;
            }
        }
        let layout = self.sq.layout;
        let done = |e: EntityIdx, assigned: &[bool]| layout.columns(e).all(|c| assigned[c]);
        let touched = |e: EntityIdx| layout.columns(e).any(|c| cols.contains(&c));
        for e in self.sq.system.entity_indices() {
            if let Some(repr) = layout.repr(e)
                && touched(e)
                && done(e, &self.assigned)
            {
                let x: Vec<Q> = self.value[layout.columns(e)].iter().map(|v| Num::P(*v)).collect();
                if repr.degenerate(&x) {
                    return false;
                }
            }
        }
        self.apart.iter().all(|(a, b)| {
            !(touched(*a) || touched(*b))
                || !done(*a, &self.assigned)
                || !done(*b, &self.assigned)
                || self.value[layout.columns(*a)] != self.value[layout.columns(*b)]
        })
    }
}

/// The solutions of the linear system `m` (rows: `n` coefficients, then the right-hand side):
/// a particular one and a basis of the kernel; `None` when there is none.
fn affine_solutions(mut m: Vec<Vec<ModQ>>, n: usize) -> Option<(Vec<ModQ>, Vec<Vec<ModQ>>)> {
    let mut pivot_row = 0;
    let mut pivot_of: Vec<Option<usize>> = vec![None; n];
    for col in 0..n {
        let Some(p) = (pivot_row..m.len()).find(|r| !m[*r][col].is_zero()) else { continue };
        m.swap(pivot_row, p);
        let inv = m[pivot_row][col].inv()?;
        for v in m[pivot_row].iter_mut() {
            *v = v.mul(&inv);
        }
        let top = m[pivot_row].clone();
        for (r, line) in m.iter_mut().enumerate() {
            if r != pivot_row && !line[col].is_zero() {
                let f = line[col];
                for (x, y) in line.iter_mut().zip(&top) {
                    x.sub_mul_assign(&f, y);
                }
            }
        }
        pivot_of[col] = Some(pivot_row);
        pivot_row += 1;
    }
    // (A row left `0 = c ≠ 0`: no solution.)
    if m[pivot_row..].iter().any(|r| !r[n].is_zero()) {
        return None;
    }
    let particular: Vec<ModQ> =
        pivot_of.iter().map(|p| p.map_or(ModQ::zero(), |r| m[r][n])).collect();
    let kernel = (0..n)
        .filter(|f| pivot_of[*f].is_none())
        .map(|f| {
            let mut v = vec![ModQ::zero(); n];
            v[f] = ModQ::one();
            for (c, p) in pivot_of.iter().enumerate() {
                if let Some(r) = p {
                    v[c] = m[*r][f].neg();
                }
            }
            v
        })
        .collect();
    Some((particular, kernel))
}
