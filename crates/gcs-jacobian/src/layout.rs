//! The unknowns: how each entity is represented by coordinates (the columns of the Jacobian).
//!
//! | entity | coordinates | internal rows | DOF |
//! |---|---|---|---|
//! | 2D point | `x, y` | – | 2 |
//! | 3D point | `x, y, z` | – | 3 |
//! | 2D line | homogeneous `a, b, c` (`a·x + b·y + c = 0`) | normalisation | 2 |
//! | 3D line | Plücker `d, m` (direction, moment `m = p × d`) | Plücker relation `d·m = 0`, normalisation | 4 |
//! | circle | `cx, cy, r` | – | 3 |
//! | plane | homogeneous `a, b, c, d` (`a·x + b·y + c·z + d = 0`) | normalisation | 3 |
//! | sphere | `cx, cy, cz, r` | – | 4 |
//! | segment | none: the line through its two points | – | 0 |
//!
//! Homogeneous coordinates keep everything rational (a line through two rational points, a
//! plane through a rational point with a rational normal) where a unit normal would need a
//! square root. Their scale is a gauge freedom, removed by one linear normalisation row per
//! entity whose gradient is the witness coordinates themselves (`x0 · x = |x0|²`, satisfied by
//! the witness, transversal to the scaling direction `x0` since `x0 · x0 > 0`). Every equation
//! is homogeneous in a homogeneous entity's coordinates, so the scaling direction is in the
//! kernel of every constraint row at a solution and the normalisation row removes exactly it:
//! the kernel of the Jacobian is then exactly the real infinitesimal motions.

use std::ops::Range;

use gcs_model::{Dim, EntityIdx, EntityKind, System};

/// How an entity is represented.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Repr {
    /// `x, y`.
    Point2,
    /// `x, y, z`.
    Point3,
    /// Homogeneous `a, b, c`.
    Line2,
    /// Plücker `d, m`.
    Line3,
    /// `cx, cy, r`.
    Circle,
    /// Homogeneous `a, b, c, d`.
    Plane,
    /// `cx, cy, cz, r`.
    Sphere,
}

impl Repr {
    /// The representation of an entity kind in a dimension; `None` for segments.
    pub fn of(kind: EntityKind, dim: Dim) -> Option<Repr> {
        match (kind, dim) {
            (EntityKind::Point, Dim::Two) => Some(Repr::Point2),
            (EntityKind::Point, Dim::Three) => Some(Repr::Point3),
            (EntityKind::Line, Dim::Two) => Some(Repr::Line2),
            (EntityKind::Line, Dim::Three) => Some(Repr::Line3),
            (EntityKind::Circle, _) => Some(Repr::Circle),
            (EntityKind::Plane, _) => Some(Repr::Plane),
            (EntityKind::Sphere, _) => Some(Repr::Sphere),
            (EntityKind::Segment, _) => None,
        }
    }

    /// Number of coordinates (columns).
    pub fn coords(self) -> usize {
        match self {
            Repr::Point2 => 2,
            Repr::Point3 | Repr::Line2 | Repr::Circle => 3,
            Repr::Plane | Repr::Sphere => 4,
            Repr::Line3 => 6,
        }
    }

    /// Number of entity-internal rows (normalisation, Plücker relation).
    pub fn internal_rows(self) -> usize {
        match self {
            Repr::Line2 | Repr::Plane => 1,
            Repr::Line3 => 2,
            _ => 0,
        }
    }

    /// Whether the coordinates are homogeneous (defined up to a nonzero factor).
    pub fn homogeneous(self) -> bool {
        matches!(self, Repr::Line2 | Repr::Line3 | Repr::Plane)
    }

    /// Degrees of freedom: coordinates minus internal rows.
    pub fn dof(self) -> usize {
        self.coords() - self.internal_rows()
    }
}

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
