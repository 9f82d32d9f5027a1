//! Nonlinear least squares: damped Gauss–Newton (Levenberg–Marquardt) on any system of
//! residuals, geometry-free — the one implementation below the witness projection of
//! `gcs-jacobian` and the solver of `gcs-solve`. The problem gives residuals and their gradient
//! rows at a point; the kernel takes damped Gauss–Newton steps `(JᵀJ + μ·I) h = Jᵀr`, solved
//! by Cholesky (faer), with Levenberg's isotropic damping `μ` on the scale of `JᵀJ`'s largest
//! diagonal entry: the same in every direction, so that as `μ` shrinks the step tends to the
//! minimum-norm Gauss–Newton step (the nearest point, for an underdetermined projection; the
//! trivial motions of a free sketch kept out of the step). Marquardt's `μ·diag(JᵀJ)` would
//! tilt it along directions the residuals do not see.
//!
//! Two damping updates ([`Damping`]): a fixed schedule (`μ` ÷3 after a step that lowers
//! `|r|²`, ×4 after one that does not), what the projection and the homotopy's inner steps
//! use; and Nielsen's gain-ratio update with a stall rule, what the solver uses straight from
//! a drawing (Madsen, Nielsen and Tingleff, *Methods for non-linear least squares problems*,
//! 2004, §3.2): a badly conditioned core (a random Laman core of a thousand points drawn 5%
//! off: the scaled Jacobian's smallest singular value 1.2e-8 against a largest of 3.4e-3)
//! needs about 70 steps, which the fixed schedule takes far more slowly (BENCHMARKS.md,
//! "Large Laman cores").
//!
//! Small problems take the step densely (`O(n²)` memory, `O(n³)` time for `n` unknowns);
//! above [`LmOptions::sparse_above`] unknowns, on the sparse normal matrix with faer's sparse
//! Cholesky (its cost is the fill of the factor: near-linear for chains and grids, up to
//! dense for expander-like graphs). Problems beyond [`LmOptions::max_unknowns`] are refused
//! rather than attempted. Convergence is the residuals themselves within the tolerance: no
//! rank is decided here.

use std::collections::VecDeque;

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Mat, Side};

use crate::SparseRow;

/// A system of residuals in `f64`: `r(x)`, with one gradient row per residual.
pub trait Residuals {
    /// The number of unknowns.
    fn unknowns(&self) -> usize;
    /// The residuals at `x` and their gradients (sparse rows over the unknowns), in the same
    /// order.
    fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>);
}

/// How [`levenberg_marquardt`] updates its damping `μ` (always relative to the largest
/// diagonal entry `s` of `JᵀJ` at the current point).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Damping {
    /// `μ = λ·s`, `λ` ÷3 after a step that lowers `|r|²` (down to 1e-12), ×4 after one that
    /// does not, ×10 when the damped matrix does not factor; the run gives up when `λ` passes
    /// 1e12.
    Fixed,
    /// Nielsen's update from the gain ratio `ρ` (actual over predicted decrease of `|r|²`):
    /// `μ ← μ·max(1/3, 1 − (2ρ − 1)³)` after an accepted step, `μ ← μ·ν, ν ← 2ν` after a
    /// rejected one, `μ ≥ 1e-14·s`; the run stops when `|r|²` has not halved in `stall`
    /// steps (a valley or a local minimum: the caller's fallback takes over), when `μ` passes
    /// 1e10·s, or when the damped matrix does not factor.
    Nielsen {
        /// Steps without `|r|²` halving after which the run gives up.
        stall: usize,
    },
}

