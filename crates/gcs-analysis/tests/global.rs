//! Global rigidity (issue 19): the known answers of the stress-matrix test, in every backend,
//! and what the test covers (coincident points merged, one fixed point; nothing else).
//!
//! 2D: K4 yes; K3,3 no (minimally rigid); a triangle strip no; the wheel W5 yes; a triangle
//! with a pendant degree-2 vertex no. 3D: K5 yes; the cone over the triangular prism no; the
//! double banana no (not even rigid); Connelly's K5,5 no although it is redundantly rigid and
//! 5-connected.

use gcs_analysis::{AnalysisOptions, Arithmetic, Backend, analyze};
use gcs_model::generate::{framework, random_coords};
use gcs_model::rng::SplitMix64;
use gcs_model::{BigRational, ConstraintKind, Dim, System, SystemBuilder};
use num_bigint::BigInt;

const BACKENDS: [Backend; 4] =
    [Backend::Exact, Backend::ModP, Backend::Rational, Backend::Float { tolerance: 1e-9 }];

fn complete(n: usize) -> Vec<(usize, usize)> {
    (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j))).collect()
}

fn bipartite(a: usize, b: usize) -> Vec<(usize, usize)> {
    (0..a).flat_map(|i| (0..b).map(move |j| (i, a + j))).collect()
}

/// Vertex `hub` joined to every vertex of `rim`, plus the rim's own edges.
fn cone(rim: &[(usize, usize)], n: usize) -> Vec<(usize, usize)> {
    let mut e = rim.to_vec();
    e.extend((0..n).map(|i| (i, n)));
    e
}

fn wheel(rim: usize) -> Vec<(usize, usize)> {
    let cycle: Vec<(usize, usize)> = (0..rim).map(|i| (i, (i + 1) % rim)).collect();
    cone(&cycle, rim)
}

fn prism() -> Vec<(usize, usize)> {
    vec![(0, 1), (1, 2), (0, 2), (3, 4), (4, 5), (3, 5), (0, 3), (1, 4), (2, 5)]
}

fn strip(n: usize) -> Vec<(usize, usize)> {
    let mut e = vec![(0, 1)];
    for v in 2..n {
        e.extend([(v - 2, v), (v - 1, v)]);
    }
    e
}

/// Two bananas (K5 minus an edge) glued at the ends of their missing edges, 0 and 1.
fn double_banana() -> Vec<(usize, usize)> {
    let mut e = Vec::new();
    for extra in [[2, 3, 4], [5, 6, 7]] {
        let vs = [0, 1, extra[0], extra[1], extra[2]];
        for (i, a) in vs.iter().enumerate() {
            for b in &vs[i + 1..] {
                if (*a, *b) != (0, 1) {
                    e.push((*a, *b));
                }
            }
        }
    }
    e
}

fn model(name: &str, dim: Dim, edges: &[(usize, usize)], seed: u64) -> System {
    let n = edges.iter().map(|(a, b)| a.max(b) + 1).max().unwrap_or(0);
    let coords = random_coords(n, dim, 1000, &mut SplitMix64::new(seed));
    framework(name, dim, &coords, edges)
}

