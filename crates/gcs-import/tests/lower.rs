//! The lowering of neutral sketches into gcs models: every sketch of the corpus lowers, writes
//! to RON and reads back the same; the coverage (complete imports per format) is measured; and
//! each rule of the lowering on a small sketch.

mod common;

use std::collections::BTreeMap;

use gcs_import::ir::{Constraint, Entity, Geometry, Kind, Number, Part, Ref, Sketch, Skipped};
use gcs_import::{Lowered, lower};
use gcs_model::{ConstraintKind, System};

fn corpus() -> Option<Vec<(String, Vec<Lowered>)>> {
    let files = common::sketch_files()?;
    Some(
        files
            .into_iter()
            .map(|(name, bytes)| {
                let lowered = gcs_import::import(&name, &bytes).unwrap_or_else(|e| panic!("{e}"));
                (name, lowered)
            })
            .collect(),
    )
}

fn format_of(file: &str) -> &'static str {
    if file.ends_with(".slvs") {
        "slvs"
    } else if file.ends_with(".json") {
        "onshape"
    } else {
        "freecad"
    }
}

/// The first words of a skip reason, for a histogram of what is missing.
fn reason_class(reason: &str) -> String {
    reason.split([':', '(']).next().unwrap_or(reason).trim().to_owned()
}

#[test]
#[allow(clippy::print_stdout)] // the skipped items, listed on request (GCS_SHOW_SKIPPED)
fn corpus_lowers_and_round_trips_through_ron() {
    let Some(corpus) = corpus() else { return };
    let mut per_format: BTreeMap<&str, (usize, usize)> = BTreeMap::new();
    let mut missing: BTreeMap<String, usize> = BTreeMap::new();
    for (file, sketches) in &corpus {
        for l in sketches {
            let entry = per_format.entry(format_of(file)).or_default();
            entry.0 += 1;
            entry.1 += usize::from(l.complete());
            for s in &l.skipped {
                if std::env::var_os("GCS_SHOW_SKIPPED").is_some() {
                    println!("{}\t{}\t{}", l.system.name(), s.item, s.reason);
                }
                *missing.entry(reason_class(&s.reason)).or_default() += 1;
            }
            let ron = l.system.to_ron();
            let back = System::from_ron_str(&ron, Some(file))
                .unwrap_or_else(|e| panic!("{}: the RON does not read back: {e}", l.system.name()));
            assert_eq!(back.to_ron(), ron, "{}: round trip", l.system.name());
            assert!(l.system.name().contains('/'), "model names are <file stem>/<sketch>");
        }
    }
    let summary = format!("{per_format:?}\n{missing:#?}");
    // The coverage measured today (README, "Reading CAD files"): it may only grow.
    let (slvs, freecad, onshape) =
        (per_format["slvs"], per_format["freecad"], per_format["onshape"]);
    assert_eq!((slvs.0, freecad.0, onshape.0), (44, 32, 237), "{summary}");
    assert!(slvs.1 >= 36 && freecad.1 >= 30 && onshape.1 >= 36, "{summary}");
}

fn n(x: i64) -> Number {
    Number::from_i64(x)
}

fn entity(id: &str, geometry: Geometry) -> Entity {
    Entity { id: id.to_owned(), geometry, construction: false, external: false }
}

fn constraint(id: &str, kind: Kind, refs: Vec<Ref>, value: Option<i64>) -> Constraint {
    Constraint { id: id.to_owned(), kind, refs, value: value.map(n), driving: true }
}

fn sketch(entities: Vec<Entity>, constraints: Vec<Constraint>) -> Sketch {
    Sketch {
        name: "t/s".to_owned(),
        label: None,
        dim: 2,
        entities,
        constraints,
        skipped: Vec::new(),
        notes: Vec::new(),
        source_verdict: Vec::new(),
    }
}

/// The gcs constraint `id`: its kind, its arguments' ids and its value.
fn lowered(l: &Lowered, id: &str) -> (ConstraintKind, Vec<String>, Option<String>) {
    let s = &l.system;
    let c = s.constraint(s.constraint_by_id(id).unwrap_or_else(|| panic!("no {id}")));
    let args = c.args.iter().map(|a| s.entity(*a).id.clone()).collect();
    (c.kind, args, c.value.as_ref().map(gcs_model::number::format_exact))
}

