//! The Onshape sketch JSON reader: on SketchGraphs' sample of real sketches (every file reads,
//! the totals, facts checked by hand in the JSON, the drawing satisfies what was read), on small
//! hand-written files for each entity and constraint type, and on bad input.

mod common;

use std::collections::BTreeMap;
use std::path::Path;

use gcs_import::ir::{Constraint, Entity, Geometry, Kind, Number, Part, Ref, Sketch};
use gcs_import::{Format, ImportError};

fn read_corpus_file<'a>(files: &'a [(String, Vec<u8>)], stem: &str) -> (&'a str, Vec<Sketch>) {
    let (path, bytes) =
        files.iter().find(|(p, _)| p.contains(stem)).expect("the file is in the sample");
    (path, gcs_import::onshape::read(path, bytes).expect("reads"))
}

fn data(name: &str) -> Vec<Sketch> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/onshape").join(name);
    let bytes = std::fs::read(&path).expect("test file");
    gcs_import::read(Format::Onshape, &path.to_string_lossy(), &bytes).expect("reads")
}

fn n(text: &str) -> Number {
    Number::parse(text).expect("a number")
}

fn at(x: &str, y: &str) -> Vec<Number> {
    vec![n(x), n(y)]
}

fn entity<'a>(s: &'a Sketch, id: &str) -> &'a Entity {
    s.entities.iter().find(|e| e.id == id).unwrap_or_else(|| panic!("entity {id} in {}", s.name))
}

fn constraint<'a>(s: &'a Sketch, id: &str) -> &'a Constraint {
    s.constraints
        .iter()
        .find(|c| c.id == id)
        .unwrap_or_else(|| panic!("constraint {id} in {}", s.name))
}

fn skipped<'a>(s: &'a Sketch, id: &str) -> &'a str {
    &s.skipped
        .iter()
        .find(|k| k.item == id)
        .unwrap_or_else(|| panic!("skipped {id} in {}", s.name))
        .reason
}

fn whole(id: &str) -> Ref {
    Ref::whole(id)
}

fn part(id: &str, p: Part) -> Ref {
    Ref::part(id, p)
}

fn close(a: &[Number], b: [f64; 2]) -> bool {
    a.len() == 2 && (a[0].to_f64() - b[0]).abs() < 1e-9 && (a[1].to_f64() - b[1]).abs() < 1e-9
}

/// What a skipped item is about, for counting.
fn category(reason: &str) -> &'static str {
    const CATEGORIES: &[(&str, &str)] = &[
        ("reference to external geometry without its geometry in the file", "external geometry"),
        ("skipped entity", "reference to a skipped entity"),
        ("has zero length", "zero-length line used as a line"),
        ("the variable", "expression with a variable"),
        ("OFFSET: ", "offset"),
        ("circular pattern", "circular pattern"),
        ("projection of type", "silhouette projection"),
        ("is not expressible", "combination not expressible"),
        ("interpolated spline", "interpolated spline"),
        ("text box", "text box"),
        ("image box", "image box"),
    ];
    CATEGORIES.iter().find(|(needle, _)| reason.contains(needle)).map_or("other", |&(_, c)| c)
}

#[test]
fn every_sample_file_reads_with_the_expected_totals() {
    let Some(files) = common::onshape_files() else { return };
    assert_eq!(files.len(), 84);
    let mut sketches = Vec::new();
    let mut source_constraints = 0;
    for (path, bytes) in &files {
        let read = gcs_import::onshape::read(path, bytes).unwrap_or_else(|e| panic!("{e}"));
        let json: serde_json::Value = serde_json::from_slice(bytes).expect("JSON");
        let features = json.as_array().expect("a list of features");
        assert_eq!(read.len(), features.len(), "{path}: every feature of the sample is a sketch");
        for (i, (s, f)) in read.iter().zip(features).enumerate() {
            let stem = Path::new(path).file_stem().expect("stem").to_string_lossy();
            assert_eq!(s.name, format!("{stem}/{i}"));
            assert_eq!(s.label.as_deref(), f["name"].as_str());
            assert_eq!(s.dim, 2);
            source_constraints += f["constraints"].as_array().expect("constraints").len();
        }
        sketches.extend(read);
    }
    let count = |f: fn(&Sketch) -> usize| sketches.iter().map(f).sum::<usize>();
    assert_eq!(sketches.len(), 237);
    // 2,481 entities in the files, of which 4 are skipped (trimmed interpolated splines), 6
    // interpolated splines read as the spline and its 24 inner interpolation points, and 5
    // boxes (4 text boxes, 1 image box) read as 5 entities each (4 edges, a centre):
    // 2,481 − 4 + 24 + 20 = 2,521, and the 15 zero-length lines read as their carriers and
    // their 30 ends: 2,551.
    assert_eq!(count(|s| s.entities.len()), 2551);
    assert_eq!(
        count(|s| s
            .entities
            .iter()
            .filter(|e| matches!(e.geometry, Geometry::Point { .. }))
            .count()),
        247 + 30 + 5 + 24
    );
    // 5,531 constraints in the files: 540 skipped, 43 mirrors of segments said by the mirrors
    // of their end points (notes), 9 patterns read as 301 moves of points
    // (`<id>#<element>,<instance>`: 216 `Rotated`, 85 `Translated`, and 9 `#radius`
    // equalities), 40 offsets read as 55 parallelisms or concentricities of their pairs of
    // curves (`#master`, once per operation, and `#second`) and, for 37 of them, equal gaps (the
    // id: 28 `EqualPointLineDistances` of lines, 9 `EqualGaps` where a pair is of circles),
    // 4,913 others read; 15 of these become two (two coincident circles, 14 mirrored circles:
    // the second is `<id>#equal`); the 5 boxes add 9 constraints each (`<id>#corner1`…), the 6
    // interpolated splines read hold their 24 inner points (`<id>#through<k>`):
    // 4,913 + 15 + 301 + 9 + 55 + 37 + 45 + 24 = 5,399.
    assert_eq!(source_constraints, 5531);
    // And the 52 constraints on the 15 zero-length lines, and their 30 ends on their carriers:
    // 5,399 + 52 + 30 = 5,481.
    assert_eq!(count(|s| s.constraints.len()), 5481);
    let relations = count(|s| {
        s.constraints
            .iter()
            .filter(|c| c.id.ends_with("#master") || c.id.ends_with("#second"))
            .count()
    });
    assert_eq!(relations, 55);
    assert_eq!(count(|s| s.constraints.iter().filter(|c| c.id.ends_with("#equal")).count()), 15);
    assert_eq!(count(|s| s.constraints.iter().filter(|c| c.id.ends_with("#radius")).count()), 9);
    let moves = count(|s| {
        s.constraints.iter().filter(|c| matches!(c.kind, Kind::Rotated | Kind::Translated)).count()
    });
    assert_eq!(moves, 301);
    // Skipped: 4 trimmed interpolated splines and 464 constraints; notes: the 43 mirrors and
    // 10 coincidences of an interpolated spline's end with its end interpolation point (one
    // point here).
    assert_eq!(count(|s| s.skipped.len()), 4 + 464);
    assert_eq!(count(|s| s.notes.len()), 43 + 10);
    let notes = |prefix: &str| {
        sketches.iter().flat_map(|s| &s.notes).filter(|n| n.reason.starts_with(prefix)).count()
    };
    assert_eq!(notes("MIRROR of two segments"), 43);
    assert_eq!(notes("COINCIDENT of two names of one point"), 10);
    assert_eq!(
        count(|s| s.constraints.iter().filter(|c| !c.id.contains('#')).count()) + 464 + 53 + 9 + 3,
        5531
    );
    // Sketches with nothing skipped: most others reference the sketch origin or model edges,
    // which SketchGraphs' files do not carry.
    assert_eq!(sketches.iter().filter(|s| s.skipped.is_empty()).count(), 36);
    let mut reasons = BTreeMap::new();
    for s in &sketches {
        for k in &s.skipped {
            *reasons.entry(category(&k.reason)).or_insert(0) += 1;
        }
    }
    let expected = BTreeMap::from([
        ("external geometry", 426),
        ("reference to a skipped entity", 18),
        ("offset", 3),
        ("circular pattern", 2),
        ("interpolated spline", 4),
        ("combination not expressible", 8),
        ("silhouette projection", 4),
        ("expression with a variable", 3),
    ]);
    assert_eq!(reasons, expected);
    let mut kinds = BTreeMap::new();
    for s in &sketches {
        for c in &s.constraints {
            *kinds.entry(format!("{:?}", c.kind)).or_insert(0) += 1;
        }
    }
    assert_eq!(kinds["Coincident"], 1957);
    assert_eq!(kinds["SplinePoint"], 24);
    assert_eq!(kinds["Symmetric"], 210);
    assert_eq!((kinds["Rotated"], kinds["Translated"]), (216, 85));
    assert_eq!(kinds["EqualPointLineDistances"], 28);
    assert_eq!(kinds["Fix"], 69);
}

