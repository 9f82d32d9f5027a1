//! Reader of FreeCAD documents (`.FCStd`, FreeCAD 0.18 to 1.x): every `Sketcher::SketchObject`
//! (and `Sketcher::SketchObjectPython`) of the archive's `Document.xml` becomes one
//! [`ir::Sketch`].
//!
//! # Names
//! - Model name `"<file stem>/<object Name>"` (`Bielle/Sketch005`), label the object's `Label`.
//! - Geometry `i` (FreeCAD GeoId `i`, 0-based) is `Edge<i+1>`, as FreeCAD's sketcher names it
//!   (points too); external geometry `k` (GeoId `−3 − k`) is `ExternalEdge<k+1>`; the sketch's
//!   axes and origin are `H_Axis` (GeoId −1, the line through (0,0) and (1,0)), `V_Axis`
//!   (GeoId −2, through (0,0) and (0,1)) and `RootPoint` (GeoId −1 or −2 at position 1), added
//!   as external construction entities only when a constraint uses them.
//! - Constraint `i` is `Constraint<i+1>`, FreeCAD's numbering in its constraint list. A
//!   constraint's `Name` is not carried (the IR has no label for constraints). When one FreeCAD
//!   constraint becomes two IR constraints, the second has a suffix: `Constraint7/tangent`,
//!   `Constraint7/perpendicular`, `Constraint7/end`.
//! - Errors name the element as `<object>/Geometry[n]` or `<object>/Constrain[n]` (1-based,
//!   `Constrain[n]` is `Constraint<n>`) with the XML line.
//!
//! # Geometry
//! Lengths are millimetres as stored. Numbers written in the file are read exactly; arc and
//! elliptical-arc end points (FreeCAD stores angles) and rotated ellipses' major vertices are
//! computed in floats. A conic whose normal is `−z` runs clockwise; its start and end are swapped,
//! as FreeCAD's sketcher reads it. Construction: `<Construction value="1"/>` or the construction
//! bit of the `SketchGeometryExtension` (FreeCAD ≥ 0.19).
//!
//! | FreeCAD | IR |
//! |---|---|
//! | `Part::GeomPoint` | `Point` |
//! | `Part::GeomLineSegment` | `Segment` |
//! | `Part::GeomLine` | `Line` |
//! | `Part::GeomCircle` | `Circle` |
//! | `Part::GeomArcOfCircle` | `Arc` |
//! | `Part::GeomEllipse` | `Ellipse` (`major` = centre + a·u, u toward focus 1) |
//! | `Part::GeomArcOfEllipse` | `EllipticalArc` |
//! | `Part::GeomBSplineCurve` | `BSpline` (weights `None` when all are 1) |
//! | hyperbolas, parabolas, other types | skipped |
//!
//! External geometry: FreeCAD ≥ 1.0 stores it (`ExternalGeo`, whose first two entries are the
//! axes); older documents store only the links, which are resolved against the linked objects'
//! stored shapes: the BRep files of the archive, read by a small reader of OpenCASCADE's text
//! format; see the `external` submodule for the cases projected. Either way it is `external: true`.
//!
//! # Constraints
//! Positions (`FirstPos`…): 1 start, 2 end, 3 centre → `Part::Start`/`End`/`Center`; a point
//! geometry at any of them is the point itself. Values: lengths in mm as written, angles from
//! radians to degrees (rounded to 10⁻⁹° when that recovers a typed value). `IsDriving="0"` →
//! `driving: false`; `IsActive="0"` → skipped, "inactive". Where FreeCAD's solver ignores a
//! constraint (a reference that is not a point where a point is needed, a pair of curves it does
//! not support) it is skipped saying so. Distances to circles and arc lengths came with FreeCAD
//! 1.0: in documents written by an older FreeCAD (`ProgramVersion` below 0.22, 1.0's development
//! number) they are skipped, as their solver ignored them.
//!
//! | code | FreeCAD | IR |
//! |---|---|---|
//! | 1 | Coincident | `Coincident [p, p]` |
//! | 2, 3 | Horizontal, Vertical | `[line]` or `[p, p]` |
//! | 4 | Parallel | `Parallel [line, line]` |
//! | 5 | Tangent, simple | lines: `Collinear`; line/circle/arc/ellipse, circle/arc pairs: `Tangent` |
//! | 5 | Tangent, end point to end point | `TangentAtEnds [end, end]` |
//! | 5 | Tangent, end point to curve | lines: `Collinear`; lines/circles/arcs: `PointOnObject [end, curve]` + `Tangent` (`/tangent`); else skipped |
//! | 5, 9, 10 | … via a point (`Third` set) | skipped (angle-via-point) |
//! | 6 | Distance | `[p, p]`, `[p, line or circle]`, `[circle, circle]` → `Distance`; one segment → `Length`; one arc → `ArcLength` |
//! | 7, 8 | DistanceX, DistanceY | segment: `[start, end]`; one point: `[RootPoint, p]`; two points: `[p1, p2]` (value = p2 − p1) |
//! | 9 | Angle | one line: `AngleToXAxis`; two lines: `Angle` (from given ends: ±180° to the IR's start→end directions); an arc's sweep: skipped |
//! | 10 | Perpendicular, simple | lines: `Perpendicular`; line and circle/arc: `PointOnObject [centre, line]` |
//! | 10 | … end point to end point | `PerpendicularAtEnds` |
//! | 10 | … end point to curve | `PointOnObject` + `Perpendicular` (lines) or + `PointOnObject [centre, line]` (line and circle/arc) |
//! | 11, 18 | Radius, Diameter | `Radius`, `Diameter` |
//! | 12 | Equal | segments, circles/arcs: `Equal`; ellipses: skipped |
//! | 13 | PointOnObject | `PointOnObject [p, curve]` |
//! | 14 | Symmetric | `Symmetric [p, p, line or point]` |
//! | 15 | InternalAlignment | ellipse major/minor diameter: two `Coincident` of the helper line's ends with `MajorEnd`/`MajorStart` (`MinorEnd`/`MinorStart`), the end nearer the positive vertex to it as FreeCAD decides; foci: `Coincident [p, Focus1/Focus2]`; B-spline control point: `Coincident [centre, Pole(i)]` (FreeCAD's radius = weight link: listed as skipped); knot points, hyperbola, parabola: skipped |
//! | 16 | SnellsLaw | skipped |
//! | 17 | Block | `Fix [entity]` |
//! | 19 | Weight | skipped |
//!
//! # Source verdict
//! FreeCAD ≥ 1.0 saves `FullyConstrained` (a flag the sketcher sets after solving): it is given as
//! `("FullyConstrained", "true"/"false")`. Older documents record nothing.
//!
//! The reader never panics, bounds what it decompresses (`Document.xml` to 256 MiB, each shape
//! file to 64 MiB) and prints nothing.

