//! `gcs check`: validate models and print their counts.

use std::path::PathBuf;
use std::process::ExitCode;

use serde::Serialize;

use crate::Format;
use crate::batch::{self, Out};

#[derive(Serialize)]
struct CheckReport<'a> {
    schema: u32,
    model: &'a str,
    file: &'a str,
    dim: usize,
    entities: usize,
    constraints: usize,
    entity_dof: usize,
    constraint_doc: usize,
    naive_dof: i64,
    displacements: usize,
}

pub(crate) fn run(paths: &[PathBuf], format: Format) -> ExitCode {
    let mut out = Out::new();
    let mut failed = 0;
    for (file, result) in batch::models(paths) {
        match result {
            Ok(system) => {
                let report = CheckReport {
                    schema: 1,
                    model: system.name(),
                    file: &file,
                    dim: system.dim().coords(),
                    entities: system.entities().len(),
                    constraints: system.constraints().len(),
                    entity_dof: system.dof_sum(),
                    constraint_doc: system.doc_sum(),
                    naive_dof: system.naive_dof(),
                    displacements: system.dim().displacements(),
                };
                match format {
                    Format::Json => out.line(&serde_json::to_string(&report).unwrap_or_default()),
                    Format::Text => out.line(&text(&report)),
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

fn text(r: &CheckReport<'_>) -> String {
    format!(
        "{}: {}, {}D, {} entities, {} constraints: DOF {} − DOC {} = {} (naive count; a free rigid body keeps {})",
        r.file,
        r.model,
        r.dim,
        r.entities,
        r.constraints,
        r.entity_dof,
        r.constraint_doc,
        r.naive_dof,
        r.displacements,
    )
}
