//! Constructive placement of a rational witness (docs/design.md, "Witness").
//!
//! Entities are placed one at a time inside the solution set of their parameter-free
//! constraints to the entities already placed. Those constraints are linear in the entity
//! being placed (incidences, parallelism, perpendicularity, midpoints, symmetry, horizontal and
//! vertical, fixes: bilinear forms), except the quadratic ones (a point on a circle or a
//! sphere, tangencies, equal lengths), which all have the form `|P|² = |M|²` with `P`, `M`
//! linear in the entity: the placement picks a rational orthogonal matrix `R` (a Householder
//! reflection, exactly orthogonal for any rational vector) and solves the linear `P = R·M`.
//! That is the tangent half-angle parametrisation of rational points on circles, generalised:
//! a point on a circle `c + r·u` with `u` a rational unit vector, a circle through a point,
//! tangent to a line with a rational unit normal or to another circle, a segment of the same
//! length as another. Metric constraints (distances, angles, radii) are ignored: their values
//! are read off the witness.
//!
//! Every free choice is random (from the seed), near a preference: the sketch when there is
//! one, so that the witness keeps the sketch's chirality (which side, which tangency), else a
//! random position. The result is checked exactly against every parameter-free equation.
//!
//! The order is greedy: next comes the unplaced entity with the most degrees of constraint
//! towards the placed ones (ties: file order), so that determined entities are constructed
//! from their determiners; an entity whose equations have no rational solution is retried
//! when more of its neighbours are placed, and the placement fails if it never succeeds.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use gcs_model::rng::SplitMix64;
use gcs_model::{ConstraintIdx, ConstraintKind, EntityIdx, System};

use crate::dual::Dual;
use crate::laws;
use crate::layout::Layout;
use crate::qla::{self, Affine, Num, Q};
use crate::repr::{Draw, Snap};
use crate::views::Local;

/// How to place.
#[derive(Clone, Debug)]
pub(crate) struct PlaceOptions {
    /// Random seed.
    pub(crate) seed: u64,
    /// Amplitude of the random moves, relative to the model's scale.
    pub(crate) noise: f64,
    /// Place over the integers modulo 2^61 − 1 instead of ℚ ([`crate::qla::Num`]): square
    /// roots exist for half the residues, so tangencies, mirrors and intersections of circles
    /// that need an irrational coordinate over ℚ are placed; the sides (tangency branches) are
    /// still the preference's, the rest is random.
    pub(crate) modular: bool,
}

/// Why a placement failed: the entity that could not be placed and the constraints binding it
/// to the placed ones.
#[derive(Clone, Debug)]
pub(crate) struct PlaceFailure {
    pub(crate) entity: EntityIdx,
    pub(crate) constraints: Vec<ConstraintIdx>,
}

struct Placer<'a> {
    system: &'a System,
    layout: &'a Layout,
    /// Current coordinates: placed entities hold their placement, the others a preference.
    coords: Vec<Q>,
    pref: Vec<Q>,
    placed: Vec<bool>,
    /// Exact (parameter-free) constraints by base entity.
    adjacent: Vec<Vec<ConstraintIdx>>,
    /// Base entities of each constraint.
    bases: Vec<Vec<EntityIdx>>,
    /// Variant of each constraint (tangency branch) chosen from the preference.
    variant: Vec<usize>,
    rng: SplitMix64,
    scale: f64,
    noise: f64,
    /// Whether the placement runs modulo the prime.
    modular: bool,
    /// The entity being placed.
    current: Option<EntityIdx>,
    /// For each point, the other endpoints of the segments it is an endpoint of.
    partners: Vec<Vec<EntityIdx>>,
}

fn is_exact_kind(kind: ConstraintKind) -> bool {
    !kind.is_metric()
}

/// The sketch in layout coordinates, with random positions for entities that have none.
pub(crate) fn preferences(system: &System, layout: &Layout, rng: &mut SplitMix64) -> (Vec<Q>, f64) {
    let mut scale: f64 = 0.0;
    for e in system.entity_indices() {
        if let Some(s) = crate::sketch::sketch_coords_in::<Q>(system, e)
            && layout.repr(e).is_some_and(|r| !r.homogeneous())
        {
            for x in &s {
                scale = scale.max(qla::to_f64(x).abs());
            }
        }
    }
    let scale = if scale > 0.0 { scale } else { 10.0 };
    let mut pref = vec![Q::ZERO; layout.ncols()];
    for e in system.entity_indices() {
        let Some(repr) = layout.repr(e) else { continue };
        let cols = layout.columns(e);
        let s = crate::sketch::sketch_coords_in::<Q>(system, e).unwrap_or_else(|| {
            repr.random(&mut |draw| match draw {
                Draw::Position(k) => (0..k)
                    .map(|_| qla::approx(scale * (2.0 * rng.unit_f64() - 1.0), 1000))
                    .collect(),
                Draw::Length => vec![qla::approx(scale * (0.1 + 0.3 * rng.unit_f64()), 1000)],
            })
        });
        for (col, v) in cols.zip(s) {
            pref[col] = v;
        }
    }
    (pref, scale)
}

