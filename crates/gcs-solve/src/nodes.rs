//! The core's DR-plan: a plane core of points and distances split into rigid bodies, each
//! enumerated on its own and then assembled (the ESM paper §2–3: a node is solved with its
//! children as rigid bodies, and stores its solution as their placements).
//!
//! **The plan.** For a core that is a minimally rigid plane framework (points, distances,
//! `2n − 3` of them, independent by the (2,3) pebble game: Laman's theorem), every distance
//! `e` is tried: the maximal rigid components of the framework without `e` are its rigid
//! bodies (the W-decomposition's step, the witness paper §5, decided combinatorially as the
//! pebble game decides it in 2D). The bodies of at least three points become the node's
//! children, decomposed in turn; the points on none stay free; the distances between bodies
//! (and `e`) are the node's own constraints. The distance kept out is the one that leaves the
//! fewest unknowns at the node (four per body beyond the first, two per free point). A core
//! whose frameworks without any one distance have no body of three points (K3,3) is one node.
//!
//! **Candidates.** A leaf's candidates are its realizations ([`alternatives::realizations`]:
//! held by one of its distances); a node's are the placements of its children's chosen
//! realizations as rigid bodies ([`alternatives::assemble`]) — so a node's homotopy is small
//! (two K3,3 joined by three distances: 70 paths per K3,3 and 6 for the assembly, where the
//! whole has 184,756). A node whose children are all at the drawing's realization has the
//! solve's own configuration as its candidate 0; otherwise its candidates are ordered by how
//! little they move the solved configuration.

use gcs_jacobian::{Equations, Layout};
use gcs_model::{ConstraintIdx, ConstraintKind, EntityIdx, System};

use crate::alternatives::{self, PathCounts, Shortfall};

/// The most points a core may have to be decomposed (every distance is tried).
const MAX_POINTS: usize = 64;

/// The most node homotopies one enumeration runs (each combination of the children's
/// candidates is one).
pub(crate) const MAX_ASSEMBLIES: usize = 4096;

/// A node of the core's DR-plan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Node {
    /// Its points (its children's too), in file order.
    pub entities: Vec<EntityIdx>,
    /// Its own constraints (between its children and on its free points; a leaf: all of
    /// them), in file order.
    pub constraints: Vec<ConstraintIdx>,
    /// Its children, as indices of earlier nodes (empty for a leaf).
    pub children: Vec<usize>,
    /// The groups the user declared ([`System::groups`], by index) whose points it is.
    pub groups: Vec<usize>,
}

impl Node {
    /// Whether the node is one distance between two points: its one realization (up to
    /// moving it) is all it has.
    pub fn single_distance(&self, system: &System) -> bool {
        match self.constraints.as_slice() {
            [c] => {
                system.constraint(*c).kind == ConstraintKind::Distance
                    && self.entities.len() == 2
                    && self.children.is_empty()
            }
            _ => false,
        }
    }
}

/// The core's DR-plan, children before parents, the whole core last (see the module
/// documentation); one node when the core does not decompose.
pub fn plan(system: &System, core: &[ConstraintIdx]) -> Vec<Node> {
    let mut entities: Vec<EntityIdx> =
        core.iter().flat_map(|&c| system.constraint_base_entities(c)).collect();
    entities.sort();
    entities.dedup();
    let mut constraints = core.to_vec();
    constraints.sort();
    let whole = vec![Node {
        entities: entities.clone(),
        constraints,
        children: Vec::new(),
        groups: groups_of(system, &entities),
    }];
    let Some(bars) = framework(system, core, &entities) else { return whole };
    let n = entities.len();
    if n > MAX_POINTS || bars.len() + 3 != 2 * n {
        return whole;
    }
    let pairs: Vec<(usize, usize)> = bars.iter().map(|b| (b.0, b.1)).collect();
    if gcs_decompose::pebble_game(n, &pairs).rank != bars.len() {
        return whole;
    }
    // The groups of points of the core: each kept whole while it is a proper part of a node.
    let groups: Vec<Vec<usize>> = (system.groups().iter())
        .filter_map(|g| {
            let mut vertices: Vec<usize> =
                g.entities.iter().map(|e| entities.binary_search(e).ok()).collect::<Option<_>>()?;
            vertices.sort_unstable();
            (vertices.len() >= 3).then_some(vertices)
        })
        .collect();
    let mut nodes = Vec::new();
    decompose((0..n).collect(), bars, &groups, &mut nodes);
    nodes
        .into_iter()
        .map(|(vertices, mut constraints, children)| {
            constraints.sort();
            let entities: Vec<EntityIdx> = vertices.iter().map(|&v| entities[v]).collect();
            let groups = groups_of(system, &entities);
            Node { entities, constraints, children, groups }
        })
        .collect()
}

/// The groups whose entities are exactly `entities` (ascending).
fn groups_of(system: &System, entities: &[EntityIdx]) -> Vec<usize> {
    (system.groups().iter().enumerate())
        .filter(|(_, g)| {
            g.entities.len() == entities.len()
                && g.entities.iter().all(|e| entities.binary_search(e).is_ok())
        })
        .map(|(k, _)| k)
        .collect()
}

