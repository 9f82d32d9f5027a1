//! Sketch entities: `BTMSketchPoint`, `BTMSketchCurve` (whole curves) and
//! `BTMSketchCurveSegment` (bounded curves) with their `BTCurveGeometry…` geometry, read into
//! [`ir::Entity`]s, and the table that resolves the constraints' references to them.

use std::collections::HashMap;

use num_rational::BigRational;

use super::json::{self, Object};
use crate::ir::{self, Coords, Geometry, Kind, Number, Part, Ref};

/// A line whose parameter range is at most this long (in metres, 1e-9 mm) has zero length: it is
/// read as its carrier and two points on it ([`zero_line`]). Onshape leaves such lines behind
/// when fillets consume a whole side; their end parameters then agree to about 1e-17 m.
const ZERO_LENGTH: f64 = 1e-12;

/// How a read entity can be addressed by constraints.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Shape {
    /// A point (`BTMSketchPoint`).
    Point,
    /// A zero-length line, read as its carrier (an unbounded line, the id) and its end points
    /// `<id>#start`, `<id>#end` on it, which `.start` and `.end` name.
    ZeroLine,
    /// A line segment.
    Segment,
    /// An unbounded line (a `BTMSketchCurve` with line geometry).
    Line,
    /// A circle.
    Circle,
    /// A circular arc; `swapped` when Onshape's runs clockwise, so that its `.start` is the
    /// IR's end point.
    Arc { swapped: bool },
    /// An ellipse.
    Ellipse,
    /// An elliptical arc (`swapped` as for arcs).
    EllipticalArc { swapped: bool },
    /// A B-spline.
    Spline,
}

