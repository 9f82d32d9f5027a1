//! Enumerates the realizations of generated Laman sketches (`generate::laman_drawn`, drawn at
//! their realization, one consistent redundant distance) and prints, per sketch, the core
//! the closed-form steps leave, its homotopy (paths, finite and real solutions, undecided
//! paths), the realizations listed and the time: `cargo run --release -p gcs-solve --example
//! enumerate -- N... [--seeds K]`.

use std::time::Instant;

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_solve::{SolveOptions, solve};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut seeds = 3u64;
    let mut sizes = Vec::new();
    let mut i = 0;
    while i < args.len() {
        if args[i] == "--seeds" {
            seeds = args.get(i + 1).and_then(|a| a.parse().ok()).unwrap_or(3);
            i += 2;
        } else {
            sizes.extend(args[i].parse::<usize>().ok());
            i += 1;
        }
    }
    if sizes.is_empty() {
        sizes = vec![6, 7, 8, 9];
    }
    let options = AnalysisOptions {
        clusters: false,
        sketch: false,
        global_rigidity: false,
        ..AnalysisOptions::default()
    };
    println!(
        "points seed core_points paths finite real undecided realizations seconds paths_per_second"
    );
    for &n in &sizes {
        for seed in 1..=seeds {
            let (system, _) = gcs_model::generate::laman_drawn(n, seed, 0.0);
            let analysis = analyze(&system, &options).expect("analysis");
            let t = Instant::now();
            let solution = solve(
                &system,
                &analysis,
                &SolveOptions { all: Some(10_000), ..SolveOptions::default() },
            )
            .expect("solve");
            let seconds = t.elapsed().as_secs_f64();
            let core = solution.plan.first().filter(|p| p.method == gcs_solve::Method::Newton);
            let points = core.map_or(0, |p| p.entities.len());
            let listed = solution.solutions.as_ref().map_or(0, Vec::len);
            match core.and_then(|p| p.paths) {
                Some(c) => println!(
                    "{n} {seed} {points} {} {} {} {} {listed} {seconds:.3} {:.0}",
                    c.paths,
                    c.finite,
                    c.real,
                    c.failed,
                    c.paths as f64 / seconds
                ),
                None => println!("{n} {seed} {points} - - - - {listed} {seconds:.3} -"),
            }
        }
    }
}
