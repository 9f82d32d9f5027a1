//! Exact turns by `k/N` of a full turn modulo [`gcs_rank::TURN_PRIME`], for the last-resort
//! modular witness ([`crate::place`]): a regular hexagon's vertices are each the one before
//! turned by 60° about the centre, and `sin 60° = √3/2` is no rational number, but it is a
//! residue modulo the turn prime, together with every relation between such numbers.
//!
//! Modulo `p ≡ 3 (mod 4)`, `−1` is no square and `𝔽_{p²} = 𝔽_p(i)` with `i² = −1`; the points
//! `(c, s)` of the unit circle over `𝔽_p` are the elements `c + s·i` of norm one, a cyclic
//! group of order `p + 1`. The turn prime makes [`gcs_rank::TURN_PERIOD`] `M = lcm(1, …, 36)`
//! divide `p + 1`, so the group has an element `g` of order `M`; `g` plays `e^{2πi/M}`, and the
//! turn by `k/N` is `g^{k·M/N}`. Choosing `g` with `g^{M/4} = i` (not `−i`) keeps the turn by a
//! quarter the rational `(0, 1)` the rest of the placement uses; any such `g` is the image of
//! `e^{2πi/M}` under a ring map from `ℤ[e^{2πi/M}]`, so every algebraic relation between the
//! cosines and sines of these angles holds modulo `p` too.

use gcs_rank::{Field, ModQ, TURN_PERIOD};

/// An element `re + im·i` of `𝔽_{p²}`.
type Gauss = (ModQ, ModQ);

fn mul(a: Gauss, b: Gauss) -> Gauss {
    (a.0.mul(&b.0).sub(&a.1.mul(&b.1)), a.0.mul(&b.1).add(&a.1.mul(&b.0)))
}

fn pow(mut base: Gauss, mut e: u64) -> Gauss {
    let mut out = (ModQ::one(), ModQ::zero());
    while e > 0 {
        if e & 1 == 1 {
            out = mul(out, base);
        }
        base = mul(base, base);
        e >>= 1;
    }
    out
}

/// The turns modulo the current prime (inside [`gcs_rank::with_modulus`] of the turn prime).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Turns {
    /// An element of order [`TURN_PERIOD`] of the unit circle, with `g^{M/4} = i`.
    g: Gauss,
}

impl Turns {
    /// The table for the current prime; `None` when its unit circle has no element of order
    /// [`TURN_PERIOD`] (a prime other than the turn prime).
    pub(crate) fn new() -> Option<Turns> {
        let p = gcs_rank::modulus();
        if p % 4 != 3 || !(p + 1).is_multiple_of(TURN_PERIOD) {
            return None;
        }
        let factors = [2_u64, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31];
        let one = (ModQ::one(), ModQ::zero());
        // z^{p−1} = z̄/z has norm one; its power (p+1)/M has order dividing M, and has order M
        // for a fraction φ(M)/M of the z (about a fifth), so a few candidates suffice.
        for a in 2..200_i64 {
            let z = (ModQ::from_i64(a), ModQ::one());
            let norm = z.0.mul(&z.0).add(&z.1.mul(&z.1)).inv()?;
            let bar = (z.0, z.1.neg());
            let w = mul(mul(bar, bar), (norm, ModQ::zero()));
            let g = pow(w, (p + 1) / TURN_PERIOD);
            if factors.iter().any(|q| pow(g, TURN_PERIOD / q) == one) {
                continue;
            }
            let quarter = pow(g, TURN_PERIOD / 4);
            let g = if quarter == (ModQ::zero(), ModQ::one()) { g } else { (g.0, g.1.neg()) };
            return Some(Turns { g });
        }
        None
    }

    /// `(cos, sin)` of `k/n` of a full turn (`n` divides [`TURN_PERIOD`]: every `n ≤ 36`).
    pub(crate) fn turn(&self, k: i64, n: u64) -> Option<[ModQ; 2]> {
        if n == 0 || !TURN_PERIOD.is_multiple_of(n) {
            return None;
        }
        let k = k.rem_euclid(n as i64) as u64;
        let (c, s) = pow(self.g, k * (TURN_PERIOD / n));
        Some([c, s])
    }
}

