//! The structure of a sparse system: the bipartite graph between rows (equations) and columns
//! (unknowns), a maximum matching (Hopcroft–Karp) and the Dulmage–Mendelsohn decomposition,
//! coarse (over-, well-, under-determined) and fine (the well part's blocks in solving order).
//! Used by the structural analysis (`gcs-rigidity`'s `dm`, which reads it at the level of a
//! model) and by the witness placement (`gcs-jacobian`, a square system solved block by block).

const NONE: u32 = u32::MAX;

/// A bipartite graph between rows (equations) and columns (unknowns), stored compactly.
#[derive(Clone, Debug, Default)]
pub struct Bipartite {
    cols: usize,
    start: Vec<u32>,
    adj: Vec<u32>,
}

impl Bipartite {
    /// A bipartite graph with `cols` columns and one row per item of `rows`, listing the
    /// columns it is adjacent to. Columns out of range are ignored.
    pub fn new<R, C>(cols: usize, rows: R) -> Bipartite
    where
        R: IntoIterator<Item = C>,
        C: IntoIterator<Item = usize>,
    {
        let mut start = vec![0u32];
        let mut adj = Vec::new();
        for row in rows {
            let begin = adj.len();
            adj.extend(row.into_iter().filter(|&c| c < cols).map(|c| c as u32));
            adj[begin..].sort_unstable();
            let mut w = begin;
            for r in begin..adj.len() {
                if w == begin || adj[r] != adj[w - 1] {
                    adj[w] = adj[r];
                    w += 1;
                }
            }
            adj.truncate(w);
            start.push(adj.len() as u32);
        }
        Bipartite { cols, start, adj }
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.start.len() - 1
    }

    /// Number of columns.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// The columns of a row.
    pub fn row(&self, r: usize) -> &[u32] {
        &self.adj[self.start[r] as usize..self.start[r + 1] as usize]
    }

    fn transpose(&self) -> Bipartite {
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); self.cols];
        for r in 0..self.rows() {
            for &c in self.row(r) {
                cols[c as usize].push(r);
            }
        }
        Bipartite::new(self.rows(), cols)
    }
}

/// A matching of a bipartite graph.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Matching {
    /// The column matched to each row.
    pub row_mate: Vec<Option<usize>>,
    /// The row matched to each column.
    pub col_mate: Vec<Option<usize>>,
    /// Number of matched pairs.
    pub size: usize,
}

/// A maximum matching by Hopcroft and Karp's algorithm: phases of a BFS from the free rows
/// that layers the graph, then vertex-disjoint shortest augmenting paths by DFS (iterative,
/// so long paths do not exhaust the stack).
///
/// # Complexity
/// `O(E √V)`.
///
/// # Example
/// ```
/// use gcs_rank::bipartite::{hopcroft_karp, Bipartite};
/// // Rows 0 and 1 both want column 0; row 1 can also take column 1.
/// let g = Bipartite::new(2, vec![vec![0], vec![0, 1]]);
/// assert_eq!(hopcroft_karp(&g).size, 2);
/// ```
pub fn hopcroft_karp(g: &Bipartite) -> Matching {
    let rows = g.rows();
    let mut row_mate = vec![NONE; rows];
    let mut col_mate = vec![NONE; g.cols];
    let mut dist = vec![NONE; rows];
    let mut queue: Vec<u32> = Vec::with_capacity(rows);
    let mut next = vec![0u32; rows];
    let mut stack: Vec<u32> = Vec::new();
    let mut via: Vec<u32> = Vec::new();
    let mut size = 0;
    loop {
        queue.clear();
        for r in 0..rows {
            if row_mate[r] == NONE {
                dist[r] = 0;
                queue.push(r as u32);
            } else {
                dist[r] = NONE;
            }
        }
        let mut found = false;
        let mut qi = 0;
        while qi < queue.len() {
            let r = queue[qi] as usize;
            qi += 1;
            for &c in g.row(r) {
                let r2 = col_mate[c as usize];
                if r2 == NONE {
                    found = true;
                } else if dist[r2 as usize] == NONE {
                    dist[r2 as usize] = dist[r] + 1;
                    queue.push(r2);
                }
            }
        }
        if !found {
            break;
        }
        next.copy_from_slice(&g.start[..rows]);
        for r0 in 0..rows {
            if row_mate[r0] != NONE || dist[r0] != 0 {
                continue;
            }
            stack.clear();
            via.clear();
            stack.push(r0 as u32);
            while let Some(&r) = stack.last() {
                let r = r as usize;
                if next[r] == g.start[r + 1] {
                    dist[r] = NONE; // dead end for this phase
                    stack.pop();
                    via.pop();
                    continue;
                }
                let c = g.adj[next[r] as usize];
                next[r] += 1;
                let r2 = col_mate[c as usize];
                if r2 == NONE {
                    // Augment along the stack.
                    via.push(c);
                    for (&row, &col) in stack.iter().zip(via.iter()) {
                        row_mate[row as usize] = col;
                        col_mate[col as usize] = row;
                    }
                    size += 1;
                    break;
                } else if dist[r2 as usize] == dist[r] + 1 {
                    stack.push(r2);
                    via.push(c);
                }
            }
        }
    }
    let opt = |v: Vec<u32>| v.into_iter().map(|x| (x != NONE).then_some(x as usize)).collect();
    Matching { row_mate: opt(row_mate), col_mate: opt(col_mate), size }
}

