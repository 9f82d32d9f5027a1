//! Levenberg–Marquardt with Nielsen's damping update, straight at the system's values from
//! the drawing: what a problem of [`crate`] tries before its Newton homotopy.
//!
//! Why not `gcs_rank::levenberg_marquardt` (which the homotopy uses): its damping shrinks by a
//! fixed factor after a step that lowers `|r|²`, grows ×4 after one that does not, and the
//! homotopy caps it at 60 steps. A random Laman core of a thousand points drawn 5% off is
//! badly conditioned (measured at the drawing: the smallest singular value of the scaled
//! Jacobian 1.2e-8 against a largest of 3.4e-3) and needs about 70 steps from the drawing;
//! capped at 60 it stopped at 8e-10, and the homotopy's shorter steps then stalled at a fold
//! (BENCHMARKS.md, "Large Laman cores"). Here the damping follows the gain ratio `ρ` (actual
//! over predicted decrease of `|r|²`): `μ ← μ·max(1/3, 1 − (2ρ − 1)³)` after an accepted step,
//! `μ ← μ·ν, ν ← 2ν` after a rejected one (Madsen, Nielsen and Tingleff, *Methods for
//! non-linear least squares problems*, 2004, §3.2), and the run stops when `|r|²` has not
//! halved in [`STALL`] steps (a valley or a local minimum: the caller's homotopy takes over)
//! rather than after a fixed count.
//!
//! The step solves `(JᵀJ + μ·I) h = Jᵀr` by faer's supernodal sparse Cholesky (its
//! fill-reducing ordering; the symbolic factorisation kept while the pattern stays), with `μ`
//! at least 1e-14 of `JᵀJ`'s largest diagonal entry: Levenberg's isotropic damping keeps the
//! trivial motions of a free sketch out of the step (the step tends to the minimum-norm
//! Gauss–Newton step). Conjugate gradients on the normal equations preconditioned by their
//! diagonal were measured too and do not converge on these cores (their condition number is
//! the square of the Jacobian's); no iterative step is offered.
//!
//! Convergence is the residuals themselves within the tolerance: no rank is decided here.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use faer::{Mat, Side};
use gcs_rank::{Residuals, SparseRow};

/// Steps without `|r|²` halving after which the run gives up.
pub(crate) const STALL: usize = 20;

/// Options of [`levenberg_marquardt`].
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct NewtonOptions {
    /// Converged when every residual is at most this in absolute value.
    pub tolerance: f64,
    /// The most steps tried (accepted or not).
    pub max_iterations: usize,
    /// The first damping, relative to the largest diagonal entry of `JᵀJ`.
    pub initial_damping: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions { tolerance: 1e-12, max_iterations: 300, initial_damping: 1e-3 }
    }
}

/// What [`levenberg_marquardt`] found.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct NewtonOutcome {
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

