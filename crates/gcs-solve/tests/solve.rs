//! The solver at the user's values: a sketch solves from a rough drawing keeping its
//! orientation; a redundant dimension that agrees is consistent, one that disagrees conflicts
//! with its spanning group; the solved model, analysed again, has the same verdict and a
//! drawing that satisfies it; every example of data/ solves.

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_model::System;
use gcs_solve::{SolveOptions, Status, solve, solved_system};

fn model(text: &str) -> System {
    System::from_ron_str(text, None).unwrap()
}

fn run(system: &System) -> gcs_solve::Solution {
    let analysis = analyze(system, &AnalysisOptions::default()).unwrap();
    solve(system, &analysis, &SolveOptions::default()).unwrap()
}

fn rectangle(width_top: &str) -> System {
    model(&gcs_suite::solver_rectangle(width_top))
}

fn point(system: &System, x: &[f64], id: &str) -> (f64, f64) {
    let layout = gcs_jacobian::Layout::new(system);
    let cols = layout.columns(system.entity_by_id(id).unwrap());
    (x[cols.start], x[cols.start + 1])
}

#[test]
fn a_consistent_redundant_dimension_is_not_a_conflict() {
    let s = rectangle("40");
    let sol = run(&s);
    assert_eq!(sol.status, Status::Solved, "{sol:?}");
    assert!(sol.max_residual <= 1e-9);
    let (x2, y2) = point(&s, &sol.x, "p2");
    let (x3, y3) = point(&s, &sol.x, "p3");
    assert!((x2 - 50.0).abs() < 1e-6 && (y2 - 5.0).abs() < 1e-6, "({x2}, {y2})");
    assert!((x3 - 50.0).abs() < 1e-6 && (y3 - 35.0).abs() < 1e-6, "({x3}, {y3})");
    assert!((sol.moved - 20.0).abs() < 1e-6, "the right side moved 20 to the left");
    let [r] = sol.redundant.as_slice() else { panic!("one redundant: {:?}", sol.redundant) };
    assert_eq!(s.constraint(r.constraint).id, "width_top");
    assert!(!r.conflicting && r.residual.abs() <= 1e-9);
}

/// Values written to four decimals (a kite whose sixth distance is √10 ≈ 3.1623) agree within
/// their written precision: consistent, not a conflict.
#[test]
fn values_agree_within_their_written_precision() {
    let s = gcs_suite::load("data/paper/kite.ron");
    let sol = run(&s);
    assert_eq!(sol.status, Status::Solved, "{:?}", sol.redundant);
    let [r] = sol.redundant.as_slice() else { panic!("{:?}", sol.redundant) };
    assert!(r.residual.abs() > 1e-7, "the values are not exactly consistent");
    assert!(r.residual.abs() <= r.allowance && !r.conflicting);
}

#[test]
fn a_disagreeing_redundant_dimension_conflicts_with_its_spanning_group() {
    let s = rectangle("48");
    let sol = run(&s);
    assert_eq!(sol.status, Status::Inconsistent);
    let [r] = sol.redundant.as_slice() else { panic!("{:?}", sol.redundant) };
    assert!(r.conflicting);
    // 8 mm off: the top measures 40 where it says 48.
    assert!((r.residual + 8.0).abs() < 1e-6, "{}", r.residual);
    let group: Vec<&str> = r.spanning_group.iter().map(|c| s.constraint(*c).id.as_str()).collect();
    assert_eq!(group, ["v_right", "v_left", "width"]);
}

/// A triangle by three distances, drawn roughly: it solves, and keeps the drawing's
/// orientation (the mirror image satisfies the distances as well).
#[test]
fn a_rough_drawing_solves_with_its_orientation() {
    for (ax, ay) in [(1.0, 3.5), (2.0, -3.0)] {
        let s = model(&format!(
            r#"System(name: "t", dim: 2, entities: [Point(id: "o", at: [0, 0]),
            Point(id: "b", at: [4.5, 0.3]), Point(id: "a", at: [{ax}, {ay}])],
            constraints: [Distance(id: "ob", a: "o", b: "b", value: 4),
            Distance(id: "oa", a: "o", b: "a", value: 3), Distance(id: "ab", a: "a", b: "b", value: 5)])"#
        ));
        let sol = run(&s);
        assert_eq!(sol.status, Status::Solved);
        let (o, a, b) = (point(&s, &sol.x, "o"), point(&s, &sol.x, "a"), point(&s, &sol.x, "b"));
        let d = |p: (f64, f64), q: (f64, f64)| ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt();
        assert!((d(o, b) - 4.0).abs() < 1e-8 && (d(o, a) - 3.0).abs() < 1e-8);
        assert!((d(a, b) - 5.0).abs() < 1e-8);
        let area = (b.0 - o.0) * (a.1 - o.1) - (b.1 - o.1) * (a.0 - o.0);
        assert_eq!(area > 0.0, ay > 0.0, "the drawing's orientation is kept");
    }
}

#[test]
fn the_solved_model_satisfies_itself_and_keeps_its_verdict() {
    let s = rectangle("40");
    let sol = run(&s);
    let solved = solved_system(&s, &sol);
    let again = analyze(&solved, &AnalysisOptions::default()).unwrap();
    let before = analyze(&s, &AnalysisOptions::default()).unwrap();
    assert_eq!((again.rank, again.dof), (before.rank, before.dof));
    assert_eq!(again.redundant.len(), before.redundant.len());
    assert_eq!(again.sketch.as_ref().map(|k| k.satisfied), Some(true), "{:?}", again.sketch);
    let back = System::from_ron_str(&solved.to_ron(), None).unwrap();
    assert_eq!(back.to_ron(), solved.to_ron());
}

/// Every example of data/ solves at its values (its drawings are solutions already, or
/// close), with no conflict unless the example says it has one.
#[test]
fn every_example_solves() {
    for file in gcs_suite::data_files() {
        let s = gcs_suite::load(&file);
        let analysis = analyze(&s, &AnalysisOptions::default()).unwrap();
        let sol = solve(&s, &analysis, &SolveOptions::default()).unwrap();
        assert_eq!(sol.status, Status::Solved, "{file}: {:?}", sol.redundant);
    }
}

/// A model whose witness is modular (the zoo: an arc's tangency at a point needs a square root,
/// and its drawing is incomplete) starts where its drawing is silent from the witness's
/// residues mapped into the drawing's size, not from residues of 2^61 − 1 taken as reals
/// (which made the model's size, and so every tolerance, about 1e18).
#[test]
fn a_modular_witness_is_no_real_start() {
    let s = gcs_suite::load("crates/gcs-model/tests/good/zoo2d.ron");
    let analysis = analyze(&s, &AnalysisOptions::default()).unwrap();
    assert_eq!(analysis.witness.source, gcs_jacobian::WitnessSource::Modular);
    let sol = solve(&s, &analysis, &SolveOptions::default()).unwrap();
    assert!(sol.scale < 1e3, "the model's size is the drawing's: {}", sol.scale);
    for r in &sol.redundant {
        assert!(r.allowance < 1.0, "{r:?}");
    }
}

fn ids(s: &System, c: &[gcs_model::ConstraintIdx]) -> Vec<String> {
    c.iter().map(|c| s.constraint(*c).id.clone()).collect()
}

