//! Solves a generated Laman sketch drawn with jitter and prints the time, the status and
//! whether every triangle kept its drawn orientation: `cargo run --release -p gcs-solve
//! --example drawn -- N [SEED] [JITTER]`.

use std::time::Instant;

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_solve::{SolveOptions, solve};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(100);
    let seed: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(1);
    let jitter: f64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(0.2);
    let constructive = args.get(4).is_none_or(|a| a != "numeric");
    let (system, _) = gcs_model::generate::laman_drawn(n, seed, jitter);
    let t = Instant::now();
    let options = AnalysisOptions {
        clusters: false,
        sketch: false,
        global_rigidity: false,
        ..AnalysisOptions::default()
    };
    let analysis = analyze(&system, &options).expect("analysis");
    let analysed = t.elapsed();
    let t = Instant::now();
    let solution =
        solve(&system, &analysis, &SolveOptions { constructive, ..SolveOptions::default() })
            .expect("solve");
    let solved = t.elapsed();
    let kept = gcs_solve::orientation_kept(&system, &solution.x);
    if std::env::var_os("VERBOSE").is_some() {
        eprintln!("no_solution {:?}\nredundant {:?}", solution.no_solution, solution.redundant);
    }
    println!(
        "n={n} seed={seed} jitter={jitter} analysis={:.3}s solve={:.3}s status={} max_residual={:.1e} iterations={} closed_form={} orientation_kept={}/{}",
        analysed.as_secs_f64(),
        solved.as_secs_f64(),
        solution.status.name(),
        solution.max_residual,
        solution.iterations,
        solution.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).count(),
        kept.0,
        kept.1
    );
}
