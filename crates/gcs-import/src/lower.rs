//! The lowering: a neutral sketch ([`Sketch`]) becomes a gcs model ([`System`]).
//!
//! One place decides how the CAD vocabulary becomes gcs entities and constraints, for every
//! reader. The rules (also in `docs/format.md`, "Importing CAD files"):
//!
//! - **Entities.** A point is a `Point`; a segment is a `Segment` between two points of its
//!   own, `<id>.start` and `<id>.end`; a line is a `Line`; a circle a `Circle`; an arc an `Arc`
//!   (its end points `<id>.start`, `<id>.end` are the arc's own); a 3D plane a `Plane`. A
//!   named point of a curve is addressed as the model does: `<id>.start`, `<id>.end`,
//!   `<id>.center`. External geometry is fixed where it is drawn: a `Fix` named `<id>#fixed`.
//!   A B-spline is a `BSpline` on control points of its own: `<id>.start` and `<id>.end` (the
//!   curve's end points) for the first and last of a clamped spline, `<id>.pole<i>` for the
//!   others. Ellipses and elliptical arcs are not in the gcs model yet: skipped, with every
//!   constraint that refers to them.
//! - **Constraints** keep the source's id. Where one CAD constraint says two things it becomes
//!   two gcs constraints, the second named after the first: tangency at shared end points is
//!   `TangentAt` (id) + `Coincident` (`<id>#coincident`) — one transversal formulation, never
//!   incidence + tangency, which is singular at every solution. For the same reason a tangency
//!   between two curves that the sketch joins elsewhere (an end point of one coincident with an
//!   end point of the other, or on the other: how Onshape and FreeCAD write many fillets) is
//!   `TangentAt` that point; collinear lines are `Parallel`
//!   and `Incident` (`<id>#on`). Horizontal (vertical) points are `DistanceY` (`DistanceX`) 0, a
//!   length is the distance between the segment's end points, a diameter a radius of half the
//!   value, equal lengths or radii `EqualLength` or `EqualRadius`, a line's angle to the x axis
//!   an `Angle` to a fixed horizontal line `#x-axis`.
//! - **Numbers** are snapped to 10^-9 ([`snap`]): CAD float noise off, the drawing unmoved.
//! - **Reference (non-driving) dimensions** are measured, not imposed: listed in
//!   [`Lowered::reference`], and a reference dimension of the model
//!   ([`gcs_model::System::references`]) where they are one dimension of the model's (a
//!   distance, a length, an angle, a radius: a diameter is measured as its radius).
//! - **Construction geometry** keeps its flag ([`gcs_model::Entity::construction`]).
//! - Whatever cannot be expressed is listed in [`Lowered::skipped`] with its reason (after
//!   what the reader skipped), and the import is not complete.

use gcs_model::{ConstraintKind as K, Dim, System, SystemBuilder};
use num_rational::BigRational;
use num_traits::ToPrimitive;

use crate::ir::{Constraint, Geometry, Kind, Part, Ref, Sketch, Skipped};

/// A sketch as a gcs model, with what did not make it.
#[derive(Clone, Debug)]
pub struct Lowered {
    /// The model, named `<file stem>/<sketch>` (the sketch's name).
    pub system: System,
    /// The sketch's human label, when the source has one.
    pub label: Option<String>,
    /// What could not be expressed — by the reader, then by the lowering — each with its
    /// reason.
    pub skipped: Vec<Skipped>,
    /// What was not imported although nothing is lost (see [`Sketch::notes`]).
    pub notes: Vec<Skipped>,
    /// The reference (non-driving) dimensions: measured by the CAD program, not imposed, so
    /// not in the model.
    pub reference: Vec<String>,
    /// What the source program recorded about its own solution, verbatim.
    pub source_verdict: Vec<(String, String)>,
}

impl Lowered {
    /// Everything in the sketch was expressed.
    pub fn complete(&self) -> bool {
        self.skipped.is_empty()
    }
}

/// What a lowered entity is, for choosing how constraints on it lower.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Shape {
    Point,
    Segment,
    Line,
    Circle,
    Arc,
    Plane,
    /// A B-spline with this many control points, clamped (its ends are its first and last
    /// control points) or not.
    Spline {
        poles: usize,
        clamped: bool,
    },
}

/// What a reference stands for once resolved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Class {
    /// A point entity or a named point of a curve.
    Point,
    /// A segment or a line.
    Straight,
    /// A circle or an arc.
    Round,
    /// A plane.
    Plane,
    /// A free-form curve (a B-spline).
    Curve,
}

/// A resolved reference: the model id and what it is.
#[derive(Clone, Debug)]
struct Target {
    id: String,
    class: Class,
    shape: Option<Shape>,
}

/// The id of the fixed horizontal line that angles to the x axis are measured against.
const X_AXIS: &str = "#x-axis";

struct Lowering {
    builder: SystemBuilder,
    /// Points joined by the sketch's coincidences: point id → representative.
    joined: std::collections::HashMap<String, String>,
    /// `(point id, curve id)` of the sketch's point-on-curve constraints.
    on_curve: std::collections::HashSet<(String, String)>,
    shapes: std::collections::HashMap<String, Shape>,
    /// Entities of the sketch not lowered, with the reason.
    dropped: std::collections::HashMap<String, String>,
    skipped: Vec<Skipped>,
    reference: Vec<String>,
    /// Lowering a reference (non-driving) dimension: what it measures becomes a reference of
    /// the model, never an equation.
    as_reference: bool,
    /// The reference dimension being lowered has no value in the file (it is driven: the CAD
    /// program computes it).
    reference_without_value: bool,
    /// The moves of patterns made so far, by the coincidence classes of their points (and the
    /// turn): a point that two listed elements share (a corner of two patterned segments) is
    /// moved once, with the constraint that made it.
    moves: std::collections::HashMap<Vec<String>, String>,
    /// The regular polygons of irrational turns made so far ([`Lowering::turned`]): by the
    /// coincidence classes of the turned point and the pivot and the number of vertices, the
    /// ids of the vertices after the point (counter-clockwise).
    polygons: std::collections::BTreeMap<(String, String, u64), Vec<String>>,
    /// What was not imported because another constraint says it (see [`Sketch::notes`]).
    notes: Vec<Skipped>,
}