fn strings(ids: &[&str]) -> Vec<String> {
    ids.iter().map(|s| s.to_string()).collect()
}

/// The arc `a` about (10, 5) of radius 5, from (10, 0) (where it is tangent to the x axis)
/// counter-clockwise to (15, 5).
fn quarter_arc() -> Entity {
    entity(
        "a",
        Geometry::Arc {
            center: vec![n(10), n(5)],
            start: vec![n(10), n(0)],
            end: vec![n(15), n(5)],
        },
    )
}

/// A fillet: a segment ending where an arc starts, tangent there, written as CAD programs
/// write it (one constraint). It lowers into the transversal formulation.
#[test]
fn tangency_at_shared_ends_is_one_transversal_constraint() {
    let s = sketch(
        vec![
            entity("l", Geometry::Segment { start: vec![n(0), n(0)], end: vec![n(10), n(0)] }),
            quarter_arc(),
        ],
        vec![constraint(
            "t",
            Kind::TangentAtEnds,
            vec![Ref::part("l", Part::End), Ref::part("a", Part::Start)],
            None,
        )],
    );
    let l = lower(&s);
    assert!(l.complete(), "{:?}", l.skipped);
    assert_eq!(lowered(&l, "t"), (ConstraintKind::TangentAt, strings(&["l", "a", "l.end"]), None));
    assert_eq!(
        lowered(&l, "t#coincident"),
        (ConstraintKind::Coincident, strings(&["l.end", "a.start"]), None)
    );
    // The segment's end points are written points; the arc's are its own.
    assert_eq!(l.system.written_entities(), 4);
    assert_eq!(l.system.written_constraints(), 2);
}

#[test]
fn dimensions_axes_externals_and_references() {
    let seg = |id: &str, a: (i64, i64), b: (i64, i64)| {
        entity(id, Geometry::Segment { start: vec![n(a.0), n(a.1)], end: vec![n(b.0), n(b.1)] })
    };
    let mut origin = entity("o", Geometry::Point { at: vec![n(0), n(0)] });
    origin.external = true;
    let mut reference = constraint("ref", Kind::Length, vec![Ref::whole("m")], Some(5));
    reference.driving = false;
    let s = sketch(
        vec![
            origin,
            seg("l", (0, 0), (4, 3)),
            seg("m", (0, 0), (0, 5)),
            Entity {
                construction: true,
                ..entity("c", Geometry::Circle { center: vec![n(1), n(1)], radius: n(3) })
            },
        ],
        vec![
            constraint("d", Kind::Diameter, vec![Ref::whole("c")], Some(6)),
            constraint("len", Kind::Length, vec![Ref::whole("l")], Some(5)),
            constraint(
                "h",
                Kind::Horizontal,
                vec![Ref::whole("o"), Ref::part("c", Part::Center)],
                None,
            ),
            constraint("ang", Kind::AngleToXAxis, vec![Ref::whole("l")], Some(37)),
            constraint("ang2", Kind::AngleToXAxis, vec![Ref::whole("m")], Some(90)),
            constraint("dx", Kind::DistanceX, vec![Ref::whole("m")], Some(0)),
            reference,
        ],
    );
    let l = lower(&s);
    assert!(l.complete(), "{:?}", l.skipped);
    assert_eq!(lowered(&l, "o#fixed"), (ConstraintKind::Fix, strings(&["o"]), None));
    assert_eq!(lowered(&l, "d"), (ConstraintKind::Radius, strings(&["c"]), Some("3".into())));
    assert_eq!(
        lowered(&l, "len"),
        (ConstraintKind::Distance, strings(&["l.start", "l.end"]), Some("5".into()))
    );
    assert_eq!(
        lowered(&l, "h"),
        (ConstraintKind::DistanceY, strings(&["o", "c.center"]), Some("0".into()))
    );
    assert_eq!(
        lowered(&l, "ang"),
        (ConstraintKind::Angle, strings(&["l", "#x-axis"]), Some("37".into()))
    );
    assert_eq!(lowered(&l, "ang2").1, strings(&["m", "#x-axis"]), "one axis for all");
    assert_eq!(lowered(&l, "#x-axis#fixed").0, ConstraintKind::Fix);
    assert_eq!(lowered(&l, "dx").1, strings(&["m.start", "m.end"]));
    assert_eq!(l.reference, strings(&["ref"]));
    assert!(l.system.constraint_by_id("ref").is_none(), "a reference dimension is not imposed");
    // It is a reference dimension of the model: m's length, measured (5 at the drawing).
    let refs: Vec<(&str, ConstraintKind)> =
        l.system.references().iter().map(|r| (r.id.as_str(), r.kind)).collect();
    assert_eq!(refs, [("ref", ConstraintKind::Distance)]);
    let c = l.system.entity_by_id("c").unwrap();
    assert!(l.system.entity(c).construction, "construction geometry keeps its flag");
    assert!(
        l.system
            .to_ron()
            .contains("Circle(id: \"c\", center: [1, 1], radius: 3, construction: true)")
    );
}

