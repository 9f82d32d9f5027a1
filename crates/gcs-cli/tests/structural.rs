//! `gcs analyze --structural` end to end: the `structural` section of docs/format.md §3 on every model
//! of `data/`, the papers' examples with what each method says, and the disagreements the text
//! report names.

mod common;

use common::gcs;

use serde_json::Value;

/// The JSON report of one model, with `--structural`.
fn report(file: &str) -> Value {
    let (code, stdout, stderr) = gcs(&["analyze", "--structural", "--format", "json", file]);
    assert_eq!(code, 0, "{stderr}");
    serde_json::from_str(stdout.trim_end()).unwrap()
}

/// The text report of one model, with `--structural`.
fn text(file: &str) -> String {
    let (code, stdout, stderr) = gcs(&["analyze", "--structural", file]);
    assert_eq!(code, 0, "{stderr}");
    stdout
}

fn strings(v: &Value) -> Vec<&str> {
    v.as_array().unwrap().iter().map(|s| s.as_str().unwrap()).collect()
}

fn disagreements(text: &str) -> Vec<&str> {
    text.lines().filter_map(|l| l.trim_start().strip_prefix("disagreement: ")).collect()
}

#[test]
fn flow_fig1a_dense_is_fooled_by_the_parallel_lines() {
    let r = report("data/paper/flow_fig1a.ron");
    let s = &r["structural"];
    assert_eq!(s["dense"]["verdict"], "over-rigid");
    assert_eq!(strings(&s["dense"]["subsystem"]), ["A", "B"]);
    assert_eq!(strings(&s["dense"]["subsystem_constraints"]), ["par_AB", "d_AB"]);
    assert_eq!(s["dense"]["subsystem_dof"], 2);
    for (key, dor) in [("over_rigid", "rules"), ("over_rigid_witness", "witness")] {
        assert_eq!(s[key]["verdict"], "well-rigid", "{key}");
        assert_eq!(strings(&s[key]["subsystem"]), Vec::<&str>::new());
        assert_eq!(s[key]["dor"], dor);
        assert_eq!((&s[key]["dof"], &s[key]["displacements"]), (&Value::from(2), &Value::from(2)));
    }
    assert_eq!(r["well_constrained"], true);
    let t = text("data/paper/flow_fig1a.ron");
    assert!(t.contains("    Dense: over-rigid: A, B (DOF 2 < 3 displacements)\n"), "{t}");
    assert!(t.contains("    Over-Rigid (rules DOR): well-rigid (DOF 2 = DOR 2)\n"), "{t}");
    assert!(t.contains("    Over-Rigid (witness DOR): well-rigid (DOF 2 = DOR 2)\n"), "{t}");
    assert_eq!(
        disagreements(&t),
        ["Dense: A, B: 2 displacements admitted, not 3, and no redundant constraint among them: \
          Dense charges a subsystem with more displacements than it admits (a segment in 3D, \
          parallel lines, a circle)"]
    );
}

#[test]
fn flow_fig1b_over_rigid_finds_acdef_dense_a_point_on_the_line() {
    let r = report("data/paper/flow_fig1b.ron");
    let s = &r["structural"];
    for key in ["over_rigid", "over_rigid_witness"] {
        assert_eq!(s[key]["verdict"], "over-rigid", "{key}");
        assert_eq!(strings(&s[key]["subsystem"]), ["A", "C", "D", "E", "F"], "{key}");
        assert_eq!(s[key]["subsystem_dof"], 5);
        // The witness confirms: d_EF, redundant, is one of its constraints.
        assert!(strings(&s[key]["subsystem_constraints"]).contains(&"d_EF"));
    }
    assert_eq!(r["redundant"][0]["constraint"], "d_EF");
    // Dense flags a point on the line with the line (or a bar): two objects, DOF 5 < 6.
    assert_eq!(s["dense"]["verdict"], "over-rigid");
    assert_eq!(strings(&s["dense"]["subsystem"]), ["A", "B"]);
    assert_eq!(s["dense"]["subsystem_dof"], 5);
    let t = text("data/paper/flow_fig1b.ron");
    assert!(t.contains("    Over-Rigid (rules DOR): over-rigid: A, C, D, E, F (DOF 5 < DOR 6)\n"));
    assert!(
        t.contains("    Over-Rigid (witness DOR): over-rigid: A, C, D, E, F (DOF 5 < DOR 6)\n")
    );
    let d = disagreements(&t);
    assert_eq!(d.len(), 1, "{t}");
    assert!(d[0].starts_with("Dense: A, B: 5 displacements admitted, not 6"), "{t}");
}