/// What became of an entity element.
pub(super) enum Read {
    /// An entity of the neutral sketch.
    Entity(ir::Entity, Shape),
    /// An entity that cannot be expressed, with the reason.
    Skip(String),
    /// An entity that is several of the neutral sketch's, held together by constraints (a text
    /// or image box: a rectangle of four segments and its centre; an interpolated spline: a
    /// B-spline and its interpolation points), with the ids of Onshape's that name a part of
    /// one of them (`<id>.0.internal`: the spline's start) as `(id, entity, suffix)`.
    Composite(Vec<(ir::Entity, Shape)>, Vec<ir::Constraint>, Vec<(String, String, &'static str)>),
}

/// Reads one entity whose `message` is `msg` (the id has been read by the caller).
pub(super) fn read(type_name: &str, msg: &Object, id: &str) -> Result<Read, String> {
    let construction = json::flag(msg, "isConstruction")?;
    let made = |geometry: Geometry, shape: Shape| {
        Ok(Read::Entity(
            ir::Entity { id: id.to_owned(), geometry, construction, external: false },
            shape,
        ))
    };
    match type_name {
        "BTMSketchPoint" => {
            let at = point(json::number(msg, "x")?, json::number(msg, "y")?)?;
            made(Geometry::Point { at }, Shape::Point)
        }
        "BTMSketchCurve" | "BTMSketchCurveSegment" => {
            let bounded = type_name == "BTMSketchCurveSegment";
            let geometry = json::field_object(msg, "geometry")?;
            let geometry_type = json::string(geometry, "typeName")?;
            let g = json::field_object(geometry, "message")?;
            let range = || -> Result<(f64, f64), String> {
                Ok((json::number(msg, "startParam")?, json::number(msg, "endParam")?))
            };
            match geometry_type {
                "BTCurveGeometryLine" => {
                    line(g, bounded.then(range).transpose()?, made, (id, construction))
                }
                "BTCurveGeometryCircle" => circle(g, bounded.then(range).transpose()?, made),
                "BTCurveGeometryEllipse" => ellipse(g, bounded.then(range).transpose()?, made),
                "BTCurveGeometrySpline" => spline(g, msg, made),
                "BTCurveGeometryInterpolatedSpline" => interpolated(g, msg, id, construction),
                other => Ok(Read::Skip(format!("curve geometry {other} is not supported"))),
            }
        }
        "BTMSketchTextEntity" => {
            let start =
                (json::number(msg, "baselineStartX")?, json::number(msg, "baselineStartY")?);
            let width = (
                json::number(msg, "baselineDirectionX")?,
                json::number(msg, "baselineDirectionY")?,
            );
            let height = json::number(msg, "ascent")?;
            let names = ["baseline", "ascent", "left", "right"];
            boxed(id, "sketch_text", construction, start, width, height, names)
        }
        "BTMSketchImageEntity" => {
            let start = (json::number(msg, "originX")?, json::number(msg, "originY")?);
            let width = (json::number(msg, "xAxisX")?, json::number(msg, "xAxisY")?);
            let height = json::number(msg, "aspectRatio")? * width.0.hypot(width.1);
            let names = ["bottom", "top", "left", "right"];
            boxed(id, "sketch_image", construction, start, width, height, names)
        }
        other => Ok(Read::Skip(format!("entity type {other} is not supported"))),
    }
}

/// A text or image box as the rectangle Onshape draws: from the bottom-left corner `start`
/// along `width` (a vector, metres) and `height` up (to its left). Its edges are segments
/// `<id>.<kind>.<bottom>` (bottom-left to bottom-right), `.<top>` (top-left to top-right),
/// `.left`, `.right` (bottom to top), joined at the corners, and its centre a point
/// `<id>.<kind>.center`; the constraints (`<id>#…`) make it a rectangle (`#parallel`,
/// `#perpendicular`, `#perpendicular2`, the corners `#corner1`…`#corner4`) of the drawn
/// proportions (`#ratio`: the left edge's length over the bottom's, a `LengthRatio`: a text's
/// width follows its height through the font, an image's through its aspect ratio), with its
/// centre the middle of a diagonal (`#center`). Four degrees of freedom: place, turn, size.
fn boxed(
    id: &str,
    kind: &str,
    construction: bool,
    start: (f64, f64),
    width: (f64, f64),
    height: f64,
    edges: [&str; 4],
) -> Result<Read, String> {
    let [bottom, top, left, right] = edges;
    // Numbers out of range skip the box, not the file.
    let rectangle = || -> Result<Read, String> {
        let length = width.0.hypot(width.1);
        if !(length.is_finite() && length > 0.0 && height.is_finite() && height > 0.0) {
            return Ok(Read::Skip(format!("a {kind} box with an empty outline")));
        }
        let up = (-width.1 / length * height, width.0 / length * height);
        let bl = start;
        let br = (bl.0 + width.0, bl.1 + width.1);
        let tl = (bl.0 + up.0, bl.1 + up.1);
        let tr = (br.0 + up.0, br.1 + up.1);
        let center = ((bl.0 + tr.0) / 2.0, (bl.1 + tr.1) / 2.0);
        let name = |edge: &str| format!("{id}.{kind}.{edge}");
        let entity = |eid: String, geometry: Geometry| ir::Entity {
            id: eid,
            geometry,
            construction,
            external: false,
        };
        let segment =
            |edge: &str, a: (f64, f64), b: (f64, f64)| -> Result<(ir::Entity, Shape), String> {
                let geometry = Geometry::Segment { start: point(a.0, a.1)?, end: point(b.0, b.1)? };
                Ok((entity(name(edge), geometry), Shape::Segment))
            };
        let entities = vec![
            segment(bottom, bl, br)?,
            segment(top, tl, tr)?,
            segment(left, bl, tl)?,
            segment(right, br, tr)?,
            (
                entity(name("center"), Geometry::Point { at: point(center.0, center.1)? }),
                Shape::Point,
            ),
        ];
        let end = |edge: &str, part: Part| Ref::part(name(edge), part);
        let whole = |edge: &str| Ref::whole(name(edge));
        let constraint = |suffix: &str, kind: Kind, refs: Vec<Ref>, value: Option<Number>| {
            ir::Constraint { id: format!("{id}#{suffix}"), kind, refs, value, driving: true }
        };
        let ratio =
            Number::from_f64(height / length).ok_or("the box's proportions are not a number")?;
        let corners = [
            ((bottom, Part::Start), (left, Part::Start)),
            ((bottom, Part::End), (right, Part::Start)),
            ((top, Part::Start), (left, Part::End)),
            ((top, Part::End), (right, Part::End)),
        ];
        let mut constraints: Vec<ir::Constraint> = (1..)
            .zip(corners)
            .map(|(k, ((e, p), (f, q)))| {
                let refs = vec![end(e, p), end(f, q)];
                constraint(&format!("corner{k}"), Kind::Coincident, refs, None)
            })
            .collect();
        constraints.extend([
            constraint("parallel", Kind::Parallel, vec![whole(bottom), whole(top)], None),
            constraint(
                "perpendicular",
                Kind::Perpendicular,
                vec![whole(bottom), whole(left)],
                None,
            ),
            constraint(
                "perpendicular2",
                Kind::Perpendicular,
                vec![whole(bottom), whole(right)],
                None,
            ),
            constraint("ratio", Kind::LengthRatio, vec![whole(left), whole(bottom)], Some(ratio)),
            constraint(
                "center",
                Kind::Symmetric,
                vec![end(bottom, Part::Start), end(top, Part::End), Ref::whole(name("center"))],
                None,
            ),
        ]);
        Ok(Read::Composite(entities, constraints, Vec::new()))
    };
    rectangle().or_else(|why| Ok(Read::Skip(format!("a {kind} box: {why}"))))
}

/// Metres (a double read from the file) to millimetres, exactly: the shortest decimal of the
/// double, times 1000 on the rational.
pub(super) fn mm(x: f64) -> Result<Number, String> {
    let metres = Number::from_f64(x).ok_or("a coordinate is out of range")?;
    Ok(Number(metres.0 * BigRational::from_integer(1000.into())))
}

fn point(x: f64, y: f64) -> Result<Coords, String> {
    Ok(vec![mm(x)?, mm(y)?])
}

/// A unit direction, or `None` when it is zero or not finite.
fn unit(x: f64, y: f64) -> Option<(f64, f64)> {
    let n = x.hypot(y);
    (n.is_finite() && n > 0.0).then(|| (x / n, y / n))
}

fn line(
    g: &Object,
    range: Option<(f64, f64)>,
    made: impl Fn(Geometry, Shape) -> Result<Read, String>,
    (id, construction): (&str, bool),
) -> Result<Read, String> {
    let (px, py) = (json::number(g, "pntX")?, json::number(g, "pntY")?);
    let (dx, dy) = (json::number(g, "dirX")?, json::number(g, "dirY")?);
    let Some(u) = unit(dx, dy) else {
        return Ok(Read::Skip("line with a zero direction".into()));
    };
    let Some((t0, t1)) = range else {
        return made(
            Geometry::Line { a: point(px, py)?, b: point(px + u.0, py + u.1)? },
            Shape::Line,
        );
    };
    // Onshape's direction is a unit vector; the parameters are arc lengths along it.
    let start = point(px + t0 * dx, py + t0 * dy)?;
    if ((t1 - t0) * dx.hypot(dy)).abs() <= ZERO_LENGTH {
        // (A centimetre along the line: of the size of the sketch's own distances.)
        let through = point(px + t0 * dx + 0.01 * u.0, py + t0 * dy + 0.01 * u.1)?;
        return Ok(zero_line(id, construction, start, through));
    }
    let end = point(px + t1 * dx, py + t1 * dy)?;
    made(Geometry::Segment { start, end }, Shape::Segment)
}

/// A zero-length line from `start` (a segment from a point to itself, whose direction the
/// segment's own coordinates no longer hold) as what Onshape still solves: its carrier, the
/// unbounded line `<id>` through `start` and `through` (along the file's direction),
/// and its end points `<id>#start`, `<id>#end`, both drawn at `start`, each on the carrier
/// (`PointOnObject`, `<id>#start-on`, `<id>#end-on`). Four degrees of freedom, as a segment
/// has, and no degenerate equation where the ends coincide: a constraint on the line (its
/// direction: vertical, perpendicular, tangent…) is one on the carrier, a constraint on an end
/// point one on that point.
fn zero_line(id: &str, construction: bool, start: Coords, through: Coords) -> Read {
    let entity = |id: String, geometry| ir::Entity { id, geometry, construction, external: false };
    let carrier = entity(id.to_owned(), Geometry::Line { a: start.clone(), b: through });
    let ends = ["start", "end"]
        .map(|end| entity(format!("{id}#{end}"), Geometry::Point { at: start.clone() }));
    let on = ends
        .iter()
        .map(|p| ir::Constraint {
            id: format!("{}-on", p.id),
            kind: Kind::PointOnObject,
            refs: vec![Ref::whole(p.id.clone()), Ref::whole(id)],
            value: None,
            driving: true,
        })
        .collect();
    let mut entities = vec![(carrier, Shape::ZeroLine)];
    entities.extend(ends.into_iter().map(|p| (p, Shape::Point)));
    Read::Composite(entities, on, Vec::new())
}

fn circle(
    g: &Object,
    range: Option<(f64, f64)>,
    made: impl Fn(Geometry, Shape) -> Result<Read, String>,
) -> Result<Read, String> {
    let (cx, cy) = (json::number(g, "xCenter")?, json::number(g, "yCenter")?);
    let r = json::number(g, "radius")?;
    if r.is_nan() || r <= 0.0 {
        return Ok(Read::Skip(format!("circle of radius {r} (not positive)")));
    }
    let center = point(cx, cy)?;
    let Some((t0, t1)) = range else {
        return made(Geometry::Circle { center, radius: mm(r)? }, Shape::Circle);
    };
    let clockwise = json::flag(g, "clockwise")?;
    let Some(u) = unit(
        json::opt_number(g, "xDir")?.unwrap_or(1.0),
        json::opt_number(g, "yDir")?.unwrap_or(0.0),
    ) else {
        return Ok(Read::Skip("arc with a zero reference direction".into()));
    };
    if (t1 - t0).abs() >= std::f64::consts::TAU - 1e-12 {
        return Ok(Read::Skip("arc spanning a whole turn (its end points coincide)".into()));
    }
    // Onshape's parameter is the angle from the reference direction, turning clockwise when
    // the curve is clockwise: the point at t is c + r (cos t · u + s sin t · u⊥), s = ∓1.
    let s = if clockwise { -1.0 } else { 1.0 };
    let at = |t: f64| {
        point(
            cx + r * (t.cos() * u.0 - s * t.sin() * u.1),
            cy + r * (t.cos() * u.1 + s * t.sin() * u.0),
        )
    };
    let (a, b) = (at(t0)?, at(t1)?);
    // The neutral arc runs counter-clockwise from start to end.
    let (start, end) = if clockwise { (b, a) } else { (a, b) };
    made(Geometry::Arc { center, start, end }, Shape::Arc { swapped: clockwise })
}

fn ellipse(
    g: &Object,
    range: Option<(f64, f64)>,
    made: impl Fn(Geometry, Shape) -> Result<Read, String>,
) -> Result<Read, String> {
    let (cx, cy) = (json::number(g, "xCenter")?, json::number(g, "yCenter")?);
    let (major, minor) = (json::number(g, "radius")?, json::number(g, "minorRadius")?);
    if major.is_nan() || minor.is_nan() || major <= 0.0 || minor <= 0.0 {
        return Ok(Read::Skip(format!("ellipse of radii {major} and {minor} (not positive)")));
    }
    let Some(u) = unit(json::number(g, "xDir")?, json::number(g, "yDir")?) else {
        return Ok(Read::Skip("ellipse with a zero axis direction".into()));
    };
    let center = point(cx, cy)?;
    // `radius` lies along (xDir, yDir); the neutral form wants the major axis.
    let (axis_end, minor_radius) = if major >= minor {
        (point(cx + major * u.0, cy + major * u.1)?, mm(minor)?)
    } else {
        (point(cx - minor * u.1, cy + minor * u.0)?, mm(major)?)
    };
    let Some((t0, t1)) = range else {
        return made(Geometry::Ellipse { center, major: axis_end, minor_radius }, Shape::Ellipse);
    };
    if (t1 - t0).abs() >= std::f64::consts::TAU - 1e-12 {
        return Ok(Read::Skip(
            "elliptical arc spanning a whole turn (its end points coincide)".into(),
        ));
    }
    let clockwise = json::flag(g, "clockwise")?;
    let s = if clockwise { -1.0 } else { 1.0 };
    let at = |t: f64| {
        point(
            cx + major * t.cos() * u.0 - s * minor * t.sin() * u.1,
            cy + major * t.cos() * u.1 + s * minor * t.sin() * u.0,
        )
    };
    let (a, b) = (at(t0)?, at(t1)?);
    let (start, end) = if clockwise { (b, a) } else { (a, b) };
    let geometry = Geometry::EllipticalArc { center, major: axis_end, minor_radius, start, end };
    made(geometry, Shape::EllipticalArc { swapped: clockwise })
}

/// Largest spline degree read (Onshape draws degree 2 and 3).
const MAX_DEGREE: f64 = 32.0;

fn spline(
    g: &Object,
    msg: &Object,
    made: impl Fn(Geometry, Shape) -> Result<Read, String>,
) -> Result<Read, String> {
    let degree = json::number(g, "degree")?;
    if !((1.0..=MAX_DEGREE).contains(&degree) && degree.fract() == 0.0) {
        return Ok(Read::Skip(format!("spline of degree {degree}")));
    }
    let degree = degree as usize;
    if json::flag(g, "isPeriodic")? {
        return Ok(Read::Skip(
            "periodic control-point spline: Onshape's periodic knot convention is not verified"
                .into(),
        ));
    }
    if json::flag(g, "isRational")? {
        return Ok(Read::Skip(
            "rational control-point spline: where Onshape stores the weights is not documented"
                .into(),
        ));
    }
    let coordinates = json::numbers(g, "controlPoints")?;
    if coordinates.len() % 2 != 0 {
        return Ok(Read::Skip("spline with an odd number of control point coordinates".into()));
    }
    let count = coordinates.len() / 2;
    if let Some(declared) = json::opt_number(g, "controlPointCount")?
        && declared != count as f64
    {
        return Ok(Read::Skip(format!(
            "spline declaring {declared} control points but giving {count}"
        )));
    }
    let knots = json::numbers(g, "knots")?;
    if count <= degree || knots.len() != count + degree + 1 {
        return Ok(Read::Skip(format!(
            "spline with {count} control points, degree {degree} and {} knots (not a B-spline)",
            knots.len()
        )));
    }
    if knots.windows(2).any(|w| w[0].partial_cmp(&w[1]).is_none_or(std::cmp::Ordering::is_gt)) {
        return Ok(Read::Skip("spline with a decreasing knot vector".into()));
    }
    // A segment bounded inside the knot domain is a trimmed spline, which the neutral form has not.
    let domain = (knots[degree], knots[count]);
    let (t0, t1) = (json::opt_number(msg, "startParam")?, json::opt_number(msg, "endParam")?);
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs()));
    if t0.is_some_and(|t| !near(t, domain.0)) || t1.is_some_and(|t| !near(t, domain.1)) {
        return Ok(Read::Skip(format!(
            "spline trimmed to parameters [{}, {}] inside its knot domain [{}, {}]",
            t0.unwrap_or(domain.0),
            t1.unwrap_or(domain.1),
            domain.0,
            domain.1
        )));
    }
    let poles = coordinates.chunks(2).map(|c| point(c[0], c[1])).collect::<Result<Vec<_>, _>>()?;
    let mut grouped: Vec<(f64, u32)> = Vec::new();
    for &k in &knots {
        match grouped.last_mut() {
            Some((last, m)) if *last == k => *m += 1,
            _ => grouped.push((k, 1)),
        }
    }
    let knots = grouped
        .into_iter()
        .map(|(k, m)| Ok((Number::from_f64(k).ok_or("a knot is out of range")?, m)))
        .collect::<Result<Vec<_>, String>>()?;
    made(
        Geometry::BSpline { degree: degree as u32, poles, weights: None, knots, periodic: false },
        Shape::Spline,
    )
}

