//! Degree of rigidity (DOR): how many independent displacements a set of entities admits.
//!
//! Flow paper §2.4 and the survey's Definition 6: the DOR of a subsystem is "the number of
//! independent displacements it admits". Here it is computed from its definition: with `G` the
//! group of direct displacements (dim 3 in 2D, 6 in 3D) and `Stab(X)` the subgroup that maps
//! every entity of `X` onto itself,
//!
//! ```text
//! DOR(X) = dim G − dim Stab(X)
//! ```
//!
//! It depends on geometric properties of the solution (two lines in 2D: 3, but 2 if they are
//! parallel). [`DorOracle`] abstracts where those properties come from; [`RuleDor`] reads them
//! from explicit constraints with a rule table, [`WitnessDor`](crate::WitnessDor) (exact rank of
//! the trivial motions restricted to `X` at a witness) can be plugged in instead.
//!
//! # The rule table of [`RuleDor`]
//!
//! Circles and spheres count as their centre (a displacement cannot change a radius); a segment
//! stands for its two points. Each row is the stabiliser computed by hand, `D` = dim G.
//!
//! **2D** (`D` = 3: two translations, one rotation)
//!
//! | set | stabiliser (continuous part) | DOR |
//! |---|---|---|
//! | one point (or centre) | rotations about it (1) | 2 |
//! | one line | translations along it (1) | 2 |
//! | two distinct points | none | 3 |
//! | point and line (on it or not) | none | 3 |
//! | two secant lines | none (the rotation by π is not continuous) | 3 |
//! | two parallel lines | translations along them (1) | 2 |
//! | three collinear points | none | 3 |
//!
//! **3D** (`D` = 6: three translations, three rotations)
//!
//! | set | stabiliser | DOR |
//! |---|---|---|
//! | one point | rotations about it (3) | 3 |
//! | one line | rotations about it, translations along it (2) | 4 |
//! | one plane | translations in it, rotations about its normals (3) | 3 |
//! | two points | rotations about their line (1) | 5 |
//! | point on a line | rotations about the line (1) | 5 |
//! | point off a line | none | 6 |
//! | point and plane | rotations about the normal through the point (1) | 5 |
//! | two parallel lines | translations along them (1) | 5 |
//! | two secant or skew lines | none | 6 |
//! | line and plane, line ⊥ plane | rotations about the line (1) | 5 |
//! | line and plane, line ∥ plane or in it | translations along the line (1) | 5 |
//! | line and plane, oblique | none | 6 |
//! | two parallel planes | translations in them, rotations about their normals (3) | 3 |
//! | two secant planes | translations along their common line (1) | 5 |
//! | three collinear points (or points on one line, with it) | rotations about the line (1) | 5 |
//! | three non-collinear points | none | 6 |
//! | two points and a plane, their line ⊥ plane | rotations about that line (1) | 5 |
//! | point, line ⊥ plane through the point, plane | rotations about the line (1) | 5 |
//! | point and two parallel planes | rotations about the normal through the point (1) | 5 |
//! | three parallel lines | translations along them (1) | 5 |
//! | two parallel lines ∥ a plane | translations along them (1) | 5 |
//! | line ⊥ or ∥ two parallel planes | as line and plane (1) | 5 |
//! | line ∥ two secant planes | translations along the line (1) | 5 |
//! | planes whose normals span a plane | translations along the common direction (1) | 5 |
//! | any other set | none | 6 |
//!
//! A larger set is evaluated greedily: start from its element of largest DOR and add, while
//! one exists, the element that increases the DOR of the chosen set the most. This is exact:
//! if `DOR(Y) < DOR(X)` for `Y ⊂ X`, then some `x ∈ X` has `Stab(Y ∪ {x}) ⊊ Stab(Y)` (the
//! stabilisers' Lie algebras are subspaces), and the chosen set never needs more than 2
//! elements in 2D and 3 in 3D, which is the flow paper's result that DOR-minimal subsets have
//! 2 and 3 objects (§4.3): the stabiliser dimensions of points, lines and planes go 3 → 1 → 0
//! or 2 → 1 → 0, SO(3) having no 2-dimensional subgroup.
//!
//! **Disagreement with the survey.** The survey (§2.2.1, after Definition 6) quotes "two
//! parallel planes 4" and "3 collinear points 2" (2D). Both contradict the definition: two
//! parallel planes are kept in place by the 2 translations in their direction and the rotations
//! about their common normal direction, so DOR = 6 − 3 = 3; three distinct collinear points in
//! the plane are moved by every non-trivial displacement, so DOR = 3 (it is 5 in 3D, where the
//! rotation about their line fixes them). This crate implements the definition.
//!
//! # Facts read from the constraints
//!
//! A rule table can only see what the constraints say explicitly; everything else is assumed
//! generic. [`RuleDor`] reads, from **all** constraints of the system (a DOR is a property of
//! the solution, like the witness would give):
//!
//! - coincident points (`Coincident`, transitively) are one point;
//! - a point is on a line when `Incident` says so, on a segment's line when `Incident`
//!   or `Midpoint` says so, and a segment's endpoints are on its line; two lines or segments
//!   that share two distinct points are the same line (applied until nothing changes);
//! - directions: `Parallel` between lines (or segments) and between planes, a `Distance`
//!   between two 2D lines or two planes (it only exists for parallel ones), `Perpendicular`
//!   between a line and a plane in 3D (the line is along the normal); in 2D also
//!   `Perpendicular` between lines (two lines perpendicular to a third are parallel),
//!   `Horizontal` and `Vertical`; all transitively;
//! - a line is parallel to a plane when `Parallel` says so or it lies in it (`Incident`, or
//!   two of its points on the plane); 3D `Perpendicular` between lines or between planes
//!   record orthogonal directions.
//!
//! `Angle` constraints are not read (their value is a dimension, not a property), nor are
//! consequences that need theorem proving (Pappus, Desargues…): that is what
//! [`WitnessDor`](crate::WitnessDor) is for.

