//! When no rational witness can be constructed, a numerical projection gives an approximate
//! one: the exact backends refuse it with a clear message (a rank decided exactly at an
//! approximate point would be a silent wrong answer), the float backend analyses there and the
//! report says the witness is approximate.

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
fn exact_backends_refuse_an_approximate_witness() {
    let s = System::from_ron_str(TWO_CIRCLES, Some("two_circles.ron")).unwrap();
    for backend in [Backend::Exact, Backend::Rational, Backend::ModP] {
        let err =
            analyze(&s, &AnalysisOptions { backend, ..AnalysisOptions::default() }).unwrap_err();
        assert!(matches!(err, AnalysisError::ApproximateWitness(_)), "{backend:?}: {err}");
        let msg = err.to_string();
        assert!(msg.contains("entity \"p\" cannot be placed rationally"), "{msg}");
        assert!(msg.contains("only the float backend"), "{msg}");
        // A library message names no command-line flag: that is the CLI's to add.
        assert!(!msg.contains("--"), "{msg}");
    }
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
