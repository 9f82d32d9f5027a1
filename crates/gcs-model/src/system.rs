//! The validated system: entities and constraints with ids resolved to indices, kinds checked
//! against the constraint table, degrees of freedom and of constraint known.

use std::collections::HashMap;
use std::fmt;

use num_rational::BigRational;
use num_traits::Signed;

use crate::entity::{EntityKind, Geometry};
use crate::error::{ModelError, ModelErrorKind, Position};
use crate::kinds::{ConstraintKind, Dim};
use crate::signature::Signature;

/// Index of an entity in [`System::entities`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EntityIdx(pub u32);

/// Index of a constraint in [`System::constraints`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ConstraintIdx(pub u32);

impl EntityIdx {
    /// The index as a `usize`.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

impl ConstraintIdx {
    /// The index as a `usize`.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A sketch position: one exact rational per coordinate.
pub type Coords = Vec<BigRational>;

/// A geometric entity of a system.
#[derive(Clone, Debug, PartialEq)]
pub struct Entity {
    /// The id from the model file.
    pub id: String,
    /// Kind and sketch.
    pub geometry: Geometry,
    /// Where the entity is written, when it was read from a file.
    pub position: Option<Position>,
    /// For a named point of a curve that the system made itself (an arc's `<id>.start` and
    /// `<id>.end`, a circle's `<id>.center` once a constraint names it): the curve. Such an
    /// entity is not written back to a model file (its owner's fields say it all).
    pub owner: Option<EntityIdx>,
    /// Construction geometry (`construction: true` in the file): a helper the CAD user drew to
    /// constrain other entities. Analysed and solved like the rest; drawn dashed.
    pub construction: bool,
}

impl Entity {
    /// The entity kind.
    pub fn kind(&self) -> EntityKind {
        self.geometry.kind()
    }

    /// Whether every sketch field that defines its placement is given. A composite entity has
    /// a position when all its parts have one; the caller checks that through the system
    /// ([`System::has_position`]).
    fn has_own_position(&self) -> bool {
        self.geometry.has_own_position()
    }
}

/// A constraint of a system.
#[derive(Clone, Debug, PartialEq)]
pub struct Constraint {
    /// The id from the model file.
    pub id: String,
    /// The kind.
    pub kind: ConstraintKind,
    /// The entities in the order of the file's fields (`a`, `b`, `axis`; `point`, `segment`).
    pub args: Vec<EntityIdx>,
    /// The row of the constraint table that applies, with the entities in their roles.
    pub signature: Signature,
    /// The metric value (a length in model units or an angle in degrees), when written.
    pub value: Option<BigRational>,
    /// Degrees of freedom it removes in general (format §1, table "Constraints").
    pub doc: usize,
    /// Where the constraint is written, when it was read from a file.
    pub position: Option<Position>,
    /// For a constraint the system made itself to hold a named point of a curve in place
    /// (an arc's end on its circle, `<point>@<arc>`; a circle's centre point at its centre,
    /// `<point>@<circle>`): the curve. Not written back to a model file.
    pub owner: Option<EntityIdx>,
}

/// Either kind of item an id can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Item {
    /// An entity.
    Entity(EntityIdx),
    /// A constraint.
    Constraint(ConstraintIdx),
    /// An orientation condition (its index in [`System::orientations`]).
    Orientation(usize),
    /// A group (its index in [`System::groups`]).
    Group(usize),
    /// A reference (driven) dimension (its index in [`System::references`]).
    Reference(usize),
}

/// A feature or part the user declares (the ESM paper's feature incorporation): a set of
/// entities meant to be solved as a whole. Where the group is rigid on its own and lies in the
/// part of a plane sketch the solve splits into a DR-plan, it is a node of that plan. Written
/// in the optional `groups` list as `Group(id: "g", entities: ["a", "b", "c"])`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Group {
    /// Its id (unique among all ids).
    pub id: String,
    /// Its entities, as written (distinct).
    pub entities: Vec<EntityIdx>,
}

/// A chirality condition, the ESM paper's navigation constraint: the points, in order, turn the
/// way `sign` says — the sign of the determinant of `(b − a, c − a)` in 2D, of
/// `(b − a, c − a, d − a)` in 3D (1: counterclockwise in the plane, right-handed in space).
/// An inequality: it removes no degree of freedom, the analysis does not count it, and the
/// solver keeps only the realizations where it holds. Written in the `constraints` list as
/// `Orientation(id: "o", points: ["a", "b", "c"], sign: 1)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Orientation {
    /// Its id (unique among entities and constraints).
    pub id: String,
    /// Its points: three in 2D, four in 3D, distinct.
    pub points: Vec<EntityIdx>,
    /// 1 or −1.
    pub sign: i8,
}

