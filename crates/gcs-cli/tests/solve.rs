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

/// `gcs solve --all` on the triangular prism, a core no closed-form step places: its DR-plan
/// is its two triangles (steps 0 and 1, 2 paths each) and their assembly as rigid bodies (step
/// 2, 6 paths: with the triangles' 2 × 2 realizations, Capco et al.'s 24 complex ones); every
/// realization is listed with the candidate of each node; `--choose 0=1` flips the first
/// triangle and the assembly follows; `--max-paths 0` keeps the core as solved.
#[test]
fn the_core_is_enumerated_by_homotopy_continuation() {
    let (code, out, err) = gcs(&["solve", "--all", "--format", "json", "data/paper/prism.ron"]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    let plan = v["plan"].as_array().unwrap();
    let tracked =
        |k: usize| (plan[k]["paths"]["tracked"].as_u64(), plan[k]["paths"]["finite"].as_u64());
    assert_eq!(
        (tracked(0), tracked(1), tracked(2)),
        ((Some(2), Some(2)), (Some(2), Some(2)), (Some(6), Some(6))),
        "{v}"
    );
    assert_eq!(plan[2]["children"], serde_json::json!([0, 1]));
    assert!(plan[..3].iter().all(|p| p["complete"] == true && p["paths"]["failed"] == 0));
    let real = plan[2]["paths"]["real"].as_u64().unwrap();
    assert_eq!(plan[2]["candidates"].as_u64(), Some(real));
    let solutions = v["solutions"].as_array().unwrap();
    let nodes: Vec<Vec<u64>> = (v["node_choices"].as_array().unwrap().iter())
        .map(|c| c.as_array().unwrap().iter().map(|k| k.as_u64().unwrap()).collect())
        .collect();
    assert_eq!(nodes.len(), solutions.len());
    assert_eq!(nodes[0], vec![0, 0, 0], "the drawing's realization first");
    // Each triangle at each of its two sides; per pair, the assembly's real candidates.
    for a in 0..2 {
        for b in 0..2 {
            assert!(nodes.iter().any(|c| c[0] == a && c[1] == b), "{nodes:?}");
        }
    }
    let at_drawn = nodes.iter().filter(|c| c[0] == 0 && c[1] == 0).count() as u64;
    assert_eq!(at_drawn, real);
    let (_, text, _) = gcs(&["solve", "--all", "data/paper/prism.ron"]);
    assert!(
        text.contains("the core assembled along its DR-plan: step 0: 2 real of 2 complex"),
        "{text}"
    );

    let flipped = nodes.iter().position(|c| c[..2] == [1, 0] && c[2] == 0).unwrap();
    let (code, out, _) =
        gcs(&["solve", "--choose", "0=1", "--format", "json", "data/paper/prism.ron"]);
    assert_eq!(code, 0);
    let chosen: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(
        (chosen["plan"][0]["chosen"].as_u64(), chosen["plan"][0]["fixed"].as_bool()),
        (Some(1), Some(true))
    );
    assert_eq!(chosen["status"], "solved");
    assert_eq!(chosen["entities"], solutions[flipped]);
    let (code, _, err) = gcs(&["solve", "--choose", "2=99", "data/paper/prism.ron"]);
    assert_eq!(code, 1);
    assert!(err.contains("cannot choose candidate 99 of step 2"), "{err}");
    let (code, out, _) =
        gcs(&["solve", "--all", "--max-paths", "0", "--format", "json", "data/paper/prism.ron"]);
    assert_eq!(code, 0);
    let kept: Value = serde_json::from_str(out.trim()).unwrap();
    assert!(kept["plan"][0].get("paths").is_none());
    assert_eq!(kept["plan"][0]["complete"], false);
    assert_eq!(kept["plan"][0]["incomplete"], serde_json::json!([{"reason": "not-sought"}]));
    assert!(plan.iter().all(|p| p.get("incomplete").is_none()), "complete: no reason");
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

/// A reference (driven) dimension is measured, not imposed: at the drawing by `analyze`, at the
/// solution by `solve` (where the drawing moved, so did it), and `--out` writes it back as a
/// reference; construction geometry keeps its flag.
#[test]
fn reference_dimensions_are_measured_at_the_drawing_and_at_the_solution() {
    let file = temp("triangle_ref.ron");
    std::fs::write(
        &file,
        r#"System(name: "tri", dim: 2, entities: [
            Point(id: "a", at: [0, 0]), Point(id: "b", at: [4, 0]), Point(id: "c", at: [1, 3]),
            Segment(id: "ab", from: "a", to: "b", construction: true),
            Segment(id: "ac", from: "a", to: "c"),
        ], constraints: [
            Fix(id: "f", a: "a"), Horizontal(id: "h", a: "ab"),
            Distance(id: "d1", a: "a", b: "b", value: 4),
            Distance(id: "d2", a: "b", b: "c", value: 4),
            Distance(id: "d3", a: "a", b: "c", value: 3),
            Distance(id: "ref_bc", a: "b", b: "c", value: 4.2, reference: true),
            Angle(id: "ref_angle", a: "ab", b: "ac", reference: true),
        ])"#,
    )
    .unwrap();
    let path = file.to_str().unwrap();
    let (code, out, err) = gcs(&["analyze", "--format", "json", path]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["constraints"], 5, "references are not constraints: {v}");
    assert_eq!(v["dof"], 0);
    let m = &v["measured"];
    assert_eq!(m[0]["constraint"], "ref_bc");
    // At the drawing: |bc| = √18, the angle at a is atan(3) = 71.565…°.
    assert!((m[0]["value"].as_f64().unwrap() - 18f64.sqrt()).abs() < 1e-12, "{m}");
    assert_eq!(m[0]["written"], 4.2);
    assert!((m[1]["value"].as_f64().unwrap() - 3f64.atan().to_degrees()).abs() < 1e-9, "{m}");

    let dir = temp("out_ref");
    let (code, out, err) =
        gcs(&["solve", "--format", "json", "--out", dir.to_str().unwrap(), path]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["status"], "solved");
    let m = &v["measured"];
    // Solved: |bc| = 4 as d2 says; cos A = (16 + 9 − 16) / 24.
    assert!((m[0]["value"].as_f64().unwrap() - 4.0).abs() < 1e-9, "{m}");
    assert!((m[1]["value"].as_f64().unwrap() - (9.0f64 / 24.0).acos().to_degrees()).abs() < 1e-6);
    let written = std::fs::read_to_string(dir.join("tri.ron")).unwrap();
    assert!(
        written
            .contains("Distance(id: \"ref_bc\", a: \"b\", b: \"c\", value: 4.2, reference: true)")
    );
    assert!(written.contains("Segment(id: \"ab\", from: \"a\", to: \"b\", construction: true)"));
    let (_, text, _) = gcs(&["solve", path]);
    assert!(
        text.contains("reference dimensions (measured at the solution, not imposed): ref_bc = 4,"),
        "{text}"
    );
}