/// Most interpolation points read (a larger spline is skipped: its control points are solved
/// for densely).
const MAX_INTERPOLATION_POINTS: usize = 400;

/// An interpolated spline (`BTCurveGeometryInterpolatedSpline`): the cubic through its
/// interpolation points `Q₀ … Q_{m−1}`, as the B-spline Onshape builds (the NURBS Book's global
/// interpolation with end derivatives, §9.2.2): parameters `t_k` by the centripetal rule (the
/// sum of the square roots of the chords, from 0 to 1), knots `0⁴ t₁ … t_{m−2} 1⁴`, control
/// points `Q₀`, the start handle, m − 2 inner ones, the end handle, `Q_{m−1}` — the handles
/// are `Q₀ + t₁·D₀/3` and `Q_{m−1} − (1 − t_{m−2})·D₁/3`, which the file's `startHandle` and
/// `endHandle` are (to 1e-16 m on every spline of SketchGraphs' sample), so the derivatives are
/// the legs of the control polygon. A periodic one: the periodic cubic with knots `t₀ … t_m`
/// (the closing chord included) and its m control points. The inner control points are
/// solved (in doubles) so that the curve passes through the points at their knots.
///
/// It becomes the B-spline `<id>`, its inner interpolation points `<id>.<k>.internal` (all of
/// them for a periodic spline) held on it at their knots (`SplinePoint`, `<id>#through<k>`),
/// and the aliases: `<id>.0.internal` and `<id>.<m−1>.internal` are its start and end,
/// `<id>.startDerivative` and `<id>.endDerivative` its end legs. A spline trimmed to a part of
/// its range is skipped, as control-point splines are.
fn interpolated(g: &Object, msg: &Object, id: &str, construction: bool) -> Result<Read, String> {
    let what = "interpolated spline (BTCurveGeometryInterpolatedSpline)";
    let coordinates = json::numbers(g, "interpolationPoints")?;
    if coordinates.len() % 2 != 0 {
        return Ok(Read::Skip(format!("{what} with an odd number of coordinates")));
    }
    let q: Vec<(f64, f64)> = coordinates.chunks(2).map(|c| (c[0], c[1])).collect();
    let m = q.len();
    let periodic = json::flag(g, "isPeriodic")?;
    if m < 2 || (periodic && m < 4) || m > MAX_INTERPOLATION_POINTS {
        return Ok(Read::Skip(format!(
            "{what} through {m} points (read: 2 to {MAX_INTERPOLATION_POINTS}, 4 or more when \
             periodic)"
        )));
    }
    let (t0, t1) = (json::opt_number(msg, "startParam")?, json::opt_number(msg, "endParam")?);
    if t0.is_some_and(|t| t.abs() > 1e-12) || t1.is_some_and(|t| (t - 1.0).abs() > 1e-12) {
        return Ok(Read::Skip(format!(
            "{what} trimmed to parameters [{}, {}] inside its range [0, 1]: the ends of a \
             trimmed spline are no control points",
            t0.unwrap_or(0.0),
            t1.unwrap_or(1.0)
        )));
    }
    // Centripetal parameters.
    let chords: Vec<f64> = (0..if periodic { m } else { m - 1 })
        .map(|i| {
            let (a, b) = (q[i], q[(i + 1) % m]);
            (b.0 - a.0).hypot(b.1 - a.1).sqrt()
        })
        .collect();
    let total: f64 = chords.iter().sum();
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !positive(total) || !chords.iter().all(|c| positive(*c)) {
        return Ok(Read::Skip(format!("{what} with two consecutive points at the same place")));
    }
    let mut params = vec![0.0];
    let mut run = 0.0;
    for c in &chords[..chords.len() - 1] {
        run += c;
        params.push(run / total);
    }
    params.push(1.0);
    // Exact knots (the shortest decimals of the parameters), strictly increasing.
    let knots: Vec<Number> = params
        .iter()
        .map(|t| Number::from_f64(*t).ok_or("a parameter is out of range"))
        .collect::<Result<_, _>>()?;
    if knots.windows(2).any(|w| w[0].0 >= w[1].0) {
        return Ok(Read::Skip(format!("{what} whose parameters do not increase")));
    }
    let flat: Vec<BigRational> = if periodic {
        knots.iter().map(|k| k.0.clone()).collect()
    } else {
        let (zero, one) = (&knots[0].0, &knots[m - 1].0);
        let inner = knots[1..m - 1].iter().map(|k| k.0.clone());
        std::iter::repeat_n(zero.clone(), 4)
            .chain(inner)
            .chain(std::iter::repeat_n(one.clone(), 4))
            .collect()
    };
    let n = if periodic { m } else { m + 2 };
    // The control points: the ends and handles known (open), the others solved from the
    // interpolation conditions Σ N_j(t_k) P_j = Q_k.
    let mut known: Vec<Option<(f64, f64)>> = vec![None; n];
    if !periodic {
        let handle = |x: &str, y: &str| -> Result<Option<(f64, f64)>, String> {
            Ok(json::opt_number(g, x)?.zip(json::opt_number(g, y)?))
        };
        let (Some(start), Some(end)) =
            (handle("startHandleX", "startHandleY")?, handle("endHandleX", "endHandleY")?)
        else {
            return Ok(Read::Skip(format!("{what} without its end handles")));
        };
        known[0] = Some(q[0]);
        known[1] = Some(start);
        known[n - 2] = Some(end);
        known[n - 1] = Some(q[m - 1]);
    }
    let unknown: Vec<usize> = (0..n).filter(|j| known[*j].is_none()).collect();
    let rows: Vec<usize> = if periodic { (0..m).collect() } else { (1..m - 1).collect() };
    let size = unknown.len();
    let mut a = vec![vec![0.0; size + 2]; size];
    for (r, &k) in rows.iter().enumerate() {
        let basis = gcs_model::spline::basis(3, n, &flat, &[], periodic, &knots[k].0)
            .ok_or("an interpolation parameter is outside the spline's range")?;
        let (mut bx, mut by) = q[k];
        for (j, c) in basis {
            let c = num_traits::ToPrimitive::to_f64(&c).unwrap_or(f64::NAN);
            match known[j] {
                Some((x, y)) => {
                    bx -= c * x;
                    by -= c * y;
                }
                None => {
                    let col = unknown.iter().position(|u| *u == j).unwrap_or(0);
                    a[r][col] += c;
                }
            }
        }
        a[r][size] = bx;
        a[r][size + 1] = by;
    }
    let Some(solved) = solve(a) else {
        return Ok(Read::Skip(format!("{what} whose control points its points do not determine")));
    };
    for (j, xy) in unknown.iter().zip(solved) {
        known[*j] = Some(xy);
    }
    let poles = known
        .iter()
        .map(|p| p.map_or(Err("a control point is missing".to_owned()), |(x, y)| point(x, y)))
        .collect::<Result<Vec<_>, _>>()?;
    let mut grouped: Vec<(Number, u32)> = Vec::new();
    for k in flat {
        match grouped.last_mut() {
            Some((last, mult)) if last.0 == k => *mult += 1,
            _ => grouped.push((Number(k), 1)),
        }
    }
    let spline = ir::Entity {
        id: id.to_owned(),
        geometry: Geometry::BSpline { degree: 3, poles, weights: None, knots: grouped, periodic },
        construction,
        external: false,
    };
    let mut entities = vec![(spline, Shape::Spline)];
    let mut constraints = Vec::new();
    for &k in &rows {
        let pid = format!("{id}.{k}.internal");
        entities.push((
            ir::Entity {
                id: pid.clone(),
                geometry: Geometry::Point { at: point(q[k].0, q[k].1)? },
                construction,
                external: false,
            },
            Shape::Point,
        ));
        constraints.push(ir::Constraint {
            id: format!("{id}#through{k}"),
            kind: Kind::SplinePoint,
            refs: vec![Ref::whole(pid), Ref::whole(id)],
            value: Some(knots[k].clone()),
            driving: true,
        });
    }
    let aliases = if periodic {
        Vec::new()
    } else {
        vec![
            (format!("{id}.0.internal"), id.to_owned(), "start"),
            (format!("{id}.{}.internal", m - 1), id.to_owned(), "end"),
        ]
    };
    Ok(Read::Composite(entities, constraints, aliases))
}

