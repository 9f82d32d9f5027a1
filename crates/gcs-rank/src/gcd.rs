//! Greatest common divisors: binary gcds on machine words, and Lehmer's algorithm on big
//! integers (what keeps [`crate::Rat`] and the [`num_rational::BigRational`] backend in lowest
//! terms).
//!
//! num-bigint's `gcd` is Stein's binary algorithm on whole numbers: every iteration shifts and
//! subtracts the full operands to remove about one bit, so two `n`-word operands cost about
//! `64·n` passes over `n` words, each with its own allocation. Lehmer's algorithm (Knuth,
//! *TAOCP* vol. 2, §4.5.2, Algorithm L) runs Euclid's algorithm on the leading 62 bits of the
//! operands in machine words for as long as the quotients it finds are provably those of the
//! full operands, then applies the accumulated 2×2 matrix to the full operands in one pass:
//! about 30 bits removed per pass instead of one.

use num_bigint::{BigInt, BigUint};
use num_traits::{One, ToPrimitive, Zero};

/// Binary gcd (Stein), after one remainder when the operands differ by 8 bits or more.
///
/// Measured on random operands, the binary loop is about twice as fast as Euclid's algorithm
/// with `%` when the operands have similar sizes (6, 20 or 63 bits), but it removes only about
/// one bit per iteration, so a small operand against a large one (a small denominator against
/// an accumulated one) is 2–3 times faster with one remainder first.
#[inline]
pub(crate) fn gcd_u64(a: u64, b: u64) -> u64 {
    if a == 0 || b == 0 {
        return a | b;
    }
    let (mut a, mut b) = if a < b { (a, b) } else { (b, a) };
    if a.leading_zeros() - b.leading_zeros() >= 8 {
        b %= a;
        if b == 0 {
            return a;
        }
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    b >>= b.trailing_zeros();
    while a != b {
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        let d = hi - lo;
        a = lo;
        b = d >> d.trailing_zeros();
    }
    a << shift
}

/// Gcd on 128-bit words: one remainder brings a wide operand down to the other's size, then the
/// 64-bit binary gcd finishes.
#[inline]
pub(crate) fn gcd_u128(a: u128, b: u128) -> u128 {
    if (a | b) >> 64 == 0 {
        return gcd_u64(a as u64, b as u64) as u128;
    }
    gcd_u128_wide(a, b)
}

#[inline(never)]
fn gcd_u128_wide(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        if (a | b) >> 64 == 0 {
            return gcd_u64(a as u64, b as u64) as u128;
        }
        (a, b) = (b, a % b);
    }
    a
}

/// The gcd of two big integers, non-negative (`gcd(0, 0) = 0`), equal to num-integer's
/// `Integer::gcd` and computed by Lehmer's algorithm.
pub(crate) fn gcd_int(a: &BigInt, b: &BigInt) -> BigInt {
    BigInt::from(gcd_uint(a.magnitude(), b.magnitude()))
}

/// The gcd of two big natural numbers (`gcd(0, 0) = 0`), by Lehmer's algorithm.
pub(crate) fn gcd_uint(a: &BigUint, b: &BigUint) -> BigUint {
    if a.is_zero() {
        return b.clone();
    }
    if b.is_zero() {
        return a.clone();
    }
    if a.is_one() || b.is_one() {
        return BigUint::one();
    }
    if let (Some(a), Some(b)) = (a.to_u64(), b.to_u64()) {
        return BigUint::from(gcd_u64(a, b));
    }
    let (mut u, mut v) = (a.to_u64_digits(), b.to_u64_digits());
    if less(&u, &v) {
        std::mem::swap(&mut u, &mut v);
    }
    from_limbs(&lehmer(u, v))
}