/// A validated geometric constraint system.
///
/// Built by the RON reader ([`System::from_ron_str`]) or by a [`SystemBuilder`]; both run the
/// same checks, so every `System` satisfies: ids are unique and non-empty, every reference
/// names an entity, every entity kind exists in the dimension, every sketch field has the
/// right number of coordinates and is not degenerate, every constraint applies to the kinds
/// it binds, and every `Fix` has a position to pin.
#[derive(Clone, Debug, PartialEq)]
pub struct System {
    name: String,
    dim: Dim,
    entities: Vec<Entity>,
    constraints: Vec<Constraint>,
    orientations: Vec<Orientation>,
    groups: Vec<Group>,
    references: Vec<Constraint>,
    ids: HashMap<String, Item>,
}

impl System {
    /// The model's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The dimension.
    pub fn dim(&self) -> Dim {
        self.dim
    }

    /// The entities, in file order.
    pub fn entities(&self) -> &[Entity] {
        &self.entities
    }

    /// The constraints, in file order.
    pub fn constraints(&self) -> &[Constraint] {
        &self.constraints
    }

    /// The orientation conditions (navigation constraints: no equations), in file order.
    pub fn orientations(&self) -> &[Orientation] {
        &self.orientations
    }

    /// The groups the user declared, in file order.
    pub fn groups(&self) -> &[Group] {
        &self.groups
    }

    /// The reference (driven, non-driving) dimensions, in file order: dimensions of a metric
    /// kind (`reference: true` in the file) that are measured, not imposed — no equation of the
    /// system; the analysis and the solve report their measure.
    pub fn references(&self) -> &[Constraint] {
        &self.references
    }

    /// One entity.
    ///
    /// # Panics
    /// When the index is not from this system.
    pub fn entity(&self, idx: EntityIdx) -> &Entity {
        &self.entities[idx.index()]
    }

    /// One constraint.
    ///
    /// # Panics
    /// When the index is not from this system.
    pub fn constraint(&self, idx: ConstraintIdx) -> &Constraint {
        &self.constraints[idx.index()]
    }

    /// What an id names.
    pub fn lookup(&self, id: &str) -> Option<Item> {
        self.ids.get(id).copied()
    }

    /// The entity an id names.
    pub fn entity_by_id(&self, id: &str) -> Option<EntityIdx> {
        match self.lookup(id) {
            Some(Item::Entity(e)) => Some(e),
            _ => None,
        }
    }

    /// The constraint an id names.
    pub fn constraint_by_id(&self, id: &str) -> Option<ConstraintIdx> {
        match self.lookup(id) {
            Some(Item::Constraint(c)) => Some(c),
            _ => None,
        }
    }

    /// The two points of a segment, `None` for any other kind.
    pub fn segment_points(&self, idx: EntityIdx) -> Option<(EntityIdx, EntityIdx)> {
        match &self.entity(idx).geometry {
            Geometry::Segment { from, to } => Some((*from, *to)),
            Geometry::Point { .. }
            | Geometry::Line { .. }
            | Geometry::Circle { .. }
            | Geometry::Plane { .. }
            | Geometry::Sphere { .. }
            | Geometry::Arc { .. }
            | Geometry::BSpline { .. } => None,
        }
    }

    /// The start and end points of an arc, `None` for any other kind.
    pub fn arc_points(&self, idx: EntityIdx) -> Option<(EntityIdx, EntityIdx)> {
        match &self.entity(idx).geometry {
            Geometry::Arc { start, end, .. } => Some((*start, *end)),
            Geometry::Point { .. }
            | Geometry::Line { .. }
            | Geometry::Segment { .. }
            | Geometry::Circle { .. }
            | Geometry::Plane { .. }
            | Geometry::Sphere { .. }
            | Geometry::BSpline { .. } => None,
        }
    }

    /// The number of entities written in the model (those the system made itself, the named
    /// points of curves, not counted).
    pub fn written_entities(&self) -> usize {
        self.entities.iter().filter(|e| e.owner.is_none()).count()
    }

    /// The number of constraints written in the model (the implicit ones that hold named
    /// points of curves not counted).
    pub fn written_constraints(&self) -> usize {
        self.constraints.iter().filter(|c| c.owner.is_none()).count()
    }

