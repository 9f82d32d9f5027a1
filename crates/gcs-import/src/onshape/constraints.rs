//! Sketch constraints (`BTMSketchConstraint`): their parameters (references, quantities,
//! options) and their translation into the neutral vocabulary.

use num_rational::BigRational;
use num_traits::ToPrimitive;

use super::entities::{Shape, Table, Target};
use super::expr::{self, Measure};
use super::json::{self, Object};
use crate::ir::{self, Constraint, Geometry, Kind, Number, Part, Ref, Skipped};

/// What became of a constraint element: neutral constraints (usually one), or a skipped item.
pub(super) enum Outcome {
    /// The constraints it translates to.
    Constraints(Vec<Constraint>),
    /// Why it cannot be expressed.
    Skip(Skipped),
    /// What of it can be expressed, and why the rest cannot (the skipped item carries the
    /// constraint's own id, which none of the constraints takes).
    Part(Vec<Constraint>, Skipped),
}

/// A reference parameter.
struct RefParam<'a> {
    /// Its `parameterId` (`localFirst`, `externalSecond`, `localMirror`, `local0`, …).
    role: &'a str,
    /// The referenced id, `None` for an external reference (a query into the part studio).
    local: Option<&'a str>,
}

/// The parameters of a constraint, by kind.
#[derive(Default)]
struct Params<'a> {
    refs: Vec<RefParam<'a>>,
    quantities: Vec<(&'a str, &'a str)>,
    enums: Vec<(&'a str, &'a str)>,
    flags: Vec<(&'a str, bool)>,
}

impl<'a> Params<'a> {
    fn read(msg: &'a Object) -> Result<Params<'a>, String> {
        let mut params = Params::default();
        for (k, p) in json::array(msg, "parameters")?.iter().enumerate() {
            let at = |e: String| format!("parameters[{k}]: {e}");
            let p = json::object(p, "parameter").map_err(at)?;
            let type_name = json::string(p, "typeName").map_err(at)?;
            let m = json::field_object(p, "message").map_err(at)?;
            let role = json::string(m, "parameterId").map_err(at)?;
            match type_name {
                "BTMParameterString" if role.starts_with("local") => {
                    params.refs.push(RefParam {
                        role,
                        local: Some(json::string(m, "value").map_err(at)?),
                    });
                }
                "BTMParameterString" | "BTMParameterQueryList" if role.starts_with("external") => {
                    params.refs.push(RefParam { role, local: None });
                }
                "BTMParameterQuantity" => {
                    if let Some(e) = json::opt_string(m, "expression").map_err(at)? {
                        params.quantities.push((role, e));
                    }
                }
                "BTMParameterEnum" => {
                    if let Some(v) = json::opt_string(m, "value").map_err(at)? {
                        params.enums.push((role, v));
                    }
                }
                "BTMParameterBoolean" => {
                    params.flags.push((role, json::flag(m, "value").map_err(at)?))
                }
                _ => {}
            }
        }
        // Order the references: first, second, … whatever order the file lists them in.
        params.refs.sort_by_key(|r| rank(r.role));
        Ok(params)
    }

    fn quantity(&self, role: &str) -> Option<&'a str> {
        self.quantities.iter().find(|(r, _)| *r == role).map(|&(_, e)| e)
    }

    fn option(&self, role: &str) -> Option<&'a str> {
        self.enums.iter().find(|(r, _)| *r == role).map(|&(_, v)| v)
    }

    fn flag(&self, role: &str) -> bool {
        self.flags.iter().any(|&(r, v)| r == role && v)
    }
}

/// The position of a reference parameter among the constraint's references.
fn rank(role: &str) -> u32 {
    if role.contains("Midpoint") {
        return 0;
    }
    if role.contains("First") || role.ends_with("Entity1") {
        return 1;
    }
    if role.contains("Second") || role.ends_with("Entity2") {
        return 2;
    }
    if role.contains("Mirror") {
        return 90;
    }
    let digits = role.trim_start_matches(|c: char| !c.is_ascii_digit());
    digits.parse::<u32>().map_or(50, |d| 1 + d.min(40))
}

/// A resolved reference.
#[derive(Clone)]
struct Arg {
    r: Ref,
    shape: Shape,
}

