//! Prime fields: [`ModP`] modulo the Mersenne prime 2^61 − 1 (the fast exact path) and
//! [`ModPrime`] modulo any prime below 2^64 (the extra primes of multi-modular certification).

use std::cell::Cell;
use std::sync::Mutex;

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
/// algorithm: in 64-bit words for `p < 2^63` (every coefficient is at most `p` in magnitude), in
/// 128-bit ones otherwise (several times slower: the divisions are library calls).
pub(crate) fn inv_mod(a: u64, p: u64) -> u64 {
    if let (Ok(p), Ok(a)) = (i64::try_from(p), i64::try_from(a)) {
        let (mut t, mut new_t) = (0i64, 1i64);
        let (mut r, mut new_r) = (p, a);
        while new_r != 0 {
            let q = r / new_r;
            (t, new_t) = (new_t, t - q * new_t);
            (r, new_r) = (new_r, r - q * new_r);
        }
        return if t < 0 { (t + p) as u64 } else { t as u64 };
    }
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
    // (|n| ≤ 2^63 and p < 2^64: the residue of the magnitude, in 64-bit words.)
    let m = n.unsigned_abs() % p;
    let n = if n < 0 && m != 0 { p - m } else { m };
    if d == 1 {
        return Ok(n);
    }
    Ok(((n as u128 * inv_mod(d, p) as u128) % p as u128) as u64)
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

    /// `self + (−a)·b` folded once, branch-free: for `self < 2^62` and canonical `−a`, `b`,
    /// the sum is at most `2^62 − 1 + (2^61 − 1)^2 = 2^122`, and `lo + hi` of it is below
    /// `2^61 + 2^61 = 2^62` again — so values stay below `2^62` step after step.
    #[inline]
    fn sub_mul_unsettled(&mut self, _a: &Self, neg_a: &Self, b: &Self) {
        const P: u64 = ModP::PRIME;
        let t = self.0 as u128 + neg_a.0 as u128 * b.0 as u128;
        self.0 = (t as u64 & P) + (t >> 61) as u64;
    }

    #[inline]
    fn settle(&mut self) {
        const P: u64 = ModP::PRIME;
        // self < 2^62: one fold leaves at most 2^61, one subtraction a canonical value.
        let folded = (self.0 & P) + (self.0 >> 61);
        self.0 = if folded >= P { folded - P } else { folded };
    }
}

impl<const P: u64> Field for ModPrime<P> {
    prime_field_common!(ModPrime::<P>, P);

    #[inline]
    fn mul(&self, rhs: &Self) -> Self {
        ModPrime(((self.0 as u128 * rhs.0 as u128) % P as u128) as u64)
    }
}

thread_local! {
    /// The modulus of [`ModQ`] on this thread, set by [`with_modulus`].
    static MODULUS: Cell<u64> = const { Cell::new(ModP::PRIME) };
}

/// An integer modulo a prime chosen at run time: the many primes of multi-modular lifting,
/// which a const generic cannot enumerate, and the primes of a modular witness
/// ([`WITNESS_PRIMES`]). The modulus is per thread and is set for the duration of a closure
/// by [`with_modulus`] (outside any, it is [`ModP::PRIME`]).
///
/// A value means nothing outside the closure it was made in: callers keep residues inside it
/// and let only plain numbers (ranks, indices, [`ModQ::value`]) out.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Default)]
pub struct ModQ(u64);

impl ModQ {
    /// The residue of `v` modulo the current prime.
    pub fn new(v: u64) -> Self {
        ModQ(v % modulus())
    }

    /// The canonical representative, in `[0, modulus())`.
    pub fn value(self) -> u64 {
        self.0
    }
}

/// The modulus of [`ModQ`] on this thread.
pub fn modulus() -> u64 {
    MODULUS.with(Cell::get)
}

/// The primes a modular witness is built over, in the order tried: first the Mersenne prime
/// of [`ModP`] (the fast one), then primes `≡ 3 (mod 4)` just below `2^61` (a square root is
/// one power), the first of which has every prime up to 23 as a square. A construction whose
/// numbers are forced irrational (an equilateral triangle needs `√3`, a regular octagon `√2`)
/// has a modular point only where those are squares: `3` is none modulo `2^61 − 1`, and each
/// further prime is a further chance, about one in two per square root.
pub const WITNESS_PRIMES: [u64; 4] =
    [ModP::PRIME, 2_305_843_009_213_682_039, 2_305_843_009_213_682_027, 2_305_843_009_213_681_999];

/// The number of turns [`TURN_PRIME`] carries exactly: `lcm(1, …, 36)`.
pub const TURN_PERIOD: u64 = 144_403_552_893_600;

