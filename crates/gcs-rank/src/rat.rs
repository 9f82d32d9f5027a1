//! [`Rat`]: an exact rational number that stays in machine words while it is small and moves
//! to a [`BigRational`] only when it has to.

use std::borrow::Cow;
use std::cmp::Ordering;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::iter::{Product, Sum};
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{FromPrimitive, One, Signed, ToPrimitive, Zero};

use crate::Field;
use crate::error::RankError;
use crate::field::{reduced_product, subtract_fraction};
use crate::gcd::{gcd_int, gcd_u64, gcd_u128};

/// An exact rational number with an allocation-free fast path for small values.
///
/// A value whose numerator and denominator (in lowest terms, denominator positive) both fit in
/// an `i64` is stored as two machine words; arithmetic on such values runs in 128-bit integers
/// with binary gcds, and falls back to [`BigRational`] when a result does not fit. The
/// representation is canonical: a value that fits is *always* stored small, whatever
/// operations produced it (`(2^64/3)·(3/2^64)` is the small `1`), so equality and hashing
/// compare representations and never compute.
///
/// Arithmetic is exact and never overflows: the intermediates of two 64-bit fractions fit in
/// 128 bits. Integer operands skip every gcd for `+`, `−` and `×`, equal denominators skip the
/// cross products for `+` and `−`, products cancel across and sums use Knuth's gcd of the
/// denominators (*TAOCP* vol. 2, §4.5.1), so no gcd of a full 128-bit result is needed.
///
/// The `/` operator panics on a zero divisor, like integer division and [`BigRational`];
/// [`Rat::checked_div`], [`Rat::recip`] and [`Field::inv`] return `None` instead.
///
/// # Example
///
/// ```
/// use gcs_rank::Rat;
///
/// let a = Rat::new(1, 3).unwrap();
/// let b = Rat::from(-2);
/// assert_eq!((&a * &b + Rat::ONE).to_string(), "1/3");
/// assert_eq!(a.recip(), Some(Rat::from(3)));
///
/// // Overflow moves to big integers and back, exactly.
/// let big = Rat::from(i64::MAX) + Rat::ONE; // 2^63
/// assert!(!big.is_small());
/// let third = Rat::new(1, 3).unwrap();
/// assert_eq!(&big * &third * Rat::from(3) - Rat::from(i64::MAX), Rat::ONE);
/// ```
#[derive(Clone)]
pub struct Rat(Repr);

#[derive(Clone)]
enum Repr {
    /// `num/den` with `den > 0` and `gcd(|num|, den) = 1`.
    Small { num: i64, den: i64 },
    /// A value that is not representable as `Small`, in lowest terms with a positive
    /// denominator (the invariant of [`BigRational`]).
    Big(Box<BigRational>),
}

/// The fraction `num/den` (in lowest terms, `den > 0`) computed in 128-bit integers.
#[inline]
fn from_parts(num: i128, den: u128) -> Rat {
    debug_assert!(den > 0 && gcd_u128(num.unsigned_abs(), den) == 1);
    match (i64::try_from(num), i64::try_from(den)) {
        (Ok(num), Ok(den)) => Rat(Repr::Small { num, den }),
        _ => big_from_parts(num, den),
    }
}

#[cold]
#[inline(never)]
fn big_from_parts(num: i128, den: u128) -> Rat {
    Rat(Repr::Big(Box::new(BigRational::new_raw(BigInt::from(num), BigInt::from(den)))))
}

/// `n / g` for a divisor `0 < g < 2^63` of `n`, in 64-bit arithmetic when `n` fits (128-bit
/// division is a library call, several times slower).
#[inline]
fn div_exact(n: i128, g: u64) -> i128 {
    debug_assert!(g > 0 && g <= i64::MAX as u64 && n % g as i128 == 0);
    if g == 1 {
        n
    } else if let Ok(n) = i64::try_from(n) {
        (n / g as i64) as i128
    } else {
        n / g as i128
    }
}

/// `a/b + c/d` for fractions in lowest terms with `|a|, |c| ≤ 2^63` and `0 < b, d < 2^63`.
///
/// Every intermediate fits: `|a·d + c·b| < 2^127` and `b·d < 2^126`.
#[inline]
fn add_small(a: i128, b: u64, c: i128, d: u64) -> Rat {
    if b == d {
        let n = a + c;
        if b == 1 {
            return from_parts(n, 1);
        }
        let g = gcd_u128(n.unsigned_abs(), b as u128) as u64;
        return from_parts(div_exact(n, g), (b / g) as u128);
    }
    let g = if b == 1 || d == 1 { 1 } else { gcd_u64(b, d) };
    if g == 1 {
        // gcd(a·d + c·b, b·d) = 1 when gcd(b, d) = 1.
        return from_parts(a * d as i128 + c * b as i128, b as u128 * d as u128);
    }
    // Knuth: with g = gcd(b, d), t = a·(d/g) + c·(b/g), the only common factor of t and
    // (b/g)·d divides g.
    let (b1, d1) = (b / g, d / g);
    let t = a * d1 as i128 + c * b1 as i128;
    let g2 = gcd_u128(t.unsigned_abs(), g as u128) as u64;
    from_parts(div_exact(t, g2), b1 as u128 * (d / g2) as u128)
}

