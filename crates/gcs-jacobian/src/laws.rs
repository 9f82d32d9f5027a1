//! The equations of every constraint, in one table keyed by [`Signature`]: for each row of the
//! constraint table, its variants (branches), its equations written once over dual numbers in
//! any field, and — for the constructive placement — their difference-of-squares form.
//!
//! Every equation is polynomial in the coordinates of [`crate::repr`] (no square root, no
//! trigonometry). Parameter-free constraints (incidence, parallelism, tangency…) give residuals
//! that must vanish at the witness. Metric constraints (distance, angle, radius) give the
//! gradient of their measure — the value is read off the witness, so it needs no equation; a
//! measure that would need a square root (a signed distance, a cosine) is differentiated as a
//! ratio (`Dual::ratio_sqrt`), which stays rational. Their measure itself, which does need
//! square roots and trigonometry, is [`measure`] (in `f64`).
//!
//! Where a constraint's natural equations are more than its DOC (a 3D point on a 3D line as a
//! cross product), all of them are returned as candidates and [`crate::plan`] keeps DOC of them
//! that are independent at the witness.
//!
//! Adding a constraint kind: its rows in [`gcs_model::Signature`], then one arm here in [`law`]
//! and, for a metric one, in [`measure`] (the compiler lists them).

use gcs_model::{EntityIdx, Gap, Metric, Signature};
use gcs_rank::{BigRational, Field};

use crate::dual::{Dual, vec as v};
use crate::views::Local;

/// `(P, M)` of an equation `|P|² − |M|² = 0`.
pub(crate) type Split<F> = (Vec<Dual<F>>, Vec<Dual<F>>);

/// An entity's sketch coordinates in a field (for `Fix`).
pub(crate) type SketchFn<'s, F> = dyn Fn(EntityIdx) -> Option<Vec<F>> + 's;

/// What the table says of one constraint in one variant, at one configuration.
pub(crate) struct Law<F> {
    /// How many variants (branches) the equations have; the plan picks the one that holds at
    /// the witness (external or internal tangency, skew or parallel lines).
    pub(crate) variants: usize,
    /// The candidate rows: residuals that must vanish (parameter-free constraints) or the
    /// gradients of the measure (metric constraints).
    pub(crate) rows: Vec<Dual<F>>,
    /// Whether the rows are measures (metric constraints) rather than residuals.
    pub(crate) metric: bool,
    /// The same equations as `|P|² − |M|² = 0` with `P`, `M` bilinear in the entities (so
    /// linear in any one of them when the others are fixed), when they have that form and it
    /// was asked for. The constructive placement solves `P = R M` for a rational orthogonal
    /// `R`, which is linear.
    pub(crate) split: Option<Split<F>>,
    /// For a distance between lines or planes (or circles): values that all vanish exactly
    /// when they are parallel (concentric) — the condition under which the distance between 2D lines or planes is
    /// defined, and which picks the formula between 3D lines (variant 1: parallel).
    pub(crate) parallel: Option<Vec<Dual<F>>>,
}

impl<F: Field> Law<F> {
    /// Whether the lines or planes of a distance between them are parallel (`None` for
    /// every other constraint), with `is_zero` the zero test of the caller.
    pub(crate) fn parallel(&self, is_zero: &dyn Fn(&F) -> bool) -> Option<bool> {
        self.parallel.as_ref().map(|xs| xs.iter().all(|x| is_zero(&x.value)))
    }
}

impl<F> Law<F> {
    fn exact(rows: Vec<Dual<F>>) -> Self {
        Law { variants: 1, rows, metric: false, split: None, parallel: None }
    }

    fn measure(row: Dual<F>) -> Self {
        Law { variants: 1, rows: vec![row], metric: true, split: None, parallel: None }
    }

    fn parallel_when(mut self, vanishing: Vec<Dual<F>>) -> Self {
        self.parallel = Some(vanishing);
        self
    }

    fn variants(mut self, n: usize) -> Self {
        self.variants = n;
        self
    }

    fn split(mut self, want: bool, split: impl FnOnce() -> Split<F>) -> Self {
        if want {
            self.split = Some(split());
        }
        self
    }
}

