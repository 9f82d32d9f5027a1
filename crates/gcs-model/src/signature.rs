//! The constraint table of the format: which entity classes each constraint kind takes, in which
//! dimension, and how many degrees of freedom it removes (DOC) — one row per [`Signature`].
//!
//! A [`Signature`] is a constraint kind resolved against the classes of the entities it binds
//! (argument order in the file does not matter where the roles differ: `Distance(a: line, b:
//! point)` is `Signature::Metric(Metric::DistancePointLine { .. })`). Every layer that attaches something to a
//! constraint — its equations, its rule in the structural methods — matches on it, without a
//! catch-all arm, so that adding a row here makes the compiler list every place that must learn
//! about it.

use crate::kinds::{ConstraintKind, Dim, EntityClass, EntityKind};
use crate::system::EntityIdx;

/// The metric rows of the constraint table ([`Signature::metric`]): what a measure is taken
/// of, with the entities in their roles.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Metric {
    /// The distance between two points.
    DistancePointPoint(EntityIdx, EntityIdx),
    /// The distance from a point to a line.
    DistancePointLine {
        /// The point.
        point: EntityIdx,
        /// The line.
        line: EntityIdx,
    },
    /// The distance from a point to a plane.
    DistancePointPlane {
        /// The point.
        point: EntityIdx,
        /// The plane.
        plane: EntityIdx,
    },
    /// The distance between two lines.
    DistanceLineLine(EntityIdx, EntityIdx),
    /// The distance between two parallel planes.
    DistancePlanePlane(EntityIdx, EntityIdx),
    /// The angle between two lines.
    AngleLineLine(EntityIdx, EntityIdx),
    /// The angle between two planes.
    AnglePlanePlane(EntityIdx, EntityIdx),
    /// The angle between a line and a plane.
    AngleLinePlane {
        /// The line.
        line: EntityIdx,
        /// The plane.
        plane: EntityIdx,
    },
    /// The radius of a circle or sphere.
    Radius(EntityIdx),
    /// The horizontal distance from the first point to the second (signed, absolute).
    DistanceX(EntityIdx, EntityIdx),
    /// The vertical distance from the first point to the second (signed, absolute).
    DistanceY(EntityIdx, EntityIdx),
    /// The length of the first segment over the length of the second.
    LengthRatio(EntityIdx, EntityIdx),
    /// The distance between two concentric circles: the difference of their radii (2D).
    DistanceCircleCircle(EntityIdx, EntityIdx),
}

impl Metric {
    /// The constraint kind: `Distance`, `Angle` or `Radius`.
    pub fn kind(self) -> ConstraintKind {
        use Metric as M;
        match self {
            M::DistancePointPoint(..)
            | M::DistancePointLine { .. }
            | M::DistancePointPlane { .. }
            | M::DistanceLineLine(..)
            | M::DistancePlanePlane(..)
            | M::DistanceCircleCircle(..) => ConstraintKind::Distance,
            M::AngleLineLine(..) | M::AnglePlanePlane(..) | M::AngleLinePlane { .. } => {
                ConstraintKind::Angle
            }
            M::Radius(_) => ConstraintKind::Radius,
            M::DistanceX(..) => ConstraintKind::DistanceX,
            M::DistanceY(..) => ConstraintKind::DistanceY,
            M::LengthRatio(..) => ConstraintKind::LengthRatio,
        }
    }

    /// The entities measured, in role order.
    pub fn entities(self) -> Vec<EntityIdx> {
        use Metric as M;
        match self {
            M::DistancePointPoint(a, b)
            | M::DistanceLineLine(a, b)
            | M::DistancePlanePlane(a, b)
            | M::AngleLineLine(a, b)
            | M::AnglePlanePlane(a, b)
            | M::DistanceX(a, b)
            | M::DistanceY(a, b)
            | M::LengthRatio(a, b)
            | M::DistanceCircleCircle(a, b) => vec![a, b],
            M::DistancePointLine { point, line: other }
            | M::DistancePointPlane { point, plane: other } => vec![point, other],
            M::AngleLinePlane { line, plane } => vec![line, plane],
            M::Radius(e) => vec![e],
        }
    }
}