/// Positions of the named points the drawing checks need (mm).
fn position(s: &Sketch, r: &Ref) -> Option<[f64; 2]> {
    let e = s.entities.iter().find(|e| e.id == r.entity)?;
    let p = |c: &[Number]| Some([c[0].to_f64(), c[1].to_f64()]);
    match (&e.geometry, r.part) {
        (Geometry::Point { at }, Part::Whole) => p(at),
        (Geometry::Segment { start, .. } | Geometry::Arc { start, .. }, Part::Start) => p(start),
        (Geometry::Segment { end, .. } | Geometry::Arc { end, .. }, Part::End) => p(end),
        (Geometry::Circle { center, .. } | Geometry::Arc { center, .. }, Part::Center) => p(center),
        (Geometry::BSpline { poles, .. }, Part::Start) => p(poles.first()?),
        (Geometry::BSpline { poles, .. }, Part::End) => p(poles.last()?),
        _ => None,
    }
}

fn direction(s: &Sketch, id: &str) -> Option<[f64; 2]> {
    let a = position(s, &part(id, Part::Start))?;
    let b = position(s, &part(id, Part::End))?;
    Some([b[0] - a[0], b[1] - a[1]])
}

/// Onshape's drawing is its last solution: the point constraints read must hold there. This
/// checks the end points of lines and arcs (clockwise arcs swapped), the signs of horizontal and
/// vertical distances and the orientation of angles.
#[test]
fn the_sample_drawings_satisfy_the_constraints_read() {
    let Some(files) = common::onshape_files() else { return };
    let mut checked = BTreeMap::new();
    for (path, bytes) in &files {
        for s in gcs_import::onshape::read(path, bytes).expect("reads") {
            for c in &s.constraints {
                let p: Vec<_> = c.refs.iter().map(|r| position(&s, r)).collect();
                let v = c.value.as_ref().map(Number::to_f64);
                let near = |a: f64, b: f64| (a - b).abs() < 1e-6;
                let holds = match (c.kind, p.as_slice(), v) {
                    (Kind::Coincident, [Some(a), Some(b)], _) => {
                        near(a[0], b[0]) && near(a[1], b[1])
                    }
                    (Kind::Horizontal, [Some(a), Some(b)], _) => near(a[1], b[1]),
                    (Kind::Vertical, [Some(a), Some(b)], _) => near(a[0], b[0]),
                    (Kind::DistanceX, [Some(a), Some(b)], Some(v)) => near(b[0] - a[0], v),
                    (Kind::DistanceY, [Some(a), Some(b)], Some(v)) => near(b[1] - a[1], v),
                    (Kind::Distance, [Some(a), Some(b)], Some(v)) => {
                        near((b[0] - a[0]).hypot(b[1] - a[1]), v)
                    }
                    (Kind::Symmetric, [Some(a), Some(b), Some(m)], _) => {
                        near((a[0] + b[0]) / 2.0, m[0]) && near((a[1] + b[1]) / 2.0, m[1])
                    }
                    (Kind::Angle, _, Some(v)) => {
                        let u = direction(&s, &c.refs[0].entity).expect("a segment");
                        let w = direction(&s, &c.refs[1].entity).expect("a segment");
                        near(
                            (u[0] * w[1] - u[1] * w[0])
                                .atan2(u[0] * w[0] + u[1] * w[1])
                                .to_degrees(),
                            v,
                        )
                    }
                    _ => continue,
                };
                assert!(
                    holds,
                    "{}: {} {:?} {:?} at {p:?}, value {v:?}",
                    s.name, c.id, c.kind, c.refs
                );
                *checked.entry(format!("{:?}", c.kind)).or_insert(0) += 1;
            }
        }
    }
    let expected = [
        ("Angle", 18),
        ("Coincident", 1957),
        ("Distance", 27),
        ("DistanceX", 49),
        ("DistanceY", 29),
        ("Horizontal", 71),
        ("Symmetric", 98),
        ("Vertical", 51),
    ];
    assert_eq!(checked, expected.into_iter().map(|(k, v)| (k.to_owned(), v)).collect());
}