/// Euclid's algorithm on `(m, a)` (`m > a ≥ 0`) with the second cofactor, stopped at the
/// first remainder at most `bound`: the remainders `r0 > r1` and cofactors `t0, t1` (with
/// `r ≡ t·a mod m`) of that step, the same as step by step (Wang's rational reconstruction runs
/// this). While `r0` has more than 64 bits beyond `bound`, Lehmer's batches take many steps at
/// once: a batch's matrix has entries below 2^62, so its new `r0` is more than `r0 / 2^63` —
/// still above `bound` — and no batch passes the step where the plain loop stops. The last
/// steps, near the bound, are taken one at a time (and so are all of them once `r1` has no more
/// bits than `bound`: a bit count decides without building the number).
pub(crate) fn euclid_to_bound(
    m: &BigUint,
    a: &BigUint,
    bound: &BigUint,
) -> (BigUint, BigUint, BigInt, BigInt) {
    let (mut t0, mut t1) = (BigInt::zero(), BigInt::one());
    let mut u = m.to_u64_digits();
    let mut v = a.to_u64_digits();
    let bound_bits = bound.bits() as usize;
    while !v.is_empty() && bit_length(&v) > bound_bits && bit_length(&u) > bound_bits + 64 {
        let [a, b, c, d] = cosequence(&u, &v);
        if b == 0 {
            let (q, r) = num_integer::Integer::div_rem(&from_limbs(&u), &from_limbs(&v));
            let t = &t0 - BigInt::from(q) * &t1;
            (t0, t1) = (t1, t);
            (u, v) = (v, r.to_u64_digits());
        } else {
            let (t0n, t1n) = (&t0 * a + &t1 * b, &t0 * c + &t1 * d);
            (t0, t1) = (t0n, t1n);
            combine(&mut u, &mut v, [a, b, c, d]);
            normalise(&mut u);
            normalise(&mut v);
        }
    }
    let (mut r0, mut r1) = (from_limbs(&u), from_limbs(&v));
    while r1 > *bound {
        let (q, r) = num_integer::Integer::div_rem(&r0, &r1);
        (r0, r1) = (r1, r);
        let t = &t0 - BigInt::from(q) * &t1;
        (t0, t1) = (t1, t);
    }
    (r0, r1, t0, t1)
}

fn from_limbs(limbs: &[u64]) -> BigUint {
    let mut halves = Vec::with_capacity(2 * limbs.len());
    for &d in limbs {
        halves.push(d as u32);
        halves.push((d >> 32) as u32);
    }
    BigUint::new(halves)
}

/// `u < v` for normalised limb vectors (no leading zero limb), least significant limb first.
fn less(u: &[u64], v: &[u64]) -> bool {
    if u.len() != v.len() {
        return u.len() < v.len();
    }
    for (a, b) in u.iter().rev().zip(v.iter().rev()) {
        if a != b {
            return a < b;
        }
    }
    false
}

fn normalise(x: &mut Vec<u64>) {
    while x.last() == Some(&0) {
        x.pop();
    }
}

/// The bit length of a normalised, nonzero limb vector.
fn bit_length(x: &[u64]) -> usize {
    64 * x.len() - x[x.len() - 1].leading_zeros() as usize
}

/// The 64 bits of `x` from bit `k` on (zeros beyond its end).
fn bits_from(x: &[u64], k: usize) -> u64 {
    let (i, off) = (k / 64, k % 64);
    let lo = x.get(i).copied().unwrap_or(0);
    let hi = x.get(i + 1).copied().unwrap_or(0);
    ((u128::from(hi) << 64 | u128::from(lo)) >> off) as u64
}

/// `u mod d` for a one-word divisor.
fn rem_word(u: &[u64], d: u64) -> u64 {
    let d = u128::from(d);
    u.iter().rev().fold(0u128, |r, &x| ((r << 64) | u128::from(x)) % d) as u64
}

/// `(v, u mod v)`, the step of Euclid's algorithm on the full operands (num-bigint's
/// division), for a quotient too large for the leading words to find.
fn euclid_step(u: &[u64], v: Vec<u64>) -> (Vec<u64>, Vec<u64>) {
    let r = from_limbs(u) % from_limbs(&v);
    (v, r.to_u64_digits())
}

/// How many leading bits the single-precision steps see: with `û, v̂ < 2^62` the cosequence
/// stays below `2^62` in magnitude, so `û + A` and the products `q·C` fit in an `i64`.
const LEAD: usize = 62;