/// Solves the square system `a` (each row its coefficients, then two right-hand sides) by
/// Gaussian elimination with partial pivoting; `None` when it is singular.
fn solve(mut a: Vec<Vec<f64>>) -> Option<Vec<(f64, f64)>> {
    let n = a.len();
    for col in 0..n {
        let pivot = (col..n).max_by(|i, j| a[*i][col].abs().total_cmp(&a[*j][col].abs()))?;
        // (The drawing only: an exactly zero pivot is a singular system.)
        let p = a[pivot][col].abs();
        if p.is_nan() || p == 0.0 {
            return None;
        }
        a.swap(col, pivot);
        let (top, rest) = a.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for row in rest {
            let f = row[col] / pivot_row[col];
            if f != 0.0 {
                for (x, y) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                    *x -= f * y;
                }
            }
        }
    }
    let mut x = vec![(0.0, 0.0); n];
    for r in (0..n).rev() {
        let (mut sx, mut sy) = (a[r][n], a[r][n + 1]);
        for c in r + 1..n {
            sx -= a[r][c] * x[c].0;
            sy -= a[r][c] * x[c].1;
        }
        x[r] = (sx / a[r][r], sy / a[r][r]);
    }
    x.iter().all(|(x, y)| x.is_finite() && y.is_finite()).then_some(x)
}