/// The neutral arcs run counter-clockwise: a fillet arc, tangent to two lines, bulges toward
/// their corner. Its middle (counter-clockwise from start to end) must be nearer the corner
/// than the opposite point of the circle, for clockwise and counter-clockwise Onshape arcs.
#[test]
fn fillet_arcs_bulge_toward_their_corner() {
    let Some(files) = common::onshape_files() else { return };
    let (mut checked, mut clockwise_checked) = (0, 0);
    for (path, bytes) in &files {
        let json: serde_json::Value = serde_json::from_slice(bytes).expect("JSON");
        let clockwise: Vec<&str> = json
            .as_array()
            .into_iter()
            .flatten()
            .flat_map(|f| f["entities"].as_array().into_iter().flatten())
            .filter(|e| e["message"]["geometry"]["message"]["clockwise"] == true)
            .filter_map(|e| e["message"]["entityId"].as_str())
            .collect();
        for s in gcs_import::onshape::read(path, bytes).expect("reads") {
            for e in &s.entities {
                let Geometry::Arc { center, start, end } = &e.geometry else { continue };
                let lines: Vec<&str> = s
                    .constraints
                    .iter()
                    .filter(|c| c.kind == Kind::Tangent && c.refs.iter().any(|r| r.entity == e.id))
                    .filter_map(|c| c.refs.iter().find(|r| r.entity != e.id))
                    .filter(|r| matches!(entity(&s, &r.entity).geometry, Geometry::Segment { .. }))
                    .map(|r| r.entity.as_str())
                    .collect();
                let [l1, l2] = lines.as_slice() else { continue };
                let (Some(d1), Some(d2)) = (direction(&s, l1), direction(&s, l2)) else { continue };
                let cross = d1[0] * d2[1] - d1[1] * d2[0];
                if cross.abs() < 1e-3 * d1[0].hypot(d1[1]) * d2[0].hypot(d2[1]) {
                    continue; // parallel lines (a slot's end): no corner
                }
                let (Some(p1), Some(p2)) =
                    (position(&s, &part(l1, Part::Start)), position(&s, &part(l2, Part::Start)))
                else {
                    continue;
                };
                let t = ((p2[0] - p1[0]) * d2[1] - (p2[1] - p1[1]) * d2[0]) / cross;
                let corner = [p1[0] + t * d1[0], p1[1] + t * d1[1]];
                let c = [center[0].to_f64(), center[1].to_f64()];
                let angle = |p: &[Number]| (p[1].to_f64() - c[1]).atan2(p[0].to_f64() - c[0]);
                let (a0, a1) = (angle(start), angle(end));
                let sweep = (a1 - a0).rem_euclid(std::f64::consts::TAU);
                let r = (start[0].to_f64() - c[0]).hypot(start[1].to_f64() - c[1]);
                let mid = a0 + sweep / 2.0;
                let middle = [c[0] + r * mid.cos(), c[1] + r * mid.sin()];
                let opposite = [c[0] - r * mid.cos(), c[1] - r * mid.sin()];
                let dist = |p: [f64; 2]| (p[0] - corner[0]).hypot(p[1] - corner[1]);
                assert!(
                    dist(middle) < dist(opposite),
                    "{}: arc {} bulges away from its corner",
                    s.name,
                    e.id
                );
                checked += 1;
                clockwise_checked += usize::from(clockwise.contains(&e.id.as_str()));
            }
        }
    }
    assert_eq!((checked, clockwise_checked), (86, 0));
}

