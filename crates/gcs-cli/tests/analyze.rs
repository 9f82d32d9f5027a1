//! `gcs analyze` end to end: the JSON Lines report of format §2 (every required field, with
//! its type, for every model, in sorted file order), failures that do not stop the batch,
//! the reported tolerance and seed, exit codes, determinism; and golden reports of every
//! model of `data/`, JSON and text, in `tests/expected/analyze/` beside this file.
//!
//! Golden files are regenerated with `UPDATE_EXPECT=1 cargo test -p gcs-cli --test analyze`
//! (rust-analyzer's expect-test convention), so that any change in a report shows as a diff.

mod common;

use common::{gcs, root};

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use serde_json::Value;

fn json_lines(stdout: &str) -> Vec<Value> {
    stdout
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("not JSON ({e}): {l}")))
        .collect()
}

/// The models of `data/`, relative to the root, sorted (the order of `gcs analyze data/`).
fn data_files() -> Vec<String> {
    fn walk(dir: &Path, base: &Path, out: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, base, out);
            } else if path.extension().is_some_and(|e| e == "ron") {
                let rel = path.strip_prefix(base).unwrap();
                out.push(
                    rel.components()
                        .map(|c| c.as_os_str().to_string_lossy())
                        .collect::<Vec<_>>()
                        .join("/"),
                );
            }
        }
    }
    let mut out = Vec::new();
    walk(&root().join("data"), &root(), &mut out);
    out.sort();
    assert!(out.len() >= 10, "{out:?}");
    out
}

fn uint(v: &Value, field: &str) -> u64 {
    v[field].as_u64().unwrap_or_else(|| panic!("{field} must be an unsigned integer in {v}"))
}

fn string<'a>(v: &'a Value, field: &str) -> &'a str {
    v[field].as_str().unwrap_or_else(|| panic!("{field} must be a string in {v}"))
}

fn boolean(v: &Value, field: &str) -> bool {
    v[field].as_bool().unwrap_or_else(|| panic!("{field} must be a boolean in {v}"))
}

fn strings(v: &Value, field: &str) -> Vec<String> {
    v[field]
        .as_array()
        .unwrap_or_else(|| panic!("{field} must be an array in {v}"))
        .iter()
        .map(|s| s.as_str().unwrap_or_else(|| panic!("{field}: strings, in {v}")).to_owned())
        .collect()
}

/// Checks every field format §2 requires, its type, and the relations between them.
fn check_report(v: &Value, file: &str) {
    assert_eq!(v["schema"], 1, "{v}");
    assert_eq!(string(v, "file"), file);
    let stem = Path::new(file).file_stem().unwrap().to_string_lossy();
    assert_eq!(string(v, "model"), stem, "the shipped models are named after their file");
    let dim = uint(v, "dim");
    assert!(dim == 2 || dim == 3, "{v}");
    assert!(["exact", "rational", "rug", "modp", "float"].contains(&string(v, "backend")));
    assert!(["sketch", "perturbed", "generated"].contains(&string(v, "witness")), "{v}");
    let (unknowns, equations, rank) = (uint(v, "unknowns"), uint(v, "equations"), uint(v, "rank"));
    assert!(uint(v, "entities") > 0 && uint(v, "constraints") > 0, "{v}");
    assert!(rank <= unknowns.min(equations), "{v}");
    let (dof_absolute, trivial, dof) =
        (uint(v, "dof_absolute"), uint(v, "trivial_motions"), uint(v, "dof"));
    assert_eq!(dof_absolute, unknowns - rank, "{file}: dof_absolute = unknowns − rank");
    assert!(trivial <= 3 * (dim - 1), "{file}: at most 3 (2D) or 6 (3D) trivial motions");
    assert_eq!(dof, dof_absolute - trivial, "{file}: dof = dof_absolute − trivial_motions");
    let redundant = v["redundant"].as_array().unwrap_or_else(|| panic!("redundant: array in {v}"));
    assert_eq!(boolean(v, "rigid"), dof == 0, "{file}");
    assert_eq!(boolean(v, "well_constrained"), dof == 0 && redundant.is_empty(), "{file}");
    for r in redundant {
        assert!(!string(r, "constraint").is_empty());
        let (rows, doc) = (uint(r, "rows"), uint(r, "doc"));
        assert!(1 <= rows && rows <= doc, "{file}: {r}");
        let group = strings(r, "spanning_group");
        assert!(!group.contains(&string(r, "constraint").to_owned()), "{file}: {r}");
    }
}

