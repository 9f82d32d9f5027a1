//! Points: their coordinates are their position.

use gcs_model::Geometry;
use gcs_rank::{BigRational, Field};

use super::{Draw, Representation, Snap, point_velocity};
use crate::qla::Q;

/// A 2D point: `x, y`.
pub(crate) struct Point2;

/// A 3D point: `x, y, z`.
pub(crate) struct Point3;

fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
    match geometry {
        Geometry::Point { at } => at.clone(),
        Geometry::Line { .. }
        | Geometry::Segment { .. }
        | Geometry::Circle { .. }
        | Geometry::Plane { .. }
        | Geometry::Sphere { .. } => None,
    }
}

impl Representation for Point2 {
    const COORDS: usize = 2;
    const INTERNAL_ROWS: usize = 0;
    const HOMOGENEOUS: bool = false;
    const SNAP: Snap = Snap::Direction;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        from_sketch(geometry)
    }

    fn to_sketch(x: &[BigRational]) -> Geometry {
        Geometry::Point { at: Some(x.to_vec()) }
    }

    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        point_velocity(x, g)
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        draw(Draw::Position(2))
    }

    fn degenerate(_: &[Q]) -> bool {
        false
    }
}

impl Representation for Point3 {
    const COORDS: usize = 3;
    const INTERNAL_ROWS: usize = 0;
    const HOMOGENEOUS: bool = false;
    const SNAP: Snap = Snap::Direction;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        from_sketch(geometry)
    }

    fn to_sketch(x: &[BigRational]) -> Geometry {
        Geometry::Point { at: Some(x.to_vec()) }
    }

    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        point_velocity(x, g)
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        draw(Draw::Position(3))
    }

    fn degenerate(_: &[Q]) -> bool {
        false
    }
}
