//! The object–constraint network of a system and the two versions of `Distribute`.
//!
//! Flow paper (003_da7837b37878e133.txt), Definition 5: a source `s`, a sink `t`, one node per
//! constraint with an arc `s → c` of capacity DOC(c), one node per object with an arc `o → t`
//! of capacity DOF(o), and an arc `c → o` of infinite capacity for every object `c` binds. A
//! maximum flow distributes the constraints' DOC onto the objects' DOF; a constraint arc that
//! stays unsaturated betrays a subsystem with more DOC than DOF.
//!
//! # Objects
//!
//! The objects are the entities that carry degrees of freedom: every entity but segments. A
//! constraint on a segment binds the segment's two points ([`System::constraint_base_entities`]).
//!
//! **The reference frame.** The flow paper assumes every constraint is invariant under the
//! displacements; CAD sketches also have absolute constraints (`Fix`, `Horizontal`, `Vertical`)
//! that tie entities to the page. Counted naively they make every fixed point look over-rigid
//! (a fixed 2D point: DOF 2 − DOC 2 = 0 < 3). So when a system has an absolute constraint, the
//! network gets one more object, [`Object::Frame`]: the reference frame as a rigid body with
//! DOF = DOR = the number of displacements (3 in 2D, 6 in 3D), and every absolute constraint
//! binds the frame as well as its entities. The system becomes a relative one, `S ∪ {frame}`,
//! and the paper's machinery applies unchanged: a fully fixed sketch has DOF(S ∪ frame) =
//! ΣDOF + D − ΣDOC = D = DOR, i.e. it is well-rigid exactly when ΣDOF = ΣDOC. A system without
//! absolute constraints has no frame object.
//!
//! # Distribute, incrementally
//!
//! The network computes one maximum flow when it is built (the *base flow*, no overload). Each
//! `Distribute` call then pushes the overload `K` on top of it with at most `K` augmenting-path
//! searches ([`FlowGraph::augment_from`]), reads the residual reachability, and rolls the flow
//! back to the base flow. A call therefore costs `O(K · (n + m))` instead of the
//! `O(n²(n + m))` of a fresh Ford–Fulkerson run that the flow paper counts (§4.2, "Time
//! Complexity"; the paper notes the flow "could be computed in an incremental way"). That is
//! what makes Dense and Over-Rigid practical here.
//!
//! The reading is the paper's: if the overload cannot be fully distributed, the objects `V`
//! reachable from the overloaded node in the residual graph induce a subsystem with
//! DOF < K. (Every object of `V` is saturated, all the flow into `V` comes from reachable
//! constraints, which bind only objects of `V`, or from the overload, which was short; so
//! ΣDOF(V) < ΣDOC(induced) + K.) When the base flow itself leaves a constraint unsaturated, the
//! system has a subsystem with DOF < 0, read the same way from that constraint
//! ([`Network::over_constrained`]).

use gcs_model::{ConstraintIdx, Dim, EntityIdx, System};

use crate::error::RigidityError;
use crate::flow::{FlowGraph, INFINITE};

const SOURCE: usize = 0;
const SINK: usize = 1;
const NONE: u32 = u32::MAX;

/// An object of the object–constraint network.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Object {
    /// An entity with degrees of freedom of its own (any entity but a segment).
    Entity(EntityIdx),
    /// The reference frame, present when the system has absolute constraints (see the module
    /// documentation): a rigid body with as many DOF as there are displacements.
    Frame,
}

/// A subsystem found by a flow computation: a set of objects and the constraints it induces
/// (those that bind only these objects; an absolute constraint also needs the frame).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Subsystem {
    /// The objects (entities with DOF > 0), in file order.
    pub objects: Vec<EntityIdx>,
    /// The segments whose two points are both among `objects`, in file order. They carry no
    /// DOF; they are listed because a user thinks of them as part of the subsystem.
    pub segments: Vec<EntityIdx>,
    /// Whether the reference frame is part of the subsystem, i.e. whether its absolute
    /// constraints (`Fix`, `Horizontal`, `Vertical`) are among `constraints`.
    pub grounded: bool,
    /// The induced constraints, in file order.
    pub constraints: Vec<ConstraintIdx>,
    /// The subsystem's degrees of freedom by count: ΣDOF(objects) (+ the frame's DOF when
    /// grounded) − ΣDOC(constraints).
    pub dof: i64,
}