/// Lehmer's gcd of `u ≥ v`, both normalised limb vectors.
fn lehmer(mut u: Vec<u64>, mut v: Vec<u64>) -> Vec<u64> {
    loop {
        if v.is_empty() {
            return u;
        }
        if v.len() == 1 {
            return vec![gcd_u64(v[0], rem_word(&u, v[0]))];
        }
        let [a, b, c, d] = cosequence(&u, &v);
        if b == 0 {
            (u, v) = euclid_step(&u, v);
        } else {
            combine(&mut u, &mut v, [a, b, c, d]);
            normalise(&mut u);
            normalise(&mut v);
        }
    }
}

/// The matrix `[a, b, c, d]` of the steps of Euclid's algorithm that the leading 62 bits of
/// `u ≥ v` (normalised, `u` longer than one word) determine: the pair after them is
/// `(a·u + b·v, c·u + d·v)`; `b = 0` when not even one step is certain.
fn cosequence(u: &[u64], v: &[u64]) -> [i64; 4] {
    let k = bit_length(u) - LEAD;
    let (uh, vh) = (bits_from(u, k) as i64, bits_from(v, k) as i64);
    let mut state = [uh, vh, 1, 0, 0, 1];
    while let Some(next) = certain_step(state) {
        state = next;
    }
    let [_, _, a, b, c, d] = state;
    [a, b, c, d]
}

/// One step of Euclid's algorithm on the leading words `[û, v̂, a, b, c, d]` when they
/// determine the quotient of the full operands, `None` otherwise. Knuth's step L2: the full
/// operands' ratio lies between `(û + a)/(v̂ + c)` and `(û + b)/(v̂ + d)`, and the quotient is
/// certain when both give the same one. Every bound is checked for sign and overflow, so a
/// step taken is always a step of the full operands.
#[inline]
fn certain_step([uh, vh, a, b, c, d]: [i64; 6]) -> Option<[i64; 6]> {
    let (n1, n2) = (uh.checked_add(a)?, uh.checked_add(b)?);
    let (d1, d2) = (vh.checked_add(c)?, vh.checked_add(d)?);
    if n1 < 0 || n2 < 0 || d1 <= 0 || d2 <= 0 {
        return None;
    }
    let q = quotient(n1, d1);
    // q = ⌊n2/d2⌋, checked by multiplying (a second division costs more than the rest).
    let low = q.checked_mul(d2)?;
    if low > n2 || n2 - low >= d2 {
        return None;
    }
    let next = |x: i64, y: i64| x.checked_sub(q.checked_mul(y)?);
    Some([vh, next(uh, vh)?, c, d, next(a, c)?, next(b, d)?])
}

/// `⌊n/d⌋` for `n ≥ 0`, `d > 0`: by subtraction for the small quotients that make most of
/// Euclid's algorithm (1, 2 and 3 are two thirds of them), by a division otherwise.
#[inline]
fn quotient(n: i64, d: i64) -> i64 {
    let mut r = n;
    for q in 0..4 {
        if r < d {
            return q;
        }
        r -= d;
    }
    n / d
}

/// `(u, v) ← (a·u + b·v, c·u + d·v)` in one pass, for a cosequence of Euclid's algorithm
/// (`a` and `b` of opposite signs or zero, likewise `c` and `d`; both results non-negative).
fn combine(u: &mut [u64], v: &mut Vec<u64>, [a, b, c, d]: [i64; 4]) {
    v.resize(u.len(), 0);
    let (a, b, c, d) = (i128::from(a), i128::from(b), i128::from(c), i128::from(d));
    let (mut carry_u, mut carry_v) = (0i128, 0i128);
    for (x, y) in u.iter_mut().zip(v.iter_mut()) {
        let (ux, vx) = (i128::from(*x), i128::from(*y));
        // |a·ux + b·vx| < 2^126 since a and b have opposite signs, and |carry| < 2^63.
        let tu = a * ux + b * vx + carry_u;
        let tv = c * ux + d * vx + carry_v;
        *x = tu as u64;
        *y = tv as u64;
        carry_u = tu >> 64;
        carry_v = tv >> 64;
    }
    debug_assert!(carry_u == 0 && carry_v == 0, "the cosequence keeps both results in range");
}

#[cfg(test)]
mod tests {
    use num_integer::Integer;

    use super::*;

    /// A deterministic xorshift, for reproducible random operands.
    struct Rng(u64);

    impl Rng {
        fn next(&mut self) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0
        }

