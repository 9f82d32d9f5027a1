//! Maximal rigid subsystems (witness paper §4) and the W-decomposition (§5) on the papers'
//! examples, and against a combinatorial oracle on random 2D bar frameworks.

use std::collections::BTreeSet;
use std::path::Path;

use gcs_analysis::{
    Analysis, AnalysisOptions, Backend, ClusterMethod, DecompositionNode, RemovalOrder, analyze,
};
use gcs_model::generate::{framework, laman_edges, random_coords};
use gcs_model::rng::SplitMix64;
use gcs_model::{Dim, EntityIdx, System};
use proptest::prelude::*;

fn model(name: &str) -> System {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data").join(name);
    let text = std::fs::read_to_string(&path).unwrap();
    System::from_ron_str(&text, Some(name)).unwrap()
}

fn run(s: &System, decompose: bool) -> Analysis {
    analyze(s, &AnalysisOptions { decompose, ..AnalysisOptions::default() }).unwrap()
}

/// Entity ids, segments left out, as a sorted set.
fn entity_set(s: &System, entities: &[EntityIdx]) -> BTreeSet<String> {
    entities
        .iter()
        .filter(|e| s.segment_points(**e).is_none())
        .map(|e| s.entity(*e).id.clone())
        .collect()
}

/// The models of `data/paper` and `data/sketches`, each with its name there (`paper/kite.ron`).
fn paper_and_sketch_models() -> Vec<(String, System)> {
    gcs_suite::data_files()
        .iter()
        .filter_map(|f| f.strip_prefix("data/"))
        .filter(|f| f.starts_with("paper/") || f.starts_with("sketches/"))
        .map(|name| (name.to_owned(), model(name)))
        .collect()
}

/// Cluster entity ids, segments left out, as sorted sets.
fn clusters(s: &System, a: &Analysis) -> Vec<BTreeSet<String>> {
    a.clusters.iter().map(|c| entity_set(s, &c.entities)).collect()
}

fn set(ids: &[&str]) -> BTreeSet<String> {
    ids.iter().map(|s| s.to_string()).collect()
}

#[test]
fn chain_of_three_triangles() {
    let s = model("paper/chain.ron");
    let a = run(&s, false);
    assert_eq!(a.dof, 2);
    assert_eq!(
        clusters(&s, &a),
        vec![set(&["p1", "p2", "p3"]), set(&["p3", "p4", "p5"]), set(&["p5", "p6", "p7"])]
    );
    for c in &a.clusters {
        assert_eq!(c.constraints.len(), 3, "each triangle keeps its three distances");
    }
}

#[test]
fn butterfly_and_double_banana_share_hinges() {
    let s = model("paper/butterfly.ron");
    assert_eq!(
        clusters(&s, &run(&s, false)),
        vec![set(&["p0", "p1", "p2"]), set(&["p0", "p3", "p4"])]
    );
    let s = model("paper/double_banana.ron");
    let c = clusters(&s, &run(&s, false));
    assert_eq!(c.len(), 2);
    let shared: BTreeSet<String> = c[0].intersection(&c[1]).cloned().collect();
    assert_eq!(shared, set(&["N", "S"]));
    assert!(c.iter().all(|x| x.len() == 5));
}

#[test]
fn flow_fig1b_clusters() {
    // {A, C, D, E, F} is rigid (over-rigid even); B slides along A. A point on an infinite
    // line keeps its relative placement with it (the slide is a translation along the line),
    // so {A, B} is a rigid pair, sharing A with the big cluster (docs/format.md §4).
    let s = model("paper/flow_fig1b.ron");
    assert_eq!(
        clusters(&s, &run(&s, false)),
        vec![set(&["A", "B"]), set(&["A", "C", "D", "E", "F"])]
    );
}

