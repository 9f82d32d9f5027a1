//! When no rational witness can be constructed (the witness paper's tangencies and
//! intersections of circles that need a square root): the prime-field backends (exact, modp)
//! build a modular witness and analyse there, saying so (issue 10.4: they never refuse what
//! float analyses); the float backend analyses at a numerical projection and says the witness
//! is approximate; the rational backends refuse with a clear message (a rank decided exactly at
//! an approximate point would be a silent wrong answer).

use gcs_analysis::{AnalysisError, AnalysisOptions, Backend, analyze};
use gcs_jacobian::WitnessSource;
use gcs_model::System;

/// A point on two fixed circles whose intersection is irrational: (1.5, ±√1.75).
const TWO_CIRCLES: &str = r#"System(dim: 2,
  entities: [Circle(id: "k1", center: [0, 0], radius: 2), Circle(id: "k2", center: [3, 0], radius: 2),
             Point(id: "p", at: [1.5, 1.3229])],
  constraints: [Fix(id: "f1", a: "k1"), Fix(id: "f2", a: "k2"),
                Incident(id: "i1", a: "p", b: "k1"), Incident(id: "i2", a: "p", b: "k2")])"#;

#[test]
fn rational_backends_refuse_an_approximate_witness() {
    let s = System::from_ron_str(TWO_CIRCLES, Some("two_circles.ron")).unwrap();
    let backend = Backend::Rational;
    let err = analyze(&s, &AnalysisOptions { backend, ..AnalysisOptions::default() }).unwrap_err();
    assert!(matches!(err, AnalysisError::ApproximateWitness(_)), "{err}");
    let msg = err.to_string();
    assert!(msg.contains("entity \"p\" cannot be placed rationally"), "{msg}");
    assert!(msg.contains("only the float backend"), "{msg}");
    // A library message names no command-line flag: that is the CLI's to add.
    assert!(!msg.contains("--"), "{msg}");
}

#[test]
fn float_analyses_at_the_projection_and_says_so() {
    let s = System::from_ron_str(TWO_CIRCLES, None).unwrap();
    let o = AnalysisOptions {
        backend: Backend::Float { tolerance: 1e-9 },
        ..AnalysisOptions::default()
    };
    let a = analyze(&s, &o).unwrap();
    assert_eq!(a.witness.source, WitnessSource::Approximate);
    assert!(a.well_constrained());
    assert_eq!((a.rank, a.trivial_motions), (8, 0));
    assert_eq!(a.float_qr_rank, Some(8));
    // The projection put `p` on both circles, at (1.5, ±√1.75), to the float precision.
    let layout = gcs_jacobian::Layout::new(&s);
    let p = s.entity_indices().find(|e| s.entity(*e).id == "p").unwrap();
    let coords: Vec<f64> = a.witness.coords_in().unwrap();
    let at: Vec<f64> = layout.columns(p).map(|c| coords[c]).collect();
    approx::assert_abs_diff_eq!(at[0], 1.5, epsilon = 1e-9);
    approx::assert_abs_diff_eq!(at[1].abs(), 1.75f64.sqrt(), epsilon = 1e-9);
}

