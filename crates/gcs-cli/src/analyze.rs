//! `gcs analyze`: the witness analysis of each model, printed as text for people or as JSON
//! Lines (the reports themselves are `gcs-report`'s).

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use gcs_analysis::{AnalysisError, Backend};
use gcs_report::ReportError;
use gcs_report::run::{AnalyzeOptions, analyze};

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
    /// Let the pebble game decide 2D bar frameworks (not `--no-pebble-game`).
    pub(crate) pebble_game: bool,
    /// Write the W-decompositions as Graphviz DOT to this file (`--dot`).
    pub(crate) dot: Option<PathBuf>,
    /// Draw each model as SVG into this directory (`--svg`).
    pub(crate) svg: Option<PathBuf>,
    /// Files analysed at once (`--jobs`).
    pub(crate) jobs: usize,
    /// Only this shard of the inputs (`--shard i/n`).
    pub(crate) shard: Option<(usize, usize)>,
    /// Each model in a process of its own, stopped after a time limit (`--timeout`).
    pub(crate) timeout: Option<Timeout>,
    /// Only the model at this index of each file (`--only-model`, what a model's own process
    /// runs).
    pub(crate) only_model: Option<usize>,
}

/// `--timeout`: the limit per model, and the arguments of `gcs` that analyse one model the way
/// this command would (the model's index and path are added).
pub(crate) struct Timeout {
    pub(crate) limit: std::time::Duration,
    pub(crate) child_args: Vec<String>,
}

/// What to tell a user whose exact analysis found only an approximate witness.
fn hint(e: &ReportError) -> &'static str {
    match e {
        ReportError::Analysis(
            AnalysisError::ApproximateWitness(_) | AnalysisError::NoModularWitness(_),
        ) => ": rerun with --backend float to analyse it there",
        _ => "",
    }
}

/// What one model gave: its report (text or JSON), and its W-decompositions as DOT; or the
/// message of why it failed.
type Outcome = Result<(String, String), String>;

/// The analysis of one model, its report rendered.
fn one(file: &str, model: Result<batch::Model, String>, settings: &Settings) -> Outcome {
    let model = model?;
    // A CAD file holds several sketches: the message names the one that failed.
    let at = model.at(file);
    let batch::Model { system, import } = model;
    let options = AnalyzeOptions {
        backend: settings.backend,
        seed: settings.seed,
        structural: settings.structural,
        decompose: settings.decompose,
        pebble_game: settings.pebble_game,
    };
    let analyzed = analyze(&system, &options).map_err(|e| format!("{at}: {e}{}", hint(&e)))?;
    let dot = match (&settings.dot, &analyzed.analysis.decomposition) {
        (Some(_), Some(trees)) => gcs_report::clusters::dot(&system, trees),
        _ => String::new(),
    };
    if let Some(dir) = &settings.svg {
        let report = analyzed.report(&system, file, import.clone());
        // Named by the file (its path as given, without the extension), and for a CAD file's
        // sketch by the sketch within it: unique in a batch, whatever the models are called.
        let stem =
            file.rsplit_once('.').filter(|(_, ext)| !ext.contains('/')).map_or(file, |s| s.0);
        let name = match &import {
            Some(_) => {
                let sketch = system.name().rsplit_once('/').map_or(system.name(), |s| s.1);
                format!("{stem}/{sketch}")
            }
            None => stem.to_owned(),
        };
        let path = dir.join(format!("{}.svg", batch::file_name(&name)));
        let written = path.parent().map_or(Ok(()), std::fs::create_dir_all).and_then(|()| {
            std::fs::write(&path, gcs_report::picture::analysis_svg(&system, &report))
        });
        written.map_err(|e| format!("{at}: cannot write {}: {e}", batch::display(&path)))?;
        // With --decompose: the W-decomposition as a tree beside it.
        if let Some(trees) = &analyzed.analysis.decomposition {
            let path = dir.join(format!("{}.plan.svg", batch::file_name(&name)));
            std::fs::write(&path, gcs_report::picture::plan_svg(&system, trees))
                .map_err(|e| format!("{at}: cannot write {}: {e}", batch::display(&path)))?;
        }
    }
    let report = match settings.format {
        Format::Json => analyzed.report(&system, file, import).to_json(),
        Format::Text => analyzed.text(&system, file, import.as_ref()),
    };
    Ok((report, dot))
}