impl Arg {
    fn is_point(&self) -> bool {
        self.shape == Shape::Point
    }
    fn is_line(&self) -> bool {
        matches!(self.shape, Shape::Segment | Shape::Line | Shape::ZeroLine)
    }
    fn is_segment(&self) -> bool {
        self.shape == Shape::Segment
    }
    fn is_round(&self) -> bool {
        matches!(self.shape, Shape::Circle | Shape::Arc { .. })
    }
    fn has_center(&self) -> bool {
        matches!(
            self.shape,
            Shape::Circle | Shape::Arc { .. } | Shape::Ellipse | Shape::EllipticalArc { .. }
        )
    }
    fn is_curve(&self) -> bool {
        matches!(
            self.shape,
            Shape::Segment
                | Shape::Line
                | Shape::ZeroLine
                | Shape::Circle
                | Shape::Arc { .. }
                | Shape::Ellipse
                | Shape::EllipticalArc { .. }
                | Shape::Spline
        )
    }
    fn center(&self) -> Ref {
        Ref::part(self.r.entity.clone(), Part::Center)
    }
}

fn describe(shape: Shape) -> &'static str {
    match shape {
        Shape::Point => "point",
        Shape::ZeroLine => "zero-length line",
        Shape::Segment => "line",
        Shape::Line => "unbounded line",
        Shape::Circle => "circle",
        Shape::Arc { .. } => "arc",
        Shape::Ellipse => "ellipse",
        Shape::EllipticalArc { .. } => "elliptical arc",
        Shape::Spline => "spline",
    }
}

/// The constraint types this reader knows; others are skipped as unsupported.
const KNOWN: &[&str] = &[
    "COINCIDENT",
    "HORIZONTAL",
    "VERTICAL",
    "PARALLEL",
    "PERPENDICULAR",
    "TANGENT",
    "NORMAL",
    "EQUAL",
    "CONCENTRIC",
    "MIDPOINT",
    "MIRROR",
    "SYMMETRIC",
    "DISTANCE",
    "LENGTH",
    "RADIUS",
    "DIAMETER",
    "ANGLE",
    "FIX",
    "CENTERLINE_DIMENSION",
    "PROJECTED",
];

/// The reason given when a constraint needs external geometry (normative wording).
const EXTERNAL: &str = "reference to external geometry without its geometry in the file";

