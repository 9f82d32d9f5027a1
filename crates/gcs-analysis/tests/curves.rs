//! Curves as CAD programs have them: arcs with their end points, the centres of circles and
//! arcs and the end points of segments named by constraints (`c1.center`, `a1.start`,
//! `s1.end`), a point at a centre (`Concentric` point–circle), a fixed arc.

use gcs_analysis::{AnalysisOptions, Backend, analyze};
use gcs_model::System;

fn system(entities: &str, constraints: &str) -> System {
    let text = format!("System(dim: 2, entities: [{entities}], constraints: [{constraints}])");
    System::from_ron_str(&text, Some("curves.ron")).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// `(dof, trivial motions, redundant ids)` in the exact and modp backends (which must agree).
fn verdict(s: &System) -> (usize, usize, Vec<String>) {
    let mut out = None;
    for backend in [Backend::Exact, Backend::ModP] {
        let a = analyze(s, &AnalysisOptions { backend, ..Default::default() })
            .unwrap_or_else(|e| panic!("{backend:?}: {e}"));
        let redundant: Vec<String> =
            a.redundant.iter().map(|r| s.constraint(r.constraint).id.clone()).collect();
        let v = (a.dof, a.trivial_motions, redundant);
        if let Some(prev) = &out {
            assert_eq!(prev, &v, "{backend:?}");
        }
        out = Some(v);
    }
    out.unwrap()
}

const ARC: &str = r#"Arc(id: "a", center: [1, 2], radius: 5, start: [4, 6], end: [-3, 5])"#;

#[test]
fn an_arc_has_five_degrees_of_freedom() {
    let s = system(ARC, "");
    // Its circle (3) and two points (4), held on the circle by two implicit incidences.
    assert_eq!(s.entities().len(), 3);
    assert_eq!(s.written_entities(), 1);
    assert_eq!((s.dof_sum(), s.doc_sum()), (7, 2));
    assert_eq!(
        s.constraints().iter().map(|c| c.id.as_str()).collect::<Vec<_>>(),
        ["a.start@a", "a.end@a"]
    );
    assert_eq!(verdict(&s), (2, 3, vec![]));
    // The sketch satisfies its incidences: it is the witness.
    let a = analyze(&s, &AnalysisOptions::default()).unwrap();
    assert_eq!(a.witness.source, gcs_jacobian::WitnessSource::Sketch);
}

#[test]
fn a_fixed_arc_is_rigid_and_not_redundant() {
    // Fix pins the circle and each end point's place along it: DOC 5, all independent.
    let s = system(ARC, r#"Fix(id: "f", a: "a")"#);
    assert_eq!(s.constraint(s.constraint_by_id("f").unwrap()).doc, 5);
    assert_eq!(verdict(&s), (0, 0, vec![]));
    // Fixing an end point as well is redundant, partially (it can only slide on the circle).
    let s = system(ARC, r#"Fix(id: "f", a: "a"), Fix(id: "g", a: "a.start")"#);
    assert_eq!(verdict(&s), (0, 0, vec!["g".to_owned()]));
}

#[test]
fn the_radius_and_end_points_of_an_arc_are_dimensioned() {
    // A chord and a radius: the arc keeps one internal freedom (the chord slides round).
    let s = system(
        ARC,
        r#"Radius(id: "r", a: "a", value: 5), Distance(id: "chord", a: "a.start", b: "a.end", value: 7.07)"#,
    );
    assert_eq!(verdict(&s), (0, 3, vec![]));
    // The distance from an end point to the centre is the radius: redundant.
    let s = system(
        ARC,
        r#"Radius(id: "r", a: "a", value: 5), Distance(id: "d", a: "a.start", b: "a.center", value: 5)"#,
    );
    assert_eq!(verdict(&s), (1, 3, vec!["d".to_owned()]));
}

#[test]
fn a_centre_named_by_a_constraint_becomes_a_point() {
    // Two circles whose centres are dimensioned apart: c1.center and c2.center are points,
    // each held at its circle's centre.
    let s = system(
        r#"Circle(id: "c1", center: [0, 0], radius: 2), Circle(id: "c2", center: [5, 0], radius: 1)"#,
        r#"Distance(id: "d", a: "c1.center", b: "c2.center", value: 5)"#,
    );
    assert_eq!(s.written_entities(), 2);
    assert_eq!(s.entities().len(), 4);
    let center = s.entity_by_id("c1.center").expect("the centre is an entity");
    assert_eq!(s.entity(center).owner, s.entity_by_id("c1"));
    assert_eq!(s.constraint_by_id("c1.center@c1").map(|c| s.constraint(c).doc), Some(2));
    // 6 unknowns of the circles + 4 of the centres − 4 implicit − 1 = 5, less 3 motions.
    assert_eq!(verdict(&s), (2, 3, vec![]));
    // Naming a centre again reuses the same point; a point put at the centre with
    // `Concentric` and a coincidence with the centre say the same thing twice.
    let s = system(
        r#"Circle(id: "c", center: [0, 0], radius: 2), Point(id: "p", at: [0, 0])"#,
        r#"Concentric(id: "k", a: "p", b: "c"), Coincident(id: "same", a: "p", b: "c.center")"#,
    );
    // (A circle and its centre alone do not see rotations about it: two trivial motions.)
    assert_eq!(verdict(&s), (1, 2, vec!["same".to_owned()]));
}

#[test]
fn segment_end_points_have_names() {
    let s = system(
        r#"Point(id: "p", at: [0, 0]), Point(id: "q", at: [3, 4]), Segment(id: "s", from: "p", to: "q")"#,
        r#"Distance(id: "len", a: "s.start", b: "s.end", value: 5), Distance(id: "again", a: "p", b: "q", value: 5)"#,
    );
    assert_eq!(s.entity_by_id("s.start"), s.entity_by_id("p"));
    assert_eq!(s.entity_by_id("s.end"), s.entity_by_id("q"));
    assert_eq!(verdict(&s), (0, 3, vec!["again".to_owned()]));
}

#[test]
fn named_points_are_written_by_their_owners() {
    let s = system(
        &format!(r#"{ARC}, Circle(id: "c", center: [1, 2], radius: 3)"#),
        r#"Concentric(id: "k", a: "a", b: "c"), Distance(id: "d", a: "a.end", b: "c.center", value: 5)"#,
    );
    let text = s.to_ron();
    assert!(
        text.contains(r#"Arc(id: "a", center: [1, 2], radius: 5, start: [4, 6], end: [-3, 5])"#)
    );
    assert!(!text.contains("@"), "implicit constraints are not written:\n{text}");
    assert!(!text.contains(r#"Point(id: "a.start""#), "{text}");
    let again = System::from_ron_str(&text, None).unwrap();
    assert_eq!(again.entities().len(), s.entities().len());
    assert_eq!(again.constraints().len(), s.constraints().len());
    for (x, y) in again.entities().iter().zip(s.entities()) {
        assert_eq!((&x.id, &x.geometry, x.owner), (&y.id, &y.geometry, y.owner));
    }
}

#[test]
fn bad_named_points_are_reported_with_their_place() {
    let bad = |entities: &str, constraints: &str| {
        let text =
            format!("System(dim: 2,\n entities: [{entities}],\n constraints: [{constraints}])");
        System::from_ron_str(&text, Some("bad.ron")).unwrap_err().to_string()
    };
    // A point has no centre.
    let e = bad(
        r#"Point(id: "p", at: [0, 0]), Point(id: "q")"#,
        r#"Coincident(id: "k", a: "q", b: "p.center")"#,
    );
    assert_eq!(e, r#"bad.ron:3:47: constraint "k": field b: unknown entity id "p.center""#);
    // An arc's end point with three coordinates in 2D.
    let e = bad(r#"Arc(id: "a", center: [0, 0], radius: 1, start: [1, 0, 0])"#, "");
    assert!(
        e.starts_with("bad.ron:2:") && e.contains(r#"entity "a""#) && e.contains("start"),
        "{e}"
    );
    // The name of an arc's end point is taken.
    let e = bad(r#"Point(id: "a.start"), Arc(id: "a", center: [0, 0], radius: 1)"#, "");
    assert!(e.contains(r#"duplicate id "a.start""#), "{e}");
}

/// A fillet: a horizontal and a vertical segment joined by a quarter arc of radius 2, tangent
/// at both joints. Written as CAD programs mean it — the arc's end coincides with the segment's
/// and they are tangent *there* (`TangentAt`) — it is well-constrained once its lengths and
/// radius are given. Written as incidence + coincidence + tangency (`Tangent`, tangent
/// somewhere), the three equations are dependent at every solution: one false redundancy and
/// one false freedom per joint, the trap every emulation falls into.
#[test]
fn a_fillet_is_tangent_at_its_joints() {
    let entities = r#"
        Point(id: "p1", at: [0, 0]), Point(id: "p2", at: [10, 0]),
        Point(id: "p3", at: [12, 2]), Point(id: "p4", at: [12, 10]),
        Segment(id: "s1", from: "p1", to: "p2"), Segment(id: "s2", from: "p3", to: "p4"),
        Arc(id: "a", center: [10, 2], radius: 2, start: [10, 0], end: [12, 2])"#;
    let common = r#"
        Fix(id: "fix", a: "p1"), Horizontal(id: "h", a: "s1"), Vertical(id: "v", a: "s2"),
        Coincident(id: "j1", a: "s1.end", b: "a.start"), Coincident(id: "j2", a: "a.end", b: "s2.start"),
        Radius(id: "r", a: "a", value: 2), Distance(id: "l1", a: "p1", b: "p2", value: 10),
        Distance(id: "l2", a: "p3", b: "p4", value: 8)"#;
    let cad = system(
        entities,
        &format!(
            r#"{common}, TangentAt(id: "t1", a: "s1", b: "a", at: "a.start"),
                TangentAt(id: "t2", a: "a", b: "s2", at: "a.end")"#
        ),
    );
    assert_eq!(verdict(&cad), (0, 0, vec![]));
    let trap = system(
        entities,
        &format!(
            r#"{common}, Tangent(id: "t1", a: "s1", b: "a"), Tangent(id: "t2", a: "a", b: "s2")"#
        ),
    );
    assert_eq!(verdict(&trap), (2, 0, vec!["t1".to_owned(), "t2".to_owned()]));
}

/// An arc slot as CAD programs draw it (SketchGraphs' Onshape sample, 00275001/4, ids
/// renamed): a path arc, a cap at each of its ends (arcs centred on its end points), and the
/// outer and inner arcs of the slot, each tangent to both caps at the points they share with
/// them — no concentricity (Onshape's offsets are not expressible), so the sides are circles
/// tangent to the two caps. The drawing holds to 1e-9 only (no witness). Built points first,
/// a side would be a circle through two placed points with both tangents given, and the
/// placement failed in every backend but float. With the tangencies of circles those points
/// imply, the witness is rational at every seed, and exact and modp agree with float (5
/// degrees of freedom, nothing redundant).
#[test]
fn an_arc_slot_tangent_at_its_caps_has_an_exact_witness() {
    let s = system(
        r#"Arc(id: "path", center: [0, 0], radius: 40, start: [37.587704831, -13.680805733], end: [13.680805733, 37.587704831]),
    Arc(id: "cap1", center: [13.680805733, 37.587704831], radius: 5, start: [15.390906450, 42.286167935], end: [11.970705016, 32.889241728]),
    Arc(id: "cap2", center: [37.587704831, -13.680805733], radius: 5, start: [32.889241728, -11.970705016], end: [42.286167935, -15.390906450]),
    Arc(id: "outer", center: [0, 0], radius: 45, start: [42.286167935, -15.390906450], end: [15.390906450, 42.286167935]),
    Arc(id: "inner", center: [0, 0], radius: 35, start: [32.889241728, -11.970705016], end: [11.970705016, 32.889241728])"#,
        r#"Coincident(id: "cap1_on_path", a: "cap1.center", b: "path.end"),
        Coincident(id: "cap2_on_path", a: "cap2.center", b: "path.start"),
        Coincident(id: "c1", a: "cap1.end", b: "inner.end"),
        Coincident(id: "c2", a: "cap1.start", b: "outer.end"),
        Coincident(id: "c3", a: "cap2.end", b: "outer.start"),
        Coincident(id: "c4", a: "cap2.start", b: "inner.start"),
        TangentAt(id: "t1", a: "cap1", b: "outer", at: "cap1.start"),
        TangentAt(id: "t2", a: "cap1", b: "inner", at: "cap1.end"),
        TangentAt(id: "t3", a: "cap2", b: "outer", at: "cap2.end"),
        TangentAt(id: "t4", a: "cap2", b: "inner", at: "cap2.start"),
        Radius(id: "width", a: "cap1", value: 5)"#,
    );
    assert_eq!(verdict(&s), (5, 3, Vec::<String>::new()));
    for seed in [1, 2, 3] {
        let witness = gcs_jacobian::WitnessOptions { seed, ..Default::default() };
        let exact = analyze(&s, &AnalysisOptions { witness, ..Default::default() }).expect("exact");
        assert_eq!(exact.witness.source, gcs_jacobian::WitnessSource::Generated, "seed {seed}");
        assert_eq!(exact.dof, 5, "seed {seed}");
    }
    let float = analyze(
        &s,
        &AnalysisOptions { backend: Backend::Float { tolerance: 1e-9 }, ..Default::default() },
    )
    .expect("float");
    assert_eq!((float.dof, float.rank), (5, 31));
}