    /// Degrees of freedom of one entity (0 for a segment).
    pub fn entity_dof(&self, idx: EntityIdx) -> usize {
        self.entity(idx).kind().dof(self.dim)
    }

    /// Sum of the entities' degrees of freedom.
    pub fn dof_sum(&self) -> usize {
        self.entities.iter().map(|e| e.kind().dof(self.dim)).sum()
    }

    /// Sum of the constraints' degrees of constraint.
    pub fn doc_sum(&self) -> usize {
        self.constraints.iter().map(|c| c.doc).sum()
    }

    /// The naive count `Σ DOF − Σ DOC`, which ignores both redundancy and the displacements.
    pub fn naive_dof(&self) -> i64 {
        self.dof_sum() as i64 - self.doc_sum() as i64
    }
    /// Replaces the sketch of entity `e` (a solver's result), keeping its kind and parts: the
    /// new geometry must be of the same kind, built on the same entities, and valid.
    ///
    /// # Errors
    /// A [`ModelError`] when the geometry is of another kind, names other parts, or is invalid
    /// (a negative radius, a degenerate line).
    pub fn set_sketch(&mut self, e: EntityIdx, geometry: Geometry) -> Result<(), ModelError> {
        let entity = &self.entities[e.index()];
        let same_parts = match (&entity.geometry, &geometry) {
            (Geometry::Segment { from, to }, Geometry::Segment { from: f, to: t }) => {
                from == f && to == t
            }
            (Geometry::Arc { start, end, .. }, Geometry::Arc { start: s, end: t, .. }) => {
                start == s && end == t
            }
            (a, b) => a.kind() == b.kind(),
        };
        if !same_parts {
            return Err(ModelError::new(ModelErrorKind::Degenerate {
                id: entity.id.clone(),
                field: None,
                what: "a new sketch must keep the entity's kind and parts".to_owned(),
            }));
        }
        geometry.check(&entity.id, self.dim)?;
        self.entities[e.index()].geometry = geometry;
        Ok(())
    }

    /// Whether an entity has a complete sketch position (a composite entity: all its parts).
    pub fn has_position(&self, idx: EntityIdx) -> bool {
        let e = self.entity(idx);
        if e.kind().is_composite() {
            e.geometry.parts().iter().all(|p| self.has_position(*p))
        } else {
            e.has_own_position()
        }
    }

    /// The row of the constraint table a constraint of `kind` on `args` (in the order of the
    /// kind's fields) would have, `None` when the table has no such row: the relations that can
    /// be stated between entities (the boundary of a rigid subsystem asks which distances and
    /// angles apply).
    pub fn relation(&self, kind: ConstraintKind, args: &[EntityIdx]) -> Option<Signature> {
        let kinds: Vec<EntityKind> = args.iter().map(|e| self.entity(*e).kind()).collect();
        Signature::resolve(self.dim, kind, args, &kinds).ok().map(|(s, _)| s)
    }

    /// Indices of all entities.
    pub fn entity_indices(&self) -> impl Iterator<Item = EntityIdx> + '_ {
        (0..self.entities.len() as u32).map(EntityIdx)
    }

    /// Indices of all constraints.
    pub fn constraint_indices(&self) -> impl Iterator<Item = ConstraintIdx> + '_ {
        (0..self.constraints.len() as u32).map(ConstraintIdx)
    }

    /// The entities with coordinates of their own that an entity stands for: itself, or for a
    /// composite entity (a segment) the entities it is built on. Constraints on a composite
    /// entity act on its parts.
    pub fn base_entities(&self, idx: EntityIdx) -> Vec<EntityIdx> {
        let e = self.entity(idx);
        if e.kind().is_composite() {
            let mut out = Vec::new();
            for p in e.geometry.parts() {
                for b in self.base_entities(p) {
                    if !out.contains(&b) {
                        out.push(b);
                    }
                }
            }
            out
        } else {
            vec![idx]
        }
    }

    /// The entities with degrees of freedom that a constraint acts on (segments replaced by
    /// their points; a `Fix` on an arc also pins its end points), without repetition, in
    /// first-use order.
    pub fn constraint_base_entities(&self, c: ConstraintIdx) -> Vec<EntityIdx> {
        self.signature_base_entities(self.constraint(c).signature)
    }

    /// The entities with degrees of freedom that a row of the constraint table acts on (of a
    /// constraint: [`Self::constraint_base_entities`]; of a reference dimension).
    pub fn signature_base_entities(&self, signature: Signature) -> Vec<EntityIdx> {
        let mut out = Vec::new();
        let mut entities = signature.entities();
        if let Signature::Fix(e) = signature
            && let Some((start, end)) = self.arc_points(e)
        {
            entities.extend([start, end]);
        }
        for e in entities {
            for b in self.base_entities(e) {
                if !out.contains(&b) {
                    out.push(b);
                }
            }
        }
        out
    }

    /// Sets where items are written: `(entity, position)` and `(constraint, position)` pairs.
    /// The named points and implicit constraints of a curve take its position.
    pub(crate) fn set_position(
        &mut self,
        entities: &[(EntityIdx, Option<Position>)],
        constraints: &[(ConstraintIdx, Option<Position>)],
    ) {
        for (e, p) in entities {
            self.entities[e.index()].position = *p;
        }
        for (c, p) in constraints {
            self.constraints[c.index()].position = *p;
        }
        for i in 0..self.entities.len() {
            if let Some(owner) = self.entities[i].owner {
                self.entities[i].position = self.entities[owner.index()].position;
            }
        }
        for c in &mut self.constraints {
            if let Some(owner) = c.owner {
                c.position = self.entities[owner.index()].position;
            }
        }
    }
}

