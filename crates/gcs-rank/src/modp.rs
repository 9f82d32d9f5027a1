//! Prime fields: [`ModP`] modulo the Mersenne prime 2^61 − 1 (the fast exact path) and
//! [`ModPrime`] modulo any prime below 2^64 (the extra primes of multi-modular certification).

use num_bigint::{BigInt, Sign};
use num_rational::BigRational;

use crate::error::{RankError, describe};
use crate::{Field, Rat};

/// An integer modulo the Mersenne prime `2^61 − 1`, stored reduced in `[0, PRIME)`.
///
/// Multiplication reduces a 122-bit product with two shifts and masks instead of a division.
/// The rank of a rational matrix modulo a prime never exceeds its rank over ℚ and equals it
/// unless the prime divides the relevant minors, which for this prime is vanishingly unlikely;
/// [`analyse_rows_exact`](crate::analyse_rows_exact) turns "unlikely" into "proven".
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug, Default)]
pub struct ModP(u64);

/// An integer modulo the prime `P` (`2 < P < 2^64`), stored reduced in `[0, P)`.
///
/// Slower than [`ModP`] (one 128-bit remainder per product); used as the second and third
/// primes of multi-modular certification. `P` must be prime: nothing checks it, and
/// [`Field::inv`] gives wrong answers modulo a composite.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug, Default)]
pub struct ModPrime<const P: u64>(u64);

/// The residue of a big integer modulo `p`, by Horner's rule over its 64-bit digits.
pub(crate) fn bigint_mod(x: &BigInt, p: u64) -> u64 {
    let mut r: u64 = 0;
    for digit in x.magnitude().iter_u64_digits().rev() {
        r = ((((r as u128) << 64) | digit as u128) % p as u128) as u64;
    }
    if x.sign() == Sign::Minus && r != 0 { p - r } else { r }
}

/// The inverse of `a` (nonzero, reduced) modulo the prime `p`, by the extended Euclidean
/// algorithm.
pub(crate) fn inv_mod(a: u64, p: u64) -> u64 {
    let (mut t, mut new_t) = (0i128, 1i128);
    let (mut r, mut new_r) = (p as i128, a as i128);
    while new_r != 0 {
        let q = r / new_r;
        (t, new_t) = (new_t, t - q * new_t);
        (r, new_r) = (new_r, r - q * new_r);
    }
    if t < 0 { (t + p as i128) as u64 } else { t as u64 }
}

#[inline]
fn add_mod(a: u64, b: u64, p: u64) -> u64 {
    let s = a as u128 + b as u128;
    if s >= p as u128 { (s - p as u128) as u64 } else { s as u64 }
}

#[inline]
fn sub_mod(a: u64, b: u64, p: u64) -> u64 {
    if a >= b { a - b } else { a + (p - b) }
}

/// Reduction modulo `2^61 − 1` of a product of two reduced values (`x < 2^122`).
#[inline]
fn mersenne_reduce(x: u128) -> u64 {
    const P: u64 = ModP::PRIME;
    // 2^61 ≡ 1, so x = hi·2^61 + lo ≡ hi + lo.
    let folded = (x as u64 & P) + (x >> 61) as u64; // < 2^62
    let folded = (folded & P) + (folded >> 61); // ≤ 2^61
    if folded >= P { folded - P } else { folded }
}

/// The residue of the small rational `n/d` (`d > 0`) modulo `p`, in machine words.
fn small_rational_mod(q: &Rat, n: i64, d: i64, p: u64) -> Result<u64, RankError> {
    let d = d as u64 % p;
    if d == 0 {
        return Err(RankError::DenominatorDivisibleByPrime { prime: p, value: describe(q) });
    }
    let n = (n as i128).rem_euclid(p as i128) as u128;
    Ok(((n * inv_mod(d, p) as u128) % p as u128) as u64)
}

fn rational_mod(q: &BigRational, p: u64) -> Result<u64, RankError> {
    let d = bigint_mod(q.denom(), p);
    if d == 0 {
        return Err(RankError::DenominatorDivisibleByPrime { prime: p, value: describe(q) });
    }
    let n = bigint_mod(q.numer(), p);
    Ok(((n as u128 * inv_mod(d, p) as u128) % p as u128) as u64)
}

impl ModP {
    /// The modulus, `2^61 − 1`.
    pub const PRIME: u64 = (1 << 61) - 1;

    /// The residue of `v`.
    pub fn new(v: u64) -> Self {
        ModP(v % Self::PRIME)
    }

    /// The canonical representative, in `[0, PRIME)`.
    pub fn value(self) -> u64 {
        self.0
    }
}

impl<const P: u64> ModPrime<P> {
    /// The modulus `P`.
    pub const PRIME: u64 = P;

    /// The residue of `v`.
    pub fn new(v: u64) -> Self {
        ModPrime(v % P)
    }

    /// The canonical representative, in `[0, P)`.
    pub fn value(self) -> u64 {
        self.0
    }
}

impl std::fmt::Display for ModP {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} (mod {})", self.0, Self::PRIME)
    }
}

impl<const P: u64> std::fmt::Display for ModPrime<P> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} (mod {})", self.0, P)
    }
}