/// Translates one constraint whose `message` is `msg` and whose id is `id`.
pub(super) fn read(
    msg: &Object,
    id: &str,
    table: &Table,
    entities: &[ir::Entity],
) -> Result<Outcome, String> {
    let ctype = json::string(msg, "constraintType")?;
    let params = Params::read(msg)?;
    let skip = |reason: String| {
        Ok(Outcome::Skip(Skipped { item: id.to_owned(), reason: format!("{ctype}: {reason}") }))
    };
    match ctype {
        "OFFSET" => {
            return match offset(&params, id, table) {
                Ok((out, None)) => Ok(Outcome::Constraints(out)),
                Ok((out, Some(why))) => Ok(Outcome::Part(
                    out,
                    Skipped { item: id.to_owned(), reason: format!("{ctype}: {why}") },
                )),
                Err(why) => skip(why),
            };
        }
        "CIRCULAR_PATTERN" | "LINEAR_PATTERN" => {
            return match pattern(ctype, &params, id, table, &Drawing { table, entities }) {
                Ok(out) => Ok(Outcome::Constraints(out)),
                Err(why) => skip(why),
            };
        }
        _ if !KNOWN.contains(&ctype) => {
            return skip("this constraint type is not supported".into());
        }
        _ => {}
    }
    // PROJECTED ties a sketch entity to model geometry projected onto the sketch plane: the
    // entity is where the file draws it, fixed.
    let projected = ctype == "PROJECTED";
    if projected {
        let how = params.option("projectionType").unwrap_or("USE");
        if !matches!(how, "USE" | "USE_START" | "USE_END") {
            return skip(format!(
                "projection of type {how} (onto a silhouette of model geometry) is not expressible"
            ));
        }
    } else if let Some(external) = params.refs.iter().find(|r| r.local.is_none()) {
        return skip(format!("{EXTERNAL} ({})", external.role));
    }
    let mut args = Vec::new();
    let mut axis = None;
    for p in &params.refs {
        let Some(local) = p.local else { continue };
        let arg = match resolved(table, local) {
            Ok(arg) => arg,
            Err(why) => return skip(why),
        };
        if p.role.contains("Mirror") {
            axis = Some(arg);
        } else {
            // `localMidpoint` ranks first.
            args.push(arg);
        }
    }
    let driving = !params.flag("driven");
    let value = |role: &str, measure: Measure| -> Result<Option<Number>, String> {
        match params.quantity(role) {
            Some(text) => match expr::evaluate(text, measure) {
                Ok(v) => Ok(Some(v)),
                Err(_) if !driving => Ok(None),
                Err(why) => Err(why),
            },
            None if !driving => Ok(None),
            None => Err(format!("the dimension's `{role}` is not in the file")),
        }
    };
    let one = |kind: Kind, refs: Vec<Ref>| Constraint {
        id: id.to_owned(),
        kind,
        refs,
        value: None,
        driving: true,
    };
    let with = |kind: Kind, refs: Vec<Ref>, value: Option<Number>| Constraint {
        id: id.to_owned(),
        kind,
        refs,
        value,
        driving,
    };
    let second = |suffix: &str, kind: Kind, refs: Vec<Ref>| Constraint {
        id: format!("{id}#{suffix}"),
        kind,
        refs,
        value: None,
        driving: true,
    };
    let shapes = || {
        let mut all: Vec<&str> = args.iter().chain(&axis).map(|a| describe(a.shape)).collect();
        if all.is_empty() {
            all.push("nothing");
        }
        all.join(", ")
    };
    let unexpressible = || skip(format!("between {} is not expressible", shapes()));
    let drawing = Drawing { table, entities };

    let out = match (ctype, args.as_slice()) {
        ("COINCIDENT", [a, b]) if a.is_point() && b.is_point() => {
            vec![one(Kind::Coincident, vec![a.r.clone(), b.r.clone()])]
        }
        ("COINCIDENT", [a, b]) if a.is_point() && b.is_curve() => {
            vec![one(Kind::PointOnObject, vec![a.r.clone(), b.r.clone()])]
        }
        ("COINCIDENT", [a, b]) if a.is_curve() && b.is_point() => {
            vec![one(Kind::PointOnObject, vec![b.r.clone(), a.r.clone()])]
        }
        ("COINCIDENT", [a, b]) if a.is_line() && b.is_line() => {
            vec![one(Kind::Collinear, vec![a.r.clone(), b.r.clone()])]
        }
        // Two circles made to coincide are one circle: same centre, same radius.
        ("COINCIDENT", [a, b]) if a.is_round() && b.is_round() => vec![
            one(Kind::Concentric, vec![a.r.clone(), b.r.clone()]),
            second("equal", Kind::Equal, vec![a.r.clone(), b.r.clone()]),
        ],
        ("HORIZONTAL" | "VERTICAL", [a]) if a.is_line() => {
            vec![one(level(ctype), vec![a.r.clone()])]
        }
        ("HORIZONTAL" | "VERTICAL", [a, b]) if a.is_point() && b.is_point() => {
            vec![one(level(ctype), vec![a.r.clone(), b.r.clone()])]
        }
        ("PARALLEL", [a, b]) if a.is_line() && b.is_line() => {
            vec![one(Kind::Parallel, vec![a.r.clone(), b.r.clone()])]
        }
        ("PERPENDICULAR", [a, b]) if a.is_line() && b.is_line() => {
            vec![one(Kind::Perpendicular, vec![a.r.clone(), b.r.clone()])]
        }
        ("TANGENT", [a, b]) if a.is_curve() && b.is_curve() && !(a.is_line() && b.is_line()) => {
            vec![one(Kind::Tangent, vec![a.r.clone(), b.r.clone()])]
        }
        // A line normal to a circle passes through its centre.
        ("NORMAL", [a, b]) if a.is_line() && b.is_round() => {
            vec![one(Kind::PointOnObject, vec![b.center(), a.r.clone()])]
        }
        ("NORMAL", [a, b]) if a.is_round() && b.is_line() => {
            vec![one(Kind::PointOnObject, vec![a.center(), b.r.clone()])]
        }
        ("NORMAL", [a, b]) if a.is_line() && b.is_line() => {
            vec![one(Kind::Perpendicular, vec![a.r.clone(), b.r.clone()])]
        }
        ("EQUAL", [a, b])
            if (a.is_segment() && b.is_segment()) || (a.is_round() && b.is_round()) =>
        {
            vec![one(Kind::Equal, vec![a.r.clone(), b.r.clone()])]
        }
        ("CONCENTRIC", [a, b]) if a.is_round() && b.is_round() => {
            vec![one(Kind::Concentric, vec![a.r.clone(), b.r.clone()])]
        }
        ("CONCENTRIC", [a, b]) if a.has_center() && b.has_center() => {
            vec![one(Kind::Coincident, vec![a.center(), b.center()])]
        }
        ("CONCENTRIC", [a, b]) if a.is_point() && b.has_center() => {
            vec![one(Kind::Coincident, vec![a.r.clone(), b.center()])]
        }
        ("CONCENTRIC", [a, b]) if a.has_center() && b.is_point() => {
            vec![one(Kind::Coincident, vec![b.r.clone(), a.center()])]
        }
        ("MIDPOINT", [a, b])
            if a.is_point() && matches!(b.shape, Shape::Segment | Shape::Arc { .. }) =>
        {
            vec![one(Kind::Midpoint, vec![a.r.clone(), b.r.clone()])]
        }
        ("MIDPOINT", [a, b])
            if b.is_point() && matches!(a.shape, Shape::Segment | Shape::Arc { .. }) =>
        {
            vec![one(Kind::Midpoint, vec![b.r.clone(), a.r.clone()])]
        }
        // The midpoint of two points (`localMidpoint`, or the older `local0`, comes first): the
        // two are symmetric about it.
        ("MIDPOINT", [m, a, b]) if m.is_point() && a.is_point() && b.is_point() => {
            vec![one(Kind::Symmetric, vec![a.r.clone(), b.r.clone(), m.r.clone()])]
        }
        ("MIRROR" | "SYMMETRIC", [a, b]) => {
            let Some(m) = axis.as_ref().filter(|m| m.is_line() || m.is_point()) else {
                return unexpressible();
            };
            if a.is_point() && b.is_point() {
                vec![one(Kind::Symmetric, vec![a.r.clone(), b.r.clone(), m.r.clone()])]
            } else if a.is_round() && b.is_round() {
                // Mirrored circles: mirrored centres, equal radii.
                vec![
                    one(Kind::Symmetric, vec![a.center(), b.center(), m.r.clone()]),
                    second("equal", Kind::Equal, vec![a.r.clone(), b.r.clone()]),
                ]
            } else if a.is_line() && b.is_line() {
                // Mirrored lines: their carriers symmetric.
                vec![one(Kind::Symmetric, vec![a.r.clone(), b.r.clone(), m.r.clone()])]
            } else {
                return unexpressible();
            }
        }
        ("MIRROR" | "SYMMETRIC", [a, b, m])
            if axis.is_none() && a.is_point() && b.is_point() && (m.is_line() || m.is_point()) =>
        {
            vec![one(Kind::Symmetric, vec![a.r.clone(), b.r.clone(), m.r.clone()])]
        }
        ("DISTANCE", [a, b]) => {
            let v = match value("length", Measure::Length) {
                Ok(v) => v,
                Err(why) => return skip(why),
            };
            match params.option("direction").unwrap_or("MINIMUM") {
                "MINIMUM" => {
                    let refs = if (a.is_point() && (b.is_point() || b.is_line() || b.is_round()))
                        || (a.is_line() && b.is_line())
                        || (a.is_round() && b.is_round())
                    {
                        vec![a.r.clone(), b.r.clone()]
                    } else if b.is_point() && (a.is_line() || a.is_round()) {
                        vec![b.r.clone(), a.r.clone()]
                    } else {
                        return unexpressible();
                    };
                    vec![with(Kind::Distance, refs, v)]
                }
                direction @ ("HORIZONTAL" | "VERTICAL") if a.is_point() && b.is_point() => {
                    let axis = usize::from(direction == "VERTICAL");
                    let v = v.map(|v| drawing.signed(v, drawing.delta(&a.r, &b.r, axis)));
                    let kind = if axis == 0 { Kind::DistanceX } else { Kind::DistanceY };
                    vec![with(kind, vec![a.r.clone(), b.r.clone()], v)]
                }
                direction => {
                    return skip(format!(
                        "a {direction} distance between {} is not expressible",
                        shapes()
                    ));
                }
            }
        }
        ("CENTERLINE_DIMENSION", [a, b]) => {
            // Twice the distance to the centreline (a diameter in a sketch to revolve).
            let v = match value("length", Measure::Length) {
                Ok(v) => v.map(|v| Number(v.0 / BigRational::from_integer(2.into()))),
                Err(why) => return skip(why),
            };
            let refs = if a.is_line() && (b.is_point() || b.is_line()) {
                vec![b.r.clone(), a.r.clone()]
            } else if b.is_line() && a.is_point() {
                vec![a.r.clone(), b.r.clone()]
            } else {
                return unexpressible();
            };
            vec![with(Kind::Distance, refs, v)]
        }
        ("LENGTH", [a]) if a.is_segment() => {
            let v = match value("length", Measure::Length) {
                Ok(v) => v,
                Err(why) => return skip(why),
            };
            match params.option("direction").unwrap_or("MINIMUM") {
                "MINIMUM" => vec![with(Kind::Length, vec![a.r.clone()], v)],
                direction @ ("HORIZONTAL" | "VERTICAL") => {
                    let axis = usize::from(direction == "VERTICAL");
                    let (s, e) = (
                        Ref::part(a.r.entity.clone(), Part::Start),
                        Ref::part(a.r.entity.clone(), Part::End),
                    );
                    let v = v.map(|v| drawing.signed(v, drawing.delta(&s, &e, axis)));
                    let kind = if axis == 0 { Kind::DistanceX } else { Kind::DistanceY };
                    vec![with(kind, vec![a.r.clone()], v)]
                }
                direction => return skip(format!("a {direction} length is not expressible")),
            }
        }
        ("RADIUS" | "DIAMETER", [a]) if a.is_round() => {
            let v = match value("length", Measure::Length) {
                Ok(v) => v,
                Err(why) => return skip(why),
            };
            let kind = if ctype == "RADIUS" { Kind::Radius } else { Kind::Diameter };
            vec![with(kind, vec![a.r.clone()], v)]
        }
        ("ANGLE", [a, b]) if a.is_line() && b.is_line() => {
            let v = match value("angle", Measure::Angle) {
                Ok(v) => v,
                Err(why) => return skip(why),
            };
            let v = v.map(|v| drawing.oriented_angle(v, &a.r, &b.r));
            vec![with(Kind::Angle, vec![a.r.clone(), b.r.clone()], v)]
        }
        // Its ends fixed where they coincide, the carrier's two incidences would be one.
        ("FIX" | "PROJECTED", [a]) if a.shape == Shape::ZeroLine => {
            return skip(format!(
                "fixing the zero-length line `{}` is not expressible: its ends, fixed where they \
                 coincide, would leave its carrier's two incidences dependent",
                a.r.entity
            ));
        }
        ("FIX" | "PROJECTED", [a]) => vec![one(Kind::Fix, vec![a.r.clone()])],
        _ => return unexpressible(),
    };
    Ok(Outcome::Constraints(out))
}

