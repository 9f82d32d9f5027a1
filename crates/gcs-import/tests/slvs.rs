//! The SolveSpace reader: the corpus of SolveSpace's own test files, the hand-written files of
//! `tests/data/slvs/` (one mapping each), and bad input.

mod common;

use std::path::{Path, PathBuf};

use gcs_import::ir::{Constraint, Geometry, Kind, Number, Part, Ref, Sketch};
use gcs_import::{Format, ImportError};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/slvs").join(name)
}

fn read_path(path: &Path) -> Result<Vec<Sketch>, ImportError> {
    let bytes = std::fs::read(path).expect("readable test file");
    gcs_import::slvs::read(&path.to_string_lossy(), &bytes)
}

fn read_data(name: &str) -> Vec<Sketch> {
    read_path(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A corpus file, by its path under `solvespace/`; `None` without the corpus.
fn corpus(rel: &str) -> Option<Vec<Sketch>> {
    let path = common::external()?.join("solvespace").join(rel);
    Some(read_path(&path).unwrap_or_else(|e| panic!("{rel}: {e}")))
}

fn sketch<'a>(sketches: &'a [Sketch], name: &str) -> &'a Sketch {
    sketches.iter().find(|s| s.name == name).unwrap_or_else(|| panic!("no sketch {name}"))
}

fn constraint<'a>(s: &'a Sketch, id: &str) -> &'a Constraint {
    s.constraints.iter().find(|c| c.id == id).unwrap_or_else(|| panic!("no {id} in {}", s.name))
}

fn skipped_reason<'a>(s: &'a Sketch, item: &str) -> &'a str {
    s.skipped
        .iter()
        .find(|k| k.item == item)
        .map(|k| k.reason.as_str())
        .unwrap_or_else(|| panic!("{item} not skipped in {}", s.name))
}

fn note<'a>(s: &'a Sketch, item: &str) -> &'a str {
    s.notes
        .iter()
        .find(|k| k.item == item)
        .map(|k| k.reason.as_str())
        .unwrap_or_else(|| panic!("{item} not in the notes of {}", s.name))
}

fn geometry<'a>(s: &'a Sketch, id: &str) -> &'a Geometry {
    &s.entities.iter().find(|e| e.id == id).unwrap_or_else(|| panic!("no {id}")).geometry
}

fn n(x: i64) -> Number {
    Number::from_i64(x)
}

fn num(text: &str) -> Number {
    Number::parse(text).expect("a number")
}

fn refs(c: &Constraint) -> Vec<(String, Part)> {
    c.refs.iter().map(|r| (r.entity.clone(), r.part)).collect()
}

fn r(entity: &str, part: Part) -> (String, Part) {
    (entity.to_owned(), part)
}

// ---------------------------------------------------------------- the corpus

#[test]
fn every_corpus_file_reads() {
    let Some(dir) = common::external() else { return };
    let files = common::files_with_suffix(&dir.join("solvespace"), ".slvs");
    assert_eq!(files.len(), 40, "the corpus has 40 .slvs files");
    let mut sketches = 0;
    for path in &files {
        let bytes = std::fs::read(path).unwrap();
        assert_eq!(Format::detect(&path.to_string_lossy(), &bytes), Some(Format::Slvs));
        let read = gcs_import::read(Format::Slvs, &path.to_string_lossy(), &bytes)
            .unwrap_or_else(|e| panic!("{e}"));
        for s in &read {
            let stem = gcs_import::file_stem(&path.to_string_lossy());
            assert!(s.name.starts_with(&format!("{stem}/g")), "{}", s.name);
            assert!(s.dim == 2 || s.dim == 3);
            // Every reference resolves to an entity of the sketch, ids are unique.
            let mut ids: Vec<&str> = s.entities.iter().map(|e| e.id.as_str()).collect();
            ids.extend(s.constraints.iter().map(|c| c.id.as_str()));
            let mut sorted = ids.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), ids.len(), "duplicate ids in {}", s.name);
            for c in &s.constraints {
                for Ref { entity, .. } in &c.refs {
                    assert!(s.entities.iter().any(|e| &e.id == entity), "{}: {entity}", c.id);
                }
            }
            for e in &s.entities {
                let coords = match &e.geometry {
                    Geometry::Point { at } => vec![at],
                    Geometry::Segment { start, end } => vec![start, end],
                    Geometry::Line { a, b } => vec![a, b],
                    Geometry::Circle { center, .. } => vec![center],
                    Geometry::Arc { center, start, end } => vec![center, start, end],
                    Geometry::BSpline { poles, .. } => poles.iter().collect(),
                    Geometry::Plane { origin, normal } => vec![origin, normal],
                    other => panic!("unexpected geometry {other:?}"),
                };
                assert!(coords.iter().all(|c| c.len() == s.dim as usize), "{}", e.id);
            }
        }
        sketches += read.len();
    }
    // One sketch per group with geometry or constraints: one in each of the 35 constraint
    // files and a second in pt_on_face and pt_face_distance (their extrudes), four in
    // boolean_tangent_fillet, one in contour_area, prune/angle and translate_asy, none in link.
    assert_eq!(sketches, 35 + 2 + 4 + 1 + 1 + 1);
}

