//! Generated families of systems of growing size, for benchmarks and property tests.
//!
//! Every generator is deterministic in its arguments (sizes and seed) and returns a valid
//! [`System`] whose sketch is generic for its constraints (random integer coordinates), so the
//! sketch is a witness.

use num_rational::BigRational;

use crate::kinds::{ConstraintKind, Dim};
use crate::number::int;
use crate::rng::SplitMix64;
use crate::system::{System, SystemBuilder};

// The builder only fails on invalid input; the generators produce valid input by
// construction (unique ids, existing references, correct kinds), so a failure is a bug here.
fn ok<T>(r: Result<T, crate::ModelError>) -> T {
    match r {
        Ok(v) => v,
        Err(e) => panic!("generator produced an invalid model: {e}"),
    }
}

/// A distance value as a CAD user would type it: the Euclidean distance rounded to 4 decimals.
fn dimension(p: &[BigRational], q: &[BigRational]) -> BigRational {
    use num_traits::ToPrimitive;
    let d2: f64 =
        p.iter().zip(q).map(|(a, b)| (a - b).to_f64().unwrap_or(0.0)).map(|x| x * x).sum();
    BigRational::new(((d2.sqrt() * 10_000.0).round() as i64).into(), 10_000.into())
}

/// `n` fully constrained CAD rectangles side by side on a grid, each written as a user writes
/// it: four points, four segments, `Fix` on one corner, `Horizontal` on the bottom and top
/// sides, `Vertical` on the left and right sides, a width and a height. Each rectangle is an
/// independent well-constrained component (8 DOF, 8 DOC).
///
/// # Example
/// ```
/// let s = gcs_model::generate::rectangles(3);
/// assert_eq!(s.entities().len(), 3 * 8);
/// assert_eq!(s.dof_sum(), s.doc_sum());
/// ```
pub fn rectangles(n: usize) -> System {
    rectangles_drawn(n, 0.0, 0)
}

/// [`rectangles`] drawn off their dimensions: every corner but the fixed one moved by up to
/// `jitter` (model units) in each coordinate, written to four decimals — a sketch to solve.
pub fn rectangles_drawn(n: usize, jitter: f64, seed: u64) -> System {
    let mut b = SystemBuilder::new(format!("rectangles-{n}"), Dim::Two);
    let columns = (n as f64).sqrt().ceil().max(1.0) as i64;
    let mut rng = SplitMix64::new(seed);
    let mut drawn = |v: i64, fixed: bool| {
        if fixed || jitter == 0.0 {
            return int(v);
        }
        let moved = v as f64 + jitter * (2.0 * rng.unit_f64() - 1.0);
        BigRational::new(((moved * 10_000.0).round() as i64).into(), 10_000.into())
    };
    for k in 0..n as i64 {
        let (ox, oy) = ((k % columns) * 20, (k / columns) * 20);
        let (w, h) = (3 + k % 7, 2 + k % 5);
        let corners = [[ox, oy], [ox + w, oy], [ox + w, oy + h], [ox, oy + h]];
        let names = ["a", "b", "c", "d"].map(|s| format!("r{k}{s}"));
        for (i, (name, c)) in names.iter().zip(&corners).enumerate() {
            let at = vec![drawn(c[0], i == 0), drawn(c[1], i == 0)];
            ok(b.point(name, Some(at)));
        }
        let sides = ["bottom", "right", "top", "left"].map(|s| format!("r{k}_{s}"));
        for i in 0..4 {
            ok(b.segment(&sides[i], &names[i], &names[(i + 1) % 4]));
        }
        let c = |s: &str| format!("r{k}_{s}");
        ok(b.constraint(ConstraintKind::Fix, &c("fix"), &[&names[0]], None));
        ok(b.constraint(ConstraintKind::Horizontal, &c("hb"), &[&sides[0]], None));
        ok(b.constraint(ConstraintKind::Horizontal, &c("ht"), &[&sides[2]], None));
        ok(b.constraint(ConstraintKind::Vertical, &c("vl"), &[&sides[3]], None));
        ok(b.constraint(ConstraintKind::Vertical, &c("vr"), &[&sides[1]], None));
        ok(b.constraint(ConstraintKind::Distance, &c("w"), &[&names[0], &names[1]], Some(int(w))));
        ok(b.constraint(ConstraintKind::Distance, &c("h"), &[&names[0], &names[3]], Some(int(h))));
    }
    b.build()
}