/// The equations of a constraint with signature `sig` in variant `variant` at the
/// configuration `l` (see [`Law`]); `sketch` gives sketch coordinates for `Fix`; the
/// difference-of-squares form is computed only when `want_split` — the constructive
/// placement's form, which is also branch-free where a constraint has such a form (an equal
/// angle: the product of its two branches).
pub(crate) fn law<F: Field>(
    sig: Signature,
    variant: usize,
    l: &Local<'_, F>,
    sketch: &SketchFn<'_, F>,
    want_split: bool,
) -> Law<F> {
    use Signature as S;
    let d3 = l.is_3d();
    match sig {
        S::CoincidentPoints(a, b) => Law::exact(v::sub(&l.point(a), &l.point(b))),
        S::Metric(Metric::DistancePointPoint(a, b)) => {
            Law::measure(v::norm2(&v::sub(&l.point(a), &l.point(b))))
        }
        S::Metric(Metric::DistancePointLine { point, line }) if !d3 => {
            let x = l.point(point);
            let [a, b, c0] = l.line2(line);
            let p = &(&(&a * &x[0]) + &(&b * &x[1])) + &c0;
            Law::measure(Dual::ratio_sqrt(&p, &(&(&a * &a) + &(&b * &b))))
        }
        S::Metric(Metric::DistancePointLine { point, line }) => {
            let x = l.point(point);
            let (d, m) = l.line3(line);
            let w = v::sub(&v::cross3(&x, &d), &m);
            Law::measure(Dual::ratio(&v::norm2(&w), &v::norm2(&d)))
        }
        S::Metric(Metric::DistancePointPlane { point, plane }) => {
            let x = l.point(point);
            let (n, delta) = l.plane(plane);
            Law::measure(Dual::ratio_sqrt(&(&v::dot(&n, &x) + &delta), &v::norm2(&n)))
        }
        S::Metric(Metric::DistanceLineLine(p, q)) if !d3 => {
            let [a1, b1, c1] = l.line2(p);
            let [a2, b2, c2] = l.line2(q);
            let cross = v::cross2(&[a1.clone(), b1.clone()], &[a2.clone(), b2.clone()]);
            Law::measure(parallel_offset(&[a1, b1], &c1, &[a2, b2], &c2)).parallel_when(vec![cross])
        }
        S::Metric(Metric::DistanceLineLine(p, q)) => {
            let (d1, m1) = l.line3(p);
            let (d2, m2) = l.line3(q);
            let cross = v::cross3(&d1, &d2);
            let row = if variant == 0 {
                // Skew lines: (d1·m2 + d2·m1) / |d1 × d2|.
                let num = &v::dot(&d1, &m2) + &v::dot(&d2, &m1);
                Dual::ratio_sqrt(&num, &v::norm2(&v::cross3(&d1, &d2)))
            } else {
                // Parallel lines: |(d1·d2) m1 − |d1|² m2|² / ((d1·d2)² |d1|²).
                let k = v::dot(&d1, &d2);
                let w = v::sub(&v::scale(&m1, &k), &v::scale(&m2, &v::norm2(&d1)));
                Dual::ratio(&v::norm2(&w), &(&(&k * &k) * &v::norm2(&d1)))
            };
            Law::measure(row).variants(2).parallel_when(cross)
        }
        S::Metric(Metric::DistancePlanePlane(p, q)) => {
            let (n1, e1) = l.plane(p);
            let (n2, e2) = l.plane(q);
            let cross = v::cross3(&n1, &n2);
            Law::measure(parallel_offset(&n1, &e1, &n2, &e2)).parallel_when(cross)
        }
        S::Metric(Metric::AngleLineLine(p, q)) if !d3 => {
            // Oriented angle between normals: its gradient is proportional to
            // cross0·∇dot − dot0·∇cross, regular at every angle (0° and 90° included).
            let (n1, n2) = (l.normal2(p), l.normal2(q));
            let dot = v::dot(&n1, &n2);
            let cross = v::cross2(&n1, &n2);
            Law::measure(&dot.scale(&cross.value) - &cross.scale(&dot.value))
        }
        S::Metric(Metric::AngleLineLine(p, q)) => {
            Law::measure(cosine(&l.direction3(p), &l.direction3(q)))
        }
        S::Metric(Metric::AngleLinePlane { line, plane }) => {
            Law::measure(cosine(&l.direction3(line), &l.plane(plane).0))
        }
        S::Metric(Metric::AnglePlanePlane(p, q)) => {
            Law::measure(cosine(&l.plane(p).0, &l.plane(q).0))
        }
        S::ParallelLineLine(p, q) if !d3 => {
            Law::exact(vec![v::cross2(&l.normal2(p), &l.normal2(q))])
        }
        S::ParallelLineLine(p, q) => Law::exact(v::cross3(&l.line3(p).0, &l.line3(q).0)),
        S::ParallelPlanePlane(p, q) => Law::exact(v::cross3(&l.plane(p).0, &l.plane(q).0)),
        S::ParallelLinePlane { line, plane } => {
            Law::exact(vec![v::dot(&l.direction3(line), &l.plane(plane).0)])
        }
        S::PerpendicularLineLine(p, q) => {
            // u·w = 0 is |u + w|² = |u − w|² (polarisation): quadratic in a point shared by
            // two perpendicular segments (Thales).
            let (u, w) = if d3 {
                (l.direction3(p), l.direction3(q))
            } else {
                (l.normal2(p).to_vec(), l.normal2(q).to_vec())
            };
            Law::exact(vec![v::dot(&u, &w)]).split(want_split, || (v::add(&u, &w), v::sub(&u, &w)))
        }
        S::PerpendicularPlanePlane(p, q) => Law::exact(vec![v::dot(&l.plane(p).0, &l.plane(q).0)]),
        S::PerpendicularLinePlane { line, plane } => {
            Law::exact(v::cross3(&l.direction3(line), &l.plane(plane).0))
        }
        S::IncidentPointLine { point, line } if !d3 => {
            let x = l.point(point);
            let [a, b, c0] = l.line2(line);
            Law::exact(vec![&(&(&a * &x[0]) + &(&b * &x[1])) + &c0])
        }
        S::IncidentPointLine { point, line } => {
            let (d, m) = l.line3(line);
            Law::exact(v::sub(&v::cross3(&l.point(point), &d), &m))
        }
        S::IncidentPointPlane { point, plane } => {
            let (n, delta) = l.plane(plane);
            Law::exact(vec![&v::dot(&n, &l.point(point)) + &delta])
        }
        S::IncidentPointCircle { point, circle: round }
        | S::IncidentPointSphere { point, sphere: round } => {
            let (c0, r) = l.round(round);
            let d = v::sub(&l.point(point), &c0);
            Law::exact(vec![&v::norm2(&d) - &(&r * &r)]).split(want_split, || (d, vec![r]))
        }
        S::IncidentLinePlane { line, plane } => {
            // The line lies in the plane: n·d = 0 and n × m = δ d (a point x of the line has
            // m = x × d, so n × m = x (n·d) − d (n·x) = δ d).
            let (d, m) = l.line3(line);
            let (n, delta) = l.plane(plane);
            let mut rows = vec![v::dot(&n, &d)];
            rows.extend(v::sub(&v::cross3(&n, &m), &v::scale(&d, &delta)));
            Law::exact(rows)
        }
        S::TangentLineCircle { line, circle } => {
            let [a, b, c0] = l.line2(line);
            let (c, r) = l.round(circle);
            let s = &(&(&a * &c[0]) + &(&b * &c[1])) + &c0;
            let n2 = &(&a * &a) + &(&b * &b);
            Law::exact(vec![&(&s * &s) - &(&(&r * &r) * &n2)])
                .split(want_split, || (vec![s.clone()], vec![&r * &a, &r * &b]))
        }
        S::TangentPlaneSphere { plane, sphere } => {
            let (n, delta) = l.plane(plane);
            let (c, r) = l.round(sphere);
            let s = &v::dot(&n, &c) + &delta;
            Law::exact(vec![&(&s * &s) - &(&(&r * &r) * &v::norm2(&n))])
                .split(want_split, || (vec![s.clone()], v::scale(&n, &r)))
        }
        S::TangentCircleCircle(p, q) | S::TangentSphereSphere(p, q) => {
            // External (variant 0) or internal (variant 1) tangency.
            let (c1, r1) = l.round(p);
            let (c2, r2) = l.round(q);
            let rr = if variant == 0 { &r1 + &r2 } else { &r1 - &r2 };
            let d = v::sub(&c1, &c2);
            Law::exact(vec![&v::norm2(&d) - &(&rr * &rr)])
                .variants(2)
                .split(want_split, || (d, vec![rr]))
        }
        S::ConcentricCircles(p, q) => Law::exact(v::sub(&l.round(p).0, &l.round(q).0)),
        S::CenterPoint { point, round } => Law::exact(v::sub(&l.point(point), &l.round(round).0)),
        S::Metric(Metric::Radius(e)) => Law::measure(l.round(e).1),
        S::Metric(Metric::DistanceX(a, b)) => Law::measure(&l.point(b)[0] - &l.point(a)[0]),
        S::Metric(Metric::DistanceY(a, b)) => Law::measure(&l.point(b)[1] - &l.point(a)[1]),
        S::EqualRadius(a, b) => Law::exact(vec![&l.round(a).1 - &l.round(b).1]),
        S::SymmetricAboutPoint { a, b, center } => {
            let two = Dual::int(2);
            let (x, y, m) = (l.point(a), l.point(b), l.point(center));
            Law::exact(
                m.iter().zip(x.iter().zip(&y)).map(|(m, (x, y))| &(&two * m) - &(x + y)).collect(),
            )
        }
        S::TangentAtLineCircle { line, circle, at } => {
            // The radius to the point is along the line's normal.
            let r = v::sub(&l.point(at), &l.round(circle).0);
            Law::exact(vec![v::cross2(&r, &l.normal2(line))])
        }
        S::TangentAtCircleCircle { a, b, at } => {
            // The point and the two centres are collinear.
            let p = l.point(at);
            Law::exact(vec![v::cross2(&v::sub(&p, &l.round(a).0), &v::sub(&p, &l.round(b).0))])
        }
        S::EqualLength(s, t) => {
            let (p1, q1) = l.segment(s);
            let (p2, q2) = l.segment(t);
            let (u, w) = (v::sub(&q1, &p1), v::sub(&q2, &p2));
            Law::exact(vec![&v::norm2(&u) - &v::norm2(&w)]).split(want_split, || (u, w))
        }
        S::Midpoint { point, segment } => {
            let m = l.point(point);
            let (p, q) = l.segment(segment);
            let two = Dual::int(2);
            Law::exact(
                m.iter().zip(p.iter().zip(&q)).map(|(m, (p, q))| &(&two * m) - &(p + q)).collect(),
            )
        }
        S::Symmetric { a, b, axis } => {
            let (x, y) = (l.point(a), l.point(b));
            let [la, lb, lc] = l.line2(axis);
            let s = v::add(&x, &y);
            let d = v::sub(&x, &y);
            let two = Dual::int(2);
            let on_axis = &(&(&la * &s[0]) + &(&lb * &s[1])) + &(&two * &lc);
            let across = v::cross2(&[la, lb], &d);
            Law::exact(vec![on_axis, across])
        }
        S::Horizontal(e) => {
            let [a, _] = l.normal2(e);
            Law::exact(vec![a])
        }
        S::Vertical(e) => {
            let [_, b] = l.normal2(e);
            Law::exact(vec![b])
        }
        S::Fix(e) => Law::exact(fix_rows(l, e, sketch)),
        S::Metric(Metric::DistanceCircleCircle(p, q)) => {
            // Defined between concentric circles (as the distance between lines is between
            // parallel ones): the difference of the radii.
            let (c1, r1) = l.round(p);
            let (c2, r2) = l.round(q);
            Law::measure(&r1 - &r2).parallel_when(v::sub(&c1, &c2))
        }
        S::Metric(Metric::LengthRatio(s, t)) => {
            // The ratio of the squared lengths: a monotone function of the ratio, rational.
            let (p1, q1) = l.segment(s);
            let (p2, q2) = l.segment(t);
            Law::measure(Dual::ratio(&v::norm2(&v::sub(&q1, &p1)), &v::norm2(&v::sub(&q2, &p2))))
        }
        S::EqualAngle { a, b, c, d } => {
            // With θ₁ from a to b and θ₂ from c to d (normals turn as the lines do): the same
            // angle modulo 180°, sin(θ₁ − θ₂) = 0 (variant 0), or opposite ones,
            // sin(θ₁ + θ₂) = 0 (variant 1): equal angles between the undirected lines, either
            // of the two supplementary angles. For the placement (`want_split`), both at once
            // and with no branch to choose, so that an equality other constraints imply holds
            // whichever the witness lands on: their product, a difference of squares,
            // (sin θ₁ cos θ₂)² − (cos θ₁ sin θ₂)² (singular where both vanish — right angles,
            // parallel lines —, which is why the analysis keeps the branch).
            let (na, nb, nc, nd) = (l.normal2(a), l.normal2(b), l.normal2(c), l.normal2(d));
            let x = &v::cross2(&na, &nb) * &v::dot(&nc, &nd);
            let y = &v::dot(&na, &nb) * &v::cross2(&nc, &nd);
            if want_split {
                Law::exact(vec![&(&x * &x) - &(&y * &y)])
                    .variants(2)
                    .split(true, || (vec![x], vec![y]))
            } else {
                Law::exact(vec![if variant == 0 { &x - &y } else { &x + &y }]).variants(2)
            }
        }
        S::SplinePoint { point, spline, knot } => {
            // x − Σ cᵢ Pᵢ = 0: the curve's point at the knot, an affine combination of the
            // control points with exact coefficients (`gcs_model::spline::basis`). Linear.
            // (A coefficient whose denominator the field's prime divides, which knots of a
            // few digits never have, is taken as 0 there: the exact rank is certified against
            // the rational rows.)
            let mut rows = l.point(point);
            for (pole, c) in spline_basis(l.system(), spline, knot) {
                let c = Dual::constant(F::from_rational(&c).unwrap_or_else(|_| F::zero()));
                for (r, y) in rows.iter_mut().zip(l.point(pole)) {
                    *r = &*r - &(&c * &y);
                }
            }
            Law::exact(rows)
        }
        S::EqualDistance(p, q) => {
            // d₁² = n₁/m₁ and d₂² = n₂/m₂: n₁ m₂ − n₂ m₁ = 0, a difference of squares (a
            // point–point squared distance times a squared normal is |(u·n, u×n)|², Lagrange's
            // identity).
            let gap = |g: Gap| -> (Vec<Dual<F>>, Option<Vec<Dual<F>>>) {
                match g {
                    Gap::PointPoint(x, y) => (v::sub(&l.point(x), &l.point(y)), None),
                    Gap::CircleCircle(x, y) => (vec![&l.round(x).1 - &l.round(y).1], None),
                    Gap::PointLine { point, line } => {
                        let x = l.point(point);
                        let [a, b, c0] = l.line2(line);
                        let s = &(&(&a * &x[0]) + &(&b * &x[1])) + &c0;
                        (vec![s], Some(vec![a, b]))
                    }
                }
            };
            // |u|² |n|² as |w|²: w = u ⊗ n in the form above.
            let times = |u: &[Dual<F>], n: &Option<Vec<Dual<F>>>| -> Vec<Dual<F>> {
                match (n, u) {
                    (None, _) => u.to_vec(),
                    (Some(n), [s]) => v::scale(n, s),
                    (Some(n), _) => vec![v::dot(u, n), v::cross2(u, n)],
                }
            };
            let ((u1, n1), (u2, n2)) = (gap(p), gap(q));
            let (left, right) = (times(&u1, &n2), times(&u2, &n1));
            Law::exact(vec![&v::norm2(&left) - &v::norm2(&right)])
                .split(want_split, || (left, right))
        }
    }
}

