//! Every reason a node's candidates may not be all its real solutions (`Shortfall`, the
//! report's `incomplete`: docs/format.md, `gcs solve`'s `plan`) is produced by some input:
//! one test per reason, each building the input and asserting the reason and its counts.
//! (`homotopy-budget` is the exception, explained at its test.)

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_model::System;
use gcs_solve::alternatives::Shortfall;
use gcs_solve::{Method, PlanStep, Solution, SolveOptions, Status, solve};

fn model(text: &str) -> System {
    System::from_ron_str(text, None).unwrap()
}

fn solve_with(system: &System, options: &SolveOptions) -> Solution {
    let analysis = analyze(system, &AnalysisOptions::default()).unwrap();
    solve(system, &analysis, options).unwrap()
}

fn all(limit: usize) -> SolveOptions {
    SolveOptions { all: Some(limit), ..SolveOptions::default() }
}

/// The core's nodes (the plan's `newton` steps).
fn nodes(solution: &Solution) -> Vec<PlanStep> {
    (solution.plan.iter()).filter(|p| p.method == Method::Newton).cloned().collect()
}

/// Points in space `p0…` drawn at `points`, one distance per edge at its drawn length (to
/// the digits `{}` prints).
fn space_framework(points: &[[f64; 3]], edges: &[(usize, usize)]) -> System {
    let mut text = String::from("System(dim: 3, entities: [");
    for (i, p) in points.iter().enumerate() {
        text += &format!("Point(id: \"p{i}\", at: [{}, {}, {}]),", p[0], p[1], p[2]);
    }
    text += "], constraints: [";
    for &(a, b) in edges {
        let d = (0..3).map(|k| (points[a][k] - points[b][k]).powi(2)).sum::<f64>().sqrt();
        text += &format!("Distance(id: \"d{a}_{b}\", a: \"p{a}\", b: \"p{b}\", value: {d}),");
    }
    text += "])";
    model(&text)
}

/// The octahedron (opposite vertices 0–5, 1–3, 2–4 not joined), drawn irregular.
fn octahedron() -> System {
    let points = [
        [0.2, -0.3, 3.1],
        [2.9, 0.4, 0.3],
        [0.1, 3.2, -0.2],
        [-3.3, 0.2, 0.4],
        [0.3, -2.7, -0.3],
        [-0.4, 0.2, -2.8],
    ];
    let edges = gcs_model::generate::octahedron_edges();
    space_framework(&points, &edges)
}

/// `not-sought`: without `--all` (or with `--max-paths 0`) a node is solved from the drawing
/// only — one candidate, no paths.
#[test]
fn not_sought() {
    let s = octahedron();
    for options in [SolveOptions::default(), SolveOptions { max_paths: 0, ..all(10) }] {
        let sol = solve_with(&s, &options);
        assert_eq!(sol.status, Status::Solved);
        let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
        assert_eq!(node.shortfall, vec![Shortfall::NotSought]);
        assert!(!node.complete && node.paths.is_none() && node.candidates == 1, "{node:?}");
    }
}

/// `core-unsolved`: a prism whose first triangle breaks the triangle inequality (1 + 1 < 5)
/// has no real realization; its realizations are not enumerated, and every node says why.
#[test]
fn core_unsolved() {
    let s = model(
        r#"System(dim: 2, entities: [
            Point(id: "p0", at: [0, 0]), Point(id: "p1", at: [3.1, 0.4]), Point(id: "p2", at: [1.2, 2.9]),
            Point(id: "p3", at: [4.3, 3.3]), Point(id: "p4", at: [-0.7, 4.1]), Point(id: "p5", at: [2.6, 5.7])],
          constraints: [
            Distance(id: "a", a: "p0", b: "p1", value: 1), Distance(id: "b", a: "p1", b: "p2", value: 1),
            Distance(id: "c", a: "p2", b: "p0", value: 5),
            Distance(id: "d", a: "p3", b: "p4", value: 5.1), Distance(id: "e", a: "p4", b: "p5", value: 3.7),
            Distance(id: "f", a: "p5", b: "p3", value: 3.6),
            Distance(id: "g", a: "p0", b: "p3", value: 5.4), Distance(id: "h", a: "p1", b: "p4", value: 5.5),
            Distance(id: "i", a: "p2", b: "p5", value: 3.1)])"#,
    );
    let sol = solve_with(&s, &all(10));
    assert_ne!(sol.status, Status::Solved);
    let core = nodes(&sol);
    assert!(!core.is_empty());
    for node in &core {
        assert_eq!(node.shortfall, vec![Shortfall::Unsolved], "{node:?}");
        assert!(!node.complete && node.paths.is_none() && node.candidates == 1, "{node:?}");
    }
}