/// A connected CAD plate: an `n × n` grid of rectangular cells sharing their sides, with a
/// hole in every cell, written as a CAD user writes it — `(n + 1)²` lattice points, the
/// horizontal and vertical segments between neighbours (`Horizontal`, `Vertical`), a `Fix` on
/// the corner, the widths of the bottom row's cells and the heights of the left column's
/// (`Distance`), and in each cell a circle placed from the cell's lower left corner
/// (`DistanceX`, `DistanceY` to its centre `c….center`) with a `Radius`. Well-constrained as a
/// whole (every point is bound to its row and column, so nothing decouples), no redundancy:
/// about `4n²` entities as written, `(n + 1)² + 2n(n + 1) + n²` (and the circles' `n²`
/// implicit centres).
///
/// # Example
/// ```
/// let s = gcs_model::generate::grid(3);
/// assert_eq!(s.entities().len(), 16 + 24 + 9 + 9);
/// assert_eq!(s.dof_sum(), s.doc_sum());
/// ```
pub fn grid(n: usize) -> System {
    let mut b = SystemBuilder::new(format!("grid-{n}"), Dim::Two);
    // Cell sizes 3–9 by 3–7, varied so no two rows or columns line up by accident.
    let width = |j: usize| 3 + (j * 5 % 7) as i64;
    let height = |i: usize| 3 + (i * 3 % 5) as i64;
    let xs: Vec<i64> = (0..=n).scan(0, |x, j| Some(std::mem::replace(x, *x + width(j)))).collect();
    let ys: Vec<i64> = (0..=n).scan(0, |y, i| Some(std::mem::replace(y, *y + height(i)))).collect();
    let p = |i: usize, j: usize| format!("p{i}_{j}");
    for (i, y) in ys.iter().enumerate() {
        for (j, x) in xs.iter().enumerate() {
            ok(b.point(&p(i, j), Some(vec![int(*x), int(*y)])));
        }
    }
    ok(b.constraint(ConstraintKind::Fix, "fix", &[&p(0, 0)], None));
    for i in 0..=n {
        for j in 0..=n {
            if j < n {
                let s = format!("h{i}_{j}");
                ok(b.segment(&s, &p(i, j), &p(i, j + 1)));
                ok(b.constraint(ConstraintKind::Horizontal, &format!("{s}.h"), &[&s], None));
                if i == 0 {
                    let w = Some(int(width(j)));
                    let ends = [p(i, j), p(i, j + 1)];
                    ok(b.constraint(
                        ConstraintKind::Distance,
                        &format!("w{j}"),
                        &[&ends[0], &ends[1]],
                        w,
                    ));
                }
            }
            if i < n {
                let s = format!("v{i}_{j}");
                ok(b.segment(&s, &p(i, j), &p(i + 1, j)));
                ok(b.constraint(ConstraintKind::Vertical, &format!("{s}.v"), &[&s], None));
                if j == 0 {
                    let h = Some(int(height(i)));
                    let ends = [p(i, j), p(i + 1, j)];
                    ok(b.constraint(
                        ConstraintKind::Distance,
                        &format!("t{i}"),
                        &[&ends[0], &ends[1]],
                        h,
                    ));
                }
            }
        }
    }
    let half = |v: i64| BigRational::new(v.into(), 2.into());
    for (i, y) in ys.iter().take(n).enumerate() {
        for (j, x) in xs.iter().take(n).enumerate() {
            let (w, h) = (width(j), height(i));
            let c = format!("c{i}_{j}");
            let centre = vec![int(2 * x + w) / int(2), int(2 * y + h) / int(2)];
            ok(b.circle(&c, Some(centre), Some(int(1))));
            let centre = format!("{c}.center");
            let corner = p(i, j);
            for (kind, axis, v) in [
                (ConstraintKind::DistanceX, "x", half(w)),
                (ConstraintKind::DistanceY, "y", half(h)),
            ] {
                let id = format!("{c}.{axis}");
                ok(b.constraint(kind, &id, &[corner.as_str(), centre.as_str()], Some(v)));
            }
            ok(b.constraint(ConstraintKind::Radius, &format!("{c}.r"), &[&c], Some(int(1))));
        }
    }
    b.build()
}