/// One side of an [`Signature::EqualDistance`]: the distance it measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Gap {
    /// Between two points.
    PointPoint(EntityIdx, EntityIdx),
    /// From a point to a line or segment (its carrier).
    PointLine {
        /// The point.
        point: EntityIdx,
        /// The line.
        line: EntityIdx,
    },
    /// Between two circles or arcs: the difference of their radii (their gap when they are
    /// concentric, as an offset's are).
    CircleCircle(EntityIdx, EntityIdx),
}

impl Gap {
    /// The entities, in the order the constraint names them.
    pub fn entities(self) -> [EntityIdx; 2] {
        match self {
            Gap::PointPoint(a, b) | Gap::CircleCircle(a, b) => [a, b],
            Gap::PointLine { point, line } => [point, line],
        }
    }
}

/// A constraint kind resolved against the classes of its entities: one variant per row of the
/// constraint table (format §1), with the entities in their roles. "Line" roles take lines and
/// segments alike, "circle" roles every circle-like entity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Signature {
    /// A dimension: a distance, an angle or a radius ([`Metric`]).
    Metric(Metric),
    /// Two points at the same place (DOC: the dimension).
    CoincidentPoints(EntityIdx, EntityIdx),
    /// Two parallel lines (DOC 1 in 2D, 2 in 3D).
    ParallelLineLine(EntityIdx, EntityIdx),
    /// Two parallel planes (DOC 2).
    ParallelPlanePlane(EntityIdx, EntityIdx),
    /// A line parallel to a plane.
    ParallelLinePlane {
        /// The line.
        line: EntityIdx,
        /// The plane.
        plane: EntityIdx,
    },
    /// Two perpendicular lines.
    PerpendicularLineLine(EntityIdx, EntityIdx),
    /// Two perpendicular planes.
    PerpendicularPlanePlane(EntityIdx, EntityIdx),
    /// A line perpendicular to a plane (DOC 2).
    PerpendicularLinePlane {
        /// The line.
        line: EntityIdx,
        /// The plane.
        plane: EntityIdx,
    },
    /// A point on a line (DOC 1 in 2D, 2 in 3D).
    IncidentPointLine {
        /// The point.
        point: EntityIdx,
        /// The line.
        line: EntityIdx,
    },
    /// A point on a plane.
    IncidentPointPlane {
        /// The point.
        point: EntityIdx,
        /// The plane.
        plane: EntityIdx,
    },
    /// A point on a circle.
    IncidentPointCircle {
        /// The point.
        point: EntityIdx,
        /// The circle.
        circle: EntityIdx,
    },
    /// A point on a sphere.
    IncidentPointSphere {
        /// The point.
        point: EntityIdx,
        /// The sphere.
        sphere: EntityIdx,
    },
    /// A line in a plane (DOC 2).
    IncidentLinePlane {
        /// The line.
        line: EntityIdx,
        /// The plane.
        plane: EntityIdx,
    },
    /// A line tangent to a circle.
    TangentLineCircle {
        /// The line.
        line: EntityIdx,
        /// The circle.
        circle: EntityIdx,
    },
    /// Two tangent circles (externally or internally, as the witness has them).
    TangentCircleCircle(EntityIdx, EntityIdx),
    /// A plane tangent to a sphere.
    TangentPlaneSphere {
        /// The plane.
        plane: EntityIdx,
        /// The sphere.
        sphere: EntityIdx,
    },
    /// Two tangent spheres.
    TangentSphereSphere(EntityIdx, EntityIdx),
    /// Two circles with the same centre (DOC 2).
    ConcentricCircles(EntityIdx, EntityIdx),
    /// A point at the centre of a circle, arc or sphere (DOC: the dimension).
    CenterPoint {
        /// The point.
        point: EntityIdx,
        /// The circle, arc or sphere.
        round: EntityIdx,
    },
    /// Two segments of equal length.
    EqualLength(EntityIdx, EntityIdx),
    /// A point at the middle of a segment (DOC: the dimension).
    Midpoint {
        /// The point.
        point: EntityIdx,
        /// The segment.
        segment: EntityIdx,
    },
    /// Two points symmetric about a point: it is their midpoint (DOC: the dimension).
    SymmetricAboutPoint {
        /// First point.
        a: EntityIdx,
        /// Second point.
        b: EntityIdx,
        /// The centre of symmetry.
        center: EntityIdx,
    },
    /// Two circles or arcs of equal radius.
    EqualRadius(EntityIdx, EntityIdx),
    /// A line and a circle tangent at a point: the radius to the point is perpendicular to
    /// the line.
    TangentAtLineCircle {
        /// The line.
        line: EntityIdx,
        /// The circle or arc.
        circle: EntityIdx,
        /// The point of tangency.
        at: EntityIdx,
    },
    /// Two circles tangent at a point: the point and the two centres are collinear.
    TangentAtCircleCircle {
        /// First circle or arc.
        a: EntityIdx,
        /// Second circle or arc.
        b: EntityIdx,
        /// The point of tangency.
        at: EntityIdx,
    },
    /// Two points symmetric about a line (2D, DOC 2).
    Symmetric {
        /// First point.
        a: EntityIdx,
        /// Second point.
        b: EntityIdx,
        /// The axis.
        axis: EntityIdx,
    },
    /// A horizontal line (2D, absolute).
    Horizontal(EntityIdx),
    /// A vertical line (2D, absolute).
    Vertical(EntityIdx),
    /// An entity pinned at its sketch position (absolute; DOC: the entity's DOF).
    Fix(EntityIdx),
    /// The angle between lines `a` and `b` equals the angle between `c` and `d` (2D; lines
    /// are undirected: the angle from `a` to `b` equals the angle from `c` to `d` modulo 180°,
    /// or its opposite).
    EqualAngle {
        /// First line of the first angle.
        a: EntityIdx,
        /// Second line of the first angle.
        b: EntityIdx,
        /// First line of the second angle.
        c: EntityIdx,
        /// Second line of the second angle.
        d: EntityIdx,
    },
    /// Two equal distances (2D).
    EqualDistance(Gap, Gap),
    /// A point of a B-spline at one of its knots (DOC: the dimension): the curve's point there,
    /// a fixed affine combination of the control points.
    SplinePoint {
        /// The point.
        point: EntityIdx,
        /// The B-spline.
        spline: EntityIdx,
        /// The knot: its index in the spline's flat knot vector
        /// ([`crate::spline::knots_or_default`]).
        knot: u32,
    },
}