mod brep;
mod constraints;
mod external;
mod geometry;

use std::collections::HashMap;
use std::io::Read;
use std::rc::Rc;

use roxmltree::{Document, Node};

use crate::ir::{self, Entity, Skipped};
use crate::{ImportError, file_stem};
use brep::Brep;
use constraints::{GeoTable, Slot};
use external::Projected;
use geometry::GeoRead;

/// The largest `Document.xml` read.
const MAX_DOCUMENT_BYTES: u64 = 256 << 20;
/// The largest shape (BRep) file read.
const MAX_SHAPE_BYTES: u64 = 64 << 20;
/// The most shape data read for one document.
const MAX_TOTAL_SHAPE_BYTES: u64 = 512 << 20;

/// Reads every sketch of a FreeCAD document (the bytes of an `.FCStd` zip archive).
///
/// # Errors
/// See [`crate::read`]: not a zip archive, no `Document.xml`, XML that does not parse, a
/// malformed geometry or constraint element.
pub fn read(file: &str, bytes: &[u8]) -> Result<Vec<ir::Sketch>, ImportError> {
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).map_err(|e| {
        ImportError::new(file, format!("not a FreeCAD document (not a zip archive: {e})"))
    })?;
    let xml = read_entry(&mut archive, "Document.xml", MAX_DOCUMENT_BYTES)
        .map_err(|e| ImportError::new(file, e).in_element("Document.xml"))?;
    let mut shapes = Shapes { archive, cache: HashMap::new(), total: 0 };
    read_document(file, &xml, Some(&mut shapes))
}