/// The distances of a core of points and point-to-point distances (positive), as bars
/// between the indices of `points`; `None` for any other core.
fn framework(
    system: &System,
    core: &[ConstraintIdx],
    points: &[EntityIdx],
) -> Option<Vec<(usize, usize, ConstraintIdx)>> {
    if system.dim() != gcs_model::Dim::Two || core.is_empty() {
        return None;
    }
    if points.iter().any(|&p| system.entity(p).kind() != gcs_model::EntityKind::Point) {
        return None;
    }
    core.iter()
        .map(|&c| {
            let constraint = system.constraint(c);
            let positive = constraint
                .value
                .as_ref()
                .is_some_and(|v| num_traits::ToPrimitive::to_f64(v).is_some_and(|v| v > 0.0));
            match constraint.signature.metric() {
                Some(gcs_model::Metric::DistancePointPoint(a, b))
                    if constraint.kind == ConstraintKind::Distance && positive && a != b =>
                {
                    Some((points.binary_search(&a).ok()?, points.binary_search(&b).ok()?, c))
                }
                _ => None,
            }
        })
        .collect()
}

/// A node as vertices, its own constraints and its children.
type Raw = (Vec<usize>, Vec<ConstraintIdx>, Vec<usize>);

/// Decomposes the rigid framework on `vertices` (ascending) with `bars`, pushing its nodes
/// (children first); returns its own index. A group (ascending vertices) that is a proper rigid
/// part of the framework is kept whole: no distance inside it is the one left out, so it lies
/// in one rigid body of every split, each smaller than the last, until it is one.
fn decompose(
    vertices: Vec<usize>,
    bars: Vec<(usize, usize, ConstraintIdx)>,
    groups: &[Vec<usize>],
    out: &mut Vec<Raw>,
) -> usize {
    let local = |v: usize| vertices.binary_search(&v).unwrap_or(usize::MAX);
    let inside = |group: &[usize], b: &(usize, usize, ConstraintIdx)| {
        group.binary_search(&b.0).is_ok() && group.binary_search(&b.1).is_ok()
    };
    let kept: Vec<&Vec<usize>> = (groups.iter())
        .filter(|g| g.len() < vertices.len() && g.iter().all(|v| vertices.binary_search(v).is_ok()))
        .filter(|g| {
            let own: Vec<(usize, usize)> = (bars.iter())
                .filter(|b| inside(g, b))
                .map(|b| (g.binary_search(&b.0).unwrap_or(0), g.binary_search(&b.1).unwrap_or(0)))
                .collect();
            gcs_decompose::pebble_game(g.len(), &own).rank + 3 == 2 * g.len()
        })
        .collect();
    let mut best: Option<(usize, Vec<Vec<usize>>)> = None;
    if vertices.len() > 3 {
        for skip in 0..bars.len() {
            if kept.iter().any(|g| inside(g, &bars[skip])) {
                continue;
            }
            let rest: Vec<(usize, usize)> = (bars.iter().enumerate())
                .filter(|(i, _)| *i != skip)
                .map(|(_, b)| (local(b.0), local(b.1)))
                .collect();
            let report = gcs_decompose::pebble_game(vertices.len(), &rest);
            let bodies: Vec<Vec<usize>> =
                report.components.into_iter().filter(|c| c.len() >= 3).collect();
            if bodies.is_empty() || bodies.iter().any(|b| b.len() == vertices.len()) {
                continue;
            }
            let mut covered = vec![false; vertices.len()];
            for &v in bodies.iter().flatten() {
                covered[v] = true;
            }
            let free = covered.iter().filter(|c| !**c).count();
            let unknowns = 4 * (bodies.len() - 1) + 2 * free;
            if best.as_ref().is_none_or(|(u, _)| unknowns < *u) {
                best = Some((unknowns, bodies));
            }
        }
    }
    let Some((_, mut bodies)) = best else {
        let constraints = bars.iter().map(|b| b.2).collect();
        out.push((vertices, constraints, Vec::new()));
        return out.len() - 1;
    };
    // The largest body first: the reference of the node's assembly, and the outermost loop of
    // the enumeration.
    bodies.sort_by_key(|b| std::cmp::Reverse(b.len()));
    let mut children = Vec::new();
    let mut inside = vec![false; bars.len()];
    for body in &bodies {
        let global: Vec<usize> = body.iter().map(|&v| vertices[v]).collect();
        let own: Vec<(usize, usize, ConstraintIdx)> = (bars.iter().enumerate())
            .filter(|(_, b)| {
                global.binary_search(&b.0).is_ok() && global.binary_search(&b.1).is_ok()
            })
            .map(|(i, b)| {
                inside[i] = true;
                *b
            })
            .collect();
        children.push(decompose(global, own, groups, out));
    }
    let constraints = bars.iter().zip(&inside).filter(|(_, i)| !**i).map(|(b, _)| b.2).collect();
    out.push((vertices, constraints, children));
    out.len() - 1
}

/// A node's candidates given its children's configurations.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Candidates {
    /// Its homotopy's paths, when it was enumerated.
    pub counts: Option<PathCounts>,
    /// Each candidate's record (the ESM paper §3: a node's solution is stored as the
    /// placements of its children, not as positions): for a leaf, its configuration, whole
    /// (the solved configuration outside the leaf); for a node with children (`placed`), a
    /// rotation and a translation per child after the first and the coordinates of its free
    /// points ([`alternatives::place`] computes the positions, [`Enumerator::config`]).
    pub list: Vec<Vec<f64>>,
    /// Whether `list` holds placements.
    pub placed: bool,
    /// Whether `list` is every real solution (that the orientation conditions allow).
    pub complete: bool,
    /// Why it may not be (empty when `complete`).
    pub shortfall: Vec<Shortfall>,
    /// Whether `list[0]` is the solved configuration (the drawing's candidate).
    pub drawn_first: bool,
}