/// A circular or linear pattern: each instance of each element is its seed (instance 0) turned
/// about the pivot or moved along the directions, as `Rotated` / `Translated` constraints on
/// their points, named `<id>#<element>,<instance>` (`#<element>,<i>,<j>` for a linear pattern in
/// two directions; a circle's radius: `…#radius`, an `Equal`).
///
/// A closed circular pattern of N instances turns instance i by i·360°/N (its sense, as the
/// drawing shows); instance (i, j) of a linear pattern is instance (i − 1, j) moved by the
/// vector of `localDirection1` (from its start to its end), or (0, j − 1) by that of
/// `localDirection2`. An element is a point, a segment (its end points), an arc (its centre and
/// end points) or a circle (its centre, and an equal radius). Instances the file leaves empty
/// are not made. Skipped whole: an open circular pattern (its angle is not in the file), a
/// count that is not a positive integer, a circular pattern of more than 36 instances, an
/// element of another kind.
fn pattern(
    ctype: &str,
    params: &Params<'_>,
    id: &str,
    table: &Table,
    drawing: &Drawing<'_>,
) -> Result<Vec<Constraint>, String> {
    let circular = ctype == "CIRCULAR_PATTERN";
    if circular && params.flag("openPattern") {
        return Err(
            "an open circular pattern: the angle between its instances is not in the file".into()
        );
    }
    let resolve = |value: &str| resolved(table, value);
    let local = |role: &str| params.refs.iter().find(|r| r.role == role).and_then(|r| r.local);
    // The instances: element k, instance index (i or i, j) → reference.
    let mut instances: std::collections::BTreeMap<(usize, usize, usize), &str> = Default::default();
    for r in &params.refs {
        let (Some(index), Some(value)) = (r.role.strip_prefix("localInstance"), r.local) else {
            continue;
        };
        let parts: Option<Vec<usize>> = index.split(',').map(|x| x.parse().ok()).collect();
        let key = match parts.as_deref() {
            Some([k, i]) => (*k, *i, 0),
            Some([k, i, j]) => (*k, *i, *j),
            _ => return Err(format!("the instance parameter `{}` is not understood", r.role)),
        };
        if !value.is_empty() {
            instances.insert(key, value);
        }
    }
    let mut out = Vec::new();
    let push = |out: &mut Vec<Constraint>, cid: String, kind: Kind, refs: Vec<Ref>, value| {
        out.push(Constraint { id: cid, kind, refs, value, driving: true });
    };
    if circular {
        let pivot = resolve(local("localPivot").ok_or("the pattern has no pivot")?)?;
        let pivot = if pivot.is_point() {
            pivot.r
        } else if pivot.has_center() {
            pivot.center()
        } else {
            return Err(format!("the pivot is a {}, not a point", describe(pivot.shape)));
        };
        let count = params
            .quantity("patternc1")
            .and_then(Number::parse)
            .filter(|n| n.0.is_integer() && n.0 > BigRational::from_integer(0.into()))
            .ok_or("the pattern's count is not a positive integer")?;
        // Turns by multiples of 360°/N: rational (their cosines and sines) only for N = 1, 2
        // or 4; the others become regular polygons (see the lowering), up to N = 36, the turns
        // the turn prime carries. Skipped whole, not in part.
        if count.0 > BigRational::from_integer(36.into()) {
            return Err(format!(
                "a circular pattern of {} instances: turns by multiples of 360°/{} are beyond the \
                 36 divisions of a turn the analysis carries exactly",
                count.0, count.0
            ));
        }
        let step = BigRational::from_integer(360.into()) / count.0;
        for (&(k, i, j), value) in &instances {
            if i == 0 && j == 0 {
                continue;
            }
            let seed = instances.get(&(k, 0, 0)).ok_or(format!("element {k} has no seed"))?;
            let (seed, image) = (resolve(seed)?, resolve(value)?);
            let pairs = element_points(&seed, &image)?;
            let angle = &step * BigRational::from_integer(i.into());
            // The sense the drawing shows (turning the first pair of points).
            let sense = pairs
                .first()
                .and_then(|(s, q)| {
                    let (c, s, q) =
                        (drawing.position(&pivot)?, drawing.position(s)?, drawing.position(q)?);
                    let a = angle.to_f64()?.to_radians();
                    let miss = |a: f64| {
                        let (u, v) = (s[0] - c[0], s[1] - c[1]);
                        let t =
                            [c[0] + a.cos() * u - a.sin() * v, c[1] + a.sin() * u + a.cos() * v];
                        (t[0] - q[0]).hypot(t[1] - q[1])
                    };
                    Some(if miss(-a) < miss(a) { -1 } else { 1 })
                })
                .unwrap_or(1);
            let angle = Number(angle * BigRational::from_integer(sense.into()));
            for (n, (s, q)) in pairs.into_iter().enumerate() {
                let cid =
                    format!("{id}#{k},{i}{}", if n == 0 { String::new() } else { format!("#{n}") });
                push(&mut out, cid, Kind::Rotated, vec![s, q, pivot.clone()], Some(angle.clone()));
            }
            if seed.shape == Shape::Circle {
                let cid = format!("{id}#{k},{i}#radius");
                push(&mut out, cid, Kind::Equal, vec![seed.r.clone(), image.r.clone()], None);
            }
        }
    } else {
        let direction = |role: &str| -> Result<Option<(Ref, Ref)>, String> {
            let Some(d) = local(role) else { return Ok(None) };
            let d = resolve(d)?;
            if !d.is_segment() {
                return Err(format!(
                    "the direction `{role}` is a {}, not a segment",
                    describe(d.shape)
                ));
            }
            Ok(Some((Ref::part(d.r.entity.clone(), Part::Start), Ref::part(d.r.entity, Part::End))))
        };
        let directions = [direction("localDirection1")?, direction("localDirection2")?];
        for (&(k, i, j), value) in &instances {
            if i == 0 && j == 0 {
                continue;
            }
            // One step from the previous instance along the first direction, or along the
            // second from the first column.
            let (previous, along) = if i > 0 { ((k, i - 1, j), 0) } else { ((k, 0, j - 1), 1) };
            let Some((from, to)) = directions[along].clone() else {
                return Err(format!(
                    "instance {i},{j} needs the direction `localDirection{}`",
                    along + 1
                ));
            };
            let previous = instances
                .get(&previous)
                .ok_or(format!("instance {i},{j} of element {k} follows an empty instance"))?;
            let (seed, image) = (resolve(previous)?, resolve(value)?);
            let pairs = element_points(&seed, &image)?;
            let name =
                if directions[1].is_some() { format!("{k},{i},{j}") } else { format!("{k},{i}") };
            for (n, (s, q)) in pairs.into_iter().enumerate() {
                let cid =
                    format!("{id}#{name}{}", if n == 0 { String::new() } else { format!("#{n}") });
                push(&mut out, cid, Kind::Translated, vec![s, q, from.clone(), to.clone()], None);
            }
            if seed.shape == Shape::Circle {
                let cid = format!("{id}#{name}#radius");
                push(&mut out, cid, Kind::Equal, vec![seed.r.clone(), image.r.clone()], None);
            }
        }
    }
    // A point listed as an element of its own and as an end of a listed segment: once.
    let mut seen = std::collections::HashSet::new();
    out.retain(|c| c.kind == Kind::Equal || seen.insert((c.refs[0].clone(), c.refs[1].clone())));
    Ok(out)
}