/// 10, 10, 50 around a triangle has no real solution: reported as such with the triangle's
/// points and distances, not as a numerical failure; the point hanging off it by two more
/// distances is still placed, and a separate triangle is solved.
#[test]
fn a_broken_triangle_inequality_is_no_real_solution() {
    let s = model(
        r#"System(name: "t", dim: 2, entities: [Point(id: "a", at: [0, 0]),
        Point(id: "b", at: [40, 0]), Point(id: "c", at: [20, 8]),
        Point(id: "u", at: [100, 0]), Point(id: "v", at: [104, 0]), Point(id: "w", at: [100, 3])],
        constraints: [Distance(id: "ab", a: "a", b: "b", value: 50),
        Distance(id: "bc", a: "b", b: "c", value: 10), Distance(id: "ca", a: "c", b: "a", value: 10),
        Distance(id: "uv", a: "u", b: "v", value: 4), Distance(id: "vw", a: "v", b: "w", value: 5),
        Distance(id: "wu", a: "w", b: "u", value: 3)])"#,
    );
    let sol = run(&s);
    assert_eq!(sol.status, Status::Inconsistent, "{sol:?}");
    let [part] = sol.no_solution.as_slice() else { panic!("{:?}", sol.no_solution) };
    let names: Vec<&str> = part.entities.iter().map(|e| s.entity(*e).id.as_str()).collect();
    assert_eq!(names, ["a", "b", "c"]);
    assert_eq!(ids(&s, &part.constraints), ["ab", "bc", "ca"]);
    assert!(sol.max_residual <= 1e-9, "the rest is solved: {}", sol.max_residual);
    let (u, v, w) = (point(&s, &sol.x, "u"), point(&s, &sol.x, "v"), point(&s, &sol.x, "w"));
    let d = |p: (f64, f64), q: (f64, f64)| ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt();
    assert!((d(u, v) - 4.0).abs() < 1e-9 && (d(v, w) - 5.0).abs() < 1e-9);
    let failed: Vec<_> = sol.plan.iter().filter(|p| p.chosen.is_none()).collect();
    assert_eq!(failed.len(), 1);
    assert_eq!(failed[0].candidates, 0);
}

/// Three lines at pairwise angles 60, 60 and 70 degrees: the third angle is redundant with the
/// other two and cannot hold — a conflict, measured, not a numerical failure.
#[test]
fn three_lines_at_60_60_70_conflict() {
    let s = model(
        r#"System(name: "l", dim: 2, entities: [Line(id: "l1", at: [[0, 0], [10, 0]]),
        Line(id: "l2", at: [[0, 0], [5, 8]]), Line(id: "l3", at: [[0, 0], [-5, 8]])],
        constraints: [Angle(id: "a12", a: "l1", b: "l2", value: 60),
        Angle(id: "a23", a: "l2", b: "l3", value: 60), Angle(id: "a13", a: "l1", b: "l3", value: 70)])"#,
    );
    let sol = run(&s);
    assert_eq!(sol.status, Status::Inconsistent, "{sol:?}");
    let [r] = sol.redundant.as_slice() else { panic!("{:?}", sol.redundant) };
    assert!(r.conflicting && r.residual.abs() > 1.0, "{r:?}");
    assert_eq!(r.spanning_group.len(), 2);
}

/// Random Laman sketches built from a known realization, drawn with 20% jitter (no triangle
/// turned over): most solve (a realization where every step finds its point), and every one
/// that solves keeps the drawing's orientation of every triangle; none is claimed to have no
/// real solution (its distances have one). The points placed by two distances are placed in
/// closed form. Where the solve from the drawing does not hold, the autosolve searches the
/// core's and the closed-form steps' candidates: 10 of the 12 solve (seed 5's redundant
/// distance agrees with none of its 256 realizations within its allowance — its rounded
/// values amplified by a flat triangle —, seed 9's last core node has more paths than the
/// search tracks).
#[test]
fn jittered_laman_sketches_solve_keeping_their_orientation() {
    let (mut closed, mut solved) = (0, 0);
    for seed in 1..=12 {
        let (s, _) = gcs_model::generate::laman_drawn(16, seed, 0.2);
        let sol = run(&s);
        assert!(sol.no_solution.is_empty(), "seed {seed}: {:?}", sol.no_solution);
        if sol.status == Status::Solved {
            solved += 1;
            let (kept, all) = gcs_solve::orientation_kept(&s, &sol.x);
            assert_eq!(kept, all, "seed {seed}: every triangle as drawn");
        }
        closed += sol.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).count();
    }
    assert!(solved >= 10, "{solved} of 12 solved");
    assert!(closed > 12, "closed-form steps taken: {closed}");
}

/// A large irreducible core from a rough drawing: 1000 points (about 600 of them in one
/// rigid core that no closed-form step peels) drawn 5% off. Levenberg–Marquardt straight from
/// the drawing with Nielsen's damping (the crate's `newton` module) solves it; before, the
/// capped damped steps stopped at 8e-10 and the homotopy stalled at a fold: `failed`, the
/// drawing returned with a residual of 0.75 (BENCHMARKS.md, "Large Laman cores").
#[test]
fn a_thousand_point_laman_core_solves_from_a_rough_drawing() {
    let (s, _) = gcs_model::generate::laman_drawn(1000, 1, 0.05);
    // The analysis as `examples/drawn.rs` runs it: no clusters, which the solve does not need.
    let options = AnalysisOptions {
        clusters: false,
        sketch: false,
        global_rigidity: false,
        ..AnalysisOptions::default()
    };
    let analysis = analyze(&s, &options).unwrap();
    let sol = solve(&s, &analysis, &SolveOptions::default()).unwrap();
    assert_eq!(sol.status, Status::Solved, "worst {:?}", sol.worst);
    assert!(sol.max_residual <= 1e-9, "{}", sol.max_residual);
    let core = (sol.plan.iter().filter(|p| p.method == gcs_solve::Method::Newton))
        .map(|p| p.entities.len())
        .max();
    assert!(core.is_some_and(|c| c > 500), "the core: {core:?} points");
    let (kept, all) = gcs_solve::orientation_kept(&s, &sol.x);
    assert!(all > 0 && kept == all, "{kept} of {all} triangles as drawn");
    let [r] = sol.redundant.as_slice() else { panic!("{:?}", sol.redundant) };
    assert!(!r.conflicting, "the redundant distance at its true value: {r:?}");
}