impl Signature {
    /// The constraint kind.
    pub fn kind(self) -> ConstraintKind {
        use ConstraintKind as K;
        use Signature as S;
        match self {
            S::Metric(m) => m.kind(),
            S::CoincidentPoints(..) => K::Coincident,
            S::ParallelLineLine(..) | S::ParallelPlanePlane(..) | S::ParallelLinePlane { .. } => {
                K::Parallel
            }
            S::PerpendicularLineLine(..)
            | S::PerpendicularPlanePlane(..)
            | S::PerpendicularLinePlane { .. } => K::Perpendicular,
            S::IncidentPointLine { .. }
            | S::IncidentPointPlane { .. }
            | S::IncidentPointCircle { .. }
            | S::IncidentPointSphere { .. }
            | S::IncidentLinePlane { .. } => K::Incident,
            S::TangentLineCircle { .. }
            | S::TangentCircleCircle(..)
            | S::TangentPlaneSphere { .. }
            | S::TangentSphereSphere(..) => K::Tangent,
            S::ConcentricCircles(..) | S::CenterPoint { .. } => K::Concentric,
            S::EqualLength(..) => K::EqualLength,
            S::Midpoint { .. } => K::Midpoint,
            S::Symmetric { .. } | S::SymmetricAboutPoint { .. } => K::Symmetric,
            S::EqualRadius(..) => K::EqualRadius,
            S::TangentAtLineCircle { .. } | S::TangentAtCircleCircle { .. } => K::TangentAt,
            S::Horizontal(_) => K::Horizontal,
            S::Vertical(_) => K::Vertical,
            S::Fix(_) => K::Fix,
            S::EqualAngle { .. } => K::EqualAngle,
            S::EqualDistance(..) => K::EqualDistance,
            S::SplinePoint { .. } => K::SplinePoint,
        }
    }

