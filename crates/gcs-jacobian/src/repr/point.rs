//! Points: their coordinates are their position (`x, y` or `x, y, z`).

use gcs_model::Geometry;
use gcs_rank::{BigRational, Field};

use super::{Draw, Representation, Snap, point_velocity};
use crate::qla::Q;

/// A point of the `N`-dimensional space.
pub(crate) struct Point<const N: usize>;

impl<const N: usize> Representation for Point<N> {
    const COORDS: usize = N;
    const INTERNAL_ROWS: usize = 0;
    const HOMOGENEOUS: bool = false;
    const SNAP: Snap = Snap::Direction;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        match geometry {
            Geometry::Point { at } => at.clone(),
            Geometry::Line { .. }
            | Geometry::Segment { .. }
            | Geometry::Circle { .. }
            | Geometry::Plane { .. }
            | Geometry::Sphere { .. }
            | Geometry::Arc { .. }
            | Geometry::BSpline { .. } => None,
        }
    }

    fn to_sketch(x: &[BigRational], _like: &Geometry) -> Geometry {
        Geometry::Point { at: Some(x.to_vec()) }
    }

    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        point_velocity(x, g)
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        draw(Draw::Position(N))
    }

    fn degenerate(_: &[Q]) -> bool {
        false
    }
}
