//! Maximum flow on a compact residual graph, with incremental augmentation and rollback.
//!
//! [`FlowGraph`] is the low-level layer under [`Network`](crate::Network): it knows nothing
//! about geometry. Arcs are stored in pairs (arc `2i` forward, `2i + 1` its reverse) with their
//! residual capacities; the adjacency is a compressed (CSR) index rebuilt when arcs were added.
//!
//! What the flow-based rigidity algorithms need from it, and why it is not a plain max-flow:
//!
//! - [`FlowGraph::max_flow`] — Dinic's algorithm from the *current* flow, so a flow can be
//!   completed after capacities or arcs were added instead of recomputed;
//! - [`FlowGraph::augment_from`] — push up to a budget of extra units from a set of seed nodes
//!   (a virtual node attached to them by arcs of infinite capacity) to the sink: this is how an
//!   overload is distributed on top of an existing maximum flow, in `O(budget · (V + E))`;
//! - [`FlowGraph::reachable`] — the nodes reachable from the seeds in the residual graph, which
//!   is where the over-dense subsystem is read (flow paper, §4.1: "the objects reachable from the
//!   overloaded constraint-node in the residual graph");
//! - [`FlowGraph::checkpoint`] / [`FlowGraph::rollback`] — a journal of the pushes, so one base
//!   flow serves many overload trials at the cost of the trial only.

/// The capacity used for "infinite" arcs (constraint → object). Large enough never to be the
/// bottleneck of any flow in this crate, small enough that sums do not overflow.
pub const INFINITE: u64 = u64::MAX / 4;

const NONE: u32 = u32::MAX;

/// A directed graph with arc capacities and a flow, stored as its residual graph.
///
/// # Example
/// ```
/// use gcs_rigidity::flow::FlowGraph;
///
/// // s → a → t and s → b → t, with a → b in between.
/// let mut g = FlowGraph::new(4);
/// let (s, a, b, t) = (0, 1, 2, 3);
/// g.add_arc(s, a, 3);
/// g.add_arc(s, b, 1);
/// g.add_arc(a, b, 2);
/// g.add_arc(a, t, 1);
/// let bt = g.add_arc(b, t, 5);
/// assert_eq!(g.max_flow(s, t), 4);
/// assert_eq!(g.flow(bt), 3);
/// // An overload of 3 attached to `b`: only 2 more units reach the sink (b → t has room for 2).
/// g.checkpoint();
/// assert_eq!(g.augment_from(&[b], t, 3), 2);
/// assert!(!g.reachable(&[b])[t]);
/// g.rollback();
/// assert_eq!(g.flow(bt), 3);
/// ```
#[derive(Clone, Debug, Default)]
pub struct FlowGraph {
    nodes: usize,
    head: Vec<u32>,
    capacity: Vec<u64>,
    residual: Vec<u64>,
    start: Vec<u32>,
    order: Vec<u32>,
    csr_arcs: usize,
    journal: Option<Vec<(u32, u64)>>,
}

impl FlowGraph {
    /// An empty graph with `nodes` nodes numbered `0..nodes`.
    pub fn new(nodes: usize) -> FlowGraph {
        FlowGraph { nodes, ..FlowGraph::default() }
    }

    /// Adds a node and returns its number.
    pub fn add_node(&mut self) -> usize {
        self.nodes += 1;
        self.nodes - 1
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes
    }

    /// Number of arcs added (reverse arcs not counted).
    pub fn arc_count(&self) -> usize {
        self.head.len() / 2
    }

    /// Adds an arc `from → to` of capacity `capacity` with no flow, and returns its id (use it
    /// with [`flow`](Self::flow), [`residual`](Self::residual), [`endpoints`](Self::endpoints)).
    ///
    /// # Panics
    /// When `from` or `to` is not a node of the graph.
    pub fn add_arc(&mut self, from: usize, to: usize, capacity: u64) -> usize {
        assert!(from < self.nodes && to < self.nodes, "arc endpoint out of range");
        let id = self.head.len();
        self.head.push(to as u32);
        self.head.push(from as u32);
        let capacity = capacity.min(INFINITE);
        self.capacity.push(capacity);
        self.capacity.push(0);
        self.residual.push(capacity);
        self.residual.push(0);
        id
    }

    /// Tail and head of an arc.
    pub fn endpoints(&self, arc: usize) -> (usize, usize) {
        (self.head[arc ^ 1] as usize, self.head[arc] as usize)
    }