/// Lowers a sketch into a gcs model. Never fails: what cannot be expressed is skipped with its
/// reason.
pub fn lower(sketch: &Sketch) -> Lowered {
    let dim = if sketch.dim == 3 { Dim::Three } else { Dim::Two };
    let mut l = Lowering {
        builder: SystemBuilder::new(sketch.name.clone(), dim),
        joined: Default::default(),
        on_curve: Default::default(),
        shapes: Default::default(),
        dropped: Default::default(),
        skipped: sketch.skipped.clone(),
        reference: Vec::new(),
        as_reference: false,
        reference_without_value: false,
        moves: Default::default(),
        polygons: Default::default(),
        notes: Vec::new(),
    };
    for entity in &sketch.entities {
        match l.entity(&entity.id, &entity.geometry) {
            Ok(shape) => {
                l.shapes.insert(entity.id.clone(), shape);
                if entity.construction {
                    // The entity was just made: marking it cannot fail.
                    let _ = l.builder.construction(&entity.id);
                }
                if entity.external {
                    let id = format!("{}#fixed", entity.id);
                    if let Err(e) = l.builder.constraint(K::Fix, &id, &[&entity.id], None) {
                        l.skip(&id, format!("external geometry not fixed: {e}"));
                    }
                }
            }
            Err(reason) => {
                l.dropped.insert(entity.id.clone(), reason.clone());
                l.skip(&entity.id, reason);
            }
        }
    }
    l.find_joints(&sketch.constraints);
    let mut notes = sketch.notes.clone();
    let mut said = std::mem::take(&mut l.notes);
    for c in &sketch.constraints {
        if !c.driving {
            // Measured, not imposed: a reference dimension of the model where it is one
            // dimension of the model's; otherwise only listed (nothing is lost: it imposes
            // nothing).
            l.reference.push(c.id.clone());
            l.as_reference = true;
            l.reference_without_value = c.value.is_none();
            if let Err(reason) = l.constraint(c) {
                notes.push(Skipped {
                    item: c.id.clone(),
                    reason: format!("a reference dimension, not measured: {reason}"),
                });
            }
            l.as_reference = false;
            continue;
        }
        if let Err(reason) = l.constraint(c) {
            l.skip(&c.id, reason);
        }
        said.append(&mut l.notes);
    }
    notes.extend(said);
    Lowered {
        system: l.builder.build(),
        label: sketch.label.clone(),
        skipped: l.skipped,
        notes,
        reference: l.reference,
        source_verdict: sketch.source_verdict.clone(),
    }
}

/// The grid numbers are snapped to: 10^-9 (a nanometre, a nano-degree).
const SNAP_PLACES: u32 = 9;

/// A number of the file on the grid of [`SNAP_PLACES`] decimals: unchanged when it has at most
/// that many, else rounded to the nearest point of the grid. CAD programs store doubles:
/// `10.000000000000002` is 10 with float noise, which would hide that an arc's end lies on its
/// circle or a point on an axis; the rounding moves nothing by more than half a nanometre, far
/// below any CAD program's precision, and far above its float noise.
pub fn snap(q: &BigRational) -> BigRational {
    let scale = BigRational::from_integer(num_bigint::BigInt::from(10u32).pow(SNAP_PLACES));
    let scaled = q * &scale;
    if scaled.is_integer() {
        return q.clone();
    }
    scaled.round() / scale
}

fn rational(coords: &[crate::ir::Number]) -> Vec<BigRational> {
    coords.iter().map(|n| snap(&n.0)).collect()
}

impl Lowering {
    fn skip(&mut self, item: &str, reason: String) {
        self.skipped.push(Skipped { item: item.to_owned(), reason });
    }

    fn entity(&mut self, id: &str, geometry: &Geometry) -> Result<Shape, String> {
        let b = &mut self.builder;
        let e = |e: gcs_model::ModelError| e.to_string();
        match geometry {
            Geometry::Point { at } => b.point(id, Some(rational(at))).map(|_| Shape::Point),
            Geometry::Segment { start, end } => {
                let (from, to) = (format!("{id}.start"), format!("{id}.end"));
                b.point(&from, Some(rational(start))).map_err(e)?;
                b.point(&to, Some(rational(end))).map_err(e)?;
                b.segment(id, &from, &to).map(|_| Shape::Segment)
            }
            Geometry::Line { a, b: other } => {
                b.line(id, Some([rational(a), rational(other)])).map(|_| Shape::Line)
            }
            Geometry::Circle { center, radius } => {
                b.circle(id, Some(rational(center)), Some(snap(&radius.0))).map(|_| Shape::Circle)
            }
            Geometry::Arc { center, start, end } => b
                .arc(id, Some(rational(center)), None, Some(rational(start)), Some(rational(end)))
                .map(|_| Shape::Arc),
            Geometry::Plane { origin, normal } => {
                b.plane(id, Some([rational(origin), rational(normal)])).map(|_| Shape::Plane)
            }
            Geometry::Ellipse { .. } => return Err(not_in_model("an ellipse")),
            Geometry::EllipticalArc { .. } => return Err(not_in_model("an elliptical arc")),
            Geometry::BSpline { degree, poles, weights, knots, periodic } => {
                return self.bspline(id, *degree, poles, weights.as_deref(), knots, *periodic);
            }
        }
        .map_err(e)
    }

    /// A B-spline on control points of its own ([`pole_id`]).
    fn bspline(
        &mut self,
        id: &str,
        degree: u32,
        poles: &[crate::ir::Coords],
        weights: Option<&[crate::ir::Number]>,
        knots: &[(crate::ir::Number, u32)],
        periodic: bool,
    ) -> Result<Shape, String> {
        let e = |e: gcs_model::ModelError| e.to_string();
        let mut flat: Vec<BigRational> = Vec::new();
        for (i, (k, m)) in knots.iter().enumerate() {
            // A periodic spline's knots are those of one period: its last knot closes the period
            // (and repeats the first's multiplicity), so it is written once.
            let m = if periodic && i + 1 == knots.len() { 1 } else { *m };
            flat.extend(std::iter::repeat_n(k.0.clone(), m as usize));
        }
        let weights = weights.map(|w| w.iter().map(|w| w.0.clone()).collect::<Vec<_>>());
        let weights =
            weights.filter(|w| w.iter().any(|w| *w != BigRational::from_integer(1.into())));
        // Checked before its control points are made, so that a spline the model refuses
        // leaves nothing behind.
        gcs_model::spline::check(degree, poles.len(), Some(&flat), weights.as_deref(), periodic)
            .map_err(|(field, what)| {
                format!("a B-spline the model cannot hold: {field}: {what}")
            })?;
        let clamped = gcs_model::spline::is_clamped(degree, poles.len(), Some(&flat), periodic);
        let n = poles.len();
        let ids: Vec<String> = (0..n).map(|i| pole_id(id, i, n, clamped)).collect();
        for (pole, at) in ids.iter().zip(poles) {
            self.builder.point(pole, Some(rational(at))).map_err(e)?;
        }
        let names: Vec<&str> = ids.iter().map(String::as_str).collect();
        self.builder.bspline(id, degree, &names, Some(flat), weights, periodic).map_err(e)?;
        Ok(Shape::Spline { poles: n, clamped })
    }