#[test]
fn corpus_rectangle() {
    // contour_area: a square of four segments, joined end to end, two horizontal, two vertical.
    let Some(sk) = corpus("test/analysis/contour_area/normal.slvs") else { return };
    assert_eq!(sk.len(), 1);
    let s = &sk[0];
    assert_eq!(s.name, "normal/g2");
    assert_eq!(s.label.as_deref(), Some("sketch-in-plane"));
    assert_eq!(s.dim, 2);
    assert_eq!(s.entities.len(), 4);
    assert_eq!(s.constraints.len(), 8);
    assert!(s.skipped.is_empty());
    assert!(s.entities.iter().all(|e| !e.external && !e.construction));
    assert_eq!(
        geometry(s, "e.00040000"),
        &Geometry::Segment { start: vec![n(10), n(-10)], end: vec![n(10), n(10)] }
    );
    let c1 = constraint(s, "c.00000001");
    assert_eq!(c1.kind, Kind::Coincident);
    assert_eq!(refs(c1), vec![r("e.00040000", Part::Start), r("e.00050000", Part::End)]);
    assert_eq!(constraint(s, "c.00000005").kind, Kind::Vertical);
    assert_eq!(constraint(s, "c.00000006").kind, Kind::Horizontal);
}

#[test]
fn corpus_dimensions() {
    let Some(sk) = corpus("test/constraint/pt_pt_distance/normal.slvs") else { return };
    let c = constraint(&sk[0], "c.00000001");
    assert_eq!(c.kind, Kind::Distance);
    assert_eq!(c.value, Some(n(10)));
    assert!(c.driving);
    assert_eq!(geometry(&sk[0], "e.00040000"), &Geometry::Point { at: vec![n(-5), n(5)] });

    // PT_LINE_DISTANCE is signed in SolveSpace (-5 in the file); the IR distance is 5.
    let sk = corpus("test/constraint/pt_line_distance/normal.slvs").unwrap();
    assert_eq!(constraint(&sk[0], "c.00000001").value, Some(n(5)));

    // ANGLE 45 with other=1: the lines make 135 degrees (the png shows an obtuse angle).
    let sk = corpus("test/constraint/angle/normal.slvs").unwrap();
    let c = constraint(&sk[0], "c.00000002");
    assert_eq!((c.kind, c.value.clone()), (Kind::Angle, Some(n(135))));

    // The prune test's right triangle: a 100 side and a 30 degree angle (other=1: 150).
    let sk = corpus("test/core/prune/angle.slvs").unwrap();
    assert_eq!(sk.len(), 1);
    assert_eq!((sk[0].entities.len(), sk[0].constraints.len()), (3, 7));
    assert_eq!(constraint(&sk[0], "c.00000006").value, Some(n(100)));
    assert_eq!(constraint(&sk[0], "c.00000007").value, Some(n(150)));

    let sk = corpus("test/constraint/diameter/normal.slvs").unwrap();
    assert_eq!(
        geometry(&sk[0], "e.00040000"),
        &Geometry::Circle { center: vec![n(-10), n(10)], radius: n(5) }
    );
    assert_eq!(constraint(&sk[0], "c.00000001").kind, Kind::Diameter);

    // PROJ_PT_DISTANCE along the YZ plane's normal, the x axis: a horizontal distance.
    let sk = corpus("test/constraint/proj_pt_distance/normal.slvs").unwrap();
    let c = constraint(&sk[0], "c.00000001");
    assert_eq!((c.kind, c.value.clone()), (Kind::DistanceX, Some(n(5))));
}