/// `unsupported`, with what it is not set up for: a flexible core (the double banana, its
/// redundant distance left out: 24 coordinates, 17 distances, one motion beyond the six of
/// space), and a 3D core with planes (the corner of a block).
#[test]
fn unsupported() {
    let banana = gcs_suite::load("data/paper/double_banana.ron");
    let sol = solve_with(&banana, &all(10));
    let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
    assert_eq!(
        node.shortfall,
        vec![Shortfall::Unsupported("a flexible node (its realizations are not isolated)")]
    );
    assert!(!node.complete && node.paths.is_none() && node.candidates == 1, "{node:?}");
    let block = gcs_suite::load("data/sketches/block_3d.ron");
    let sol = solve_with(&block, &all(10));
    let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
    let [Shortfall::Unsupported(why)] = node.shortfall[..] else { panic!("{node:?}") };
    assert!(why.contains("homogeneous") || why.contains("other than points"), "{why}");
}

/// `too-many-unknowns`: a triangulated sphere of 26 points in space (minimally rigid, one
/// node: space has no DR-plan split here), held by a triangle, has 3·26 − 9 = 69 unknowns,
/// over the 64 a node may have.
#[test]
fn too_many_unknowns() {
    let s = gcs_model::generate::triangulated_sphere(26, 3);
    let sol = solve_with(&s, &all(10));
    assert_eq!(sol.status, Status::Solved);
    let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
    assert_eq!(node.shortfall, vec![Shortfall::Unknowns { unknowns: 69, max: 64 }]);
    assert!(!node.complete && node.paths.is_none() && node.candidates == 1, "{node:?}");
}

/// `too-many-paths`: the octahedron held by a face has 9 unknowns and 9 quadrics, 2^9 = 512
/// paths; allowed 100, none is tracked, and the 512 bound the complex solutions not sought.
#[test]
fn too_many_paths() {
    let sol = solve_with(&octahedron(), &SolveOptions { max_paths: 100, ..all(10) });
    let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
    assert_eq!(node.shortfall, vec![Shortfall::Paths { paths: 512, max: 100 }]);
    assert!(!node.complete && node.paths.is_none() && node.candidates == 1, "{node:?}");
}

/// `homotopy-budget`: not produced through `solve` — the plan records the nodes on the chosen
/// combination, and those are solved before any budget is spent (the enumeration that spends
/// it reports `node-homotopies` in `bounds_hit`, checked in `solve.rs`); the reason itself is
/// checked on the enumerator, `nodes::tests::a_node_past_the_budget_says_so`. Here: its
/// name and its limits as the report gives them.
#[test]
fn homotopy_budget() {
    let budget = Shortfall::Budget { homotopies: gcs_solve::SEARCH_HOMOTOPIES };
    assert_eq!(budget.name(), "homotopy-budget");
    assert_eq!(gcs_solve::Bound::NodeHomotopies.limit(), 4096);
    assert_eq!(gcs_solve::Bound::SearchHomotopies.limit(), 64);
}