#[test]
fn sample_facts_checked_in_the_json() {
    let Some(files) = common::onshape_files() else { return };

    // Two sketch features, named by their index; lines from point, direction and parameters.
    let (_, s) = read_corpus_file(&files, "00270969_57f2a049a86627109b6a04e1_featurescript_008");
    assert_eq!(s.len(), 2);
    assert_eq!(s[0].name, "00270969_57f2a049a86627109b6a04e1_featurescript_008/0");
    assert_eq!(s[1].name, "00270969_57f2a049a86627109b6a04e1_featurescript_008/1");
    assert_eq!(
        (s[0].label.as_deref(), s[1].label.as_deref()),
        (Some("Sketch 1"), Some("Sketch 2"))
    );
    // pnt (0, 0.05506647378206253), dir (0, 1), parameters -0.05506647378206253 … 1.5401102996706963.
    let line = entity(&s[0], "2eQ4rM0k-HdoK-ovpq-o8LK-ECQmJEFddjlQ");
    assert_eq!(
        line.geometry,
        Geometry::Segment { start: at("0", "0"), end: at("0", "1595.1767734527589") }
    );
    // pnt (-0.009525, 1.5951767734527589), dir (-1, -1.2e-16), parameters -0.009525 … 0.009525.
    let line = entity(&s[0], "nHapqw77-W2Ot-T1yG-nR99-7niW1Qhh9KrT");
    assert_eq!(
        line.geometry,
        Geometry::Segment {
            start: at("0", "1595.1767734527589"),
            end: at("-19.05", "1595.1767734527589")
        }
    );
    assert!(!line.construction && !line.external);
    // x -0.28575, y 0.7975883867263794 (metres), exactly ×1000.
    assert_eq!(
        entity(&s[1], "79be023f-5c5a-4215-9aa0-b3b5a7cef71c").geometry,
        Geometry::Point { at: at("-285.75", "797.5883867263794") }
    );
    let c = constraint(&s[0], "nHapqw77-W2Ot-T1yG-nR99-7niW1Qhh9KrT.startSnap0");
    assert_eq!(c.kind, Kind::Coincident);
    assert_eq!(
        c.refs,
        vec![
            part("nHapqw77-W2Ot-T1yG-nR99-7niW1Qhh9KrT", Part::Start),
            part("2eQ4rM0k-HdoK-ovpq-o8LK-ECQmJEFddjlQ", Part::End)
        ]
    );
    // Its start is coincident with `externalSecond`, a query whose ids the dataset stripped.
    assert_eq!(
        skipped(&s[0], "2eQ4rM0k-HdoK-ovpq-o8LK-ECQmJEFddjlQ.startSnap0"),
        "COINCIDENT: reference to external geometry without its geometry in the file (externalSecond)"
    );

    // Dimensions typed as expressions: `(122.22/2) mm` from a line's start to a line, and
    // `.5*(0.25*inch)`.
    let (_, s) = read_corpus_file(&files, "00270094_7f4db2a310b479aaf1eb2e1e_featurescript_008");
    let c = constraint(&s[0], "mZjC5T7R-W9Du-vFHI-VErP-6YfJu3vqeO8w");
    assert_eq!((c.kind, c.value.clone(), c.driving), (Kind::Distance, Some(n("61.11")), true));
    assert_eq!(
        c.refs,
        vec![
            part("6wGZpdi3-nCUM-CUhw-pgvA-e3jNtQU3s0eZ", Part::Start),
            whole("0K1IcVTd-YdC1-qqWE-ILau-GqSoppPe6ZbO")
        ]
    );
    let (_, s) = read_corpus_file(&files, "00273546_57f46c0b42bdfa10a9cb13a2_featurescript_000");
    let c = constraint(&s[0], "3dc5b6d4-1437-4160-8a5b-bad7b1867366");
    assert_eq!((c.kind, c.value.clone()), (Kind::Radius, Some(n("3.175"))));

    // A clockwise arc (centre (-0.0975…, 0.004), radius 0.004, parameters -π … 0): Onshape's
    // start (-101.5…, 4) is the neutral end, and the counter-clockwise arc passes over the top.
    let (_, s) = read_corpus_file(&files, "00273703_57f4c32907e7ba110aaa239b_featurescript_000");
    assert_eq!(s[1].label.as_deref(), Some("Sketch lato base"));
    let Geometry::Arc { center, start, end } =
        &entity(&s[1], "8cef3c61-8763-49e1-bfd6-77bc748f1327").geometry
    else {
        panic!("an arc")
    };
    assert_eq!(center, &at("-97.51246727790153", "4"));
    assert!(close(start, [-93.51246727790152, 4.0]) && close(end, [-101.51246727790153, 4.0]));

    // A zero-length line (parameters 0.0019398416822009887 and 0.001939841682200987) is its
    // carrier, with its two ends on it: the constraints on its direction are the carrier's, those
    // on its ends the end points'.
    let (_, s) = read_corpus_file(&files, "00271719_e4b75658a7c39a68a2bc7045_featurescript_003");
    let zero = "f79a1f50-f10d-458a-bd2b-381a696e89d2";
    assert!(matches!(entity(&s[0], zero).geometry, Geometry::Line { .. }));
    let uses = |r: &Ref| -> Vec<Kind> {
        let mut k: Vec<Kind> =
            s[0].constraints.iter().filter(|c| c.refs.contains(r)).map(|c| c.kind).collect();
        k.sort_by_key(|k| format!("{k:?}"));
        k
    };
    assert_eq!(
        uses(&whole(zero)),
        [Kind::Perpendicular, Kind::PointOnObject, Kind::PointOnObject, Kind::Vertical]
    );
    for end in ["start", "end"] {
        assert_eq!(uses(&whole(&format!("{zero}#{end}"))), [Kind::Coincident, Kind::PointOnObject]);
    }
    assert!(s[0].skipped.iter().all(|k| !k.reason.contains(zero)));
    // Driven (reference) dimensions carry no value in the file.
    let c = constraint(&s[0], "8ByAct7U-zcxo-uNBb-MQog-EfCcXD3sOVtJ");
    assert_eq!((c.kind, c.value.clone(), c.driving), (Kind::DistanceY, None, false));
    assert_eq!(
        c.refs,
        vec![
            part("91a9b8d5-3142-4450-8c1b-82cee981a20a", Part::Start),
            part("bd4df1b0-1118-45d1-b419-0e50d5e8ae20", Part::End)
        ]
    );

    // Mirrors: of two points about a line, and of two circles (centres mirrored, radii equal).
    let (_, s) = read_corpus_file(&files, "00271707_acaa045bb4d84be94f06d392_featurescript_000");
    let c = constraint(&s[5], "ff7fd2df-001f-41b1-83f7-a7542ad42c110.MirrorCS.begCons");
    assert_eq!(c.kind, Kind::Symmetric);
    assert_eq!(
        c.refs,
        vec![
            part("BiehdWAl-vJ2O-tMdK-E08p-BEBwONMQSojy.top", Part::Start),
            part("ff7fd2df-001f-41b1-83f7-a7542ad42c110.MirrorCS", Part::Start),
            whole("d815f340-7c54-4809-9d1e-89aa200eef91.anchor2"),
        ]
    );
    // An angle of 20°, drawn as 160° from the first line to the second.
    assert_eq!(constraint(&s[2], "vUgtdZQd-0Mhc-8eCK-azf2-3BmTnTccpEpP").value, Some(n("160")));
    // A diameter given by a variable of the part studio.
    assert!(skipped(&s[0], "QcAsTxsS-cix0-7adF-wd3o-1sdfmQNRcXwN").contains("#VentDiam"));

    let (_, s) = read_corpus_file(&files, "00271719_e4b75658a7c39a68a2bc7045_featurescript_003");
    let id = "de1d9d79-03ef-498b-80ce-4fa4191665c60.MirrorC.cons";
    let (a, b, m) = (
        "gzTHyhAb-8QYI-Jp3g-zHrh-nQgpPqgSNEuj",
        "de1d9d79-03ef-498b-80ce-4fa4191665c60.MirrorC",
        "JiI3Aw7l-60l1-cnMZ-NSYd-OFe8kZ509g45",
    );
    assert_eq!(
        constraint(&s[1], id).refs,
        vec![part(a, Part::Center), part(b, Part::Center), whole(m)]
    );
    let equal = constraint(&s[1], &format!("{id}#equal"));
    assert_eq!((equal.kind, equal.refs.clone()), (Kind::Equal, vec![whole(a), whole(b)]));

    // A slot along a clockwise arc, with clockwise caps: each cap bulges away from the other.
    let (_, s) = read_corpus_file(&files, "00275001_57f5a6c110cee010fd6de5c2_featurescript_001");
    let cap =
        |end: &str| match &entity(&s[4], &format!("5cd3acbe-21e1-45f2-935c-4cbfd4906adf.0.{end}"))
            .geometry
        {
            Geometry::Arc { center, start, end } => {
                [center, start, end].map(|p| [p[0].to_f64(), p[1].to_f64()])
            }
            other => panic!("{other:?}"),
        };
    for (this, other) in [(cap("startCap"), cap("endCap")), (cap("endCap"), cap("startCap"))] {
        let [c, a, b] = this;
        let angle = |p: [f64; 2]| (p[1] - c[1]).atan2(p[0] - c[0]);
        let mid = angle(a) + (angle(b) - angle(a)).rem_euclid(std::f64::consts::TAU) / 2.0;
        let (r, far) = ((a[0] - c[0]).hypot(a[1] - c[1]), other[0]);
        let dist = |sign: f64| {
            (c[0] + sign * r * mid.cos() - far[0]).hypot(c[1] + sign * r * mid.sin() - far[1])
        };
        assert!(dist(1.0) > dist(-1.0), "a slot's cap bulges inward");
    }

    // An angle of 290° drawn as -70°.
    let (_, s) = read_corpus_file(&files, "00271987_40c36c005a002394b4719b25_featurescript_000");
    assert_eq!(
        constraint(&s[4], "24c380b6-d4d8-43b5-84c6-3a3074cec00f.angle").value,
        Some(n("-70"))
    );
}

