//! `gcs analyze`: the witness analysis of each model, printed as text for people or as JSON
//! Lines (the reports themselves are `gcs-report`'s).

use std::path::PathBuf;
use std::process::ExitCode;

use gcs_analysis::{AnalysisOptions, Backend, analyze};
use gcs_jacobian::WitnessOptions;
use gcs_report::{Report, Structural};
use gcs_solve::{Solution, SolveOptions};

use crate::Format;
use crate::batch::{self, Out};

/// Options of the analysis, from the command line.
pub(crate) struct Settings {
    pub(crate) backend: Backend,
    pub(crate) seed: u64,
    pub(crate) format: Format,
    /// Add the structural section (`--structural`).
    pub(crate) structural: bool,
    /// Add the W-decomposition (`--decompose`).
    pub(crate) decompose: bool,
    /// Write the W-decompositions as Graphviz DOT to this file (`--dot`).
    pub(crate) dot: Option<PathBuf>,
}

/// What to tell a user whose exact analysis found only an approximate witness.
fn hint(e: &gcs_analysis::AnalysisError) -> &'static str {
    match e {
        gcs_analysis::AnalysisError::ApproximateWitness(_)
        | gcs_analysis::AnalysisError::NoModularWitness(_) => {
            ": rerun with --backend float to analyse it there"
        }
        _ => "",
    }
}

/// A text report with the import section of a CAD sketch after its first line.
pub(crate) fn with_import_text(text: &str, import: Option<&gcs_report::ImportReport>) -> String {
    let Some(import) = import else { return text.to_owned() };
    match text.split_once('\n') {
        Some((first, rest)) => format!("{first}\n{}{rest}", import.text()),
        None => format!("{text}\n{}", import.text().trim_end()),
    }
}

/// The model solved at its values when it has redundant constraints, to tell those that agree
/// from those that conflict (`None` without redundancy, without a complete drawing to start
/// from, or when it is too large for the solver: the report then says only "redundant").
fn values(system: &gcs_model::System, analysis: &gcs_analysis::Analysis) -> Option<Solution> {
    if analysis.sketch.is_none() || analysis.redundant.iter().all(|r| r.rows < r.doc) {
        return None;
    }
    let options = SolveOptions { max_unknowns: ANALYZE_SOLVE_LIMIT, ..SolveOptions::default() };
    gcs_solve::solve(system, analysis, &options).ok()
}

/// The most unknowns `gcs analyze` solves for to check redundant constraints against the
/// values (the solver's steps are dense: `gcs solve` takes more).
const ANALYZE_SOLVE_LIMIT: usize = 1_000;

pub(crate) fn run(paths: &[PathBuf], settings: &Settings) -> ExitCode {
    let mut out = Out::new();
    let mut failed = 0;
    let options = AnalysisOptions {
        backend: settings.backend,
        witness: WitnessOptions { seed: settings.seed, ..WitnessOptions::default() },
        decompose: settings.decompose,
        ..AnalysisOptions::default()
    };
    let mut dot = String::new();
    for (file, model) in batch::models(paths) {
        let result = model.and_then(|(system, import)| {
            // A CAD file holds several sketches: the message names the one that failed.
            let at = match &import {
                Some(_) => format!("{file}: {}", system.name()),
                None => file.clone(),
            };
            let analysis =
                analyze(&system, &options).map_err(|e| format!("{at}: {e}{}", hint(&e)))?;
            let structural = if settings.structural {
                Some(Structural::new(&system, &analysis).map_err(|e| format!("{at}: {e}"))?)
            } else {
                None
            };
            let solution = values(&system, &analysis);
            Ok((system, import, analysis, structural, solution))
        });
        match result {
            Ok((system, import, analysis, s, solution)) => {
                if settings.dot.is_some()
                    && let Some(trees) = &analysis.decomposition
                {
                    dot.push_str(&gcs_report::clusters::dot(&system, trees));
                }
                match settings.format {
                    Format::Json => {
                        let mut report = Report::new(&system, &file, &analysis, s.as_ref());
                        if let Some(sol) = &solution {
                            report = report.with_solution(&system, sol);
                        }
                        out.line(&report.with_import(import).to_json())
                    }
                    Format::Text => {
                        let text = gcs_report::text_with_solution(
                            &system,
                            &file,
                            &analysis,
                            s.as_ref(),
                            solution.as_ref(),
                        );
                        out.line(&with_import_text(&text, import.as_ref()))
                    }
                }
            }
            Err(message) => {
                failed += 1;
                out.failure(settings.format, &file, &message);
            }
        }
    }
    out.flush();
    if let Some(path) = &settings.dot
        && let Err(e) = std::fs::write(path, dot)
    {
        eprintln!("error: cannot write {}: {e}", batch::display(path));
        failed += 1;
    }
    batch::status(failed)
}