/// The edges of a random 2D Laman graph on `n ≥ 2` vertices built by Henneberg moves from one
/// edge: a type I move adds a vertex joined to two existing vertices; a type II move (chosen
/// with probability `type2` when an edge exists) removes an edge `uv` and adds a vertex joined
/// to `u`, `v` and a third vertex. The result has `2n − 3` edges and is generically minimally
/// rigid (Laman; Henneberg).
pub fn laman_edges(n: usize, type2: f64, rng: &mut SplitMix64) -> Vec<(usize, usize)> {
    let mut edges: Vec<(usize, usize)> = Vec::new();
    if n < 2 {
        return edges;
    }
    edges.push((0, 1));
    for v in 2..n {
        let existing = v as u64;
        if v >= 3 && rng.unit_f64() < type2 {
            let k = rng.below(edges.len() as u64) as usize;
            let (a, b) = edges.swap_remove(k);
            let mut c = rng.below(existing) as usize;
            while c == a || c == b {
                c = rng.below(existing) as usize;
            }
            edges.extend([(a, v), (b, v), (c, v)]);
        } else {
            let a = rng.below(existing) as usize;
            let mut b = rng.below(existing) as usize;
            while b == a {
                b = rng.below(existing) as usize;
            }
            edges.extend([(a, v), (b, v)]);
        }
    }
    edges
}

/// A bar-and-joint framework: points `p0…` at the given integer coordinates and one
/// `Distance` per edge (`d0…`, in edge order), in dimension `dim`.
pub fn framework(name: &str, dim: Dim, coords: &[Vec<i64>], edges: &[(usize, usize)]) -> System {
    let coords: Vec<Vec<BigRational>> =
        coords.iter().map(|c| c.iter().map(|x| int(*x)).collect()).collect();
    framework_at(name, dim, &coords, edges)
}

/// [`framework`] at rational coordinates.
pub fn framework_at(
    name: &str,
    dim: Dim,
    coords: &[Vec<BigRational>],
    edges: &[(usize, usize)],
) -> System {
    let mut b = SystemBuilder::new(name, dim);
    for (i, c) in coords.iter().enumerate() {
        ok(b.point(&format!("p{i}"), Some(c.clone())));
    }
    for (k, &(u, v)) in edges.iter().enumerate() {
        let value = dimension(&coords[u], &coords[v]);
        let (pu, pv) = (format!("p{u}"), format!("p{v}"));
        ok(b.constraint(ConstraintKind::Distance, &format!("d{k}"), &[&pu, &pv], Some(value)));
    }
    b.build()
}

/// The edges of the octahedron on vertices `0…5`: every pair but the opposite ones (0–5, 1–3,
/// 2–4), in lexicographic order (12 edges).
pub fn octahedron_edges() -> Vec<(usize, usize)> {
    (0..6)
        .flat_map(|a| (a + 1..6).map(move |b| (a, b)))
        .filter(|e| ![(0, 5), (1, 3), (2, 4)].contains(e))
        .collect()
}

/// The octahedron ([`octahedron_edges`]) in space at random integer coordinates in
/// `[-range, range]³` from `seed`, each distance at its drawn length.
pub fn random_octahedron(range: i64, seed: u64) -> System {
    let coords = random_coords(6, Dim::Three, range, &mut SplitMix64::new(seed));
    framework(&format!("octahedron-{seed}"), Dim::Three, &coords, &octahedron_edges())
}

/// Random integer coordinates in `[-range, range]^d`, pairwise distinct.
pub fn random_coords(n: usize, dim: Dim, range: i64, rng: &mut SplitMix64) -> Vec<Vec<i64>> {
    let mut out: Vec<Vec<i64>> = Vec::with_capacity(n);
    while out.len() < n {
        let c: Vec<i64> = (0..dim.coords()).map(|_| rng.range(-range, range)).collect();
        if !out.contains(&c) {
            out.push(c);
        }
    }
    out
}

/// A random generically rigid 2D bar framework on `n` points (a Laman graph by Henneberg
/// moves) with random integer coordinates: rigid, no redundancy.
pub fn laman(n: usize, seed: u64) -> System {
    let mut rng = SplitMix64::new(seed);
    let edges = laman_edges(n, 0.5, &mut rng);
    let coords = random_coords(n, Dim::Two, 1000, &mut rng);
    framework(&format!("laman-{n}-{seed}"), Dim::Two, &coords, &edges)
}