/// The redundant distance of a Laman sketch (`extra`) at its true value is consistent; 10% off
/// it conflicts, off by 10% of its value, and its spanning group with it is a rigidity circuit
/// (2·points − 2 distances on the points they join).
#[test]
fn a_redundant_distance_off_by_ten_percent_conflicts_with_its_circuit() {
    for seed in [3, 4] {
        let (s, _) = gcs_model::generate::laman_drawn(12, seed, 0.05);
        let sol = run(&s);
        let [r] = sol.redundant.as_slice() else { panic!("{:?}", sol.redundant) };
        assert_eq!(s.constraint(r.constraint).id, "extra");
        assert!(!r.conflicting, "at its true value: {r:?}");
        let value = s.constraint(r.constraint).value.clone().unwrap();
        let v = num_traits::ToPrimitive::to_f64(&value).unwrap();
        // The same model with extra's value 10% larger.
        let text = s.to_ron();
        let at = text.find("id: \"extra\"").unwrap();
        let from = at + text[at..].find("value: ").unwrap() + "value: ".len();
        let to = from + text[from..].find(|c: char| c == ')' || c == ',').unwrap();
        let bad = model(&format!("{}{:.4}{}", &text[..from], 1.1 * v, &text[to..]));
        let sol = run(&bad);
        assert_eq!(sol.status, Status::Inconsistent);
        let [r] = sol.redundant.as_slice() else { panic!("{:?}", sol.redundant) };
        assert!(r.conflicting && (r.residual + 0.1 * v).abs() < 1e-3 * v, "{r:?}");
        let mut points = std::collections::BTreeSet::new();
        for &c in r.spanning_group.iter().chain([&r.constraint]) {
            points.extend(bad.constraint_base_entities(c));
        }
        assert_eq!(r.spanning_group.len() + 1, 2 * points.len() - 2, "a circuit");
    }
}

/// A triangle `abc` on its base `ab`, and `d` hung on `b` and `c`: two closed-form steps.
fn hung_triangle() -> System {
    model(
        r#"System(dim: 2,
  entities: [Point(id: "a", at: [0, 0]), Point(id: "b", at: [4, 0]), Point(id: "c", at: [2, 3]),
             Point(id: "d", at: [5, 3])],
  constraints: [Distance(id: "ab", a: "a", b: "b", value: 4), Distance(id: "ac", a: "a", b: "c", value: 3.5),
                Distance(id: "bc", a: "b", b: "c", value: 3.5), Distance(id: "bd", a: "b", b: "d", value: 3),
                Distance(id: "cd", a: "c", b: "d", value: 3)])"#,
    )
}

fn solve_with(system: &System, options: &SolveOptions) -> gcs_solve::Solution {
    let analysis = analyze(system, &AnalysisOptions::default()).unwrap();
    solve(system, &analysis, options).unwrap()
}

/// Every distance of `system` holds at `x` to 1e-9.
fn distances_hold(system: &System, x: &[f64]) -> bool {
    system.constraint_indices().all(|c| {
        let k = system.constraint(c);
        let ends = system.constraint_base_entities(c);
        let value = num_traits::ToPrimitive::to_f64(k.value.as_ref().unwrap()).unwrap();
        let (p, q) = (
            point(system, x, &system.entity(ends[0]).id),
            point(system, x, &system.entity(ends[1]).id),
        );
        ((p.0 - q.0).hypot(p.1 - q.1) - value).abs() < 1e-9
    })
}

/// `--all`: two closed-form steps give four realizations with the base as solved, each
/// satisfying every constraint, all different, the drawn one among them; a limit truncates.
#[test]
fn every_realization_of_the_closed_form_steps_is_listed() {
    let s = hung_triangle();
    let sol = solve_with(&s, &SolveOptions { all: Some(64), ..SolveOptions::default() });
    assert_eq!(sol.status, Status::Solved);
    let all = sol.solutions.as_ref().unwrap();
    assert_eq!(all.len(), 4, "{all:?}");
    assert!(!sol.truncated);
    for (i, x) in all.iter().enumerate() {
        assert!(distances_hold(&s, x), "realization {i}: {x:?}");
        for y in &all[..i] {
            assert!(x.iter().zip(y).any(|(u, v)| (u - v).abs() > 1e-6), "two alike: {x:?}");
        }
    }
    assert!(all.contains(&sol.x), "the realization the drawing shows is one of them");
    // Closed-form steps are complete; the core of one distance too.
    assert!(sol.plan.iter().all(|p| p.complete), "{:?}", sol.plan);
    let few = solve_with(&s, &SolveOptions { all: Some(3), ..SolveOptions::default() });
    assert_eq!((few.solutions.unwrap().len(), few.truncated), (3, true));
    // Without --all: none listed.
    assert!(run(&s).solutions.is_none());
}

/// Two triangles sharing an edge (the kite without its diagonal): each apex on either side of
/// the shared edge, 4 realizations, all distinct and satisfying every distance.
#[test]
fn two_triangles_sharing_an_edge_have_four_realizations() {
    let s = framework(
        &[[0.0, 0.0], [5.0, 0.5], [2.0, 3.0], [3.0, -2.5]],
        &[(0, 1), (0, 2), (1, 2), (0, 3), (1, 3)],
        "",
    );
    let sol = solve_with(&s, &SolveOptions { all: Some(64), ..SolveOptions::default() });
    let all = sol.solutions.unwrap();
    assert_eq!((all.len(), sol.truncated), (4, false));
    for (i, x) in all.iter().enumerate() {
        assert!(distances_hold(&s, x), "realization {i}");
        assert!(all[..i].iter().all(|y| x.iter().zip(y).any(|(u, v)| (u - v).abs() > 1e-6)));
    }
}

/// The kite of the witness paper: its redundant sixth distance prunes the realizations whose
/// two triangles are folded against each other; two remain (one the mirror of the other).
#[test]
fn a_consistent_redundant_constraint_prunes_the_realizations() {
    let s = gcs_suite::load("data/paper/kite.ron");
    let sol = solve_with(&s, &SolveOptions { all: Some(64), ..SolveOptions::default() });
    let closed = sol.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).count();
    assert_eq!(closed, 2, "{:?}", sol.plan);
    let all = sol.solutions.unwrap();
    assert_eq!(all.len(), 2, "{all:?}");
    let [r] = sol.redundant.as_slice() else { panic!() };
    let c6 = s.constraint(r.constraint);
    let ends = s.constraint_base_entities(r.constraint);
    let value = num_traits::ToPrimitive::to_f64(c6.value.as_ref().unwrap()).unwrap();
    for x in &all {
        let (p, q) = (point(&s, x, &s.entity(ends[0]).id), point(&s, x, &s.entity(ends[1]).id));
        assert!(((p.0 - q.0).hypot(p.1 - q.1) - value).abs() <= r.allowance, "{x:?}");
    }
}

/// `--choose STEP=K` fixes a closed-form step's side against the drawing: the solution and
/// every listed realization have it; a step that is not in closed form is refused.
#[test]
fn a_fixed_choice_overrides_the_drawing() {
    let s = hung_triangle();
    let drawn = run(&s);
    assert!(point(&s, &drawn.x, "c").1 > 0.0, "c is drawn above ab");
    // Step 1 of the plan places c (step 0 is the core, ab); candidate 1 is to the right of a→b.
    assert_eq!(drawn.plan[1].entities, vec![s.entity_by_id("c").unwrap()]);
    let options = SolveOptions { choose: vec![(1, 1)], all: Some(64), ..SolveOptions::default() };
    let sol = solve_with(&s, &options);
    assert_eq!(sol.status, Status::Solved);
    assert!(point(&s, &sol.x, "c").1 < 0.0);
    assert!(sol.plan[1].fixed && !sol.plan[2].fixed);
    let all = sol.solutions.unwrap();
    assert_eq!(all.len(), 2);
    assert!(all.iter().all(|x| point(&s, x, "c").1 < 0.0 && distances_hold(&s, x)));
    let analysis = analyze(&s, &AnalysisOptions::default()).unwrap();
    for bad in [(0, 1), (3, 0), (1, 2)] {
        let options = SolveOptions { choose: vec![bad], ..SolveOptions::default() };
        let err = solve(&s, &analysis, &options).unwrap_err();
        assert!(matches!(err, gcs_solve::SolveError::Choice { .. }), "{bad:?}: {err}");
    }
}