/// Places every entity; returns the witness coordinates or the entity that could not be
/// placed.
pub(crate) fn place(
    system: &System,
    layout: &Layout,
    pref: &[Q],
    scale: f64,
    options: &PlaceOptions,
) -> Result<Vec<Q>, PlaceFailure> {
    let nent = system.entities().len();
    let mut adjacent = vec![Vec::new(); nent];
    let mut bases = Vec::with_capacity(system.constraints().len());
    for ci in system.constraint_indices() {
        let b = system.constraint_base_entities(ci);
        let kind = system.constraint(ci).kind;
        // Modulo the prime, a fixed position is a parameter like a dimension (its rows do not
        // depend on it), read off the witness: with it free, a construction the fixes determine
        // completely (a point on two fixed circles) still has random choices, and so a square
        // root for half of them.
        let parameter = options.modular && kind == ConstraintKind::Fix;
        if is_exact_kind(kind) && !parameter {
            for e in &b {
                adjacent[e.index()].push(ci);
            }
        }
        bases.push(b);
    }
    let mut partners = vec![Vec::new(); nent];
    for e in system.entity_indices() {
        if let Some((a, b)) = system.segment_points(e) {
            partners[a.index()].push(b);
            partners[b.index()].push(a);
        }
    }
    let attempts = if nent <= 2000 { 8 } else { 2 };
    let mut rng = SplitMix64::new(options.seed ^ 0x5EED);
    let mut failure = None;
    for attempt in 0..attempts {
        // The first attempt breaks ties in file order, the others at random.
        let tiebreak: Vec<u64> =
            (0..nent as u64).map(|i| if attempt == 0 { i } else { rng.next_u64() }).collect();
        let mut p = Placer {
            system,
            layout,
            coords: pref.to_vec(),
            pref: pref.to_vec(),
            placed: vec![false; nent],
            adjacent: adjacent.clone(),
            bases: bases.clone(),
            variant: vec![0; system.constraints().len()],
            rng: SplitMix64::new(options.seed.wrapping_add(attempt as u64)),
            scale,
            noise: options.noise,
            modular: false,
            current: None,
            partners: partners.clone(),
        };
        p.choose_variants();
        if options.modular {
            // The branches were chosen at the rational preference; the rest runs modulo p.
            for x in p.coords.iter_mut().chain(p.pref.iter_mut()) {
                *x = Num::P(x.modular());
            }
            p.modular = true;
        }
        match p.run(&tiebreak) {
            Ok(()) => return Ok(p.coords),
            Err(f) => failure = Some(f),
        }
    }
    Err(failure.unwrap_or(PlaceFailure { entity: EntityIdx(0), constraints: Vec::new() }))
}

