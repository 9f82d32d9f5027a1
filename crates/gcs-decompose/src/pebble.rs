//! The (2,3) pebble game of Jacobs and Hendrickson (*An algorithm for two-dimensional
//! rigidity percolation: the pebble game*, J. Comput. Phys. 137, 1997), in the form of Lee
//! and Streinu (*Pebble game algorithms and sparse graphs*, Discrete Math. 308, 2008): the
//! generic rigidity of 2D bar frameworks, without numbers.
//!
//! By Laman's theorem the generic rigidity matroid of a 2D bar framework is the
//! (2,3)-sparsity matroid of its graph, so for points joined by distances in the plane this
//! answers exactly what the witness method answers at a generic configuration (the witness
//! decides it with probability and the game with certainty): the rank, which bars are
//! redundant and with which earlier bars (the fundamental circuits, taken in the order the
//! bars are given, as the witness's greedy elimination takes its rows), and the maximal rigid
//! components.
//!
//! **The game.** Every vertex holds two pebbles; a bar is accepted (independent) when four
//! pebbles can be gathered on its two end points, and is then covered by a pebble of one of
//! them and directed away from it. A pebble is fetched along a directed path, reversing it.
//! When the fourth pebble cannot be fetched, the vertices reachable from the two ends (which
//! then hold three pebbles) span the smallest tight subgraph containing both — a set `X`
//! whose accepted bars number `2|X| − 3` — and the bar's fundamental circuit is the bar with
//! the accepted bars inside `X`. (A tight set containing both ends is closed under the
//! directed bars, since its three pebbles are on the ends: so it contains everything reachable
//! from them; and the reachable set is tight, since no pebble was found in it.)
//!
//! **Components.** A maximal rigid component is found from any bar not yet in one: with three
//! pebbles on its ends, a vertex is rigid with them exactly when no pebble can be fetched to it
//! (Lee–Streinu, §5). Each bar lies in exactly one component; vertices on no bar are
//! components of their own.
//!
//! **Cost.** Each insertion is at most four depth-first searches, `O(n + m)` each: `O(n·m)`
//! in the worst case; a bar to a vertex with at most one bar needs none. On random Laman
//! frameworks it grows as n^1.2 to n^1.6 (1,000 to 1,000,000 points: `BENCHMARKS.md`). The
//! components phase is linear per component: its searches are fenced by the vertices already
//! found rigid, so each vertex is explored once.

/// What the pebble game finds for a 2D bar framework.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PebbleReport {
    /// The rank of the generic rigidity matrix: the number of independent bars.
    pub rank: usize,
    /// For each bar, in the order given: `None` when independent of the bars before it, else
    /// the indices of the earlier independent bars of its fundamental circuit, ascending (a
    /// bar from a vertex to itself has an empty circuit: its row is zero).
    pub circuits: Vec<Option<Vec<usize>>>,
    /// The maximal rigid components as vertex sets, each ascending, ordered by their first
    /// vertex; every bar's two end points lie in exactly one of them, and a vertex on no bar
    /// is a component of its own.
    pub components: Vec<Vec<usize>>,
}

impl PebbleReport {
    /// The generic degrees of freedom left beyond the three trivial motions of the plane
    /// (for two or more vertices; a single vertex has two and none is trivial beyond them).
    pub fn dof(&self, vertices: usize) -> usize {
        match vertices {
            0 => 0,
            1 => 0,
            n => (2 * n).saturating_sub(self.rank).saturating_sub(3),
        }
    }

    /// For each bar, whether it lies in some circuit (is not a coloop): the dependent bars,
    /// and the independent ones in the fundamental circuit of some dependent bar — a basis
    /// element is in a circuit exactly when it is in one of its fundamental circuits (its
    /// fundamental cocircuit is then more than itself). A framework whose bars all lie in
    /// circuits, and that is rigid, is *redundantly rigid*: it stays rigid without any one bar.
    pub fn in_circuit(&self) -> Vec<bool> {
        let mut inside: Vec<bool> = self.circuits.iter().map(Option::is_some).collect();
        for c in self.circuits.iter().flatten() {
            for &b in c {
                inside[b] = true;
            }
        }
        inside
    }
}

