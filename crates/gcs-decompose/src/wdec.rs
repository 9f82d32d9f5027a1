//! W-decomposition (witness paper §5, Algorithm 3) and the well-constrained boundary (§3.2).
//!
//! A rigid subsystem is decomposed by removing one constraint `e`, finding the maximal rigid
//! subsystems of what is left ([`crate::rigid`]), and keeping those that are *non-trivial*:
//! that have an entity not on their boundary (an entity bound only by the subsystem's own
//! constraints — a bar between two boundary points is trivial, a triangle hanging from two
//! points is not), and are not the whole system. Each non-trivial subsystem `M` is replaced by
//! its boundary: an independent set of relations (distances, angles) among its boundary
//! entities, chosen by incremental elimination at the witness until they make the boundary as
//! rigid as `M` does (§3.2: all maximal independent subsets are equivalent). With `e` put back
//! the reduced system is rigid; the reduced system and every `M` are decomposed recursively.
//! A system for which no constraint gives a non-trivial subsystem is W-indecomposable: a leaf.
//!
//! The result is a DR-plan (decomposition–recombination plan, Sitharam et al.): a tree of
//! rigid subsystems ordered by containment, whose leaves are W-indecomposable. Nodes found in
//! a reduced system are mapped back to the original entities and constraints (each boundary
//! replaced by the subsystem it stands for) and kept only if rigid there.
//!
//! **Which constraint first.** The paper's §7 suggests trying constraints that appear in few
//! chains. The default heuristic ([`RemovalOrder::FewShortCycles`]) ranks the constraints by
//! how central they are (a central removal splits the system into halves of similar size, so
//! the recursion is balanced: triangulated strips), then by how few short cycles go through
//! them; after the most central one it turns to the constraints of low-degree entities (an
//! entity attached by few constraints, such as a vertex added by a Henneberg move, is split off
//! by removing one of them: random Laman graphs, where central removals are fruitless).
//! [`Statistics`] counts the maximal rigid subsystem computations, so the saving over file
//! order can be measured.

use std::collections::{HashMap, HashSet};

use gcs_jacobian::relation_row;
use gcs_model::{ConstraintIdx, ConstraintKind, EntityIdx, Signature, System};
use gcs_rank::{Echelon, Field};

use crate::pebble::Game;
use crate::rigid::{Context, Group, Label, RawCluster, Subsystem, bar_clusters, clusters};

/// Order in which constraints are tried for removal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum RemovalOrder {
    /// The most central constraint first (its entities equally far from the two ends of a
    /// longest path found by a double breadth-first sweep; ties broken by few short cycles —
    /// triangles, then 4-cycles — through its entities, then file order), then the others by
    /// the lowest degree of their entities, in that same order within a degree (the default).
    #[default]
    FewShortCycles,
    /// Constraints binding low-degree entities first, then file order.
    LowDegreeFirst,
    /// File order.
    FileOrder,
}

/// How many constraints [`RemovalOrder::FewShortCycles`] tries in its central order before
/// turning to the constraints of low-degree entities.
const CENTRAL_TRIES: usize = 1;

/// For each group of a subsystem, the smallest degree (number of groups binding it) among its
/// entities.
fn min_degree<F>(sub: &Subsystem<F>) -> Vec<usize> {
    let mut degree: HashMap<EntityIdx, usize> = HashMap::new();
    for g in &sub.groups {
        for e in &g.entities {
            *degree.entry(*e).or_default() += 1;
        }
    }
    sub.groups
        .iter()
        .map(|g| g.entities.iter().map(|e| degree[e]).min().unwrap_or(usize::MAX))
        .collect()
}

/// Counters of a W-decomposition.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Statistics {
    /// Maximal rigid subsystem computations (each one elimination plus anchoring).
    pub mrs_computations: usize,
    /// Entities over all those computations: a measure of their total cost, which depends on
    /// how balanced the recursion is as much as on how many computations it takes.
    pub searched_entities: usize,
    /// Constraints removed without revealing a non-trivial subsystem.
    pub fruitless_removals: usize,
    /// Whether the decomposition ran to the end; false when the work budget was exhausted
    /// (the subsystems not yet examined are then reported as leaves).
    pub complete: bool,
}

/// A node of a W-decomposition: a rigid subsystem and the rigid subsystems it decomposes into.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DecompositionNode {
    /// Its entities in file order (segments whose points are in it included).
    pub entities: Vec<EntityIdx>,
    /// Its constraints in file order.
    pub constraints: Vec<ConstraintIdx>,
    /// Sub-subsystems; empty for a W-indecomposable leaf.
    pub children: Vec<DecompositionNode>,
    /// The groups the user declared ([`System::groups`], by index) that this node is: a rigid
    /// group is a node of the DR-plan (feature incorporation, [`crate::clusters`]).
    pub groups: Vec<usize>,
}

/// A node over the labels of a (possibly reduced) subsystem.
#[derive(Clone, Debug, Default)]
struct Node {
    entities: Vec<EntityIdx>,
    labels: Vec<Label>,
    children: Vec<Node>,
}