impl Placer<'_> {
    /// Tangency branches from the preference (the sketch's side).
    fn choose_variants(&mut self) {
        for ci in self.system.constraint_indices() {
            let c = self.system.constraint(ci);
            if !is_exact_kind(c.kind) {
                continue;
            }
            let local = Local::new(self.system, self.layout, &self.bases[ci.index()], &self.pref);
            let none = |_: EntityIdx| None;
            let nv = laws::law(c.signature, 0, &local, &none, false).variants;
            if nv < 2 {
                continue;
            }
            let best = (0..nv)
                .map(|v| {
                    let law = laws::law(c.signature, v, &local, &none, false);
                    let r: f64 = law.rows.iter().map(|r| qla::to_f64(&r.value).abs()).sum();
                    (r, v)
                })
                .fold((f64::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a });
            self.variant[ci.index()] = best.1;
        }
    }

    /// DOC of the constraints binding `e` to placed entities only.
    fn score(&self, e: EntityIdx) -> usize {
        self.ready(e).iter().map(|c| self.system.constraint(*c).doc).sum()
    }

    /// The exact constraints on `e` whose other base entities are all placed.
    fn ready(&self, e: EntityIdx) -> Vec<ConstraintIdx> {
        self.adjacent[e.index()]
            .iter()
            .copied()
            .filter(|c| self.bases[c.index()].iter().all(|b| *b == e || self.placed[b.index()]))
            .collect()
    }

    fn run(&mut self, tiebreak: &[u64]) -> Result<(), PlaceFailure> {
        let system = self.system;
        let mut heap: BinaryHeap<(usize, Reverse<u64>, u32)> = BinaryHeap::new();
        let mut score = vec![0usize; system.entities().len()];
        let mut failed_at: Vec<Option<usize>> = vec![None; system.entities().len()];
        for e in system.entity_indices() {
            if self.layout.repr(e).is_some() {
                score[e.index()] = self.score(e);
                heap.push((score[e.index()], Reverse(tiebreak[e.index()]), e.0));
            }
        }
        let mut last_failure = None;
        while let Some((s, _, i)) = heap.pop() {
            let e = EntityIdx(i);
            if self.placed[e.index()] || s != score[e.index()] {
                continue;
            }
            if failed_at[e.index()] == Some(s) {
                continue;
            }
            let ready = self.ready(e);
            if self.place_one(e, &ready) {
                self.placed[e.index()] = true;
                // Neighbours may now have more constraints towards placed entities.
                let mut touched: Vec<EntityIdx> = Vec::new();
                for c in &self.adjacent[e.index()] {
                    for b in &self.bases[c.index()] {
                        if !self.placed[b.index()] && !touched.contains(b) {
                            touched.push(*b);
                        }
                    }
                }
                for b in touched {
                    let s = self.score(b);
                    if s != score[b.index()] {
                        score[b.index()] = s;
                        heap.push((s, Reverse(tiebreak[b.index()]), b.0));
                    }
                }
            } else {
                failed_at[e.index()] = Some(s);
                last_failure = Some(PlaceFailure { entity: e, constraints: ready });
            }
        }
        if self.placed.iter().zip(system.entities()).all(|(p, ent)| *p || ent.kind().is_composite())
        {
            Ok(())
        } else {
            let first_unplaced = system
                .entity_indices()
                .find(|e| !self.placed[e.index()] && self.layout.repr(*e).is_some());
            Err(last_failure.unwrap_or(PlaceFailure {
                entity: first_unplaced.unwrap_or(EntityIdx(0)),
                constraints: Vec::new(),
            }))
        }
    }

    /// Linear equations making the normal of a 2D line or a plane parallel to a rational
    /// unit vector near the preference's normal.
    fn rational_normal(&mut self, pref: &[Q], n: usize) -> Vec<(Vec<Q>, Q)> {
        let k = if n == 3 { 2 } else { 3 };
        let w: Vec<f64> = pref[0..k].iter().map(qla::to_f64).collect();
        let Some(u) = self.unit_near(&w) else { return Vec::new() };
        parallel_to(&u, n, None)
    }

    /// Linear equations putting `x − other` along a rational unit vector near the direction
    /// from `other` to the preference `pref`.
    fn rational_direction(&mut self, pref: &[Q], other: &[Q]) -> Vec<(Vec<Q>, Q)> {
        let n = pref.len();
        let w: Vec<f64> =
            pref.iter().zip(other).map(|(a, b)| qla::to_f64(a) - qla::to_f64(b)).collect();
        let Some(u) = self.unit_near(&w) else { return Vec::new() };
        parallel_to(&u, n, Some(other))
    }

    /// A random unit vector with exact coordinates (2 or 3 of them, as `w`), from the
    /// rational parametrisation of the circle or the sphere ([`unit_at`]): over ℚ, at
    /// parameters moved at random near those of `w`'s direction (the sketch's side, never
    /// exactly `w`'s: a direction rounded to a few digits would put a line drawn horizontal
    /// exactly horizontal, parallel to every horizontal line, a special position the
    /// constraints do not ask for); modulo the prime, at uniform parameters (a residue has no
    /// direction: `w` is then meaningless, and a uniform choice is what makes the witness
    /// generic).
    fn unit_near(&mut self, w: &[f64]) -> Option<Vec<Q>> {
        if self.modular {
            let params: Vec<Q> = (0..w.len() - 1)
                .map(|_| Num::P(gcs_rank::ModP::new(self.rng.next_u64())))
                .collect();
            return unit_at(&params, false);
        }
        let (params, flip) = unit_params(w)?;
        let params: Vec<Q> = params
            .iter()
            .map(|t| qla::approx(t + 1e-3 * (2.0 * self.rng.unit_f64() - 1.0), 1_000_000))
            .collect();
        unit_at(&params, flip)
    }

    /// A small random move (over ℚ, near the preference); modulo the prime a uniform residue:
    /// there is no "near", and uniform choices are what makes a random point generic with
    /// overwhelming probability.
    fn random_small(&mut self) -> Q {
        if self.modular {
            return Num::P(gcs_rank::ModP::new(self.rng.next_u64()));
        }
        qla::approx(self.noise * self.scale * (2.0 * self.rng.unit_f64() - 1.0), 1_000_000)
    }

    /// Places `e` under its ready constraints; on success writes its coordinates.
    fn place_one(&mut self, e: EntityIdx, ready: &[ConstraintIdx]) -> bool {
        self.current = Some(e);
        let cols = self.layout.columns(e);
        let n = cols.len();
        let homogeneous = self.layout.repr(e).is_some_and(|r| r.homogeneous());
        let pref: Vec<Q> = self.pref[cols.clone()].to_vec();
        // Linearise every equation at the preference, and at a shifted point to tell linear
        // equations from quadratic ones.
        let delta: Vec<Q> =
            (0..n).map(|_| self.random_small() + Q::new(1, 7).unwrap_or(Q::ONE)).collect();
        let mut linear: Vec<(Vec<Q>, Q)> = Vec::new();
        let _ = &mut linear;
        let mut quads: Vec<(AffineMap, AffineMap)> = Vec::new();
        for &ci in ready {
            let variant = self.variant[ci.index()];
            let ([l0, l1], local) = self.laws_at(e, ci, variant, &pref, &delta);
            let linearised = |law: &laws::Law<Q>| -> Vec<Linearised> {
                law.rows.iter().map(|d| (d.value.clone(), restrict(d, &local, &cols))).collect()
            };
            let (f0, f1) = (linearised(&l0), linearised(&l1));
            let mut split = None;
            for (k, (r0, r1)) in f0.iter().zip(&f1).enumerate() {
                let g = &r0.1;
                let predicted = &r0.0 + &qla::dot(g, &delta);
                if predicted == r1.0 {
                    if g.iter().all(Q::is_zero) {
                        if !r0.0.is_zero() {
                            return false;
                        }
                        continue;
                    }
                    linear.push((g.clone(), qla::dot(g, &pref) - &r0.0));
                } else if let Some(Some(maps)) = {
                    if split.is_none() {
                        split = Some(split_maps([&l0, &l1], &local, &cols, &pref, &delta));
                    }
                    split.as_ref().and_then(|s| s.as_ref()).and_then(|s| s.get(k).cloned())
                } {
                    quads.push(maps);
                } else {
                    return false;
                }
            }
        }
        // Quadratic internal relations (the Plücker relation of a 3D line).
        for (p, m) in self.layout.repr(e).map(|r| r.internal_quadrics()).unwrap_or_default() {
            let map = |rows: Vec<Vec<i64>>| AffineMap {
                rows: rows
                    .into_iter()
                    .map(|r| (r.into_iter().map(Q::from).collect(), Q::ZERO))
                    .collect(),
            };
            quads.push((map(p), map(m)));
        }
        let Some(space) = qla::solve(n, &linear) else { return false };
        // A free line or plane gets a normal of rational length (a Pythagorean direction near
        // the preference): tangencies to it then have rational solutions.
        let repr = self.layout.repr(e);
        // A free endpoint of a segment whose other end is placed goes at a rational distance
        // from it (a rational unit direction): tangencies and equal lengths involving the
        // segment then have rational solutions.
        let snap = repr.map_or(Snap::Nothing, |r| r.snap());
        if snap == Snap::Direction && space.basis.len() == n {
            let placed_partner =
                self.partners[e.index()].iter().copied().find(|o| self.placed[o.index()]);
            if let Some(o) = placed_partner {
                let other: Vec<Q> = self.coords[self.layout.columns(o)].to_vec();
                let rows = self.rational_direction(&pref, &other);
                let mut with = linear.clone();
                with.extend(rows);
                if qla::solve(n, &with).is_some() {
                    linear = with;
                }
            }
        }
        if snap == Snap::Normal && normal_is_free(&space, n) {
            let rows = self.rational_normal(&pref, n);
            let mut with = linear.clone();
            with.extend(rows.iter().cloned());
            if let Some(snapped) = qla::solve(n, &with)
                && snapped.basis.len() + rows.len() == space.basis.len()
            {
                linear = with;
            }
        }
        let Some(space) = qla::solve(n, &linear) else { return false };
        let linear_only = quads.is_empty();
        let chosen = if quads.is_empty() {
            self.choose(&space, &pref, homogeneous)
        } else {
            self.solve_quadrics(n, &linear, &quads, &pref, homogeneous)
        };
        let Some(x) = chosen else { return false };
        if repr.is_some_and(|r| r.degenerate(&x)) {
            return false;
        }
        // A segment must keep two distinct points.
        for o in &self.partners[e.index()] {
            if self.placed[o.index()] && self.coords[self.layout.columns(*o)] == x[..] {
                return false;
            }
        }
        let old: Vec<Q> = self.coords[cols.clone()].to_vec();
        for (col, v) in cols.clone().zip(&x) {
            self.coords[col] = v.clone();
        }
        // Exact check of every ready equation (a solution of linear equations checked linear
        // satisfies them by construction).
        let ok = linear_only
            || ready.iter().all(|&ci| {
                let local =
                    Local::new(self.system, self.layout, &self.bases[ci.index()], &self.coords);
                let none = |_: EntityIdx| None;
                let sketch = |b: EntityIdx| crate::sketch::sketch_coords_in::<Q>(self.system, b);
                let c = self.system.constraint(ci);
                let sketch: &laws::SketchFn<'_, Q> =
                    if c.kind == ConstraintKind::Fix { &sketch } else { &none };
                let law = laws::law(c.signature, self.variant[ci.index()], &local, sketch, false);
                law.rows.iter().all(|r| r.value.is_zero())
            });
        if !ok {
            for (col, v) in cols.zip(old) {
                self.coords[col] = v;
            }
        }
        ok
    }

    /// The law of `ci` (with its difference-of-squares form) with entity `e` at `pref` and at
    /// `pref + delta`, and the local columns of the constraint.
    fn laws_at(
        &mut self,
        e: EntityIdx,
        ci: ConstraintIdx,
        variant: usize,
        pref: &[Q],
        delta: &[Q],
    ) -> ([laws::Law<Q>; 2], Vec<usize>) {
        let signature = self.system.constraint(ci).signature;
        let cols = self.layout.columns(e);
        let shifted: Vec<Q> = pref.iter().zip(delta).map(|(a, b)| a + b).collect();
        let mut at = |x: &[Q]| {
            for (col, v) in cols.clone().zip(x) {
                self.coords[col] = v.clone();
            }
            let local = Local::new(self.system, self.layout, &self.bases[ci.index()], &self.coords);
            let sketch = |b: EntityIdx| crate::sketch::sketch_coords_in::<Q>(self.system, b);
            (laws::law(signature, variant, &local, &sketch, true), local.cols)
        };
        let (l0, local_cols) = at(pref);
        let (l1, _) = at(&shifted);
        for (col, v) in cols.zip(pref) {
            self.coords[col] = v.clone();
        }
        ([l0, l1], local_cols)
    }

    /// A point of `space` near the preference, moved at random inside it.
    fn choose(&mut self, space: &Affine, pref: &[Q], homogeneous: bool) -> Option<Vec<Q>> {
        let mut t = space.project(pref);
        let norm: f64 = if homogeneous {
            pref.iter().map(|x| qla::to_f64(x).powi(2)).sum::<f64>().sqrt().max(1e-9) / self.scale
        } else {
            1.0
        };
        for ti in t.iter_mut() {
            let r = self.random_small();
            *ti += r * qla::approx(norm, 1_000_000);
        }
        let x = space.point(&t);
        if homogeneous && x.iter().all(Q::is_zero) {
            // The preference projects to zero: take a random element of the subspace.
            let t: Vec<Q> = (0..space.basis.len()).map(|_| self.random_small() + Q::ONE).collect();
            return Some(space.point(&t));
        }
        Some(x)
    }

    /// Solves the linear equations plus quadrics `|P|² = |M|²`.
    fn solve_quadrics(
        &mut self,
        n: usize,
        linear: &[(Vec<Q>, Q)],
        quads: &[(AffineMap, AffineMap)],
        pref: &[Q],
        homogeneous: bool,
    ) -> Option<Vec<Q>> {
        let mut linear = linear.to_vec();
        let mut rest: Vec<&(AffineMap, AffineMap)> = Vec::new();
        for q in quads {
            // |P|² = |M|² where P and M keep a fixed direction factorises over ℚ when the
            // product of the lengths of the directions is rational: p·|dP|² = ±m·|dP||dM|
            // (a circle tangent to a line with a rational unit normal…). The sign is the
            // preference's side.
            if let Some(rows) = factorise(q, pref) {
                linear.extend(rows);
                continue;
            }
            // Quadrics with the same quadratic part differ by a linear equation (two circles
            // through a point, two points on a circle…).
            if let Some(first) = rest.first() {
                let h = q.0.quadratic_form(&q.1, n);
                let h0 = first.0.quadratic_form(&first.1, n);
                if let Some(lambda) = proportional(&h, &h0) {
                    let (g, c) = q.0.linear_part(&q.1, n);
                    let (g0, c0) = first.0.linear_part(&first.1, n);
                    let row: Vec<Q> = g.iter().zip(&g0).map(|(a, b)| a - &(&lambda * b)).collect();
                    let rhs = -(c - &lambda * &c0);
                    linear.push((row, rhs));
                    continue;
                }
            }
            rest.push(q);
        }
        let space = qla::solve(n, &linear)?;
        let Some((p, m)) = rest.first() else {
            return self.choose(&space, pref, homogeneous);
        };
        // P = R·M for a rational orthogonal R near the preference, a few tries.
        for attempt in 0..6 {
            let k = p.rows.len().max(m.rows.len());
            let r = self.orthogonal_near(p, m, pref, k, attempt);
            let mut sys = linear.clone();
            for i in 0..k {
                // P_i(x) − Σ_j R_ij M_j(x) = 0
                let mut row = p.rows.get(i).map_or(vec![Q::ZERO; n], |r| r.0.clone());
                let mut rhs = p.rows.get(i).map_or(Q::ZERO, |r| -r.1.clone());
                for (j, mrow) in m.rows.iter().enumerate() {
                    for (a, b) in row.iter_mut().zip(&mrow.0) {
                        *a -= &r[i][j] * b;
                    }
                    rhs += &r[i][j] * &mrow.1;
                }
                sys.push((row, rhs));
            }
            if let Some(sub) = qla::solve(n, &sys) {
                if homogeneous && sub.basis.is_empty() {
                    continue;
                }
                let x = self.choose(&sub, pref, homogeneous)?;
                let repr = self.layout.repr(self.current?);
                if repr.is_some_and(|r| r.degenerate(&x)) {
                    continue;
                }
                if rest.iter().all(|(p2, m2)| p2.norm2(&x) == m2.norm2(&x)) {
                    return Some(x);
                }
            }
        }
        // A one-parameter family: intersect with the quadric, if the roots are rational.
        self.univariate(&space, p, m, pref, homogeneous)
            .filter(|x| rest.iter().all(|(p2, m2)| p2.norm2(x) == m2.norm2(x)))
    }

    fn univariate(
        &mut self,
        space: &Affine,
        p: &AffineMap,
        m: &AffineMap,
        pref: &[Q],
        homogeneous: bool,
    ) -> Option<Vec<Q>> {
        let (x0, w) = match (space.basis.len(), homogeneous) {
            (1, false) => (space.x0.clone(), space.basis[0].clone()),
            (2, true) => (space.basis[0].clone(), space.basis[1].clone()),
            (1, true) => {
                let x = space.basis[0].clone();
                return (p.norm2(&x) == m.norm2(&x)).then_some(x);
            }
            (0, false) => {
                let x = space.x0.clone();
                return (p.norm2(&x) == m.norm2(&x)).then_some(x);
            }
            _ => return None,
        };
        // |P(x0 + t w)|² − |M(x0 + t w)|² = α t² + β t + γ.
        let coef = |map: &AffineMap| {
            let a: Vec<Q> = map.rows.iter().map(|(g, _)| qla::dot(g, &w)).collect();
            let b: Vec<Q> = map.rows.iter().map(|(g, c)| qla::dot(g, &x0) + c).collect();
            (qla::dot(&a, &a), qla::dot(&a, &b) * Q::from(2_i64), qla::dot(&b, &b))
        };
        let (pa, pb, pc) = coef(p);
        let (ma, mb, mc) = coef(m);
        let (a, b, c) = (pa - ma, pb - mb, pc - mc);
        let t_pref = {
            let ww = qla::dot(&w, &w);
            let d: Vec<Q> = pref.iter().zip(&x0).map(|(u, v)| u - v).collect();
            if ww.is_zero() { Q::ZERO } else { qla::dot(&d, &w) / ww }
        };
        let roots: Vec<Q> = if a.is_zero() {
            if b.is_zero() {
                return None;
            }
            vec![-c / b]
        } else {
            let disc = &b * &b - Q::from(4_i64) * &a * &c;
            let s = qla::sqrt(&disc)?;
            let two_a = &a * Q::from(2_i64);
            vec![(-&b + &s) / &two_a, (-&b - &s) / &two_a]
        };
        let t = roots.into_iter().min_by_key(|t| {
            let d = qla::to_f64(&(t - &t_pref)).abs();
            (d * 1e9) as u64
        })?;
        Some(x0.iter().zip(&w).map(|(x, wi)| x + &t * wi).collect())
    }

    /// A rational orthogonal `k×k` matrix mapping `M(pref)`'s direction near `P(pref)`'s.
    fn orthogonal_near(
        &mut self,
        p: &AffineMap,
        m: &AffineMap,
        pref: &[Q],
        k: usize,
        attempt: usize,
    ) -> Vec<Vec<Q>> {
        let pv = p.eval_f64(pref, k);
        let mv = m.eval_f64(pref, k);
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let (np, nm) = (norm(&pv), norm(&mv));
        if k == 1 {
            let same = pv[0] * mv[0] >= 0.0;
            let s = if attempt.is_multiple_of(2) { same } else { !same };
            return vec![vec![if s { Q::ONE } else { -Q::ONE }]];
        }
        if self.modular {
            // A uniform rotation: residues have no direction to be near.
            let mut reflection = || {
                (0..8).find_map(|_| {
                    let v: Vec<Q> =
                        (0..k).map(|_| Num::P(gcs_rank::ModP::new(self.rng.next_u64()))).collect();
                    qla::reflection(&v)
                })
            };
            let ha = reflection().unwrap_or_else(|| identity(k));
            let hb = reflection().unwrap_or_else(|| identity(k));
            return qla::matmul(&hb, &ha);
        }
        // A rotation (det +1: the product of two Householder reflections, exactly orthogonal
        // for rational vectors) taking M's direction near P's. Rotations, not single
        // reflections: for the Plücker relation |d + m|² = |d − m|² a reflection would force
        // the direction into a plane; a rotation gives the Cayley parametrisation.
        let jitter = 1e-3 * (1.0 + attempt as f64);
        let mut random = |scale: f64| -> Vec<f64> {
            (0..k).map(|_| scale * (2.0 * self.rng.unit_f64() - 1.0)).collect()
        };
        let a: Vec<f64> = random(1.0);
        let noise = random(jitter);
        let aq: Vec<Q> = a.iter().map(|x| qla::approx(*x, 1 << 20)).collect();
        let ha = qla::reflection(&aq).unwrap_or_else(|| identity(k));
        let (phat, mhat): (Vec<f64>, Vec<f64>) = if np > 1e-12 && nm > 1e-12 {
            (pv.iter().map(|x| x / np).collect(), mv.iter().map(|x| x / nm).collect())
        } else {
            (vec![0.0; k], vec![0.0; k])
        };
        // u = H_a m̂; then H_b with b = u − p̂ maps u to p̂.
        let haf: Vec<Vec<f64>> = ha.iter().map(|r| r.iter().map(qla::to_f64).collect()).collect();
        let u: Vec<f64> =
            haf.iter().map(|r| r.iter().zip(&mhat).map(|(x, y)| x * y).sum()).collect();
        let mut b: Vec<f64> = u.iter().zip(&phat).map(|(x, y)| x - y).collect();
        if norm(&b) < 1e-6 {
            // H_a already does it: any b orthogonal to p̂ keeps it.
            let r = random(1.0);
            let dot: f64 = r.iter().zip(&phat).map(|(x, y)| x * y).sum();
            b = r.iter().zip(&phat).map(|(x, y)| x - dot * y).collect();
        }
        let bq: Vec<Q> = b.iter().zip(&noise).map(|(x, n)| qla::approx(x + n, 1 << 24)).collect();
        let hb = qla::reflection(&bq).unwrap_or_else(|| identity(k));
        qla::matmul(&hb, &ha)
    }
}

