//! Over-Rigid with the exact DOR of a witness ([`WitnessDor`]) on the papers' examples and the
//! CAD sketches of `data/`, beside the rule table.

use gcs_jacobian::Layout;
use gcs_model::{BigRational, EntityIdx, System};
use gcs_rigidity::{
    DorOracle, RigidityError, RuleDor, Verdict, WitnessDor, minimal_over_rigid,
    over_rigid_analysis, structural_analysis,
};
use gcs_suite::{data_files, load};

fn ids(system: &System, entities: &[EntityIdx]) -> Vec<String> {
    entities.iter().map(|e| system.entity(*e).id.clone()).collect()
}

fn entities(system: &System, names: &[&str]) -> Vec<EntityIdx> {
    names.iter().map(|n| system.entity_by_id(n).unwrap()).collect()
}

/// Every set of one, two or three entities.
fn small_sets(n: usize) -> Vec<Vec<EntityIdx>> {
    let e = |i: usize| EntityIdx(i as u32);
    let mut out = Vec::new();
    for i in 0..n {
        out.push(vec![e(i)]);
        for j in i + 1..n {
            out.push(vec![e(i), e(j)]);
            for k in j + 1..n {
                out.push(vec![e(i), e(j), e(k)]);
            }
        }
    }
    out
}