/// A non-trivial subsystem replaced by its boundary in a reduced system.
struct Replacement {
    /// The boundary relations standing for it.
    virtual_labels: Vec<Label>,
    entities: Vec<EntityIdx>,
    labels: Vec<Label>,
}

pub(crate) struct Decomposer<'c, 'a, F> {
    pub(crate) ctx: &'c Context<'a, F>,
    witness: Vec<F>,
    order: RemovalOrder,
    next_virtual: usize,
    pub(crate) stats: Statistics,
    /// Work budget: maximal rigid subsystem computations left, to bound the work on huge
    /// inputs.
    budget: usize,
}

impl<'c, 'a, F: Field> Decomposer<'c, 'a, F> {
    pub(crate) fn new(ctx: &'c Context<'a, F>, witness: Vec<F>, order: RemovalOrder) -> Self {
        Decomposer {
            ctx,
            witness,
            order,
            next_virtual: 0,
            stats: Statistics { complete: true, ..Statistics::default() },
            budget: usize::MAX,
        }
    }

    /// Bounds the number of maximal rigid subsystem computations.
    pub(crate) fn with_budget(mut self, budget: usize) -> Self {
        self.budget = budget;
        self
    }

    /// The W-decomposition of a rigid subsystem.
    pub(crate) fn decompose(&mut self, sub: &Subsystem<F>) -> DecompositionNode {
        let node = self.wdec(sub, None);
        self.to_public(node)
    }

    fn to_public(&self, node: Node) -> DecompositionNode {
        let system = self.ctx.system;
        let mut entities = node.entities.clone();
        for e in system.entity_indices() {
            if system.entity(e).kind().is_composite()
                && system.entity(e).geometry.parts().iter().all(|p| node.entities.contains(p))
            {
                entities.push(e);
            }
        }
        entities.sort_unstable();
        let mut constraints: Vec<ConstraintIdx> = node
            .labels
            .iter()
            .filter_map(|l| match l {
                Label::Constraint(c) => Some(*c),
                Label::Virtual(_) => None,
            })
            .collect();
        constraints.sort_unstable();
        let mut children: Vec<DecompositionNode> =
            node.children.into_iter().map(|c| self.to_public(c)).collect();
        children.sort_by(|a, b| a.entities.cmp(&b.entities));
        DecompositionNode { entities, constraints, children, groups: Vec::new() }
    }

    fn leaf(sub: &Subsystem<F>) -> Node {
        Node {
            entities: sub.entities.clone(),
            labels: sub.groups.iter().map(|g| g.label).collect(),
            children: Vec::new(),
        }
    }

    fn removal_order(&self, sub: &Subsystem<F>) -> Vec<usize> {
        let mut order: Vec<usize> = (0..sub.groups.len()).collect();
        if self.order == RemovalOrder::FewShortCycles {
            // The entity graph: two entities are adjacent when a group binds both.
            let position: HashMap<EntityIdx, usize> =
                sub.entities.iter().enumerate().rev().map(|(i, e)| (*e, i)).collect();
            let index = |e: &EntityIdx| position.get(e).copied();
            let n = sub.entities.len();
            let mut adj: Vec<Vec<usize>> = vec![Vec::new(); n];
            for g in &sub.groups {
                let ix: Vec<usize> = g.entities.iter().filter_map(index).collect();
                for &a in &ix {
                    for &b in &ix {
                        if a != b && !adj[a].contains(&b) {
                            adj[a].push(b);
                        }
                    }
                }
            }
            // Centrality: distances to the two ends of a long path (double BFS sweep); a
            // constraint in the middle splits the system into halves of similar size, so the
            // recursion is balanced instead of peeling one piece at a time.
            let bfs = |start: usize| -> Vec<usize> {
                let mut dist = vec![usize::MAX; n];
                let mut queue = std::collections::VecDeque::from([start]);
                dist[start] = 0;
                while let Some(u) = queue.pop_front() {
                    for &w in &adj[u] {
                        if dist[w] == usize::MAX {
                            dist[w] = dist[u] + 1;
                            queue.push_back(w);
                        }
                    }
                }
                dist
            };
            let far = |d: &[usize]| {
                (0..n).filter(|i| d[*i] != usize::MAX).max_by_key(|i| d[*i]).unwrap_or(0)
            };
            let (d1, d2) = if n > 0 {
                let u = far(&bfs(0));
                let du = bfs(u);
                let v = far(&du);
                (du, bfs(v))
            } else {
                (Vec::new(), Vec::new())
            };
            let key: Vec<(usize, usize, usize)> = sub
                .groups
                .iter()
                .map(|g| {
                    let ix: Vec<usize> = g.entities.iter().filter_map(index).collect();
                    let (mut triangles, mut squares) = (0, 0);
                    for (i, &u) in ix.iter().enumerate() {
                        for &v in &ix[i + 1..] {
                            triangles += adj[u].iter().filter(|w| adj[v].contains(w)).count();
                            for &w in adj[u].iter().filter(|w| **w != v) {
                                squares += adj[w]
                                    .iter()
                                    .filter(|x| **x != u && adj[v].contains(x))
                                    .count();
                            }
                        }
                    }
                    let off_centre =
                        ix.iter().map(|&u| d1[u].abs_diff(d2[u])).min().unwrap_or(usize::MAX);
                    (off_centre, triangles, squares)
                })
                .collect();
            order.sort_by_key(|&g| (key[g], g));
            // A few central tries, then the constraints of low-degree entities: where no
            // central constraint splits the system (random Laman graphs), peeling a vertex
            // added by a Henneberg move costs one try instead of dozens of fruitless ones.
            let tries = CENTRAL_TRIES.min(order.len());
            let degree = min_degree(sub);
            order[tries..].sort_by_key(|&g| degree[g]);
        } else if self.order == RemovalOrder::LowDegreeFirst {
            let degree = min_degree(sub);
            order.sort_by_key(|&g| (degree[g], g));
        }
        order
    }