/// An offset: a curve and its offset (`localMaster`, `localOffset`, or `local2`, `local0`) are
/// parallel lines or concentric circles (`<id>#master`); with a second pair (`localSecond`,
/// `localSecondOffset`, or `local3`, `local1`), that pair is too (`<id>#second`) and its gap is
/// the first's: for lines, the distance from the offset's start to its curve is the same in
/// both pairs (`EqualPointLineDistances`, the id). The first pair is shared by every offset of
/// one operation: its relation is stated once ([`super::fold_repeated_offsets`]). Where a pair
/// is of circles, its gap is the difference of their radii, and the gaps are equal
/// (`EqualGaps`, the id). Where the offset is an infinite line, the equal gap is skipped and the
/// relations kept: the reason comes back beside them.
fn offset(
    params: &Params<'_>,
    id: &str,
    table: &Table,
) -> Result<(Vec<Constraint>, Option<String>), String> {
    let local = |roles: [&str; 2]| {
        params.refs.iter().find(|r| roles.contains(&r.role)).and_then(|r| r.local)
    };
    let resolve = |value: &str| resolved(table, value);
    let pair = |curve: [&str; 2], offset: [&str; 2]| -> Result<Option<(Arg, Arg)>, String> {
        match (local(curve), local(offset)) {
            (Some(c), Some(o)) => Ok(Some((resolve(c)?, resolve(o)?))),
            (None, None) => Ok(None),
            _ => Err("an offset without its curve or without its offset curve".into()),
        }
    };
    let first = pair(["localMaster", "local2"], ["localOffset", "local0"])?
        .ok_or("an offset without its curves")?;
    let second = pair(["localSecond", "local3"], ["localSecondOffset", "local1"])?;
    let relation = |(c, o): &(Arg, Arg)| -> Result<(Kind, Vec<Ref>), String> {
        if c.is_line() && o.is_line() {
            Ok((Kind::Parallel, vec![c.r.clone(), o.r.clone()]))
        } else if c.is_round() && o.is_round() {
            Ok((Kind::Concentric, vec![c.r.clone(), o.r.clone()]))
        } else {
            Err(format!("an offset of a {} as a {}", describe(c.shape), describe(o.shape)))
        }
    };
    let constraint = |cid: String, (kind, refs): (Kind, Vec<Ref>)| Constraint {
        id: cid,
        kind,
        refs,
        value: None,
        driving: true,
    };
    let mut out = vec![constraint(format!("{id}#master"), relation(&first)?)];
    let Some(second) = second else { return Ok((out, None)) };
    out.push(constraint(format!("{id}#second"), relation(&second)?));
    // A pair's gap: of concentric circles, the two circles (a difference of radii); of
    // parallel lines, the offset's start and the curve.
    let gap = |(c, o): &(Arg, Arg)| -> Result<(Ref, Ref), String> {
        if c.is_round() {
            return Ok((c.r.clone(), o.r.clone()));
        }
        if !o.is_segment() {
            return Err("an offset that is an infinite line (no point of its own)".into());
        }
        Ok((Ref::part(o.r.entity.clone(), Part::Start), c.r.clone()))
    };
    let lines = first.0.is_line() && second.0.is_line();
    match (gap(&first), gap(&second)) {
        (Ok((p, l)), Ok((q, m))) => {
            let kind = if lines { Kind::EqualPointLineDistances } else { Kind::EqualGaps };
            out.push(constraint(id.to_owned(), (kind, vec![p, l, q, m])));
            Ok((out, None))
        }
        (Err(why), _) | (_, Err(why)) => {
            Ok((out, Some(format!("the equal gap of the two pairs: {why}"))))
        }
    }
}