/// Options of [`levenberg_marquardt`].
#[derive(Clone, Debug, PartialEq)]
pub struct LmOptions {
    /// Converged when every residual is at most this in absolute value.
    pub tolerance: f64,
    /// The most steps tried (accepted or not).
    pub max_iterations: usize,
    /// The damping of the first step, relative to the largest diagonal entry of `JᵀJ`.
    pub initial_damping: f64,
    /// Problems with more unknowns are not attempted.
    pub max_unknowns: usize,
    /// Above this many unknowns the step is solved on the sparse normal matrix (sparse
    /// Cholesky); at most this many, densely.
    pub sparse_above: usize,
    /// The damping update.
    pub damping: Damping,
    /// Geodesic acceleration (Transtrum and Sethna, 2012), with Nielsen's damping only: each
    /// step corrected by half the second-order term along it, from one more residual
    /// evaluation and one more solve with the same factor — what follows a long curved valley
    /// (a near-flex of a large sketch) in fewer steps.
    pub acceleration: bool,
}

impl Default for LmOptions {
    fn default() -> Self {
        LmOptions {
            tolerance: 1e-12,
            max_iterations: 200,
            initial_damping: 1e-3,
            max_unknowns: 3000,
            sparse_above: 400,
            damping: Damping::Fixed,
            acceleration: false,
        }
    }
}

/// What [`levenberg_marquardt`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct LmOutcome {
    /// The last accepted point.
    pub x: Vec<f64>,
    /// Whether every residual there is within the tolerance (and every coordinate finite).
    pub converged: bool,
    /// Steps tried.
    pub iterations: usize,
    /// The largest residual in absolute value at `x`.
    pub max_residual: f64,
}

