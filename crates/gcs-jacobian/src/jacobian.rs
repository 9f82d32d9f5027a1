//! Assembling the sparse Jacobian at a witness, in any field.

use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rank::{Field, SparseRow};

use crate::equations::{self, Local};
use crate::layout::Layout;
use crate::plan::{Plan, grad_row};

/// What a row of the Jacobian comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RowOwner {
    /// An entity-internal row (normalisation, Plücker relation).
    Internal(EntityIdx),
    /// A constraint's equation.
    Constraint(ConstraintIdx),
}

/// The Jacobian at a witness: entity-internal rows first (entity order), then each
/// constraint's rows in file order.
#[derive(Clone, Debug, PartialEq)]
pub struct Jacobian<F> {
    /// Number of unknowns.
    pub ncols: usize,
    /// The rows.
    pub rows: Vec<SparseRow<F>>,
    /// Where each row comes from.
    pub owners: Vec<RowOwner>,
}

impl<F: Field> Jacobian<F> {
    /// The rows of one constraint, as indices into `rows`.
    pub fn constraint_rows(&self, c: ConstraintIdx) -> Vec<usize> {
        (0..self.rows.len()).filter(|&i| self.owners[i] == RowOwner::Constraint(c)).collect()
    }

    /// Number of entity-internal rows (they come first).
    pub fn internal_count(&self) -> usize {
        self.owners.iter().take_while(|o| matches!(o, RowOwner::Internal(_))).count()
    }
}

/// Assembles the Jacobian of `system` at `witness` (one value per column of `layout`, in the
/// field `F`) following `plan`. `sketch` gives sketch coordinates in `F` for `Fix`.
pub fn assemble<F: Field>(
    system: &System,
    layout: &Layout,
    plan: &Plan,
    witness: &[F],
    sketch: &dyn Fn(EntityIdx) -> Option<Vec<F>>,
) -> Jacobian<F> {
    let mut rows = Vec::new();
    let mut owners = Vec::new();
    for e in system.entity_indices() {
        let Some(repr) = layout.repr(e) else { continue };
        if repr.internal_rows() == 0 {
            continue;
        }
        let local = Local::new(system, layout, &[e], witness);
        for r in equations::internal_rows(repr, local.coords(e)) {
            rows.push(grad_row(&r, Some(&local.cols)));
            owners.push(RowOwner::Internal(e));
        }
    }
    for (ci, cp) in system.constraint_indices().zip(&plan.constraints) {
        let c = system.constraint(ci);
        let base = system.constraint_base_entities(ci);
        let local = Local::new(system, layout, &base, witness);
        let cand = equations::candidates(system, c, cp.variant, &local, sketch);
        for &k in &cp.rows {
            if let Some(r) = cand.rows.get(k) {
                rows.push(grad_row(r, Some(&local.cols)));
                owners.push(RowOwner::Constraint(ci));
            }
        }
    }
    Jacobian { ncols: layout.ncols(), rows, owners }
}

/// The Jacobian row of a metric relation that is not a constraint of the system (a *virtual*
/// constraint, such as the boundary of a rigid subsystem: witness paper §3.2): `kind` is
/// `Distance` or `Angle`, `shape` the entities it binds, evaluated at `witness` (one value per
/// column, in `F`). `None` when the relation does not apply there (a distance between lines
/// that are not parallel, a kind that is not metric).
pub fn relation_row<F: Field>(
    system: &System,
    layout: &Layout,
    kind: gcs_model::ConstraintKind,
    shape: gcs_model::Shape,
    witness: &[F],
) -> Option<SparseRow<F>> {
    use gcs_model::{Constraint, ConstraintKind, Shape};
    if !matches!(kind, ConstraintKind::Distance | ConstraintKind::Angle) {
        return None;
    }
    let c = Constraint {
        id: String::new(),
        kind,
        args: shape.entities(),
        shape,
        value: None,
        doc: 1,
        position: None,
    };
    let mut base = Vec::new();
    for e in shape.entities() {
        for b in system.base_entities(e) {
            if !base.contains(&b) {
                base.push(b);
            }
        }
    }
    let local = Local::new(system, layout, &base, witness);
    let mut variant = 0;
    if kind == ConstraintKind::Distance
        && matches!(shape, Shape::LineLine(..) | Shape::PlanePlane(..))
    {
        let parallel = equations::parallel_at(system, shape, &local, &|x: &F| x.is_zero());
        if equations::variants(system, &c) == 2 {
            variant = usize::from(parallel);
        } else if !parallel {
            return None;
        }
    }
    let none = |_: EntityIdx| None;
    let cand = equations::candidates(system, &c, variant, &local, &none);
    cand.rows.first().map(|r| grad_row(r, Some(&local.cols)))
}