/// The enumeration of a core's DR-plan at a solved configuration.
pub(crate) struct Enumerator<'a> {
    pub system: &'a System,
    pub layout: &'a Layout,
    pub equations: &'a Equations<'a>,
    pub nodes: &'a [Node],
    /// The solved configuration.
    pub x: &'a [f64],
    /// The model's size (what "the solved configuration" is compared at).
    pub scale: f64,
    pub max_paths: usize,
    /// The solve's relative tolerance: what a real candidate must satisfy its constraints to
    /// ([`crate::SolveOptions::tolerance`]).
    pub tolerance: f64,
    /// Homotopies left to run.
    pub budget: std::cell::Cell<usize>,
    /// The budget the current enumeration or search started with (what a node the budget did
    /// not reach reports).
    budget_size: std::cell::Cell<usize>,
    /// Each node's candidates, once computed for its children's choices (the choices of the
    /// nodes of its subtree below it, which come just before it in the plan).
    known: std::cell::RefCell<std::collections::HashMap<(usize, Choices), Candidates>>,
    /// The first node of each node's subtree.
    first: Vec<usize>,
    /// The core's wedges: three points `a, b, c` with distances `a–b` and `a–c` — whose turns
    /// say the chirality of a candidate.
    wedges: Vec<[EntityIdx; 3]>,
    /// The orientation conditions on the core's points: a node's candidates are those where
    /// each condition on its points holds.
    pub orientations: Vec<&'a gcs_model::Orientation>,
    /// For the autosolve's search ([`Enumerator::search`]): the drawing, whose chirality
    /// orders each node's candidates as they are visited (`None`: in their own order).
    drawing: std::cell::Cell<Option<&'a [f64]>>,
    /// The most paths of a node's homotopy during the search (`max_paths` otherwise).
    path_cap: std::cell::Cell<usize>,
    /// Every homotopy run, and those of earlier solves of the same model at the same solved
    /// core ([`crate::NodeCache`]), when kept: a node whose children's choices are unchanged
    /// is not solved again (each still counts against the budget, so that a solve is the same
    /// with or without them).
    pub(crate) homotopies: Option<&'a std::cell::RefCell<Homotopies>>,
}

/// What a node's homotopy found (its path counts and each real candidate as record and
/// configuration), or why it was not run.
pub(crate) type Found = Result<(PathCounts, Vec<(Vec<f64>, Vec<f64>)>), Shortfall>;

/// The homotopies' results kept across solves ([`crate::NodeCache`]): by node, the choices of
/// the nodes below it (which fix its children's configurations) and the most paths it was
/// allowed.
pub(crate) type Homotopies = std::collections::HashMap<(usize, Choices, usize), Found>;

/// A choice a node does not offer: the node, the candidate asked for, why not.
pub(crate) type Refused = (usize, usize, String);

/// A node's choices: for each node, its candidate.
pub(crate) type Choices = Vec<usize>;

impl<'a> Enumerator<'a> {
    pub(crate) fn new(
        system: &'a System,
        layout: &'a Layout,
        equations: &'a Equations<'a>,
        nodes: &'a [Node],
        x: &'a [f64],
        scale: f64,
        max_paths: usize,
    ) -> Self {
        let budget = std::cell::Cell::new(MAX_ASSEMBLIES);
        let known = Default::default();
        let mut first: Vec<usize> = (0..nodes.len()).collect();
        for (k, node) in nodes.iter().enumerate() {
            first[k] = node.children.iter().map(|&c| first[c]).min().unwrap_or(k).min(k);
        }
        // The wedges of the core's distances.
        let mut adjacent: std::collections::BTreeMap<EntityIdx, Vec<EntityIdx>> =
            Default::default();
        for node in nodes {
            for &c in &node.constraints {
                if let Some(gcs_model::Metric::DistancePointPoint(a, b)) =
                    system.constraint(c).signature.metric()
                {
                    adjacent.entry(a).or_default().push(b);
                    adjacent.entry(b).or_default().push(a);
                }
            }
        }
        let mut wedges = Vec::new();
        for (&a, around) in &adjacent {
            for (i, &b) in around.iter().enumerate() {
                for &c in &around[i + 1..] {
                    wedges.push([a, b, c]);
                }
            }
        }
        Enumerator {
            system,
            layout,
            equations,
            nodes,
            x,
            scale,
            max_paths,
            tolerance: crate::SolveOptions::default().tolerance,
            budget,
            budget_size: std::cell::Cell::new(MAX_ASSEMBLIES),
            known,
            first,
            wedges,
            orientations: Vec::new(),
            drawing: std::cell::Cell::new(None),
            path_cap: std::cell::Cell::new(usize::MAX),
            homotopies: None,
        }
    }

