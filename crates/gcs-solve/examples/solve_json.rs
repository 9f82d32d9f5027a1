//! Solves a sketch written by the `export_drawn` example (JSON) and prints one line in the
//! format of the `drawn` example, with the setup time, the largest distance residual in model
//! units and, with `VERBOSE`, the redundant constraints and the parts without a solution:
//! `cargo run --release -p gcs-solve --example solve_json -- FILE`. The side of gcs in
//! `benches/compare_solvers.sh`.

// A command-line tool: it prints by design.
#![allow(clippy::print_stdout, clippy::print_stderr)]

use std::time::Instant;

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_jacobian::Layout;
use gcs_model::{ConstraintKind, Dim, SystemBuilder};
use gcs_rank::BigRational;
use gcs_solve::{SolveOptions, solve};
use serde_json::Value;

/// A decimal of the file as an exact number: the generator writes at most 6 decimals.
fn exact(x: f64) -> BigRational {
    BigRational::new(((x * 1e6).round() as i64).into(), 1_000_000.into())
}

fn main() {
    let path = std::env::args().nth(1).expect("usage: solve_json FILE");
    let text = std::fs::read_to_string(&path).expect("read the file");
    let json: Value = serde_json::from_str(&text).expect("JSON");
    let f = |v: &Value| v.as_f64().expect("a number");
    let u = |v: &Value| v.as_u64().expect("an index") as usize;
    let t = Instant::now();
    let mut b = SystemBuilder::new(json["name"].as_str().unwrap_or("sketch"), Dim::Two);
    let points = json["points"].as_array().expect("points");
    for (i, p) in points.iter().enumerate() {
        b.point(&format!("p{i}"), Some(vec![exact(f(&p[0])), exact(f(&p[1]))])).expect("point");
    }
    let distances: Vec<(usize, usize, f64)> = json["distances"]
        .as_array()
        .expect("distances")
        .iter()
        .map(|d| (u(&d[0]), u(&d[1]), f(&d[2])))
        .collect();
    for (k, &(i, j, v)) in distances.iter().enumerate() {
        let (pi, pj) = (format!("p{i}"), format!("p{j}"));
        b.constraint(ConstraintKind::Distance, &format!("d{k}"), &[&pi, &pj], Some(exact(v)))
            .expect("distance");
    }
    // GCS_CMP_PIN=0: nothing held (the trivial motions left to the solver).
    let pinned = std::env::var("GCS_CMP_PIN").map_or(true, |v| v != "0");
    for (k, a) in json["fixed"].as_array().expect("fixed").iter().enumerate().filter(|_| pinned) {
        b.constraint(ConstraintKind::Fix, &format!("fix{k}"), &[&format!("p{}", u(a))], None)
            .expect("fix");
    }
    let pin = &json["pin"];
    let kind =
        if pin["axis"] == "x" { ConstraintKind::DistanceX } else { ConstraintKind::DistanceY };
    let (from, to) = (format!("p{}", u(&pin["from"])), format!("p{}", u(&pin["point"])));
    if pinned {
        b.constraint(kind, "pin", &[&from, &to], Some(exact(f(&pin["offset"])))).expect("pin");
    }
    let system = b.build();
    let setup = t.elapsed();
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
    let solution = solve(&system, &analysis, &SolveOptions::default()).expect("solve");
    let solved = t.elapsed();
    let layout = Layout::new(&system);
    let at = |i: usize| -> Vec<f64> {
        let e = system.entity_by_id(&format!("p{i}")).expect("point");
        layout.columns(e).map(|c| solution.x[c]).collect()
    };
    let residual = distances
        .iter()
        .map(|&(i, j, v)| {
            let (p, q) = (at(i), at(j));
            ((p[0] - q[0]).hypot(p[1] - q[1]) - v).abs()
        })
        .fold(0.0, f64::max);
    let kept = gcs_solve::orientation_kept(&system, &solution.x);
    if std::env::var_os("VERBOSE").is_some() {
        let id = |c| system.constraint(c).id.clone();
        eprintln!(
            "gcs {}: dof {} (absolute {}), {} redundant",
            system.name(),
            analysis.dof,
            analysis.dof_absolute,
            analysis.redundant.len()
        );
        for r in &solution.redundant {
            let group: Vec<String> = r.spanning_group.iter().map(|&c| id(c)).collect();
            eprintln!(
                "  redundant {} residual {:.3e} {} spanning group {group:?}",
                id(r.constraint),
                r.residual,
                if r.conflicting { "CONFLICTING" } else { "consistent" },
            );
        }
        for part in &solution.no_solution {
            eprintln!("  no solution: {} constraints", part.constraints.len());
        }
    }
    println!(
        "tool=gcs{} n={} seed={} jitter={} setup={:.3}s analysis={:.3}s solve={:.3}s status={} max_residual={:.1e} orientation_kept={}/{}",
        if pinned { "" } else { "-free" },
        points.len(),
        json["seed"],
        json["jitter"],
        setup.as_secs_f64(),
        analysed.as_secs_f64(),
        solved.as_secs_f64(),
        solution.status.name(),
        residual,
        kept.0,
        kept.1
    );
}
