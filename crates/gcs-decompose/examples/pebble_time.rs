//! Times the (2,3) pebble game on the bar framework of a model file (points and distances,
//! as `gcs generate laman-sketch N` writes them), in process: the side-by-side comparison with
//! PyRigi (`benches/pyrigi_rigidity.py`) calls it.
//!
//! ```sh
//! cargo run --release -p gcs-decompose --example pebble_time -- MODEL.ron
//! ```
//!
//! Prints one JSON line: vertices, bars, rank, redundant bars, rigid components, and the best
//! of five runs of `pebble_game` in seconds (reading the file excluded).

#![allow(clippy::print_stdout)]

use std::time::Instant;

use gcs_decompose::pebble_game;
use gcs_model::{Metric, Signature, System};

fn main() -> Result<(), String> {
    let path = std::env::args().nth(1).ok_or("usage: pebble_time MODEL.ron")?;
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{path}: {e}"))?;
    let system = System::from_ron_str(&text, Some(&path)).map_err(|e| e.to_string())?;
    let bars: Vec<(usize, usize)> = system
        .constraints()
        .iter()
        .filter_map(|c| match c.signature {
            Signature::Metric(Metric::DistancePointPoint(a, b)) => Some((a.index(), b.index())),
            _ => None,
        })
        .collect();
    let n = system.entities().len();
    let mut best = f64::INFINITY;
    let mut report = None;
    for _ in 0..5 {
        let start = Instant::now();
        let r = pebble_game(n, &bars);
        best = best.min(start.elapsed().as_secs_f64());
        report = Some(r);
    }
    let r = report.ok_or("no run")?;
    let redundant = r.circuits.iter().filter(|c| c.is_some()).count();
    println!(
        "{{\"vertices\":{n},\"bars\":{},\"rank\":{},\"redundant\":{redundant},\"components\":{},\"seconds\":{best}}}",
        bars.len(),
        r.rank,
        r.components.len()
    );
    Ok(())
}
