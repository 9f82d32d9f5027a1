//! FreeCAD sketch constraints (`<Constrain>` elements) to IR constraints.
//!
//! The meaning of each type code and of its `First`/`FirstPos`/… references follows FreeCAD's
//! `Sketch::addConstraint` (which solver constraints a sketch constraint becomes); see the
//! module documentation of [`super`] for the table. Where FreeCAD's own solver ignores a
//! constraint (a point reference that is not a point, a combination of curves it does not
//! support), the constraint is skipped with that reason.

use roxmltree::Node;

use super::geometry::{Draw, Num, P2, int_attr, num_attr_or};
use crate::ir::{self, Kind, Number, Part, Ref};

/// FreeCAD's "no geometry" GeoId.
pub(crate) const GEO_UNDEF: i32 = -2000;

/// One geometry slot of the table.
#[derive(Clone, Debug)]
pub(crate) enum Slot {
    /// An entity: its IR id and drawing.
    Geo { id: String, draw: Draw },
    /// Skipped (its id and why).
    Skipped { id: String, reason: String },
}

/// The geometry a sketch's constraints can address, by FreeCAD GeoId: `0..` the sketch's own
/// geometry, `-1`/`-2` the H and V axes (and `-1`/`-2` at position 1 the root point), `-3 - k`
/// the external geometry `k`.
#[derive(Debug, Default)]
pub(crate) struct GeoTable {
    pub(crate) normal: Vec<Slot>,
    pub(crate) external: Vec<Slot>,
    /// Why external geometry beyond `external` cannot be addressed.
    pub(crate) external_beyond: Option<String>,
    /// Which of H_Axis, V_Axis, RootPoint the constraints used.
    pub(crate) used_axes: [bool; 3],
    /// The FreeCAD version that wrote the document, when it is older than 1.0 (its sketcher
    /// ignores distances to circles and arc lengths, which came with 1.0 (0.22 development)).
    pub(crate) before_1_0: Option<String>,
}

pub(crate) const H_AXIS: &str = "H_Axis";
pub(crate) const V_AXIS: &str = "V_Axis";
pub(crate) const ROOT_POINT: &str = "RootPoint";

/// The IR id of external geometry `k` (0-based): `ExternalEdge<k+1>`, FreeCAD's name for GeoId
/// `-3 - k`.
pub(crate) fn external_id(k: usize) -> String {
    format!("ExternalEdge{}", k + 1)
}

/// A point reference's part: FreeCAD's `PointPos` (1 start, 2 end, 3 mid/centre).
fn pos_name(pos: i32) -> &'static str {
    match pos {
        0 => "the curve itself (position 0)",
        1 => "its start (position 1)",
        2 => "its end (position 2)",
        3 => "its centre (position 3)",
        _ => "an unknown position",
    }
}

impl GeoTable {
    /// The slot of a GeoId.
    fn slot(&mut self, geo: i32) -> Result<(String, Draw), String> {
        let s = match geo {
            -1 => {
                self.used_axes[0] = true;
                return Ok((H_AXIS.into(), Draw::Line([0.0, 0.0], [1.0, 0.0])));
            }
            -2 => {
                self.used_axes[1] = true;
                return Ok((V_AXIS.into(), Draw::Line([0.0, 0.0], [0.0, 1.0])));
            }
            GEO_UNDEF => return Err("a reference is missing (GeoId -2000, undefined)".into()),
            g if g >= 0 => {
                let i = g as usize;
                self.normal.get(i).ok_or_else(|| {
                    format!("references geometry {} (GeoId {g}), which does not exist (the sketch has {})", i + 1, self.normal.len())
                })?
            }
            g if g <= -3 => {
                let k = (-3 - i64::from(g)) as usize;
                match self.external.get(k) {
                    Some(s) => s,
                    None => {
                        return Err(match &self.external_beyond {
                            Some(why) => {
                                format!("references {} (GeoId {g}): {why}", external_id(k))
                            }
                            None => format!(
                                "references {} (GeoId {g}), which does not exist (the sketch has {} external geometries)",
                                external_id(k),
                                self.external.len()
                            ),
                        });
                    }
                }
            }
            g => return Err(format!("GeoId {g} is not a valid reference")),
        };
        match s {
            Slot::Geo { id, draw } => Ok((id.clone(), draw.clone())),
            Slot::Skipped { id, reason } => {
                Err(format!("references {id}, which is skipped ({reason})"))
            }
        }
    }