#[test]
fn flow_fig1a_parallel_lines_are_well_rigid() {
    let s = load("data/paper/flow_fig1a.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    assert_eq!(w.dor(&s, &entities(&s, &["A", "B"])), 2);
    assert_eq!(w.dor(&s, &entities(&s, &["A", "B", "C"])), 2);
    let a = over_rigid_analysis(&s, &w);
    assert_eq!(a.verdict, Verdict::WellRigid);
    assert_eq!((a.dof, a.dor, a.dor_source.as_str()), (2, 2, "witness"));
}

#[test]
fn flow_fig1b_finds_acdef() {
    let s = load("data/paper/flow_fig1b.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    // The paper's DORs: BC 5, CEF 6, CDE 5 (collinear on A).
    assert_eq!(w.dor(&s, &entities(&s, &["B", "C"])), 5);
    assert_eq!(w.dor(&s, &entities(&s, &["C", "E", "F"])), 6);
    assert_eq!(w.dor(&s, &entities(&s, &["C", "D", "E"])), 5);
    assert_eq!(w.dor(&s, &entities(&s, &["A", "C", "D", "E"])), 5);
    let a = over_rigid_analysis(&s, &w);
    assert_eq!(a.verdict, Verdict::OverRigid);
    let sub = a.subsystem.unwrap();
    assert_eq!(ids(&s, &sub.objects), ["A", "C", "D", "E", "F"]);
    assert_eq!(sub.dof, 5);
    let min = minimal_over_rigid(&s, &w).unwrap();
    assert_eq!(ids(&s, &min.objects), ["A", "C", "D", "E", "F"]);
}

#[test]
fn double_banana_still_fools_over_rigid() {
    // The hinge is not a DOR matter: every DOR is the generic one, and the count is fooled
    // with the exact DOR as with the rules.
    let s = load("data/paper/double_banana.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    let r = RuleDor::for_system(&s);
    for set in small_sets(s.entities().len()) {
        assert_eq!(w.dor(&s, &set), r.dor(&s, &set));
    }
    let a = over_rigid_analysis(&s, &w);
    assert_eq!((a.verdict, a.dof, a.dor), (Verdict::WellRigid, 6, 6));
}

#[test]
fn fig6_the_theorem_is_invisible_to_the_dor() {
    let s = load("data/paper/fig6_harmonic.ron");
    let a = over_rigid_analysis(&s, &WitnessDor::find(&s, 1).unwrap());
    // DOF 5 by count (d_ay "removes" one), DOR 3: 2 internal DOF; the witness analysis says 3.
    assert_eq!((a.verdict, a.dof, a.dor), (Verdict::UnderRigid, 5, 3));
}

#[test]
fn block_corner_hidden_collinearity() {
    // O and b are on the edge Y ∩ Z, which is perpendicular to X (X ⊥ Y, X ⊥ Z): the rotation
    // about that edge keeps X, O and b in place. The rules do not chain it.
    let s = load("data/sketches/block_3d.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    let r = RuleDor::for_system(&s);
    let set = entities(&s, &["X", "O", "b"]);
    assert_eq!((w.dor(&s, &set), r.dor(&s, &set)), (5, 6));
    // Both still find the redundant diagonal's subsystem.
    assert_eq!(over_rigid_analysis(&s, &w).verdict, Verdict::OverRigid);
    assert_eq!(over_rigid_analysis(&s, &r).verdict, Verdict::OverRigid);
}

#[test]
fn the_witness_dor_never_exceeds_the_rules() {
    // Every fact the rules read holds at the witness, so the exact DOR is at most the rules'
    // (they can only miss properties). Equality except where the geometry hides something.
    let mut differences = Vec::new();
    for f in data_files() {
        let s = load(&f);
        let w = WitnessDor::find(&s, 1).unwrap();
        let r = RuleDor::for_system(&s);
        for set in small_sets(s.entities().len()) {
            let (a, b) = (w.dor(&s, &set), r.dor(&s, &set));
            assert!(a <= b, "{f}: {:?}: witness {a} > rules {b}", ids(&s, &set));
            if a != b {
                differences.push(format!("{}: {}", s.name(), ids(&s, &set).join(" ")));
            }
        }
        // Over-Rigid with the exact DOR never finds more than with the rules: an over-rigid
        // verdict with the witness implies one with the rules.
        let with_w = over_rigid_analysis(&s, &w);
        let with_r = structural_analysis(&s, &r).over_rigid;
        if with_w.verdict == Verdict::OverRigid {
            assert_eq!(with_r.verdict, Verdict::OverRigid, "{f}");
        }
        assert!(with_w.dor <= with_r.dor, "{f}");
    }
    assert_eq!(
        differences,
        [
            "block_3d: X O b",
            "block_3d: Y O c",
            "block_3d: Z O a",
            // Equal radii make the two sides tangent to both circles parallel.
            "slot: side_low side_high",
        ]
    );
}

#[test]
fn generated_families_agree_with_the_rules() {
    // Bar frameworks at a generic witness: no hidden property, the two oracles agree on every
    // pair and triple, and so do the analyses.
    for s in [
        gcs_model::generate::laman(12, 7),
        gcs_model::generate::triangulated_sphere(10, 7),
        gcs_model::generate::rectangles(2),
    ] {
        let w = WitnessDor::find(&s, 1).unwrap();
        let r = RuleDor::for_system(&s);
        for set in small_sets(s.entities().len().min(14)) {
            assert_eq!(w.dor(&s, &set), r.dor(&s, &set), "{}: {set:?}", s.name());
        }
        assert_eq!(over_rigid_analysis(&s, &w).verdict, over_rigid_analysis(&s, &r).verdict);
    }
}

// ---- Properties of the exact DOR on small systems ----

fn system(text: &str) -> System {
    System::from_ron_str(text, None).unwrap()
}

fn both(s: &System) -> (WitnessDor, RuleDor) {
    (WitnessDor::find(s, 1).unwrap(), RuleDor::for_system(s))
}

#[test]
fn general_position_2d_equals_the_rules() {
    let s = system(
        r#"System(dim: 2, entities: [
            Point(id: "p", at: [0, 0]), Point(id: "q", at: [5, 1]), Point(id: "r", at: [2, 7]),
            Line(id: "A", at: [[1, 3], [4, -2]]), Line(id: "B", at: [[-3, 1], [2, 9]]),
            Line(id: "C", at: [[7, 7], [0, 3]]),
            Circle(id: "k", center: [3, -4], radius: 2) ], constraints: [])"#,
    );
    let (w, r) = both(&s);
    assert_eq!(w.displacements(), 3);
    for set in small_sets(s.entities().len()) {
        assert_eq!(w.dor(&s, &set), r.dor(&s, &set), "{set:?}");
    }
    assert_eq!(w.dor(&s, &[]), 0);
}

#[test]
fn general_position_3d_equals_the_rules() {
    let s = system(
        r#"System(dim: 3, entities: [
            Point(id: "p", at: [0, 0, 0]), Point(id: "q", at: [5, 1, 2]),
            Point(id: "r", at: [2, 7, -3]),
            Line(id: "A", at: [[1, 3, 0], [4, -2, 1]]), Line(id: "B", at: [[-3, 1, 5], [2, 9, 4]]),
            Plane(id: "P", at: [[0, 0, 1], [1, 2, 3]]), Plane(id: "Q", at: [[2, 0, 0], [-1, 4, 1]]),
            Sphere(id: "S", center: [3, -4, 1], radius: 2) ], constraints: [])"#,
    );
    let (w, r) = both(&s);
    assert_eq!(w.displacements(), 6);
    let single: Vec<usize> = s.entity_indices().map(|e| w.entity_dor(e)).collect();
    assert_eq!(single, [3, 3, 3, 4, 4, 3, 3, 3]);
    for set in small_sets(s.entities().len()) {
        assert_eq!(w.dor(&s, &set), r.dor(&s, &set), "{set:?}");
    }
}