impl fmt::Display for System {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ({}, {} entities, {} constraints)",
            self.name,
            self.dim,
            self.written_entities(),
            self.written_constraints()
        )
    }
}

/// Builds a [`System`] item by item, with the same checks as the RON reader.
///
/// # Example
/// ```
/// use gcs_model::{ConstraintKind, Dim, SystemBuilder, number::int};
///
/// let mut b = SystemBuilder::new("segment", Dim::Two);
/// b.point("p", Some(vec![int(0), int(0)])).unwrap();
/// b.point("q", Some(vec![int(3), int(4)])).unwrap();
/// b.constraint(ConstraintKind::Distance, "d", &["p", "q"], Some(int(5))).unwrap();
/// let system = b.build();
/// assert_eq!(system.dof_sum(), 4);
/// assert_eq!(system.doc_sum(), 1);
/// ```
#[derive(Clone, Debug)]
pub struct SystemBuilder {
    system: System,
}

impl SystemBuilder {
    /// An empty system.
    pub fn new(name: impl Into<String>, dim: Dim) -> SystemBuilder {
        SystemBuilder {
            system: System {
                name: name.into(),
                dim,
                entities: Vec::new(),
                constraints: Vec::new(),
                orientations: Vec::new(),
                references: Vec::new(),
                groups: Vec::new(),
                ids: HashMap::new(),
            },
        }
    }

    /// A builder that goes on from an existing system (its items keep their ids and order).
    pub fn from_system(system: System) -> SystemBuilder {
        SystemBuilder { system }
    }

    /// The system as built so far.
    pub fn system(&self) -> &System {
        &self.system
    }

    /// Finishes the system.
    pub fn build(self) -> System {
        self.system
    }

    fn claim_id(&self, id: &str) -> Result<(), ModelError> {
        if id.is_empty() {
            return Err(ModelError::new(ModelErrorKind::EmptyId));
        }
        if self.system.ids.contains_key(id) {
            return Err(ModelError::new(ModelErrorKind::DuplicateId { id: id.to_owned() }));
        }
        Ok(())
    }

    /// Adds an entity of any kind: checks its id, that its kind exists in the dimension, its
    /// sketch fields, and for a composite kind its parts (already resolved indices; `names`
    /// are their ids as written, for messages).
    fn push_entity(
        &mut self,
        id: &str,
        geometry: Geometry,
        names: &[&str],
    ) -> Result<EntityIdx, ModelError> {
        self.push_owned_entity(id, geometry, names, None)
    }

