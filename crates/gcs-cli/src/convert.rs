//! `gcs convert`: CAD files to gcs models in RON.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::batch::{self, Out};

pub(crate) fn run(input: &Path, output: Option<&Path>) -> ExitCode {
    let file = batch::display(input);
    let bytes = match std::fs::read(input) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: {file}: cannot read: {e}");
            return ExitCode::from(1);
        }
    };
    let sketches = match gcs_import::import(&file, &bytes) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    for l in &sketches {
        for s in &l.skipped {
            eprintln!("warning: {}: {} not converted: {}", l.system.name(), s.item, s.reason);
        }
    }
    match (output, sketches.as_slice()) {
        (_, []) => {
            eprintln!("error: {file}: no sketch in it");
            ExitCode::from(1)
        }
        (None, [one]) => {
            let mut out = Out::new();
            out.line(one.system.to_ron().trim_end());
            out.flush();
            ExitCode::SUCCESS
        }
        (None, many) => {
            let names: Vec<&str> = many.iter().map(|l| l.system.name()).collect();
            eprintln!(
                "error: {file} holds {} sketches ({}); give -o DIR to write one file each",
                many.len(),
                names.join(", ")
            );
            ExitCode::from(2)
        }
        // (OUT ending in a separator names a directory, made if it does not exist.)
        (Some(path), [one]) if !path.is_dir() && !names_a_directory(path) => {
            write(path, &one.system.to_ron())
        }
        (Some(dir), many) => {
            let mut status = ExitCode::SUCCESS;
            for l in many {
                let path = sketch_path(dir, l.system.name());
                if let Some(parent) = path.parent()
                    && let Err(e) = std::fs::create_dir_all(parent)
                {
                    eprintln!("error: cannot create {}: {e}", batch::display(parent));
                    return ExitCode::from(1);
                }
                if write(&path, &l.system.to_ron()) != ExitCode::SUCCESS {
                    status = ExitCode::from(1);
                }
            }
            status
        }
    }
}

/// Whether `path` is written as a directory: it ends in a path separator (`out/`).
fn names_a_directory(path: &Path) -> bool {
    let text = path.as_os_str().to_string_lossy();
    text.ends_with('/') || text.ends_with(std::path::MAIN_SEPARATOR)
}

/// `DIR/<model name>.ron`, with each `/`-separated part of the name made a safe file name.
fn sketch_path(dir: &Path, model: &str) -> PathBuf {
    let mut path = dir.to_path_buf();
    let parts: Vec<String> = model
        .split('/')
        .map(|p| {
            let safe: String = p
                .chars()
                .map(|c| if c.is_alphanumeric() || "-_.+ ".contains(c) { c } else { '_' })
                .collect();
            if safe.is_empty() || safe.chars().all(|c| c == '.') { "_".to_owned() } else { safe }
        })
        .collect();
    for (i, part) in parts.iter().enumerate() {
        if i + 1 == parts.len() {
            path.push(format!("{part}.ron"));
        } else {
            path.push(part);
        }
    }
    path
}

fn write(path: &Path, text: &str) -> ExitCode {
    match std::fs::write(path, text) {
        Ok(()) => {
            eprintln!("wrote {}", batch::display(path));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: cannot write {}: {e}", batch::display(path));
            ExitCode::from(1)
        }
    }
}