/// The degree in lengths of the residuals of a parameter-free constraint (how they grow when
/// the model is scaled, the coordinates of lines scaling as the segments' do): 2 for most (a
/// point on a circle, an equal length), more for the equalities, whose polynomials are
/// products — 4 for equal angles, 2 more per point–line distance for equal distances. What a
/// residual is measured against (the model's size to this power) in the projection and the
/// solver.
pub fn residual_degree(sig: Signature) -> i32 {
    use Signature as S;
    match sig {
        S::EqualAngle { .. } => 4,
        S::SplinePoint { .. } => 1,
        S::EqualDistance(p, q) => {
            2 + 2 * [p, q].iter().filter(|g| matches!(g, Gap::PointLine { .. })).count() as i32
        }
        S::Metric(_)
        | S::CoincidentPoints(..)
        | S::ParallelLineLine(..)
        | S::ParallelPlanePlane(..)
        | S::ParallelLinePlane { .. }
        | S::PerpendicularLineLine(..)
        | S::PerpendicularPlanePlane(..)
        | S::PerpendicularLinePlane { .. }
        | S::IncidentPointLine { .. }
        | S::IncidentPointPlane { .. }
        | S::IncidentPointCircle { .. }
        | S::IncidentPointSphere { .. }
        | S::IncidentLinePlane { .. }
        | S::TangentLineCircle { .. }
        | S::TangentCircleCircle(..)
        | S::TangentPlaneSphere { .. }
        | S::TangentSphereSphere(..)
        | S::ConcentricCircles(..)
        | S::CenterPoint { .. }
        | S::EqualLength(..)
        | S::Midpoint { .. }
        | S::SymmetricAboutPoint { .. }
        | S::EqualRadius(..)
        | S::TangentAtLineCircle { .. }
        | S::TangentAtCircleCircle { .. }
        | S::Symmetric { .. }
        | S::Horizontal(_)
        | S::Vertical(_)
        | S::Fix(_) => 2,
    }
}