    /// `Err` when the document is older than FreeCAD 1.0, whose solver ignores `what`.
    fn older_than_1_0(&self, what: &str) -> Result<(), String> {
        match &self.before_1_0 {
            Some(version) => Err(format!(
                "{what}: FreeCAD before 1.0 ignores it, and this document was written by FreeCAD {version}"
            )),
            None => Ok(()),
        }
    }

    /// A point: `(GeoId, PointPos)`.
    fn point(&mut self, geo: i32, pos: i32) -> Result<Ref, String> {
        if matches!(geo, -1 | -2) && pos == 1 {
            self.used_axes[2] = true;
            return Ok(Ref::whole(ROOT_POINT));
        }
        let (id, draw) = self.slot(geo)?;
        let has_ends = matches!(
            draw,
            Draw::Segment(..)
                | Draw::Arc { .. }
                | Draw::Ellipse { arc: true, .. }
                | Draw::BSpline { .. }
        );
        let has_centre =
            matches!(draw, Draw::Circle { .. } | Draw::Arc { .. } | Draw::Ellipse { .. });
        match pos {
            1..=3 if matches!(draw, Draw::Point(_)) => Ok(Ref::whole(id)),
            1 if has_ends => Ok(Ref::part(id, Part::Start)),
            2 if has_ends => Ok(Ref::part(id, Part::End)),
            3 if has_centre => Ok(Ref::part(id, Part::Center)),
            _ => Err(format!(
                "refers to {} of {id}, {}, which is not a point FreeCAD's solver knows: it ignores the constraint",
                pos_name(pos),
                draw.noun()
            )),
        }
    }

    /// A curve: `(GeoId, 0)`.
    fn curve(&mut self, geo: i32, pos: i32) -> Result<(Ref, Draw), String> {
        let (id, draw) = self.slot(geo)?;
        if pos != 0 {
            return Err(format!("refers to {} of {id} where a curve is needed", pos_name(pos)));
        }
        if !draw.is_curve() {
            return Err(format!(
                "refers to {id}, a point, where FreeCAD needs a curve: its solver ignores the constraint"
            ));
        }
        Ok((Ref::whole(id), draw))
    }

    fn line(&mut self, geo: i32, pos: i32) -> Result<(Ref, Draw), String> {
        let (r, d) = self.curve(geo, pos)?;
        if !d.is_line() {
            return Err(format!(
                "refers to {}, {}, where FreeCAD needs a line",
                r.entity,
                d.noun()
            ));
        }
        Ok((r, d))
    }

    /// An end point of a curve (position 1 or 2 of a curve that has ends).
    fn end_point(&mut self, geo: i32, pos: i32) -> Result<(Ref, Draw), String> {
        let (id, draw) = self.slot(geo)?;
        if !(matches!(pos, 1 | 2)
            && matches!(
                draw,
                Draw::Segment(..)
                    | Draw::Arc { .. }
                    | Draw::Ellipse { arc: true, .. }
                    | Draw::BSpline { .. }
            ))
        {
            return Err(format!(
                "refers to {} of {id}, {}, where an end point of a curve is needed",
                pos_name(pos),
                draw.noun()
            ));
        }
        Ok((self.point(geo, pos)?, draw))
    }
}