    /// The W-decomposition of `sub`, given its certificate when the caller derived it from
    /// its parent's ([`Decomposer::sub_certificate`]).
    fn wdec(&mut self, sub: &Subsystem<F>, given: Option<Certificate>) -> Node {
        let mut certificate = given.or_else(|| self.pebble_certificate(sub));
        if sub.groups.len() <= 1
            || sub.entities.len() <= 1
            || certificate.as_ref().is_some_and(|c| c.leaf)
        {
            return Self::leaf(sub);
        }
        for gi in self.removal_order(sub) {
            if let Some(c) = &certificate
                && let (a, b) = c.bars[gi]
                && c.common[a]
                && c.common[b]
            {
                // Fruitless, by the certificate: no search.
                self.stats.fruitless_removals += 1;
                continue;
            }
            if self.budget == 0 {
                self.stats.complete = false;
                return Self::leaf(sub);
            }
            self.budget -= 1;
            let mut without = sub.clone();
            let removed = without.groups.remove(gi);
            self.stats.mrs_computations += 1;
            self.stats.searched_entities += without.entities.len();
            let found = match certificate.as_ref().and_then(|c| c.clusters_without(&without, gi)) {
                Some(found) => found,
                None => clusters(self.ctx, &without),
            };
            let degrees = Degrees::new(&without);
            let nontrivial: Vec<RawCluster> = found
                .into_iter()
                .filter(|m| {
                    m.entities.len() < sub.entities.len()
                        && m.entities.len() > 1
                        && degrees.boundary(&without, &removed, m).iter().any(|b| !b)
                })
                .collect();
            if nontrivial.is_empty() {
                self.stats.fruitless_removals += 1;
                continue;
            }
            let split = self.split(sub, &without, (gi, &removed), nontrivial, certificate.as_mut());
            if let Some(node) = split {
                return node;
            }
            self.stats.fruitless_removals += 1;
        }
        Self::leaf(sub)
    }

    /// The pebble game's certificate of which removals are fruitful, with none tried, for a
    /// minimally rigid 2D bar framework on four or more points ([`Certificate`]); `None` where
    /// it does not apply. Let `U_x` be the smallest rigid part holding the point `x` and all
    /// its neighbours. A removal is fruitful exactly when some `U_x` that is not the whole
    /// does not hold both ends of the removed bar — when an end is outside the intersection
    /// of those parts (so with none, `sub` is a leaf).
    ///
    /// Why that is exact: a removal is fruitful when it leaves a cluster `M`, not the whole,
    /// with a point `x` all of whose bars lie in `M`. Such an `M` is tight in `sub` too (its
    /// `2|M| − 3` bars; the removed one cannot join two of its points, sparsity forbids it),
    /// and holds `x` with its neighbours, so `U_x` lies in `M` and does not hold both ends of
    /// the removed bar. Conversely, a tight `U_x` without both ends of the removed bar stays
    /// rigid, inside a cluster that is not the whole (the rest is not rigid) with `x` inside
    /// it. `U_x` is `x` with the union of the smallest tight sets holding its first neighbour
    /// `y₁` and each other `y_j` ([`crate::pebble::Game::span`]): each of those with `x` is
    /// tight (`x` brings its two bars to them), they share `x` and `y₁`, and the union of
    /// tight sets sharing two points is tight.
    fn pebble_certificate(&self, sub: &Subsystem<F>) -> Option<Certificate> {
        if !self.ctx.pebble {
            return None;
        }
        let bars = crate::rigid::bar_framework(self.ctx, sub)?;
        let n = sub.entities.len();
        if n < 4 || bars.len() != 2 * n - 3 {
            return None;
        }
        let mut game = Game::new(n);
        let mut neighbours = vec![Vec::new(); n];
        for (i, &(u, v)) in bars.iter().enumerate() {
            if !game.add(u, v, i) {
                return None;
            }
            neighbours[u].push(v);
            neighbours[v].push(u);
        }
        let (mut size, mut count) = (vec![n; n], vec![0; n]);
        let mut mark = vec![u32::MAX; n];
        for (x, around) in neighbours.iter().enumerate() {
            let members = part(&mut game, x, around, &mut mark, x as u32)?;
            size[x] = members.len();
            if members.len() < n {
                for v in members {
                    count[v] += 1;
                }
            }
        }
        Some(Certificate::new(bars, game, neighbours, size, count))
    }