/// `(a/b)·(c/d)` for fractions in lowest terms with `b, d > 0`, as a numerator and denominator in
/// lowest terms, by cancelling across: `gcd(a, d)` and `gcd(c, b)`.
#[inline]
fn mul_parts(a: i64, b: i64, c: i64, d: i64) -> (i128, u128) {
    if b == 1 && d == 1 {
        return (a as i128 * c as i128, 1);
    }
    // Magnitudes, so that the divisions need no overflow check; most gcds of small values
    // are 1, and a skipped division saves its latency.
    let (ua, ub, uc, ud) = (a.unsigned_abs(), b as u64, c.unsigned_abs(), d as u64);
    let g1 = if ud == 1 { 1 } else { gcd_u64(ua, ud) };
    let g2 = if ub == 1 { 1 } else { gcd_u64(uc, ub) };
    let (ua, ud) = if g1 == 1 { (ua, ud) } else { (ua / g1, ud / g1) };
    let (uc, ub) = if g2 == 1 { (uc, ub) } else { (uc / g2, ub / g2) };
    let magnitude = (ua as u128 * uc as u128) as i128; // < 2^126
    let num = if (a < 0) != (c < 0) { -magnitude } else { magnitude };
    (num, ub as u128 * ud as u128)
}

/// `(a/b) / (c/d)` for fractions in lowest terms with `b, d > 0` and `c ≠ 0`.
#[inline]
fn div_small(a: i64, b: i64, c: i64, d: i64) -> Rat {
    // gcd(|a|, |c|) can be 2^63 (a = c = MIN): divide in 128 bits.
    let g1 = gcd_u64(a.unsigned_abs(), c.unsigned_abs()) as i128;
    let g2 = gcd_u64(b as u64, d as u64) as i64;
    let num = (a as i128 / g1) * (d / g2) as i128;
    let den = (b / g2) as u128 * (c as i128 / g1).unsigned_abs();
    from_parts(if c < 0 { -num } else { num }, den)
}

/// `n / g`, skipping the division when `g` is one.
fn div_by(n: &BigInt, g: &BigInt) -> BigInt {
    if g.is_one() { n.clone() } else { n / g }
}

/// The fraction `num/den` known to be in lowest terms with `den > 0`.
fn from_lowest(num: BigInt, den: BigInt) -> Rat {
    Rat::from(BigRational::new_raw(num, den))
}

/// `x ± y` with a big operand, in lowest terms by Knuth's rule (as [`add_small`]): with
/// `g = gcd(b, d)` and `t = a·(d/g) ± c·(b/g)`, only a divisor of `g` can divide both `t` and
/// the denominator, so the only gcds taken are of the denominators and of `t` with `g`, never
/// of the full numerator and denominator (num-rational's operators take that one too).
#[inline(never)]
fn big_add(x: &Rat, y: &Rat, subtract: bool) -> Rat {
    let (p, q) = (x.big_cow(), y.big_cow());
    let (a, b, c, d) = (p.numer(), p.denom(), q.numer(), q.denom());
    let combine = |l: BigInt, r: BigInt| if subtract { l - r } else { l + r };
    if b == d {
        let t = combine(a.clone(), c.clone());
        if t.is_zero() {
            return Rat::ZERO;
        }
        let g = gcd_int(&t, b);
        return from_lowest(div_by(&t, &g), div_by(b, &g));
    }
    let g = gcd_int(b, d);
    if g.is_one() {
        // gcd(a·d ± c·b, b·d) = 1 when gcd(b, d) = 1.
        let t = combine(a * d, c * b);
        if t.is_zero() {
            return Rat::ZERO;
        }
        return from_lowest(t, b * d);
    }
    let (b1, d1) = (b / &g, d / &g);
    let t = combine(a * &d1, c * &b1);
    if t.is_zero() {
        return Rat::ZERO;
    }
    let g2 = gcd_int(&t, &g);
    from_lowest(div_by(&t, &g2), b1 * div_by(d, &g2))
}

/// `x · y` (or `x / y` when `divide`, `y ≠ 0`) with a big operand, in lowest terms by
/// cancelling across (`gcd(a, d)` and `gcd(c, b)`), without the gcd of the full product.
#[inline(never)]
fn big_mul(x: &Rat, y: &Rat, divide: bool) -> Rat {
    let (p, q) = (x.big_cow(), y.big_cow());
    let (a, b) = (p.numer(), p.denom());
    // y or its reciprocal, as c/d with d > 0.
    let (c, d) = if divide {
        if q.numer().is_negative() {
            (-q.denom(), -q.numer())
        } else {
            (q.denom().clone(), q.numer().clone())
        }
    } else {
        (q.numer().clone(), q.denom().clone())
    };
    if a.is_zero() || c.is_zero() {
        return Rat::ZERO;
    }
    let g1 = gcd_int(a, &d);
    let g2 = gcd_int(&c, b);
    from_lowest(div_by(a, &g1) * div_by(&c, &g2), div_by(b, &g2) * div_by(&d, &g1))
}

impl Rat {
    /// Zero.
    pub const ZERO: Rat = Rat(Repr::Small { num: 0, den: 1 });
    /// One.
    pub const ONE: Rat = Rat(Repr::Small { num: 1, den: 1 });

    /// `num / den` in lowest terms, `None` when `den == 0`.
    ///
    /// Any pair of `i64` is accepted: `Rat::new(i64::MIN, -1)` is `2^63`, stored big.
    pub fn new(num: i64, den: i64) -> Option<Rat> {
        if den == 0 {
            return None;
        }
        let g = gcd_u64(num.unsigned_abs(), den.unsigned_abs()) as i128;
        let (num, den) = (num as i128 / g, den as i128 / g);
        Some(if den < 0 { from_parts(-num, (-den) as u128) } else { from_parts(num, den as u128) })
    }

    /// The numerator and denominator when the value is stored small (both fit in an `i64`),
    /// in lowest terms with a positive denominator.
    #[inline]
    pub fn as_small(&self) -> Option<(i64, i64)> {
        match self.0 {
            Repr::Small { num, den } => Some((num, den)),
            Repr::Big(_) => None,
        }
    }

    /// Whether the value is stored small, that is whether its numerator and denominator in
    /// lowest terms both fit in an `i64`.
    #[inline]
    pub fn is_small(&self) -> bool {
        matches!(self.0, Repr::Small { .. })
    }

    /// The value as a [`BigRational`].
    pub fn to_big(&self) -> BigRational {
        self.big_cow().into_owned()
    }