/// The audit's reproducer: `gcs generate laman-drawn 16 --seed 1`, solved. The solve from the
/// drawing leaves a point without a place; the autosolve's search over the core's nodes finds
/// the combination that holds, and the report shows it: `combinations` tried, a node of the
/// core `chosen` off its candidate 0, `backtracked`, every constraint within 1e-9.
#[test]
fn the_autosolve_backtracks_over_the_core() {
    let (code, model, err) = gcs(&["generate", "laman-drawn", "16", "--seed", "1"]);
    assert_eq!(code, 0, "{err}");
    let file = temp("laman-drawn-16-1.ron");
    std::fs::write(&file, model).unwrap();
    let (code, out, err) = gcs(&["solve", "--format", "json", file.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(v["status"], "solved", "{v}");
    assert!(v["max_residual"].as_f64().unwrap() <= 1e-9);
    assert!(v["combinations"].as_u64().unwrap() >= 2, "{v}");
    assert!(v["backtracked"].as_u64().unwrap() >= 1);
    assert_eq!(v["bound_hit"], false);
    let plan = v["plan"].as_array().unwrap();
    assert!(
        plan.iter().any(|p| p["method"] == "newton" && p["chosen"].as_u64().unwrap_or(0) > 0),
        "{v}"
    );
    let (_, text, _) = gcs(&["solve", file.to_str().unwrap()]);
    assert!(text.contains("status: solved"), "{text}");
    assert!(text.contains("backtracking over the core:"), "{text}");
}

/// A node that is not completely enumerated says why and how many solutions may be missing
/// (issue 14): two K3,3 with fewer paths allowed than a K3,3's 70; the bounds that cut a
/// search short are listed (here `--max-solutions`).
#[test]
fn an_incomplete_node_says_why() {
    let args = ["solve", "--all", "--max-paths", "32", "--max-solutions", "2"];
    let (code, out, err) =
        gcs(&[&args[..], &["--format", "json", "data/paper/two_k33.ron"]].concat());
    assert_eq!(code, 0, "{err}");
    let v: Value = serde_json::from_str(out.trim()).unwrap();
    for k in 0..2 {
        assert_eq!(v["plan"][k]["complete"], false);
        assert_eq!(
            v["plan"][k]["incomplete"],
            serde_json::json!([{"reason": "too-many-paths", "paths": 70, "limit": 32}]),
            "{v}"
        );
    }
    assert_eq!(v["plan"][2]["complete"], true);
    assert_eq!(v["truncated"], true);
    assert_eq!(v["bounds_hit"], serde_json::json!([{"bound": "max-solutions", "limit": 2}]));
    let (_, text, _) = gcs(&[&args[..], &["data/paper/two_k33.ron"]].concat());
    assert!(
        text.contains(
            "step 0 not completely enumerated: not enumerated: 70 paths, more than 32 (--max-paths): up to 70 complex solutions not sought"
        ),
        "{text}"
    );
    assert!(text.contains("bounds that cut a search short: max-solutions (2)"), "{text}");
}
