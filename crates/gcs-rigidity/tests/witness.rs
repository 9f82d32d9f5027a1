//! Over-Rigid with the exact DOR of a witness ([`WitnessDor`]) on the papers' examples and the
//! CAD sketches of `data/`, beside the rule table.

use gcs_model::{EntityIdx, System};
use gcs_rigidity::{
    DorOracle, RuleDor, Verdict, WitnessDor, minimal_over_rigid, over_rigid_analysis,
    structural_analysis,
};

fn load(relative: &str) -> System {
    let path = format!("{}/../../data/{relative}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    System::from_ron_str(&text, Some(&path)).unwrap_or_else(|e| panic!("{e}"))
}

fn data_files() -> Vec<String> {
    let mut out = Vec::new();
    for dir in ["paper", "sketches"] {
        let path = format!("{}/../../data/{dir}", env!("CARGO_MANIFEST_DIR"));
        let mut files: Vec<String> = std::fs::read_dir(&path)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|f| f.ends_with(".ron"))
            .map(|f| format!("{dir}/{f}"))
            .collect();
        files.sort();
        out.extend(files);
    }
    assert!(out.len() >= 10);
    out
}

fn ids(system: &System, entities: &[EntityIdx]) -> Vec<String> {
    entities.iter().map(|e| system.entity(*e).id.clone()).collect()
}

fn entities(system: &System, names: &[&str]) -> Vec<EntityIdx> {
    names.iter().map(|n| system.entity_by_id(n).unwrap()).collect()
}

/// Every set of one, two or three entities.
fn small_sets(n: usize) -> Vec<Vec<EntityIdx>> {
    let e = |i: usize| EntityIdx(i as u32);
    let mut out = Vec::new();
    for i in 0..n {
        out.push(vec![e(i)]);
        for j in i + 1..n {
            out.push(vec![e(i), e(j)]);
            for k in j + 1..n {
                out.push(vec![e(i), e(j), e(k)]);
            }
        }
    }
    out
}

#[test]
fn flow_fig1a_parallel_lines_are_well_rigid() {
    let s = load("paper/flow_fig1a.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    assert_eq!(w.dor(&s, &entities(&s, &["A", "B"])), 2);
    assert_eq!(w.dor(&s, &entities(&s, &["A", "B", "C"])), 2);
    let a = over_rigid_analysis(&s, &w);
    assert_eq!(a.verdict, Verdict::WellRigid);
    assert_eq!((a.dof, a.dor, a.dor_source.as_str()), (2, 2, "witness"));
}

#[test]
fn flow_fig1b_finds_acdef() {
    let s = load("paper/flow_fig1b.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    // The paper's DORs: BC 5, CEF 6, CDE 5 (collinear on A).
    assert_eq!(w.dor(&s, &entities(&s, &["B", "C"])), 5);
    assert_eq!(w.dor(&s, &entities(&s, &["C", "E", "F"])), 6);
    assert_eq!(w.dor(&s, &entities(&s, &["C", "D", "E"])), 5);
    assert_eq!(w.dor(&s, &entities(&s, &["A", "C", "D", "E"])), 5);
    let a = over_rigid_analysis(&s, &w);
    assert_eq!(a.verdict, Verdict::OverRigid);
    let sub = a.subsystem.unwrap();
    assert_eq!(ids(&s, &sub.objects), ["A", "C", "D", "E", "F"]);
    assert_eq!(sub.dof, 5);
    let min = minimal_over_rigid(&s, &w).unwrap();
    assert_eq!(ids(&s, &min.objects), ["A", "C", "D", "E", "F"]);
}

#[test]
fn double_banana_still_fools_over_rigid() {
    // The hinge is not a DOR matter: every DOR is the generic one, and the count is fooled
    // with the exact DOR as with the rules.
    let s = load("paper/double_banana.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    let r = RuleDor::for_system(&s);
    for set in small_sets(s.entities().len()) {
        assert_eq!(w.dor(&s, &set), r.dor(&s, &set));
    }
    let a = over_rigid_analysis(&s, &w);
    assert_eq!((a.verdict, a.dof, a.dor), (Verdict::WellRigid, 6, 6));
}

#[test]
fn fig6_the_theorem_is_invisible_to_the_dor() {
    let s = load("paper/fig6_harmonic.ron");
    let a = over_rigid_analysis(&s, &WitnessDor::find(&s, 1).unwrap());
    // DOF 5 by count (d_ay "removes" one), DOR 3: 2 internal DOF; the witness analysis says 3.
    assert_eq!((a.verdict, a.dof, a.dor), (Verdict::UnderRigid, 5, 3));
}

#[test]
fn block_corner_hidden_collinearity() {
    // O and b are on the edge Y ∩ Z, which is perpendicular to X (X ⊥ Y, X ⊥ Z): the rotation
    // about that edge keeps X, O and b in place. The rules do not chain it.
    let s = load("sketches/block_3d.ron");
    let w = WitnessDor::find(&s, 1).unwrap();
    let r = RuleDor::for_system(&s);
    let set = entities(&s, &["X", "O", "b"]);
    assert_eq!((w.dor(&s, &set), r.dor(&s, &set)), (5, 6));
    // Both still find the redundant diagonal's subsystem.
    assert_eq!(over_rigid_analysis(&s, &w).verdict, Verdict::OverRigid);
    assert_eq!(over_rigid_analysis(&s, &r).verdict, Verdict::OverRigid);
}

#[test]
fn the_witness_dor_never_exceeds_the_rules() {
    // Every fact the rules read holds at the witness, so the exact DOR is at most the rules'
    // (they can only miss properties). Equality except where the geometry hides something.
    let mut differences = Vec::new();
    for f in data_files() {
        let s = load(&f);
        let w = WitnessDor::find(&s, 1).unwrap();
        let r = RuleDor::for_system(&s);
        for set in small_sets(s.entities().len()) {
            let (a, b) = (w.dor(&s, &set), r.dor(&s, &set));
            assert!(a <= b, "{f}: {:?}: witness {a} > rules {b}", ids(&s, &set));
            if a != b {
                differences.push(format!("{}: {}", s.name(), ids(&s, &set).join(" ")));
            }
        }
        // Over-Rigid with the exact DOR never finds more than with the rules: an over-rigid
        // verdict with the witness implies one with the rules.
        let with_w = over_rigid_analysis(&s, &w);
        let with_r = structural_analysis(&s, &r).over_rigid;
        if with_w.verdict == Verdict::OverRigid {
            assert_eq!(with_r.verdict, Verdict::OverRigid, "{f}");
        }
        assert!(with_w.dor <= with_r.dor, "{f}");
    }
    assert_eq!(
        differences,
        [
            "block_3d: X O b",
            "block_3d: Y O c",
            "block_3d: Z O a",
            // Equal radii make the two sides tangent to both circles parallel.
            "slot: side_low side_high",
        ]
    );
}

#[test]
fn generated_families_agree_with_the_rules() {
    // Bar frameworks at a generic witness: no hidden property, the two oracles agree on every
    // pair and triple, and so do the analyses.
    for s in [
        gcs_model::generate::laman(12, 7),
        gcs_model::generate::triangulated_sphere(10, 7),
        gcs_model::generate::rectangles(2),
    ] {
        let w = WitnessDor::find(&s, 1).unwrap();
        let r = RuleDor::for_system(&s);
        for set in small_sets(s.entities().len().min(14)) {
            assert_eq!(w.dor(&s, &set), r.dor(&s, &set), "{}: {set:?}", s.name());
        }
        assert_eq!(over_rigid_analysis(&s, &w).verdict, over_rigid_analysis(&s, &r).verdict);
    }
}