    /// The entities bound, in role order.
    pub fn entities(self) -> Vec<EntityIdx> {
        use Signature as S;
        match self {
            S::Metric(m) => m.entities(),
            S::CoincidentPoints(a, b)
            | S::ParallelLineLine(a, b)
            | S::ParallelPlanePlane(a, b)
            | S::PerpendicularLineLine(a, b)
            | S::PerpendicularPlanePlane(a, b)
            | S::TangentCircleCircle(a, b)
            | S::TangentSphereSphere(a, b)
            | S::ConcentricCircles(a, b)
            | S::EqualLength(a, b)
            | S::EqualRadius(a, b) => vec![a, b],
            S::IncidentPointLine { point, line: other }
            | S::IncidentPointPlane { point, plane: other }
            | S::IncidentPointCircle { point, circle: other }
            | S::IncidentPointSphere { point, sphere: other }
            | S::Midpoint { point, segment: other }
            | S::CenterPoint { point, round: other }
            | S::SplinePoint { point, spline: other, .. } => vec![point, other],
            S::ParallelLinePlane { line, plane }
            | S::PerpendicularLinePlane { line, plane }
            | S::IncidentLinePlane { line, plane } => vec![line, plane],
            S::TangentLineCircle { line, circle } => vec![line, circle],
            S::TangentPlaneSphere { plane, sphere } => vec![plane, sphere],
            S::Symmetric { a, b, axis } => vec![a, b, axis],
            S::SymmetricAboutPoint { a, b, center } => vec![a, b, center],
            S::TangentAtLineCircle { line, circle, at } => vec![line, circle, at],
            S::TangentAtCircleCircle { a, b, at } => vec![a, b, at],
            S::Horizontal(e) | S::Vertical(e) | S::Fix(e) => vec![e],
            S::EqualAngle { a, b, c, d } => vec![a, b, c, d],
            S::EqualDistance(p, q) => {
                let (p, q) = (p.entities(), q.entities());
                vec![p[0], p[1], q[0], q[1]]
            }
        }
    }

    /// The metric row (a measure the user dimensions: a distance, an angle, a radius);
    /// `None` for the parameter-free rows.
    pub fn metric(self) -> Option<Metric> {
        if let Signature::Metric(m) = self { Some(m) } else { None }
    }

    /// Whether the constraint carries a metric value ([`Signature::metric`]).
    pub fn is_metric(self) -> bool {
        self.metric().is_some()
    }

    /// Whether the constraint is absolute: not invariant under displacements.
    pub fn is_absolute(self) -> bool {
        self.kind().is_absolute()
    }

