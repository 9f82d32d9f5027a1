//! The unknowns: the columns of the Jacobian, entity by entity ([`crate::repr`] says how
//! each kind is represented).

use std::ops::Range;

use gcs_model::{Dim, EntityIdx, System};

use crate::repr::Repr;

/// The columns of the Jacobian: each entity with degrees of freedom owns a contiguous range,
/// in entity order.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    dim: Dim,
    repr: Vec<Option<Repr>>,
    offset: Vec<usize>,
    ncols: usize,
    /// Column → entity.
    owner: Vec<EntityIdx>,
}

impl Layout {
    /// The layout of a system.
    pub fn new(system: &System) -> Layout {
        let dim = system.dim();
        let mut repr = Vec::with_capacity(system.entities().len());
        let mut offset = Vec::with_capacity(system.entities().len());
        let mut owner = Vec::new();
        let mut ncols = 0;
        for (i, e) in system.entities().iter().enumerate() {
            let r = Repr::of(e.kind(), dim);
            offset.push(ncols);
            if let Some(r) = r {
                ncols += r.coords();
                owner.extend(std::iter::repeat_n(EntityIdx(i as u32), r.coords()));
            }
            repr.push(r);
        }
        Layout { dim, repr, offset, ncols, owner }
    }

    /// The dimension.
    pub fn dim(&self) -> Dim {
        self.dim
    }

    /// Total number of unknowns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// The representation of an entity (`None` for a segment).
    pub fn repr(&self, e: EntityIdx) -> Option<Repr> {
        self.repr[e.index()]
    }

    /// The columns of an entity (empty for a segment).
    pub fn columns(&self, e: EntityIdx) -> Range<usize> {
        let start = self.offset[e.index()];
        start..start + self.repr[e.index()].map_or(0, Repr::coords)
    }

    /// The entity owning a column.
    pub fn owner(&self, col: usize) -> EntityIdx {
        self.owner[col]
    }

    /// Total number of entity-internal rows.
    pub fn internal_rows(&self) -> usize {
        self.repr.iter().flatten().map(|r| r.internal_rows()).sum()
    }
}