impl Subsystem {
    /// Objects and segments together, in file order: the entities to show a user.
    pub fn entities(&self) -> Vec<EntityIdx> {
        let mut all: Vec<EntityIdx> =
            self.objects.iter().chain(self.segments.iter()).copied().collect();
        all.sort();
        all
    }
}

/// How much of one constraint's DOC the flow sends to one of its objects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Share {
    /// The constraint.
    pub constraint: ConstraintIdx,
    /// One of the objects it binds.
    pub object: Object,
    /// The units of flow on the arc `constraint → object`.
    pub amount: u64,
}

/// The object–constraint network of a system (or of an induced subsystem), with a maximum
/// flow that is kept between calls.
///
/// # Example
/// ```
/// use gcs_model::System;
/// use gcs_rigidity::{Network, Object};
///
/// let text = r#"System(dim: 2, entities: [
///     Line(id: "A", at: [[0, 0], [1, 0]]), Line(id: "B", at: [[0, 1], [1, 1]]) ],
///   constraints: [ Parallel(id: "p", a: "A", b: "B"), Distance(id: "d", a: "A", b: "B", value: 1) ])"#;
/// let system = System::from_ron_str(text, None).unwrap();
/// let mut net = Network::new(&system);
/// assert!(net.is_saturated());
/// let [a, b] = [0, 1].map(|i| Object::Entity(gcs_model::EntityIdx(i)));
/// // Hoffmann et al.: an overload of 3 on `p` cannot be absorbed by two lines (4 DOF).
/// let p = system.constraint_by_id("p").unwrap();
/// let dense = net.distribute_on_constraint(p, 3).unwrap().unwrap();
/// assert_eq!(dense.dof, 2);
/// // Jermann et al.: two parallel lines admit only 2 displacements, and 2 is absorbed.
/// assert!(net.distribute(&[a, b], 2).unwrap().is_none());
/// ```
#[derive(Clone, Debug)]
pub struct Network {
    parts: Parts,
    local_of_entity: Vec<u32>,
    frame: Option<usize>,
    local_of_constraint: Vec<u32>,
    graph: FlowGraph,
    source_arcs: Vec<usize>,
    link_arcs: Vec<Vec<usize>>,
    base_flow: u64,
}

/// The parts a network is built from, before its nodes are numbered.
#[derive(Clone, Debug)]
struct Parts {
    dim: Dim,
    objects: Vec<Object>,
    object_dof: Vec<u64>,
    constraints: Vec<ConstraintIdx>,
    constraint_doc: Vec<u64>,
    constraint_objects: Vec<Vec<u32>>,
    segments: Vec<(EntityIdx, u32, u32)>,
}

impl Network {
    /// Builds the network of a whole system and computes its base maximum flow.
    ///
    /// # Complexity
    /// Dinic's algorithm on `n + m + 2` nodes: `O((n + m)² · (n + m + arcs))` at worst, much
    /// less on these layered networks.
    pub fn new(system: &System) -> Network {
        let dim = system.dim();
        let mut objects = Vec::new();
        let mut object_dof = Vec::new();
        let mut local = vec![NONE; system.entities().len()];
        for e in system.entity_indices() {
            let dof = system.entity_dof(e);
            if dof > 0 {
                local[e.index()] = objects.len() as u32;
                objects.push(Object::Entity(e));
                object_dof.push(dof as u64);
            }
        }
        let grounded = system.constraints().iter().any(|c| c.kind.is_absolute());
        let frame = grounded.then(|| {
            objects.push(Object::Frame);
            object_dof.push(dim.displacements() as u64);
            (objects.len() - 1) as u32
        });
        let mut constraints = Vec::new();
        let mut constraint_doc = Vec::new();
        let mut constraint_objects = Vec::new();
        for c in system.constraint_indices() {
            let constraint = system.constraint(c);
            let mut bound: Vec<u32> = system
                .constraint_base_entities(c)
                .iter()
                .map(|e| local[e.index()])
                .filter(|&l| l != NONE)
                .collect();
            if let (true, Some(f)) = (constraint.kind.is_absolute(), frame) {
                bound.push(f);
            }
            constraints.push(c);
            constraint_doc.push(constraint.doc as u64);
            constraint_objects.push(bound);
        }
        let segments = system
            .entity_indices()
            .filter_map(|e| {
                let (a, b) = system.segment_points(e)?;
                Some((e, local[a.index()], local[b.index()]))
            })
            .filter(|&(_, a, b)| a != NONE && b != NONE)
            .collect();
        let parts = Parts {
            dim,
            objects,
            object_dof,
            constraints,
            constraint_doc,
            constraint_objects,
            segments,
        };
        Network::build(parts, system.entities().len(), system.constraints().len())
    }