    /// The certificate of `msub` — a cluster `M` of `sub` without one bar, with its bars
    /// (`in_sub`: their indices in `sub`'s groups) — from `sub`'s certificate `parent`, where
    /// that is cheaper than [`Decomposer::pebble_certificate`] afresh; `None` otherwise, and
    /// where `msub` is not such a sub-framework.
    ///
    /// Why it is the same certificate: the `2|M| − 3` bars of `msub` are bars of `sub`, which is
    /// (2,3)-sparse, so `M` is tight in `sub` and spans no other bar of it: `msub` is the
    /// sub-framework induced on `M`, its game is `sub`'s restricted to it ([`Game::restrict`]),
    /// and its tight sets are those of `sub` inside `M`. A point `x` of `M` whose neighbours all
    /// lie in `M` keeps its part `U_x`: the smallest tight sets holding two of its neighbours
    /// lie in the tight `M`, so they are the same in both; `U_x` is proper in `msub` when it is
    /// smaller than `M`. Only the parts of the other points — outside `M`, or in it with a
    /// neighbour outside — are spanned again: in `sub`, to take them out of the counts, and in
    /// `msub`, to put the new ones in. On a peeling chain that is a few points a level, where
    /// the certificate afresh spans every point.
    fn sub_certificate(
        &self,
        parent: &mut Certificate,
        sub: &Subsystem<F>,
        msub: &Subsystem<F>,
        in_sub: &[usize],
    ) -> Option<Certificate> {
        let n = parent.size.len();
        let k = msub.entities.len();
        let bars = crate::rigid::bar_framework(self.ctx, msub)?;
        if k < 4 || k >= n || bars.len() != 2 * k - 3 || in_sub.len() != bars.len() {
            return None;
        }
        // The new number of each point of `sub` in `msub`, and the old of each point of `msub`.
        let position: HashMap<EntityIdx, usize> =
            sub.entities.iter().enumerate().map(|(i, e)| (*e, i)).collect();
        let mut vertex: Vec<Option<usize>> = vec![None; n];
        let mut old: Vec<usize> = Vec::with_capacity(k);
        for (y, e) in msub.entities.iter().enumerate() {
            let x = *position.get(e)?;
            if vertex[x].replace(y).is_some() {
                return None;
            }
            old.push(x);
        }
        // Each bar of `msub` is the bar of `sub` it is said to be.
        let mut bar: Vec<Option<usize>> = vec![None; parent.bars.len()];
        for (j, (&(a, b), &g)) in bars.iter().zip(in_sub).enumerate() {
            if *parent.bars.get(g)? != (old[a], old[b]) || bar[g].replace(j).is_some() {
                return None;
            }
        }
        // The points whose parts change: outside `M`, or in it with a neighbour outside.
        let changed: Vec<usize> = (0..n)
            .filter(|&x| {
                vertex[x].is_none() || parent.neighbours[x].iter().any(|y| vertex[*y].is_none())
            })
            .collect();
        if 4 * changed.len() > k {
            return None;
        }
        let mut count = parent.count.clone();
        let mut mark = vec![u32::MAX; n];
        for (stamp, &x) in changed.iter().enumerate() {
            if parent.size[x] < n {
                let members =
                    part(&mut parent.game, x, &parent.neighbours[x], &mut mark, stamp as u32)?;
                for v in members {
                    count[v] = count[v].checked_sub(1)?;
                }
            }
        }
        let mut again = vec![false; k];
        for &x in &changed {
            if let Some(y) = vertex[x] {
                again[y] = true;
            }
        }
        // The parts kept; those that are the whole of `M` are proper no more.
        let mut size = vec![k; k];
        let mut whole = 0;
        for (y, &x) in old.iter().enumerate() {
            if !again[y] {
                if parent.size[x] > k {
                    return None;
                }
                size[y] = parent.size[x];
                whole += usize::from(size[y] == k);
            }
        }
        let mut count: Vec<usize> =
            old.iter().map(|&x| count[x].checked_sub(whole)).collect::<Option<_>>()?;
        let mut game = parent.game.restrict(&vertex, &bar);
        let mut neighbours = vec![Vec::new(); k];
        for &(a, b) in &bars {
            neighbours[a].push(b);
            neighbours[b].push(a);
        }
        let mut mark = vec![u32::MAX; k];
        for y in (0..k).filter(|&y| again[y]) {
            let members = part(&mut game, y, &neighbours[y], &mut mark, y as u32)?;
            size[y] = members.len();
            if members.len() < k {
                for v in members {
                    count[v] += 1;
                }
            }
        }
        Some(Certificate::new(bars, game, neighbours, size, count))
    }

