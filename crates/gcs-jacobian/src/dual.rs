//! Forward-mode automatic differentiation: dual numbers with a gradient over the few local
//! unknowns of one constraint.
//!
//! A constraint's equations are evaluated once on dual numbers whose values are the witness
//! coordinates of the entities it binds; the value part gives the residual at the witness and
//! the gradient part is the Jacobian row over those unknowns, exactly, in any field. No
//! derivative is written by hand.

use std::ops::{Add, Mul, Neg, Sub};

use gcs_rank::Field;

/// A value and its gradient over local variables `0..n`. A gradient shorter than `n` has
/// implicit zeros at the end (constants have an empty gradient).
#[derive(Clone, Debug, PartialEq)]
pub struct Dual<F> {
    /// The value at the evaluation point.
    pub value: F,
    /// Partial derivatives with respect to the local variables.
    pub grad: Vec<F>,
}

impl<F: Field> Dual<F> {
    /// A constant.
    pub fn constant(value: F) -> Self {
        Dual { value, grad: Vec::new() }
    }

    /// A constant from a small integer.
    pub fn int(v: i64) -> Self {
        Dual::constant(F::from_i64(v))
    }

    /// Local variable `index` (of `n`) at `value`.
    pub fn variable(value: F, index: usize, n: usize) -> Self {
        let mut grad = vec![F::zero(); n.max(index + 1)];
        grad[index] = F::one();
        Dual { value, grad }
    }

    /// `self * k` for a constant `k`.
    pub fn scale(&self, k: &F) -> Self {
        Dual { value: self.value.mul(k), grad: self.grad.iter().map(|g| g.mul(k)).collect() }
    }

    /// `a * self - b * other`, the combination used for ratio derivatives.
    fn combine(a: &F, x: &Self, b: &F, y: &Self) -> Self {
        let n = x.grad.len().max(y.grad.len());
        let zero = F::zero();
        let grad = (0..n)
            .map(|i| {
                let gx = x.grad.get(i).unwrap_or(&zero);
                let gy = y.grad.get(i).unwrap_or(&zero);
                a.mul(gx).sub(&b.mul(gy))
            })
            .collect();
        Dual { value: a.mul(&x.value).sub(&b.mul(&y.value)), grad }
    }

    /// A row proportional to the gradient of `p / q` at the evaluation point, when `q ≠ 0`:
    /// `q·∇p − p·∇q` (the factor `1/q²` does not change a rank). Its value is `p·q`, which
    /// vanishes exactly when `p` does.
    pub fn ratio(p: &Self, q: &Self) -> Self {
        let mut d = Dual::combine(&q.value, p, &p.value, q);
        d.value = p.value.mul(&q.value);
        d
    }

    /// A row proportional to the gradient of `p / √q` at the evaluation point, when `q > 0`:
    /// `2q·∇p − p·∇q` (rational although `√q` may not be). This is how a signed distance or a
    /// cosine is differentiated exactly without a square root. Its value is `p`.
    pub fn ratio_sqrt(p: &Self, q: &Self) -> Self {
        let two_q = q.value.add(&q.value);
        let mut d = Dual::combine(&two_q, p, &p.value, q);
        d.value = p.value.clone();
        d
    }

    /// Whether the gradient is identically zero.
    pub fn is_singular(&self) -> bool {
        self.grad.iter().all(Field::is_zero)
    }
}

/// Real functions, for measures (square roots, angles) in `f64`.
impl Dual<f64> {
    /// `f(self)`, with `df` the derivative of `f`.
    pub fn map(&self, f: impl Fn(f64) -> f64, df: impl Fn(f64) -> f64) -> Self {
        let d = df(self.value);
        Dual { value: f(self.value), grad: self.grad.iter().map(|g| g * d).collect() }
    }

    /// `self / other`.
    pub fn over(&self, other: &Self) -> Self {
        let (a, b) = (self.value, other.value);
        let mut d = Dual::combine(&(1.0 / b), self, &(a / (b * b)), other);
        d.value = a / b;
        d
    }

    /// The angle of the vector `(x, y)`, `atan2(y, x)`, in radians.
    pub fn atan2(y: &Self, x: &Self) -> Self {
        let r2 = x.value * x.value + y.value * y.value;
        let scale = if r2 > 0.0 { 1.0 / r2 } else { 0.0 };
        let mut d = Dual::combine(&(x.value * scale), y, &(y.value * scale), x);
        d.value = y.value.atan2(x.value);
        d
    }
}

fn zip_grad<F: Field>(a: &[F], b: &[F], f: impl Fn(&F, &F) -> F) -> Vec<F> {
    let n = a.len().max(b.len());
    let zero = F::zero();
    (0..n)
        .map(|i| {
            let (x, y) = (a.get(i).unwrap_or(&zero), b.get(i).unwrap_or(&zero));
            match (x.is_zero(), y.is_zero()) {
                (true, true) => F::zero(),
                // f is addition or subtraction: f(x, 0) = x.
                (false, true) => x.clone(),
                _ => f(x, y),
            }
        })
        .collect()
}

impl<F: Field> Add for &Dual<F> {
    type Output = Dual<F>;
    fn add(self, rhs: &Dual<F>) -> Dual<F> {
        Dual { value: self.value.add(&rhs.value), grad: zip_grad(&self.grad, &rhs.grad, F::add) }
    }
}