    /// The model id of a reference, and what it is.
    fn target(&mut self, r: &Ref) -> Result<Target, String> {
        let Some(&shape) = self.shapes.get(&r.entity) else {
            return Err(match self.dropped.get(&r.entity) {
                Some(_) => format!("refers to {}, which was skipped", r.entity),
                None => format!("refers to {}, which is not in the sketch", r.entity),
            });
        };
        let point = |suffix: &str| Target {
            id: format!("{}.{suffix}", r.entity),
            class: Class::Point,
            shape: None,
        };
        match (r.part, shape) {
            (Part::Whole, _) => Ok(Target {
                id: r.entity.clone(),
                class: match shape {
                    Shape::Point => Class::Point,
                    Shape::Segment | Shape::Line => Class::Straight,
                    Shape::Circle | Shape::Arc => Class::Round,
                    Shape::Plane => Class::Plane,
                    Shape::Spline { .. } => Class::Curve,
                },
                shape: Some(shape),
            }),
            (Part::Start, Shape::Segment | Shape::Arc) => Ok(point("start")),
            (Part::End, Shape::Segment | Shape::Arc) => Ok(point("end")),
            (Part::Center, Shape::Circle | Shape::Arc) => Ok(point("center")),
            (Part::Pole(i), Shape::Spline { poles, clamped }) if i < poles => Ok(Target {
                id: pole_id(&r.entity, i, poles, clamped),
                class: Class::Point,
                shape: None,
            }),
            (Part::Start, Shape::Spline { clamped: true, .. }) => Ok(point("start")),
            (Part::End, Shape::Spline { clamped: true, .. }) => Ok(point("end")),
            (Part::StartTangent | Part::EndTangent, Shape::Spline { clamped: true, .. }) => {
                let curve =
                    Target { id: r.entity.clone(), class: Class::Curve, shape: Some(shape) };
                let end = if r.part == Part::StartTangent { Part::Start } else { Part::End };
                self.end_leg(curve, shape, end)
            }
            (Part::Start | Part::End, Shape::Spline { clamped: false, .. }) => Err(format!(
                "refers to the {} of {}, a B-spline that is not clamped: its end is no control \
                 point, and a point on the curve is not in the gcs model yet",
                part_name(r.part),
                r.entity
            )),
            (part, shape) => Err(format!(
                "refers to the {} of {} ({}), which the gcs model does not name",
                part_name(part),
                r.entity,
                shape_name(shape)
            )),
        }
    }

    /// The joints the sketch states: coincident points (by union-find over the driving
    /// `Coincident`s) and points on curves (the driving `PointOnObject`s).
    fn find_joints(&mut self, constraints: &[Constraint]) {
        for c in constraints.iter().filter(|c| c.driving) {
            let targets: Vec<Target> = c.refs.iter().filter_map(|r| self.target(r).ok()).collect();
            match (c.kind, targets.as_slice()) {
                (Kind::Coincident, [a, b])
                    if a.class == Class::Point && b.class == Class::Point =>
                {
                    let (ra, rb) = (self.root(&a.id), self.root(&b.id));
                    if ra != rb {
                        self.joined.insert(ra, rb);
                    }
                }
                (Kind::PointOnObject, [p, curve]) if p.class == Class::Point => {
                    self.on_curve.insert((p.id.clone(), curve.id.clone()));
                }
                _ => {}
            }
        }
    }

    fn root(&self, id: &str) -> String {
        let mut id = id.to_owned();
        while let Some(next) = self.joined.get(&id) {
            id = next.clone();
        }
        id
    }

    /// Where the sketch joins curves `a` and `b`: an end point of one that the sketch makes
    /// coincide with an end point of the other, or puts on the other. An unbounded line's "end
    /// points" are the points the sketch puts on it (a zero-length line's ends are such points).
    fn joint(&self, a: &Target, b: &Target) -> Option<Target> {
        let ends = |t: &Target| -> Vec<String> {
            match t.shape {
                Some(Shape::Segment | Shape::Arc | Shape::Spline { clamped: true, .. }) => {
                    vec![format!("{}.start", t.id), format!("{}.end", t.id)]
                }
                Some(Shape::Line) => {
                    let mut on: Vec<String> = self
                        .on_curve
                        .iter()
                        .filter(|(_, curve)| *curve == t.id)
                        .map(|(p, _)| p.clone())
                        .collect();
                    on.sort_unstable();
                    on
                }
                _ => Vec::new(),
            }
        };
        let point = |id: &String| Target { id: id.clone(), class: Class::Point, shape: None };
        for ea in ends(a) {
            for eb in ends(b) {
                if self.root(&ea) == self.root(&eb) {
                    return Some(point(&ea));
                }
            }
            if self.on_curve.contains(&(ea.clone(), b.id.clone())) {
                return Some(point(&ea));
            }
        }
        ends(b).iter().find(|eb| self.on_curve.contains(&((*eb).clone(), a.id.clone()))).map(point)
    }

    fn push(
        &mut self,
        kind: K,
        id: &str,
        args: &[&Target],
        value: Option<BigRational>,
    ) -> Result<(), String> {
        let ids: Vec<&str> = args.iter().map(|t| t.id.as_str()).collect();
        if self.as_reference {
            let value = value.filter(|_| !self.reference_without_value);
            return self.builder.reference(kind, id, &ids, value).map_err(|e| e.to_string());
        }
        self.builder.constraint(kind, id, &ids, value).map(|_| ()).map_err(|e| e.to_string())
    }

    /// Pushes the parts of a constraint that CAD writes as one and gcs as several: the first
    /// keeps the id, the others are `<id>#<suffix>`. A failure after the first part says what
    /// was imported.
    fn push_all(
        &mut self,
        id: &str,
        parts: &[(K, &str, Vec<&Target>, Option<BigRational>)],
    ) -> Result<(), String> {
        if self.as_reference {
            return Err("a reference dimension that is not one dimension of the model".into());
        }
        let mut done = Vec::new();
        for (kind, suffix, args, value) in parts {
            let part_id = if suffix.is_empty() { id.to_owned() } else { format!("{id}#{suffix}") };
            if let Err(e) = self.push(*kind, &part_id, args, value.clone()) {
                return Err(if done.is_empty() {
                    e
                } else {
                    format!("{e} (only {} imported)", done.join(", "))
                });
            }
            done.push(part_id);
        }
        Ok(())
    }

    /// A distance `v` from a point, a line or a circle to a circle or arc `C` (to its
    /// boundary; between circles drawn concentric, the model's `Distance` of two circles): the
    /// circle `<id>#offset` concentric with `C` through the point (tangent to the
    /// line or the other circle), at distance `v` from `C` — the difference of their radii, a
    /// dimension rational at a rational witness where the distance to the boundary itself is
    /// not. Its sketch radius is the drawing's (to 10^-9).
    fn distance_to_round(&mut self, id: &str, t: &[Target], v: BigRational) -> Result<(), String> {
        if self.as_reference {
            return Err("a reference distance to a circle's boundary".into());
        }
        let (round, other) =
            if t[1].class == Class::Round { (&t[1], &t[0]) } else { (&t[0], &t[1]) };
        let (center, r) = self.round_f64(&round.id).ok_or("the circle has no sketch position")?;
        // Two circles drawn concentric: the distance between them is the model's own.
        if other.class == Class::Round
            && self.round_f64(&other.id).is_some_and(|(c2, _)| c2 == center)
        {
            return self.push(K::Distance, id, &[other, round], Some(v));
        }
        let d = |p: &[f64]| ((p[0] - center[0]).powi(2) + (p[1] - center[1]).powi(2)).sqrt();
        let radius = match other.class {
            Class::Point => {
                d(&self.point_f64(&other.id).ok_or("the point has no sketch position")?)
            }
            Class::Straight => {
                let (p, q) = self.line_f64(other).ok_or("the line has no sketch position")?;
                let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
                ((center[0] - p[0]) * dy - (center[1] - p[1]) * dx).abs() / dx.hypot(dy)
            }
            _ => {
                let (c2, r2) =
                    self.round_f64(&other.id).ok_or("the circle has no sketch position")?;
                let (gap, vf) = (d(&c2), v.to_f64().unwrap_or(0.0));
                // Tangent outside or inside: the one whose radius is C's plus or minus `v`.
                [gap - r2, gap + r2, r2 - gap]
                    .into_iter()
                    .filter(|x| *x > 0.0)
                    .min_by(|a, b| {
                        let off = |x: f64| (x - r - vf).abs().min((x - (r - vf)).abs());
                        off(*a).total_cmp(&off(*b))
                    })
                    .ok_or("the circles have no tangent circle concentric with the first")?
            }
        };
        let exact = |x: f64| BigRational::from_float(x).map(|q| snap(&q));
        let (cx, cy, rr) = (exact(center[0]), exact(center[1]), exact(radius));
        let (Some(cx), Some(cy), Some(rr)) = (cx, cy, rr) else {
            return Err("the drawing's distance is not a number".into());
        };
        if rr <= BigRational::from_integer(0.into()) {
            return Err("the point, line or circle is at the circle's centre".into());
        }
        let offset = format!("{id}#offset");
        self.builder.circle(&offset, Some(vec![cx, cy]), Some(rr)).map_err(|e| e.to_string())?;
        let helper = Target { id: offset, class: Class::Round, shape: Some(Shape::Circle) };
        let touch = if other.class == Class::Point { K::Incident } else { K::Tangent };
        self.push_all(
            id,
            &[
                (K::Concentric, "concentric", vec![&helper, round], None),
                (touch, "on", vec![other, &helper], None),
                (K::Distance, "", vec![&helper, round], Some(v)),
            ],
        )
    }