/// The pebble game's state: free pebbles per vertex and the accepted bars, directed (for
/// callers that add and remove bars themselves, as the redundant-rigidity test does).
#[derive(Clone, Debug)]
pub struct Game {
    pebbles: Vec<u8>,
    /// The free pebbles in all.
    free: usize,
    /// Out-neighbours: `out[u]` holds `(v, bar)` for each accepted bar covered by `u` (at
    /// most two: a vertex's free pebbles and out-bars make two).
    out: Vec<Vec<(u32, u32)>>,
    /// Accepted bars at each vertex, either direction.
    degree: Vec<u32>,
    /// Search marks (by generation, so that nothing is cleared between searches).
    seen: Vec<u32>,
    /// Vertices every search skips while `fence[x] == fence_id` (the vertices found rigid
    /// with a component's bar: no pebble is reachable from them, so a search need not enter).
    fence: Vec<u32>,
    fence_id: u32,
    generation: u32,
    /// The search's predecessor of each vertex: `(vertex, index in its out list)`.
    parent: Vec<(u32, u32)>,
    /// How far each vertex's out list has been scanned in the current search.
    cursor: Vec<u32>,
    stack: Vec<u32>,
    /// The vertices the last search marked, in order (the root first).
    trail: Vec<u32>,
}

impl Game {
    /// `n` vertices with two pebbles each, no bar.
    pub fn new(n: usize) -> Game {
        Game {
            pebbles: vec![2; n],
            free: 2 * n,
            out: vec![Vec::new(); n],
            degree: vec![0; n],
            seen: vec![0; n],
            fence: vec![0; n],
            fence_id: u32::MAX,
            generation: 0,
            parent: vec![(0, 0); n],
            cursor: vec![0; n],
            stack: Vec::new(),
            trail: Vec::new(),
        }
    }

    /// Accepts the bar `uv` (numbered `bar`) if it is independent of the accepted ones: four
    /// pebbles gathered on its ends. Returns whether it was.
    pub fn add(&mut self, u: usize, v: usize, bar: usize) -> bool {
        if u == v {
            return false;
        }
        // A bar to a vertex with at most one accepted bar, not already joined to the other end,
        // is independent without a search: a set of vertices holding that end spans at most
        // two more bars than it does without it, one vertex fewer (`2|X| − 3` stays met), and
        // the pair itself one bar. That end has a free pebble (at most one out-bar) to cover
        // it. (Henneberg's first move: the common case of a sketch built point by point.)
        for (x, y) in [(v, u), (u, v)] {
            if self.degree[x] <= 1 && !self.joined(x, y) {
                self.cover(x, y, bar);
                return true;
            }
        }
        if !self.gather(u, v, 4) {
            return false;
        }
        self.cover(u, v, bar);
        true
    }

    /// Covers the bar `xy` with a pebble of `x`.
    fn cover(&mut self, x: usize, y: usize, bar: usize) {
        debug_assert!(self.pebbles[x] > 0);
        self.pebbles[x] -= 1;
        self.free -= 1;
        self.out[x].push((y as u32, bar as u32));
        self.degree[x] += 1;
        self.degree[y] += 1;
    }

    /// Whether an accepted bar joins `x` and `y` (out-lists have at most two entries).
    fn joined(&self, x: usize, y: usize) -> bool {
        self.out[x].iter().any(|&(t, _)| t as usize == y)
            || self.out[y].iter().any(|&(t, _)| t as usize == x)
    }

    /// Removes the accepted bar `uv` (in whichever direction it has); its pebble is freed.
    pub fn remove(&mut self, u: usize, v: usize) {
        for (a, b) in [(u, v), (v, u)] {
            if let Some(k) = self.out[a].iter().position(|&(t, _)| t as usize == b) {
                self.out[a].swap_remove(k);
                self.pebbles[a] += 1;
                self.free += 1;
                self.degree[a] -= 1;
                self.degree[b] -= 1;
                return;
            }
        }
    }

