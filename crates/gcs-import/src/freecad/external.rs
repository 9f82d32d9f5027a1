//! External geometry of documents that do not store it (FreeCAD before 1.0): each link of the
//! sketch's `ExternalGeometry` property (`Sketch004` / `Edge9`) is resolved against the linked
//! object's stored shape (its `Shape` property, a BRep file of the archive) and projected onto the
//! sketch plane as FreeCAD's `SketchObject::rebuildExternalGeometry` does for the cases it handles
//! in one geometry each:
//! - a vertex → a point;
//! - a line edge → a segment between its projected ends (a point when they coincide);
//! - a circle or arc edge parallel to the sketch → a circle or an arc (counter-clockwise);
//! - a full circle perpendicular to the sketch → a segment across its diameter;
//! - a full circle at another angle → an ellipse (major radius the circle's, minor `r·|cos θ|`).
//!
//! Anything else is skipped with its reason. FreeCAD makes external geometry `−3 − k` from link
//! `k` only while each link gives one geometry: after a link whose count is not known (a face, a
//! B-spline edge, a link that cannot be read) the later GeoIds are unknown, and are skipped too.

use super::brep::{Curve, ShapeKind, SubShape, Trsf, V3};
use super::geometry::{Draw, P2};
use crate::ir::{self, Number};

/// What a link gives.
pub(crate) enum Projected {
    /// One geometry.
    Geo { geometry: ir::Geometry, draw: Draw },
    /// Not expressible, but FreeCAD makes one geometry of it (the GeoIds after it stay known).
    Skip(String),
    /// Not expressible, and how many geometries FreeCAD makes of it is not known.
    Unknown(String),
}

/// The sketch placement (`PropertyPlacement`: position `Px, Py, Pz`, rotation quaternion `Q0..Q3`
/// = x, y, z, w) as a map from sketch to model coordinates.
pub(crate) fn placement(px: f64, py: f64, pz: f64, q: [f64; 4]) -> Option<Trsf> {
    let n = (q.iter().map(|v| v * v).sum::<f64>()).sqrt();
    let usable = n.is_finite() && n > 1e-12 && [px, py, pz].iter().all(|v| v.is_finite());
    if !usable {
        return None;
    }
    let [x, y, z, w] = [q[0] / n, q[1] / n, q[2] / n, q[3] / n];
    Some(Trsf {
        m: [
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w), px],
            [2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w), py],
            [2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y), pz],
        ],
    })
}

/// Splits a sub-element name (`Edge9`, `Vertex2`) into its kind and 1-based number.
pub(crate) fn sub_name(sub: &str) -> Option<(ShapeKind, usize)> {
    let (kind, digits) = if let Some(d) = sub.strip_prefix("Edge") {
        (ShapeKind::Edge, d)
    } else if let Some(d) = sub.strip_prefix("Vertex") {
        (ShapeKind::Vertex, d)
    } else if let Some(d) = sub.strip_prefix("Face") {
        (ShapeKind::Face, d)
    } else {
        return None;
    };
    let n: usize = digits.parse().ok()?;
    (n > 0).then_some((kind, n))
}

fn xy(p: V3) -> P2 {
    [p[0], p[1]]
}

fn coords(p: P2) -> Option<ir::Coords> {
    Some(vec![Number::from_f64(p[0])?, Number::from_f64(p[1])?])
}

const NON_FINITE: &str = "its projection is not finite";

/// Projects a resolved sub-shape; `to_sketch` maps model to sketch coordinates.
pub(crate) fn project(sub: &SubShape, to_sketch: &Trsf) -> Projected {
    match sub {
        SubShape::Vertex(p) => {
            let q = xy(to_sketch.point(*p));
            match coords(q) {
                Some(at) => {
                    Projected::Geo { geometry: ir::Geometry::Point { at }, draw: Draw::Point(q) }
                }
                None => Projected::Skip(NON_FINITE.into()),
            }
        }
        SubShape::Edge(None) => Projected::Unknown("the edge has no 3D curve".into()),
        SubShape::Edge(Some((curve, first, last))) => {
            project_edge(&curve.transformed(to_sketch), *first, *last)
        }
        SubShape::Other(kind) => Projected::Unknown(format!(
            "a {} is not projected by this reader (FreeCAD projects only planar faces perpendicular to the sketch)",
            match kind {
                ShapeKind::Face => "face",
                _ => "shape of this kind",
            }
        )),
    }
}

