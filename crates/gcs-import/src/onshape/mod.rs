//! Reader of Onshape sketch features as JSON, the raw form SketchGraphs distributes: a list of
//! features (or one feature object, or an object with a `features` list), each sketch a
//! `newSketch` feature (`BTMSketch`) with `entities` and `constraints`.
//!
//! # Sketches
//! Every `newSketch` feature becomes one [`ir::Sketch`] named `<file stem>/<index>`, the index
//! counting the file's sketch features from 0; its label is the feature's `name`. Other features
//! (extrudes, planes) are not sketches and are passed over.
//!
//! # Entities
//! Onshape stores metres and radians; coordinates are the shortest decimals of the file's doubles
//! times 1000, exactly. Ids are Onshape's `entityId`s.
//!
//! | Onshape | neutral sketch |
//! |---|---|
//! | `BTMSketchPoint` | `Point` |
//! | `BTMSketchCurveSegment` + `BTCurveGeometryLine` | `Segment` from `pnt + startParam·dir` to `pnt + endParam·dir`; when the parameter range is ≤ 1e-12 m (a zero-length line), its carrier `Line` (the id) and its ends `Point`s `<id>#start`, `<id>#end` on it (`PointOnObject`, `<id>#start-on`, `<id>#end-on`), which `.start` and `.end` name |
//! | `BTMSketchCurve` + `BTCurveGeometryLine` | `Line` (unbounded) |
//! | `BTMSketchCurve` + `BTCurveGeometryCircle` | `Circle` |
//! | `BTMSketchCurveSegment` + `BTCurveGeometryCircle` | `Arc`: the point at parameter t is `c + r(cos t·u + s·sin t·u⊥)`, u = (xDir, yDir), s = −1 when `clockwise`; a clockwise arc has its ends swapped (Onshape's `.start` is the neutral `End`) |
//! | `BTCurveGeometryEllipse` (curve / segment) | `Ellipse` / `EllipticalArc` (same parametrisation with the two radii; ends swapped when clockwise) |
//! | `BTCurveGeometrySpline` (not periodic, not rational, not trimmed) | `BSpline` (poles in mm, knots as given) |
//! | `BTMSketchTextEntity`, `BTMSketchImageEntity` | a rectangle of 4 segments (`<id>.sketch_text.baseline`, `.ascent` (its top), `.left`, `.right`; `<id>.sketch_image.bottom`, `.top`, `.left`, `.right`) and its centre (`….center`), with the drawn proportions (a text's through its font, an image's aspect ratio): constraints `<id>#corner1`…`#corner4`, `#parallel`, `#perpendicular`, `#perpendicular2`, `#ratio` (`LengthRatio`), `#center` |
//! | `BTCurveGeometryInterpolatedSpline` (not trimmed) | the cubic `BSpline` through its points Onshape builds (centripetal knots, its end handles as the second and last-but-one control points; periodic: the periodic cubic), its inner interpolation points `<id>.<k>.internal` (all, when periodic) held at their knots (`SplinePoint`, `<id>#through<k>`); `<id>.0.internal` and the last are its start and end, `<id>.startDerivative` and `.endDerivative` its end legs (see `entities::interpolated`) |
//! | periodic, rational or trimmed control-point splines, trimmed interpolated splines, conics | skipped, with the reason |
//!
//! SketchGraphs' files carry no external geometry: references outside the sketch (the origin,
//! model edges) are queries whose ids the dataset stripped, so no entity is `external`.
//!
//! # Constraints
//! References are `<entity id>` (the entity) or `<entity id>.start`, `.end`, `.center` (its
//! named points); a point id an entity declares (`startPointId`…) is accepted too. The
//! parameters `localFirst`/`localSecond` (or the older `local0`, `local1`, …) give the order.
//! Dimension values are the quantity expressions (`15 mm`, `(1/8)*inch`, `45 deg`) evaluated
//! exactly, in mm and degrees (the files' numeric `value` fields are all 0); a `driven`
//! dimension is non-driving, without a value when the file has none.
//!
//! | `constraintType` | references | neutral sketch |
//! |---|---|---|
//! | COINCIDENT | point, point / point, curve / line, line / circle, circle | `Coincident` / `PointOnObject` / `Collinear` / `Concentric` + `Equal` (id `<id>#equal`) |
//! | HORIZONTAL, VERTICAL | line / point, point | `Horizontal`, `Vertical` |
//! | PARALLEL, PERPENDICULAR | line, line | `Parallel`, `Perpendicular` |
//! | TANGENT | two curves, not both lines | `Tangent` |
//! | NORMAL | line, circle / line, line | `PointOnObject` (the centre on the line) / `Perpendicular` |
//! | EQUAL | two lines / two circles or arcs | `Equal` |
//! | CONCENTRIC | circles, arcs / ellipses / a point and a circle | `Concentric` / `Coincident` of the centres / `Coincident` with the centre |
//! | MIDPOINT | point, line or arc / midpoint, point, point | `Midpoint` / `Symmetric` about the midpoint |
//! | MIRROR, SYMMETRIC | point, point, mirror line / circle, circle, line / segment, segment, line | `Symmetric` / `Symmetric` of the centres + `Equal` (`<id>#equal`) / `Symmetric` of the segments (their carriers), or a note when mirrors of both their end points about the same line say it |
//! | OFFSET | curve, offset (`localMaster`, `localOffset` or `local2`, `local0`) [, second curve, its offset (`localSecond`, `localSecondOffset` or `local3`, `local1`)] | `Parallel` / `Concentric` of each pair (`<id>#master`, once per operation; `<id>#second`), and the equal gaps (the id): `EqualPointLineDistances` from the offsets' starts where both pairs are lines (where the offsets are joined end to end, each from the corner it shares with its neighbour on the way to the first offset: the same equations given the parallels), else `EqualGaps` (a pair of circles by its two circles: a difference of radii) |
//! | CIRCULAR_PATTERN (closed), LINEAR_PATTERN | pivot or directions, instances `localInstance<k>,<i>[,<j>]` | `Rotated` by i·360°/N (the drawing's sense; N ≤ 36) / `Translated` by one step along a direction segment, per point of each instance (`<id>#<k>,<i>[,<j>]`), `Equal` radii of circles (`…#radius`) |
//! | DISTANCE (direction MINIMUM) | point–point, point–line, line–line, point–circle, circle–circle | `Distance` |
//! | DISTANCE (HORIZONTAL, VERTICAL) | point, point | `DistanceX`, `DistanceY`, signed as the drawing shows |
//! | LENGTH | line | `Length` (or `DistanceX`/`DistanceY` with a direction) |
//! | RADIUS, DIAMETER | circle or arc | `Radius`, `Diameter` |
//! | ANGLE | line, line | `Angle`: of `±value + k·180°`, the oriented angle nearest the drawing |
//! | FIX | any | `Fix` |
//! | CENTERLINE_DIMENSION | centreline, point or line | `Distance` of half the value |
//! | PROJECTED (USE, USE_END, USE_START) | a sketch entity or point and model geometry | `Fix` of the sketch entity (it is drawn on the projection) |
//!
//! Skipped, with the reason: the equal gap of an offset that is an infinite line, open circular patterns (their angle is
//! not in the file), circular patterns of other than 2 or 4 instances,
//! silhouette projections, other types; a line–circle distance;
//! anything with a reference to external geometry ("reference to external geometry without its
//! geometry in the file"); a reference to a skipped entity or to an unknown id; a fix of a
//! zero-length line; a driving dimension whose expression cannot be evaluated (variables).
//! A second entity or constraint with an id already taken is skipped too. Not read: the angle
//! dimension's `aligned`/`clockwise`/`flipped` flags (the drawing orients it) and the distances'
//! `halfSpace` options: Onshape may measure a point–circle distance to the far side of the
//! circle, which the neutral `Distance` does not distinguish.
//!
//! # Errors
//! Input that is not JSON, or JSON not of this shape (a feature that is not an object, an entity
//! without its id or coordinates, a constraint without its type), is an [`ImportError`] naming
//! the element (`features[3].entities[2] (id …)`). Never panics, never prints.

