//! Solves `n` CAD rectangles (`gcs_model::generate::rectangles_drawn`: a fixed corner,
//! horizontal and vertical sides, a width and a height each) drawn off their dimensions by up
//! to JITTER model units, and prints the time, the status and how many steps were closed-form:
//! `cargo run --release -p gcs-solve --example rectangles -- N [JITTER] [numeric]`.

use std::time::Instant;

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_solve::{Method, SolveOptions, solve};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(100);
    let jitter: f64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(0.5);
    let constructive = args.get(3).is_none_or(|a| a != "numeric");
    let system = gcs_model::generate::rectangles_drawn(n, jitter, 7);
    let t = Instant::now();
    let options = AnalysisOptions { clusters: false, sketch: false, ..AnalysisOptions::default() };
    let analysis = analyze(&system, &options).expect("analysis");
    let analysed = t.elapsed();
    let t = Instant::now();
    let solution =
        solve(&system, &analysis, &SolveOptions { constructive, ..SolveOptions::default() })
            .expect("solve");
    let solved = t.elapsed();
    println!(
        "rectangles={n} jitter={jitter} constructive={constructive} analysis={:.3}s solve={:.3}s status={} max_residual={:.1e} moved={:.3} closed_form={} iterations={}",
        analysed.as_secs_f64(),
        solved.as_secs_f64(),
        solution.status.name(),
        solution.max_residual,
        solution.moved,
        solution.plan.iter().filter(|p| p.method == Method::ClosedForm).count(),
        solution.iterations,
    );
}