    /// The value as a [`BigRational`], borrowed when it is stored big.
    pub(crate) fn big_cow(&self) -> Cow<'_, BigRational> {
        match &self.0 {
            &Repr::Small { num, den } => {
                Cow::Owned(BigRational::new_raw(BigInt::from(num), BigInt::from(den)))
            }
            Repr::Big(q) => Cow::Borrowed(q),
        }
    }

    /// The height in bits: the larger bit length of the numerator and the denominator in
    /// lowest terms.
    pub fn height_bits(&self) -> u64 {
        match &self.0 {
            &Repr::Small { num, den } => {
                let bits = |v: u64| u64::from(u64::BITS - v.leading_zeros());
                bits(num.unsigned_abs()).max(bits(den.unsigned_abs()))
            }
            Repr::Big(q) => q.numer().bits().max(q.denom().bits()),
        }
    }

    /// The numerator in lowest terms (its sign is the sign of the value).
    pub fn numer(&self) -> BigInt {
        match &self.0 {
            &Repr::Small { num, .. } => BigInt::from(num),
            Repr::Big(q) => q.numer().clone(),
        }
    }

    /// The denominator in lowest terms (positive).
    pub fn denom(&self) -> BigInt {
        match &self.0 {
            &Repr::Small { den, .. } => BigInt::from(den),
            Repr::Big(q) => q.denom().clone(),
        }
    }

    /// The nearest `f64` (correctly rounded), `±∞` beyond the `f64` range.
    pub fn to_f64(&self) -> f64 {
        const EXACT: u64 = 1 << f64::MANTISSA_DIGITS;
        match &self.0 {
            // Both operands exact, so the one rounding of the division is the only one.
            &Repr::Small { num, den } if num.unsigned_abs() <= EXACT && den as u64 <= EXACT => {
                num as f64 / den as f64
            }
            // `to_f64` of a BigRational is only `None` for 0/0.
            _ => self.big_cow().to_f64().unwrap_or(f64::NAN),
        }
    }

    /// `round(x · den) / den` with the product and the rounding (half away from zero) in
    /// floating point: the fraction with denominator `den` nearest to `x`, reduced. Zero when
    /// `x` is not finite.
    ///
    /// # Panics
    /// When `den <= 0`.
    pub fn from_f64_approx(x: f64, den: i64) -> Rat {
        assert!(den > 0, "Rat::from_f64_approx: the denominator must be positive, got {den}");
        if !x.is_finite() {
            return Rat::ZERO;
        }
        let scaled = (x * den as f64).round();
        const TWO_63: f64 = (1u64 << 63) as f64;
        // -2^63 ≤ scaled < 2^63: the cast is exact.
        if (-TWO_63..TWO_63).contains(&scaled) {
            return Rat::new(scaled as i64, den).expect("den > 0");
        }
        match BigInt::from_f64(scaled) {
            Some(n) => Rat::from(BigRational::new(n, BigInt::from(den))),
            // x · den overflowed: x is then a (huge) integer and is its own rounding.
            None => Rat::from(BigRational::from_integer(
                BigInt::from_f64(x).expect("a finite f64 has an integer part"),
            )),
        }
    }

    /// Whether the value is zero.
    #[inline]
    pub fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Small { num: 0, .. })
    }

    /// Whether the value is an integer.
    pub fn is_integer(&self) -> bool {
        match &self.0 {
            Repr::Small { den, .. } => *den == 1,
            Repr::Big(q) => q.is_integer(),
        }
    }

    /// Whether the value is negative (zero is not).
    pub fn is_negative(&self) -> bool {
        match &self.0 {
            Repr::Small { num, .. } => *num < 0,
            Repr::Big(q) => q.is_negative(),
        }
    }

    /// `-1`, `0` or `1`, the sign of the value.
    pub fn signum(&self) -> Rat {
        let sign = match &self.0 {
            Repr::Small { num, .. } => num.signum(),
            Repr::Big(q) => {
                if q.is_negative() {
                    -1
                } else {
                    1
                }
            }
        };
        Rat::from(sign)
    }

    /// The absolute value.
    pub fn abs(&self) -> Rat {
        if self.is_negative() { -self } else { self.clone() }
    }

    /// `1 / self`, `None` for zero.
    pub fn recip(&self) -> Option<Rat> {
        match &self.0 {
            Repr::Small { num: 0, .. } => None,
            &Repr::Small { num, den } if num > 0 => Some(Rat(Repr::Small { num: den, den: num })),
            &Repr::Small { num, den } => {
                Some(from_parts(-(den as i128), num.unsigned_abs() as u128))
            }
            Repr::Big(q) => Some(Rat::from(q.recip())),
        }
    }

    /// `self / rhs`, `None` when `rhs` is zero.
    pub fn checked_div(&self, rhs: &Rat) -> Option<Rat> {
        if rhs.is_zero() { None } else { Some(self / rhs) }
    }

    /// `self^exp`, by repeated squaring (`0^0 = 1`).
    pub fn pow(&self, mut exp: u32) -> Rat {
        let mut base = self.clone();
        let mut acc = Rat::ONE;
        while exp > 0 {
            if exp & 1 == 1 {
                acc *= &base;
            }
            exp >>= 1;
            if exp > 0 {
                base = &base * &base;
            }
        }
        acc
    }

    /// The rational square root, when the value is the square of a rational: `Some(r)` with
    /// `r ≥ 0` and `r² = self`, `None` otherwise (negative values included).
    ///
    /// In lowest terms `p/q` is a square exactly when `p` and `q` are.
    pub fn sqrt_exact(&self) -> Option<Rat> {
        match &self.0 {
            &Repr::Small { num, den } => {
                if num < 0 {
                    return None;
                }
                let (r, s) = (num.isqrt(), den.isqrt());
                (r * r == num && s * s == den).then_some(Rat(Repr::Small { num: r, den: s }))
            }
            Repr::Big(q) => {
                if q.is_negative() {
                    return None;
                }
                let (r, s) = (q.numer().sqrt(), q.denom().sqrt());
                (&r * &r == *q.numer() && &s * &s == *q.denom())
                    .then(|| Rat::from(BigRational::new_raw(r, s)))
            }
        }
    }
}

