//! Helpers of the workspace-level tests that need the analysis (`gcs-decompose` is a
//! dev-dependency, so they cannot live in `src/lib.rs`).

#![allow(dead_code, unreachable_pub)]

use gcs_analysis::{Analysis, AnalysisOptions, Backend, analyze};
use gcs_jacobian::WitnessOptions;
use gcs_model::System;
use gcs_report::{ArithmeticName, BackendName, RankMethodName, Report, WitnessName};

/// What the analysis decides, with ids instead of indices: the model's report (format §2)
/// without what may depend on the backend, the seed, the witness or the drawing, so that it must
/// be the same whatever they are. Its fields are the report's.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict(Report);

impl Verdict {
    pub fn of(system: &System, a: &Analysis) -> Verdict {
        let mut r = Report::new(system, "", a, None);
        r.model.clear();
        r.backend = BackendName::Exact;
        r.witness = WitnessName::Sketch;
        r.entities = 0;
        r.constraints = 0;
        r.decomposition = None;
        r.decomposition_complete = None;
        r.seed = 0;
        r.tolerance = None;
        r.proof = None;
        r.rank_method = RankMethodName::Witness;
        r.internal_equations = 0;
        r.float_qr_rank = None;
        r.clusters_arithmetic = ArithmeticName::None;
        r.sketch = None;
        // Measured at the drawing, which a generated witness does not have.
        r.measured.clear();
        r.witness_error_bound = None;
        r.uncertain = None;
        // How global rigidity was decided (method, arithmetic, configuration, bound) is the
        // backend's; `globally_rigid` itself stays.
        r.global_rigidity = None;
        r.method = None;
        Verdict(r)
    }
}

impl std::ops::Deref for Verdict {
    type Target = Report;

    fn deref(&self) -> &Report {
        &self.0
    }
}

/// The options for a backend and a seed.
pub fn options(backend: Backend, seed: u64) -> AnalysisOptions {
    AnalysisOptions {
        backend,
        witness: WitnessOptions { seed, ..WitnessOptions::default() },
        ..AnalysisOptions::default()
    }
}

/// Analyses, panicking with the model's name on an error.
pub fn run(system: &System, backend: Backend, seed: u64) -> Analysis {
    analyze(system, &options(backend, seed))
        .unwrap_or_else(|e| panic!("{} ({}, seed {seed}): {e}", system.name(), backend.name()))
}

/// Analyses; an error or a panic (a bug in the code under test) becomes a message naming
/// the model, the backend and the seed, so that a harness can report every failing case.
pub fn try_run(system: &System, backend: Backend, seed: u64) -> Result<Analysis, String> {
    let context = format!("{} ({}, seed {seed})", system.name(), backend.name());
    let options = options(backend, seed);
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| analyze(system, &options))) {
        Ok(Ok(a)) => Ok(a),
        Ok(Err(e)) => Err(format!("{context}: error: {e}")),
        Err(panic) => {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                .unwrap_or_default();
            Err(format!("{context}: PANIC: {message}"))
        }
    }
}

/// Every backend compiled in: exact, rational, modp, float with tolerance 1e-9, and rug when
/// gcs-decompose was built with its `rug` feature (`--features gcs-decompose/rug`).
pub fn backends() -> Vec<Backend> {
    let mut out =
        vec![Backend::Exact, Backend::Rational, Backend::ModP, Backend::Float { tolerance: 1e-9 }];
    if Backend::Rug.available() {
        out.push(Backend::Rug);
    }
    out
}