        fn big(&mut self, bits: u64) -> BigUint {
            let words = bits.div_ceil(64) as usize;
            let digits: Vec<u64> = (0..words).map(|_| self.next()).collect();
            from_limbs(&digits) >> (64 * words as u64 - bits)
        }
    }

    fn check(a: &BigUint, b: &BigUint) {
        let expected = a.gcd(b);
        assert_eq!(gcd_uint(a, b), expected, "gcd({a}, {b})");
        assert_eq!(gcd_uint(b, a), expected, "gcd({b}, {a})");
        let (x, y) = (BigInt::from(a.clone()), -BigInt::from(b.clone()));
        assert_eq!(gcd_int(&x, &y), x.gcd(&y), "gcd({x}, {y})");
        assert_eq!(gcd_int(&-&x, &-&y), x.gcd(&y), "gcd(-{x}, -{y})");
    }

    #[test]
    fn machine_word_gcds_match_euclid() {
        fn euclid(mut a: u128, mut b: u128) -> u128 {
            while b != 0 {
                (a, b) = (b, a % b);
            }
            a
        }
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let edge = [0u64, 1, 2, 3, 6, 1 << 63, u64::MAX, u64::MAX - 1, 1 << 32, 3 << 40];
        for &a in &edge {
            for &b in &edge {
                assert_eq!(u128::from(gcd_u64(a, b)), euclid(a.into(), b.into()), "{a} {b}");
            }
        }
        for _ in 0..10_000 {
            let g = rng.next() >> (rng.next() % 64);
            let (a, b) = (rng.next() >> (rng.next() % 64), rng.next() >> (rng.next() % 64));
            let (a, b) = (a.wrapping_mul(g), b.wrapping_mul(g));
            assert_eq!(u128::from(gcd_u64(a, b)), euclid(a.into(), b.into()), "{a} {b}");
            let (a, b) = ((u128::from(a) << 64) | u128::from(b), u128::from(b) * u128::from(g));
            assert_eq!(gcd_u128(a, b), euclid(a, b), "{a} {b}");
        }
    }

    #[test]
    fn edge_cases_match_num_integer() {
        let zero = BigUint::zero();
        let one = BigUint::one();
        let huge = BigUint::from(3u32).pow(2000) * BigUint::from(7u32).pow(300);
        let pow2 = |k: u32| BigUint::one() << k;
        for x in [&zero, &one, &huge, &pow2(64), &pow2(1000), &(pow2(128) - 1u32)] {
            check(&zero, x);
            check(&one, x);
            check(x, x);
            check(&huge, x);
        }
        check(&pow2(1000), &pow2(999));
        check(&(pow2(1000) - 1u32), &(pow2(500) - 1u32));
        check(&(pow2(1000) + 1u32), &(pow2(1000) - 1u32));
        check(&pow2(4000), &(pow2(130) * 3u32));
        // Words of all ones and all zeros (bit patterns at the leading-word boundary).
        check(&((pow2(640) - 1u32) << 64u32), &((pow2(576) - 1u32) << 128u32));
    }

    /// Consecutive Fibonacci numbers are Euclid's worst case: every quotient is 1, and the
    /// leading words run out of certain quotients as slowly as possible.
    #[test]
    fn consecutive_fibonacci_numbers() {
        let (mut f0, mut f1) = (BigUint::zero(), BigUint::one());
        for n in 1..3000 {
            (f0, f1) = (f1.clone(), f0 + &f1);
            if n % 97 == 0 || n > 2990 {
                check(&f1, &f0);
                check(&(&f1 * 6u32), &(&f0 * 10u32));
            }
        }
    }

    #[test]
    fn random_operands_with_planted_common_factors() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        for i in 0..3000 {
            let bits = [1, 63, 64, 65, 127, 128, 129, 200, 700, 1500, 5000];
            let pick = |rng: &mut Rng| bits[(rng.next() % bits.len() as u64) as usize];
            let (a, b, g) = (pick(&mut rng), pick(&mut rng), pick(&mut rng));
            let (a, b) = (rng.big(a), rng.big(b));
            if i % 2 == 0 {
                let g = rng.big(g) | BigUint::one();
                check(&(&a * &g), &(&b * &g));
            } else {
                check(&a, &b);
            }
        }
    }
}
