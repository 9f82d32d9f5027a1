//! The sketch in the layout's coordinates.

use gcs_model::{EntityIdx, Geometry, System};
use gcs_rank::{BigRational, Field};

fn cross<F: Field>(a: &[F], b: &[F]) -> Vec<F> {
    vec![
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

/// The homogeneous coordinates `(a, b, c)` of the 2D line through `p` and `q`.
pub fn line2_through<F: Field>(p: &[F], q: &[F]) -> Vec<F> {
    vec![p[1].sub(&q[1]), q[0].sub(&p[0]), p[0].mul(&q[1]).sub(&q[0].mul(&p[1]))]
}

/// The Plücker coordinates `(d, m)` of the 3D line through `p` and `q`: `d = q − p`,
/// `m = p × q`.
pub fn line3_through<F: Field>(p: &[F], q: &[F]) -> Vec<F> {
    let mut out: Vec<F> = q.iter().zip(p).map(|(a, b)| a.sub(b)).collect();
    out.extend(cross(p, q));
    out
}

/// The coordinates `(n, −n·p)` of the plane through `p` with normal `n`.
pub fn plane_through<F: Field>(p: &[F], n: &[F]) -> Vec<F> {
    let d = n.iter().zip(p).fold(F::zero(), |acc, (a, b)| acc.add(&a.mul(b)));
    let mut out = n.to_vec();
    out.push(d.neg());
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

/// [`sketch_coords`] in any field.
pub fn sketch_coords_in<F: Field>(system: &System, e: EntityIdx) -> Option<Vec<F>> {
    sketch_coords(system, e)?.iter().map(|q| F::from_rational(q).ok()).collect()
}