    /// Replaces the non-trivial subsystems by their boundaries, decomposes the reduced system
    /// and the subsystems, and assembles the node of `sub`.
    /// `removed` is the group removed from `sub` (with its index) to leave `without`;
    /// `certificate` is `sub`'s, from which those of the subsystems are derived.
    fn split(
        &mut self,
        sub: &Subsystem<F>,
        without: &Subsystem<F>,
        (gi, removed): (usize, &Group<F>),
        nontrivial: Vec<RawCluster>,
        mut certificate: Option<&mut Certificate>,
    ) -> Option<Node> {
        let mut used_groups = vec![false; without.groups.len()];
        let mut internal: Vec<EntityIdx> = Vec::new();
        let mut replacements: Vec<Replacement> = Vec::new();
        let mut subtrees: Vec<Node> = Vec::new();
        let mut boundary_groups: Vec<Group<F>> = Vec::new();
        let degrees = Degrees::new(without);
        let last = nontrivial.len().saturating_sub(1);
        for (i, m) in nontrivial.into_iter().enumerate() {
            let groups: Vec<usize> =
                m.groups.iter().copied().filter(|g| !used_groups[*g]).collect();
            let on_boundary = degrees.boundary(without, removed, &m);
            let boundary: Vec<EntityIdx> =
                m.entities.iter().zip(on_boundary).filter(|(_, b)| *b).map(|(e, _)| *e).collect();
            let Some(relations) = self.boundary(&boundary) else { continue };
            for g in &groups {
                used_groups[*g] = true;
            }
            internal.extend(m.entities.iter().copied().filter(|e| !boundary.contains(e)));
            let msub = Subsystem {
                entities: m.entities.clone(),
                groups: groups.iter().map(|g| without.groups[*g].clone()).collect(),
            };
            let derived = certificate.as_deref_mut().and_then(|c| {
                let in_sub: Vec<usize> = groups.iter().map(|&g| g + usize::from(g >= gi)).collect();
                let derived = self.sub_certificate(c, sub, &msub, &in_sub);
                if i == last {
                    // `sub`'s game is not asked again: a subsystem is decomposed, so the split
                    // succeeds and `sub` tries no further removal. (Memory along the chain.)
                    c.release();
                }
                derived
            });
            subtrees.push(self.wdec(&msub, derived));
            replacements.push(Replacement {
                virtual_labels: relations.iter().map(|g| g.label).collect(),
                entities: m.entities.clone(),
                labels: msub.groups.iter().map(|g| g.label).collect(),
            });
            boundary_groups.extend(relations);
        }
        if replacements.is_empty() {
            return None;
        }
        let internal: HashSet<EntityIdx> = internal.into_iter().collect();
        let mut reduced = Subsystem {
            entities: sub.entities.iter().copied().filter(|e| !internal.contains(e)).collect(),
            groups: Vec::new(),
        };
        for (g, group) in without.groups.iter().enumerate() {
            if !used_groups[g] {
                reduced.groups.push(group.clone());
            }
        }
        reduced.groups.extend(boundary_groups);
        reduced.groups.push(removed.clone());
        let reduced_tree = self.wdec(&reduced, None);
        // Map the reduced tree back: the root is `sub` itself; its descendants are expanded
        // (boundaries replaced by their subsystems) and kept when rigid in `sub`.
        let mut root = Self::leaf(sub);
        let mut nodes: Vec<Node> = Vec::new();
        // The replacement each boundary relation stands in (the first, as they are unique).
        let mut of_virtual: HashMap<Label, &Replacement> = HashMap::new();
        for r in &replacements {
            for l in &r.virtual_labels {
                of_virtual.entry(*l).or_insert(r);
            }
        }
        for child in reduced_tree.children {
            nodes.extend(self.expand(child, &of_virtual, sub));
        }
        nodes.extend(subtrees);
        // A node as large as `sub` is `sub` itself: keep its children only.
        let mut flat: Vec<Node> = Vec::new();
        for n in nodes {
            if n.entities.len() >= sub.entities.len() {
                flat.extend(n.children);
            } else {
                flat.push(n);
            }
        }
        root.children = nest(flat);
        Some(root)
    }

    /// Expands a node of a reduced system; returns the expanded node, or its expanded children
    /// when it is not rigid once expanded.
    fn expand(
        &mut self,
        node: Node,
        of_virtual: &HashMap<Label, &Replacement>,
        sub: &Subsystem<F>,
    ) -> Vec<Node> {
        let mut entities = node.entities.clone();
        let mut has_entity: HashSet<EntityIdx> = entities.iter().copied().collect();
        let mut labels: Vec<Label> = Vec::new();
        let mut has_label: HashSet<Label> = HashSet::new();
        for l in &node.labels {
            if let Some(r) = of_virtual.get(l) {
                for e in &r.entities {
                    if has_entity.insert(*e) {
                        entities.push(*e);
                    }
                }
                for m in &r.labels {
                    if has_label.insert(*m) {
                        labels.push(*m);
                    }
                }
            } else if has_label.insert(*l) {
                labels.push(*l);
            }
        }
        entities.sort_unstable();
        let children: Vec<Node> =
            node.children.into_iter().flat_map(|c| self.expand(c, of_virtual, sub)).collect();
        let groups: Vec<Group<F>> =
            sub.groups.iter().filter(|g| has_label.contains(&g.label)).cloned().collect();
        let candidate = Subsystem { entities: entities.clone(), groups };
        self.stats.mrs_computations += 1;
        self.stats.searched_entities += candidate.entities.len();
        let found = clusters(self.ctx, &candidate);
        if found.iter().any(|c| c.entities == entities) {
            vec![Node { entities, labels, children }]
        } else {
            children
        }
    }

