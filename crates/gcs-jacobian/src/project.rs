//! The last resort: a numerical projection onto the constraints (Levenberg–Marquardt from the
//! sketch), when no rational witness can be constructed. The result is only approximately a
//! witness; every report made at it says so, and only the float backend is honest there.

use gcs_model::{ConstraintIdx, EntityIdx, System};
use nalgebra::{DMatrix, DVector};

use crate::equations::{self, Local};
use crate::layout::{Layout, Repr};

/// Dense projections beyond this many unknowns are not attempted (they would take too long
/// and too much memory: the normal equations are dense).
pub(crate) const MAX_UNKNOWNS: usize = 3_000;

/// The residuals of every parameter-free constraint (and of the Plücker relations) at `x`, with
/// their gradients, as a dense system.
fn residuals(
    system: &System,
    layout: &Layout,
    x: &[f64],
    variants: &[usize],
    sketch: &dyn Fn(EntityIdx) -> Option<Vec<f64>>,
) -> (DVector<f64>, DMatrix<f64>) {
    let n = layout.ncols();
    let mut values: Vec<f64> = Vec::new();
    let mut rows: Vec<Vec<(usize, f64)>> = Vec::new();
    for ci in system.constraint_indices() {
        let c = system.constraint(ci);
        if c.kind.is_metric() {
            continue;
        }
        let base = system.constraint_base_entities(ci);
        let local = Local::new(system, layout, &base, x);
        let cand = equations::candidates(system, c, variants[ci.index()], &local, sketch);
        for r in cand.rows {
            values.push(r.value);
            rows.push(r.grad.iter().enumerate().map(|(i, g)| (local.cols[i], *g)).collect());
        }
    }
    for e in system.entity_indices() {
        if layout.repr(e) == Some(Repr::Line3) {
            let local = Local::new(system, layout, &[e], x);
            let rel = equations::internal_rows(Repr::Line3, local.coords(e));
            if let Some(r) = rel.first() {
                values.push(r.value);
                rows.push(r.grad.iter().enumerate().map(|(i, g)| (local.cols[i], *g)).collect());
            }
        }
    }
    let mut j = DMatrix::zeros(values.len(), n);
    for (i, row) in rows.iter().enumerate() {
        for &(c, g) in row {
            j[(i, c)] += g;
        }
    }
    (DVector::from_vec(values), j)
}

/// Projects `start` onto the parameter-free constraints by damped Gauss–Newton
/// (Levenberg–Marquardt): small steps from the sketch keep its shape. Returns the point when
/// the residuals fall below `1e-12` relative to the model's scale.
pub(crate) fn project(
    system: &System,
    layout: &Layout,
    start: &[f64],
    scale: f64,
) -> Option<Vec<f64>> {
    let n = layout.ncols();
    if n > MAX_UNKNOWNS {
        return None;
    }
    // Tangency branches from the starting point.
    let none = |_: EntityIdx| None;
    let variants: Vec<usize> = system
        .constraint_indices()
        .map(|ci: ConstraintIdx| {
            let c = system.constraint(ci);
            let base = system.constraint_base_entities(ci);
            let local = Local::new(system, layout, &base, start);
            (0..equations::variants(system, c))
                .map(|v| {
                    let cand = equations::candidates(system, c, v, &local, &none);
                    (cand.rows.iter().map(|r| r.value.abs()).sum::<f64>(), v)
                })
                .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a })
                .1
        })
        .collect();
    let sketch = |e: EntityIdx| crate::sketch::sketch_coords_in::<f64>(system, e);
    let tol = 1e-12 * scale.max(1.0).powi(2);
    let mut x = DVector::from_column_slice(start);
    let mut lambda = 1e-3;
    let (mut r, mut j) = residuals(system, layout, x.as_slice(), &variants, &sketch);
    let mut cost = r.norm_squared();
    for _ in 0..200 {
        if r.amax() <= tol {
            return x.iter().all(|v| v.is_finite()).then(|| x.as_slice().to_vec());
        }
        let jt = j.transpose();
        let g = &jt * &r;
        let mut h = &jt * &j;
        let diag: Vec<f64> = (0..n).map(|i| h[(i, i)]).collect();
        for (i, d) in diag.iter().enumerate() {
            h[(i, i)] += lambda * d.max(1e-12);
        }
        let Some(chol) = h.cholesky() else {
            lambda *= 10.0;
            continue;
        };
        let step = chol.solve(&(-g));
        let candidate = &x + &step;
        let (r2, j2) = residuals(system, layout, candidate.as_slice(), &variants, &sketch);
        let cost2 = r2.norm_squared();
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
    (r.amax() <= tol && x.iter().all(|v| v.is_finite())).then(|| x.as_slice().to_vec())
}