/// The control points of B-spline `spline` and their coefficients at its knot `knot` (its
/// index in the flat knot vector), exactly; empty when the model's data make no curve (which
/// the builder has refused already).
pub(crate) fn spline_basis(
    system: &gcs_model::System,
    spline: EntityIdx,
    knot: u32,
) -> Vec<(EntityIdx, BigRational)> {
    let gcs_model::Geometry::BSpline { degree, poles, knots, weights, periodic } =
        &system.entity(spline).geometry
    else {
        return Vec::new();
    };
    let flat =
        gcs_model::spline::knots_or_default(*degree, poles.len(), knots.as_deref(), *periodic);
    let Some(u) = flat.get(knot as usize) else { return Vec::new() };
    let w = weights.as_deref().unwrap_or(&[]);
    gcs_model::spline::basis(*degree, poles.len(), &flat, w, *periodic, u)
        .unwrap_or_default()
        .into_iter()
        .map(|(i, c)| (poles[i], c))
        .collect()
}

/// `Fix`: every coordinate of the entity (or of its parts) equal to its sketch, homogeneous
/// coordinates up to their scale.
fn fix_rows<F: Field>(l: &Local<'_, F>, e: EntityIdx, sketch: &SketchFn<'_, F>) -> Vec<Dual<F>> {
    let mut rows = Vec::new();
    for b in l.system().base_entities(e) {
        let x = l.coords(b);
        let Some(s) = sketch(b) else { continue };
        if x.len() == s.len() && l.homogeneous(b) {
            // x ∝ s: x_j s_k − x_k s_j for every pair.
            for j in 0..x.len() {
                for k in j + 1..x.len() {
                    rows.push(&x[j].scale(&s[k]) - &x[k].scale(&s[j]));
                }
            }
        } else {
            for (xj, sj) in x.iter().zip(&s) {
                rows.push(xj - &Dual::constant(sj.clone()));
            }
        }
    }
    // An arc's end points keep their places along its circle: each stays on the ray from the
    // centre through its sketch position, `(p − c) × (p₀ − c₀) = 0`.
    if let (Some((start, end)), Some(c0)) = (l.system().arc_points(e), sketch(e)) {
        let c = l.round(e).0;
        for p in [start, end] {
            let Some(p0) = sketch(p) else { continue };
            let ray: Vec<F> = p0.iter().zip(&c0).map(|(a, b)| a.sub(b)).collect();
            let u = v::sub(&l.point(p), &c);
            rows.push(&u[0].scale(&ray[1]) - &u[1].scale(&ray[0]));
        }
    }
    rows
}

