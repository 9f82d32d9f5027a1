//! A Henneberg sequence of a Laman bar graph, found backwards with the pebble game: the order
//! in which a minimally rigid plane framework can be built vertex by vertex (a vertex on two
//! bars, or on three bars replacing one between two of its neighbours).
//!
//! **Why it is found backwards.** Every Laman graph (`2n − 3` bars, (2,3)-sparse) on three or
//! more vertices has a vertex of degree 2 or 3: the degrees sum to `4n − 6`, and none is below
//! 2. A vertex of degree 2 is removed with its two bars and leaves a Laman graph (Henneberg's
//! first move, backwards). A vertex `v` of degree 3 with neighbours `a, b, c` is removed with
//! its bars and one bar between two of its neighbours added (the second move, backwards); one
//! of the three pairs keeps the graph Laman (Tay and Whiteley, *Generating isostatic
//! frameworks*, Structural Topology 11, 1985, §2). With `v`'s bars gone the graph has
//! `2(n − 1) − 4` bars and is sparse, so a new bar keeps it Laman exactly when it is independent
//! of them — no tight set holds both its ends — which is what the pebble game's [`Game::add`]
//! decides, with certainty (four pebbles gathered on the two ends). The game is played once on
//! the whole graph and kept up to date as bars go ([`Game::remove`]: a valid pebble-game state
//! stays one) and the new bars come; no second independence test is written. The new bar is
//! *virtual*: it has no length of the user's, and the move forwards that adds `v` removes it.
//!
//! What it was built for, and measured: a start for the core's Levenberg–Marquardt placed
//! along the sequence instead of the drawing (BENCHMARKS.md, "Henneberg starts", 2026-11-29,
//! eighteenth session); that start did not solve what the drawing's fails, and is not in the
//! solve.

use gcs_decompose::pebble::Game;

/// One vertex added forwards.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Step {
    /// The vertex added.
    pub vertex: usize,
    /// Its bars to vertices already there: the neighbour, and the bar's number among the
    /// given bars (`None`: a virtual bar, made by a later second move).
    pub bars: Vec<(usize, Option<usize>)>,
    /// A second move (three bars): the virtual bar between two of its neighbours that it
    /// replaces. `None` for a first move (two bars).
    pub removes: Option<(usize, usize)>,
}

/// A Henneberg sequence: the first bar (its two vertices and its number, `None` when
/// virtual), then the vertices in the order they are added. Replayed forwards — each step's
/// bars added, its `removes` bar taken out — it builds the given graph, with no virtual bar
/// left.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Sequence {
    /// The first bar: its two vertices and its number.
    pub base: (usize, usize, Option<usize>),
    /// The other vertices, in the order they are added.
    pub steps: Vec<Step>,
}

