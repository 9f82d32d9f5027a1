//! Circles (2D) and spheres (3D): a centre and a radius, both unknown.

use gcs_model::Geometry;
use gcs_rank::{BigRational, Field};

use super::{Draw, Representation, Snap, point_velocity};
use crate::qla::Q;

/// A circle: `cx, cy, r`.
pub(crate) struct Circle;

/// A sphere: `cx, cy, cz, r`.
pub(crate) struct Sphere;

fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
    match geometry {
        Geometry::Circle { center, radius } | Geometry::Sphere { center, radius } => {
            let mut c = center.clone()?;
            c.push(radius.clone()?);
            Some(c)
        }
        Geometry::Point { .. }
        | Geometry::Line { .. }
        | Geometry::Segment { .. }
        | Geometry::Plane { .. } => None,
    }
}

/// The centre moves as a point; the radius does not change.
fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
    let n = x.len() - 1;
    let mut v = point_velocity(&x[..n], g);
    v.push(F::zero());
    v
}

fn random(n: usize, draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
    let mut c = draw(Draw::Position(n));
    c.extend(draw(Draw::Length));
    c
}

fn split(x: &[BigRational]) -> (Option<Vec<BigRational>>, Option<BigRational>) {
    let n = x.len().saturating_sub(1);
    (Some(x[..n].to_vec()), x.get(n).cloned())
}

impl Representation for Circle {
    const COORDS: usize = 3;
    const INTERNAL_ROWS: usize = 0;
    const HOMOGENEOUS: bool = false;
    const SNAP: Snap = Snap::Nothing;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        from_sketch(geometry)
    }

    fn to_sketch(x: &[BigRational]) -> Geometry {
        let (center, radius) = split(x);
        Geometry::Circle { center, radius }
    }

    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        velocity(x, g)
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        random(2, draw)
    }

    fn degenerate(x: &[Q]) -> bool {
        x[2].is_zero()
    }
}

impl Representation for Sphere {
    const COORDS: usize = 4;
    const INTERNAL_ROWS: usize = 0;
    const HOMOGENEOUS: bool = false;
    const SNAP: Snap = Snap::Nothing;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        from_sketch(geometry)
    }

    fn to_sketch(x: &[BigRational]) -> Geometry {
        let (center, radius) = split(x);
        Geometry::Sphere { center, radius }
    }

    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        velocity(x, g)
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        random(3, draw)
    }

    fn degenerate(x: &[Q]) -> bool {
        x[3].is_zero()
    }
}