/// A point on two fixed circles, and a circle tangent to the three fixed sides of a triangle
/// (its incircle, irrational): the exact and modular backends analyse at a modular witness,
/// with the same verdict as float at its projection, and say how sure they are.
#[test]
fn prime_field_backends_build_a_modular_witness() {
    const INCIRCLE: &str = r#"System(dim: 2,
      entities: [Line(id: "a", at: [[0, 0], [10, 0]]), Line(id: "b", at: [[0, 0], [3, 7]]),
                 Line(id: "c", at: [[10, 0], [3, 7]]), Circle(id: "k", center: [4.1, 2.3], radius: 2.2)],
      constraints: [Fix(id: "fa", a: "a"), Fix(id: "fb", a: "b"), Fix(id: "fc", a: "c"),
                    Tangent(id: "ta", a: "a", b: "k"), Tangent(id: "tb", a: "b", b: "k"),
                    Tangent(id: "tc", a: "c", b: "k")])"#;
    // The point is written to four decimals, on both circles to that precision; the circle
    // is drawn well off the incircle (radius 2.2 against 35/13.76 ≈ 2.54).
    for (text, drawn_on) in [(TWO_CIRCLES, true), (INCIRCLE, false)] {
        let s = System::from_ron_str(text, None).unwrap();
        let float = analyze(
            &s,
            &AnalysisOptions { backend: Backend::Float { tolerance: 1e-9 }, ..Default::default() },
        )
        .unwrap();
        assert_eq!(float.witness.source, WitnessSource::Approximate);
        for backend in [Backend::Exact, Backend::ModP] {
            let decompose = AnalysisOptions { backend, decompose: true, ..Default::default() };
            let a = analyze(&s, &decompose).unwrap_or_else(|e| panic!("{backend:?}: {e}"));
            assert_eq!(a.witness.source, WitnessSource::Modular, "{backend:?}");
            assert!(a.well_constrained());
            assert_eq!((a.rank, a.trivial_motions, a.dof), (float.rank, 0, 0));
            assert_eq!(a.proof, None, "nothing is proven at a modular witness");
            let bound = a.witness_error_bound.expect("a modular witness says how sure it is");
            assert!(bound > 0.0 && bound < 1e-15, "{bound}");
            assert_eq!(a.clusters.len(), 1);
            assert!(a.decomposition.is_some());
            // The drawing itself is still judged, exactly or to its written precision.
            let sketch = a.sketch.as_ref().unwrap();
            assert_eq!(sketch.satisfied, drawn_on, "{backend:?}");
            assert_eq!(sketch.largest_residual.is_some(), !drawn_on, "{backend:?}");
        }
    }
}

/// The drawing satisfies an incidence to the precision its coordinates are written with, and
/// no further: (1.5, 1.3229) is on both circles, (1.5, 1.35) is not (its distance to k1,
/// 0.018, is beyond what moving each coordinate by 0.005 can reach).
#[test]
fn incidence_is_judged_to_the_written_precision() {
    for (at, satisfied) in [("[1.5, 1.3229]", true), ("[1.5, 1.35]", false), ("[1.5, 1.3]", true)] {
        let text = TWO_CIRCLES.replace("[1.5, 1.3229]", at);
        let s = System::from_ron_str(&text, None).unwrap();
        let a = analyze(&s, &AnalysisOptions::default()).unwrap();
        let sketch = a.sketch.as_ref().unwrap();
        assert_eq!(sketch.satisfied, satisfied, "{at}");
        if let Some(r) = &sketch.largest_residual {
            assert_eq!(s.constraint(r.constraint).id, "i1", "{at}");
        }
    }
}

