//! Nonlinear least squares: damped Gauss–Newton (Levenberg–Marquardt) on any system of
//! residuals, geometry-free. Below the witness projection of `gcs-jacobian` and, later, the
//! solver: the problem gives residuals and their gradient rows at a point; the kernel takes
//! damped Gauss–Newton steps `(JᵀJ + λ·s·I) δ = −Jᵀr` (`s` the largest diagonal entry of
//! `JᵀJ`), solved densely by Cholesky (faer), shrinking `λ` after a step that lowers `|r|²` and
//! growing it otherwise.
//!
//! Small problems take the step densely (`O(n²)` memory, `O(n³)` time for `n` unknowns);
//! above [`LmOptions::sparse_above`] unknowns, on the sparse normal matrix with faer's sparse
//! Cholesky (its cost is the fill of the factor: near-linear for chains and grids, up to
//! dense for expander-like graphs). Problems beyond [`LmOptions::max_unknowns`] are refused
//! rather than attempted.

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

/// Options of [`levenberg_marquardt`].
#[derive(Clone, Debug, PartialEq)]
pub struct LmOptions {
    /// Converged when every residual is at most this in absolute value.
    pub tolerance: f64,
    /// The most steps tried (accepted or not).
    pub max_iterations: usize,
    /// The damping of the first step.
    pub initial_damping: f64,
    /// Problems with more unknowns are not attempted.
    pub max_unknowns: usize,
    /// Above this many unknowns the step is solved on the sparse normal matrix (sparse
    /// Cholesky); at most this many, densely.
    pub sparse_above: usize,
}

impl Default for LmOptions {
    fn default() -> Self {
        LmOptions {
            tolerance: 1e-12,
            max_iterations: 200,
            initial_damping: 1e-3,
            max_unknowns: 3000,
            sparse_above: 400,
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
    let mut lambda = options.initial_damping;
    let (mut r, mut j) = problem.evaluate(&x);
    let mut cost: f64 = r.iter().map(|v| v * v).sum();
    let mut iterations = 0;
    let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
    let mut sparse = (n > options.sparse_above).then(SparseNormal::default);
    while iterations < options.max_iterations {
        if max_abs(&r) <= options.tolerance {
            break;
        }
        iterations += 1;
        let step = match sparse.as_mut() {
            Some(s) => s.step(n, &j, &r, lambda),
            None => dense_step(n, &j, &r, lambda),
        };
        let Some(step) = step else {
            lambda *= 10.0;
            if lambda > 1e12 {
                break;
            }
            continue;
        };
        let candidate: Vec<f64> = (0..n).map(|i| x[i] - step[i]).collect();
        let (r2, j2) = problem.evaluate(&candidate);
        let cost2: f64 = r2.iter().map(|v| v * v).sum();
        if cost2 < cost {
            x = candidate;
            r = r2;
            j = j2;
            cost = cost2;
            lambda = (lambda / 3.0).max(1e-12);
        } else {
            lambda *= 4.0;
            if lambda > 1e12 {
                break;
            }
        }
    }
    let max_residual = max_abs(&r);
    let converged = max_residual <= options.tolerance && finite(&x);
    Some(LmOutcome { x, converged, iterations, max_residual })
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

/// The damped Gauss–Newton step `(JᵀJ + λ·s·I)⁻¹ Jᵀr`, dense (faer's Cholesky); `None` when
/// the damped matrix is not numerically positive definite.
///
/// Levenberg's damping, `λ·s·I` at the scale `s` of JᵀJ's diagonal: the same in every
/// direction, so that as λ shrinks the step tends to the minimum-norm Gauss–Newton step (the
/// nearest point, for an underdetermined projection). Marquardt's `λ·diag(JᵀJ)` would tilt it
/// along directions the residuals do not see.
fn dense_step(n: usize, j: &[SparseRow<f64>], r: &[f64], lambda: f64) -> Option<Vec<f64>> {
    let mut h = Mat::<f64>::zeros(n, n);
    let g = normal_equations(n, j, r, |a, b, v| {
        h[(a, b)] += v;
        if a != b {
            h[(b, a)] += v;
        }
    });
    let scale = (0..n).map(|i| h[(i, i)]).fold(0.0, f64::max).max(1e-12);
    for i in 0..n {
        h[(i, i)] += lambda * scale;
    }
    let llt = h.llt(Side::Lower).ok()?;
    let step = llt.solve(&g);
    Some((0..n).map(|i| step[(i, 0)]).collect())
}

/// The same step on the sparse normal matrix (faer's supernodal sparse Cholesky, with its
/// fill-reducing ordering), the symbolic factorisation kept while the pattern of `J` stays
/// the same (it changes only when a gradient entry vanishes exactly).
#[derive(Default)]
struct SparseNormal {
    /// The lower triangle's pattern (column pointers, row indices) and its symbolic
    /// factorisation.
    symbolic: Option<(Vec<usize>, Vec<usize>, SymbolicLlt<usize>)>,
}

impl SparseNormal {
    fn step(&mut self, n: usize, j: &[SparseRow<f64>], r: &[f64], lambda: f64) -> Option<Vec<f64>> {
        // JᵀJ's lower triangle as (column, row, value), every diagonal entry present.
        let mut entries: Vec<(usize, usize, f64)> = (0..n).map(|i| (i, i, 0.0)).collect();
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
        let scale = (0..n).map(|c| values[col_ptr[c]]).fold(0.0, f64::max).max(1e-12);
        for c in 0..n {
            values[col_ptr[c]] += lambda * scale;
        }
        let same = matches!(&self.symbolic, Some((p, i, _)) if *p == col_ptr && *i == row_idx);
        if !same {
            let pattern =
                SymbolicSparseColMat::new_checked(n, n, col_ptr.clone(), None, row_idx.clone());
            let symbolic = SymbolicLlt::try_new(pattern.as_ref(), Side::Lower).ok()?;
            self.symbolic = Some((col_ptr.clone(), row_idx.clone(), symbolic));
        }
        let (_, _, symbolic) = self.symbolic.as_ref()?;
        let matrix = SparseColMat::new(
            SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx),
            values,
        );
        let llt =
            Llt::try_new_with_symbolic(symbolic.clone(), matrix.as_ref(), Side::Lower).ok()?;
        let step = llt.solve(&g);
        let step: Vec<f64> = (0..n).map(|i| step[(i, 0)]).collect();
        step.iter().all(|v| v.is_finite()).then_some(step)
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
}