    /// An independent set of relations among `boundary` as rigid as the boundary is in a rigid
    /// subsystem (§3.2), or `None` when the available relations cannot express it.
    fn boundary(&mut self, boundary: &[EntityIdx]) -> Option<Vec<Group<F>>> {
        let ctx = self.ctx;
        let system = ctx.system;
        let layout = ctx.layout;
        let cols: Vec<usize> = boundary.iter().flat_map(|e| layout.columns(*e)).collect();
        // Target: DOF of the boundary entities minus their degree of rigidity.
        let k = ctx.generators.len();
        let mut t = Echelon::new(k, ctx.options.clone());
        for &c in &cols {
            t.insert(ctx.t_row(c));
        }
        let dof: usize = boundary.iter().map(|e| system.entity_dof(*e)).sum();
        let target = dof.saturating_sub(t.rank());
        let mut e = Echelon::new(layout.ncols(), ctx.options.clone());
        for b in boundary {
            for r in ctx.internal.get(b).into_iter().flatten() {
                e.insert(r.clone());
            }
        }
        let base = e.rank();
        let mut out = Vec::new();
        'pairs: for (i, &a) in boundary.iter().enumerate() {
            for &b in &boundary[i + 1..] {
                if e.rank() - base == target {
                    break 'pairs;
                }
                for signature in relations(system, a, b) {
                    let Some(row) = relation_row(system, layout, signature, &self.witness) else {
                        continue;
                    };
                    if e.insert(row.clone()).is_independent() {
                        out.push(Group {
                            label: Label::Virtual(self.next_virtual),
                            entities: vec![a, b],
                            rows: vec![row],
                            absolute: false,
                        });
                        self.next_virtual += 1;
                    }
                }
            }
        }
        (e.rank() - base == target).then_some(out)
    }
}

/// The metric relations that can stand between two entities in a boundary: the angles and
/// distances the constraint table has between their classes.
fn relations(system: &System, a: EntityIdx, b: EntityIdx) -> Vec<Signature> {
    [ConstraintKind::Angle, ConstraintKind::Distance]
        .into_iter()
        .filter_map(|kind| system.relation(kind, &[a, b]))
        .collect()
}

/// What [`Decomposer::pebble_certificate`] finds, with what it takes to derive the
/// certificates of sub-frameworks ([`Decomposer::sub_certificate`]).
struct Certificate {
    /// The bars, group by group, as positions in the subsystem's entities.
    bars: Vec<(usize, usize)>,
    /// The intersection of the proper parts `U_x` (everything when there is none): a removal
    /// is fruitless exactly when both ends of its bar are in it.
    common: Vec<bool>,
    /// Whether there is no proper part: the subsystem is a leaf.
    leaf: bool,
    /// The game with every bar accepted.
    game: Game,
    /// The neighbours of each point, bar by bar.
    neighbours: Vec<Vec<usize>>,
    /// `|U_x|` for each point `x` (a part is proper when smaller than the whole).
    size: Vec<usize>,
    /// How many proper parts hold each point.
    count: Vec<usize>,
}

impl Certificate {
    fn new(
        bars: Vec<(usize, usize)>,
        game: Game,
        neighbours: Vec<Vec<usize>>,
        size: Vec<usize>,
        count: Vec<usize>,
    ) -> Certificate {
        let n = size.len();
        let proper = size.iter().filter(|s| **s < n).count();
        let common = count.iter().map(|c| *c == proper).collect();
        Certificate { bars, common, leaf: proper == 0, game, neighbours, size, count }
    }

    /// Drops what only derivations need (then [`Decomposer::sub_certificate`] declines).
    fn release(&mut self) {
        self.game = Game::new(0);
        self.neighbours = Vec::new();
        self.size = Vec::new();
        self.count = Vec::new();
    }

    /// The clusters of `without`, the framework without its bar `gi`: the components of the
    /// certificate's game without that bar, which is the game of `without`
    /// ([`Game::restrict`]; its bars are independent) — so no game is played afresh.
    /// `None` once released.
    fn clusters_without<F>(&self, without: &Subsystem<F>, gi: usize) -> Option<Vec<RawCluster>> {
        if self.size.is_empty() || gi >= self.bars.len() {
            return None;
        }
        let mut game = self.game.clone();
        let (u, v) = self.bars[gi];
        game.remove(u, v);
        let mut bars = self.bars.clone();
        bars.remove(gi);
        let components = game.components(&bars);
        Some(bar_clusters(without, &bars, &components))
    }
}

/// `U_x`, the smallest rigid part holding the point `x` and its neighbours `around`, in a
/// tight framework's game (see [`Decomposer::pebble_certificate`]): its points, `x` and the
/// first neighbour first, all of them once it is the whole. `mark` holds a stamp per point,
/// `stamp` one it does not hold yet. `None` when `x` has no neighbour or the game is not tight.
fn part(
    game: &mut Game,
    x: usize,
    around: &[usize],
    mark: &mut [u32],
    stamp: u32,
) -> Option<Vec<usize>> {
    let n = mark.len();
    let (&first, rest) = around.split_first()?;
    mark[x] = stamp;
    mark[first] = stamp;
    let mut members = vec![x, first];
    for &y in rest {
        if members.len() == n {
            // (The whole already: the usual case, after one span.)
            break;
        }
        for v in game.span(first, y)? {
            if mark[v] != stamp {
                mark[v] = stamp;
                members.push(v);
            }
        }
    }
    Some(members)
}