/// A hexagon about a circle as Onshape draws it (SketchGraphs' sample): six segments, each
/// tangent to the circle somewhere, joined end to end, with the midpoint of one side on the
/// circle and a distance between two opposite sides (a distance between lines: they must be
/// parallel). The loop of tangencies closes only if each side's line is placed before its
/// end points (a carrier tangent to the circle), and the distance only if the parallelism it
/// implies is imposed; with both, the exact and modular backends analyse it at a modular
/// witness (its tangent points are irrational), with float's verdict: 5 degrees of freedom,
/// and the side's tangency redundant with its midpoint on the circle (never transversal).
#[test]
fn a_polygon_about_a_circle_closes_its_loop() {
    const HEXAGON: &str = r#"System(dim: 2,
      entities: [Circle(id: "c", center: [0, 0], radius: 6.5),
        Point(id: "a0", at: [6.5, 3.75277675]), Point(id: "b0", at: [6.5, -3.75277675]),
        Segment(id: "s0", from: "a0", to: "b0"),
        Point(id: "a1", at: [6.5, -3.75277675]), Point(id: "b1", at: [0, -7.505553499]),
        Segment(id: "s1", from: "a1", to: "b1"),
        Point(id: "a2", at: [0, -7.505553499]), Point(id: "b2", at: [-6.5, -3.75277675]),
        Segment(id: "s2", from: "a2", to: "b2"),
        Point(id: "a3", at: [-6.5, -3.75277675]), Point(id: "b3", at: [-6.5, 3.75277675]),
        Segment(id: "s3", from: "a3", to: "b3"),
        Point(id: "a4", at: [-6.5, 3.75277675]), Point(id: "b4", at: [0, 7.505553499]),
        Segment(id: "s4", from: "a4", to: "b4"),
        Point(id: "a5", at: [0, 7.505553499]), Point(id: "b5", at: [6.5, 3.75277675]),
        Segment(id: "s5", from: "a5", to: "b5"),
        Point(id: "m", at: [6.5, 0])],
      constraints: [DistanceY(id: "level", a: "c.center", b: "m", value: 0),
        Midpoint(id: "mid", point: "m", segment: "s0"), Incident(id: "on", a: "m", b: "c"),
        Coincident(id: "j0", a: "b0", b: "a1"), Coincident(id: "j1", a: "b1", b: "a2"),
        Coincident(id: "j2", a: "b2", b: "a3"), Coincident(id: "j3", a: "b3", b: "a4"),
        Coincident(id: "j4", a: "b4", b: "a5"), Coincident(id: "j5", a: "b5", b: "a0"),
        Tangent(id: "t0", a: "c", b: "s0"), Tangent(id: "t1", a: "c", b: "s1"),
        Tangent(id: "t2", a: "c", b: "s2"), Tangent(id: "t3", a: "c", b: "s3"),
        Tangent(id: "t4", a: "c", b: "s4"), Tangent(id: "t5", a: "c", b: "s5"),
        Distance(id: "width", a: "s3", b: "s0", value: 13)])"#;
    let s = System::from_ron_str(HEXAGON, None).unwrap();
    let float = analyze(
        &s,
        &AnalysisOptions { backend: Backend::Float { tolerance: 1e-9 }, ..Default::default() },
    )
    .unwrap();
    let ids = |a: &gcs_analysis::Analysis| -> Vec<String> {
        a.redundant.iter().map(|r| s.constraint(r.constraint).id.clone()).collect()
    };
    assert_eq!((float.dof, ids(&float)), (5, vec!["t0".to_string()]));
    for backend in [Backend::Exact, Backend::ModP] {
        let a = analyze(&s, &AnalysisOptions { backend, ..Default::default() })
            .unwrap_or_else(|e| panic!("{backend:?}: {e}"));
        assert_ne!(a.witness.source, WitnessSource::Approximate, "{backend:?}");
        assert_eq!((a.rank, a.dof, ids(&a)), (float.rank, 5, ids(&float)), "{backend:?}");
    }
}

/// An equilateral triangle as Onshape and FreeCAD draw it: three segments with end points of
/// their own, joined by coincidences, two equal lengths and a vertical side. Its third vertex
/// needs √3, irrational and no square modulo 2^61 − 1 either: the modular witness is built
/// modulo a prime where 3 is a square (the turn prime, tried next since the drawing shows a
/// turn by 60°) and says so; the verdict is float's.
#[test]
fn an_equilateral_triangle_takes_the_next_prime() {
    const TRIANGLE: &str = r#"System(dim: 2,
      entities: [Point(id: "a1", at: [16.75, 92.5]), Point(id: "b1", at: [16.75, 94.5]),
        Segment(id: "ab", from: "a1", to: "b1"),
        Point(id: "b2", at: [16.75, 94.5]), Point(id: "c2", at: [15.017949192, 93.5]),
        Segment(id: "bc", from: "b2", to: "c2"),
        Point(id: "c3", at: [15.017949192, 93.5]), Point(id: "a3", at: [16.75, 92.5]),
        Segment(id: "ca", from: "c3", to: "a3")],
      constraints: [Vertical(id: "v", a: "ab"), Coincident(id: "k1", a: "b2", b: "b1"),
        Coincident(id: "k2", a: "c3", b: "c2"), Coincident(id: "k3", a: "a3", b: "a1"),
        EqualLength(id: "e1", a: "ca", b: "ab"), EqualLength(id: "e2", a: "ca", b: "bc"),
        Distance(id: "d", a: "b2", b: "c2", value: 2)])"#;
    let s = System::from_ron_str(TRIANGLE, None).unwrap();
    let (float, modular) = modular_where_3_is_a_square(&s, true);
    for (backend, a) in modular {
        assert!(a.well_constrained(), "{backend:?}");
        assert_eq!((a.rank, a.dof, a.trivial_motions), (float.rank, 0, float.trivial_motions));
        let bound = a.witness_error_bound.expect("a modular witness says how sure it is");
        assert!(bound > 0.0 && bound < 1e-15, "{bound}");
        assert_eq!(a.clusters.len(), 1, "{backend:?}: one rigid body");
        assert!(a.decomposition.is_some());
    }
}