    /// Capacity of an arc.
    pub fn capacity(&self, arc: usize) -> u64 {
        self.capacity[arc]
    }

    /// Flow on an arc (for a reverse arc: 0).
    pub fn flow(&self, arc: usize) -> u64 {
        self.capacity[arc].saturating_sub(self.residual[arc])
    }

    /// Residual capacity of an arc: how much more flow it can take.
    pub fn residual(&self, arc: usize) -> u64 {
        self.residual[arc]
    }

    /// Starts recording every change of the flow, so that [`rollback`](Self::rollback) can
    /// restore the flow as it is now. A checkpoint already open is replaced.
    pub fn checkpoint(&mut self) {
        self.journal = Some(Vec::new());
    }

    /// Restores the flow of the last [`checkpoint`](Self::checkpoint) and stops recording.
    /// Without an open checkpoint, does nothing.
    pub fn rollback(&mut self) {
        if let Some(journal) = self.journal.take() {
            for &(arc, amount) in journal.iter().rev() {
                let arc = arc as usize;
                self.residual[arc] += amount;
                self.residual[arc ^ 1] -= amount;
            }
        }
    }

    /// Keeps the flow as it is and stops recording.
    pub fn commit(&mut self) {
        self.journal = None;
    }

    fn push(&mut self, arc: usize, amount: u64) {
        self.residual[arc] -= amount;
        self.residual[arc ^ 1] += amount;
        if let Some(journal) = &mut self.journal {
            journal.push((arc as u32, amount));
        }
    }