/// The sketch's entities as constraints see them.
#[derive(Default)]
pub(super) struct Table {
    /// Read entities: id → (shape, index in the sketch's entities).
    read: HashMap<String, (Shape, usize)>,
    /// Skipped entities: id → why.
    skipped: HashMap<String, String>,
    /// Point ids the entities declare (`startPointId`, `endPointId`, `centerId`) that are not
    /// `<entity id>.start` etc.: id → (entity, suffix). Only ids declared once.
    aliases: HashMap<String, Option<(String, &'static str)>>,
}

/// What a reference string denotes.
pub(super) enum Target {
    /// A reference, with the shape it points at (`Shape::Point` for a named point of a curve).
    Found(Ref, Shape),
    /// A reference to something that cannot be used: why.
    Unusable(String),
}

impl Table {
    /// Whether `id` is already taken.
    pub(super) fn contains(&self, id: &str) -> bool {
        self.read.contains_key(id) || self.skipped.contains_key(id)
    }

    /// Records a read entity at `index` of the sketch's entities.
    pub(super) fn add(&mut self, id: &str, shape: Shape, index: usize, msg: &Object) {
        self.read.insert(id.to_owned(), (shape, index));
        for (key, suffix) in
            [("startPointId", "start"), ("endPointId", "end"), ("centerId", "center")]
        {
            if let Ok(Some(alias)) = json::opt_string(msg, key)
                && !alias.is_empty()
                && alias != format!("{id}.{suffix}")
            {
                self.aliases
                    .entry(alias.to_owned())
                    .and_modify(|a| *a = None)
                    .or_insert_with(|| Some((id.to_owned(), suffix)));
            }
        }
    }