    /// The game on part of the framework, as if played on the kept bars alone: `vertex[v]` is
    /// the new number of vertex `v` (`None`: dropped; the kept ones numbered without gaps) and
    /// `bar[b]` the new number of the accepted bar numbered `b` (`None`, or beyond the slice:
    /// dropped). An accepted bar is kept, in its direction, when it and both its ends are;
    /// every other one is removed, its pebble back on its tail.
    ///
    /// What the game decides depends only on its state being a pebble-game graph (Lee–Streinu,
    /// §3): the accepted bars are (2,3)-sparse and each vertex's free pebbles and out-bars make
    /// two. A set `X` then holds `2|X| − span(X) − out(X)` free pebbles, at least three when it
    /// spans a bar, so gathering four on two vertices fails exactly when a tight set holds
    /// both, and the vertices reachable from them are then the smallest such set. Any subset of
    /// sparse bars is sparse and keeps its directions, so the restriction is such a state: it
    /// answers every question ([`Game::add`], [`Game::span`], the components) as a game played
    /// afresh on the kept bars would — the decomposition's sub-frameworks reuse their parent's
    /// game this way. Linear in the vertices and bars.
    pub fn restrict(&self, vertex: &[Option<usize>], bar: &[Option<usize>]) -> Game {
        let n = vertex.iter().flatten().map(|v| v + 1).max().unwrap_or(0);
        let mut game = Game::new(n);
        for (x, out) in vertex.iter().zip(&self.out) {
            let Some(x) = *x else { continue };
            for &(y, b) in out {
                if let (Some(&Some(y)), Some(&Some(b))) =
                    (vertex.get(y as usize), bar.get(b as usize))
                {
                    game.cover(x, y, b);
                }
            }
        }
        game
    }

    /// The maximal rigid components of the accepted bars, as [`pebble_game`] reports them,
    /// when `bars` are the bars the game was given (all accepted, or the rejected ones too).
    pub(crate) fn components(&mut self, bars: &[(usize, usize)]) -> Vec<Vec<usize>> {
        let n = self.pebbles.len();
        components(self, n, bars)
    }

    /// Whether the accepted bars leave exactly three free pebbles: the framework (on at least
    /// two vertices) is rigid, its bars independent.
    fn tight(&self) -> bool {
        self.free == 3
    }

    /// In a tight framework ([`Game::tight`]): the vertices of the smallest tight set holding
    /// `a` and `b` (the two first, then the others as found). With the three free pebbles
    /// gathered on `a` and `b`, no other vertex holds one, so what is reachable from them
    /// along the directed bars is closed and spans `2|X| − 3` bars; and every tight set
    /// holding both contains it, since its vertices cover its own bars and nothing else
    /// (Lee–Streinu). `None` when the framework is not tight or a vertex is out of range.
    pub fn span(&mut self, a: usize, b: usize) -> Option<Vec<usize>> {
        let n = self.pebbles.len();
        if a >= n || b >= n || a == b || !self.tight() {
            return None;
        }
        self.fence_id = u32::MAX;
        if !self.gather(a, b, 3) {
            return None;
        }
        let g = self.next_generation();
        self.seen[a] = g;
        self.seen[b] = g;
        let mut found = vec![a, b];
        let mut next = 0;
        while let Some(&x) = found.get(next) {
            next += 1;
            for &(y, _) in &self.out[x] {
                if self.seen[y as usize] != g {
                    self.seen[y as usize] = g;
                    found.push(y as usize);
                }
            }
        }
        Some(found)
    }

    /// A fresh search mark.
    fn next_generation(&mut self) -> u32 {
        self.generation = self.generation.wrapping_add(1);
        if self.generation == 0 {
            self.seen.iter_mut().for_each(|s| *s = 0);
            self.generation = 1;
        }
        self.generation
    }

    /// Fetches one pebble to `root` from a vertex reachable from it along the directed bars,
    /// without passing through `blocked`; reverses the path. On failure, the vertices marked
    /// with the current generation are `blocked` and those reachable from `root` avoiding it.
    fn fetch(&mut self, root: usize, blocked: &[usize]) -> bool {
        let g = self.next_generation();
        for &b in blocked {
            self.seen[b] = g;
        }
        self.search(root, g)
    }