    /// Node `k`'s candidates with its children at `children` (configurations, in the order
    /// of `Node::children`); `own`: they are the drawing's, so the solved configuration is
    /// one of them, and comes first.
    #[cfg(test)]
    pub(crate) fn candidates(&self, k: usize, children: &[&[f64]], own: bool) -> Candidates {
        self.candidates_below(k, None, children, own)
    }

    /// [`Enumerator::candidates`], its homotopy kept in [`Enumerator::homotopies`] under the
    /// choices `below` of the nodes below it, when given.
    fn candidates_below(
        &self,
        k: usize,
        below: Option<&[usize]>,
        children: &[&[f64]],
        own: bool,
    ) -> Candidates {
        let node = &self.nodes[k];
        let (mut candidates, mut configs) = self.unfiltered(k, below, children, own);
        // The orientation conditions on the node's points prune its candidates.
        let on: Vec<&gcs_model::Orientation> = (self.orientations.iter().copied())
            .filter(|o| o.points.iter().all(|p| node.entities.contains(p)))
            .collect();
        if !on.is_empty() {
            let keep: Vec<bool> = (configs.iter())
                .map(|y| on.iter().all(|o| crate::orientation_holds(self.layout, y, o)))
                .collect();
            let mut i = 0;
            candidates.list.retain(|_| (keep[i], i += 1).0);
            let mut i = 0;
            configs.retain(|_| (keep[i], i += 1).0);
            if candidates.drawn_first {
                candidates.drawn_first = configs.first().is_some_and(|y| y == self.x);
            }
        }
        candidates
    }