#[test]
fn what_cannot_be_expressed_is_skipped_with_its_dependents() {
    let mut s = sketch(
        vec![
            entity(
                "e",
                Geometry::Ellipse {
                    center: vec![n(0), n(0)],
                    major: vec![n(4), n(0)],
                    minor_radius: n(2),
                },
            ),
            entity("p", Geometry::Point { at: vec![n(4), n(0)] }),
            entity("c", Geometry::Circle { center: vec![n(0), n(0)], radius: n(1) }),
        ],
        vec![
            constraint("on", Kind::PointOnObject, vec![Ref::whole("p"), Ref::whole("e")], None),
            constraint("q", Kind::Coincident, vec![Ref::whole("p"), Ref::whole("nope")], None),
        ],
    );
    s.skipped.push(Skipped { item: "x".into(), reason: "the reader's own".into() });
    let l = lower(&s);
    assert!(!l.complete());
    let reasons: Vec<(&str, &str)> =
        l.skipped.iter().map(|k| (k.item.as_str(), k.reason.as_str())).collect();
    assert_eq!(reasons[0], ("x", "the reader's own"));
    assert_eq!(reasons[1], ("e", "an ellipse: not in the gcs model yet"));
    assert_eq!(reasons[2], ("on", "refers to e, which was skipped"));
    assert_eq!(reasons[3], ("q", "refers to nope, which is not in the sketch"));
    assert_eq!(l.system.written_entities(), 2);
}

/// Onshape's and FreeCAD's fillets: a coincidence of the end points and a tangency of the
/// curves. The tangency lowers at the joint (transversal), and float noise is snapped off.
#[test]
fn a_tangency_of_joined_curves_is_at_the_joint() {
    let noisy = Number::parse("10.000000000000002").unwrap();
    let s = sketch(
        vec![
            entity("l", Geometry::Segment { start: vec![n(-20), n(0)], end: vec![n(0), n(0)] }),
            entity(
                "a",
                Geometry::Arc {
                    center: vec![n(0), n(10)],
                    start: vec![n(0), n(0)],
                    end: vec![n(10), noisy],
                },
            ),
            entity("m", Geometry::Segment { start: vec![n(10), n(10)], end: vec![n(10), n(30)] }),
            entity("c", Geometry::Circle { center: vec![n(0), n(40)], radius: n(10) }),
        ],
        vec![
            constraint(
                "j1",
                Kind::Coincident,
                vec![Ref::part("l", Part::End), Ref::part("a", Part::Start)],
                None,
            ),
            constraint("t1", Kind::Tangent, vec![Ref::whole("l"), Ref::whole("a")], None),
            constraint(
                "j2",
                Kind::PointOnObject,
                vec![Ref::part("m", Part::Start), Ref::whole("a")],
                None,
            ),
            constraint("t2", Kind::Tangent, vec![Ref::whole("a"), Ref::whole("m")], None),
            constraint("t3", Kind::Tangent, vec![Ref::whole("m"), Ref::whole("c")], None),
        ],
    );
    let l = lower(&s);
    assert!(l.complete(), "{:?}", l.skipped);
    assert_eq!(lowered(&l, "t1"), (ConstraintKind::TangentAt, strings(&["l", "a", "l.end"]), None));
    assert_eq!(
        lowered(&l, "t2"),
        (ConstraintKind::TangentAt, strings(&["a", "m", "m.start"]), None)
    );
    assert_eq!(lowered(&l, "t3").0, ConstraintKind::Tangent, "not joined: tangent somewhere");
    let end = l.system.entity_by_id("a.end").unwrap();
    let gcs_model::entity::Geometry::Point { at: Some(at) } = &l.system.entity(end).geometry else {
        panic!("a point")
    };
    assert_eq!(at[1], gcs_model::number::int(10), "the float noise is snapped off");
}