/// A strip of 23 points (21 closed-form steps: 2^21 combinations) with a redundant distance
/// from its first point to its last, checked only once every step is placed: the enumeration
/// stops at its budget of partial placements and says so, with only realizations where the
/// redundant distance holds.
#[test]
fn the_enumeration_stops_at_its_budget() {
    let n = 23;
    let mut entities = Vec::new();
    let mut constraints = Vec::new();
    for k in 0..n {
        entities.push(format!("Point(id: \"p{k}\", at: [{}, {}])", 3 * k, 4 * (k % 2)));
        if k >= 1 {
            constraints
                .push(format!("Distance(id: \"a{k}\", a: \"p{}\", b: \"p{k}\", value: 5)", k - 1));
        }
        if k >= 2 {
            constraints
                .push(format!("Distance(id: \"b{k}\", a: \"p{}\", b: \"p{k}\", value: 6)", k - 2));
        }
    }
    constraints.push(format!(
        "Distance(id: \"extra\", a: \"p0\", b: \"p{}\", value: {})",
        n - 1,
        3 * (n - 1)
    ));
    let s = model(&format!(
        "System(dim: 2, entities: [{}], constraints: [{}])",
        entities.join(", "),
        constraints.join(", ")
    ));
    let sol = solve_with(&s, &SolveOptions { all: Some(64), ..SolveOptions::default() });
    assert_eq!(sol.status, Status::Solved, "{:?}", sol.redundant);
    let [r] = sol.redundant.as_slice() else { panic!("{:?}", sol.redundant) };
    assert_eq!(s.constraint(r.constraint).id, "extra");
    let closed = sol.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).count();
    assert_eq!(closed, n - 2, "{:?}", sol.plan);
    assert!(sol.truncated, "2^21 combinations exceed the budget");
    let all = sol.solutions.unwrap();
    assert!(all.len() <= 2, "{}", all.len());
    for x in &all {
        assert!(distances_hold(&s, x));
    }
}

/// An articulated chain of 8 triangles, flexible: the peeling places 12 points in closed form
/// and leaves the others where the drawing has them (no core). Every listed realization
/// satisfies every distance, they are distinct, the solve's own is among them; the apexes that
/// no other step depends on double the count each, and combinations whose circles do not meet
/// are no realization.
#[test]
fn a_flexible_chain_lists_its_realizations_given_its_free_points() {
    let s = gcs_model::generate::triangle_chain(8, 3);
    let sol = solve_with(&s, &SolveOptions { all: Some(5000), ..SolveOptions::default() });
    assert_eq!(sol.status, Status::Solved);
    let steps: Vec<_> =
        sol.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).collect();
    assert_eq!((steps.len(), sol.plan.len()), (12, 12));
    assert!(steps.iter().all(|p| p.candidates == 2 && p.complete));
    let all = sol.solutions.unwrap();
    assert!(!sol.truncated);
    assert!(all.len() >= 1 << 4 && all.len() <= 1 << 12, "{}", all.len());
    assert!(all.len() % 16 == 0, "four leaf apexes double the count: {}", all.len());
    assert!(all.contains(&sol.x));
    for (i, x) in all.iter().enumerate() {
        assert!(distances_hold(&s, x), "realization {i}");
        assert!(all[..i].iter().all(|y| x.iter().zip(y).any(|(u, v)| (u - v).abs() > 1e-9)));
    }
    let few = solve_with(&s, &SolveOptions { all: Some(10), ..SolveOptions::default() });
    assert_eq!((few.solutions.unwrap().len(), few.truncated), (10, true));
}

/// A rigid chain of 8 triangles, each on an edge of the one before (a triangulated strip of 10
/// points): 8 closed-form steps of 2 candidates each — every flip realizable, since each new
/// triangle's base is itself a distance — so exactly 2^8 realizations, all distinct.
#[test]
fn a_chain_of_eight_triangles_has_two_to_the_eight_realizations() {
    let s = gcs_model::generate::strip(5, 2);
    assert_eq!(s.constraints().len(), 2 * 10 - 3);
    let sol = solve_with(&s, &SolveOptions { all: Some(5000), ..SolveOptions::default() });
    assert_eq!(sol.status, Status::Solved);
    let steps: Vec<_> =
        sol.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).collect();
    assert_eq!(steps.len(), 8);
    assert!(steps.iter().all(|p| p.candidates == 2 && p.complete));
    let all = sol.solutions.unwrap();
    assert_eq!((all.len(), sol.truncated), (256, false));
    let choices = sol.solution_choices.unwrap();
    let mut distinct = choices.clone();
    distinct.sort();
    distinct.dedup();
    assert_eq!(distinct.len(), 256, "every combination of the 8 choices once");
    for (i, x) in all.iter().enumerate() {
        assert!(distances_hold(&s, x), "realization {i}");
    }
}

/// The issue's small counts: a triangle has 2 realizations (its apex on either side of its
/// base); one dimensioned 10, 10, 50 has none, and says so with every step complete.
#[test]
fn a_triangle_has_two_realizations_and_an_impossible_one_none() {
    let triangle = |c: &str| {
        model(&format!(
            r#"System(dim: 2,
  entities: [Point(id: "a", at: [0, 0]), Point(id: "b", at: [40, 0]), Point(id: "c", at: [20, 8])],
  constraints: [Distance(id: "ab", a: "a", b: "b", value: 40), Distance(id: "bc", a: "b", b: "c", value: {c}),
                Distance(id: "ca", a: "c", b: "a", value: 25)])"#
        ))
    };
    let all = SolveOptions { all: Some(64), ..SolveOptions::default() };
    let s = triangle("25");
    let sol = solve_with(&s, &all);
    assert_eq!(sol.status, Status::Solved);
    let found = sol.solutions.unwrap();
    assert_eq!(found.len(), 2);
    assert!(found.iter().all(|x| distances_hold(&s, x)));
    assert!(point(&s, &found[0], "c").1 * point(&s, &found[1], "c").1 < 0.0, "mirror images");
    let impossible = triangle("10");
    let sol = solve_with(&impossible, &all);
    assert_eq!(sol.status, Status::Inconsistent);
    assert_eq!(sol.solutions.unwrap().len(), 0);
    assert!(!sol.truncated && sol.plan.iter().all(|p| p.complete), "{:?}", sol.plan);
}