/// Linear equations making `x − origin` (or `x` when there is no origin), restricted to its
/// first `u.len()` coordinates, parallel to `u`: one in 2D, two (independent: the components
/// opposite the largest of `u`) in 3D.
fn parallel_to(u: &[Q], n: usize, origin: Option<&[Q]>) -> Vec<(Vec<Q>, Q)> {
    // (x − o)_i u_j − (x − o)_j u_i = 0
    let row = |i: usize, j: usize| {
        let mut g = vec![Q::ZERO; n];
        g[i] = u[j].clone();
        g[j] = -u[i].clone();
        let rhs = origin.map_or(Q::ZERO, |o| &o[i] * &u[j] - &o[j] * &u[i]);
        (g, rhs)
    };
    if u.len() == 2 {
        vec![row(0, 1)]
    } else {
        let big = (0..3)
            .max_by(|a, b| qla::to_f64(&u[*a]).abs().total_cmp(&qla::to_f64(&u[*b]).abs()))
            .unwrap_or(2);
        (0..3).filter(|i| *i != big).map(|i| row(i, big)).collect()
    }
}

/// Whether the normal of a line or plane (its first `n − 1` coordinates) can point anywhere in
/// the solution space.
fn normal_is_free(space: &Affine, n: usize) -> bool {
    let k = n - 1;
    let rows: Vec<(Vec<Q>, Q)> = space.basis.iter().map(|v| (v[0..k].to_vec(), Q::ZERO)).collect();
    // The rank of the normal parts of the basis: k minus the dimension of the solutions of
    // the transposed system is awkward here; count independent rows by elimination.
    rank(&rows, k) == k
}