impl Default for Rat {
    fn default() -> Self {
        Rat::ZERO
    }
}

impl From<i64> for Rat {
    #[inline]
    fn from(v: i64) -> Self {
        Rat(Repr::Small { num: v, den: 1 })
    }
}

impl From<i32> for Rat {
    #[inline]
    fn from(v: i32) -> Self {
        Rat::from(i64::from(v))
    }
}

impl From<BigRational> for Rat {
    /// Stores the value small when it fits. The [`BigRational`] is trusted to be in lowest
    /// terms, as every `BigRational` not built with `new_raw` is.
    fn from(q: BigRational) -> Self {
        match (q.numer().to_i64(), q.denom().to_i64()) {
            (Some(num), Some(den)) => Rat(Repr::Small { num, den }),
            _ => Rat(Repr::Big(Box::new(q))),
        }
    }
}

impl From<&BigRational> for Rat {
    fn from(q: &BigRational) -> Self {
        match (q.numer().to_i64(), q.denom().to_i64()) {
            (Some(num), Some(den)) => Rat(Repr::Small { num, den }),
            _ => Rat(Repr::Big(Box::new(q.clone()))),
        }
    }
}

impl From<Rat> for BigRational {
    fn from(q: Rat) -> Self {
        match q.0 {
            Repr::Small { num, den } => BigRational::new_raw(BigInt::from(num), BigInt::from(den)),
            Repr::Big(q) => *q,
        }
    }
}

impl From<&Rat> for BigRational {
    fn from(q: &Rat) -> Self {
        q.to_big()
    }
}

impl PartialEq for Rat {
    #[inline]
    fn eq(&self, other: &Self) -> bool {
        match (&self.0, &other.0) {
            (Repr::Small { num: a, den: b }, Repr::Small { num: c, den: d }) => a == c && b == d,
            // Both in lowest terms: compare the parts (BigRational's `==` cross-multiplies).
            (Repr::Big(p), Repr::Big(q)) => p.numer() == q.numer() && p.denom() == q.denom(),
            _ => false,
        }
    }
}

impl Eq for Rat {}

impl Hash for Rat {
    fn hash<H: Hasher>(&self, state: &mut H) {
        // Canonical form makes the parts a valid key (BigRational's own hash expands a
        // continued fraction).
        match &self.0 {
            Repr::Small { num, den } => {
                num.hash(state);
                den.hash(state);
            }
            Repr::Big(q) => {
                q.numer().hash(state);
                q.denom().hash(state);
            }
        }
    }
}

impl Ord for Rat {
    fn cmp(&self, other: &Self) -> Ordering {
        match (&self.0, &other.0) {
            (&Repr::Small { num: a, den: b }, &Repr::Small { num: c, den: d }) => {
                if b == d {
                    a.cmp(&c)
                } else {
                    (a as i128 * d as i128).cmp(&(c as i128 * b as i128))
                }
            }
            _ => self.big_cow().cmp(&other.big_cow()),
        }
    }
}

impl PartialOrd for Rat {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Display for Rat {
    /// `"3"`, `"-7/2"`: the format of [`BigRational`], padding and sign flags included.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Small { num, den: 1 } => fmt::Display::fmt(num, f),
            Repr::Small { num, den } => {
                f.pad_integral(*num >= 0, "", &format!("{}/{den}", num.unsigned_abs()))
            }
            Repr::Big(q) => fmt::Display::fmt(q, f),
        }
    }
}

impl fmt::Debug for Rat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Rat({self})")
    }
}

#[inline]
fn add_ref(x: &Rat, y: &Rat) -> Rat {
    match (&x.0, &y.0) {
        (&Repr::Small { num: a, den: b }, &Repr::Small { num: c, den: d }) => {
            add_small(a as i128, b as u64, c as i128, d as u64)
        }
        _ => big_add(x, y, false),
    }
}

#[inline]
fn sub_ref(x: &Rat, y: &Rat) -> Rat {
    match (&x.0, &y.0) {
        (&Repr::Small { num: a, den: b }, &Repr::Small { num: c, den: d }) => {
            add_small(a as i128, b as u64, -(c as i128), d as u64)
        }
        _ => big_add(x, y, true),
    }
}

#[inline]
fn mul_ref(x: &Rat, y: &Rat) -> Rat {
    match (&x.0, &y.0) {
        (&Repr::Small { num: a, den: b }, &Repr::Small { num: c, den: d }) => {
            let (num, den) = mul_parts(a, b, c, d);
            from_parts(num, den)
        }
        _ => big_mul(x, y, false),
    }
}

#[inline]
fn div_ref(x: &Rat, y: &Rat) -> Rat {
    match (&x.0, &y.0) {
        (_, Repr::Small { num: 0, .. }) => panic!("attempt to divide a Rat by zero"),
        (&Repr::Small { num: a, den: b }, &Repr::Small { num: c, den: d }) => div_small(a, b, c, d),
        _ => big_mul(x, y, true),
    }
}

#[inline]
fn neg_ref(x: &Rat) -> Rat {
    match &x.0 {
        &Repr::Small { num, den } if num != i64::MIN => Rat(Repr::Small { num: -num, den }),
        &Repr::Small { num, den } => from_parts(-(num as i128), den as u128),
        Repr::Big(q) => Rat::from(-&**q),
    }
}

