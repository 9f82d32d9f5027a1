//! `gcs navigate`: the solution navigator of one model, as one self-contained HTML page.

use std::path::Path;
use std::process::ExitCode;

use crate::batch;

pub(crate) fn run(
    input: &Path,
    output: &Path,
    sketch: Option<&str>,
    limit: usize,
    max_paths: usize,
) -> ExitCode {
    let file = batch::display(input);
    let fail = |message: String| {
        eprintln!("error: {message}");
        ExitCode::from(1)
    };
    let bytes = match std::fs::read(input) {
        Ok(b) => b,
        Err(e) => return fail(format!("{file}: cannot read: {e}")),
    };
    let model = gcs_report::run::read_models(&file, &bytes, None)
        .and_then(|models| gcs_report::run::pick(models, &file, sketch));
    let model = match model {
        Ok(m) => m,
        Err(e) => return fail(e.to_string()),
    };
    let page = match gcs_report::navigate::navigate_page(&model.system, &file, limit, max_paths) {
        Ok(p) => p,
        Err(e) => return fail(format!("{file}: {e}")),
    };
    if let Err(e) = std::fs::write(output, page) {
        return fail(format!("cannot write {}: {e}", batch::display(output)));
    }
    ExitCode::SUCCESS
}