fn project_edge(curve: &Curve, first: f64, last: f64) -> Projected {
    match curve {
        Curve::Line { .. } => {
            // FreeCAD replaces infinite parameters by ±10000.
            let first = if first.abs() > 1e99 { -10000.0 } else { first };
            let last = if last.abs() > 1e99 { 10000.0 } else { last };
            let (Some(a), Some(b)) = (curve.value(first), curve.value(last)) else {
                return Projected::Skip(NON_FINITE.into());
            };
            let (a, b) = (xy(a), xy(b));
            let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
            if !d.is_finite() {
                return Projected::Skip(NON_FINITE.into());
            }
            if d < 1e-7 {
                let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
                return match coords(m) {
                    Some(at) => Projected::Geo { geometry: ir::Geometry::Point { at }, draw: Draw::Point(m) },
                    None => Projected::Skip(NON_FINITE.into()),
                };
            }
            match (coords(a), coords(b)) {
                (Some(start), Some(end)) => {
                    Projected::Geo { geometry: ir::Geometry::Segment { start, end }, draw: Draw::Segment(a, b) }
                }
                _ => Projected::Skip(NON_FINITE.into()),
            }
        }
        Curve::Circle { p, n, r, .. } => {
            let (Some(beg), Some(end)) = (curve.value(first), curve.value(last)) else {
                return Projected::Skip(NON_FINITE.into());
            };
            let closed = (0..3).map(|i| (beg[i] - end[i]).powi(2)).sum::<f64>() < 1e-7;
            let c = xy(*p);
            let sin = (n[0] * n[0] + n[1] * n[1]).sqrt();
            if !(sin.is_finite() && r.is_finite() && *r > 0.0) {
                return Projected::Skip(NON_FINITE.into());
            }
            let Some(center) = coords(c) else { return Projected::Skip(NON_FINITE.into()) };
            if sin < 1e-7 {
                if closed {
                    let Some(radius) = Number::from_f64(*r) else { return Projected::Skip(NON_FINITE.into()) };
                    return Projected::Geo { geometry: ir::Geometry::Circle { center, radius }, draw: Draw::Circle { c } };
                }
                let (mut s, mut e) = (xy(beg), xy(end));
                if n[2] < 0.0 {
                    std::mem::swap(&mut s, &mut e);
                }
                return match (coords(s), coords(e)) {
                    (Some(start), Some(end)) => {
                        Projected::Geo { geometry: ir::Geometry::Arc { center, start, end }, draw: Draw::Arc { c } }
                    }
                    _ => Projected::Skip(NON_FINITE.into()),
                };
            }
            if !closed {
                return Projected::Skip(
                    "an arc not parallel to the sketch: its projection (FreeCAD's rules for the ends of a \
                     perpendicular arc, an ellipse for an oblique one) is not reproduced"
                        .into(),
                );
            }
            // The direction in the sketch plane perpendicular to the circle's normal.
            let u = [-n[1] / sin, n[0] / sin];
            if n[2].abs() < 1e-12 {
                let a = [c[0] - r * u[0], c[1] - r * u[1]];
                let b = [c[0] + r * u[0], c[1] + r * u[1]];
                return match (coords(a), coords(b)) {
                    (Some(start), Some(end)) => {
                        Projected::Geo { geometry: ir::Geometry::Segment { start, end }, draw: Draw::Segment(a, b) }
                    }
                    _ => Projected::Skip(NON_FINITE.into()),
                };
            }
            let b = r * n[2].abs();
            let m = [c[0] + r * u[0], c[1] + r * u[1]];
            match (coords(m), Number::from_f64(b)) {
                (Some(major), Some(minor_radius)) => Projected::Geo {
                    geometry: ir::Geometry::Ellipse { center, major, minor_radius },
                    draw: Draw::Ellipse { c, u, a: *r, b, arc: false },
                },
                _ => Projected::Skip(NON_FINITE.into()),
            }
        }
        Curve::Ellipse { .. } => Projected::Unknown(
            "an ellipse edge: FreeCAD projects it by a general normal projection, not reproduced here".into(),
        ),
        Curve::Other(kind) => Projected::Unknown(format!(
            "a {kind} edge: FreeCAD projects it by a general normal projection, not reproduced here"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placement_of_identity_and_rotation() {
        assert_eq!(placement(0.0, 0.0, 0.0, [0.0, 0.0, 0.0, 1.0]), Some(Trsf::IDENTITY));
        // 120° about (1,1,1): x → y.
        let t = placement(0.0, 0.0, 0.0, [0.5, 0.5, 0.5, 0.5]).unwrap();
        let p = t.point([1.0, 0.0, 0.0]);
        assert!((p[0]).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12 && p[2].abs() < 1e-12, "{p:?}");
    }

    #[test]
    fn oblique_circle_becomes_an_ellipse() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let c = Curve::Circle {
            p: [1.0, 2.0, 3.0],
            n: [0.0, s, s],
            x: [1.0, 0.0, 0.0],
            y: [0.0, s, -s],
            r: 2.0,
        };
        match project_edge(&c, 0.0, 2.0 * std::f64::consts::PI) {
            Projected::Geo { draw: Draw::Ellipse { c, u, a, b, .. }, .. } => {
                assert_eq!(c, [1.0, 2.0]);
                assert!((u[0] + 1.0).abs() < 1e-12 && u[1].abs() < 1e-12);
                assert_eq!(a, 2.0);
                assert!((b - 2.0 * s).abs() < 1e-12);
            }
            _ => panic!("not an ellipse"),
        }
    }

    #[test]
    fn names() {
        assert_eq!(sub_name("Edge12"), Some((ShapeKind::Edge, 12)));
        assert_eq!(sub_name("Vertex2"), Some((ShapeKind::Vertex, 2)));
        assert_eq!(sub_name("Edge0"), None);
        assert_eq!(sub_name("Edge"), None);
    }
}
