//! The constructive order of a plane sketch: the points placed in closed form from entities
//! placed before them (the closed-form steps of a DR-plan, ESM paper §3), found by peeling
//! them off the end of the construction; what does not peel is the core, solved numerically
//! first.
//!
//! A point is placed by constraints that each confine it to a *locus* given the other
//! entities: a circle (a `Distance` with a value to another point) or a line (a condition
//! affine in the point: on a line or segment, horizontal or vertical with the other end of
//! its segment, a `DistanceX`/`DistanceY` from a point), or both coordinates at once (a `Fix`,
//! a coincidence, a midpoint, a symmetry about a point). Two circles, a circle and a line, or
//! two lines (or one two-row condition) determine it: two candidates, two, one.
//!
//! Peeling: a point whose constraints (among those solved) are all loci and remove exactly
//! two degrees of freedom can be placed last, once the entities they refer to are placed;
//! removing it may make its neighbours peelable in turn. Linear in the size of the system.

use gcs_model::{
    ConstraintIdx, ConstraintKind, Dim, EntityIdx, EntityKind, Metric, Signature, System,
};

/// How a constraint confines the point a step places.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Locus {
    /// A circle: a distance with a value to another point.
    Circle,
    /// A line (one row) or a point (two rows) — the constraint's equations are affine in the
    /// point's coordinates.
    Affine {
        /// The degrees of freedom it removes from the point: 1 or 2.
        rows: usize,
    },
}

impl Locus {
    /// The degrees of freedom the locus removes from the point.
    pub fn doc(self) -> usize {
        match self {
            Locus::Circle => 1,
            Locus::Affine { rows } => rows,
        }
    }
}

/// A point placed in closed form.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The point placed.
    pub point: EntityIdx,
    /// The entities its constraints refer to besides it (placed before it: in the core or by
    /// an earlier step), in the order of the constraints.
    pub anchors: Vec<EntityIdx>,
    /// Its constraints with their loci, in the system's order; their degrees of constraint sum
    /// to two.
    pub constraints: Vec<(ConstraintIdx, Locus)>,
}

impl Step {
    /// The constraints, without their loci.
    pub fn constraint_ids(&self) -> Vec<ConstraintIdx> {
        self.constraints.iter().map(|(c, _)| *c).collect()
    }

    /// The two distances of a point by two distances (the anchors' circles), if it is one.
    pub fn two_distances(&self) -> Option<[ConstraintIdx; 2]> {
        match self.constraints.as_slice() {
            [(a, Locus::Circle), (b, Locus::Circle)] => Some([*a, *b]),
            _ => None,
        }
    }
}

/// The constructive order: `steps` in the order they are placed (each one's anchors are in
/// the core or placed by an earlier step), and the constraints left to the core.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Construction {
    /// The closed-form steps, in placing order.
    pub steps: Vec<Step>,
    /// The constraints of the core (those of `solved` in no step), in their order in `solved`.
    pub core: Vec<ConstraintIdx>,
}

/// The two points of a `Distance` with a value between two distinct points.
pub fn distance_points(system: &System, c: ConstraintIdx) -> Option<[EntityIdx; 2]> {
    let constraint = system.constraint(c);
    if constraint.kind != ConstraintKind::Distance || constraint.value.is_none() {
        return None;
    }
    let base = system.constraint_base_entities(c);
    let [p, q] = base.as_slice() else { return None };
    let point = |e: EntityIdx| system.entity(e).kind() == EntityKind::Point;
    (point(*p) && point(*q) && p != q).then_some([*p, *q])
}

/// How constraint `c` confines the 2D point `p`, given every other entity it refers to;
/// `None` when it is not one of the loci above (or does not involve `p` as a whole point once).
pub fn locus(system: &System, c: ConstraintIdx, p: EntityIdx) -> Option<Locus> {
    let constraint = system.constraint(c);
    let base = system.constraint_base_entities(c);
    if !base.contains(&p) {
        return None;
    }
    let valued = constraint.value.is_some();
    let line = Locus::Affine { rows: 1 };
    let whole = Locus::Affine { rows: 2 };
    match constraint.signature {
        Signature::Metric(Metric::DistancePointPoint(..)) => {
            distance_points(system, c).map(|_| Locus::Circle)
        }
        Signature::Metric(Metric::DistanceX(a, b) | Metric::DistanceY(a, b)) => {
            (valued && a != b).then_some(line)
        }
        Signature::IncidentPointLine { point, line: l } => {
            (point == p && !system.base_entities(l).contains(&p)).then_some(line)
        }
        Signature::Horizontal(e) | Signature::Vertical(e) => {
            let (a, b) = system.segment_points(e)?;
            (a != b && (a == p || b == p)).then_some(line)
        }
        Signature::Fix(e) => (e == p).then_some(whole),
        Signature::CoincidentPoints(a, b) => (a != b).then_some(whole),
        Signature::Midpoint { point, segment } => {
            let (a, b) = system.segment_points(segment)?;
            (point != a && point != b && a != b).then_some(whole)
        }
        Signature::SymmetricAboutPoint { a, b, center } => {
            (a != b && a != center && b != center).then_some(whole)
        }
        Signature::SplinePoint { point, spline, .. } => {
            (point == p && !system.base_entities(spline).contains(&p)).then_some(whole)
        }
        _ => None,
    }
}