    /// The depth-first search of [`Game::fetch`] with the marks of generation `g` kept (so
    /// that several failed searches mark the union of what they reached).
    fn search(&mut self, root: usize, g: u32) -> bool {
        self.seen[root] = g;
        self.cursor[root] = 0;
        self.trail.clear();
        self.trail.push(root as u32);
        self.stack.clear();
        self.stack.push(root as u32);
        while let Some(&x) = self.stack.last() {
            let x = x as usize;
            let mut next = None;
            while let Some(&(y, _)) = self.out[x].get(self.cursor[x] as usize) {
                let k = self.cursor[x];
                self.cursor[x] += 1;
                if self.seen[y as usize] != g && self.fence[y as usize] != self.fence_id {
                    next = Some((y as usize, k));
                    break;
                }
            }
            let Some((y, k)) = next else {
                self.stack.pop();
                continue;
            };
            self.seen[y] = g;
            self.trail.push(y as u32);
            self.parent[y] = (x as u32, k);
            if self.pebbles[y] > 0 {
                self.reverse_path(root, y);
                return true;
            }
            self.cursor[y] = 0;
            self.stack.push(y as u32);
        }
        false
    }

    /// Moves a pebble from `end` to `root` along the search tree, reversing each bar on the
    /// way.
    fn reverse_path(&mut self, root: usize, end: usize) {
        self.pebbles[end] -= 1;
        self.pebbles[root] += 1;
        let mut y = end;
        while y != root {
            let (x, k) = self.parent[y];
            let (x, k) = (x as usize, k as usize);
            // `k` is still y's slot: a path's bars are all distinct and each list is touched
            // once, after its successor's.
            let (to, bar) = self.out[x].swap_remove(k);
            debug_assert_eq!(to as usize, y);
            self.out[y].push((x as u32, bar));
            y = x;
        }
    }

    /// Gathers pebbles on `u` and `v` until they hold `want` together (at most four); returns
    /// whether it succeeded. (Three can always be gathered on two vertices; when four cannot,
    /// the two hold three, and what is reachable from them is the smallest tight set holding
    /// both: see [`pebble_game`].)
    fn gather(&mut self, u: usize, v: usize, want: u8) -> bool {
        loop {
            if self.pebbles[u] + self.pebbles[v] >= want {
                return true;
            }
            if self.pebbles[u] < 2 && self.fetch(u, &[v]) {
                continue;
            }
            if self.pebbles[v] < 2 && self.fetch(v, &[u]) {
                continue;
            }
            return false;
        }
    }
}

/// Plays the (2,3) pebble game on `n` vertices with the given bars, in order (see the module
/// documentation). A bar with an end point `>= n` is ignored: its circuit is `None` and it
/// counts for nothing (callers validate their input).
pub fn pebble_game(n: usize, bars: &[(usize, usize)]) -> PebbleReport {
    let mut game = Game::new(n);
    let mut listed = vec![u32::MAX; n];
    let mut rank = 0;
    let mut circuits = Vec::with_capacity(bars.len());
    for (i, &(u, v)) in bars.iter().enumerate() {
        if u >= n || v >= n {
            circuits.push(None);
            continue;
        }
        if u == v {
            circuits.push(Some(Vec::new()));
            continue;
        }
        if game.add(u, v, i) {
            rank += 1;
            circuits.push(None);
        } else {
            // The accepted bars inside the smallest tight set holding both ends: everything
            // reachable from them, which is closed under the directed bars.
            let mut circuit: Vec<usize> = Vec::new();
            let mut stack = vec![u, v];
            listed[u] = i as u32;
            listed[v] = i as u32;
            while let Some(x) = stack.pop() {
                for &(y, bar) in &game.out[x] {
                    let y = y as usize;
                    circuit.push(bar as usize);
                    if listed[y] != i as u32 {
                        listed[y] = i as u32;
                        stack.push(y);
                    }
                }
            }
            circuit.sort_unstable();
            circuits.push(Some(circuit));
        }
    }
    let components = components(&mut game, n, bars);
    PebbleReport { rank, circuits, components }
}

