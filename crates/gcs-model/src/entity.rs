//! Entity kinds, in one place: for each kind its name, the dimensions it exists in, its degrees
//! of freedom, its class (how constraints see it), the entities it is built on, its sketch fields
//! with their checks, and its RON form (read and written).
//!
//! Adding an entity kind means a variant of [`EntityKind`] and of [`Geometry`] and one arm in
//! each exhaustive `match` of this file (the compiler lists them), plus its representation in
//! `gcs-jacobian`; see `ARCHITECTURE.md`, "Adding an entity or constraint kind".

use std::fmt;
use std::fmt::Write as _;

use num_rational::BigRational;
use num_traits::{Signed, Zero};
use serde::Deserialize;

use crate::error::{ModelError, ModelErrorKind};
use crate::kinds::Dim;
use crate::number::{Num, format_exact};
use crate::system::{Coords, EntityIdx, System};

/// The kind of a geometric entity.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EntityKind {
    /// A point.
    Point,
    /// An infinite line.
    Line,
    /// The line through two existing points; it has no degree of freedom of its own.
    Segment,
    /// A circle of variable centre and radius (2D).
    Circle,
    /// A plane (3D).
    Plane,
    /// A sphere of variable centre and radius (3D).
    Sphere,
    /// A circular arc (2D): a circle of variable centre and radius with two points on it, its
    /// start and end, counter-clockwise from start to end.
    Arc,
    /// A B-spline curve (NURBS when weighted), built on its control points (point entities);
    /// its degree, knots and weights are constants, so it has no degree of freedom of its own.
    BSpline,
}

/// How constraints see an entity: the roles of the constraint table (format §1). Several kinds
/// can share a class — a segment is a line — so that a new kind reuses the constraints and
/// equations of its class.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EntityClass {
    /// Point-like: a position.
    Point,
    /// Line-like: lines and segments.
    Line,
    /// Plane-like.
    Plane,
    /// Circle-like: a centre and a radius in the plane.
    Circle,
    /// Sphere-like: a centre and a radius in space.
    Sphere,
    /// A free-form curve (a B-spline). No constraint takes it whole yet: constraints reach its
    /// control points, which are point entities.
    Curve,
}

impl EntityClass {
    /// Whether the class has a centre and a radius (circles, spheres).
    pub fn is_round(self) -> bool {
        match self {
            EntityClass::Circle | EntityClass::Sphere => true,
            EntityClass::Point | EntityClass::Line | EntityClass::Plane | EntityClass::Curve => {
                false
            }
        }
    }
}

impl EntityKind {
    /// Every entity kind, in the order of the format's table.
    pub const ALL: [EntityKind; 8] = [
        EntityKind::Point,
        EntityKind::Line,
        EntityKind::Segment,
        EntityKind::Circle,
        EntityKind::Plane,
        EntityKind::Sphere,
        EntityKind::Arc,
        EntityKind::BSpline,
    ];

