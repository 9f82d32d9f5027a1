//! Exact 3-vectors over the rationals, SolveSpace's quaternion bases, and a workplane's frame.

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

use crate::ir::Number;

/// Relative tolerance of the geometric tests made in floating point (is a plane perpendicular
/// to the workplane, is a point on it): the file's numbers are doubles printed with 20 decimals.
pub(super) const TOL: f64 = 1e-9;

/// A vector of exact rationals.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct V3(pub(super) [BigRational; 3]);

impl V3 {
    pub(super) fn zero() -> V3 {
        V3([BigRational::zero(), BigRational::zero(), BigRational::zero()])
    }

    pub(super) fn from_numbers(xs: [&Number; 3]) -> V3 {
        V3([xs[0].0.clone(), xs[1].0.clone(), xs[2].0.clone()])
    }

    pub(super) fn sub(&self, o: &V3) -> V3 {
        V3([&self.0[0] - &o.0[0], &self.0[1] - &o.0[1], &self.0[2] - &o.0[2]])
    }

    pub(super) fn dot(&self, o: &V3) -> BigRational {
        &self.0[0] * &o.0[0] + &self.0[1] * &o.0[1] + &self.0[2] * &o.0[2]
    }

    pub(super) fn f64(&self) -> [f64; 3] {
        [f(&self.0[0]), f(&self.0[1]), f(&self.0[2])]
    }

    pub(super) fn coords(&self) -> Vec<Number> {
        self.0.iter().map(|x| Number(x.clone())).collect()
    }
}

/// The nearest `f64` (NaN never: infinities for out-of-range values).
pub(super) fn f(x: &BigRational) -> f64 {
    x.to_f64().unwrap_or(if x.is_negative() { f64::NEG_INFINITY } else { f64::INFINITY })
}

pub(super) fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

pub(super) fn dot_f(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn cross_f(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// The cosine of the angle between two vectors, `None` when one is (nearly) zero or not finite.
pub(super) fn cosine(a: [f64; 3], b: [f64; 3]) -> Option<f64> {
    let (na, nb) = (norm(a), norm(b));
    if !(na > 0.0 && nb > 0.0 && na.is_finite() && nb.is_finite()) {
        return None;
    }
    Some(dot_f(a, b) / (na * nb))
}

/// A quaternion `w, vx, vy, vz` (SolveSpace's orientation of a normal).
#[derive(Clone, Debug)]
pub(super) struct Quat(pub(super) [BigRational; 4]);

impl Quat {
    /// The first axis of the rotated frame (SolveSpace's `RotationU`).
    pub(super) fn u(&self) -> V3 {
        let [w, x, y, z] = &self.0;
        let two = BigRational::from_integer(2.into());
        V3([w * w + x * x - y * y - z * z, &two * (w * z + x * y), &two * (x * z - w * y)])
    }

    /// The second axis (`RotationV`).
    pub(super) fn v(&self) -> V3 {
        let [w, x, y, z] = &self.0;
        let two = BigRational::from_integer(2.into());
        V3([&two * (x * y - w * z), w * w - x * x + y * y - z * z, &two * (w * x + y * z)])
    }

    /// The normal (`RotationN`).
    pub(super) fn n(&self) -> V3 {
        let [w, x, y, z] = &self.0;
        let two = BigRational::from_integer(2.into());
        V3([&two * (w * y + x * z), &two * (y * z - w * x), w * w - x * x - y * y + z * z])
    }
}

/// A workplane's frame: origin and axes, exact, and their floating-point images for tests.
#[derive(Clone, Debug)]
pub(super) struct Frame {
    /// The workplane's handle.
    pub(super) h: u32,
    pub(super) origin: V3,
    pub(super) u: V3,
    pub(super) v: V3,
    pub(super) n: V3,
}

impl Frame {
    /// The coordinates `(u, v)` of a point in the frame: its projection onto the plane.
    pub(super) fn project(&self, p: &V3) -> [BigRational; 2] {
        let d = p.sub(&self.origin);
        [d.dot(&self.u), d.dot(&self.v)]
    }

    /// Whether a point lies in the plane (within [`TOL`], relative to the sizes at hand).
    pub(super) fn contains(&self, p: &V3) -> bool {
        let d = p.sub(&self.origin);
        let off = f(&d.dot(&self.n)).abs();
        let scale = 1.0_f64.max(norm(p.f64())).max(norm(self.origin.f64()));
        off <= TOL * scale
    }

    /// Whether a direction is parallel to the plane's normal (a circle with this normal is
    /// drawn parallel to the plane).
    pub(super) fn normal_parallel(&self, d: &V3) -> bool {
        let (a, b) = (d.f64(), self.n.f64());
        let (na, nb) = (norm(a), norm(b));
        na > 0.0 && nb > 0.0 && na.is_finite() && nb.is_finite() && {
            let sine = norm(cross_f(a, b)) / (na * nb);
            sine <= TOL
        }
    }

    /// Whether a direction lies in the plane (is perpendicular to its normal).
    pub(super) fn in_plane_direction(&self, d: &V3) -> bool {
        cosine(d.f64(), self.n.f64()).is_some_and(|c| c.abs() <= TOL)
    }
}
