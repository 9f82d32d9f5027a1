//! Property tests with an oracle: 2D bar frameworks, where generic rigidity is combinatorial
//! (Laman's theorem), and 3D triangulated spheres (Gluck's theorem).
//!
//! - A framework on a Laman graph built by Henneberg moves, at random integer coordinates, is
//!   rigid with no redundancy: rank `2n − 3`, 3 trivial motions, no internal DOF.
//! - Every bar added after those is redundant, and its spanning group closes a circuit of the
//!   2D generic rigidity matroid: with the bar, `2v − 2` bars on the `v` points they touch.
//!   Deleting a member of the group removes the dependency (format §2); deleting a Laman bar
//!   outside it does not.
//! - Removing `k ≤ 3` bars (from the end of the list) leaves exactly `k` internal DOF.
//! - A triangulated sphere in 3D is rigid with no redundancy: rank `3n − 6`, 6 trivial motions.
//!
//! Fixed seed and small case counts: the whole file runs in about a second.

use std::collections::BTreeSet;

use gcs_analysis::{Analysis, AnalysisOptions, analyze};
use gcs_model::generate::{framework, laman_edges, random_coords, sphere_edges};
use gcs_model::rng::SplitMix64;
use gcs_model::{Dim, System};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(0x6c61_6d61),
        failure_persistence: None,
        ..Config::default()
    }
}

