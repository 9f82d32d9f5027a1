//! Writes a generated Laman sketch drawn with jitter ([`gcs_model::generate::laman_drawn`])
//! as JSON, for solving the same sketch with other tools (`benches/compare_solvers.sh`):
//! `cargo run --release -p gcs-solve --example export_drawn -- N SEED JITTER [conflict|minimal]`.
//!
//! `{"name", "points": [[x, y], ...], "distances": [[i, j, value], ...], "extra": k,
//! "fixed": [a], "pin": {"point": b, "from": a, "axis": "x"|"y", "offset": d}}`: the drawn
//! coordinates, the distances in the generator's order (`extra`, the last one, is the
//! redundant distance the generator adds), and how the trivial motions are removed the same
//! way in every tool: point `a` is held at its drawing and one coordinate of point `b` is held
//! at its drawn offset from `a` (`b.axis - a.axis = offset`), where `a`–`b` is the distance
//! of the sketch drawn closest to an axis (the other axis is pinned, so the distance can
//! always be met). With `conflict`, the extra distance is 10% longer than the realization's:
//! a redundant distance that contradicts the others; with `minimal`, it is left out (the
//! sketch is then minimally rigid: no redundant constraint).

// A command-line tool: it prints by design.
#![allow(clippy::print_stdout, clippy::print_stderr)]

use std::collections::HashMap;

use gcs_model::ConstraintKind;
use num_traits::ToPrimitive;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(100);
    let seed: u64 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(1);
    let jitter: f64 = args.get(3).and_then(|a| a.parse().ok()).unwrap_or(0.2);
    let variant = args.get(4).map_or("", |a| a.as_str());
    let (conflict, minimal) = (variant == "conflict", variant == "minimal");
    let (system, _) = gcs_model::generate::laman_drawn(n, seed, jitter);
    let mut index = HashMap::new();
    let mut points = Vec::new();
    for e in system.entity_indices() {
        let Some(c) = gcs_jacobian::sketch::sketch_coords_in::<f64>(&system, e) else {
            continue;
        };
        index.insert(e, points.len());
        points.push([c[0], c[1]]);
    }
    let mut distances = Vec::new();
    let mut extra = None;
    for c in system.constraint_indices() {
        let constraint = system.constraint(c);
        if constraint.kind != ConstraintKind::Distance {
            continue;
        }
        let [p, q] = constraint.args[..] else { continue };
        let mut value = constraint.value.as_ref().and_then(|v| v.to_f64()).unwrap_or(0.0);
        if constraint.id == "extra" {
            if minimal {
                continue;
            }
            extra = Some(distances.len());
            if conflict {
                value = (value * 1.1 * 1e6).round() / 1e6;
            }
        }
        distances.push((index[&p], index[&q], value));
    }
    // The pinned distance: the one whose smaller drawn extent is the least part of its value.
    let off_axis = |&(i, j, v): &(usize, usize, f64)| {
        let (dx, dy) = (points[j][0] - points[i][0], points[j][1] - points[i][1]);
        dx.abs().min(dy.abs()) / v
    };
    let &(a, b, _) = distances
        .iter()
        .min_by(|s, t| off_axis(s).total_cmp(&off_axis(t)))
        .expect("a sketch with distances");
    let (dx, dy) = (points[b][0] - points[a][0], points[b][1] - points[a][1]);
    let (axis, offset) = if dx.abs() >= dy.abs() { ("y", dy) } else { ("x", dx) };
    let offset = (offset * 1e4).round() / 1e4;
    let list = |items: Vec<String>| items.join(",");
    let suffix = if variant.is_empty() { String::new() } else { format!("-{variant}") };
    println!("{{\"name\":\"{}{suffix}\",", system.name());
    println!("\"n\":{n},\"seed\":{seed},\"jitter\":{jitter},");
    println!(
        "\"points\":[{}],",
        list(points.iter().map(|p| format!("[{:?},{:?}]", p[0], p[1])).collect())
    );
    println!(
        "\"distances\":[{}],",
        list(distances.iter().map(|(i, j, v)| format!("[{i},{j},{v:?}]")).collect())
    );
    match extra {
        Some(k) => println!("\"extra\":{k},"),
        None => println!("\"extra\":null,"),
    }
    println!("\"fixed\":[{a}],");
    println!("\"pin\":{{\"point\":{b},\"from\":{a},\"axis\":\"{axis}\",\"offset\":{offset:?}}}}}");
}