/// The coordinate a one-row condition fixes whatever the other entities (0: x, 1: y), for the
/// conditions that have one: a vertical segment or a `DistanceX` fixes x, a horizontal one or
/// a `DistanceY` fixes y.
fn axis(system: &System, c: ConstraintIdx) -> Option<usize> {
    match system.constraint(c).signature {
        Signature::Vertical(_) | Signature::Metric(Metric::DistanceX(..)) => Some(0),
        Signature::Horizontal(_) | Signature::Metric(Metric::DistanceY(..)) => Some(1),
        _ => None,
    }
}

/// The constructive order of the constraints `solved` of a 2D system (empty for 3D: every
/// constraint is in the core).
pub fn construction(system: &System, solved: &[ConstraintIdx]) -> Construction {
    if system.dim() != Dim::Two {
        return Construction { steps: Vec::new(), core: solved.to_vec() };
    }
    let n = system.entities().len();
    let mut incident: Vec<Vec<ConstraintIdx>> = vec![Vec::new(); n];
    let mut bases: Vec<Vec<EntityIdx>> = vec![Vec::new(); system.constraints().len()];
    for &c in solved {
        let base = system.constraint_base_entities(c);
        for &e in &base {
            incident[e.index()].push(c);
        }
        bases[c.index()] = base;
    }
    let mut removed = vec![false; system.constraints().len()];
    // Per entity, the number of its constraints not yet peeled.
    let mut live: Vec<usize> = incident.iter().map(Vec::len).collect();
    let mut peeled = vec![false; n];
    let mut steps = Vec::new();
    let point = |e: EntityIdx| system.entity(e).kind() == EntityKind::Point;
    let mut queue: Vec<EntityIdx> =
        system.entity_indices().filter(|e| point(*e) && matches!(live[e.index()], 1 | 2)).collect();
    while let Some(p) = queue.pop() {
        if peeled[p.index()] || !matches!(live[p.index()], 1 | 2) || !point(p) {
            continue;
        }
        let mut constraints = Vec::new();
        for &c in incident[p.index()].iter().filter(|c| !removed[c.index()]) {
            let Some(l) = locus(system, c, p) else { break };
            constraints.push((c, l));
        }
        if constraints.len() != live[p.index()]
            || constraints.iter().map(|(_, l)| l.doc()).sum::<usize>() != 2
        {
            continue;
        }
        // Two circles about the same centre fix no point.
        let mut anchors: Vec<EntityIdx> = Vec::new();
        for (c, _) in &constraints {
            for &e in &bases[c.index()] {
                if e != p && !anchors.contains(&e) {
                    anchors.push(e);
                }
            }
        }
        if constraints.iter().all(|(_, l)| *l == Locus::Circle) && anchors.len() != 2 {
            continue;
        }
        // Two conditions on the same coordinate fix no point either.
        if let [(a, _), (b, _)] = constraints.as_slice()
            && axis(system, *a).is_some()
            && axis(system, *a) == axis(system, *b)
        {
            continue;
        }
        peeled[p.index()] = true;
        for (c, _) in &constraints {
            removed[c.index()] = true;
            for &e in &bases[c.index()] {
                live[e.index()] -= 1;
                if matches!(live[e.index()], 1 | 2) && !peeled[e.index()] {
                    queue.push(e);
                }
            }
        }
        steps.push(Step { point: p, anchors, constraints });
    }
    // Peeled last-placed first: placing runs the other way.
    steps.reverse();
    let core = solved.iter().copied().filter(|c| !removed[c.index()]).collect();
    Construction { steps, core }
}
