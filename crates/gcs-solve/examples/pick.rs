//! The cost of one pick in the navigator: choosing another candidate of one node of the core's
//! DR-plan (`gcs solve --choose NODE=1`, what `gcs navigate` runs for a candidate its listing
//! did not reach), solved afresh and with the nodes' homotopies kept from the solve before it
//! (`solve_cached`: only the node's parent chain is solved again). Per sketch: the first
//! solve (every node at the drawing's choices), then a pick of the first leaf (its parent
//! chain: every assembly above it) and of the last leaf (its parent: the root), each the
//! median of `--runs` runs (3), and the node homotopies each pick ran.
//!
//! `cargo run --release -p gcs-solve --example pick -- k33 1 2 4 8` (chains of M K3,3) or
//! `-- strip 8 16 32` (triangulated strips: closed-form steps; the pick is step 1's other side).

#![allow(clippy::print_stdout)] // An example that prints its table.

use std::time::Instant;

use gcs_analysis::{AnalysisOptions, analyze};
use gcs_solve::{Method, NodeCache, SolveOptions, solve, solve_cached};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut runs = 3usize;
    let mut family = "k33".to_owned();
    let mut sizes = Vec::new();
    let mut i = 0;
    while i < args.len() {
        if args[i] == "--runs" {
            runs = args.get(i + 1).and_then(|a| a.parse().ok()).unwrap_or(3);
            i += 2;
        } else if let Ok(n) = args[i].parse::<usize>() {
            sizes.push(n);
            i += 1;
        } else {
            family.clone_from(&args[i]);
            i += 1;
        }
    }
    let options = AnalysisOptions {
        clusters: false,
        sketch: false,
        global_rigidity: false,
        ..AnalysisOptions::default()
    };
    println!(
        "family size nodes first_solve_s pick pick_chain fresh_s cached_s homotopies_fresh homotopies_cached"
    );
    for &n in &sizes {
        let system = match family.as_str() {
            "strip" => gcs_model::generate::strip(n, 1),
            _ => gcs_model::generate::k33_chain(n, 1),
        };
        let analysis = analyze(&system, &options).expect("analysis");
        let base = SolveOptions { all: Some(1), ..SolveOptions::default() };
        let t = Instant::now();
        let mut first_cache = NodeCache::default();
        let first = solve_cached(&system, &analysis, &base, &mut first_cache).expect("solve");
        let first_s = t.elapsed().as_secs_f64();
        let nodes = first.plan.iter().take_while(|p| p.method == Method::Newton).count();
        // The picks: the first and the last leaf of the core's DR-plan, or a closed-form step.
        let mut picks: Vec<(String, usize, usize)> = Vec::new();
        let leaves: Vec<usize> = (0..nodes)
            .filter(|&k| first.plan[k].children.is_empty() && first.plan[k].candidates > 1)
            .collect();
        // The nodes above node k (its parent chain).
        let chain = |k: usize| {
            let mut up = 0;
            let mut at = k;
            while let Some(p) = (0..nodes).find(|&q| first.plan[q].children.contains(&at)) {
                up += 1;
                at = p;
            }
            up
        };
        if let Some(&k) = leaves.first() {
            picks.push(("first-leaf".into(), k, chain(k)));
        }
        if let Some(&k) = leaves.last().filter(|&&k| Some(&k) != leaves.first()) {
            picks.push(("last-leaf".into(), k, chain(k)));
        }
        if nodes < first.plan.len() {
            picks.push(("closed-form".into(), nodes, 0));
        }
        for (name, k, up) in picks {
            let options = SolveOptions { choose: vec![(k, 1)], ..base.clone() };
            let (mut fresh, mut cached) = (Vec::new(), Vec::new());
            let (mut ran_fresh, mut ran_cached) = (0, 0);
            for _ in 0..runs {
                let mut cache = NodeCache::default();
                let t = Instant::now();
                let a = solve_cached(&system, &analysis, &options, &mut cache).expect("pick");
                fresh.push(t.elapsed().as_secs_f64());
                ran_fresh = cache.len();
                // A cache as the first solve left it, then the pick.
                let mut cache = NodeCache::default();
                solve_cached(&system, &analysis, &base, &mut cache).expect("solve");
                let before = cache.len();
                let t = Instant::now();
                let b = solve_cached(&system, &analysis, &options, &mut cache).expect("pick");
                cached.push(t.elapsed().as_secs_f64());
                ran_cached = cache.len() - before;
                assert_eq!(a.x, b.x, "the same pick with and without the cache");
                assert_eq!(a.plan, b.plan);
            }
            // (The plain solve, for reference: the same as the fresh pick.)
            let _ = solve(&system, &analysis, &options).expect("pick");
            println!(
                "{family} {n} {nodes} {first_s:.3} {name} {up} {:.4} {:.4} {ran_fresh} {ran_cached}",
                median(fresh),
                median(cached),
            );
        }
    }
}
