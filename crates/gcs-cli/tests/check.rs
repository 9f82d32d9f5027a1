//! `gcs check` end to end: counts, JSON Lines, failures that do not stop the batch, exit codes.

mod common;

use common::{gcs, root};

#[test]
fn json_lines_with_counts_and_failures_in_order() {
    let (code, stdout, _) = gcs(&[
        "check",
        "--format",
        "json",
        "crates/gcs-model/tests/good",
        "crates/gcs-model/tests/bad/unknown_id.ron",
        "no/such/file.ron",
    ]);
    assert_eq!(code, 1, "some files failed");
    let lines: Vec<serde_json::Value> =
        stdout.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert_eq!(lines.len(), 4);
    assert_eq!(lines[0]["file"], "crates/gcs-model/tests/good/zoo2d.ron");
    assert_eq!(lines[0]["model"], "zoo 2d");
    // Every kind of the format: the arc's end points and its centre (named by a constraint)
    // count, with the implicit constraints holding them.
    assert_eq!(lines[0]["entity_dof"], 54);
    assert_eq!(lines[0]["constraint_doc"], 42);
    assert_eq!(lines[0]["naive_dof"], 12);
    assert_eq!(lines[1]["file"], "crates/gcs-model/tests/good/zoo3d.ron");
    assert_eq!(lines[1]["naive_dof"], 6);
    assert_eq!(lines[2]["schema"], 1);
    assert_eq!(
        lines[2]["error"],
        "crates/gcs-model/tests/bad/unknown_id.ron:4:48: constraint \"d\": field b: unknown entity id \"r\""
    );
    assert!(lines[3]["error"].as_str().unwrap().starts_with("no/such/file.ron: "));
}

#[test]
fn text_reports_on_stdout_errors_on_stderr() {
    let (code, stdout, stderr) =
        gcs(&["check", "crates/gcs-model/tests/good/zoo2d.ron", "crates/gcs-model/tests/bad"]);
    assert_eq!(code, 1);
    assert_eq!(stdout.lines().count(), 1);
    assert!(stdout.contains("DOF 54 − DOC 42 = 12"), "{stdout}");
    let bad = std::fs::read_dir(root().join("crates/gcs-model/tests/bad"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().extension().is_some_and(|x| x == "ron"))
        .count();
    assert!(bad >= 24);
    assert_eq!(stderr.lines().count(), bad, "one line per bad file:\n{stderr}");
    assert!(stderr.lines().all(|l| l.starts_with("error: crates/gcs-model/tests/bad/")));
}

#[test]
fn all_good_is_exit_zero_and_usage_error_is_two() {
    assert_eq!(gcs(&["check", "crates/gcs-model/tests/good"]).0, 0);
    assert_eq!(gcs(&["check"]).0, 2);
    assert_eq!(gcs(&["check", "--format", "xml", "x.ron"]).0, 2);
    assert_eq!(gcs(&["frobnicate"]).0, 2);
}