    /// The first segment's length minus the second's is `v` (SolveSpace's LENGTH_DIFFERENCE),
    /// in the model's own terms: each segment is the radius of a helper circle about its
    /// start through its end (`<id>#length1`, `<id>#length2`: `#center1`, `#on1`…), and a
    /// third circle (`<id>#difference`) concentric with the longer one's and of the shorter
    /// one's radius (`#concentric`, `#equal`) is `|v|` inside it: the distance between
    /// concentric circles, the difference of their radii (the id). The helpers add no degree
    /// of freedom and each equation is independent where the segments have length, so the rank
    /// is that of the difference of the two lengths; everything stays polynomial and exact.
    fn length_difference(&mut self, id: &str, t: &[Target], v: BigRational) -> Result<(), String> {
        if self.as_reference {
            return Err("a reference difference of lengths".into());
        }
        if self.builder.system().dim() != Dim::Two {
            return Err(not_in_model("a difference of lengths in 3D (its helpers are circles)"));
        }
        // The longer segment first.
        let (long, short, v) = if v < BigRational::from_integer(0.into()) {
            (&t[1], &t[0], -v)
        } else {
            (&t[0], &t[1], v)
        };
        let length = |l: &Self, seg: &Target| -> Option<(Vec<BigRational>, BigRational)> {
            let (a, b) = l.ends(seg);
            let (p, q) = (l.point_f64(&a.id)?, l.point_f64(&b.id)?);
            let r = BigRational::from_float((q[0] - p[0]).hypot(q[1] - p[1]))?;
            Some((l.point_q(&a.id)?, snap(&r)))
        };
        let ((c1, r1), (c2, r2)) = length(self, long)
            .zip(length(self, short))
            .ok_or("a segment has no sketch position")?;
        if r1 <= BigRational::from_integer(0.into()) || r2 <= BigRational::from_integer(0.into()) {
            return Err("a segment of zero length in the drawing".into());
        }
        let circle = |l: &mut Self, name: &str, c: Vec<BigRational>, r: BigRational| {
            let cid = format!("{id}#{name}");
            l.builder.circle(&cid, Some(c), Some(r)).map_err(|e| e.to_string())?;
            Ok::<Target, String>(Target {
                id: cid,
                class: Class::Round,
                shape: Some(Shape::Circle),
            })
        };
        let k1 = circle(self, "length1", c1.clone(), r1)?;
        let k2 = circle(self, "length2", c2, r2.clone())?;
        let kd = circle(self, "difference", c1, r2)?;
        let (a1, b1) = self.ends(long);
        let (a2, b2) = self.ends(short);
        self.push_all(
            id,
            &[
                (K::Distance, "", vec![&k1, &kd], Some(v)),
                (K::Concentric, "center1", vec![&a1, &k1], None),
                (K::Incident, "on1", vec![&b1, &k1], None),
                (K::Concentric, "center2", vec![&a2, &k2], None),
                (K::Incident, "on2", vec![&b2, &k2], None),
                (K::Concentric, "concentric", vec![&kd, &k1], None),
                (K::EqualRadius, "equal", vec![&kd, &k2], None),
            ],
        )
    }

    /// Two segments mirrored about a line or a point, their carriers symmetric: the mirror
    /// images of the first's end points, `<id>#image-start` and `<id>#image-end` (points of
    /// their own, drawn at the exact images of the drawn end points), are on the second. The
    /// constraints: `Symmetric` of each end point and its image (`<id>`, `<id>#end`), and the
    /// images on the second segment's carrier (`<id>#on-start`, `<id>#on-end`).
    fn mirror_lines(&mut self, id: &str, t: &[Target]) -> Result<(), String> {
        if t[0].shape != Some(Shape::Segment) {
            return Err(not_in_model("the mirror image of an infinite line"));
        }
        if self.as_reference {
            return Err("a reference dimension that is not one dimension of the model".into());
        }
        let (start, end) = self.ends(&t[0]);
        let mut images = Vec::new();
        for (point, name) in [(&start, "start"), (&end, "end")] {
            let image = format!("{id}#image-{name}");
            let at = self.mirrored_q(&point.id, &t[2]);
            self.builder.point(&image, at).map_err(|e| e.to_string())?;
            images.push(Target { id: image, class: Class::Point, shape: Some(Shape::Point) });
        }
        self.push_all(
            id,
            &[
                (K::Symmetric, "", vec![&start, &images[0], &t[2]], None),
                (K::Symmetric, "end", vec![&end, &images[1], &t[2]], None),
                (K::Incident, "on-start", vec![&images[0], &t[1]], None),
                (K::Incident, "on-end", vec![&images[1], &t[1]], None),
            ],
        )
    }

