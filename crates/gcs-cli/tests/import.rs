//! CAD files end to end: `gcs check`, `gcs analyze` and `gcs convert` on SolveSpace and Onshape
//! files (our own test files of gcs-import), with the normative import fields of each JSON line
//! (`model` as `<file stem>/<sketch>`, `complete_import`, `skipped` with item and reason).

mod common;

use common::{gcs, root};
use serde_json::Value;

const SLVS: &str = "crates/gcs-import/tests/data/slvs";
const ONSHAPE: &str = "crates/gcs-import/tests/data/onshape";

fn json_lines(stdout: &str) -> Vec<Value> {
    stdout.lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

#[test]
fn check_reports_the_import_section() {
    let (code, out, err) = gcs(&["check", "--format", "json", &format!("{SLVS}/flags.slvs")]);
    assert_eq!(code, 0, "{err}");
    let lines = json_lines(&out);
    assert_eq!(lines.len(), 2, "one line per sketch (group) of the file");
    assert_eq!(lines[1]["model"], "flags/g3");
    let l = &lines[0];
    assert_eq!(l["model"], "flags/g2");
    assert_eq!(l["file"], format!("{SLVS}/flags.slvs"));
    assert_eq!(l["complete_import"], true);
    assert_eq!(l["skipped"], serde_json::json!([]));
    // Every dimension of the group is a reference dimension: measured, not imposed.
    assert_eq!(l["reference"], serde_json::json!(["c.00000001"]));
    assert_eq!(l["label"], "all dims reference");
}

#[test]
fn analyze_lists_what_was_not_imported() {
    let file = format!("{SLVS}/mapping2d.slvs");
    let (code, out, err) = gcs(&["analyze", "--format", "json", &file]);
    assert_eq!(code, 0, "{err}");
    let l = &json_lines(&out)[0];
    assert_eq!(l["model"], "mapping2d/g2");
    assert_eq!(l["complete_import"], false);
    let skipped = l["skipped"].as_array().unwrap();
    assert!(!skipped.is_empty());
    for s in skipped {
        assert!(s["item"].as_str().is_some_and(|i| !i.is_empty()), "{s}");
        assert!(s["reason"].as_str().is_some_and(|r| r.len() > 10), "{s}");
    }
    assert!(l["rank"].as_u64().is_some(), "the rest is analysed");
    // The text report says so too, under the model's first line.
    let (_, text, _) = gcs(&["analyze", &file]);
    let second = text.lines().nth(2).unwrap();
    assert!(second.starts_with("  import: INCOMPLETE"), "{text}");
}

#[test]
fn onshape_sketches_are_named_by_their_index() {
    let (code, out, err) = gcs(&["check", "--format", "json", &format!("{ONSHAPE}/features.json")]);
    assert_eq!(code, 0, "{err}");
    let l = &json_lines(&out)[0];
    assert_eq!(l["model"], "features/0");
    assert_eq!(l["label"], "Listed");
    assert_eq!(l["complete_import"], true);
}

#[test]
fn a_directory_includes_cad_files_and_a_bad_file_does_not_stop_the_batch() {
    let dir = std::env::temp_dir().join(format!("gcs-import-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(root().join(SLVS).join("flags.slvs"), dir.join("a.slvs")).unwrap();
    std::fs::write(dir.join("b.json"), "{\"not\": \"a sketch\"").unwrap();
    std::fs::write(dir.join("c.txt"), "ignored").unwrap();
    let (code, out, _) = gcs(&["check", "--format", "json", dir.to_str().unwrap()]);
    let lines = json_lines(&out);
    assert_eq!(code, 1, "one file failed");
    assert_eq!(lines.len(), 3, "{out}");
    assert_eq!((&lines[0]["model"], &lines[1]["model"]), (&"a/g2".into(), &"a/g3".into()));
    let error = lines[2]["error"].as_str().unwrap();
    assert!(error.contains("b.json"), "the error names the file: {error}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn convert_writes_ron_that_reads_back() {
    let (code, ron, err) = gcs(&["convert", &format!("{SLVS}/mapping2d.slvs")]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning: mapping2d/g2: "), "skipped items are listed: {err}");
    let system = gcs_model::System::from_ron_str(&ron, None).unwrap();
    assert_eq!(system.name(), "mapping2d/g2");
    assert_eq!(system.to_ron().trim_end(), ron.trim_end(), "RON → model → RON");

    let dir = std::env::temp_dir().join(format!("gcs-convert-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (code, _, err) = gcs(&["convert", &format!("{SLVS}/flags.slvs")]);
    assert_eq!(code, 2, "two sketches need -o DIR");
    assert!(err.contains("flags/g2, flags/g3"), "{err}");
    let (code, _, err) =
        gcs(&["convert", &format!("{SLVS}/flags.slvs"), "-o", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.join("flags/g3.ron").is_file());
    let written = dir.join("flags/g2.ron");
    let text = std::fs::read_to_string(&written).unwrap();
    assert_eq!(gcs_model::System::from_ron_str(&text, None).unwrap().name(), "flags/g2");
    // One sketch, to a directory not made yet, written with a trailing slash.
    let new = format!("{}/new/", dir.to_str().unwrap());
    let (code, _, err) = gcs(&["convert", &format!("{SLVS}/mapping2d.slvs"), "-o", &new]);
    assert_eq!(code, 0, "{err}");
    assert!(dir.join("new/mapping2d/g2.ron").is_file(), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();

    let (code, _, err) = gcs(&["convert", "README.md"]);
    assert_eq!(code, 1);
    assert!(err.contains("README.md") && err.contains("not a SolveSpace"), "{err}");
}