#[test]
fn explicit_properties_equal_the_rules() {
    // Properties the constraints state: the rule table and the witness agree.
    let s = system(
        r#"System(dim: 3, entities: [
            Line(id: "L", at: [[0, 0, 0], [1, 0, 0]]), Line(id: "M", at: [[0, 1, 0], [1, 1, 0]]),
            Point(id: "p", at: [0, 0, 0]), Point(id: "q", at: [1, 0, 0]), Point(id: "r", at: [2, 0, 0]),
            Point(id: "off", at: [0, 3, 3]),
            Plane(id: "Pa", at: [[0, 0, 0], [0, 0, 1]]), Plane(id: "Pb", at: [[0, 0, 2], [0, 0, 1]]),
            Line(id: "Z", at: [[0, 0, 0], [0, 0, 1]]), Segment(id: "pq", from: "p", to: "q") ],
          constraints: [
            Parallel(id: "lm", a: "L", b: "M"), Incident(id: "p_on", a: "p", b: "L"),
            Incident(id: "q_on", a: "q", b: "L"), Incident(id: "r_on", a: "r", b: "L"),
            Parallel(id: "ab", a: "Pa", b: "Pb"), Perpendicular(id: "z", a: "Z", b: "Pa"),
            Incident(id: "l_in", a: "L", b: "Pa") ])"#,
    );
    let (w, r) = both(&s);
    let cases: [(&[&str], usize); 12] = [
        (&["L", "M"], 5),
        (&["p", "L"], 5),
        (&["off", "L"], 6),
        (&["p", "q", "r"], 5),
        (&["p", "q", "off"], 6),
        (&["Pa", "Pb"], 3),
        (&["Z", "Pa"], 5),
        (&["L", "Pa"], 5),
        (&["L", "M", "Pa"], 5),
        (&["pq"], 5),
        (&["pq", "r", "L"], 5),
        (&["pq", "off"], 6),
    ];
    for (names, expected) in cases {
        let set = entities(&s, names);
        assert_eq!(w.dor(&s, &set), expected, "{names:?}");
        assert_eq!(r.dor(&s, &set), expected, "{names:?}");
    }
}