/// Reads every sketch of a FreeCAD `Document.xml` given as text. External geometry of documents
/// older than FreeCAD 1.0 cannot be resolved without the archive's shape files: it is skipped.
///
/// # Errors
/// See [`read`].
pub fn read_document_xml(file: &str, xml: &str) -> Result<Vec<ir::Sketch>, ImportError> {
    read_document(file, xml, None)
}

fn read_entry<R: std::io::Read + std::io::Seek>(
    archive: &mut zip::ZipArchive<R>,
    name: &str,
    limit: u64,
) -> Result<String, String> {
    let entry =
        archive.by_name(name).map_err(|e| format!("the archive has no readable {name}: {e}"))?;
    if entry.size() > limit {
        return Err(format!(
            "{name} is {} bytes, more than the {limit} this reader accepts",
            entry.size()
        ));
    }
    let mut data = Vec::new();
    entry
        .take(limit + 1)
        .read_to_end(&mut data)
        .map_err(|e| format!("cannot decompress {name}: {e}"))?;
    if data.len() as u64 > limit {
        return Err(format!("{name} is more than the {limit} bytes this reader accepts"));
    }
    String::from_utf8(data).map_err(|_| format!("{name} is not UTF-8 text"))
}

/// The archive's shape files, parsed on demand.
struct Shapes<'b> {
    archive: zip::ZipArchive<std::io::Cursor<&'b [u8]>>,
    cache: HashMap<String, Result<Rc<Brep>, String>>,
    total: u64,
}

impl Shapes<'_> {
    fn get(&mut self, name: &str) -> Result<Rc<Brep>, String> {
        if let Some(r) = self.cache.get(name) {
            return r.clone();
        }
        let r = (|| {
            if self.total > MAX_TOTAL_SHAPE_BYTES {
                return Err("the document's shape files exceed what this reader reads".to_owned());
            }
            let text = read_entry(&mut self.archive, name, MAX_SHAPE_BYTES)?;
            self.total += text.len() as u64;
            Brep::parse(&text)
                .map(Rc::new)
                .map_err(|e| format!("its shape {name} cannot be read: {e}"))
        })();
        self.cache.insert(name.to_owned(), r.clone());
        r
    }
}

/// Error context: the file and the parsed XML (for line numbers).
struct Ctx<'a, 'i> {
    file: &'a str,
    doc: &'a Document<'i>,
}

impl Ctx<'_, '_> {
    fn err(
        &self,
        node: Node<'_, '_>,
        element: impl Into<String>,
        message: impl Into<String>,
    ) -> ImportError {
        let line = self.doc.text_pos_at(node.range().start).row as usize;
        ImportError::new(self.file, message).at_line(line).in_element(element)
    }
}

fn elements<'a, 'i>(node: Node<'a, 'i>, tag: &'a str) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    node.children().filter(move |c| c.is_element() && c.tag_name().name() == tag)
}

fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|c| c.is_element() && c.tag_name().name() == tag)
}

/// An object's persistent properties by name.
fn properties<'a, 'i>(object: Node<'a, 'i>) -> HashMap<&'a str, Node<'a, 'i>> {
    let mut out = HashMap::new();
    if let Some(props) = child(object, "Properties") {
        for p in elements(props, "Property") {
            if let Some(name) = p.attribute("name") {
                out.entry(name).or_insert(p);
            }
        }
    }
    out
}