    /// Records an id Onshape gives to a named point of a read entity (`suffix`: `start`…).
    pub(super) fn alias(&mut self, alias: &str, entity: &str, suffix: &'static str) {
        self.aliases
            .entry(alias.to_owned())
            .and_modify(|a| *a = None)
            .or_insert_with(|| Some((entity.to_owned(), suffix)));
    }

    /// Records a skipped entity.
    pub(super) fn add_skipped(&mut self, id: &str, reason: &str) {
        self.skipped.insert(id.to_owned(), reason.to_owned());
    }

    /// Resolves a reference string: `<entity id>` (the entity), `<entity id>.start`, `.end`,
    /// `.center` (its named points), or a point id an entity declares.
    pub(super) fn resolve(&self, value: &str) -> Target {
        if let Some(&(shape, _)) = self.read.get(value) {
            return Target::Found(Ref::whole(value), shape);
        }
        if let Some((base, suffix)) = value.rsplit_once('.')
            && let Some(&(shape, _)) = self.read.get(base)
        {
            return self.part(base, shape, suffix, value);
        }
        if let Some(Some((base, suffix))) = self.aliases.get(value)
            && let Some(&(shape, _)) = self.read.get(base)
        {
            return self.part(base, shape, suffix, value);
        }
        // A part of a skipped entity (`<text id>.sketch_text.baseline`, `<spline id>.3.internal`).
        let mut prefix = value;
        loop {
            if let Some(reason) = self.skipped.get(prefix) {
                // The kind of entity: the reason up to its first parenthesis or colon.
                let what = reason.split([':', '(']).next().unwrap_or(reason).trim();
                return Target::Unusable(if prefix == value {
                    format!("references `{value}`, a skipped entity ({what})")
                } else {
                    format!(
                        "references `{value}`, a part of the skipped entity `{prefix}` ({what})"
                    )
                });
            }
            match prefix.rsplit_once('.') {
                Some((head, _)) => prefix = head,
                None => break,
            }
        }
        if value.is_empty() {
            return Target::Unusable("an empty entity reference".into());
        }
        Target::Unusable(format!("references the unknown entity `{value}`"))
    }

