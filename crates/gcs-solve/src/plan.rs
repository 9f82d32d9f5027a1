//! The constructive order of a plane sketch: the points placed by two distances from points
//! placed before them (Henneberg type I steps, the simplest closed-form steps of a DR-plan),
//! found by peeling them off the end of the construction; what does not peel is the core,
//! solved numerically first.
//!
//! Peeling: a point whose only constraints (among those solved) are two `Distance`s with a
//! value to two other points can be placed last, once those points are placed; removing it
//! may make its neighbours peelable in turn. Linear in the size of the system.

use gcs_model::{ConstraintIdx, ConstraintKind, Dim, EntityIdx, EntityKind, System};

/// A point placed by two distances.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The point placed.
    pub point: EntityIdx,
    /// The two points it is measured from, in the order of the constraints.
    pub anchors: [EntityIdx; 2],
    /// The two distances.
    pub constraints: [ConstraintIdx; 2],
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
fn distance_points(system: &System, c: ConstraintIdx) -> Option<[EntityIdx; 2]> {
    let constraint = system.constraint(c);
    if constraint.kind != ConstraintKind::Distance || constraint.value.is_none() {
        return None;
    }
    let base = system.constraint_base_entities(c);
    let [p, q] = base.as_slice() else { return None };
    let point = |e: EntityIdx| system.entity(e).kind() == EntityKind::Point;
    (point(*p) && point(*q) && p != q).then_some([*p, *q])
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
    let mut live: Vec<usize> = incident.iter().map(Vec::len).collect();
    let mut peeled = vec![false; n];
    let mut steps = Vec::new();
    let mut queue: Vec<EntityIdx> =
        system.entity_indices().filter(|e| live[e.index()] == 2).collect();
    while let Some(p) = queue.pop() {
        if peeled[p.index()] || live[p.index()] != 2 || system.entity(p).kind() != EntityKind::Point
        {
            continue;
        }
        let cs: Vec<ConstraintIdx> =
            incident[p.index()].iter().copied().filter(|c| !removed[c.index()]).collect();
        let [c1, c2] = cs.as_slice() else { continue };
        let other = |c: ConstraintIdx| {
            let [a, b] = distance_points(system, c)?;
            Some(if a == p { b } else { a })
        };
        let (Some(a), Some(b)) = (other(*c1), other(*c2)) else { continue };
        if a == b {
            continue;
        }
        peeled[p.index()] = true;
        for c in [*c1, *c2] {
            removed[c.index()] = true;
            for &e in &bases[c.index()] {
                live[e.index()] -= 1;
                if live[e.index()] == 2 && !peeled[e.index()] {
                    queue.push(e);
                }
            }
        }
        steps.push(Step { point: p, anchors: [a, b], constraints: [*c1, *c2] });
    }
    // Peeled last-placed first: placing runs the other way.
    steps.reverse();
    let core = solved.iter().copied().filter(|c| !removed[c.index()]).collect();
    Construction { steps, core }
}