/// A `<Constrain>` element's attributes.
#[derive(Debug)]
pub(crate) struct Raw {
    /// The type code, or the text when it is not an integer.
    pub(crate) type_code: Result<i64, String>,
    pub(crate) value: Num,
    /// `(GeoId, PointPos)` of First, Second, Third.
    pub(crate) el: [(i32, i32); 3],
    /// Elements beyond the third (newer files' `ElementIds`), when any is defined.
    pub(crate) extra: usize,
    pub(crate) alignment_type: i64,
    pub(crate) alignment_index: i64,
    pub(crate) driving: bool,
    pub(crate) active: bool,
}

fn i32_attr(node: Node<'_, '_>, name: &str, default: i32) -> Result<i32, String> {
    if node.attribute(name).is_none() {
        return Ok(default);
    }
    let v = int_attr(node, name)?;
    i32::try_from(v).map_err(|_| format!("<Constrain> attribute {name}={v} is out of range"))
}

fn bool_attr(node: Node<'_, '_>, name: &str, default: bool) -> Result<bool, String> {
    match node.attribute(name).map(str::trim) {
        None => Ok(default),
        Some("1") | Some("true") => Ok(true),
        Some("0") | Some("false") => Ok(false),
        Some(other) => Err(format!("<Constrain> attribute {name}=\"{other}\" is not a boolean")),
    }
}

/// Reads a `<Constrain>` element (`Err(message)` when malformed).
pub(crate) fn read_raw(node: Node<'_, '_>) -> Result<Raw, String> {
    let type_text = node.attribute("Type").ok_or("<Constrain> has no attribute Type")?;
    let type_code = type_text.trim().parse::<i64>().map_err(|_| type_text.to_owned());
    let value = num_attr_or(node, "Value", 0.0)?;
    // Newer files (FreeCAD 1.1) also write all elements as ElementIds/ElementPositions; the
    // First/Second/Third attributes take precedence for the first three.
    let mut el = [(GEO_UNDEF, 0); 3];
    let mut extra = 0;
    if let (Some(ids), Some(pos)) =
        (node.attribute("ElementIds"), node.attribute("ElementPositions"))
    {
        let ids: Vec<&str> = ids.split_ascii_whitespace().collect();
        let pos: Vec<&str> = pos.split_ascii_whitespace().collect();
        if ids.len() != pos.len() {
            return Err(format!(
                "<Constrain> has {} ElementIds but {} ElementPositions",
                ids.len(),
                pos.len()
            ));
        }
        for (i, (g, p)) in ids.iter().zip(&pos).enumerate() {
            let g: i32 = g
                .parse()
                .map_err(|_| format!("<Constrain> ElementIds entry '{g}' is not an integer"))?;
            let p: i32 = p.parse().map_err(|_| {
                format!("<Constrain> ElementPositions entry '{p}' is not an integer")
            })?;
            if i < 3 {
                el[i] = (g, p);
            } else if g != GEO_UNDEF {
                extra += 1;
            }
        }
    }
    for (i, (g, p)) in
        [("First", "FirstPos"), ("Second", "SecondPos"), ("Third", "ThirdPos")].iter().enumerate()
    {
        if node.attribute(*g).is_some() {
            el[i] = (i32_attr(node, g, GEO_UNDEF)?, i32_attr(node, p, 0)?);
        }
    }
    let alignment_type = if node.attribute("InternalAlignmentType").is_some() {
        int_attr(node, "InternalAlignmentType")?
    } else {
        0
    };
    let alignment_index = if node.attribute("InternalAlignmentIndex").is_some() {
        int_attr(node, "InternalAlignmentIndex")?
    } else {
        -1
    };
    Ok(Raw {
        type_code,
        value,
        el,
        extra,
        alignment_type,
        alignment_index,
        driving: bool_attr(node, "IsDriving", true)?,
        active: bool_attr(node, "IsActive", true)?,
    })
}

