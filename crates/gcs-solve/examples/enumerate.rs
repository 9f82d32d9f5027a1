//! Enumerates the realizations of generated sketches and prints, per sketch, the core's
//! DR-plan nodes, their homotopies (paths, finite and real solutions, undecided paths, summed
//! over the nodes at the drawing's choices), the realizations listed and the times:
//!
//! - `laman N...`: random Laman sketches on N points (`generate::laman_drawn`, drawn at their
//!   realization, one consistent redundant distance) — the core left by the closed-form steps
//!   is one node;
//! - `k33 M...`: chains of M K3,3 joined by three distances (`generate::k33_chain`) — the core
//!   splits block by block;
//! - `sphere N...`: random triangulated spheres in space on N points
//!   (`generate::triangulated_sphere`, minimally rigid in 3D) — one node, held by a triangle;
//! - `octahedron R`: octahedra in space at random integer coordinates in [−R, R]³ (the
//!   octahedron has 16 complex realizations with a face held).
//!
//! `met` counts the paths found at the same point as another at a checkpoint `t < 1` (a jump
//! detected, the paths tracked again; `homotopy::Ends::met`), `unaccounted` the paths to
//! infinity or to a singular end the endgame's cycles did not account for at first (tracked
//! or looped again; `homotopy::Ends::unaccounted`).
//! `seconds_nodes` is the solve with every node's candidates at the drawing's choices (one
//! realization listed: `all: Some(1)`), `seconds_all` the solve listing up to 10,000.
//! `cargo run --release -p gcs-solve --example enumerate -- laman 6 7 8 [--seeds K]`.

use std::time::Instant;

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_solve::{Method, SolveOptions, solve};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut seeds = 3u64;
    let mut sizes = Vec::new();
    let mut family = "laman".to_owned();
    let mut i = 0;
    while i < args.len() {
        if args[i] == "--seeds" {
            seeds = args.get(i + 1).and_then(|a| a.parse().ok()).unwrap_or(3);
            i += 2;
        } else if let Ok(n) = args[i].parse::<usize>() {
            sizes.push(n);
            i += 1;
        } else {
            family.clone_from(&args[i]);
            i += 1;
        }
    }
    if sizes.is_empty() {
        sizes = if family == "k33" { vec![1, 2, 3, 4] } else { vec![6, 7, 8, 9] };
    }
    let options = AnalysisOptions {
        clusters: false,
        sketch: false,
        global_rigidity: false,
        ..AnalysisOptions::default()
    };
    println!(
        "family size seed core_points nodes paths finite real undecided realizations seconds_nodes seconds_all nodes_per_second paths_per_second met unaccounted"
    );
    for &n in &sizes {
        for seed in 1..=seeds {
            let system = match family.as_str() {
                "k33" => gcs_model::generate::k33_chain(n, seed),
                "sphere" => gcs_model::generate::triangulated_sphere(n, seed),
                "octahedron" => gcs_model::generate::random_octahedron(n as i64, seed),
                _ => gcs_model::generate::laman_drawn(n, seed, 0.0).0,
            };
            let analysis = analyze(&system, &options).expect("analysis");
            let t = Instant::now();
            let one = solve(
                &system,
                &analysis,
                &SolveOptions { all: Some(1), ..SolveOptions::default() },
            )
            .expect("solve");
            let seconds_nodes = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let all = solve(
                &system,
                &analysis,
                &SolveOptions { all: Some(10_000), ..SolveOptions::default() },
            )
            .expect("solve");
            let seconds_all = t.elapsed().as_secs_f64();
            let nodes: Vec<&gcs_solve::PlanStep> =
                one.plan.iter().take_while(|p| p.method == Method::Newton).collect();
            let points = nodes.last().map_or(0, |p| p.entities.len());
            let listed = all.solutions.as_ref().map_or(0, Vec::len);
            let counted: Vec<_> = nodes.iter().filter_map(|p| p.paths).collect();
            let sum = |f: fn(&gcs_solve::alternatives::PathCounts) -> usize| {
                counted.iter().map(f).sum::<usize>()
            };
            let paths = sum(|c| c.paths);
            if counted.is_empty() {
                println!(
                    "{family} {n} {seed} {points} {} - - - - {listed} {seconds_nodes:.3} {seconds_all:.3} - - - -",
                    nodes.len()
                );
            } else {
                println!(
                    "{family} {n} {seed} {points} {} {paths} {} {} {} {listed} {seconds_nodes:.3} {seconds_all:.3} {:.1} {:.0} {} {}",
                    nodes.len(),
                    sum(|c| c.finite),
                    sum(|c| c.real),
                    sum(|c| c.failed),
                    nodes.len() as f64 / seconds_nodes,
                    paths as f64 / seconds_nodes,
                    sum(|c| c.met),
                    sum(|c| c.unaccounted),
                );
            }
        }
    }
}
