//! The [`Field`] trait and its rational and floating-point backends.

use num_bigint::BigInt;
use num_complex::Complex64;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::Rat;
use crate::error::{RankError, describe};
use crate::gcd::gcd_int;

/// A field with exact arithmetic, or `f64`.
///
/// The trait describes algebra, not floating point: [`Field::is_zero`] is the literal test
/// (`== 0.0` for `f64`) and tolerances are explicit options of the algorithms that use them
/// ([`EchelonOptions::tolerance`](crate::EchelonOptions::tolerance)). Arithmetic takes its
/// operands by reference so that big rationals are not cloned needlessly.
///
/// Implemented for [`BigRational`] (`"rational"`), [`Rat`] (`"rat"`), [`ModP`](crate::ModP)
/// and [`ModPrime`](crate::ModPrime) (`"modp"`), `f64` (`"float"`), [`Complex64`] (`"complex"`:
/// the homotopy continuation of a solver evaluates the equations over ℂ) and, with the `rug`
/// feature, `rug::Rational` (`"rug"`).
pub trait Field: Clone + PartialEq + std::fmt::Debug + Send + Sync + 'static {
    /// Short name of the backend, for reports: `"rational"`, `"rat"`, `"rug"`, `"modp"` or
    /// `"float"`.
    const NAME: &'static str;
    /// Whether arithmetic is exact (`false` only for `f64`).
    const EXACT: bool;
    /// The additive identity.
    fn zero() -> Self;
    /// The multiplicative identity.
    fn one() -> Self;
    /// The exact zero test (`f64`: `== 0.0`).
    fn is_zero(&self) -> bool;
    /// The image of an integer.
    fn from_i64(v: i64) -> Self;
    /// The image of a rational number.
    ///
    /// # Errors
    /// [`RankError::DenominatorDivisibleByPrime`] in a prime field whose modulus divides the
    /// denominator; [`RankError::NotRepresentable`] for `f64` when the value overflows.
    fn from_rational(q: &BigRational) -> Result<Self, RankError>;
    /// The image of a [`Rat`]; the same as [`Field::from_rational`] of its value, without big
    /// integers when it is small (the prime fields, `f64`, [`BigRational`] and [`Rat`]
    /// override it).
    ///
    /// # Errors
    /// Those of [`Field::from_rational`].
    fn from_rat(q: &Rat) -> Result<Self, RankError> {
        Self::from_rational(&q.big_cow())
    }
    /// `self + rhs`.
    fn add(&self, rhs: &Self) -> Self;
    /// `self - rhs`.
    fn sub(&self, rhs: &Self) -> Self;
    /// `self * rhs`.
    fn mul(&self, rhs: &Self) -> Self;
    /// `-self`.
    fn neg(&self) -> Self;
    /// The multiplicative inverse, `None` for zero.
    fn inv(&self) -> Option<Self>;
    /// `self -= a * b`, the elimination hot loop.
    fn sub_mul_assign(&mut self, a: &Self, b: &Self);
    /// `self -= a * b` in a dense accumulator, where `neg_a` is `a.neg()`: the result may be
    /// left in a redundant form (another representative of the same residue) that only
    /// [`Field::settle`] makes canonical; until then, nothing but this step and `settle` may
    /// read it. The default is [`Field::sub_mul_assign`] (always canonical); `ModP` skips the
    /// final reductions.
    #[inline]
    fn sub_mul_unsettled(&mut self, a: &Self, neg_a: &Self, b: &Self) {
        let _ = neg_a;
        self.sub_mul_assign(a, b);
    }
    /// Makes a value left by [`Field::sub_mul_unsettled`] canonical (nothing by default).
    #[inline]
    fn settle(&mut self) {}
    /// `|self|` as an `f64`, for tolerances and pivoting. Exact fields give an approximation;
    /// prime fields give `0.0` for zero and `1.0` otherwise.
    fn magnitude(&self) -> f64;
}