    /// A point turned about another by `degrees` (an instance of a circular pattern), where
    /// the turn is rational: by 180°, the two symmetric about the pivot; by ±90°, the arms
    /// from the pivot to the point and to its image (segments `<id>#arm` and
    /// `<id>#arm-image`) perpendicular (`<id>`) and of equal length (`<id>#equal`) — which
    /// does not say which of the two senses, a discrete choice the drawing makes; by 0°, the
    /// two coincide. A point the sketch joins to the pivot: its image is the pivot (a note
    /// when the sketch joins that too). Other turns, whose cosine or sine is irrational, are a
    /// vertex of a regular polygon ([`Self::turned`]) up to 36 vertices.
    fn rotated(&mut self, id: &str, t: &[Target], degrees: &BigRational) -> Result<(), String> {
        let full = BigRational::from_integer(360.into());
        let turn = degrees - (degrees / &full).floor() * &full;
        let is = |d: i64| turn == BigRational::from_integer(d.into());
        let pivot = self.root(&t[2].id);
        if self.root(&t[0].id) == pivot {
            // A point the sketch puts at the pivot (an arc's centre) stays there.
            if self.root(&t[1].id) == pivot {
                self.notes.push(Skipped {
                    item: id.to_owned(),
                    reason:
                        "a turn of the pivot itself, which the sketch's coincidences keep in place"
                            .into(),
                });
                return Ok(());
            }
            return self.push(K::Coincident, id, &[&t[1], &t[2]], None);
        }
        if is(0) {
            self.push(K::Coincident, id, &[&t[0], &t[1]], None)
        } else if is(180) {
            self.push(K::Symmetric, id, &[&t[0], &t[1], &t[2]], None)
        } else if is(90) || is(270) {
            let mut arms = Vec::new();
            for (point, name) in [(&t[0], "arm"), (&t[1], "arm-image")] {
                let arm = format!("{id}#{name}");
                self.builder.segment(&arm, &t[2].id, &point.id).map_err(|e| e.to_string())?;
                arms.push(Target { id: arm, class: Class::Straight, shape: Some(Shape::Segment) });
            }
            self.push_all(
                id,
                &[
                    (K::Perpendicular, "", vec![&arms[0], &arms[1]], None),
                    (K::EqualLength, "equal", vec![&arms[0], &arms[1]], None),
                ],
            )
        } else if let Some((k, n)) = turn_fraction(&turn) {
            self.turned(id, t, k, n)
        } else {
            Err(not_in_model(&format!(
                "a rotation by {}° (not a multiple of 360°/N for an N up to 36)",
                degrees.to_f64().unwrap_or(f64::NAN)
            )))
        }
    }

    /// A point turned about a pivot by `k/n` of a full turn (counter-clockwise), where the
    /// turn's cosine or sine is irrational (the model has no such constant): the image is vertex
    /// `k` of the regular `n`-gon about the pivot with the point as vertex 0, and the polygon is
    /// made of helper points `<id>#vertex<j>` (once per point, pivot and `n`, named after the
    /// first turn that needs it), each as far from the pivot as the point
    /// (`EqualDistance`, `#spoke<j>`) and each side as long as the first (`#side<j>`, the last
    /// closing on the point); a polygon made already for the point and pivot with a multiple of
    /// `n` vertices is used instead. Equal sides and spokes hold the polygon's turn in place (its
    /// other solutions are the star polygons, the images of the regular one under the
    /// field automorphisms of the turn, where the rank is the same, and folded ones). The
    /// helpers are drawn exactly turned, to the drawing's rounding.
    fn turned(&mut self, id: &str, t: &[Target], k: u64, n: u64) -> Result<(), String> {
        if self.as_reference {
            return Err("a reference dimension that is not one dimension of the model".into());
        }
        let (point, pivot) = (self.root(&t[0].id), self.root(&t[2].id));
        // A polygon made already with a multiple of n vertices has this turn's vertex too (the
        // hexagon of a pattern of 6 holds its turns by 120°).
        let made = self.polygons.iter().find_map(|((x, c, m), v)| {
            (*x == point && *c == pivot && m % n == 0).then(|| (v.clone(), m / n))
        });
        let (vertices, k) = match made {
            Some((v, every)) => (v, k * every),
            None => {
                let key = (point, pivot, n);
                let (x, c) = (self.point_f64(&t[0].id), self.point_f64(&t[2].id));
                let mut made = Vec::new();
                for j in 1..n {
                    let vertex = format!("{id}#vertex{j}");
                    let at = x.as_ref().zip(c.as_ref()).and_then(|(x, c)| {
                        let a = std::f64::consts::TAU * j as f64 / n as f64;
                        let (u, v) = (x[0] - c[0], x[1] - c[1]);
                        let turned =
                            [c[0] + a.cos() * u - a.sin() * v, c[1] + a.sin() * u + a.cos() * v];
                        turned.iter().map(|z| BigRational::from_float(*z)).collect()
                    });
                    self.builder.point(&vertex, at).map_err(|e| e.to_string())?;
                    made.push(vertex);
                }
                let point =
                    |id: &String| Target { id: id.clone(), class: Class::Point, shape: None };
                let ring: Vec<Target> =
                    std::iter::once(t[0].clone()).chain(made.iter().map(point)).collect();
                let mut parts = Vec::new();
                let (spokes, sides): (Vec<String>, Vec<String>) =
                    (1..n).map(|j| (format!("vertex{j}#spoke"), format!("vertex{j}#side"))).unzip();
                for j in 1..n as usize {
                    parts.push((
                        K::EqualDistance,
                        spokes[j - 1].as_str(),
                        vec![&t[2], &t[0], &t[2], &ring[j]],
                    ));
                    let next = &ring[(j + 1) % n as usize];
                    parts.push((
                        K::EqualDistance,
                        sides[j - 1].as_str(),
                        vec![&ring[0], &ring[1], &ring[j], next],
                    ));
                }
                for (kind, suffix, args) in parts {
                    self.push(kind, &format!("{id}#{suffix}"), &args, None)?;
                }
                self.polygons.insert(key, made.clone());
                (made, k)
            }
        };
        let image =
            Target { id: vertices[k as usize - 1].clone(), class: Class::Point, shape: None };
        self.push(K::Coincident, id, &[&t[1], &image], None)
    }

    /// A point moved as a direction segment goes from its start to its end (an instance of a
    /// linear pattern): the point, its image and the segment's ends make a parallelogram,
    /// whose diagonals share their midpoint `<id>#middle` (a point of its own, drawn at the
    /// exact midpoint of the first diagonal): the point and the segment's end symmetric about
    /// it (`<id>`), the image and the segment's start too (`<id>#image`). Linear, so regular
    /// even where the step is zero.
    fn translated(&mut self, id: &str, t: &[Target]) -> Result<(), String> {
        if self.as_reference {
            return Err("a reference dimension that is not one dimension of the model".into());
        }
        let middle = format!("{id}#middle");
        let two = BigRational::from_integer(2.into());
        let at = self
            .point_q(&t[0].id)
            .zip(self.point_q(&t[3].id))
            .map(|(a, d)| a.iter().zip(&d).map(|(x, y)| (x + y) / &two).collect::<Vec<_>>());
        self.builder.point(&middle, at).map_err(|e| e.to_string())?;
        let m = Target { id: middle, class: Class::Point, shape: Some(Shape::Point) };
        self.push_all(
            id,
            &[
                (K::Symmetric, "", vec![&t[0], &t[3], &m], None),
                (K::Symmetric, "image", vec![&t[1], &t[2], &m], None),
            ],
        )
    }

    /// A pattern's move of a point (`Rotated` by `turn` degrees, or `Translated`), once: the
    /// same move of the same points up to the sketch's coincidences (a corner two patterned
    /// segments share) is a note naming the constraint that made it. Recorded only once
    /// lowered, so that a note never names a skipped constraint.
    fn move_once(
        &mut self,
        id: &str,
        t: &[Target],
        turn: Option<&BigRational>,
        lower: impl FnOnce(&mut Self) -> Result<(), String>,
    ) -> Result<(), String> {
        let full = BigRational::from_integer(360.into());
        let mut key: Vec<String> = vec![if turn.is_some() { "turn" } else { "move" }.to_owned()];
        key.extend(t.iter().map(|x| self.root(&x.id)));
        key.extend(turn.map(|d| (d - (d / &full).floor() * &full).to_string()));
        if let Some(first) = self.moves.get(&key) {
            self.notes.push(Skipped {
                item: id.to_owned(),
                reason: format!("a move of a pattern's point that `{first}` says already"),
            });
            return Ok(());
        }
        lower(self)?;
        self.moves.insert(key, id.to_owned());
        Ok(())
    }