/// A tangency between an unbounded line and an arc that the sketch joins at a point put on the
/// line (how an Onshape zero-length line, its carrier and its ends, meets a fillet) is
/// `TangentAt` that point: written as incidence + `Tangent` it would be singular at every
/// solution, one false redundancy and one false degree of freedom.
#[test]
fn tangency_of_a_line_at_a_point_on_it_is_transversal() {
    let s = sketch(
        vec![
            entity("l", Geometry::Line { a: vec![n(0), n(0)], b: vec![n(10), n(0)] }),
            entity("p", Geometry::Point { at: vec![n(10), n(0)] }),
            quarter_arc(),
        ],
        vec![
            constraint("on", Kind::PointOnObject, vec![Ref::whole("p"), Ref::whole("l")], None),
            constraint(
                "j",
                Kind::Coincident,
                vec![Ref::whole("p"), Ref::part("a", Part::Start)],
                None,
            ),
            constraint("t", Kind::Tangent, vec![Ref::whole("l"), Ref::whole("a")], None),
        ],
    );
    let l = lower(&s);
    assert!(l.complete(), "{:?}", l.skipped);
    assert_eq!(lowered(&l, "t"), (ConstraintKind::TangentAt, strings(&["l", "a", "p"]), None));
    let a = gcs_analysis::analyze(&l.system, &Default::default()).unwrap();
    assert!(a.redundant.is_empty(), "{:?}", a.redundant);
    // Line 2, point 2, arc 5 (centre, radius, two angles) less 1 + 2 + 1.
    assert_eq!(a.dof_absolute, 2 + 2 + 5 - 4);
}

/// A distance to a circle's boundary (from a point, a line or another circle) becomes a circle
/// concentric with it through the point (tangent to the line or circle), at that distance from
/// it; between circles drawn concentric, the model's own distance of two circles. Each removes
/// one degree of freedom, which the analysis confirms.
#[test]
fn distances_to_circles_are_offset_circles() {
    let s = sketch(
        vec![
            entity("c", Geometry::Circle { center: vec![n(0), n(0)], radius: n(5) }),
            entity("p", Geometry::Point { at: vec![n(8), n(0)] }),
            entity("l", Geometry::Segment { start: vec![n(-10), n(9)], end: vec![n(10), n(9)] }),
            entity("k", Geometry::Circle { center: vec![n(0), n(-20)], radius: n(10) }),
            entity("in", Geometry::Circle { center: vec![n(0), n(0)], radius: n(2) }),
        ],
        vec![
            constraint("dp", Kind::Distance, vec![Ref::whole("p"), Ref::whole("c")], Some(3)),
            constraint("dl", Kind::Distance, vec![Ref::whole("c"), Ref::whole("l")], Some(4)),
            constraint("dk", Kind::Distance, vec![Ref::whole("k"), Ref::whole("c")], Some(5)),
            constraint("din", Kind::Distance, vec![Ref::whole("in"), Ref::whole("c")], Some(3)),
        ],
    );
    let l = lower(&s);
    assert!(l.complete(), "{:?}", l.skipped);
    let circle = |id: &str| {
        let e = l.system.entity(l.system.entity_by_id(id).unwrap_or_else(|| panic!("no {id}")));
        format!("{:?}", e.geometry)
    };
    // Through the point: radius 8; tangent to the line y = 9: radius 9; tangent to k (centre
    // 20 away, radius 10) from outside: radius 10.
    for (id, r) in [("dp", 8), ("dl", 9), ("dk", 10)] {
        let helper = format!("{id}#offset");
        assert!(
            circle(&helper).contains(&format!("radius: Some(Ratio {{ numer: {r}, denom: 1 }})"))
        );
        assert_eq!(lowered(&l, &format!("{id}#concentric")).1, strings(&[&helper, "c"]));
        assert_eq!(
            lowered(&l, id),
            (
                ConstraintKind::Distance,
                strings(&[&helper, "c"]),
                Some(format!("{}", [3, 4, 5][(r - 8) as usize]))
            )
        );
    }
    assert_eq!(
        lowered(&l, "dp#on"),
        (ConstraintKind::Incident, strings(&["p", "dp#offset"]), None)
    );
    assert_eq!(lowered(&l, "dl#on").0, ConstraintKind::Tangent);
    assert_eq!(lowered(&l, "dk#on"), (ConstraintKind::Tangent, strings(&["k", "dk#offset"]), None));
    assert_eq!(
        lowered(&l, "din"),
        (ConstraintKind::Distance, strings(&["in", "c"]), Some("3".into()))
    );
    // Every constraint independent at the witness: each distance removes one degree of
    // freedom (the helpers' own three are removed by their concentricity and contact), none
    // redundant.
    let a = gcs_analysis::analyze(&l.system, &Default::default()).unwrap();
    assert!(a.redundant.is_empty(), "{:?}", a.redundant);
    assert_eq!(a.rank, l.system.doc_sum());
}