/// `add`, `sub`, `mul` and `neg` of a [`Field`] whose references have the standard operators,
/// inside its `impl Field` block (also for fields of other crates: the placement's numbers).
#[macro_export]
macro_rules! arithmetic_by_operators {
    () => {
        fn add(&self, rhs: &Self) -> Self {
            self + rhs
        }

        fn sub(&self, rhs: &Self) -> Self {
            self - rhs
        }

        fn mul(&self, rhs: &Self) -> Self {
            self * rhs
        }

        fn neg(&self) -> Self {
            -self
        }
    };
}

impl Field for BigRational {
    const NAME: &'static str = "rational";
    const EXACT: bool = true;

    fn zero() -> Self {
        Zero::zero()
    }

    fn one() -> Self {
        One::one()
    }

    fn is_zero(&self) -> bool {
        Zero::is_zero(self)
    }

    fn from_i64(v: i64) -> Self {
        BigRational::from_integer(BigInt::from(v))
    }

    fn from_rational(q: &BigRational) -> Result<Self, RankError> {
        Ok(q.clone())
    }

    fn from_rat(q: &Rat) -> Result<Self, RankError> {
        Ok(q.to_big())
    }

    arithmetic_by_operators!();

    fn inv(&self) -> Option<Self> {
        if Zero::is_zero(self) { None } else { Some(self.recip()) }
    }

    fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
        if Zero::is_zero(a) || Zero::is_zero(b) {
            return;
        }
        let (p, q) = reduced_product(a, b);
        subtract_fraction(self, p, q);
    }

    fn magnitude(&self) -> f64 {
        self.abs().to_f64().unwrap_or(f64::INFINITY)
    }
}

/// `a * b` as a numerator and a positive denominator in lowest terms, cancelling across
/// (`gcd(a.numer, b.denom)` and `gcd(b.numer, a.denom)`) so that no gcd of the full product is
/// needed; integer operands skip the gcds.
pub(crate) fn reduced_product(a: &BigRational, b: &BigRational) -> (BigInt, BigInt) {
    let (an, ad) = (a.numer(), a.denom());
    let (bn, bd) = (b.numer(), b.denom());
    if ad.is_one() && bd.is_one() {
        return (an * bn, BigInt::one());
    }
    let g1 = if bd.is_one() { BigInt::one() } else { gcd_int(an, bd) };
    let g2 = if ad.is_one() { BigInt::one() } else { gcd_int(bn, ad) };
    let divide = |x: &BigInt, g: &BigInt| if g.is_one() { x.clone() } else { x / g };
    let numer = divide(an, &g1) * divide(bn, &g2);
    let denom = divide(ad, &g2) * divide(bd, &g1);
    (numer, denom)
}

/// `x -= p / q` for `p / q` in lowest terms with `q > 0`, by Knuth's method (TAOCP 4.5.1):
/// only the gcd of the two denominators and one small gcd are computed.
pub(crate) fn subtract_fraction(x: &mut BigRational, p: BigInt, q: BigInt) {
    let (n, d) =
        std::mem::replace(x, BigRational::new_raw(BigInt::zero(), BigInt::one())).into_raw();
    let (numer, denom) = if d.is_one() && q.is_one() {
        (n - p, d)
    } else if d == q {
        let t = n - p;
        let g = gcd_int(&t, &d);
        if g.is_one() { (t, d) } else { (t / &g, d / g) }
    } else {
        let g = gcd_int(&d, &q);
        if g.is_one() {
            (&n * &q - &p * &d, d * q)
        } else {
            let d1 = &d / &g;
            let t = &n * (&q / &g) - &p * &d1;
            let g2 = gcd_int(&t, &g);
            if g2.is_one() { (t, d1 * q) } else { (t / &g2, d1 * (q / g2)) }
        }
    };
    *x = if numer.is_zero() {
        BigRational::new_raw(numer, BigInt::one())
    } else {
        BigRational::new_raw(numer, denom)
    };
}

impl Field for f64 {
    const NAME: &'static str = "float";
    const EXACT: bool = false;

    fn zero() -> Self {
        0.0
    }

    fn one() -> Self {
        1.0
    }

