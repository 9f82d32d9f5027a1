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

/// Expands the paths given on the command line: files stay as they are, directories become
/// every `*.ron` file below them (recursively), sorted by path.
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
        } else if path.extension().is_some_and(|e| e == "ron") {
            files.push(path);
        }
    }
    Ok(())
}

/// Every model the paths stand for, in order: its display name, and the validated system or
/// the message of why it could not be read (naming the file).
pub(crate) fn models(
    paths: &[PathBuf],
) -> impl Iterator<Item = (String, Result<gcs_model::System, String>)> {
    expand(paths).into_iter().map(|input| match input {
        Input::Missing(p, why) => {
            let file = display(&p);
            let msg = format!("{file}: {why}");
            (file, Err(msg))
        }
        Input::File(p) => {
            let file = display(&p);
            let result = read(&p).and_then(|text| {
                gcs_model::System::from_ron_str(&text, Some(&file)).map_err(|e| e.to_string())
            });
            (file, result)
        }
    })
}

/// The display form of a path in reports: as given, with `/` separators.
pub(crate) fn display(path: &Path) -> String {
    path.display().to_string().replace('\\', "/")
}

/// Reads a file as UTF-8 text, with an error message naming it.
pub(crate) fn read(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("{}: cannot read: {e}", display(path)))
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