    /// The variant name used in model files (`Point`, `Line`, …).
    pub fn name(self) -> &'static str {
        match self {
            EntityKind::Point => "Point",
            EntityKind::Line => "Line",
            EntityKind::Segment => "Segment",
            EntityKind::Circle => "Circle",
            EntityKind::Plane => "Plane",
            EntityKind::Sphere => "Sphere",
            EntityKind::Arc => "Arc",
            EntityKind::BSpline => "BSpline",
        }
    }

    /// The name in messages (`point`, `line`, …).
    pub fn noun(self) -> &'static str {
        match self {
            EntityKind::Point => "point",
            EntityKind::Line => "line",
            EntityKind::Segment => "segment",
            EntityKind::Circle => "circle",
            EntityKind::Plane => "plane",
            EntityKind::Sphere => "sphere",
            EntityKind::Arc => "arc",
            EntityKind::BSpline => "B-spline",
        }
    }

    /// Whether the kind exists in dimension `dim` (circles are planar, planes and spheres
    /// spatial).
    pub fn exists_in(self, dim: Dim) -> bool {
        match self {
            EntityKind::Point | EntityKind::Line | EntityKind::Segment | EntityKind::BSpline => {
                true
            }
            EntityKind::Circle | EntityKind::Arc => dim == Dim::Two,
            EntityKind::Plane | EntityKind::Sphere => dim == Dim::Three,
        }
    }

    /// Degrees of freedom of one entity of this kind (format §1, table "Entities"), not
    /// counting those of the entities it is built on ([`Geometry::parts`]).
    ///
    /// Returns 0 for a kind that does not exist in `dim`.
    pub fn dof(self, dim: Dim) -> usize {
        if !self.exists_in(dim) {
            return 0;
        }
        match self {
            EntityKind::Point => dim.coords(),
            EntityKind::Line => match dim {
                Dim::Two => 2,
                Dim::Three => 4,
            },
            EntityKind::Segment | EntityKind::BSpline => 0,
            EntityKind::Circle | EntityKind::Plane | EntityKind::Arc => 3,
            EntityKind::Sphere => 4,
        }
    }

    /// The class constraints see it as.
    pub fn class(self) -> EntityClass {
        match self {
            EntityKind::Point => EntityClass::Point,
            EntityKind::Line | EntityKind::Segment => EntityClass::Line,
            EntityKind::Plane => EntityClass::Plane,
            EntityKind::Circle | EntityKind::Arc => EntityClass::Circle,
            EntityKind::Sphere => EntityClass::Sphere,
            EntityKind::BSpline => EntityClass::Curve,
        }
    }

    /// Whether the kind is built on other entities and has no coordinates of its own
    /// (a segment: the line through its two points; a B-spline: the curve of its control
    /// points). Constraints on it act on its parts.
    pub fn is_composite(self) -> bool {
        match self {
            EntityKind::Segment | EntityKind::BSpline => true,
            EntityKind::Point
            | EntityKind::Line
            | EntityKind::Circle
            | EntityKind::Plane
            | EntityKind::Sphere
            | EntityKind::Arc => false,
        }
    }

    /// The fields naming the entities a composite kind is built on, in order (a segment:
    /// `from`, `to`); empty for the others. A kind built on a list (a B-spline's `poles`) has
    /// one field, which names every part.
    pub fn part_fields(self) -> &'static [&'static str] {
        match self {
            EntityKind::Segment => &["from", "to"],
            EntityKind::BSpline => &["poles"],
            EntityKind::Point
            | EntityKind::Line
            | EntityKind::Circle
            | EntityKind::Plane
            | EntityKind::Sphere
            | EntityKind::Arc => &[],
        }
    }

    /// Whether the kind is line-like: a line or a segment. Every constraint that takes a line
    /// also takes a segment.
    pub fn is_line_like(self) -> bool {
        self.class() == EntityClass::Line
    }
}

impl fmt::Display for EntityKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.noun())
    }
}

/// An entity's kind with its sketch data (every sketch field is optional) or, for a composite
/// kind, the entities it is built on.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A point.
    Point {
        /// Sketch position.
        at: Option<Coords>,
    },
    /// An infinite line, sketched by two distinct points on it.
    Line {
        /// Two distinct points on the line.
        at: Option<[Coords; 2]>,
    },
    /// The line through two point entities.
    Segment {
        /// First point.
        from: EntityIdx,
        /// Second point.
        to: EntityIdx,
    },
    /// A circle (2D).
    Circle {
        /// Sketch centre.
        center: Option<Coords>,
        /// Sketch radius.
        radius: Option<BigRational>,
    },
    /// A plane (3D), sketched by a point on it and a normal.
    Plane {
        /// `[point, normal]`.
        at: Option<[Coords; 2]>,
    },
    /// A sphere (3D).
    Sphere {
        /// Sketch centre.
        center: Option<Coords>,
        /// Sketch radius.
        radius: Option<BigRational>,
    },
    /// A circular arc (2D): its circle, and its start and end points — point entities of their
    /// own (`<id>.start`, `<id>.end`, owned by the arc), held on the circle by implicit
    /// `Incident` constraints.
    Arc {
        /// Sketch centre.
        center: Option<Coords>,
        /// Sketch radius.
        radius: Option<BigRational>,
        /// The start point.
        start: EntityIdx,
        /// The end point.
        end: EntityIdx,
    },
    /// A B-spline curve (NURBS when weighted): the curve of its control points, which are
    /// point entities; its degree, knots and weights are constants ([`crate::spline`]).
    BSpline {
        /// The degree (1 to [`crate::spline::MAX_DEGREE`]).
        degree: u32,
        /// The control points, in order.
        poles: Vec<EntityIdx>,
        /// The knot vector, flat with repetitions: `poles + degree + 1` knots for an open
        /// spline, the `poles + 1` knots of one period for a periodic one. `None`: clamped
        /// and uniform (open), uniform (periodic).
        knots: Option<Vec<BigRational>>,
        /// One positive weight per control point (`None`: all 1, a polynomial B-spline).
        weights: Option<Vec<BigRational>>,
        /// Closed and periodic (the control points wrap around).
        periodic: bool,
    },
}

