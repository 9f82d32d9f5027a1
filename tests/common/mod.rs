//! Helpers of the workspace-level tests that need the analysis (`gcs-decompose` is a
//! dev-dependency, so they cannot live in `src/lib.rs`).

#![allow(dead_code, unreachable_pub)]

use gcs_analysis::{Analysis, AnalysisOptions, Backend, analyze};
use gcs_jacobian::WitnessOptions;
use gcs_model::System;

/// What the analysis decides, with ids instead of indices: what must not depend on the
/// backend nor on the witness.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Verdict {
    pub unknowns: usize,
    pub equations: usize,
    pub rank: usize,
    pub dof_absolute: usize,
    pub trivial_motions: usize,
    pub dof: usize,
    pub rigid: bool,
    pub well_constrained: bool,
    /// `(constraint, rows, doc, spanning group)` in file order.
    pub redundant: Vec<(String, usize, usize, Vec<String>)>,
    /// `(entities, constraints)` of every cluster, in report order.
    pub clusters: Vec<(Vec<String>, Vec<String>)>,
}

impl Verdict {
    pub fn of(system: &System, a: &Analysis) -> Verdict {
        let c = |c: &gcs_model::ConstraintIdx| system.constraint(*c).id.clone();
        let e = |e: &gcs_model::EntityIdx| system.entity(*e).id.clone();
        Verdict {
            unknowns: a.unknowns,
            equations: a.equations,
            rank: a.rank,
            dof_absolute: a.dof_absolute,
            trivial_motions: a.trivial_motions,
            dof: a.dof,
            rigid: a.rigid(),
            well_constrained: a.well_constrained(),
            redundant: a
                .redundant
                .iter()
                .map(|r| {
                    (c(&r.constraint), r.rows, r.doc, r.spanning_group.iter().map(c).collect())
                })
                .collect(),
            clusters: a
                .clusters
                .iter()
                .map(|k| {
                    (k.entities.iter().map(e).collect(), k.constraints.iter().map(c).collect())
                })
                .collect(),
        }
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
