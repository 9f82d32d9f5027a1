//! Exact rationals with GMP through `rug` (cargo feature `rug`).

use std::cell::RefCell;

use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use rug::integer::Order;
use rug::{Assign, Integer, Rational};

use crate::Field;
use crate::error::RankError;

thread_local! {
    /// Scratch space for `a * b` in [`Field::sub_mul_assign`], so that the hot loop reuses one
    /// GMP allocation per thread instead of allocating a product per call.
    static PRODUCT: RefCell<Rational> = RefCell::new(Rational::new());
}

fn integer_from_bigint(x: &BigInt) -> Integer {
    let (sign, digits) = x.to_u32_digits();
    let magnitude = Integer::from_digits(&digits, Order::Lsf);
    if sign == Sign::Minus { -magnitude } else { magnitude }
}

fn bigint_from_integer(x: &Integer) -> BigInt {
    let digits = x.to_digits::<u32>(Order::Lsf);
    let sign = match x.cmp0() {
        std::cmp::Ordering::Less => Sign::Minus,
        std::cmp::Ordering::Equal => Sign::NoSign,
        std::cmp::Ordering::Greater => Sign::Plus,
    };
    BigInt::from_slice(sign, &digits)
}

/// Converts a `rug::Rational` to a [`BigRational`] (exact; both are kept in lowest terms).
pub fn rug_to_big(q: &Rational) -> BigRational {
    BigRational::new_raw(bigint_from_integer(q.numer()), bigint_from_integer(q.denom()))
}

/// Converts a [`BigRational`] to a `rug::Rational` (exact).
pub fn big_to_rug(q: &BigRational) -> Rational {
    Rational::from((integer_from_bigint(q.numer()), integer_from_bigint(q.denom())))
}

impl Field for Rational {
    const NAME: &'static str = "rug";
    const EXACT: bool = true;

    fn zero() -> Self {
        Rational::new()
    }

    fn one() -> Self {
        Rational::from(1)
    }

    fn is_zero(&self) -> bool {
        Rational::is_zero(self)
    }

    fn from_i64(v: i64) -> Self {
        Rational::from(v)
    }

    fn from_rational(q: &BigRational) -> Result<Self, RankError> {
        Ok(big_to_rug(q))
    }

    fn add(&self, rhs: &Self) -> Self {
        Rational::from(self + rhs)
    }

    fn sub(&self, rhs: &Self) -> Self {
        Rational::from(self - rhs)
    }

    fn mul(&self, rhs: &Self) -> Self {
        Rational::from(self * rhs)
    }

    fn neg(&self) -> Self {
        Rational::from(-self)
    }

    fn inv(&self) -> Option<Self> {
        if Rational::is_zero(self) { None } else { Some(Rational::from(self.recip_ref())) }
    }

    fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
        if Rational::is_zero(a) || Rational::is_zero(b) {
            return;
        }
        PRODUCT.with(|cell| {
            let mut product = cell.borrow_mut();
            product.assign(a * b);
            *self -= &*product;
        });
    }

    fn magnitude(&self) -> f64 {
        self.to_f64().abs()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_round_trip() {
        let big = BigInt::from(3).pow(200u32);
        for q in [
            BigRational::new(BigInt::from(-7), BigInt::from(12)),
            BigRational::from_integer(BigInt::from(0)),
            BigRational::new(-big.clone(), big.clone() + 1),
            BigRational::new(big.clone(), BigInt::from(5)),
        ] {
            assert_eq!(rug_to_big(&big_to_rug(&q)), q);
        }
    }

    #[test]
    fn sub_mul_matches_plain_arithmetic() {
        let mut x = Rational::from((5, 6));
        x.sub_mul_assign(&Rational::from((2, 3)), &Rational::from((-9, 4)));
        assert_eq!(x, Rational::from((7, 3)));
        assert_eq!(Field::inv(&Rational::new()), None);
    }
}