/// A pinned point (`Fix`), a point at a distance from it on a horizontal segment, and a point
/// given by `DistanceX` and `DistanceY` from the first: each placed in closed form (a point;
/// a circle and a line, on the drawing's side; two lines), with nothing left to the numerics.
fn pinned(side: f64) -> System {
    model(&format!(
        r#"System(name: "pinned", dim: 2,
            entities: [
                Point(id: "o", at: [1, 2]),
                Point(id: "p", at: [{}, 2.5]),
                Segment(id: "op", from: "o", to: "p"),
                Point(id: "q", at: [35, 21]),
            ],
            constraints: [
                Fix(id: "pin", a: "o"),
                Horizontal(id: "flat", a: "op"),
                Distance(id: "len", a: "o", b: "p", value: 10),
                DistanceX(id: "dx", a: "o", b: "q", value: 30),
                DistanceY(id: "dy", a: "o", b: "q", value: 20),
            ])"#,
        1.0 + side * 9.0
    ))
}

#[test]
fn pinned_points_and_lines_are_placed_in_closed_form() {
    for (side, x) in [(1.0, 11.0), (-1.0, -9.0)] {
        let s = pinned(side);
        let sol = run(&s);
        assert_eq!(sol.status, Status::Solved, "{sol:?}");
        assert!(
            sol.plan.iter().all(|p| p.method == gcs_solve::Method::ClosedForm),
            "{:?}",
            sol.plan
        );
        assert_eq!(sol.plan.len(), 3, "o, then p and q: {:?}", sol.plan);
        let candidates: Vec<usize> = sol.plan.iter().map(|p| p.candidates).collect();
        assert_eq!(candidates.iter().filter(|&&c| c == 2).count(), 1, "{candidates:?}");
        assert_eq!(point(&s, &sol.x, "o"), (1.0, 2.0));
        let (px, py) = point(&s, &sol.x, "p");
        assert!((px - x).abs() < 1e-12 && (py - 2.0).abs() < 1e-12, "the drawn side: ({px}, {py})");
        let (qx, qy) = point(&s, &sol.x, "q");
        assert!((qx - 31.0).abs() < 1e-12 && (qy - 22.0).abs() < 1e-12, "({qx}, {qy})");
    }
    // Both sides are realizations.
    let s = pinned(1.0);
    let all = solve_with(&s, &SolveOptions { all: Some(10), ..SolveOptions::default() });
    assert_eq!(all.solutions.as_ref().map(Vec::len), Some(2), "{:?}", all.solutions);
}

/// A point on a segment's line at a distance from a point off it: the circle and the line meet
/// twice; the drawing picks one, `--choose` the other; with the distance too short they do
/// not meet and the solve does not claim success.
#[test]
fn a_point_by_a_distance_and_a_line() {
    let text = |d: &str| {
        format!(
            r#"System(name: "on_line", dim: 2,
            entities: [
                Point(id: "a", at: [0, 0]), Point(id: "b", at: [10, 0]), Point(id: "c", at: [3, 4]),
                Segment(id: "ab", from: "a", to: "b"),
                Point(id: "p", at: [6.5, 0.3]),
            ],
            constraints: [
                Fix(id: "fa", a: "a"), Fix(id: "fb", a: "b"), Fix(id: "fc", a: "c"),
                Incident(id: "on", a: "p", b: "ab"),
                Distance(id: "cp", a: "c", b: "p", value: {d}),
            ])"#
        )
    };
    let s = model(&text("5"));
    let sol = run(&s);
    assert_eq!(sol.status, Status::Solved, "{sol:?}");
    let (px, py) = point(&s, &sol.x, "p");
    assert!((px - 6.0).abs() < 1e-12 && py.abs() < 1e-12, "the drawn one, (6, 0): ({px}, {py})");
    let step = sol.plan.iter().position(|p| p.candidates == 2).expect("a step with two candidates");
    let chosen = sol.plan[step].chosen.expect("chosen");
    let other = solve_with(
        &s,
        &SolveOptions { choose: vec![(step, 1 - chosen)], ..SolveOptions::default() },
    );
    let (qx, qy) = point(&s, &other.x, "p");
    assert!(qx.abs() < 1e-12 && qy.abs() < 1e-12, "the other one, (0, 0): ({qx}, {qy})");
    let short = model(&text("3"));
    let sol = run(&short);
    assert_ne!(sol.status, Status::Solved, "a circle of radius 3 about (3, 4) misses y = 0");
}

/// A ratio of lengths is a dimension the solver meets: edited from 2 to 4, the right side of
/// `data/sketches/ratios.ron` shrinks to 2, and the corner above it follows (equal heights,
/// equal slopes).
#[test]
fn an_edited_ratio_moves_the_sketch() {
    let text =
        std::fs::read_to_string(gcs_suite::workspace_root().join("data/sketches/ratios.ron"))
            .unwrap()
            .replace("value: 2)", "value: 4)");
    let s = System::from_ron_str(&text, None).unwrap();
    let analysis = analyze(&s, &AnalysisOptions::default()).unwrap();
    let sol = solve(&s, &analysis, &SolveOptions::default()).unwrap();
    assert_eq!(sol.status, gcs_solve::Status::Solved);
    let layout = gcs_jacobian::Layout::new(&s);
    let at = |id: &str| sol.x[layout.columns(s.entity_by_id(id).unwrap())].to_vec();
    let near = |p: Vec<f64>, q: [f64; 2]| (p[0] - q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9;
    assert!(near(at("p3"), [8.0, 2.0]), "{:?}", at("p3"));
    assert!(near(at("p4"), [0.0, 2.0]), "{:?}", at("p4"));
}

/// The triangular prism (a core no closed-form step places) with a point hung on it by two
/// distances: `--all` lists the prism's real realizations, found by homotopy continuation
/// among its 24 complex ones (Capco et al. 2018), each with the hung point on either side.
#[test]
fn the_core_realizations_come_from_homotopy_continuation() {
    let points: [[f64; 2]; 7] =
        [[0.0, 0.0], [3.1, 0.4], [1.2, 2.9], [4.3, 3.3], [-0.7, 4.1], [2.6, 5.7], [5.9, 1.3]];
    let edges =
        [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5), (6, 1), (6, 3)];
    let s = framework(&points, &edges, "");
    let sol = solve_with(&s, &SolveOptions { all: Some(1000), ..SolveOptions::default() });
    assert_eq!(sol.status, Status::Solved);
    // The prism's DR-plan: its two triangles, then their assembly (24 complex realizations
    // in all: 2 × 2 × 6).
    let root = &sol.plan[2];
    assert_eq!(root.children, vec![0, 1]);
    let paths = root.paths.expect("the prism is enumerated");
    assert_eq!((paths.paths, paths.finite, paths.failed), (6, 6, 0), "{paths:?}");
    for leaf in &sol.plan[..2] {
        let p = leaf.paths.expect("a triangle is enumerated");
        assert_eq!((p.paths, p.finite, leaf.candidates), (2, 2, 2), "{leaf:?}");
    }
    assert_eq!(root.candidates, paths.real);
    assert!(root.complete && root.candidates >= 2 && root.candidates % 2 == 0, "{root:?}");
    let all = sol.solutions.as_ref().unwrap();
    let cores = sol.core_choices.as_ref().unwrap();
    assert_eq!(all.len(), cores.len());
    assert_eq!(sol.node_choices.as_ref().map(|n| n[0].clone()), Some(vec![0, 0, 0]));
    for (i, x) in all.iter().enumerate() {
        assert!(distances_hold(&s, x), "realization {i}: {x:?}");
    }
    // In the order of the nodes' candidates, the drawing's first; each with the hung point on
    // both sides, or none where its two circles do not meet.
    let nodes = sol.node_choices.as_ref().unwrap();
    assert_eq!(cores[0], 0);
    assert!(nodes.iter().zip(cores).all(|(n, c)| n[2] == *c));
    let mut distinct = nodes.clone();
    distinct.dedup();
    for n in &distinct {
        assert!(matches!(nodes.iter().filter(|&m| m == n).count(), 0 | 2), "{nodes:?}");
    }
    assert!(distinct.len() > 4, "{nodes:?}");
    assert!(all.contains(&sol.x), "the realization the drawing shows is one of them");
    assert!(!sol.truncated);
    // Choosing the assembly's last candidate (step 2) on which the hung point has a place, the
    // triangles as drawn: the solve lands on it, and the rest is placed as the drawing shows.
    let k = nodes.iter().filter(|n| n[..2] == [0, 0]).map(|n| n[2]).max().unwrap();
    assert!(k > 0, "{nodes:?}");
    let chosen = solve_with(&s, &SolveOptions { choose: vec![(2, k)], ..SolveOptions::default() });
    assert_eq!(chosen.status, Status::Solved);
    assert_eq!((chosen.plan[2].chosen, chosen.plan[2].fixed), (Some(k), true));
    assert!(distances_hold(&s, &chosen.x));
    let same_core =
        |x: &[f64]| x[..12].iter().zip(&chosen.x[..12]).all(|(a, b)| (a - b).abs() < 1e-9);
    assert!(all.iter().zip(nodes).any(|(x, n)| n == &[0, 0, k] && same_core(x)));
    let listed = solve_with(
        &s,
        &SolveOptions { all: Some(100), choose: vec![(2, k)], ..SolveOptions::default() },
    );
    assert!(listed.node_choices.unwrap().iter().all(|n| n[2] == k));
    // A realization the node does not have is an error.
    let analysis = analyze(&s, &AnalysisOptions::default()).unwrap();
    let beyond = SolveOptions { choose: vec![(2, root.candidates)], ..SolveOptions::default() };
    assert!(matches!(
        solve(&s, &analysis, &beyond),
        Err(gcs_solve::SolveError::Choice { step: 2, .. })
    ));
}