    fn push_owned_entity(
        &mut self,
        id: &str,
        geometry: Geometry,
        names: &[&str],
        owner: Option<EntityIdx>,
    ) -> Result<EntityIdx, ModelError> {
        self.claim_id(id)?;
        let kind = geometry.kind();
        if !kind.exists_in(self.system.dim) {
            return Err(ModelError::new(ModelErrorKind::KindNotInDim {
                id: id.to_owned(),
                kind,
                dim: self.system.dim,
            }));
        }
        geometry.check(id, self.system.dim)?;
        if kind.is_composite() {
            let fields: Vec<&'static str> = part_fields(kind, names.len());
            geometry.check_parts(id, &fields, names, &self.system)?;
        }
        let idx = EntityIdx(self.system.entities.len() as u32);
        self.system.entities.push(Entity {
            id: id.to_owned(),
            geometry,
            position: None,
            owner,
            construction: false,
        });
        self.system.ids.insert(id.to_owned(), Item::Entity(idx));
        if let Some((from, to)) = self.system.segment_points(idx) {
            // A segment's end points are also `<id>.start` and `<id>.end`.
            for (part, point) in [("start", from), ("end", to)] {
                let alias = format!("{id}.{part}");
                match self.system.ids.get(&alias) {
                    None => {
                        self.system.ids.insert(alias, Item::Entity(point));
                    }
                    Some(Item::Entity(e)) if *e == point => {}
                    Some(_) => {
                        return Err(ModelError::new(ModelErrorKind::Degenerate {
                            id: id.to_owned(),
                            field: None,
                            what: format!(
                                "\"{alias}\" names another item, not this segment's {part} point"
                            ),
                        }));
                    }
                }
            }
        }
        Ok(idx)
    }

    /// Adds an entity given by its geometry. For a composite kind, `parts` are the ids of the
    /// entities it is built on, in the order of [`EntityKind::part_fields`] (the geometry's own
    /// references are replaced); for the others `parts` must be empty.
    pub fn entity(
        &mut self,
        id: &str,
        geometry: Geometry,
        parts: &[&str],
    ) -> Result<EntityIdx, ModelError> {
        if let Geometry::Arc { center, radius, .. } = geometry {
            return self.arc(id, center, radius, None, None);
        }
        let fields = part_fields(geometry.kind(), parts.len());
        let mut resolved = Vec::with_capacity(parts.len());
        for (field, part) in fields.iter().zip(parts) {
            resolved.push(self.resolve("entity", id, field, part)?);
        }
        let geometry = if resolved.len() == fields.len() && !fields.is_empty() {
            geometry.with_parts(&resolved)
        } else {
            geometry
        };
        self.push_entity(id, geometry, parts)
    }

    /// Adds a B-spline curve on existing control points (format §1; [`crate::spline`] says
    /// what the knots and weights mean).
    pub fn bspline(
        &mut self,
        id: &str,
        degree: u32,
        poles: &[&str],
        knots: Option<Vec<BigRational>>,
        weights: Option<Vec<BigRational>>,
        periodic: bool,
    ) -> Result<EntityIdx, ModelError> {
        let none = EntityIdx(u32::MAX);
        let geometry =
            Geometry::BSpline { degree, poles: vec![none; poles.len()], knots, weights, periodic };
        self.entity(id, geometry, poles)
    }

    /// Adds a point.
    pub fn point(&mut self, id: &str, at: Option<Coords>) -> Result<EntityIdx, ModelError> {
        self.entity(id, Geometry::Point { at }, &[])
    }

    /// Adds an infinite line, sketched by two distinct points.
    pub fn line(&mut self, id: &str, at: Option<[Coords; 2]>) -> Result<EntityIdx, ModelError> {
        self.entity(id, Geometry::Line { at }, &[])
    }

    /// Adds a segment between two existing points.
    pub fn segment(&mut self, id: &str, from: &str, to: &str) -> Result<EntityIdx, ModelError> {
        let none = EntityIdx(u32::MAX);
        self.entity(id, Geometry::Segment { from: none, to: none }, &[from, to])
    }

    /// Adds a circle (2D).
    pub fn circle(
        &mut self,
        id: &str,
        center: Option<Coords>,
        radius: Option<BigRational>,
    ) -> Result<EntityIdx, ModelError> {
        self.entity(id, Geometry::Circle { center, radius }, &[])
    }