/// FreeCAD's type names, by code.
pub(crate) fn type_name(code: i64) -> &'static str {
    match code {
        0 => "None",
        1 => "Coincident",
        2 => "Horizontal",
        3 => "Vertical",
        4 => "Parallel",
        5 => "Tangent",
        6 => "Distance",
        7 => "DistanceX",
        8 => "DistanceY",
        9 => "Angle",
        10 => "Perpendicular",
        11 => "Radius",
        12 => "Equal",
        13 => "PointOnObject",
        14 => "Symmetric",
        15 => "InternalAlignment",
        16 => "SnellsLaw",
        17 => "Block",
        18 => "Diameter",
        19 => "Weight",
        _ => "unknown",
    }
}

/// Radians to degrees, rounded to 10⁻⁹° when that is within 10⁻¹² (relative) of the float: the
/// degrees a user typed (30°) are recovered from the radians FreeCAD stored (0.5235987755982988).
pub(crate) fn degrees(rad: f64) -> Option<Number> {
    let d = rad.to_degrees();
    if !d.is_finite() {
        return None;
    }
    let rounded = format!("{d:.9}");
    if let Ok(r) = rounded.parse::<f64>()
        && (r - d).abs() <= 1e-12 * d.abs().max(1.0)
    {
        return Number::parse(&rounded);
    }
    Number::from_f64(d)
}

/// The result of mapping one constraint.
#[derive(Debug, Default)]
pub(crate) struct Mapped {
    pub(crate) constraints: Vec<ir::Constraint>,
    /// A part of the constraint that could not be expressed although the rest was.
    pub(crate) partial: Option<String>,
}

struct Out<'a> {
    id: &'a str,
    driving: bool,
    m: Mapped,
}

impl Out<'_> {
    fn push(&mut self, suffix: &str, kind: Kind, refs: Vec<Ref>, value: Option<Number>) {
        let id =
            if suffix.is_empty() { self.id.to_owned() } else { format!("{}/{suffix}", self.id) };
        self.m.constraints.push(ir::Constraint { id, kind, refs, value, driving: self.driving });
    }
}