/// A random Laman framework as a CAD program writes it (the issue-10 family): points with
/// 10-significant-digit decimal coordinates in `[-1000, 1000]` (`123.4567891`), dimensions
/// rounded to 4 decimals, and one redundant distance `extra` between the first point and the
/// last one not already joined to it, whose circuit spans a large rigid part. Rigid, one
/// redundant constraint.
pub fn laman_sketch(n: usize, seed: u64) -> System {
    let n = n.max(3);
    let mut rng = SplitMix64::new(seed);
    let edges = laman_edges(n, 0.5, &mut rng);
    let coords: Vec<Vec<BigRational>> = (0..n)
        .map(|_| {
            (0..2)
                .map(|_| {
                    let k = rng.range(-9_999_999_999, 9_999_999_999);
                    BigRational::new(k.into(), 10_000_000.into())
                })
                .collect()
        })
        .collect();
    let mut s = framework_at(&format!("laman-sketch-{n}-{seed}"), Dim::Two, &coords, &edges);
    let joined = |v: usize| edges.iter().any(|&(a, b)| (a, b) == (0, v) || (a, b) == (v, 0));
    if let Some(v) = (1..n).rev().find(|&v| !joined(v)) {
        let mut b = SystemBuilder::from_system(s);
        let value = dimension(&coords[0], &coords[v]);
        ok(b.constraint(ConstraintKind::Distance, "extra", &["p0", &format!("p{v}")], Some(value)));
        s = b.build();
    }
    s
}

/// The triangles of a graph: the triples `a < b < c` joined pairwise, in order.
pub fn triangles(n: usize, edges: &[(usize, usize)]) -> Vec<[usize; 3]> {
    let mut adjacent: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &(u, v) in edges {
        if u < n && v < n && u != v {
            adjacent[u].push(v);
            adjacent[v].push(u);
        }
    }
    for a in &mut adjacent {
        a.sort_unstable();
        a.dedup();
    }
    let mut out = Vec::new();
    for a in 0..n {
        for &b in adjacent[a].iter().filter(|&&b| b > a) {
            for &c in adjacent[b].iter().filter(|&&c| c > b) {
                if adjacent[a].binary_search(&c).is_ok() {
                    out.push([a, b, c]);
                }
            }
        }
    }
    out
}