    /// Node `k`'s children as rigid bodies at `children` (the largest first: the reference of
    /// its assembly) and its free points.
    fn bodies<'c>(
        &self,
        k: usize,
        children: &[&'c [f64]],
    ) -> (Vec<(Vec<EntityIdx>, &'c [f64])>, Vec<EntityIdx>) {
        let node = &self.nodes[k];
        let mut bodies: Vec<(Vec<EntityIdx>, &[f64])> = (node.children.iter())
            .zip(children)
            .map(|(&c, config)| (self.nodes[c].entities.clone(), *config))
            .collect();
        bodies.sort_by_key(|b| std::cmp::Reverse(b.0.len()));
        let free: Vec<EntityIdx> = (node.entities.iter().copied())
            .filter(|e| bodies.iter().all(|b| !b.0.contains(e)))
            .collect();
        (bodies, free)
    }

    /// The configuration of node `k`'s candidate `j` with its children at `children`: a
    /// leaf's is stored; a node's is computed from its placement of its children.
    pub(crate) fn config(
        &self,
        k: usize,
        children: &[&[f64]],
        candidates: &Candidates,
        j: usize,
    ) -> Option<Vec<f64>> {
        let record = candidates.list.get(j)?;
        if !candidates.placed {
            return Some(record.clone());
        }
        let (bodies, free) = self.bodies(k, children);
        alternatives::place(self.layout, &bodies, &free, self.x, record)
    }

    /// [`Enumerator::candidates`] before the orientation conditions, with each candidate's
    /// configuration.
    fn unfiltered(
        &self,
        k: usize,
        below: Option<&[usize]>,
        children: &[&[f64]],
        own: bool,
    ) -> (Candidates, Vec<Vec<f64>>) {
        let node = &self.nodes[k];
        let seed = 0x5eed ^ (k as u64).wrapping_mul(0x9E37_79B9);
        let placed = !node.children.is_empty();
        if node.single_distance(self.system) && own {
            let c = Candidates {
                counts: None,
                list: vec![self.x.to_vec()],
                placed: false,
                complete: true,
                shortfall: Vec::new(),
                drawn_first: true,
            };
            return (c, vec![self.x.to_vec()]);
        }
        let (bodies, free) = self.bodies(k, children);
        // Each candidate as (record, configuration).
        let max_paths = self.max_paths.min(self.path_cap.get());
        let kept = self.homotopies.filter(|_| below.is_some());
        let key = below.filter(|_| kept.is_some()).map(|b| (k, b.to_vec(), max_paths));
        let found: Found = if self.budget.get() == 0 {
            Err(Shortfall::Budget { homotopies: self.budget_size.get() })
        } else if let Some(kept) =
            key.as_ref().zip(kept).and_then(|(key, h)| h.borrow().get(key).cloned())
        {
            self.budget.set(self.budget.get() - 1);
            kept
        } else if !placed {
            self.budget.set(self.budget.get() - 1);
            alternatives::realizations(
                self.system,
                self.layout,
                self.equations,
                &node.constraints,
                self.x,
                (max_paths, self.tolerance),
                seed,
            )
            .map(|(counts, list)| (counts, list.into_iter().map(|y| (y.clone(), y)).collect()))
        } else {
            self.budget.set(self.budget.get() - 1);
            alternatives::assemble(
                (self.system, self.layout, self.equations),
                &bodies,
                &free,
                &node.constraints,
                self.x,
                (max_paths, self.tolerance),
                seed,
            )
            .map(|(counts, list)| {
                let pairs = (list.into_iter())
                    .filter_map(|y| {
                        let config = alternatives::place(self.layout, &bodies, &free, self.x, &y)?;
                        Some((y, config))
                    })
                    .collect();
                (counts, pairs)
            })
        };
        if let (Some(key), Some(h)) = (key, kept)
            && !matches!(found, Err(Shortfall::Budget { .. }))
        {
            h.borrow_mut().entry(key).or_insert_with(|| found.clone());
        }
        // The drawing's candidate: the solved configuration (for a node, its children where
        // they are).
        let drawing = || -> (Vec<f64>, Vec<f64>) {
            let record = if placed {
                alternatives::identity_placement(bodies.len(), free.len())
            } else {
                self.x.to_vec()
            };
            (record, self.x.to_vec())
        };
        let mut shortfall = Vec::new();
        let (counts, mut pairs) = match found {
            Ok((counts, pairs)) => {
                if counts.failed > 0 {
                    shortfall
                        .push(Shortfall::Failed { failed: counts.failed, tracked: counts.paths });
                }
                (Some(counts), pairs)
            }
            Err(why) => {
                shortfall.push(why);
                (None, Vec::new())
            }
        };
        if own {
            let near = pairs.first().is_some_and(|(_, f)| {
                f.iter().zip(self.x).all(|(a, b)| (a - b).abs() <= 1e-7 * self.scale)
            });
            if near {
                pairs[0] = drawing();
            } else {
                pairs.insert(0, drawing());
                if counts.is_some() {
                    shortfall.push(Shortfall::DrawingMissed);
                }
            }
        } else {
            // Autosolve by chirality (the ESM paper §3): the candidates whose turns agree with
            // the solved drawing's first, then by least displacement (the order they come in).
            let wedges: Vec<&[EntityIdx; 3]> = (self.wedges.iter())
                .filter(|w| w.iter().all(|p| node.entities.binary_search(p).is_ok()))
                .collect();
            let turn = |y: &[f64], w: &[EntityIdx; 3]| {
                let at = |p: EntityIdx| {
                    let c = self.layout.columns(p).start;
                    [y[c], y[c + 1]]
                };
                crate::closed::orientation(at(w[0]), at(w[1]), at(w[2])) > 0.0
            };
            let drawn: Vec<bool> = wedges.iter().map(|w| turn(self.x, w)).collect();
            pairs.sort_by_cached_key(|(_, y)| {
                wedges.iter().zip(&drawn).filter(|(w, d)| turn(y, w) != **d).count()
            });
        }
        let (list, configs): (Vec<Vec<f64>>, Vec<Vec<f64>>) = pairs.into_iter().unzip();
        let complete = shortfall.is_empty();
        (Candidates { counts, list, placed, complete, shortfall, drawn_first: own }, configs)
    }

    /// The configuration at the choices `forced` (per node; `None`: candidate 0), with each
    /// node's candidates there and the choices taken; `Err((node, candidate, why))` when a
    /// choice is not offered.
    pub(crate) fn choose(
        &self,
        forced: &[Option<usize>],
    ) -> Result<(Vec<f64>, Vec<Candidates>, Choices), Refused> {
        let mut configs: Vec<Vec<f64>> = Vec::with_capacity(self.nodes.len());
        let mut drawn: Vec<bool> = Vec::with_capacity(self.nodes.len());
        let mut all = Vec::with_capacity(self.nodes.len());
        let mut picks = Vec::with_capacity(self.nodes.len());
        for (k, node) in self.nodes.iter().enumerate() {
            let children: Vec<&[f64]> =
                node.children.iter().map(|&c| configs[c].as_slice()).collect();
            let own = node.children.iter().all(|&c| drawn[c]);
            let candidates = self.known(k, &picks[self.first[k]..k], &children, own);
            let pick = forced.get(k).copied().flatten().unwrap_or(0);
            let Some(config) = self.config(k, &children, &candidates, pick) else {
                let why = match candidates.list.len() {
                    0 => "it has no real candidate at the choices of its children".to_owned(),
                    m => format!("it has {m} real candidate(s), 0–{}", m - 1),
                };
                return Err((k, pick, why));
            };
            configs.push(config);
            drawn.push(candidates.drawn_first && pick == 0);
            all.push(candidates);
            picks.push(pick);
        }
        Ok((configs.pop().unwrap_or_else(|| self.x.to_vec()), all, picks))
    }

    /// Every combination of the nodes' candidates (each node at `forced` where given), at most
    /// `limit`: the whole core's configurations with each node's candidate, and the bounds
    /// that cut the list short (the limit, the budget of homotopies). Depth first, the first
    /// child outermost, so that the limit stops the work too.
    pub(crate) fn all(
        &self,
        forced: &[Option<usize>],
        limit: usize,
    ) -> (Vec<(Vec<f64>, Choices)>, Vec<crate::Bound>) {
        let mut out = Vec::new();
        let mut cut = Vec::new();
        let Some(root) = self.nodes.len().checked_sub(1) else { return (out, cut) };
        self.visit(root, forced, &mut |x, choices, _| {
            if out.len() == limit {
                cut.push(crate::Bound::Solutions(limit));
                return false;
            }
            out.push((x, choices));
            true
        });
        if self.budget.get() == 0 {
            cut.push(crate::Bound::NodeHomotopies);
        }
        (out, cut)
    }

    /// The autosolve's search (the ESM paper §3–4): the combinations of the nodes' candidates
    /// (each node at `forced` where given), depth first — the first child outermost, the
    /// whole core innermost — each node's candidates in the order of their agreement with the
    /// chirality of `drawing` (how many wedges of the node's points turn against it, fewest
    /// first; ties in their own order, by least displacement), until `accept` returns true
    /// for one (the whole core's configuration and each node's candidate) or `limit` were
    /// tried. Returns how many were tried, whether the search was cut short (by `limit`
    /// or by the budget of homotopies, or by a node whose candidates are not all known: not
    /// enumerated within `max_paths`, or some paths undecided) before it accepted one, and the
    /// bounds that cut it (`limit`, `homotopies`). Its
    /// homotopies have at most `max_paths` paths (fewer than the enumeration's: the search
    /// runs in a plain solve) and it runs at most `homotopies` new ones.
    pub(crate) fn search(
        &self,
        forced: &[Option<usize>],
        drawing: &'a [f64],
        (limit, max_paths, homotopies): (usize, usize, usize),
        accept: &mut dyn FnMut(&[f64], &Choices) -> bool,
    ) -> (usize, bool, Vec<crate::Bound>) {
        let Some(root) = self.nodes.len().checked_sub(1) else { return (0, false, Vec::new()) };
        self.drawing.set(Some(drawing));
        self.path_cap.set(max_paths);
        let budget = self.budget.get();
        self.budget.set(budget.min(homotopies));
        // (The search's own budget, unless less than it is left of the enumeration's.)
        let searching = homotopies < budget;
        let previous =
            self.budget_size.replace(if searching { homotopies } else { MAX_ASSEMBLIES });
        let (mut tried, mut found, mut cut) = (0, false, false);
        self.visit(root, forced, &mut |x, choices, _| {
            if tried == limit {
                cut = true;
                return false;
            }
            tried += 1;
            found = accept(&x, &choices);
            !found
        });
        self.drawing.set(None);
        self.path_cap.set(usize::MAX);
        self.budget_size.set(previous);
        let spent = budget.min(homotopies) - self.budget.get();
        let exhausted = self.budget.get() == 0;
        self.budget.set(budget - spent);
        // Nodes whose candidates may not be all: the search did not see every combination.
        let partial = self.known.borrow().values().any(|c| !c.complete);
        let mut by = Vec::new();
        if cut {
            by.push(crate::Bound::Combinations);
        }
        if exhausted && !found {
            by.push(if searching {
                crate::Bound::SearchHomotopies
            } else {
                crate::Bound::NodeHomotopies
            });
        }
        (tried, !found && (cut || exhausted || partial), by)
    }

    /// The order in which the search visits node `k`'s candidates with its children at
    /// `children`: by how many wedges of its points turn against the drawing (a wedge drawn
    /// flat counts for none), fewest first, ties in their own order; their own order outside
    /// the search.
    fn order(&self, k: usize, children: &[&[f64]], candidates: &Candidates) -> Vec<usize> {
        let mut order: Vec<usize> = (0..candidates.list.len()).collect();
        let Some(drawing) = self.drawing.get() else { return order };
        let node = &self.nodes[k];
        let wedges: Vec<&[EntityIdx; 3]> = (self.wedges.iter())
            .filter(|w| w.iter().all(|p| node.entities.binary_search(p).is_ok()))
            .collect();
        // The sine of a wedge's turn at `y`.
        let turn = |y: &[f64], w: &[EntityIdx; 3]| {
            let at = |p: EntityIdx| {
                let c = self.layout.columns(p).start;
                [y[c], y[c + 1]]
            };
            let (a, b, c) = (at(w[0]), at(w[1]), at(w[2]));
            let n = (b[0] - a[0]).hypot(b[1] - a[1]) * (c[0] - a[0]).hypot(c[1] - a[1]);
            let det = crate::closed::orientation(a, b, c);
            if n > 0.0 { det / n } else { 0.0 }
        };
        let drawn: Vec<f64> = wedges.iter().map(|w| turn(drawing, w)).collect();
        let against: Vec<usize> = (0..candidates.list.len())
            .map(|j| match self.config(k, children, candidates, j) {
                Some(y) => (wedges.iter().zip(&drawn))
                    .filter(|(w, d)| d.abs() > 1e-6 && turn(&y, w) * **d <= 0.0)
                    .count(),
                None => usize::MAX,
            })
            .collect();
        order.sort_by_key(|&j| against[j]);
        order
    }

    /// Calls `emit` with each realization of node `k`'s subtree — configuration, choices (zero
    /// outside the subtree), whether every choice in it is the drawing's — until it returns
    /// false (then returns false).
    fn visit(&self, k: usize, forced: &[Option<usize>], emit: &mut Emit<'_>) -> bool {
        let choices = vec![0; self.nodes.len()];
        self.combine(k, 0, &mut Vec::new(), &choices, true, forced, emit)
    }

    /// [`Enumerator::visit`] from node `k`'s child `i` on, the earlier children at `configs`
    /// with `choices` (`own`: all the drawing's).
    #[allow(clippy::too_many_arguments)]
    fn combine(
        &self,
        k: usize,
        i: usize,
        configs: &mut Vec<Vec<f64>>,
        choices: &Choices,
        own: bool,
        forced: &[Option<usize>],
        emit: &mut Emit<'_>,
    ) -> bool {
        let node = &self.nodes[k];
        let Some(&child) = node.children.get(i) else {
            let children: Vec<&[f64]> = configs.iter().map(Vec::as_slice).collect();
            let candidates = self.known(k, &choices[self.first[k]..k], &children, own);
            for j in self.order(k, &children, &candidates) {
                if forced.get(k).copied().flatten().is_some_and(|f| f != j) {
                    continue;
                }
                let Some(config) = self.config(k, &children, &candidates, j) else { continue };
                let mut c = choices.clone();
                c[k] = j;
                if !emit(config, c, candidates.drawn_first && j == 0) {
                    return false;
                }
            }
            return true;
        };
        self.visit(child, forced, &mut |config, below, drawn| {
            let merged: Choices = choices.iter().zip(&below).map(|(a, b)| a + b).collect();
            configs.push(config);
            let go = self.combine(k, i + 1, configs, &merged, own && drawn, forced, emit);
            configs.pop();
            go
        })
    }

    /// [`Enumerator::candidates`] of node `k` with the nodes below it at `below` (their
    /// choices) and its children at `children`, computed once.
    fn known(&self, k: usize, below: &[usize], children: &[&[f64]], own: bool) -> Candidates {
        let key = (k, below.to_vec());
        if let Some(c) = self.known.borrow().get(&key) {
            return c.clone();
        }
        let c = self.candidates_below(k, Some(below), children, own);
        self.known.borrow_mut().insert(key, c.clone());
        c
    }
}

/// What receives the realizations of [`Enumerator::visit`]; false stops it.
type Emit<'e> = dyn FnMut(Vec<f64>, Choices, bool) -> bool + 'e;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::alternatives::tests::framework;
    use crate::homotopy::MAX_PATHS;

