//! `gcs solve` end to end: the JSON line's normative fields, a conflict named with the
//! constraints it conflicts with, `--out` writing a solved model that `gcs analyze` reads and
//! finds satisfied, and every example of data/ (CAD files included) solved.

mod common;

use common::gcs;
use gcs_suite::solver_rectangle;
use serde_json::Value;

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("gcs-solve-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn a_conflict_is_named_with_what_it_conflicts_with() {
    let file = temp("rect48.ron");
    std::fs::write(&file, solver_rectangle("48")).unwrap();
    let (code, out, err) = gcs(&["solve", "--format", "json", file.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["schema"], 1);
    assert_eq!(v["model"], "rect");
    assert_eq!(v["status"], "inconsistent");
    assert!(v["max_residual"].as_f64().unwrap() < 1e-9);
    assert!((v["moved"].as_f64().unwrap() - 20.0).abs() < 1e-6);
    let conflict = &v["conflicting"][0];
    assert_eq!(conflict["constraint"], "width_top");
    assert!((conflict["residual"].as_f64().unwrap() + 8.0).abs() < 1e-6);
    assert_eq!(conflict["spanning_group"], serde_json::json!(["v_right", "v_left", "width"]));
    let p3 = v["entities"].as_array().unwrap().iter().find(|e| e["id"] == "p3").unwrap();
    let at: Vec<f64> = p3["at"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    assert!((at[0] - 50.0).abs() < 1e-6 && (at[1] - 35.0).abs() < 1e-6, "{at:?}");
    let (_, text, _) = gcs(&["solve", file.to_str().unwrap()]);
    assert!(text.contains("conflicting: width_top is off by -8"), "{text}");
}

#[test]
fn the_solved_model_is_written_and_reads_back_satisfied() {
    let file = temp("rect40.ron");
    std::fs::write(&file, solver_rectangle("40")).unwrap();
    let dir = temp("out");
    let (code, out, err) = gcs(&["solve", "--out", dir.to_str().unwrap(), file.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("status: solved"), "{out}");
    assert!(out.contains("redundant (consistent): width_top"), "{out}");
    let solved = dir.join("rect.ron");
    let (code, json, err) = gcs(&["analyze", "--format", "json", solved.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(json.trim()).unwrap();
    assert_eq!(v["witness"], "sketch", "the solution is a witness: {v}");
    assert_eq!(v["sketch"]["satisfied"], true, "{v}");
}

#[test]
fn every_example_solves() {
    let (code, out, err) = gcs(&["solve", "--format", "json", "data/"]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<Value> = out.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert!(lines.len() >= 20);
    for v in &lines {
        assert_eq!(v["status"], "solved", "{v}");
    }
}

/// `gcs analyze` tells a redundant dimension that agrees with the others from one that
/// conflicts, at the user's values (format §4, `redundant[].conflicting`): the same rectangle
/// with its top at 40 and at 48, and the kite of the witness paper, whose 3.1623 for √10
/// agrees within its written precision.
#[test]
fn analyze_tells_consistent_from_conflicting() {
    let redundant = |file: &std::path::Path| -> Value {
        let (code, out, err) = gcs(&["analyze", "--format", "json", file.to_str().unwrap()]);
        assert_eq!(code, 0, "{err}");
        let v: Value = serde_json::from_str(out.trim()).unwrap();
        v["redundant"][0].clone()
    };
    let conflicting = temp("analyze48.ron");
    std::fs::write(&conflicting, solver_rectangle("48")).unwrap();
    let r = redundant(&conflicting);
    assert_eq!(r["constraint"], "width_top");
    assert_eq!(r["conflicting"], true, "{r}");
    assert!((r["residual"].as_f64().unwrap() + 8.0).abs() < 1e-6, "{r}");
    assert_eq!(r["spanning_group"], serde_json::json!(["v_right", "v_left", "width"]));
    let (_, text, _) = gcs(&["analyze", conflicting.to_str().unwrap()]);
    assert!(text.contains("1 of them conflicting at these values"), "{text}");
    assert!(text.contains("conflicting: width_top (Distance p4–p3) is off by -8"), "{text}");

    let consistent = temp("analyze40.ron");
    std::fs::write(&consistent, solver_rectangle("40")).unwrap();
    let r = redundant(&consistent);
    assert_eq!(r["conflicting"], false, "{r}");
    assert!(r["residual"].as_f64().unwrap().abs() <= r["allowance"].as_f64().unwrap(), "{r}");
    let (_, text, _) = gcs(&["analyze", consistent.to_str().unwrap()]);
    assert!(text.contains("redundant (consistent): width_top"), "{text}");

    let kite = common::root().join("data/paper/kite.ron");
    let r = redundant(&kite);
    assert_eq!((r["constraint"].as_str(), r["conflicting"].as_bool()), (Some("c6"), Some(false)));
}

/// `gcs solve --all`: the kite's realizations (two: its redundant distance prunes the folded
/// ones), each in the shape of `entities`, every plan step complete; `--choose` fixes a side
/// and marks the step, a step out of the plan is an error line, a malformed one a usage error.
#[test]
fn all_realizations_and_fixed_choices() {
    let (code, out, err) = gcs(&["solve", "--all", "--format", "json", "data/paper/kite.ron"]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    let solutions = v["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 2, "{v}");
    assert_eq!(v["truncated"], false);
    let ids = |entities: &Value| -> Vec<String> {
        entities.as_array().unwrap().iter().map(|e| e["id"].as_str().unwrap().to_owned()).collect()
    };
    for s in solutions {
        assert_eq!(ids(s), ids(&v["entities"]));
    }
    assert!(v["plan"].as_array().unwrap().iter().all(|p| p["complete"] == true), "{v}");
    let (_, text, _) = gcs(&["solve", "--all", "data/paper/kite.ron"]);
    assert!(text.contains("realizations: 2 "), "{text}");

    let (code, out, _) =
        gcs(&["solve", "--choose", "1=1", "--format", "json", "data/paper/kite.ron"]);
    assert_eq!(code, 0);
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(
        (v["plan"][1]["fixed"].clone(), v["plan"][1]["chosen"].clone()),
        (true.into(), 1.into())
    );
    assert!(v.get("solutions").is_none(), "listed only with --all");
    let (code, _, err) = gcs(&["solve", "--choose", "9=0", "data/paper/kite.ron"]);
    assert_eq!(code, 1);
    assert!(err.contains("cannot choose candidate 0 of step 9"), "{err}");
    let (code, _, _) = gcs(&["solve", "--choose", "one=0", "data/paper/kite.ron"]);
    assert_eq!(code, 2);
}

/// `gcs solve --all` on the triangular prism, a core no closed-form step places: its real
/// realizations come from homotopy continuation (70 paths, 24 complex solutions), each listed
/// with the core candidate it is; `--choose 0=K` takes one; `--max-paths 0` keeps the core as
/// solved.
#[test]
fn the_core_is_enumerated_by_homotopy_continuation() {
    let (code, out, err) = gcs(&["solve", "--all", "--format", "json", "data/paper/prism.ron"]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    let core = &v["plan"][0];
    assert_eq!(
        (core["paths"]["tracked"].as_u64(), core["paths"]["finite"].as_u64()),
        (Some(70), Some(24)),
        "{core}"
    );
    assert_eq!(
        (core["paths"]["failed"].as_u64(), core["complete"].as_bool()),
        (Some(0), Some(true))
    );
    let real = core["paths"]["real"].as_u64().unwrap();
    assert_eq!(core["candidates"].as_u64(), Some(real));
    let solutions = v["solutions"].as_array().unwrap();
    let cores: Vec<u64> =
        v["core_choices"].as_array().unwrap().iter().map(|c| c.as_u64().unwrap()).collect();
    assert_eq!(solutions.len() as u64, real);
    assert_eq!(cores, (0..real).collect::<Vec<_>>());
    let (_, text, _) = gcs(&["solve", "--all", "data/paper/prism.ron"]);
    assert!(text.contains(&format!("the core's {real} real realizations — 24 complex")), "{text}");

    let k = (real - 1).to_string();
    let (code, out, _) =
        gcs(&["solve", "--choose", &format!("0={k}"), "--format", "json", "data/paper/prism.ron"]);
    assert_eq!(code, 0);
    let chosen: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(
        (chosen["plan"][0]["chosen"].as_u64(), chosen["status"].as_str()),
        (Some(real - 1), Some("solved"))
    );
    assert_eq!(chosen["entities"], solutions[(real - 1) as usize]);
    let (code, out, _) =
        gcs(&["solve", "--all", "--max-paths", "0", "--format", "json", "data/paper/prism.ron"]);
    assert_eq!(code, 0);
    let kept: Value = serde_json::from_str(out.trim()).unwrap();
    assert!(kept["plan"][0].get("paths").is_none());
    assert_eq!(kept["solutions"].as_array().unwrap().len(), 1);
}

/// `gcs solve --jobs N`: byte for byte the one-at-a-time output, in the same order.
#[test]
fn parallel_solves_are_the_sequential_run() {
    let (code, one, err) = gcs(&["solve", "--format", "json", "--jobs", "1", "data/"]);
    assert_eq!(code, 0, "{err}");
    let (code, three, err) = gcs(&["solve", "--format", "json", "--jobs", "3", "data/"]);
    assert_eq!(code, 0, "{err}");
    assert!(one.lines().count() > 20);
    assert_eq!(three, one);
}