/// Maps a constraint to IR constraints (`Err(reason)`: skipped).
pub(crate) fn map(raw: &Raw, id: &str, t: &mut GeoTable) -> Result<Mapped, String> {
    if !raw.active {
        return Err("inactive".into());
    }
    let code = match &raw.type_code {
        Ok(c) => *c,
        Err(text) => return Err(format!("constraint type \"{text}\" is not a FreeCAD type code")),
    };
    if raw.extra > 0 {
        return Err(format!(
            "a {} constraint with more than three elements is not understood",
            type_name(code)
        ));
    }
    let mut o = Out { id, driving: raw.driving, m: Mapped::default() };
    let [(f, fp), (s, sp), (th, tp)] = raw.el;
    let undef = |g: i32| g == GEO_UNDEF;
    let length = || -> Result<Number, String> {
        if !raw.value.f.is_finite() {
            return Err(format!("its value {} is not finite", raw.value.f));
        }
        raw.value.exact.clone().ok_or_else(|| "its value is not a number".into())
    };
    let angle = |rad: f64| degrees(rad).ok_or_else(|| format!("its value {rad} is not finite"));
    match code {
        1 => {
            let a = t.point(f, fp)?;
            let b = t.point(s, sp)?;
            o.push("", Kind::Coincident, vec![a, b], None);
        }
        2 | 3 => {
            let kind = if code == 2 { Kind::Horizontal } else { Kind::Vertical };
            if undef(s) {
                let (l, _) = t.line(f, fp)?;
                o.push("", kind, vec![l], None);
            } else {
                let a = t.point(f, fp)?;
                let b = t.point(s, sp)?;
                o.push("", kind, vec![a, b], None);
            }
        }
        4 => {
            let (a, _) = t.line(f, fp)?;
            let (b, _) = t.line(s, sp)?;
            o.push("", Kind::Parallel, vec![a, b], None);
        }
        5 | 10 => map_angle_like(code == 5, raw, t, &mut o)?,
        6 => {
            if sp != 0 {
                let a = t.point(f, fp)?;
                let b = t.point(s, sp)?;
                o.push("", Kind::Distance, vec![a, b], Some(length()?));
            } else if !undef(s) {
                if fp != 0 {
                    let a = t.point(f, fp)?;
                    let (c, d) = t.curve(s, sp)?;
                    if !(d.is_line() || d.is_circular()) {
                        return Err(format!(
                            "a distance from a point to {} has no IR equivalent",
                            d.noun()
                        ));
                    }
                    if d.is_circular() {
                        t.older_than_1_0("a distance from a point to a circle")?;
                    }
                    o.push("", Kind::Distance, vec![a, c], Some(length()?));
                } else {
                    let (a, da) = t.curve(f, fp)?;
                    let (b, db) = t.curve(s, sp)?;
                    if da.is_circular() && db.is_circular() {
                        t.older_than_1_0("a distance between circles")?;
                        o.push("", Kind::Distance, vec![a, b], Some(length()?));
                    } else {
                        return Err(format!(
                            "a distance between {} and {} has no IR equivalent",
                            da.noun(),
                            db.noun()
                        ));
                    }
                }
            } else if fp == 0 {
                let (a, d) = t.curve(f, fp)?;
                match d {
                    Draw::Segment(..) => o.push("", Kind::Length, vec![a], Some(length()?)),
                    Draw::Arc { .. } => {
                        t.older_than_1_0("an arc length")?;
                        o.push("", Kind::ArcLength, vec![a], Some(length()?));
                    }
                    other => {
                        return Err(format!(
                            "FreeCAD has no length of {}: its solver ignores it",
                            other.noun()
                        ));
                    }
                }
            } else {
                return Err(
                    "a distance with one point and nothing else: FreeCAD's solver ignores it"
                        .into(),
                );
            }
        }
        7 | 8 => {
            let kind = if code == 7 { Kind::DistanceX } else { Kind::DistanceY };
            if fp == 0 {
                let (l, d) = t.curve(f, fp)?;
                if !matches!(d, Draw::Segment(..)) {
                    return Err(format!(
                        "a horizontal or vertical length of {} has no meaning for FreeCAD",
                        d.noun()
                    ));
                }
                let id = l.entity;
                o.push(
                    "",
                    kind,
                    vec![Ref::part(id.clone(), Part::Start), Ref::part(id, Part::End)],
                    Some(length()?),
                );
            } else if undef(s) {
                let p = t.point(f, fp)?;
                t.used_axes[2] = true;
                o.push("", kind, vec![Ref::whole(ROOT_POINT), p], Some(length()?));
            } else if sp != 0 {
                let a = t.point(f, fp)?;
                let b = t.point(s, sp)?;
                o.push("", kind, vec![a, b], Some(length()?));
            } else {
                return Err(
                    "a point and a curve (position 0): FreeCAD's solver ignores this distance"
                        .into(),
                );
            }
        }
        9 => {
            if !undef(th) {
                return Err("an angle via a point (angle-via-point) has no IR equivalent".into());
            } else if sp != 0 {
                let (a, _) = t.line(f, 0)?;
                let (b, _) = t.line(s, 0)?;
                if !(matches!(fp, 1 | 2) && matches!(sp, 1 | 2)) {
                    return Err(
                        "an angle between lines from given ends needs end positions 1 or 2".into(),
                    );
                }
                // FreeCAD measures each line from the given end; the IR from start to end.
                let value = if (fp == 2) != (sp == 2) {
                    let mut deg = raw.value.f.to_degrees() + 180.0;
                    while deg > 180.0 {
                        deg -= 360.0;
                    }
                    while deg <= -180.0 {
                        deg += 360.0;
                    }
                    deg.to_radians()
                } else {
                    raw.value.f
                };
                o.push("", Kind::Angle, vec![a, b], Some(angle(value)?));
            } else if !undef(s) {
                let (a, _) = t.line(f, fp)?;
                let (b, _) = t.line(s, sp)?;
                o.push("", Kind::Angle, vec![a, b], Some(angle(raw.value.f)?));
            } else {
                let (a, d) = t.curve(f, fp)?;
                match d {
                    Draw::Segment(..) | Draw::Line(..) => {
                        o.push("", Kind::AngleToXAxis, vec![a], Some(angle(raw.value.f)?));
                    }
                    Draw::Arc { .. } => {
                        return Err("an arc's sweep angle has no IR equivalent".into());
                    }
                    other => {
                        return Err(format!(
                            "FreeCAD has no angle of {}: its solver ignores it",
                            other.noun()
                        ));
                    }
                }
            }
        }
        11 | 18 => {
            let (a, d) = t.curve(f, fp)?;
            if !d.is_circular() {
                return Err(format!(
                    "a radius or diameter of {}: FreeCAD's solver ignores it",
                    d.noun()
                ));
            }
            let kind = if code == 11 { Kind::Radius } else { Kind::Diameter };
            o.push("", kind, vec![a], Some(length()?));
        }
        12 => {
            let (a, da) = t.curve(f, fp)?;
            let (b, db) = t.curve(s, sp)?;
            let ok = (matches!(da, Draw::Segment(..)) && matches!(db, Draw::Segment(..)))
                || (da.is_circular() && db.is_circular());
            if ok {
                o.push("", Kind::Equal, vec![a, b], None);
            } else if matches!(da, Draw::Ellipse { .. }) && matches!(db, Draw::Ellipse { .. }) {
                return Err("equal ellipses (both radii) have no IR equivalent".into());
            } else {
                return Err(format!(
                    "FreeCAD has no equality between {} and {}: its solver ignores it",
                    da.noun(),
                    db.noun()
                ));
            }
        }
        13 => {
            let p = t.point(f, fp)?;
            let (c, _) = t.curve(s, sp)?;
            o.push("", Kind::PointOnObject, vec![p, c], None);
        }
        14 => {
            let a = t.point(f, fp)?;
            let b = t.point(s, sp)?;
            let c = if tp != 0 { t.point(th, tp)? } else { t.line(th, tp)?.0 };
            o.push("", Kind::Symmetric, vec![a, b, c], None);
        }
        15 => map_alignment(raw, t, &mut o)?,
        16 => return Err("Snell's law (refraction) has no IR equivalent".into()),
        17 => {
            let (id, _) = t.slot(f)?;
            o.push("", Kind::Fix, vec![Ref::whole(id)], None);
        }
        19 => {
            return Err(
                "a B-spline weight (the radius of a control-point circle) has no IR equivalent"
                    .into(),
            );
        }
        0 => return Err("constraint type 0 (None) means nothing".into()),
        other => return Err(format!("constraint type {other} is not known")),
    }
    Ok(o.m)
}

