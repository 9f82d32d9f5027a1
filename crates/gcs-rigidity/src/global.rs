//! Global rigidity in the plane, combinatorially: Jackson and Jordán (2005), "Connected rigidity
//! matroids and unique realizations of graphs" — a graph is generically globally rigid in R²
//! iff it is complete on at most 3 vertices, or 3-connected and redundantly rigid.
//!
//! Rigidity is Laman's count decided by the (2,3)-pebble game (Jacobs and Hendrickson 1997);
//! redundant rigidity asks whether every bar lies in one of the game's fundamental circuits;
//! 3-connectivity removes each vertex in turn and looks for an articulation point of the rest
//! (`O(n · (n + m))`). The analysis decides global rigidity by the stress matrix
//! (`gcs_analysis::global`, a sparse elimination modulo a prime, in 2D and 3D); this is its
//! combinatorial cross-check in 2D (`tests/global.rs`: the two agree on thousands of random
//! graphs).
//!
//! Parallel edges and loops are ignored: global rigidity depends on the simple graph only.

use gcs_decompose::pebble_game;

/// The simple graph: each unordered pair once, loops and out-of-range vertices dropped.
fn simple(n: usize, edges: &[(usize, usize)]) -> Vec<(usize, usize)> {
    let mut e: Vec<(usize, usize)> = edges
        .iter()
        .filter(|(a, b)| a != b && *a < n && *b < n)
        .map(|&(a, b)| (a.min(b), a.max(b)))
        .collect();
    e.sort_unstable();
    e.dedup();
    e
}

/// Whether the graph is generically rigid in the plane (Laman): its pebble game accepts
/// `2n − 3` edges (every graph on at most one vertex is rigid).
///
/// # Complexity
/// That of [`gcs_decompose::pebble_game`]: `O(n · m)` at worst.
pub fn laman_rigid(n: usize, edges: &[(usize, usize)]) -> bool {
    n <= 1 || pebble_game(n, &simple(n, edges)).rank == 2 * n - 3
}

/// Whether the graph is generically redundantly rigid in the plane: rigid, and still rigid
/// after removing any one edge — every edge lies in a circuit of the rigidity matroid, which
/// the pebble game's fundamental circuits tell ([`gcs_decompose::PebbleReport::in_circuit`]).
///
/// # Complexity
/// That of the pebble game, `O(n · m)` at worst.
pub fn redundantly_rigid(n: usize, edges: &[(usize, usize)]) -> bool {
    if n <= 1 {
        return true;
    }
    let report = pebble_game(n, &simple(n, edges));
    report.rank == 2 * n - 3 && report.in_circuit().iter().all(|&inside| inside)
}

/// Whether the graph stays connected after removing any `k − 1` vertices and has more than
/// `k` vertices, for `k ≤ 3` (the complete graphs `K_{k+1}` are `k`-connected too).
///
/// # Complexity
/// `O(n · (n + m))` for `k = 3`.
pub fn k_connected(n: usize, edges: &[(usize, usize)], k: usize) -> bool {
    let e = simple(n, edges);
    if n <= k {
        return false;
    }
    let mut adj = vec![Vec::new(); n];
    for &(a, b) in &e {
        adj[a].push(b);
        adj[b].push(a);
    }
    match k {
        0 => true,
        1 => connected_without(&adj, None),
        2 => biconnected_without(&adj, None),
        _ => (0..n).all(|x| biconnected_without(&adj, Some(x))),
    }
}

fn connected_without(adj: &[Vec<usize>], removed: Option<usize>) -> bool {
    let n = adj.len();
    let Some(start) = (0..n).find(|v| Some(*v) != removed) else { return true };
    let mut seen = vec![false; n];
    seen[start] = true;
    let mut stack = vec![start];
    let mut count = 1;
    while let Some(x) = stack.pop() {
        for &y in &adj[x] {
            if !seen[y] && Some(y) != removed {
                seen[y] = true;
                count += 1;
                stack.push(y);
            }
        }
    }
    count == n - usize::from(removed.is_some())
}