/// An equilateral triangle inscribed in a circle with two vertices on given lines (kunda1's
/// sketch in the FreeCAD sample, its triangle alone): placed one vertex at a time, the last
/// vertex must lie on the circle *and* at the equal distances, which the earlier free choices
/// (the first vertex on its line) decide; it closes only as a loop, solved as a polynomial system
/// modulo the prime (issue 10.4), and only modulo a prime where 3 is a square.
#[test]
fn an_inscribed_triangle_closes_as_a_polynomial_system() {
    const INSCRIBED: &str = r#"System(dim: 2,
      entities: [Point(id: "o", at: [0, 0]), Point(id: "u", at: [17.624787723, 80.607874997]),
        Point(id: "w", at: [-60.99607363, 55.567451403]),
        Segment(id: "d1", from: "o", to: "u"), Segment(id: "d2", from: "o", to: "w"),
        Point(id: "a", at: [-16.404000828, -75.024543212]),
        Point(id: "b", at: [37.435983138, -34.104198023]),
        Point(id: "c", at: [-24.92206731, -7.937576764]),
        Segment(id: "ab", from: "a", to: "b"), Segment(id: "bc", from: "b", to: "c"),
        Segment(id: "ca", from: "c", to: "a"),
        Circle(id: "k", center: [-1.296695, -39.022106], radius: 39.043644484)],
      constraints: [Fix(id: "fo", a: "o"), Fix(id: "fu", a: "u"), Fix(id: "fw", a: "w"),
        EqualLength(id: "e1", a: "ab", b: "bc"), EqualLength(id: "e2", a: "ab", b: "ca"),
        Incident(id: "ia", a: "a", b: "k"), Incident(id: "ib", a: "b", b: "k"),
        Incident(id: "ic", a: "c", b: "k"),
        Incident(id: "la", a: "a", b: "d1"), Incident(id: "lb", a: "b", b: "d2"),
        DistanceX(id: "cx", a: "o", b: "k.center", value: -1.296695),
        DistanceY(id: "cy", a: "o", b: "k.center", value: -39.022106)])"#;
    let s = System::from_ron_str(INSCRIBED, None).unwrap();
    let (float, modular) = modular_where_3_is_a_square(&s, false);
    for (backend, a) in modular {
        assert!(a.well_constrained(), "{backend:?}");
        assert_eq!((a.rank, a.dof), (float.rank, float.dof), "{backend:?}");
    }
}