    /// A point's exact sketch position (a named centre: its curve's).
    fn point_q(&self, id: &str) -> Option<Vec<BigRational>> {
        let s = self.builder.system();
        let e =
            s.entity(s.entity_by_id(id).or_else(|| s.entity_by_id(id.strip_suffix(".center")?))?);
        match &e.geometry {
            gcs_model::Geometry::Point { at } => at.clone(),
            gcs_model::Geometry::Circle { center, .. }
            | gcs_model::Geometry::Arc { center, .. } => center.clone(),
            _ => None,
        }
    }

    /// The exact mirror image of point `id`'s sketch position about a line or a point.
    fn mirrored_q(&self, id: &str, axis: &Target) -> Option<Vec<BigRational>> {
        let p = self.point_q(id)?;
        let two = BigRational::from_integer(2.into());
        if axis.class == Class::Point {
            let c = self.point_q(&axis.id)?;
            return Some(c.iter().zip(&p).map(|(c, p)| c * &two - p).collect());
        }
        let s = self.builder.system();
        let (a, b) = match &s.entity(s.entity_by_id(&axis.id)?).geometry {
            gcs_model::Geometry::Segment { from, to } => {
                (self.point_q(&s.entity(*from).id)?, self.point_q(&s.entity(*to).id)?)
            }
            gcs_model::Geometry::Line { at: Some([a, b]) } => (a.clone(), b.clone()),
            _ => return None,
        };
        let d: Vec<BigRational> = b.iter().zip(&a).map(|(b, a)| b - a).collect();
        let dd: BigRational = d.iter().map(|x| x * x).sum();
        if dd == BigRational::from_integer(0.into()) {
            return None;
        }
        let k: BigRational =
            p.iter().zip(&a).zip(&d).map(|((p, a), d)| (p - a) * d).sum::<BigRational>() / dd;
        // The foot of the perpendicular, then as far beyond it.
        Some(p.iter().zip(&a).zip(&d).map(|((p, a), d)| (a + d * &k) * &two - p).collect())
    }

    /// A point's sketch position in floats (a named centre: its curve's).
    fn point_f64(&self, id: &str) -> Option<Vec<f64>> {
        let s = self.builder.system();
        if let Some(e) = s.entity_by_id(id)
            && let gcs_model::Geometry::Point { at: Some(at) } = &s.entity(e).geometry
        {
            return at.iter().map(|x| x.to_f64()).collect();
        }
        self.round_f64(id.strip_suffix(".center")?).map(|(c, _)| c)
    }

    /// A circle's or arc's sketch centre and radius in floats.
    fn round_f64(&self, id: &str) -> Option<(Vec<f64>, f64)> {
        let s = self.builder.system();
        let (center, radius) = match &s.entity(s.entity_by_id(id)?).geometry {
            gcs_model::Geometry::Circle { center, radius }
            | gcs_model::Geometry::Arc { center, radius, .. } => {
                (center.as_ref()?, radius.as_ref()?)
            }
            _ => return None,
        };
        Some((center.iter().map(|x| x.to_f64()).collect::<Option<Vec<f64>>>()?, radius.to_f64()?))
    }

    /// Two sketch points of a line or segment in floats.
    fn line_f64(&self, line: &Target) -> Option<(Vec<f64>, Vec<f64>)> {
        let s = self.builder.system();
        match &s.entity(s.entity_by_id(&line.id)?).geometry {
            gcs_model::Geometry::Segment { from, to } => {
                Some((self.point_f64(&s.entity(*from).id)?, self.point_f64(&s.entity(*to).id)?))
            }
            gcs_model::Geometry::Line { at: Some([p, q]) } => Some((
                p.iter().map(|x| x.to_f64()).collect::<Option<Vec<f64>>>()?,
                q.iter().map(|x| x.to_f64()).collect::<Option<Vec<f64>>>()?,
            )),
            _ => None,
        }
    }

    fn x_axis(&mut self) -> Result<Target, String> {
        if self.builder.system().entity_by_id(X_AXIS).is_none() {
            let (zero, one) =
                (BigRational::from_integer(0.into()), BigRational::from_integer(1.into()));
            let at = [vec![zero.clone(), zero.clone()], vec![one, zero]];
            self.builder.line(X_AXIS, Some(at)).map_err(|e| e.to_string())?;
            let fixed = format!("{X_AXIS}#fixed");
            self.builder.constraint(K::Fix, &fixed, &[X_AXIS], None).map_err(|e| e.to_string())?;
        }
        Ok(Target { id: X_AXIS.to_owned(), class: Class::Straight, shape: Some(Shape::Line) })
    }