/// A reference resolved, or why it cannot be.
fn resolved(table: &Table, value: &str) -> Result<Arg, String> {
    match table.resolve(value) {
        Target::Found(r, shape) => Ok(Arg { r, shape }),
        Target::Unusable(why) => Err(why),
    }
}

/// The pairs of points (seed, image) a patterned element moves: a point, a segment's end
/// points, an arc's centre and end points, a circle's centre.
fn element_points(seed: &Arg, image: &Arg) -> Result<Vec<(Ref, Ref)>, String> {
    // (Arcs compare as arcs: the neutral ones all run counter-clockwise, whichever way the
    // file stores each, and a turn or a move keeps the sense, so start goes to start.)
    let kind = |a: &Arg| std::mem::discriminant(&a.shape);
    if kind(seed) != kind(image) {
        return Err(format!(
            "an instance is a {} where its seed is a {}",
            describe(image.shape),
            describe(seed.shape)
        ));
    }
    let part = |a: &Arg, p: Part| Ref::part(a.r.entity.clone(), p);
    let parts: &[Part] = match seed.shape {
        Shape::Point => return Ok(vec![(seed.r.clone(), image.r.clone())]),
        // A zero-length line's ends are points of their own (`<id>#start`, `<id>#end`).
        Shape::ZeroLine => {
            let end = |a: &Arg, e: &str| Ref::whole(format!("{}#{e}", a.r.entity));
            return Ok(["start", "end"].map(|e| (end(seed, e), end(image, e))).to_vec());
        }
        Shape::Segment => &[Part::Start, Part::End],
        Shape::Arc { .. } => &[Part::Center, Part::Start, Part::End],
        Shape::Circle => &[Part::Center],
        other => return Err(format!("a patterned {} is not expressible", describe(other))),
    };
    Ok(parts.iter().map(|&p| (part(seed, p), part(image, p))).collect())
}