#[test]
fn corpus_planes_become_traces() {
    // PT_IN_PLANE on the ZX reference plane (y = 0), seen from the XY workplane: the x axis.
    let Some(sk) = corpus("test/constraint/pt_in_plane/normal.slvs") else { return };
    let s = &sk[0];
    let c = constraint(s, "c.00000001");
    assert_eq!(c.kind, Kind::PointOnObject);
    assert_eq!(refs(c)[1], r("e.00030000", Part::Whole));
    let Geometry::Line { a, b } = geometry(s, "e.00030000") else { panic!("a line") };
    assert_eq!((a[1].clone(), b[1].clone()), (n(0), n(0)));
    assert!(s.entities.iter().find(|e| e.id == "e.00030000").unwrap().external);

    let sk = corpus("test/constraint/pt_plane_distance/normal.slvs").unwrap();
    let c = constraint(&sk[0], "c.00000001");
    assert_eq!((c.kind, c.value.clone()), (Kind::Distance, Some(n(5))));

    // SYMMETRIC about the YZ reference plane: about the y axis of the sketch.
    let sk = corpus("test/constraint/symmetric/normal.slvs").unwrap();
    let c = constraint(&sk[0], "c.00000001");
    assert_eq!(c.kind, Kind::Symmetric);
    assert_eq!(
        geometry(&sk[0], "e.00020000"),
        &Geometry::Line { a: vec![n(0), n(0)], b: vec![n(0), n(1)] }
    );

    // SYMMETRIC_HORIZ: mirror images about the workplane's vertical axis.
    let sk = corpus("test/constraint/symmetric_horiz/normal.slvs").unwrap();
    let c = constraint(&sk[0], "c.00000001");
    assert_eq!(refs(c)[2], r("e.80020000.v-axis", Part::Whole));
    let sk = corpus("test/constraint/symmetric_vert/normal.slvs").unwrap();
    assert_eq!(refs(constraint(&sk[0], "c.00000001"))[2], r("e.80020000.u-axis", Part::Whole));
}

#[test]
fn corpus_tangency_folds_the_joint() {
    let Some(sk) = corpus("test/constraint/arc_line_tangent/normal.slvs") else { return };
    let s = &sk[0];
    // The arc runs counter-clockwise from (-15, 15) to (-15, 5) about (-5, 10), as drawn.
    assert_eq!(
        geometry(s, "e.00040000"),
        &Geometry::Arc {
            center: vec![n(-5), n(10)],
            start: vec![n(-15), n(15)],
            end: vec![n(-15), n(5)]
        }
    );
    let c = constraint(s, "c.00000002");
    assert_eq!(c.kind, Kind::TangentAtEnds);
    assert_eq!(refs(c), vec![r("e.00040000", Part::Start), r("e.00050000", Part::Start)]);
    let c = constraint(s, "c.00000004");
    assert_eq!(refs(c), vec![r("e.00040000", Part::End), r("e.00060000", Part::Start)]);
    assert_eq!(s.constraints.len(), 2);
    assert!(note(s, "c.00000001").contains("folded into the tangency c.00000002"));
    assert!(note(s, "c.00000003").contains("folded into the tangency c.00000004"));
    assert!(s.skipped.is_empty(), "a folded coincidence is not a loss");

    let sk = corpus("test/constraint/cubic_line_tangent/normal.slvs").unwrap();
    let s = &sk[0];
    let Geometry::BSpline { degree, poles, knots, .. } = geometry(s, "e.00040000") else {
        panic!("a spline")
    };
    assert_eq!((*degree, poles.len(), knots.len()), (3, 4, 2));
    assert_eq!(refs(constraint(s, "c.00000002"))[0], r("e.00040000", Part::End));

    let sk = corpus("test/constraint/curve_curve_tangent/arc_arc.slvs").unwrap();
    let c = constraint(&sk[0], "c.00000002");
    assert_eq!(refs(c), vec![r("e.00050000", Part::Start), r("e.00040000", Part::Start)]);
}