/// Tangent (5) and Perpendicular (10): simple, endpoint-to-endpoint, endpoint-to-curve, via a
/// point.
fn map_angle_like(
    tangent: bool,
    raw: &Raw,
    t: &mut GeoTable,
    o: &mut Out<'_>,
) -> Result<(), String> {
    let [(f, fp), (s, sp), (th, _)] = raw.el;
    let what = if tangent { "tangency" } else { "perpendicularity" };
    if th != GEO_UNDEF {
        return Err(format!("{what} via a point (angle-via-point) has no IR equivalent"));
    }
    if fp == 0 && sp == 0 {
        let (a, da) = t.curve(f, 0)?;
        let (b, db) = t.curve(s, 0)?;
        if tangent {
            if da.is_line() && db.is_line() {
                // FreeCAD puts both ends of the second line on the first: collinear.
                o.push("", Kind::Collinear, vec![a, b], None);
            } else if (da.is_line() && (db.is_circular() || matches!(db, Draw::Ellipse { .. })))
                || (db.is_line() && (da.is_circular() || matches!(da, Draw::Ellipse { .. })))
                || (da.is_circular() && db.is_circular())
            {
                o.push("", Kind::Tangent, vec![a, b], None);
            } else {
                return Err(format!(
                    "FreeCAD does not support simple tangency between {} and {}: its solver ignores it",
                    da.noun(),
                    db.noun()
                ));
            }
        } else if da.is_line() && db.is_line() {
            o.push("", Kind::Perpendicular, vec![a, b], None);
        } else if da.is_line() && db.is_circular() {
            // FreeCAD puts the centre on the line.
            o.push("", Kind::PointOnObject, vec![Ref::part(b.entity, Part::Center), a], None);
        } else if db.is_line() && da.is_circular() {
            o.push("", Kind::PointOnObject, vec![Ref::part(a.entity, Part::Center), b], None);
        } else {
            return Err(format!(
                "FreeCAD does not support simple perpendicularity between {} and {}: its solver ignores it",
                da.noun(),
                db.noun()
            ));
        }
        return Ok(());
    }
    if fp != 0 && sp != 0 {
        let (a, _) = t.end_point(f, fp)?;
        let (b, _) = t.end_point(s, sp)?;
        let kind = if tangent { Kind::TangentAtEnds } else { Kind::PerpendicularAtEnds };
        o.push("", kind, vec![a, b], None);
        return Ok(());
    }
    if sp != 0 {
        return Err(format!(
            "{what} with a point only on the second curve: FreeCAD's solver ignores it"
        ));
    }
    // Endpoint to curve: the end point lies on the second curve, and the curves meet there at
    // the angle.
    let (p, d1) = t.end_point(f, fp)?;
    let (c1, _) = t.curve(f, 0)?;
    let (c2, d2) = t.curve(s, 0)?;
    let unsupported = || {
        Err(format!(
            "endpoint-to-curve {what} between {} and {} has no exact IR equivalent",
            d1.noun(),
            d2.noun()
        ))
    };
    if tangent {
        if d1.is_line() && d2.is_line() {
            // A line's end on a line it is tangent to: the lines are one.
            o.push("", Kind::Collinear, vec![c1, c2], None);
        } else if (d1.is_line() || d1.is_circular()) && (d2.is_line() || d2.is_circular()) {
            // Lines and circles touch once where they are tangent: the end point on the
            // second curve and tangency are the same conditions.
            o.push("", Kind::PointOnObject, vec![p, c2.clone()], None);
            o.push("tangent", Kind::Tangent, vec![c1, c2], None);
        } else {
            return unsupported();
        }
    } else if d1.is_line() && d2.is_line() {
        o.push("", Kind::PointOnObject, vec![p, c2.clone()], None);
        o.push("perpendicular", Kind::Perpendicular, vec![c1, c2], None);
    } else if d1.is_line() && d2.is_circular() {
        // Perpendicular to a circle where it meets it: the line passes through the centre.
        o.push("", Kind::PointOnObject, vec![p, c2.clone()], None);
        o.push(
            "perpendicular",
            Kind::PointOnObject,
            vec![Ref::part(c2.entity, Part::Center), c1],
            None,
        );
    } else if d1.is_circular() && d2.is_line() {
        o.push("", Kind::PointOnObject, vec![p, c2.clone()], None);
        o.push(
            "perpendicular",
            Kind::PointOnObject,
            vec![Ref::part(c1.entity, Part::Center), c2],
            None,
        );
    } else {
        return unsupported();
    }
    Ok(())
}

