//! Assembling the sparse Jacobian at a witness, in any field.

use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rank::{Field, SparseRow};

use crate::laws;
use crate::layout::Layout;
use crate::plan::{Plan, grad_row};
use crate::views::Local;

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
        for r in repr.internal_equations(local.coords(e)) {
            rows.push(grad_row(&r, Some(&local.cols)));
            owners.push(RowOwner::Internal(e));
        }
    }
    for (ci, cp) in system.constraint_indices().zip(&plan.constraints) {
        let c = system.constraint(ci);
        let base = system.constraint_base_entities(ci);
        let local = Local::new(system, layout, &base, witness);
        let law = laws::law(c.signature, cp.variant, &local, sketch, false);
        for &k in &cp.rows {
            if let Some(r) = law.rows.get(k) {
                rows.push(grad_row(r, Some(&local.cols)));
                owners.push(RowOwner::Constraint(ci));
            }
        }
    }
    Jacobian { ncols: layout.ncols(), rows, owners }
}

/// The Jacobian row of a metric relation that is not a constraint of the system (a *virtual*
/// constraint, such as the boundary of a rigid subsystem: witness paper §3.2): `signature` is
/// a distance or an angle between entities of the system ([`System::relation`]), evaluated at
/// `witness` (one value per column, in `F`). `None` when the relation does not apply there (a
/// distance between lines that are not parallel, a relation that is not metric).
///
/// [`System::relation`]: gcs_model::System::relation
pub fn relation_row<F: Field>(
    system: &System,
    layout: &Layout,
    signature: gcs_model::Signature,
    witness: &[F],
) -> Option<SparseRow<F>> {
    if !signature.is_metric() {
        return None;
    }
    let mut base = Vec::new();
    for e in signature.entities() {
        for b in system.base_entities(e) {
            if !base.contains(&b) {
                base.push(b);
            }
        }
    }
    let local = Local::new(system, layout, &base, witness);
    let variants = |v| laws::law(signature, v, &local, &|_| None, false);
    let first = variants(0);
    let variant = match first.parallel(&|x: &F| x.is_zero()) {
        Some(parallel) if first.variants == 2 => usize::from(parallel),
        Some(false) => return None,
        Some(true) | None => 0,
    };
    let law = if variant == 0 { first } else { variants(variant) };
    law.rows.first().map(|r| grad_row(r, Some(&local.cols)))
}