    /// Numbers the nodes of `parts` (of a system of `entity_count` entities and
    /// `constraint_count` constraints) and computes the base maximum flow.
    fn build(parts: Parts, entity_count: usize, constraint_count: usize) -> Network {
        let m = parts.constraints.len();
        let mut local_of_entity = vec![NONE; entity_count];
        let mut frame = None;
        for (j, o) in parts.objects.iter().enumerate() {
            match o {
                Object::Entity(e) => local_of_entity[e.index()] = j as u32,
                Object::Frame => frame = Some(j),
            }
        }
        let mut local_of_constraint = vec![NONE; constraint_count];
        for (i, c) in parts.constraints.iter().enumerate() {
            local_of_constraint[c.index()] = i as u32;
        }
        let mut graph = FlowGraph::new(2 + m + parts.objects.len());
        let mut source_arcs = Vec::with_capacity(m);
        let mut link_arcs = Vec::with_capacity(m);
        for i in 0..m {
            source_arcs.push(graph.add_arc(SOURCE, 2 + i, parts.constraint_doc[i]));
            link_arcs.push(
                parts.constraint_objects[i]
                    .iter()
                    .map(|&j| graph.add_arc(2 + i, 2 + m + j as usize, INFINITE))
                    .collect(),
            );
        }
        for (j, &dof) in parts.object_dof.iter().enumerate() {
            graph.add_arc(2 + m + j, SINK, dof);
        }
        let base_flow = graph.max_flow(SOURCE, SINK);
        Network {
            parts,
            local_of_entity,
            frame,
            local_of_constraint,
            graph,
            source_arcs,
            link_arcs,
            base_flow,
        }
    }

    /// The network of the subsystem induced by some of this network's objects: those objects,
    /// and the constraints that bind only them. Its base flow is computed afresh.
    ///
    /// # Errors
    /// [`RigidityError::NotAnObject`] or [`RigidityError::NoFrame`] for an object this network
    /// does not have.
    pub fn induced(&self, objects: &[Object]) -> Result<Network, RigidityError> {
        let mut keep = vec![false; self.parts.objects.len()];
        for &o in objects {
            keep[self.local(o)?] = true;
        }
        let mut new_local = vec![NONE; self.parts.objects.len()];
        let mut sub_objects = Vec::new();
        let mut sub_dof = Vec::new();
        for j in 0..self.parts.objects.len() {
            if keep[j] {
                new_local[j] = sub_objects.len() as u32;
                sub_objects.push(self.parts.objects[j]);
                sub_dof.push(self.parts.object_dof[j]);
            }
        }
        let mut constraints = Vec::new();
        let mut constraint_doc = Vec::new();
        let mut constraint_objects = Vec::new();
        for i in 0..self.parts.constraints.len() {
            if self.parts.constraint_objects[i].iter().all(|&j| keep[j as usize]) {
                constraints.push(self.parts.constraints[i]);
                constraint_doc.push(self.parts.constraint_doc[i]);
                constraint_objects.push(
                    self.parts.constraint_objects[i]
                        .iter()
                        .map(|&j| new_local[j as usize])
                        .collect(),
                );
            }
        }
        let segments = self
            .parts
            .segments
            .iter()
            .filter(|&&(_, a, b)| keep[a as usize] && keep[b as usize])
            .map(|&(s, a, b)| (s, new_local[a as usize], new_local[b as usize]))
            .collect();
        let parts = Parts {
            dim: self.parts.dim,
            objects: sub_objects,
            object_dof: sub_dof,
            constraints,
            constraint_doc,
            constraint_objects,
            segments,
        };
        Ok(Network::build(parts, self.local_of_entity.len(), self.local_of_constraint.len()))
    }