    fn constraint(&mut self, c: &Constraint) -> Result<(), String> {
        let targets = c.refs.iter().map(|r| self.target(r)).collect::<Result<Vec<_>, _>>()?;
        // (A reference dimension may have none: it is measured, and the model keeps no value.)
        let as_reference = self.as_reference;
        let value = || -> Result<BigRational, String> {
            match c.value.as_ref() {
                Some(v) => Ok(snap(&v.0)),
                None if as_reference => Ok(BigRational::from_integer(0.into())),
                None => Err("no value".to_owned()),
            }
        };
        let zero = || BigRational::from_integer(0.into());
        let classes: Vec<Class> = targets.iter().map(|t| t.class).collect();
        let t = &targets;
        use Class::{Point as P, Round as R, Straight as S};
        let unsupported = |what: &str| Err(not_in_model(what));
        match (c.kind, classes.as_slice()) {
            (Kind::Coincident, [P, P]) => self.push(K::Coincident, &c.id, &[&t[0], &t[1]], None),
            (Kind::PointOnObject, [P, S | R | Class::Plane]) => {
                self.push(K::Incident, &c.id, &[&t[0], &t[1]], None)
            }
            (Kind::Horizontal, [S]) => self.push(K::Horizontal, &c.id, &[&t[0]], None),
            (Kind::Vertical, [S]) => self.push(K::Vertical, &c.id, &[&t[0]], None),
            (Kind::Horizontal, [P, P]) => {
                self.push(K::DistanceY, &c.id, &[&t[0], &t[1]], Some(zero()))
            }
            (Kind::Vertical, [P, P]) => {
                self.push(K::DistanceX, &c.id, &[&t[0], &t[1]], Some(zero()))
            }
            (Kind::Parallel, [S | Class::Plane, S | Class::Plane]) => {
                self.push(K::Parallel, &c.id, &[&t[0], &t[1]], None)
            }
            (Kind::Perpendicular, [S | Class::Plane, S | Class::Plane]) => {
                self.push(K::Perpendicular, &c.id, &[&t[0], &t[1]], None)
            }
            (Kind::Tangent, [S, R] | [R, S] | [R, R]) => match self.joint(&t[0], &t[1]) {
                // Joined by the sketch: tangent there (transversal), not "somewhere".
                Some(at) => self.push(K::TangentAt, &c.id, &[&t[0], &t[1], &at], None),
                None => self.push(K::Tangent, &c.id, &[&t[0], &t[1]], None),
            },
            (Kind::Tangent, [_, _]) if classes.contains(&Class::Curve) => {
                self.tangent_to_spline(&c.id, t)
            }
            (Kind::Tangent, _) => unsupported("a tangency other than line–circle or circle–circle"),
            (Kind::SplinePoint, [P, Class::Curve]) => {
                // (The knot exactly as the reader wrote it: not snapped.)
                let knot = c.value.as_ref().map(|v| v.0.clone());
                self.push(K::SplinePoint, &c.id, &[&t[0], &t[1]], knot)
            }
            (Kind::TangentAtEnds | Kind::PerpendicularAtEnds, [P, P]) => self.at_ends(c, t),
            (Kind::Equal, [S, S]) => self.push(K::EqualLength, &c.id, &[&t[0], &t[1]], None),
            (Kind::Equal, [R, R]) => self.push(K::EqualRadius, &c.id, &[&t[0], &t[1]], None),
            (Kind::Equal, _) => unsupported("equal length of a segment and an arc"),
            (Kind::Symmetric, [P, P, P | S]) => {
                self.push(K::Symmetric, &c.id, &[&t[0], &t[1], &t[2]], None)
            }
            (Kind::Symmetric, [S, S, P | S]) => self.mirror_lines(&c.id, t),
            (Kind::Rotated, [P, P, P]) => {
                let degrees = value()?;
                self.move_once(&c.id, t, Some(&degrees), |l| l.rotated(&c.id, t, &degrees))
            }
            (Kind::Rotated, _) => unsupported("a rotated copy of something other than a point"),
            (Kind::Translated, [P, P, P, P]) => {
                self.move_once(&c.id, t, None, |l| l.translated(&c.id, t))
            }
            (Kind::Translated, _) => unsupported("a moved copy of something other than a point"),
            (Kind::Distance, [P, P] | [P, S] | [S, P] | [S, S] | [P, Class::Plane]) => {
                let v = value()?;
                self.push(K::Distance, &c.id, &[&t[0], &t[1]], Some(abs(v)))
            }
            (Kind::Distance, [P | S | R, R] | [R, P | S]) => {
                let v = abs(value()?);
                self.distance_to_round(&c.id, t, v)
            }
            (Kind::Distance, _) => unsupported("a distance to a circle or an arc in 3D"),
            (Kind::Length, [S]) if t[0].shape == Some(Shape::Segment) => {
                let (a, b) = self.ends(&t[0]);
                self.push(K::Distance, &c.id, &[&a, &b], Some(abs(value()?)))
            }
            (Kind::Length, _) => unsupported("the length of an arc or an infinite line"),
            (Kind::DistanceX | Kind::DistanceY, [P, P] | [S]) => {
                let kind = if c.kind == Kind::DistanceX { K::DistanceX } else { K::DistanceY };
                let (a, b) = if t.len() == 2 {
                    (t[0].clone(), t[1].clone())
                } else if t[0].shape == Some(Shape::Segment) {
                    self.ends(&t[0])
                } else {
                    return unsupported("a horizontal or vertical distance along an infinite line");
                };
                self.push(kind, &c.id, &[&a, &b], Some(value()?))
            }
            (Kind::Angle, [S, S]) => self.push(K::Angle, &c.id, &[&t[0], &t[1]], Some(value()?)),
            (Kind::AngleToXAxis, [S]) => {
                let axis = self.x_axis()?;
                self.push(K::Angle, &c.id, &[&t[0], &axis], Some(value()?))
            }
            (Kind::Radius, [R]) => self.push(K::Radius, &c.id, &[&t[0]], Some(value()?)),
            (Kind::Diameter, [R]) => {
                let half = value()? / BigRational::from_integer(2.into());
                self.push(K::Radius, &c.id, &[&t[0]], Some(half))
            }
            (Kind::Fix, [_]) => self.push(K::Fix, &c.id, &[&t[0]], None),
            (Kind::Midpoint, [P, S]) if t[1].shape == Some(Shape::Segment) => {
                self.push(K::Midpoint, &c.id, &[&t[0], &t[1]], None)
            }
            (Kind::Midpoint, _) => unsupported("the midpoint of an arc or an infinite line"),
            (Kind::Concentric, [R | P, R] | [R, P]) => {
                self.push(K::Concentric, &c.id, &[&t[0], &t[1]], None)
            }
            (Kind::Collinear, [S, S]) => {
                // Parallel, and a point of one on the other.
                let (on, other) = if t[1].shape == Some(Shape::Segment) {
                    (self.ends(&t[1]).0, &t[0])
                } else if t[0].shape == Some(Shape::Segment) {
                    (self.ends(&t[0]).0, &t[1])
                } else {
                    return unsupported("two collinear infinite lines");
                };
                self.push_all(
                    &c.id,
                    &[
                        (K::Parallel, "", vec![&t[0], &t[1]], None),
                        (K::Incident, "on", vec![&on, other], None),
                    ],
                )
            }
            (Kind::EqualAngle, [S, S, S, S]) => {
                self.push(K::EqualAngle, &c.id, &[&t[0], &t[1], &t[2], &t[3]], None)
            }
            (Kind::EqualAngle, _) => unsupported("equal angles between curves other than lines"),
            (Kind::LengthRatio, [S, S]) if t.iter().all(|x| x.shape == Some(Shape::Segment)) => {
                self.push(K::LengthRatio, &c.id, &[&t[0], &t[1]], Some(abs(value()?)))
            }
            (Kind::LengthRatio, _) => unsupported("a ratio of lengths of arcs or infinite lines"),
            (Kind::LengthDifference, [S, S])
                if t.iter().all(|x| x.shape == Some(Shape::Segment)) =>
            {
                let v = value()?;
                self.length_difference(&c.id, t, v)
            }
            (Kind::LengthDifference, _) => {
                unsupported("a difference of lengths of arcs or infinite lines")
            }
            (Kind::EqualLineArcLength, _) => unsupported("a segment as long as an arc"),
            (Kind::EqualPointLineDistances, [P, S, P, S]) => {
                self.push(K::EqualDistance, &c.id, &[&t[0], &t[1], &t[2], &t[3]], None)
            }
            (Kind::EqualPointLineDistances, _) => unsupported("equal point–line distances"),
            (Kind::EqualGaps, [a, b, c2, d])
                if [(a, b), (c2, d)]
                    .iter()
                    .all(|pair| matches!(pair, (R, R) | (P, S) | (S, P) | (P, P))) =>
            {
                self.push(K::EqualDistance, &c.id, &[&t[0], &t[1], &t[2], &t[3]], None)
            }
            (Kind::EqualGaps, _) => {
                unsupported("equal gaps other than of circles, points and lines")
            }
            // (The model's EqualDistance states a length equal to a point–line distance too;
            // lowered, it leaves loops beside other equal lengths that the placement does not
            // close yet — SolveSpace's `mapping2d` test file is then refused a witness —, so it
            // stays skipped.)
            (Kind::EqualLengthPointLineDistance, _) => {
                unsupported("a length equal to a point–line distance")
            }
            (Kind::ArcLength, _) => unsupported("an arc length"),
            (kind, _) => Err(format!(
                "{kind:?} on {} is not a combination the gcs model has",
                classes.iter().map(|c| class_name(*c)).collect::<Vec<_>>().join(", ")
            )),
        }
    }

