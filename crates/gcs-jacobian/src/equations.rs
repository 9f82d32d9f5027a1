//! The constraint equations as a public API: residuals and Jacobian rows of any constraints at
//! any configuration — one set of equations for the analysis, the witness projection and a
//! solver.
//!
//! - [`Equations::rows`]: the rows of a constraint at a configuration in any [`Field`]:
//!   residuals of parameter-free constraints (which vanish where the constraint holds) and, for
//!   metric constraints, rows proportional to the gradient of the measure (rational in the
//!   coordinates: what a rank needs).
//! - [`Equations::residual`]: in `f64`, what a solver minimises: the residuals of a
//!   parameter-free constraint, or the measure minus the user's value for a metric one
//!   (lengths in model units, angles in degrees; measures need square roots and trigonometry,
//!   hence `f64`), each with its gradient.
//! - [`Equations::internal`]: the entity-internal rows (normalisations, Plücker relations).
//!
//! # Example
//! ```
//! use gcs_jacobian::{Equations, Layout};
//! let s = gcs_model::System::from_ron_str(r#"System(dim: 2,
//!     entities: [Point(id: "p", at: [0, 0]), Point(id: "q", at: [3, 4])],
//!     constraints: [Distance(id: "d", a: "p", b: "q", value: 6)])"#, None).unwrap();
//! let layout = Layout::new(&s);
//! let eq = Equations::new(&s, &layout);
//! let x = [0.0, 0.0, 3.0, 4.0];
//! let r = eq.residual(s.constraint_by_id("d").unwrap(), &x).unwrap();
//! assert!((r.values[0] - (5.0 - 6.0)).abs() < 1e-12);
//! // The gradient of |q − p| with respect to (px, py, qx, qy).
//! let g: Vec<f64> = r.rows[0].entries().iter().map(|(_, v)| *v).collect();
//! assert!(g.iter().zip([-0.6, -0.8, 0.6, 0.8]).all(|(a, b)| (a - b).abs() < 1e-12));
//! ```

use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rank::{BigRational, Field, SparseRow};
use num_traits::ToPrimitive;

use crate::dual::Dual;
use crate::laws;
use crate::layout::Layout;
use crate::views::Local;

/// The equations of a system over the columns of a [`Layout`], with the branch of every
/// constraint that has several (external or internal tangency, skew or parallel lines).
#[derive(Clone, Debug)]
pub struct Equations<'s> {
    system: &'s System,
    layout: &'s Layout,
    variants: Vec<usize>,
}

/// The residual rows of one constraint at a configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct Residual<F> {
    /// The constraint.
    pub constraint: ConstraintIdx,
    /// One value per equation: the residual of each equation of a parameter-free constraint,
    /// or the measure minus the value of a metric one.
    pub values: Vec<F>,
    /// The gradient of each value over the columns.
    pub rows: Vec<SparseRow<F>>,
}

impl<F: Field> Residual<F> {
    /// The largest value in magnitude.
    pub fn magnitude(&self) -> f64 {
        self.values.iter().map(Field::magnitude).fold(0.0, f64::max)
    }
}

fn grad_row<F: Field>(d: &Dual<F>, cols: &[usize]) -> SparseRow<F> {
    SparseRow::from_entries(
        d.grad
            .iter()
            .enumerate()
            .filter(|(_, g)| !g.is_zero())
            .map(|(i, g)| (cols[i], g.clone()))
            .collect(),
    )
}

impl<'s> Equations<'s> {
    /// The equations of `system`, every constraint in its first branch.
    pub fn new(system: &'s System, layout: &'s Layout) -> Self {
        Equations { system, layout, variants: vec![0; system.constraints().len()] }
    }