fn norm2(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// Levenberg–Marquardt from `x0` with Nielsen's damping update (see the module
/// documentation).
pub(crate) fn levenberg_marquardt(
    problem: &impl Residuals,
    x0: &[f64],
    options: &NewtonOptions,
) -> NewtonOutcome {
    let n = problem.unknowns();
    let mut x = x0.to_vec();
    x.resize(n, 0.0);
    let (mut r, mut j) = problem.evaluate(&x);
    let mut cost = norm2(&r);
    let mut iterations = 0;
    let mut direct = Direct::default();
    // The damping μ (absolute, on JᵀJ's scale) and Nielsen's growth factor ν.
    let mut mu: Option<f64> = None;
    let mut nu = 2.0f64;
    // The cost STALL steps ago, to tell a stall.
    let mut history: std::collections::VecDeque<f64> = Default::default();
    while iterations < options.max_iterations && !(max_abs(&r) <= options.tolerance) {
        iterations += 1;
        history.push_back(cost);
        // NaN-safe: a cost that is not below half of it STALL steps ago is a stall.
        if history.len() > STALL && history.pop_front().is_some_and(|old| !(cost <= 0.5 * old)) {
            break;
        }
        let g = gradient(n, &j, &r);
        let top = diagonal(n, &j).into_iter().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
        let damping = mu.get_or_insert(options.initial_damping * top).max(1e-14 * top);
        let Some(h) = direct.step(n, &j, &g, damping).filter(|s| s.iter().all(|v| v.is_finite()))
        else {
            break;
        };
        // The decrease of |r|² the linear model predicts for the step x − h: hᵀ(μh + g).
        let predicted: f64 = h.iter().zip(&g).map(|(hi, gi)| hi * (damping * hi + gi)).sum();
        let candidate: Vec<f64> = (0..n).map(|i| x[i] - h[i]).collect();
        let (r2, j2) = problem.evaluate(&candidate);
        let cost2 = norm2(&r2);
        if cost2 < cost {
            let rho = (cost - cost2) / predicted.max(f64::MIN_POSITIVE);
            x = candidate;
            r = r2;
            j = j2;
            cost = cost2;
            mu = Some(damping * (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0));
            nu = 2.0;
        } else {
            mu = Some(damping * nu);
            nu *= 2.0;
            if damping > 1e10 * top {
                break;
            }
        }
    }
    let max_residual = max_abs(&r);
    let converged = max_residual <= options.tolerance && x.iter().all(|v| v.is_finite());
    NewtonOutcome { x, converged, iterations, max_residual }
}

/// `Jᵀr` over the first `n` columns.
fn gradient(n: usize, j: &[SparseRow<f64>], r: &[f64]) -> Vec<f64> {
    let mut g = vec![0.0; n];
    for (row, ri) in j.iter().zip(r) {
        for &(c, v) in row.entries() {
            if c < n {
                g[c] += v * ri;
            }
        }
    }
    g
}

/// The diagonal of `JᵀJ`.
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

/// The damped step `(JᵀJ + μ·I)⁻¹ g` by faer's supernodal sparse Cholesky, the symbolic
/// factorisation kept while the pattern stays (it changes only when a gradient entry vanishes
/// exactly).
#[derive(Default)]
struct Direct {
    symbolic: Option<(Vec<usize>, Vec<usize>, SymbolicLlt<usize>)>,
}

impl Direct {
    fn step(&mut self, n: usize, j: &[SparseRow<f64>], g: &[f64], mu: f64) -> Option<Vec<f64>> {
        let mut entries: Vec<(usize, usize, f64)> = (0..n).map(|i| (i, i, mu)).collect();
        for row in j {
            let e = row.entries();
            for (a, &(ca, va)) in e.iter().enumerate() {
                if ca >= n {
                    continue;
                }
                for &(cb, vb) in &e[a..] {
                    if cb < n {
                        entries.push((ca.min(cb), ca.max(cb), va * vb));
                    }
                }
            }
        }
        let mut rhs = Mat::<f64>::zeros(n, 1);
        for (i, v) in g.iter().enumerate() {
            rhs[(i, 0)] = *v;
        }
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
        let step = llt.solve(&rhs);
        Some((0..n).map(|i| step[(i, 0)]).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A free triangle of distances 3, 4, 5 (three trivial motions): the steps are orthogonal
    /// to the translations, so the solve keeps the start's centroid, and it converges.
    struct Triangle;

    impl Residuals for Triangle {
        fn unknowns(&self) -> usize {
            6
        }
        fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
            let mut out: (Vec<f64>, Vec<SparseRow<f64>>) = (Vec::new(), Vec::new());
            for (a, b, d) in [(0, 1, 3.0), (1, 2, 4.0), (0, 2, 5.0)] {
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

    #[test]
    fn free_triangle_keeps_its_centroid() {
        let start = [0.2, -0.1, 3.3, 0.2, 2.7, 4.4];
        let out = levenberg_marquardt(&Triangle, &start, &NewtonOptions::default());
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
        struct Flat;
        impl Residuals for Flat {
            fn unknowns(&self) -> usize {
                6
            }
            fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
                let mut out: (Vec<f64>, Vec<SparseRow<f64>>) = (Vec::new(), Vec::new());
                for (a, b, d) in [(0, 1, 1.0), (1, 2, 1.0), (0, 2, 3.0)] {
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
        let options = NewtonOptions { max_iterations: 10_000, ..NewtonOptions::default() };
        let out = levenberg_marquardt(&Flat, &[0.0, 0.0, 1.0, 0.3, 2.0, 0.1], &options);
        assert!(!out.converged);
        assert!(out.iterations < 1000, "{out:?}");
    }
}