/// The measure of a metric constraint at a real configuration, in the units of its value
/// (lengths in model units, angles in degrees), with its gradient, and the user's `value`
/// reduced to the range of the measure; `None` for parameter-free constraints. Distances are
/// unsigned; the angle between 2D lines is the angle from the first line to the second,
/// modulo 180° (lines have no orientation; the value is taken modulo 180° too, nearest the
/// measure); the angles in 3D are unsigned, in `[0°, 90°]` (a value `v` stands for
/// `min(v mod 180°, 180° − v mod 180°)`).
pub(crate) fn measure(
    metric: Metric,
    variant: usize,
    l: &Local<'_, f64>,
    value: f64,
) -> Option<(Dual<f64>, f64)> {
    use Metric as M;
    let d3 = l.is_3d();
    let unsigned = |m: Dual<f64>| {
        let t = value.rem_euclid(180.0);
        (m, t.min(180.0 - t))
    };
    let sqrt = |x: &Dual<f64>| x.map(f64::sqrt, |v| 0.5 / v.sqrt());
    let abs = |x: &Dual<f64>| if x.value < 0.0 { -x } else { x.clone() };
    let length = |m: Dual<f64>| (m, value);
    Some(match metric {
        M::DistancePointPoint(a, b) => length(sqrt(&v::norm2(&v::sub(&l.point(a), &l.point(b))))),
        M::DistancePointLine { point, line } if !d3 => {
            let (p, n2) = point_line_2d(l, point, line);
            length(abs(&p).over(&sqrt(&n2)))
        }
        M::DistancePointLine { point, line } => {
            let (w2, d2) = point_line_3d(l, point, line);
            length(sqrt(&w2.over(&d2)))
        }
        M::DistancePointPlane { point, plane } => {
            let (s, n2) = point_plane(l, point, plane);
            length(abs(&s).over(&sqrt(&n2)))
        }
        M::DistanceLineLine(p, q) if !d3 => {
            let (num, k, n2) = parallel_lines_2d(l, p, q);
            length(abs(&num).over(&(&abs(&k) * &sqrt(&n2))))
        }
        M::DistanceLineLine(p, q) => {
            let (d1, m1) = l.line3(p);
            let (d2, m2) = l.line3(q);
            length(if variant == 0 {
                let num = &v::dot(&d1, &m2) + &v::dot(&d2, &m1);
                abs(&num).over(&sqrt(&v::norm2(&v::cross3(&d1, &d2))))
            } else {
                let k = v::dot(&d1, &d2);
                let w = v::sub(&v::scale(&m1, &k), &v::scale(&m2, &v::norm2(&d1)));
                sqrt(&v::norm2(&w).over(&(&(&k * &k) * &v::norm2(&d1))))
            })
        }
        M::DistancePlanePlane(p, q) => {
            let (num, k, n2) = parallel_planes(l, p, q);
            length(abs(&num).over(&(&abs(&k) * &sqrt(&n2))))
        }
        M::AngleLineLine(p, q) if !d3 => {
            // From the direction of the first line to that of the second: the directions are
            // the normals turned by 90°, the same angle.
            let (n1, n2) = (l.normal2(p), l.normal2(q));
            let dot = v::dot(&n1, &n2);
            let cross = v::cross2(&n1, &n2);
            let degrees = Dual::atan2(&cross, &dot).scale(&(180.0 / std::f64::consts::PI));
            let m = degrees.map(|x| x.rem_euclid(180.0), |_| 1.0);
            // The representative of the value modulo 180° nearest the measure.
            let t = value.rem_euclid(180.0);
            let target = t + 180.0 * ((m.value - t) / 180.0).round();
            (m, target)
        }
        M::AngleLineLine(p, q) => {
            unsigned(unsigned_angle(&l.direction3(p), &l.direction3(q), false))
        }
        M::AngleLinePlane { line, plane } => {
            unsigned(unsigned_angle(&l.direction3(line), &l.plane(plane).0, true))
        }
        M::AnglePlanePlane(p, q) => unsigned(unsigned_angle(&l.plane(p).0, &l.plane(q).0, false)),
        M::Radius(e) => length(l.round(e).1),
        M::DistanceX(a, b) => length(&l.point(b)[0] - &l.point(a)[0]),
        M::DistanceY(a, b) => length(&l.point(b)[1] - &l.point(a)[1]),
        M::DistanceCircleCircle(p, q) => length(abs(&(&l.round(p).1 - &l.round(q).1))),
        M::LengthRatio(s, t) => {
            let (u2, w2) = squared_lengths(l, s, t);
            (sqrt(&u2).over(&sqrt(&w2)), value)
        }
    })
}

