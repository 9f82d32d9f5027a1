//! The (2,3) pebble game against the witness method on 2D bar frameworks: the same rank, the
//! same redundant bars with the same spanning groups (fundamental circuits in file order), and
//! the same rigid clusters, on random graphs from sparse to dense (with repeated bars), and on
//! Henneberg frameworks with bars added and removed; and the whole analysis with the pebble
//! game (the default for such frameworks) equal to the analysis by the witness alone, field by
//! field, but for the fields that say how it was decided.

use gcs_analysis::{AnalysisOptions, Arithmetic, Backend, RankMethod, analyze};
use gcs_decompose::pebble_game;
use gcs_model::System;
use gcs_model::rng::SplitMix64;

/// The RON of `n` points at random integer coordinates joined by `bars` (distances with the
/// drawn values left out: the analysis reads them off the witness).
fn framework(n: usize, bars: &[(usize, usize)], rng: &mut SplitMix64) -> System {
    let mut text = String::from("System(dim: 2, entities: [");
    for i in 0..n {
        let (x, y) = (rng.below(2000) as i64 - 1000, rng.below(2000) as i64 - 1000);
        text.push_str(&format!("Point(id: \"p{i}\", at: [{x}, {y}]),"));
    }
    text.push_str("], constraints: [");
    for (k, (a, b)) in bars.iter().enumerate() {
        text.push_str(&format!("Distance(id: \"d{k}\", a: \"p{a}\", b: \"p{b}\"),"));
    }
    text.push_str("])");
    System::from_ron_str(&text, None).expect("valid RON")
}

/// A random graph on `n` vertices with `m` bars (pairs may repeat), no loops.
fn random_bars(n: usize, m: usize, rng: &mut SplitMix64) -> Vec<(usize, usize)> {
    let mut bars = Vec::with_capacity(m);
    while bars.len() < m {
        let (a, b) = (rng.below(n as u64) as usize, rng.below(n as u64) as usize);
        if a != b {
            bars.push((a, b));
        }
    }
    bars
}

/// Asserts that the pebble game and the exact witness analysis agree on the framework.
fn agree(n: usize, bars: &[(usize, usize)], seed: u64) -> (usize, usize) {
    let mut rng = SplitMix64::new(seed);
    let system = framework(n, bars, &mut rng);
    let by_witness = AnalysisOptions { pebble_game: false, ..AnalysisOptions::default() };
    let analysis = analyze(&system, &by_witness).expect("analysis");
    assert_eq!(analysis.rank_method, RankMethod::Witness);
    let game = pebble_game(n, bars);
    let what = format!("n = {n}, bars {bars:?}");
    assert_eq!(game.rank, analysis.rank, "rank, {what}");
    assert_eq!(game.dof(n), analysis.dof, "dof, {what}");
    let witness: Vec<(usize, Vec<usize>)> = analysis
        .redundant
        .iter()
        .map(|r| (r.constraint.index(), r.spanning_group.iter().map(|c| c.index()).collect()))
        .collect();
    let pebbles: Vec<(usize, Vec<usize>)> =
        game.circuits.iter().enumerate().filter_map(|(i, c)| c.clone().map(|c| (i, c))).collect();
    assert_eq!(pebbles, witness, "redundant bars and spanning groups, {what}");
    let mut clusters: Vec<Vec<usize>> =
        analysis.clusters.iter().map(|c| c.entities.iter().map(|e| e.index()).collect()).collect();
    clusters.sort();
    assert_eq!(game.components, clusters, "rigid clusters, {what}");
    // The whole analysis through the pebble game, in both backends that use it.
    for backend in [Backend::Exact, Backend::ModP] {
        let witness_only = AnalysisOptions { backend, ..by_witness.clone() };
        let mut slow = analyze(&system, &witness_only).expect("analysis");
        let mut fast = analyze(&system, &AnalysisOptions { backend, ..AnalysisOptions::default() })
            .expect("analysis");
        assert_eq!(fast.rank_method, RankMethod::PebbleGame, "{what}");
        assert_eq!(fast.clusters_arithmetic, Arithmetic::Combinatorial);
        if backend == Backend::Exact {
            assert_eq!(fast.proof, Some(gcs_rank::Proof::PebbleGame));
        }
        // Global rigidity: where the pebble game shows the framework not redundantly rigid,
        // Jackson and Jordán's condition answers instead of the stress test; the answers and
        // what they rest on agree.
        let pairs = std::iter::once((&fast.global_rigidity, &slow.global_rigidity))
            .chain(fast.cluster_global_rigidity.iter().zip(&slow.cluster_global_rigidity));
        for (f, s) in pairs {
            let key = |g: &Option<gcs_analysis::GlobalRigidity>| {
                g.as_ref().map(|g| {
                    (g.globally_rigid, g.rigid, g.points, g.bars, g.stress_rank, g.unstressed_bars)
                })
            };
            assert_eq!(key(f), key(s), "global rigidity, {backend:?}, {what}");
        }
        fast.global_rigidity = slow.global_rigidity.clone();
        fast.cluster_global_rigidity = slow.cluster_global_rigidity.clone();
        // How it was decided differs; nothing else may.
        fast.rank_method = slow.rank_method;
        fast.clusters_arithmetic = slow.clusters_arithmetic;
        fast.proof = None;
        slow.proof = None;
        assert_eq!(fast, slow, "{backend:?}, {what}");
    }
    (witness.len(), clusters.len())
}