fn is_sketch_type(t: &str) -> bool {
    matches!(t, "Sketcher::SketchObject" | "Sketcher::SketchObjectPython")
}

fn read_document(
    file: &str,
    xml: &str,
    mut shapes: Option<&mut Shapes<'_>>,
) -> Result<Vec<ir::Sketch>, ImportError> {
    // No DTD (no entity expansion); the text itself bounds the node count.
    let options =
        roxmltree::ParsingOptions { allow_dtd: false, ..roxmltree::ParsingOptions::default() };
    let doc = Document::parse_with_options(xml, options).map_err(|e| {
        ImportError::new(file, format!("Document.xml is not well-formed XML: {e}"))
            .at_line(e.pos().row as usize)
            .in_element("Document.xml")
    })?;
    let cx = Ctx { file, doc: &doc };
    let root = doc.root_element();
    if root.tag_name().name() != "Document" {
        return Err(cx.err(
            root,
            "Document.xml",
            format!("the root element is <{}>, not <Document>", root.tag_name().name()),
        ));
    }
    let mut types: HashMap<&str, &str> = HashMap::new();
    if let Some(objects) = child(root, "Objects") {
        for o in elements(objects, "Object") {
            if let (Some(name), Some(ty)) = (o.attribute("name"), o.attribute("type")) {
                types.insert(name, ty);
            }
        }
    }
    let mut data: HashMap<&str, Node<'_, '_>> = HashMap::new();
    let mut order = Vec::new();
    if let Some(object_data) = child(root, "ObjectData") {
        for o in elements(object_data, "Object") {
            if let Some(name) = o.attribute("name")
                && data.insert(name, o).is_none()
            {
                order.push(name);
            }
        }
    }
    let version = root.attribute("ProgramVersion").unwrap_or("");
    let before_1_0 = older_than_1_0(version).then(|| version.trim().to_owned());
    let stem = file_stem(file);
    let mut out = Vec::new();
    for name in order {
        if !types.get(name).is_some_and(|t| is_sketch_type(t)) {
            continue;
        }
        let sketch =
            read_sketch(&cx, &stem, name, data[name], &data, shapes.as_deref_mut(), &before_1_0)?;
        out.push(sketch);
    }
    Ok(out)
}

/// Whether a `ProgramVersion` (`0.19R19107 (Git)`, `1.0.0R39109 (Git)`) is older than FreeCAD 1.0
/// (whose development versions were numbered 0.22). Unknown versions are taken as recent.
fn older_than_1_0(version: &str) -> bool {
    let number: String =
        version.trim().chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect();
    let mut parts = number.split('.').map(|p| p.parse::<u32>().ok());
    match (parts.next().flatten(), parts.next().flatten()) {
        (Some(0), Some(minor)) => minor < 22,
        _ => false,
    }
}

fn string_value(prop: Option<&Node<'_, '_>>) -> Option<String> {
    prop.and_then(|p| child(*p, "String")).and_then(|s| s.attribute("value")).map(str::to_owned)
}