impl<F: Field> Sub for &Dual<F> {
    type Output = Dual<F>;
    fn sub(self, rhs: &Dual<F>) -> Dual<F> {
        Dual { value: self.value.sub(&rhs.value), grad: zip_grad(&self.grad, &rhs.grad, F::sub) }
    }
}

impl<F: Field> Mul for &Dual<F> {
    type Output = Dual<F>;
    fn mul(self, rhs: &Dual<F>) -> Dual<F> {
        let (a, b) = (&self.value, &rhs.value);
        let n = self.grad.len().max(rhs.grad.len());
        let zero = F::zero();
        let (a_zero, b_zero) = (a.is_zero(), b.is_zero());
        // Product rule, skipping the zero terms (exact big rationals make every operation
        // costly, and Jacobians are mostly zeros).
        let grad = (0..n)
            .map(|i| {
                let ga = self.grad.get(i).unwrap_or(&zero);
                let gb = rhs.grad.get(i).unwrap_or(&zero);
                match (ga.is_zero() || b_zero, gb.is_zero() || a_zero) {
                    (true, true) => F::zero(),
                    (false, true) => ga.mul(b),
                    (true, false) => a.mul(gb),
                    (false, false) => ga.mul(b).add(&a.mul(gb)),
                }
            })
            .collect();
        Dual { value: a.mul(b), grad }
    }
}

impl<F: Field> Neg for &Dual<F> {
    type Output = Dual<F>;
    fn neg(self) -> Dual<F> {
        Dual { value: self.value.neg(), grad: self.grad.iter().map(F::neg).collect() }
    }
}

impl<F: Field> Add for Dual<F> {
    type Output = Dual<F>;
    fn add(self, rhs: Dual<F>) -> Dual<F> {
        &self + &rhs
    }
}

impl<F: Field> Sub for Dual<F> {
    type Output = Dual<F>;
    fn sub(self, rhs: Dual<F>) -> Dual<F> {
        &self - &rhs
    }
}

impl<F: Field> Mul for Dual<F> {
    type Output = Dual<F>;
    fn mul(self, rhs: Dual<F>) -> Dual<F> {
        &self * &rhs
    }
}

impl<F: Field> Neg for Dual<F> {
    type Output = Dual<F>;
    fn neg(self) -> Dual<F> {
        -&self
    }
}

/// Small vector algebra on duals (2D and 3D).
pub(crate) mod vec {
    use super::Dual;
    use gcs_rank::Field;

    pub(crate) fn sub<F: Field>(a: &[Dual<F>], b: &[Dual<F>]) -> Vec<Dual<F>> {
        a.iter().zip(b).map(|(x, y)| x - y).collect()
    }

    pub(crate) fn add<F: Field>(a: &[Dual<F>], b: &[Dual<F>]) -> Vec<Dual<F>> {
        a.iter().zip(b).map(|(x, y)| x + y).collect()
    }

    pub(crate) fn dot<F: Field>(a: &[Dual<F>], b: &[Dual<F>]) -> Dual<F> {
        let mut acc = Dual::int(0);
        for (x, y) in a.iter().zip(b) {
            acc = &acc + &(x * y);
        }
        acc
    }

    pub(crate) fn norm2<F: Field>(a: &[Dual<F>]) -> Dual<F> {
        dot(a, a)
    }

    /// The 2D cross product `a.x b.y − a.y b.x`.
    pub(crate) fn cross2<F: Field>(a: &[Dual<F>], b: &[Dual<F>]) -> Dual<F> {
        &(&a[0] * &b[1]) - &(&a[1] * &b[0])
    }

    pub(crate) fn cross3<F: Field>(a: &[Dual<F>], b: &[Dual<F>]) -> Vec<Dual<F>> {
        vec![
            &(&a[1] * &b[2]) - &(&a[2] * &b[1]),
            &(&a[2] * &b[0]) - &(&a[0] * &b[2]),
            &(&a[0] * &b[1]) - &(&a[1] * &b[0]),
        ]
    }

    pub(crate) fn scale<F: Field>(a: &[Dual<F>], k: &Dual<F>) -> Vec<Dual<F>> {
        a.iter().map(|x| x * k).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcs_rank::BigRational;

    fn q(n: i64) -> BigRational {
        BigRational::from_i64(n)
    }

    #[test]
    fn product_rule_and_ratios() {
        // f(x, y) = x^2 y at (3, 2): value 18, gradient (12, 9).
        let x = Dual::variable(q(3), 0, 2);
        let y = Dual::variable(q(2), 1, 2);
        let f = &(&x * &x) * &y;
        assert_eq!(f.value, q(18));
        assert_eq!(f.grad, vec![q(12), q(9)]);
        // d(x/y) ∝ y∇x − x∇y = (2, −3).
        assert_eq!(Dual::ratio(&x, &y).grad, vec![q(2), q(-3)]);
        // d(x/√y) ∝ 2y∇x − x∇y = (4, −3).
        assert_eq!(Dual::ratio_sqrt(&x, &y).grad, vec![q(4), q(-3)]);
        let c = Dual::<BigRational>::int(5);
        assert!((&c * &x).grad == vec![q(5), q(0)]);
        assert!(c.is_singular());
    }
}
