//! Planning at the exact witness: which branch of each constraint holds (internal or external
//! tangency, parallel or skew lines), and which of its candidate equations to keep so that it
//! contributes exactly DOC rows independent at the witness.
//!
//! The plan is made once, over ℚ, and then the Jacobian is assembled in any field following
//! it: every backend sees the same equations, which is what lets a modular rank be certified
//! against the rational rows.

use gcs_model::{ConstraintIdx, System};
use gcs_rank::{Echelon, EchelonOptions, Field, SparseRow};

use crate::dual::Dual;
use crate::error::JacobianError;
use crate::laws;
use crate::layout::Layout;
use crate::views::Local;

/// The branch and the kept equations of one constraint.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConstraintPlan {
    /// The variant of its equations that holds at the witness.
    pub variant: usize,
    /// Indices of the candidate equations kept (DOC of them).
    pub rows: Vec<usize>,
    /// Whether the kept rows are independent at the witness (false: the constraint is
    /// singular there, e.g. a distance between coincident points).
    pub regular: bool,
}

/// A plan for every constraint, in file order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    /// One entry per constraint.
    pub constraints: Vec<ConstraintPlan>,
}

/// Why a configuration is not a witness of a system.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Unsatisfied {
    /// A parameter-free constraint does not hold.
    Constraint(ConstraintIdx),
    /// A distance between lines or planes that are not parallel.
    NotParallel(ConstraintIdx),
}

pub(crate) fn grad_row<F: Field>(d: &Dual<F>, cols: Option<&[usize]>) -> SparseRow<F> {
    let entries = d
        .grad
        .iter()
        .enumerate()
        .filter(|(_, g)| !g.is_zero())
        .map(|(i, g)| (cols.map_or(i, |c| c[i]), g.clone()))
        .collect();
    SparseRow::from_entries(entries)
}

/// Whether a configuration satisfies the parameter-free constraints of a system exactly, and
/// the plan if it does.
pub fn plan<F: Field>(
    system: &System,
    layout: &Layout,
    witness: &[F],
    sketch: &dyn Fn(gcs_model::EntityIdx) -> Option<Vec<F>>,
) -> Result<Result<Plan, Unsatisfied>, JacobianError> {
    plan_with(system, layout, witness, sketch, &|_, x: &F| x.is_zero(), EchelonOptions::default())
}

/// [`plan`] with a zero test (of a constraint's residual) and echelon options of one's own: for
/// an approximate witness, residuals below a tolerance count as zero and the row selection uses
/// a tolerance.
pub(crate) fn plan_with<F: Field>(
    system: &System,
    layout: &Layout,
    witness: &[F],
    sketch: &dyn Fn(gcs_model::EntityIdx) -> Option<Vec<F>>,
    zero: &dyn Fn(ConstraintIdx, &F) -> bool,
    options: EchelonOptions,
) -> Result<Result<Plan, Unsatisfied>, JacobianError> {
    let mut out = Vec::with_capacity(system.constraints().len());
    for ci in system.constraint_indices() {
        let c = system.constraint(ci);
        let base = system.constraint_base_entities(ci);
        let local = Local::new(system, layout, &base, witness);
        // Metric distances between lines or planes need them parallel (2D lines, planes) or
        // choose their formula (3D lines).
        let first = laws::law(c.signature, 0, &local, sketch, false);
        let zero = |x: &F| zero(ci, x);
        let variant = match first.parallel(&zero) {
            Some(parallel) if first.variants == 2 => usize::from(parallel),
            Some(false) => return Ok(Err(Unsatisfied::NotParallel(ci))),
            Some(true) => 0,
            None => {
                let holds =
                    |law: &laws::Law<F>| law.metric || law.rows.iter().all(|r| zero(&r.value));
                let found = if holds(&first) {
                    Some(0)
                } else {
                    (1..first.variants)
                        .find(|&v| holds(&laws::law(c.signature, v, &local, sketch, false)))
                };
                match found {
                    Some(v) => v,
                    None => return Ok(Err(Unsatisfied::Constraint(ci))),
                }
            }
        };
        let cand = if variant == 0 {
            first
        } else {
            laws::law(c.signature, variant, &local, sketch, false)
        };
        out.push(select(layout, &base, &local, &cand.rows, c.doc, options.clone()));
        out.last_mut().expect("just pushed").variant = variant;
    }
    Ok(Ok(Plan { constraints: out }))
}

/// A plan at any configuration, satisfied or not (a drawing whose dimensions were edited, a
/// sketch exported in floating point): each constraint in the branch whose residuals are
/// smallest there (for a distance between 3D lines, the parallel formula exactly when they are
/// parallel), with `doc` candidate rows independent there. With it, the Jacobian at the
/// configuration ([`crate::Witness`] with these coordinates) is the one a user's drawing has.
pub fn plan_anywhere<F: Field>(
    system: &System,
    layout: &Layout,
    x: &[F],
    sketch: &dyn Fn(gcs_model::EntityIdx) -> Option<Vec<F>>,
) -> Plan {
    let mut out = Vec::with_capacity(system.constraints().len());
    for ci in system.constraint_indices() {
        let c = system.constraint(ci);
        let base = system.constraint_base_entities(ci);
        let local = Local::new(system, layout, &base, x);
        let first = laws::law(c.signature, 0, &local, sketch, false);
        let variant = match first.parallel(&|v: &F| v.is_zero()) {
            Some(parallel) if first.variants == 2 => usize::from(parallel),
            Some(_) => 0,
            None => {
                let size = |law: &laws::Law<F>| -> f64 {
                    law.rows.iter().map(|r| r.value.magnitude()).sum()
                };
                let mut best = (size(&first), 0);
                for v in 1..first.variants {
                    let s = size(&laws::law(c.signature, v, &local, sketch, false));
                    if s < best.0 {
                        best = (s, v);
                    }
                }
                best.1
            }
        };
        let cand = if variant == 0 {
            first
        } else {
            laws::law(c.signature, variant, &local, sketch, false)
        };
        let mut cp = select(layout, &base, &local, &cand.rows, c.doc, EchelonOptions::default());
        cp.variant = variant;
        out.push(cp);
    }
    Plan { constraints: out }
}

/// Keeps `doc` candidate rows independent at the witness, modulo the internal rows of the
/// entities involved; when there are not enough, fills up with the first dependent ones and
/// marks the constraint singular.
fn select<F: Field>(
    layout: &Layout,
    base: &[gcs_model::EntityIdx],
    local: &Local<'_, F>,
    rows: &[Dual<F>],
    doc: usize,
    options: EchelonOptions,
) -> ConstraintPlan {
    if rows.len() == doc {
        // Nothing to choose: the rows are the constraint's equations.
        return ConstraintPlan { variant: 0, rows: (0..doc).collect(), regular: true };
    }
    let n = local.nvars();
    let mut ech = Echelon::new(n, options);
    // Internal rows of the local entities, over local variables.
    for &e in base {
        if let Some(repr) = layout.repr(e) {
            for r in repr.internal_equations(local.coords(e)) {
                ech.insert(grad_row(&r, None));
            }
        }
    }
    let mut kept = Vec::new();
    let mut dependent = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        if kept.len() == doc {
            break;
        }
        if ech.insert(grad_row(r, None)).is_independent() {
            kept.push(i);
        } else {
            dependent.push(i);
        }
    }
    let regular = kept.len() == doc;
    for i in dependent {
        if kept.len() >= doc {
            break;
        }
        kept.push(i);
    }
    kept.sort_unstable();
    ConstraintPlan { variant: 0, rows: kept, regular }
}