/// (name, dimension, edges, rigid, globally rigid)
type Case = (&'static str, Dim, Vec<(usize, usize)>, bool, bool);

fn cases() -> Vec<Case> {
    vec![
        ("K4", Dim::Two, complete(4), true, true),
        ("K3,3", Dim::Two, bipartite(3, 3), true, false),
        ("strip", Dim::Two, strip(7), true, false),
        ("W5", Dim::Two, wheel(5), true, true),
        ("pendant", Dim::Two, vec![(0, 1), (1, 2), (0, 2), (0, 3), (1, 3)], true, false),
        ("triangle", Dim::Two, complete(3), true, true),
        ("path", Dim::Two, vec![(0, 1), (1, 2)], false, false),
        ("K5", Dim::Three, complete(5), true, true),
        ("K4 in 3D", Dim::Three, complete(4), true, true),
        ("cone over the prism", Dim::Three, cone(&prism(), 6), true, false),
        ("double banana", Dim::Three, double_banana(), false, false),
        ("K5,5", Dim::Three, bipartite(5, 5), true, false),
        ("K6", Dim::Three, complete(6), true, true),
    ]
}

#[test]
fn known_answers_in_every_backend() {
    for (name, dim, edges, rigid, yes) in cases() {
        for seed in [1, 2] {
            let s = model(name, dim, &edges, seed);
            for (backend, pebble_game) in BACKENDS.into_iter().flat_map(|b| [(b, false), (b, true)])
            {
                let options =
                    AnalysisOptions { backend, pebble_game, ..AnalysisOptions::default() };
                let a = analyze(&s, &options).unwrap_or_else(|e| panic!("{name} {backend:?}: {e}"));
                let g = a.global_rigidity.as_ref().unwrap_or_else(|| panic!("{name}: absent"));
                let at =
                    format!("{name}, {}, seed {seed}, pebble game {pebble_game}", backend.name());
                assert_eq!(g.globally_rigid, yes, "{at}: {g:?}");
                assert_eq!(g.rigid, rigid, "{at}: {g:?}");
                assert_eq!(
                    a.rigid(),
                    rigid,
                    "{at}: the analysis and the test disagree on rigidity"
                );
                // The pebble game (2D, exact backends) decides the *no* of a framework that is
                // not redundantly rigid by Jackson and Jordán's condition, with certainty.
                let combinatorial =
                    a.rank_method == gcs_analysis::RankMethod::PebbleGame && !yes && g.points >= 4;
                match backend {
                    _ if combinatorial => {
                        assert_eq!(g.arithmetic, Arithmetic::Combinatorial, "{at}");
                        assert_eq!(g.method.name(), "Jackson–Jordán", "{at}");
                        assert!(g.error_bound.is_none(), "{at}");
                    }
                    Backend::Float { .. } => {
                        assert!(matches!(g.arithmetic, Arithmetic::Float { .. }));
                        assert!(g.error_bound.is_none());
                    }
                    _ => {
                        assert_eq!(g.arithmetic, Arithmetic::ModP);
                        // A yes is proven; a no comes with its Schwartz–Zippel bound, tiny.
                        assert_eq!(g.error_bound.is_some(), !yes, "{at}");
                        assert!(g.error_bound.is_none_or(|b| b < 1e-15), "{at}: {g:?}");
                    }
                }
                if rigid && !yes && g.target_rank > 0 {
                    assert!(g.stress_rank < g.target_rank, "{at}: {g:?}");
                }
            }
        }
    }
}

/// K5,5 in 3D: redundantly rigid (every bar can go) and 5-connected, yet not globally rigid;
/// only the stress rank says so (Connelly).
#[test]
fn k55_is_redundantly_rigid_but_its_stresses_fall_short() {
    let edges = bipartite(5, 5);
    let s = model("K5,5", Dim::Three, &edges, 7);
    let a = analyze(&s, &AnalysisOptions::default()).unwrap();
    assert!(a.rigid() && a.redundant.len() == 1);
    for k in 0..edges.len() {
        let mut fewer = edges.clone();
        fewer.remove(k);
        let t = model("K5,5 minus a bar", Dim::Three, &fewer, 7);
        let b = analyze(&t, &AnalysisOptions { clusters: false, ..AnalysisOptions::default() })
            .unwrap();
        assert!(b.rigid(), "K5,5 minus bar {k} is still rigid");
    }
    let g = a.global_rigidity.unwrap();
    assert_eq!((g.target_rank, g.globally_rigid), (6, false));
    assert!(g.stress_rank < 6 && g.random_configuration);
    // Every bar is stressed: the stress matrix had to be formed.
    assert_eq!(g.unstressed_bars, 0);
}

/// K4 with a vertex hanging on two of its corners: rigid, one redundant bar, but the two bars
/// of the hanging vertex lie in no circuit. The random stress leaves them at zero, which
/// decides *no* without the stress matrix (Hendrickson), in both exact backends.
#[test]
fn unstressed_bars_decide_no_without_the_stress_matrix() {
    let mut edges = complete(4);
    edges.extend([(0, 4), (1, 4)]);
    for backend in [Backend::Exact, Backend::ModP] {
        let s = model("K4 and a hanging vertex", Dim::Two, &edges, 3);
        let witness_only = AnalysisOptions { backend, pebble_game: false, ..Default::default() };
        let a = analyze(&s, &witness_only).unwrap();
        let g = a.global_rigidity.unwrap();
        assert!(g.rigid && !g.globally_rigid, "{g:?}");
        assert_eq!((g.unstressed_bars, g.stress_rank), (2, 0), "{g:?}");
        assert!(g.random_configuration && g.error_bound.is_some_and(|b| b < 1e-15));
        // The pebble game finds the same two bars in no circuit, and says no for certain.
        let a = analyze(&s, &AnalysisOptions { backend, ..Default::default() }).unwrap();
        let g = a.global_rigidity.unwrap();
        assert!(g.rigid && !g.globally_rigid, "{g:?}");
        assert_eq!((g.unstressed_bars, g.stress_rank), (2, 0), "{g:?}");
        assert_eq!((g.arithmetic, g.error_bound), (Arithmetic::Combinatorial, None));
    }
    // Without the hanging vertex: every bar stressed, and the stress matrix says yes.
    let s = model("K4", Dim::Two, &complete(4), 3);
    let g = analyze(&s, &AnalysisOptions::default()).unwrap().global_rigidity.unwrap();
    assert!(g.globally_rigid && g.unstressed_bars == 0 && g.stress_rank == 1, "{g:?}");
}

fn builder_k4(dim: Dim, split: bool, fixes: usize) -> System {
    let mut b = SystemBuilder::new("k4-variant", dim);
    let coords = random_coords(5, dim, 100, &mut SplitMix64::new(3));
    let at = |i: usize| {
        Some(coords[i].iter().map(|x| BigRational::from_integer(BigInt::from(*x))).collect())
    };
    for i in 0..4 {
        b.point(&format!("p{i}"), at(i)).unwrap();
    }
    // p0's twin: the same position, joined by a coincidence; p0's bars to p2 and p3 go to it.
    let twin = if split {
        b.point("q0", at(0)).unwrap();
        b.constraint(ConstraintKind::Coincident, "c", &["p0", "q0"], None).unwrap();
        "q0"
    } else {
        "p0"
    };
    let bars = [("p0", "p1"), (twin, "p2"), (twin, "p3"), ("p1", "p2"), ("p1", "p3"), ("p2", "p3")];
    for (k, (u, v)) in bars.iter().enumerate() {
        b.constraint(ConstraintKind::Distance, &format!("d{k}"), &[u, v], None).unwrap();
    }
    for k in 0..fixes {
        b.constraint(ConstraintKind::Fix, &format!("f{k}"), &[&format!("p{k}")], None).unwrap();
    }
    b.build()
}

#[test]
fn coincident_points_are_merged_and_one_fixed_point_is_covered() {
    for dim in [Dim::Two, Dim::Three] {
        let yes = dim == Dim::Two; // K4 is globally rigid in the plane, rigid in space too.
        for (split, fixes, covered) in [
            (false, 0, true),
            (true, 0, true),
            (false, 1, true),
            (true, 1, true),
            (false, 2, false),
        ] {
            let s = builder_k4(dim, split, fixes);
            for backend in BACKENDS {
                let a = analyze(&s, &AnalysisOptions { backend, ..AnalysisOptions::default() })
                    .unwrap();
                let at = format!("{dim:?} split {split} fixes {fixes} {}", backend.name());
                assert_eq!(a.global_rigidity.is_some(), covered, "{at}");
                if let Some(g) = a.global_rigidity {
                    assert_eq!(g.points, 4, "{at}");
                    assert!(g.globally_rigid || !yes, "{at}: {g:?}");
                    // K4 in 3D: 4 = d + 1 points, complete: globally rigid as well.
                    assert!(g.globally_rigid, "{at}: {g:?}");
                }
            }
        }
    }
}

#[test]
fn other_entities_or_constraints_are_not_covered() {
    let text = r#"System(dim: 2,
        entities: [Point(id: "a", at: [0, 0]), Point(id: "b", at: [4, 1]),
                   Line(id: "l", at: [[0, 5], [3, 7]])],
        constraints: [Distance(id: "d", a: "a", b: "b"), Incident(id: "i", a: "a", b: "l")])"#;
    let s = System::from_ron_str(text, None).unwrap();
    let a = analyze(&s, &AnalysisOptions::default()).unwrap();
    assert!(a.global_rigidity.is_none());
    // The cluster {a, b} is a distance framework of its own; the line's clusters are not.
    let covered: Vec<bool> = a.cluster_global_rigidity.iter().map(Option::is_some).collect();
    assert_eq!(covered.len(), a.clusters.len());
    assert!(covered.contains(&true) && covered.contains(&false), "{:?}", a.clusters);
}