/// `s` is well-constrained in floating point, and exact and modp analyse it at a modular witness
/// modulo a prime where 3 is a square (the second witness prime, or the turn prime where the
/// drawing shows a turn by 60°, which is tried before it): the float analysis, and each
/// backend's.
fn modular_where_3_is_a_square(
    s: &System,
    decompose: bool,
) -> (gcs_analysis::Analysis, Vec<(Backend, gcs_analysis::Analysis)>) {
    let float = analyze(
        s,
        &AnalysisOptions { backend: Backend::Float { tolerance: 1e-9 }, ..Default::default() },
    )
    .unwrap();
    assert!(float.well_constrained());
    let modular = [Backend::Exact, Backend::ModP]
        .into_iter()
        .map(|backend| {
            let a = analyze(s, &AnalysisOptions { backend, decompose, ..Default::default() })
                .unwrap_or_else(|e| panic!("{backend:?}: {e}"));
            assert_eq!(a.witness.source, WitnessSource::Modular, "{backend:?}");
            let three_is_a_square = [gcs_rank::WITNESS_PRIMES[1], gcs_rank::TURN_PRIME];
            assert!(a.witness.modulus.is_some_and(|p| three_is_a_square.contains(&p)));
            (backend, a)
        })
        .collect();
    (float, modular)
}

/// A regular hexagon drawn inscribed in a circle, as FreeCAD's polygon tool writes it (six
/// vertices on the circle, five equal sides): its loop closes only at 60°, which no random
/// choice hits, and in its polynomial system every folded (zigzag) hexagon is a curve of
/// solutions. Exact and modp take the turns by 60° from the drawing, modulo the turn prime,
/// and agree with float on the rank: one motion left, the hexagon's rotation about its fixed
/// centre, which is a rotation of the whole drawing (a trivial motion: nothing moves relative
/// to anything else), as it is for an inscribed square at rational coordinates. (Float finds
/// it too at its approximate witness, where the projection leaves the fixed centre 1e-13 off
/// the origin: `J·T` is judged against the row's size times the displacement's.)
#[test]
fn an_inscribed_hexagon_takes_its_turns_from_the_drawing() {
    const HEXAGON: &str = gcs_suite::INSCRIBED_HEXAGON;
    // The second vertex's turn was a free choice when it was taken, but the loop holds it.
    hexagon_agrees_with_float(HEXAGON, &[6], true);
    // A point on the circle drawn 30° from a vertex and held by nothing else: its turn is taken
    // too (it is drawn so), but the constraints leave it free, so the witness may be special.
    let with_free_point = HEXAGON
        .replace(
            r#"Point(id: "p1""#,
            r#"Point(id: "q", at: [-25.040423594, 78.620861354]), Point(id: "p1""#,
        )
        .replace(
            r#"Incident(id: "i1""#,
            r#"Incident(id: "iq", a: "q", b: "k"), Incident(id: "i1""#,
        );
    hexagon_agrees_with_float(&with_free_point, &[6, 12], false);
}

/// `text` analysed by float, exact and modp: the prime-field backends build their witness
/// modulo the turn prime with the turns `turns` (and their divisors: a vertex is taken from
/// whichever placed one comes first, 60° or 120° away), say whether its genericity was tested
/// as `tested`, and agree with float on the rank; the rotation about the fixed centre is a
/// trivial motion.
fn hexagon_agrees_with_float(text: &str, turns: &[u32], tested: bool) {
    let s = System::from_ron_str(text, None).unwrap();
    let float = analyze(
        &s,
        &AnalysisOptions { backend: Backend::Float { tolerance: 1e-9 }, ..Default::default() },
    )
    .unwrap();
    for backend in [Backend::Exact, Backend::ModP] {
        let a = analyze(&s, &AnalysisOptions { backend, ..Default::default() })
            .unwrap_or_else(|e| panic!("{backend:?}: {e}"));
        assert_eq!(a.witness.source, WitnessSource::Modular, "{backend:?}");
        assert_eq!(a.witness.modulus, Some(gcs_rank::TURN_PRIME), "{backend:?}");
        let taken = &a.witness.turns;
        assert!(turns.iter().all(|n| taken.contains(n)), "{backend:?}: {taken:?}");
        assert!(taken.iter().all(|n| turns.iter().any(|t| t % n == 0)), "{backend:?}: {taken:?}");
        assert_eq!(a.witness.genericity_tested, tested, "{backend:?}");
        // The probability bound rests on random choices: not given for a turn left free.
        assert_eq!(a.witness_error_bound.is_some(), tested, "{backend:?}");
        assert_eq!((a.rank, a.dof_absolute), (float.rank, float.dof_absolute), "{backend:?}");
        assert_eq!((a.trivial_motions, float.trivial_motions), (1, 1), "{backend:?}");
        assert_eq!(a.dof, float.dof, "{backend:?}");
        assert!(a.redundant.is_empty(), "{backend:?}");
    }
}