/// Twice the signed area of the triangle `a, b, c`.
fn turn(a: &[f64], b: &[f64], c: &[f64]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// A random Laman sketch drawn roughly, for solvers (issue 13): a random realization of a
/// Laman graph (Henneberg moves, half of them type II; points with 4-decimal coordinates in
/// `[-1000, 1000]`, distances its measures rounded to 6 decimals, plus one redundant distance
/// `extra` as in [`laman_sketch`]), drawn with every point moved by up to `jitter` times the
/// mean distance in each coordinate — except that a point of a triangle the move would turn
/// over has its move halved until no triangle turns (the drawing shows the realization's
/// orientation, as a user's rough drawing does). Returns the system and the realization.
pub fn laman_drawn(n: usize, seed: u64, jitter: f64) -> (System, Vec<[f64; 2]>) {
    let n = n.max(3);
    let mut rng = SplitMix64::new(seed);
    let edges = laman_edges(n, 0.5, &mut rng);
    let truth: Vec<[f64; 2]> = (0..n)
        .map(|_| [0, 1].map(|_| rng.range(-10_000_000, 10_000_000) as f64 / 10_000.0))
        .collect();
    let length = |&(u, v): &(usize, usize)| {
        ((truth[u][0] - truth[v][0]).powi(2) + (truth[u][1] - truth[v][1]).powi(2)).sqrt()
    };
    let mean = edges.iter().map(length).sum::<f64>() / edges.len().max(1) as f64;
    let mut moves: Vec<[f64; 2]> =
        (0..n).map(|_| [0, 1].map(|_| (2.0 * rng.unit_f64() - 1.0) * jitter * mean)).collect();
    let tri = triangles(n, &edges);
    for _ in 0..60 {
        let drawn: Vec<[f64; 2]> =
            (0..n).map(|i| [truth[i][0] + moves[i][0], truth[i][1] + moves[i][1]]).collect();
        let mut flipped = vec![false; n];
        for t in &tri {
            let [a, b, c] = *t;
            let before = turn(&truth[a], &truth[b], &truth[c]);
            let after = turn(&drawn[a], &drawn[b], &drawn[c]);
            if before * after <= 0.0 {
                for v in [a, b, c] {
                    flipped[v] = true;
                }
            }
        }
        if !flipped.contains(&true) {
            break;
        }
        for (m, f) in moves.iter_mut().zip(&flipped) {
            if *f {
                *m = [m[0] / 2.0, m[1] / 2.0];
            }
        }
    }
    let decimal = |x: f64| BigRational::new(((x * 10_000.0).round() as i64).into(), 10_000.into());
    // Distances to 6 decimals: a redundant one at its true value agrees within the solver's
    // tolerance however long its circuit.
    let dimension = |p: &[BigRational], q: &[BigRational]| {
        use num_traits::ToPrimitive;
        let d2: f64 =
            p.iter().zip(q).map(|(a, b)| (a - b).to_f64().unwrap_or(0.0)).map(|x| x * x).sum();
        BigRational::new(((d2.sqrt() * 1e6).round() as i64).into(), 1_000_000.into())
    };
    let exact = |p: &[f64; 2]| vec![decimal(p[0]), decimal(p[1])];
    let mut b = SystemBuilder::new(format!("laman-drawn-{n}-{seed}"), Dim::Two);
    for i in 0..n {
        let drawn = [truth[i][0] + moves[i][0], truth[i][1] + moves[i][1]];
        ok(b.point(&format!("p{i}"), Some(exact(&drawn))));
    }
    let joined = |v: usize| edges.iter().any(|&(a, b)| (a, b) == (0, v) || (a, b) == (v, 0));
    let extra = (1..n).rev().find(|&v| !joined(v)).map(|v| (0, v));
    for (k, &(u, v)) in edges.iter().chain(extra.iter()).enumerate() {
        let value = dimension(&exact(&truth[u]), &exact(&truth[v]));
        let id = if k < edges.len() { format!("d{k}") } else { "extra".to_owned() };
        let (pu, pv) = (format!("p{u}"), format!("p{v}"));
        ok(b.constraint(ConstraintKind::Distance, &id, &[&pu, &pv], Some(value)));
    }
    (b.build(), truth)
}

/// The edges of a random triangulated sphere on `n ≥ 4` vertices: from a tetrahedron, by
/// stellar subdivision of a face (a vertex joined to its three corners) and edge splits (edge
/// `ab` with faces `abc`, `abd` replaced by a vertex joined to `a, b, c, d`). A triangulated
/// sphere has `3n − 6` edges and is generically rigid in 3D (Gluck).
pub fn sphere_edges(n: usize, rng: &mut SplitMix64) -> Vec<(usize, usize)> {
    let n = n.max(4);
    let mut edges = vec![(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    let mut faces: Vec<[usize; 3]> = vec![[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]];
    for v in 4..n {
        if rng.below(2) == 0 {
            let f = rng.below(faces.len() as u64) as usize;
            let [a, b, c] = faces.swap_remove(f);
            faces.extend([[a, b, v], [b, c, v], [a, c, v]]);
            edges.extend([(a, v), (b, v), (c, v)]);
        } else {
            let k = rng.below(edges.len() as u64) as usize;
            let (a, b) = edges[k];
            let adjacent: Vec<usize> = (0..faces.len())
                .filter(|&i| faces[i].contains(&a) && faces[i].contains(&b))
                .collect();
            let [f1, f2] = adjacent[..] else {
                unreachable!("an edge of a triangulated sphere has two faces")
            };
            let third = |f: [usize; 3]| f.into_iter().find(|x| *x != a && *x != b).unwrap_or(a);
            let (c, d) = (third(faces[f1]), third(faces[f2]));
            let (hi, lo) = (f1.max(f2), f1.min(f2));
            faces.swap_remove(hi);
            faces.swap_remove(lo);
            faces.extend([[a, c, v], [b, c, v], [a, d, v], [b, d, v]]);
            edges.swap_remove(k);
            edges.extend([(a, v), (b, v), (c, v), (d, v)]);
        }
    }
    edges
}

/// A random triangulated sphere in 3D with random integer coordinates: generically rigid,
/// no redundancy.
pub fn triangulated_sphere(n: usize, seed: u64) -> System {
    let mut rng = SplitMix64::new(seed);
    let edges = sphere_edges(n, &mut rng);
    let coords = random_coords(n.max(4), Dim::Three, 1000, &mut rng);
    framework(&format!("sphere-{n}-{seed}"), Dim::Three, &coords, &edges)
}

/// An articulated chain of `n` triangles in 2D (the witness paper's fig. 7 for `n = 3`):
/// triangle `i` has points `2i`, `2i + 1`, `2i + 2`, consecutive triangles share a point (a
/// hinge). `n` clusters, `n − 1` internal DOF.
pub fn triangle_chain(n: usize, seed: u64) -> System {
    let n = n.max(1);
    let mut rng = SplitMix64::new(seed);
    let points = 2 * n + 1;
    let coords: Vec<Vec<i64>> = (0..points as i64)
        .map(|i| vec![10 * i + rng.range(-3, 3), if i % 2 == 0 { 0 } else { 8 } + rng.range(-3, 3)])
        .collect();
    let mut edges = Vec::new();
    for t in 0..n {
        let (a, b, c) = (2 * t, 2 * t + 1, 2 * t + 2);
        edges.extend([(a, b), (b, c), (a, c)]);
    }
    framework(&format!("triangle-chain-{n}"), Dim::Two, &coords, &edges)
}

/// A chain of `m` K3,3 frameworks in 2D, each joined to the next by three distances (two K3,3
/// so joined are the witness paper's figure 8a): block `k` has points `6k…6k + 5`, the first
/// three joined to the last three by all nine distances, its last three joined to the next
/// block's first three one to one. Random integer coordinates, block by block from left to
/// right: minimally rigid (`2·6m − 3` bars), and its DR-plan splits it block by block.
pub fn k33_chain(m: usize, seed: u64) -> System {
    let m = m.max(1);
    let mut rng = SplitMix64::new(seed);
    let coords: Vec<Vec<i64>> = (0..6 * m as i64)
        .map(|i| {
            let (block, side, k) = (i / 6, (i % 6) / 3, i % 3);
            vec![30 * block + 12 * side + rng.range(-3, 3), 8 * k + rng.range(-3, 3)]
        })
        .collect();
    let mut edges = Vec::new();
    for block in 0..m {
        let o = 6 * block;
        for i in 0..3 {
            for j in 3..6 {
                edges.push((o + i, o + j));
            }
        }
        if block + 1 < m {
            edges.extend((3..6).map(|j| (o + j, o + j + 3)));
        }
    }
    framework(&format!("k33-chain-{m}"), Dim::Two, &coords, &edges)
}

/// A triangulated strip in 2D: `2n` points in two rows, consecutive quads split by a
/// diagonal — rigid, no redundancy (`2·2n − 3` bars), and W-decomposable at every diagonal.
pub fn strip(n: usize, seed: u64) -> System {
    let n = n.max(2);
    let mut rng = SplitMix64::new(seed);
    let coords: Vec<Vec<i64>> = (0..2 * n as i64)
        .map(|i| vec![10 * (i / 2) + rng.range(-3, 3), 10 * (i % 2) + rng.range(-3, 3)])
        .collect();
    let mut edges = vec![(0, 1)];
    for q in 0..n - 1 {
        let (a, b, c, d) = (2 * q, 2 * q + 1, 2 * q + 2, 2 * q + 3);
        edges.extend([(a, c), (b, d), (c, d), if q % 2 == 0 { (a, d) } else { (b, c) }]);
    }
    framework(&format!("strip-{n}"), Dim::Two, &coords, &edges)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_match_the_theorems() {
        for n in [2, 3, 10, 57] {
            let s = laman(n, n as u64);
            assert_eq!(s.constraints().len(), 2 * n - 3);
            assert_eq!(s.naive_dof(), 3);
        }
        for n in [4, 5, 30] {
            let s = triangulated_sphere(n, 3);
            assert_eq!(s.constraints().len(), 3 * n - 6);
            assert_eq!(s.naive_dof(), 6);
        }
        let c = triangle_chain(5, 1);
        assert_eq!((c.entities().len(), c.constraints().len()), (11, 15));
        let s = strip(6, 1);
        assert_eq!(s.constraints().len(), 2 * 12 - 3);
        let k = k33_chain(4, 1);
        assert_eq!((k.entities().len(), k.constraints().len()), (24, 2 * 24 - 3));
        for n in [4, 30] {
            let s = laman_sketch(n, 5);
            assert_eq!(s.constraints().len(), 2 * n - 2);
            assert_eq!(s.constraints().last().map(|c| c.id.as_str()), Some("extra"));
            assert!(s.to_ron().contains("extra"));
        }
        let r = rectangles(10);
        assert_eq!(r.naive_dof(), 0);
        assert_eq!(r.constraints().len(), 70);
    }

    #[test]
    fn laman_edges_are_simple() {
        let mut rng = SplitMix64::new(9);
        let mut e = laman_edges(200, 0.5, &mut rng);
        let n = e.len();
        for (a, b) in e.iter_mut() {
            assert_ne!(a, b);
            if a > b {
                std::mem::swap(a, b);
            }
        }
        e.sort();
        e.dedup();
        assert_eq!(e.len(), n, "no repeated edge");
    }
}