use std::collections::{HashMap, HashSet};

use gcs_model::{Dim, EntityClass, EntityIdx, Metric, Signature, System};

/// Computes the degree of rigidity of a set of entities of a system.
///
/// Implementations must be monotone (a superset never has a smaller DOR, flow paper Lemma 1)
/// and return at most the number of displacements of the dimension. A segment in `entities`
/// stands for its two points. The reference frame of absolute constraints is never passed: a
/// set containing it has the full DOR, and the algorithms handle that themselves.
pub trait DorOracle {
    /// The number of independent displacements that move the entities.
    fn dor(&self, system: &System, entities: &[EntityIdx]) -> usize;

    /// A short name for reports (`"rules"`, `"witness"`).
    fn name(&self) -> &str {
        "custom"
    }
}

/// The DOR from a rule table over explicit geometric facts (see the module documentation for
/// the table and the facts).
///
/// Build it with [`RuleDor::for_system`] to read the facts once; [`RuleDor::new`] reads them
/// again on every call (correct, but slow inside Over-Rigid). A `RuleDor` built for one system
/// and called with another notices it (different sizes or name) and reads the other's facts.
///
/// # Example
/// ```
/// use gcs_model::System;
/// use gcs_rigidity::{DorOracle, RuleDor};
///
/// let text = r#"System(dim: 3, entities: [
///     Line(id: "L", at: [[0, 0, 0], [1, 0, 0]]),
///     Point(id: "p", at: [2, 0, 0]), Point(id: "q", at: [0, 5, 1]) ],
///   constraints: [ Incident(id: "i", a: "p", b: "L") ])"#;
/// let system = System::from_ron_str(text, None).unwrap();
/// let dor = RuleDor::for_system(&system);
/// let [l, p, q] = [0, 1, 2].map(gcs_model::EntityIdx);
/// assert_eq!(dor.dor(&system, &[l]), 4);
/// assert_eq!(dor.dor(&system, &[l, p]), 5); // a point on a line
/// assert_eq!(dor.dor(&system, &[l, q]), 6); // a point off it
/// ```
#[derive(Clone, Debug, Default)]
pub struct RuleDor {
    facts: Option<Facts>,
}

impl RuleDor {
    /// A rule oracle that reads the facts of the system it is called with, on every call.
    pub fn new() -> RuleDor {
        RuleDor { facts: None }
    }

    /// A rule oracle with the facts of `system` read once.
    pub fn for_system(system: &System) -> RuleDor {
        RuleDor { facts: Some(Facts::new(system)) }
    }
}

impl DorOracle for RuleDor {
    fn dor(&self, system: &System, entities: &[EntityIdx]) -> usize {
        match &self.facts {
            Some(f) if f.fits(system) => f.dor(system, entities),
            _ => Facts::new(system).dor(system, entities),
        }
    }

    fn name(&self) -> &str {
        "rules"
    }
}

/// A normalised element of a set: coincident points merged, lines merged by carrier.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Elem {
    Point(u32),
    Line(u32),
    Plane(u32),
}

/// Union-find with a parity bit per node (parity = 1: perpendicular in 2D).
#[derive(Clone, Debug, Default)]
struct ParityUnionFind {
    parent: Vec<u32>,
    parity: Vec<u8>,
}

impl ParityUnionFind {
    fn new(n: usize) -> ParityUnionFind {
        ParityUnionFind { parent: (0..n as u32).collect(), parity: vec![0; n] }
    }

    fn find(&mut self, x: u32) -> (u32, u8) {
        let mut path = Vec::new();
        let mut r = x;
        while self.parent[r as usize] != r {
            path.push(r);
            r = self.parent[r as usize];
        }
        // Compress: parity to the root is the xor along the path.
        let mut acc = 0u8;
        for &v in path.iter().rev() {
            acc ^= self.parity[v as usize];
            self.parity[v as usize] = acc;
            self.parent[v as usize] = r;
        }
        (r, if path.is_empty() { 0 } else { self.parity[x as usize] })
    }