    /// Adds a circular arc (2D) and its end points `<id>.start` and `<id>.end`, held on its
    /// circle by implicit `Incident` constraints (`<id>.start@<id>`, `<id>.end@<id>`). Without
    /// a radius, the sketch radius is the distance from the centre to the start point (exactly
    /// when it is rational, else to 17 significant digits).
    pub fn arc(
        &mut self,
        id: &str,
        center: Option<Coords>,
        radius: Option<BigRational>,
        start: Option<Coords>,
        end: Option<Coords>,
    ) -> Result<EntityIdx, ModelError> {
        let radius = match (radius, &center, &start) {
            (Some(r), _, _) => Some(r),
            (None, Some(c), Some(s)) if c.len() == s.len() => {
                let r2: BigRational = c.iter().zip(s).map(|(a, b)| (a - b) * (a - b)).sum();
                crate::number::sqrt_rational(&r2)
            }
            (None, _, _) => None,
        };
        for (field, at) in [("start", &start), ("end", &end)] {
            if let Some(at) = at {
                crate::entity::check_coords(id, field, at, self.system.dim)?;
            }
        }
        let first = self.system.entities.len() as u32;
        let (start_idx, end_idx) = (EntityIdx(first + 1), EntityIdx(first + 2));
        let geometry = Geometry::Arc { center, radius, start: start_idx, end: end_idx };
        let arc = self.push_entity(id, geometry, &[])?;
        for (part, at) in [("start", start), ("end", end)] {
            let point = format!("{id}.{part}");
            self.push_owned_entity(&point, Geometry::Point { at }, &[], Some(arc))?;
            self.push_constraint(
                ConstraintKind::Incident,
                &format!("{point}@{id}"),
                &[&point, id],
                None,
                Some(arc),
            )?;
        }
        debug_assert_eq!(self.system.arc_points(arc), Some((start_idx, end_idx)));
        Ok(arc)
    }

    /// Adds a plane (3D), sketched by a point on it and a normal.
    pub fn plane(&mut self, id: &str, at: Option<[Coords; 2]>) -> Result<EntityIdx, ModelError> {
        self.entity(id, Geometry::Plane { at }, &[])
    }

    /// Adds a sphere (3D).
    pub fn sphere(
        &mut self,
        id: &str,
        center: Option<Coords>,
        radius: Option<BigRational>,
    ) -> Result<EntityIdx, ModelError> {
        self.entity(id, Geometry::Sphere { center, radius }, &[])
    }

    /// The entity `id` names. `<curve>.center` names the centre of a circle, arc or sphere: the
    /// first time it is named, the centre becomes a point entity of that id, held at the centre
    /// by an implicit `Concentric` constraint (`<curve>.center@<curve>`).
    fn resolve(
        &mut self,
        item: &'static str,
        owner: &str,
        field: &'static str,
        id: &str,
    ) -> Result<EntityIdx, ModelError> {
        if !self.system.ids.contains_key(id)
            && let Some(curve) = id.strip_suffix(".center")
            && let Some(Item::Entity(c)) = self.system.ids.get(curve).copied()
            && let Some(center) = self.system.entity(c).geometry.center()
        {
            let center = center.cloned();
            self.push_owned_entity(id, Geometry::Point { at: center }, &[], Some(c))?;
            self.push_constraint(
                ConstraintKind::Concentric,
                &format!("{id}@{curve}"),
                &[id, curve],
                None,
                Some(c),
            )?;
        }
        match self.system.ids.get(id) {
            Some(Item::Entity(e)) => Ok(*e),
            Some(
                Item::Constraint(_) | Item::Orientation(_) | Item::Group(_) | Item::Reference(_),
            ) => Err(ModelError::new(ModelErrorKind::NotAnEntity {
                item,
                owner: owner.to_owned(),
                field,
                id: id.to_owned(),
            })),
            None => Err(ModelError::new(ModelErrorKind::UnknownId {
                item,
                owner: owner.to_owned(),
                field,
                id: id.to_owned(),
            })),
        }
    }

    /// Adds a constraint. `args` are the entity ids in the order of the kind's fields
    /// ([`ConstraintKind::fields`]): `a`, `b` (and `axis` for `Symmetric`), or `point`,
    /// `segment` for `Midpoint`.
    pub fn constraint(
        &mut self,
        kind: ConstraintKind,
        id: &str,
        args: &[&str],
        value: Option<BigRational>,
    ) -> Result<ConstraintIdx, ModelError> {
        self.push_constraint(kind, id, args, value, None)
    }

    /// Adds a reference (driven) dimension ([`System::references`]): checked as a constraint of
    /// the same kind, arguments and value would be, but measured, not imposed.
    ///
    /// # Errors
    /// Those of [`Self::constraint`], and a kind that is not a dimension.
    pub fn reference(
        &mut self,
        kind: ConstraintKind,
        id: &str,
        args: &[&str],
        value: Option<BigRational>,
    ) -> Result<(), ModelError> {
        if !kind.is_metric() {
            return Err(ModelError::new(ModelErrorKind::NotADimension { id: id.to_owned(), kind }));
        }
        let c = self.push_constraint(kind, id, args, value, None)?;
        // Checked as a constraint, kept as a reference.
        let reference = self.system.constraints.pop();
        debug_assert_eq!(c.index(), self.system.constraints.len());
        let index = self.system.references.len();
        self.system.references.extend(reference);
        self.system.ids.insert(id.to_owned(), Item::Reference(index));
        Ok(())
    }

