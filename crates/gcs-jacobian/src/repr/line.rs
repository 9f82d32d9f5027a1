//! Lines: homogeneous `a, b, c` in 2D, Plücker coordinates `(d, m)` in 3D.

use gcs_model::Geometry;
use gcs_rank::{BigRational, Field};

use super::{Draw, Representation, Snap, cross, normalisation, unit};
use crate::dual::{Dual, vec as v};
use crate::qla::Q;

/// A 2D line: homogeneous `(a, b, c)`, `a·x + b·y + c = 0`.
pub(crate) struct Line2;

/// A 3D line: Plücker `(d, m)`, direction and moment `m = p × d`.
pub(crate) struct Line3;

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

fn sketch_points(geometry: &Geometry) -> Option<&[Vec<BigRational>; 2]> {
    match geometry {
        Geometry::Line { at } => at.as_ref(),
        Geometry::Point { .. }
        | Geometry::Segment { .. }
        | Geometry::Circle { .. }
        | Geometry::Plane { .. }
        | Geometry::Sphere { .. }
        | Geometry::Arc { .. }
        | Geometry::BSpline { .. } => None,
    }
}

impl Representation for Line2 {
    const COORDS: usize = 3;
    const INTERNAL_ROWS: usize = 1;
    const HOMOGENEOUS: bool = true;
    const SNAP: Snap = Snap::Normal;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        let [p, q] = sketch_points(geometry)?;
        Some(line2_through(p, q))
    }

    /// The point of the line nearest the origin, `−c (a, b) / (a² + b²)`, and that point moved
    /// along the line by `(−b, a)`.
    fn to_sketch(x: &[BigRational], _like: &Geometry) -> Geometry {
        let (a, b, c) = (&x[0], &x[1], &x[2]);
        let Some(inv) = Field::inv(&(a * a + b * b)) else { return Geometry::Line { at: None } };
        let s = -(c * inv);
        let p = vec![a * &s, b * &s];
        let q = vec![&p[0] - b, &p[1] + a];
        Geometry::Line { at: Some([p, q]) }
    }

    /// `ċ = −n·t`; `(ȧ, ḃ) = ω (−b, a)`.
    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        let z = F::zero;
        match g {
            0 => vec![z(), z(), x[0].neg()],
            1 => vec![z(), z(), x[1].neg()],
            _ => vec![x[1].neg(), x[0].clone(), z()],
        }
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        let (p, q) = (draw(Draw::Position(2)), draw(Draw::Position(2)));
        let l = line2_through(&p, &q);
        if l.iter().all(Q::is_zero) { vec![Q::ONE, Q::ZERO, Q::ZERO] } else { l }
    }

    fn degenerate(x: &[Q]) -> bool {
        x[0..2].iter().all(Q::is_zero)
    }
}

impl Representation for Line3 {
    const COORDS: usize = 6;
    const INTERNAL_ROWS: usize = 2;
    const HOMOGENEOUS: bool = true;
    const SNAP: Snap = Snap::Nothing;

    /// The Plücker relation: `d·m = ¼(|d + m|² − |d − m|²)`.
    fn internal_quadrics() -> Vec<super::IntQuadric> {
        let row = |i: usize, sign: i64| {
            let mut r = vec![0; 6];
            r[i] = 1;
            r[i + 3] = sign;
            r
        };
        vec![((0..3).map(|i| row(i, 1)).collect(), (0..3).map(|i| row(i, -1)).collect())]
    }

    /// The Plücker relation `d·m = 0`, then the normalisation.
    fn internal_rows<F: Field>(x: &[Dual<F>]) -> Vec<Dual<F>> {
        vec![v::dot(&x[0..3], &x[3..6]), normalisation(x)]
    }

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        let [p, q] = sketch_points(geometry)?;
        Some(line3_through(p, q))
    }

    /// The point of the line nearest the origin, `d × m / |d|²`, and that point plus `d`.
    fn to_sketch(x: &[BigRational], _like: &Geometry) -> Geometry {
        let (d, m) = (&x[0..3], &x[3..6]);
        let dd = d.iter().fold(<BigRational as Field>::zero(), |acc, v| acc + v * v);
        let Some(inv) = Field::inv(&dd) else { return Geometry::Line { at: None } };
        let p: Vec<BigRational> = cross(d, m).iter().map(|v| v * &inv).collect();
        let q: Vec<BigRational> = p.iter().zip(d).map(|(a, b)| a + b).collect();
        Geometry::Line { at: Some([p, q]) }
    }

    /// `ḋ = ω × d`, `ṁ = ω × m + t × d`.
    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        let (d, m) = (&x[0..3], &x[3..6]);
        if g < 3 {
            let mut v = vec![F::zero(), F::zero(), F::zero()];
            v.extend(cross(&unit::<F>(g), d));
            v
        } else {
            let w = unit::<F>(g - 3);
            let mut v = cross(&w, d);
            v.extend(cross(&w, m));
            v
        }
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        let p = draw(Draw::Position(3));
        let q = draw(Draw::Position(3));
        line3_through(&p, &q)
    }

    fn degenerate(x: &[Q]) -> bool {
        x[0..3].iter().all(Q::is_zero)
    }
}