#[test]
fn each_entity_type() {
    let s = data("entities.json");
    // The extrude between the two sketches is passed over; the index counts sketches only.
    assert_eq!(s.len(), 2);
    assert_eq!((s[0].name.as_str(), s[0].label.as_deref()), ("entities/0", Some("Entities")));
    assert_eq!((s[1].name.as_str(), s[1].label.as_deref()), ("entities/1", Some("Empty")));
    assert!(s[1].entities.is_empty() && s[1].skipped.is_empty());
    let s = &s[0];
    let ids: Vec<&str> = s.entities.iter().map(|e| e.id.as_str()).collect();
    fn boxes(id: &str, kind: &str, edges: [&str; 4]) -> Vec<String> {
        edges.into_iter().chain(["center"]).map(|e| format!("{id}.{kind}.{e}")).collect()
    }
    let mut expected: Vec<String> =
        ["p1", "s1", "z1", "z1#start", "z1#end", "l1", "c1", "a1", "a2", "e1", "e2", "e3", "b1"]
            .map(str::to_owned)
            .into();
    expected.extend(boxes("t1", "sketch_text", ["baseline", "ascent", "left", "right"]));
    expected.extend(boxes("m1", "sketch_image", ["bottom", "top", "left", "right"]));
    assert_eq!(ids, expected);
    // A text box: the rectangle on its baseline (10 mm) up to its ascent (4 mm), its proportions
    // kept; an image box: its aspect ratio (1.5) over its x axis.
    assert_eq!(
        entity(s, "t1.sketch_text.ascent").geometry,
        Geometry::Segment { start: at("0", "4"), end: at("10", "4") }
    );
    assert_eq!(entity(s, "t1.sketch_text.center").geometry, Geometry::Point { at: at("5", "2") });
    assert_eq!(constraint(s, "t1#ratio").value, Some(n("0.4")));
    assert_eq!(
        constraint(s, "t1#corner3").refs,
        [part("t1.sketch_text.ascent", Part::Start), part("t1.sketch_text.left", Part::End)]
    );
    assert_eq!(
        entity(s, "m1.sketch_image.right").geometry,
        Geometry::Segment { start: at("10", "0"), end: at("10", "15") }
    );
    assert_eq!(constraint(s, "m1#ratio").value, Some(n("1.5")));
    // Two boxes, and the zero-length line's ends on its carrier.
    assert_eq!(s.constraints.len(), 2 * 9 + 2);
    assert_eq!(entity(s, "p1").geometry, Geometry::Point { at: at("10", "20") });
    assert_eq!(
        entity(s, "s1").geometry,
        Geometry::Segment { start: at("1", "0"), end: at("31", "0") }
    );
    assert!(entity(s, "s1").construction && !entity(s, "p1").construction);
    // A zero-length line: its carrier (through its point, a centimetre along its direction)
    // and its two ends on it, both at its point.
    assert_eq!(entity(s, "z1").geometry, Geometry::Line { a: at("5", "7"), b: at("5", "17") });
    for end in ["z1#start", "z1#end"] {
        assert_eq!(entity(s, end).geometry, Geometry::Point { at: at("5", "7") });
        let on = constraint(s, &format!("{end}-on"));
        assert_eq!(
            (on.kind, on.refs.clone()),
            (Kind::PointOnObject, vec![whole(end), whole("z1")])
        );
    }
    assert_eq!(entity(s, "l1").geometry, Geometry::Line { a: at("0", "10"), b: at("1000", "10") });
    assert_eq!(
        entity(s, "c1").geometry,
        Geometry::Circle { center: at("50", "0"), radius: n("12.5") }
    );
    // Counter-clockwise from (10, 0) to (0, 10).
    let Geometry::Arc { center, start, end } = &entity(s, "a1").geometry else { panic!("an arc") };
    assert!(center == &at("0", "0") && close(start, [10.0, 0.0]) && close(end, [0.0, 10.0]));
    // Clockwise in Onshape from (10, 0) to (0, -10): counter-clockwise from (0, -10) to (10, 0).
    let Geometry::Arc { start, end, .. } = &entity(s, "a2").geometry else { panic!("an arc") };
    assert!(close(start, [0.0, -10.0]) && close(end, [10.0, 0.0]));
    assert_eq!(
        entity(s, "e1").geometry,
        Geometry::Ellipse { center: at("0", "0"), major: at("0", "20"), minor_radius: n("10") }
    );
    let Geometry::EllipticalArc { major, minor_radius, start, end, .. } = &entity(s, "e2").geometry
    else {
        panic!("an elliptical arc")
    };
    assert!(major == &at("20", "0") && minor_radius == &n("10"));
    assert!(close(start, [0.0, -10.0]) && close(end, [20.0, 0.0]));
    // The minor radius larger than `radius`: the major axis is the other one.
    assert_eq!(
        entity(s, "e3").geometry,
        Geometry::Ellipse { center: at("0", "0"), major: at("0", "20"), minor_radius: n("10") }
    );
    assert_eq!(
        entity(s, "b1").geometry,
        Geometry::BSpline {
            degree: 2,
            poles: vec![at("0", "0"), at("10", "10"), at("20", "0"), at("30", "10")],
            weights: None,
            knots: vec![(n("0"), 3), (n("1"), 1), (n("2"), 3)],
            periodic: false,
        }
    );
    for (id, why) in [
        ("b2", "trimmed"),
        ("b3", "periodic"),
        ("i1", "interpolated spline"),
        ("x1", "BTCurveGeometryConic"),
        ("u1", "BTMSketchSomethingNew"),
    ] {
        assert!(skipped(s, id).contains(why), "{id}: {}", skipped(s, id));
    }
    assert_eq!(s.skipped.len(), 5);
}