fn read_sketch(
    cx: &Ctx<'_, '_>,
    stem: &str,
    name: &str,
    object: Node<'_, '_>,
    objects: &HashMap<&str, Node<'_, '_>>,
    shapes: Option<&mut Shapes<'_>>,
    before_1_0: &Option<String>,
) -> Result<ir::Sketch, ImportError> {
    let props = properties(object);
    let mut sketch = ir::Sketch::planar(format!("{stem}/{name}"), string_value(props.get("Label")));
    let mut table = GeoTable { before_1_0: before_1_0.clone(), ..GeoTable::default() };

    // The sketch's own geometry.
    if let Some(list) = props.get("Geometry").and_then(|p| child(*p, "GeometryList")) {
        for (i, g) in elements(list, "Geometry").enumerate() {
            let id = format!("Edge{}", i + 1);
            let element = format!("{name}/Geometry[{}]", i + 1);
            let read = geometry::read_geometry(g).map_err(|m| cx.err(g, element, m))?;
            table.normal.push(add_entity(&mut sketch, id, read, false));
        }
    }

    // External geometry: stored (FreeCAD ≥ 1.0), else resolved from the links.
    if let Some(list) = props.get("ExternalGeo").and_then(|p| child(*p, "GeometryList")) {
        for (i, g) in elements(list, "Geometry").enumerate().skip(2) {
            let id = constraints::external_id(i - 2);
            let element = format!("{name}/ExternalGeo[{}]", i + 1);
            let read = geometry::read_geometry(g).map_err(|m| cx.err(g, element, m))?;
            table.external.push(add_entity(&mut sketch, id, read, true));
        }
    } else {
        resolve_links(&props, objects, shapes, &mut sketch, &mut table);
    }

    // Constraints.
    if let Some(list) = props.get("Constraints").and_then(|p| child(*p, "ConstraintList")) {
        for (i, c) in elements(list, "Constrain").enumerate() {
            let id = format!("Constraint{}", i + 1);
            let element = format!("{name}/Constrain[{}]", i + 1);
            let raw = constraints::read_raw(c).map_err(|m| cx.err(c, element, m))?;
            match constraints::map(&raw, &id, &mut table) {
                Ok(m) => {
                    sketch.constraints.extend(m.constraints);
                    if let Some(reason) = m.partial {
                        sketch.skipped.push(Skipped { item: id, reason });
                    }
                }
                Err(reason) => {
                    let reason = match &raw.type_code {
                        Ok(code) if reason != "inactive" => {
                            format!("{} (type {code}): {reason}", constraints::type_name(*code))
                        }
                        _ => reason,
                    };
                    sketch.skipped.push(Skipped { item: id, reason });
                }
            }
        }
    }

    // The axes and the origin, when used.
    let axes = [
        (constraints::H_AXIS, ir::Geometry::Line { a: xy(0, 0), b: xy(1, 0) }),
        (constraints::V_AXIS, ir::Geometry::Line { a: xy(0, 0), b: xy(0, 1) }),
        (constraints::ROOT_POINT, ir::Geometry::Point { at: xy(0, 0) }),
    ];
    for (used, (id, geometry)) in table.used_axes.iter().zip(axes) {
        if *used {
            sketch.entities.push(Entity {
                id: id.to_owned(),
                geometry,
                construction: true,
                external: true,
            });
        }
    }

    if let Some(b) = props
        .get("FullyConstrained")
        .and_then(|p| child(*p, "Bool"))
        .and_then(|b| b.attribute("value"))
    {
        sketch.source_verdict.push(("FullyConstrained".to_owned(), b.to_owned()));
    }
    Ok(sketch)
}

fn xy(x: i64, y: i64) -> ir::Coords {
    vec![ir::Number::from_i64(x), ir::Number::from_i64(y)]
}

fn add_entity(sketch: &mut ir::Sketch, id: String, read: GeoRead, external: bool) -> Slot {
    match read {
        GeoRead::Entity { geometry, draw, construction } => {
            sketch.entities.push(Entity { id: id.clone(), geometry, construction, external });
            Slot::Geo { id, draw }
        }
        GeoRead::Skip(reason) => {
            sketch.skipped.push(Skipped { item: id.clone(), reason: reason.clone() });
            Slot::Skipped { id, reason }
        }
    }
}