    /// The dimension of the system.
    pub fn dim(&self) -> Dim {
        self.parts.dim
    }

    /// The objects, entities in file order then the frame if any.
    pub fn objects(&self) -> &[Object] {
        &self.parts.objects
    }

    /// The constraints (nodes of the network), in file order.
    pub fn constraints(&self) -> &[ConstraintIdx] {
        &self.parts.constraints
    }

    /// The objects a constraint binds (segments replaced by their points, the frame for an
    /// absolute constraint), or `None` if it is not in the network.
    pub fn constraint_objects(&self, c: ConstraintIdx) -> Option<Vec<Object>> {
        let i = self.constraint_local(c).ok()?;
        Some(
            self.parts.constraint_objects[i]
                .iter()
                .map(|&j| self.parts.objects[j as usize])
                .collect(),
        )
    }

    /// Whether the network has the reference frame object (the system has absolute
    /// constraints).
    pub fn has_frame(&self) -> bool {
        self.frame.is_some()
    }

    /// Degrees of freedom of an object (the frame: the number of displacements).
    pub fn object_dof(&self, object: Object) -> Result<usize, RigidityError> {
        Ok(self.parts.object_dof[self.local(object)?] as usize)
    }

    /// ΣDOC of the constraints: what the source offers.
    pub fn demand(&self) -> u64 {
        self.parts.constraint_doc.iter().sum()
    }

    /// Value of the base maximum flow (without overload).
    pub fn max_flow(&self) -> u64 {
        self.base_flow
    }

    /// Whether the base flow saturates every constraint arc, i.e. no subsystem has more DOC
    /// than DOF.
    pub fn is_saturated(&self) -> bool {
        self.base_flow == self.demand()
    }

    /// The whole system's degrees of freedom by count: ΣDOF(objects, frame included) −
    /// ΣDOC.
    pub fn dof(&self) -> i64 {
        self.parts.object_dof.iter().sum::<u64>() as i64 - self.demand() as i64
    }

    /// The base flow on the arc `s → c`: how much of the constraint's DOC is distributed.
    pub fn constraint_flow(&self, c: ConstraintIdx) -> Option<u64> {
        let i = self.constraint_local(c).ok()?;
        Some(self.graph.flow(self.source_arcs[i]))
    }

    /// The base flow on every arc `constraint → object` that carries some: the distribution of
    /// the constraints' DOC onto the objects' DOF.
    pub fn distribution(&self) -> Vec<Share> {
        let mut out = Vec::new();
        for (i, arcs) in self.link_arcs.iter().enumerate() {
            for (k, &arc) in arcs.iter().enumerate() {
                let amount = self.graph.flow(arc);
                if amount > 0 {
                    let object = self.parts.objects[self.parts.constraint_objects[i][k] as usize];
                    out.push(Share { constraint: self.parts.constraints[i], object, amount });
                }
            }
        }
        out
    }

    /// The underlying flow graph (node 0 the source, 1 the sink, then the constraints in the
    /// order of [`constraints`](Self::constraints), then the objects in the order of
    /// [`objects`](Self::objects)), with the base flow.
    pub fn graph(&self) -> &FlowGraph {
        &self.graph
    }

    /// When the base flow leaves some constraint unsaturated, the subsystem with DOF < 0 read
    /// from the first such constraint (objects reachable from it in the residual graph, and the
    /// constraints they induce); `None` when the base flow is saturating.
    pub fn over_constrained(&mut self) -> Option<Subsystem> {
        let i = (0..self.parts.constraints.len())
            .find(|&i| self.graph.residual(self.source_arcs[i]) > 0)?;
        let reach = self.graph.reachable(&[2 + i]);
        Some(self.subsystem_from_nodes(&reach))
    }

