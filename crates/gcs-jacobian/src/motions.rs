//! Trivial motions: the velocities of every entity's coordinates under the infinitesimal
//! displacements (2D: two translations and a rotation; 3D: three and three), tangent to the
//! entity's normalisation.
//!
//! The trivial motions a system admits are `span(T) ∩ ker J`, of dimension
//! `rank(T) − rank(J·T)`; the internal degrees of freedom are `dim ker J` minus that.

use gcs_model::{Dim, System};
use gcs_rank::Field;

use crate::error::JacobianError;
use crate::layout::Layout;

/// The generators of the displacements as dense vectors over the columns of `layout`, at
/// `witness`: 3 in 2D (x, y translations; rotation about the origin), 6 in 3D (x, y, z
/// translations; rotations about the axes).
///
/// # Errors
/// When a homogeneous entity's coordinates have zero norm in the field (impossible over ℚ,
/// negligibly likely modulo a large prime).
pub fn generators<F: Field>(
    system: &System,
    layout: &Layout,
    witness: &[F],
) -> Result<Vec<Vec<F>>, JacobianError> {
    let k = system.dim().displacements();
    let mut t = vec![vec![F::zero(); layout.ncols()]; k];
    for e in system.entity_indices() {
        let Some(repr) = layout.repr(e) else { continue };
        let cols = layout.columns(e);
        let x = &witness[cols.clone()];
        for (g, column) in t.iter_mut().enumerate() {
            let vel = repr
                .velocity(x, g)
                .ok_or_else(|| JacobianError::ZeroNorm { entity: system.entity(e).id.clone() })?;
            for (c, v) in cols.clone().zip(vel) {
                column[c] = v;
            }
        }
    }
    debug_assert!(system.dim() == Dim::Two || k == 6);
    Ok(t)
}