#[test]
fn corpus_groups_and_externals() {
    // Four groups with content: two sketches in workplanes and two extrudes.
    let Some(sk) = corpus("test/group/boolean_tangent_fillet/normal.slvs") else { return };
    let names: Vec<&str> = sk.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["normal/g2", "normal/g3", "normal/g4", "normal/g5"]);
    let g2 = sketch(&sk, "normal/g2");
    assert_eq!((g2.dim, g2.entities.len(), g2.constraints.len()), (2, 4, 8));
    assert!(g2.skipped.is_empty());
    // The group's own workplane origin is a fixed point.
    let origin = g2.entities.iter().find(|e| e.id == "e.80020002").unwrap();
    assert!(origin.external);
    assert_eq!(origin.geometry, Geometry::Point { at: vec![n(0), n(0)] });

    // The extrude: 3D, its equal-length constraint on its own extrusion edges is skipped.
    let g3 = sketch(&sk, "normal/g3");
    assert_eq!(g3.dim, 3);
    assert!(g3.constraints.is_empty());
    assert!(skipped_reason(g3, "g3").contains("extrusion vector"));
    assert!(skipped_reason(g3, "c.00000009").contains("generated by this EXTRUDE group"));

    // The second sketch references edges of the first extrusion: external, fixed.
    let g4 = sketch(&sk, "normal/g4");
    assert_eq!((g4.entities.len(), g4.constraints.len()), (6, 7));
    let edge = g4.entities.iter().find(|e| e.id == "e.8003000a").unwrap();
    assert!(edge.external);
    assert_eq!(edge.geometry, Geometry::Segment { start: vec![n(1), n(0)], end: vec![n(0), n(0)] });
    assert_eq!(constraint(g4, "c.00000014").kind, Kind::LengthRatio);
    assert_eq!(constraint(g4, "c.00000014").value, Some(num("0.5")));
    let own: Vec<&str> =
        g4.entities.iter().filter(|e| !e.external).map(|e| e.id.as_str()).collect();
    assert_eq!(own, ["e.00070000", "e.00080000", "e.00090000"]);

    // translate_asy: the sketch only; the extrude and the translate have nothing of their own.
    let sk = corpus("test/group/translate_asy/normal.slvs").unwrap();
    assert_eq!(sk.len(), 1);
    // link: a linked part and an empty sketch: nothing.
    assert!(corpus("test/group/link/normal.slvs").unwrap().is_empty());
}

#[test]
fn corpus_three_d_and_skips() {
    // The datum point of pt_on_face's extrude group is free in 3D: a 3D sketch.
    let Some(sk) = corpus("test/constraint/pt_on_face/normal.slvs") else { return };
    let g3 = sketch(&sk, "normal/g3");
    assert_eq!(g3.dim, 3);
    assert_eq!(geometry(g3, "e.00050000"), &Geometry::Point { at: vec![n(5), n(5), n(0)] });
    assert!(g3.constraints.is_empty());

    // pt_face_distance's second sketch is drawn in the YZ reference workplane: u = y, v = z.
    let sk = corpus("test/constraint/pt_face_distance/normal.slvs").unwrap();
    let g2 = sketch(&sk, "normal/g2");
    assert_eq!(g2.dim, 2);
    assert_eq!(
        geometry(g2, "e.00040000"),
        &Geometry::Circle { center: vec![n(0), n(0)], radius: n(5) }
    );

    let sk = corpus("test/constraint/same_orientation/normal.slvs").unwrap();
    assert_eq!(sk[0].dim, 3);
    assert!(skipped_reason(&sk[0], "e.00040000").contains("normal"));
    assert!(skipped_reason(&sk[0], "c.00000002").contains("SAME_ORIENTATION"));

    let sk = corpus("test/constraint/comment/normal.slvs").unwrap();
    assert!(note(&sk[0], "c.00000001").starts_with("comment (1000)"));
    let sk = corpus("test/constraint/at_midpoint/line_plane_normal.slvs").unwrap();
    assert!(skipped_reason(&sk[0], "c.00000001").contains("AT_MIDPOINT"));
}

#[test]
fn crlf_and_utf8_header_read_the_same() {
    let bytes = std::fs::read(data("mapping2d.slvs")).unwrap();
    let plain = gcs_import::slvs::read("mapping2d.slvs", &bytes).unwrap();
    let crlf: Vec<u8> =
        bytes.split(|b| *b == b'\n').flat_map(|l| l.iter().copied().chain(*b"\r\n")).collect();
    assert_eq!(gcs_import::slvs::read("mapping2d.slvs", &crlf).unwrap(), plain);
    let mut utf8 = "\u{b1}\u{b2}\u{b3}".as_bytes().to_vec();
    utf8.extend_from_slice(&bytes[3..]);
    assert_eq!(gcs_import::slvs::read("mapping2d.slvs", &utf8).unwrap(), plain);
}

// ---------------------------------------------------------------- hand-written files