    fn part(&self, base: &str, shape: Shape, suffix: &str, value: &str) -> Target {
        let part = match (shape, suffix) {
            (Shape::ZeroLine, "start" | "end") => {
                return Target::Found(Ref::whole(format!("{base}#{suffix}")), Shape::Point);
            }
            (Shape::Segment | Shape::Spline, "start") => Part::Start,
            (Shape::Segment | Shape::Spline, "end") => Part::End,
            // An interpolated spline's end derivatives: the legs of its control polygon.
            (Shape::Spline, "startDerivative" | "endDerivative") => {
                let part =
                    if suffix == "startDerivative" { Part::StartTangent } else { Part::EndTangent };
                return Target::Found(Ref::part(base, part), Shape::Segment);
            }
            (
                Shape::Circle | Shape::Arc { .. } | Shape::Ellipse | Shape::EllipticalArc { .. },
                "center",
            ) => Part::Center,
            (Shape::Arc { swapped } | Shape::EllipticalArc { swapped }, "start") => {
                if swapped {
                    Part::End
                } else {
                    Part::Start
                }
            }
            (Shape::Arc { swapped } | Shape::EllipticalArc { swapped }, "end") => {
                if swapped {
                    Part::Start
                } else {
                    Part::End
                }
            }
            _ => {
                return Target::Unusable(format!(
                    "references `{value}`: the entity `{base}` has no point `{suffix}`"
                ));
            }
        };
        Target::Found(Ref::part(base, part), Shape::Point)
    }

    /// The index in the sketch's entities of a read entity.
    pub(super) fn index(&self, id: &str) -> Option<usize> {
        self.read.get(id).map(|&(_, i)| i)
    }
}