    /// Records `x ~ y` with relative parity `p`. A contradiction (two lines said both parallel
    /// and perpendicular) keeps the first statement.
    fn union(&mut self, x: u32, y: u32, p: u8) {
        let (rx, px) = self.find(x);
        let (ry, py) = self.find(y);
        if rx != ry {
            self.parent[rx as usize] = ry;
            self.parity[rx as usize] = px ^ py ^ p;
        }
    }
}

fn plain_find(parent: &mut [u32], x: u32) -> u32 {
    let mut r = x;
    while parent[r as usize] != r {
        r = parent[r as usize];
    }
    let mut v = x;
    while parent[v as usize] != r {
        let next = parent[v as usize];
        parent[v as usize] = r;
        v = next;
    }
    r
}

/// The explicit geometric facts of a system, closed under the few rules listed in the module
/// documentation.
#[derive(Clone, Debug)]
struct Facts {
    dim: Dim,
    name: String,
    entity_count: usize,
    constraint_count: usize,
    /// Per entity: the point class of a point, circle or sphere (its centre).
    point_class: Vec<u32>,
    /// Per entity: the carrier (merged line) of a line or segment.
    carrier: Vec<u32>,
    /// Per carrier root: the point classes on it, sorted.
    carrier_points: HashMap<u32, Vec<u32>>,
    /// Per point class: the carrier roots through it.
    point_carriers: HashMap<u32, Vec<u32>>,
    /// Per carrier root: its direction (root, parity); per plane entity: its normal.
    line_dir: HashMap<u32, (u32, u8)>,
    plane_normal: HashMap<u32, (u32, u8)>,
    /// Orthogonal direction roots (3D), both orders.
    orth: HashMap<u32, HashSet<u32>>,
}

const NONE: u32 = u32::MAX;