impl Geometry {
    /// The entity kind.
    pub fn kind(&self) -> EntityKind {
        match self {
            Geometry::Point { .. } => EntityKind::Point,
            Geometry::Line { .. } => EntityKind::Line,
            Geometry::Segment { .. } => EntityKind::Segment,
            Geometry::Circle { .. } => EntityKind::Circle,
            Geometry::Plane { .. } => EntityKind::Plane,
            Geometry::Sphere { .. } => EntityKind::Sphere,
            Geometry::Arc { .. } => EntityKind::Arc,
            Geometry::BSpline { .. } => EntityKind::BSpline,
        }
    }

    /// Whether the kind has a centre that constraints can name (`<id>.center`: circles, arcs,
    /// spheres), and its sketch position.
    pub fn center(&self) -> Option<Option<&Coords>> {
        match self {
            Geometry::Circle { center, .. }
            | Geometry::Sphere { center, .. }
            | Geometry::Arc { center, .. } => Some(center.as_ref()),
            Geometry::Point { .. }
            | Geometry::Line { .. }
            | Geometry::Segment { .. }
            | Geometry::Plane { .. }
            | Geometry::BSpline { .. } => None,
        }
    }

    /// The entities a composite entity is built on (a segment's two points), in order; empty
    /// for the others.
    pub fn parts(&self) -> Vec<EntityIdx> {
        match self {
            Geometry::Segment { from, to } => vec![*from, *to],
            Geometry::BSpline { poles, .. } => poles.clone(),
            Geometry::Point { .. }
            | Geometry::Line { .. }
            | Geometry::Circle { .. }
            | Geometry::Plane { .. }
            | Geometry::Sphere { .. }
            | Geometry::Arc { .. } => Vec::new(),
        }
    }

    /// The same composite entity built on `parts` (as many as [`Geometry::parts`] returns, in
    /// that order); the others unchanged.
    pub(crate) fn with_parts(self, parts: &[EntityIdx]) -> Geometry {
        match (self, parts) {
            (Geometry::Segment { .. }, [from, to]) => Geometry::Segment { from: *from, to: *to },
            (Geometry::BSpline { degree, poles, knots, weights, periodic }, parts)
                if parts.len() == poles.len() =>
            {
                Geometry::BSpline { degree, poles: parts.to_vec(), knots, weights, periodic }
            }
            (g, _) => g,
        }
    }