/// Model `index` of `path` analysed by `gcs` in a process of its own, stopped when
/// `timeout.limit` is up: its report as the process printed it, or the message of why it failed
/// (its own, the limit, or how the process ended). `at` names the model in messages.
fn in_own_process(
    at: &str,
    path: &std::path::Path,
    index: usize,
    timeout: &Timeout,
    format: Format,
) -> Outcome {
    let exe = std::env::current_exe().map_err(|e| format!("{at}: cannot run gcs again: {e}"))?;
    let mut args = timeout.child_args.clone();
    args.extend(["--jobs".to_owned(), "1".to_owned(), "--only-model".to_owned()]);
    args.push(index.to_string());
    let ran = batch::run_with_limit(&exe, &args, path, timeout.limit)
        .map_err(|e| format!("{at}: cannot run gcs again: {e}"))?;
    let Some((status, stdout, stderr)) = ran else {
        let limit = timeout.limit.as_secs_f64();
        return Err(format!("{at}: stopped after {limit} s (the limit set by --timeout)"));
    };
    let stdout = stdout.trim_end().to_owned();
    match status.code() {
        Some(0) => Ok((stdout, String::new())),
        // The model failed: its message, as the process reported it (on standard output in
        // JSON, on standard error in text).
        Some(1) => Err(match format {
            Format::Json => serde_json::from_str::<serde_json::Value>(&stdout)
                .ok()
                .and_then(|v| v.get("error").and_then(|e| e.as_str()).map(str::to_owned))
                .unwrap_or(stdout),
            Format::Text => {
                stderr.trim_end().strip_prefix("error: ").unwrap_or(stderr.trim_end()).to_owned()
            }
        }),
        _ => Err(format!("{at}: the analysis ended abnormally ({status}): {}", stderr.trim_end())),
    }
}

pub(crate) fn run(paths: &[PathBuf], settings: &Settings) -> ExitCode {
    let started = std::time::Instant::now();
    let inputs = batch::shard(batch::expand(paths), settings.shard);
    let mut out = Out::new();
    let (mut models, mut failed) = (0usize, 0usize);
    let mut dot = String::new();
    let work = |input: &batch::Input| -> Vec<(String, Outcome)> {
        batch::input_models(input)
            .into_iter()
            .enumerate()
            .filter(|(k, _)| settings.only_model.is_none_or(|only| only == *k))
            .map(|(k, (file, model))| {
                let outcome = match (&settings.timeout, input, model) {
                    (Some(timeout), batch::Input::File(path), Ok(model)) => {
                        in_own_process(&model.at(&file), path, k, timeout, settings.format)
                    }
                    (_, _, model) => one(&file, model, settings),
                };
                (file, outcome)
            })
            .collect()
    };
    let panicked = |input: &batch::Input, why: String| vec![batch::internal_error(input, &why)];
    // A progress bar on a terminal only (indicatif draws nothing when standard error is not
    // one: pipes, files, CI).
    let progress = indicatif::ProgressBar::new(inputs.len() as u64);
    let terminal = std::io::stderr().is_terminal() && inputs.len() > 1;
    if !terminal {
        progress.set_draw_target(indicatif::ProgressDrawTarget::hidden());
    }
    batch::ordered(&inputs, settings.jobs, work, panicked, |results| {
        progress.inc(1);
        // (The bar is cleared while reports are written, in case standard output is the same
        // terminal.)
        progress.suspend(|| {
            for (file, outcome) in results {
                models += 1;
                match outcome {
                    Ok((report, d)) => {
                        dot.push_str(&d);
                        out.line(&report);
                    }
                    Err(message) => {
                        failed += 1;
                        out.failure(settings.format, &file, &message);
                    }
                }
            }
            out.flush();
        });
    });
    progress.finish_and_clear();
    let analysed = models - failed;
    out.flush();
    if let Some(path) = &settings.dot
        && let Err(e) = std::fs::write(path, dot)
    {
        eprintln!("error: cannot write {}: {e}", batch::display(path));
        failed += 1;
    }
    if terminal {
        eprintln!(
            "gcs: {} files, {models} models: {} analysed, {} failed, in {:.1} s",
            inputs.len(),
            analysed,
            models - analysed,
            started.elapsed().as_secs_f64()
        );
    }
    batch::status(failed)
}
