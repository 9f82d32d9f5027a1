//! The sketch in the layout's coordinates.

use gcs_model::{EntityIdx, System};
use gcs_rank::{BigRational, Field};

use crate::repr::Repr;

pub use crate::repr::line::{line2_through, line3_through};
pub use crate::repr::plane::plane_through;

/// An entity's sketch in the coordinates of its representation (`None` when its sketch
/// fields are missing, and for composite entities, which have no coordinates).
pub fn sketch_coords(system: &System, e: EntityIdx) -> Option<Vec<BigRational>> {
    let entity = system.entity(e);
    Repr::of(entity.kind(), system.dim())?.from_sketch(&entity.geometry)
}

/// The drawing as a configuration over the layout's columns, in any field: every entity's
/// sketch ([`sketch_coords`]); `None` when an entity with coordinates has no sketch position
/// (or a number is not in the field).
pub fn drawing_in<F: Field>(system: &System, layout: &crate::Layout) -> Option<Vec<F>> {
    let mut x = vec![F::zero(); layout.ncols()];
    for e in system.entity_indices() {
        if layout.repr(e).is_none() {
            continue;
        }
        for (col, v) in layout.columns(e).zip(sketch_coords_in::<F>(system, e)?) {
            x[col] = v;
        }
    }
    Some(x)
}

/// [`sketch_coords`] in any field.
pub fn sketch_coords_in<F: Field>(system: &System, e: EntityIdx) -> Option<Vec<F>> {
    sketch_coords(system, e)?.iter().map(|q| F::from_rational(q).ok()).collect()
}