    /// The equations with every constraint in the branch whose residuals are smallest at `x`
    /// (the side of a tangency a drawing shows).
    pub fn with_branches_at(mut self, x: &[f64]) -> Self {
        let none = |_: EntityIdx| None;
        for ci in self.system.constraint_indices() {
            let local = self.local(ci, x);
            let sig = self.system.constraint(ci).signature;
            let count = laws::law(sig, 0, &local, &none, false).variants;
            let residual = |v| -> f64 {
                laws::law(sig, v, &local, &none, false).rows.iter().map(|r| r.value.abs()).sum()
            };
            self.variants[ci.index()] = (0..count)
                .map(|v| (residual(v), v))
                .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a })
                .1;
        }
        self
    }

    /// The branch of a constraint.
    pub fn branch(&self, c: ConstraintIdx) -> usize {
        self.variants[c.index()]
    }

    fn local<F: Field>(&self, c: ConstraintIdx, x: &[F]) -> Local<'s, F> {
        let base = self.system.constraint_base_entities(c);
        Local::new(self.system, self.layout, &base, x)
    }

    /// The measure at `x` of a dimension of the system — a metric constraint or a reference
    /// dimension ([`gcs_model::System::references`]) — in its units (model units, degrees, a
    /// ratio): what a CAD program shows beside it. `None` for a constraint that is not a
    /// dimension, or where the measure is undefined (a line of zero length).
    pub fn measure(&self, c: &gcs_model::Constraint, x: &[f64]) -> Option<f64> {
        let metric = c.signature.metric()?;
        let base = self.system.signature_base_entities(c.signature);
        let local = Local::new(self.system, self.layout, &base, x);
        let (m, _) = laws::measure(metric, 0, &local, 0.0)?;
        m.value.is_finite().then_some(m.value)
    }

    /// The rows of constraint `c` at `x` (one value per column) in any field: every candidate
    /// equation (a constraint whose natural equations outnumber its DOC gives them all), with
    /// its value; see the module documentation for metric constraints. `Fix` compares with the
    /// sketch.
    pub fn rows<F: Field>(&self, c: ConstraintIdx, x: &[F]) -> Residual<F> {
        let local = self.local(c, x);
        let sketch = |e: EntityIdx| crate::sketch::sketch_coords_in::<F>(self.system, e);
        let law =
            laws::law(self.system.constraint(c).signature, self.branch(c), &local, &sketch, false);
        Residual {
            constraint: c,
            values: law.rows.iter().map(|r| r.value.clone()).collect(),
            rows: law.rows.iter().map(|r| grad_row(r, &local.cols)).collect(),
        }
    }

    /// The polynomial equations of constraint `c` at `x` in any field, with the user's value
    /// for a dimension: the rows of a parameter-free constraint ([`Self::rows`]), or the
    /// dimension's polynomial measure minus what it is where the dimension holds (the squared
    /// distance between two points minus the value squared; a radius or a coordinate
    /// difference minus the value). `None` for a dimension without a value or whose measure
    /// is not a polynomial: what a solver that needs polynomials (homotopy continuation)
    /// cannot take. A dimension whose measure is a quotient of polynomials (distances to
    /// lines and planes, between parallel lines and planes, a ratio of lengths) gives its
    /// equation cleared of the denominator instead, `p² − v²q²` where the measure is
    /// `|p| / √q` (one row, zero exactly where the measure is the value; [`Self::target`] is
    /// `None` for it); angles and the distances whose measure takes a branch give `None`.
    pub fn polynomial<F: Field>(&self, c: ConstraintIdx, x: &[F]) -> Option<Residual<F>> {
        let Some(target) = self.target(c) else { return self.cleared(c, x) };
        let target = F::from_rational(&target).ok()?;
        let mut rows = self.rows(c, x);
        if !target.is_zero() {
            for v in &mut rows.values {
                *v = v.sub(&target);
            }
        }
        Some(rows)
    }

    /// The equation of a dimension cleared of its denominator (see [`Self::polynomial`]).
    fn cleared<F: Field>(&self, c: ConstraintIdx, x: &[F]) -> Option<Residual<F>> {
        let constraint = self.system.constraint(c);
        let local = self.local(c, x);
        let row =
            laws::cleared(constraint.signature.metric()?, constraint.value.as_ref()?, &local)?;
        Some(Residual {
            constraint: c,
            values: vec![row.value.clone()],
            rows: vec![grad_row(&row, &local.cols)],
        })
    }

    /// What every row of [`Self::rows`] of constraint `c` is where `c` holds at the user's
    /// value, when that is a constant: zero for a parameter-free constraint; for a dimension,
    /// what its polynomial measure is at the value (see [`Self::polynomial`]: a solver that
    /// evaluates often computes it once). `None` where [`Self::polynomial`] is.
    pub fn target(&self, c: ConstraintIdx) -> Option<BigRational> {
        let constraint = self.system.constraint(c);
        if !constraint.kind.is_metric() {
            return Some(BigRational::from_integer(0.into()));
        }
        laws::polynomial_target(constraint.signature.metric()?, constraint.value.as_ref()?)
    }

    /// The total degree of each equation of [`Self::polynomial`] in the coordinates (computed
    /// on polynomials modulo a prime: exact for equations with rational coefficients, up to
    /// a coefficient that vanishes modulo 2^61 − 1). `None` where [`Self::polynomial`] is, or
    /// when the constraint reads more than 31 coordinates.
    pub fn degrees(&self, c: ConstraintIdx) -> Option<Vec<u32>> {
        use crate::polysolve::{MAX_VARS, Poly};
        type P = Poly<gcs_rank::ModP>;
        let mut x: Vec<P> = vec![P::zero(); self.layout.ncols()];
        let mut k = 0;
        for e in self.system.constraint_base_entities(c) {
            for col in self.layout.columns(e) {
                if k == MAX_VARS {
                    return None;
                }
                x[col] = P::var(k);
                k += 1;
            }
        }
        let rows = self.polynomial(c, &x)?;
        Some(rows.values.iter().map(P::max_degree).collect())
    }

    /// The residual of constraint `c` at the real configuration `x`: the residuals of a
    /// parameter-free constraint, or the measure minus the constraint's value for a metric
    /// one (a distance in model units, an angle in degrees: 2D angles modulo 180°, 3D angles
    /// between 0° and 90°, the value reduced the same way). `None` for a metric constraint
    /// without a value.
    pub fn residual(&self, c: ConstraintIdx, x: &[f64]) -> Option<Residual<f64>> {
        let constraint = self.system.constraint(c);
        if !constraint.kind.is_metric() {
            return Some(self.rows(c, x));
        }
        let value = constraint.value.as_ref()?.to_f64()?;
        let local = self.local(c, x);
        let metric = constraint.signature.metric()?;
        let (m, target) = laws::measure(metric, self.branch(c), &local, value)?;
        Some(Residual {
            constraint: c,
            values: vec![m.value - target],
            rows: vec![grad_row(&m, &local.cols)],
        })
    }

    /// The entity-internal rows of entity `e` at `x` (normalisations of homogeneous
    /// coordinates, whose value is the scale, and the Plücker relation of a 3D line).
    pub fn internal<F: Field>(&self, e: EntityIdx, x: &[F]) -> Vec<SparseRow<F>> {
        self.internal_residuals(e, x).1
    }

    /// The entity-internal equations of entity `e` at `x` with their values (a solver's
    /// residuals): the relations first, then the normalisation of homogeneous coordinates
    /// (whose value is the scale, not a residual).
    pub fn internal_residuals<F: Field>(
        &self,
        e: EntityIdx,
        x: &[F],
    ) -> (Vec<F>, Vec<SparseRow<F>>) {
        let Some(repr) = self.layout.repr(e) else { return (Vec::new(), Vec::new()) };
        let local = Local::new(self.system, self.layout, &[e], x);
        let rows = repr.internal_equations(local.coords(e));
        (
            rows.iter().map(|r| r.value.clone()).collect(),
            rows.iter().map(|r| grad_row(r, &local.cols)).collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(text: &str) -> System {
        System::from_ron_str(text, None).unwrap()
    }

    /// Residuals vanish at a configuration that satisfies the constraints, and their
    /// gradients match finite differences.
    #[test]
    fn residuals_vanish_on_solutions_and_have_the_right_gradients() {
        let s = model(
            r#"System(dim: 2,
            entities: [Point(id: "p", at: [0, 0]), Point(id: "q", at: [4, 0]), Point(id: "r", at: [4, 3]),
                       Segment(id: "pq", from: "p", to: "q"), Segment(id: "qr", from: "q", to: "r"),
                       Segment(id: "pr", from: "p", to: "r"), Circle(id: "k", center: [0, 0], radius: 5)],
            constraints: [Distance(id: "d", a: "p", b: "r", value: 5), Perpendicular(id: "perp", a: "pq", b: "qr"),
                          Angle(id: "a", a: "pq", b: "pr", value: 36.86989764584402),
                          Incident(id: "on", a: "r", b: "k"), Horizontal(id: "h", a: "pq"),
                          Radius(id: "rad", a: "k", value: 5), Distance(id: "dl", a: "r", b: "pq", value: 3)])"#,
        );
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        let x: Vec<f64> = [0.0, 0.0, 4.0, 0.0, 4.0, 3.0, 0.0, 0.0, 5.0].to_vec();
        for c in s.constraint_indices() {
            let r = eq.residual(c, &x).unwrap();
            assert!(r.magnitude() < 1e-9, "{}: {:?}", s.constraint(c).id, r.values);
            // Finite differences along every column.
            let h = 1e-6;
            for col in 0..x.len() {
                let mut y = x.clone();
                y[col] += h;
                let r2 = eq.residual(c, &y).unwrap();
                for (k, row) in r.rows.iter().enumerate() {
                    let numeric = (r2.values[k] - r.values[k]) / h;
                    let analytic = row.get(col).copied().unwrap_or(0.0);
                    assert!(
                        (numeric - analytic).abs() < 1e-4 * (1.0 + analytic.abs()),
                        "{} column {col}: {numeric} vs {analytic}",
                        s.constraint(c).id
                    );
                }
            }
        }
        // An edited dimension shows as its difference, in model units and degrees.
        let moved: Vec<f64> = [0.0, 0.0, 4.0, 0.0, 4.0, 4.0, 0.0, 0.0, 5.0].to_vec();
        let d = eq.residual(s.constraint_by_id("d").unwrap(), &moved).unwrap();
        assert!((d.values[0] - (32f64.sqrt() - 5.0)).abs() < 1e-12);
        let a = eq.residual(s.constraint_by_id("a").unwrap(), &moved).unwrap();
        assert!((a.values[0] - (45.0 - 36.86989764584402)).abs() < 1e-9, "{:?}", a.values);
    }
}