/// How many groups of a subsystem bind each entity: what tells the boundary of a cluster of
/// it in time linear in the cluster's groups.
struct Degrees(HashMap<EntityIdx, usize>);

impl Degrees {
    fn new<F>(sub: &Subsystem<F>) -> Degrees {
        let mut degree: HashMap<EntityIdx, usize> = HashMap::new();
        for group in &sub.groups {
            for e in &group.entities {
                *degree.entry(*e).or_default() += 1;
            }
        }
        Degrees(degree)
    }

    /// For each entity of `m` (a cluster of `sub`, whose degrees these are), whether it is on
    /// `m`'s boundary: bound by a group outside `m` (the removed constraint counts) — that is,
    /// by more groups of `sub` than of `m`.
    fn boundary<F>(&self, sub: &Subsystem<F>, removed: &Group<F>, m: &RawCluster) -> Vec<bool> {
        let mut inside: HashMap<EntityIdx, usize> = HashMap::new();
        for &g in &m.groups {
            for e in &sub.groups[g].entities {
                *inside.entry(*e).or_default() += 1;
            }
        }
        m.entities
            .iter()
            .map(|e| {
                removed.entities.contains(e)
                    || self.0.get(e).copied().unwrap_or(0) > inside.get(e).copied().unwrap_or(0)
            })
            .collect()
    }
}

/// Arranges nodes into a forest by containment of their entity sets; nodes with the same
/// entities are merged. The nodes are flattened, merged, and placed largest first (ties in
/// the order flattened), each under the first node already placed at its level that strictly
/// contains it, descending while one does — so that each goes under the smallest container
/// already placed.
///
/// Containment is tested on bit sets over the range of the entities, a few words each, and
/// the forest is built on indices: on a long peeling chain the nodes below are placed again
/// at every level, and each placement descends the chain.
fn nest(nodes: Vec<Node>) -> Vec<Node> {
    let mut all: Vec<Node> = Vec::new();
    fn flatten(n: Node, out: &mut Vec<Node>) {
        let Node { entities, labels, children } = n;
        out.push(Node { entities, labels, children: Vec::new() });
        for c in children {
            flatten(c, out);
        }
    }
    for n in nodes {
        flatten(n, &mut all);
    }
    let mut merged: Vec<Node> = Vec::new();
    // Merged nodes by a fingerprint of their entities (equal sets then compared in full).
    let mut by_fingerprint: HashMap<u64, Vec<usize>> = HashMap::new();
    for n in all {
        let candidates = by_fingerprint.entry(fingerprint(&n.entities)).or_default();
        if let Some(&k) = candidates.iter().find(|k| merged[**k].entities == n.entities) {
            let m = &mut merged[k];
            for l in n.labels {
                if !m.labels.contains(&l) {
                    m.labels.push(l);
                }
            }
        } else {
            candidates.push(merged.len());
            merged.push(n);
        }
    }
    merged.sort_by_key(|n| std::cmp::Reverse(n.entities.len()));
    let sets = BitSets::new(&merged);
    let contains = |parent: usize, child: usize| {
        merged[parent].entities.len() > merged[child].entities.len()
            && sets.is_subset(child, parent)
    };
    let mut roots: Vec<usize> = Vec::new();
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); merged.len()];
    for i in 0..merged.len() {
        let mut parent: Option<usize> = None;
        loop {
            let level = parent.map_or(&roots, |p| &children[p]);
            match level.iter().copied().find(|&p| contains(p, i)) {
                Some(p) => parent = Some(p),
                None => break,
            }
        }
        match parent {
            Some(p) => children[p].push(i),
            None => roots.push(i),
        }
    }
    fn build(i: usize, merged: &mut [Node], children: &[Vec<usize>]) -> Node {
        let mut node = std::mem::take(&mut merged[i]);
        node.children = children[i].iter().map(|&c| build(c, merged, children)).collect();
        node
    }
    roots.iter().map(|&r| build(r, &mut merged, &children)).collect()
}

/// A hash of a list of entities, cheaper than the standard one on long lists.
fn fingerprint(entities: &[EntityIdx]) -> u64 {
    entities.iter().fold(entities.len() as u64, |h, e| {
        (h.rotate_left(26) ^ u64::from(e.0)).wrapping_mul(0x9e37_79b9_7f4a_7c15)
    })
}

/// The entity sets of nodes as bit sets over the range the entities span.
struct BitSets {
    words: usize,
    bits: Vec<u64>,
}