#[test]
fn each_constraint_type() {
    let s = data("constraints.json");
    let s = &s[0];
    let c = |id: &str| {
        let c = constraint(s, id);
        (c.kind, c.refs.clone())
    };
    let v = |id: &str| constraint(s, id).value.clone();
    let (p1, p2, p3, p4) = (whole("p1"), whole("p2"), whole("p3"), whole("p4"));
    let (s1, s2, s3, s4) = (whole("s1"), whole("s2"), whole("s3"), whole("s4"));
    let (c1, c2, a1) = (whole("c1"), whole("c2"), whole("a1"));
    assert_eq!(c("k01"), (Kind::Coincident, vec![p1.clone(), part("s1", Part::Start)]));
    assert_eq!(c("k02"), (Kind::PointOnObject, vec![p2.clone(), s2.clone()]));
    assert_eq!(c("k03"), (Kind::Collinear, vec![s3.clone(), s4.clone()]));
    assert_eq!(c("k04"), (Kind::Concentric, vec![c1.clone(), c2.clone()]));
    assert_eq!(c("k04#equal"), (Kind::Equal, vec![c1.clone(), c2.clone()]));
    assert_eq!(c("k05"), (Kind::PointOnObject, vec![p3.clone(), s1.clone()]));
    assert_eq!(c("k06"), (Kind::Horizontal, vec![s1.clone()]));
    assert_eq!(c("k07"), (Kind::Vertical, vec![p1.clone(), p2.clone()]));
    assert_eq!(c("k08"), (Kind::Parallel, vec![s1.clone(), s2.clone()]));
    assert_eq!(c("k09"), (Kind::Perpendicular, vec![s1.clone(), s3.clone()]));
    assert_eq!(c("k10"), (Kind::Tangent, vec![s1.clone(), c1.clone()]));
    assert_eq!(c("k11"), (Kind::PointOnObject, vec![part("a1", Part::Center), s1.clone()]));
    assert_eq!(c("k12"), (Kind::Equal, vec![s1.clone(), s2.clone()]));
    assert_eq!(c("k13"), (Kind::Equal, vec![c1.clone(), a1.clone()]));
    assert_eq!(c("k14"), (Kind::Concentric, vec![c1.clone(), a1.clone()]));
    assert_eq!(c("k15"), (Kind::Coincident, vec![p1.clone(), part("c1", Part::Center)]));
    assert_eq!(c("k16"), (Kind::Midpoint, vec![p1.clone(), s1.clone()]));
    assert_eq!(c("k17"), (Kind::Symmetric, vec![p1.clone(), p2.clone(), p3.clone()]));
    assert_eq!(c("k18"), (Kind::Midpoint, vec![p4.clone(), s2.clone()]));
    assert_eq!(
        c("k19"),
        (Kind::Symmetric, vec![part("s1", Part::Start), part("s2", Part::Start), s3.clone()])
    );
    assert_eq!(
        c("k20"),
        (Kind::Symmetric, vec![part("c1", Part::Center), part("c2", Part::Center), s3.clone()])
    );
    assert_eq!(c("k20#equal"), (Kind::Equal, vec![c1.clone(), c2.clone()]));
    // Mirrored segments (their carriers), not said by mirrors of both their end points.
    assert_eq!(c("k21"), (Kind::Symmetric, vec![s1.clone(), s2.clone(), s3.clone()]));
    assert_eq!(
        (c("k22"), v("k22")),
        ((Kind::Distance, vec![p1.clone(), p2.clone()]), Some(n("15")))
    );
    assert_eq!(
        (c("k23"), v("k23")),
        ((Kind::Distance, vec![p1.clone(), s1.clone()]), Some(n("3.175")))
    );
    // p1 is 10 mm left of p2: the horizontal distance from p2 to p1 is -10.
    assert_eq!(
        (c("k24"), v("k24")),
        ((Kind::DistanceX, vec![p2.clone(), p1.clone()]), Some(n("-10")))
    );
    assert_eq!((c("k25"), v("k25")), ((Kind::DistanceY, vec![p1.clone(), p2.clone()]), None));
    assert!(!constraint(s, "k25").driving && constraint(s, "k24").driving);
    assert_eq!(skipped(s, "k26"), "DISTANCE: between line, arc is not expressible");
    assert_eq!((c("k27"), v("k27")), ((Kind::Length, vec![s1.clone()]), Some(n("30"))));
    assert_eq!((c("k28"), v("k28")), ((Kind::Radius, vec![a1.clone()]), Some(n("10"))));
    assert_eq!((c("k29"), v("k29")), ((Kind::Diameter, vec![c1.clone()]), Some(n("25"))));
    assert!(skipped(s, "k30").contains("`#d`"));
    // s1 runs along +x, s3 along -y: from the first to the second is -90°.
    assert_eq!((c("k31"), v("k31")), ((Kind::Angle, vec![s1.clone(), s3.clone()]), Some(n("-90"))));
    assert_eq!(c("k32"), (Kind::Fix, vec![p4.clone()]));
    assert_eq!(
        (c("k33"), v("k33")),
        ((Kind::Distance, vec![p1.clone(), s3.clone()]), Some(n("10")))
    );
    assert_eq!(c("k34"), (Kind::Fix, vec![s4.clone()]));
    assert!(skipped(s, "k35").contains("SILHOUETTE_START"));
    // Offsets: a curve and its offset parallel (concentric for circles); with a second pair,
    // that pair too, and the offsets' starts as far from their curves. The first pair's
    // relation is stated once for all the offsets of one operation.
    assert_eq!(c("k36#master"), (Kind::Parallel, vec![s1.clone(), s2.clone()]));
    assert_eq!(c("k49#master"), (Kind::Parallel, vec![s3.clone(), s4.clone()]));
    assert_eq!(c("k49#second"), (Kind::Parallel, vec![s1.clone(), s2.clone()]));
    assert_eq!(
        c("k49"),
        (
            Kind::EqualPointLineDistances,
            vec![part("s4", Part::Start), s3.clone(), part("s2", Part::Start), s1.clone()]
        )
    );
    // Circles: concentric, and the gap of a circle's pair (a difference of radii) equal to the
    // gap of a segment's pair (its offset's start to it).
    assert_eq!(c("k50#master"), (Kind::Concentric, vec![c1.clone(), c2.clone()]));
    assert_eq!(
        c("k50"),
        (Kind::EqualGaps, vec![c1.clone(), c2.clone(), part("s2", Part::Start), s1.clone()])
    );
    assert!(s.constraints.iter().all(|x| x.id != "k51#master"), "said by k49#master");
    assert_eq!(c("k51#second"), (Kind::Parallel, vec![s2.clone(), s1.clone()]));
    assert_eq!(c("k51").1[2], part("s1", Part::Start));
    assert_eq!(
        skipped(s, "k37"),
        "CIRCULAR_PATTERN: the pattern's count is not a positive integer"
    );
    // A linear pattern: each instance one step along s1 from the one before; an empty
    // instance is not made.
    let (s1_start, s1_end) = (part("s1", Part::Start), part("s1", Part::End));
    let step = |a: &Ref, b: &Ref| vec![a.clone(), b.clone(), s1_start.clone(), s1_end.clone()];
    assert_eq!(c("k38#0,1"), (Kind::Translated, step(&p1, &p2)));
    assert_eq!(c("k38#0,2"), (Kind::Translated, step(&p2, &p4)));
    assert!(s.constraints.iter().all(|x| x.id != "k38#0,3"));
    // A closed circular pattern of 4: instance 2 is its seed turned by 180°; a circle's centre
    // turns and its radius stays.
    assert_eq!(
        (c("k47#0,2"), v("k47#0,2")),
        ((Kind::Rotated, vec![p1.clone(), p2.clone(), p3.clone()]), Some(n("180")))
    );
    assert_eq!(
        c("k47#1,2"),
        (Kind::Rotated, vec![part("c1", Part::Center), part("c2", Part::Center), p3.clone()])
    );
    assert_eq!(c("k47#1,2#radius"), (Kind::Equal, vec![c1.clone(), c2.clone()]));
    // A closed circular pattern of 6: turns by 60° (a regular hexagon in the model).
    assert_eq!(c("k48#0,1"), (Kind::Rotated, vec![p1.clone(), p2.clone(), p3.clone()]));
    assert!(v("k48#0,1").is_some_and(|d| d == n("60") || d == n("-60")), "{:?}", v("k48#0,1"));
    assert_eq!(skipped(s, "k39"), "PIERCE: this constraint type is not supported");
    assert_eq!(
        skipped(s, "k40"),
        "COINCIDENT: reference to external geometry without its geometry in the file (externalSecond)"
    );
    assert_eq!(skipped(s, "k41"), "HORIZONTAL: references the unknown entity `nope`");
    // A zero-length line's end is a point of its own; the line, its carrier.
    assert_eq!(c("k42"), (Kind::Coincident, vec![whole("z1#start"), part("s1", Part::End)]));
    assert_eq!(c("k43"), (Kind::Parallel, vec![whole("z1"), s1.clone()]));
    // a2 is clockwise in Onshape: its `.start` is the neutral end point.
    assert_eq!(c("k44"), (Kind::Coincident, vec![part("a2", Part::End), part("s4", Part::End)]));
    assert_eq!(c("k45"), (Kind::Symmetric, vec![p1.clone(), p2.clone(), s3.clone()]));
    // s2 runs from x = 30 to x = 0.
    assert_eq!((c("k46"), v("k46")), ((Kind::DistanceX, vec![s2.clone()]), Some(n("-30"))));
    assert_eq!(s.skipped.len(), 7);
    // Two `#equal`s, the patterns' second and third constraints, the offsets' second and
    // third (k51's first pair said by k49), the zero-length line's ends on its carrier.
    assert_eq!(s.constraints.len(), 51 - 7 + 2 + 1 + 2 + 2 + 1 + 2 + 2);
}

