//! `gcs solve --all` on nodes that are not bar frameworks: lines (homogeneous coordinates, a
//! random complex chart each), dimensions cleared of their denominators (a distance to a line,
//! between parallel lines, a ratio of lengths), and floating nodes held by a point and a
//! direction or by a line (each realization found with its half-turn, one of the two kept).
//! Every count here is proven by hand in the test's comment; every real candidate satisfies
//! every constraint of the model to 1e-9 relative, the candidates are distinct, and the
//! solve's own realization is candidate 0.

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_jacobian::{Equations, Layout};
use gcs_model::System;
use gcs_solve::{Method, PlanStep, Solution, SolveOptions, solve};

fn model(text: &str) -> System {
    System::from_ron_str(text, None).unwrap()
}

/// Solved with `--all`, its core's one node, and the realizations found.
fn enumerate(system: &System) -> (Solution, PlanStep, Vec<Vec<f64>>) {
    let analysis = analyze(system, &AnalysisOptions::default()).unwrap();
    let options = SolveOptions { all: Some(1000), ..SolveOptions::default() };
    let solution = solve(system, &analysis, &options).unwrap();
    let nodes: Vec<PlanStep> =
        (solution.plan.iter()).filter(|p| p.method == Method::Newton).cloned().collect();
    assert_eq!(nodes.len(), 1, "{:?}", solution.plan);
    let found = solution.solutions.clone().unwrap();
    let node = nodes[0].clone();
    (solution, node, found)
}

/// Every realization satisfies every constraint with a value (or none) to 1e-9 relative to
/// the model's size, they are pairwise distinct, and the first is the solve's own.
fn check(system: &System, solution: &Solution, found: &[Vec<f64>]) {
    let layout = Layout::new(system);
    let equations = Equations::new(system, &layout).with_branches_at(&solution.x);
    let size = solution.scale.max(1.0);
    for y in found {
        for c in system.constraint_indices() {
            let Some(r) = equations.residual(c, y) else { continue };
            let unit = match gcs_jacobian::residual_degree(system.constraint(c).signature) {
                _ if system.constraint(c).kind == gcs_model::ConstraintKind::LengthRatio => 1.0,
                _ if system.constraint(c).kind.is_metric() => size,
                d => size.powi(d),
            };
            let worst = r.values.iter().fold(0.0f64, |m, v| m.max((v / unit).abs()));
            assert!(worst <= 1e-9, "{}: {worst:e} at {y:?}", system.constraint(c).id);
        }
    }
    for (i, a) in found.iter().enumerate() {
        for b in &found[..i] {
            let apart = a.iter().zip(b).any(|(p, q)| (p - q).abs() > 1e-6 * size);
            assert!(apart, "{a:?} twice");
        }
    }
    let first = &found[0];
    assert!(first.iter().zip(&solution.x).all(|(p, q)| (p - q).abs() <= 1e-7 * size));
}

/// A line tangent to two circles held in place: the common tangents. Two disjoint circles
/// (neither inside the other) have 4 real common tangents, two circles that cross 2; the
/// line has homogeneous coordinates (one random complex chart), each tangency is
/// `(n·c + d)² = r²|n|²`, degree 4: 16 paths, 4 finite complex solutions either way.
#[test]
fn a_line_tangent_to_two_circles() {
    for (second, real) in [("[10, 1], radius: 2", 4), ("[4, 1], radius: 3", 2)] {
        let s = model(&format!(
            r#"System(dim: 2, entities: [
                Circle(id: "c1", center: [0, 0], radius: 3),
                Circle(id: "c2", center: {second}),
                Line(id: "l", at: [[-1, 3], [9, 3.2]]),
            ], constraints: [
                Fix(id: "f1", a: "c1"), Fix(id: "f2", a: "c2"),
                Tangent(id: "t1", a: "l", b: "c1"), Tangent(id: "t2", a: "l", b: "c2"),
            ])"#
        ));
        let (solution, node, found) = enumerate(&s);
        let paths = node.paths.unwrap();
        assert_eq!((paths.paths, paths.finite, paths.real), (16, 4, real), "{node:?}");
        assert!(node.complete, "{node:?}");
        assert_eq!(node.candidates, real);
        assert_eq!(found.len(), real);
        check(&s, &solution, &found);
    }
}