#[test]
fn json_lines_for_every_model_in_sorted_order() {
    let (code, stdout, stderr) = gcs(&["analyze", "--format", "json", "data/"]);
    assert_eq!(code, 0, "{stderr}");
    let all = json_lines(&stdout);
    // The CAD examples of data/cad/: one report per sketch, with the import section.
    let (reports, cad): (Vec<Value>, Vec<Value>) =
        all.into_iter().partition(|v| string(v, "file").ends_with(".ron"));
    for v in &cad {
        let file = string(v, "file");
        let stem = Path::new(file).file_stem().unwrap().to_string_lossy();
        assert!(string(v, "model").starts_with(&format!("{stem}/")), "{v}");
        assert!(boolean(v, "complete_import"), "the shipped CAD examples import completely: {v}");
        assert!(uint(v, "rank") > 0, "{v}");
    }
    let files = data_files();
    let got: Vec<&str> = reports.iter().map(|v| string(v, "file")).collect();
    assert_eq!(
        got,
        files.iter().map(String::as_str).collect::<Vec<_>>(),
        "one report per model, sorted"
    );
    for (v, file) in reports.iter().zip(&files) {
        check_report(v, file);
        assert_eq!(v["backend"], "exact", "the default backend");
        assert_eq!(v["seed"], 1, "the default seed is reported");
    }
    // Not vacuous: the reports cover both dimensions, redundancy and fixed sketches.
    assert!(reports.iter().any(|v| v["dim"] == 3) && reports.iter().any(|v| v["dim"] == 2));
    assert!(reports.iter().any(|v| !v["redundant"].as_array().unwrap().is_empty()));
    assert!(reports.iter().any(|v| v["trivial_motions"] == 0));
}

/// Format §2: `clusters`, each with its entities and constraints; every entity is in one.
#[test]
fn json_reports_carry_the_clusters() {
    let (code, stdout, _) =
        gcs(&["analyze", "--format", "json", "data/paper/kite.ron", "data/sketches/four_bar.ron"]);
    assert_eq!(code, 0);
    for v in json_lines(&stdout) {
        let clusters =
            v["clusters"].as_array().unwrap_or_else(|| panic!("no clusters array in {v}"));
        assert!(!clusters.is_empty(), "{v}");
        let mut covered = BTreeSet::new();
        for c in clusters {
            covered.extend(strings(c, "entities"));
            strings(c, "constraints");
        }
        assert_eq!(covered.len() as u64, uint(&v, "entities"), "every entity is in a cluster: {v}");
    }
}

#[test]
fn a_bad_file_is_reported_and_the_batch_goes_on() {
    let (code, stdout, _) = gcs(&[
        "analyze",
        "--format",
        "json",
        "data/paper/kite.ron",
        "crates/gcs-model/tests/bad/unknown_id.ron",
        "no/such/file.ron",
        "data/paper/butterfly.ron",
    ]);
    assert_eq!(code, 1, "some files failed");
    let lines = json_lines(&stdout);
    assert_eq!(lines.len(), 4);
    check_report(&lines[0], "data/paper/kite.ron");
    check_report(&lines[3], "data/paper/butterfly.ron");
    let error = &lines[1];
    let keys: BTreeSet<&str> = error.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(keys, ["error", "file", "schema"].into(), "{error}");
    assert_eq!(error["schema"], 1);
    assert_eq!(error["file"], "crates/gcs-model/tests/bad/unknown_id.ron");
    assert_eq!(
        error["error"],
        "crates/gcs-model/tests/bad/unknown_id.ron:4:48: constraint \"d\": field b: unknown entity id \"r\""
    );
    assert_eq!(lines[2]["file"], "no/such/file.ron");
    assert!(string(&lines[2], "error").starts_with("no/such/file.ron"), "{}", lines[2]);

    // Text: reports on stdout, one error line on stderr, same exit status.
    let (code, stdout, stderr) =
        gcs(&["analyze", "data/paper/kite.ron", "crates/gcs-model/tests/bad/unknown_id.ron"]);
    assert_eq!(code, 1);
    assert!(stdout.starts_with("data/paper/kite.ron: kite"), "{stdout}");
    assert!(!stdout.contains("unknown_id"), "{stdout}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: crates/gcs-model/tests/bad/unknown_id.ron:4:48:"),
        "{stderr}"
    );
}