/// The prime of the last-resort modular witness, `15959 · TURN_PERIOD − 1`: `≡ 3 (mod 4)` like
/// the other witness primes (a square root is one power), and the points of the unit circle
/// modulo it (the norm-one elements of `𝔽_{p²}`, `p + 1` of them) include a turn by `k/N` of a
/// full turn for every `N ≤ 36`: the cosine and sine of 360°/N, irrational over ℚ for N other
/// than 1, 2 and 4, are residues modulo it, with every relation between them that holds over
/// the reals (`cos 60° = 1/2`, the turn by 30° twice is the turn by 60°). A regular hexagon or
/// a circular pattern of 6 has a point there.
pub const TURN_PRIME: u64 = 2_304_536_300_628_962_399;

/// A prime field: its prime, and its elements from and to machine words.
pub trait PrimeField: Field + Copy {
    /// The prime (for [`ModQ`], the current one).
    fn prime() -> u64;
    /// The residue of `v`.
    fn residue(v: u64) -> Self;
    /// The canonical representative, in `[0, prime)`.
    fn representative(self) -> u64;
}

impl PrimeField for ModP {
    fn prime() -> u64 {
        ModP::PRIME
    }
    fn residue(v: u64) -> Self {
        ModP::new(v)
    }
    fn representative(self) -> u64 {
        self.0
    }
}

impl<const P: u64> PrimeField for ModPrime<P> {
    fn prime() -> u64 {
        P
    }
    fn residue(v: u64) -> Self {
        ModPrime::new(v)
    }
    fn representative(self) -> u64 {
        self.0
    }
}

impl PrimeField for ModQ {
    fn prime() -> u64 {
        modulus()
    }
    fn residue(v: u64) -> Self {
        ModQ::new(v)
    }
    fn representative(self) -> u64 {
        self.0
    }
}

/// Runs `f` with the modulus of [`ModQ`] set to the prime `q` on this thread (restored after,
/// even on unwinding). `q` must be prime: nothing checks it.
pub fn with_modulus<R>(q: u64, f: impl FnOnce() -> R) -> R {
    struct Restore(u64);
    impl Drop for Restore {
        fn drop(&mut self) {
            MODULUS.with(|m| m.set(self.0));
        }
    }
    let _restore = Restore(MODULUS.with(|m| m.replace(q)));
    f()
}

impl Field for ModQ {
    prime_field_common!(ModQ, modulus());

    #[inline]
    fn mul(&self, rhs: &Self) -> Self {
        let (product, q) = (self.0 as u128 * rhs.0 as u128, modulus());
        // The Mersenne prime keeps its fast reduction (a modular witness is built over it first).
        ModQ(if q == ModP::PRIME { mersenne_reduce(product) } else { (product % q as u128) as u64 })
    }
}

/// `b^e mod m` for `m < 2^64`.
fn pow_mod(mut b: u64, mut e: u64, m: u64) -> u64 {
    let mul = |x: u64, y: u64| ((x as u128 * y as u128) % m as u128) as u64;
    let mut r = 1 % m;
    b %= m;
    while e > 0 {
        if e & 1 == 1 {
            r = mul(r, b);
        }
        b = mul(b, b);
        e >>= 1;
    }
    r
}

/// Deterministic Miller–Rabin: the first twelve prime bases decide every `n < 3.3·10^24`.
pub(crate) fn is_prime(n: u64) -> bool {
    const BASES: [u64; 12] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37];
    if n < 2 {
        return false;
    }
    for b in BASES {
        if n.is_multiple_of(b) {
            return n == b;
        }
    }
    let (mut d, mut s) = (n - 1, 0);
    while d % 2 == 0 {
        d /= 2;
        s += 1;
    }
    BASES.iter().all(|&a| {
        let mut x = pow_mod(a, d, n);
        if x == 1 || x == n - 1 {
            return true;
        }
        for _ in 1..s {
            x = ((x as u128 * x as u128) % n as u128) as u64;
            if x == n - 1 {
                return true;
            }
        }
        false
    })
}

/// The primes of multi-modular lifting after [`ModP::PRIME`]: `2^64 − 59`, `2^63 − 25`, then the
/// primes below `2^62` in decreasing order. `nth_lifting_prime(0)` is `2^64 − 59`. Generated on
/// demand (a few dozen Miller–Rabin tests each) and kept for the life of the process.
pub(crate) fn nth_lifting_prime(k: usize) -> u64 {
    static PRIMES: Mutex<Vec<u64>> = Mutex::new(Vec::new());
    let mut primes = match PRIMES.lock() {
        Ok(guard) => guard,
        Err(poisoned) => poisoned.into_inner(),
    };
    if primes.is_empty() {
        primes.extend([crate::SECOND_PRIME, crate::THIRD_PRIME]);
    }
    while primes.len() <= k {
        let last = *primes.last().unwrap_or(&(1 << 62));
        let mut n = if last > 1 << 62 { (1 << 62) - 1 } else { last - 2 };
        while !is_prime(n) {
            n -= 2;
        }
        primes.push(n);
    }
    primes[k]
}