    /// A tangency of a clamped B-spline and a curve the sketch joins at one of the spline's
    /// ends: the leg of its control polygon there is tangent to the other curve at that point
    /// (parallel to a line or to another spline's leg, `TangentAt` a circle or arc). A
    /// tangency elsewhere along the spline is not in the model (no point on a spline).
    fn tangent_to_spline(&mut self, id: &str, t: &[Target]) -> Result<(), String> {
        let elsewhere = || not_in_model("a tangency to a B-spline away from its end points");
        let at = self.joint(&t[0], &t[1]).ok_or_else(elsewhere)?;
        let mut sides = Vec::new();
        for x in t {
            let Some(shape @ Shape::Spline { .. }) = x.shape else {
                sides.push(x.clone());
                continue;
            };
            let joint = self.root(&at.id);
            let part = if self.root(&format!("{}.start", x.id)) == joint {
                Part::Start
            } else if self.root(&format!("{}.end", x.id)) == joint {
                Part::End
            } else {
                return Err(elsewhere());
            };
            sides.push(self.end_leg(x.clone(), shape, part)?);
        }
        match (sides[0].class, sides[1].class) {
            (Class::Straight, Class::Straight) => {
                self.push(K::Parallel, id, &[&sides[0], &sides[1]], None)
            }
            (Class::Straight, Class::Round) | (Class::Round, Class::Straight) => {
                self.push(K::TangentAt, id, &[&sides[0], &sides[1], &at], None)
            }
            _ => Err(not_in_model(
                "a tangency of a B-spline to a curve other than a line, \
                                   circle, arc or spline",
            )),
        }
    }

    /// For an end of a B-spline, the segment of its control polygon at that end (made once, as
    /// `<id>#start-leg` or `<id>#end-leg`): the line the curve is tangent to there. Other
    /// curves are returned as they are.
    fn end_leg(&mut self, curve: Target, shape: Shape, part: Part) -> Result<Target, String> {
        let Shape::Spline { poles, clamped } = shape else { return Ok(curve) };
        let start = part == Part::Start;
        let leg = format!("{}#{}-leg", curve.id, if start { "start" } else { "end" });
        if self.builder.system().entity_by_id(&leg).is_none() {
            let (i, j) = if start { (0, 1) } else { (poles - 1, poles - 2) };
            let (p, q) =
                (pole_id(&curve.id, i, poles, clamped), pole_id(&curve.id, j, poles, clamped));
            self.builder.segment(&leg, &p, &q).map_err(|e| e.to_string())?;
        }
        Ok(Target { id: leg, class: Class::Straight, shape: Some(Shape::Segment) })
    }

    /// A segment's end points as targets.
    fn ends(&self, segment: &Target) -> (Target, Target) {
        let point = |part: &str| Target {
            id: format!("{}.{part}", segment.id),
            class: Class::Point,
            shape: None,
        };
        (point("start"), point("end"))
    }

    /// Tangency or perpendicularity at shared end points: the curves of the two end points
    /// meet there (`<id>#coincident`) and are tangent (`TangentAt`, or `Parallel` for two
    /// straight curves) or perpendicular there (`Perpendicular` for two straight curves).
    fn at_ends(&mut self, c: &Constraint, t: &[Target]) -> Result<(), String> {
        let curve = |r: &Ref| -> Result<Target, String> {
            if !matches!(r.part, Part::Start | Part::End) {
                return Err("refers to a point that is not a curve's end".to_owned());
            }
            Ok(Target { id: r.entity.clone(), class: Class::Point, shape: None })
        };
        let (a, b) = (curve(&c.refs[0])?, curve(&c.refs[1])?);
        let shape = |id: &str| {
            self.shapes.get(id).copied().ok_or_else(|| format!("refers to {id}, which is unknown"))
        };
        let (sa, sb) = (shape(&a.id)?, shape(&b.id)?);
        // A clamped B-spline is tangent at its end to the leg of its control polygon there.
        let a = self.end_leg(a, sa, c.refs[0].part)?;
        let b = self.end_leg(b, sb, c.refs[1].part)?;
        let round = |s: Shape| matches!(s, Shape::Circle | Shape::Arc);
        let meet = (K::Coincident, "coincident", vec![&t[0], &t[1]], None);
        match (c.kind, round(sa), round(sb)) {
            (Kind::TangentAtEnds, false, false) => {
                self.push_all(&c.id, &[(K::Parallel, "", vec![&a, &b], None), meet])
            }
            (Kind::TangentAtEnds, _, _) => {
                self.push_all(&c.id, &[(K::TangentAt, "", vec![&a, &b, &t[0]], None), meet])
            }
            (_, false, false) => {
                self.push_all(&c.id, &[(K::Perpendicular, "", vec![&a, &b], None), meet])
            }
            _ => Err(not_in_model("a perpendicularity at the end of an arc")),
        }
    }
}

fn abs(v: BigRational) -> BigRational {
    if v < BigRational::from_integer(0.into()) { -v } else { v }
}

/// A turn of `degrees` in `[0, 360)` as `k/n` of a full turn in lowest terms, for `n` up to
/// 36 (the turns the turn prime carries, `gcs_rank::TURN_PERIOD`) and `k > 0`.
fn turn_fraction(degrees: &BigRational) -> Option<(u64, u64)> {
    let f = degrees / BigRational::from_integer(360.into());
    let (k, n) = (f.numer().to_u64()?, f.denom().to_u64()?);
    (k > 0 && n <= 36).then_some((k, n))
}

fn not_in_model(what: &str) -> String {
    format!("{what}: not in the gcs model yet")
}

fn part_name(part: Part) -> String {
    match part {
        Part::Whole => "whole".to_owned(),
        Part::Start => "start point".to_owned(),
        Part::End => "end point".to_owned(),
        Part::Center => "centre".to_owned(),
        Part::Focus1 => "first focus".to_owned(),
        Part::Focus2 => "second focus".to_owned(),
        Part::MajorStart | Part::MajorEnd => "major axis end".to_owned(),
        Part::MinorStart | Part::MinorEnd => "minor axis end".to_owned(),
        Part::Pole(i) => format!("control point {i}"),
        Part::Origin => "origin".to_owned(),
        Part::StartTangent => "start tangent".to_owned(),
        Part::EndTangent => "end tangent".to_owned(),
    }
}

fn shape_name(shape: Shape) -> &'static str {
    match shape {
        Shape::Point => "a point",
        Shape::Segment => "a segment",
        Shape::Line => "a line",
        Shape::Circle => "a circle",
        Shape::Arc => "an arc",
        Shape::Plane => "a plane",
        Shape::Spline { .. } => "a B-spline",
    }
}

fn class_name(class: Class) -> &'static str {
    match class {
        Class::Point => "a point",
        Class::Straight => "a line",
        Class::Round => "a circle",
        Class::Plane => "a plane",
        Class::Curve => "a B-spline",
    }
}

/// The model id of control point `i` of B-spline `id` (of `n`): a clamped spline's first and last
/// are the curve's end points, `<id>.start` and `<id>.end`; the others `<id>.pole<i>`.
fn pole_id(id: &str, i: usize, n: usize, clamped: bool) -> String {
    match i {
        0 if clamped => format!("{id}.start"),
        i if clamped && i + 1 == n => format!("{id}.end"),
        i => format!("{id}.pole{i}"),
    }
}