mod constraints;
mod entities;
mod expr;
mod json;

use serde_json::Value;

use crate::{ImportError, ir};
use constraints::Outcome;
use entities::{Read, Table};

/// Reads every sketch of the file.
///
/// # Errors
/// See [`crate::read`].
pub fn read(file: &str, bytes: &[u8]) -> Result<Vec<ir::Sketch>, ImportError> {
    let value: Value = serde_json::from_slice(bytes)
        .map_err(|e| ImportError::new(file, format!("not JSON: {e}")).at_line(e.line()))?;
    let features: Vec<(String, &Value)> = match &value {
        Value::Array(list) => {
            list.iter().enumerate().map(|(i, f)| (format!("features[{i}]"), f)).collect()
        }
        Value::Object(map) => match map.get("features") {
            Some(Value::Array(list)) => {
                list.iter().enumerate().map(|(i, f)| (format!("features[{i}]"), f)).collect()
            }
            _ => vec![("feature".to_owned(), &value)],
        },
        other => {
            return Err(ImportError::new(
                file,
                format!(
                    "expected a list of Onshape features or a feature object, found {}",
                    json::kind(other)
                ),
            ));
        }
    };
    let stem = crate::file_stem(file);
    let mut sketches = Vec::new();
    for (path, feature) in features {
        let at = |message: String| ImportError::new(file, message).in_element(path.clone());
        let mut map = json::object(feature, "feature").map_err(at)?;
        // The API's wrapped form: `{"type": 151, "typeName": "BTMSketch", "message": {...}}`.
        if let Some(Value::Object(inner)) = map.get("message")
            && (inner.contains_key("featureType")
                || map.get("typeName").and_then(Value::as_str) == Some("BTMSketch"))
        {
            map = inner;
        }
        let feature_type = json::string(map, "featureType").map_err(at)?;
        if feature_type != "newSketch" {
            continue;
        }
        let name = format!("{stem}/{}", sketches.len());
        sketches.push(read_sketch(file, &path, map, name)?);
    }
    Ok(sketches)
}