fn dist2(a: P2, b: P2) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

/// InternalAlignment (15): the helper geometry of ellipses and B-splines.
fn map_alignment(raw: &Raw, t: &mut GeoTable, o: &mut Out<'_>) -> Result<(), String> {
    let [(f, fp), (s, _), _] = raw.el;
    match raw.alignment_type {
        1 | 2 => {
            let major = raw.alignment_type == 1;
            let (line, dl) = t.line(f, 0)?;
            let (ell, de) = t.curve(s, 0)?;
            let (Draw::Segment(p1, p2), Draw::Ellipse { c, u, a, b, .. }) = (&dl, &de) else {
                return Err(format!("an ellipse axis alignment of {} to {}", dl.noun(), de.noun()));
            };
            // FreeCAD ties the end nearer the positive vertex (centre + a·u for the major axis,
            // centre + b·v, v = u turned +90°, for the minor) to it, the other to the negative.
            let (dir, r, pos_part, neg_part) = if major {
                (*u, *a, Part::MajorEnd, Part::MajorStart)
            } else {
                ([-u[1], u[0]], *b, Part::MinorEnd, Part::MinorStart)
            };
            let positive = [c[0] + r * dir[0], c[1] + r * dir[1]];
            let (start_part, end_part) = if dist2(*p2, positive) < dist2(*p1, positive) {
                (neg_part, pos_part)
            } else {
                (pos_part, neg_part)
            };
            let lid = line.entity;
            let eid = ell.entity;
            o.push(
                "",
                Kind::Coincident,
                vec![Ref::part(lid.clone(), Part::Start), Ref::part(eid.clone(), start_part)],
                None,
            );
            o.push(
                "end",
                Kind::Coincident,
                vec![Ref::part(lid, Part::End), Ref::part(eid, end_part)],
                None,
            );
        }
        3 | 4 => {
            let p = t.point(f, fp)?;
            let (ell, de) = t.curve(s, 0)?;
            if !matches!(de, Draw::Ellipse { .. }) {
                return Err(format!("an ellipse focus alignment to {}", de.noun()));
            }
            let part = if raw.alignment_type == 3 { Part::Focus1 } else { Part::Focus2 };
            o.push("", Kind::Coincident, vec![p, Ref::part(ell.entity, part)], None);
        }
        9 => {
            let (sp, ds) = t.curve(s, 0)?;
            let Draw::BSpline { poles } = ds else {
                return Err(format!("a B-spline control point alignment to {}", ds.noun()));
            };
            let i = usize::try_from(raw.alignment_index).ok().filter(|i| *i < poles).ok_or_else(|| {
                format!("B-spline control point index {} is out of range (the spline has {poles} poles)", raw.alignment_index)
            })?;
            let (id, d) = t.slot(f)?;
            let at = match d {
                Draw::Circle { .. } => {
                    o.m.partial = Some(format!(
                        "B-spline control point alignment: the circle's centre is the pole {i} (mapped), but \
                         FreeCAD also ties its radius to the pole's weight, which the IR cannot express"
                    ));
                    Ref::part(id, Part::Center)
                }
                Draw::Point(_) => Ref::whole(id),
                other => {
                    return Err(format!("a B-spline control point alignment of {}", other.noun()));
                }
            };
            o.push("", Kind::Coincident, vec![at, Ref::part(sp.entity, Part::Pole(i))], None);
        }
        10 => {
            return Err(
                "a B-spline knot point alignment has no IR equivalent (the IR has no knot points)"
                    .into(),
            );
        }
        5..=8 | 11 => {
            return Err(
                "a hyperbola or parabola alignment: the IR has no hyperbolas or parabolas".into()
            );
        }
        other => return Err(format!("internal alignment type {other} is not known")),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degrees_recovers_typed_values() {
        assert_eq!(degrees(std::f64::consts::FRAC_PI_6), Number::parse("30"));
        assert_eq!(degrees(std::f64::consts::FRAC_PI_2), Number::parse("90"));
        assert_eq!(degrees(-std::f64::consts::PI), Number::parse("-180"));
        assert_eq!(degrees(0.123456789), Number::from_f64(0.123456789f64.to_degrees()));
    }
}