fn rank(rows: &[(Vec<Q>, Q)], n: usize) -> usize {
    match qla::solve(n, rows) {
        // The solution set of the homogeneous system has dimension n − rank.
        Some(s) => n - s.basis.len(),
        None => n,
    }
}

/// The parameters of the direction of `w` in the rational parametrisation of the unit circle
/// or sphere ([`unit_at`]) and whether it is flipped, `None` for a zero vector.
fn unit_params(w: &[f64]) -> Option<(Vec<f64>, bool)> {
    let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt();
    if norm < 1e-300 {
        return None;
    }
    let w: Vec<f64> = w.iter().map(|x| x / norm).collect();
    if w.len() == 2 {
        // t = tan(θ/2), on the half circle of positive x (the other is flipped).
        let flip = w[0] < 0.0;
        let (c, s) = if flip { (-w[0], -w[1]) } else { (w[0], w[1]) };
        Some((vec![s / (1.0 + c)], flip))
    } else {
        // Stereographic from the pole opposite to w's z sign.
        let flip = w[2] < 0.0;
        let z = if flip { -w[2] } else { w[2] };
        Some((vec![w[0] / (1.0 + z), w[1] / (1.0 + z)], flip))
    }
}

/// The unit vector of parameters `params` (2D: `((1 − t²), 2t)/(1 + t²)`, the tangent
/// half-angle; 3D: the inverse stereographic projection of `(s, t)`), negated (2D) or
/// mirrored in the plane `z = 0` (3D) when `flip`; exact for exact parameters, `None` when the
/// denominator vanishes (only modulo the prime, in 3D).
fn unit_at(params: &[Q], flip: bool) -> Option<Vec<Q>> {
    let one = Q::ONE;
    let two = Q::from(2_i64);
    if let [t] = params {
        let d = &one + t * t;
        if d.is_zero() {
            return None;
        }
        let u = [(&one - t * t) / &d, &two * t / &d];
        Some(u.into_iter().map(|x| if flip { -x } else { x }).collect())
    } else {
        let (s, t) = (params.first()?, params.get(1)?);
        let d = &one + s * s + t * t;
        if d.is_zero() {
            return None;
        }
        let zq = (&one - s * s - t * t) / &d;
        Some(vec![&two * s / &d, &two * t / &d, if flip { -zq } else { zq }])
    }
}