#[test]
fn double_banana_the_counts_miss_the_hinge() {
    let r = report("data/paper/double_banana.ron");
    let s = &r["structural"];
    for key in ["over_rigid", "over_rigid_witness"] {
        assert_eq!(s[key]["verdict"], "well-rigid", "{key}");
        assert_eq!((&s[key]["dof"], &s[key]["displacements"]), (&Value::from(6), &Value::from(6)));
    }
    assert_eq!(r["rigid"], false);
    assert_eq!(r["redundant"][0]["constraint"], "Sb3");
    let t = text("data/paper/double_banana.ron");
    let d = disagreements(&t);
    assert_eq!(d.len(), 2, "{t}");
    assert!(d[0].starts_with("Dense: a1, a2: 5 displacements admitted, not 6"), "{t}");
    assert_eq!(
        d[1],
        "Over-Rigid (rules DOR) and Over-Rigid (witness DOR) find no over-rigid subsystem, but \
         the witness finds Sb3 redundant and 1 DOF left, not 0: the count cannot see a geometric \
         dependency (a theorem, or a hinge such as the double banana's)"
    );
}

#[test]
fn fig6_the_count_believes_d_ay_removes_a_dof() {
    let r = report("data/paper/fig6_harmonic.ron");
    let s = &r["structural"];
    for key in ["dense", "over_rigid", "over_rigid_witness"] {
        assert_eq!(s[key]["verdict"], "under-rigid", "{key}");
        // 18 − 13 = 5 DOF by count, 3 displacements: 2 left; the witness says 3.
        assert_eq!((&s[key]["dof"], &s[key]["displacements"]), (&Value::from(5), &Value::from(3)));
    }
    assert_eq!(r["dof"], 3);
    assert_eq!(r["redundant"][0]["constraint"], "d_ay");
    let t = text("data/paper/fig6_harmonic.ron");
    assert_eq!(
        disagreements(&t),
        ["Dense, Over-Rigid (rules DOR) and Over-Rigid (witness DOR) find no over-rigid \
          subsystem, but the witness finds d_ay redundant and 3 DOF left, not 2: the count cannot \
          see a geometric dependency (a theorem, or a hinge such as the double banana's)"]
    );
}

#[test]
fn agreement_is_said_once() {
    // The kite: every method finds the K4, the witness finds c6 redundant in it.
    let t = text("data/paper/kite.ron");
    assert!(disagreements(&t).is_empty(), "{t}");
    assert!(t.ends_with("    no disagreement with the witness analysis\n"), "{t}");
}

#[test]
fn a_parallelism_the_rules_cannot_see() {
    // Two 2D lines at an angle of 0: parallel at the witness (the sketch), which only the
    // witness DOR sees (the rules do not read angle values).
    let dir = std::env::temp_dir().join(format!("gcs-structural-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("angle_zero.ron");
    std::fs::write(
        &file,
        r#"System(dim: 2, entities: [
            Line(id: "L1", at: [[0, 0], [4, 3]]), Line(id: "L2", at: [[1, 5], [5, 8]]) ],
          constraints: [ Angle(id: "ang", a: "L1", b: "L2", value: 0) ])"#,
    )
    .unwrap();
    let path = file.to_str().unwrap();
    let t = text(path);
    let json = report(path);
    std::fs::remove_dir_all(&dir).unwrap();
    let s = &json["structural"];
    assert_eq!(s["over_rigid"]["verdict"], "well-rigid");
    assert_eq!(s["over_rigid_witness"]["verdict"], "under-rigid");
    assert_eq!(s["over_rigid_witness"]["displacements"], 2);
    assert_eq!(json["dof"], 1);
    assert_eq!(
        disagreements(&t),
        [
            "Dense counts 0 DOF left, the witness 1: the system admits 2 displacements, Dense \
             charges 3",
            "Over-Rigid (rules DOR) counts 0 DOF left, the witness 1: the system admits 2 \
             displacements, not 3: a parallelism/collinearity the rules cannot see",
        ]
    );
}

/// Ids in file order: strictly increasing positions among the model's entities (constraints).
fn in_file_order(ids: &[&str], position: impl Fn(&str) -> usize) -> bool {
    ids.windows(2).all(|w| position(w[0]) < position(w[1]))
}