#[cfg(test)]
mod tests {
    use num_traits::One;

    use super::*;

    type Big = ModPrime<18_446_744_073_709_551_557>; // 2^64 − 59

    #[test]
    fn unsettled_steps_settle_to_the_canonical_residue() {
        // Chains of unsettled steps against the canonical ones, on the extreme operands (the
        // bound 2^62 is reached only by products near (p − 1)^2) and on pseudo-random ones.
        let p = ModP::PRIME;
        let edges = [0, 1, 2, p / 2, p - 2, p - 1];
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % p
        };
        for round in 0..200 {
            let (mut lazy, mut exact) = (ModP::new(next()), ModP::new(0));
            exact = exact.add(&lazy);
            for step in 0..500 {
                let (a, b) = if round < 36 {
                    (edges[round % 6], edges[(round / 6 + step) % 6])
                } else {
                    (next(), next())
                };
                let (a, b) = (ModP::new(a), ModP::new(b));
                lazy.sub_mul_unsettled(&a, &a.neg(), &b);
                assert!(lazy.0 < 1 << 62, "unsettled value {} past 2^62", lazy.0);
                exact.sub_mul_assign(&a, &b);
                let mut settled = lazy;
                settled.settle();
                assert_eq!(settled, exact, "round {round}, step {step}");
            }
        }
        // Every representative below 2^62 settles: 0, p, 2p, 2^62 − 1.
        for (x, r) in [(0, 0), (p, 0), (2 * p, 0), ((1 << 62) - 1, 1)] {
            let mut v = ModP(x);
            v.settle();
            assert_eq!(v.0, r, "{x}");
        }
    }

    #[test]
    fn inverses_and_small_fractions_in_either_word_size() {
        // 2^61 − 1 and the turn prime take the 64-bit path, 2^64 − 59 the 128-bit one.
        for p in [ModP::PRIME, crate::TURN_PRIME, 18_446_744_073_709_551_557] {
            for a in [1, 2, 3, 12_345, p / 3, p - 2, p - 1] {
                let inv = inv_mod(a, p);
                assert!(inv < p);
                assert_eq!((a as u128 * inv as u128) % p as u128, 1, "{a} mod {p}");
            }
            for (n, d) in
                [(0, 1), (5, 1), (-5, 1), (i64::MIN, 1), (i64::MAX, 3), (-7, 9), (i64::MIN, 5)]
            {
                let q = Rat::new(n, d).unwrap();
                let (n, d) = q.as_small().unwrap();
                let r = small_rational_mod(&q, n, d, p).unwrap();
                // r · d ≡ n (mod p).
                let n_mod = (n as i128).rem_euclid(p as i128) as u128;
                assert_eq!((r as u128 * d as u128) % p as u128, n_mod, "{q:?} mod {p}");
            }
        }
    }

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

    #[test]
    fn lifting_primes_are_distinct_large_primes() {
        assert!(is_prime(ModP::PRIME) && is_prime(crate::SECOND_PRIME));
        assert!(!is_prime(1) && !is_prime(91) && !is_prime(3_215_031_751) && is_prime(2));
        // 2^62 − 57 is the largest prime below 2^62.
        assert_eq!(nth_lifting_prime(2), (1 << 62) - 57);
        let primes: Vec<u64> = (0..40).map(nth_lifting_prime).collect();
        assert_eq!(primes[..2], [crate::SECOND_PRIME, crate::THIRD_PRIME]);
        assert!(primes[2..].windows(2).all(|w| w[0] > w[1] && w[1] > 1 << 61));
        assert!(primes.iter().all(|p| is_prime(*p) && *p != ModP::PRIME));
    }

    #[test]
    fn run_time_moduli_agree_with_const_ones() {
        let q = BigRational::new(BigInt::from(-1234567), BigInt::from(89));
        let x = with_modulus(crate::SECOND_PRIME, || {
            let x = ModQ::from_rational(&q).unwrap();
            assert_eq!(Field::mul(&x, &x.inv().unwrap()), ModQ::one());
            Field::mul(&x, &ModQ::from_i64(-5)).value()
        });
        let y = Field::mul(&Big::from_rational(&q).unwrap(), &Big::from_i64(-5)).value();
        assert_eq!(x, y);
        // the modulus is restored afterwards
        assert_eq!(modulus(), ModP::PRIME);
    }
}
