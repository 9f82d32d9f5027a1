//! The equations of every constraint kind, written once over dual numbers in any field.
//!
//! Every equation is polynomial in the coordinates of [`crate::layout`] (no square root, no
//! trigonometry). Parameter-free constraints (incidence, parallelism, tangency…) give residuals
//! that must vanish at the witness. Metric constraints (distance, angle, radius) give the
//! gradient of their measure — the value is read off the witness, so it needs no equation; a
//! measure that would need a square root (a signed distance, a cosine) is differentiated as a
//! ratio (`Dual::ratio_sqrt`), which stays rational.
//!
//! Where a constraint's natural equations are more than its DOC (a 3D point on a 3D line as a
//! cross product), all of them are returned as candidates and [`crate::plan`] keeps DOC of them
//! that are independent at the witness.

use gcs_model::{Constraint, ConstraintKind, Dim, EntityIdx, Geometry, Shape, System};
use gcs_rank::Field;

use crate::dual::{Dual, vec as v};
use crate::layout::{Layout, Repr};

/// The dual-number views of the entities bound by one constraint.
pub(crate) struct Local<'a, F> {
    system: &'a System,
    /// `(entity, its coordinates as variables)` for the base entities.
    vars: Vec<(EntityIdx, Vec<Dual<F>>)>,
    /// Local variable index → global column.
    pub(crate) cols: Vec<usize>,
}

impl<'a, F: Field> Local<'a, F> {
    /// Variables for the base entities `entities` (no segments) at `witness` (indexed by global
    /// column).
    pub(crate) fn new(
        system: &'a System,
        layout: &Layout,
        entities: &[EntityIdx],
        witness: &[F],
    ) -> Local<'a, F> {
        let n: usize = entities.iter().map(|e| layout.columns(*e).len()).sum();
        let mut vars = Vec::with_capacity(entities.len());
        let mut cols = Vec::with_capacity(n);
        for &e in entities {
            let mut ev = Vec::new();
            for col in layout.columns(e) {
                ev.push(Dual::variable(witness[col].clone(), cols.len(), n));
                cols.push(col);
            }
            vars.push((e, ev));
        }
        Local { system, vars, cols }
    }

    pub(crate) fn nvars(&self) -> usize {
        self.cols.len()
    }

    pub(crate) fn coords(&self, e: EntityIdx) -> &[Dual<F>] {
        self.vars.iter().find(|(x, _)| *x == e).map(|(_, c)| c.as_slice()).unwrap_or(&[])
    }

    pub(crate) fn point(&self, e: EntityIdx) -> Vec<Dual<F>> {
        self.coords(e).to_vec()
    }

    /// A 2D line or segment as homogeneous `(a, b, c)`.
    pub(crate) fn line2(&self, e: EntityIdx) -> [Dual<F>; 3] {
        match self.system.segment_points(e) {
            Some((p, q)) => {
                let (p, q) = (self.coords(p), self.coords(q));
                // The line through p and q: (p.y − q.y) x + (q.x − p.x) y + (p.x q.y − q.x p.y).
                [&p[1] - &q[1], &q[0] - &p[0], v::cross2(p, q)]
            }
            None => {
                let c = self.coords(e);
                [c[0].clone(), c[1].clone(), c[2].clone()]
            }
        }
    }

    /// The normal `(a, b)` of a 2D line or segment (without computing its offset).
    pub(crate) fn normal2(&self, e: EntityIdx) -> [Dual<F>; 2] {
        match self.system.segment_points(e) {
            Some((p, q)) => {
                let (p, q) = (self.coords(p), self.coords(q));
                [&p[1] - &q[1], &q[0] - &p[0]]
            }
            None => {
                let c = self.coords(e);
                [c[0].clone(), c[1].clone()]
            }
        }
    }

    /// The direction `d` of a 3D line or segment (without computing its moment).
    pub(crate) fn direction3(&self, e: EntityIdx) -> Vec<Dual<F>> {
        match self.system.segment_points(e) {
            Some((p, q)) => v::sub(self.coords(q), self.coords(p)),
            None => self.coords(e)[0..3].to_vec(),
        }
    }

    /// A 3D line or segment in Plücker coordinates `(d, m)`.
    pub(crate) fn line3(&self, e: EntityIdx) -> (Vec<Dual<F>>, Vec<Dual<F>>) {
        match self.system.segment_points(e) {
            Some((p, q)) => {
                let (p, q) = (self.coords(p), self.coords(q));
                (v::sub(q, p), v::cross3(p, q))
            }
            None => {
                let c = self.coords(e);
                (c[0..3].to_vec(), c[3..6].to_vec())
            }
        }
    }

    /// A plane as `(normal, offset)`.
    pub(crate) fn plane(&self, e: EntityIdx) -> (Vec<Dual<F>>, Dual<F>) {
        let c = self.coords(e);
        (c[0..3].to_vec(), c[3].clone())
    }

    /// A circle or sphere as `(centre, radius)`.
    pub(crate) fn round(&self, e: EntityIdx) -> (Vec<Dual<F>>, Dual<F>) {
        let c = self.coords(e);
        let n = c.len() - 1;
        (c[..n].to_vec(), c[n].clone())
    }

    /// The endpoints of a segment.
    fn segment(&self, e: EntityIdx) -> (Vec<Dual<F>>, Vec<Dual<F>>) {
        let (p, q) = self.system.segment_points(e).unwrap_or((e, e));
        (self.point(p), self.point(q))
    }
}