    fn enumerate(points: &[[f64; 2]], edges: &[(usize, usize)]) -> (System, Vec<Node>) {
        let s = framework(points, edges);
        let core: Vec<ConstraintIdx> = s.constraint_indices().collect();
        let nodes = plan(&s, &core);
        (s, nodes)
    }

    /// The sum, over every combination of the children's real candidates, of the root's
    /// finite complex solutions, and every realization.
    fn count(s: &System, nodes: &[Node], x: &[f64]) -> (usize, Vec<Vec<f64>>) {
        let layout = Layout::new(s);
        let eq = Equations::new(s, &layout);
        let e = Enumerator::new(s, &layout, &eq, nodes, x, 10.0, MAX_PATHS);
        let root = nodes.len() - 1;
        let leaves: Vec<Candidates> =
            nodes[root].children.iter().map(|&c| e.candidates(c, &[], true)).collect();
        let [a, b] = &leaves[..] else { panic!("{nodes:?}") };
        let mut finite = 0;
        for (i, u) in a.list.iter().enumerate() {
            for (j, v) in b.list.iter().enumerate() {
                let r = e.candidates(root, &[u, v], i == 0 && j == 0);
                let counts = r.counts.unwrap();
                assert_eq!(counts.failed, 0, "{counts:?}");
                finite += counts.finite;
            }
        }
        let (all, cut) = e.all(&vec![None; nodes.len()], 100_000);
        assert!(cut.is_empty(), "{cut:?}");
        (finite, all.into_iter().map(|a| a.0).collect())
    }