#[test]
fn every_model_is_covered_and_every_cluster_is_rigid_alone() {
    for (name, s) in paper_and_sketch_models() {
        let a = run(&s, false);
        for e in s.entity_indices() {
            assert!(
                a.clusters.iter().any(|c| c.entities.contains(&e)),
                "{name}: {e:?} in no cluster"
            );
        }
        // Cut out with its constraints, a cluster with more than one entity is rigid (up to
        // absolute constraints: a grounded cluster has no trivial motion left, a free one
        // only displacements).
        for c in a.clusters.iter().filter(|c| c.entities.len() > 1) {
            let cut = cut_out(&s, &c.entities, &c.constraints);
            let ca = run(&cut, false);
            assert_eq!(ca.dof, 0, "{name}: cluster {:?} is not rigid alone", c.entities);
        }
    }
}

/// The subsystem of `s` made of some entities and constraints (with the points of segments).
fn cut_out(
    s: &System,
    entities: &[gcs_model::EntityIdx],
    constraints: &[gcs_model::ConstraintIdx],
) -> System {
    // The cluster's entities, and the points of its segments (already among them: a segment is
    // in a cluster only with both its points).
    let keep: Vec<gcs_model::EntityIdx> =
        s.entity_indices().filter(|e| entities.contains(e)).collect();
    let mut b = gcs_model::SystemBuilder::new("cut", s.dim());
    for e in &keep {
        let ent = s.entity(*e);
        if ent.owner.is_some() {
            continue; // made with its owner
        }
        match &ent.geometry {
            gcs_model::Geometry::Point { at } => b.point(&ent.id, at.clone()).map(|_| ()),
            gcs_model::Geometry::Line { at } => b.line(&ent.id, at.clone()).map(|_| ()),
            gcs_model::Geometry::Plane { at } => b.plane(&ent.id, at.clone()).map(|_| ()),
            gcs_model::Geometry::Circle { center, radius } => {
                b.circle(&ent.id, center.clone(), radius.clone()).map(|_| ())
            }
            gcs_model::Geometry::Sphere { center, radius } => {
                b.sphere(&ent.id, center.clone(), radius.clone()).map(|_| ())
            }
            gcs_model::Geometry::Segment { from, to } => {
                b.segment(&ent.id, &s.entity(*from).id, &s.entity(*to).id).map(|_| ())
            }
            gcs_model::Geometry::Arc { center, radius, start, end } => {
                let at = |p: &gcs_model::EntityIdx| match &s.entity(*p).geometry {
                    gcs_model::Geometry::Point { at } => at.clone(),
                    _ => None,
                };
                b.arc(&ent.id, center.clone(), radius.clone(), at(start), at(end)).map(|_| ())
            }
            gcs_model::Geometry::BSpline { degree, poles, knots, weights, periodic } => {
                let poles: Vec<&str> = poles.iter().map(|p| s.entity(*p).id.as_str()).collect();
                b.bspline(&ent.id, *degree, &poles, knots.clone(), weights.clone(), *periodic)
                    .map(|_| ())
            }
        }
        .unwrap();
    }
    for c in constraints {
        let con = s.constraint(*c);
        if con.owner.is_some() {
            continue;
        }
        let args: Vec<&str> = con.args.iter().map(|a| s.entity(*a).id.as_str()).collect();
        b.constraint(con.kind, &con.id, &args, con.value.clone()).unwrap();
    }
    b.build()
}

fn children_sets(s: &System, n: &DecompositionNode) -> Vec<BTreeSet<String>> {
    n.children.iter().map(|c| entity_set(s, &c.entities)).collect()
}

fn all_nodes(n: &DecompositionNode, out: &mut Vec<BTreeSet<gcs_model::EntityIdx>>) {
    out.push(n.entities.iter().copied().collect());
    for c in &n.children {
        all_nodes(c, out);
    }
}

#[test]
fn two_k33_decompose_into_the_two_k33() {
    let s = model("paper/two_k33.ron");
    let a = run(&s, true);
    assert_eq!(a.clusters.len(), 1, "rigid: one cluster");
    let tree = &a.decomposition.as_ref().unwrap()[0];
    let k33 = |p: &str, q: &str| -> BTreeSet<String> {
        ["1", "2", "3"].iter().flat_map(|i| [format!("{p}{i}"), format!("{q}{i}")]).collect()
    };
    assert_eq!(children_sets(&s, tree), vec![k33("a", "b"), k33("c", "d")]);
    // Each K3,3 is W-indecomposable, and so is fig. 8b (the reduced system): no other node.
    assert!(tree.children.iter().all(|c| c.children.is_empty()));
    // The same subsystems whichever constraint is tried first (e1 or e2 in the paper).
    for order in [RemovalOrder::FileOrder, RemovalOrder::LowDegreeFirst] {
        let b = analyze(
            &s,
            &AnalysisOptions {
                decompose: true,
                removal_order: order,
                ..AnalysisOptions::default()
            },
        )
        .unwrap();
        let (mut x, mut y) = (Vec::new(), Vec::new());
        all_nodes(tree, &mut x);
        all_nodes(&b.decomposition.as_ref().unwrap()[0], &mut y);
        x.sort();
        y.sort();
        assert_eq!(x, y, "{order:?}");
    }
}

