//! Circles and arcs (2D) and spheres (3D): a centre and a radius, both unknown (an arc's end
//! points are point entities of their own).

use gcs_model::Geometry;
use gcs_rank::{BigRational, Field};

use super::{Draw, Representation, Snap, point_velocity};
use crate::qla::Q;

/// A circle (`N = 2`: `cx, cy, r`) or a sphere (`N = 3`: `cx, cy, cz, r`).
pub(crate) struct Round<const N: usize>;

impl<const N: usize> Representation for Round<N> {
    const COORDS: usize = N + 1;
    const INTERNAL_ROWS: usize = 0;
    const HOMOGENEOUS: bool = false;
    const SNAP: Snap = Snap::Nothing;

    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>> {
        match geometry {
            Geometry::Circle { center, radius }
            | Geometry::Sphere { center, radius }
            | Geometry::Arc { center, radius, .. } => {
                let mut c = center.clone()?;
                c.push(radius.clone()?);
                Some(c)
            }
            Geometry::Point { .. }
            | Geometry::Line { .. }
            | Geometry::Segment { .. }
            | Geometry::Plane { .. }
            | Geometry::BSpline { .. } => None,
        }
    }

    /// An arc keeps its end points (entities of their own).
    fn to_sketch(x: &[BigRational], like: &Geometry) -> Geometry {
        let center = Some(x[..N].to_vec());
        let radius = x.get(N).cloned();
        if let Geometry::Arc { start, end, .. } = *like {
            return Geometry::Arc { center, radius, start, end };
        }
        if N == 2 {
            Geometry::Circle { center, radius }
        } else {
            Geometry::Sphere { center, radius }
        }
    }

    /// The centre moves as a point; the radius does not change.
    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F> {
        let mut v = point_velocity(&x[..N], g);
        v.push(F::zero());
        v
    }

    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        let mut c = draw(Draw::Position(N));
        c.extend(draw(Draw::Length));
        c
    }

    fn degenerate(x: &[Q]) -> bool {
        x[N].is_zero()
    }
}