/// For a metric whose measure in [`law`] is a polynomial in the coordinates, the value that
/// measure takes where the dimension holds at `value`: the value squared for the distance
/// between two points (the measure is the squared distance), the value itself for a radius
/// and a coordinate difference. `None` where the measure is a ratio or needs a square root
/// (distances to lines and planes, between circles, angles, ratios): a solver that needs
/// polynomial equations (homotopy continuation) cannot take those.
pub(crate) fn polynomial_target(metric: Metric, value: &BigRational) -> Option<BigRational> {
    use Metric as M;
    match metric {
        M::DistancePointPoint(..) => Some(value * value),
        M::Radius(_) | M::DistanceX(..) | M::DistanceY(..) => Some(value.clone()),
        M::DistancePointLine { .. }
        | M::DistancePointPlane { .. }
        | M::DistanceLineLine(..)
        | M::DistancePlanePlane(..)
        | M::AngleLineLine(..)
        | M::AnglePlanePlane(..)
        | M::AngleLinePlane { .. }
        | M::DistanceCircleCircle(..)
        | M::LengthRatio(..) => None,
    }
}

/// The polynomial equation of a dimension whose measure is a quotient (or the square root of
/// one) of polynomials, cleared of its denominator and squared where the measure is unsigned,
/// at the user's `value`: zero exactly where the measure is the value (and the denominator
/// does not vanish) — the 2D point–line distance `s² − v²|n|²` (`s = n·x + c`), the distance
/// between parallel 2D lines or planes `num² − v² k² |n₁|²` (the measure `|num| / (|k| |n₁|)`),
/// the point–plane distance `s² − v²|n|²`, the 3D point–line distance `|x × d − m|² −
/// v²|d|²`, a ratio of lengths `|u|² − v²|w|²`. `None` for the others: the dimensions
/// [`polynomial_target`] gives (their rows minus a constant are already polynomial), angles,
/// and the distances whose measure depends on a branch (skew or parallel 3D lines) or on the
/// sign of a difference (circle to circle).
pub(crate) fn cleared<F: Field>(
    metric: Metric,
    value: &BigRational,
    l: &Local<'_, F>,
) -> Option<Dual<F>> {
    use Metric as M;
    let v2 = Dual::constant(F::from_rational(&(value * value)).ok()?);
    let d3 = l.is_3d();
    let minus = |p: Dual<F>, q: Dual<F>| &p - &(&v2 * &q);
    match metric {
        M::DistancePointLine { point, line } if !d3 => {
            let (s, n2) = point_line_2d(l, point, line);
            Some(minus(&s * &s, n2))
        }
        M::DistancePointLine { point, line } => {
            let (w2, d2) = point_line_3d(l, point, line);
            Some(minus(w2, d2))
        }
        M::DistancePointPlane { point, plane } => {
            let (s, n2) = point_plane(l, point, plane);
            Some(minus(&s * &s, n2))
        }
        M::DistanceLineLine(p, q) if !d3 => {
            let (num, k, n2) = parallel_lines_2d(l, p, q);
            Some(minus(&num * &num, &(&k * &k) * &n2))
        }
        M::DistancePlanePlane(p, q) => {
            let (num, k, n2) = parallel_planes(l, p, q);
            Some(minus(&num * &num, &(&k * &k) * &n2))
        }
        M::LengthRatio(s, t) => {
            let (u2, w2) = squared_lengths(l, s, t);
            Some(minus(u2, w2))
        }
        M::DistancePointPoint(..)
        | M::Radius(_)
        | M::DistanceX(..)
        | M::DistanceY(..)
        | M::DistanceLineLine(..)
        | M::AngleLineLine(..)
        | M::AnglePlanePlane(..)
        | M::AngleLinePlane { .. }
        | M::DistanceCircleCircle(..) => None,
    }
}