fn read_sketch(
    file: &str,
    path: &str,
    map: &json::Object,
    name: String,
) -> Result<ir::Sketch, ImportError> {
    let at = |element: String| {
        move |message: String| ImportError::new(file, message).in_element(element)
    };
    let label = json::opt_string(map, "name").map_err(at(path.to_owned()))?.map(str::to_owned);
    let mut sketch = ir::Sketch::planar(name, label);
    let mut table = Table::default();
    for (j, element) in
        json::array(map, "entities").map_err(at(path.to_owned()))?.iter().enumerate()
    {
        let element_path = format!("{path}.entities[{j}]");
        let entity = json::object(element, "entity").map_err(at(element_path.clone()))?;
        let type_name = json::string(entity, "typeName").map_err(at(element_path.clone()))?;
        let msg = json::field_object(entity, "message").map_err(at(element_path.clone()))?;
        let id = json::string(msg, "entityId").map_err(at(element_path.clone()))?;
        let in_entity = at(format!("{element_path} (id {id})"));
        if table.contains(id) {
            sketch.skipped.push(ir::Skipped {
                item: id.to_owned(),
                reason: format!("a second entity with the id `{id}` ({element_path})"),
            });
            continue;
        }
        match entities::read(type_name, msg, id).map_err(in_entity)? {
            Read::Entity(entity, shape) => {
                table.add(id, shape, sketch.entities.len(), msg);
                sketch.entities.push(entity);
            }
            Read::Skip(reason) => {
                table.add_skipped(id, &reason);
                sketch.skipped.push(ir::Skipped { item: id.to_owned(), reason });
            }
            Read::Composite(parts, constraints, aliases) => {
                // (The element's point ids name the part that has its id, if one does.)
                let none = json::Object::new();
                for (entity, shape) in parts {
                    let own = if entity.id == id { msg } else { &none };
                    table.add(&entity.id, shape, sketch.entities.len(), own);
                    sketch.entities.push(entity);
                }
                for (alias, entity, suffix) in aliases {
                    table.alias(&alias, &entity, suffix);
                }
                sketch.constraints.extend(constraints);
            }
        }
    }
    let mut ids = std::collections::HashSet::new();
    for (j, element) in
        json::array(map, "constraints").map_err(at(path.to_owned()))?.iter().enumerate()
    {
        let element_path = format!("{path}.constraints[{j}]");
        let constraint = json::object(element, "constraint").map_err(at(element_path.clone()))?;
        let msg = json::field_object(constraint, "message").map_err(at(element_path.clone()))?;
        let id = json::string(msg, "entityId").map_err(at(element_path.clone()))?;
        let in_constraint = at(format!("{element_path} (id {id})"));
        if !ids.insert(id.to_owned()) {
            sketch.skipped.push(ir::Skipped {
                item: id.to_owned(),
                reason: format!("a second constraint with the id `{id}` ({element_path})"),
            });
            continue;
        }
        match constraints::read(msg, id, &table, &sketch.entities).map_err(in_constraint)? {
            // Onshape ties an interpolated spline's start and end to its first and last
            // interpolation points, which are one point here.
            Outcome::Constraints(list)
                if matches!(list.as_slice(), [c] if c.kind == ir::Kind::Coincident
                    && c.refs.len() == 2 && c.refs[0] == c.refs[1]) =>
            {
                sketch.notes.push(ir::Skipped {
                    item: id.to_owned(),
                    reason: "COINCIDENT of two names of one point (an interpolated spline's end \
                             and its end interpolation point)"
                        .into(),
                });
            }
            Outcome::Constraints(list) => sketch.constraints.extend(list),
            Outcome::Skip(skipped) => sketch.skipped.push(skipped),
            Outcome::Part(list, skipped) => {
                sketch.constraints.extend(list);
                sketch.skipped.push(skipped);
            }
        }
    }
    fold_implied_mirrors(&mut sketch);
    fold_repeated_offsets(&mut sketch);
    offset_gaps_at_joints(&mut sketch);
    Ok(sketch)
}