    /// Checks the parts of a composite entity against what it is built on: their kinds, and
    /// that the sketch does not make it degenerate. `names` are the ids as written (for
    /// messages), `fields` their field names.
    pub(crate) fn check_parts(
        &self,
        id: &str,
        fields: &[&'static str],
        names: &[&str],
        system: &System,
    ) -> Result<(), ModelError> {
        match self {
            Geometry::Segment { from, to } => {
                for ((field, e), name) in fields.iter().zip([from, to]).zip(names) {
                    let found = system.entity(*e).kind();
                    if found != EntityKind::Point {
                        return Err(ModelError::new(ModelErrorKind::SegmentEndpoint {
                            id: id.to_owned(),
                            field,
                            entity: (*name).to_owned(),
                            found,
                        }));
                    }
                }
                if from == to {
                    return Err(degenerate(
                        id,
                        "to",
                        &format!("segment from \"{}\" to itself", names[0]),
                    ));
                }
                if let (Geometry::Point { at: Some(p) }, Geometry::Point { at: Some(q) }) =
                    (&system.entity(*from).geometry, &system.entity(*to).geometry)
                    && p == q
                {
                    return Err(ModelError::new(ModelErrorKind::Degenerate {
                        id: id.to_owned(),
                        field: None,
                        what: format!(
                            "its points \"{}\" and \"{}\" coincide in the sketch",
                            names[0], names[1]
                        ),
                    }));
                }
                Ok(())
            }
            Geometry::BSpline { poles, .. } => {
                for (e, name) in poles.iter().zip(names) {
                    let found = system.entity(*e).kind();
                    if found != EntityKind::Point {
                        return Err(degenerate(
                            id,
                            fields.first().copied().unwrap_or("poles"),
                            &format!(
                                "a B-spline's control points are points, \"{name}\" is a {found}"
                            ),
                        ));
                    }
                }
                Ok(())
            }
            Geometry::Point { .. }
            | Geometry::Line { .. }
            | Geometry::Circle { .. }
            | Geometry::Plane { .. }
            | Geometry::Sphere { .. }
            | Geometry::Arc { .. } => Ok(()),
        }
    }

    /// Whether every sketch field that places the entity is given (a composite entity has no
    /// field of its own: its parts decide, see [`crate::System::has_position`]).
    pub(crate) fn has_own_position(&self) -> bool {
        match self {
            Geometry::Point { at } => at.is_some(),
            Geometry::Line { at } | Geometry::Plane { at } => at.is_some(),
            Geometry::Circle { center, radius }
            | Geometry::Sphere { center, radius }
            | Geometry::Arc { center, radius, .. } => center.is_some() && radius.is_some(),
            Geometry::Segment { .. } | Geometry::BSpline { .. } => false,
        }
    }

    /// Checks the sketch fields against the dimension: coordinate counts, degenerate values.
    /// (References of composite kinds are checked by the builder, which resolves them.)
    pub(crate) fn check(&self, id: &str, dim: Dim) -> Result<(), ModelError> {
        let coords = |field: &'static str, c: &Coords| check_coords(id, field, c, dim);
        match self {
            Geometry::Point { at } => at.as_ref().map_or(Ok(()), |at| coords("at", at)),
            Geometry::Line { at } => {
                if let Some([p, q]) = at {
                    coords("at", p)?;
                    coords("at", q)?;
                    if p == q {
                        return Err(degenerate(id, "at", "the two points of the line coincide"));
                    }
                }
                Ok(())
            }
            Geometry::Plane { at } => {
                if let Some([p, n]) = at {
                    coords("at", p)?;
                    coords("at", n)?;
                    if n.iter().all(Zero::is_zero) {
                        return Err(degenerate(id, "at", "the normal of the plane is zero"));
                    }
                }
                Ok(())
            }
            Geometry::Circle { center, radius }
            | Geometry::Sphere { center, radius }
            | Geometry::Arc { center, radius, .. } => {
                if let Some(c) = center {
                    coords("center", c)?;
                }
                check_radius(id, radius)
            }
            Geometry::Segment { .. } => Ok(()),
            Geometry::BSpline { degree, poles, knots, weights, periodic } => crate::spline::check(
                *degree,
                poles.len(),
                knots.as_deref(),
                weights.as_deref(),
                *periodic,
            )
            .map_err(|(field, what)| degenerate(id, field, &what)),
        }
    }

    /// The RON form of the entity (format §1), exactly: numbers that are not terminating
    /// decimals are written as quoted fractions. `name` gives the id of a referenced entity.
    pub(crate) fn to_ron(&self, id: &str, system: &System) -> String {
        let name = |e: EntityIdx| system.entity(e).id.clone();
        let id = quote(id);
        let kind = self.kind().name();
        match self {
            Geometry::Point { at } => match at {
                Some(at) => format!("Point(id: {id}, at: {})", ron_coords(at)),
                None => format!("Point(id: {id})"),
            },
            Geometry::Line { at } | Geometry::Plane { at } => match at {
                Some([p, q]) => {
                    format!("{kind}(id: {id}, at: [{}, {}])", ron_coords(p), ron_coords(q))
                }
                None => format!("{kind}(id: {id})"),
            },
            Geometry::Segment { from, to } => format!(
                "Segment(id: {id}, from: {}, to: {})",
                quote(&name(*from)),
                quote(&name(*to))
            ),
            Geometry::Circle { center, radius } | Geometry::Sphere { center, radius } => {
                let mut s = format!("{kind}(id: {id}");
                if let Some(c) = center {
                    let _ = write!(s, ", center: {}", ron_coords(c));
                }
                if let Some(r) = radius {
                    let _ = write!(s, ", radius: {}", format_exact(r));
                }
                s.push(')');
                s
            }
            Geometry::Arc { center, radius, start, end } => {
                let mut s = format!("Arc(id: {id}");
                if let Some(c) = center {
                    let _ = write!(s, ", center: {}", ron_coords(c));
                }
                if let Some(r) = radius {
                    let _ = write!(s, ", radius: {}", format_exact(r));
                }
                for (field, p) in [("start", start), ("end", end)] {
                    if let Geometry::Point { at: Some(at) } = &system.entity(*p).geometry {
                        let _ = write!(s, ", {field}: {}", ron_coords(at));
                    }
                }
                s.push(')');
                s
            }
            Geometry::BSpline { degree, poles, knots, weights, periodic } => {
                let poles: Vec<String> = poles.iter().map(|p| quote(&name(*p))).collect();
                let mut s =
                    format!("BSpline(id: {id}, degree: {degree}, poles: [{}]", poles.join(", "));
                if let Some(k) = knots {
                    let _ = write!(s, ", knots: {}", ron_coords(k));
                }
                if let Some(w) = weights {
                    let _ = write!(s, ", weights: {}", ron_coords(w));
                }
                if *periodic {
                    s.push_str(", periodic: true");
                }
                s.push(')');
                s
            }
        }
    }
}

fn degenerate(id: &str, field: &'static str, what: &str) -> ModelError {
    ModelError::new(ModelErrorKind::Degenerate {
        id: id.to_owned(),
        field: Some(field),
        what: what.into(),
    })
}

pub(crate) fn check_coords(
    id: &str,
    field: &'static str,
    c: &Coords,
    dim: Dim,
) -> Result<(), ModelError> {
    let expected = dim.coords();
    if c.len() != expected {
        return Err(ModelError::new(ModelErrorKind::WrongCoordinateCount {
            id: id.to_owned(),
            field,
            expected,
            found: c.len(),
            dim,
        }));
    }
    Ok(())
}

fn check_radius(id: &str, r: &Option<BigRational>) -> Result<(), ModelError> {
    match r {
        Some(r) if r.is_negative() => Err(ModelError::new(ModelErrorKind::Negative {
            item: "entity",
            owner: id.to_owned(),
            field: "radius",
            value: format_exact(r),
        })),
        Some(r) if r.is_zero() => Err(degenerate(
            id,
            "radius",
            "radius 0: a circle or sphere of radius 0 is a point; use a Point",
        )),
        _ => Ok(()),
    }
}

/// A string literal in RON.
pub(crate) fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{{{:x}}}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn ron_coords(c: &Coords) -> String {
    let parts: Vec<String> = c.iter().map(format_exact).collect();
    format!("[{}]", parts.join(", "))
}

/// An entity as written in a model file, before ids are resolved.
#[derive(Deserialize)]
#[serde(rename = "Entity", deny_unknown_fields)]
pub(crate) enum RawEntity {
    Point {
        id: String,
        #[serde(default)]
        at: Option<Vec<Num>>,
        #[serde(default)]
        construction: bool,
    },
    Line {
        id: String,
        #[serde(default)]
        at: Option<Vec<Vec<Num>>>,
        #[serde(default)]
        construction: bool,
    },
    Segment {
        id: String,
        from: String,
        to: String,
        #[serde(default)]
        construction: bool,
    },
    Circle {
        id: String,
        #[serde(default)]
        center: Option<Vec<Num>>,
        #[serde(default)]
        radius: Option<Num>,
        #[serde(default)]
        construction: bool,
    },
    Plane {
        id: String,
        #[serde(default)]
        at: Option<Vec<Vec<Num>>>,
        #[serde(default)]
        construction: bool,
    },
    Sphere {
        id: String,
        #[serde(default)]
        center: Option<Vec<Num>>,
        #[serde(default)]
        radius: Option<Num>,
        #[serde(default)]
        construction: bool,
    },
    Arc {
        id: String,
        #[serde(default)]
        center: Option<Vec<Num>>,
        #[serde(default)]
        radius: Option<Num>,
        #[serde(default)]
        start: Option<Vec<Num>>,
        #[serde(default)]
        end: Option<Vec<Num>>,
        #[serde(default)]
        construction: bool,
    },
    BSpline {
        id: String,
        degree: u32,
        poles: Vec<String>,
        #[serde(default)]
        knots: Option<Vec<Num>>,
        #[serde(default)]
        weights: Option<Vec<Num>>,
        #[serde(default)]
        periodic: bool,
        #[serde(default)]
        construction: bool,
    },
}

/// What a [`RawEntity`] becomes: its id, its sketch data, and the ids of the entities it is
/// built on (with their field names), still unresolved.
pub(crate) struct ReadEntity<'r> {
    pub(crate) id: &'r str,
    /// The geometry; parts are placeholders until the builder resolves `refs`.
    pub(crate) geometry: Geometry,
    pub(crate) refs: Vec<(&'static str, &'r str)>,
    /// The sketch positions of the points an arc owns (start, end).
    pub(crate) owned_points: Vec<Option<Coords>>,
    /// Construction geometry.
    pub(crate) construction: bool,
}