/// The prism of `the_core_realizations_come_from_homotopy_continuation` (its core splits into
/// two triangles and their assembly), with `extra` appended to its constraints.
fn prism_with(extra: &str) -> System {
    let points: [[f64; 2]; 6] =
        [[0.0, 0.0], [3.1, 0.4], [1.2, 2.9], [4.3, 3.3], [-0.7, 4.1], [2.6, 5.7]];
    let edges = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)];
    framework(&points, &edges, extra)
}

/// Points `p0…` drawn at `points`, a distance `d<a><b>` per edge at its drawn length, then
/// `extra` (RON items) in the constraints list.
fn framework(points: &[[f64; 2]], edges: &[(usize, usize)], extra: &str) -> System {
    let mut text = String::from("System(dim: 2, entities: [");
    for (i, p) in points.iter().enumerate() {
        text += &format!("Point(id: \"p{i}\", at: [{}, {}]),", p[0], p[1]);
    }
    text += "], constraints: [";
    for &(a, b) in edges {
        let d = (points[a][0] - points[b][0]).hypot(points[a][1] - points[b][1]);
        text += &format!("Distance(id: \"d{a}{b}\", a: \"p{a}\", b: \"p{b}\", value: {d}),");
    }
    text += extra;
    text += "])";
    model(&text)
}

