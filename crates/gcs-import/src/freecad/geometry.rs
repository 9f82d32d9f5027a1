//! FreeCAD sketch geometry (`Part::Geom*` elements of a `GeometryList`) to IR entities.
//!
//! Each element gives an [`ir::Geometry`] (exact where the file writes the number: centres,
//! radii, segment end points, poles; computed from floats where FreeCAD stores angles: arc and
//! elliptical-arc end points, an ellipse's major vertex when its axis is not along x) and a float
//! [`Draw`] of it, which the constraint mapping uses for its few decisions that depend on the
//! drawing (which end of a helper line is the positive major vertex of an ellipse).

use roxmltree::Node;

use crate::ir::{self, Number};

/// A 2D position as floats.
pub(crate) type P2 = [f64; 2];

/// A float drawing of a geometry, in sketch coordinates.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Draw {
    Point(P2),
    Segment(P2, P2),
    /// An infinite line through two points (the sketch axes, `Part::GeomLine`).
    Line(P2, P2),
    Circle {
        c: P2,
    },
    Arc {
        c: P2,
    },
    /// An ellipse (or an arc of one): centre, unit major direction, radii.
    Ellipse {
        c: P2,
        u: P2,
        a: f64,
        b: f64,
        arc: bool,
    },
    BSpline {
        poles: usize,
    },
}

impl Draw {
    /// A word for messages.
    pub(crate) fn noun(&self) -> &'static str {
        match self {
            Draw::Point(_) => "a point",
            Draw::Segment(..) => "a line segment",
            Draw::Line(..) => "a line",
            Draw::Circle { .. } => "a circle",
            Draw::Arc { .. } => "an arc",
            Draw::Ellipse { arc: false, .. } => "an ellipse",
            Draw::Ellipse { arc: true, .. } => "an arc of an ellipse",
            Draw::BSpline { .. } => "a B-spline",
        }
    }

    pub(crate) fn is_line(&self) -> bool {
        matches!(self, Draw::Segment(..) | Draw::Line(..))
    }

    pub(crate) fn is_circular(&self) -> bool {
        matches!(self, Draw::Circle { .. } | Draw::Arc { .. })
    }

    pub(crate) fn is_curve(&self) -> bool {
        !matches!(self, Draw::Point(_))
    }
}

/// A number as written: its float and, when finite, its exact value.
#[derive(Clone, Debug)]
pub(crate) struct Num {
    pub(crate) f: f64,
    pub(crate) exact: Option<Number>,
}

/// Parses a float as C++ streams write it (`nan`, `inf` included), white space around it
/// ignored.
pub(crate) fn parse_float(t: &str) -> Option<f64> {
    parse_float_token(t.trim())
}

/// Parses one token of a float as C++ streams write it (`nan`, `inf` included): the numbers of
/// the XML attributes and of the BRep shape data.
pub(crate) fn parse_float_token(t: &str) -> Option<f64> {
    if let Ok(x) = t.parse::<f64>() {
        return Some(x);
    }
    match t.to_ascii_lowercase().as_str() {
        "nan" | "-nan" | "+nan" | "nan(ind)" | "-nan(ind)" => Some(f64::NAN),
        "inf" | "+inf" | "infinity" => Some(f64::INFINITY),
        "-inf" | "-infinity" => Some(f64::NEG_INFINITY),
        _ => None,
    }
}

/// The numeric attribute `name` of `node`: an error message when it is missing or not a number.
pub(crate) fn num_attr(node: Node<'_, '_>, name: &str) -> Result<Num, String> {
    let text = node
        .attribute(name)
        .ok_or_else(|| format!("<{}> has no attribute {name}", node.tag_name().name()))?;
    num_text(node, name, text)
}

/// Like [`num_attr`], `default` when the attribute is absent.
pub(crate) fn num_attr_or(node: Node<'_, '_>, name: &str, default: f64) -> Result<Num, String> {
    match node.attribute(name) {
        None => Ok(Num { f: default, exact: Number::from_f64(default) }),
        Some(text) => num_text(node, name, text),
    }
}