impl RawEntity {
    /// The entity's sketch data as exact numbers.
    pub(crate) fn read(&self) -> Result<ReadEntity<'_>, ModelError> {
        let mut read = self.read_geometry()?;
        read.construction = match self {
            RawEntity::Point { construction, .. }
            | RawEntity::Line { construction, .. }
            | RawEntity::Segment { construction, .. }
            | RawEntity::Circle { construction, .. }
            | RawEntity::Plane { construction, .. }
            | RawEntity::Sphere { construction, .. }
            | RawEntity::Arc { construction, .. }
            | RawEntity::BSpline { construction, .. } => *construction,
        };
        Ok(read)
    }

    fn read_geometry(&self) -> Result<ReadEntity<'_>, ModelError> {
        use crate::read::{number, read_coords, two_coords};
        let placeholder = EntityIdx(u32::MAX);
        Ok(match self {
            RawEntity::Point { id, at, .. } => ReadEntity {
                id,
                geometry: Geometry::Point {
                    at: at.as_deref().map(|v| read_coords(id, "at", v)).transpose()?,
                },
                refs: Vec::new(),
                owned_points: Vec::new(),
                construction: false,
            },
            RawEntity::Line { id, at, .. } => ReadEntity {
                id,
                geometry: Geometry::Line {
                    at: at.as_deref().map(|v| two_coords(id, "at", v)).transpose()?,
                },
                refs: Vec::new(),
                owned_points: Vec::new(),
                construction: false,
            },
            RawEntity::Segment { id, from, to, .. } => ReadEntity {
                id,
                geometry: Geometry::Segment { from: placeholder, to: placeholder },
                refs: vec![("from", from), ("to", to)],
                owned_points: Vec::new(),
                construction: false,
            },
            RawEntity::Circle { id, center, radius, .. }
            | RawEntity::Sphere { id, center, radius, .. } => {
                let center = center.as_deref().map(|v| read_coords(id, "center", v)).transpose()?;
                let radius =
                    radius.as_ref().map(|r| number("entity", id, "radius", r)).transpose()?;
                let geometry = if matches!(self, RawEntity::Circle { .. }) {
                    Geometry::Circle { center, radius }
                } else {
                    Geometry::Sphere { center, radius }
                };
                ReadEntity {
                    id,
                    geometry,
                    refs: Vec::new(),
                    owned_points: Vec::new(),
                    construction: false,
                }
            }
            RawEntity::Arc { id, center, radius, start, end, .. } => {
                let center = center.as_deref().map(|v| read_coords(id, "center", v)).transpose()?;
                let radius =
                    radius.as_ref().map(|r| number("entity", id, "radius", r)).transpose()?;
                let start = start.as_deref().map(|v| read_coords(id, "start", v)).transpose()?;
                let end = end.as_deref().map(|v| read_coords(id, "end", v)).transpose()?;
                let placeholder = EntityIdx(u32::MAX);
                ReadEntity {
                    id,
                    geometry: Geometry::Arc {
                        center,
                        radius,
                        start: placeholder,
                        end: placeholder,
                    },
                    refs: Vec::new(),
                    owned_points: vec![start, end],
                    construction: false,
                }
            }
            RawEntity::BSpline { id, degree, poles, knots, weights, periodic, .. } => {
                let list = |field: &'static str, v: &Option<Vec<Num>>| {
                    v.as_ref()
                        .map(|v| v.iter().map(|x| number("entity", id, field, x)).collect())
                        .transpose()
                };
                ReadEntity {
                    id,
                    geometry: Geometry::BSpline {
                        degree: *degree,
                        poles: vec![placeholder; poles.len()],
                        knots: list("knots", knots)?,
                        weights: list("weights", weights)?,
                        periodic: *periodic,
                    },
                    refs: poles.iter().map(|p| ("poles", p.as_str())).collect(),
                    owned_points: Vec::new(),
                    construction: false,
                }
            }
            RawEntity::Plane { id, at, .. } => ReadEntity {
                id,
                geometry: Geometry::Plane {
                    at: at.as_deref().map(|v| two_coords(id, "at", v)).transpose()?,
                },
                refs: Vec::new(),
                owned_points: Vec::new(),
                construction: false,
            },
        })
    }
}