#[test]
fn mapping_in_a_workplane() {
    let sk = read_data("mapping2d.slvs");
    assert_eq!(sk.len(), 1);
    let s = &sk[0];
    assert_eq!((s.name.as_str(), s.dim), ("mapping2d/g2", 2));
    let kind = |id: &str| constraint(s, id).kind;
    let value = |id: &str| constraint(s, id).value.clone();

    assert_eq!(kind("c.00000001"), Kind::Coincident);
    // A reference dimension.
    let c2 = constraint(s, "c.00000002");
    assert_eq!((c2.kind, c2.value.clone(), c2.driving), (Kind::Distance, Some(n(10)), false));
    assert_eq!(refs(c2), vec![r("e.00040000", Part::Start), r("e.00040000", Part::End)]);
    assert_eq!((kind("c.00000003"), value("c.00000003")), (Kind::Distance, Some(n(5))));
    assert_eq!(refs(constraint(s, "c.00000003"))[1], r("e.00040000", Part::Whole));
    assert_eq!(kind("c.00000004"), Kind::PointOnObject);
    assert_eq!(kind("c.00000005"), Kind::PointOnObject);
    assert_eq!(refs(constraint(s, "c.00000005"))[1], r("e.00070000", Part::Whole));
    assert_eq!(kind("c.00000006"), Kind::Equal);
    assert_eq!(kind("c.00000007"), Kind::Equal);
    assert_eq!((kind("c.00000008"), value("c.00000008")), (Kind::LengthRatio, Some(n(1))));
    assert_eq!(kind("c.00000009"), Kind::Horizontal);
    let c10 = constraint(s, "c.0000000a");
    assert_eq!(c10.kind, Kind::Vertical);
    assert_eq!(refs(c10), vec![r("e.00050000", Part::Start), r("e.00050000", Part::End)]);
    assert_eq!((kind("c.0000000b"), value("c.0000000b")), (Kind::Diameter, Some(n(10))));
    assert_eq!(kind("c.0000000c"), Kind::Perpendicular);
    assert_eq!((kind("c.0000000d"), value("c.0000000d")), (Kind::Angle, Some(n(45))));
    assert_eq!(kind("c.0000000e"), Kind::Midpoint);
    let c15 = constraint(s, "c.0000000f");
    assert_eq!(c15.kind, Kind::Symmetric);
    assert_eq!(refs(c15)[2], r("e.00040000", Part::Whole));
    assert_eq!(kind("c.00000010"), Kind::Fix);
    // The supplementary form (other=1) is an EqualAngle like the other.
    assert_eq!(kind("c.00000011"), Kind::EqualAngle);
    assert!(skipped_reason(s, "c.00000012").contains("ARC_ARC_LEN_RATIO (210)"));
    let c19 = constraint(s, "c.00000013");
    assert_eq!(c19.kind, Kind::TangentAtEnds);
    assert_eq!(refs(c19), vec![r("e.000d0000", Part::End), r("e.000e0000", Part::Start)]);
    assert!(note(s, "c.00000014").contains("folded"));
    assert!(skipped_reason(s, "c.00000015").contains("999"));
    assert!(note(s, "c.00000016").contains("comment"));
    assert_eq!(refs(constraint(s, "c.00000017"))[2], r("e.80020000.v-axis", Part::Whole));
    // Stated in 3D between points of the workplane: the same distance.
    assert_eq!((kind("c.00000018"), value("c.00000018")), (Kind::Distance, Some(n(5))));
    assert!(skipped_reason(s, "c.00000019").contains("needs a workplane"));
    assert_eq!(kind("c.0000001a"), Kind::EqualLineArcLength);
    assert_eq!((kind("c.0000001b"), value("c.0000001b")), (Kind::LengthDifference, Some(n(0))));
    assert_eq!(kind("c.0000001c"), Kind::EqualLengthPointLineDistance);
    assert_eq!(
        refs(constraint(s, "c.0000001c")),
        vec![
            r("e.00050000", Part::Whole),
            r("e.00060000", Part::Whole),
            r("e.00040000", Part::Whole)
        ]
    );
    assert_eq!(kind("c.0000001d"), Kind::EqualPointLineDistances);
    assert!(skipped_reason(s, "c.0000001e").contains("no POINTS_COINCIDENT"));
    assert_eq!(kind("c.0000001f"), Kind::Parallel);
    // ANGLE 30 with other=1 from a 45-degree line back to the x axis: -150 (clockwise).
    assert_eq!(value("c.00000020"), Some(n(-150)));

    assert_eq!(s.constraints.len(), 26);
    assert_eq!((s.skipped.len(), s.notes.len()), (4, 2));
    assert_eq!(
        geometry(s, "e.00080000"),
        &Geometry::Arc {
            center: vec![n(0), n(20)],
            start: vec![n(5), n(20)],
            end: vec![n(0), n(25)]
        }
    );
}

