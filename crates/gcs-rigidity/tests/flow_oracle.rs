//! The maximum flow of [`FlowGraph`] against petgraph's `dinics` as an oracle, on random
//! networks: the value of a flow from scratch, and the incremental reading the flow-based
//! rigidity algorithms rely on — an overload of `K` units pushed from a node on top of a
//! maximum flow ([`FlowGraph::augment_from`]) adds exactly what a fresh maximum flow gains
//! when an arc of capacity `K` from the source to that node is added — and the rollback.

use gcs_rigidity::flow::FlowGraph;
use petgraph::algo::dinics;
use petgraph::graph::{Graph, NodeIndex};
use proptest::prelude::*;

/// petgraph's maximum flow value from node 0 to node `n − 1`.
fn oracle(n: usize, arcs: &[(usize, usize, u64)]) -> u64 {
    let mut g: Graph<(), u64> = Graph::new();
    let nodes: Vec<NodeIndex> = (0..n).map(|_| g.add_node(())).collect();
    for &(a, b, c) in arcs {
        g.add_edge(nodes[a], nodes[b], c);
    }
    dinics(&g, nodes[0], nodes[n - 1]).0
}

fn arcs_strategy() -> impl Strategy<Value = (usize, Vec<(usize, usize, u64)>)> {
    (3usize..12).prop_flat_map(|n| {
        let arc = (0..n, 0..n, 0u64..10).prop_filter("no loops", |(a, b, _)| a != b);
        (Just(n), prop::collection::vec(arc, 0..40))
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn max_flow_matches_petgraph((n, arcs) in arcs_strategy(), v in 1usize..64, budget in 1u64..15) {
        let (s, t) = (0, n - 1);
        let mut flow = FlowGraph::new(n);
        let ids: Vec<usize> = arcs.iter().map(|&(a, b, c)| flow.add_arc(a, b, c)).collect();
        let base = flow.max_flow(s, t);
        prop_assert_eq!(base, oracle(n, &arcs));
        let out_of_source = |f: &FlowGraph| -> u64 {
            ids.iter().filter(|id| f.endpoints(**id).0 == s).map(|id| f.flow(*id)).sum::<u64>()
                - ids.iter().filter(|id| f.endpoints(**id).1 == s).map(|id| f.flow(*id)).sum::<u64>()
        };
        prop_assert_eq!(out_of_source(&flow), base);

        // The overload on node `v` (not the sink), on top of the maximum flow.
        let v = 1 + v % (n - 2).max(1);
        prop_assume!(v != t);
        flow.checkpoint();
        let extra = flow.augment_from(&[v], t, budget);
        let mut overloaded = arcs.clone();
        overloaded.push((s, v, budget));
        prop_assert_eq!(base + extra, oracle(n, &overloaded));
        flow.rollback();
        prop_assert_eq!(out_of_source(&flow), base);
        for id in &ids {
            prop_assert!(flow.flow(*id) <= flow.capacity(*id));
        }
    }
}