#[test]
fn a_feature_object_and_a_features_list() {
    let s = data("wrapped.json");
    assert_eq!(s.len(), 1);
    assert_eq!((s[0].name.as_str(), s[0].label.as_deref()), ("wrapped/0", Some("Wrapped")));
    assert_eq!(s[0].entities[0].geometry, Geometry::Point { at: at("1", "-2") });
    let s = data("features.json");
    assert_eq!(s.len(), 1);
    assert_eq!((s[0].name.as_str(), s[0].label.as_deref()), ("features/0", Some("Listed")));
    assert_eq!(s[0].entities[0].geometry, Geometry::Point { at: at("500", "250") });
}

fn error(json: &str) -> ImportError {
    gcs_import::onshape::read("bad.json", json.as_bytes()).expect_err("an error")
}

#[test]
fn bad_input_is_a_clear_error() {
    let e = error("[{\"featureType\": \"newSketch\",");
    assert_eq!((e.file.as_str(), e.line), ("bad.json", Some(1)));
    assert!(e.message.starts_with("not JSON"), "{e}");
    assert!(error("42").message.contains("expected a list of Onshape features"));
    let e = error("[1]");
    assert_eq!(e.element.as_deref(), Some("features[0]"));
    assert!(e.message.contains("expected an object"), "{e}");
    assert!(error("[{}]").message.contains("featureType"));
    assert!(error("{\"name\": \"x\"}").message.contains("featureType"));
    let e = error(r#"[{"featureType": "newSketch", "entities": {}}]"#);
    assert!(e.message.contains("`entities`: expected a list"), "{e}");
    let e = error(
        r#"[{"featureType": "extrude"}, {"featureType": "newSketch", "entities": [
            {"typeName": "BTMSketchPoint", "message": {"entityId": "p", "x": 0.0, "y": 0.0}},
            {"typeName": "BTMSketchPoint", "message": {"entityId": "q", "x": "one", "y": 0.0}}]}]"#,
    );
    assert_eq!(e.element.as_deref(), Some("features[1].entities[1] (id q)"));
    assert_eq!(e.message, "field `x`: expected a number, found a string");
    assert_eq!(
        e.to_string(),
        "bad.json: features[1].entities[1] (id q): field `x`: expected a number, found a string"
    );
    let e = error(
        r#"[{"featureType": "newSketch", "entities": [{"typeName": "BTMSketchPoint", "message": {"x": 0}}]}]"#,
    );
    assert_eq!(e.element.as_deref(), Some("features[0].entities[0]"));
    assert!(e.message.contains("entityId"));
    let e = error(
        r#"[{"featureType": "newSketch", "constraints": [
            {"typeName": "BTMSketchConstraint", "message": {"entityId": "c", "parameters": []}}]}]"#,
    );
    assert_eq!(e.element.as_deref(), Some("features[0].constraints[0] (id c)"));
    assert!(e.message.contains("constraintType"));
    let e = error(
        r#"[{"featureType": "newSketch", "constraints": [{"message": {"entityId": "c",
            "constraintType": "FIX", "parameters": [{"typeName": "BTMParameterString"}]}}]}]"#,
    );
    assert_eq!(e.element.as_deref(), Some("features[0].constraints[0] (id c)"));
    assert!(e.message.starts_with("parameters[0]"), "{e}");
}

#[test]
fn an_unknown_reference_is_skipped_and_the_rest_read() {
    let json = r#"[{"featureType": "newSketch", "name": "S", "entities": [
        {"typeName": "BTMSketchPoint", "message": {"entityId": "p", "x": 0.0, "y": 0.0}},
        {"typeName": "BTMSketchPoint", "message": {"entityId": "p", "x": 1.0, "y": 0.0}},
        {"typeName": "BTMSketchPoint", "message": {"entityId": "q", "x": 0.001, "y": 0.0}}],
      "constraints": [
        {"message": {"entityId": "c1", "constraintType": "COINCIDENT", "parameters": [
          {"typeName": "BTMParameterString", "message": {"parameterId": "localFirst", "value": "p"}},
          {"typeName": "BTMParameterString", "message": {"parameterId": "localSecond", "value": "ghost.start"}}]}},
        {"message": {"entityId": "c2", "constraintType": "HORIZONTAL", "parameters": [
          {"typeName": "BTMParameterString", "message": {"parameterId": "localFirst", "value": "p"}},
          {"typeName": "BTMParameterString", "message": {"parameterId": "localSecond", "value": "q"}}]}},
        {"message": {"entityId": "c3", "constraintType": "HORIZONTAL", "parameters": [
          {"typeName": "BTMParameterString", "message": {"parameterId": "localFirst", "value": "q.start"}}]}},
        {"message": {"entityId": "c2", "constraintType": "FIX", "parameters": []}}]}]"#;
    let s = gcs_import::onshape::read("dir/unknown.json", json.as_bytes()).expect("reads");
    assert_eq!(s[0].name, "unknown/0");
    assert_eq!(s[0].entities.len(), 2);
    assert_eq!(s[0].constraints.len(), 1);
    assert_eq!(constraint(&s[0], "c2").refs, vec![whole("p"), whole("q")]);
    let reasons: Vec<(&str, &str)> =
        s[0].skipped.iter().map(|k| (k.item.as_str(), k.reason.as_str())).collect();
    assert_eq!(
        reasons,
        [
            ("p", "a second entity with the id `p` (features[0].entities[1])"),
            ("c1", "COINCIDENT: references the unknown entity `ghost.start`"),
            ("c3", "HORIZONTAL: references `q.start`: the entity `q` has no point `start`"),
            ("c2", "a second constraint with the id `c2` (features[0].constraints[3])"),
        ]
    );
}