/// A B-spline lowers on control points of its own (a clamped spline's first and last are its
/// end points); a tangency at its end is one transversal equation on the leg of its control
/// polygon there; an unclamped spline's ends and a point on the curve are skipped with their
/// reason. The analysis counts the control points' degrees of freedom.
#[test]
fn b_splines_lower_on_their_control_points() {
    let xy = |x: i64, y: i64| vec![n(x), n(y)];
    let knots = |v: &[(i64, u32)]| v.iter().map(|(k, m)| (n(*k), *m)).collect::<Vec<_>>();
    let s = sketch(
        vec![
            entity("l", Geometry::Segment { start: xy(-10, 0), end: xy(0, 0) }),
            entity(
                "s",
                Geometry::BSpline {
                    degree: 3,
                    poles: vec![xy(0, 0), xy(5, 0), xy(10, 5), xy(10, 10)],
                    weights: Some(vec![n(1), n(2), n(1), n(1)]),
                    knots: knots(&[(0, 4), (1, 4)]),
                    periodic: false,
                },
            ),
            entity("a", Geometry::Arc { center: xy(0, 10), start: xy(10, 10), end: xy(0, 20) }),
            entity(
                "u",
                Geometry::BSpline {
                    degree: 2,
                    poles: vec![xy(20, 0), xy(25, 5), xy(30, 0)],
                    weights: None,
                    knots: knots(&[(0, 1), (1, 1), (2, 1), (3, 1), (4, 1), (5, 1)]),
                    periodic: false,
                },
            ),
            entity("p", Geometry::Point { at: xy(25, 2) }),
        ],
        vec![
            constraint(
                "g1",
                Kind::TangentAtEnds,
                vec![Ref::part("l", Part::End), Ref::part("s", Part::Start)],
                None,
            ),
            constraint(
                "g2",
                Kind::TangentAtEnds,
                vec![Ref::part("s", Part::End), Ref::part("a", Part::Start)],
                None,
            ),
            constraint(
                "h",
                Kind::Horizontal,
                vec![Ref::part("s", Part::Pole(1)), Ref::part("l", Part::Start)],
                None,
            ),
            constraint(
                "ue",
                Kind::Coincident,
                vec![Ref::part("u", Part::End), Ref::whole("p")],
                None,
            ),
            constraint("on", Kind::PointOnObject, vec![Ref::whole("p"), Ref::whole("u")], None),
        ],
    );
    let l = lower(&s);
    let reasons: Vec<(&str, &str)> =
        l.skipped.iter().map(|k| (k.item.as_str(), k.reason.as_str())).collect();
    assert_eq!(reasons.len(), 2, "{reasons:?}");
    assert_eq!(reasons[0].0, "ue");
    assert!(reasons[0].1.contains("a B-spline that is not clamped"), "{}", reasons[0].1);
    assert_eq!(reasons[1].0, "on");
    assert!(reasons[1].1.contains("a B-spline"), "{}", reasons[1].1);

    let sys = &l.system;
    let spline = &sys.entity(sys.entity_by_id("s").unwrap()).geometry;
    let gcs_model::entity::Geometry::BSpline { degree, poles, knots, weights, periodic } = spline
    else {
        panic!("a B-spline: {spline:?}")
    };
    let ids: Vec<&str> = poles.iter().map(|p| sys.entity(*p).id.as_str()).collect();
    assert_eq!(ids, ["s.start", "s.pole1", "s.pole2", "s.end"]);
    assert_eq!((*degree, knots.as_ref().map(Vec::len), *periodic), (3, Some(8), false));
    assert_eq!(weights.as_ref().map(Vec::len), Some(4), "weights other than 1 are kept");
    let u = &sys.entity(sys.entity_by_id("u").unwrap()).geometry;
    let gcs_model::entity::Geometry::BSpline { poles, .. } = u else { panic!("{u:?}") };
    let ids: Vec<&str> = poles.iter().map(|p| sys.entity(*p).id.as_str()).collect();
    assert_eq!(ids, ["u.pole0", "u.pole1", "u.pole2"], "no end points: not clamped");

    // Tangent at the start: parallel to the leg s.start → s.pole1, joined at the point.
    assert_eq!(lowered(&l, "g1"), (ConstraintKind::Parallel, strings(&["l", "s#start-leg"]), None));
    assert_eq!(lowered(&l, "g1#coincident").1, strings(&["l.end", "s.start"]));
    // Tangent to the arc at the end: the leg s.end → s.pole2 is tangent to it there.
    assert_eq!(
        lowered(&l, "g2"),
        (ConstraintKind::TangentAt, strings(&["s#end-leg", "a", "s.end"]), None)
    );
    assert_eq!(lowered(&l, "h").1, strings(&["s.pole1", "l.start"]));

    // Unknowns: l 4, s 8, a 3 + 4 (its end points), u 6, p 2 = 27; equations: g1 1 + 2, g2
    // 1 + 2, h 1, the arc's two incidences = 9: 18 DOF with the 3 displacements.
    let a = gcs_analysis::analyze(sys, &Default::default()).unwrap();
    assert_eq!(a.rank - a.internal_equations, 9);
    assert_eq!(a.dof + a.trivial_motions, 18);
    let back = System::from_ron_str(&sys.to_ron(), None).unwrap();
    assert_eq!(back.to_ron(), sys.to_ron());
}

