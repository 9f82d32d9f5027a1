//! How each entity kind is represented by coordinates (the columns of the Jacobian), in one
//! place: one [`Representation`] per kind and dimension, dispatched by [`Repr`].
//!
//! | entity | coordinates | internal rows | DOF |
//! |---|---|---|---|
//! | 2D point | `x, y` | – | 2 |
//! | 3D point | `x, y, z` | – | 3 |
//! | 2D line | homogeneous `a, b, c` (`a·x + b·y + c = 0`) | normalisation | 2 |
//! | 3D line | Plücker `d, m` (direction, moment `m = p × d`) | Plücker relation `d·m = 0`, normalisation | 4 |
//! | circle | `cx, cy, r` | – | 3 |
//! | plane | homogeneous `a, b, c, d` (`a·x + b·y + c·z + d = 0`) | normalisation | 3 |
//! | sphere | `cx, cy, cz, r` | – | 4 |
//! | segment | none: built on its two points ([`gcs_model::EntityKind::is_composite`]) | – | 0 |
//!
//! Homogeneous coordinates keep everything rational (a line through two rational points, a
//! plane through a rational point with a rational normal) where a unit normal would need a
//! square root. Their scale is a gauge freedom, removed by one linear normalisation row per
//! entity whose gradient is the witness coordinates themselves (`x0 · x = |x0|²`, satisfied by
//! the witness, transversal to the scaling direction `x0` since `x0 · x0 > 0`). Every equation
//! is homogeneous in a homogeneous entity's coordinates, so the scaling direction is in the
//! kernel of every constraint row at a solution and the normalisation row removes exactly it:
//! the kernel of the Jacobian is then exactly the real infinitesimal motions.
//!
//! Adding a kind: a type implementing [`Representation`] (in its own file here), a variant of
//! [`Repr`], and one arm in each `match` of this file — the compiler lists them.

pub(crate) mod line;
pub(crate) mod plane;
mod point;
mod round;

use gcs_model::{Dim, EntityKind, Geometry};
use gcs_rank::{BigRational, Field};

use crate::dual::Dual;
use crate::qla::Q;

pub(crate) use line::{Line2, Line3};
pub(crate) use plane::Plane;
pub(crate) use point::Point;
pub(crate) use round::Round;

/// How one kind of entity is represented, in one dimension.
///
/// Velocities are those of the displacement generators: 2D: the `x` and `y` translations and
/// the rotation about the origin; 3D: the three translations, then the rotations about the
/// three axes (see [`crate::motions`]).
pub(crate) trait Representation {
    /// Number of coordinates (columns).
    const COORDS: usize;
    /// Number of entity-internal rows (normalisation, Plücker relation).
    const INTERNAL_ROWS: usize;
    /// Whether the coordinates are homogeneous (defined up to a nonzero factor).
    const HOMOGENEOUS: bool;

    /// The entity-internal rows at `x`: relations (the Plücker relation) and the
    /// normalisation of homogeneous coordinates (gradient = the coordinates).
    fn internal_rows<F: Field>(x: &[Dual<F>]) -> Vec<Dual<F>> {
        if Self::HOMOGENEOUS { vec![normalisation(x)] } else { Vec::new() }
    }

    /// The sketch fields of `geometry` as coordinates (`None` when a field is missing).
    fn from_sketch(geometry: &Geometry) -> Option<Vec<BigRational>>;

    /// Coordinates back to sketch fields: the inverse of [`Representation::from_sketch`] up to
    /// the scale of homogeneous coordinates (a line is given back by two of its points).
    /// `like` is the entity's geometry, whose references (an arc's end points) are kept.
    fn to_sketch(x: &[BigRational], like: &Geometry) -> Geometry;

    /// The velocity of coordinates `x` under displacement generator `g` (before the projection
    /// that keeps homogeneous coordinates on their normalisation).
    fn velocity<F: Field>(x: &[F], g: usize) -> Vec<F>;

    /// Random coordinates for an entity the sketch does not place, from random positions and
    /// lengths at the model's scale (see [`Draw`]).
    fn random(draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q>;

    /// Whether coordinates describe no entity of the kind (a line without direction, a
    /// circle of radius zero).
    fn degenerate(x: &[Q]) -> bool;

    /// What the constructive placement rounds when the entity is free (see [`Snap`]).
    const SNAP: Snap;

    /// The quadratic internal relations as `|P x|² = |M x|²`, with `P`, `M` integer matrices
    /// over the entity's own coordinates (rows of coefficients): the Plücker relation of a 3D
    /// line, `d·m = ¼(|d + m|² − |d − m|²)`. The placement solves them as it solves quadratic
    /// constraints.
    fn internal_quadrics() -> Vec<IntQuadric> {
        Vec::new()
    }
}

/// `(P, M)` of `|P x|² = |M x|²`, integer matrices by rows.
pub(crate) type IntQuadric = (Vec<Vec<i64>>, Vec<Vec<i64>>);

/// What the constructive placement rounds when an entity's constraints leave it free, so that
/// later tangencies and equal lengths to it have rational solutions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Snap {
    /// Nothing.
    Nothing,
    /// A point with a placed segment partner goes at a rational distance from it (along a
    /// rational unit direction).
    Direction,
    /// The normal of a line or plane gets a rational length (a Pythagorean direction).
    Normal,
}

