//! `gcs solve`: each model solved at its values, from its drawing; the redundant constraints
//! told consistent or conflicting; the solved model optionally written as RON.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use gcs_analysis::{AnalysisError, AnalysisOptions, Backend, analyze};
use gcs_report::SolveReport;
use gcs_solve::{SolveOptions, solve, solved_system};

use crate::Format;
use crate::batch::{self, Out};

pub(crate) fn run(paths: &[PathBuf], format: Format, out_dir: Option<&Path>) -> ExitCode {
    let mut out = Out::new();
    let mut failed = 0;
    let options = SolveOptions::default();
    for (file, model) in batch::models(paths) {
        let result = model.and_then(|(system, import)| {
            let at = match &import {
                Some(_) => format!("{file}: {}", system.name()),
                None => file.clone(),
            };
            // The redundant constraints come from the exact analysis; where it has no witness
            // (a CAD drawing that no construction reproduces), from the float one.
            let exact = analyze(&system, &AnalysisOptions::default());
            let (analysis, backend) = match exact {
                Ok(a) => (a, "exact"),
                Err(AnalysisError::ApproximateWitness(_) | AnalysisError::NoModularWitness(_)) => {
                    let float = AnalysisOptions {
                        backend: Backend::Float { tolerance: 1e-9 },
                        ..AnalysisOptions::default()
                    };
                    (analyze(&system, &float).map_err(|e| format!("{at}: {e}"))?, "float")
                }
                Err(e) => return Err(format!("{at}: {e}")),
            };
            let solution = solve(&system, &analysis, &options).map_err(|e| format!("{at}: {e}"))?;
            if let Some(dir) = out_dir {
                let path = dir.join(format!("{}.ron", system.name()));
                let solved = solved_system(&system, &solution);
                if let Some(parent) = path.parent() {
                    std::fs::create_dir_all(parent)
                        .map_err(|e| format!("cannot create {}: {e}", batch::display(parent)))?;
                }
                std::fs::write(&path, solved.to_ron())
                    .map_err(|e| format!("cannot write {}: {e}", batch::display(&path)))?;
            }
            let report = SolveReport::new(&system, &file, &solution, options.tolerance, backend);
            Ok(report.with_import(import))
        });
        match result {
            Ok(report) => match format {
                Format::Json => out.line(&report.to_json()),
                Format::Text => out.line(&report.text()),
            },
            Err(message) => {
                failed += 1;
                out.failure(format, &file, &message);
            }
        }
    }
    out.flush();
    batch::status(failed)
}