/// Patterns and mirrored segments lower into the equations they imply: a turn by 90° as
/// perpendicular arms of equal length, by 180° as a symmetry about the pivot, a move along a
/// direction segment as a parallelogram with a shared middle, a mirrored segment as the images
/// of its end points on the other; a turn beyond the 36 divisions the analysis carries is
/// skipped, and a move said twice (a shared corner) is a note.
#[test]
fn patterns_and_mirrored_segments_lower_to_their_equations() {
    let xy = |x: i64, y: i64| vec![n(x), n(y)];
    let point = |id: &str, x: i64, y: i64| entity(id, Geometry::Point { at: xy(x, y) });
    let segment = |id: &str, a: (i64, i64), b: (i64, i64)| {
        entity(id, Geometry::Segment { start: xy(a.0, a.1), end: xy(b.0, b.1) })
    };
    let w = |id: &str| Ref::whole(id);
    let (start, end) = (|id: &str| Ref::part(id, Part::Start), |id: &str| Ref::part(id, Part::End));
    let s = sketch(
        vec![
            point("c", 0, 0),
            point("a", 2, 1),
            point("q90", -1, 2),
            point("q180", -2, -1),
            point("t0", 10, 10),
            point("t1", 14, 10),
            segment("d", (0, -5), (4, -5)),
            segment("s1", (1, 1), (3, 2)),
            segment("s2", (-1, 1), (-3, 2)),
            segment("m", (0, 0), (0, 10)),
            point("o", 0, 0),
            point("o90", 0, 0),
            point("o180", 0, 0),
        ],
        vec![
            constraint("r90", Kind::Rotated, vec![w("a"), w("q90"), w("c")], Some(90)),
            constraint("r180", Kind::Rotated, vec![w("a"), w("q180"), w("c")], Some(-180)),
            constraint("r1", Kind::Rotated, vec![w("a"), w("q90"), w("c")], Some(1)),
            constraint("tr", Kind::Translated, vec![w("t0"), w("t1"), start("d"), end("d")], None),
            constraint(
                "again",
                Kind::Translated,
                vec![w("t0"), w("t1"), start("d"), end("d")],
                None,
            ),
            constraint("mirror", Kind::Symmetric, vec![w("s1"), w("s2"), w("m")], None),
            // A point the sketch puts at the pivot, turned.
            constraint("at", Kind::Coincident, vec![w("o"), w("c")], None),
            constraint("at2", Kind::Coincident, vec![w("o180"), w("c")], None),
            constraint("turn90", Kind::Rotated, vec![w("o"), w("o90"), w("c")], Some(90)),
            constraint("turn180", Kind::Rotated, vec![w("o"), w("o180"), w("c")], Some(180)),
        ],
    );
    let l = lower(&s);
    let reasons: Vec<(&str, &str)> =
        l.skipped.iter().map(|k| (k.item.as_str(), k.reason.as_str())).collect();
    assert_eq!(reasons.len(), 1, "{reasons:?}");
    assert_eq!(reasons[0].0, "r1");
    assert!(reasons[0].1.contains("a rotation by 1°"), "{}", reasons[0].1);
    assert_eq!(l.notes.len(), 2);
    assert_eq!(l.notes[0].item, "again");
    assert!(l.notes[0].reason.contains("`tr` says already"), "{}", l.notes[0].reason);
    assert_eq!(l.notes[1].item, "turn180");
    assert!(l.notes[1].reason.contains("the pivot itself"), "{}", l.notes[1].reason);
    // Its image is the pivot.
    assert_eq!(lowered(&l, "turn90"), (ConstraintKind::Coincident, strings(&["o90", "c"]), None));

    assert_eq!(
        lowered(&l, "r90"),
        (ConstraintKind::Perpendicular, strings(&["r90#arm", "r90#arm-image"]), None)
    );
    assert_eq!(lowered(&l, "r90#equal").0, ConstraintKind::EqualLength);
    let sys = &l.system;
    let ends = |id: &str| sys.segment_points(sys.entity_by_id(id).unwrap()).unwrap();
    let name = |e: gcs_model::EntityIdx| sys.entity(e).id.clone();
    let (p, q) = ends("r90#arm-image");
    assert_eq!((name(p), name(q)), ("c".to_owned(), "q90".to_owned()));
    assert_eq!(
        lowered(&l, "r180"),
        (ConstraintKind::Symmetric, strings(&["a", "q180", "c"]), None)
    );
    assert_eq!(
        lowered(&l, "tr"),
        (ConstraintKind::Symmetric, strings(&["t0", "d.end", "tr#middle"]), None)
    );
    assert_eq!(
        lowered(&l, "tr#image"),
        (ConstraintKind::Symmetric, strings(&["t1", "d.start", "tr#middle"]), None)
    );
    assert_eq!(lowered(&l, "mirror").1, strings(&["s1.start", "mirror#image-start", "m"]));
    assert_eq!(
        lowered(&l, "mirror#on-end"),
        (ConstraintKind::Incident, strings(&["mirror#image-end", "s2"]), None)
    );
    // Helpers are drawn where the drawing puts them, exactly: the middle of t0 and d's end,
    // the images of s1's ends across x = 0.
    let at = |id: &str| match &sys.entity(sys.entity_by_id(id).unwrap()).geometry {
        gcs_model::entity::Geometry::Point { at: Some(at) } => {
            at.iter().map(gcs_model::number::format_exact).collect::<Vec<_>>()
        }
        other => panic!("{other:?}"),
    };
    assert_eq!(at("tr#middle"), strings(&["7", "2.5"]));
    assert_eq!(
        (at("mirror#image-start"), at("mirror#image-end")),
        (strings(&["-1", "1"]), strings(&["-3", "2"]))
    );

    // Unknowns: 17 points of the sketch (9 points, 4 segments: 34) and 3 helper points (6) =
    // 40; equations: the turns 2 + 2, the move 4, the mirror 4 + 2, the points at the pivot
    // 2 + 2 + 2 = 20, independent: 20 DOF with the 3 displacements.
    let a = gcs_analysis::analyze(sys, &Default::default()).unwrap();
    assert_eq!(a.rank - a.internal_equations, 20);
    assert_eq!(a.dof + a.trivial_motions, 40 - 20);
    assert!(a.redundant.is_empty());
    let back = System::from_ron_str(&sys.to_ron(), None).unwrap();
    assert_eq!(back.to_ron(), sys.to_ron());
}