fn num_text(node: Node<'_, '_>, name: &str, text: &str) -> Result<Num, String> {
    let f = parse_float(text).ok_or_else(|| {
        format!("<{}> attribute {name}=\"{text}\" is not a number", node.tag_name().name())
    })?;
    let exact = if f.is_finite() {
        Number::parse(text.trim()).or_else(|| Number::from_f64(f))
    } else {
        None
    };
    Ok(Num { f, exact })
}

/// An integer attribute (error message when missing or malformed).
pub(crate) fn int_attr(node: Node<'_, '_>, name: &str) -> Result<i64, String> {
    let text = node
        .attribute(name)
        .ok_or_else(|| format!("<{}> has no attribute {name}", node.tag_name().name()))?;
    text.trim().parse::<i64>().map_err(|_| {
        format!("<{}> attribute {name}=\"{text}\" is not an integer", node.tag_name().name())
    })
}

/// What a `<Geometry>` element becomes.
#[derive(Debug)]
pub(crate) enum GeoRead {
    /// An entity's geometry, its drawing, and whether it is construction geometry.
    Entity { geometry: ir::Geometry, draw: Draw, construction: bool },
    /// Not expressible: why.
    Skip(String),
}

fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.is_element() && c.tag_name().name() == tag)
}

/// Whether a `<Geometry>` element is construction geometry: the legacy `<Construction
/// value="1"/>` or the construction bit (bit 1) of a `Sketcher::SketchGeometryExtension`'s
/// `geometryModeFlags` (a bitset written most significant bit first).
fn is_construction(node: Node<'_, '_>) -> bool {
    let legacy = node
        .children()
        .filter(|c| c.is_element() && c.tag_name().name() == "Construction")
        .any(|c| c.attribute("value").is_some_and(|v| v.trim() != "0" && v.trim() != "false"));
    let flags = node
        .descendants()
        .filter(|c| c.is_element() && c.tag_name().name() == "GeoExtension")
        .filter_map(|c| c.attribute("geometryModeFlags"))
        .any(|f| f.len() >= 2 && f.as_bytes()[f.len() - 2] == b'1');
    legacy || flags
}

/// A conic's frame: the unit x axis (in its plane, at `AngleXU` from OpenCASCADE's reference
/// direction for the normal) and the unit normal.
struct Frame {
    x: [f64; 3],
    y: [f64; 3],
    n: [f64; 3],
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (n.is_finite() && n > 1e-300).then(|| [v[0] / n, v[1] / n, v[2] / n])
}

/// OpenCASCADE's default x direction of an axis system with main direction `n`
/// (`gp_Ax2(P, V)`): perpendicular to `n`, with a zero in the coordinate where `n` is smallest.
pub(crate) fn reference_x(n: [f64; 3]) -> [f64; 3] {
    let (a, b, c) = (n[0], n[1], n[2]);
    let (aa, ba, ca) = (a.abs(), b.abs(), c.abs());
    let v = if ba <= aa && ba <= ca {
        if aa > ca { [-c, 0.0, a] } else { [c, 0.0, -a] }
    } else if aa <= ba && aa <= ca {
        if ba > ca { [0.0, -c, b] } else { [0.0, c, -b] }
    } else if aa > ba {
        [-b, a, 0.0]
    } else {
        [b, -a, 0.0]
    };
    unit(v).unwrap_or([1.0, 0.0, 0.0])
}

fn frame(n: [f64; 3], angle_xu: f64) -> Option<Frame> {
    let n = unit(n)?;
    let r = reference_x(n);
    let s = cross(n, r);
    let (sin, cos) = angle_xu.sin_cos();
    let x = [r[0] * cos + s[0] * sin, r[1] * cos + s[1] * sin, r[2] * cos + s[2] * sin];
    let y = cross(n, x);
    Some(Frame { x, y, n })
}

/// Reads a conic's placement: centre, frame. `Err(reason)` to skip it.
/// A conic's centre, frame, and whether its major axis is exactly along +x in the +z plane.
type Placed = ([Num; 2], Frame, bool);