/// The projection's result is checked constraint by constraint against the size to the degree
/// of each residual, as the projection measures them: an equality of two point–line distances
/// is a polynomial of degree 6 in lengths, whose rounding at a drawing of a few hundred units
/// exceeds a tolerance meant for degree 2. Here the point where two fixed circles meet
/// (irrational: no exact placement) is drawn 1e-7 off it, within the projection's tolerance at
/// once; the equal distances to two fixed lines hold there (the circles are mirror images in
/// the bisector of the lines) and are redundant.
#[test]
fn the_projection_is_checked_at_each_residuals_degree() {
    const BISECTOR: &str = r#"System(dim: 2,
      entities: [Circle(id: "k1", center: [300, 100], radius: 250), Circle(id: "k2", center: [100, 300], radius: 250),
                 Point(id: "p", at: [345.773797471, 345.773797271]),
                 Line(id: "l1", at: [[-7, 0], [993, 0]]), Line(id: "l2", at: [[0, 13], [0, 1013]])],
      constraints: [Fix(id: "f1", a: "k1"), Fix(id: "f2", a: "k2"), Fix(id: "f3", a: "l1"), Fix(id: "f4", a: "l2"),
                    Incident(id: "i1", a: "p", b: "k1"), Incident(id: "i2", a: "p", b: "k2"),
                    EqualDistance(id: "e", a: "p", b: "l1", c: "p", d: "l2")])"#;
    let s = System::from_ron_str(BISECTOR, None).unwrap();
    let o = AnalysisOptions {
        backend: Backend::Float { tolerance: 1e-9 },
        ..AnalysisOptions::default()
    };
    let a = analyze(&s, &o).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.witness.source, WitnessSource::Approximate);
    assert_eq!((a.dof, a.trivial_motions), (0, 0));
    let redundant: Vec<&str> =
        a.redundant.iter().map(|r| s.constraint(r.constraint).id.as_str()).collect();
    assert_eq!(redundant, ["e"]);
}

/// Fourteen constraints of a SketchGraphs sketch (`00273760…_004/1`, reduced by dropping
/// constraints while the placement still failed): offsets of offsets (parallels and equal
/// gaps), mirror axes and an equal length, which every order of the constructive placement
/// fails to close, over ℚ and modulo the prime. The prime-field backends find their modular
/// witness from the numerical projection's structure (`gcs_jacobian`'s `square`: random free
/// coordinates, the square system solved block by block), and agree with float.
#[test]
fn a_sketch_no_construction_places_gets_a_modular_witness_from_its_projection() {
    let text = include_str!("data/offsets_and_mirrors.ron");
    let s = System::from_ron_str(text, Some("offsets_and_mirrors.ron")).unwrap();
    let float = analyze(
        &s,
        &AnalysisOptions { backend: Backend::Float { tolerance: 1e-9 }, ..Default::default() },
    )
    .unwrap();
    assert_eq!(float.witness.source, WitnessSource::Approximate);
    let redundant = |a: &gcs_analysis::Analysis| -> Vec<String> {
        a.redundant.iter().map(|r| s.constraint(r.constraint).id.clone()).collect()
    };
    // (The default backend: the rational placement fails, then the modular one, then this.)
    let a = analyze(&s, &AnalysisOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.witness.source, WitnessSource::Modular);
    let msg = a.witness.no_exact_witness.as_ref().map(ToString::to_string).unwrap_or_default();
    assert!(msg.contains("cannot be placed rationally"), "{msg}");
    assert_eq!((a.rank, a.dof, a.trivial_motions), (float.rank, float.dof, float.trivial_motions));
    assert_eq!(redundant(&a), redundant(&float));
}