/// The four owned/borrowed combinations of a binary operator and its two assignments.
macro_rules! binary_operator {
    ($Op:ident, $op:ident, $OpAssign:ident, $op_assign:ident, $core:ident) => {
        impl $Op<&Rat> for &Rat {
            type Output = Rat;
            #[inline]
            fn $op(self, rhs: &Rat) -> Rat {
                $core(self, rhs)
            }
        }

        impl $Op<Rat> for &Rat {
            type Output = Rat;
            #[inline]
            fn $op(self, rhs: Rat) -> Rat {
                $core(self, &rhs)
            }
        }

        impl $Op<&Rat> for Rat {
            type Output = Rat;
            #[inline]
            fn $op(self, rhs: &Rat) -> Rat {
                $core(&self, rhs)
            }
        }

        impl $Op<Rat> for Rat {
            type Output = Rat;
            #[inline]
            fn $op(self, rhs: Rat) -> Rat {
                $core(&self, &rhs)
            }
        }

        impl $OpAssign<&Rat> for Rat {
            #[inline]
            fn $op_assign(&mut self, rhs: &Rat) {
                *self = $core(self, rhs);
            }
        }

        impl $OpAssign<Rat> for Rat {
            #[inline]
            fn $op_assign(&mut self, rhs: Rat) {
                *self = $core(self, &rhs);
            }
        }
    };
}

binary_operator!(Add, add, AddAssign, add_assign, add_ref);
binary_operator!(Sub, sub, SubAssign, sub_assign, sub_ref);
binary_operator!(Mul, mul, MulAssign, mul_assign, mul_ref);
binary_operator!(Div, div, DivAssign, div_assign, div_ref);

impl Neg for Rat {
    type Output = Rat;
    #[inline]
    fn neg(self) -> Rat {
        match self.0 {
            Repr::Big(q) => Rat::from(-*q),
            _ => neg_ref(&self),
        }
    }
}

impl Neg for &Rat {
    type Output = Rat;
    #[inline]
    fn neg(self) -> Rat {
        neg_ref(self)
    }
}

impl Sum for Rat {
    fn sum<I: Iterator<Item = Rat>>(iter: I) -> Rat {
        iter.fold(Rat::ZERO, |acc, x| acc + x)
    }
}

impl<'a> Sum<&'a Rat> for Rat {
    fn sum<I: Iterator<Item = &'a Rat>>(iter: I) -> Rat {
        iter.fold(Rat::ZERO, |acc, x| acc + x)
    }
}

impl Product for Rat {
    fn product<I: Iterator<Item = Rat>>(iter: I) -> Rat {
        iter.fold(Rat::ONE, |acc, x| acc * x)
    }
}

impl<'a> Product<&'a Rat> for Rat {
    fn product<I: Iterator<Item = &'a Rat>>(iter: I) -> Rat {
        iter.fold(Rat::ONE, |acc, x| acc * x)
    }
}

impl Rat {
    /// `self -= a·b` through big integers, in place when `self` is already big.
    #[inline(never)]
    fn sub_mul_big(&mut self, a: &Rat, b: &Rat) {
        let (p, q) = reduced_product(&a.big_cow(), &b.big_cow());
        let mut x = match std::mem::replace(&mut self.0, Repr::Small { num: 0, den: 1 }) {
            Repr::Big(x) => x,
            Repr::Small { num, den } => {
                Box::new(BigRational::new_raw(BigInt::from(num), BigInt::from(den)))
            }
        };
        subtract_fraction(&mut x, p, q);
        *self = match (x.numer().to_i64(), x.denom().to_i64()) {
            (Some(num), Some(den)) => Rat(Repr::Small { num, den }),
            _ => Rat(Repr::Big(x)),
        };
    }
}

impl Field for Rat {
    const NAME: &'static str = "rat";
    const EXACT: bool = true;

    #[inline]
    fn zero() -> Self {
        Rat::ZERO
    }

    #[inline]
    fn one() -> Self {
        Rat::ONE
    }

    #[inline]
    fn is_zero(&self) -> bool {
        Rat::is_zero(self)
    }

    #[inline]
    fn from_i64(v: i64) -> Self {
        Rat::from(v)
    }

    fn from_rational(q: &BigRational) -> Result<Self, RankError> {
        Ok(Rat::from(q))
    }

    fn from_rat(q: &Rat) -> Result<Self, RankError> {
        Ok(q.clone())
    }

    #[inline]
    fn add(&self, rhs: &Self) -> Self {
        add_ref(self, rhs)
    }

    #[inline]
    fn sub(&self, rhs: &Self) -> Self {
        sub_ref(self, rhs)
    }

    #[inline]
    fn mul(&self, rhs: &Self) -> Self {
        mul_ref(self, rhs)
    }

    #[inline]
    fn neg(&self) -> Self {
        neg_ref(self)
    }

    fn inv(&self) -> Option<Self> {
        self.recip()
    }

    /// Without allocating when `self`, `a`, `b` and `a·b` are small.
    #[inline]
    fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
        if let (&Repr::Small { num: an, den: ad }, &Repr::Small { num: bn, den: bd }) = (&a.0, &b.0)
        {
            if an == 0 || bn == 0 {
                return;
            }
            if let Repr::Small { num, den } = self.0 {
                let (pn, pd) = mul_parts(an, ad, bn, bd);
                // The product fits when |pn| ≤ 2^63 and pd < 2^63 (see `add_small`).
                if pn.unsigned_abs() <= 1 << 63 && pd < 1 << 63 {
                    *self = add_small(num as i128, den as u64, -pn, pd as u64);
                    return;
                }
            }
        } else if a.is_zero() || b.is_zero() {
            return;
        }
        self.sub_mul_big(a, b);
    }

    fn magnitude(&self) -> f64 {
        self.to_f64().abs()
    }
}

#[cfg(test)]
mod tests {
    use std::collections::hash_map::DefaultHasher;

    use num_traits::One;

    use super::*;

    const MIN: i64 = i64::MIN;
    const MAX: i64 = i64::MAX;

    fn r(n: i64, d: i64) -> Rat {
        Rat::new(n, d).unwrap()
    }