#[test]
fn json_shape_on_all_of_data() {
    let (code, stdout, stderr) = gcs(&["analyze", "--structural", "--format", "json", "data"]);
    assert_eq!(code, 0, "{stderr}");
    let lines: Vec<Value> = stdout.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    assert!(lines.len() >= 16);
    let verdicts = ["over-rigid", "well-rigid", "under-rigid"];
    for r in &lines {
        let file = r["file"].as_str().unwrap();
        let system = gcs_suite::load_model(file, r["model"].as_str().unwrap());
        let entity = |id: &str| system.entity_by_id(id).unwrap().index();
        let constraint = |id: &str| system.constraint_by_id(id).unwrap().index();
        let s = &r["structural"];
        let redundant: Vec<&str> = r["redundant"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x["constraint"].as_str().unwrap())
            .collect();
        for (key, dor) in [
            ("dense", None),
            ("over_rigid", Some("rules")),
            ("over_rigid_witness", Some("witness")),
        ] {
            let m = &s[key];
            let verdict = m["verdict"].as_str().unwrap();
            assert!(verdicts.contains(&verdict), "{file} {key}");
            assert_eq!(m["dor"].as_str(), dor, "{file} {key}");
            let sub = strings(&m["subsystem"]);
            let sub_c = strings(&m["subsystem_constraints"]);
            assert!(in_file_order(&sub, entity), "{file} {key}");
            assert!(in_file_order(&sub_c, constraint), "{file} {key}");
            assert!(m["dof"].is_i64() && m["displacements"].is_u64(), "{file} {key}");
            if verdict == "over-rigid" {
                assert!(!sub.is_empty() || m["subsystem_grounded"] == true, "{file} {key}");
                // Fewer DOF than charged, hence than the whole system's DOR (monotone).
                let dof = m["subsystem_dof"].as_i64().unwrap();
                assert!(dof < m["displacements"].as_i64().unwrap(), "{file} {key}");
                // With the exact DOR, an over-rigid subsystem has a redundant constraint.
                if key == "over_rigid_witness" {
                    assert!(sub_c.iter().any(|c| redundant.contains(c)), "{file}");
                }
            } else {
                assert!(sub.is_empty() && sub_c.is_empty(), "{file} {key}");
                assert!(m.get("subsystem_dof").is_none());
                let (dof, k) = (m["dof"].as_i64().unwrap(), m["displacements"].as_i64().unwrap());
                assert_eq!(verdict == "well-rigid", dof == k, "{file} {key}");
            }
        }
        // D-M: every constraint with DOC > 0 and every entity with DOF > 0 in exactly one part.
        let dm = &s["dm"];
        let mut cs: Vec<usize> = Vec::new();
        let mut es: Vec<usize> = Vec::new();
        for part in ["over", "well", "under"] {
            let c = strings(&dm[part]["constraints"]);
            let e = strings(&dm[part]["entities"]);
            assert!(in_file_order(&c, constraint) && in_file_order(&e, entity), "{file} {part}");
            cs.extend(c.iter().map(|x| constraint(x)));
            es.extend(e.iter().map(|x| entity(x)));
        }
        cs.sort_unstable();
        es.sort_unstable();
        let expect_c: Vec<usize> = system
            .constraint_indices()
            .filter(|c| system.constraint(*c).doc > 0)
            .map(|c| c.index())
            .collect();
        let expect_e: Vec<usize> = system
            .entity_indices()
            .filter(|e| system.entity_dof(*e) > 0)
            .map(|e| e.index())
            .collect();
        assert_eq!(cs, expect_c, "{file}");
        assert_eq!(es, expect_e, "{file}");
        assert!(dm["blocks"].is_array() && dm["matched"].is_u64());
    }
}

/// A JSON object's text with one member (`,"key":value`) cut out, bytes otherwise untouched.
fn without_member(json: &str, key: &str) -> String {
    let start = json.find(&format!(",\"{key}\":")).unwrap();
    let value = start + key.len() + 4;
    let (mut depth, mut in_string, mut escaped) = (0i32, false, false);
    for (i, ch) in json[value..].char_indices() {
        match ch {
            _ if escaped => escaped = false,
            '\\' if in_string => escaped = true,
            '"' => in_string = !in_string,
            '{' | '[' if !in_string => depth += 1,
            '}' | ']' if !in_string => {
                depth -= 1;
                if depth == 0 {
                    return format!("{}{}", &json[..start], &json[value + i + 1..]);
                }
            }
            _ => {}
        }
    }
    panic!("unterminated member {key}");
}

#[test]
fn without_the_flag_nothing_changes() {
    // JSON: the same bytes, minus the structural member.
    let (_, plain, _) = gcs(&["analyze", "--format", "json", "data"]);
    let (_, with, _) = gcs(&["analyze", "--structural", "--format", "json", "data"]);
    assert!(!plain.contains("\"structural\""));
    let plain: Vec<&str> = plain.lines().collect();
    let with: Vec<&str> = with.lines().collect();
    assert_eq!(plain.len(), with.len());
    for (p, w) in plain.iter().zip(&with) {
        assert_eq!(without_member(w, "structural"), *p);
    }
    // Text: the same lines, followed by the structural block.
    let (_, plain, _) = gcs(&["analyze", "data/paper", "data/sketches/slot.ron"]);
    let (_, with, _) = gcs(&["analyze", "--structural", "data/paper", "data/sketches/slot.ron"]);
    assert!(!plain.contains("structural:"));
    let stripped: Vec<&str> = with
        .lines()
        .scan(false, |inside, l| {
            if l == "  structural:" {
                *inside = true;
            } else if !l.starts_with("    ") {
                *inside = false;
            }
            Some((*inside, l))
        })
        .filter(|(inside, _)| !inside)
        .map(|(_, l)| l)
        .collect();
    assert_eq!(stripped, plain.lines().collect::<Vec<_>>());
    assert_eq!(
        with.matches("  structural:\n").count(),
        plain.lines().filter(|l| !l.starts_with(' ')).count()
    );
}