fn conic(data: Node<'_, '_>) -> Result<Result<Placed, String>, String> {
    let cx = num_attr(data, "CenterX")?;
    let cy = num_attr(data, "CenterY")?;
    let n =
        [num_attr(data, "NormalX")?.f, num_attr(data, "NormalY")?.f, num_attr(data, "NormalZ")?.f];
    let angle = num_attr_or(data, "AngleXU", 0.0)?;
    let Some(fr) = frame(n, angle.f) else {
        return Ok(Err("its normal is zero or not finite".into()));
    };
    if fr.n[2].abs() < 1.0 - 1e-9 {
        return Ok(Err("it is not in the sketch plane (its normal is not along z)".into()));
    }
    if !cx.f.is_finite() || !cy.f.is_finite() || !angle.f.is_finite() {
        return Ok(Err("a coordinate is not finite".into()));
    }
    let axis_aligned = angle.f == 0.0 && n == [0.0, 0.0, 1.0];
    Ok(Ok(([cx, cy], fr, axis_aligned)))
}

fn exact(n: &Num) -> Option<Number> {
    if n.f.is_finite() { n.exact.clone() } else { None }
}

fn coords(p: &[Num; 2]) -> Option<ir::Coords> {
    Some(vec![exact(&p[0])?, exact(&p[1])?])
}

fn float_coords(p: P2) -> Option<ir::Coords> {
    Some(vec![Number::from_f64(p[0])?, Number::from_f64(p[1])?])
}

fn on_conic(c: P2, fr: &Frame, a: f64, b: f64, t: f64) -> P2 {
    let (s, co) = t.sin_cos();
    [c[0] + a * co * fr.x[0] + b * s * fr.y[0], c[1] + a * co * fr.x[1] + b * s * fr.y[1]]
}

const NON_FINITE: &str = "a coordinate is not finite";