/// A sketch without a rational witness (a point on two circles whose intersection is
/// irrational): the exact backend fails with the entity and constraints at fault, and the CLI
/// (not the library) suggests the float backend, which analyses it.
#[test]
fn an_approximate_witness_is_refused_with_a_hint() {
    let dir = std::env::temp_dir().join(format!("gcs-approximate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("two_circles.ron");
    std::fs::write(
        &file,
        r#"System(dim: 2,
  entities: [Circle(id: "k1", center: [0, 0], radius: 2), Circle(id: "k2", center: [3, 0], radius: 2),
             Point(id: "p", at: [1.5, 1.3229])],
  constraints: [Fix(id: "f1", a: "k1"), Fix(id: "f2", a: "k2"),
                Incident(id: "i1", a: "p", b: "k1"), Incident(id: "i2", a: "p", b: "k2")])"#,
    )
    .unwrap();
    let path = file.to_str().unwrap();
    // The default (exact) backend builds the witness modulo a prime, where
    // the square root exists, and says the answer is probabilistic.
    let (code, stdout, _) = gcs(&["analyze", "--format", "json", path]);
    assert_eq!(code, 0);
    let v = &json_lines(&stdout)[0];
    assert_eq!(v["witness"], "modular", "{v}");
    assert_eq!(v["rank"], 8, "{v}");
    assert_eq!(v["sketch"]["satisfied"], true, "{v}");
    assert_eq!(v["dof"], 0, "{v}");
    assert!(v["witness_error_bound"].as_f64().is_some_and(|b| b > 0.0 && b < 1e-6), "{v}");
    // The rational backend wants a rational witness and refuses with a hint.
    let (code, _, stderr) = gcs(&["analyze", "--backend", "rational", path]);
    assert_eq!(code, 1);
    assert!(stderr.contains("entity \"p\" cannot be placed rationally"), "{stderr}");
    assert!(
        stderr.trim_end().ends_with("rerun with --backend float to analyse it there"),
        "{stderr}"
    );
    let (code, stdout, _) = gcs(&["analyze", "--backend", "float", "--format", "json", path]);
    assert_eq!(code, 0);
    assert_eq!(json_lines(&stdout)[0]["witness"], "approximate");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A regular hexagon inscribed in a circle (FreeCAD's polygon tool): the default backend takes
/// its turns from the drawing modulo the turn prime and says so in both reports
/// (`witness_prime`, `witness_turns`; the text's witness line).
#[test]
fn an_inscribed_hexagon_reports_the_turns_it_took() {
    let dir = std::env::temp_dir().join(format!("gcs-hexagon-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("hexagon.ron");
    std::fs::write(&file, gcs_suite::INSCRIBED_HEXAGON).unwrap();
    let path = file.to_str().unwrap();
    let (code, stdout, stderr) = gcs(&["analyze", "--format", "json", path]);
    assert_eq!(code, 0, "{stderr}");
    let v = &json_lines(&stdout)[0];
    assert_eq!(v["witness"], "modular", "{v}");
    assert_eq!(v["witness_prime"], 2_304_536_300_628_962_399_u64, "{v}");
    let turns = v["witness_turns"].as_array().expect("the turns taken");
    assert!(turns.contains(&Value::from(6)), "{v}");
    assert_eq!((v["dof"].as_u64(), v["redundant"].as_array().map(Vec::len)), (Some(0), Some(0)));
    let (code, stdout, _) = gcs(&["analyze", path]);
    assert_eq!(code, 0);
    assert!(stdout.contains("witness: modular, turns by multiples of"), "{stdout}");
    assert!(stdout.contains("360°/6 taken from the drawing"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_float_backend_reports_its_tolerance() {
    let file = "data/paper/kite.ron";
    let (code, stdout, _) =
        gcs(&["analyze", "--format", "json", "--backend", "float", "--tolerance", "1e-6", file]);
    assert_eq!(code, 0);
    let v = &json_lines(&stdout)[0];
    check_report(v, file);
    assert_eq!(v["backend"], "float");
    assert_eq!(v["tolerance"].as_f64(), Some(1e-6), "{v}");
    assert_eq!(v["rank"], 5);
    // The default tolerance is reported too.
    let (_, stdout, _) = gcs(&["analyze", "--format", "json", "--backend", "float", file]);
    assert_eq!(json_lines(&stdout)[0]["tolerance"].as_f64(), Some(1e-9));
    // And in text.
    let (_, stdout, _) = gcs(&["analyze", "--backend", "float", "--tolerance", "1e-6", file]);
    assert!(stdout.contains("float arithmetic") && stdout.contains("tolerance 1e-6"), "{stdout}");
}

#[test]
fn every_backend_is_named_in_the_report() {
    let file = "data/paper/double_banana.ron";
    for backend in ["exact", "rational", "modp", "float"] {
        let (code, stdout, stderr) =
            gcs(&["analyze", "--format", "json", "--backend", backend, file]);
        assert_eq!(code, 0, "{backend}: {stderr}");
        let v = &json_lines(&stdout)[0];
        check_report(v, file);
        assert_eq!(v["backend"], backend);
        assert_eq!((uint(v, "rank"), uint(v, "dof")), (17, 1), "{backend}");
    }
}

#[test]
fn the_seed_is_reported() {
    let (code, stdout, stderr) =
        gcs(&["analyze", "--format", "json", "--seed", "42", "data/paper/kite.ron"]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(json_lines(&stdout)[0]["seed"], 42);
    let (_, stdout, _) = gcs(&["analyze", "--seed", "42", "data/paper/kite.ron"]);
    assert!(stdout.contains("seed 42"), "{stdout}");

    // A model with an incomplete sketch needs a generated witness: the seed is used there,
    // and any seed, the largest included, gives the same verdict.
    let file = "crates/gcs-model/tests/good/zoo2d.ron";
    let verdict = |seed: &str| {
        let (code, stdout, stderr) = gcs(&["analyze", "--format", "json", "--seed", seed, file]);
        assert_eq!(code, 0, "{stderr}");
        let v = json_lines(&stdout).remove(0);
        // (Its arc's tangency at a point needs a square root: the witness is built modulo p.)
        assert_eq!(v["witness"], "modular");
        assert_eq!(v["seed"].as_u64().map(|s| s.to_string()).as_deref(), Some(seed));
        (v["rank"].clone(), v["trivial_motions"].clone(), v["dof"].clone(), v["redundant"].clone())
    };
    assert_eq!(verdict("42"), verdict("18446744073709551615"));
}

#[test]
fn usage_errors_exit_with_two() {
    for args in [
        &["analyze"][..],
        &["analyze", "--backend", "nope", "data/paper/kite.ron"],
        &["analyze", "--format", "xml", "data/paper/kite.ron"],
        &["analyze", "--seed", "abc", "data/paper/kite.ron"],
        &["analyze", "--seed", "-1", "data/paper/kite.ron"],
        &["analyze", "--tolerance", "-1", "data/paper/kite.ron"],
        &["analyze", "--tolerance", "NaN", "--backend", "float", "data/paper/kite.ron"],
        &["analyze", "--frobnicate", "data/paper/kite.ron"],
    ] {
        let (code, stdout, _) = gcs(args);
        assert_eq!(code, 2, "{args:?}");
        assert!(stdout.is_empty(), "{args:?}: nothing on stdout on a usage error");
    }
    if !cfg!(feature = "rug") {
        let (code, _, stderr) = gcs(&["analyze", "--backend", "rug", "data/paper/kite.ron"]);
        assert_eq!(code, 2, "rug is not in this build: {stderr}");
    }
}

#[test]
fn reports_are_byte_identical_from_run_to_run() {
    let args = ["analyze", "--format", "json", "data/"];
    let (_, first, _) = gcs(&args);
    let (_, second, _) = gcs(&args);
    assert_eq!(first, second);
    let (_, first, _) = gcs(&["analyze", "data/sketches"]);
    let (_, second, _) = gcs(&["analyze", "data/sketches"]);
    assert_eq!(first, second);
}

// ---------------------------------------------------------------------------------------------
// Golden reports

/// Whether golden files are being regenerated.
fn update_expect() -> bool {
    std::env::var_os("UPDATE_EXPECT").is_some_and(|v| v == "1")
}

/// Compares `actual` with the golden file, or (re)writes it with `UPDATE_EXPECT=1`. A mismatch
/// is returned as a message with a line diff (for one-line JSON, a field diff).
fn expect_file(path: &Path, actual: &str) -> Result<(), String> {
    if update_expect() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        if std::fs::read_to_string(path).ok().as_deref() != Some(actual) {
            std::fs::write(path, actual).unwrap();
        }
        return Ok(());
    }
    let Ok(expected) = std::fs::read_to_string(path) else {
        return Err(format!("{}: missing (run with UPDATE_EXPECT=1 to create it)", path.display()));
    };
    if expected == actual {
        return Ok(());
    }
    Err(format!(
        "{} differs (UPDATE_EXPECT=1 accepts the new output):\n{}",
        path.display(),
        diff(&expected, actual)
    ))
}

fn diff(expected: &str, actual: &str) -> String {
    let parse = |s: &str| serde_json::from_str::<Value>(s.trim_end()).ok().filter(Value::is_object);
    if let (Some(e), Some(a)) = (parse(expected), parse(actual)) {
        let (e, a) = (e.as_object().unwrap(), a.as_object().unwrap());
        let keys: BTreeSet<&String> = e.keys().chain(a.keys()).collect();
        let mut out = String::new();
        for k in keys {
            if e.get(k) != a.get(k) {
                out.push_str(&format!("  {k}: {:?} -> {:?}\n", e.get(k), a.get(k)));
            }
        }
        if out.is_empty() {
            out.push_str("  same fields and values; the order or the spacing changed\n");
        }
        return out;
    }
    let (e, a): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), actual.lines().collect());
    let mut out = String::new();
    for i in 0..e.len().max(a.len()) {
        if e.get(i) != a.get(i) {
            if let Some(x) = e.get(i) {
                out.push_str(&format!("  -{x}\n"));
            }
            if let Some(y) = a.get(i) {
                out.push_str(&format!("  +{y}\n"));
            }
        }
    }
    out
}

fn expected_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/expected/analyze")
}

/// `data/paper/kite.ron` → `tests/expected/analyze/paper/kite.<ext>`.
fn golden_path(file: &str, ext: &str) -> PathBuf {
    let rel = Path::new(file).strip_prefix("data").unwrap().with_extension(ext);
    expected_dir().join(rel)
}

fn golden(format: &str, ext: &str) {
    let mut failures = Vec::new();
    let mut wanted = BTreeSet::new();
    for file in data_files() {
        let (code, stdout, stderr) = gcs(&["analyze", "--format", format, &file]);
        assert_eq!(code, 0, "{file}: {stderr}");
        let path = golden_path(&file, ext);
        wanted.insert(path.clone());
        if let Err(e) = expect_file(&path, &stdout) {
            failures.push(e);
        }
    }
    // A golden file without a model is stale.
    let mut stale = Vec::new();
    for sub in ["paper", "sketches"] {
        let Ok(entries) = std::fs::read_dir(expected_dir().join(sub)) else { continue };
        for entry in entries {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == ext) && !wanted.contains(&path) {
                if update_expect() {
                    std::fs::remove_file(&path).unwrap();
                } else {
                    stale.push(path.display().to_string());
                }
            }
        }
    }
    assert!(stale.is_empty(), "stale golden files (UPDATE_EXPECT=1 removes them): {stale:?}");
    assert!(failures.is_empty(), "{} reports changed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn golden_json_reports() {
    golden("json", "json");
}

#[test]
fn golden_text_reports() {
    golden("text", "txt");
}

/// Batches (issue 15): files analysed on several threads give the sequential run's output,
/// byte for byte and in the same order; the shards of `--shard i/n` are disjoint and together
/// are the whole run; a shard that does not exist is a usage error.
#[test]
fn parallel_and_sharded_batches_are_the_sequential_run() {
    let run = |args: &[&str]| {
        let (code, stdout, stderr) = gcs(args);
        assert_eq!(code, 0, "{args:?}: {stderr}");
        stdout
    };
    let sequential = run(&["analyze", "--format", "json", "--jobs", "1", "data/"]);
    let parallel = run(&["analyze", "--format", "json", "--jobs", "3", "data/"]);
    assert!(sequential.lines().count() > 20, "{sequential}");
    assert_eq!(parallel, sequential);

    let mut union: Vec<String> = Vec::new();
    for i in 0..3 {
        let shard = format!("{i}/3");
        let out = run(&["analyze", "--format", "json", "--shard", &shard, "data/"]);
        assert!(out.lines().count() > 0, "shard {shard} is empty");
        union.extend(out.lines().map(str::to_owned));
    }
    let mut all: Vec<String> = sequential.lines().map(str::to_owned).collect();
    let n = union.len();
    union.sort();
    union.dedup();
    assert_eq!(union.len(), n, "a model in two shards");
    all.sort();
    assert_eq!(union, all);

    let (code, _, stderr) = gcs(&["analyze", "--shard", "3/3", "data/"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("0 ≤ i < n"), "{stderr}");
}

/// `--timeout`: a model over the limit gets an error line naming it and the batch goes on with
/// the next file; the models within it are reported exactly as without the limit (text and
/// JSON, a CAD file's several sketches included); a bad limit or `--dot` beside it is a usage
/// error.
#[test]
fn a_model_over_the_timeout_gets_an_error_line_and_the_batch_goes_on() {
    let dir = std::env::temp_dir().join(format!("gcs-timeout-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A 5,000-point framework takes seconds; the limit is a tenth of one.
    let (code, big, _) = gcs(&["generate", "laman-sketch", "5000"]);
    assert_eq!(code, 0);
    std::fs::write(dir.join("b_big.ron"), big).unwrap();
    for name in ["kite", "chain"] {
        let text = std::fs::read_to_string(root().join(format!("data/paper/{name}.ron"))).unwrap();
        std::fs::write(dir.join(format!("{}_{name}.ron", &name[..1])), text).unwrap();
    }
    let path = dir.to_str().unwrap();
    let (code, stdout, _) = gcs(&["analyze", "--format", "json", "--timeout", "0.1", path]);
    assert_eq!(code, 1, "{stdout}");
    let lines = json_lines(&stdout);
    assert_eq!(lines.len(), 3, "{stdout}");
    // In sorted order: b_big.ron, c_chain.ron, k_kite.ron.
    assert_eq!(lines[1]["model"], "chain");
    assert_eq!(lines[2]["model"], "kite");
    let error = string(&lines[0], "error");
    assert!(
        error.ends_with("b_big.ron: stopped after 0.1 s (the limit set by --timeout)"),
        "{error}"
    );

    // Within the limit: the same reports as without it.
    let files = ["data/paper/kite.ron", "data/cad/bracket.json", "data/cad/plate.FCStd"];
    for format in ["json", "text"] {
        let mut plain = vec!["analyze", "--format", format];
        plain.extend(files);
        let mut limited = vec!["analyze", "--format", format, "--timeout", "60"];
        limited.extend(files);
        assert_eq!(gcs(&limited), gcs(&plain), "{format}");
    }
    // A file that cannot be read fails the same way with the limit.
    let bad = ["analyze", "--format", "json", "crates/gcs-model/tests/bad/unknown_id.ron"];
    let with_limit = [&bad[..], &["--timeout", "5"]].concat();
    assert_eq!(gcs(&with_limit), gcs(&bad));

    for args in
        [&["--timeout", "0"][..], &["--timeout", "soon"], &["--timeout", "5", "--dot", "x.dot"]]
    {
        let mut all = vec!["analyze"];
        all.extend(args);
        all.push(path);
        let (code, _, stderr) = gcs(&all);
        assert_eq!(code, 2, "{args:?}: {stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--svg DIR`: one picture per model, named by its file (a CAD file's sketches in a directory
/// of the file's name); the redundant constraint drawn with what it is redundant with as its
/// tooltip, the singular drawing's dependent constraints and configuration named, its extra
/// motion drawn as arrows; an absolute path lands inside the directory.
#[test]
fn pictures_of_the_analysis() {
    let dir = std::env::temp_dir().join(format!("gcs-svg-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let copy = dir.join("copy.ron");
    std::fs::copy(root().join("data/paper/kite.ron"), &copy).unwrap();
    let out = dir.join("pictures");
    let (code, _, err) = gcs(&[
        "analyze",
        "--svg",
        out.to_str().unwrap(),
        "data/paper/kite.ron",
        "data/singular/collinear_inside_rigid.ron",
        "data/cad/slot.slvs",
        copy.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let read = |name: &str| {
        std::fs::read_to_string(out.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
    };
    let kite = read("data/paper/kite.svg");
    assert!(kite.starts_with("<svg") && kite.trim_end().ends_with("</svg>"), "{kite}");
    assert!(
        kite.contains("<title>c6 (Distance): redundant (consistent): remove it or one of c1, c2, c3, c4, c5</title>"),
        "{kite}"
    );
    assert!(kite.contains("kite: over-constrained"), "{kite}");
    let singular = read("data/singular/collinear_inside_rigid.svg");
    assert!(singular.contains("dependent at this drawing (singular) with d12, d23"), "{singular}");
    assert!(singular.contains("collinear p1, p2, p3"), "{singular}");
    assert!(read("data/cad/slot/g2.svg").contains("<svg"));
    // Free motions: none for the rigid kite; one at the singular drawing (its extra motion),
    // drawn as arrows at the points it moves.
    assert!(!kite.contains("free motion"), "{kite}");
    assert!(singular.contains("1 free motion at this drawing"), "{singular}");
    assert!(singular.matches("<title>free motion 1 of 1:").count() >= 1, "{singular}");
    // The copy of the kite, given by its absolute path: inside the directory, beside the other.
    let inside = copy.with_extension("svg");
    let relative = inside.to_str().unwrap().trim_start_matches('/');
    assert!(read(relative).contains("kite: over-constrained"));
    assert!(!out.join("data/paper/kite.plan.svg").exists(), "a plan only with --decompose");
    // With --decompose: the W-decomposition as a tree beside the picture — two K3,3 under
    // their union, each box with its entities.
    let (code, _, err) =
        gcs(&["analyze", "--decompose", "--svg", out.to_str().unwrap(), "data/paper/two_k33.ron"]);
    assert_eq!(code, 0, "{err}");
    let plan = read("data/paper/two_k33.plan.svg");
    assert_eq!(plan.matches("<rect").count(), 3, "{plan}");
    assert_eq!(plan.matches("(leaf)").count(), 2, "{plan}");
    assert!(plan.contains("<title>6 entities: a1, a2, a3, b1, b2, b3</title>"), "{plan}");
    assert!(plan.contains("<title>12 entities: a1"), "{plan}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every node of a decomposition tree in the JSON report, depth first.
fn json_nodes(node: &Value) -> Vec<&Value> {
    let mut out = vec![node];
    for c in node["children"].as_array().into_iter().flatten() {
        out.extend(json_nodes(c));
    }
    out
}

/// `gcs analyze --decompose` incorporates declared groups (issue 14): a chain of three K3,3
/// with a rigid group (blocks A and B) and a loose one (A and one point of B): the first is a
/// node of the DR-plan marked with its id, the second is not, and the report says why.
#[test]
fn decompose_makes_a_rigid_group_a_node() {
    let mut b = gcs_model::SystemBuilder::from_system(gcs_model::generate::k33_chain(3, 1));
    let ab: Vec<String> = (0..12).map(|i| format!("p{i}")).collect();
    let loose: Vec<String> = (0..7).map(|i| format!("p{i}")).collect();
    b.group("AB", &ab.iter().map(String::as_str).collect::<Vec<_>>()).unwrap();
    b.group("loose", &loose.iter().map(String::as_str).collect::<Vec<_>>()).unwrap();
    let dir = std::env::temp_dir().join(format!("gcs-groups-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("chain.ron");
    std::fs::write(&file, b.build().to_ron()).unwrap();
    let path = file.to_str().unwrap();
    let (code, out, err) = gcs(&["analyze", "--decompose", "--format", "json", path]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(
        v["groups"],
        serde_json::json!([
            {"id": "AB", "rigid": true, "parts": 1},
            {"id": "loose", "rigid": false, "parts": 2},
        ])
    );
    let nodes = json_nodes(&v["decomposition"][0]);
    let marked: Vec<&&Value> = nodes.iter().filter(|n| n.get("groups").is_some()).collect();
    let [node] = marked.as_slice() else { panic!("one node is a group: {v}") };
    assert_eq!(node["groups"], serde_json::json!(["AB"]));
    let mut entities: Vec<&str> =
        node["entities"].as_array().unwrap().iter().map(|e| e.as_str().unwrap()).collect();
    entities.sort_unstable();
    let mut want: Vec<&str> = ab.iter().map(String::as_str).collect();
    want.sort_unstable();
    assert_eq!(entities, want);
    let (_, text, _) = gcs(&["analyze", "--decompose", path]);
    assert!(text.contains("(group AB)"), "{text}");
    assert!(
        text.contains(
            "group loose is not rigid on its own constraints (2 rigid parts): not a node"
        ),
        "{text}"
    );
    // Without --decompose, nothing of the groups.
    let (_, out, _) = gcs(&["analyze", "--format", "json", path]);
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    assert!(v.get("groups").is_none());
}