#[test]
fn frames_three_d_and_projection() {
    let sk = read_data("frames.slvs");
    let g2 = sketch(&sk, "frames/g2");
    assert_eq!((g2.dim, g2.label.as_deref()), (3, Some("space")));
    assert_eq!(geometry(g2, "e.00040000"), &Geometry::Point { at: vec![n(1), n(2), n(3)] });
    assert_eq!(
        geometry(g2, "e.00060000"),
        &Geometry::Plane { origin: vec![n(0), n(0), n(5)], normal: vec![n(0), n(0), n(1)] }
    );
    assert!(skipped_reason(g2, "e.00070000").contains("normal"));
    assert!(skipped_reason(g2, "e.00080000").contains("drawn in workplane e.00010000"));
    assert_eq!(constraint(g2, "c.00000001").value, Some(n(3)));
    assert_eq!(constraint(g2, "c.00000002").kind, Kind::Parallel);
    assert!(skipped_reason(g2, "c.00000003").contains("projected"));
    assert!(skipped_reason(g2, "c.00000004").contains("plane"));
    assert!(skipped_reason(g2, "c.00000005").contains("e.00070000 is skipped"));
    assert!(skipped_reason(g2, "c.00000006").contains("e.00080000 is skipped"));
    assert_eq!(constraint(g2, "c.00000007").kind, Kind::Fix);
    assert_eq!(refs(constraint(g2, "c.00000008"))[0], r("e.00090000", Part::End));

    // Drawn in the YZ reference workplane (u = y, v = z); the 3D point (1, 2, 3) of g2 is
    // projected to (2, 3) and is external.
    let g3 = sketch(&sk, "frames/g3");
    assert_eq!(g3.dim, 2);
    assert_eq!(geometry(g3, "e.000a0000"), &Geometry::Point { at: vec![n(2), n(4)] });
    let p4 = g3.entities.iter().find(|e| e.id == "e.00040000").unwrap();
    assert!(p4.external);
    assert_eq!(p4.geometry, Geometry::Point { at: vec![n(2), n(3)] });
    assert_eq!(constraint(g3, "c.00000009").value, Some(n(1)));
    // A 3D coincidence with a point off the workplane cannot be drawn in it.
    assert!(skipped_reason(g3, "c.0000000a").contains("off the workplane"));
    // The XY plane crosses the YZ workplane along its u axis.
    let c11 = constraint(g3, "c.0000000b");
    assert_eq!(c11.kind, Kind::PointOnObject);
    let Geometry::Line { a, b } = geometry(g3, "e.00010000") else { panic!("a line") };
    assert_eq!((a[1].clone(), b[1].clone()), (n(0), n(0)));
    let c12 = constraint(g3, "c.0000000c");
    assert_eq!((c12.kind, c12.value.clone()), (Kind::DistanceX, Some(n(-2))));
    assert_eq!(refs(constraint(g3, "c.0000000d"))[1], r("e.00050000", Part::End));
    assert_eq!(constraint(g3, "c.0000000e").value, Some(n(4)));
}

#[test]
fn group_flags() {
    let sk = read_data("flags.slvs");
    let g2 = sketch(&sk, "flags/g2");
    assert!(!constraint(g2, "c.00000001").driving, "allDimsReference makes dimensions reference");
    assert!(constraint(g2, "c.00000002").driving, "a horizontal is no dimension");
    let g3 = sketch(&sk, "flags/g3");
    assert_eq!(constraint(g3, "c.00000003").kind, Kind::Coincident);
    assert!(skipped_reason(g3, "c.00000004").contains("relaxConstraints"));
}

// ---------------------------------------------------------------- bad input

fn error(bytes: &[u8]) -> ImportError {
    match gcs_import::slvs::read("bad.slvs", bytes) {
        Ok(_) => panic!("read without error"),
        Err(e) => e,
    }
}