/// A point on a line held in place, at a given distance from another point of it (held):
/// the point on either side, 2. The point is placed in closed form; here the line is the
/// unknown — a line through a held point `p` at distance 3 from a held point `q` (|pq| = 5):
/// the two tangents from `p` to the circle of radius 3 about `q`, 2 real.
#[test]
fn a_line_through_a_point_at_a_distance_from_another() {
    let s = model(
        r#"System(dim: 2, entities: [
            Point(id: "p", at: [0, 0]), Point(id: "q", at: [5, 0]),
            Line(id: "l", at: [[0, 0], [4, 3]]),
        ], constraints: [
            Fix(id: "fp", a: "p"), Fix(id: "fq", a: "q"),
            Incident(id: "on", a: "p", b: "l"),
            Distance(id: "d", a: "q", b: "l", value: 3),
        ])"#,
    );
    let (solution, node, found) = enumerate(&s);
    assert!(node.complete, "{node:?}");
    assert_eq!((node.candidates, found.len()), (2, 2), "{node:?}");
    check(&s, &solution, &found);
}

/// Three parallel lines at distances 2 (A to B) and 3 (B to C), floating: only a rotation and
/// a translation across them move them (the translation along them does not), so the node is
/// held by A where the solve put it; B is then 2 from A on either side and C 3 from B on
/// either side — 4, and the half-turn about a point of A (which keeps A) maps each to the
/// one with both sides swapped: 2 realizations up to direct isometries (C beyond B, or back
/// between or past A).
#[test]
fn three_parallel_lines_have_two_realizations() {
    let s = gcs_suite::load("data/paper/flow_fig1a.ron");
    let (solution, node, found) = enumerate(&s);
    assert!(node.complete, "{node:?}");
    assert_eq!((node.candidates, found.len()), (2, 2), "{node:?}");
    check(&s, &solution, &found);
}

/// The flange: three concentric circles (radii dimensioned) and a bolt point on the rim,
/// floating, with no point-to-point distance: held by the bore's centre where the solve put
/// it and the bolt on the solved ray from it. The bolt is then at either end of a diameter
/// of the rim, one the half-turn of the other: 1 realization.
#[test]
fn the_flange_has_one_realization() {
    let s = gcs_suite::load("data/sketches/flange.ron");
    let (solution, node, found) = enumerate(&s);
    assert!(node.complete, "{node:?}");
    assert_eq!((node.candidates, found.len()), (1, 1), "{node:?}");
    check(&s, &solution, &found);
}

/// `data/sketches/ratios.ron`: `p1` fixed, `bottom` horizontal of length 8 (`p2` at
/// `(±8, 0)`: 2), `right` perpendicular to it with `|bottom| / |right| = 2` (the ratio
/// cleared of its denominator, `|u|² − 4|w|²`: `p3 = p2 + (0, ±4)`, 2), `p4` as far from
/// `bottom` as `p3` (`p4` at height ±4: 2) on the line through `p2` that makes with `bottom`
/// the angle `diagonal` makes (one point on that height): 8 realizations, all found. Some of
/// its paths end neither at a solution nor at infinity (the endgame leaves them undecided):
/// the node says so (`paths-failed`) and is not complete, but the 8 are all there are.
#[test]
fn the_ratios_sketch_has_eight_realizations() {
    let s = gcs_suite::load("data/sketches/ratios.ron");
    let (solution, node, found) = enumerate(&s);
    assert_eq!((node.candidates, found.len()), (8, 8), "{node:?}");
    let paths = node.paths.unwrap();
    assert_eq!((paths.finite, paths.real), (8, 8), "{node:?}");
    check(&s, &solution, &found);
}