    /// Hoffmann et al.'s `Distribute`: the overload `k` is added to constraint `c`'s source
    /// arc (capacity DOC(c) + k) and distributed on top of the base flow. Returns the
    /// subsystem with DOF < k read from the residual graph when the overload cannot be
    /// absorbed, `None` otherwise. The base flow is restored afterwards.
    ///
    /// Adding `k` to the arc `s → c` and augmenting is the same as pushing `k` extra units from
    /// `c`, which is how it is done (the other source arcs are saturated and stay so).
    ///
    /// # Errors
    /// [`RigidityError::UnknownConstraint`] when `c` is not in the network.
    ///
    /// # Complexity
    /// `O(k · (n + m + arcs))`.
    pub fn distribute_on_constraint(
        &mut self,
        c: ConstraintIdx,
        k: usize,
    ) -> Result<Option<Subsystem>, RigidityError> {
        let i = self.constraint_local(c)?;
        Ok(self.overload(&[2 + i], k as u64))
    }

    /// Jermann et al.'s geometrically correct `Distribute(S, K, S′)`: a virtual constraint
    /// node `R` of capacity `k` joined to the objects `attach` (= S′) by arcs of infinite
    /// capacity. Returns the subsystem with DOF < k read from the objects reachable from `R`
    /// in the residual graph when the overload cannot be absorbed (it contains `attach`), or
    /// `None`. The base flow is restored afterwards.
    ///
    /// The flow paper requires DOR(S′) ≥ k so that the answer means over-rigidity
    /// (DOF(S″) < k ≤ DOR(S′) ≤ DOR(S″)); the flow itself only proves DOF(S″) < k, and
    /// checking DOR(S′) is the caller's business ([`over_rigid`](crate::over_rigid) does).
    ///
    /// # Errors
    /// [`RigidityError::EmptyAttachment`] for an empty `attach`, [`RigidityError::NotAnObject`]
    /// or [`RigidityError::NoFrame`] for an object this network does not have.
    ///
    /// # Complexity
    /// `O(k · (n + m + arcs))`.
    pub fn distribute(
        &mut self,
        attach: &[Object],
        k: usize,
    ) -> Result<Option<Subsystem>, RigidityError> {
        if attach.is_empty() {
            return Err(RigidityError::EmptyAttachment);
        }
        let m = self.parts.constraints.len();
        let seeds =
            attach.iter().map(|&o| Ok(2 + m + self.local(o)?)).collect::<Result<Vec<_>, _>>()?;
        Ok(self.overload(&seeds, k as u64))
    }

    fn overload(&mut self, seeds: &[usize], k: u64) -> Option<Subsystem> {
        self.graph.checkpoint();
        let pushed = self.graph.augment_from(seeds, SINK, k);
        let found = (pushed < k).then(|| {
            let reach = self.graph.reachable(seeds);
            self.subsystem_from_nodes(&reach)
        });
        self.graph.rollback();
        found
    }

    /// The subsystem induced by a set of objects, with its DOF.
    ///
    /// # Errors
    /// [`RigidityError::NotAnObject`] or [`RigidityError::NoFrame`] for an object this network
    /// does not have.
    pub fn subsystem(&self, objects: &[Object]) -> Result<Subsystem, RigidityError> {
        let mut keep = vec![false; self.parts.objects.len()];
        for &o in objects {
            keep[self.local(o)?] = true;
        }
        Ok(self.subsystem_from_members(&keep))
    }

    fn subsystem_from_nodes(&self, reach: &[bool]) -> Subsystem {
        let m = self.parts.constraints.len();
        let keep: Vec<bool> = (0..self.parts.objects.len()).map(|j| reach[2 + m + j]).collect();
        self.subsystem_from_members(&keep)
    }