/// The offsets of one operation each restate the relation of its first pair of curves (parallel
/// or concentric, `<id>#master`): it is kept once, where it is first stated (the others are
/// parts of constraints that are imported, not items of the sketch).
pub(super) fn fold_repeated_offsets(sketch: &mut ir::Sketch) {
    let mut seen = std::collections::HashSet::new();
    sketch
        .constraints
        .retain(|c| !c.id.ends_with("#master") || seen.insert((c.kind, c.refs.clone())));
}

/// The equal gaps of an offset operation measured at the corners where its offset segments
/// meet. Each second pair's gap is read as equal to its first pair's, from the offsets' starts
/// (`EqualPointLineDistances`); where the offsets of one operation are joined end to end (an end
/// of one coincident with an end of the other), each second offset's gap is instead equal to the
/// gap of its neighbour on the way to the first offset, both measured at their common corner.
/// The equations are equivalent: given the parallels of the offset (`#master`, `#second`), every
/// point of an offset segment is at the same distance from its curve (the difference of two
/// such distances vanishes where the parallel holds, and so does its row on the tangent space),
/// and the gaps compared along a tree from the first offset span the same equations as the gaps
/// each compared with the first. Measured at a corner, the equation says what an offset is to a
/// CAD user — the corner on the bisector of the two curves — and binds one point, which the
/// witness's construction places there; from the starts, it binds the corner only through
/// segments' directions and a far point, a loop the construction cannot close.
fn offset_gaps_at_joints(sketch: &mut ir::Sketch) {
    use ir::{Kind, Part, Ref};
    use std::collections::HashMap;
    // Coincidence classes of point references.
    let mut class: HashMap<Ref, usize> = HashMap::new();
    let mut parent: Vec<usize> = Vec::new();
    fn root(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    for c in &sketch.constraints {
        if let (Kind::Coincident, [a, b]) = (c.kind, c.refs.as_slice()) {
            let mut index = |r: &Ref| {
                *class.entry(r.clone()).or_insert_with(|| {
                    parent.push(parent.len());
                    parent.len() - 1
                })
            };
            let (a, b) = (index(a), index(b));
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent[ra] = rb;
        }
    }
    let ends = |o: &str| [Part::Start, Part::End].map(|e| Ref::part(o.to_owned(), e));
    // Where offsets `a` and `b` meet: an end of each, coincident.
    let mut joint = |a: &str, b: &str| -> Option<(Ref, Ref)> {
        for x in ends(a) {
            for y in ends(b) {
                if let (Some(&i), Some(&j)) = (class.get(&x), class.get(&y))
                    && root(&mut parent, i) == root(&mut parent, j)
                {
                    return Some((x, y));
                }
            }
        }
        None
    };
    // The operations: the gaps with their first pair (its offset's start, its curve), each
    // with its second pair (offset, curve).
    let gaps: Vec<usize> = (0..sketch.constraints.len())
        .filter(|&i| {
            let c = &sketch.constraints[i];
            c.kind == Kind::EqualPointLineDistances
                && c.refs.len() == 4
                && c.refs[0].part == Part::Start
                && c.refs[2].part == Part::Start
        })
        .collect();
    let mut operations: HashMap<(Ref, Ref), Vec<usize>> = HashMap::new();
    for &i in &gaps {
        let r = &sketch.constraints[i].refs;
        operations.entry((r[0].clone(), r[1].clone())).or_default().push(i);
    }
    for ((first_start, first_curve), members) in operations {
        // The offsets (the first one at 0) with their curves.
        let mut offsets = vec![(first_start.entity.clone(), first_curve.clone())];
        for &i in &members {
            let r = &sketch.constraints[i].refs;
            offsets.push((r[2].entity.clone(), r[3].clone()));
        }
        // Breadth first from the first offset along the joints: each offset's way there.
        let mut via: Vec<Option<(usize, Ref, Ref)>> = vec![None; offsets.len()];
        let mut reached = vec![false; offsets.len()];
        reached[0] = true;
        let mut queue = std::collections::VecDeque::from([0]);
        while let Some(a) = queue.pop_front() {
            for b in 0..offsets.len() {
                if reached[b] || offsets[a].0 == offsets[b].0 {
                    continue;
                }
                if let Some((x, y)) = joint(&offsets[a].0, &offsets[b].0) {
                    reached[b] = true;
                    via[b] = Some((a, x, y));
                    queue.push_back(b);
                }
            }
        }
        for (k, &i) in members.iter().enumerate() {
            if let Some((a, x, y)) = via[k + 1].clone() {
                let c = &mut sketch.constraints[i];
                c.refs = vec![x, offsets[a].1.clone(), y, offsets[k + 1].1.clone()];
            }
        }
    }
}

/// Onshape's mirror tool writes, beside the mirror of two segments (their carriers), the
/// mirrors of their end points about the same line, which imply it: such a mirror of segments
/// becomes a note ("said by the mirrors of its end points"), not two more equations that would
/// only be redundant.
fn fold_implied_mirrors(sketch: &mut ir::Sketch) {
    use ir::{Kind, Part, Ref};
    let segments: std::collections::HashSet<&str> = sketch
        .entities
        .iter()
        .filter(|e| matches!(e.geometry, ir::Geometry::Segment { .. }))
        .map(|e| e.id.as_str())
        .collect();
    let is_segment = |r: &Ref| r.part == Part::Whole && segments.contains(r.entity.as_str());
    // The mirrored pairs of points, each with its axis and the constraint saying it.
    let mut pairs: std::collections::HashMap<(Ref, Ref, Ref), String> = Default::default();
    for c in &sketch.constraints {
        if let (Kind::Symmetric, [a, b, axis]) = (c.kind, c.refs.as_slice())
            && !is_segment(a)
        {
            pairs.insert((a.clone(), b.clone(), axis.clone()), c.id.clone());
            pairs.insert((b.clone(), a.clone(), axis.clone()), c.id.clone());
        }
    }
    let mut notes = Vec::new();
    sketch.constraints.retain(|c| {
        let (Kind::Symmetric, [a, b, axis]) = (c.kind, c.refs.as_slice()) else { return true };
        if !(is_segment(a) && is_segment(b)) {
            return true;
        }
        let end = |r: &Ref, p: Part| Ref::part(r.entity.clone(), p);
        let said = |p: Part, q: Part| pairs.get(&(end(a, p), end(b, q), axis.clone()));
        let by = [(Part::Start, Part::Start), (Part::End, Part::End)]
            .map(|(p, q)| said(p, q))
            .into_iter()
            .collect::<Option<Vec<_>>>()
            .or_else(|| {
                [(Part::Start, Part::End), (Part::End, Part::Start)]
                    .map(|(p, q)| said(p, q))
                    .into_iter()
                    .collect::<Option<Vec<_>>>()
            });
        let Some(by) = by else { return true };
        notes.push(ir::Skipped {
            item: c.id.clone(),
            reason: format!(
                "MIRROR of two segments: said by the mirrors of their end points (`{}`, `{}`)",
                by[0], by[1]
            ),
        });
        false
    });
    sketch.notes.extend(notes);
}