fn identity(k: usize) -> Vec<Vec<Q>> {
    (0..k).map(|i| (0..k).map(|j| if i == j { Q::ONE } else { Q::ZERO }).collect()).collect()
}

/// `x ↦ (λ·x + λ0) d`: an affine map into a fixed direction `d`, if it is one.
fn fixed_direction(map: &AffineMap) -> Option<(Vec<Q>, Vec<Q>, Q)> {
    let i0 = map.rows.iter().position(|(g, c)| !c.is_zero() || g.iter().any(|x| !x.is_zero()))?;
    let (g0, c0) = &map.rows[i0];
    let mut d = Vec::with_capacity(map.rows.len());
    for (g, c) in &map.rows {
        // row = d_i · row0
        let k = g.iter().zip(g0).chain(std::iter::once((c, c0))).find(|(_, b)| !b.is_zero())?;
        let di = k.0 / k.1;
        let same = g.iter().zip(g0).all(|(a, b)| *a == &di * b) && *c == &di * c0;
        if !same {
            return None;
        }
        d.push(di);
    }
    Some((d, g0.clone(), c0.clone()))
}

/// Linear equations equivalent to `|P|² = |M|²` (on the preference's branch) when `P` and
/// `M` have fixed directions whose lengths have a rational product, or when one side is
/// identically zero.
fn factorise(q: &(AffineMap, AffineMap), pref: &[Q]) -> Option<Vec<(Vec<Q>, Q)>> {
    let (p, m) = q;
    let zero =
        |map: &AffineMap| map.rows.iter().all(|(g, c)| c.is_zero() && g.iter().all(Q::is_zero));
    let as_rows = |map: &AffineMap| -> Vec<(Vec<Q>, Q)> {
        map.rows.iter().map(|(g, c)| (g.clone(), -c.clone())).collect()
    };
    if zero(m) {
        return Some(as_rows(p));
    }
    if zero(p) {
        return Some(as_rows(m));
    }
    let (dp, lp, lp0) = fixed_direction(p)?;
    let (dm, lm, lm0) = fixed_direction(m)?;
    let (np, nm) = (qla::dot(&dp, &dp), qla::dot(&dm, &dm));
    let l = qla::sqrt(&(&np * &nm))?;
    // p(x)·|dP|² − σ·m(x)·L = 0 with σ = ±1 from the preference.
    let pv = qla::dot(&lp, pref) + &lp0;
    let mv = qla::dot(&lm, pref) + &lm0;
    let plus = qla::to_f64(&(&pv * &np - &mv * &l)).abs();
    let minus = qla::to_f64(&(&pv * &np + &mv * &l)).abs();
    let sigma = if plus <= minus { Q::ONE } else { -Q::ONE };
    let row: Vec<Q> = lp.iter().zip(&lm).map(|(a, b)| a * &np - &sigma * b * &l).collect();
    let rhs = -(&lp0 * &np - &sigma * &lm0 * &l);
    Some(vec![(row, rhs)])
}