/// An orientation condition on a closed-form step's point: the drawing shows `c` to the left
/// of `a → b`, the condition wants it to the right; the solve takes the other candidate, and
/// `--all` lists only the realizations that turn its way.
#[test]
fn an_orientation_condition_picks_the_side_of_a_closed_form_point() {
    let text = |orientation: &str| {
        format!(
            r#"System(dim: 2, entities: [Point(id: "a", at: [0, 0]), Point(id: "b", at: [4, 0]),
                Point(id: "c", at: [2, 3]), Point(id: "d", at: [6, 3])],
            constraints: [Distance(id: "ab", a: "a", b: "b", value: 4),
                Distance(id: "ac", a: "a", b: "c", value: 3.6055513),
                Distance(id: "bc", a: "b", b: "c", value: 3.6055513),
                Distance(id: "bd", a: "b", b: "d", value: 3.6055513),
                Distance(id: "cd", a: "c", b: "d", value: 4), {orientation}])"#
        )
    };
    let drawn = model(&text(""));
    let s = model(&text(r#"Orientation(id: "below", points: ["a", "b", "c"], sign: -1)"#));
    let sol = run(&s);
    assert_eq!(sol.status, Status::Solved, "{:?}", sol.turned);
    assert!(point(&s, &sol.x, "c").1 < 0.0, "c below the line: {:?}", point(&s, &sol.x, "c"));
    assert!(distances_hold(&s, &sol.x));
    // Every listed realization turns its way, and they are exactly those of the sketch
    // without the condition that do.
    let all = SolveOptions { all: Some(64), ..SolveOptions::default() };
    let with = solve_with(&s, &all).solutions.unwrap();
    let without = solve_with(&drawn, &SolveOptions { all: Some(64), ..SolveOptions::default() })
        .solutions
        .unwrap();
    let below = |x: &Vec<f64>| point(&s, x, "c").1 < 0.0;
    assert_eq!(with.len(), without.iter().filter(|x| below(x)).count());
    assert!(with.len() >= 1 && with.len() < without.len(), "{} of {}", with.len(), without.len());
    assert!(with.iter().all(below));
    // The analysis counts no orientation: the DOF are those of the sketch without it.
    let (a, b) = (
        analyze(&s, &AnalysisOptions::default()).unwrap(),
        analyze(&drawn, &AnalysisOptions::default()).unwrap(),
    );
    assert_eq!((a.dof, a.rank), (b.dof, b.rank));
}

/// An orientation condition on the core: the prism's first triangle turned against the
/// drawing. The solved core breaks it, so the core's DR-plan is searched: the triangle's
/// candidates are pruned to the mirrored one, and the assembly is solved for it — the
/// drawing's chirality overruled where the user asked, every distance holding.
#[test]
fn an_orientation_condition_on_the_core_forces_another_child_choice() {
    let plain = prism_with("");
    let turned = prism_with(r#"Orientation(id: "o", points: ["p0", "p1", "p2"], sign: -1),"#);
    let sol = run(&turned);
    assert_eq!(sol.status, Status::Solved, "{:?} {:?}", sol.turned, sol.plan);
    assert!(distances_hold(&turned, &sol.x));
    let layout = gcs_jacobian::Layout::new(&turned);
    assert!(gcs_solve::orientation_holds(&layout, &sol.x, &turned.orientations()[0]));
    // The other triangle keeps the drawing's turn.
    let same = gcs_model::Orientation {
        id: "q".into(),
        points: ["p3", "p4", "p5"].map(|p| turned.entity_by_id(p).unwrap()).to_vec(),
        sign: 1,
    };
    let drawn_turn = gcs_solve::orientation_holds(&layout, &run(&plain).x, &same);
    assert_eq!(gcs_solve::orientation_holds(&layout, &sol.x, &same), drawn_turn);
    // With --all: exactly the realizations of the plain prism that turn the condition's way.
    let all = SolveOptions { all: Some(1000), ..SolveOptions::default() };
    let with = solve_with(&turned, &all).solutions.unwrap();
    let without = solve_with(&plain, &all).solutions.unwrap();
    let o = &turned.orientations()[0];
    let kept: Vec<&Vec<f64>> =
        without.iter().filter(|x| gcs_solve::orientation_holds(&layout, x, o)).collect();
    assert_eq!(with.len(), kept.len());
    assert!(!with.is_empty() && with.len() < without.len());
    for x in &with {
        assert!(kept.iter().any(|y| x.iter().zip(y.iter()).all(|(a, b)| (a - b).abs() < 1e-7)));
    }
}

/// Two orientation conditions that contradict each other: no realization keeps both, and the
/// solve says so (status inconsistent, the condition named) rather than pretending.
#[test]
fn contradicting_orientations_are_reported() {
    let s = prism_with(
        r#"Orientation(id: "o1", points: ["p0", "p1", "p2"], sign: 1),
           Orientation(id: "o2", points: ["p1", "p0", "p2"], sign: 1),"#,
    );
    let sol = run(&s);
    assert_eq!(sol.status, Status::Inconsistent);
    assert_eq!(sol.turned.len(), 1, "{:?}", sol.turned);
    assert!(distances_hold(&s, &sol.x), "the rest is solved");
}

/// A group the user declares is a node of the core's DR-plan when it is rigid: in a chain of
/// three K3,3 (blocks A, B, C), the plan splits off one end; declaring either A ∪ B or B ∪ C
/// makes that pair the node, the rest following, and the solve is the same.
#[test]
fn a_declared_rigid_group_is_a_node_of_the_plan() {
    let chain = gcs_model::generate::k33_chain(3, 1);
    let one = SolveOptions { all: Some(1), ..SolveOptions::default() };
    let plain = solve_with(&chain, &one);
    let points =
        |range: std::ops::Range<usize>| -> Vec<String> { range.map(|i| format!("p{i}")).collect() };
    // Without a group, one of the two pairs is a node and the other is not.
    let is = |p: &gcs_solve::PlanStep, range: std::ops::Range<usize>| {
        let mut ids: Vec<String> = p.entities.iter().map(|e| chain.entity(*e).id.clone()).collect();
        ids.sort();
        let mut want = points(range);
        want.sort();
        ids == want
    };
    let pairs = plain.plan.iter().filter(|p| is(p, 0..12) || is(p, 6..18)).count();
    assert_eq!(pairs, 1, "{:?}", plain.plan);
    for (name, range) in [("AB", 0..12), ("BC", 6..18)] {
        let mut b = gcs_model::SystemBuilder::from_system(chain.clone());
        let ids = points(range.clone());
        b.group(name, &ids.iter().map(String::as_str).collect::<Vec<_>>()).unwrap();
        let s = b.build();
        let sol = solve_with(&s, &one);
        assert_eq!(sol.status, Status::Solved);
        let node = sol.plan.iter().find(|p| p.groups == vec![0]).expect("the group is a node");
        let mut entities: Vec<String> =
            node.entities.iter().map(|e| s.entity(*e).id.clone()).collect();
        entities.sort();
        let mut want = ids.clone();
        want.sort();
        assert_eq!(entities, want, "{name}");
        assert_eq!(node.children.len(), 2, "{name}: two K3,3 assembled");
        assert!(sol.x.iter().zip(&plain.x).all(|(a, b)| (a - b).abs() < 1e-9), "{name}");
    }
    // A group that is not rigid (A with one point of B) changes nothing.
    let mut b = gcs_model::SystemBuilder::from_system(chain.clone());
    let ids = points(0..7);
    b.group("loose", &ids.iter().map(String::as_str).collect::<Vec<_>>()).unwrap();
    let sol = solve_with(&b.build(), &one);
    assert!(sol.plan.iter().all(|p| p.groups.is_empty()));
    assert_eq!(sol.plan.len(), plain.plan.len());
}

/// The autosolve backtracks over the core's DR-plan (issue 13, the ESM paper §3–4): a jittered
/// Laman sketch (laman-drawn 16, seed 1) whose core, solved from the drawing, reaches a
/// realization where a point placed after it finds no place (its two circles do not meet).
/// The search over the core nodes' candidates finds the combination with which everything
/// holds — a node off the drawing's first choice, as the report says — and keeps every
/// triangle's turn.
#[test]
fn a_failed_solve_backtracks_over_the_cores_nodes() {
    let (s, _) = gcs_model::generate::laman_drawn(16, 1, 0.2);
    let sol = run(&s);
    assert_eq!(sol.status, Status::Solved, "{:?}", sol.plan);
    assert!(gcs_solve::max_relative_residual(&s, &sol.x, sol.scale) <= 1e-9);
    let (kept, all) = gcs_solve::orientation_kept(&s, &sol.x);
    assert_eq!(kept, all, "every triangle as drawn");
    // The core's nodes it took off their candidate 0.
    let moved: Vec<(usize, usize)> = (sol.plan.iter().enumerate())
        .filter(|(_, p)| p.method == gcs_solve::Method::Newton && !p.fixed)
        .filter_map(|(k, p)| p.chosen.filter(|c| *c > 0).map(|c| (k, c)))
        .collect();
    assert!(!moved.is_empty(), "{:?}", sol.plan);
    assert!(moved.iter().all(|&(k, c)| c < sol.plan[k].candidates));
    assert!(sol.combinations >= 2 && sol.backtracked >= moved.len(), "{}", sol.combinations);
    assert!(!sol.bound_hit);
    // Choosing those candidates by hand gives the same realization, without a search.
    let chosen = solve_with(&s, &SolveOptions { choose: moved.clone(), ..SolveOptions::default() });
    assert_eq!(chosen.status, Status::Solved);
    assert_eq!(chosen.combinations, 0);
    assert!(chosen.x.iter().zip(&sol.x).all(|(a, b)| (a - b).abs() <= 1e-9 * sol.scale));
}

/// The search is bounded and says so: a jittered sketch whose core's last node, three
/// triangles assembled, has more paths than the search's homotopies may track (a quarter of
/// `max_paths`) is not searched beyond the drawing's combination, and `bound_hit` says the
/// search did not see every combination.
#[test]
fn the_search_over_the_core_reports_its_bound() {
    let (s, _) = gcs_model::generate::laman_drawn(16, 9, 0.2);
    let sol = run(&s);
    assert_ne!(sol.status, Status::Solved);
    assert!(sol.combinations >= 1 && sol.combinations <= gcs_solve::SEARCH_BOUND);
    assert!(sol.bound_hit);
}

/// A node whose candidates are not all its real solutions says why and how many may be
/// missing (issue 14: "otherwise say how many paths failed"): two K3,3 joined by three
/// distances, without `--all`, are solved from the drawing only; with fewer paths allowed than
/// a K3,3's homotopy has (70), each K3,3 says so — its 70 paths bound the complex solutions
/// not sought — while their assembly (6 paths) is enumerated in full.
#[test]
fn an_incomplete_node_says_why_and_how_much() {
    use gcs_solve::alternatives::Shortfall;
    let s = gcs_suite::load("data/paper/two_k33.ron");
    let plain = run(&s);
    let core = |sol: &gcs_solve::Solution| -> Vec<gcs_solve::PlanStep> {
        (sol.plan.iter()).filter(|p| p.method == gcs_solve::Method::Newton).cloned().collect()
    };
    assert_eq!(core(&plain).len(), 3, "{:?}", plain.plan);
    for p in core(&plain) {
        assert!(!p.complete);
        assert_eq!(p.shortfall, vec![Shortfall::NotSought]);
    }
    let few =
        solve_with(&s, &SolveOptions { all: Some(8), max_paths: 32, ..SolveOptions::default() });
    let nodes = core(&few);
    for leaf in &nodes[..2] {
        assert!(!leaf.complete && leaf.paths.is_none() && leaf.candidates == 1, "{leaf:?}");
        assert_eq!(leaf.shortfall, vec![Shortfall::Paths { paths: 70, max: 32 }]);
    }
    let root = &nodes[2];
    assert!(root.complete && root.shortfall.is_empty(), "{root:?}");
    assert_eq!(root.paths.map(|c| c.paths), Some(6));
    // With enough paths, every node is complete and nothing is said.
    let all = solve_with(&s, &SolveOptions { all: Some(8), ..SolveOptions::default() });
    assert!(core(&all).iter().all(|p| p.complete && p.shortfall.is_empty()), "{:?}", all.plan);
    // A step in closed form is complete.
    assert!(
        all.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).all(|p| p.complete)
    );
}

/// A strip of `n` points, each after the first three placed by distances to the points one and
/// three before it (so no three points but the first are joined pairwise: no triangle turns to
/// prune a side), and a redundant distance between its ends of `closing` (`None`: as drawn).
fn point_strip(n: usize, closing: Option<f64>) -> System {
    let at = |i: usize| [i as f64 * 1.5, if i % 2 == 0 { 0.0 } else { 2.0 + 0.1 * i as f64 }];
    let mut text = String::from("System(dim: 2, entities: [");
    for i in 0..n {
        let [x, y] = at(i);
        text += &format!("Point(id: \"p{i}\", at: [{x}, {y}]),");
    }
    text += "], constraints: [";
    let mut bar = |a: usize, b: usize, value: Option<f64>| {
        let d = value.unwrap_or_else(|| {
            let (p, q) = (at(a), at(b));
            (p[0] - q[0]).hypot(p[1] - q[1])
        });
        text += &format!("Distance(id: \"d{a}_{b}\", a: \"p{a}\", b: \"p{b}\", value: {d}),");
    };
    bar(0, 1, None);
    bar(1, 2, None);
    bar(0, 2, None);
    for k in 3..n {
        bar(k - 1, k, None);
        bar(k - 3, k, None);
    }
    bar(0, n - 1, closing);
    text += "])";
    model(&text)
}

/// Every bound that cuts a search short is in the report (issue 14's audit: the layer-1
/// placement budget set no flag): in a strip of 16 points whose ends are to be 1,000 apart,
/// no placement of the 13 closed-form steps' sides holds, and the autosolve's depth-first
/// search over them (2^13 leaves) stops at its 4,096 placements.
#[test]
fn the_placement_bound_is_reported() {
    use gcs_solve::Bound;
    let s = point_strip(16, Some(1000.0));
    let sol = run(&s);
    assert_eq!(sol.status, Status::Inconsistent, "{:?}", sol.redundant);
    assert!(sol.bounds_hit.contains(&Bound::Placements), "{:?}", sol.bounds_hit);
    assert!(sol.bound_hit);
    assert_eq!(Bound::Placements.limit(), 4096);
    // At its drawn length the closing distance agrees: no search, no bound.
    let sol = run(&point_strip(16, None));
    assert_eq!(sol.status, Status::Solved);
    assert!(sol.bounds_hit.is_empty() && !sol.bound_hit, "{:?}", sol.bounds_hit);
}

/// `--max-solutions` is a bound like the others: a chain of eight triangles has 2^8
/// realizations; asked for 10, the enumeration says which bound stopped it.
#[test]
fn the_solutions_limit_is_a_bound_hit() {
    use gcs_solve::Bound;
    let s = gcs_model::generate::strip(5, 2);
    let ten = solve_with(&s, &SolveOptions { all: Some(10), ..SolveOptions::default() });
    assert!(ten.truncated);
    assert_eq!(ten.bounds_hit, vec![Bound::Solutions(10)]);
    let every = solve_with(&s, &SolveOptions { all: Some(1000), ..SolveOptions::default() });
    assert!(!every.truncated && every.bounds_hit.is_empty(), "{:?}", every.bounds_hit);
}

/// A pick with the nodes' homotopies kept (`solve_cached`, what `gcs navigate` runs for each
/// candidate its listing did not reach) is the same solve as afresh, and solves again only the
/// picked node's parent chain: in the prism (two triangles, then their assembly), choosing the
/// first triangle's other candidate runs the assembly's homotopies (for each combination the
/// listing visits) but neither triangle's, where a fresh solve runs those too.
#[test]
fn a_pick_with_kept_homotopies_solves_only_its_parent_chain() {
    let s = prism_with("");
    let analysis = analyze(&s, &AnalysisOptions::default()).unwrap();
    let first = SolveOptions { all: Some(1), ..SolveOptions::default() };
    let mut cache = gcs_solve::NodeCache::default();
    let drawn = gcs_solve::solve_cached(&s, &analysis, &first, &mut cache).unwrap();
    assert_eq!((drawn.plan[2].children.clone(), cache.len()), (vec![0, 1], 3));
    let pick = SolveOptions { choose: vec![(0, 1)], ..first.clone() };
    let kept = gcs_solve::solve_cached(&s, &analysis, &pick, &mut cache).unwrap();
    let mut fresh_cache = gcs_solve::NodeCache::default();
    let fresh = gcs_solve::solve_cached(&s, &analysis, &pick, &mut fresh_cache).unwrap();
    // The fresh pick ran both triangles and some assemblies; the kept one those assemblies only.
    let new = cache.len() - 3;
    assert!(new >= 1 && new + 2 == fresh_cache.len(), "{new} {}", fresh_cache.len());
    assert_eq!((kept.x.clone(), kept.plan.clone()), (fresh.x.clone(), fresh.plan.clone()));
    assert_eq!(kept.plan[0].chosen, Some(1));
    assert!(distances_hold(&s, &kept.x));
    // Another drawing (other lengths) empties the cache rather than reuse what does not apply.
    let points: [[f64; 2]; 6] =
        [[0.0, 0.0], [3.1, 0.4], [1.2, 2.9], [4.3, 3.3], [-0.7, 4.1], [2.9, 5.2]];
    let edges = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)];
    let other = framework(&points, &edges, "");
    let analysis = analyze(&other, &AnalysisOptions::default()).unwrap();
    gcs_solve::solve_cached(&other, &analysis, &first, &mut cache).unwrap();
    assert_eq!(cache.len(), 3);
}