fn run(system: &System) -> Analysis {
    analyze(system, &AnalysisOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A random Laman graph on `n` points by Henneberg moves, at random integer coordinates.
fn laman(n: usize, type2: f64, seed: u64) -> (Vec<Vec<i64>>, Vec<(usize, usize)>) {
    let mut rng = SplitMix64::new(seed);
    let edges = laman_edges(n, type2, &mut rng);
    let coords = random_coords(n, Dim::Two, 1000, &mut rng);
    (coords, edges)
}

/// Up to `count` pairs of points that are not joined by an edge, chosen at random.
fn extra_bars(n: usize, edges: &[(usize, usize)], count: usize, seed: u64) -> Vec<(usize, usize)> {
    let key = |(a, b): (usize, usize)| (a.min(b), a.max(b));
    let taken: BTreeSet<(usize, usize)> = edges.iter().map(|e| key(*e)).collect();
    let mut free: Vec<(usize, usize)> = (0..n)
        .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
        .filter(|e| !taken.contains(e))
        .collect();
    let mut rng = SplitMix64::new(seed ^ 0xba5e);
    let mut out = Vec::new();
    while out.len() < count && !free.is_empty() {
        let k = rng.below(free.len() as u64) as usize;
        out.push(free.swap_remove(k));
    }
    out
}

/// The points touched by a set of bars.
fn points(bars: &[(usize, usize)]) -> BTreeSet<usize> {
    bars.iter().flat_map(|&(a, b)| [a, b]).collect()
}

/// The index of bar `d{k}` of a framework.
fn bar_index(system: &System, c: gcs_model::ConstraintIdx) -> usize {
    system.constraint(c).id[1..].parse().expect("framework bars are named d0, d1, …")
}

proptest! {
    #![proptest_config(config(32))]

    /// Laman frameworks are rigid without redundancy; extra bars are redundant with a
    /// spanning group that closes a rigidity circuit.
    #[test]
    fn laman_frameworks_and_extra_bars(
        n in 3usize..=20,
        type2 in 0.0f64..1.0,
        seed in any::<u64>(),
        extra in 1usize..=3,
    ) {
        let (coords, edges) = laman(n, type2, seed);
        prop_assert_eq!(edges.len(), 2 * n - 3);
        let base = run(&framework("laman", Dim::Two, &coords, &edges));
        prop_assert_eq!(base.rank, 2 * n - 3);
        prop_assert_eq!(base.trivial_motions, 3);
        prop_assert_eq!(base.dof, 0);
        prop_assert!(base.redundant.is_empty(), "Laman graph with redundancy: {:?}", base.redundant);

        let added = extra_bars(n, &edges, extra, seed);
        let pairs = n * (n - 1) / 2;
        prop_assert_eq!(added.len(), extra.min(pairs - edges.len()));
        let mut all = edges.clone();
        all.extend(&added);
        let s = framework("laman+", Dim::Two, &coords, &all);
        let a = run(&s);
        prop_assert_eq!(a.rank, 2 * n - 3, "extra bars add no rank");
        prop_assert_eq!(a.dof, 0);
        let flagged: Vec<usize> = a.redundant.iter().map(|r| bar_index(&s, r.constraint)).collect();
        let expected: Vec<usize> = (edges.len()..all.len()).collect();
        prop_assert_eq!(flagged, expected, "exactly the extra bars are redundant");

        for r in &a.redundant {
            prop_assert_eq!((r.rows, r.doc), (1, 1));
            prop_assert!(!r.spanning_group.is_empty());
            let bar = bar_index(&s, r.constraint);
            let group: Vec<usize> = r.spanning_group.iter().map(|c| bar_index(&s, *c)).collect();
            prop_assert!(group.iter().all(|&g| g < edges.len()), "the group is made of Laman bars");
            // A circuit of the 2D rigidity matroid: 2v − 2 bars on v points.
            let mut circuit: Vec<(usize, usize)> = group.iter().map(|&g| all[g]).collect();
            circuit.push(all[bar]);
            prop_assert_eq!(circuit.len(), 2 * points(&circuit).len() - 2, "circuit {:?}", circuit);

            // Deleting a member of the group removes the dependency of this bar; deleting a
            // Laman bar outside the group does not.
            let pick = group[seed as usize % group.len()];
            let mut without: Vec<(usize, usize)> = edges.clone();
            without.remove(pick);
            without.push(all[bar]);
            let b = run(&framework("minus-member", Dim::Two, &coords, &without));
            prop_assert!(b.redundant.is_empty(), "without bar {} of its group, {} is independent", pick, bar);
            if let Some(outside) = (0..edges.len()).find(|g| !group.contains(g)) {
                let mut without: Vec<(usize, usize)> = edges.clone();
                without.remove(outside);
                without.push(all[bar]);
                let b = run(&framework("minus-other", Dim::Two, &coords, &without));
                prop_assert_eq!(b.redundant.len(), 1, "bar {} outside the group", outside);
            }
        }
    }

    /// Removing k bars of a Laman framework leaves exactly k internal degrees of freedom.
    #[test]
    fn laman_frameworks_minus_k_bars(
        n in 3usize..=20,
        type2 in 0.0f64..1.0,
        seed in any::<u64>(),
        k in 1usize..=3,
    ) {
        let (coords, mut edges) = laman(n, type2, seed);
        edges.truncate(edges.len() - k);
        let a = run(&framework("laman-k", Dim::Two, &coords, &edges));
        prop_assert_eq!(a.rank, 2 * n - 3 - k);
        prop_assert_eq!(a.trivial_motions, 3);
        prop_assert_eq!(a.dof, k);
        prop_assert!(a.redundant.is_empty());
        prop_assert!(!a.rigid());
    }
}

proptest! {
    #![proptest_config(config(12))]

    /// Triangulated spheres are generically rigid in 3D (Gluck): no redundancy, 6 trivial
    /// motions, no internal DOF.
    #[test]
    fn triangulated_spheres_are_rigid(n in 4usize..=16, seed in any::<u64>()) {
        let mut rng = SplitMix64::new(seed);
        let edges = sphere_edges(n, &mut rng);
        prop_assert_eq!(edges.len(), 3 * n - 6);
        let coords = random_coords(n, Dim::Three, 1000, &mut rng);
        let a = run(&framework("sphere", Dim::Three, &coords, &edges));
        prop_assert_eq!(a.rank, 3 * n - 6);
        prop_assert_eq!(a.trivial_motions, 6);
        prop_assert_eq!(a.dof, 0);
        prop_assert!(a.redundant.is_empty(), "redundant: {:?}", a.redundant);
    }
}

/// The awkward sizes, deterministically: the smallest frameworks, where a fixed point set
/// leaves no room (a single bar, a triangle, the smallest type II move).
#[test]
fn smallest_frameworks() {
    for n in [2, 3, 4] {
        for seed in 0..4 {
            let (coords, edges) = laman(n, 1.0, seed);
            let a = run(&framework("small", Dim::Two, &coords, &edges));
            assert_eq!((a.rank, a.trivial_motions, a.dof), (2 * n - 3, 3, 0), "n = {n}");
            assert!(a.redundant.is_empty());
        }
    }
    let (coords, _) = laman(4, 0.0, 7);
    let k4: Vec<(usize, usize)> = vec![(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    let a = run(&framework("k4", Dim::Two, &coords, &k4));
    assert_eq!(a.redundant.len(), 1, "K4 has one redundant bar");
    assert_eq!(a.redundant[0].spanning_group.len(), 5, "the whole K4 is the circuit");
}

/// Sketches as CAD programs write them (10-digit decimal coordinates) with a redundant bar
/// whose circuit spans most of the framework: the dependency's coefficients have thousands of
/// digits, beyond any reasonable number of primes, and the exact backend proves it with the
/// displacements instead (`proof: kernel`). Its report equals the modular one, and every
/// member of the spanning group is a Laman bar of the rigid part the extra bar closes.
#[test]
fn decimal_sketches_are_certified_exactly_by_the_displacements() {
    use gcs_analysis::Backend;
    use gcs_model::generate::laman_sketch;
    for (n, seed) in [(40, 1), (120, 7)] {
        let s = laman_sketch(n, seed);
        // The witness path (the pebble game would decide this framework without arithmetic).
        let witness_only = AnalysisOptions { pebble_game: false, ..Default::default() };
        let exact = analyze(&s, &witness_only).unwrap_or_else(|e| panic!("{e}"));
        let modp = analyze(&s, &AnalysisOptions { backend: Backend::ModP, ..witness_only })
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(exact.proof.as_ref().map(|p| p.name()), Some("kernel"), "n = {n}");
        assert_eq!(exact.rank, 2 * n - 3);
        assert_eq!((exact.dof, exact.trivial_motions), (0, 3));
        assert_eq!(exact.redundant.len(), 1);
        let extra = &exact.redundant[0];
        assert_eq!(s.constraint(extra.constraint).id, "extra");
        assert_eq!(exact.redundant, modp.redundant);
        assert!(extra.spanning_group.len() > n / 4, "{}", extra.spanning_group.len());
    }
}