/// The maximal rigid components (see the module documentation).
fn components(game: &mut Game, n: usize, bars: &[(usize, usize)]) -> Vec<Vec<usize>> {
    let mut adjacency = vec![Vec::new(); n];
    for &(u, v) in bars {
        if u < n && v < n && u != v {
            adjacency[u].push(v);
            adjacency[v].push(u);
        }
    }
    // The components each vertex is in (a vertex can be in several: a hinge).
    let mut member: Vec<Vec<u32>> = vec![Vec::new(); n];
    let mut out: Vec<Vec<usize>> = Vec::new();
    // The last component each vertex was decided for (rigid with its bar's ends or not).
    let mut mark: Vec<u32> = vec![u32::MAX; n];
    for &(u, v) in bars {
        if u >= n || v >= n || u == v || member[u].iter().any(|c| member[v].contains(c)) {
            continue;
        }
        // (No fence while gathering: the last component's rigid vertices are not this one's.)
        game.fence_id = u32::MAX;
        let ok = game.gather(u, v, 3);
        debug_assert!(ok, "three pebbles can always be gathered on two vertices");
        let id = out.len() as u32;
        let mut comp = vec![u, v];
        mark[u] = id;
        mark[v] = id;
        // The rigid vertices found so far fence every later search of this component: nothing
        // reachable from them holds a pebble (a pebble moved to a free vertex travels along a
        // path that no rigid vertex reaches, or that vertex would have reached the pebble), so
        // each vertex is explored once per component.
        // (Fence ids start at 1: the fences start at 0.)
        game.fence_id = id + 1;
        game.fence[u] = id + 1;
        game.fence[v] = id + 1;
        // A rigid component is connected through its own vertices: walk from the ends over
        // the bars, deciding each neighbour of a rigid vertex. A vertex is rigid with u and v
        // when no pebble can be fetched to it with their three pebbles kept (Lee–Streinu);
        // everything a failed search reached is rigid too.
        let mut queue = vec![u, v];
        while let Some(x) = queue.pop() {
            for &y in &adjacency[x] {
                if mark[y] == id {
                    continue;
                }
                let rigid = game.pebbles[y] == 0 && !game.fetch(y, &[u, v]);
                if !rigid {
                    mark[y] = id;
                    continue;
                }
                for t in 0..game.trail.len() {
                    let z = game.trail[t] as usize;
                    if mark[z] != id {
                        mark[z] = id;
                        game.fence[z] = id + 1;
                        comp.push(z);
                        queue.push(z);
                    }
                }
            }
        }
        comp.sort_unstable();
        for &x in &comp {
            member[x].push(id);
        }
        out.push(comp);
    }
    game.fence_id = u32::MAX;
    for (x, m) in member.iter().enumerate() {
        if m.is_empty() {
            out.push(vec![x]);
        }
    }
    out.sort();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smallest tight set holding two points: a triangle 0 1 2, point 3 on 0 and 1,
    /// point 4 on 2 and 3.
    #[test]
    fn span_is_the_smallest_tight_set_holding_both() {
        let bars = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 4), (3, 4)];
        let mut game = Game::new(5);
        for (i, &(u, v)) in bars.iter().enumerate() {
            assert!(game.add(u, v, i));
        }
        let mut span = |a, b| {
            let mut s: Vec<usize> = game.span(a, b).unwrap();
            s.sort_unstable();
            s
        };
        assert_eq!(span(0, 1), [0, 1]);
        assert_eq!(span(2, 3), [0, 1, 2, 3]);
        assert_eq!(span(1, 2), [1, 2]);
        assert_eq!(span(0, 4), [0, 1, 2, 3, 4]);
        // Not tight: a bar too few.
        let mut loose = Game::new(3);
        assert!(loose.add(0, 1, 0) && loose.add(1, 2, 1));
        assert_eq!(loose.span(0, 2), None);
    }

    /// A random Laman framework's bars, accepted by a game.
    fn played(n: usize, rng: &mut gcs_model::rng::SplitMix64) -> (Vec<(usize, usize)>, Game) {
        let bars = gcs_model::generate::laman_edges(n, 0.5, rng);
        let mut game = Game::new(n);
        for (i, &(u, v)) in bars.iter().enumerate() {
            assert!(game.add(u, v, i));
        }
        (bars, game)
    }

    /// A game restricted to some vertices and bars answers as the game played afresh on them:
    /// the same rank (every kept bar accepted, and a new bar accepted exactly when afresh it
    /// is) and the same components.
    #[test]
    fn a_restricted_game_is_the_game_of_what_is_kept() {
        let mut rng = gcs_model::rng::SplitMix64::new(7);
        for case in 0..60 {
            let n = 4 + rng.below(40) as usize;
            let (bars, game) = played(n, &mut rng);
            let keep: Vec<bool> = (0..n).map(|_| rng.below(5) != 0).collect();
            let mut vertex = vec![None; n];
            let mut k = 0;
            for x in (0..n).filter(|x| keep[*x]) {
                vertex[x] = Some(k);
                k += 1;
            }
            let mut bar = vec![None; bars.len()];
            let mut kept: Vec<(usize, usize)> = Vec::new();
            for (i, &(u, v)) in bars.iter().enumerate() {
                if let (Some(a), Some(b)) = (vertex[u], vertex[v])
                    && rng.below(6) != 0
                {
                    bar[i] = Some(kept.len());
                    kept.push((a, b));
                }
            }
            let mut restricted = game.restrict(&vertex, &bar);
            let fresh = pebble_game(k, &kept);
            assert_eq!(fresh.rank, kept.len(), "case {case}");
            assert_eq!(restricted.free, 2 * k - kept.len(), "case {case}");
            assert_eq!(restricted.components(&kept), fresh.components, "case {case}");
            let mut afresh = Game::new(k);
            for (i, &(a, b)) in kept.iter().enumerate() {
                assert!(afresh.add(a, b, i));
            }
            for _ in 0..10 {
                let (a, b) = (rng.below(k as u64) as usize, rng.below(k as u64) as usize);
                let i = kept.len();
                assert_eq!(restricted.clone().add(a, b, i), afresh.clone().add(a, b, i));
            }
        }
    }

    /// The W-decomposition's use: a Laman framework's game without one bar has the components
    /// of the game played afresh without it, and restricted to one of those (a tight
    /// sub-framework) it spans, for every two points, the set the game afresh spans.
    #[test]
    fn a_game_without_a_bar_and_on_a_component_spans_as_afresh() {
        let mut rng = gcs_model::rng::SplitMix64::new(11);
        let mut spanned = 0;
        for case in 0..12 {
            let n = 6 + rng.below(20) as usize;
            let (bars, game) = played(n, &mut rng);
            for (gi, &(u, v)) in bars.iter().enumerate() {
                let mut without = game.clone();
                without.remove(u, v);
                let mut rest = bars.clone();
                rest.remove(gi);
                let components = without.components(&rest);
                assert_eq!(components, pebble_game(n, &rest).components, "case {case}, bar {gi}");
                for c in components.iter().filter(|c| c.len() >= 3 && c.len() < n) {
                    let mut vertex = vec![None; n];
                    for (y, &x) in c.iter().enumerate() {
                        vertex[x] = Some(y);
                    }
                    let mut bar = vec![None; bars.len()];
                    let mut inside = Vec::new();
                    for (i, &(a, b)) in bars.iter().enumerate() {
                        if let (Some(a), Some(b)) = (vertex[a], vertex[b]) {
                            bar[i] = Some(inside.len());
                            inside.push((a, b));
                        }
                    }
                    let mut restricted = without.restrict(&vertex, &bar);
                    let mut afresh = Game::new(c.len());
                    for (i, &(a, b)) in inside.iter().enumerate() {
                        assert!(afresh.add(a, b, i));
                    }
                    for a in 0..c.len() {
                        for b in a + 1..c.len() {
                            let sorted = |s: Option<Vec<usize>>| {
                                let mut s = s.unwrap();
                                s.sort_unstable();
                                s
                            };
                            assert_eq!(
                                sorted(restricted.span(a, b)),
                                sorted(afresh.span(a, b)),
                                "case {case}, bar {gi}"
                            );
                            spanned += 1;
                        }
                    }
                }
            }
        }
        assert!(spanned > 1000, "{spanned}");
    }
}