    /// Resolves the roles of a constraint's entities and its DOC (format §1, table
    /// "Constraints"): the row of the table that applies.
    ///
    /// `args` are the entities in field order ([`ConstraintKind::fields`]), `kinds` their kinds.
    /// For `Fix` the DOC returned is 0: it is the DOF of the entity (and of a segment's points),
    /// which the caller adds up.
    ///
    /// # Errors
    /// A description of what the constraint takes in this dimension, when the kinds do not
    /// fit any row.
    pub fn resolve(
        dim: Dim,
        kind: ConstraintKind,
        args: &[EntityIdx],
        kinds: &[EntityKind],
    ) -> Result<(Signature, usize), &'static str> {
        use ConstraintKind as K;
        use Directions as D;
        use EntityClass as C;
        use Metric as M;
        use Signature as S;
        let d2 = dim == Dim::Two;
        let n = dim.coords();
        let classes: Vec<EntityClass> = kinds.iter().map(|k| k.class()).collect();
        // Pairs in either order: returns the arguments reordered to (x, y) roles.
        let pair = |x: EntityClass, y: EntityClass| -> Option<(EntityIdx, EntityIdx)> {
            match classes.as_slice() {
                [a, b] if *a == x && *b == y => Some((args[0], args[1])),
                [a, b] if *a == y && *b == x => Some((args[1], args[0])),
                _ => None,
            }
        };
        // Lines and planes, for the kinds that relate directions.
        let directions = || -> Result<Directions, &'static str> {
            pair(C::Line, C::Line)
                .map(|(a, b)| Directions::LineLine(a, b))
                .or_else(|| pair(C::Plane, C::Plane).map(|(a, b)| Directions::PlanePlane(a, b)))
                .or_else(|| {
                    pair(C::Line, C::Plane)
                        .map(|(line, plane)| Directions::LinePlane { line, plane })
                })
                .ok_or(if d2 { "two lines" } else { "line–line, line–plane or plane–plane" })
        };
        let single = |x: EntityClass| -> Option<EntityIdx> {
            match classes.as_slice() {
                [a] if *a == x => Some(args[0]),
                _ => None,
            }
        };
        match kind {
            K::Coincident => pair(C::Point, C::Point)
                .map(|(a, b)| (S::CoincidentPoints(a, b), n))
                .ok_or("two points"),
            K::Distance => {
                let expected = if d2 {
                    "point–point, point–line, line–line (parallel lines) or circle–circle \
                     (concentric circles)"
                } else {
                    "point–point, point–line, point–plane, line–line or plane–plane (parallel \
                     planes)"
                };
                if let Some((a, b)) = pair(C::Point, C::Point) {
                    Ok((S::Metric(M::DistancePointPoint(a, b)), 1))
                } else if let Some((point, line)) = pair(C::Point, C::Line) {
                    Ok((S::Metric(M::DistancePointLine { point, line }), 1))
                } else if let Some((point, plane)) = pair(C::Point, C::Plane) {
                    Ok((S::Metric(M::DistancePointPlane { point, plane }), 1))
                } else if let Some((a, b)) = pair(C::Line, C::Line) {
                    Ok((S::Metric(M::DistanceLineLine(a, b)), 1))
                } else if let Some((a, b)) = pair(C::Plane, C::Plane) {
                    Ok((S::Metric(M::DistancePlanePlane(a, b)), 1))
                } else if let Some((a, b)) = pair(C::Circle, C::Circle) {
                    Ok((S::Metric(M::DistanceCircleCircle(a, b)), 1))
                } else {
                    Err(expected)
                }
            }
            K::Angle => Ok(match directions()? {
                D::LineLine(a, b) => (S::Metric(M::AngleLineLine(a, b)), 1),
                D::PlanePlane(a, b) => (S::Metric(M::AnglePlanePlane(a, b)), 1),
                D::LinePlane { line, plane } => (S::Metric(M::AngleLinePlane { line, plane }), 1),
            }),
            K::Parallel => Ok(match directions()? {
                D::LineLine(a, b) => (S::ParallelLineLine(a, b), if d2 { 1 } else { 2 }),
                D::PlanePlane(a, b) => (S::ParallelPlanePlane(a, b), 2),
                D::LinePlane { line, plane } => (S::ParallelLinePlane { line, plane }, 1),
            }),
            K::Perpendicular => Ok(match directions()? {
                D::LineLine(a, b) => (S::PerpendicularLineLine(a, b), 1),
                D::PlanePlane(a, b) => (S::PerpendicularPlanePlane(a, b), 1),
                D::LinePlane { line, plane } => (S::PerpendicularLinePlane { line, plane }, 2),
            }),
            K::Incident => {
                let expected = if d2 {
                    "point–line or point–circle"
                } else {
                    "point–line, point–plane, point–sphere or line–plane"
                };
                if let Some((point, line)) = pair(C::Point, C::Line) {
                    Ok((S::IncidentPointLine { point, line }, if d2 { 1 } else { 2 }))
                } else if let Some((point, plane)) = pair(C::Point, C::Plane) {
                    Ok((S::IncidentPointPlane { point, plane }, 1))
                } else if let Some((point, circle)) = pair(C::Point, C::Circle) {
                    Ok((S::IncidentPointCircle { point, circle }, 1))
                } else if let Some((point, sphere)) = pair(C::Point, C::Sphere) {
                    Ok((S::IncidentPointSphere { point, sphere }, 1))
                } else if let Some((line, plane)) = pair(C::Line, C::Plane) {
                    Ok((S::IncidentLinePlane { line, plane }, 2))
                } else {
                    Err(expected)
                }
            }
            K::Tangent => {
                let expected = if d2 {
                    "line–circle or circle–circle"
                } else {
                    "plane–sphere or sphere–sphere"
                };
                if let Some((line, circle)) = pair(C::Line, C::Circle) {
                    Ok((S::TangentLineCircle { line, circle }, 1))
                } else if let Some((a, b)) = pair(C::Circle, C::Circle) {
                    Ok((S::TangentCircleCircle(a, b), 1))
                } else if let Some((plane, sphere)) = pair(C::Plane, C::Sphere) {
                    Ok((S::TangentPlaneSphere { plane, sphere }, 1))
                } else if let Some((a, b)) = pair(C::Sphere, C::Sphere) {
                    Ok((S::TangentSphereSphere(a, b), 1))
                } else {
                    Err(expected)
                }
            }
            K::Concentric => pair(C::Circle, C::Circle)
                .map(|(a, b)| (S::ConcentricCircles(a, b), 2))
                .or_else(|| {
                    pair(C::Point, C::Circle)
                        .or_else(|| pair(C::Point, C::Sphere))
                        .map(|(point, round)| (S::CenterPoint { point, round }, n))
                })
                .ok_or(if d2 {
                    "two circles, or a point and a circle"
                } else {
                    "a point and a sphere"
                }),
            K::Radius => single(C::Circle)
                .or_else(|| single(C::Sphere))
                .map(|e| (S::Metric(M::Radius(e)), 1))
                .ok_or(if d2 { "a circle" } else { "a sphere" }),
            K::EqualLength => match kinds {
                [EntityKind::Segment, EntityKind::Segment] => {
                    Ok((S::EqualLength(args[0], args[1]), 1))
                }
                _ => Err("two segments"),
            },
            K::SplinePoint => match kinds {
                // (The knot is found from the value by the builder, which knows the spline.)
                [EntityKind::Point, EntityKind::BSpline] => {
                    Ok((S::SplinePoint { point: args[0], spline: args[1], knot: 0 }, n))
                }
                _ => Err("a point (field point) and a B-spline (field spline)"),
            },
            K::Midpoint => match kinds {
                [EntityKind::Point, EntityKind::Segment] => {
                    Ok((S::Midpoint { point: args[0], segment: args[1] }, n))
                }
                _ => Err("a point (field point) and a segment (field segment)"),
            },
            K::Symmetric => match classes.as_slice() {
                [C::Point, C::Point, C::Line] if d2 => {
                    Ok((S::Symmetric { a: args[0], b: args[1], axis: args[2] }, 2))
                }
                [C::Point, C::Point, C::Point] => {
                    Ok((S::SymmetricAboutPoint { a: args[0], b: args[1], center: args[2] }, n))
                }
                _ if d2 => {
                    Err("two points (fields a, b) and a line, segment or point (field axis)")
                }
                _ => Err(
                    "two points (fields a, b) and a point (field axis); about a line in 2D only",
                ),
            },
            K::EqualRadius => pair(C::Circle, C::Circle)
                .map(|(a, b)| (S::EqualRadius(a, b), 1))
                .ok_or("two circles or arcs"),
            K::DistanceX | K::DistanceY => {
                if !d2 {
                    return Err("two points, in 2D only");
                }
                match classes.as_slice() {
                    [C::Point, C::Point] => Ok((
                        S::Metric(if kind == K::DistanceX {
                            M::DistanceX(args[0], args[1])
                        } else {
                            M::DistanceY(args[0], args[1])
                        }),
                        1,
                    )),
                    _ => Err("two points"),
                }
            }
            K::TangentAt => {
                let expected = "two curves (line–circle or circle–circle; arcs are circles) and \
                                a point (field at), in 2D";
                if !d2 {
                    return Err(expected);
                }
                match classes.as_slice() {
                    [C::Line, C::Circle, C::Point] => Ok((
                        S::TangentAtLineCircle { line: args[0], circle: args[1], at: args[2] },
                        1,
                    )),
                    [C::Circle, C::Line, C::Point] => Ok((
                        S::TangentAtLineCircle { line: args[1], circle: args[0], at: args[2] },
                        1,
                    )),
                    [C::Circle, C::Circle, C::Point] => {
                        Ok((S::TangentAtCircleCircle { a: args[0], b: args[1], at: args[2] }, 1))
                    }
                    _ => Err(expected),
                }
            }
            K::Horizontal | K::Vertical => {
                if !d2 {
                    return Err("a line or segment, in 2D only");
                }
                let line = single(C::Line).ok_or("a line or segment")?;
                Ok((if kind == K::Horizontal { S::Horizontal(line) } else { S::Vertical(line) }, 1))
            }
            K::LengthRatio => match kinds {
                [EntityKind::Segment, EntityKind::Segment] => {
                    Ok((S::Metric(M::LengthRatio(args[0], args[1])), 1))
                }
                _ => Err("two segments"),
            },
            K::EqualAngle => match classes.as_slice() {
                [C::Line, C::Line, C::Line, C::Line] if d2 => {
                    Ok((S::EqualAngle { a: args[0], b: args[1], c: args[2], d: args[3] }, 1))
                }
                _ => Err("four lines or segments (fields a, b, c, d), in 2D"),
            },
            K::EqualDistance => {
                let expected = "two pairs (fields a, b and c, d), each two points, a point and \
                                a line or segment, or two circles or arcs, in 2D";
                if !d2 {
                    return Err(expected);
                }
                let gap = |x: usize| match (classes[x], classes[x + 1]) {
                    (C::Point, C::Point) => Some(Gap::PointPoint(args[x], args[x + 1])),
                    (C::Point, C::Line) => {
                        Some(Gap::PointLine { point: args[x], line: args[x + 1] })
                    }
                    (C::Line, C::Point) => {
                        Some(Gap::PointLine { point: args[x + 1], line: args[x] })
                    }
                    (C::Circle, C::Circle) => Some(Gap::CircleCircle(args[x], args[x + 1])),
                    _ => None,
                };
                match (classes.len() == 4).then(|| (gap(0), gap(2))) {
                    Some((Some(p), Some(q))) => Ok((S::EqualDistance(p, q), 1)),
                    _ => Err(expected),
                }
            }
            K::Fix => match args {
                [e] => Ok((S::Fix(*e), 0)),
                _ => Err("one entity"),
            },
        }
    }
}

/// Two entities whose directions an angle, a parallelism or a perpendicularity relates.
enum Directions {
    LineLine(EntityIdx, EntityIdx),
    PlanePlane(EntityIdx, EntityIdx),
    LinePlane { line: EntityIdx, plane: EntityIdx },
}