/// Interpolated splines: the B-spline Onshape builds through the points (centripetal knots,
/// the handles as the second and last-but-one control points) passes through every
/// interpolation point at its knot, on every spline of SketchGraphs' sample that is read; the
/// sample's handles are those of that form, which is what makes it Onshape's.
#[test]
fn interpolated_splines_pass_through_their_points_at_their_knots() {
    use num_traits::ToPrimitive;
    let Some(files) = common::onshape_files() else { return };
    let mut splines = 0;
    let mut through = 0;
    for (path, bytes) in &files {
        let json: serde_json::Value = serde_json::from_slice(bytes).expect("JSON");
        for (s, feature) in gcs_import::onshape::read(path, bytes)
            .expect("reads")
            .iter()
            .zip(json.as_array().expect("features"))
        {
            for e in &s.entities {
                let Geometry::BSpline { degree, poles, knots, periodic, .. } = &e.geometry else {
                    continue;
                };
                let source = feature["entities"]
                    .as_array()
                    .expect("entities")
                    .iter()
                    .find(|x| x["message"]["entityId"] == e.id.as_str())
                    .expect("the entity");
                let g = &source["message"]["geometry"]["message"];
                if source["message"]["geometry"]["typeName"] != "BTCurveGeometryInterpolatedSpline"
                {
                    continue;
                }
                splines += 1;
                let q: Vec<f64> = g["interpolationPoints"]
                    .as_array()
                    .expect("points")
                    .iter()
                    .map(|x| x.as_f64().expect("a number") * 1000.0)
                    .collect();
                let m = q.len() / 2;
                assert_eq!(*degree, 3);
                assert_eq!(poles.len(), if *periodic { m } else { m + 2 }, "{}", e.id);
                if !*periodic {
                    let handle = |x: &str, y: &str| {
                        [g[x].as_f64().unwrap() * 1000.0, g[y].as_f64().unwrap() * 1000.0]
                    };
                    assert!(close(&poles[1], handle("startHandleX", "startHandleY")));
                    assert!(close(&poles[m], handle("endHandleX", "endHandleY")));
                    assert!(
                        close(&poles[0], [q[0], q[1]])
                            && close(&poles[m + 1], [q[2 * m - 2], q[2 * m - 1]])
                    );
                }
                let mut flat = Vec::new();
                for (k, mult) in knots {
                    flat.extend(std::iter::repeat_n(k.0.clone(), *mult as usize));
                }
                // Every interpolation point at its knot: the ends (open) are the end control
                // points, the others are held there by `SplinePoint`s whose value is the knot.
                let inner: Vec<usize> =
                    if *periodic { (0..m).collect() } else { (1..m - 1).collect() };
                for k in inner {
                    let c = constraint(s, &format!("{}#through{k}", e.id));
                    assert_eq!(c.kind, Kind::SplinePoint);
                    assert_eq!(c.refs, [whole(&format!("{}.{k}.internal", e.id)), whole(&e.id)]);
                    let t = &c.value.as_ref().expect("a parameter").0;
                    let basis = gcs_model::spline::basis(3, poles.len(), &flat, &[], *periodic, t)
                        .expect("a knot in range");
                    let x: Vec<f64> = (0..2)
                        .map(|d| {
                            basis
                                .iter()
                                .map(|(i, b)| b.to_f64().unwrap() * poles[*i][d].to_f64())
                                .sum()
                        })
                        .collect();
                    assert!(
                        (x[0] - q[2 * k]).abs() < 1e-9 && (x[1] - q[2 * k + 1]).abs() < 1e-9,
                        "{} point {k}: {x:?} vs {:?}",
                        e.id,
                        &q[2 * k..2 * k + 2]
                    );
                    through += 1;
                }
            }
        }
    }
    // 10 interpolated splines in the sample, 4 of them trimmed (skipped); 24 inner points.
    assert_eq!((splines, through), (6, 24));
}

/// An interpolated spline on its own and joined to a line: its start and end are its first
/// and last interpolation points (Onshape's coincidence of the two names is a note), its end
/// derivatives the legs of its control polygon, a tangency at its joined start the leg
/// parallel to the line; a periodic one has all its points on it. Degrees of freedom: an open
/// spline through 5 points with free handles 2·5 + 4, a periodic one through 4 points 2·4.
#[test]
fn interpolated_splines_lower_and_count_their_points_and_handles() {
    use num_traits::ToPrimitive;
    let sketches = data("interpolated.json");
    let s = &sketches[0];
    assert!(s.skipped.is_empty(), "{:?}", s.skipped);
    assert_eq!(s.notes.len(), 1);
    assert_eq!(s.notes[0].item, "start");
    let handle = constraint(s, "handle");
    assert_eq!(
        (handle.kind, handle.refs.clone()),
        (Kind::Horizontal, vec![part("s", Part::StartTangent)])
    );
    let l = gcs_import::lower(s);
    assert!(l.complete(), "{:?}", l.skipped);
    let sys = &l.system;
    let kind = |id: &str| sys.constraint(sys.constraint_by_id(id).expect(id)).kind;
    assert_eq!(kind("tangent"), gcs_model::ConstraintKind::Parallel);
    assert_eq!(kind("s#through2"), gcs_model::ConstraintKind::SplinePoint);
    assert_eq!(kind("c#through0"), gcs_model::ConstraintKind::SplinePoint);
    let a = gcs_analysis::analyze(sys, &Default::default()).expect("analysed");
    assert!(a.redundant.is_empty(), "{:?}", a.redundant);
    // s 14, c 8, l 4, p 2; join 2, tangent 1, on 2, handle 1, ring 1.
    assert_eq!(a.dof + a.trivial_motions, 14 + 8 + 4 + 2 - 7);
    // The control points the reader solved make the curve pass through the drawn points.
    let point = |id: &str| match &sys.entity(sys.entity_by_id(id).unwrap()).geometry {
        gcs_model::entity::Geometry::Point { at: Some(at) } => {
            at.iter().map(|x| x.to_f64().unwrap()).collect::<Vec<_>>()
        }
        other => panic!("{other:?}"),
    };
    assert!((point("s.2.internal")[1] - 274.1506099700928).abs() < 1e-9);
}

/// An offset of two joined segments: its equal gaps are measured from the corner where the
/// two offsets meet (the corner on the bisector of the two curves), not from the offsets'
/// starts — the same equation given the offset's parallels, so the analysis is the same
/// either way (rank, DOF, no redundancy), and the corner binds one point.
#[test]
fn offset_gaps_are_measured_at_the_corner_where_the_offsets_meet() {
    let sketches = data("offset_corner.json");
    let s = &sketches[0];
    assert!(s.skipped.is_empty(), "{:?}", s.skipped);
    let gap = constraint(s, "k3");
    assert_eq!(
        (gap.kind, gap.refs.clone()),
        (
            Kind::EqualPointLineDistances,
            vec![part("o1", Part::End), whole("m1"), part("o2", Part::Start), whole("m2")]
        )
    );
    // The same sketch with the gaps from the starts, as before: the same analysis.
    let mut starts = s.clone();
    for c in &mut starts.constraints {
        if c.id == "k3" {
            c.refs[0] = part("o1", Part::Start);
            c.refs[2] = part("o2", Part::Start);
        }
    }
    let analysed = |s: &Sketch| {
        let l = gcs_import::lower(s);
        assert!(l.complete(), "{:?}", l.skipped);
        let a = gcs_analysis::analyze(&l.system, &Default::default()).expect("analysed");
        (a.rank, a.dof, a.redundant.len())
    };
    let corner = analysed(s);
    assert_eq!(corner, analysed(&starts));
    // 4 segments (16) − 2 coincidences (4) − 2 parallels (2) − the equal gaps (1) − 3 motions.
    assert_eq!(corner, (7, 16 - 7 - 3, 0));
}