    fn big(n: &BigInt, d: &BigInt) -> BigRational {
        BigRational::new(n.clone(), d.clone())
    }

    fn pow2(k: u32) -> BigInt {
        BigInt::one() << k
    }

    #[test]
    fn height_bits_is_the_longer_part_in_lowest_terms() {
        assert_eq!(Rat::ZERO.height_bits(), 1);
        assert_eq!(r(-5, 3).height_bits(), 3);
        assert_eq!(r(6, 16).height_bits(), 4, "3/8 in lowest terms: 8 has 4 bits");
        assert_eq!(r(MIN, 1).height_bits(), 64);
        let tall = Rat::from(big(&(pow2(200) + BigInt::one()), &pow2(100)));
        assert_eq!(tall.height_bits(), 201);
        assert_eq!(Rat::from(big(&BigInt::one(), &pow2(300))).height_bits(), 301);
    }

    /// `x` is stored small exactly when its parts fit, and its parts are in lowest terms.
    fn assert_canonical(x: &Rat) {
        let q = x.to_big();
        assert_eq!(q, BigRational::new(q.numer().clone(), q.denom().clone()), "{x:?} reduced");
        let fits = q.numer().to_i64().is_some() && q.denom().to_i64().is_some();
        assert_eq!(x.is_small(), fits, "{x:?}: small iff it fits");
        assert!(x.denom().is_positive());
    }

    fn hash_of(x: &Rat) -> u64 {
        let mut h = DefaultHasher::new();
        x.hash(&mut h);
        h.finish()
    }

    /// Small values at the boundaries, and big ones.
    fn samples() -> Vec<Rat> {
        let mut v: Vec<Rat> = [
            (0, 1),
            (1, 1),
            (-1, 1),
            (2, 3),
            (-5, 6),
            (MAX, 1),
            (MIN, 1),
            (MIN + 1, 1),
            (1, MAX),
            (-1, MAX),
            (MAX, MAX - 1),
            (MIN, MAX),
            (MIN + 1, MAX - 1),
            (1 << 62, 3),
            (3, 1 << 62),
            (-(1 << 62), 1),
            (MAX - 1, 1 << 61),
        ]
        .iter()
        .map(|&(n, d)| r(n, d))
        .collect();
        v.push(Rat::from(big(&pow2(63), &BigInt::one())));
        v.push(Rat::from(big(&-pow2(64), &BigInt::from(3))));
        v.push(Rat::from(big(&BigInt::from(7), &pow2(63))));
        v.push(Rat::from(big(&BigInt::from(3).pow(90), &BigInt::from(5).pow(40))));
        // Big values whose denominators share factors (the cancellations of the big sums and
        // products), with either sign.
        let (two, three, five, seven) =
            (BigInt::from(2), BigInt::from(3), BigInt::from(5), BigInt::from(7));
        v.push(Rat::from(big(&(pow2(70) * 3 + 1), &(five.pow(30) * 7))));
        v.push(Rat::from(big(&-three.pow(50), &(pow2(80) * 77))));
        v.push(Rat::from(big(&(pow2(65) + 1), &(two.pow(30) * three.pow(30)))));
        v.push(Rat::from(big(&(seven.pow(40) - BigInt::one()), &(five.pow(30) * 6))));
        let n: BigInt = five.pow(31) * 7 + 3;
        v.push(Rat::from(big(&-n, &(pow2(81) * 11))));
        v
    }

    #[test]
    fn constructors_reduce_and_normalise_signs() {
        assert_eq!(Rat::new(6, -4), Some(r(-3, 2)));
        assert_eq!(r(-6, -4).as_small(), Some((3, 2)));
        assert_eq!(r(0, -7).as_small(), Some((0, 1)));
        assert_eq!(Rat::new(1, 0), None);
        assert_eq!(r(MIN, MIN), Rat::ONE);
        assert_eq!(r(MIN, 2).as_small(), Some((MIN / 2, 1)));
        // 2^63 does not fit: MIN / -1 and 1 / MIN's reciprocal.
        let two63 = r(MIN, -1);
        assert!(!two63.is_small());
        assert_eq!(two63.to_big(), BigRational::from_integer(pow2(63)));
        assert_eq!(r(1, MIN).as_small(), None);
        assert_eq!(r(-1, MIN), Rat::from(big(&BigInt::one(), &pow2(63))));
        assert_eq!(r(2, MIN).as_small(), Some((-1, 1 << 62)));
        assert_eq!(Rat::default(), Rat::ZERO);
        assert_eq!(Rat::from(-3i32), r(-3, 1));
        for x in samples() {
            assert_canonical(&x);
            assert_eq!(Rat::from(x.to_big()), x);
            assert_eq!(Rat::from(&x.to_big()), x);
            assert_eq!(BigRational::from(x.clone()), x.to_big());
            assert_eq!(x.numer(), x.to_big().numer().clone());
            assert_eq!(x.denom(), x.to_big().denom().clone());
        }
        // A BigRational that fits is stored small.
        assert!(Rat::from(big(&BigInt::from(MIN), &BigInt::from(MAX))).is_small());
    }

    #[test]
    fn arithmetic_matches_big_rational_at_the_boundaries() {
        let values = samples();
        for x in &values {
            for y in &values {
                let (p, q) = (x.to_big(), y.to_big());
                let results = [
                    (x + y, &p + &q, "+"),
                    (x - y, &p - &q, "-"),
                    (x * y, &p * &q, "*"),
                    (-x, -&p, "neg"),
                    (x.abs(), p.abs(), "abs"),
                ];
                for (got, expected, op) in results {
                    assert_eq!(got.to_big(), expected, "{x} {op} {y}");
                    assert_canonical(&got);
                }
                if !y.is_zero() {
                    let got = x / y;
                    assert_eq!(got.to_big(), &p / &q, "{x} / {y}");
                    assert_canonical(&got);
                }
                let mut z = x.clone();
                z.sub_mul_assign(x, y);
                assert_eq!(z.to_big(), &p - &p * &q, "{x} - {x}*{y}");
                assert_canonical(&z);
                assert_eq!(x.cmp(y), p.cmp(&q), "{x} <=> {y}");
                assert_eq!(x == y, p == q, "{x} == {y}");
            }
        }
    }

