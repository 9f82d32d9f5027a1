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
pub(crate) type Model = gcs_report::run::Model;

/// Every model the paths stand for, in order: its file's display name, and the model or the
/// message of why it could not be read (naming the file). A CAD file stands for each of its
/// sketches, in the file's order.
pub(crate) fn models(paths: &[PathBuf]) -> impl Iterator<Item = (String, Result<Model, String>)> {
    expand(paths).into_iter().flat_map(|input| input_models(&input))
}

/// The models of one file: a RON model, or the sketches of a CAD file (recognised by
/// extension, then by content: [`gcs_report::run::read_models`]).
fn read_models(path: &Path, file: &str) -> Vec<Result<Model, String>> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => return vec![Err(format!("{file}: cannot read: {e}"))],
    };
    match gcs_report::run::read_models(file, &bytes, None) {
        Ok(models) => models.into_iter().map(Ok).collect(),
        Err(e) => vec![Err(e.to_string())],
    }
}

/// A path or name as a relative file name: its `/`-separated parts kept as directories, each
/// reduced to letters, digits, `.`, `-` and `_` (others become `_`), empty, `.` and `..` parts
/// dropped — never a path outside the directory it is joined to.
pub(crate) fn file_name(name: &str) -> String {
    let parts: Vec<String> = name
        .split(['/', '\\'])
        .filter(|p| !p.is_empty() && *p != "." && *p != "..")
        .map(|p| {
            p.chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_') { c } else { '_' }
                })
                .collect()
        })
        .collect();
    if parts.is_empty() { "model".to_owned() } else { parts.join("/") }
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

/// `--shard i/n`: the inputs of shard `i` of `n`, in their order: the `k`-th input in sorted
/// path order belongs to shard `k mod n`, so the shards of one command line are disjoint,
/// cover every input, and do not depend on the machine that runs them.
pub(crate) fn shard(inputs: Vec<Input>, shard: Option<(usize, usize)>) -> Vec<Input> {
    let Some((i, n)) = shard else { return inputs };
    let path = |input: &Input| match input {
        Input::File(p) | Input::Missing(p, _) => display(p),
    };
    let mut order: Vec<usize> = (0..inputs.len()).collect();
    order.sort_by_key(|&k| path(&inputs[k]));
    let mut mine = vec![false; inputs.len()];
    for (rank, k) in order.into_iter().enumerate() {
        mine[k] = rank % n == i;
    }
    inputs.into_iter().zip(mine).filter(|(_, m)| *m).map(|(input, _)| input).collect()
}

/// Parses `i/n` (`0 ≤ i < n`).
pub(crate) fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let parsed = text.split_once('/').and_then(|(i, n)| Some((i.parse().ok()?, n.parse().ok()?)));
    match parsed {
        Some((i, n)) if i < n => Ok((i, n)),
        _ => Err(format!("expected i/n with 0 ≤ i < n (such as 0/4), not {text:?}")),
    }
}

/// The models of one input, as [`models`] yields them.
pub(crate) fn input_models(input: &Input) -> Vec<(String, Result<Model, String>)> {
    match input {
        Input::Missing(p, why) => {
            let file = display(p);
            let msg = format!("{file}: {why}");
            vec![(file, Err(msg))]
        }
        Input::File(p) => {
            let file = display(p);
            read_models(p, &file).into_iter().map(|r| (file.clone(), r)).collect()
        }
    }
}

/// The error line of an input whose processing panicked (a bug): its file and the message.
pub(crate) fn internal_error<T>(input: &Input, why: &str) -> (String, Result<T, String>) {
    let (Input::File(p) | Input::Missing(p, _)) = input;
    let file = display(p);
    let message = format!("{file}: internal error (a bug of gcs, please report it): {why}");
    (file, Err(message))
}

/// Runs `exe args path` with its output captured, and stops it when `limit` is up: `None` then,
/// otherwise its exit status, standard output and standard error.
///
/// # Errors
/// When the process cannot be started.
pub(crate) fn run_with_limit(
    exe: &Path,
    args: &[String],
    path: &Path,
    limit: std::time::Duration,
) -> io::Result<Option<(std::process::ExitStatus, String, String)>> {
    use std::io::Read;
    use std::process::{Command, Stdio};
    let mut child = Command::new(exe)
        .args(args)
        .arg(path)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()?;
    // Both pipes are drained on threads of their own (a full pipe would stall the process);
    // standard output reaching its end tells that the process is done.
    let (tx, rx) = std::sync::mpsc::channel();
    let mut stdout = child.stdout.take();
    let out_reader = std::thread::spawn(move || {
        let mut text = String::new();
        if let Some(pipe) = stdout.as_mut() {
            let _ = pipe.read_to_string(&mut text);
        }
        let _ = tx.send(());
        text
    });
    let mut stderr = child.stderr.take();
    let err_reader = std::thread::spawn(move || {
        let mut text = String::new();
        if let Some(pipe) = stderr.as_mut() {
            let _ = pipe.read_to_string(&mut text);
        }
        text
    });
    let finished = rx.recv_timeout(limit).is_ok();
    if !finished {
        let _ = child.kill();
    }
    let status = child.wait()?;
    let stdout = out_reader.join().unwrap_or_default();
    let stderr = err_reader.join().unwrap_or_default();
    Ok(finished.then_some((status, stdout, stderr)))
}

/// Runs `work` on every item on `jobs` threads and hands the results to `emit` in the items'
/// order, each as soon as it and every one before it are done (so the output is the
/// sequential run's, streamed). A panic in `work` (there should be none) becomes
/// `panicked(item, message)` instead, and the batch goes on.
pub(crate) fn ordered<T: Sync, R: Send>(
    items: &[T],
    jobs: usize,
    work: impl Fn(&T) -> R + Sync,
    panicked: impl Fn(&T, String) -> R + Sync,
    mut emit: impl FnMut(R),
) {
    let run = |item: &T| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| work(item))).unwrap_or_else(|e| {
            let why = e
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| e.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown cause".to_owned());
            panicked(item, why)
        })
    };
    let jobs = jobs.clamp(1, items.len().max(1));
    if jobs == 1 {
        items.iter().for_each(|item| emit(run(item)));
        return;
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (tx, rx) = std::sync::mpsc::channel::<(usize, R)>();
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let tx = tx.clone();
            let (next, run) = (&next, &run);
            scope.spawn(move || {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(item) = items.get(k) else { break };
                    if tx.send((k, run(item))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut waiting = std::collections::BTreeMap::new();
        let mut due = 0;
        for (k, r) in rx {
            waiting.insert(k, r);
            while let Some(r) = waiting.remove(&due) {
                emit(r);
                due += 1;
            }
        }
    });
}
