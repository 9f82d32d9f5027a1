//! Every constraint kind, in every shape it takes, in 2D and 3D, contributes exactly DOC
//! equations independent at a generated witness (docs/design.md: "a constraint contributes exactly
//! DOC independent rows at a generic witness"), and every entity kind alone admits exactly its
//! degree of rigidity in trivial motions.

use gcs_analysis::{AnalysisOptions, Backend, analyze};
use gcs_jacobian::{WitnessOptions, WitnessSource};
use gcs_model::System;

fn system(dim: u8, entities: &str, constraints: &str) -> System {
    let text = format!("System(dim: {dim}, entities: [{entities}], constraints: [{constraints}])");
    System::from_ron_str(&text, None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// Checks that the system is analysed at a generated witness with no redundancy: every
/// constraint's rows are independent and there are exactly DOC of them.
fn independent(dim: u8, entities: &str, constraints: &str) {
    let s = system(dim, entities, constraints);
    for backend in [Backend::Exact, Backend::ModP] {
        for seed in [1, 2] {
            let options = AnalysisOptions {
                backend,
                witness: WitnessOptions { seed, rounds: 1, ..WitnessOptions::default() },
                clusters: false,
                ..AnalysisOptions::default()
            };
            let a = analyze(&s, &options).unwrap_or_else(|e| panic!("{constraints}: {e}"));
            assert!(a.redundant.is_empty(), "{dim}D {constraints}: redundant {:?}", a.redundant);
            assert_eq!(
                a.rank,
                a.internal_equations + s.doc_sum(),
                "{dim}D {constraints}: rank vs DOC"
            );
            assert_eq!(a.witness.source, WitnessSource::Generated, "{constraints}");
        }
    }
}

/// The dimensions a case of [`CASES`] is tried in.
const BOTH: &[u8] = &[2, 3];
const TWO: &[u8] = &[2];
const THREE: &[u8] = &[3];

/// Every constraint kind in every shape it takes, on the entities of [`entities`], with the
/// dimensions it is tried in.
const CASES: &[(&[u8], &str)] = &[
    (BOTH, r#"Coincident(id: "c", a: "q", b: "s")"#),
    (BOTH, r#"Distance(id: "c", a: "p", b: "q")"#),
    (BOTH, r#"Distance(id: "c", a: "p", b: "l")"#),
    (TWO, r#"Distance(id: "c", a: "rs", b: "p")"#),
    (THREE, r#"Distance(id: "c", a: "p", b: "rs")"#),
    (THREE, r#"Distance(id: "c", a: "p", b: "a")"#),
    (THREE, r#"Distance(id: "c", a: "l", b: "m")"#),
    (THREE, r#"Distance(id: "c", a: "pq", b: "rs")"#),
    (BOTH, r#"Parallel(id: "c0", a: "l", b: "m"), Distance(id: "c", a: "l", b: "m")"#),
    (TWO, r#"Parallel(id: "c0", a: "pq", b: "rs"), Distance(id: "c", a: "pq", b: "rs")"#),
    (TWO, r#"Concentric(id: "c0", a: "k", b: "k2"), Distance(id: "c", a: "k", b: "k2")"#),
    (THREE, r#"Parallel(id: "c0", a: "a", b: "b"), Distance(id: "c", a: "a", b: "b")"#),
    (BOTH, r#"Angle(id: "c", a: "l", b: "m")"#),
    (TWO, r#"Angle(id: "c", a: "pq", b: "m")"#),
    (TWO, r#"Angle(id: "c", a: "pq", b: "pr")"#),
    (BOTH, r#"LengthRatio(id: "c", a: "pq", b: "rs")"#),
    (TWO, r#"EqualAngle(id: "c", a: "pq", b: "l", c: "rs", d: "m")"#),
    (TWO, r#"EqualAngle(id: "c", a: "pq", b: "pr", c: "pr", d: "rs")"#),
    // At a right angle both branches of an equal angle hold: the analysis keeps one, regular.
    (
        TWO,
        r#"Perpendicular(id: "c0", a: "pq", b: "pr"),
           EqualAngle(id: "c", a: "pq", b: "pr", c: "rs", d: "l")"#,
    ),
    (TWO, r#"EqualDistance(id: "c", a: "p", b: "q", c: "r", d: "s")"#),
    (TWO, r#"EqualDistance(id: "c", a: "p", b: "q", c: "r", d: "l")"#),
    (TWO, r#"EqualDistance(id: "c", a: "l", b: "p", c: "q", d: "r")"#),
    (TWO, r#"EqualDistance(id: "c", a: "p", b: "l", c: "q", d: "rs")"#),
    (TWO, r#"EqualDistance(id: "c", a: "p", b: "l", c: "q", d: "l")"#),
    // The gap of two circles is the difference of their radii (an offset's, when concentric).
    (TWO, r#"EqualDistance(id: "c", a: "k", b: "k2", c: "p", d: "q")"#),
    (TWO, r#"EqualDistance(id: "c", a: "p", b: "l", c: "k2", d: "k")"#),
    (
        TWO,
        r#"Concentric(id: "c0", a: "k", b: "k2"), EqualDistance(id: "c", a: "k", b: "k2", c: "q", d: "rs")"#,
    ),
    (THREE, r#"Angle(id: "c", a: "l", b: "a")"#),
    (THREE, r#"Angle(id: "c", a: "a", b: "b")"#),
    (BOTH, r#"Parallel(id: "c", a: "l", b: "m")"#),
    (BOTH, r#"Parallel(id: "c", a: "pq", b: "rs")"#),
    (TWO, r#"Parallel(id: "c", a: "pq", b: "l")"#),
    (THREE, r#"Parallel(id: "c", a: "a", b: "b")"#),
    (THREE, r#"Parallel(id: "c", a: "l", b: "a")"#),
    (BOTH, r#"Perpendicular(id: "c", a: "l", b: "m")"#),
    (BOTH, r#"Perpendicular(id: "c", a: "pq", b: "pr")"#),
    (TWO, r#"Perpendicular(id: "c", a: "pq", b: "rs")"#),
    (THREE, r#"Perpendicular(id: "c", a: "a", b: "b")"#),
    (THREE, r#"Perpendicular(id: "c", a: "l", b: "a")"#),
    (BOTH, r#"Incident(id: "c", a: "p", b: "l")"#),
    (TWO, r#"Incident(id: "c", a: "rs", b: "p")"#),
    (THREE, r#"Incident(id: "c", a: "s", b: "pq")"#),
    (THREE, r#"Incident(id: "c", a: "p", b: "a")"#),
    (BOTH, r#"Incident(id: "c", a: "p", b: "k")"#),
    (THREE, r#"Incident(id: "c", a: "l", b: "a")"#),
    (THREE, r#"Incident(id: "c", a: "pq", b: "a")"#),
    (TWO, r#"Tangent(id: "c", a: "l", b: "k")"#),
    (TWO, r#"Tangent(id: "c", a: "pq", b: "k")"#),
    (THREE, r#"Tangent(id: "c", a: "a", b: "k")"#),
    (BOTH, r#"Tangent(id: "c", a: "k", b: "k2")"#),
    (BOTH, r#"Radius(id: "c", a: "k")"#),
    (BOTH, r#"EqualLength(id: "c", a: "pq", b: "rs")"#),
    (TWO, r#"EqualLength(id: "c", a: "pq", b: "pr")"#),
    (BOTH, r#"Midpoint(id: "c", point: "s", segment: "pq")"#),
    (TWO, r#"Symmetric(id: "c", a: "p", b: "q", axis: "l")"#),
    (TWO, r#"Symmetric(id: "c", a: "p", b: "q", axis: "rs")"#),
    (TWO, r#"Horizontal(id: "c", a: "l")"#),
    (TWO, r#"Horizontal(id: "c", a: "pq")"#),
    (TWO, r#"Vertical(id: "c", a: "l")"#),
    (TWO, r#"Vertical(id: "c", a: "pq")"#),
    // Several at once, sharing entities.
    (
        TWO,
        r#"Incident(id: "c1", a: "p", b: "l"), Incident(id: "c2", a: "q", b: "l"),
           Incident(id: "c3", a: "p", b: "k"), Tangent(id: "c4", a: "m", b: "k"),
           Perpendicular(id: "c5", a: "l", b: "m")"#,
    ),
    (
        THREE,
        r#"Incident(id: "c1", a: "p", b: "l"), Incident(id: "c2", a: "q", b: "l"),
           Incident(id: "c3", a: "l", b: "a"), Perpendicular(id: "c4", a: "a", b: "b"),
           Incident(id: "c5", a: "r", b: "b")"#,
    ),
];

/// The entities [`CASES`] refer to: four points, two lines, three segments between the points,
/// two circles (spheres in 3D), and two planes in 3D.
fn entities(dim: u8) -> String {
    let shared = r#"Point(id: "p"), Point(id: "q"), Point(id: "r"), Point(id: "s"),
        Line(id: "l"), Line(id: "m"), Segment(id: "pq", from: "p", to: "q"),
        Segment(id: "rs", from: "r", to: "s"), Segment(id: "pr", from: "p", to: "r")"#;
    match dim {
        2 => format!(r#"{shared}, Circle(id: "k"), Circle(id: "k2")"#),
        _ => format!(
            r#"{shared}, Plane(id: "a"), Plane(id: "b"), Sphere(id: "k"), Sphere(id: "k2")"#
        ),
    }
}

/// Every case of [`CASES`] tried in `dim` is independent there.
fn every_case_removes_its_doc(dim: u8) {
    let all = entities(dim);
    for (_, c) in CASES.iter().filter(|(dims, _)| dims.contains(&dim)) {
        independent(dim, &all, c);
    }
}

#[test]
fn every_2d_constraint_removes_its_doc() {
    every_case_removes_its_doc(2);
}

#[test]
fn every_3d_constraint_removes_its_doc() {
    every_case_removes_its_doc(3);
}

#[test]
fn fix_pins_every_kind() {
    let two = r#"Point(id: "p", at: [1, 2]), Point(id: "q", at: [4, -1]),
        Segment(id: "pq", from: "p", to: "q"), Line(id: "l", at: [[0, 1], [3, 2]]),
        Circle(id: "k", center: [5, 5], radius: 2)"#;
    let three = r#"Point(id: "p", at: [1, 2, 3]), Point(id: "q", at: [4, -1, 0]),
        Segment(id: "pq", from: "p", to: "q"), Line(id: "l", at: [[0, 1, 2], [3, 2, -1]]),
        Plane(id: "a", at: [[1, 1, 1], [1, 2, 3]]), Sphere(id: "k", center: [5, 5, 5], radius: 2)"#;
    for (dim, ents, ids) in
        [(2, two, &["p", "pq", "l", "k"][..]), (3, three, &["p", "pq", "l", "a", "k"][..])]
    {
        for id in ids {
            let s = system(dim, ents, &format!(r#"Fix(id: "f", a: "{id}")"#));
            let a = analyze(&s, &AnalysisOptions::default()).unwrap();
            assert!(a.redundant.is_empty(), "Fix({id}) in {dim}D");
            assert_eq!(a.rank, a.internal_equations + s.doc_sum(), "Fix({id}) in {dim}D");
        }
    }
}

/// One entity alone admits as many trivial motions as its degree of rigidity (the
/// displacements that move it) and keeps the rest of its DOF as internal ones.
#[test]
fn trivial_motions_of_single_entities() {
    for (dim, entity, trivial, dof) in [
        (2, r#"Point(id: "x")"#, 2, 0),
        (2, r#"Line(id: "x")"#, 2, 0),
        (2, r#"Circle(id: "x")"#, 2, 1),
        (3, r#"Point(id: "x")"#, 3, 0),
        (3, r#"Line(id: "x")"#, 4, 0),
        (3, r#"Plane(id: "x")"#, 3, 0),
        (3, r#"Sphere(id: "x")"#, 3, 1),
    ] {
        let s = system(dim, entity, "");
        let a = analyze(&s, &AnalysisOptions::default()).unwrap();
        assert_eq!((a.trivial_motions, a.dof), (trivial, dof), "{dim}D {entity}");
    }
    // Two points: the full group in 2D; in 3D the rotation about their axis moves nothing.
    for (dim, trivial) in [(2, 3), (3, 5)] {
        let s = system(
            dim,
            r#"Point(id: "p"), Point(id: "q")"#,
            r#"Distance(id: "d", a: "p", b: "q")"#,
        );
        let a = analyze(&s, &AnalysisOptions::default()).unwrap();
        assert_eq!((a.trivial_motions, a.dof), (trivial, 0), "{dim}D segment");
    }
}

/// Every row of the constraint table, found by asking the resolver about every tuple of
/// entity kinds in both dimensions (so that a row added later is covered without editing this
/// test): at a generated witness, the constraint alone contributes exactly its DOC rows, all
/// independent. A distance between 2D lines or planes needs them parallel: a `Parallel`
/// constraint comes first there, and counts too.
#[test]
fn every_row_the_resolver_accepts_removes_its_doc() {
    use gcs_model::number::int;
    use gcs_model::{ConstraintKind, Dim, EntityIdx, EntityKind, Signature, SystemBuilder};
    let mut seen = std::collections::BTreeSet::new();
    for dim in [Dim::Two, Dim::Three] {
        let kinds: Vec<EntityKind> =
            EntityKind::ALL.into_iter().filter(|k| k.exists_in(dim)).collect();
        for kind in ConstraintKind::ALL {
            let arity = kind.fields().len();
            let mut tuples: Vec<Vec<EntityKind>> = vec![Vec::new()];
            for _ in 0..arity {
                tuples = tuples
                    .into_iter()
                    .flat_map(|t| {
                        kinds.iter().map(move |k| {
                            let mut t = t.clone();
                            t.push(*k);
                            t
                        })
                    })
                    .collect();
            }
            for tuple in tuples {
                let fake: Vec<EntityIdx> = (0..arity as u32).map(EntityIdx).collect();
                let Ok((signature, _)) = Signature::resolve(dim, kind, &fake, &tuple) else {
                    continue;
                };
                let name: String = format!("{signature:?}")
                    .trim_start_matches("Metric(")
                    .chars()
                    .take_while(char::is_ascii_alphanumeric)
                    .collect();
                seen.insert(format!("{dim} {name}"));
                // Fresh entities of those kinds, at distinct integer positions.
                let mut b = SystemBuilder::new("row", dim);
                let n = dim.coords();
                let mut next = 0i64;
                let mut at = |k: i64| -> Vec<_> {
                    next += 1;
                    (0..n as i64).map(|i| int((next * 7 + i * 3 + k) % 11 - 5 + i)).collect()
                };
                let mut ids = Vec::new();
                for (i, k) in tuple.iter().enumerate() {
                    let id = format!("e{i}");
                    let made = match k {
                        EntityKind::Point => b.point(&id, Some(at(0))),
                        EntityKind::Line => b.line(&id, Some([at(1), at(2)])),
                        EntityKind::Segment => {
                            b.point(&format!("{id}a"), Some(at(3))).unwrap();
                            b.point(&format!("{id}b"), Some(at(4))).unwrap();
                            b.segment(&id, &format!("{id}a"), &format!("{id}b"))
                        }
                        EntityKind::Circle => b.circle(&id, Some(at(5)), Some(int(2))),
                        EntityKind::Plane => b.plane(&id, Some([at(6), at(7)])),
                        EntityKind::Sphere => b.sphere(&id, Some(at(8)), Some(int(3))),
                        EntityKind::Arc => {
                            // Radius 5, end points at rational places on it.
                            let c = at(9);
                            let on = |dx: i64, dy: i64| vec![&c[0] + int(dx), &c[1] + int(dy)];
                            b.arc(
                                &id,
                                Some(c.clone()),
                                Some(int(5)),
                                Some(on(3, 4)),
                                Some(on(-4, 3)),
                            )
                        }
                        EntityKind::BSpline => {
                            let poles: Vec<String> = (0..5).map(|j| format!("{id}p{j}")).collect();
                            for (j, p) in poles.iter().enumerate() {
                                b.point(p, Some(at(10 + j as i64))).unwrap();
                            }
                            let poles: Vec<&str> = poles.iter().map(String::as_str).collect();
                            b.bspline(&id, 3, &poles, None, None, false)
                        }
                    };
                    made.unwrap_or_else(|e| panic!("{e}"));
                    ids.push(id);
                }
                let args: Vec<&str> = ids.iter().map(String::as_str).collect();
                if matches!(signature, Signature::Metric(gcs_model::Metric::DistanceLineLine(..)) if dim == Dim::Two)
                    || matches!(
                        signature,
                        Signature::Metric(gcs_model::Metric::DistancePlanePlane(..))
                    )
                {
                    b.constraint(ConstraintKind::Parallel, "parallel", &args, None).unwrap();
                }
                if matches!(
                    signature,
                    Signature::Metric(gcs_model::Metric::DistanceCircleCircle(..))
                ) {
                    b.constraint(ConstraintKind::Concentric, "concentric", &args, None).unwrap();
                }
                // (A spline point at the interior knot of the default knots 0⁴ 1 2⁴.)
                let value = (kind == ConstraintKind::SplinePoint).then(|| int(1));
                b.constraint(kind, "c", &args, value).unwrap_or_else(|e| panic!("{e}"));
                let s = b.build();
                let a = analyze(&s, &AnalysisOptions { clusters: false, ..Default::default() })
                    .unwrap_or_else(|e| panic!("{dim} {signature:?}: {e}"));
                assert!(a.redundant.is_empty(), "{dim} {signature:?}: {:?}", a.redundant);
                assert_eq!(a.rank, a.internal_equations + s.doc_sum(), "{dim} {signature:?}");
            }
        }
    }
    // Every row of the table in docs/format.md, 2D and 3D (a new row adds to the count).
    assert!(seen.len() >= 60, "{} rows: {seen:?}", seen.len());
}

/// The equalities of angles and distances and the ratio of lengths are redundant exactly where
/// the other constraints imply them, with those constraints as their spanning group.
#[test]
fn equalities_and_ratios_are_redundant_where_implied() {
    let cases = [
        // Parallel pairs make the angles equal.
        (
            r#"Parallel(id: "x1", a: "pq", b: "l"), Parallel(id: "x2", a: "pr", b: "m"),
               EqualAngle(id: "c", a: "pq", b: "pr", c: "l", d: "m")"#,
            vec!["x1", "x2"],
        ),
        // Two right angles are equal angles.
        (
            r#"Perpendicular(id: "x1", a: "pq", b: "pr"), Perpendicular(id: "x2", a: "rs", b: "l"),
               EqualAngle(id: "c", a: "pq", b: "pr", c: "rs", d: "l")"#,
            vec!["x1", "x2"],
        ),
        // Two dimensioned lengths fix their ratio and the equality of two distances.
        (
            r#"Distance(id: "x1", a: "p", b: "q"), Distance(id: "x2", a: "r", b: "s"),
               LengthRatio(id: "c", a: "pq", b: "rs")"#,
            vec!["x1", "x2"],
        ),
        (
            r#"Distance(id: "x1", a: "p", b: "l"), Distance(id: "x2", a: "q", b: "rs"),
               EqualDistance(id: "c", a: "p", b: "l", c: "q", d: "rs")"#,
            vec!["x1", "x2"],
        ),
        // Two radii and a length fix the equality of the circles' gap and the length.
        (
            r#"Radius(id: "x1", a: "k"), Radius(id: "x2", a: "k2"), Distance(id: "x3", a: "p", b: "q"),
               EqualDistance(id: "c", a: "k", b: "k2", c: "p", d: "q")"#,
            vec!["x1", "x2", "x3"],
        ),
        // Equal distances between points are equal lengths.
        (
            r#"EqualLength(id: "x1", a: "pq", b: "rs"),
               EqualDistance(id: "c", a: "p", b: "q", c: "r", d: "s")"#,
            vec!["x1"],
        ),
    ];
    for (constraints, group) in cases {
        let s = system(2, &entities(2), constraints);
        for backend in [Backend::Exact, Backend::ModP] {
            let a = analyze(&s, &AnalysisOptions { backend, ..AnalysisOptions::default() })
                .unwrap_or_else(|e| panic!("{constraints}: {e}"));
            assert_eq!(a.redundant.len(), 1, "{constraints}: {:?}", a.redundant);
            let r = &a.redundant[0];
            assert_eq!(s.constraint(r.constraint).id, "c", "{constraints}");
            let spanning: Vec<&str> =
                r.spanning_group.iter().map(|c| s.constraint(*c).id.as_str()).collect();
            assert_eq!(spanning, group, "{constraints}");
        }
    }
}