#[test]
fn two_points_on_two_planes_and_a_third_are_collinear() {
    // a, b, c on both planes: on their common line. The rules do not chain incidences on
    // planes into collinearity; the witness sees the rotation about that line.
    let text = |extra: &str| {
        format!(
            r#"System(dim: 3, entities: [
                Plane(id: "P", at: [[0, 0, 0], [0, 0, 1]]), Plane(id: "Q", at: [[0, 0, 0], [0, 1, 0]]),
                Point(id: "a", at: [0, 0, 0]), Point(id: "b", at: [2, 0, 0]), Point(id: "c", at: [7, 0, 0]),
                Line(id: "L", at: [[0, 0, 0], [1, 0, 0]]) ],
              constraints: [
                Incident(id: "a_P", a: "a", b: "P"), Incident(id: "a_Q", a: "a", b: "Q"),
                Incident(id: "b_P", a: "b", b: "P"), Incident(id: "b_Q", a: "b", b: "Q"),
                Incident(id: "c_P", a: "c", b: "P"), Incident(id: "c_Q", a: "c", b: "Q") {extra} ])"#
        )
    };
    let s = system(&text(""));
    let (w, r) = both(&s);
    let abc = entities(&s, &["a", "b", "c"]);
    assert_eq!(r.dor(&s, &abc), 6);
    assert_eq!(w.dor(&s, &abc), 5);
    // The right value: the rules give it once the line is explicit.
    let explicit = system(&text(
        r#", Incident(id: "a_L", a: "a", b: "L"), Incident(id: "b_L", a: "b", b: "L"),
            Incident(id: "c_L", a: "c", b: "L")"#,
    ));
    assert_eq!(RuleDor::for_system(&explicit).dor(&explicit, &abc), 5);
}

#[test]
fn medians_are_concurrent() {
    // Theorem: the medians of a triangle meet at one point. G is put on two medians; it is
    // on the third, so c, its opposite midpoint mc and G are collinear (3D: DOR 5).
    let s = system(
        r#"System(dim: 3, entities: [
            Point(id: "a", at: [0, 0, 0]), Point(id: "b", at: [6, 0, 3]), Point(id: "c", at: [0, 6, 9]),
            Segment(id: "ab", from: "a", to: "b"), Segment(id: "bc", from: "b", to: "c"),
            Segment(id: "ca", from: "c", to: "a"),
            Point(id: "ma", at: [3, 3, 6]), Point(id: "mb", at: [0, 3, 4.5]), Point(id: "mc", at: [3, 0, 1.5]),
            Segment(id: "med_a", from: "a", to: "ma"), Segment(id: "med_b", from: "b", to: "mb"),
            Point(id: "G", at: [2, 2, 4]) ],
          constraints: [
            Midpoint(id: "m_a", point: "ma", segment: "bc"), Midpoint(id: "m_b", point: "mb", segment: "ca"),
            Midpoint(id: "m_c", point: "mc", segment: "ab"),
            Incident(id: "G_a", a: "G", b: "med_a"), Incident(id: "G_b", a: "G", b: "med_b") ])"#,
    );
    let (w, r) = both(&s);
    let set = entities(&s, &["c", "mc", "G"]);
    assert_eq!(r.dor(&s, &set), 6);
    assert_eq!(w.dor(&s, &set), 5);
    // Stated explicitly (the midpoints and G on one segment), the rules agree.
    assert_eq!(r.dor(&s, &entities(&s, &["a", "ma", "G"])), 5);
    assert_eq!(w.dor(&s, &entities(&s, &["a", "ma", "G"])), 5);
    // A control: a, b, G are not collinear.
    assert_eq!(w.dor(&s, &entities(&s, &["a", "b", "G"])), 6);
}

#[test]
fn midline_is_parallel_to_the_base() {
    // 2D theorem: the line through the midpoints of two sides is parallel to the third.
    let s = system(
        r#"System(dim: 2, entities: [
            Point(id: "a", at: [0, 0]), Point(id: "b", at: [8, 2]), Point(id: "c", at: [2, 6]),
            Segment(id: "ab", from: "a", to: "b"), Segment(id: "ac", from: "a", to: "c"),
            Point(id: "m", at: [4, 1]), Point(id: "n", at: [1, 3]),
            Line(id: "mid", at: [[4, 1], [1, 3]]), Line(id: "base", at: [[8, 2], [2, 6]]) ],
          constraints: [
            Midpoint(id: "m_ab", point: "m", segment: "ab"), Midpoint(id: "n_ac", point: "n", segment: "ac"),
            Incident(id: "m_on", a: "m", b: "mid"), Incident(id: "n_on", a: "n", b: "mid"),
            Incident(id: "b_on", a: "b", b: "base"), Incident(id: "c_on", a: "c", b: "base") ])"#,
    );
    let (w, r) = both(&s);
    let set = entities(&s, &["mid", "base"]);
    assert_eq!(r.dor(&s, &set), 3);
    assert_eq!(w.dor(&s, &set), 2);
    // The points are what they are: 3 whatever their alignment in 2D.
    assert_eq!(w.dor(&s, &entities(&s, &["m", "n", "b"])), 3);
}

