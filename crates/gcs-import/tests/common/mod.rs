//! Shared helpers of the reader tests: where the corpus of real files from other projects is.
//!
//! The corpus (`shared/data/external`: SolveSpace's test files, FreeCAD documents, SketchGraphs'
//! Onshape sample) is not in the repository (other projects' files, under their licences). The
//! tests look for it at `$GCS_EXTERNAL_DATA`, then `../shared/data/external` beside the
//! workspace, then `/work/shared/data/external`. Without it a corpus test says so on stderr and
//! passes — except under CI (`CI` set), where a missing corpus is a failure.
#![allow(dead_code, unreachable_pub)]

use std::path::{Path, PathBuf};

/// The corpus directory, or `None` (after saying so) when it is absent outside CI.
#[allow(clippy::print_stderr)] // a test binary telling why it skipped
pub fn external() -> Option<PathBuf> {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let candidates = std::env::var_os("GCS_EXTERNAL_DATA")
        .map(PathBuf::from)
        .into_iter()
        .chain([workspace.join("../shared/data/external"), "/work/shared/data/external".into()]);
    for dir in candidates {
        if dir.is_dir() {
            return Some(dir);
        }
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "the external corpus is missing: set GCS_EXTERNAL_DATA to shared/data/external"
    );
    eprintln!("external corpus not found (set GCS_EXTERNAL_DATA): corpus test skipped");
    None
}

/// Every file under `dir` whose name ends with `suffix` (case-insensitive), sorted.
pub fn files_with_suffix(dir: &Path, suffix: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.to_string_lossy().to_ascii_lowercase().ends_with(suffix) {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// Every sketch file of the corpus as `(name, bytes)`: SolveSpace's `.slvs` files, the FreeCAD
/// documents, and the Onshape JSON files of SketchGraphs' sample (unpacked from its `.tar.xz`,
/// named `SketchGraphs/<path in the archive>`), sorted by name. `None` without the corpus.
pub fn sketch_files() -> Option<Vec<(String, Vec<u8>)>> {
    let dir = external()?;
    let mut files = Vec::new();
    for (sub, suffix) in [("solvespace", ".slvs"), ("FreeCAD_Assembly4", ".fcstd")] {
        for path in files_with_suffix(&dir.join(sub), suffix) {
            let name = path.strip_prefix(&dir).unwrap_or(&path).to_string_lossy().into_owned();
            files.push((name, std::fs::read(&path).expect("a corpus file")));
        }
    }
    files.extend(
        sketchgraphs_sample(&dir)
            .into_iter()
            .map(|(path, bytes)| (format!("SketchGraphs/{path}"), bytes)),
    );
    files.sort();
    Some(files)
}

/// The Onshape JSON files of SketchGraphs' sample, unpacked in memory as `(path inside the
/// archive, bytes)`, sorted by path. `None` without the corpus.
pub fn onshape_files() -> Option<Vec<(String, Vec<u8>)>> {
    Some(sketchgraphs_sample(&external()?))
}

/// SketchGraphs' sample archive of the corpus at `dir`, unpacked: its `.json` files as
/// `(path inside the archive, bytes)`, sorted by path.
fn sketchgraphs_sample(dir: &Path) -> Vec<(String, Vec<u8>)> {
    use std::io::Read;
    let archive = std::fs::read(dir.join("SketchGraphs/tests/testdata/sample_json.tar.xz"))
        .expect("the sample archive");
    let mut tar = Vec::new();
    lzma_rs::xz_decompress(&mut archive.as_slice(), &mut tar).expect("an xz archive");
    let mut files = Vec::new();
    for entry in tar::Archive::new(tar.as_slice()).entries().expect("a tar archive") {
        let mut entry = entry.expect("a tar entry");
        let path = entry.path().expect("a path").to_string_lossy().into_owned();
        if path.ends_with(".json") {
            let mut bytes = Vec::new();
            entry.read_to_end(&mut bytes).expect("readable");
            files.push((path, bytes));
        }
    }
    files.sort();
    files
}