fn max_abs(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The state of a [`Damping`] update during a run.
enum Schedule {
    Fixed { lambda: f64 },
    Nielsen { stall: usize, mu: Option<f64>, nu: f64, history: VecDeque<f64> },
}

/// Minimises `|r(x)|²` from `x0` by Levenberg–Marquardt with isotropic damping: small steps
/// from the start, tending to minimum-norm Gauss–Newton steps, which keep the start's shape
/// when the problem is a projection (an underdetermined system lands near its start).
///
/// Returns `None` when the problem has more unknowns than [`LmOptions::max_unknowns`].
///
/// # Example
/// ```
/// use gcs_rank::{LmOptions, Residuals, SparseRow, levenberg_marquardt};
///
/// /// The point of the unit circle nearest to where it starts: x² + y² − 1 = 0.
/// struct Circle;
/// impl Residuals for Circle {
///     fn unknowns(&self) -> usize { 2 }
///     fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
///         let r = x[0] * x[0] + x[1] * x[1] - 1.0;
///         (vec![r], vec![SparseRow::from_entries(vec![(0, 2.0 * x[0]), (1, 2.0 * x[1])])])
///     }
/// }
/// let out = levenberg_marquardt(&Circle, &[3.0, 4.0], &LmOptions::default()).unwrap();
/// assert!(out.converged);
/// assert!((out.x[0] - 0.6).abs() < 1e-9 && (out.x[1] - 0.8).abs() < 1e-9);
/// ```
pub fn levenberg_marquardt(
    problem: &impl Residuals,
    x0: &[f64],
    options: &LmOptions,
) -> Option<LmOutcome> {
    let n = problem.unknowns();
    if n > options.max_unknowns {
        return None;
    }
    let mut x = x0.to_vec();
    x.resize(n, 0.0);
    let mut schedule = match options.damping {
        Damping::Fixed => Schedule::Fixed { lambda: options.initial_damping },
        Damping::Nielsen { stall } => {
            Schedule::Nielsen { stall, mu: None, nu: 2.0, history: VecDeque::new() }
        }
    };
    let (mut r, mut j) = problem.evaluate(&x);
    let mut cost: f64 = r.iter().map(|v| v * v).sum();
    let mut iterations = 0;
    let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
    let mut normal = if n > options.sparse_above {
        Normal::Sparse(SparseNormal::default())
    } else {
        Normal::Dense(Mat::zeros(0, 0))
    };
    while iterations < options.max_iterations {
        if max_abs(&r) <= options.tolerance {
            break;
        }
        iterations += 1;
        if let Schedule::Nielsen { stall, history, .. } = &mut schedule {
            history.push_back(cost);
            // NaN-safe: a cost that is not below half of it `stall` steps ago is a stall.
            let halved = |old: f64| cost.partial_cmp(&(0.5 * old)).is_some_and(|o| o.is_le());
            if history.len() > *stall && history.pop_front().is_some_and(|old| !halved(old)) {
                break;
            }
        }
        // Fixed: μ on the assembled diagonal's scale, added after; Nielsen: μ on the scale of
        // the rows' diagonal, the diagonal seeded with it (each order of summation kept as it
        // was when they were two implementations: the reports do not move by a bit).
        let (g, top, damping, shift) = match &mut schedule {
            Schedule::Fixed { lambda } => {
                let (g, top) = normal.assemble(n, &j, &r, 0.0);
                let damping = *lambda * top.max(1e-12);
                (g, top, damping, damping)
            }
            Schedule::Nielsen { mu, .. } => {
                let top = diagonal(n, &j).into_iter().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
                let damping = mu.get_or_insert(options.initial_damping * top).max(1e-14 * top);
                let (g, _) = normal.assemble(n, &j, &r, damping);
                (g, top, damping, 0.0)
            }
        };
        let factor = normal.factor(shift);
        let step = factor.as_ref().and_then(|f| f.solve(&g));
        let Some(step) = step else {
            match &mut schedule {
                Schedule::Fixed { lambda } => {
                    *lambda *= 10.0;
                    if *lambda > 1e12 {
                        break;
                    }
                    continue;
                }
                Schedule::Nielsen { .. } => break,
            }
        };
        if matches!(schedule, Schedule::Nielsen { .. }) && !finite(&step) {
            break;
        }
        let mut candidate: Vec<f64> = (0..n).map(|i| x[i] - step[i]).collect();
        if options.acceleration
            && matches!(schedule, Schedule::Nielsen { .. })
            && let Some(f) = factor.as_ref()
        {
            // Geodesic acceleration (Transtrum and Sethna, "Improvements to the
            // Levenberg–Marquardt algorithm for nonlinear least-squares minimization",
            // 2012): the second directional derivative along the velocity v = −step,
            // r_vv ≈ (2/δ)·((r(x + δv) − r(x))/δ − J v), gives the acceleration
            // a = −(JᵀJ + μI)⁻¹ Jᵀ r_vv with the same factor; the step is v + a/2, taken
            // when |a| ≤ 0.375·|v| (else the plain step).
            let delta = 0.1;
            let probe: Vec<f64> = (0..n).map(|i| x[i] - delta * step[i]).collect();
            let (rp, _) = problem.evaluate(&probe);
            let mut gvv = Mat::<f64>::zeros(n, 1);
            for (k, row) in j.iter().enumerate().take(rp.len().min(r.len())) {
                let jv: f64 =
                    row.entries().iter().filter(|(c, _)| *c < n).map(|&(c, v)| -v * step[c]).sum();
                let rvv = 2.0 / delta * ((rp[k] - r[k]) / delta - jv);
                for &(c, v) in row.entries() {
                    if c < n {
                        gvv[(c, 0)] += v * rvv;
                    }
                }
            }
            if let Some(a) = f.solve(&gvv) {
                let na: f64 = a.iter().map(|v| v * v).sum::<f64>().sqrt();
                let nv: f64 = step.iter().map(|v| v * v).sum::<f64>().sqrt();
                if 2.0 * na <= 0.75 * nv {
                    for i in 0..n {
                        candidate[i] -= 0.5 * a[i];
                    }
                }
            }
        }
        let (r2, j2) = problem.evaluate(&candidate);
        let cost2: f64 = r2.iter().map(|v| v * v).sum();
        let accepted = cost2 < cost;
        match &mut schedule {
            Schedule::Fixed { lambda } => {
                if accepted {
                    *lambda = (*lambda / 3.0).max(1e-12);
                } else {
                    *lambda *= 4.0;
                    if *lambda > 1e12 {
                        break;
                    }
                }
            }
            Schedule::Nielsen { mu, nu, .. } => {
                if accepted {
                    // The decrease of |r|² the linear model predicts for the step x − h:
                    // hᵀ(μh + Jᵀr).
                    let predicted: f64 =
                        (0..n).map(|i| step[i] * (damping * step[i] + g[(i, 0)])).sum();
                    let rho = (cost - cost2) / predicted.max(f64::MIN_POSITIVE);
                    *mu = Some(damping * (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0));
                    *nu = 2.0;
                } else {
                    *mu = Some(damping * *nu);
                    *nu *= 2.0;
                    if damping > 1e10 * top {
                        break;
                    }
                }
            }
        }
        if accepted {
            x = candidate;
            r = r2;
            j = j2;
            cost = cost2;
        }
    }
    let max_residual = max_abs(&r);
    let converged = max_residual <= options.tolerance && finite(&x);
    Some(LmOutcome { x, converged, iterations, max_residual })
}

/// The diagonal of `JᵀJ`, summed row by row.
fn diagonal(n: usize, j: &[SparseRow<f64>]) -> Vec<f64> {
    let mut d = vec![0.0; n];
    for row in j {
        for &(c, v) in row.entries() {
            if c < n {
                d[c] += v * v;
            }
        }
    }
    d
}

/// `Jᵀr` (as a column), and each product `J[k][a]·J[k][b]` of `JᵀJ` for every row `k` and pair
/// of its columns `a ≤ b` (in the row's order) below `n`, to `add(a, b, value)`: the normal
/// equations, assembled once for the dense and the sparse step.
fn normal_equations(
    n: usize,
    j: &[SparseRow<f64>],
    r: &[f64],
    mut add: impl FnMut(usize, usize, f64),
) -> Mat<f64> {
    let mut g = Mat::<f64>::zeros(n, 1);
    for (row, ri) in j.iter().zip(r) {
        let e = row.entries();
        for (a, (ca, va)) in e.iter().enumerate() {
            if *ca >= n {
                continue;
            }
            g[(*ca, 0)] += va * ri;
            for (cb, vb) in &e[a..] {
                if *cb < n {
                    add(*ca, *cb, va * vb);
                }
            }
        }
    }
    g
}

/// The normal matrix `JᵀJ` of the current point, dense or sparse, and its damped solve.
enum Normal {
    Dense(Mat<f64>),
    Sparse(SparseNormal),
}

impl Normal {
    /// Assembles `JᵀJ` in place, its diagonal starting from `seed`; returns `Jᵀr` and the
    /// assembled matrix's largest diagonal entry.
    fn assemble(
        &mut self,
        n: usize,
        j: &[SparseRow<f64>],
        r: &[f64],
        seed: f64,
    ) -> (Mat<f64>, f64) {
        match self {
            Normal::Dense(h) => {
                *h = Mat::<f64>::zeros(n, n);
                for i in 0..n {
                    h[(i, i)] = seed;
                }
                let g = normal_equations(n, j, r, |a, b, v| {
                    h[(a, b)] += v;
                    if a != b {
                        h[(b, a)] += v;
                    }
                });
                (g, (0..n).map(|i| h[(i, i)]).fold(0.0, f64::max))
            }
            Normal::Sparse(s) => s.assemble(n, j, r, seed),
        }
    }

    /// The Cholesky factor of `JᵀJ + μ·I` (`None` when it is not numerically positive
    /// definite), for one or more right-hand sides.
    fn factor(&mut self, mu: f64) -> Option<Factor> {
        match self {
            Normal::Dense(h) => {
                let n = h.nrows();
                let mut h = h.clone();
                for i in 0..n {
                    h[(i, i)] += mu;
                }
                Some(Factor::Dense(h.llt(Side::Lower).ok()?))
            }
            Normal::Sparse(s) => Some(Factor::Sparse(s.factor(mu)?)),
        }
    }
}

/// A factorised damped normal matrix.
enum Factor {
    Dense(faer::linalg::solvers::Llt<f64>),
    Sparse(Llt<usize, f64>),
}

impl Factor {
    /// `(JᵀJ + μ·I)⁻¹ g`; `None` when a sparse solve is not finite.
    fn solve(&self, g: &Mat<f64>) -> Option<Vec<f64>> {
        match self {
            Factor::Dense(llt) => {
                let step = llt.solve(g);
                Some((0..g.nrows()).map(|i| step[(i, 0)]).collect())
            }
            Factor::Sparse(llt) => {
                let step = llt.solve(g);
                let step: Vec<f64> = (0..g.nrows()).map(|i| step[(i, 0)]).collect();
                step.iter().all(|v| v.is_finite()).then_some(step)
            }
        }
    }
}

/// The sparse normal matrix's lower triangle (faer's supernodal sparse Cholesky, with its
/// fill-reducing ordering), the symbolic factorisation kept while the pattern of `J` stays
/// the same (it changes only when a gradient entry vanishes exactly).
#[derive(Default)]
struct SparseNormal {
    /// The lower triangle's pattern (column pointers, row indices) and its symbolic
    /// factorisation.
    symbolic: Option<(Vec<usize>, Vec<usize>, SymbolicLlt<usize>)>,
    /// The last assembled lower triangle: column pointers, row indices, values.
    matrix: (Vec<usize>, Vec<usize>, Vec<f64>),
}

impl SparseNormal {
    fn assemble(
        &mut self,
        n: usize,
        j: &[SparseRow<f64>],
        r: &[f64],
        seed: f64,
    ) -> (Mat<f64>, f64) {
        // JᵀJ's lower triangle as (column, row, value), every diagonal entry present.
        let mut entries: Vec<(usize, usize, f64)> = (0..n).map(|i| (i, i, seed)).collect();
        let g = normal_equations(n, j, r, |a, b, v| entries.push((a.min(b), a.max(b), v)));
        entries.sort_unstable_by_key(|&(c, r, _)| (c, r));
        let mut col_ptr = vec![0usize; n + 1];
        let mut row_idx: Vec<usize> = Vec::with_capacity(entries.len());
        let mut values: Vec<f64> = Vec::with_capacity(entries.len());
        let mut last = None;
        for (c, r, v) in entries {
            if last == Some((c, r)) {
                if let Some(x) = values.last_mut() {
                    *x += v;
                }
            } else {
                row_idx.push(r);
                values.push(v);
                col_ptr[c + 1] += 1;
                last = Some((c, r));
            }
        }
        for c in 0..n {
            col_ptr[c + 1] += col_ptr[c];
        }
        // The diagonal entry is each column's first (rows sorted, the diagonal always there).
        let top = (0..n).map(|c| values[col_ptr[c]]).fold(0.0, f64::max);
        self.matrix = (col_ptr, row_idx, values);
        (g, top)
    }

    fn factor(&mut self, mu: f64) -> Option<Llt<usize, f64>> {
        let (col_ptr, row_idx, values) = &self.matrix;
        let n = col_ptr.len() - 1;
        let mut values = values.clone();
        for c in 0..n {
            values[col_ptr[c]] += mu;
        }
        let same = matches!(&self.symbolic, Some((p, i, _)) if p == col_ptr && i == row_idx);
        if !same {
            let pattern =
                SymbolicSparseColMat::new_checked(n, n, col_ptr.clone(), None, row_idx.clone());
            let symbolic = SymbolicLlt::try_new(pattern.as_ref(), Side::Lower).ok()?;
            self.symbolic = Some((col_ptr.clone(), row_idx.clone(), symbolic));
        }
        let (_, _, symbolic) = self.symbolic.as_ref()?;
        let matrix = SparseColMat::new(
            SymbolicSparseColMat::new_checked(n, n, col_ptr.clone(), None, row_idx.clone()),
            values,
        );
        Llt::try_new_with_symbolic(symbolic.clone(), matrix.as_ref(), Side::Lower).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three lines through the origin at different slopes: a consistent overdetermined
    /// system, solved at the origin; and an inconsistent one, minimised but not converged.
    struct Lines(Vec<(f64, f64, f64)>);

    impl Residuals for Lines {
        fn unknowns(&self) -> usize {
            2
        }
        fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
            self.0
                .iter()
                .map(|&(a, b, c)| {
                    (a * x[0] + b * x[1] + c, SparseRow::from_entries(vec![(0, a), (1, b)]))
                })
                .unzip()
        }
    }

    #[test]
    fn consistent_and_inconsistent_systems() {
        let o = LmOptions::default();
        let ok = Lines(vec![(1.0, 2.0, 0.0), (3.0, -1.0, 0.0), (1.0, 1.0, 0.0)]);
        let out = levenberg_marquardt(&ok, &[5.0, -7.0], &o).unwrap();
        assert!(out.converged && out.max_residual <= 1e-12, "{out:?}");
        let bad = Lines(vec![(1.0, 0.0, -1.0), (1.0, 0.0, 1.0)]);
        let out = levenberg_marquardt(&bad, &[5.0, 0.0], &o).unwrap();
        assert!(!out.converged);
        assert!(out.x[0].abs() < 1e-6, "the least-squares point x = 0: {out:?}");
        // The sparse step agrees with the dense one.
        let sparse = LmOptions { sparse_above: 0, ..o.clone() };
        let out2 = levenberg_marquardt(&ok, &[5.0, -7.0], &sparse).unwrap();
        assert!(out2.converged && out2.x.iter().all(|v| v.abs() < 1e-9), "{out2:?}");
        let too_big = LmOptions { max_unknowns: 1, ..o };
        assert!(levenberg_marquardt(&ok, &[0.0, 0.0], &too_big).is_none());
    }

    /// A chain of unit distances on a line, x[i+1] − x[i] = 1 with x[0] = 0, underdetermined
    /// by one more free end when the last equation is dropped: the sparse step reaches the
    /// solution, and on the underdetermined system it moves as little as the dense one.
    struct Chain(usize, bool);

    impl Residuals for Chain {
        fn unknowns(&self) -> usize {
            self.0
        }
        fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
            let mut out: (Vec<f64>, Vec<SparseRow<f64>>) = (Vec::new(), Vec::new());
            if self.1 {
                out.0.push(x[0]);
                out.1.push(SparseRow::from_entries(vec![(0, 1.0)]));
            }
            for i in 0..self.0 - 1 {
                let d = x[i + 1] - x[i];
                out.0.push(d * d - 1.0);
                out.1.push(SparseRow::from_entries(vec![(i, -2.0 * d), (i + 1, 2.0 * d)]));
            }
            out
        }
    }

    #[test]
    fn sparse_and_dense_steps_agree() {
        let n = 60;
        let start: Vec<f64> = (0..n).map(|i| i as f64 * 1.1 + 0.3 * ((i * 7) % 5) as f64).collect();
        for anchored in [true, false] {
            let dense = LmOptions { sparse_above: n, ..LmOptions::default() };
            let sparse = LmOptions { sparse_above: 0, ..LmOptions::default() };
            let a = levenberg_marquardt(&Chain(n, anchored), &start, &dense).unwrap();
            let b = levenberg_marquardt(&Chain(n, anchored), &start, &sparse).unwrap();
            assert!(a.converged && b.converged, "{a:?} {b:?}");
            for (u, v) in a.x.iter().zip(&b.x) {
                assert!((u - v).abs() < 1e-6, "{u} {v}");
            }
            for i in 0..n - 1 {
                assert!(((b.x[i + 1] - b.x[i]).abs() - 1.0).abs() < 1e-9);
            }
        }
    }
    /// The solver's options: Nielsen's damping, sparse steps throughout.
    fn nielsen() -> LmOptions {
        LmOptions {
            max_iterations: 300,
            sparse_above: 0,
            damping: Damping::Nielsen { stall: 20 },
            ..LmOptions::default()
        }
    }

    /// Rosenbrock's valley as residuals, r = (10·(y − x²), 1 − x): with and without geodesic
    /// acceleration the run reaches (1, 1). (Here acceleration takes 22 steps against 18: it
    /// pays on the long valleys of large sketches, BENCHMARKS.md, not on every problem.)
    #[test]
    fn acceleration_follows_a_curved_valley() {
        struct Rosenbrock;
        impl Residuals for Rosenbrock {
            fn unknowns(&self) -> usize {
                2
            }
            fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
                (
                    vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]],
                    vec![
                        SparseRow::from_entries(vec![(0, -20.0 * x[0]), (1, 10.0)]),
                        SparseRow::from_entries(vec![(0, -1.0)]),
                    ],
                )
            }
        }
        let plain = levenberg_marquardt(&Rosenbrock, &[-1.2, 1.0], &nielsen()).unwrap();
        let options = LmOptions { acceleration: true, ..nielsen() };
        let fast = levenberg_marquardt(&Rosenbrock, &[-1.2, 1.0], &options).unwrap();
        for out in [&plain, &fast] {
            assert!(out.converged, "{out:?}");
            assert!((out.x[0] - 1.0).abs() < 1e-9 && (out.x[1] - 1.0).abs() < 1e-9, "{out:?}");
        }
    }

    /// A free triangle of the given distances (between points 0–1, 1–2, 0–2; three trivial
    /// motions).
    struct Triangle([f64; 3]);

    impl Residuals for Triangle {
        fn unknowns(&self) -> usize {
            6
        }
        fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
            let mut out: (Vec<f64>, Vec<SparseRow<f64>>) = (Vec::new(), Vec::new());
            for ((a, b), d) in [(0, 1), (1, 2), (0, 2)].into_iter().zip(self.0) {
                let (dx, dy) = (x[2 * b] - x[2 * a], x[2 * b + 1] - x[2 * a + 1]);
                let l = dx.hypot(dy);
                out.0.push(l - d);
                out.1.push(SparseRow::from_entries(vec![
                    (2 * a, -dx / l),
                    (2 * a + 1, -dy / l),
                    (2 * b, dx / l),
                    (2 * b + 1, dy / l),
                ]));
            }
            out
        }
    }

    /// Distances 3, 4, 5: the steps are orthogonal to the translations, so the solve keeps the
    /// start's centroid, and it converges.
    #[test]
    fn free_triangle_keeps_its_centroid() {
        let start = [0.2, -0.1, 3.3, 0.2, 2.7, 4.4];
        let out = levenberg_marquardt(&Triangle([3.0, 4.0, 5.0]), &start, &nielsen()).unwrap();
        assert!(out.converged && out.max_residual <= 1e-12, "{out:?}");
        for axis in 0..2 {
            let before: f64 = (0..3).map(|p| start[2 * p + axis]).sum();
            let after: f64 = (0..3).map(|p| out.x[2 * p + axis]).sum();
            assert!((before - after).abs() < 1e-9, "axis {axis}: {before} → {after}");
        }
        // The drawn turn (counter-clockwise) is kept.
        let turn = |x: &[f64]| (x[2] - x[0]) * (x[5] - x[1]) - (x[3] - x[1]) * (x[4] - x[0]);
        assert!(turn(&start) > 0.0 && turn(&out.x) > 0.0);
    }

    /// Inconsistent distances (1, 1, 3: no triangle): no convergence, and the run ends (by the
    /// stall rule or the damping bound) well before the iteration limit.
    #[test]
    fn no_solution_stops_early() {
        let options = LmOptions { max_iterations: 10_000, ..nielsen() };
        let out = levenberg_marquardt(
            &Triangle([1.0, 1.0, 3.0]),
            &[0.0, 0.0, 1.0, 0.3, 2.0, 0.1],
            &options,
        )
        .unwrap();
        assert!(!out.converged);
        assert!(out.iterations < 1000, "{out:?}");
    }
}