// The quotient measures' parts, shared by [`measure`] and [`cleared`].

/// The 2D point–line distance `|s| / √|n|²`: `s = n·x + c` and `|n|²`.
fn point_line_2d<F: Field>(
    l: &Local<'_, F>,
    point: EntityIdx,
    line: EntityIdx,
) -> (Dual<F>, Dual<F>) {
    let x = l.point(point);
    let [a, b, c0] = l.line2(line);
    let s = &(&(&a * &x[0]) + &(&b * &x[1])) + &c0;
    (s, &(&a * &a) + &(&b * &b))
}

/// The 3D point–line distance `√(|x × d − m|² / |d|²)`: the two squared norms.
fn point_line_3d<F: Field>(
    l: &Local<'_, F>,
    point: EntityIdx,
    line: EntityIdx,
) -> (Dual<F>, Dual<F>) {
    let (d, m) = l.line3(line);
    let w = v::sub(&v::cross3(&l.point(point), &d), &m);
    (v::norm2(&w), v::norm2(&d))
}

/// The point–plane distance `|s| / √|n|²`: `s = n·x + δ` and `|n|²`.
fn point_plane<F: Field>(
    l: &Local<'_, F>,
    point: EntityIdx,
    plane: EntityIdx,
) -> (Dual<F>, Dual<F>) {
    let (n, delta) = l.plane(plane);
    (&v::dot(&n, &l.point(point)) + &delta, v::norm2(&n))
}