    /// Marks an entity as construction geometry ([`Entity::construction`]).
    ///
    /// # Errors
    /// An id that names no entity.
    pub fn construction(&mut self, id: &str) -> Result<(), ModelError> {
        let e = self.resolve("entity", id, "construction", id)?;
        self.system.entities[e.index()].construction = true;
        Ok(())
    }

    /// Adds a group ([`Group`]) of the named entities (at least one, each once).
    ///
    /// # Errors
    /// A duplicate or empty id, an unknown id, no entity, an entity named twice.
    pub fn group(&mut self, id: &str, entities: &[&str]) -> Result<(), ModelError> {
        self.claim_id(id)?;
        if entities.is_empty() {
            return Err(ModelError::new(ModelErrorKind::Group {
                id: id.to_owned(),
                why: "no entity".to_owned(),
            }));
        }
        let mut resolved = Vec::with_capacity(entities.len());
        for name in entities {
            let e = self.resolve("group", id, "entities", name)?;
            if resolved.contains(&e) {
                return Err(ModelError::new(ModelErrorKind::Group {
                    id: id.to_owned(),
                    why: format!("\"{name}\" is named twice"),
                }));
            }
            resolved.push(e);
        }
        let index = self.system.groups.len();
        self.system.groups.push(Group { id: id.to_owned(), entities: resolved });
        self.system.ids.insert(id.to_owned(), Item::Group(index));
        Ok(())
    }

    /// Adds an orientation condition ([`Orientation`]): `points` names three points in 2D,
    /// four in 3D, all distinct; `sign` is 1 or −1.
    ///
    /// # Errors
    /// A duplicate or empty id, an unknown id, an entity that is not a point, the wrong number
    /// of points, a point named twice, a sign other than ±1.
    pub fn orientation(&mut self, id: &str, points: &[&str], sign: i64) -> Result<(), ModelError> {
        self.claim_id(id)?;
        let wrong = |field: &'static str, why: String| {
            Err(ModelError::new(ModelErrorKind::Orientation { id: id.to_owned(), field, why }))
        };
        let expected = self.system.dim.coords() + 1;
        if points.len() != expected {
            return wrong(
                "points",
                format!("{expected} points in {}, found {}", self.system.dim, points.len()),
            );
        }
        let mut resolved = Vec::with_capacity(points.len());
        for name in points {
            let e = self.resolve("constraint", id, "points", name)?;
            let kind = self.system.entity(e).kind();
            if kind != EntityKind::Point {
                return wrong("points", format!("\"{name}\" is a {kind}, not a point"));
            }
            if resolved.contains(&e) {
                return wrong("points", format!("\"{name}\" is named twice"));
            }
            resolved.push(e);
        }
        if sign != 1 && sign != -1 {
            return wrong("sign", format!("sign {sign}: 1 or -1"));
        }
        let index = self.system.orientations.len();
        self.system.orientations.push(Orientation {
            id: id.to_owned(),
            points: resolved,
            sign: if sign > 0 { 1 } else { -1 },
        });
        self.system.ids.insert(id.to_owned(), Item::Orientation(index));
        Ok(())
    }

    fn push_constraint(
        &mut self,
        kind: ConstraintKind,
        id: &str,
        args: &[&str],
        value: Option<BigRational>,
        owner: Option<EntityIdx>,
    ) -> Result<ConstraintIdx, ModelError> {
        self.claim_id(id)?;
        let fields = kind.fields();
        if args.len() != fields.len() {
            return Err(ModelError::new(ModelErrorKind::KindMismatch {
                id: id.to_owned(),
                kind,
                found: format!("{} entities", args.len()),
                expected: format!("{} entities ({})", fields.len(), fields.join(", ")),
                dim: self.system.dim,
            }));
        }
        let mut resolved = Vec::with_capacity(args.len());
        for (field, arg) in fields.iter().zip(args) {
            resolved.push(self.resolve("constraint", id, field, arg)?);
        }
        // (Between two pairs, an entity may be in both: a line bisecting an angle, two points
        // at the same distance from one line.)
        for i in 0..resolved.len() {
            for j in i + 1..resolved.len() {
                if resolved[i] == resolved[j] && !(kind.compares_pairs() && i / 2 != j / 2) {
                    return Err(ModelError::new(ModelErrorKind::RepeatedEntity {
                        id: id.to_owned(),
                        entity: args[i].to_string(),
                        first: fields[i],
                        second: fields[j],
                    }));
                }
            }
        }
        if let Some(v) = &value
            && matches!(
                kind,
                ConstraintKind::Distance | ConstraintKind::Radius | ConstraintKind::LengthRatio
            )
            && v.is_negative()
        {
            return Err(ModelError::new(ModelErrorKind::Negative {
                item: "constraint",
                owner: id.to_owned(),
                field: "value",
                value: crate::number::format_exact(v),
            }));
        }
        let kinds: Vec<EntityKind> =
            resolved.iter().map(|e| self.system.entity(*e).kind()).collect();
        let (signature, doc) = Signature::resolve(self.system.dim, kind, &resolved, &kinds)
            .map_err(|expected| {
                let found = kinds.iter().map(|k| k.to_string()).collect::<Vec<_>>().join("–");
                ModelError::new(ModelErrorKind::KindMismatch {
                    id: id.to_owned(),
                    kind,
                    found,
                    expected: expected.to_owned(),
                    dim: self.system.dim,
                })
            })?;
        let signature = match signature {
            Signature::SplinePoint { point, spline, .. } => {
                let knot = self.spline_knot(id, spline, value.as_ref())?;
                Signature::SplinePoint { point, spline, knot }
            }
            other => other,
        };
        // The DOC of `Fix` is the DOF it pins: the entity's, or its parts', and for an arc
        // one more for each end point (its place along the circle).
        let doc = if let Signature::Fix(e) = signature {
            let points = self.system.arc_points(e).map_or(Vec::new(), |(a, b)| vec![a, b]);
            if !self.system.has_position(e) || !points.iter().all(|p| self.system.has_position(*p))
            {
                return Err(ModelError::new(ModelErrorKind::FixWithoutPosition {
                    id: id.to_owned(),
                    entity: args[0].to_string(),
                }));
            }
            let along = if self.system.arc_points(e).is_some() { 2 } else { 0 };
            self.system.base_entities(e).iter().map(|b| self.system.entity_dof(*b)).sum::<usize>()
                + along
        } else {
            doc
        };
        let idx = ConstraintIdx(self.system.constraints.len() as u32);
        self.system.constraints.push(Constraint {
            id: id.to_owned(),
            kind,
            args: resolved,
            signature,
            value,
            doc,
            position: None,
            owner,
        });
        self.system.ids.insert(id.to_owned(), Item::Constraint(idx));
        Ok(idx)
    }
}

