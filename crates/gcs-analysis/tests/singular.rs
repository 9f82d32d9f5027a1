//! The drawing itself (the survey's criterion (f)): the classical singular positions of
//! rigidity theory in `data/singular/`, each beside a generic control (the same sketch with one
//! point moved off the special position), in every backend; a drawing whose dimensions were
//! edited; and a property: in random Laman sketches, drawing one triangle flat creates exactly
//! one extra motion, and the dependency named contains its three points.

use gcs_analysis::{Analysis, AnalysisOptions, Backend, Position, SketchAnalysis, analyze};
use gcs_jacobian::WitnessSource;
use gcs_model::number::int;
use gcs_model::rng::SplitMix64;
use gcs_model::{BigRational, Geometry, System, SystemBuilder};
use gcs_suite::load;

const BACKENDS: [Backend; 3] = [Backend::Exact, Backend::ModP, Backend::Float { tolerance: 1e-9 }];

fn run(s: &System, backend: Backend) -> Analysis {
    analyze(s, &AnalysisOptions { backend, ..AnalysisOptions::default() })
        .unwrap_or_else(|e| panic!("{}: {e}", s.name()))
}

fn ids(s: &System, c: &[gcs_model::ConstraintIdx]) -> Vec<String> {
    c.iter().map(|c| s.constraint(*c).id.clone()).collect()
}

/// What the drawing's analysis says, with ids, for comparing backends.
fn summary(s: &System, sk: &SketchAnalysis) -> String {
    let dependent: Vec<(String, Vec<String>)> = sk
        .dependent
        .iter()
        .map(|d| (s.constraint(d.constraint).id.clone(), ids(s, &d.spanning_group)))
        .collect();
    let configurations: Vec<(&str, Vec<String>, Vec<String>)> = sk
        .configurations
        .iter()
        .map(|c| {
            let e = c.entities.iter().map(|e| s.entity(*e).id.clone()).collect();
            (c.position.name(), e, ids(s, &c.constraints))
        })
        .collect();
    format!(
        "rank {} singular {} extra {} dependent {dependent:?} at {configurations:?}",
        sk.rank, sk.singular, sk.extra_motions
    )
}

/// The same system with one point moved by `(dx, dy[, dz])`: a generic control.
fn moved(s: &System, point: &str, delta: &[BigRational]) -> System {
    let mut b = SystemBuilder::new(format!("{} moved", s.name()), s.dim());
    for e in s.entities() {
        let Geometry::Point { at } = &e.geometry else { panic!("points only") };
        let at = at.as_ref().map(|x| {
            if e.id == point {
                x.iter().zip(delta).map(|(a, d)| a + d).collect()
            } else {
                x.clone()
            }
        });
        b.point(&e.id, at).unwrap();
    }
    for c in s.constraints() {
        let args: Vec<&str> = c.args.iter().map(|a| s.entity(*a).id.as_str()).collect();
        b.constraint(c.kind, &c.id, &args, None).unwrap();
    }
    b.build()
}

/// `(file, generic rank, rank at the drawing, dependent constraint, its spanning group,
/// recognised position and its entities or constraints, point to move for the control)`.
type Case = (
    &'static str,
    usize,
    usize,
    &'static str,
    &'static [&'static str],
    Option<(Position, &'static [&'static str])>,
    &'static str,
);

const CASES: &[Case] = &[
    (
        "collinear_triangle",
        3,
        2,
        "d13",
        &["d12", "d23"],
        Some((Position::Collinear, &["p1", "p2", "p3"])),
        "p2",
    ),
    (
        "collinear_inside_rigid",
        7,
        6,
        "d13",
        &["d12", "d23"],
        Some((Position::Collinear, &["p1", "p2", "p3"])),
        "p2",
    ),
    (
        "k33_on_a_conic",
        9,
        8,
        "a3b3",
        &["a1b1", "a1b2", "a1b3", "a2b1", "a2b2", "a2b3", "a3b1", "a3b2"],
        None,
        "a1",
    ),
    (
        "prism_concurrent",
        9,
        8,
        "a3b3",
        &["a1a2", "a2a3", "a3a1", "b1b2", "b2b3", "b3b1", "a1b1", "a2b2"],
        Some((Position::Concurrent, &["a1b1", "a2b2", "a3b3"])),
        "b1",
    ),
    (
        "flat_tetrahedron",
        6,
        5,
        "cd",
        &["ab", "ac", "ad", "bc", "bd"],
        Some((Position::Coplanar, &["a", "b", "c", "d"])),
        "d",
    ),
];

#[test]
fn classical_singular_positions_are_reported_in_every_backend() {
    for &(file, generic, rank, dependent, group, position, _) in CASES {
        let s = load(&format!("data/singular/{file}.ron"));
        let mut seen = None;
        for backend in BACKENDS {
            let a = run(&s, backend);
            assert!(a.well_constrained(), "{file}: generically well-constrained");
            assert_eq!(a.rank, generic, "{file}");
            assert_eq!(a.witness.source, WitnessSource::Perturbed, "{file}");
            let sk = a.sketch.as_ref().expect("a complete sketch");
            assert!(sk.singular && sk.satisfied, "{file}");
            assert_eq!((sk.rank, sk.extra_motions), (rank, 1), "{file}");
            assert_eq!(sk.dependent.len(), 1, "{file}");
            assert_eq!(s.constraint(sk.dependent[0].constraint).id, dependent, "{file}");
            assert_eq!(ids(&s, &sk.dependent[0].spanning_group), group, "{file}");
            match position {
                Some((p, names)) => {
                    let found = sk
                        .configurations
                        .iter()
                        .find(|c| c.position == p)
                        .unwrap_or_else(|| panic!("{file}: {:?}", sk.configurations));
                    let got: Vec<String> = if found.constraints.is_empty() {
                        found.entities.iter().map(|e| s.entity(*e).id.clone()).collect()
                    } else {
                        ids(&s, &found.constraints)
                    };
                    assert_eq!(got, names, "{file}");
                }
                None => assert!(sk.configurations.is_empty(), "{file}: {:?}", sk.configurations),
            }
            // Every backend says the same of the drawing.
            let now = summary(&s, sk);
            assert_eq!(seen.get_or_insert_with(|| now.clone()), &now, "{file}: {backend:?}");
            if backend == Backend::Exact {
                assert!(sk.proof.is_some(), "{file}: the rank at the drawing is proven");
            }
        }
    }
}