/// A turn whose cosine or sine is irrational (by 60°, a circular pattern of 6) lowers to a
/// vertex of the regular polygon about the pivot: helper vertices `<id>#vertex<j>`, each as far
/// from the pivot as the turned point (`#spoke`) and each side as long as the first (`#side`,
/// the last closing on the point), drawn exactly turned; a second turn of the same point about
/// the same pivot (by 120°) reuses them. The analysis takes the turns from the drawing, modulo
/// the turn prime: the two images are determined (2 DOF removed each).
#[test]
fn a_turn_by_60_degrees_is_a_vertex_of_a_regular_hexagon() {
    let xy = |x: i64, y: i64| vec![n(x), n(y)];
    let point = |id: &str, x: i64, y: i64| entity(id, Geometry::Point { at: xy(x, y) });
    let w = |id: &str| Ref::whole(id);
    let s = sketch(
        vec![point("c", 0, 0), point("a", 2, 1), point("q60", 0, 2), point("q120", -2, 1)],
        vec![
            constraint("r60", Kind::Rotated, vec![w("a"), w("q60"), w("c")], Some(60)),
            constraint("r120", Kind::Rotated, vec![w("a"), w("q120"), w("c")], Some(120)),
        ],
    );
    let l = lower(&s);
    assert!(l.skipped.is_empty(), "{:?}", l.skipped);
    assert_eq!(
        lowered(&l, "r60"),
        (ConstraintKind::Coincident, strings(&["q60", "r60#vertex1"]), None)
    );
    assert_eq!(
        lowered(&l, "r120"),
        (ConstraintKind::Coincident, strings(&["q120", "r60#vertex2"]), None)
    );
    assert_eq!(
        lowered(&l, "r60#vertex1#spoke"),
        (ConstraintKind::EqualDistance, strings(&["c", "a", "c", "r60#vertex1"]), None)
    );
    assert_eq!(
        lowered(&l, "r60#vertex2#side").1,
        strings(&["a", "r60#vertex1", "r60#vertex2", "r60#vertex3"])
    );
    assert_eq!(
        lowered(&l, "r60#vertex5#side").1,
        strings(&["a", "r60#vertex1", "r60#vertex5", "a"]),
        "the last side closes on the turned point"
    );
    let sys = &l.system;
    assert!(sys.entity_by_id("r120#vertex1").is_none(), "one polygon per point and pivot");
    // Vertex 2: `a` turned by 120° about the origin, to the drawing's rounding.
    let v2: Vec<f64> = match &sys.entity(sys.entity_by_id("r60#vertex2").unwrap()).geometry {
        gcs_model::entity::Geometry::Point { at: Some(at) } => {
            at.iter().map(|x| num_traits::ToPrimitive::to_f64(x).unwrap()).collect()
        }
        other => panic!("{other:?}"),
    };
    let (cos, sin) = (-0.5, 3f64.sqrt() / 2.0);
    assert!((v2[0] - (2.0 * cos - sin)).abs() < 1e-12);
    assert!((v2[1] - (2.0 * sin + cos)).abs() < 1e-12);

    // Unknowns: 4 points and 5 vertices = 18; equations: the hexagon 5 + 5, the two images
    // 2 + 2 = 14, independent: 4 DOF with the 3 displacements (c and a free).
    let a = gcs_analysis::analyze(sys, &Default::default()).unwrap();
    assert_eq!(a.witness.modulus, Some(gcs_rank::TURN_PRIME));
    assert!(a.witness.turns.contains(&6), "{:?}", a.witness.turns);
    assert_eq!(a.rank - a.internal_equations, 14);
    assert_eq!(a.dof + a.trivial_motions, 18 - 14);
    assert!(a.redundant.is_empty());
}