/// What [`Representation::random`] asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Draw {
    /// The coordinates of a random position, in this many dimensions.
    Position(usize),
    /// One random positive length.
    Length,
}

/// The normalisation row of homogeneous coordinates: `Σ x0_i x_i` (gradient `x0`).
fn normalisation<F: Field>(x: &[Dual<F>]) -> Dual<F> {
    let mut norm = Dual::int(0);
    for xi in x {
        norm = &norm + &xi.scale(&xi.value);
    }
    norm
}

/// How an entity is represented: one variant per representation (a type implementing the
/// crate's `Representation` trait).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Repr {
    /// `x, y`.
    Point2,
    /// `x, y, z`.
    Point3,
    /// Homogeneous `a, b, c`.
    Line2,
    /// Plücker `d, m`.
    Line3,
    /// `cx, cy, r`.
    Circle,
    /// Homogeneous `a, b, c, d`.
    Plane,
    /// `cx, cy, cz, r`.
    Sphere,
}

/// Dispatches a [`Representation`] item on a [`Repr`].
macro_rules! dispatch {
    ($repr:expr, $t:ident => $e:expr) => {
        match $repr {
            Repr::Point2 => {
                type $t = Point<2>;
                $e
            }
            Repr::Point3 => {
                type $t = Point<3>;
                $e
            }
            Repr::Line2 => {
                type $t = Line2;
                $e
            }
            Repr::Line3 => {
                type $t = Line3;
                $e
            }
            Repr::Circle => {
                type $t = Round<2>;
                $e
            }
            Repr::Plane => {
                type $t = Plane;
                $e
            }
            Repr::Sphere => {
                type $t = Round<3>;
                $e
            }
        }
    };
}

impl Repr {
    /// The representation of an entity kind in a dimension; `None` for composite kinds
    /// (segments), which have no coordinates of their own.
    pub fn of(kind: EntityKind, dim: Dim) -> Option<Repr> {
        match (kind, dim) {
            (EntityKind::Point, Dim::Two) => Some(Repr::Point2),
            (EntityKind::Point, Dim::Three) => Some(Repr::Point3),
            (EntityKind::Line, Dim::Two) => Some(Repr::Line2),
            (EntityKind::Line, Dim::Three) => Some(Repr::Line3),
            (EntityKind::Circle | EntityKind::Arc, _) => Some(Repr::Circle),
            (EntityKind::Plane, _) => Some(Repr::Plane),
            (EntityKind::Sphere, _) => Some(Repr::Sphere),
            (EntityKind::Segment | EntityKind::BSpline, _) => None,
        }
    }

    /// Number of coordinates (columns).
    pub fn coords(self) -> usize {
        dispatch!(self, R => R::COORDS)
    }

    /// Number of entity-internal rows (normalisation, Plücker relation).
    pub fn internal_rows(self) -> usize {
        dispatch!(self, R => R::INTERNAL_ROWS)
    }

    /// Whether the coordinates are homogeneous (defined up to a nonzero factor).
    pub fn homogeneous(self) -> bool {
        dispatch!(self, R => R::HOMOGENEOUS)
    }

    /// Degrees of freedom: coordinates minus internal rows.
    pub fn dof(self) -> usize {
        self.coords() - self.internal_rows()
    }

    /// The entity-internal rows at `x`.
    pub(crate) fn internal_equations<F: Field>(self, x: &[Dual<F>]) -> Vec<Dual<F>> {
        dispatch!(self, R => R::internal_rows(x))
    }

    /// The sketch fields of `geometry` as coordinates of this representation.
    pub fn from_sketch(self, geometry: &Geometry) -> Option<Vec<BigRational>> {
        dispatch!(self, R => R::from_sketch(geometry))
    }

    /// Coordinates back to sketch fields (a line by two of its points, a plane by a point and
    /// its normal), for writing a configuration as a model.
    pub fn to_sketch(self, x: &[BigRational], like: &Geometry) -> Geometry {
        dispatch!(self, R => R::to_sketch(x, like))
    }

    /// The velocity of coordinates `x` under displacement generator `g`, tangent to the
    /// normalisation of homogeneous coordinates.
    ///
    /// # Errors
    /// `None` when homogeneous coordinates have zero norm in the field.
    pub(crate) fn velocity<F: Field>(self, x: &[F], g: usize) -> Option<Vec<F>> {
        let v = dispatch!(self, R => R::velocity(x, g));
        if self.homogeneous() { project(x, v) } else { Some(v) }
    }