#[test]
fn fig9_decomposable_and_indecomposable() {
    let s = model("paper/fig9a_w_decomposable.ron");
    let a = run(&s, true);
    let tree = &a.decomposition.as_ref().unwrap()[0];
    let inner: BTreeSet<String> = (1..=8).map(|i| format!("p{i}")).collect();
    assert!(children_sets(&s, tree).contains(&inner), "the inner rigid part is found");
    for name in [
        "paper/fig9b_w_indecomposable.ron",
        "paper/fig9c_w_indecomposable_member.ron",
        "paper/kite.ron",
    ] {
        let s = model(name);
        let a = run(&s, true);
        let trees = a.decomposition.as_ref().unwrap();
        assert_eq!(trees.len(), 1, "{name}");
        assert!(trees[0].children.is_empty(), "{name} is W-indecomposable");
        assert!(a.decomposition_statistics.unwrap().complete);
    }
}

#[test]
fn methods_agree_on_every_model() {
    for (name, s) in paper_and_sketch_models() {
        let base = run(&s, false).clusters;
        for method in [ClusterMethod::Kernel, ClusterMethod::Exchange, ClusterMethod::Eliminate] {
            for backend in [Backend::Exact, Backend::ModP, Backend::Rational] {
                let o = AnalysisOptions {
                    cluster_method: method,
                    backend,
                    ..AnalysisOptions::default()
                };
                assert_eq!(
                    analyze(&s, &o).unwrap().clusters,
                    base,
                    "{name} {method:?} {backend:?}"
                );
            }
        }
    }
}

/// Rank of an edge set in the 2D generic rigidity matroid: the largest (2,3)-sparse subset
/// (greedy is optimal in a matroid; sparsity checked over all vertex subsets — small graphs).
fn laman_rank(n: usize, edges: &[(usize, usize)]) -> usize {
    let mut kept: Vec<(usize, usize)> = Vec::new();
    for &e in edges {
        kept.push(e);
        let sparse = (1u32..(1 << n)).all(|mask| {
            let k = mask.count_ones() as usize;
            if k < 2 {
                return true;
            }
            let inside =
                kept.iter().filter(|(a, b)| mask >> a & 1 == 1 && mask >> b & 1 == 1).count();
            inside <= 2 * k - 3
        });
        if !sparse {
            kept.pop();
        }
    }
    kept.len()
}