    /// Rebuilds the compressed adjacency if arcs were added since it was built.
    fn index(&mut self) {
        if self.csr_arcs == self.head.len() && self.start.len() == self.nodes + 1 {
            return;
        }
        let mut start = vec![0u32; self.nodes + 1];
        for arc in 0..self.head.len() {
            start[self.head[arc ^ 1] as usize + 1] += 1;
        }
        for v in 0..self.nodes {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut order = vec![0u32; self.head.len()];
        for arc in 0..self.head.len() {
            let tail = self.head[arc ^ 1] as usize;
            order[fill[tail] as usize] = arc as u32;
            fill[tail] += 1;
        }
        self.start = start;
        self.order = order;
        self.csr_arcs = self.head.len();
    }

    fn out_arcs(&self, v: usize) -> &[u32] {
        &self.order[self.start[v] as usize..self.start[v + 1] as usize]
    }

    /// Completes the current flow into a maximum `s`–`t` flow (Dinic's algorithm: blocking
    /// flows along BFS levels) and returns the value added.
    ///
    /// # Complexity
    /// `O(V² E)` in general, `O(E √V)` on unit-capacity bipartite-like networks.
    pub fn max_flow(&mut self, s: usize, t: usize) -> u64 {
        if s == t || s >= self.nodes || t >= self.nodes {
            return 0;
        }
        self.index();
        let mut total = 0u64;
        let mut level = vec![NONE; self.nodes];
        let mut queue = Vec::with_capacity(self.nodes);
        let mut next = vec![0u32; self.nodes];
        let mut path: Vec<u32> = Vec::new();
        loop {
            // BFS levels.
            level.fill(NONE);
            queue.clear();
            level[s] = 0;
            queue.push(s as u32);
            let mut qi = 0;
            while qi < queue.len() {
                let u = queue[qi] as usize;
                qi += 1;
                for &arc in self.out_arcs(u) {
                    let v = self.head[arc as usize] as usize;
                    if self.residual[arc as usize] > 0 && level[v] == NONE {
                        level[v] = level[u] + 1;
                        queue.push(v as u32);
                    }
                }
            }
            if level[t] == NONE {
                return total;
            }
            // Blocking flow by iterative DFS with current-arc pointers.
            next.copy_from_slice(&self.start[..self.nodes]);
            path.clear();
            let mut u = s;
            loop {
                if u == t {
                    let amount = path.iter().map(|&a| self.residual[a as usize]).min().unwrap_or(0);
                    for &arc in &path {
                        self.push(arc as usize, amount);
                    }
                    total = total.saturating_add(amount);
                    // Retreat to the tail of the first saturated arc.
                    let cut = path.iter().position(|&a| self.residual[a as usize] == 0);
                    let k = cut.unwrap_or(0);
                    path.truncate(k);
                    u = match path.last() {
                        Some(&a) => self.head[a as usize] as usize,
                        None => s,
                    };
                    continue;
                }
                let mut advanced = false;
                while next[u] < self.start[u + 1] {
                    let arc = self.order[next[u] as usize] as usize;
                    let v = self.head[arc] as usize;
                    if self.residual[arc] > 0 && level[v] == level[u] + 1 {
                        path.push(arc as u32);
                        u = v;
                        advanced = true;
                        break;
                    }
                    next[u] += 1;
                }
                if advanced {
                    continue;
                }
                // Dead end: no arc of u leads on; forget u for this phase.
                level[u] = NONE;
                match path.pop() {
                    Some(arc) => {
                        u = self.head[arc as usize ^ 1] as usize;
                        next[u] += 1;
                    }
                    None => break,
                }
            }
        }
    }

    /// Pushes up to `budget` extra units from the seed nodes to `t` on top of the current flow,
    /// as if a virtual source were joined to every seed by an arc of infinite capacity, and
    /// returns how much was pushed. Shortest augmenting paths (BFS), so at most `budget`
    /// searches.
    ///
    /// When the current flow saturates every arc leaving the real source, no augmenting path
    /// can pass through it (it could enter the source but never leave it), so the flow on those
    /// arcs is left alone: the extra units come from the seeds only, which is what the overload
    /// reading of the flow paper needs on top of an earlier maximum flow.
    ///
    /// # Complexity
    /// `O(budget · (V + E))`.
    pub fn augment_from(&mut self, seeds: &[usize], t: usize, budget: u64) -> u64 {
        if t >= self.nodes {
            return 0;
        }
        self.index();
        let mut pushed = 0u64;
        let mut parent = vec![NONE; self.nodes];
        let mut seen = vec![false; self.nodes];
        let mut queue: Vec<u32> = Vec::with_capacity(self.nodes);
        while pushed < budget {
            seen.fill(false);
            queue.clear();
            for &s in seeds {
                if s < self.nodes && s != t && !seen[s] {
                    seen[s] = true;
                    parent[s] = NONE;
                    queue.push(s as u32);
                }
            }
            let mut qi = 0;
            let mut found = false;
            'bfs: while qi < queue.len() {
                let u = queue[qi] as usize;
                qi += 1;
                for &arc in self.out_arcs(u) {
                    let v = self.head[arc as usize] as usize;
                    if self.residual[arc as usize] > 0 && !seen[v] {
                        seen[v] = true;
                        parent[v] = arc;
                        if v == t {
                            found = true;
                            break 'bfs;
                        }
                        queue.push(v as u32);
                    }
                }
            }
            if !found {
                break;
            }
            let mut amount = budget - pushed;
            let mut v = t;
            while parent[v] != NONE {
                let arc = parent[v] as usize;
                amount = amount.min(self.residual[arc]);
                v = self.head[arc ^ 1] as usize;
            }
            let mut v = t;
            while parent[v] != NONE {
                let arc = parent[v] as usize;
                self.push(arc, amount);
                v = self.head[arc ^ 1] as usize;
            }
            pushed += amount;
        }
        pushed
    }

