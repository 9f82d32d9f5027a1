//! Small dense exact linear algebra for the constructive placement of one entity (a handful of
//! unknowns), over ℚ or over the integers modulo 2^61 − 1, and rational approximations.

use std::iter::Sum;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use gcs_rank::{BigRational, Field, ModQ, RankError, Rat, modulus};

/// The exact number of the placement: a rational (small values stay in machine words), or an
/// integer modulo a prime ([`ModQ`]: the prime of the [`gcs_rank::with_modulus`] the placement
/// runs in, one of [`gcs_rank::WITNESS_PRIMES`] or [`gcs_rank::TURN_PRIME`], all `≡ 3 mod 4`)
/// when the placement runs over
/// that field (a *modular* witness: square
/// roots exist for half the residues, where a rational placement needs a perfect square).
///
/// A placement is in one field; constants written as rationals (`2`, `1/7`, approximations of
/// a direction) join a modular computation as their images modulo the prime.
pub(crate) type Q = Num;

/// A rational or a residue modulo the current prime (see [`Q`]).
#[derive(Clone, Debug)]
pub(crate) enum Num {
    /// An exact rational.
    R(Rat),
    /// A residue modulo the current prime.
    P(ModQ),
}

/// The image of a rational modulo the prime (a denominator the prime divides maps to 0: no
/// constant of the placement has one).
fn residue(r: &Rat) -> ModQ {
    ModQ::from_rat(r).unwrap_or_default()
}

impl Num {
    pub(crate) const ZERO: Num = Num::R(Rat::ZERO);
    pub(crate) const ONE: Num = Num::R(Rat::ONE);

    /// `num/den`, `None` for a zero denominator.
    pub(crate) fn new(num: i64, den: i64) -> Option<Num> {
        Rat::new(num, den).map(Num::R)
    }

    pub(crate) fn is_zero(&self) -> bool {
        match self {
            Num::R(r) => r.is_zero(),
            Num::P(p) => Field::is_zero(p),
        }
    }

    /// The value, for the placement's heuristics (which side, which is nearer): a residue has
    /// no size, and gives a pseudo-random value in `[−1, 1)`, which makes those choices random.
    pub(crate) fn to_f64(&self) -> f64 {
        match self {
            Num::R(r) => r.to_f64(),
            Num::P(p) => 2.0 * (p.value() as f64 / modulus() as f64) - 1.0,
        }
    }

    /// The exact square root when it exists: of a perfect square over ℚ; modulo the prime
    /// (every witness prime is `≡ 3 mod 4`: `a^((p+1)/4)`) for half the residues.
    pub(crate) fn sqrt_exact(&self) -> Option<Num> {
        match self {
            Num::R(r) => r.sqrt_exact().map(Num::R),
            Num::P(a) => {
                let mut e = (modulus() + 1) / 4;
                let (mut base, mut root) = (*a, ModQ::new(1));
                while e > 0 {
                    if e & 1 == 1 {
                        root = Field::mul(&root, &base);
                    }
                    base = Field::mul(&base, &base);
                    e >>= 1;
                }
                (Field::mul(&root, &root) == *a).then_some(Num::P(root))
            }
        }
    }

    /// The value over ℚ (`None` for a residue).
    pub(crate) fn rational(&self) -> Option<&Rat> {
        match self {
            Num::R(r) => Some(r),
            Num::P(_) => None,
        }
    }

    /// The residue (a rational is mapped to its image).
    pub(crate) fn modular(&self) -> ModQ {
        match self {
            Num::R(r) => residue(r),
            Num::P(p) => *p,
        }
    }

    fn binary(
        a: &Num,
        b: &Num,
        r: impl Fn(&Rat, &Rat) -> Rat,
        p: impl Fn(&ModQ, &ModQ) -> ModQ,
    ) -> Num {
        match (a, b) {
            (Num::R(x), Num::R(y)) => {
                count_work(x, y);
                Num::R(r(x, y))
            }
            (Num::P(x), Num::P(y)) => Num::P(p(x, y)),
            (Num::R(x), Num::P(y)) => Num::P(p(&residue(x), y)),
            (Num::P(x), Num::R(y)) => Num::P(p(x, &residue(y))),
        }
    }
}

