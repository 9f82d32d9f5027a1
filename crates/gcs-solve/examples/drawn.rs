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
    let (system, truth) = gcs_model::generate::laman_drawn(n, seed, jitter);
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
    let off = off_truth(&system, &truth, &solution.x);
    if std::env::var_os("VERBOSE").is_some() {
        eprintln!("no_solution {:?}\nredundant {:?}", solution.no_solution, solution.redundant);
    }
    println!(
        "n={n} seed={seed} jitter={jitter} analysis={:.3}s solve={:.3}s status={} max_residual={:.1e} iterations={} closed_form={} orientation_kept={}/{} off_truth={:.1e}",
        analysed.as_secs_f64(),
        solved.as_secs_f64(),
        solution.status.name(),
        solution.max_residual,
        solution.iterations,
        solution.plan.iter().filter(|p| p.method == gcs_solve::Method::ClosedForm).count(),
        kept.0,
        kept.1,
        off
    );
}

/// How far the solution is from the generator's realization, after the rigid motion (no
/// reflection) that fits them best (2D Kabsch), as the largest point distance over the mean
/// distance of the sketch: near 0 when the solve found the drawn realization, of order 1 when
/// it found another one (same distances, another shape) or a mirror image.
fn off_truth(system: &gcs_model::System, truth: &[[f64; 2]], x: &[f64]) -> f64 {
    let layout = gcs_jacobian::Layout::new(system);
    let solved: Vec<[f64; 2]> = system
        .entity_indices()
        .map(|e| {
            let mut c = layout.columns(e);
            let (Some(a), Some(b)) = (c.next(), c.next()) else { return [0.0, 0.0] };
            [x[a], x[b]]
        })
        .collect();
    let k = solved.len().min(truth.len()).max(1) as f64;
    let centre = |p: &[[f64; 2]]| {
        let s = p.iter().fold([0.0, 0.0], |s, q| [s[0] + q[0], s[1] + q[1]]);
        [s[0] / k, s[1] / k]
    };
    let (cs, ct) = (centre(&solved), centre(truth));
    let (mut dot, mut cross) = (0.0, 0.0);
    for (s, t) in solved.iter().zip(truth) {
        let (a, b) = ([s[0] - cs[0], s[1] - cs[1]], [t[0] - ct[0], t[1] - ct[1]]);
        dot += a[0] * b[0] + a[1] * b[1];
        cross += a[0] * b[1] - a[1] * b[0];
    }
    let theta = cross.atan2(dot);
    let (sin, cos) = theta.sin_cos();
    let mut worst = 0.0f64;
    for (s, t) in solved.iter().zip(truth) {
        let a = [s[0] - cs[0], s[1] - cs[1]];
        let r = [cos * a[0] - sin * a[1] + ct[0], sin * a[0] + cos * a[1] + ct[1]];
        worst = worst.max((r[0] - t[0]).hypot(r[1] - t[1]));
    }
    let mut mean = 0.0f64;
    let mut count = 0.0f64;
    for c in system.constraint_indices() {
        if let Some(v) =
            system.constraint(c).value.as_ref().and_then(num_traits::ToPrimitive::to_f64)
        {
            mean += v;
            count += 1.0;
        }
    }
    worst / (mean / count.max(1.0)).max(1e-300)
}
