//! Trivial motions: the velocities of every entity's coordinates under the infinitesimal
//! displacements (2D: two translations and a rotation; 3D: three and three), tangent to the
//! entity's normalisation.
//!
//! The trivial motions a system admits are `span(T) ∩ ker J`, of dimension
//! `rank(T) − rank(J·T)`; the internal degrees of freedom are `dim ker J` minus that.

use gcs_model::{Dim, System};
use gcs_rank::Field;

use crate::error::JacobianError;
use crate::layout::{Layout, Repr};

fn cross<F: Field>(a: &[F; 3], b: &[F]) -> [F; 3] {
    [
        a[1].mul(&b[2]).sub(&a[2].mul(&b[1])),
        a[2].mul(&b[0]).sub(&a[0].mul(&b[2])),
        a[0].mul(&b[1]).sub(&a[1].mul(&b[0])),
    ]
}

fn unit<F: Field>(i: usize) -> [F; 3] {
    let mut u = [F::zero(), F::zero(), F::zero()];
    u[i] = F::one();
    u
}

/// The generators of the displacements as dense vectors over the columns of `layout`, at
/// `witness`: 3 in 2D (x, y translations; rotation about the origin), 6 in 3D (x, y, z
/// translations; rotations about the axes).
///
/// # Errors
/// When a homogeneous entity's coordinates have zero norm in the field (impossible over ℚ,
/// negligibly likely modulo a large prime).
pub fn generators<F: Field>(
    system: &System,
    layout: &Layout,
    witness: &[F],
) -> Result<Vec<Vec<F>>, JacobianError> {
    let k = system.dim().displacements();
    let mut t = vec![vec![F::zero(); layout.ncols()]; k];
    for e in system.entity_indices() {
        let Some(repr) = layout.repr(e) else { continue };
        let cols = layout.columns(e);
        let x = &witness[cols.clone()];
        for (g, column) in t.iter_mut().enumerate() {
            let vel = velocity(repr, x, g);
            let vel = if repr.homogeneous() { project(x, vel)? } else { vel };
            for (c, v) in cols.clone().zip(vel) {
                column[c] = v;
            }
        }
    }
    debug_assert!(system.dim() == Dim::Two || k == 6);
    Ok(t)
}

/// The velocity of coordinates `x` of representation `repr` under generator `g`.
fn velocity<F: Field>(repr: Repr, x: &[F], g: usize) -> Vec<F> {
    let z = F::zero;
    match repr {
        Repr::Point2 | Repr::Circle => {
            let mut v = match g {
                0 => vec![F::one(), z()],
                1 => vec![z(), F::one()],
                _ => vec![x[1].neg(), x[0].clone()],
            };
            if repr == Repr::Circle {
                v.push(z());
            }
            v
        }
        Repr::Line2 => match g {
            // ċ = −n·t; (ȧ, ḃ) = ω (−b, a).
            0 => vec![z(), z(), x[0].neg()],
            1 => vec![z(), z(), x[1].neg()],
            _ => vec![x[1].neg(), x[0].clone(), z()],
        },
        Repr::Point3 | Repr::Sphere => {
            let mut v: Vec<F> =
                if g < 3 { unit::<F>(g).to_vec() } else { cross(&unit(g - 3), &x[0..3]).to_vec() };
            if repr == Repr::Sphere {
                v.push(z());
            }
            v
        }
        Repr::Plane => {
            // ṅ = ω × n, δ̇ = −n·t.
            if g < 3 {
                vec![z(), z(), z(), x[g].neg()]
            } else {
                let mut v = cross(&unit(g - 3), &x[0..3]).to_vec();
                v.push(z());
                v
            }
        }
        Repr::Line3 => {
            // ḋ = ω × d, ṁ = ω × m + t × d.
            let (d, m) = (&x[0..3], &x[3..6]);
            if g < 3 {
                let mut v = vec![z(), z(), z()];
                v.extend(cross(&unit(g), d));
                v
            } else {
                let w = unit(g - 3);
                let mut v = cross(&w, d).to_vec();
                v.extend(cross(&w, m));
                v
            }
        }
    }
}

/// `v − (v·x / x·x) x`: the same motion with the gauge (scaling) component chosen so that the
/// normalisation `x0·x = |x0|²` is preserved.
fn project<F: Field>(x: &[F], v: Vec<F>) -> Result<Vec<F>, JacobianError> {
    let dot = |a: &[F], b: &[F]| a.iter().zip(b).fold(F::zero(), |acc, (p, q)| acc.add(&p.mul(q)));
    let xx = dot(x, x);
    let inv = xx
        .inv()
        .ok_or_else(|| JacobianError::NotAWitness("homogeneous coordinates of zero norm".into()))?;
    let s = dot(&v, x).mul(&inv);
    Ok(v.iter().zip(x).map(|(vi, xi)| vi.sub(&s.mul(xi))).collect())
}