thread_local! {
    /// The work of the rational operations of [`Num`] on this thread (see [`rational_work`]).
    static WORK: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// Counts an operation on two rationals with a big operand: the square of the larger one's
/// length in 64-bit words (the cost of multiplying, and of the gcds that keep a result in
/// lowest terms). Operations in machine words are not counted: their cost grows only with the
/// sketch's size, not with the heights a construction compounds.
fn count_work(x: &Rat, y: &Rat) {
    if x.is_small() && y.is_small() {
        return;
    }
    let words = x.height_bits().max(y.height_bits()) / 64 + 1;
    WORK.with(|w| w.set(w.get().wrapping_add(words * words)));
}

/// The work counted so far on this thread by the rational operations of [`Num`]: a measure of
/// the time spent in them that does not depend on the machine (differences of it bound the
/// placement over ℚ, see `place`).
pub(crate) fn rational_work() -> u64 {
    WORK.with(std::cell::Cell::get)
}

impl PartialEq for Num {
    fn eq(&self, other: &Num) -> bool {
        match (self, other) {
            (Num::R(x), Num::R(y)) => x == y,
            _ => self.modular() == other.modular(),
        }
    }
}

impl From<i64> for Num {
    fn from(v: i64) -> Num {
        Num::R(Rat::from(v))
    }
}

macro_rules! num_op {
    ($Op:ident, $op:ident, $r:expr, $p:expr) => {
        impl $Op<&Num> for &Num {
            type Output = Num;
            fn $op(self, rhs: &Num) -> Num {
                Num::binary(self, rhs, $r, $p)
            }
        }
        impl $Op<Num> for &Num {
            type Output = Num;
            fn $op(self, rhs: Num) -> Num {
                Num::binary(self, &rhs, $r, $p)
            }
        }
        impl $Op<&Num> for Num {
            type Output = Num;
            fn $op(self, rhs: &Num) -> Num {
                Num::binary(&self, rhs, $r, $p)
            }
        }
        impl $Op<Num> for Num {
            type Output = Num;
            fn $op(self, rhs: Num) -> Num {
                Num::binary(&self, &rhs, $r, $p)
            }
        }
    };
}

macro_rules! num_assign {
    ($OpAssign:ident, $op_assign:ident, $op:tt) => {
        impl $OpAssign<&Num> for Num {
            fn $op_assign(&mut self, rhs: &Num) {
                *self = &*self $op rhs;
            }
        }
        impl $OpAssign<Num> for Num {
            fn $op_assign(&mut self, rhs: Num) {
                *self = &*self $op &rhs;
            }
        }
    };
}

/// The quotient modulo the prime (0 for a zero divisor, which the placement never divides by
/// where it matters: it checks every result exactly).
fn div_mod(x: &ModQ, y: &ModQ) -> ModQ {
    y.inv().map_or(ModQ::default(), |i| Field::mul(x, &i))
}

num_op!(Add, add, |x, y| x + y, Field::add);
num_op!(Sub, sub, |x, y| x - y, Field::sub);
num_op!(Mul, mul, |x, y| x * y, Field::mul);
num_op!(Div, div, |x, y| x / y, div_mod);
num_assign!(AddAssign, add_assign, +);
num_assign!(SubAssign, sub_assign, -);

impl Neg for Num {
    type Output = Num;
    fn neg(self) -> Num {
        match self {
            Num::R(r) => Num::R(-r),
            Num::P(p) => Num::P(Field::neg(&p)),
        }
    }
}

impl Neg for &Num {
    type Output = Num;
    fn neg(self) -> Num {
        -(self.clone())
    }
}

impl Sum for Num {
    fn sum<I: Iterator<Item = Num>>(iter: I) -> Num {
        iter.fold(Num::ZERO, |a, b| a + b)
    }
}

impl<'a> Sum<&'a Num> for Num {
    fn sum<I: Iterator<Item = &'a Num>>(iter: I) -> Num {
        iter.fold(Num::ZERO, |a, b| a + b)
    }
}

impl Field for Num {
    const NAME: &'static str = "placement";
    const EXACT: bool = true;

    fn zero() -> Self {
        Num::ZERO
    }

    fn one() -> Self {
        Num::ONE
    }

    fn is_zero(&self) -> bool {
        Num::is_zero(self)
    }

    fn from_i64(v: i64) -> Self {
        Num::from(v)
    }

    fn from_rational(q: &BigRational) -> Result<Self, RankError> {
        Ok(Num::R(Rat::from(q)))
    }

    fn from_rat(q: &Rat) -> Result<Self, RankError> {
        Ok(Num::R(q.clone()))
    }

    gcs_rank::arithmetic_by_operators!();

    fn inv(&self) -> Option<Self> {
        match self {
            Num::R(r) => Field::inv(r).map(Num::R),
            Num::P(p) => p.inv().map(Num::P),
        }
    }

    fn sub_mul_assign(&mut self, a: &Self, b: &Self) {
        *self = &*self - &(a * b);
    }

    fn magnitude(&self) -> f64 {
        match self {
            Num::R(r) => r.magnitude(),
            Num::P(p) => p.magnitude(),
        }
    }
}

/// The solution set `{x0 + N t}` of a linear system.
#[derive(Clone, Debug)]
pub(crate) struct Affine {
    pub(crate) x0: Vec<Q>,
    /// Basis of the direction space, one vector per column.
    pub(crate) basis: Vec<Vec<Q>>,
}