/// Candidate rows of one constraint.
pub(crate) struct Candidates<F> {
    /// Residuals (exact constraints) or measures (metric constraints).
    pub(crate) rows: Vec<Dual<F>>,
    /// Whether the rows are residuals that must vanish at the witness.
    pub(crate) exact: bool,
}

/// How many variants (branches) a constraint's equations have. The planner picks the one that
/// holds at the witness.
pub(crate) fn variants(system: &System, c: &Constraint) -> usize {
    match (c.kind, c.shape, system.dim()) {
        (ConstraintKind::Tangent, Shape::CircleCircle(..) | Shape::SphereSphere(..), _) => 2,
        (ConstraintKind::Distance, Shape::LineLine(..), Dim::Three) => 2,
        _ => 1,
    }
}

fn exact<F>(rows: Vec<Dual<F>>) -> Candidates<F> {
    Candidates { rows, exact: true }
}

fn measure<F>(row: Dual<F>) -> Candidates<F> {
    Candidates { rows: vec![row], exact: false }
}

/// The candidate equations of constraint `c` in variant `variant`. `sketch` gives an entity's
/// sketch coordinates in the layout's representation (used by `Fix`).
pub(crate) fn candidates<F: Field>(
    system: &System,
    c: &Constraint,
    variant: usize,
    l: &Local<'_, F>,
    sketch: &dyn Fn(EntityIdx) -> Option<Vec<F>>,
) -> Candidates<F> {
    use ConstraintKind as K;
    let d3 = system.dim() == Dim::Three;
    match (c.kind, c.shape) {
        (K::Coincident, Shape::PointPoint(a, b)) => exact(v::sub(&l.point(a), &l.point(b))),
        (K::Distance, Shape::PointPoint(a, b)) => {
            measure(v::norm2(&v::sub(&l.point(a), &l.point(b))))
        }
        (K::Distance, Shape::PointLine { point, line }) if !d3 => {
            let x = l.point(point);
            let [a, b, c0] = l.line2(line);
            let p = &(&(&a * &x[0]) + &(&b * &x[1])) + &c0;
            measure(Dual::ratio_sqrt(&p, &(&(&a * &a) + &(&b * &b))))
        }
        (K::Distance, Shape::PointLine { point, line }) => {
            let x = l.point(point);
            let (d, m) = l.line3(line);
            let w = v::sub(&v::cross3(&x, &d), &m);
            measure(Dual::ratio(&v::norm2(&w), &v::norm2(&d)))
        }
        (K::Distance, Shape::PointPlane { point, plane }) => {
            let x = l.point(point);
            let (n, delta) = l.plane(plane);
            measure(Dual::ratio_sqrt(&(&v::dot(&n, &x) + &delta), &v::norm2(&n)))
        }
        (K::Distance, Shape::LineLine(p, q)) if !d3 => {
            let [a1, b1, c1] = l.line2(p);
            let [a2, b2, c2] = l.line2(q);
            measure(parallel_offset(&[a1, b1], &c1, &[a2, b2], &c2))
        }
        (K::Distance, Shape::LineLine(p, q)) => {
            let (d1, m1) = l.line3(p);
            let (d2, m2) = l.line3(q);
            if variant == 0 {
                // Skew lines: (d1·m2 + d2·m1) / |d1 × d2|.
                let num = &v::dot(&d1, &m2) + &v::dot(&d2, &m1);
                measure(Dual::ratio_sqrt(&num, &v::norm2(&v::cross3(&d1, &d2))))
            } else {
                // Parallel lines: |(d1·d2) m1 − |d1|² m2|² / ((d1·d2)² |d1|²).
                let k = v::dot(&d1, &d2);
                let w = v::sub(&v::scale(&m1, &k), &v::scale(&m2, &v::norm2(&d1)));
                measure(Dual::ratio(&v::norm2(&w), &(&(&k * &k) * &v::norm2(&d1))))
            }
        }
        (K::Distance, Shape::PlanePlane(p, q)) => {
            let (n1, e1) = l.plane(p);
            let (n2, e2) = l.plane(q);
            measure(parallel_offset(&n1, &e1, &n2, &e2))
        }
        (K::Angle, Shape::LineLine(p, q)) if !d3 => {
            // Oriented angle between normals: its gradient is proportional to
            // cross0·∇dot − dot0·∇cross, regular at every angle (0° and 90° included).
            let (n1, n2) = (l.normal2(p), l.normal2(q));
            let dot = v::dot(&n1, &n2);
            let cross = v::cross2(&n1, &n2);
            let row = &dot.scale(&cross.value) - &cross.scale(&dot.value);
            measure(row)
        }
        (K::Angle, Shape::LineLine(p, q)) => measure(cosine(&l.direction3(p), &l.direction3(q))),
        (K::Angle, Shape::LinePlane { line, plane }) => {
            let d = l.direction3(line);
            let (n, _) = l.plane(plane);
            measure(cosine(&d, &n))
        }
        (K::Angle, Shape::PlanePlane(p, q)) => {
            let (n1, _) = l.plane(p);
            let (n2, _) = l.plane(q);
            measure(cosine(&n1, &n2))
        }
        (K::Parallel, Shape::LineLine(p, q)) if !d3 => {
            let [a1, b1, _] = l.line2(p);
            let [a2, b2, _] = l.line2(q);
            exact(vec![v::cross2(&[a1, b1], &[a2, b2])])
        }
        (K::Parallel, Shape::LineLine(p, q)) => exact(v::cross3(&l.line3(p).0, &l.line3(q).0)),
        (K::Parallel, Shape::PlanePlane(p, q)) => exact(v::cross3(&l.plane(p).0, &l.plane(q).0)),
        (K::Parallel, Shape::LinePlane { line, plane }) => {
            exact(vec![v::dot(&l.direction3(line), &l.plane(plane).0)])
        }
        (K::Perpendicular, Shape::LineLine(p, q)) if !d3 => {
            exact(vec![v::dot(&l.normal2(p), &l.normal2(q))])
        }
        (K::Perpendicular, Shape::LineLine(p, q)) => {
            exact(vec![v::dot(&l.direction3(p), &l.direction3(q))])
        }
        (K::Perpendicular, Shape::PlanePlane(p, q)) => {
            exact(vec![v::dot(&l.plane(p).0, &l.plane(q).0)])
        }
        (K::Perpendicular, Shape::LinePlane { line, plane }) => {
            exact(v::cross3(&l.direction3(line), &l.plane(plane).0))
        }
        (K::Incident, Shape::PointLine { point, line }) if !d3 => {
            let x = l.point(point);
            let [a, b, c0] = l.line2(line);
            exact(vec![&(&(&a * &x[0]) + &(&b * &x[1])) + &c0])
        }
        (K::Incident, Shape::PointLine { point, line }) => {
            let x = l.point(point);
            let (d, m) = l.line3(line);
            exact(v::sub(&v::cross3(&x, &d), &m))
        }
        (K::Incident, Shape::PointPlane { point, plane }) => {
            let (n, delta) = l.plane(plane);
            exact(vec![&v::dot(&n, &l.point(point)) + &delta])
        }
        (K::Incident, Shape::PointCircle { point, circle: round })
        | (K::Incident, Shape::PointSphere { point, sphere: round }) => {
            let (c0, r) = l.round(round);
            exact(vec![&v::norm2(&v::sub(&l.point(point), &c0)) - &(&r * &r)])
        }
        (K::Incident, Shape::LinePlane { line, plane }) => {
            // The line lies in the plane: n·d = 0 and n × m = δ d (a point x of the line has
            // m = x × d, so n × m = x (n·d) − d (n·x) = δ d).
            let (d, m) = l.line3(line);
            let (n, delta) = l.plane(plane);
            let mut rows = vec![v::dot(&n, &d)];
            rows.extend(v::sub(&v::cross3(&n, &m), &v::scale(&d, &delta)));
            exact(rows)
        }
        (K::Tangent, Shape::LineCircle { line, circle }) => {
            let [a, b, c0] = l.line2(line);
            let (c, r) = l.round(circle);
            let s = &(&(&a * &c[0]) + &(&b * &c[1])) + &c0;
            let n2 = &(&a * &a) + &(&b * &b);
            exact(vec![&(&s * &s) - &(&(&r * &r) * &n2)])
        }
        (K::Tangent, Shape::PlaneSphere { plane, sphere }) => {
            let (n, delta) = l.plane(plane);
            let (c, r) = l.round(sphere);
            let s = &v::dot(&n, &c) + &delta;
            exact(vec![&(&s * &s) - &(&(&r * &r) * &v::norm2(&n))])
        }
        (K::Tangent, Shape::CircleCircle(p, q)) | (K::Tangent, Shape::SphereSphere(p, q)) => {
            // External (variant 0) or internal (variant 1) tangency.
            let (c1, r1) = l.round(p);
            let (c2, r2) = l.round(q);
            let rr = if variant == 0 { &r1 + &r2 } else { &r1 - &r2 };
            exact(vec![&v::norm2(&v::sub(&c1, &c2)) - &(&rr * &rr)])
        }
        (K::Radius, Shape::Round(e)) => measure(l.round(e).1),
        (K::EqualLength, Shape::SegmentSegment(s, t)) => {
            let (p1, q1) = l.segment(s);
            let (p2, q2) = l.segment(t);
            exact(vec![&v::norm2(&v::sub(&q1, &p1)) - &v::norm2(&v::sub(&q2, &p2))])
        }
        (K::Midpoint, Shape::PointSegment { point, segment }) => {
            let m = l.point(point);
            let (p, q) = l.segment(segment);
            let two = Dual::int(2);
            exact(
                m.iter().zip(p.iter().zip(&q)).map(|(m, (p, q))| &(&two * m) - &(p + q)).collect(),
            )
        }
        (K::Symmetric, Shape::Symmetric { a, b, axis }) => {
            let (x, y) = (l.point(a), l.point(b));
            let [la, lb, lc] = l.line2(axis);
            let s = v::add(&x, &y);
            let d = v::sub(&x, &y);
            let two = Dual::int(2);
            let on_axis = &(&(&la * &s[0]) + &(&lb * &s[1])) + &(&two * &lc);
            let across = v::cross2(&[la, lb], &d);
            exact(vec![on_axis, across])
        }
        (K::Horizontal, Shape::Line(e)) => {
            let [a, _] = l.normal2(e);
            exact(vec![a])
        }
        (K::Vertical, Shape::Line(e)) => {
            let [_, b] = l.normal2(e);
            exact(vec![b])
        }
        (K::Fix, Shape::Single(e)) => {
            let mut rows = Vec::new();
            for b in system.base_entities(e) {
                let x = l.coords(b);
                let Some(s) = sketch(b) else { continue };
                let homogeneous = x.len() == s.len()
                    && matches!(
                        system.entity(b).geometry,
                        Geometry::Line { .. } | Geometry::Plane { .. }
                    );
                if homogeneous {
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
            exact(rows)
        }
        // Unreachable for a validated system: the model's signature table only produces the
        // shapes handled above.
        _ => exact(Vec::new()),
    }
}

fn system_is_3d<F: Field>(l: &Local<'_, F>) -> bool {
    l.system.dim() == Dim::Three
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

/// The entity-internal rows of an entity: the Plücker relation of a 3D line, and the
/// normalisation of homogeneous coordinates (gradient = the witness coordinates).
pub(crate) fn internal_rows<F: Field>(repr: Repr, x: &[Dual<F>]) -> Vec<Dual<F>> {
    let mut rows = Vec::new();
    if repr == Repr::Line3 {
        rows.push(v::dot(&x[0..3], &x[3..6]));
    }
    if repr.homogeneous() {
        let mut norm = Dual::int(0);
        for xi in x {
            norm = &norm + &xi.scale(&xi.value);
        }
        rows.push(norm);
    }
    rows
}

/// Whether the 2D lines, planes, or 3D lines of a two-entity shape are parallel at the
/// witness — the condition under which the parallel-offset distance is defined.
pub(crate) fn parallel_at<F: Field>(
    system: &System,
    shape: Shape,
    l: &Local<'_, F>,
    is_zero: &dyn Fn(&F) -> bool,
) -> bool {
    let zero = |xs: &[Dual<F>]| xs.iter().all(|x| is_zero(&x.value));
    match shape {
        Shape::LineLine(p, q) if system.dim() == Dim::Two => {
            let [a1, b1, _] = l.line2(p);
            let [a2, b2, _] = l.line2(q);
            is_zero(&v::cross2(&[a1, b1], &[a2, b2]).value)
        }
        Shape::LineLine(p, q) => zero(&v::cross3(&l.line3(p).0, &l.line3(q).0)),
        Shape::PlanePlane(p, q) => zero(&v::cross3(&l.plane(p).0, &l.plane(q).0)),
        _ => false,
    }
}

/// `(P, M)` of an equation `|P|² − |M|² = 0`.
pub(crate) type Split<F> = (Vec<Dual<F>>, Vec<Dual<F>>);

/// The quadratic equations written as a difference of squares `|P|² − |M|² = 0`, where `P`
/// and `M` are bilinear in the entities (so linear in any one of them when the others are
/// fixed). The constructive placement solves `P = R M` for a rational orthogonal `R`, which is
/// linear. `None` for constraints whose equations have no such form.
pub(crate) fn split<F: Field>(
    _system: &System,
    c: &Constraint,
    variant: usize,
    l: &Local<'_, F>,
) -> Option<Split<F>> {
    use ConstraintKind as K;
    match (c.kind, c.shape) {
        (K::Incident, Shape::PointCircle { point, circle: round })
        | (K::Incident, Shape::PointSphere { point, sphere: round }) => {
            let (c0, r) = l.round(round);
            Some((v::sub(&l.point(point), &c0), vec![r]))
        }
        (K::Tangent, Shape::LineCircle { line, circle }) => {
            let [a, b, c0] = l.line2(line);
            let (cc, r) = l.round(circle);
            let s = &(&(&a * &cc[0]) + &(&b * &cc[1])) + &c0;
            Some((vec![s], vec![&r * &a, &r * &b]))
        }
        (K::Tangent, Shape::PlaneSphere { plane, sphere }) => {
            let (n, delta) = l.plane(plane);
            let (cc, r) = l.round(sphere);
            Some((vec![&v::dot(&n, &cc) + &delta], v::scale(&n, &r)))
        }
        (K::Tangent, Shape::CircleCircle(p, q)) | (K::Tangent, Shape::SphereSphere(p, q)) => {
            let (c1, r1) = l.round(p);
            let (c2, r2) = l.round(q);
            let rr = if variant == 0 { &r1 + &r2 } else { &r1 - &r2 };
            Some((v::sub(&c1, &c2), vec![rr]))
        }
        (K::EqualLength, Shape::SegmentSegment(s, t)) => {
            let (p1, q1) = l.segment(s);
            let (p2, q2) = l.segment(t);
            Some((v::sub(&q1, &p1), v::sub(&q2, &p2)))
        }
        // u·v = 0 is |u + v|² = |u − v|² (polarisation): quadratic in a point shared by two
        // perpendicular segments (Thales).
        (K::Perpendicular, Shape::LineLine(p, q)) => {
            let (u, w) = if system_is_3d(l) {
                (l.direction3(p), l.direction3(q))
            } else {
                (l.normal2(p).to_vec(), l.normal2(q).to_vec())
            };
            Some((v::add(&u, &w), v::sub(&u, &w)))
        }
        _ => None,
    }
}
