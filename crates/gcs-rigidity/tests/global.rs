//! Global rigidity in the plane, two ways: the stress-matrix test of the analysis
//! (`gcs_analysis::global`, algebraic, modulo a prime) against Jackson and Jordán's
//! characterisation (`gcs_rigidity::jackson_jordan`, combinatorial: complete on at most 3
//! vertices, or 3-connected and redundantly rigid). They must agree on every graph.
//!
//! The random graphs are drawn near the threshold where the answer changes — 4 to 11 vertices
//! with between `2n − 3` and `3n` edges, plus sparser and denser ones — so that both answers
//! are common; the test asserts that each answer occurs often.

use gcs_analysis::global::graph_globally_rigid;
use gcs_model::rng::SplitMix64;
use gcs_rigidity::jackson_jordan;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

/// A random graph on `n` vertices with about `m` distinct edges.
fn random_graph(n: usize, m: usize, rng: &mut SplitMix64) -> Vec<(usize, usize)> {
    let mut edges = Vec::new();
    let all = n * (n - 1) / 2;
    while edges.len() < m.min(all) {
        let a = rng.below(n as u64) as usize;
        let b = rng.below(n as u64) as usize;
        let e = (a.min(b), a.max(b));
        if a != b && !edges.contains(&e) {
            edges.push(e);
        }
    }
    edges
}

/// A graph from a seed: `n` in 1..=11, density around the threshold.
fn graph(seed: u64) -> (usize, Vec<(usize, usize)>) {
    let mut rng = SplitMix64::new(seed);
    let n = 1 + rng.below(11) as usize;
    let lo = (2 * n).saturating_sub(4);
    let m = lo + rng.below(n as u64 + 4) as usize;
    (n, random_graph(n, m, &mut rng))
}

#[test]
fn the_stress_test_agrees_with_jackson_jordan_on_thousands_of_graphs() {
    let (mut yes, mut no) = (0, 0);
    for seed in 0..4000u64 {
        let (n, edges) = graph(seed);
        let jj = jackson_jordan(n, &edges);
        let stress = graph_globally_rigid(n, 2, &edges, seed);
        assert_eq!(stress.globally_rigid, jj, "n = {n}, edges {edges:?}: {stress:?}");
        if jj { yes += 1 } else { no += 1 }
    }
    assert!(yes > 600 && no > 600, "{yes} globally rigid, {no} not");
}

proptest! {
    #![proptest_config(Config {
        cases: 500,
        rng_seed: RngSeed::Fixed(0x6a6a),
        failure_persistence: None,
        ..Config::default()
    })]

    /// Any edge set on up to 9 vertices (with repeated pairs), any seed of the stress draw.
    #[test]
    fn the_two_tests_agree(
        n in 1usize..10,
        raw in proptest::collection::vec((0usize..9, 0usize..9), 0..30),
        seed in any::<u64>(),
    ) {
        let edges: Vec<(usize, usize)> =
            raw.into_iter().filter(|(a, b)| a != b && *a < n && *b < n).collect();
        let stress = graph_globally_rigid(n, 2, &edges, seed);
        prop_assert_eq!(stress.globally_rigid, jackson_jordan(n, &edges), "{:?}", edges);
    }
}