/// The difference-of-squares form of a quadratic constraint, from its laws at `pref` and at
/// `pref + delta`, as affine maps of the coordinates of the entity being placed (`cols`;
/// checked affine), one per candidate row.
fn split_maps(
    laws: [&laws::Law<Q>; 2],
    local: &[usize],
    cols: &std::ops::Range<usize>,
    pref: &[Q],
    delta: &[Q],
) -> Option<Vec<Option<(AffineMap, AffineMap)>>> {
    let conv = |ds: &[Dual<Q>]| -> Vec<(Q, Vec<Q>)> {
        ds.iter().map(|d| (d.value.clone(), restrict(d, local, cols))).collect()
    };
    let (p0, m0) = laws[0].split.as_ref()?;
    let (p1, m1) = laws[1].split.as_ref()?;
    let affine = |z0: &[(Q, Vec<Q>)], z1: &[(Q, Vec<Q>)]| -> Option<AffineMap> {
        let mut rows = Vec::new();
        for (a, b) in z0.iter().zip(z1) {
            if &a.0 + &qla::dot(&a.1, delta) != b.0 {
                return None;
            }
            // Value at x: a.0 + g·(x − pref) = g·x + (a.0 − g·pref).
            rows.push((a.1.clone(), &a.0 - &qla::dot(&a.1, pref)));
        }
        Some(AffineMap { rows })
    };
    let pm = affine(&conv(p0), &conv(p1)).zip(affine(&conv(m0), &conv(m1)));
    Some(vec![pm])
}