    /// The nodes reachable from the seeds along arcs of positive residual capacity (the seeds
    /// included), as a membership vector indexed by node.
    pub fn reachable(&mut self, seeds: &[usize]) -> Vec<bool> {
        self.index();
        let mut seen = vec![false; self.nodes];
        let mut stack: Vec<usize> = Vec::new();
        for &s in seeds {
            if s < self.nodes && !seen[s] {
                seen[s] = true;
                stack.push(s);
            }
        }
        while let Some(u) = stack.pop() {
            for &arc in self.out_arcs(u) {
                let v = self.head[arc as usize] as usize;
                if self.residual[arc as usize] > 0 && !seen[v] {
                    seen[v] = true;
                    stack.push(v);
                }
            }
        }
        seen
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcs_model::rng::SplitMix64;

    /// Minimum cut by brute force over every node set containing `s` and not `t`.
    fn brute_min_cut(n: usize, arcs: &[(usize, usize, u64)], s: usize, t: usize) -> u64 {
        let mut best = u64::MAX;
        for mask in 0u32..(1 << n) {
            if mask & (1 << s) == 0 || mask & (1 << t) != 0 {
                continue;
            }
            let cut: u64 = arcs
                .iter()
                .filter(|(u, v, _)| mask & (1 << u) != 0 && mask & (1 << v) == 0)
                .map(|(_, _, c)| *c)
                .sum();
            best = best.min(cut);
        }
        best
    }

    fn random_graph(rng: &mut SplitMix64) -> (usize, Vec<(usize, usize, u64)>) {
        let n = 2 + rng.below(7) as usize;
        let m = rng.below(3 * n as u64 + 1) as usize;
        let arcs = (0..m)
            .map(|_| {
                let u = rng.below(n as u64) as usize;
                let v = rng.below(n as u64) as usize;
                (u, v, rng.below(10))
            })
            .collect();
        (n, arcs)
    }

    fn check_flow_conservation(g: &FlowGraph, arcs: &[usize], s: usize, t: usize) -> u64 {
        let mut balance = vec![0i128; g.node_count()];
        for &a in arcs {
            let (u, v) = g.endpoints(a);
            assert!(g.flow(a) <= g.capacity(a));
            balance[u] -= g.flow(a) as i128;
            balance[v] += g.flow(a) as i128;
        }
        for (v, b) in balance.iter().enumerate() {
            if v != s && v != t {
                assert_eq!(*b, 0, "conservation at {v}");
            }
        }
        balance[t] as u64
    }

    #[test]
    fn max_flow_equals_brute_force_min_cut() {
        let mut rng = SplitMix64::new(20240601);
        for _ in 0..400 {
            let (n, arcs) = random_graph(&mut rng);
            let (s, t) = (0, n - 1);
            let mut g = FlowGraph::new(n);
            let ids: Vec<usize> = arcs.iter().map(|&(u, v, c)| g.add_arc(u, v, c)).collect();
            let value = g.max_flow(s, t);
            assert_eq!(value, brute_min_cut(n, &arcs, s, t), "{arcs:?}");
            assert_eq!(check_flow_conservation(&g, &ids, s, t), value);
            // Max flow ⇔ t unreachable from s in the residual graph.
            assert!(!g.reachable(&[s])[t]);
        }
    }

    #[test]
    fn incremental_augmentation_reaches_the_same_maximum() {
        // Split the source's capacity: max flow with part of it, then the rest by augmenting
        // from the source: the total is the maximum flow of the whole graph.
        let mut rng = SplitMix64::new(77);
        for _ in 0..300 {
            let (n, arcs) = random_graph(&mut rng);
            let (s, t) = (0, n - 1);
            let mut full = FlowGraph::new(n);
            for &(u, v, c) in &arcs {
                full.add_arc(u, v, c);
            }
            let expected = full.max_flow(s, t);
            let mut g = FlowGraph::new(n);
            for &(u, v, c) in &arcs {
                g.add_arc(u, v, c);
            }
            let first = g.max_flow(s, t);
            assert_eq!(first, expected);
            // Nothing more from the source by augmentation either.
            g.checkpoint();
            assert_eq!(g.augment_from(&[s], t, 1000), 0);
            g.rollback();
            // Augmenting from a middle node pushes exactly what a max flow from it would push
            // in the residual graph (checked against a fresh max flow with a super source).
            if n > 2 {
                let mid = 1 + rng.below((n - 2) as u64) as usize;
                let budget = rng.below(6);
                let before: Vec<u64> = (0..g.arc_count()).map(|a| g.flow(2 * a)).collect();
                g.checkpoint();
                let pushed = g.augment_from(&[mid], t, budget);
                assert!(pushed <= budget);
                if pushed < budget {
                    assert!(!g.reachable(&[mid])[t]);
                }
                g.rollback();
                let after: Vec<u64> = (0..g.arc_count()).map(|a| g.flow(2 * a)).collect();
                assert_eq!(before, after, "rollback restores the flow");
            }
        }
    }

    #[test]
    fn augment_budget_and_seeds() {
        // Two seeds sharing one bottleneck arc of capacity 3.
        let mut g = FlowGraph::new(4);
        g.add_arc(0, 2, INFINITE);
        g.add_arc(1, 2, INFINITE);
        let bottleneck = g.add_arc(2, 3, 3);
        assert_eq!(g.augment_from(&[0, 1], 3, 2), 2);
        assert_eq!(g.augment_from(&[0, 1], 3, 5), 1);
        assert_eq!(g.flow(bottleneck), 3);
        let r = g.reachable(&[0]);
        assert_eq!(r, vec![true, false, true, false]);
        // Degenerate calls do nothing.
        assert_eq!(g.augment_from(&[3], 3, 5), 0);
        assert_eq!(g.max_flow(1, 1), 0);
        assert_eq!(g.max_flow(0, 9), 0);
    }
}