/// `bytes` with the first `count` occurrences of `from` replaced by `to`.
fn replacen(bytes: &[u8], from: &str, to: &str, count: usize) -> Vec<u8> {
    let mut out = Vec::new();
    let mut rest = bytes;
    for _ in 0..count {
        let Some(at) = rest.windows(from.len()).position(|w| w == from.as_bytes()) else { break };
        out.extend_from_slice(&rest[..at]);
        out.extend_from_slice(to.as_bytes());
        rest = &rest[at + from.len()..];
    }
    out.extend_from_slice(rest);
    out
}

/// The 1-based line of the first occurrence of `text`.
fn line_of(bytes: &[u8], text: &str) -> usize {
    let at = bytes.windows(text.len()).position(|w| w == text.as_bytes()).expect("text present");
    bytes[..at].iter().filter(|b| **b == b'\n').count() + 1
}

#[test]
fn wrong_header_or_empty() {
    let e = error(b"hello\nGroup.h.v=00000001\nAddGroup\n");
    assert_eq!((e.file.as_str(), e.line), ("bad.slvs", Some(1)));
    assert!(e.message.contains("not a SolveSpace file"), "{e}");
    assert_eq!(error(b"").line, Some(1));
    // An Onshape or FreeCAD file given as SolveSpace.
    assert!(error(b"[{\"entities\": []}]").message.contains("header"));
}

#[test]
fn truncated_file() {
    let bytes = std::fs::read(data("mapping2d.slvs")).unwrap();
    let at = bytes.windows(22).position(|w| w == b"Constraint.h.v=0000000").unwrap();
    // Cut inside the record of c.00000001, after its handle.
    let cut = &bytes[..at + 42];
    let e = error(cut);
    assert_eq!(e.element.as_deref(), Some("Constraint c.00000001"));
    assert_eq!(e.line, Some(line_of(&bytes, "Constraint.h.v=00000001")));
    assert!(e.message.contains("truncated"), "{e}");
    assert!(e.to_string().starts_with("bad.slvs:"), "{e}");

    // Cut between the requests and their entities: the group's workplane is missing.
    let at = bytes.windows(13).position(|w| w == b"Entity.h.v=00").unwrap();
    let e = error(&bytes[..at]);
    assert_eq!(e.element.as_deref(), Some("Group g2"), "{e}");
    assert!(e.message.contains("e.80020000 is not in the file"), "{e}");
}

#[test]
fn garbage_and_bad_values() {
    let bytes = std::fs::read(data("flags.slvs")).unwrap();
    // A line of binary garbage.
    let mut garbage = bytes.clone();
    garbage.extend_from_slice(b"\x00\x9f\xff garbage\n");
    let e = error(&garbage);
    assert_eq!(e.line, Some(bytes.iter().filter(|b| **b == b'\n').count() + 1));
    assert!(e.message.contains("unrecognised line"), "{e}");

    // A malformed value of a known key, named with its record.
    let text = replacen(&bytes, "Entity.type=11000", "Entity.type=eleven", 1);
    let e = error(&text);
    assert_eq!(e.element.as_deref(), Some("Entity e.00040000"), "{e}");
    assert_eq!(e.line, Some(line_of(&text, "Entity.type=eleven")));
    assert!(e.message.contains("Entity.type"), "{e}");

    // A constraint on an entity that is not in the file.
    let text = replacen(&bytes, "ptB.v=00040002", "ptB.v=00440002", 1);
    let e = error(&text);
    assert_eq!(e.element.as_deref(), Some("Constraint c.00000001"));
    assert_eq!(e.line, Some(line_of(&text, "Constraint.h.v=00000001")));
    assert!(e.message.contains("e.00440002"), "{e}");

    // A duplicate handle.
    let text = replacen(&bytes, "Constraint.h.v=00000002", "Constraint.h.v=00000001", 1);
    let e = error(&text);
    assert!(e.message.contains("duplicate"), "{e}");

    // Unknown keys and word-like lines are tolerated: the format grows.
    let text = replacen(&bytes, "AddGroup", "Group.newFlag=1\nAddGroup", 1);
    let text = replacen(&text, "AddEntity", "Entity.futureKey=12\nAddEntity", 1);
    let text = replacen(&text, "AddConstraint", "AddConstraint\n\nFutureLine with words 1 2", 1);
    assert_eq!(
        gcs_import::slvs::read("flags.slvs", &text).unwrap(),
        gcs_import::slvs::read("flags.slvs", &bytes).unwrap()
    );
}