#[test]
fn generic_controls_are_not_singular() {
    for &(file, generic, _, _, _, _, point) in CASES {
        let s = load(&format!("data/singular/{file}.ron"));
        let n = s.dim().coords();
        let delta: Vec<BigRational> =
            (0..n).map(|i| BigRational::new((i as i64 + 1).into(), 3.into())).collect();
        let control = moved(&s, point, &delta);
        for backend in BACKENDS {
            let a = run(&control, backend);
            assert_eq!(a.witness.source, WitnessSource::Sketch, "{file} moved: generic");
            let sk = a.sketch.as_ref().expect("a complete sketch");
            assert!(
                !sk.singular && sk.dependent.is_empty(),
                "{file} moved: {}",
                summary(&control, sk)
            );
            assert_eq!((sk.rank, sk.extra_motions), (generic, 0), "{file} moved");
        }
    }
}

#[test]
fn an_edited_dimension_is_reported_with_its_difference() {
    let text = r#"System(dim: 2,
        entities: [Point(id: "a", at: [0, 0]), Point(id: "b", at: [40, 0]),
                   Point(id: "c", at: [40, 20]), Point(id: "d", at: [0, 20])],
        constraints: [Distance(id: "bottom", a: "a", b: "b", value: 40),
                      Distance(id: "top", a: "d", b: "c", value: 48),
                      Distance(id: "left", a: "a", b: "d", value: 20.00004),
                      Distance(id: "diag", a: "a", b: "c", value: 44.7214)])"#;
    let s = System::from_ron_str(text, None).unwrap();
    let sk = run(&s, Backend::Exact).sketch.unwrap();
    assert!(!sk.satisfied);
    let r = sk.largest_residual.unwrap();
    assert_eq!(s.constraint(r.constraint).id, "top");
    assert!((r.value - (40.0 - 48.0)).abs() < 1e-12, "{}", r.value);
    // 20.00004 is written to 5 decimals: 0.00004 off is outside its precision (0.000005), but
    // 44.7214 (4 decimals) is within its precision of √2000 = 44.721359…: with the top and the
    // left put right, the drawing satisfies everything.
    let fine =
        System::from_ron_str(&text.replace("48", "40").replace("20.00004", "20"), None).unwrap();
    let sk = run(&fine, Backend::Exact).sketch.unwrap();
    assert!(sk.satisfied, "{:?}", sk.largest_residual);
    assert!(sk.largest_residual.is_none());
}

/// In a random Laman sketch, one triangle drawn flat: exactly one extra motion, and the
/// dependency contains the triangle's three points, named collinear.
#[test]
fn a_flat_triangle_in_a_random_laman_sketch_adds_one_motion() {
    for seed in 0..12u64 {
        let mut rng = SplitMix64::new(seed);
        let n = 6 + (seed as usize % 7);
        let mut edges = gcs_model::generate::laman_edges(n, 0.5, &mut rng);
        // A type I vertex on the first edge: a triangle (a, b, v).
        let (a, b) = edges[0];
        let v = n;
        edges.extend([(a, v), (b, v)]);
        let mut coords = gcs_model::generate::random_coords(n, gcs_model::Dim::Two, 100, &mut rng);
        // v on the line through a and b, between them.
        let (pa, pb) = (coords[a].clone(), coords[b].clone());
        coords.push(vec![(pa[0] + pb[0]) * 2, (pa[1] + pb[1]) * 2]);
        let s = {
            let mut coords: Vec<Vec<BigRational>> =
                coords.iter().map(|c| c.iter().map(|x| int(*x)).collect()).collect();
            // (2a + 2b) / 4 is the midpoint: divide the last point by 4.
            coords[v] = coords[v].iter().map(|x| x / int(4)).collect();
            gcs_model::generate::framework_at("flat", gcs_model::Dim::Two, &coords, &edges)
        };
        let a_ = run(&s, Backend::Exact);
        assert!(a_.well_constrained(), "seed {seed}");
        let sk = a_.sketch.unwrap();
        assert_eq!(sk.extra_motions, 1, "seed {seed}: {}", summary(&s, &sk));
        let names = [a, b, v].map(|i| format!("p{i}"));
        let flat = sk
            .configurations
            .iter()
            .find(|c| c.position == Position::Collinear)
            .unwrap_or_else(|| panic!("seed {seed}: {}", summary(&s, &sk)));
        for name in &names {
            assert!(
                flat.entities.iter().any(|e| &s.entity(*e).id == name),
                "seed {seed}: {name} in {}",
                summary(&s, &sk)
            );
        }
        let dependency: Vec<String> = sk
            .dependent
            .iter()
            .flat_map(|d| std::iter::once(d.constraint).chain(d.spanning_group.iter().copied()))
            .flat_map(|c| s.constraint(c).signature.entities())
            .map(|e| s.entity(e).id.clone())
            .collect();
        for name in &names {
            assert!(dependency.contains(name), "seed {seed}: {name} in {dependency:?}");
        }
    }
}