/// The turn `k/n` (in lowest terms, `n ≤ 36`) within `tolerance` radians of `angle`, the
/// smallest `n` first; `None` for angles near none, and for the turns whose cosine and sine are
/// rational (a multiple of 90°: those the construction takes without this table).
pub(crate) fn fraction(angle: f64, tolerance: f64) -> Option<(i64, u64)> {
    if !angle.is_finite() {
        return None;
    }
    let full = std::f64::consts::TAU;
    for n in 3..=36_u64 {
        let k = (angle / full * n as f64).round();
        if (angle - k * full / n as f64).abs() > tolerance {
            continue;
        }
        let k = (k as i64).rem_euclid(n as i64);
        let g = gcd(k as u64, n);
        let (k, n) = (k / g as i64, n / g);
        if n > 2 && n != 4 {
            return Some((k, n));
        }
        // (A multiple of 90°.)
        return None;
    }
    None
}

/// The turn `k/n` the drawing shows from `b` to `m` about `z` (points in floating point):
/// the two as far from `z` as each other (to 1e-7 relative), at an angle [`fraction`] reads
/// (to 1e-7 rad).
pub(crate) fn drawn(z: [f64; 2], b: [f64; 2], m: [f64; 2]) -> Option<(i64, u64)> {
    let (u, v) = ([b[0] - z[0], b[1] - z[1]], [m[0] - z[0], m[1] - z[1]]);
    let (lu, lv) = (u[0].hypot(u[1]), v[0].hypot(v[1]));
    if lv.is_nan() || lv <= 0.0 || (lu - lv).abs() > 1e-7 * lv {
        return None;
    }
    let angle = (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1]);
    fraction(angle, 1e-7)
}

fn gcd(mut a: u64, mut b: u64) -> u64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcs_rank::{TURN_PRIME, with_modulus};

    #[test]
    fn turns_compose_and_keep_the_rational_ones() {
        with_modulus(TURN_PRIME, || {
            let t = Turns::new().expect("the turn prime has the turns");
            let q = |v: i64| ModQ::from_i64(v);
            let half = q(1).mul(&q(2).inv().unwrap());
            // Rational values where the reals have them.
            assert_eq!(t.turn(1, 4), Some([q(0), q(1)]));
            assert_eq!(t.turn(1, 2), Some([q(-1), q(0)]));
            assert_eq!(t.turn(1, 6).unwrap()[0], half);
            assert_eq!(t.turn(1, 12).unwrap()[1], half);
            assert_eq!(t.turn(-1, 12).unwrap()[1], half.neg());
            // sin² 60° = 3/4, and on the unit circle.
            let [c, s] = t.turn(1, 6).unwrap();
            assert_eq!(s.mul(&s), q(3).mul(&q(4).inv().unwrap()));
            for n in 1..=36 {
                for k in 0..n as i64 {
                    let [c, s] = t.turn(k, n).unwrap();
                    assert_eq!(c.mul(&c).add(&s.mul(&s)), q(1), "{k}/{n}");
                }
            }
            // Turning by 1/6 twice is turning by 1/3; six times is the identity.
            let rot = |[c, s]: [ModQ; 2], [x, y]: [ModQ; 2]| {
                [c.mul(&x).sub(&s.mul(&y)), s.mul(&x).add(&c.mul(&y))]
            };
            let sixth = [c, s];
            assert_eq!(rot(sixth, sixth), t.turn(1, 3).unwrap());
            let mut v = [q(5), q(7)];
            for _ in 0..6 {
                v = rot(sixth, v);
            }
            assert_eq!(v, [q(5), q(7)]);
        });
        with_modulus(gcs_rank::ModP::PRIME, || assert!(Turns::new().is_none()));
    }

    #[test]
    fn angles_are_read_as_irrational_turns_only() {
        let deg = |d: f64| d.to_radians();
        assert_eq!(fraction(deg(60.0) + 1e-10, 1e-7), Some((1, 6)));
        assert_eq!(fraction(deg(-120.0), 1e-7), Some((2, 3)));
        assert_eq!(fraction(deg(36.0), 1e-7), Some((1, 10)));
        assert_eq!(fraction(deg(90.0), 1e-7), None);
        assert_eq!(fraction(deg(180.0), 1e-7), None);
        assert_eq!(fraction(deg(0.0), 1e-7), None);
        assert_eq!(fraction(deg(61.0), 1e-7), None);
        assert_eq!(fraction(f64::NAN, 1e-7), None);
    }
}
