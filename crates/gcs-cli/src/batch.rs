//! Batch processing: expanding paths, reading files, reporting failures without stopping.

use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// One input: a model file, or a path that could not be expanded.
pub(crate) enum Input {
    /// A file to process.
    File(PathBuf),
    /// A path that does not exist or cannot be listed, with the reason.
    Missing(PathBuf, String),
}

/// The files a directory stands for: gcs models (`.ron`) and CAD files (`.slvs`, `.fcstd` in any
/// case, `.json`).
fn is_model_file(path: &Path) -> bool {
    path.extension().is_some_and(|e| {
        let e = e.to_string_lossy().to_ascii_lowercase();
        matches!(e.as_str(), "ron" | "slvs" | "fcstd" | "json")
    })
}

/// Expands the paths given on the command line: files stay as they are, directories become
/// every model or CAD file below them (recursively; see [`is_model_file`]), sorted by path.
pub(crate) fn expand(paths: &[PathBuf]) -> Vec<Input> {
    let mut out = Vec::new();
    for p in paths {
        match std::fs::metadata(p) {
            Ok(m) if m.is_dir() => {
                let mut files = Vec::new();
                if let Err(e) = walk(p, &mut files) {
                    out.push(Input::Missing(p.clone(), e.to_string()));
                    continue;
                }
                files.sort();
                out.extend(files.into_iter().map(Input::File));
            }
            Ok(_) => out.push(Input::File(p.clone())),
            Err(e) => out.push(Input::Missing(p.clone(), e.to_string())),
        }
    }
    out
}

fn walk(dir: &Path, files: &mut Vec<PathBuf>) -> io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            walk(&path, files)?;
        } else if is_model_file(&path) {
            files.push(path);
        }
    }
    Ok(())
}

/// One model read: the validated system and, for a sketch of a CAD file, its import section.
pub(crate) type Model = (gcs_model::System, Option<gcs_report::ImportReport>);

/// Every model the paths stand for, in order: its file's display name, and the model or the
/// message of why it could not be read (naming the file). A CAD file stands for each of its
/// sketches, in the file's order.
pub(crate) fn models(paths: &[PathBuf]) -> impl Iterator<Item = (String, Result<Model, String>)> {
    expand(paths).into_iter().flat_map(|input| match input {
        Input::Missing(p, why) => {
            let file = display(&p);
            let msg = format!("{file}: {why}");
            vec![(file, Err(msg))]
        }
        Input::File(p) => {
            let file = display(&p);
            read_models(&p, &file).into_iter().map(|r| (file.clone(), r)).collect()
        }
    })
}

/// The models of one file: a RON model, or the sketches of a CAD file (recognised by
/// extension, then by content).
fn read_models(path: &Path, file: &str) -> Vec<Result<Model, String>> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => return vec![Err(format!("{file}: cannot read: {e}"))],
    };
    let is_ron = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ron"));
    if !is_ron && gcs_import::Format::detect(file, &bytes).is_some() {
        return match gcs_import::import(file, &bytes) {
            Ok(sketches) if sketches.is_empty() => vec![Err(format!("{file}: no sketch in it"))],
            Ok(sketches) => sketches
                .iter()
                .map(|l| Ok((l.system.clone(), Some(gcs_report::ImportReport::new(l)))))
                .collect(),
            Err(e) => vec![Err(e.to_string())],
        };
    }
    let result = String::from_utf8(bytes)
        .map_err(|_| format!("{file}: not UTF-8 text (nor a CAD file this build reads)"))
        .and_then(|text| {
            gcs_model::System::from_ron_str(&text, Some(file)).map_err(|e| e.to_string())
        });
    vec![result.map(|s| (s, None))]
}

/// The display form of a path in reports: as given, with `/` separators.
pub(crate) fn display(path: &Path) -> String {
    path.display().to_string().replace('\\', "/")
}

/// Standard output, with a broken pipe (`gcs … | head`) ending the program quietly.
pub(crate) struct Out {
    lock: io::StdoutLock<'static>,
}

impl Out {
    pub(crate) fn new() -> Out {
        Out { lock: io::stdout().lock() }
    }

    pub(crate) fn line(&mut self, text: &str) {
        if let Err(e) = writeln!(self.lock, "{text}") {
            if e.kind() == io::ErrorKind::BrokenPipe {
                std::process::exit(0);
            }
            eprintln!("gcs: cannot write to standard output: {e}");
            std::process::exit(1);
        }
    }

    pub(crate) fn flush(&mut self) {
        let _ = self.lock.flush();
    }

    /// Reports a file that failed: its JSON line, or `error: …` on standard error.
    pub(crate) fn failure(&mut self, format: crate::Format, file: &str, message: &str) {
        match format {
            crate::Format::Json => self.line(&gcs_report::failure_json(file, message)),
            crate::Format::Text => {
                self.flush();
                eprintln!("error: {message}");
            }
        }
    }
}

/// Exit status of a batch: 0 when every file went through, 1 otherwise.
pub(crate) fn status(failed: usize) -> ExitCode {
    if failed == 0 { ExitCode::SUCCESS } else { ExitCode::from(1) }
}