/// The coarse part a node belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Part {
    /// Over-determined (more equations than unknowns).
    Over,
    /// Well-determined (perfectly matched).
    Well,
    /// Under-determined (more unknowns than equations).
    Under,
}

/// The Dulmage–Mendelsohn decomposition of a bipartite graph, node by node.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DmNodes {
    /// The coarse part of every row.
    pub row_part: Vec<Part>,
    /// The coarse part of every column.
    pub col_part: Vec<Part>,
    /// The fine blocks of the well part in solving order: (rows, columns), both sorted.
    pub blocks: Vec<(Vec<usize>, Vec<usize>)>,
    /// The maximum matching the decomposition was read from.
    pub matching: Matching,
}

/// The Dulmage–Mendelsohn decomposition of a bipartite graph (rows = equations, columns =
/// unknowns): coarse parts by alternating reachability, fine blocks of the well part by
/// Tarjan's strongly connected components.
///
/// # Complexity
/// `O(E √V)` for the matching, `O(V + E)` for the rest.
pub fn dulmage_mendelsohn(g: &Bipartite) -> DmNodes {
    let matching = hopcroft_karp(g);
    let (rows, cols) = (g.rows(), g.cols);
    let mut row_part = vec![Part::Well; rows];
    let mut col_part = vec![Part::Well; cols];
    // Over: from unmatched rows, row → all its columns → their matched rows.
    let mut stack: Vec<usize> = (0..rows).filter(|&r| matching.row_mate[r].is_none()).collect();
    for &r in &stack {
        row_part[r] = Part::Over;
    }
    while let Some(r) = stack.pop() {
        for &c in g.row(r) {
            let c = c as usize;
            if col_part[c] == Part::Over {
                continue;
            }
            col_part[c] = Part::Over;
            if let Some(r2) = matching.col_mate[c]
                && row_part[r2] != Part::Over
            {
                row_part[r2] = Part::Over;
                stack.push(r2);
            }
        }
    }
    // Under: from unmatched columns, column → all its rows → their matched columns.
    let t = g.transpose();
    let mut stack: Vec<usize> = (0..cols).filter(|&c| matching.col_mate[c].is_none()).collect();
    for &c in &stack {
        col_part[c] = Part::Under;
    }
    while let Some(c) = stack.pop() {
        for &r in t.row(c) {
            let r = r as usize;
            if row_part[r] == Part::Under {
                continue;
            }
            row_part[r] = Part::Under;
            if let Some(c2) = matching.row_mate[r]
                && col_part[c2] != Part::Under
            {
                col_part[c2] = Part::Under;
                stack.push(c2);
            }
        }
    }
    let blocks = fine_blocks(g, &matching, &row_part, &col_part);
    DmNodes { row_part, col_part, blocks, matching }
}