/// Rigid components: maximal vertex sets (of two or more) whose induced edges have rank
/// 2k − 3; vertices in none are alone.
fn rigid_components(n: usize, edges: &[(usize, usize)]) -> Vec<BTreeSet<usize>> {
    let mut rigid: Vec<u32> = Vec::new();
    for mask in 1u32..(1 << n) {
        let k = mask.count_ones() as usize;
        if k < 2 {
            continue;
        }
        let inside: Vec<(usize, usize)> = edges
            .iter()
            .copied()
            .filter(|(a, b)| mask >> a & 1 == 1 && mask >> b & 1 == 1)
            .collect();
        if laman_rank(n, &inside) == 2 * k - 3 {
            rigid.push(mask);
        }
    }
    let maximal: Vec<u32> =
        rigid.iter().copied().filter(|m| !rigid.iter().any(|o| o != m && o & m == *m)).collect();
    let mut out: Vec<BTreeSet<usize>> =
        maximal.iter().map(|m| (0..n).filter(|i| m >> i & 1 == 1).collect()).collect();
    for v in 0..n {
        if !out.iter().any(|c| c.contains(&v)) {
            out.push(BTreeSet::from([v]));
        }
    }
    out.sort();
    out
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, failure_persistence: None, ..ProptestConfig::default() })]

    /// On random 2D bar frameworks (Laman graphs, then some bars removed and some added), the
    /// clusters are exactly the rigid components the combinatorial count finds (Laman's
    /// theorem makes the count exact for generic bar frameworks).
    #[test]
    fn clusters_are_the_rigid_components(seed in 0u64..10_000, n in 3usize..=8, removed in 0usize..4, added in 0usize..3) {
        let (s, edges) = gcs_suite::random_bar_framework(seed, n, removed, added);
        let a = run(&s, false);
        let mut ours: Vec<BTreeSet<usize>> = a
            .clusters
            .iter()
            .map(|c| c.entities.iter().map(|e| e.index()).collect())
            .collect();
        ours.sort();
        prop_assert_eq!(ours, rigid_components(n, &edges));
    }

    /// Trees of rigid bodies (small Laman frameworks, each hinged at one point of an earlier
    /// one), sometimes with a bar closing a cycle through several bodies or a bar removed:
    /// the open-chain shortcut, where it applies, and the general search give the same
    /// clusters, and both equal the rigid components of the count.
    #[test]
    fn the_open_chain_shortcut_agrees_with_the_search(seed in 0u64..10_000, bodies in 1usize..=4, close in 0usize..3, remove in 0usize..3) {
        let mut rng = SplitMix64::new(seed);
        let mut edges: Vec<(usize, usize)> = Vec::new();
        let mut n = 0;
        for b in 0..bodies {
            let size = 2 + rng.below(2) as usize;
            let local = laman_edges(size + 1, 0.5, &mut rng);
            // Local vertex 0 is the hinge: a point of an earlier body (or new for the first).
            let hinge = if b == 0 { n } else { rng.below(n as u64) as usize };
            let first_new = if b == 0 { n } else { n - 1 };
            let map = |v: usize| if v == 0 { hinge } else { first_new + v };
            edges.extend(local.iter().map(|&(x, y)| (map(x), map(y))));
            n = first_new + size + 1;
        }
        if close == 0 && n > 3 {
            let (a, b) = (rng.below(n as u64) as usize, rng.below(n as u64) as usize);
            if a != b && !edges.contains(&(a, b)) && !edges.contains(&(b, a)) {
                edges.push((a, b));
            }
        }
        if remove == 0 && edges.len() > 1 {
            let i = rng.below(edges.len() as u64) as usize;
            edges.remove(i);
        }
        let coords = random_coords(n, Dim::Two, 1000, &mut rng);
        let s = framework("tree", Dim::Two, &coords, &edges);
        let with = |method: ClusterMethod| {
            let o = AnalysisOptions { cluster_method: method, ..AnalysisOptions::default() };
            analyze(&s, &o).unwrap().clusters
        };
        let shortcut = with(ClusterMethod::OpenChain);
        prop_assert_eq!(&shortcut, &with(ClusterMethod::Kernel));
        let mut ours: Vec<BTreeSet<usize>> = shortcut
            .iter()
            .map(|c| c.entities.iter().map(|e| e.index()).collect())
            .collect();
        ours.sort();
        prop_assert_eq!(ours, rigid_components(n, &edges));
    }
}