/// Connected and without articulation point once `removed` is taken out (Hopcroft–Tarjan low
/// points, iteratively).
fn biconnected_without(adj: &[Vec<usize>], removed: Option<usize>) -> bool {
    if !connected_without(adj, removed) {
        return false;
    }
    let n = adj.len();
    let Some(root) = (0..n).find(|v| Some(*v) != removed) else { return true };
    let mut depth = vec![usize::MAX; n];
    let mut low = vec![0; n];
    let mut root_children = 0;
    // (vertex, parent, next neighbour index)
    let mut stack = vec![(root, usize::MAX, 0usize)];
    depth[root] = 0;
    low[root] = 0;
    while let Some(&mut (x, parent, ref mut i)) = stack.last_mut() {
        if *i < adj[x].len() {
            let y = adj[x][*i];
            *i += 1;
            if Some(y) == removed || y == parent {
                continue;
            }
            if depth[y] == usize::MAX {
                depth[y] = depth[x] + 1;
                low[y] = depth[y];
                if x == root {
                    root_children += 1;
                }
                stack.push((y, x, 0));
            } else {
                low[x] = low[x].min(depth[y]);
            }
        } else {
            stack.pop();
            if parent != usize::MAX {
                low[parent] = low[parent].min(low[x]);
                if parent != root && low[x] >= depth[parent] {
                    return false;
                }
            }
        }
    }
    root_children <= 1
}

/// Jackson and Jordán's characterisation: whether the graph (vertices `0..n`) is generically
/// globally rigid in the plane — complete on at most 3 vertices, or 3-connected and
/// redundantly rigid.
///
/// # Example
/// ```
/// use gcs_rigidity::jackson_jordan;
/// let k4 = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
/// assert!(jackson_jordan(4, &k4));
/// // K3,3: rigid, 3-connected, but no bar is redundant.
/// let k33: Vec<(usize, usize)> = (0..3).flat_map(|i| (3..6).map(move |j| (i, j))).collect();
/// assert!(!jackson_jordan(6, &k33));
/// ```
pub fn jackson_jordan(n: usize, edges: &[(usize, usize)]) -> bool {
    if n <= 3 {
        return simple(n, edges).len() == n * n.saturating_sub(1) / 2;
    }
    k_connected(n, edges, 3) && redundantly_rigid(n, edges)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn complete(n: usize) -> Vec<(usize, usize)> {
        (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j))).collect()
    }

    #[test]
    fn small_cases() {
        assert!(jackson_jordan(1, &[]) && jackson_jordan(2, &[(0, 1)]));
        assert!(!jackson_jordan(3, &[(0, 1), (1, 2)]));
        assert!(jackson_jordan(4, &complete(4)) && jackson_jordan(6, &complete(6)));
        // The wheel on a 5-cycle: yes; the triangular prism: rigid, 3-connected, not redundant.
        let mut w5: Vec<(usize, usize)> = (0..5).map(|i| (i, (i + 1) % 5)).collect();
        w5.extend((0..5).map(|i| (i, 5)));
        assert!(jackson_jordan(6, &w5));
        let prism = [(0, 1), (1, 2), (0, 2), (3, 4), (4, 5), (3, 5), (0, 3), (1, 4), (2, 5)];
        assert!(laman_rigid(6, &prism) && k_connected(6, &prism, 3));
        assert!(!redundantly_rigid(6, &prism) && !jackson_jordan(6, &prism));
        // Two K4 glued along an edge: redundantly rigid, only 2-connected.
        let mut two = complete(4);
        two.extend([(0, 4), (1, 4), (0, 5), (1, 5), (4, 5)]);
        assert!(redundantly_rigid(6, &two) && !k_connected(6, &two, 3));
        assert!(k_connected(6, &two, 2) && !jackson_jordan(6, &two));
    }
}