/// A Henneberg sequence of the graph of `bars` on the vertices `0..n` (see the module
/// documentation).
///
/// # Arguments
/// `n` vertices, `bars` as pairs of vertices; a bar's number is its place in `bars`.
///
/// # Returns
/// The sequence when the graph is a Laman graph (`n ≥ 2`, `2n − 3` bars, each independent of
/// the ones before it by the pebble game); `None` otherwise (too few or too many bars, a
/// repeated or dependent bar, a vertex out of range).
///
/// # Complexity
/// The pebble game's insertions of the given bars, then at most three insertions (of at most
/// four depth-first searches each) per vertex of degree 3 removed: `O(n·m)` at worst, as the
/// game; the removals and the bookkeeping are linear.
///
/// # Example
/// ```
/// use gcs_solve::henneberg::sequence;
/// // K4 minus one bar: two triangles on the bar 1–2.
/// let s = sequence(4, &[(0, 1), (0, 2), (1, 2), (1, 3), (2, 3)]).unwrap();
/// assert_eq!(s.steps.len(), 2);
/// assert!(sequence(4, &[(0, 1), (1, 2), (2, 3), (3, 0)]).is_none());
/// ```
pub fn sequence(n: usize, bars: &[(usize, usize)]) -> Option<Sequence> {
    if n < 2 || bars.len() != 2 * n - 3 {
        return None;
    }
    let mut game = Game::new(n);
    // Each vertex's bars: the neighbour and the bar's label (a number below `bars.len()`:
    // given; beyond it: virtual).
    let mut adjacent: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
    for (k, &(u, v)) in bars.iter().enumerate() {
        if u >= n || v >= n || !game.add(u, v, k) {
            return None;
        }
        adjacent[u].push((v, k));
        adjacent[v].push((u, k));
    }
    let label = |k: usize| (k < bars.len()).then_some(k);
    let mut next_virtual = bars.len();
    let mut alive = vec![true; n];
    // Candidates by degree, checked when taken (degrees change as vertices go).
    let mut two: Vec<usize> = (0..n).filter(|&v| adjacent[v].len() == 2).collect();
    let mut three: Vec<usize> = (0..n).filter(|&v| adjacent[v].len() == 3).collect();
    let mut peeled: Vec<Step> = Vec::with_capacity(n.saturating_sub(2));
    for _ in 2..n {
        let pick = |stack: &mut Vec<usize>, degree: usize, adjacent: &[Vec<(usize, usize)>]| {
            while let Some(v) = stack.pop() {
                if alive[v] && adjacent[v].len() == degree {
                    return Some(v);
                }
            }
            None
        };
        let (v, second) = match pick(&mut two, 2, &adjacent) {
            Some(v) => (v, false),
            None => (pick(&mut three, 3, &adjacent)?, true),
        };
        let own = std::mem::take(&mut adjacent[v]);
        alive[v] = false;
        for &(u, _) in &own {
            game.remove(v, u);
            adjacent[u].retain(|&(w, _)| w != v);
        }
        let mut removes = None;
        if second {
            let &[(a, _), (b, _), (c, _)] = own.as_slice() else { return None };
            let (x, y) = [(a, b), (a, c), (b, c)]
                .into_iter()
                .find(|&(x, y)| game.add(x, y, next_virtual))?;
            adjacent[x].push((y, next_virtual));
            adjacent[y].push((x, next_virtual));
            next_virtual += 1;
            removes = Some((x, y));
        }
        for &(u, _) in &own {
            match adjacent[u].len() {
                2 => two.push(u),
                3 => three.push(u),
                _ => {}
            }
        }
        if let Some((x, y)) = removes {
            for u in [x, y] {
                if adjacent[u].len() == 3 {
                    three.push(u);
                }
            }
        }
        peeled.push(Step {
            vertex: v,
            bars: own.iter().map(|&(u, k)| (u, label(k))).collect(),
            removes,
        });
    }
    let a = alive.iter().position(|&l| l)?;
    let &[(b, k)] = adjacent[a].as_slice() else { return None };
    peeled.reverse();
    Some(Sequence { base: (a, b, label(k)), steps: peeled })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Replays `sequence` forwards and returns the given bars it ends with (sorted), checking
    /// every move on the way: a new vertex each time, joined to placed ones, a second move's
    /// removed bar virtual and between two of its neighbours, every graph on the way Laman, no
    /// virtual bar left at the end.
    fn replay(n: usize, sequence: &Sequence) -> Vec<usize> {
        let mut placed = vec![false; n];
        // Bars present: (u, v, label), u < v.
        let mut present: Vec<(usize, usize, Option<usize>)> = Vec::new();
        let (a, b, k) = sequence.base;
        assert_ne!(a, b);
        (placed[a], placed[b]) = (true, true);
        present.push((a.min(b), a.max(b), k));
        for step in &sequence.steps {
            let v = step.vertex;
            assert!(!placed[v], "vertex {v} added twice");
            assert!(step.bars.iter().all(|&(u, _)| placed[u] && u != v));
            if let Some((x, y)) = step.removes {
                assert_eq!(step.bars.len(), 3);
                assert!(step.bars.iter().any(|b| b.0 == x) && step.bars.iter().any(|b| b.0 == y));
                let k = present
                    .iter()
                    .position(|&(p, q, l)| (p, q) == (x.min(y), x.max(y)) && l.is_none())
                    .expect("the removed bar is a virtual bar present");
                present.swap_remove(k);
            } else {
                assert_eq!(step.bars.len(), 2);
            }
            for &(u, l) in &step.bars {
                present.push((u.min(v), u.max(v), l));
            }
            placed[v] = true;
            // Every graph on the way is Laman: `2k − 3` bars on its `k` vertices, independent
            // by a fresh pebble game.
            let k = placed.iter().filter(|&&p| p).count();
            let bars: Vec<(usize, usize)> = present.iter().map(|&(p, q, _)| (p, q)).collect();
            assert_eq!(bars.len(), 2 * k - 3);
            assert_eq!(gcs_decompose::pebble_game(n, &bars).rank, bars.len());
        }
        assert!(placed.iter().all(|&p| p));
        assert!(present.iter().all(|p| p.2.is_some()), "a virtual bar is left");
        let mut given: Vec<usize> = present.iter().filter_map(|p| p.2).collect();
        given.sort_unstable();
        given
    }

    #[test]
    fn replaying_the_sequence_rebuilds_random_laman_graphs() {
        let mut seconds = 0;
        for seed in 1..=20 {
            for n in [2, 3, 4, 10, 57, 300] {
                let mut rng = gcs_model::rng::SplitMix64::new(seed);
                let edges = gcs_model::generate::laman_edges(n, 0.5, &mut rng);
                let s = sequence(n, &edges).expect("a Laman graph has a sequence");
                assert_eq!(s.steps.len(), n - 2);
                seconds += s.steps.iter().filter(|s| s.removes.is_some()).count();
                assert_eq!(replay(n, &s), (0..edges.len()).collect::<Vec<_>>());
            }
        }
        // The family's graphs need the second move backwards too (no vertex of degree 2).
        assert!(seconds > 0);
    }

    #[test]
    fn non_laman_graphs_have_no_sequence() {
        // Too few bars; a redundant one (the fourth bar of K4 minus one vertex's bar twice).
        assert!(sequence(4, &[(0, 1), (1, 2), (2, 3), (3, 0)]).is_none());
        assert!(sequence(4, &[(0, 1), (1, 2), (0, 2), (0, 1), (2, 3)]).is_none());
        assert!(sequence(3, &[(0, 1), (1, 2), (0, 7)]).is_none());
    }
}