fn check_tree(s: &System, node: &DecompositionNode, path: &str) {
    // Every node is rigid when cut out with its constraints.
    if node.entities.len() > 1 {
        let cut = cut_out(s, &node.entities, &node.constraints);
        let a = run(&cut, false);
        assert_eq!(a.dof, 0, "{path}: node {:?} is not rigid alone", node.entities);
    }
    for c in &node.children {
        assert!(
            c.entities.iter().all(|e| node.entities.contains(e)),
            "{path}: a child is not contained in its parent"
        );
        assert!(
            c.constraints.iter().all(|k| node.constraints.contains(k)),
            "{path}: child constraints"
        );
        assert!(c.entities.len() < node.entities.len(), "{path}: a child is smaller");
        check_tree(s, c, path);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]

    /// On random rigid 2D bar frameworks, every node of the W-decomposition is a rigid
    /// subsystem contained in its parent, and every leaf is W-indecomposable as a system of
    /// its own (decomposing it again gives no child).
    #[test]
    fn decomposition_nodes_are_rigid_subsystems(seed in 0u64..10_000, n in 4usize..=10) {
        let s = gcs_model::generate::laman(n, seed);
        let a = run(&s, true);
        let trees = a.decomposition.as_ref().unwrap();
        prop_assert_eq!(trees.len(), 1);
        check_tree(&s, &trees[0], &format!("laman({n}, {seed})"));
        fn leaves<'t>(n: &'t DecompositionNode, out: &mut Vec<&'t DecompositionNode>) {
            if n.children.is_empty() { out.push(n) } else { for c in &n.children { leaves(c, out) } }
        }
        let mut ls = Vec::new();
        leaves(&trees[0], &mut ls);
        for leaf in ls {
            let cut = cut_out(&s, &leaf.entities, &leaf.constraints);
            let again = run(&cut, true);
            let t = &again.decomposition.as_ref().unwrap()[0];
            prop_assert!(t.children.is_empty(), "a leaf decomposes further: {:?}", leaf.entities);
        }
    }
}

/// The removal heuristic (witness paper §7) is measured by the cluster searches it costs: on a
/// triangulated strip (where central removals split it into balanced halves) and on a random
/// Laman graph (where peeling low-degree vertices is what works), the default order searches
/// fewer entities in all than file order.
#[test]
fn the_default_removal_order_saves_cluster_searches() {
    use gcs_model::generate::{laman, strip};
    for s in [strip(25, 3), laman(30, 3)] {
        let searches = |order: RemovalOrder| {
            let options = AnalysisOptions {
                backend: Backend::ModP,
                decompose: true,
                removal_order: order,
                ..AnalysisOptions::default()
            };
            let a = analyze(&s, &options).unwrap();
            let stats = a.decomposition_statistics.unwrap();
            assert!(stats.complete, "{}", s.name());
            stats.searched_entities
        };
        let (default, file) =
            (searches(RemovalOrder::default()), searches(RemovalOrder::FileOrder));
        assert!(default < file, "{}: {default} entities searched, file order {file}", s.name());
    }
}

/// A 3D line `h` hinges two parts: a point `a` on it stops the turn about `h`, the plane `P`
/// through it stops the slide along it, so {h, a, P} is rigid although it crosses the hinge.
/// Every method, the open-chain shortcut included (it must stand down: the groups here have
/// low degrees of rigidity), finds it. (Found by review.)
#[test]
fn a_rigid_set_across_a_3d_line_hinge() {
    let text = r#"System(name: "hinge_line", dim: 3,
      entities: [
        Line(id: "h", at: [[1, 2, 0], [3, 3, 1]]), Point(id: "a", at: [5, 4, 2]),
        Plane(id: "P", at: [[1, 2, 0], [1, -2, 0]]), Point(id: "p", at: [0, 5, -1]),
        Point(id: "q", at: [-1, 1, 5]),
      ],
      constraints: [
        Incident(id: "a_on_h", a: "a", b: "h"), Incident(id: "h_in_P", a: "h", b: "P"),
        Distance(id: "p_h", a: "p", b: "h", value: 3), Distance(id: "a_p", a: "a", b: "p", value: 4),
        Incident(id: "q_on_P", a: "q", b: "P"), Distance(id: "q_h", a: "q", b: "h", value: 2),
      ])"#;
    let s = System::from_ron_str(text, None).unwrap();
    let expected = vec![set(&["a", "h", "p"]), set(&["a", "h", "P"]), set(&["h", "P", "q"])];
    for method in [ClusterMethod::OpenChain, ClusterMethod::Kernel, ClusterMethod::Exchange] {
        let o = AnalysisOptions { cluster_method: method, ..AnalysisOptions::default() };
        let a = analyze(&s, &o).unwrap();
        let mut found = clusters(&s, &a);
        found.sort();
        let mut want = expected.clone();
        want.sort();
        assert_eq!(found, want, "{method:?}");
    }
}