#[test]
fn perpendicular_to_two_lines_in_3d_means_parallel() {
    // In 3D, two lines perpendicular to one common line need not be parallel; perpendicular
    // to two secant directions, they are.
    // The sketch of L2 is drawn parallel to L1 only when the constraints force it: a
    // witness is a configuration, and one drawn with an accidental parallelism has it.
    let text = |with_n: bool| {
        let (extra, l2) = if with_n {
            (
                r#", Perpendicular(id: "b", a: "L1", b: "N"), Perpendicular(id: "d", a: "L2", b: "N")"#,
                "[[3, 2, 0], [3, 2, 5]]",
            )
        } else {
            ("", "[[3, 2, 0], [3, 5, 3]]")
        };
        format!(
            r#"System(dim: 3, entities: [
                Line(id: "M", at: [[0, 0, 0], [1, 0, 0]]), Line(id: "N", at: [[0, 0, 1], [0, 1, 1]]),
                Line(id: "L1", at: [[0, 0, 0], [0, 0, 1]]), Line(id: "L2", at: {l2}) ],
              constraints: [
                Perpendicular(id: "a", a: "L1", b: "M"), Perpendicular(id: "c", a: "L2", b: "M") {extra} ])"#
        )
    };
    let one = system(&text(false));
    let (w, r) = both(&one);
    let l = entities(&one, &["L1", "L2"]);
    assert_eq!((w.dor(&one, &l), r.dor(&one, &l)), (6, 6));
    let two = system(&text(true));
    let (w, r) = both(&two);
    assert_eq!(r.dor(&two, &l), 6);
    assert_eq!(w.dor(&two, &l), 5);
    // With the parallelism stated, the rules agree with the witness.
    let stated = system(&text(false).replace(
        "Perpendicular(id: \"c\"",
        "Parallel(id: \"par\", a: \"L1\", b: \"L2\"), Perpendicular(id: \"c\"",
    ));
    assert_eq!(RuleDor::for_system(&stated).dor(&stated, &l), 5);
}

#[test]
fn monotone_bounded_and_robust() {
    let s = gcs_model::generate::triangulated_sphere(12, 3);
    let w = WitnessDor::find(&s, 1).unwrap();
    let n = s.entities().len();
    for set in small_sets(n.min(8)) {
        let d = w.dor(&s, &set);
        assert!(d <= 6);
        for drop in 0..set.len() {
            let mut smaller = set.clone();
            smaller.remove(drop);
            assert!(w.dor(&s, &smaller) <= d);
        }
    }
    let all: Vec<EntityIdx> = s.entity_indices().collect();
    assert_eq!(w.dor(&s, &all), 6);
    // Out of range and repeated indices.
    assert_eq!(w.dor(&s, &[EntityIdx(10_000)]), 0);
    assert_eq!(w.dor(&s, &[EntityIdx(0), EntityIdx(0)]), 3);
    // A wrong witness is an error, not a panic.
    let layout = Layout::new(&s);
    assert!(matches!(WitnessDor::new(&s, &layout, &[]), Err(RigidityError::Witness(_))));
    let other = gcs_model::generate::laman(5, 1);
    assert!(
        WitnessDor::new(
            &other,
            &layout,
            &vec![BigRational::from_integer(1.into()); layout.ncols()]
        )
        .is_err()
    );
}