/// Resolves the `ExternalGeometry` links of a document that does not store external geometry.
fn resolve_links(
    props: &HashMap<&str, Node<'_, '_>>,
    objects: &HashMap<&str, Node<'_, '_>>,
    mut shapes: Option<&mut Shapes<'_>>,
    sketch: &mut ir::Sketch,
    table: &mut GeoTable,
) {
    let Some(prop) = props.get("ExternalGeometry") else { return };
    let Some(list) = child(*prop, "LinkSubList") else {
        if prop.children().any(|c| c.is_element()) {
            table.external_beyond =
                Some("the ExternalGeometry property is in a form this reader does not know".into());
            sketch.skipped.push(Skipped {
                item: "ExternalGeometry".into(),
                reason: "the ExternalGeometry property is in a form this reader does not know"
                    .into(),
            });
        }
        return;
    };
    let links: Vec<(String, String)> = elements(list, "Link")
        .map(|l| {
            (
                l.attribute("obj").unwrap_or("").to_owned(),
                l.attribute("sub").unwrap_or("").to_owned(),
            )
        })
        .collect();
    let to_sketch =
        props.get("Placement").and_then(|p| child(*p, "PropertyPlacement")).and_then(|p| {
            let f = |a: &str| p.attribute(a).and_then(geometry::parse_float);
            external::placement(
                f("Px")?,
                f("Py")?,
                f("Pz")?,
                [f("Q0")?, f("Q1")?, f("Q2")?, f("Q3")?],
            )
        });
    let to_sketch = to_sketch.and_then(|t| t.inverse());
    for (k, (obj, sub)) in links.iter().enumerate() {
        let id = constraints::external_id(k);
        let what = format!("{obj}/{sub}");
        let result = match (shapes.as_deref_mut(), &to_sketch) {
            (None, _) => Projected::Unknown(
                "documents older than FreeCAD 1.0 do not store external geometry, and resolving its link \
                 needs the archive's shape files (Document.xml was read alone)"
                    .into(),
            ),
            (_, None) => Projected::Unknown("the sketch has no usable Placement".into()),
            (Some(shapes), Some(to_sketch)) => resolve_one(obj, sub, objects, shapes, to_sketch),
        };
        match result {
            Projected::Geo { geometry, draw } => {
                sketch.entities.push(Entity {
                    id: id.clone(),
                    geometry,
                    construction: true,
                    external: true,
                });
                table.external.push(Slot::Geo { id, draw });
            }
            Projected::Skip(reason) => {
                let reason = format!("external geometry {what}: {reason}");
                sketch.skipped.push(Skipped { item: id.clone(), reason: reason.clone() });
                table.external.push(Slot::Skipped { id, reason });
            }
            Projected::Unknown(reason) => {
                let reason = format!("external geometry {what}: {reason}");
                sketch.skipped.push(Skipped { item: id.clone(), reason: reason.clone() });
                for (j, (o, s)) in links.iter().enumerate().skip(k + 1) {
                    sketch.skipped.push(Skipped {
                        item: constraints::external_id(j),
                        reason: format!(
                            "external geometry {o}/{s}: follows {}, whose number of geometries is not known, so its GeoId is not known",
                            constraints::external_id(k)
                        ),
                    });
                }
                table.external_beyond =
                    Some(format!("the external geometry from {} on is not known ({reason})", id));
                return;
            }
        }
    }
}

fn resolve_one(
    obj: &str,
    sub: &str,
    objects: &HashMap<&str, Node<'_, '_>>,
    shapes: &mut Shapes<'_>,
    to_sketch: &brep::Trsf,
) -> Projected {
    let Some((kind, index)) = external::sub_name(sub) else {
        return Projected::Unknown(format!(
            "the sub-element \"{sub}\" is not an edge, vertex or face"
        ));
    };
    if kind == brep::ShapeKind::Face {
        return Projected::Unknown("a face is not projected by this reader".into());
    }
    let Some(object) = objects.get(obj) else {
        return Projected::Unknown(format!("the object {obj} is not in the document"));
    };
    let props = properties(*object);
    let Some(file) =
        props.get("Shape").and_then(|p| child(*p, "Part")).and_then(|p| p.attribute("file"))
    else {
        return Projected::Unknown(format!("the object {obj} has no stored shape"));
    };
    let shape = match shapes.get(file) {
        Ok(s) => s,
        Err(e) => return Projected::Unknown(e),
    };
    match shape.find(kind, index) {
        Ok(subshape) => external::project(&subshape, to_sketch),
        Err(e) => Projected::Unknown(format!("{sub} of {obj}'s shape: {e}")),
    }
}