/// Every node of a decomposition tree, depth first.
fn tree_nodes(node: &DecompositionNode) -> Vec<&DecompositionNode> {
    let mut out = vec![node];
    for c in &node.children {
        out.extend(tree_nodes(c));
    }
    out
}

/// Whether every child of every node lies in its parent (a tree by containment).
fn nested(node: &DecompositionNode) -> bool {
    node.children.iter().all(|c| {
        c.entities.iter().all(|e| node.entities.contains(e))
            && c.constraints.iter().all(|k| node.constraints.contains(k))
            && c.entities.len() < node.entities.len()
            && nested(c)
    })
}

/// Feature incorporation (issue 14, the ESM paper §2.1): a declared group that is rigid on its
/// own constraints is a node of the analysis' DR-plan. In a chain of three K3,3 (blocks A, B,
/// C), the W-decomposition does not have both pairs A ∪ B and B ∪ C as nodes; declared, each is
/// one (marked with its group), the tree stays nested, and it is W-decomposed below into its two
/// K3,3. A group that is not rigid (A and one point of B) is no node, and the analysis says it
/// has two rigid parts. Without groups, the decomposition is the same as before.
#[test]
fn a_declared_rigid_group_is_a_node_of_the_decomposition() {
    let chain = gcs_model::generate::k33_chain(3, 1);
    let ids =
        |range: std::ops::Range<usize>| -> Vec<String> { range.map(|i| format!("p{i}")).collect() };
    let set = |v: &[String]| -> BTreeSet<String> { v.iter().cloned().collect() };
    let plain = run(&chain, true);
    let [tree] = plain.decomposition.as_deref().unwrap() else { panic!("one cluster") };
    let has = |tree: &DecompositionNode, want: &BTreeSet<String>| {
        tree_nodes(tree).iter().any(|n| entity_set(&chain, &n.entities) == *want)
    };
    let (ab, bc) = (set(&ids(0..12)), set(&ids(6..18)));
    assert!(!(has(tree, &ab) && has(tree, &bc)), "the plain plan has not both pairs");
    assert!(plain.group_rigidity.as_ref().is_some_and(Vec::is_empty));
    for groups in [vec![("AB", 0..12)], vec![("BC", 6..18)], vec![("AB", 0..12), ("BC", 6..18)]] {
        let mut b = gcs_model::SystemBuilder::from_system(chain.clone());
        for (name, range) in &groups {
            let members = ids(range.clone());
            b.group(name, &members.iter().map(String::as_str).collect::<Vec<_>>()).unwrap();
        }
        let s = b.build();
        let a = run(&s, true);
        let [tree] = a.decomposition.as_deref().unwrap() else { panic!("one cluster") };
        assert!(nested(tree));
        for (k, (name, range)) in groups.iter().enumerate() {
            let want = set(&ids(range.clone()));
            let node = (tree_nodes(tree).into_iter())
                .find(|n| n.groups == vec![k])
                .unwrap_or_else(|| panic!("{name} is a node"));
            assert_eq!(entity_set(&s, &node.entities), want, "{name}");
            assert_eq!(node.constraints.len(), 2 * 12 - 3, "{name}: its own distances");
            let kids: Vec<BTreeSet<String>> =
                node.children.iter().map(|c| entity_set(&s, &c.entities)).collect();
            assert_eq!(kids.len(), 2, "{name}: two K3,3 below it: {kids:?}");
        }
        let verdicts = a.group_rigidity.unwrap();
        assert!(verdicts.iter().all(|g| g.rigid() && g.parts == 1), "{verdicts:?}");
    }
    let mut b = gcs_model::SystemBuilder::from_system(chain.clone());
    let loose = ids(0..7);
    b.group("loose", &loose.iter().map(String::as_str).collect::<Vec<_>>()).unwrap();
    let s = b.build();
    let a = run(&s, true);
    let verdict = &a.group_rigidity.unwrap()[0];
    assert!(!verdict.rigid() && verdict.parts == 2, "{verdict:?}");
    let [tree] = a.decomposition.as_deref().unwrap() else { panic!("one cluster") };
    assert!(tree_nodes(tree).iter().all(|n| n.groups.is_empty()));
    assert_eq!(a.decomposition, plain.decomposition, "no node changes");
}
