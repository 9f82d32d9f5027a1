//! Planes (3D): homogeneous `a, b, c, d` with `a·x + b·y + c·z + d = 0`.

use gcs_model::Geometry;
use gcs_rank::{BigRational, Field};

use super::{Draw, Representation, Snap, cross, unit};
use crate::qla::Q;

/// A plane: homogeneous `(n, δ)`.
pub(crate) struct Plane;

/// The coordinates `(n, −n·p)` of the plane through `p` with normal `n`.
pub fn plane_through<F: Field>(p: &[F], n: &[F]) -> Vec<F> {
    let d = n.iter().zip(p).fold(F::zero(), |acc, (a, b)| acc.add(&a.mul(b)));
    let mut out = n.to_vec();
    out.push(d.neg());
    out
}

impl Representation for Plane {
    const COORDS: usize = 4;
    const INTERNAL_ROWS: usize = 1;
    const HOMOGENEOUS: bool = true;
    const SNAP: Snap = Snap::Normal;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        match geometry {
            Geometry::Plane { at } => {
                let [p, n] = at.as_ref()?;
                Some(plane_through(p, n))
            }
            Geometry::Point { .. }
            | Geometry::Line { .. }
            | Geometry::Segment { .. }
            | Geometry::Circle { .. }
            | Geometry::Sphere { .. }
            | Geometry::Arc { .. }
            | Geometry::BSpline { .. } => None,
        }
    }

    /// The point of the plane nearest the origin, `−δ n / |n|²`, and the normal.
    fn to_sketch(x: &[BigRational], _like: &Geometry) -> Geometry {
        let n = x[0..3].to_vec();
        let nn = n.iter().fold(<BigRational as Field>::zero(), |acc, v| acc + v * v);
        let Some(inv) = Field::inv(&nn) else { return Geometry::Plane { at: None } };
        let s = -(&x[3] * inv);
        let p: Vec<BigRational> = n.iter().map(|v| v * &s).collect();
        Geometry::Plane { at: Some([p, n]) }
    }

    /// `ṅ = ω × n`, `δ̇ = −n·t`.
    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        if g < 3 {
            vec![F::zero(), F::zero(), F::zero(), x[g].neg()]
        } else {
            let mut v = cross(&unit::<F>(g - 3), &x[0..3]);
            v.push(F::zero());
            v
        }
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        let p = draw(Draw::Position(3));
        let n = draw(Draw::Position(3));
        plane_through(&p, &n)
    }

    fn degenerate(x: &[Q]) -> bool {
        x[0..3].iter().all(Q::is_zero)
    }
}