fn level(ctype: &str) -> Kind {
    if ctype == "HORIZONTAL" { Kind::Horizontal } else { Kind::Vertical }
}

/// Measurements on the drawing, to orient unsigned dimensions the way the sketch is drawn.
struct Drawing<'a> {
    table: &'a Table,
    entities: &'a [ir::Entity],
}

impl Drawing<'_> {
    fn geometry(&self, id: &str) -> Option<&Geometry> {
        self.table.index(id).and_then(|i| self.entities.get(i)).map(|e| &e.geometry)
    }

    fn position(&self, r: &Ref) -> Option<[f64; 2]> {
        let at = |c: &[Number]| match c {
            [x, y] => Some([x.to_f64(), y.to_f64()]),
            _ => None,
        };
        match (self.geometry(&r.entity)?, r.part) {
            (Geometry::Point { at: p }, Part::Whole) => at(p),
            (Geometry::Segment { start, .. } | Geometry::Arc { start, .. }, Part::Start) => {
                at(start)
            }
            (Geometry::Segment { end, .. } | Geometry::Arc { end, .. }, Part::End) => at(end),
            (
                Geometry::Circle { center, .. }
                | Geometry::Arc { center, .. }
                | Geometry::Ellipse { center, .. }
                | Geometry::EllipticalArc { center, .. },
                Part::Center,
            ) => at(center),
            (Geometry::EllipticalArc { start, .. }, Part::Start) => at(start),
            (Geometry::EllipticalArc { end, .. }, Part::End) => at(end),
            (Geometry::BSpline { poles, .. }, Part::Start) => at(poles.first()?),
            (Geometry::BSpline { poles, .. }, Part::End) => at(poles.last()?),
            _ => None,
        }
    }

    /// Coordinate `axis` of `b` minus that of `a`, in the drawing.
    fn delta(&self, a: &Ref, b: &Ref, axis: usize) -> Option<f64> {
        Some(self.position(b)?[axis] - self.position(a)?[axis])
    }

    /// An unsigned distance given the sign the drawing shows.
    fn signed(&self, v: Number, delta: Option<f64>) -> Number {
        if delta.is_some_and(|d| d < 0.0) { Number(-v.0) } else { v }
    }

    fn direction(&self, r: &Ref) -> Option<[f64; 2]> {
        let to = |a: &[Number], b: &[Number]| match (a, b) {
            ([ax, ay], [bx, by]) => Some([bx.to_f64() - ax.to_f64(), by.to_f64() - ay.to_f64()]),
            _ => None,
        };
        match self.geometry(&r.entity)? {
            Geometry::Segment { start, end } => to(start, end),
            Geometry::Line { a, b } => to(a, b),
            _ => None,
        }
    }

    /// Onshape's angle dimension is unsigned, between undirected lines; the neutral one is the
    /// angle from the first line's direction (start to end) to the second's. Of the angles
    /// `±value + k·180°` the one nearest the drawing is taken, in (−180°, 180°].
    fn oriented_angle(&self, v: Number, a: &Ref, b: &Ref) -> Number {
        let (Some(d1), Some(d2)) = (self.direction(a), self.direction(b)) else { return v };
        let drawn =
            (d1[0] * d2[1] - d1[1] * d2[0]).atan2(d1[0] * d2[0] + d1[1] * d2[1]).to_degrees();
        let value = v.to_f64();
        if !drawn.is_finite() || value.is_nan() || value.abs() > 1e6 {
            return v;
        }
        let mut best: Option<(f64, BigRational)> = None;
        for sign in [1i64, -1] {
            let base = sign as f64 * value;
            let k = ((drawn - base) / 180.0).round();
            let miss = (drawn - (base + 180.0 * k)).abs();
            if best.as_ref().is_none_or(|(m, _)| miss < *m) {
                let Some(k) = k.to_i64() else { return v };
                let exact = &v.0 * BigRational::from_integer(sign.into())
                    + BigRational::from_integer((180 * k).into());
                best = Some((miss, exact));
            }
        }
        let Some((_, mut angle)) = best else { return v };
        let full = BigRational::from_integer(360.into());
        let half = BigRational::from_integer(180.into());
        while angle > half {
            angle -= &full;
        }
        while angle <= -&half {
            angle += &full;
        }
        Number(angle)
    }
}
