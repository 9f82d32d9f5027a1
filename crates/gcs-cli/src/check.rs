//! `gcs check`: validate models and print their counts.

use std::path::PathBuf;
use std::process::ExitCode;

use gcs_report::CheckReport;

use crate::Format;
use crate::batch::{self, Out};

pub(crate) fn run(paths: &[PathBuf], format: Format) -> ExitCode {
    let mut out = Out::new();
    let mut failed = 0;
    for (file, result) in batch::models(paths) {
        match result {
            Ok(batch::Model { system, import }) => {
                let report = CheckReport::new(&system, &file);
                match format {
                    Format::Json => out.line(&report.with_import(import).to_json()),
                    Format::Text => out
                        .line(&gcs_report::run::with_import_text(&report.text(), import.as_ref())),
                }
            }
            Err(message) => {
                failed += 1;
                out.failure(format, &file, &message);
            }
        }
    }
    out.flush();
    batch::status(failed)
}
