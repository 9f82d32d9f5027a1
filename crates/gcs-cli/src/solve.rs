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
) -> ExitCode {
    let mut out = Out::new();
    let mut failed = 0;
    for (file, model) in batch::models(paths) {
        let result = model.and_then(|model| {
            let at = model.at(&file);
            let batch::Model { system, import } = model;
            let (report, solution) = gcs_report::run::solve(&system, &file, import, options)
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
            Ok(report)
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