    fn subsystem_from_members(&self, keep: &[bool]) -> Subsystem {
        let mut objects = Vec::new();
        let mut grounded = false;
        let mut dof = 0i64;
        for (j, o) in self.parts.objects.iter().enumerate() {
            if keep[j] {
                dof += self.parts.object_dof[j] as i64;
                match o {
                    Object::Entity(e) => objects.push(*e),
                    Object::Frame => grounded = true,
                }
            }
        }
        let mut constraints = Vec::new();
        for i in 0..self.parts.constraints.len() {
            if self.parts.constraint_objects[i].iter().all(|&j| keep[j as usize]) {
                constraints.push(self.parts.constraints[i]);
                dof -= self.parts.constraint_doc[i] as i64;
            }
        }
        let segments = self
            .parts
            .segments
            .iter()
            .filter(|&&(_, a, b)| keep[a as usize] && keep[b as usize])
            .map(|&(s, _, _)| s)
            .collect();
        Subsystem { objects, segments, grounded, constraints, dof }
    }

    /// The local index of an object.
    pub(crate) fn local(&self, o: Object) -> Result<usize, RigidityError> {
        match o {
            Object::Frame => self.frame.ok_or(RigidityError::NoFrame),
            Object::Entity(e) => match self.local_of_entity.get(e.index()) {
                Some(&j) if j != NONE => Ok(j as usize),
                _ => Err(RigidityError::NotAnObject(e)),
            },
        }
    }

    fn constraint_local(&self, c: ConstraintIdx) -> Result<usize, RigidityError> {
        match self.local_of_constraint.get(c.index()) {
            Some(&i) if i != NONE => Ok(i as usize),
            _ => Err(RigidityError::UnknownConstraint(c)),
        }
    }

