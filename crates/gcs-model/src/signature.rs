//! The constraint table of the format: which entity kinds each constraint kind takes, in which
//! dimension, and how many degrees of freedom it removes (DOC).

use crate::kinds::{ConstraintKind, Dim, EntityKind};
use crate::system::{EntityIdx, Shape};

/// Coarse entity classes of the table ("line" covers lines and segments).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Class {
    Point,
    Line,
    Plane,
    Circle,
    Sphere,
}

fn class(kind: EntityKind) -> Class {
    match kind {
        EntityKind::Point => Class::Point,
        EntityKind::Line | EntityKind::Segment => Class::Line,
        EntityKind::Plane => Class::Plane,
        EntityKind::Circle => Class::Circle,
        EntityKind::Sphere => Class::Sphere,
    }
}

/// Resolves the roles of a constraint's entities and its DOC.
///
/// `args` are the entities in field order, `kinds` their kinds. On a mismatch, returns a
/// description of what the constraint takes in this dimension. For `Fix` the DOC returned is
/// 0: it depends on the entity and is filled in by the caller.
pub(crate) fn resolve(
    dim: Dim,
    kind: ConstraintKind,
    args: &[EntityIdx],
    kinds: &[EntityKind],
) -> Result<(Shape, usize), &'static str> {
    use Class as C;
    use ConstraintKind as K;
    let d2 = dim == Dim::Two;
    let n = dim.coords();
    let classes: Vec<Class> = kinds.iter().map(|k| class(*k)).collect();
    // Pairs in either order: returns the arguments reordered to (x, y) roles.
    let pair = |x: Class, y: Class| -> Option<(EntityIdx, EntityIdx)> {
        match classes.as_slice() {
            [a, b] if *a == x && *b == y => Some((args[0], args[1])),
            [a, b] if *a == y && *b == x => Some((args[1], args[0])),
            _ => None,
        }
    };
    let single = |x: Class| -> Option<EntityIdx> {
        match classes.as_slice() {
            [a] if *a == x => Some(args[0]),
            _ => None,
        }
    };
    match kind {
        K::Coincident => {
            pair(C::Point, C::Point).map(|(a, b)| (Shape::PointPoint(a, b), n)).ok_or("two points")
        }
        K::Distance => {
            let expected = if d2 {
                "point–point, point–line or line–line (parallel lines)"
            } else {
                "point–point, point–line, point–plane, line–line or plane–plane (parallel planes)"
            };
            if let Some((a, b)) = pair(C::Point, C::Point) {
                Ok((Shape::PointPoint(a, b), 1))
            } else if let Some((point, line)) = pair(C::Point, C::Line) {
                Ok((Shape::PointLine { point, line }, 1))
            } else if let Some((point, plane)) = pair(C::Point, C::Plane) {
                Ok((Shape::PointPlane { point, plane }, 1))
            } else if let Some((a, b)) = pair(C::Line, C::Line) {
                Ok((Shape::LineLine(a, b), 1))
            } else if let Some((a, b)) = pair(C::Plane, C::Plane) {
                Ok((Shape::PlanePlane(a, b), 1))
            } else {
                Err(expected)
            }
        }
        K::Angle | K::Parallel | K::Perpendicular => {
            let expected =
                if d2 { "two lines" } else { "line–line, line–plane or plane–plane" };
            if let Some((a, b)) = pair(C::Line, C::Line) {
                let doc = match (kind, d2) {
                    (K::Parallel, false) => 2,
                    _ => 1,
                };
                Ok((Shape::LineLine(a, b), doc))
            } else if let Some((a, b)) = pair(C::Plane, C::Plane) {
                let doc = if kind == K::Parallel { 2 } else { 1 };
                Ok((Shape::PlanePlane(a, b), doc))
            } else if let Some((line, plane)) = pair(C::Line, C::Plane) {
                let doc = if kind == K::Perpendicular { 2 } else { 1 };
                Ok((Shape::LinePlane { line, plane }, doc))
            } else {
                Err(expected)
            }
        }
        K::Incident => {
            let expected = if d2 {
                "point–line or point–circle"
            } else {
                "point–line, point–plane, point–sphere or line–plane"
            };
            if let Some((point, line)) = pair(C::Point, C::Line) {
                Ok((Shape::PointLine { point, line }, if d2 { 1 } else { 2 }))
            } else if let Some((point, plane)) = pair(C::Point, C::Plane) {
                Ok((Shape::PointPlane { point, plane }, 1))
            } else if let Some((point, circle)) = pair(C::Point, C::Circle) {
                Ok((Shape::PointCircle { point, circle }, 1))
            } else if let Some((point, sphere)) = pair(C::Point, C::Sphere) {
                Ok((Shape::PointSphere { point, sphere }, 1))
            } else if let Some((line, plane)) = pair(C::Line, C::Plane) {
                Ok((Shape::LinePlane { line, plane }, 2))
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
                Ok((Shape::LineCircle { line, circle }, 1))
            } else if let Some((a, b)) = pair(C::Circle, C::Circle) {
                Ok((Shape::CircleCircle(a, b), 1))
            } else if let Some((plane, sphere)) = pair(C::Plane, C::Sphere) {
                Ok((Shape::PlaneSphere { plane, sphere }, 1))
            } else if let Some((a, b)) = pair(C::Sphere, C::Sphere) {
                Ok((Shape::SphereSphere(a, b), 1))
            } else {
                Err(expected)
            }
        }
        K::Radius => single(C::Circle)
            .or_else(|| single(C::Sphere))
            .map(|e| (Shape::Round(e), 1))
            .ok_or(if d2 { "a circle" } else { "a sphere" }),
        K::EqualLength => match kinds {
            [EntityKind::Segment, EntityKind::Segment] => {
                Ok((Shape::SegmentSegment(args[0], args[1]), 1))
            }
            _ => Err("two segments"),
        },
        K::Midpoint => match kinds {
            [EntityKind::Point, EntityKind::Segment] => {
                Ok((Shape::PointSegment { point: args[0], segment: args[1] }, n))
            }
            _ => Err("a point (field point) and a segment (field segment)"),
        },
        K::Symmetric => {
            if !d2 {
                return Err("two points and an axis line, in 2D only");
            }
            match classes.as_slice() {
                [C::Point, C::Point, C::Line] => {
                    Ok((Shape::Symmetric { a: args[0], b: args[1], axis: args[2] }, 2))
                }
                _ => Err("two points (fields a, b) and a line or segment (field axis)"),
            }
        }
        K::Horizontal | K::Vertical => {
            if !d2 {
                return Err("a line or segment, in 2D only");
            }
            single(C::Line).map(|e| (Shape::Line(e), 1)).ok_or("a line or segment")
        }
        K::Fix => match args {
            [e] => Ok((Shape::Single(*e), 0)),
            _ => Err("one entity"),
        },
    }
}
