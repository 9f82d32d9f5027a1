//! The sketch in the layout's coordinates.

use gcs_model::{EntityIdx, Geometry, System};
use gcs_rank::BigRational;

fn cross(a: &[BigRational], b: &[BigRational]) -> Vec<BigRational> {
    vec![
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// The homogeneous coordinates `(a, b, c)` of the 2D line through `p` and `q`.
pub fn line2_through(p: &[BigRational], q: &[BigRational]) -> Vec<BigRational> {
    vec![&p[1] - &q[1], &q[0] - &p[0], &p[0] * &q[1] - &q[0] * &p[1]]
}

/// The Plücker coordinates `(d, m)` of the 3D line through `p` and `q`: `d = q − p`,
/// `m = p × q`.
pub fn line3_through(p: &[BigRational], q: &[BigRational]) -> Vec<BigRational> {
    let mut out: Vec<BigRational> = q.iter().zip(p).map(|(a, b)| a - b).collect();
    out.extend(cross(p, q));
    out
}

/// The coordinates `(n, −n·p)` of the plane through `p` with normal `n`.
pub fn plane_through(p: &[BigRational], n: &[BigRational]) -> Vec<BigRational> {
    let d: BigRational = n.iter().zip(p).map(|(a, b)| a * b).sum();
    let mut out = n.to_vec();
    out.push(-d);
    out
}

/// An entity's sketch in the coordinates of its representation (`None` when its sketch
/// fields are missing, and for segments, which have no coordinates).
pub fn sketch_coords(system: &System, e: EntityIdx) -> Option<Vec<BigRational>> {
    let three = system.dim() == gcs_model::Dim::Three;
    match &system.entity(e).geometry {
        Geometry::Point { at } => at.clone(),
        Geometry::Line { at } => {
            let [p, q] = at.as_ref()?;
            Some(if three { line3_through(p, q) } else { line2_through(p, q) })
        }
        Geometry::Plane { at } => {
            let [p, n] = at.as_ref()?;
            Some(plane_through(p, n))
        }
        Geometry::Circle { center, radius } | Geometry::Sphere { center, radius } => {
            let mut c = center.clone()?;
            c.push(radius.clone()?);
            Some(c)
        }
        Geometry::Segment { .. } => None,
    }
}
