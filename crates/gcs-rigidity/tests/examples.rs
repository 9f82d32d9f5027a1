//! The papers' worked examples and the CAD sketches of `data/`, with what the structural
//! methods must say of them (and where they are fooled).

use gcs_model::{EntityIdx, System};
use gcs_rigidity::{
    DorOracle, Network, Object, RuleDor, StructuralReport, Subsystem, Verdict, dense,
    minimal_dense, minimal_over_rigid, object_dor, over_rigid, structural_analysis,
};

use gcs_suite::load;

fn ids(system: &System, entities: &[EntityIdx]) -> Vec<String> {
    entities.iter().map(|e| system.entity(*e).id.clone()).collect()
}

fn constraint_ids(system: &System, s: &Subsystem) -> Vec<String> {
    s.constraints.iter().map(|c| system.constraint(*c).id.clone()).collect()
}

fn entity(system: &System, id: &str) -> EntityIdx {
    system.entity_by_id(id).unwrap()
}

fn analyse(system: &System) -> StructuralReport {
    structural_analysis(system, &RuleDor::for_system(system))
}

/// Invariants every report satisfies, whatever the system.
fn check_invariants(system: &System, r: &StructuralReport) {
    let oracle = RuleDor::for_system(system);
    for (a, is_dense) in [(&r.dense, true), (&r.over_rigid, false)] {
        match (&a.verdict, &a.subsystem) {
            (Verdict::OverRigid, Some(s)) => {
                // Fewer DOF than the whole system's comparison value, hence than its own DOR
                // (monotone) for Over-Rigid, than D for Dense.
                assert!(s.dof < a.dor as i64);
                // The constraints are exactly those the objects induce.
                let net = Network::new(system);
                let mut objects: Vec<Object> =
                    s.objects.iter().map(|e| Object::Entity(*e)).collect();
                if s.grounded {
                    objects.push(Object::Frame);
                }
                assert_eq!(&net.subsystem(&objects).unwrap(), s);
                if !is_dense {
                    assert!(s.dof < object_dor(system, &oracle, &objects) as i64);
                }
            }
            (Verdict::OverRigid, None) => panic!("over-rigid without a subsystem"),
            (Verdict::WellRigid, s) => {
                assert!(s.is_none());
                assert!(a.dof == a.dor as i64 || system.entities().is_empty());
            }
            (Verdict::UnderRigid, s) => {
                assert!(s.is_none());
                assert!(a.dof > a.dor as i64);
            }
        }
    }
    // D-M parts partition the constraints and the entities with DOF.
    let dm = &r.dm;
    let mut cs: Vec<_> = [&dm.over, &dm.well, &dm.under]
        .iter()
        .flat_map(|p| p.constraints.iter().copied())
        .collect();
    cs.sort();
    let n = cs.len();
    cs.dedup();
    assert_eq!(cs.len(), n, "no constraint in two parts");
    assert_eq!(n, system.constraints().iter().filter(|c| c.doc > 0).count());
    let mut es: Vec<_> =
        [&dm.over, &dm.well, &dm.under].iter().flat_map(|p| p.entities.iter().copied()).collect();
    es.sort();
    let n = es.len();
    es.dedup();
    assert_eq!(es.len(), n, "no entity in two parts");
    assert_eq!(n, system.entity_indices().filter(|e| system.entity_dof(*e) > 0).count());
}

