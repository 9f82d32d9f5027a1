//! The closed vocabularies of the model: dimensions and constraint kinds (the entity kinds and
//! their DOF table are in [`crate::entity`], the DOC table in [`crate::signature`]).

use std::fmt;

pub use crate::entity::{EntityClass, EntityKind};

/// The dimension of the space a system lives in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dim {
    /// The plane.
    Two,
    /// Space.
    Three,
}

impl Dim {
    /// Builds a dimension from the number written in a model file (`2` or `3`).
    pub fn from_number(n: u64) -> Option<Dim> {
        match n {
            2 => Some(Dim::Two),
            3 => Some(Dim::Three),
            _ => None,
        }
    }

    /// The number of coordinates of a point: 2 or 3.
    pub fn coords(self) -> usize {
        match self {
            Dim::Two => 2,
            Dim::Three => 3,
        }
    }

    /// The dimension of the group of direct displacements (rotations and translations):
    /// 3 in the plane, 6 in space.
    pub fn displacements(self) -> usize {
        match self {
            Dim::Two => 3,
            Dim::Three => 6,
        }
    }
}

impl fmt::Display for Dim {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}D", self.coords())
    }
}

/// What a constraint is, beyond its geometry ([`ConstraintKind::role`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Role {
    /// A dimension: a measure with a value (distance, angle, radius).
    Metric,
    /// Not invariant under displacements: it ties the system to the page (`Fix`,
    /// `Horizontal`, `Vertical`).
    Absolute,
    /// A parameter-free relation invariant under displacements (incidence, parallelism…).
    Relation,
    /// A dimension that is not invariant under displacements: a horizontal or vertical
    /// distance (`DistanceX`, `DistanceY`).
    AbsoluteMetric,
}

/// The kind of a constraint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ConstraintKind {
    /// Two points at the same place.
    Coincident,
    /// A distance (point–point, point–line, point–plane, line–line, plane–plane).
    Distance,
    /// An angle between lines and planes, in degrees.
    Angle,
    /// Parallel lines or planes.
    Parallel,
    /// Perpendicular lines or planes.
    Perpendicular,
    /// A point on a line, plane, circle or sphere; a line in a plane.
    Incident,
    /// Tangency between a line and a circle, two circles, a plane and a sphere, two spheres.
    Tangent,
    /// Two circles with the same centre.
    Concentric,
    /// The radius of a circle or sphere.
    Radius,
    /// Two segments of equal length.
    EqualLength,
    /// A point at the middle of a segment.
    Midpoint,
    /// Two points symmetric about a line (2D).
    Symmetric,
    /// A horizontal line or segment (2D, absolute).
    Horizontal,
    /// A vertical line or segment (2D, absolute).
    Vertical,
    /// An entity pinned at its sketch position (absolute).
    Fix,
    /// Two circles or arcs of equal radius.
    EqualRadius,
    /// The horizontal distance between two points: the second's x minus the first's (2D,
    /// absolute).
    DistanceX,
    /// The vertical distance between two points: the second's y minus the first's (2D,
    /// absolute).
    DistanceY,
    /// Two curves tangent at a given point (a fillet's joint): their normals there are
    /// parallel. The point is put on both curves by other constraints.
    TangentAt,
    /// The length of the first segment over the length of the second.
    LengthRatio,
    /// The angle between the first two lines equals the angle between the last two (2D;
    /// undirected lines: the angle or its supplement).
    EqualAngle,
    /// The distance between the first two entities equals the distance between the last two;
    /// each pair is two points or a point and a line (2D).
    EqualDistance,
    /// A point of a B-spline at one of its knots: the curve's point at that parameter (its
    /// `value`), a fixed affine combination of the control points (an interpolation point of
    /// a spline drawn through points).
    SplinePoint,
}

impl ConstraintKind {
    /// Every constraint kind, in the order of the format's table.
    pub const ALL: [ConstraintKind; 23] = [
        ConstraintKind::Coincident,
        ConstraintKind::Distance,
        ConstraintKind::Angle,
        ConstraintKind::Parallel,
        ConstraintKind::Perpendicular,
        ConstraintKind::Incident,
        ConstraintKind::Tangent,
        ConstraintKind::Concentric,
        ConstraintKind::Radius,
        ConstraintKind::EqualLength,
        ConstraintKind::Midpoint,
        ConstraintKind::Symmetric,
        ConstraintKind::Horizontal,
        ConstraintKind::Vertical,
        ConstraintKind::Fix,
        ConstraintKind::EqualRadius,
        ConstraintKind::DistanceX,
        ConstraintKind::DistanceY,
        ConstraintKind::TangentAt,
        ConstraintKind::LengthRatio,
        ConstraintKind::EqualAngle,
        ConstraintKind::EqualDistance,
        ConstraintKind::SplinePoint,
    ];

    /// The variant names used in model files, in the order of [`ConstraintKind::ALL`].
    pub const NAMES: [&'static str; ConstraintKind::ALL.len()] = {
        let mut names = [""; ConstraintKind::ALL.len()];
        let mut i = 0;
        while i < names.len() {
            names[i] = ConstraintKind::ALL[i].name();
            i += 1;
        }
        names
    };