/// Strongly connected components of the well part's digraph (row `r` → row matched to a well
/// column of `r`), by an iterative Tarjan; components come out dependencies first.
fn fine_blocks(
    g: &Bipartite,
    matching: &Matching,
    row_part: &[Part],
    col_part: &[Part],
) -> Vec<(Vec<usize>, Vec<usize>)> {
    let rows = g.rows();
    let succ = |r: usize| {
        g.row(r).iter().filter_map(move |&c| {
            let c = c as usize;
            if col_part[c] != Part::Well {
                return None;
            }
            matching.col_mate[c].filter(|&r2| r2 != r)
        })
    };
    let mut index = vec![NONE; rows];
    let mut low = vec![0u32; rows];
    let mut on_stack = vec![false; rows];
    let mut scc_stack: Vec<usize> = Vec::new();
    let mut counter = 0u32;
    let mut blocks = Vec::new();
    // Call stack of (row, position in its adjacency).
    let mut calls: Vec<(usize, usize)> = Vec::new();
    for root in 0..rows {
        if row_part[root] != Part::Well || index[root] != NONE {
            continue;
        }
        calls.push((root, 0));
        index[root] = counter;
        low[root] = counter;
        counter += 1;
        scc_stack.push(root);
        on_stack[root] = true;
        while let Some(top) = calls.last_mut() {
            let (v, pos) = *top;
            top.1 += 1;
            let next = succ(v).nth(pos);
            match next {
                Some(w) if index[w] == NONE => {
                    index[w] = counter;
                    low[w] = counter;
                    counter += 1;
                    scc_stack.push(w);
                    on_stack[w] = true;
                    calls.push((w, 0));
                }
                Some(w) => {
                    if on_stack[w] {
                        low[v] = low[v].min(index[w]);
                    }
                }
                None => {
                    calls.pop();
                    if let Some(&(parent, _)) = calls.last() {
                        low[parent] = low[parent].min(low[v]);
                    }
                    if low[v] == index[v] {
                        let mut block_rows = Vec::new();
                        while let Some(w) = scc_stack.pop() {
                            on_stack[w] = false;
                            block_rows.push(w);
                            if w == v {
                                break;
                            }
                        }
                        block_rows.sort_unstable();
                        let mut block_cols: Vec<usize> =
                            block_rows.iter().filter_map(|&r| matching.row_mate[r]).collect();
                        block_cols.sort_unstable();
                        blocks.push((block_rows, block_cols));
                    }
                }
            }
        }
    }
    blocks
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small xorshift generator (the tests' random graphs).
    struct XorShift(u64);
    impl XorShift {
        fn new(seed: u64) -> XorShift {
            XorShift(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
        }
        fn below(&mut self, n: u64) -> u64 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            self.0 % n
        }
    }

    fn brute_max_matching(g: &Bipartite) -> usize {
        // Exhaustive over rows: each row picks one of its columns or none.
        fn go(g: &Bipartite, r: usize, used: &mut Vec<bool>) -> usize {
            if r == g.rows() {
                return 0;
            }
            let mut best = go(g, r + 1, used);
            for &c in g.row(r) {
                if !used[c as usize] {
                    used[c as usize] = true;
                    best = best.max(1 + go(g, r + 1, used));
                    used[c as usize] = false;
                }
            }
            best
        }
        go(g, 0, &mut vec![false; g.cols()])
    }

    fn random_bipartite(rng: &mut XorShift) -> Bipartite {
        let rows = rng.below(7) as usize;
        let cols = rng.below(7) as usize;
        let adj: Vec<Vec<usize>> =
            (0..rows).map(|_| (0..cols).filter(|_| rng.below(3) == 0).collect()).collect();
        Bipartite::new(cols, adj)
    }

    #[test]
    fn hopcroft_karp_is_maximum() {
        let mut rng = XorShift::new(5);
        for _ in 0..500 {
            let g = random_bipartite(&mut rng);
            let m = hopcroft_karp(&g);
            assert_eq!(m.size, brute_max_matching(&g));
            for (r, c) in m.row_mate.iter().enumerate() {
                if let Some(c) = c {
                    assert!(g.row(r).contains(&(*c as u32)));
                    assert_eq!(m.col_mate[*c], Some(r));
                }
            }
        }
    }

    #[test]
    fn dm_parts_are_consistent() {
        let mut rng = XorShift::new(11);
        for _ in 0..500 {
            let g = random_bipartite(&mut rng);
            let d = dulmage_mendelsohn(&g);
            let count = |p: Part| {
                (
                    d.row_part.iter().filter(|x| **x == p).count(),
                    d.col_part.iter().filter(|x| **x == p).count(),
                )
            };
            let (ro, co) = count(Part::Over);
            let (rw, cw) = count(Part::Well);
            let (ru, cu) = count(Part::Under);
            assert!(ro > co || ro == 0 && co == 0, "over has more rows");
            assert_eq!(rw, cw, "well is square");
            assert!(cu > ru || ru == 0 && cu == 0, "under has more columns");
            // No edge from an over row to a non-over column, nor from a well row to an under
            // column (block triangular form).
            for r in 0..g.rows() {
                for &c in g.row(r) {
                    let (rp, cp) = (d.row_part[r], d.col_part[c as usize]);
                    if rp == Part::Over {
                        assert_eq!(cp, Part::Over);
                    }
                    if rp == Part::Well {
                        assert_ne!(cp, Part::Under);
                    }
                }
            }
            // Blocks partition the well part, each square, in solving order: a block's rows
            // use well columns of earlier blocks or its own only.
            let mut block_of_col = vec![usize::MAX; g.cols()];
            let mut covered = 0;
            for (k, (rs, cs)) in d.blocks.iter().enumerate() {
                assert_eq!(rs.len(), cs.len());
                covered += rs.len();
                for &c in cs {
                    block_of_col[c] = k;
                }
            }
            assert_eq!(covered, rw);
            for (k, (rs, _)) in d.blocks.iter().enumerate() {
                for &r in rs {
                    for &c in g.row(r) {
                        if d.col_part[c as usize] == Part::Well {
                            assert!(block_of_col[c as usize] <= k);
                        }
                    }
                }
            }
        }
    }
}