#[test]
fn flow_fig1a_dense_is_fooled_by_parallel_lines() {
    let s = load("data/paper/flow_fig1a.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    // Dense: overload 3 on par_AB cannot be absorbed by A and B (4 DOF for 2 + 3).
    assert_eq!(r.dense.verdict, Verdict::OverRigid);
    let sub = r.dense.subsystem.as_ref().unwrap();
    assert_eq!(ids(&s, &sub.entities()), ["A", "B"]);
    assert_eq!(constraint_ids(&s, sub), ["par_AB", "d_AB"]);
    assert_eq!(sub.dof, 2);
    // Over-Rigid: DOR(A, B) = 2, the flow is saturated; the whole system is well-rigid.
    assert_eq!(r.over_rigid.verdict, Verdict::WellRigid);
    assert_eq!((r.over_rigid.dof, r.over_rigid.dor), (2, 2));
    assert_eq!(r.over_rigid.dor_source, "rules");
    // The paper's two calls, literally.
    let mut net = Network::new(&s);
    let par_ab = s.constraint_by_id("par_AB").unwrap();
    let found = net.distribute_on_constraint(par_ab, 3).unwrap().unwrap();
    assert_eq!(ids(&s, &found.objects), ["A", "B"]);
    let ab = [Object::Entity(entity(&s, "A")), Object::Entity(entity(&s, "B"))];
    let dor = RuleDor::for_system(&s);
    assert_eq!(dor.dor(&s, &[entity(&s, "A"), entity(&s, "B")]), 2);
    assert!(net.distribute(&ab, 2).unwrap().is_none());
    // D-M: 4 equations on 6 unknowns, nothing over-determined.
    assert!(r.dm.over.constraints.is_empty());
}

#[test]
fn flow_fig1b_over_rigid_finds_acdef() {
    let s = load("data/paper/flow_fig1b.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    assert_eq!(r.over_rigid.verdict, Verdict::OverRigid);
    let sub = r.over_rigid.subsystem.as_ref().unwrap();
    assert_eq!(ids(&s, &sub.objects), ["A", "C", "D", "E", "F"]);
    assert_eq!(sub.dof, 5); // 4 + 4·3 − (3·2 + 5)
    assert_eq!(
        constraint_ids(&s, sub),
        ["C_on_A", "D_on_A", "E_on_A", "d_CD", "d_DE", "d_CF", "d_DF", "d_EF"]
    );
    // It is minimal.
    let min = minimal_over_rigid(&s, &RuleDor::for_system(&s)).unwrap();
    assert_eq!(ids(&s, &min.objects), ["A", "C", "D", "E", "F"]);

    // The paper's calls: Distribute(S, 5, BC) absorbs; Distribute(S, 6, CEF) does not and
    // returns ACDEF.
    let dor = RuleDor::for_system(&s);
    let e = |x: &str| entity(&s, x);
    assert_eq!(dor.dor(&s, &[e("B"), e("C")]), 5);
    assert_eq!(dor.dor(&s, &[e("C"), e("E"), e("F")]), 6);
    assert_eq!(dor.dor(&s, &[e("C"), e("D"), e("E")]), 5, "C, D, E are collinear (on A)");
    let mut net = Network::new(&s);
    let o = |x: &str| Object::Entity(e(x));
    assert!(net.distribute(&[o("B"), o("C")], 5).unwrap().is_none());
    let found = net.distribute(&[o("C"), o("E"), o("F")], 6).unwrap().unwrap();
    assert_eq!(ids(&s, &found.objects), ["A", "C", "D", "E", "F"]);

    // Dense wrongly flags a point on the line or a segment (2 objects, DOF 5 < 6).
    assert_eq!(r.dense.verdict, Verdict::OverRigid);
    let d = r.dense.subsystem.as_ref().unwrap();
    assert_eq!(d.objects.len(), 2);
    assert_eq!(d.dof, 5);
    let names = ids(&s, &d.objects);
    let point_on_line = names.contains(&"A".to_owned());
    let bar = d.constraints.len() == 1
        && s.constraint(d.constraints[0]).kind == gcs_model::ConstraintKind::Distance;
    assert!(point_on_line || bar, "{names:?}");
    assert_eq!(names, ["A", "B"], "the first constraint, B_on_A, is overloaded first");
    // Every segment and every point on A is "over-rigid" for Hoffmann's Distribute.
    for c in s.constraint_indices() {
        let found = net.distribute_on_constraint(c, 6).unwrap().unwrap();
        assert!(found.dof < 6);
    }
}

#[test]
fn double_banana_fools_the_counts() {
    let s = load("data/paper/double_banana.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    // Over-Rigid (es_rigidity): no subsystem with DOF < DOR, DOF 24 − 18 = 6 = DOR: well-rigid,
    // although the witness shows the bananas turn about NS.
    assert_eq!(r.over_rigid.verdict, Verdict::WellRigid);
    assert_eq!((r.over_rigid.dof, r.over_rigid.dor), (6, 6));
    // Dense (s_rigidity) is fooled differently: every bar (two points, DOF 5 < 6) is over-rigid
    // for it, exactly as the flow paper says of fig. 1b's segments; without that, its count
    // (DOF 6 = D, every subsystem of 3 or more points with DOF ≥ 6) says well-rigid too.
    assert_eq!(r.dense.verdict, Verdict::OverRigid);
    let bar = r.dense.subsystem.as_ref().unwrap();
    assert_eq!((bar.objects.len(), bar.constraints.len(), bar.dof), (2, 1, 5));
    assert_eq!(r.dense.dof, 6);
    // No subsystem of ≥ 3 points is over-dense: overload 6 through R on every triangle.
    let mut net = Network::new(&s);
    let all: Vec<Object> = net.objects().to_vec();
    for i in 0..all.len() {
        for j in i + 1..all.len() {
            for k in j + 1..all.len() {
                assert!(net.distribute(&[all[i], all[j], all[k]], 6).unwrap().is_none());
            }
        }
    }
    // D-M: 18 equations, 24 unknowns, no over-determined part.
    assert!(r.dm.over.constraints.is_empty());
    assert_eq!(r.dm.matched, 18);
}

fn without_last_constraint(path: &str, last_id: &str) -> System {
    let full = format!("{}/../../data/{path}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&full).unwrap();
    let kept: Vec<&str> =
        text.lines().filter(|l| !l.contains(&format!("id: \"{last_id}\""))).collect();
    System::from_ron_str(&kept.join("\n"), None).unwrap()
}

#[test]
fn fig6_the_count_believes_the_last_distance() {
    let s = load("data/paper/fig6_harmonic.ron");
    let before = without_last_constraint("paper/fig6_harmonic.ron", "d_ay");
    assert_eq!(before.constraints().len() + 1, s.constraints().len());
    let r = analyse(&s);
    let r0 = analyse(&before);
    check_invariants(&s, &r);
    check_invariants(&before, &r0);
    // 18 unknowns; 12 DOC before, 13 after: the count says d_ay removes one DOF.
    assert_eq!(r0.over_rigid.dof, 6);
    assert_eq!(r.over_rigid.dof, 5);
    for rep in [&r, &r0] {
        assert_eq!(rep.over_rigid.dor, 3);
        assert_eq!(rep.over_rigid.verdict, Verdict::UnderRigid);
        assert_eq!(rep.dense.verdict, Verdict::UnderRigid);
        assert!(rep.dm.over.constraints.is_empty());
    }
    // Internal DOF by count: 2 with d_ay (the witness says 3: d_ay is redundant by a theorem).
    assert_eq!(r.over_rigid.dof - r.over_rigid.dor as i64, 2);
    // d_ay is matched (not over-determined) in D-M.
    let d_ay = s.constraint_by_id("d_ay").unwrap();
    assert!(r.dm.well.constraints.contains(&d_ay) || r.dm.under.constraints.contains(&d_ay));
}

#[test]
fn kite_is_over_rigid() {
    let s = load("data/paper/kite.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    for a in [&r.dense, &r.over_rigid] {
        assert_eq!(a.verdict, Verdict::OverRigid);
        let sub = a.subsystem.as_ref().unwrap();
        assert_eq!(ids(&s, &sub.objects), ["p1", "p2", "p3", "p4"]);
        assert_eq!(sub.dof, 2); // K4: 8 − 6 < 3
    }
    assert_eq!(minimal_dense(&s).unwrap().constraints.len(), 6);
    // D-M alone cannot see it: 6 equations on 8 unknowns, all matched.
    assert!(r.dm.over.constraints.is_empty());
    assert_eq!(r.dm.matched, 6);
}

#[test]
fn cad_sketches_with_absolute_constraints() {
    // Fully dimensioned rectangle: well-rigid (with the frame: 8 + 3 − 8 = 3 = DOR).
    let s = load("data/sketches/rectangle.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    assert_eq!(r.dense.verdict, Verdict::WellRigid);
    assert_eq!(r.over_rigid.verdict, Verdict::WellRigid);
    assert_eq!(r.dm.well.constraints.len(), s.constraints().len());
    assert!(r.dm.over.constraints.is_empty() && r.dm.under.constraints.is_empty());

    // Over-dimensioned: one DOC too many, the base flow is not saturated.
    let s = load("data/sketches/rectangle_overdimensioned.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    assert_eq!(r.dense.verdict, Verdict::OverRigid);
    assert_eq!(r.over_rigid.verdict, Verdict::OverRigid);
    // With the frame the whole sketch has 8 + 3 − 9 = 2 < 3 DOF; the subsystem found is the
    // rectangle tied to the frame: DOF 2.
    let sub = r.over_rigid.subsystem.as_ref().unwrap();
    assert!(sub.grounded);
    assert_eq!(sub.dof, 2);
    assert_eq!(sub.objects.len(), 4);
    assert!(!r.dm.over.constraints.is_empty());

    // Four-bar linkage: one DOF left.
    let s = load("data/sketches/four_bar.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    assert_eq!(r.over_rigid.verdict, Verdict::UnderRigid);
    assert_eq!(r.over_rigid.dof - r.over_rigid.dor as i64, 1);

    // The slot: circles, tangents, perpendiculars, a fixed origin: well-rigid.
    let s = load("data/sketches/slot.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    assert_eq!(r.over_rigid.verdict, Verdict::WellRigid);
    // Dense is fooled by a circle with its radius: DOF 3 − 1 = 2 < 3, though a circle admits
    // only 2 displacements (it is its centre, rotations about it leave it in place).
    assert_eq!(r.dense.verdict, Verdict::OverRigid);
    assert_eq!(ids(&s, &r.dense.subsystem.as_ref().unwrap().objects), ["c1"]);

    // The block corner: 21 DOF, 16 DOC < 6 + 16: the count sees the redundant diagonal.
    let s = load("data/sketches/block_3d.ron");
    let r = analyse(&s);
    check_invariants(&s, &r);
    assert_eq!(r.over_rigid.verdict, Verdict::OverRigid);
    let min = minimal_over_rigid(&s, &RuleDor::for_system(&s)).unwrap();
    assert!(min.dof < 6);
}

#[test]
fn every_example_runs() {
    for dir in ["paper", "sketches"] {
        let path = format!("{}/../../data/{dir}", env!("CARGO_MANIFEST_DIR"));
        let mut files: Vec<_> = std::fs::read_dir(&path)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "ron"))
            .collect();
        files.sort();
        assert!(!files.is_empty());
        for f in files {
            let text = std::fs::read_to_string(&f).unwrap();
            let s = System::from_ron_str(&text, f.to_str()).unwrap();
            let r = analyse(&s);
            check_invariants(&s, &r);
            // The plain calls find what the report found (unless the report fell back on the
            // whole system, Definitions 3-4 with S' = S), and the unbuilt oracle agrees.
            if let Some(found) = dense(&s) {
                assert_eq!(Some(found), r.dense.subsystem);
            }
            let plain = over_rigid(&s, &RuleDor::new());
            if plain.is_some() {
                assert_eq!(plain, r.over_rigid.subsystem);
            }
        }
    }
}