impl SystemBuilder {
    /// The index in B-spline `spline`'s flat knot vector of the parameter `value` of a
    /// `SplinePoint` (`id`): a knot in the curve's parameter range.
    fn spline_knot(
        &self,
        id: &str,
        spline: EntityIdx,
        value: Option<&BigRational>,
    ) -> Result<u32, ModelError> {
        let err = |why: String| {
            ModelError::new(ModelErrorKind::SplineParameter { id: id.to_owned(), why })
        };
        let Some(t) = value else {
            return Err(err("a SplinePoint needs the curve parameter of its point".into()));
        };
        let Geometry::BSpline { degree, poles, knots, periodic, .. } =
            &self.system.entity(spline).geometry
        else {
            return Err(err("not a B-spline".into()));
        };
        let flat =
            crate::spline::knots_or_default(*degree, poles.len(), knots.as_deref(), *periodic);
        let (lo, hi) = crate::spline::domain(*degree, poles.len(), &flat, *periodic);
        flat.iter()
            .position(|k| k == t)
            .filter(|_| &lo <= t && t <= &hi)
            .map(|i| i as u32)
            .ok_or_else(|| {
                err(format!(
                    "{} is not a knot of the spline in its parameter range (a SplinePoint is at \
                     a knot)",
                    crate::number::format_exact(t)
                ))
            })
    }
}

/// The field naming each of `count` parts of a composite kind: its part fields in order, the
/// last one repeated for a kind built on a list (a B-spline's `poles`).
fn part_fields(kind: EntityKind, count: usize) -> Vec<&'static str> {
    let fields = kind.part_fields();
    match fields.last() {
        Some(last) => {
            (0..count.max(fields.len())).map(|i| *fields.get(i).unwrap_or(last)).collect()
        }
        None => Vec::new(),
    }
}