/// Reads one `<Geometry type="…">` element. `Err(message)` when it is malformed (a required
/// attribute missing or not a number).
pub(crate) fn read_geometry(node: Node<'_, '_>) -> Result<GeoRead, String> {
    let ty = node.attribute("type").ok_or("<Geometry> has no attribute type")?;
    let construction = is_construction(node);
    let data_tag = match ty {
        "Part::GeomPoint" => "GeomPoint",
        "Part::GeomLineSegment" => "LineSegment",
        "Part::GeomLine" => "Line",
        "Part::GeomCircle" => "Circle",
        "Part::GeomArcOfCircle" => "ArcOfCircle",
        "Part::GeomEllipse" => "Ellipse",
        "Part::GeomArcOfEllipse" => "ArcOfEllipse",
        "Part::GeomBSplineCurve" => "BSplineCurve",
        "Part::GeomHyperbola" | "Part::GeomArcOfHyperbola" => {
            return Ok(GeoRead::Skip("a hyperbola (arc): the IR has no hyperbolas".into()));
        }
        "Part::GeomParabola" | "Part::GeomArcOfParabola" => {
            return Ok(GeoRead::Skip("a parabola (arc): the IR has no parabolas".into()));
        }
        other => return Ok(GeoRead::Skip(format!("geometry type {other} is not supported"))),
    };
    let data = child(node, data_tag)
        .ok_or_else(|| format!("<Geometry type=\"{ty}\"> has no <{data_tag}> element"))?;
    let entity = |geometry, draw| Ok(GeoRead::Entity { geometry, draw, construction });
    match data_tag {
        "GeomPoint" => {
            let p = [num_attr(data, "X")?, num_attr(data, "Y")?];
            let Some(at) = coords(&p) else { return Ok(GeoRead::Skip(NON_FINITE.into())) };
            entity(ir::Geometry::Point { at }, Draw::Point([p[0].f, p[1].f]))
        }
        "LineSegment" => {
            let s = [num_attr(data, "StartX")?, num_attr(data, "StartY")?];
            let e = [num_attr(data, "EndX")?, num_attr(data, "EndY")?];
            let (Some(start), Some(end)) = (coords(&s), coords(&e)) else {
                return Ok(GeoRead::Skip(NON_FINITE.into()));
            };
            entity(
                ir::Geometry::Segment { start, end },
                Draw::Segment([s[0].f, s[1].f], [e[0].f, e[1].f]),
            )
        }
        "Line" => {
            let p = [num_attr(data, "PosX")?, num_attr(data, "PosY")?];
            let d = [num_attr(data, "DirX")?, num_attr(data, "DirY")?];
            let (Some(a), Some(dd)) = (coords(&p), coords(&d)) else {
                return Ok(GeoRead::Skip(NON_FINITE.into()));
            };
            if d[0].f == 0.0 && d[1].f == 0.0 {
                return Ok(GeoRead::Skip(
                    "a line whose direction is zero in the sketch plane".into(),
                ));
            }
            let b = vec![Number(&a[0].0 + &dd[0].0), Number(&a[1].0 + &dd[1].0)];
            let pa = [p[0].f, p[1].f];
            entity(ir::Geometry::Line { a, b }, Draw::Line(pa, [pa[0] + d[0].f, pa[1] + d[1].f]))
        }
        "Circle" | "ArcOfCircle" => {
            let (c, fr, _) = match conic(data)? {
                Ok(v) => v,
                Err(reason) => return Ok(GeoRead::Skip(reason)),
            };
            let r = num_attr(data, "Radius")?;
            let (Some(center), Some(radius)) = (coords(&c), exact(&r)) else {
                return Ok(GeoRead::Skip(NON_FINITE.into()));
            };
            if r.f.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return Ok(GeoRead::Skip(format!("its radius {} is not positive", r.f)));
            }
            let cf = [c[0].f, c[1].f];
            if data_tag == "Circle" {
                return entity(ir::Geometry::Circle { center, radius }, Draw::Circle { c: cf });
            }
            let t0 = num_attr(data, "StartAngle")?.f;
            let t1 = num_attr(data, "EndAngle")?.f;
            let mut s = on_conic(cf, &fr, r.f, r.f, t0);
            let mut e = on_conic(cf, &fr, r.f, r.f, t1);
            if fr.n[2] < 0.0 {
                // A reversed (clockwise) arc: FreeCAD reads it counter-clockwise from its end.
                std::mem::swap(&mut s, &mut e);
            }
            let (Some(start), Some(end)) = (float_coords(s), float_coords(e)) else {
                return Ok(GeoRead::Skip(NON_FINITE.into()));
            };
            entity(ir::Geometry::Arc { center, start, end }, Draw::Arc { c: cf })
        }
        "Ellipse" | "ArcOfEllipse" => {
            let (c, fr, axis_aligned) = match conic(data)? {
                Ok(v) => v,
                Err(reason) => return Ok(GeoRead::Skip(reason)),
            };
            let a = num_attr(data, "MajorRadius")?;
            let b = num_attr(data, "MinorRadius")?;
            let (Some(center), Some(ea), Some(minor_radius)) = (coords(&c), exact(&a), exact(&b))
            else {
                return Ok(GeoRead::Skip(NON_FINITE.into()));
            };
            let valid = b.f > 0.0 && a.f >= b.f;
            if !valid {
                return Ok(GeoRead::Skip(format!(
                    "its radii {} and {} are not major ≥ minor > 0",
                    a.f, b.f
                )));
            }
            let cf = [c[0].f, c[1].f];
            let u = [fr.x[0], fr.x[1]];
            let major = if axis_aligned {
                vec![Number(&center[0].0 + &ea.0), center[1].clone()]
            } else {
                let Some(m) = float_coords([cf[0] + a.f * u[0], cf[1] + a.f * u[1]]) else {
                    return Ok(GeoRead::Skip(NON_FINITE.into()));
                };
                m
            };
            if data_tag == "Ellipse" {
                let draw = Draw::Ellipse { c: cf, u, a: a.f, b: b.f, arc: false };
                return entity(ir::Geometry::Ellipse { center, major, minor_radius }, draw);
            }
            let t0 = num_attr(data, "StartAngle")?.f;
            let t1 = num_attr(data, "EndAngle")?.f;
            let mut s = on_conic(cf, &fr, a.f, b.f, t0);
            let mut e = on_conic(cf, &fr, a.f, b.f, t1);
            if fr.n[2] < 0.0 {
                std::mem::swap(&mut s, &mut e);
            }
            let (Some(start), Some(end)) = (float_coords(s), float_coords(e)) else {
                return Ok(GeoRead::Skip(NON_FINITE.into()));
            };
            let draw = Draw::Ellipse { c: cf, u, a: a.f, b: b.f, arc: true };
            entity(ir::Geometry::EllipticalArc { center, major, minor_radius, start, end }, draw)
        }
        _ => read_bspline(data, construction),
    }
}

