//! Property tests with an oracle: on 2D bar frameworks Dense's verdict is Laman's count, and
//! RuleDor agrees with the definition on sets of points. Fixed seeds, small case counts.

use gcs_model::generate::{framework, laman_edges, random_coords, sphere_edges};
use gcs_model::rng::SplitMix64;
use gcs_model::{Dim, EntityIdx, System};
use gcs_rigidity::{
    DorOracle, RuleDor, Verdict, dense_analysis, dm_decomposition, minimal_dense,
    over_rigid_analysis,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config(cases: u32, seed: u64) -> Config {
    Config { cases, rng_seed: RngSeed::Fixed(seed), failure_persistence: None, ..Config::default() }
}

/// A random 2D framework: a Laman graph on `n` points plus `extra` random bars (repeated bars
/// allowed), from a seed.
fn random_framework(n: usize, extra: usize, seed: u64) -> (System, Vec<(usize, usize)>) {
    let mut rng = SplitMix64::new(seed);
    let mut edges = laman_edges(n, 0.5, &mut rng);
    for _ in 0..extra {
        let u = rng.below(n as u64) as usize;
        let mut v = rng.below(n as u64) as usize;
        while v == u {
            v = rng.below(n as u64) as usize;
        }
        edges.push((u, v));
    }
    // Drop a few bars at random too, so under-rigid graphs occur.
    let drops = rng.below(3) as usize;
    for _ in 0..drops.min(edges.len()) {
        let k = rng.below(edges.len() as u64) as usize;
        edges.swap_remove(k);
    }
    let coords = random_coords(n, Dim::Two, 50, &mut rng);
    (framework("random", Dim::Two, &coords, &edges), edges)
}

/// Laman's count by brute force: over-rigid when some set of `n′ ≥ 2` points spans more than
/// `2n′ − 3` bars; else well-rigid when there are exactly `2n − 3` bars, else under-rigid.
fn laman_verdict(n: usize, edges: &[(usize, usize)]) -> Verdict {
    for mask in 0u32..(1 << n) {
        let size = mask.count_ones() as i64;
        if size < 2 {
            continue;
        }
        let inside =
            edges.iter().filter(|(u, v)| mask & (1 << u) != 0 && mask & (1 << v) != 0).count();
        if inside as i64 > 2 * size - 3 {
            return Verdict::OverRigid;
        }
    }
    if edges.len() as i64 == 2 * n as i64 - 3 { Verdict::WellRigid } else { Verdict::UnderRigid }
}

proptest! {
    #![proptest_config(config(128, 0x6c61_6d61))]

    #[test]
    fn dense_is_lamans_count(n in 2usize..=8, extra in 0usize..=3, seed in any::<u64>()) {
        let (system, edges) = random_framework(n, extra, seed);
        let expected = laman_verdict(n, &edges);
        let dense = dense_analysis(&system);
        prop_assert_eq!(dense.verdict, expected);
        // For points in 2D every pair has DOR 3: es_rigidity is s_rigidity.
        let over = over_rigid_analysis(&system, &RuleDor::for_system(&system));
        prop_assert_eq!(over.verdict, expected);
        if expected == Verdict::OverRigid {
            let found = dense.subsystem.unwrap();
            prop_assert!(found.dof < 3);
            // The minimal one is minimal in its points: DOF < 3, and every proper subset of
            // its points spans at most 2n′ − 3 of its bars.
            let min = minimal_dense(&system).unwrap();
            prop_assert!(min.dof < 3);
            let pts: Vec<usize> = min.objects.iter().map(|e| e.index()).collect();
            let sub_edges: Vec<(usize, usize)> = min
                .constraints
                .iter()
                .map(|c| {
                    let es = system.constraint_base_entities(*c);
                    let pos = |e: EntityIdx| pts.iter().position(|p| *p == e.index()).unwrap();
                    (pos(es[0]), pos(es[1]))
                })
                .collect();
            for mask in 1u32..(1 << pts.len()) - 1 {
                let size = mask.count_ones() as i64;
                let inside = sub_edges
                    .iter()
                    .filter(|(u, v)| mask & (1 << u) != 0 && mask & (1 << v) != 0)
                    .count() as i64;
                prop_assert!(size < 2 || inside <= 2 * size - 3);
            }
        }
    }

    #[test]
    fn rule_dor_of_points_follows_the_definition(n in 3usize..=9, seed in any::<u64>()) {
        let mut rng = SplitMix64::new(seed);
        for dim in [Dim::Two, Dim::Three] {
            let coords = random_coords(n, dim, 30, &mut rng);
            let edges = if dim == Dim::Three && n >= 4 {
                sphere_edges(n, &mut rng)
            } else {
                laman_edges(n, 0.5, &mut rng)
            };
            let system = framework("pts", dim, &coords, &edges);
            let oracle = RuleDor::for_system(&system);
            let p = |i: usize| EntityIdx(i as u32);
            for i in 0..n {
                prop_assert_eq!(oracle.dor(&system, &[p(i)]), dim.coords());
                for j in i + 1..n {
                    let pair = oracle.dor(&system, &[p(i), p(j)]);
                    prop_assert_eq!(pair, if dim == Dim::Two { 3 } else { 5 });
                    for k in j + 1..n {
                        // No collinearity is stated, so three points are generic.
                        let triple = oracle.dor(&system, &[p(i), p(j), p(k)]);
                        prop_assert_eq!(triple, if dim == Dim::Two { 3 } else { 6 });
                    }
                }
            }
            let all: Vec<EntityIdx> = (0..n).map(p).collect();
            prop_assert_eq!(oracle.dor(&system, &all), dim.displacements());
        }
    }

    #[test]
    fn dm_never_splits_a_constraint_or_an_entity(n in 2usize..=9, extra in 0usize..=4, seed in any::<u64>()) {
        let (system, _) = random_framework(n, extra, seed);
        let dm = dm_decomposition(&system);
        let parts = [&dm.over, &dm.well, &dm.under];
        for c in system.constraint_indices() {
            prop_assert_eq!(parts.iter().filter(|p| p.constraints.contains(&c)).count(), 1);
        }
        for e in system.entity_indices() {
            prop_assert_eq!(parts.iter().filter(|p| p.entities.contains(&e)).count(), 1);
        }
        // Blocks never split either, and cover the well part.
        let mut in_blocks: Vec<_> = dm.blocks.iter().flat_map(|b| b.constraints.clone()).collect();
        let count = in_blocks.len();
        in_blocks.sort();
        in_blocks.dedup();
        prop_assert_eq!(in_blocks.len(), count);
        prop_assert_eq!(in_blocks, dm.well.constraints.clone());
        // The coarse parts have the shapes D-M promises.
        prop_assert!(dm.over.equations > dm.over.unknowns || dm.over.equations == 0);
        prop_assert_eq!(dm.well.equations, dm.well.unknowns);
        prop_assert!(dm.under.unknowns > dm.under.equations || dm.under.unknowns == 0);
    }

    #[test]
    fn over_rigid_is_es_rigidity_on_3d_frameworks(n in 1usize..=7, m in 0usize..=16, seed in any::<u64>()) {
        // Random 3D bar frameworks (repeated bars allowed), no collinearity stated: the DOR of
        // k points is 3, 5, 6 for k = 1, 2, ≥ 3. Brute force over every subset.
        let mut rng = SplitMix64::new(seed);
        let edges: Vec<(usize, usize)> = if n < 2 {
            Vec::new()
        } else {
            (0..m)
                .map(|_| {
                    let u = rng.below(n as u64) as usize;
                    let v = (u + 1 + rng.below(n as u64 - 1) as usize) % n;
                    (u, v)
                })
                .collect()
        };
        let coords = random_coords(n, Dim::Three, 40, &mut rng);
        let system = framework("bars3d", Dim::Three, &coords, &edges);
        let dor = |k: i64| match k { 0 => 0, 1 => 3, 2 => 5, _ => 6 };
        let mut expected = None;
        for mask in 1u32..(1 << n) {
            let k = mask.count_ones() as i64;
            let inside = edges
                .iter()
                .filter(|(u, v)| mask & (1 << u) != 0 && mask & (1 << v) != 0)
                .count() as i64;
            if 3 * k - inside < dor(k) {
                expected = Some(Verdict::OverRigid);
                break;
            }
        }
        let whole = 3 * n as i64 - edges.len() as i64;
        let expected = expected.unwrap_or(if whole == dor(n as i64) {
            Verdict::WellRigid
        } else {
            Verdict::UnderRigid
        });
        let over = over_rigid_analysis(&system, &RuleDor::for_system(&system));
        prop_assert_eq!(over.verdict, expected);
        if let Some(s) = over.subsystem {
            prop_assert!(s.dof < dor(s.objects.len() as i64));
        }
    }

    #[test]
    fn triangulated_spheres_are_well_es_rigid(n in 4usize..=12, seed in any::<u64>()) {
        let system = gcs_model::generate::triangulated_sphere(n, seed);
        let over = over_rigid_analysis(&system, &RuleDor::for_system(&system));
        prop_assert_eq!(over.verdict, Verdict::WellRigid);
        // Dense flags the first bar (DOF 5 < 6): the flow paper's complaint about segments.
        let dense = dense_analysis(&system);
        prop_assert_eq!(dense.verdict, Verdict::OverRigid);
        prop_assert_eq!(dense.subsystem.unwrap().dof, 5);
    }
}