/// Solves `a_i · x = b_i` in `n` unknowns; `None` when inconsistent.
pub(crate) fn solve(n: usize, rows: &[(Vec<Q>, Q)]) -> Option<Affine> {
    let mut m: Vec<Vec<Q>> = rows
        .iter()
        .map(|(a, b)| {
            let mut r = a.clone();
            r.resize(n, Q::ZERO);
            r.push(b.clone());
            r
        })
        .collect();
    let mut pivots = Vec::new();
    let mut r = 0;
    for col in 0..n {
        let Some(p) = (r..m.len()).find(|&i| !m[i][col].is_zero()) else { continue };
        m.swap(r, p);
        let inv = Q::ONE / &m[r][col];
        for v in m[r].iter_mut() {
            *v = &*v * &inv;
        }
        for i in 0..m.len() {
            if i != r && !m[i][col].is_zero() {
                let f = m[i][col].clone();
                let pivot_row = m[r].clone();
                for (x, y) in m[i].iter_mut().zip(&pivot_row) {
                    *x -= &f * y;
                }
            }
        }
        pivots.push(col);
        r += 1;
        if r == m.len() {
            break;
        }
    }
    if m[r..].iter().any(|row| !row[n].is_zero()) {
        return None;
    }
    let mut x0 = vec![Q::ZERO; n];
    for (i, &c) in pivots.iter().enumerate() {
        x0[c] = m[i][n].clone();
    }
    let mut basis = Vec::new();
    for f in (0..n).filter(|c| !pivots.contains(c)) {
        let mut v = vec![Q::ZERO; n];
        v[f] = Q::ONE;
        for (i, &c) in pivots.iter().enumerate() {
            v[c] = -m[i][f].clone();
        }
        basis.push(v);
    }
    Some(Affine { x0, basis })
}

impl Affine {
    pub(crate) fn point(&self, t: &[Q]) -> Vec<Q> {
        let mut x = self.x0.clone();
        for (v, ti) in self.basis.iter().zip(t) {
            for (xi, vi) in x.iter_mut().zip(v) {
                *xi += vi * ti;
            }
        }
        x
    }

    /// The parameters of the point of the set closest to `target` (least squares).
    pub(crate) fn project(&self, target: &[Q]) -> Vec<Q> {
        let k = self.basis.len();
        if k == 0 {
            return Vec::new();
        }
        let diff: Vec<Q> = target.iter().zip(&self.x0).map(|(a, b)| a - b).collect();
        let rows: Vec<(Vec<Q>, Q)> = (0..k)
            .map(|i| {
                let a = (0..k).map(|j| dot(&self.basis[i], &self.basis[j])).collect();
                (a, dot(&self.basis[i], &diff))
            })
            .collect();
        // The Gram matrix of a basis is invertible: a unique solution.
        solve(k, &rows).map(|s| s.x0).unwrap_or_else(|| vec![Q::ZERO; k])
    }
}

pub(crate) fn dot(a: &[Q], b: &[Q]) -> Q {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The rational square root of `q` when it has one.
pub(crate) fn sqrt(q: &Q) -> Option<Q> {
    q.sqrt_exact()
}

/// The rational `round(x · den) / den` (0 for a non-finite `x`).
pub(crate) fn approx(x: f64, den: i64) -> Q {
    Num::R(Rat::from_f64_approx(x, den.max(1)))
}

pub(crate) fn to_f64(q: &Q) -> f64 {
    q.to_f64()
}

/// Householder reflection `I − 2 v vᵀ / |v|²`: exactly orthogonal for any rational `v ≠ 0`.
pub(crate) fn reflection(v: &[Q]) -> Option<Vec<Vec<Q>>> {
    let vv = dot(v, v);
    if vv.is_zero() {
        return None;
    }
    let two = Q::from(2i64);
    let k = v.len();
    Some(
        (0..k)
            .map(|i| {
                (0..k)
                    .map(|j| {
                        let id = if i == j { Q::ONE } else { Q::ZERO };
                        id - &two * &v[i] * &v[j] / &vv
                    })
                    .collect()
            })
            .collect(),
    )
}

pub(crate) fn matmul(a: &[Vec<Q>], b: &[Vec<Q>]) -> Vec<Vec<Q>> {
    let k = b.first().map_or(0, Vec::len);
    a.iter()
        .map(|row| (0..k).map(|j| row.iter().zip(b).map(|(x, br)| x * &br[j]).sum()).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Q {
        Q::from(n)
    }

    #[test]
    fn solves_and_projects() {
        // x + y = 2: x0 = (2, 0), direction (−1, 1); closest to (0, 0) is (1, 1).
        let s = solve(2, &[(vec![q(1), q(1)], q(2))]).unwrap();
        assert_eq!(s.basis.len(), 1);
        let t = s.project(&[q(0), q(0)]);
        assert_eq!(s.point(&t), vec![q(1), q(1)]);
        assert!(solve(1, &[(vec![q(1)], q(1)), (vec![q(2)], q(3))]).is_none());
        assert_eq!(sqrt(&Q::new(9, 4).unwrap()), Q::new(3, 2));
        assert_eq!(sqrt(&q(2)), None);
        let r = reflection(&[q(1), q(2), q(2)]).unwrap();
        let rt = matmul(&r, &r);
        assert_eq!(rt[0][0], q(1));
        assert_eq!(rt[0][1], q(0));
    }
}