/// `λ` with `a = λ b` (both nonzero), if any.
fn proportional(a: &[Vec<Q>], b: &[Vec<Q>]) -> Option<Q> {
    let mut lambda: Option<Q> = None;
    for (ra, rb) in a.iter().zip(b) {
        for (x, y) in ra.iter().zip(rb) {
            match (x.is_zero(), y.is_zero()) {
                (true, true) => {}
                (false, false) => {
                    let l = x / y;
                    if lambda.as_ref().is_some_and(|m| *m != l) {
                        return None;
                    }
                    lambda = Some(l);
                }
                _ => return None,
            }
        }
    }
    lambda
}

/// A gradient restricted to the columns of one entity.
fn restrict<F: gcs_rank::Field>(
    d: &Dual<F>,
    local_cols: &[usize],
    cols: &std::ops::Range<usize>,
) -> Vec<F> {
    let mut out = vec![F::zero(); cols.len()];
    for (i, col) in local_cols.iter().enumerate() {
        if cols.contains(col)
            && let Some(g) = d.grad.get(i)
        {
            out[col - cols.start] = g.clone();
        }
    }
    out
}

/// The value and gradient of an equation at a point.
type Linearised = (Q, Vec<Q>);

/// `x ↦ (g_i · x + c_i)_i`.
#[derive(Clone, Debug)]
struct AffineMap {
    rows: Vec<(Vec<Q>, Q)>,
}

impl AffineMap {
    fn norm2(&self, x: &[Q]) -> Q {
        self.rows.iter().map(|(g, c)| qla::dot(g, x) + c).map(|v| &v * &v).sum()
    }

    fn eval_f64(&self, x: &[Q], k: usize) -> Vec<f64> {
        let mut out: Vec<f64> =
            self.rows.iter().map(|(g, c)| qla::to_f64(&(qla::dot(g, x) + c))).collect();
        out.resize(k, 0.0);
        out
    }

    /// The matrix `H` of the quadratic part of `|self|² − |other|²`.
    fn quadratic_form(&self, other: &AffineMap, n: usize) -> Vec<Vec<Q>> {
        let mut h = vec![vec![Q::ZERO; n]; n];
        for (sign, map) in [(Q::ONE, self), (-Q::ONE, other)] {
            for (g, _) in &map.rows {
                for i in 0..n {
                    for j in 0..n {
                        h[i][j] += &sign * &g[i] * &g[j];
                    }
                }
            }
        }
        h
    }

    /// The linear part `g·x` and constant `c` of `|self|² − |other|²`.
    fn linear_part(&self, other: &AffineMap, n: usize) -> (Vec<Q>, Q) {
        let mut g = vec![Q::ZERO; n];
        let mut c = Q::ZERO;
        for (sign, map) in [(Q::ONE, self), (-Q::ONE, other)] {
            for (gi, ci) in &map.rows {
                for (a, b) in g.iter_mut().zip(gi) {
                    *a += &sign * b * ci * Q::from(2_i64);
                }
                c += &sign * ci * ci;
            }
        }
        (g, c)
    }
}