    /// The objects bound together by some constraint, per object (local indices, sorted, no
    /// repetition): the adjacency Over-Rigid builds its candidate sets from.
    pub(crate) fn adjacency(&self) -> Vec<Vec<u32>> {
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); self.parts.objects.len()];
        for bound in &self.parts.constraint_objects {
            for &a in bound {
                for &b in bound {
                    if a != b {
                        adj[a as usize].push(b);
                    }
                }
            }
        }
        for list in &mut adj {
            list.sort_unstable();
            list.dedup();
        }
        adj
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcs_model::number::int;
    use gcs_model::{ConstraintKind, SystemBuilder};

    fn triangle_plus_pendant() -> System {
        // p0 p1 p2 a triangle (rigid, DOF 3), p3 hanging on p2 by one bar, plus a second bar
        // p0–p1 (over-constrained pair).
        let mut b = SystemBuilder::new("t", Dim::Two);
        for (i, c) in [[0, 0], [4, 0], [1, 3], [5, 5]].iter().enumerate() {
            b.point(&format!("p{i}"), Some(vec![int(c[0]), int(c[1])])).unwrap();
        }
        for (k, (u, v)) in [(0, 1), (1, 2), (2, 0), (2, 3)].iter().enumerate() {
            b.constraint(
                ConstraintKind::Distance,
                &format!("d{k}"),
                &[&format!("p{u}"), &format!("p{v}")],
                Some(int(1)),
            )
            .unwrap();
        }
        b.build()
    }

    #[test]
    fn base_flow_and_distribution() {
        let s = triangle_plus_pendant();
        let net = Network::new(&s);
        assert_eq!(net.objects().len(), 4);
        assert!(!net.has_frame());
        assert_eq!(net.demand(), 4);
        assert!(net.is_saturated());
        assert_eq!(net.dof(), 4);
        let total: u64 = net.distribution().iter().map(|s| s.amount).sum();
        assert_eq!(total, 4);
        for c in s.constraint_indices() {
            assert_eq!(net.constraint_flow(c), Some(1));
        }
    }

    #[test]
    fn overload_reads_the_dense_subsystem() {
        let s = triangle_plus_pendant();
        let mut net = Network::new(&s);
        let p = |i| Object::Entity(EntityIdx(i));
        // Overload 4 on d0: the bar p0–p1 alone has DOF 3 < 4.
        let found = net.distribute_on_constraint(ConstraintIdx(0), 4).unwrap().unwrap();
        assert_eq!(found.objects, vec![EntityIdx(0), EntityIdx(1)]);
        assert_eq!(found.constraints, vec![ConstraintIdx(0)]);
        assert_eq!(found.dof, 3);
        // Overload 4 through R on the triangle: DOF 3 < 4, the pendant p3 is not in it.
        let found = net.distribute(&[p(0), p(1), p(2)], 4).unwrap().unwrap();
        assert_eq!(found.objects, vec![EntityIdx(0), EntityIdx(1), EntityIdx(2)]);
        assert_eq!(found.constraints, vec![ConstraintIdx(0), ConstraintIdx(1), ConstraintIdx(2)]);
        assert_eq!(found.dof, 3);
        // Overload 3 is absorbed, and so is 3 through R on {p2, p3}.
        assert_eq!(net.distribute_on_constraint(ConstraintIdx(0), 3).unwrap(), None);
        assert_eq!(net.distribute(&[p(2), p(3)], 3).unwrap(), None);
        // The base flow survives the trials.
        assert!(net.is_saturated());
        assert_eq!(net.graph().clone().augment_from(&[0], 1, 10), 0);
        // Bad input is an error, not a panic.
        assert_eq!(net.distribute(&[], 3), Err(RigidityError::EmptyAttachment));
        assert_eq!(net.distribute(&[Object::Frame], 3), Err(RigidityError::NoFrame));
        assert_eq!(net.distribute(&[p(99)], 3), Err(RigidityError::NotAnObject(EntityIdx(99))));
        assert_eq!(
            net.distribute_on_constraint(ConstraintIdx(42), 3),
            Err(RigidityError::UnknownConstraint(ConstraintIdx(42)))
        );
    }

    #[test]
    fn unsaturated_base_flow_reports_negative_dof() {
        let mut b = SystemBuilder::new("double", Dim::Two);
        b.point("a", Some(vec![int(0), int(0)])).unwrap();
        b.point("b", Some(vec![int(1), int(0)])).unwrap();
        b.point("c", Some(vec![int(3), int(3)])).unwrap();
        b.constraint(ConstraintKind::Coincident, "k1", &["a", "b"], None).unwrap();
        b.constraint(ConstraintKind::Coincident, "k2", &["a", "b"], None).unwrap();
        b.constraint(ConstraintKind::Coincident, "k3", &["b", "a"], None).unwrap();
        b.constraint(ConstraintKind::Distance, "d", &["b", "c"], Some(int(1))).unwrap();
        let s = b.build();
        let mut net = Network::new(&s);
        assert!(!net.is_saturated());
        let sub = net.over_constrained().unwrap();
        assert_eq!(sub.objects, vec![EntityIdx(0), EntityIdx(1)]);
        assert_eq!(sub.dof, 4 - 6);
    }

    #[test]
    fn frame_and_segments() {
        let r = gcs_model::generate::rectangles(1);
        let net = Network::new(&r);
        assert!(net.has_frame());
        assert_eq!(net.objects().len(), 5);
        assert_eq!(net.object_dof(Object::Frame), Ok(3));
        // 8 + 3 − 8: the fixed rectangle has exactly the frame's displacements.
        assert_eq!(net.dof(), 3);
        let all: Vec<Object> = net.objects().to_vec();
        let whole = net.subsystem(&all).unwrap();
        assert!(whole.grounded);
        assert_eq!(whole.segments.len(), 4);
        assert_eq!(whole.constraints.len(), 7);
        // Without the frame the absolute constraints are not induced.
        let free = net.subsystem(&all[..4]).unwrap();
        assert!(!free.grounded);
        assert_eq!(free.constraints.len(), 2);
        let sub = net.induced(&all[..2]).unwrap();
        assert_eq!(sub.constraints().len(), 1); // the width a–b
        assert_eq!(sub.dof(), 3);
        // A segment is not an object.
        let seg = r.entity_by_id("r0_bottom").unwrap();
        assert_eq!(net.object_dof(Object::Entity(seg)), Err(RigidityError::NotAnObject(seg)));
    }
}