fn read_bspline(data: Node<'_, '_>, construction: bool) -> Result<GeoRead, String> {
    let degree = int_attr(data, "Degree")?;
    let periodic = match data.attribute("IsPeriodic").map(str::trim) {
        None | Some("0") | Some("false") => false,
        Some(_) => true,
    };
    let mut poles = Vec::new();
    let mut weights = Vec::new();
    let mut knots = Vec::new();
    for c in data.children().filter(|c| c.is_element()) {
        match c.tag_name().name() {
            "Pole" => {
                let p = [num_attr(c, "X")?, num_attr(c, "Y")?];
                let w = num_attr_or(c, "Weight", 1.0)?;
                let (Some(at), Some(w)) = (coords(&p), exact(&w)) else {
                    return Ok(GeoRead::Skip(NON_FINITE.into()));
                };
                poles.push(at);
                weights.push(w);
            }
            "Knot" => {
                let v = num_attr(c, "Value")?;
                let m = int_attr(c, "Mult")?;
                let Some(v) = exact(&v) else { return Ok(GeoRead::Skip(NON_FINITE.into())) };
                let Ok(m) = u32::try_from(m) else {
                    return Ok(GeoRead::Skip(format!("a knot multiplicity {m} is out of range")));
                };
                if m == 0 {
                    return Ok(GeoRead::Skip("a knot multiplicity is 0".into()));
                }
                knots.push((v, m));
            }
            _ => {}
        }
    }
    let Ok(degree) = u32::try_from(degree) else {
        return Ok(GeoRead::Skip(format!("B-spline degree {degree} is out of range")));
    };
    if degree == 0 {
        return Ok(GeoRead::Skip("B-spline of degree 0".into()));
    }
    if poles.len() < 2 || knots.len() < 2 {
        return Ok(GeoRead::Skip(format!(
            "B-spline with {} poles and {} knots is degenerate",
            poles.len(),
            knots.len()
        )));
    }
    let one = Number::from_i64(1);
    let weights = if weights.iter().all(|w| *w == one) { None } else { Some(weights) };
    let draw = Draw::BSpline { poles: poles.len() };
    Ok(GeoRead::Entity {
        geometry: ir::Geometry::BSpline { degree, poles, weights, knots, periodic },
        draw,
        construction,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_x_of_z_is_x() {
        assert_eq!(reference_x([0.0, 0.0, 1.0]), [1.0, 0.0, 0.0]);
        assert_eq!(reference_x([0.0, 0.0, -1.0]), [-1.0, 0.0, 0.0]);
    }

    #[test]
    fn reversed_frame_runs_clockwise() {
        let f = frame([0.0, 0.0, -1.0], 0.0).unwrap();
        // From (-1, 0) at t = 0 to (0, 1) at t = π/2: clockwise seen from +z.
        let p0 = on_conic([0.0, 0.0], &f, 1.0, 1.0, 0.0);
        let p1 = on_conic([0.0, 0.0], &f, 1.0, 1.0, std::f64::consts::FRAC_PI_2);
        assert!((p0[0] + 1.0).abs() < 1e-12 && p0[1].abs() < 1e-12, "{p0:?}");
        assert!(p1[0].abs() < 1e-12 && (p1[1] - 1.0).abs() < 1e-12, "{p1:?}");
    }
}
