//! Nonlinear least squares: damped Gauss–Newton (Levenberg–Marquardt) on any system of
//! residuals, geometry-free. Below the witness projection of `gcs-jacobian` and, later, the
//! solver: the problem gives residuals and their gradient rows at a point; the kernel takes
//! damped Gauss–Newton steps `(JᵀJ + λ·s·I) δ = −Jᵀr` (`s` the largest diagonal entry of
//! `JᵀJ`), solved densely by Cholesky (faer), shrinking `λ` after a step that lowers `|r|²` and
//! growing it otherwise.
//!
//! Dense: `O(n²)` memory and `O(n³)` time per step for `n` unknowns; problems beyond
//! [`LmOptions::max_unknowns`] are refused rather than attempted.

use faer::linalg::solvers::Solve;
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
    /// Problems with more unknowns are not attempted (the step is dense).
    pub max_unknowns: usize,
}

impl Default for LmOptions {
    fn default() -> Self {
        LmOptions {
            tolerance: 1e-12,
            max_iterations: 200,
            initial_damping: 1e-3,
            max_unknowns: 3000,
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
    while iterations < options.max_iterations {
        if max_abs(&r) <= options.tolerance {
            break;
        }
        iterations += 1;
        // JᵀJ and Jᵀr, dense.
        let mut h = Mat::<f64>::zeros(n, n);
        let mut g = Mat::<f64>::zeros(n, 1);
        for (row, ri) in j.iter().zip(&r) {
            let e = row.entries();
            for (a, (ca, va)) in e.iter().enumerate() {
                if *ca >= n {
                    continue;
                }
                g[(*ca, 0)] += va * ri;
                for (cb, vb) in &e[a..] {
                    if *cb < n {
                        h[(*ca, *cb)] += va * vb;
                    }
                }
            }
        }
        for a in 0..n {
            for b in 0..a {
                h[(a, b)] = h[(b, a)];
            }
        }
        // Levenberg's damping, `λ·s·I` at the scale `s` of JᵀJ's diagonal: the same in every
        // direction, so that as λ shrinks the step tends to the minimum-norm Gauss–Newton step
        // (the nearest point, for an underdetermined projection). Marquardt's `λ·diag(JᵀJ)`
        // would tilt it along directions the residuals do not see.
        let scale = (0..n).map(|i| h[(i, i)]).fold(0.0, f64::max).max(1e-12);
        for i in 0..n {
            h[(i, i)] += lambda * scale;
        }
        let Ok(llt) = h.llt(Side::Lower) else {
            lambda *= 10.0;
            if lambda > 1e12 {
                break;
            }
            continue;
        };
        let step = llt.solve(&g);
        let candidate: Vec<f64> = (0..n).map(|i| x[i] - step[(i, 0)]).collect();
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
        let too_big = LmOptions { max_unknowns: 1, ..o };
        assert!(levenberg_marquardt(&ok, &[0.0, 0.0], &too_big).is_none());
    }
}