    /// Random coordinates (see [`Representation::random`]).
    pub(crate) fn random(self, draw: &mut dyn FnMut(Draw) -> Vec<Q>) -> Vec<Q> {
        dispatch!(self, R => R::random(draw))
    }

    /// Whether coordinates describe no entity of the kind.
    pub(crate) fn degenerate(self, x: &[Q]) -> bool {
        dispatch!(self, R => R::degenerate(x))
    }

    /// What the placement rounds when the entity is free.
    pub(crate) fn snap(self) -> Snap {
        dispatch!(self, R => R::SNAP)
    }

    /// The quadratic internal relations (see [`Representation::internal_quadrics`]).
    pub(crate) fn internal_quadrics(self) -> Vec<IntQuadric> {
        dispatch!(self, R => R::internal_quadrics())
    }
}

/// `v − (v·x / x·x) x`: the same motion with the gauge (scaling) component chosen so that the
/// normalisation `x0·x = |x0|²` is preserved.
fn project<F: Field>(x: &[F], v: Vec<F>) -> Option<Vec<F>> {
    let dot = |a: &[F], b: &[F]| a.iter().zip(b).fold(F::zero(), |acc, (p, q)| acc.add(&p.mul(q)));
    let inv = dot(x, x).inv()?;
    let s = dot(&v, x).mul(&inv);
    Some(v.iter().zip(x).map(|(vi, xi)| vi.sub(&s.mul(xi))).collect())
}

/// `a × b` in 3D.
pub(crate) fn cross<F: Field>(a: &[F], b: &[F]) -> Vec<F> {
    vec![
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

/// The unit vector `e_i` of 3D space.
fn unit<F: Field>(i: usize) -> Vec<F> {
    let mut u = vec![F::zero(), F::zero(), F::zero()];
    u[i] = F::one();
    u
}

/// The velocity of a position `p` (2D or 3D) under generator `g`.
fn point_velocity<F: Field>(p: &[F], g: usize) -> Vec<F> {
    if p.len() == 2 {
        match g {
            0 => vec![F::one(), F::zero()],
            1 => vec![F::zero(), F::one()],
            _ => vec![p[1].neg(), p[0].clone()],
        }
    } else if g < 3 {
        unit(g)
    } else {
        cross(&unit::<F>(g - 3), p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcs_model::number::int;

    const ALL: [Repr; 7] = [
        Repr::Point2,
        Repr::Point3,
        Repr::Line2,
        Repr::Line3,
        Repr::Circle,
        Repr::Plane,
        Repr::Sphere,
    ];

    /// Coordinates to sketch fields and back give the same entity: equal coordinates, or
    /// proportional ones for homogeneous representations.
    #[test]
    fn sketch_fields_round_trip() {
        let samples: Vec<(Repr, Geometry)> = vec![
            (Repr::Point2, Geometry::Point { at: Some(vec![int(3), int(-4)]) }),
            (Repr::Point3, Geometry::Point { at: Some(vec![int(3), int(-4), int(7)]) }),
            (
                Repr::Line2,
                Geometry::Line { at: Some([vec![int(1), int(2)], vec![int(4), int(-3)]]) },
            ),
            (
                Repr::Line3,
                Geometry::Line {
                    at: Some([vec![int(1), int(2), int(0)], vec![int(4), int(-3), int(5)]]),
                },
            ),
            (
                Repr::Circle,
                Geometry::Circle { center: Some(vec![int(1), int(2)]), radius: Some(int(5)) },
            ),
            (
                Repr::Plane,
                Geometry::Plane {
                    at: Some([vec![int(1), int(2), int(3)], vec![int(0), int(2), int(-1)]]),
                },
            ),
            (
                Repr::Sphere,
                Geometry::Sphere {
                    center: Some(vec![int(1), int(2), int(3)]),
                    radius: Some(int(2)),
                },
            ),
        ];
        for (repr, geometry) in samples {
            let x = repr.from_sketch(&geometry).unwrap();
            assert_eq!(x.len(), repr.coords());
            let back = repr.from_sketch(&repr.to_sketch(&x, &geometry)).unwrap();
            if repr.homogeneous() {
                // back = λ x
                let k = x.iter().position(|v| !Field::is_zero(v)).unwrap();
                let lambda = &back[k] / &x[k];
                assert!(x.iter().zip(&back).all(|(a, b)| &(a * &lambda) == b), "{repr:?}");
            } else {
                assert_eq!(back, x, "{repr:?}");
            }
        }
        assert_eq!(ALL.iter().map(|r| r.dof()).collect::<Vec<_>>(), [2, 3, 2, 4, 3, 3, 4]);
    }
}