    fn is_zero(&self) -> bool {
        *self == 0.0
    }

    fn from_i64(v: i64) -> Self {
        v as f64
    }

    fn from_rational(q: &BigRational) -> Result<Self, RankError> {
        match q.to_f64() {
            Some(v) if v.is_finite() => Ok(v),
            _ => Err(RankError::NotRepresentable { field: Self::NAME, value: describe(q) }),
        }
    }

    fn from_rat(q: &Rat) -> Result<Self, RankError> {
        // A small value is at most 2^63 in magnitude: always finite.
        if q.is_small() { Ok(q.to_f64()) } else { Self::from_rational(&q.big_cow()) }
    }

    arithmetic_by_operators!();

    fn inv(&self) -> Option<Self> {
        if *self == 0.0 { None } else { Some(1.0 / self) }
    }

    fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
        *self -= a * b;
    }

    fn magnitude(&self) -> f64 {
        self.abs()
    }
}

/// The complex numbers in floating point: what a homotopy continuation tracks its paths in
/// (the constraints' laws never divide, so they evaluate over ℂ as over any field).
impl Field for Complex64 {
    const NAME: &'static str = "complex";
    const EXACT: bool = false;

    fn zero() -> Self {
        Complex64::new(0.0, 0.0)
    }

    fn one() -> Self {
        Complex64::new(1.0, 0.0)
    }

    fn is_zero(&self) -> bool {
        self.re == 0.0 && self.im == 0.0
    }

    fn from_i64(v: i64) -> Self {
        Complex64::new(v as f64, 0.0)
    }

    fn from_rational(q: &BigRational) -> Result<Self, RankError> {
        f64::from_rational(q).map(|re| Complex64::new(re, 0.0))
    }

    fn from_rat(q: &Rat) -> Result<Self, RankError> {
        f64::from_rat(q).map(|re| Complex64::new(re, 0.0))
    }

    arithmetic_by_operators!();

    fn inv(&self) -> Option<Self> {
        if Field::is_zero(self) { None } else { Some(Complex64::new(1.0, 0.0) / self) }
    }

    fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
        *self -= a * b;
    }

    fn magnitude(&self) -> f64 {
        self.norm()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn rational_sub_mul_matches_plain_arithmetic() {
        let values = [q(0, 1), q(1, 1), q(-3, 1), q(2, 3), q(-5, 6), q(7, 12), q(9, 4), q(1, 18)];
        for x in &values {
            for a in &values {
                for b in &values {
                    let mut y = x.clone();
                    y.sub_mul_assign(a, b);
                    let expected = x - a * b;
                    assert_eq!(y, expected, "{x} - {a}*{b}");
                    // the result is in lowest terms with a positive denominator
                    assert_eq!(y, BigRational::new(y.numer().clone(), y.denom().clone()));
                    assert!(y.denom().is_positive());
                }
            }
        }
    }

    #[test]
    fn float_conversion_rejects_overflow() {
        let huge = BigRational::from_integer(BigInt::from(10).pow(400u32));
        assert!(matches!(f64::from_rational(&huge), Err(RankError::NotRepresentable { .. })));
        assert_eq!(f64::from_rational(&q(-3, 4)), Ok(-0.75));
        assert_eq!(f64::from_rat(&Rat::from(&huge)), f64::from_rational(&huge));
        assert_eq!(f64::from_rat(&Rat::new(-3, 4).unwrap()), Ok(-0.75));
        assert_eq!(BigRational::from_rat(&Rat::new(-3, 4).unwrap()), Ok(q(-3, 4)));
        assert_eq!(BigRational::from_rat(&Rat::from(&huge)), Ok(huge));
    }

    #[test]
    fn inverses() {
        assert_eq!(Field::inv(&q(-2, 3)), Some(q(-3, 2)));
        assert_eq!(Field::inv(&q(0, 1)), None);
        assert_eq!(Field::inv(&0.0f64), None);
        assert_eq!(Field::inv(&4.0f64), Some(0.25));
    }
}
