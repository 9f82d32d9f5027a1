//! One harness, every backend: each model of `data/` (at its sketch, and at a generated
//! witness once the sketch positions that no `Fix` pins are removed) and a few generated
//! models are analysed in every arithmetic the build has — exact, rational, modp, float with
//! tolerance 1e-9, and rug when gcs-decompose has its `rug` feature (`cargo test -p gcs-suite
//! --features gcs-decompose/rug`) — and every backend must reach the verdict of the exact one:
//! rank, DOF, trivial motions, redundant constraints with their spanning groups, clusters.
//! The float backend's faer QR cross-check must equal its own rank.
//!
//! Every disagreement, error and panic is collected and reported at once.

mod common;

use common::{Verdict, backends, try_run};
use gcs_analysis::Backend;
use gcs_model::generate::{
    framework, laman, laman_edges, random_coords, rectangles, triangulated_sphere,
};
use gcs_model::rng::SplitMix64;
use gcs_model::{Dim, System};
use gcs_suite::{data_files, load, strip_unfixed_sketch};

/// The generated cases: CAD rectangles, a Laman framework, a triangulated sphere, and a
/// Laman framework with two extra bars (redundancy with spanning groups in a generated
/// model).
fn generated() -> Vec<System> {
    let mut rng = SplitMix64::new(11);
    let mut edges = laman_edges(9, 0.5, &mut rng);
    let coords = random_coords(9, Dim::Two, 1000, &mut rng);
    for extra in [(0, 8), (3, 7)] {
        if !edges.contains(&extra) && !edges.contains(&(extra.1, extra.0)) {
            edges.push(extra);
        }
    }
    vec![
        rectangles(4),
        laman(15, 7),
        triangulated_sphere(12, 7),
        framework("laman-9-extra", Dim::Two, &coords, &edges),
    ]
}

/// Runs `system` through every backend and records what differs from the exact backend.
fn check_all_backends(label: &str, system: &System, failures: &mut Vec<String>) {
    let exact = match try_run(system, Backend::Exact, 1) {
        Ok(a) => a,
        Err(e) => {
            failures.push(format!("{label}: {e}"));
            return;
        }
    };
    assert!(exact.proof.is_some(), "{label}: the exact backend says how it proved its rank");
    let reference = Verdict::of(system, &exact);
    for backend in backends() {
        let a = match try_run(system, backend, 1) {
            Ok(a) => a,
            Err(e) => {
                failures.push(format!("{label}: {e}"));
                continue;
            }
        };
        assert_eq!(a.backend, backend);
        assert_eq!(a.witness, exact.witness, "{label}: the witness does not depend on the backend");
        let v = Verdict::of(system, &a);
        if v != reference {
            failures.push(format!(
                "{label} with {}:\n    got      {v:?}\n    expected {reference:?}",
                backend.name()
            ));
        }
        match backend {
            Backend::Float { .. } => {
                if a.float_qr_rank != Some(a.rank) {
                    failures.push(format!(
                        "{label}: float rank {} but faer QR rank {:?}",
                        a.rank, a.float_qr_rank
                    ));
                }
            }
            _ => assert_eq!(a.float_qr_rank, None, "{label}: QR only for float"),
        }
    }
}

fn report(failures: &[String]) {
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn every_model_in_data_agrees_across_backends_at_its_sketch() {
    let mut failures = Vec::new();
    for file in data_files() {
        check_all_backends(&file, &load(&file), &mut failures);
    }
    report(&failures);
}

#[test]
fn every_model_in_data_agrees_across_backends_at_a_generated_witness() {
    let mut failures = Vec::new();
    for file in gcs_suite::generated_witness_files() {
        let label = format!("{file} (generated witness)");
        let system = strip_unfixed_sketch(&load(&file));
        check_all_backends(&label, &system, &mut failures);
    }
    report(&failures);
}

#[test]
fn generated_models_agree_across_backends() {
    let mut failures = Vec::new();
    for system in generated() {
        check_all_backends(system.name(), &system, &mut failures);
    }
    report(&failures);
}

/// The harness is not vacuous: the generated models exercise what it compares.
#[test]
fn generated_models_cover_redundancy_and_absolute_constraints() {
    let verdicts: Vec<Verdict> =
        generated().iter().map(|s| Verdict::of(s, &common::run(s, Backend::Exact, 1))).collect();
    assert_eq!(verdicts[0].trivial_motions, 0, "fixed rectangles");
    assert!(verdicts[0].well_constrained);
    assert_eq!((verdicts[1].trivial_motions, verdicts[1].dof), (3, 0));
    assert_eq!((verdicts[2].trivial_motions, verdicts[2].dof), (6, 0));
    assert_eq!(verdicts[3].redundant.len(), 2, "two extra bars");
    assert!(verdicts[3].redundant.iter().all(|r| !r.spanning_group.is_empty()));
}

#[test]
fn backends_under_test() {
    let names: Vec<&str> = backends().iter().map(|b| b.name()).collect();
    assert!(names.starts_with(&["exact", "rational", "modp", "float"]), "{names:?}");
    assert_eq!(names.contains(&"rug"), Backend::Rug.available());
    if !Backend::Rug.available() {
        // Without the feature, asking for rug is an error, not a silent fallback.
        let s = load("data/paper/kite.ron");
        assert!(gcs_analysis::analyze(&s, &common::options(Backend::Rug, 1)).is_err());
    }
}