    #[test]
    fn big_results_come_back_small() {
        // (2^62/3)·(3/2^62): small throughout.
        let a = r(1 << 62, 3);
        let b = r(3, 1 << 62);
        assert_eq!((&a * &b).as_small(), Some((1, 1)));
        // (2^64/3)·(3/2^64) = 1: both operands big, the product small.
        let a = Rat::from(big(&pow2(64), &BigInt::from(3)));
        let b = a.recip().unwrap();
        assert!(!a.is_small() && !b.is_small());
        assert_eq!((&a * &b).as_small(), Some((1, 1)));
        assert_eq!((&a / &a).as_small(), Some((1, 1)));
        assert_eq!((&a - &a).as_small(), Some((0, 1)));
        // 2^63 − 1 = MAX, and −2^63 = MIN, are small.
        let two63 = r(MIN, -1);
        assert_eq!((&two63 - Rat::ONE).as_small(), Some((MAX, 1)));
        assert_eq!((-&two63).as_small(), Some((MIN, 1)));
        assert_eq!((-two63.clone()).as_small(), Some((MIN, 1)));
        assert_eq!(r(-1, MIN).recip().unwrap().as_small(), None);
        assert_eq!(r(1, MIN).recip().unwrap().as_small(), Some((MIN, 1)));
        // In-place big elimination that lands on a small value.
        let mut x = two63.clone();
        x.sub_mul_assign(&two63, &Rat::ONE);
        assert_eq!(x.as_small(), Some((0, 1)));
        let mut x = a.clone();
        x.sub_mul_assign(&r(1, 3), &Rat::from(big(&pow2(64), &BigInt::one())));
        assert_eq!(x.as_small(), Some((0, 1)));
        // Overflow of the small path goes big, exactly.
        let m = Rat::from(MAX);
        assert_eq!((&m + &m).to_big(), BigRational::from_integer(BigInt::from(MAX) * 2));
        assert_eq!((&m * &m).to_big(), BigRational::from_integer(BigInt::from(MAX).pow(2)));
        let tiny = r(1, MAX);
        assert_eq!((&tiny * &tiny).denom(), BigInt::from(MAX).pow(2));
        let mut s = r(1, MAX);
        s.sub_mul_assign(&r(1, MAX - 1), &r(MIN, 3));
        assert_eq!(s.to_big(), r(1, MAX).to_big() - r(1, MAX - 1).to_big() * r(MIN, 3).to_big());
    }

    #[test]
    fn fast_paths_agree_with_the_general_ones() {
        // equal denominators, integers, coprime and non-coprime denominators
        assert_eq!(r(1, 6) + r(1, 6), r(1, 3));
        assert_eq!(r(1, 6) - r(7, 6), Rat::from(-1));
        assert_eq!(r(1, 6) + r(1, 10), r(4, 15));
        assert_eq!(r(1, 6) + r(5, 6), Rat::ONE);
        assert_eq!(r(3, 4) * r(2, 9), r(1, 6));
        assert_eq!(Rat::from(MAX) + Rat::from(MIN), Rat::from(-1));
        assert_eq!(r(3, 4) / r(-9, 8), r(-2, 3));
        assert_eq!(r(MIN, 1) / r(MIN, 1), Rat::ONE);
        assert_eq!(r(MIN, 1) / Rat::from(-1), r(MIN, -1));
    }

    #[test]
    fn assignments_sums_products_and_powers() {
        let mut x = r(1, 2);
        x += r(1, 3);
        x -= &r(1, 6);
        x *= r(9, 4);
        x /= &r(3, 2);
        assert_eq!(x, Rat::ONE);
        let v = [r(1, 2), r(1, 3), r(1, 6)];
        assert_eq!(v.iter().sum::<Rat>(), Rat::ONE);
        assert_eq!(v.iter().cloned().sum::<Rat>(), Rat::ONE);
        assert_eq!(v.iter().product::<Rat>(), r(1, 36));
        assert_eq!(v.into_iter().product::<Rat>(), r(1, 36));
        assert_eq!(r(-2, 3).pow(3), r(-8, 27));
        assert_eq!(r(5, 7).pow(0), Rat::ONE);
        assert_eq!(Rat::from(2).pow(64).to_big(), BigRational::from_integer(pow2(64)));
        assert_eq!(Rat::from(2).pow(63) / Rat::from(2).pow(62), Rat::from(2));
    }

    #[test]
    #[should_panic(expected = "divide a Rat by zero")]
    fn division_by_zero_panics() {
        let _ = r(1, 2) / Rat::ZERO;
    }

    #[test]
    fn zero_divisors_give_none_in_checked_forms() {
        assert_eq!(Rat::ZERO.recip(), None);
        assert_eq!(Field::inv(&Rat::ZERO), None);
        assert_eq!(r(1, 2).checked_div(&Rat::ZERO), None);
        assert_eq!(r(1, 2).checked_div(&r(1, 4)), Some(Rat::from(2)));
        assert_eq!(Field::inv(&r(-3, 5)), Some(r(-5, 3)));
    }

    #[test]
    fn predicates() {
        let b = Rat::from(big(&-pow2(70), &BigInt::one()));
        assert!(Rat::ZERO.is_zero() && !r(1, MAX).is_zero() && !b.is_zero());
        assert!(Rat::from(MIN).is_integer() && !r(1, 2).is_integer() && b.is_integer());
        assert!(!Rat::from(big(&pow2(70), &BigInt::from(3))).is_integer());
        assert!(r(-1, 2).is_negative() && !Rat::ZERO.is_negative() && b.is_negative());
        assert_eq!(
            [r(-1, MAX), Rat::ZERO, r(MAX, 2), b.clone()].map(|x| x.signum()),
            [-1i64, 0, 1, -1].map(Rat::from)
        );
        assert_eq!(b.abs(), -&b);
    }