/// `paths-failed`: the octahedron drawn at random integer coordinates in [−100, 100]³ (the
/// `enumerate` example's `octahedron 100`, seed 20) whose homotopy leaves 3 of its 512 paths
/// undecided and finds 14 of the 16 complex solutions (Bartzos et al.'s count): the node is
/// not complete, and says that up to 3 may be missing. (Seed 3, the case here until the
/// endgame started at the last checkpoint, `1 − t = 10⁻²` exactly, now finds all 16 with every
/// path decided; a K3,3 at small integer coordinates, `k33_chain(1, 14)`, was the case before
/// that.)
#[test]
fn paths_failed() {
    let s = gcs_model::generate::random_octahedron(100, 20);
    let sol = solve_with(&s, &all(100));
    assert_eq!(sol.status, Status::Solved);
    let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
    let counts = node.paths.expect("enumerated");
    assert_eq!((counts.paths, counts.finite, counts.failed), (512, 14, 3), "{counts:?}");
    assert_eq!(node.shortfall, vec![Shortfall::Failed { failed: 3, tracked: 512 }]);
    assert!(!node.complete && node.candidates == counts.real, "{node:?}");
    // Each real candidate still holds: what was found is right, only not known to be all.
    for x in sol.solutions.as_ref().unwrap() {
        assert!(gcs_solve::max_relative_residual(&s, x, sol.scale) <= 1e-9);
    }
}

/// `drawing-missed`: a tetrahedron in space drawn flat — a 4 × 3 rectangle with its
/// diagonals, every length an integer. Held by the triangle `p0 p1 p2`, the fourth point is
/// where three spheres meet: their two meeting points are mirror images in the held plane,
/// here one double point, the drawing itself. The homotopy's 8 paths end at infinity or at
/// that singular point, never at a nonsingular solution: the solve's own realization is not
/// among the paths' ends, so it is added as candidate 0 and the node says it was missed.
#[test]
fn drawing_missed() {
    let s = model(
        r#"System(dim: 3, entities: [
            Point(id: "p0", at: [0, 0, 0]), Point(id: "p1", at: [4, 0, 0]),
            Point(id: "p2", at: [0, 3, 0]), Point(id: "p3", at: [4, 3, 0])],
          constraints: [
            Distance(id: "a", a: "p0", b: "p1", value: 4), Distance(id: "b", a: "p0", b: "p2", value: 3),
            Distance(id: "c", a: "p1", b: "p2", value: 5), Distance(id: "d", a: "p0", b: "p3", value: 5),
            Distance(id: "e", a: "p1", b: "p3", value: 3), Distance(id: "f", a: "p2", b: "p3", value: 4)])"#,
    );
    let sol = solve_with(&s, &all(10));
    assert_eq!(sol.status, Status::Solved);
    let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
    let counts = node.paths.expect("enumerated");
    assert_eq!((counts.paths, counts.finite, counts.real), (8, 0, 0), "{counts:?}");
    assert!(node.shortfall.contains(&Shortfall::DrawingMissed), "{node:?}");
    assert!(!node.complete && node.candidates == 1, "{node:?}");
    assert_eq!(sol.solutions.as_ref().map(Vec::len), Some(1));
}

/// No solution missed silently: the octahedron drawn at random integer coordinates in
/// [−100, 100]³ (the `enumerate` example's `octahedron 100`, seed 1) has two of its 16
/// complex realizations far out (about 2.5 times the drawing's size) and ill-conditioned;
/// their paths approach them slowly, and were once taken to infinity — 14 solutions, every
/// path decided, the node complete. Either all 16 are found, or the node says it is not
/// complete (here all are found).
#[test]
fn far_solutions_are_not_taken_to_infinity() {
    let s = gcs_model::generate::random_octahedron(100, 1);
    let sol = solve_with(&s, &all(100));
    let [node] = &nodes(&sol)[..] else { panic!("{:?}", sol.plan) };
    let counts = node.paths.expect("enumerated");
    assert!(counts.finite == 16 || !node.complete, "{counts:?} {node:?}");
    assert_eq!((counts.paths, counts.finite, counts.failed), (512, 16, 0), "{counts:?}");
    assert!(node.complete && node.shortfall.is_empty(), "{node:?}");
}