    fn holds(s: &System, y: &[f64]) -> bool {
        let layout = Layout::new(s);
        let eq = Equations::new(s, &layout);
        s.constraint_indices().all(|c| eq.residual(c, y).unwrap().values[0].abs() < 1e-9)
    }

    /// The prism splits into its two triangles and the three distances between them: 2 × 2
    /// leaf realizations, each assembled in 6 complex ways — Capco et al.'s 24 — and the real
    /// ones are exactly those of the whole prism's own homotopy.
    #[test]
    fn the_prism_is_two_triangles_assembled() {
        let prism = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)];
        let points = [[0.0, 0.0], [3.1, 0.4], [1.2, 2.9], [4.3, 3.3], [-0.7, 4.1], [2.6, 5.7]];
        let (s, nodes) = enumerate(&points, &prism);
        assert_eq!(nodes.len(), 3, "{nodes:?}");
        assert_eq!(nodes[2].children, vec![0, 1]);
        assert_eq!(nodes[2].constraints.len(), 3);
        assert!(nodes[..2].iter().all(|n| n.entities.len() == 3 && n.constraints.len() == 3));
        let x: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
        let (finite, all) = count(&s, &nodes, &x);
        assert_eq!(finite, 24);
        assert!(all.iter().all(|y| holds(&s, y)));
        assert!(all[0].iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-9), "the drawing first");
        // The whole prism by one homotopy (held by the same distance): the same realizations.
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        let core: Vec<ConstraintIdx> = s.constraint_indices().collect();
        let (_, flat) =
            alternatives::realizations(&s, &layout, &eq, &core, &x, (MAX_PATHS, 1e-9), 7).unwrap();
        assert_eq!(flat.len(), all.len());
        for y in &flat {
            assert!(
                all.iter().any(|z| z.iter().zip(y).all(|(a, b)| (a - b).abs() < 1e-7)),
                "{y:?} not assembled"
            );
        }
    }

    /// `homotopy-budget`: a node reached after the solve's budget of node homotopies was
    /// spent is not solved, and says so (with the budget); the drawing's own candidate is
    /// still offered where its children are the drawing's. (Through [`crate::solve`] the
    /// chosen path's nodes are all solved before any budget runs out — the enumeration that
    /// spends it reports `node-homotopies` in `bounds_hit` instead — so the reason is checked
    /// here, on the enumerator itself.)
    #[test]
    fn a_node_past_the_budget_says_so() {
        let prism = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)];
        let points = [[0.0, 0.0], [3.1, 0.4], [1.2, 2.9], [4.3, 3.3], [-0.7, 4.1], [2.6, 5.7]];
        let (s, nodes) = enumerate(&points, &prism);
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        let x: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
        let e = Enumerator::new(&s, &layout, &eq, &nodes, &x, 10.0, MAX_PATHS);
        e.budget.set(2);
        let (_, found, _) = e.choose(&[None, None, None]).unwrap();
        assert!(found[..2].iter().all(|c| c.complete && c.counts.is_some()));
        let root = &found[2];
        assert_eq!(root.shortfall, vec![Shortfall::Budget { homotopies: MAX_ASSEMBLIES }]);
        assert!(!root.complete && root.counts.is_none());
        assert_eq!((root.list.len(), root.drawn_first), (1, true), "the drawing's own");
        // Off the drawing's choices, nothing: the combination is not offered.
        let e = Enumerator::new(&s, &layout, &eq, &nodes, &x, 10.0, MAX_PATHS);
        e.budget.set(2);
        assert!(e.choose(&[Some(1), None, None]).is_err());
        let (listed, cut) = e.all(&[None, None, None], 100);
        assert_eq!(cut, vec![crate::Bound::NodeHomotopies]);
        assert_eq!(listed.len(), 1, "only the drawing's combination");
    }

    /// Two K3,3 joined by three distances (the witness paper's figure 8a): two leaves of 70
    /// paths and 16 complex realizations each, and an assembly of 6 paths per pair, where the
    /// whole would need 184,756; K3,3 alone does not split.
    #[test]
    fn two_k33_are_assembled_from_their_realizations() {
        let points = [
            [1.0, 2.0],
            [2.0, 8.0],
            [4.0, 13.0],
            [9.0, 3.0],
            [11.0, 9.0],
            [8.0, 14.0],
            [20.0, 1.0],
            [21.0, 7.0],
            [19.0, 12.0],
            [27.0, 2.0],
            [29.0, 8.0],
            [26.0, 13.0],
        ];
        let mut edges = vec![(3, 6), (4, 7), (5, 8)];
        for i in 0..3 {
            for j in 3..6 {
                edges.push((i, j));
                edges.push((i + 6, j + 6));
            }
        }
        let (s, nodes) = enumerate(&points, &edges);
        assert_eq!(nodes.len(), 3, "{nodes:?}");
        assert!(nodes[..2].iter().all(|n| n.entities.len() == 6 && n.children.is_empty()));
        assert_eq!(nodes[2].constraints.len(), 3);
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        let x: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
        let e = Enumerator::new(&s, &layout, &eq, &nodes, &x, 29.0, MAX_PATHS);
        let (at, found, _) = e.choose(&[None, None, None]).unwrap();
        assert!(at.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-9));
        for leaf in &found[..2] {
            let c = leaf.counts.unwrap();
            assert_eq!((c.paths, c.finite, c.failed), (70, 16, 0), "{c:?}");
            assert!(leaf.complete && leaf.list.len() >= 2);
        }
        let root = found[2].counts.unwrap();
        assert_eq!((root.paths, root.failed), (6, 0), "{root:?}");
        assert!(found[2].complete && root.finite <= 6);
        // The second candidate of the first K3,3: the assembly moves with it.
        let (other, _, _) = e.choose(&[Some(1), None, Some(0)]).unwrap();
        assert!(holds(&s, &other));
        assert!(other.iter().zip(&x).any(|(a, b)| (a - b).abs() > 1e-3));
        // Autosolve by chirality: with the first K3,3 at its second candidate, the assembly's
        // candidates come ordered by how many wedges (two distances at a point) turn against
        // the drawing, the fewest first. They are stored as placements of the two K3,3 (a
        // rotation and a translation of the second), the positions computed from them.
        let u = &found[0].list[1];
        let v = &found[1].list[0];
        let assembled = e.candidates(2, &[u, v], false);
        assert!(assembled.placed && assembled.list.iter().all(|p| p.len() == 4));
        let turn = |z: &[f64], w: &[EntityIdx; 3]| {
            let at = |p: EntityIdx| {
                let c = layout.columns(p).start;
                [z[c], z[c + 1]]
            };
            crate::closed::orientation(at(w[0]), at(w[1]), at(w[2])) > 0.0
        };
        let wrong = |y: &[f64]| e.wedges.iter().filter(|w| turn(y, w) != turn(&x, w)).count();
        let counts: Vec<usize> = (0..assembled.list.len())
            .map(|j| wrong(&e.config(2, &[u, v], &assembled, j).unwrap()))
            .collect();
        assert!(counts.len() >= 2 && counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
        assert!(
            (0..assembled.list.len())
                .all(|j| holds(&s, &e.config(2, &[u, v], &assembled, j).unwrap()))
        );
        let k33 = framework(
            &points[..6],
            &edges[3..].iter().copied().filter(|e| e.1 < 6).collect::<Vec<_>>(),
        );
        let core: Vec<ConstraintIdx> = k33.constraint_indices().collect();
        assert_eq!(plan(&k33, &core).len(), 1);
    }
}