    /// The variant name used in model files.
    pub const fn name(self) -> &'static str {
        match self {
            ConstraintKind::Coincident => "Coincident",
            ConstraintKind::Distance => "Distance",
            ConstraintKind::Angle => "Angle",
            ConstraintKind::Parallel => "Parallel",
            ConstraintKind::Perpendicular => "Perpendicular",
            ConstraintKind::Incident => "Incident",
            ConstraintKind::Tangent => "Tangent",
            ConstraintKind::Concentric => "Concentric",
            ConstraintKind::Radius => "Radius",
            ConstraintKind::EqualLength => "EqualLength",
            ConstraintKind::Midpoint => "Midpoint",
            ConstraintKind::Symmetric => "Symmetric",
            ConstraintKind::Horizontal => "Horizontal",
            ConstraintKind::Vertical => "Vertical",
            ConstraintKind::Fix => "Fix",
            ConstraintKind::EqualRadius => "EqualRadius",
            ConstraintKind::DistanceX => "DistanceX",
            ConstraintKind::DistanceY => "DistanceY",
            ConstraintKind::TangentAt => "TangentAt",
            ConstraintKind::LengthRatio => "LengthRatio",
            ConstraintKind::EqualAngle => "EqualAngle",
            ConstraintKind::EqualDistance => "EqualDistance",
            ConstraintKind::SplinePoint => "SplinePoint",
        }
    }

    /// What the constraint is: a dimension, an absolute constraint or a relation.
    pub fn role(self) -> Role {
        use ConstraintKind as K;
        match self {
            K::Distance | K::Angle | K::Radius | K::LengthRatio => Role::Metric,
            K::Horizontal | K::Vertical | K::Fix => Role::Absolute,
            K::DistanceX | K::DistanceY => Role::AbsoluteMetric,
            K::Coincident
            | K::Parallel
            | K::Perpendicular
            | K::Incident
            | K::Tangent
            | K::Concentric
            | K::EqualLength
            | K::Midpoint
            | K::Symmetric
            | K::EqualRadius
            | K::TangentAt
            | K::EqualAngle
            | K::EqualDistance
            | K::SplinePoint => Role::Relation,
        }
    }

    /// Whether the constraint carries a metric value (a dimension in the CAD sense). Metric
    /// constraints need no special witness: their values are read off it.
    pub fn is_metric(self) -> bool {
        matches!(self.role(), Role::Metric | Role::AbsoluteMetric)
    }

    /// Whether the constraint is absolute: not invariant under displacements.
    pub fn is_absolute(self) -> bool {
        matches!(self.role(), Role::Absolute | Role::AbsoluteMetric)
    }

    /// Whether the constraint carries a number (`value`): a dimension's value for a metric
    /// kind, the curve parameter of a `SplinePoint` (a constant of the relation, not a
    /// dimension).
    pub fn has_value(self) -> bool {
        self.is_metric() || self == ConstraintKind::SplinePoint
    }

    /// The fields of the constraint's RON form (format §1), in order: `id`, the entity fields,
    /// and `value` for a kind that has one ([`ConstraintKind::has_value`]).
    pub fn ron_fields(self) -> &'static [&'static str] {
        use ConstraintKind as K;
        match self {
            K::Distance | K::Angle | K::DistanceX | K::DistanceY | K::LengthRatio => {
                &["id", "a", "b", "value"]
            }
            K::EqualAngle | K::EqualDistance => &["id", "a", "b", "c", "d"],
            K::TangentAt => &["id", "a", "b", "at"],
            K::Radius => &["id", "a", "value"],
            K::Horizontal | K::Vertical | K::Fix => &["id", "a"],
            K::Midpoint => &["id", "point", "segment"],
            K::SplinePoint => &["id", "point", "spline", "value"],
            K::Symmetric => &["id", "a", "b", "axis"],
            K::Coincident
            | K::Parallel
            | K::Perpendicular
            | K::Incident
            | K::Tangent
            | K::Concentric
            | K::EqualLength
            | K::EqualRadius => &["id", "a", "b"],
        }
    }

    /// Whether the constraint compares two pairs of entities (fields `a`, `b` and `c`, `d`): an
    /// entity may then be named in both pairs, though not twice in one.
    pub fn compares_pairs(self) -> bool {
        matches!(self, ConstraintKind::EqualAngle | ConstraintKind::EqualDistance)
    }

    /// The names of the entity fields the constraint takes, in order.
    pub fn fields(self) -> &'static [&'static str] {
        let all = self.ron_fields();
        &all[1..all.len() - usize::from(self.has_value())]
    }
}

impl fmt::Display for ConstraintKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entity_dof_table() {
        use EntityKind::*;
        let two: Vec<usize> = EntityKind::ALL.iter().map(|k| k.dof(Dim::Two)).collect();
        let three: Vec<usize> = EntityKind::ALL.iter().map(|k| k.dof(Dim::Three)).collect();
        assert_eq!(two, [2, 2, 0, 3, 0, 0, 3, 0]);
        assert_eq!(three, [3, 4, 0, 0, 3, 4, 0, 0]);
        assert!(BSpline.exists_in(Dim::Two) && BSpline.exists_in(Dim::Three));
        assert!(Circle.exists_in(Dim::Two) && !Circle.exists_in(Dim::Three));
        assert!(Plane.exists_in(Dim::Three) && !Plane.exists_in(Dim::Two));
    }

    #[test]
    fn names_are_unique() {
        let mut names: Vec<&str> = ConstraintKind::ALL.iter().map(|k| k.name()).collect();
        names.extend(EntityKind::ALL.iter().map(|k| k.name()));
        let n = names.len();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), n);
    }
}