/// Two K4s sharing a point: not rigid (a hinge), so not globally rigid; each K4 is a
/// globally rigid cluster. A triangle with a pendant vertex: one cluster, which can flip.
#[test]
fn clusters_get_their_own_answer() {
    let mut edges = complete(4);
    edges.extend(complete(4).iter().map(|(a, b)| (a + 3, b + 3)));
    let s = model("two K4 on a hinge", Dim::Two, &edges, 5);
    let a = analyze(&s, &AnalysisOptions::default()).unwrap();
    let g = a.global_rigidity.as_ref().unwrap();
    assert!(!g.rigid && !g.globally_rigid);
    assert_eq!(a.clusters.len(), 2);
    for c in &a.cluster_global_rigidity {
        assert!(c.as_ref().unwrap().globally_rigid);
    }
    let s = model("pendant", Dim::Two, &[(0, 1), (1, 2), (0, 2), (0, 3), (1, 3)], 5);
    let a = analyze(&s, &AnalysisOptions::default()).unwrap();
    assert_eq!(a.clusters.len(), 1);
    assert!(!a.cluster_global_rigidity[0].as_ref().unwrap().globally_rigid);
    // Turned off: nothing computed.
    let off =
        analyze(&s, &AnalysisOptions { global_rigidity: false, ..Default::default() }).unwrap();
    assert!(
        off.global_rigidity.is_none() && off.cluster_global_rigidity.iter().all(Option::is_none)
    );
}