impl Facts {
    fn new(system: &System) -> Facts {
        let dim = system.dim();
        let n = system.entities().len();
        // Points: coincidence classes.
        let mut pparent: Vec<u32> = (0..n as u32).collect();
        for c in system.constraints() {
            // Circles and spheres count as their centres: concentric circles coincide, and a
            // point at a centre is that centre.
            if let Signature::CoincidentPoints(a, b)
            | Signature::ConcentricCircles(a, b)
            | Signature::CenterPoint { point: a, round: b } = c.signature
            {
                let (ra, rb) = (plain_find(&mut pparent, a.0), plain_find(&mut pparent, b.0));
                if ra != rb {
                    pparent[ra as usize] = rb;
                }
            }
        }
        let mut point_class = vec![NONE; n];
        for e in system.entity_indices() {
            // Circles and spheres count as their centres.
            match system.entity(e).kind().class() {
                EntityClass::Point | EntityClass::Circle | EntityClass::Sphere => {
                    point_class[e.index()] = plain_find(&mut pparent, e.0);
                }
                EntityClass::Line | EntityClass::Plane | EntityClass::Curve => {}
            }
        }
        // Carriers: one per line and per segment, carrying point classes.
        let mut carrier = vec![NONE; n];
        let mut points_on: Vec<Vec<u32>> = Vec::new();
        for e in system.entity_indices() {
            // One carrier per line-like entity, with the points it is built on.
            if system.entity(e).kind().class() == EntityClass::Line {
                carrier[e.index()] = points_on.len() as u32;
                let parts = system.entity(e).geometry.parts();
                points_on.push(parts.iter().map(|p| point_class[p.index()]).collect());
            }
        }
        for c in system.constraints() {
            if let Signature::IncidentPointLine { point, line: carried }
            | Signature::Midpoint { point, segment: carried } = c.signature
            {
                points_on[carrier[carried.index()] as usize].push(point_class[point.index()]);
            }
        }
        let carriers = points_on.len();
        let mut cparent: Vec<u32> = (0..carriers as u32).collect();
        // Merge carriers sharing two distinct points, until stable.
        loop {
            let mut merged = false;
            let mut by_pair: HashMap<(u32, u32), u32> = HashMap::new();
            for k in 0..carriers as u32 {
                if plain_find(&mut cparent, k) != k {
                    continue;
                }
                let pts = &mut points_on[k as usize];
                pts.sort_unstable();
                pts.dedup();
                let pts = pts.clone();
                'pairs: for i in 0..pts.len() {
                    for j in i + 1..pts.len() {
                        let key = (pts[i], pts[j]);
                        match by_pair.get(&key) {
                            Some(&other) => {
                                let (ra, rb) =
                                    (plain_find(&mut cparent, other), plain_find(&mut cparent, k));
                                if ra != rb {
                                    cparent[rb as usize] = ra;
                                    let moved = std::mem::take(&mut points_on[rb as usize]);
                                    points_on[ra as usize].extend(moved);
                                    merged = true;
                                    break 'pairs;
                                }
                            }
                            None => {
                                by_pair.insert(key, k);
                            }
                        }
                    }
                }
            }
            if !merged {
                break;
            }
        }
        for c in carrier.iter_mut().filter(|c| **c != NONE) {
            *c = plain_find(&mut cparent, *c);
        }
        let mut carrier_points = HashMap::new();
        let mut point_carriers: HashMap<u32, Vec<u32>> = HashMap::new();
        for k in 0..carriers as u32 {
            if plain_find(&mut cparent, k) == k {
                let mut pts = std::mem::take(&mut points_on[k as usize]);
                pts.sort_unstable();
                pts.dedup();
                for &p in &pts {
                    point_carriers.entry(p).or_default().push(k);
                }
                carrier_points.insert(k, pts);
            }
        }
        // Directions: nodes 0..carriers for carriers, then one per plane, then "horizontal".
        let planes: Vec<EntityIdx> = system
            .entity_indices()
            .filter(|&e| system.entity(e).kind().class() == EntityClass::Plane)
            .collect();
        let plane_node: HashMap<u32, u32> =
            planes.iter().enumerate().map(|(i, p)| (p.0, (carriers + i) as u32)).collect();
        let horizontal = (carriers + planes.len()) as u32;
        let mut dirs = ParityUnionFind::new(carriers + planes.len() + 1);
        let two_d = dim == Dim::Two;
        let mut orth_raw: Vec<(u32, u32)> = Vec::new();
        // Planes' points and lines, for "line in plane" closure (3D).
        let mut plane_points: HashMap<u32, HashSet<u32>> = HashMap::new();
        let mut plane_lines: HashMap<u32, HashSet<u32>> = HashMap::new();
        for c in system.constraints() {
            let line_node = |e: EntityIdx| carrier[e.index()];
            use Signature as S;
            match c.signature {
                S::ParallelLineLine(a, b) => dirs.union(line_node(a), line_node(b), 0),
                // A distance between two lines only exists for parallel lines in the plane
                // (format §1), and between two planes only for parallel planes.
                S::Metric(Metric::DistanceLineLine(a, b)) if two_d => {
                    dirs.union(line_node(a), line_node(b), 0)
                }
                S::Metric(Metric::DistancePlanePlane(a, b)) => {
                    dirs.union(plane_node[&a.0], plane_node[&b.0], 0)
                }
                S::PerpendicularLineLine(a, b) => {
                    if two_d {
                        dirs.union(line_node(a), line_node(b), 1);
                    } else {
                        orth_raw.push((line_node(a), line_node(b)));
                    }
                }
                S::Horizontal(a) => dirs.union(line_node(a), horizontal, 0),
                S::Vertical(a) => dirs.union(line_node(a), horizontal, 1),
                S::ParallelPlanePlane(a, b) => dirs.union(plane_node[&a.0], plane_node[&b.0], 0),
                S::PerpendicularPlanePlane(a, b) => {
                    orth_raw.push((plane_node[&a.0], plane_node[&b.0]))
                }
                S::PerpendicularLinePlane { line, plane } => {
                    dirs.union(line_node(line), plane_node[&plane.0], 0)
                }
                S::ParallelLinePlane { line, plane } => {
                    orth_raw.push((line_node(line), plane_node[&plane.0]))
                }
                S::IncidentLinePlane { line, plane } => {
                    plane_lines.entry(plane.0).or_default().insert(line_node(line));
                }
                S::IncidentPointPlane { point, plane } => {
                    plane_points.entry(plane.0).or_default().insert(point_class[point.index()]);
                }
                // No rule: these state nothing about directions or planes' contents that the
                // rules chain (metric values are not read; incidences to lines are carriers,
                // above).
                S::CoincidentPoints(..)
                | S::ConcentricCircles(..)
                | S::CenterPoint { .. }
                | S::Metric(Metric::DistancePointPoint(..))
                | S::Metric(Metric::DistancePointLine { .. })
                | S::Metric(Metric::DistancePointPlane { .. })
                | S::Metric(Metric::DistanceLineLine(..))
                | S::Metric(Metric::AngleLineLine(..))
                | S::Metric(Metric::AnglePlanePlane(..))
                | S::Metric(Metric::AngleLinePlane { .. })
                | S::IncidentPointLine { .. }
                | S::IncidentPointCircle { .. }
                | S::IncidentPointSphere { .. }
                | S::TangentLineCircle { .. }
                | S::TangentCircleCircle(..)
                | S::TangentPlaneSphere { .. }
                | S::TangentSphereSphere(..)
                | S::Metric(Metric::Radius(_))
                | S::EqualLength(..)
                | S::Midpoint { .. }
                | S::Symmetric { .. }
                | S::SymmetricAboutPoint { .. }
                | S::EqualRadius(..)
                | S::TangentAtLineCircle { .. }
                | S::TangentAtCircleCircle { .. }
                | S::Metric(Metric::DistanceX(..))
                | S::Metric(Metric::DistanceY(..))
                | S::Metric(Metric::LengthRatio(..))
                | S::Metric(Metric::DistanceCircleCircle(..))
                | S::EqualAngle { .. }
                | S::EqualDistance(..)
                | S::SplinePoint { .. }
                | S::Fix(_) => {}
            }
        }
        // Closure: a line in a plane puts its points on the plane; a line with two points on
        // a plane lies in it.
        for (plane, lines) in plane_lines.iter_mut() {
            let pts = plane_points.entry(*plane).or_default();
            loop {
                let mut changed = false;
                for l in lines.iter() {
                    for p in &carrier_points[l] {
                        changed |= pts.insert(*p);
                    }
                }
                let new_lines: Vec<u32> = carrier_points
                    .iter()
                    .filter(|(k, on)| {
                        !lines.contains(k) && on.iter().filter(|p| pts.contains(p)).count() >= 2
                    })
                    .map(|(k, _)| *k)
                    .collect();
                for k in new_lines {
                    changed |= lines.insert(k);
                }
                if !changed {
                    break;
                }
            }
        }
        for (plane, pts) in &plane_points {
            if plane_lines.contains_key(plane) {
                continue;
            }
            for (k, on) in &carrier_points {
                if on.iter().filter(|p| pts.contains(p)).count() >= 2 {
                    orth_raw.push((*k, plane_node[plane]));
                }
            }
        }
        for (plane, lines) in &plane_lines {
            for l in lines {
                orth_raw.push((*l, plane_node[plane]));
            }
        }
        // Carriers that merged share their direction.
        for k in 0..carriers as u32 {
            let root = plain_find(&mut cparent, k);
            dirs.union(k, root, 0);
        }
        let mut line_dir = HashMap::new();
        for &k in carrier_points.keys() {
            line_dir.insert(k, dirs.find(k));
        }
        let mut plane_normal = HashMap::new();
        for (&p, &node) in &plane_node {
            plane_normal.insert(p, dirs.find(node));
        }
        let mut orth: HashMap<u32, HashSet<u32>> = HashMap::new();
        for (a, b) in orth_raw {
            let (ra, rb) = (dirs.find(a).0, dirs.find(b).0);
            orth.entry(ra).or_default().insert(rb);
            orth.entry(rb).or_default().insert(ra);
        }
        Facts {
            dim,
            name: system.name().to_owned(),
            entity_count: n,
            constraint_count: system.constraints().len(),
            point_class,
            carrier,
            carrier_points,
            point_carriers,
            line_dir,
            plane_normal,
            orth,
        }
    }

    fn fits(&self, system: &System) -> bool {
        self.entity_count == system.entities().len()
            && self.constraint_count == system.constraints().len()
            && self.name == system.name()
    }

    /// The normalised elements of a set of entities.
    fn elements(&self, system: &System, entities: &[EntityIdx]) -> Vec<Elem> {
        let mut out = Vec::new();
        let add = |e: EntityIdx, out: &mut Vec<Elem>| {
            if e.index() >= self.entity_count {
                return;
            }
            let kind = system.entity(e).kind();
            match kind.class() {
                EntityClass::Point | EntityClass::Circle | EntityClass::Sphere => {
                    out.push(Elem::Point(self.point_class[e.index()]))
                }
                // A composite entity (a segment, a B-spline) counts as its points, added by
                // the caller.
                EntityClass::Line if kind.is_composite() => {}
                EntityClass::Curve => {}
                EntityClass::Line => out.push(Elem::Line(self.carrier[e.index()])),
                EntityClass::Plane => out.push(Elem::Plane(e.0)),
            }
        };
        for &e in entities {
            if e.index() >= self.entity_count {
                continue;
            }
            if system.entity(e).kind().is_composite() {
                for p in system.entity(e).geometry.parts() {
                    add(p, &mut out);
                }
            } else {
                add(e, &mut out);
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    fn dor(&self, system: &System, entities: &[EntityIdx]) -> usize {
        let elems = self.elements(system, entities);
        self.dor_of(&elems)
    }

    /// Greedy evaluation (see the module documentation).
    fn dor_of(&self, elems: &[Elem]) -> usize {
        let full = self.dim.displacements();
        let Some(&first) =
            elems.iter().max_by_key(|e| (self.table(&[**e]), std::cmp::Reverse(**e)))
        else {
            return 0;
        };
        let cap = if self.dim == Dim::Two { 2 } else { 3 };
        let mut chosen = vec![first];
        let mut current = self.table(&chosen);
        while current < full && chosen.len() < cap {
            let mut best: Option<(usize, Elem)> = None;
            for &e in elems {
                if chosen.contains(&e) {
                    continue;
                }
                let mut trial = chosen.clone();
                trial.push(e);
                let v = self.table(&trial);
                if v > current && best.is_none_or(|(bv, _)| v > bv) {
                    best = Some((v, e));
                }
            }
            match best {
                Some((v, e)) => {
                    chosen.push(e);
                    current = v;
                }
                None => break,
            }
        }
        current
    }

    // ---- predicates ----

    fn parallel_lines(&self, a: u32, b: u32) -> bool {
        a == b || self.line_dir.get(&a) == self.line_dir.get(&b)
    }

    fn planes_parallel(&self, a: u32, b: u32) -> bool {
        a == b || self.plane_normal[&a].0 == self.plane_normal[&b].0
    }

    fn on_line(&self, p: u32, l: u32) -> bool {
        self.carrier_points.get(&l).is_some_and(|pts| pts.binary_search(&p).is_ok())
    }

    fn line_perp_plane(&self, l: u32, plane: u32) -> bool {
        self.line_dir[&l].0 == self.plane_normal[&plane].0
    }

    fn orthogonal(&self, a: u32, b: u32) -> bool {
        self.orth.get(&a).is_some_and(|s| s.contains(&b))
    }

    fn line_parallel_plane(&self, l: u32, plane: u32) -> bool {
        self.orthogonal(self.line_dir[&l].0, self.plane_normal[&plane].0)
    }

    /// A known line through all the given points.
    fn common_line(&self, pts: &[u32]) -> Option<u32> {
        let first = self.point_carriers.get(&pts[0])?;
        first.iter().copied().find(|&l| pts[1..].iter().all(|&p| self.on_line(p, l)))
    }

    /// The DOR of a normalised set of at most 2 (2D) or 3 (3D) elements.
    fn table(&self, set: &[Elem]) -> usize {
        let mut s = set.to_vec();
        s.sort_unstable();
        s.dedup();
        if self.dim == Dim::Two {
            return match s.as_slice() {
                [] => 0,
                [_] => 2,
                [Elem::Line(a), Elem::Line(b)] if self.parallel_lines(*a, *b) => 2,
                _ => 3,
            };
        }
        use Elem::{Line as L, Plane as P, Point as Q};
        match s.as_slice() {
            [] => 0,
            [Q(_)] | [P(_)] => 3,
            [L(_)] => 4,
            [Q(_), Q(_)] | [Q(_), P(_)] => 5,
            [Q(p), L(l)] if self.on_line(*p, *l) => 5,
            [L(a), L(b)] if self.parallel_lines(*a, *b) => 5,
            [L(l), P(p)] if self.line_perp_plane(*l, *p) || self.line_parallel_plane(*l, *p) => 5,
            [P(a), P(b)] if self.planes_parallel(*a, *b) => 3,
            [P(_), P(_)] => 5,
            [Q(a), Q(b), Q(c)] if self.common_line(&[*a, *b, *c]).is_some() => 5,
            [Q(a), Q(b), L(l)] if self.on_line(*a, *l) && self.on_line(*b, *l) => 5,
            [Q(a), Q(b), P(p)] if self.line_through_perp(*a, *b, *p) => 5,
            [Q(q), L(l), P(p)] if self.line_perp_plane(*l, *p) && self.on_line(*q, *l) => 5,
            [Q(_), P(a), P(b)] if self.planes_parallel(*a, *b) => 5,
            [L(a), L(b), L(c)] if self.parallel_lines(*a, *b) && self.parallel_lines(*b, *c) => 5,
            [L(a), L(b), P(p)]
                if self.parallel_lines(*a, *b) && self.line_parallel_plane(*a, *p) =>
            {
                5
            }
            [L(l), P(a), P(b)]
                if (self.line_parallel_plane(*l, *a) && self.line_parallel_plane(*l, *b))
                    || (self.planes_parallel(*a, *b) && self.line_perp_plane(*l, *a)) =>
            {
                5
            }
            [P(a), P(b), P(c)] => self.three_planes(*a, *b, *c),
            _ => 6,
        }
    }

    /// Two distinct points whose known line is perpendicular to a plane.
    fn line_through_perp(&self, a: u32, b: u32, plane: u32) -> bool {
        let normal = self.plane_normal[&plane].0;
        self.point_carriers.get(&a).is_some_and(|ls| {
            ls.iter().any(|l| self.on_line(b, *l) && self.line_dir[l].0 == normal)
        })
    }

    /// Three distinct planes: 3 if parallel, 5 if their normals span a plane (two parallel,
    /// or a known direction parallel to all three), else 6.
    fn three_planes(&self, a: u32, b: u32, c: u32) -> usize {
        let normals: HashSet<u32> = [a, b, c].iter().map(|p| self.plane_normal[p].0).collect();
        match normals.len() {
            1 => 3,
            2 => 5,
            _ => {
                let mut common: Option<HashSet<u32>> = None;
                for n in &normals {
                    let o = self.orth.get(n).cloned().unwrap_or_default();
                    common = Some(match common {
                        None => o,
                        Some(c) => c.intersection(&o).copied().collect(),
                    });
                }
                if common.is_some_and(|c| !c.is_empty()) { 5 } else { 6 }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcs_model::number::int;
    use gcs_model::{ConstraintKind, SystemBuilder};

    fn pt(b: &mut SystemBuilder, id: &str, c: &[i64]) -> EntityIdx {
        b.point(id, Some(c.iter().map(|x| int(*x)).collect())).unwrap()
    }

    fn line(b: &mut SystemBuilder, id: &str, p: &[i64], q: &[i64]) -> EntityIdx {
        let v = |c: &[i64]| c.iter().map(|x| int(*x)).collect::<Vec<_>>();
        b.line(id, Some([v(p), v(q)])).unwrap()
    }

    fn plane(b: &mut SystemBuilder, id: &str, p: &[i64], n: &[i64]) -> EntityIdx {
        let v = |c: &[i64]| c.iter().map(|x| int(*x)).collect::<Vec<_>>();
        b.plane(id, Some([v(p), v(n)])).unwrap()
    }

    fn k(b: &mut SystemBuilder, kind: ConstraintKind, id: &str, args: &[&str]) {
        b.constraint(kind, id, args, None).unwrap();
    }

    #[test]
    fn table_2d() {
        let mut b = SystemBuilder::new("t2", Dim::Two);
        let p = pt(&mut b, "p", &[0, 0]);
        let q = pt(&mut b, "q", &[1, 0]);
        let r = pt(&mut b, "r", &[2, 0]);
        let coin = pt(&mut b, "coin", &[0, 0]);
        let a = line(&mut b, "A", &[0, 0], &[1, 0]);
        let bl = line(&mut b, "B", &[0, 1], &[1, 1]);
        let c = line(&mut b, "C", &[0, 2], &[1, 2]);
        let d = line(&mut b, "D", &[0, 0], &[0, 1]);
        let e = line(&mut b, "E", &[5, 0], &[5, 1]);
        let h = line(&mut b, "H", &[0, 7], &[1, 7]);
        let circle = b.circle("k", Some(vec![int(3), int(3)]), Some(int(1))).unwrap();
        k(&mut b, ConstraintKind::Parallel, "ab", &["A", "B"]);
        k(&mut b, ConstraintKind::Parallel, "bc", &["B", "C"]);
        k(&mut b, ConstraintKind::Perpendicular, "ad", &["A", "D"]);
        k(&mut b, ConstraintKind::Perpendicular, "ce", &["C", "E"]);
        k(&mut b, ConstraintKind::Horizontal, "hh", &["H"]);
        k(&mut b, ConstraintKind::Incident, "p_on_a", &["p", "A"]);
        k(&mut b, ConstraintKind::Incident, "q_on_a", &["q", "A"]);
        k(&mut b, ConstraintKind::Incident, "r_on_a", &["r", "A"]);
        k(&mut b, ConstraintKind::Coincident, "pc", &["p", "coin"]);
        let s = b.build();
        let o = RuleDor::for_system(&s);
        assert_eq!(o.name(), "rules");
        for single in [p, a, circle] {
            assert_eq!(o.dor(&s, &[single]), 2);
        }
        assert_eq!(o.dor(&s, &[]), 0);
        assert_eq!(o.dor(&s, &[p, q]), 3);
        assert_eq!(o.dor(&s, &[p, coin]), 2, "coincident points are one point");
        assert_eq!(o.dor(&s, &[p, a]), 3, "a point on a line");
        assert_eq!(o.dor(&s, &[p, q, r]), 3, "three collinear points: the definition, not 2");
        assert_eq!(o.dor(&s, &[a, bl]), 2);
        assert_eq!(o.dor(&s, &[a, c]), 2, "parallelism is transitive");
        assert_eq!(o.dor(&s, &[d, e]), 2, "two perpendiculars to parallel lines are parallel");
        assert_eq!(o.dor(&s, &[a, d]), 3);
        assert_eq!(o.dor(&s, &[a, bl, c]), 2);
        assert_eq!(o.dor(&s, &[a, bl, d]), 3);
        assert_eq!(o.dor(&s, &[h, a]), 3, "H is horizontal, A is not known to be");
        assert_eq!(o.dor(&s, &[circle, p]), 3);
        // The unbuilt oracle agrees.
        assert_eq!(RuleDor::new().dor(&s, &[a, c]), 2);
    }

    #[test]
    fn table_3d() {
        let mut b = SystemBuilder::new("t3", Dim::Three);
        let l = line(&mut b, "L", &[0, 0, 0], &[1, 0, 0]);
        let m = line(&mut b, "M", &[0, 1, 0], &[1, 1, 0]);
        let n = line(&mut b, "N", &[0, 0, 5], &[0, 1, 5]);
        let p = pt(&mut b, "p", &[0, 0, 0]);
        let q = pt(&mut b, "q", &[1, 0, 0]);
        let r = pt(&mut b, "r", &[2, 0, 0]);
        let off = pt(&mut b, "off", &[0, 3, 3]);
        let pa = plane(&mut b, "Pa", &[0, 0, 0], &[0, 0, 1]);
        let pb = plane(&mut b, "Pb", &[0, 0, 2], &[0, 0, 1]);
        let pc = plane(&mut b, "Pc", &[0, 0, 0], &[1, 0, 0]);
        let pd = plane(&mut b, "Pd", &[0, 0, 0], &[0, 1, 0]);
        let pe = plane(&mut b, "Pe", &[0, 0, 0], &[0, 1, 1]);
        let perp = line(&mut b, "Z", &[0, 0, 0], &[0, 0, 1]);
        let sphere = b.sphere("S", Some(vec![int(9), int(9), int(9)]), Some(int(1))).unwrap();
        k(&mut b, ConstraintKind::Parallel, "lm", &["L", "M"]);
        k(&mut b, ConstraintKind::Incident, "p_on_l", &["p", "L"]);
        k(&mut b, ConstraintKind::Incident, "q_on_l", &["q", "L"]);
        k(&mut b, ConstraintKind::Incident, "r_on_l", &["r", "L"]);
        k(&mut b, ConstraintKind::Parallel, "ab", &["Pa", "Pb"]);
        k(&mut b, ConstraintKind::Perpendicular, "z_perp", &["Z", "Pa"]);
        k(&mut b, ConstraintKind::Incident, "p_on_z", &["p", "Z"]);
        k(&mut b, ConstraintKind::Incident, "l_in_pa", &["L", "Pa"]);
        k(&mut b, ConstraintKind::Incident, "l_in_pd", &["L", "Pd"]);
        k(&mut b, ConstraintKind::Incident, "l_in_pe", &["L", "Pe"]);
        let s = b.build();
        let o = RuleDor::for_system(&s);
        let d = |set: &[EntityIdx]| o.dor(&s, set);
        assert_eq!(d(&[p]), 3);
        assert_eq!(d(&[l]), 4);
        assert_eq!(d(&[pa]), 3);
        assert_eq!(d(&[sphere]), 3);
        assert_eq!(d(&[p, q]), 5, "two points");
        assert_eq!(d(&[p, l]), 5, "point on a line");
        assert_eq!(d(&[off, l]), 6, "point off a line");
        assert_eq!(d(&[l, m]), 5, "two parallel lines");
        assert_eq!(d(&[l, n]), 6, "two skew lines");
        assert_eq!(
            d(&[pa, pb]),
            3,
            "two parallel planes: 3 (the survey's 4 contradicts the definition)"
        );
        assert_eq!(d(&[pa, pc]), 5, "two secant planes");
        assert_eq!(d(&[p, q, r]), 5, "three collinear points");
        assert_eq!(d(&[p, q, off]), 6, "three non-collinear points");
        assert_eq!(d(&[p, pa]), 5);
        assert_eq!(d(&[perp, pa]), 5, "line perpendicular to a plane");
        assert_eq!(d(&[l, pa]), 5, "line in a plane");
        assert_eq!(d(&[n, pa]), 6, "N is not known to be parallel to Pa");
        assert_eq!(d(&[p, perp, pa]), 5, "point on the perpendicular line");
        assert_eq!(d(&[off, perp, pa]), 6);
        assert_eq!(d(&[p, pa, pb]), 5, "point and two parallel planes");
        assert_eq!(d(&[l, m, pa]), 5, "two parallel lines in a plane");
        assert_eq!(d(&[l, pa, pd]), 5, "line in two secant planes");
        assert_eq!(d(&[pa, pd, pe]), 5, "three planes through L (normals span a plane)");
        assert_eq!(d(&[pa, pc, pd]), 6, "three planes through one point");
        assert_eq!(d(&[pa, pb, pc]), 5, "two parallel planes and a secant one");
        assert_eq!(d(&[l, m, p, q, r]), 6, "greedy over a larger set");
        assert_eq!(d(&[l, p, q, r]), 5, "all on one line");
        assert_eq!(d(&[pa, pb]), d(&[pb, pa]));
    }

    #[test]
    fn segments_and_carriers() {
        // Segment ab and line L through a and b: the same line, so c on L is collinear with
        // the segment's points.
        let mut b = SystemBuilder::new("seg", Dim::Three);
        pt(&mut b, "a", &[0, 0, 0]);
        pt(&mut b, "b", &[1, 0, 0]);
        pt(&mut b, "c", &[2, 0, 0]);
        pt(&mut b, "m", &[5, 5, 5]);
        b.segment("ab", "a", "b").unwrap();
        line(&mut b, "L", &[0, 0, 0], &[1, 0, 0]);
        k(&mut b, ConstraintKind::Incident, "a_on", &["a", "L"]);
        k(&mut b, ConstraintKind::Incident, "b_on", &["b", "L"]);
        k(&mut b, ConstraintKind::Incident, "c_on", &["c", "L"]);
        k(&mut b, ConstraintKind::Midpoint, "mid", &["m", "ab"]);
        let s = b.build();
        let o = RuleDor::for_system(&s);
        let id = |x: &str| s.entity_by_id(x).unwrap();
        assert_eq!(o.dor(&s, &[id("a"), id("b"), id("c")]), 5);
        assert_eq!(o.dor(&s, &[id("a"), id("m"), id("c")]), 5, "midpoint is on the line");
        assert_eq!(o.dor(&s, &[id("ab")]), 5, "a segment is its two points");
        assert_eq!(o.dor(&s, &[id("ab"), id("L")]), 5);
        // Out-of-range indices are ignored rather than a panic.
        assert_eq!(o.dor(&s, &[EntityIdx(1000)]), 0);
    }
}
