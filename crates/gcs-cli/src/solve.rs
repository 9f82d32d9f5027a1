//! `gcs solve`: each model solved at its values, from its drawing; the redundant constraints
//! told consistent or conflicting; the solved model optionally written as RON.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use gcs_solve::{SolveOptions, solved_system};

use crate::Format;
use crate::batch::{self, Out};

pub(crate) fn run(
    paths: &[PathBuf],
    format: Format,
    out_dir: Option<&Path>,
    options: &SolveOptions,
    jobs: usize,
) -> ExitCode {
    let mut out = Out::new();
    let mut failed = 0;
    let inputs = batch::expand(paths);
    let one = |file: &str, model: Result<batch::Model, String>| -> Result<String, String> {
        let model = model?;
        let at = model.at(file);
        let batch::Model { system, import } = model;
        let (report, solution) = gcs_report::run::solve(&system, file, import, options)
            .map_err(|e| format!("{at}: {e}"))?;
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
        Ok(match format {
            Format::Json => report.to_json(),
            Format::Text => report.text(),
        })
    };
    let work = |input: &batch::Input| -> Vec<(String, Result<String, String>)> {
        batch::input_models(input)
            .into_iter()
            .map(|(file, model)| {
                let result = one(&file, model);
                (file, result)
            })
            .collect()
    };
    let panicked = |input: &batch::Input, why: String| vec![batch::internal_error(input, &why)];
    // Written models are named by model: one at a time, so that a name two files share ends
    // as the later file's, as without --jobs.
    let jobs = if out_dir.is_some() { 1 } else { jobs };
    batch::ordered(&inputs, jobs, work, panicked, |results| {
        for (file, result) in results {
            match result {
                Ok(report) => out.line(&report),
                Err(message) => {
                    failed += 1;
                    out.failure(format, &file, &message);
                }
            }
        }
        out.flush();
    });
    out.flush();
    batch::status(failed)
}
