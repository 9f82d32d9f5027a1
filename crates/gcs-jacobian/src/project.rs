//! The last resort: a numerical projection onto the constraints (Levenberg–Marquardt from the
//! sketch, [`gcs_rank::levenberg_marquardt`]), when no rational witness can be constructed.
//! The result is only approximately a witness; every report made at it says so, and only the
//! float backend is honest there.

use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rank::{LmOptions, Residuals, SparseRow, levenberg_marquardt};

use crate::laws;
use crate::layout::Layout;
use crate::views::Local;

/// Dense projections beyond this many unknowns are not attempted (they would take too long
/// and too much memory: the normal equations are dense).
pub(crate) const MAX_UNKNOWNS: usize = 3_000;

/// The residuals of every parameter-free constraint, and the internal relations (the Plücker
/// relations) but not the normalisations: the projection moves homogeneous coordinates freely.
struct ParameterFree<'s> {
    system: &'s System,
    layout: &'s Layout,
    variants: Vec<usize>,
    /// The model's size (at least 1).
    scale: f64,
}

impl Residuals for ParameterFree<'_> {
    fn unknowns(&self) -> usize {
        self.layout.ncols()
    }

    fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
        let (system, layout) = (self.system, self.layout);
        let sketch = |e: EntityIdx| crate::sketch::sketch_coords_in::<f64>(system, e);
        let mut values = Vec::new();
        let mut rows = Vec::new();
        // Each residual over the size to its degree beyond 2 (the tolerance's).
        let mut push = |r: &crate::dual::Dual<f64>, cols: &[usize], unit: f64| {
            values.push(r.value / unit);
            rows.push(SparseRow::from_entries(
                r.grad.iter().enumerate().map(|(i, g)| (cols[i], *g / unit)).collect(),
            ));
        };
        for ci in system.constraint_indices() {
            let c = system.constraint(ci);
            if c.kind.is_metric() {
                continue;
            }
            let base = system.constraint_base_entities(ci);
            let local = Local::new(system, layout, &base, x);
            let law = laws::law(c.signature, self.variants[ci.index()], &local, &sketch, false);
            let unit = self.scale.powi(laws::residual_degree(c.signature) - 2);
            for r in &law.rows {
                push(r, &local.cols, unit);
            }
        }
        for e in system.entity_indices() {
            let Some(repr) = layout.repr(e) else { continue };
            if repr.internal_rows() > usize::from(repr.homogeneous()) {
                let local = Local::new(system, layout, &[e], x);
                if let Some(r) = repr.internal_equations(local.coords(e)).first() {
                    push(r, &local.cols, 1.0);
                }
            }
        }
        (values, rows)
    }
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
    let variants = variants_at(system, layout, start);
    let options = LmOptions {
        tolerance: 1e-12 * scale.max(1.0).powi(2),
        max_unknowns: MAX_UNKNOWNS,
        ..LmOptions::default()
    };
    let outcome = levenberg_marquardt(
        &ParameterFree { system, layout, variants, scale: scale.max(1.0) },
        start,
        &options,
    )?;
    outcome.converged.then_some(outcome.x)
}

/// Each constraint's variant (branch: internal or external tangency…) whose equations are
/// nearest to holding at `x`: the branch the drawing shows.
pub(crate) fn variants_at(system: &System, layout: &Layout, x: &[f64]) -> Vec<usize> {
    let none = |_: EntityIdx| None;
    system
        .constraint_indices()
        .map(|ci: ConstraintIdx| {
            let c = system.constraint(ci);
            let base = system.constraint_base_entities(ci);
            let local = Local::new(system, layout, &base, x);
            (0..laws::law(c.signature, 0, &local, &none, false).variants)
                .map(|v| {
                    let law = laws::law(c.signature, v, &local, &none, false);
                    (law.rows.iter().map(|r| r.value.abs()).sum::<f64>(), v)
                })
                .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a })
                .1
        })
        .collect()
}