#[test]
fn the_pebble_game_agrees_with_the_witness_on_random_frameworks() {
    let (mut redundant, mut several) = (0, 0);
    for seed in 0..300u64 {
        let mut rng = SplitMix64::new(seed ^ 0xBA55);
        let n = 2 + rng.below(12) as usize;
        // From well below 2n − 3 bars to well above.
        let m = n + rng.below(2 * n as u64 + 2) as usize;
        let bars = random_bars(n, m, &mut rng);
        let (r, c) = agree(n, &bars, seed);
        redundant += usize::from(r > 0);
        several += usize::from(c > 1);
    }
    // Both outcomes are common: the test exercises circuits and several components.
    assert!(redundant > 60 && several > 60, "{redundant} with redundancy, {several} split");
}

#[test]
fn the_pebble_game_agrees_on_henneberg_frameworks_with_bars_moved() {
    for seed in 0..20u64 {
        let mut rng = SplitMix64::new(seed);
        let n = 20 + rng.below(40) as usize;
        // Henneberg moves (half of type II: Laman), then a few bars removed and a few random
        // ones added, so that there are circuits and flexible parts.
        let mut bars = gcs_model::generate::laman_edges(n, 0.5, &mut rng);
        for _ in 0..3 {
            let k = rng.below(bars.len() as u64) as usize;
            bars.remove(k);
        }
        bars.extend(random_bars(n, 4, &mut rng));
        agree(n, &bars, seed);
    }
}

#[test]
fn a_loop_is_redundant_with_nothing_and_a_repeated_bar_with_its_twin() {
    let game = pebble_game(3, &[(0, 1), (1, 1), (1, 0), (1, 2), (2, 0)]);
    assert_eq!(game.rank, 3);
    assert_eq!(game.circuits, vec![None, Some(vec![]), Some(vec![0]), None, None]);
    assert_eq!(game.components, vec![vec![0, 1, 2]]);
    assert_eq!(game.dof(3), 0);
}

#[test]
fn two_triangles_on_a_hinge_are_two_components_and_an_isolated_point_its_own() {
    // Triangles 0-1-2 and 2-3-4 share vertex 2; vertex 5 is on no bar.
    let game = pebble_game(6, &[(0, 1), (1, 2), (2, 0), (2, 3), (3, 4), (4, 2)]);
    assert_eq!(game.rank, 6);
    assert!(game.circuits.iter().all(Option::is_none));
    assert_eq!(game.components, vec![vec![0, 1, 2], vec![2, 3, 4], vec![5]]);
    // 12 coordinates − 6 bars − 3 trivial motions: the hinge and the free point's two.
    assert_eq!(game.dof(6), 3);
}
