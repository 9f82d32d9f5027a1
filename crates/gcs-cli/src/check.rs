//! `gcs check`: validate models and print their counts.

use std::path::PathBuf;
use std::process::ExitCode;

use gcs_model::System;
use serde::Serialize;

use crate::Format;
use crate::batch::{self, Input, Out};

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
    for input in batch::expand(paths) {
        let (file, result) = match input {
            Input::Missing(p, why) => {
                let file = batch::display(&p);
                let msg = format!("{file}: {why}");
                (file, Err(msg))
            }
            Input::File(p) => {
                let file = batch::display(&p);
                let result = batch::read(&p).and_then(|text| {
                    System::from_ron_str(&text, Some(&file)).map_err(|e| e.to_string())
                });
                (file, result)
            }
        };
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
                match format {
                    Format::Json => out.line(&batch::json_error(&file, &message)),
                    Format::Text => {
                        out.flush();
                        eprintln!("error: {message}");
                    }
                }
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