/// The distance between parallel 2D lines `|num| / (|k| √|n₁|²)`: `num`, `k = n₁·n₂`, `|n₁|²`.
fn parallel_lines_2d<F: Field>(
    l: &Local<'_, F>,
    p: EntityIdx,
    q: EntityIdx,
) -> (Dual<F>, Dual<F>, Dual<F>) {
    let [a1, b1, c1] = l.line2(p);
    let [a2, b2, c2] = l.line2(q);
    let n1 = [a1, b1];
    let k = v::dot(&n1, &[a2, b2]);
    let n2 = v::norm2(&n1);
    (&(&c1 * &k) - &(&c2 * &n2), k, n2)
}

/// The distance between parallel planes `|num| / (|k| √|n₁|²)`: `num`, `k = n₁·n₂`, `|n₁|²`.
fn parallel_planes<F: Field>(
    l: &Local<'_, F>,
    p: EntityIdx,
    q: EntityIdx,
) -> (Dual<F>, Dual<F>, Dual<F>) {
    let (n1, e1) = l.plane(p);
    let (n2, e2) = l.plane(q);
    let k = v::dot(&n1, &n2);
    let n1_2 = v::norm2(&n1);
    (&(&e1 * &k) - &(&e2 * &n1_2), k, n1_2)
}

/// A ratio of lengths `√|u|² / √|w|²`: the two squared lengths.
fn squared_lengths<F: Field>(l: &Local<'_, F>, s: EntityIdx, t: EntityIdx) -> (Dual<F>, Dual<F>) {
    let (p1, q1) = l.segment(s);
    let (p2, q2) = l.segment(t);
    (v::norm2(&v::sub(&q1, &p1)), v::norm2(&v::sub(&q2, &p2)))
}

/// The angle in degrees, in `[0°, 90°]`, between two undirected lines with directions `u`, `w`
/// (`complement`: between a line and a plane of normal `w`, 90° minus that).
fn unsigned_angle(u: &[Dual<f64>], w: &[Dual<f64>], complement: bool) -> Dual<f64> {
    let dot = v::dot(u, w);
    let dot = if dot.value < 0.0 { -&dot } else { dot };
    let cross = v::cross3(u, w);
    let sin = v::norm2(&cross).map(f64::sqrt, |x| 0.5 / x.sqrt().max(f64::MIN_POSITIVE));
    let degrees = Dual::atan2(&sin, &dot).scale(&(180.0 / std::f64::consts::PI));
    if complement { &Dual::constant(90.0) - &degrees } else { degrees }
}

/// The cosine of the angle between two vectors, as a ratio row.
fn cosine<F: Field>(u: &[Dual<F>], w: &[Dual<F>]) -> Dual<F> {
    Dual::ratio_sqrt(&v::dot(u, w), &(&v::norm2(u) * &v::norm2(w)))
}

/// The signed distance between two parallel hyperplanes `n1·x + e1 = 0`, `n2·x + e2 = 0`
/// (2D lines or planes): `(e1 (n1·n2) − e2 |n1|²) / ((n1·n2) |n1|)`.
fn parallel_offset<F: Field>(
    n1: &[Dual<F>],
    e1: &Dual<F>,
    n2: &[Dual<F>],
    e2: &Dual<F>,
) -> Dual<F> {
    let k = v::dot(n1, n2);
    let n1n1 = v::norm2(n1);
    let num = &(e1 * &k) - &(e2 * &n1n1);
    Dual::ratio_sqrt(&num, &(&(&k * &k) * &n1n1))
}