impl BitSets {
    fn new(nodes: &[Node]) -> BitSets {
        let entities = || nodes.iter().flat_map(|n| &n.entities).map(|e| e.0);
        let low = entities().min().unwrap_or(0);
        let high = entities().max().unwrap_or(0);
        let words = (high - low) as usize / 64 + 1;
        let mut bits = vec![0u64; nodes.len() * words];
        for (set, n) in bits.chunks_exact_mut(words).zip(nodes) {
            for e in &n.entities {
                let k = (e.0 - low) as usize;
                set[k / 64] |= 1 << (k % 64);
            }
        }
        BitSets { words, bits }
    }

    fn set(&self, i: usize) -> &[u64] {
        &self.bits[i * self.words..(i + 1) * self.words]
    }

    /// Whether the entities of node `small` are among those of node `big`.
    fn is_subset(&self, small: usize, big: usize) -> bool {
        self.set(small).iter().zip(self.set(big)).all(|(s, b)| s & !b == 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clusters::tests::with_context;

    /// The certificates derived along peeling chains are those computed afresh, and the
    /// clusters found with the certificate's game without a bar are the cluster search's: on
    /// random Laman frameworks, for every bar removed from the whole and every cluster of what
    /// is left, then down a chain of such derivations.
    #[test]
    fn derived_certificates_are_the_fresh_ones() {
        let mut derived = 0;
        for seed in 1..=10u64 {
            let system = gcs_model::generate::laman(14 + 2 * seed as usize, seed);
            derived += with_context(&system, |ctx, whole| {
                ctx.pebble = true;
                let d = Decomposer::new(ctx, Vec::new(), RemovalOrder::default());
                let mut derived = 0;
                let mut sub = whole.clone();
                let mut certificate = d.pebble_certificate(&sub).unwrap();
                for depth in 0.. {
                    let mut next = None;
                    for gi in 0..sub.groups.len() {
                        let mut without = sub.clone();
                        without.groups.remove(gi);
                        let found = certificate.clusters_without(&without, gi).unwrap();
                        assert_eq!(found, clusters(ctx, &without), "seed {seed}, depth {depth}");
                        for m in found.iter().filter(|m| m.entities.len() < sub.entities.len()) {
                            let msub = Subsystem {
                                entities: m.entities.clone(),
                                groups: m
                                    .groups
                                    .iter()
                                    .map(|g| without.groups[*g].clone())
                                    .collect(),
                            };
                            let in_sub: Vec<usize> =
                                m.groups.iter().map(|&g| g + usize::from(g >= gi)).collect();
                            let Some(c) = d.sub_certificate(&mut certificate, &sub, &msub, &in_sub)
                            else {
                                continue;
                            };
                            let fresh = d.pebble_certificate(&msub).unwrap();
                            assert_eq!(c.bars, fresh.bars, "seed {seed}, depth {depth}");
                            assert_eq!(c.size, fresh.size, "seed {seed}, depth {depth}");
                            assert_eq!(c.count, fresh.count, "seed {seed}, depth {depth}");
                            assert_eq!(
                                (c.common.clone(), c.leaf),
                                (fresh.common, fresh.leaf),
                                "seed {seed}, depth {depth}"
                            );
                            derived += 1;
                            if next.as_ref().is_none_or(|(s, _): &(Subsystem<_>, _)| {
                                s.entities.len() < msub.entities.len()
                            }) {
                                next = Some((msub, c));
                            }
                        }
                    }
                    let Some((s, c)) = next else { break };
                    (sub, certificate) = (s, c);
                }
                derived
            });
        }
        assert!(derived > 200, "{derived}");
    }

    /// Nesting places each node under the smallest container placed before it and merges
    /// equal sets, whatever the ranges of the entities.
    #[test]
    fn nest_places_nodes_under_their_containers() {
        let node = |entities: &[u32], labels: &[usize]| Node {
            entities: entities.iter().map(|e| EntityIdx(*e)).collect(),
            labels: labels.iter().map(|l| Label::Virtual(*l)).collect(),
            children: Vec::new(),
        };
        let mut outer = node(&[0, 1, 2, 3, 70, 200], &[0]);
        outer.children = vec![node(&[1, 2, 3], &[1]), node(&[2, 3, 70, 200], &[2])];
        let forest = nest(vec![
            outer,
            node(&[2, 3, 70], &[3]),
            node(&[1, 2, 3], &[4]),
            node(&[9, 10], &[5]),
        ]);
        let shape = |n: &Node| -> (Vec<u32>, Vec<Label>, usize) {
            (n.entities.iter().map(|e| e.0).collect(), n.labels.clone(), n.children.len())
        };
        assert_eq!(forest.len(), 2);
        assert_eq!(shape(&forest[0]), (vec![0, 1, 2, 3, 70, 200], vec![Label::Virtual(0)], 2));
        assert_eq!(shape(&forest[1]), (vec![9, 10], vec![Label::Virtual(5)], 0));
        let inner = &forest[0].children;
        assert_eq!(shape(&inner[0]), (vec![2, 3, 70, 200], vec![Label::Virtual(2)], 1));
        assert_eq!(shape(&inner[0].children[0]), (vec![2, 3, 70], vec![Label::Virtual(3)], 0));
        assert_eq!(
            shape(&inner[1]),
            (vec![1, 2, 3], vec![Label::Virtual(1), Label::Virtual(4)], 0)
        );
    }
}