/// The parts of a prime-field implementation that do not depend on how products are reduced.
macro_rules! prime_field_common {
    ($ctor:expr, $p:expr) => {
        const NAME: &'static str = "modp";
        const EXACT: bool = true;

        fn zero() -> Self {
            $ctor(0)
        }

        fn one() -> Self {
            $ctor(1)
        }

        fn is_zero(&self) -> bool {
            self.0 == 0
        }

        fn from_i64(v: i64) -> Self {
            $ctor((v as i128).rem_euclid($p as i128) as u64)
        }

        fn from_rational(q: &BigRational) -> Result<Self, RankError> {
            rational_mod(q, $p).map($ctor)
        }

        fn from_rat(q: &Rat) -> Result<Self, RankError> {
            match q.as_small() {
                Some((n, d)) => small_rational_mod(q, n, d, $p).map($ctor),
                None => rational_mod(&q.big_cow(), $p).map($ctor),
            }
        }

        fn add(&self, rhs: &Self) -> Self {
            $ctor(add_mod(self.0, rhs.0, $p))
        }

        fn sub(&self, rhs: &Self) -> Self {
            $ctor(sub_mod(self.0, rhs.0, $p))
        }

        fn neg(&self) -> Self {
            $ctor(if self.0 == 0 { 0 } else { $p - self.0 })
        }

        fn inv(&self) -> Option<Self> {
            if self.0 == 0 { None } else { Some($ctor(inv_mod(self.0, $p))) }
        }

        fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
            let product = Field::mul(a, b);
            self.0 = sub_mod(self.0, product.0, $p);
        }

        fn magnitude(&self) -> f64 {
            if self.0 == 0 { 0.0 } else { 1.0 }
        }
    };
}

impl Field for ModP {
    prime_field_common!(ModP, ModP::PRIME);

    #[inline]
    fn mul(&self, rhs: &Self) -> Self {
        ModP(mersenne_reduce(self.0 as u128 * rhs.0 as u128))
    }
}

impl<const P: u64> Field for ModPrime<P> {
    prime_field_common!(ModPrime::<P>, P);

    #[inline]
    fn mul(&self, rhs: &Self) -> Self {
        ModPrime(((self.0 as u128 * rhs.0 as u128) % P as u128) as u64)
    }
}

#[cfg(test)]
mod tests {
    use num_traits::One;

    use super::*;

    type Big = ModPrime<18_446_744_073_709_551_557>; // 2^64 − 59

    #[test]
    fn mersenne_reduction_matches_remainder() {
        let p = ModP::PRIME;
        let samples = [0, 1, 2, p - 1, p - 2, 1 << 60, (1 << 61) - 2, 123_456_789_012_345];
        for &a in &samples {
            for &b in &samples {
                let (a, b) = (a % p, b % p);
                let expected = ((a as u128 * b as u128) % p as u128) as u64;
                assert_eq!(Field::mul(&ModP(a), &ModP(b)).0, expected, "{a} * {b}");
            }
        }
    }

    #[test]
    fn inverse_and_negative_values() {
        for v in [1i64, 2, -1, -7, 1 << 40, i64::MIN, i64::MAX] {
            let x = ModP::from_i64(v);
            let y = Big::from_i64(v);
            assert_eq!(Field::mul(&x, &x.inv().unwrap()), ModP::one());
            assert_eq!(Field::mul(&y, &y.inv().unwrap()), Big::one());
            assert_eq!(Field::add(&x, &x.neg()), ModP::zero());
            assert_eq!(Field::add(&y, &y.neg()), Big::zero());
            assert_eq!(Field::sub(&ModP::zero(), &x), x.neg());
        }
        assert_eq!(ModP::zero().inv(), None);
        // additions near 2^64 do not overflow
        let top = Big::from_i64(-1);
        assert_eq!(Field::add(&top, &top), Big::from_i64(-2));
    }

    #[test]
    fn rationals_map_and_denominators_divisible_by_p_fail() {
        let q = BigRational::new(BigInt::from(-3), BigInt::from(7));
        let x = ModP::from_rational(&q).unwrap();
        assert_eq!(Field::mul(&x, &ModP::from_i64(7)), ModP::from_i64(-3));
        let big = BigInt::from(ModP::PRIME) * BigInt::from(1u64 << 63) + 5;
        assert_eq!(ModP::from_rational(&BigRational::from_integer(big)).unwrap(), ModP(5));
        let bad = BigRational::new(BigInt::from(1), BigInt::from(ModP::PRIME) * 3);
        assert!(matches!(
            ModP::from_rational(&bad),
            Err(RankError::DenominatorDivisibleByPrime { prime: ModP::PRIME, .. })
        ));
    }

    #[test]
    fn rats_map_like_their_big_rational_values() {
        let p = ModP::PRIME as i64;
        let big = BigRational::new(BigInt::from(3).pow(80), BigInt::from(7).pow(30));
        let values = [
            Rat::new(-3, 7).unwrap(),
            Rat::new(i64::MIN, i64::MAX).unwrap(),
            Rat::new(i64::MAX, 2 * p).unwrap(),
            Rat::new(5, p - 1).unwrap(),
            Rat::from(-p),
            Rat::from(&big),
            Rat::ZERO,
        ];
        for q in &values {
            assert_eq!(ModP::from_rat(q), ModP::from_rational(&q.to_big()), "{q}");
            assert_eq!(Big::from_rat(q), Big::from_rational(&q.to_big()), "{q}");
        }
        for bad in [Rat::new(1, p).unwrap(), Rat::new(-7, 3 * p).unwrap()] {
            let error = ModP::from_rat(&bad).unwrap_err();
            assert_eq!(error, ModP::from_rational(&bad.to_big()).unwrap_err());
        }
        let bad = Rat::from(BigRational::new(BigInt::one(), BigInt::from(ModP::PRIME).pow(2)));
        assert!(!bad.is_small());
        assert!(matches!(ModP::from_rat(&bad), Err(RankError::DenominatorDivisibleByPrime { .. })));
    }
}