    #[test]
    fn ordering_and_hashing_are_those_of_the_values() {
        let mut values = samples();
        values.sort();
        for w in values.windows(2) {
            assert!(w[0].to_big() < w[1].to_big(), "{} < {}", w[0], w[1]);
        }
        assert!(r(MAX, MAX - 1) < r(MAX - 1, MAX - 2));
        assert!(r(1, MAX) > r(1, MAX).pow(2));
        // Equal values built different ways are equal and hash equally.
        let pairs = [
            (r(2, 4), r(1, 3) + r(1, 6)),
            (r(MIN, -1) - Rat::ONE, Rat::from(MAX)),
            (Rat::from(2).pow(70) / Rat::from(2).pow(69), Rat::from(2)),
            (Rat::from(2).pow(70) * r(1, 3), Rat::from(big(&pow2(70), &BigInt::from(3)))),
        ];
        for (a, b) in &pairs {
            assert_eq!(a, b);
            assert_eq!(a.cmp(b), Ordering::Equal);
            assert_eq!(hash_of(a), hash_of(b));
        }
    }

    #[test]
    fn display_like_big_rational() {
        for x in samples() {
            assert_eq!(x.to_string(), x.to_big().to_string());
            assert_eq!(format!("{x:>60}"), format!("{:>60}", x.to_big()));
            assert_eq!(format!("{x:+}"), format!("{:+}", x.to_big()));
        }
        assert_eq!(Rat::from(3).to_string(), "3");
        assert_eq!(r(-7, 2).to_string(), "-7/2");
        assert_eq!(format!("{:?}", r(-7, 2)), "Rat(-7/2)");
    }

    #[test]
    fn floats() {
        assert_eq!(r(-3, 4).to_f64(), -0.75);
        assert_eq!(r(1, 3).to_f64(), 1.0 / 3.0);
        assert_eq!(Rat::from(MAX).to_f64(), MAX as f64);
        assert_eq!(r(MAX, MAX - 1).to_f64(), 1.0 + 2f64.powi(-63));
        assert_eq!(Rat::from(2).pow(2000).to_f64(), f64::INFINITY);
        assert_eq!(r(-1, 4).magnitude(), 0.25);
        assert_eq!(Rat::from_f64_approx(0.3333, 3), r(1, 3));
        assert_eq!(Rat::from_f64_approx(-2.5, 2), r(-5, 2));
        assert_eq!(Rat::from_f64_approx(0.125, 1000), r(1, 8));
        assert_eq!(Rat::from_f64_approx(f64::NAN, 7), Rat::ZERO);
        assert_eq!(Rat::from_f64_approx(f64::NEG_INFINITY, 7), Rat::ZERO);
        let scaled = BigInt::from_f64((1e30f64 * 1e6).round()).unwrap();
        assert_eq!(
            Rat::from_f64_approx(1e30, 1_000_000),
            Rat::from(BigRational::new(scaled, BigInt::from(1_000_000)))
        );
        let two63 = (1u64 << 63) as f64;
        assert_eq!(Rat::from_f64_approx(-two63, 1), Rat::from(MIN));
        assert_eq!(Rat::from_f64_approx(two63, 1), r(MIN, -1));
        assert!(!Rat::from_f64_approx(two63, 1).is_small());
        assert_eq!(Rat::from_f64_approx(f64::MAX, 1 << 20).to_f64(), f64::MAX);
    }

    #[test]
    fn exact_square_roots() {
        assert_eq!(r(9, 4).sqrt_exact(), Some(r(3, 2)));
        assert_eq!(Rat::ZERO.sqrt_exact(), Some(Rat::ZERO));
        assert_eq!(r(2, 1).sqrt_exact(), None);
        assert_eq!(r(1, 2).sqrt_exact(), None);
        assert_eq!(r(-4, 9).sqrt_exact(), None);
        let s = 3_037_000_499i64; // ⌊√MAX⌋
        assert_eq!(r(s * s, 1).sqrt_exact(), Some(Rat::from(s)));
        assert_eq!(r(s * s - 1, 1).sqrt_exact(), None);
        assert_eq!(Rat::from(MAX).sqrt_exact(), None);
        let b = Rat::from(big(&BigInt::from(3).pow(50), &BigInt::from(7).pow(30)));
        assert_eq!((&b * &b).sqrt_exact(), Some(b.clone()));
        assert_eq!((&b * &b * Rat::from(2)).sqrt_exact(), None);
        assert_eq!((-(&b * &b)).sqrt_exact(), None);
        // A big square whose root is small.
        let two32 = Rat::from(1i64 << 32);
        assert_eq!((&two32 * &two32).sqrt_exact().and_then(|x| x.as_small()), Some((1 << 32, 1)));
    }

    #[test]
    fn gcds() {
        let cases = [(0u64, 0u64), (0, 5), (12, 18), (1 << 40, 1 << 20), (u64::MAX, 3), (7, 7)];
        for (a, b) in cases {
            let expected = num_integer::Integer::gcd(&a, &b);
            assert_eq!(gcd_u64(a, b), expected, "gcd({a}, {b})");
            assert_eq!(gcd_u128(a as u128, b as u128), expected as u128);
        }
        let wide = (1u128 << 100) * 3;
        assert_eq!(gcd_u128(wide, 12), 12);
        assert_eq!(gcd_u128(6, wide), 6);
        assert_eq!(gcd_u128(wide, wide * 5), wide);
        assert_eq!(gcd_u128(u128::MAX, 0), u128::MAX);
    }
}
