//! The clusters of a system at a witness, as the analysis reports them (format §2,
//! `clusters`), and their W-decompositions (§3, `decomposition`): the public face of
//! [`crate::rigid`] and [`crate::wdec`].

use gcs_jacobian::{Jacobian, JacobianError, Layout, motions};
use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rank::{EchelonOptions, Field};

use crate::rigid::ClusterMethod;
use crate::wdec::{DecompositionNode, RemovalOrder, Statistics};

/// A maximal rigid subsystem (format §2, `clusters`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cluster {
    /// Its entities, in file order (segments whose two points are in it included).
    pub entities: Vec<EntityIdx>,
    /// The constraints among its entities, in file order.
    pub constraints: Vec<ConstraintIdx>,
    /// Whether absolute constraints (`Fix`, `Horizontal`, `Vertical`) hold it in place.
    pub grounded: bool,
}

/// The W-decompositions of the clusters (one tree per cluster, in the order of the clusters),
/// the work they took, and how each declared group was taken.
pub type Decomposition = (Vec<DecompositionNode>, Statistics, Vec<GroupRigidity>);

/// A group the user declared ([`System::groups`]) as the W-decomposition took it: rigid on its
/// own constraints (those among its entities), it is a node of the DR-plan; otherwise not.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GroupRigidity {
    /// The group (its index in [`System::groups`]).
    pub group: usize,
    /// The maximal rigid subsystems of the group on its own constraints: 1 when it is rigid
    /// (0 for a group of no entity with coordinates).
    pub parts: usize,
}

impl GroupRigidity {
    /// Whether the group is rigid on its own constraints (and so a node of the DR-plan).
    pub fn rigid(&self) -> bool {
        self.parts == 1
    }
}

/// How [`clusters`] works.
#[derive(Clone, Debug, PartialEq)]
pub struct ClusterOptions {
    /// How clusters are found.
    pub method: ClusterMethod,
    /// Whether to W-decompose every cluster (witness paper §5).
    pub decompose: bool,
    /// Which constraint the W-decomposition tries to remove first.
    pub removal_order: RemovalOrder,
    /// The most maximal rigid subsystem computations a W-decomposition may spend (each one
    /// elimination); past it, the subsystems not yet examined are reported as leaves and the
    /// statistics say the decomposition is incomplete.
    pub decomposition_budget: usize,
    /// Whether, in a model that is a 2D bar framework (points and distances between them,
    /// nothing else), the cluster searches — of the model and of the W-decomposition's
    /// subsystems — are decided by the pebble game instead of at the witness, in exact fields:
    /// the generic clusters (Laman's theorem), the witness's at a generic witness; what makes
    /// W-decompositions of large frameworks fast. (Only for whole bar frameworks: in a model
    /// with other constraints, a subsystem of points and distances can be special at every
    /// solution — points that an incidence elsewhere keeps on a line.)
    pub pebble_game: bool,
}

impl Default for ClusterOptions {
    fn default() -> Self {
        ClusterOptions {
            method: ClusterMethod::default(),
            decompose: false,
            removal_order: RemovalOrder::default(),
            decomposition_budget: 20_000,
            pebble_game: true,
        }
    }
}

/// Whether `system` is a 2D framework of points and distances between distinct points.
fn is_bar_framework(system: &System) -> bool {
    use gcs_model::{Dim, EntityKind, Metric, Signature};
    system.dim() == Dim::Two
        && system.entities().iter().all(|e| e.kind() == EntityKind::Point)
        && system.constraints().iter().all(|c| {
            matches!(c.signature, Signature::Metric(Metric::DistancePointPoint(a, b)) if a != b)
        })
}

/// The clusters (maximal rigid subsystems) of a whole system at a witness, computed in the
/// field `F`: `jacobian` is the Jacobian at `coords` (see `gcs_jacobian::Witness::jacobian`),
/// `echelon` the elimination options (a tolerance for `f64`); with
/// [`ClusterOptions::decompose`], the W-decomposition of every cluster too.
///
/// # Errors
/// When the displacement generators have no image in `F` (homogeneous coordinates of zero
/// norm: impossible over ℚ, negligibly likely modulo a large prime).
pub fn clusters<F: Field>(
    system: &System,
    layout: &Layout,
    jacobian: &Jacobian<F>,
    coords: Vec<F>,
    echelon: EchelonOptions,
    options: &ClusterOptions,
) -> Result<(Vec<Cluster>, Option<Decomposition>), JacobianError> {
    let generators = motions::generators::<F>(system, layout, &coords)?;
    let mut ctx = crate::rigid::Context::new(system, layout, jacobian, generators, echelon);
    ctx.method = options.method;
    ctx.pebble = options.pebble_game && F::EXACT && is_bar_framework(system);
    let groups = ctx.constraint_groups(jacobian);
    let entities: Vec<EntityIdx> =
        system.entity_indices().filter(|e| layout.repr(*e).is_some()).collect();
    let sub = crate::rigid::Subsystem { entities, groups };
    let raw = crate::rigid::clusters(&ctx, &sub);
    let decomposition = options.decompose.then(|| {
        let mut d = crate::wdec::Decomposer::new(&ctx, coords, options.removal_order)
            .with_budget(options.decomposition_budget);
        let mut trees = Vec::new();
        // In the order of the finished clusters (sorted by first entity, segments added).
        let finished = finish_clusters(system, &sub, raw.clone());
        for c in &finished {
            let groups = sub
                .groups
                .iter()
                .filter(|g| match g.label {
                    crate::rigid::Label::Constraint(ci) => c.constraints.contains(&ci),
                    crate::rigid::Label::Virtual(_) => false,
                })
                .cloned()
                .collect();
            let entities: Vec<EntityIdx> =
                c.entities.iter().copied().filter(|e| layout.repr(*e).is_some()).collect();
            let csub = crate::rigid::Subsystem { entities, groups };
            let mut tree = d.decompose(&csub);
            // The root is the cluster itself, as reported.
            tree.entities = c.entities.clone();
            tree.constraints = c.constraints.clone();
            trees.push(tree);
        }
        let groups = incorporate(&mut d, system, layout, &sub, &mut trees);
        (trees, d.stats, groups)
    });
    Ok((finish_clusters(system, &sub, raw), decomposition))
}

/// The entities with coordinates of a list (composite entities replaced by their parts), sorted.
fn base_entities(system: &System, layout: &Layout, entities: &[EntityIdx]) -> Vec<EntityIdx> {
    let mut out: Vec<EntityIdx> = Vec::new();
    for &e in entities {
        if system.entity(e).kind().is_composite() {
            out.extend(system.entity(e).geometry.parts().iter().copied());
        } else {
            out.push(e);
        }
    }
    out.retain(|e| layout.repr(*e).is_some());
    out.sort_unstable();
    out.dedup();
    out
}

/// Whether sorted `small` lies in sorted `large`.
fn within(small: &[EntityIdx], large: &[EntityIdx]) -> bool {
    small.iter().all(|e| large.binary_search(e).is_ok())
}

/// Feature incorporation (the ESM paper §2.1, after Sitharam et al.): each declared group that
/// is rigid on its own constraints becomes a node of the DR-plan of the cluster holding it —
/// marked where a node already is the group, otherwise decomposed on its own and put under the
/// smallest node that holds it (the first child holding it, recursively), in place of that
/// node's children that lie inside it (the group's own decomposition covers them). Groups are
/// taken largest first, so that a group inside another goes below it. Returns the verdict on
/// every group, in the order of [`System::groups`]; nothing changes without groups.
fn incorporate<F: Field>(
    d: &mut crate::wdec::Decomposer<'_, '_, F>,
    system: &System,
    layout: &Layout,
    sub: &crate::rigid::Subsystem<F>,
    trees: &mut [DecompositionNode],
) -> Vec<GroupRigidity> {
    let base = |n: &DecompositionNode| base_entities(system, layout, &n.entities);
    let mut order: Vec<(usize, Vec<EntityIdx>)> = (system.groups().iter().enumerate())
        .map(|(k, g)| (k, base_entities(system, layout, &g.entities)))
        .collect();
    order.sort_by_key(|(k, e)| (std::cmp::Reverse(e.len()), *k));
    let mut verdicts = Vec::new();
    for (k, entities) in order {
        let groups = (sub.groups.iter())
            .filter(|g| {
                matches!(g.label, crate::rigid::Label::Constraint(_))
                    && within(&g.entities, &entities)
            })
            .cloned()
            .collect();
        let gsub = crate::rigid::Subsystem { entities: entities.clone(), groups };
        let parts =
            if entities.is_empty() { 0 } else { crate::rigid::clusters(d.ctx, &gsub).len() };
        verdicts.push(GroupRigidity { group: k, parts });
        if parts != 1 {
            continue;
        }
        let Some(tree) = trees.iter_mut().find(|t| within(&entities, &base(t))) else { continue };
        // A node that is the group already.
        fn mark(
            node: &mut DecompositionNode,
            is: &dyn Fn(&DecompositionNode) -> bool,
            k: usize,
        ) -> bool {
            if is(node) {
                node.groups.push(k);
                return true;
            }
            node.children.iter_mut().any(|c| mark(c, is, k))
        }
        if mark(tree, &|n| base(n) == entities, k) {
            continue;
        }
        let mut node = d.decompose(&gsub);
        node.groups.push(k);
        let mut at = tree;
        while let Some(i) = at.children.iter().position(|c| within(&entities, &base(c))) {
            at = &mut at.children[i];
        }
        at.children.retain(|c| !within(&base(c), &entities));
        at.children.push(node);
        at.children.sort_by(|a, b| a.entities.cmp(&b.entities));
    }
    verdicts.sort_by_key(|v| v.group);
    verdicts
}

/// Adds segments to the clusters holding both their points (a segment in none gets its own),
/// names the constraints, and sorts.
fn finish_clusters<F>(
    system: &System,
    sub: &crate::rigid::Subsystem<F>,
    raw: Vec<crate::rigid::RawCluster>,
) -> Vec<Cluster> {
    // Composite entities (segments, B-splines) join the clusters holding all their parts.
    let mut of_entity: std::collections::HashMap<EntityIdx, Vec<usize>> = Default::default();
    for (i, r) in raw.iter().enumerate() {
        for e in &r.entities {
            of_entity.entry(*e).or_default().push(i);
        }
    }
    let mut segments: Vec<Vec<EntityIdx>> = vec![Vec::new(); raw.len()];
    let mut lonely: Vec<EntityIdx> = Vec::new();
    for e in system.entity_indices() {
        if system.entity(e).kind().is_composite() {
            let parts = system.entity(e).geometry.parts();
            let both: Vec<usize> = (parts.first())
                .and_then(|p| of_entity.get(p))
                .into_iter()
                .flatten()
                .copied()
                .filter(|c| {
                    parts[1..].iter().all(|p| of_entity.get(p).is_some_and(|l| l.contains(c)))
                })
                .collect();
            if both.is_empty() {
                lonely.push(e);
            }
            for c in both {
                segments[c].push(e);
            }
        }
    }
    let mut out: Vec<Cluster> = raw
        .into_iter()
        .zip(segments)
        .map(|(r, segs)| {
            let mut entities = r.entities.clone();
            entities.extend(segs);
            entities.sort_unstable();
            let constraints = r
                .groups
                .iter()
                .filter_map(|g| match sub.groups[*g].label {
                    crate::rigid::Label::Constraint(c) => Some(c),
                    crate::rigid::Label::Virtual(_) => None,
                })
                .collect();
            Cluster { entities, constraints, grounded: r.grounded }
        })
        .collect();
    for e in lonely {
        let constraints = system
            .constraint_indices()
            .filter(|c| system.constraint(*c).signature.entities() == vec![e])
            .collect();
        out.push(Cluster { entities: vec![e], constraints, grounded: false });
    }
    out.sort_by(|a, b| a.entities.cmp(&b.entities));
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use gcs_jacobian::{WitnessOptions, WitnessSource, find_witness};
    use gcs_rank::ModP;

    /// Whether the open-chain shortcut applies to a model of `data/` (modulo the prime, at the
    /// default witness), and whether its clusters then equal the general search's.
    fn shortcut(name: &str) -> bool {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data").join(name);
        let text = std::fs::read_to_string(&path).unwrap();
        shortcut_on(&System::from_ron_str(&text, Some(name)).unwrap(), name)
    }

    /// Runs `f` on the cluster search's context for `system` at its default witness (modulo
    /// the prime) and the whole system as a subsystem.
    pub(crate) fn with_context<R>(
        system: &System,
        f: impl FnOnce(&mut crate::rigid::Context<'_, ModP>, &crate::rigid::Subsystem<ModP>) -> R,
    ) -> R {
        let layout = Layout::new(system);
        let witness = find_witness(system, &layout, &WitnessOptions::default()).unwrap();
        let jacobian: Jacobian<ModP> = witness.jacobian(system, &layout).unwrap();
        let coords: Vec<ModP> = witness.coords_in().unwrap();
        let generators = motions::generators::<ModP>(system, &layout, &coords).unwrap();
        let mut ctx = crate::rigid::Context::new(
            system,
            &layout,
            &jacobian,
            generators,
            EchelonOptions::default(),
        );
        let groups = ctx.constraint_groups(&jacobian);
        let entities: Vec<EntityIdx> =
            system.entity_indices().filter(|e| layout.repr(*e).is_some()).collect();
        f(&mut ctx, &crate::rigid::Subsystem { entities, groups })
    }

    fn shortcut_on(system: &System, name: &str) -> bool {
        with_context(system, |ctx, sub| {
            let Some(mut fast) = crate::rigid::open_chain(ctx, sub) else { return false };
            fast.sort_by(|a, b| a.entities.cmp(&b.entities));
            ctx.method = ClusterMethod::Kernel;
            assert_eq!(fast, crate::rigid::clusters(ctx, sub), "{name}");
            true
        })
    }

    /// The clusters at the default witness (modulo the prime), as lists of entity ids, and
    /// where the witness came from (the witness search decides, not the pebble game).
    fn clusters_by_id(system: &System) -> (WitnessSource, Vec<Vec<String>>) {
        clusters_by_id_with(system, false)
    }

    fn clusters_by_id_with(
        system: &System,
        pebble_game: bool,
    ) -> (WitnessSource, Vec<Vec<String>>) {
        let layout = Layout::new(system);
        let witness = find_witness(system, &layout, &WitnessOptions::default()).unwrap();
        let jacobian: Jacobian<ModP> = witness.jacobian(system, &layout).unwrap();
        let coords: Vec<ModP> = witness.coords_in().unwrap();
        let (found, _) = clusters(
            system,
            &layout,
            &jacobian,
            coords,
            EchelonOptions::default(),
            &ClusterOptions { pebble_game, ..ClusterOptions::default() },
        )
        .unwrap();
        let ids = |c: &Cluster| -> Vec<String> {
            c.entities.iter().map(|e| system.entity(*e).id.clone()).collect()
        };
        (witness.source, found.iter().map(ids).collect())
    }

    /// A random 2D bar framework: a Laman graph on `n` points with some bars removed and some
    /// added (so flexible parts, redundant ones and several clusters), at random integer
    /// coordinates (the sketch: a generic witness with overwhelming probability).
    fn random_framework(n: usize, seed: u64) -> System {
        let mut rng = gcs_model::rng::SplitMix64::new(seed);
        let mut edges = gcs_model::generate::laman_edges(n, 0.5, &mut rng);
        for _ in 0..rng.below(3) {
            let k = rng.below(edges.len() as u64) as usize;
            edges.swap_remove(k);
        }
        for _ in 0..rng.below(4) {
            let (a, b) = (rng.below(n as u64) as usize, rng.below(n as u64) as usize);
            if a != b {
                edges.push((a, b));
            }
        }
        let coords = gcs_model::generate::random_coords(n, gcs_model::Dim::Two, 1000, &mut rng);
        gcs_model::generate::framework("random", gcs_model::Dim::Two, &coords, &edges)
    }

    /// The pebble game's clusters of a bar framework are the witness search's, for the whole
    /// framework and for it without each of its bars in turn (the W-decomposition's question).
    #[test]
    fn the_pebble_game_finds_the_witness_clusters_of_bar_frameworks() {
        let mut compared = 0;
        for seed in 1..=40 {
            let system = random_framework(5 + (seed as usize % 9), seed);
            compared += with_context(&system, |ctx, whole| {
                ctx.method = ClusterMethod::Kernel;
                let mut subs = vec![whole.clone()];
                for g in 0..whole.groups.len() {
                    let mut without = whole.clone();
                    without.groups.remove(g);
                    subs.push(without);
                }
                for sub in &subs {
                    ctx.pebble = false;
                    let searched = crate::rigid::clusters(ctx, sub);
                    ctx.pebble = true;
                    assert_eq!(crate::rigid::clusters(ctx, sub), searched, "seed {seed}");
                }
                subs.len()
            });
        }
        assert!(compared > 400, "{compared}");
    }

    /// W-decompositions of random Laman frameworks with and without the pebble game agree.
    #[test]
    fn w_decompositions_with_the_pebble_game_are_the_witness_ones() {
        // Small ones, and a few large enough for long peeling chains ending in a leaf that
        // the pebble game certifies without a search.
        let sizes = (1..=12).map(|seed| (8 + seed as usize, seed)).chain([(40, 13), (60, 14)]);
        for (n, seed) in sizes {
            let system = gcs_model::generate::laman(n, seed);
            let layout = Layout::new(&system);
            let witness = find_witness(&system, &layout, &WitnessOptions::default()).unwrap();
            let jacobian: Jacobian<ModP> = witness.jacobian(&system, &layout).unwrap();
            let coords: Vec<ModP> = witness.coords_in().unwrap();
            let run = |pebble_game: bool| {
                let options =
                    ClusterOptions { decompose: true, pebble_game, ..ClusterOptions::default() };
                let (clusters, decomposition) = super::clusters(
                    &system,
                    &layout,
                    &jacobian,
                    coords.clone(),
                    EchelonOptions::default(),
                    &options,
                )
                .unwrap();
                (clusters, decomposition.map(|d| d.0))
            };
            let (with, without) = (run(true), run(false));
            assert!(with.1.as_ref().is_some_and(|t| !t.is_empty()), "seed {seed}");
            assert_eq!(with, without, "seed {seed}");
        }
    }

    #[test]
    fn the_open_chain_shortcut_applies_to_open_chains_only() {
        // Fig. 7: three triangles articulated at p3 and p5; the butterfly: two at p0.
        assert!(shortcut("paper/chain.ron"));
        assert!(shortcut("paper/butterfly.ron"));
        // One rigid block: the whole system.
        assert!(shortcut("paper/kite.ron"));
        // A closed non-rigid chain (the four-bar linkage) and absolute constraints (the CAD
        // rectangle's frame): not an open chain, the general search decides.
        assert!(!shortcut("sketches/four_bar.ron"));
        assert!(!shortcut("sketches/rectangle.ron"));
        let square = gcs_model::generate::framework(
            "square",
            gcs_model::Dim::Two,
            &[vec![0, 0], vec![4, 1], vec![5, 5], vec![1, 4]],
            &[(0, 1), (1, 2), (2, 3), (3, 0)],
        );
        assert!(!shortcut_on(&square, "square"));
    }

    /// Two rigid bodies sharing the line `l` slide along it; the line `m` of the second body,
    /// parallel to `l`, does not move in the slide, so it belongs to the first body's cluster
    /// too. Blocks alone would miss it: the shortcut must stand down (here by its condition 2:
    /// the group of the parallel lines has a low degree of rigidity).
    #[test]
    fn the_open_chain_shortcut_stands_down_for_an_entity_its_hinge_cannot_move() {
        let text = r#"System(name: "slide", dim: 2,
            entities: [
                Point(id: "a", at: [0, 0]), Point(id: "b", at: [4, 0]),
                Line(id: "l", at: [[0, 0], [1, 0]]), Line(id: "m", at: [[0, 3], [1, 3]]),
                Point(id: "c", at: [2, 3]), Point(id: "d", at: [7, 3]),
            ],
            constraints: [
                Incident(id: "al", a: "a", b: "l"), Incident(id: "bl", a: "b", b: "l"),
                Distance(id: "ab", a: "a", b: "b", value: 4),
                Parallel(id: "lm", a: "l", b: "m"), Distance(id: "dlm", a: "l", b: "m", value: 3),
                Incident(id: "cm", a: "c", b: "m"), Incident(id: "dm", a: "d", b: "m"),
                Distance(id: "cd", a: "c", b: "d", value: 5),
            ])"#;
        let system = System::from_ron_str(text, None).unwrap();
        assert!(!shortcut_on(&system, "slide"));
        let (_, clusters) = clusters_by_id(&system);
        assert_eq!(clusters, [["a", "b", "l", "m"], ["l", "m", "c", "d"]], "{clusters:?}");
    }

    /// Two rigid bodies hinged at `h`; the sketch (a witness: the rank is generic) puts `y`,
    /// a point of the second body, on `h`. Rotating the second body about `h` does not move
    /// `y`, so at this witness `y` is in the first body's cluster too — which the blocks
    /// alone would miss. Every block is rigid here: condition 5 is what stands the shortcut
    /// down.
    #[test]
    fn the_open_chain_shortcut_stands_down_for_a_point_on_its_hinge() {
        let text = r#"System(name: "pinned", dim: 2,
            entities: [
                Point(id: "h", at: [0, 0]), Point(id: "a", at: [-3, 4]),
                Point(id: "b", at: [-3, -4]), Point(id: "c", at: [3, 4]),
                Point(id: "d", at: [3, -4]), Point(id: "y", at: [0, 0]),
            ],
            constraints: [
                Distance(id: "ha", a: "h", b: "a", value: 5),
                Distance(id: "hb", a: "h", b: "b", value: 5),
                Distance(id: "ab", a: "a", b: "b", value: 8),
                Distance(id: "hc", a: "h", b: "c", value: 5),
                Distance(id: "hd", a: "h", b: "d", value: 5),
                Distance(id: "cd", a: "c", b: "d", value: 8),
                Distance(id: "cy", a: "c", b: "y", value: 5),
                Distance(id: "dy", a: "d", b: "y", value: 5),
            ])"#;
        let system = System::from_ron_str(text, None).unwrap();
        assert!(!shortcut_on(&system, "pinned"));
        let (source, clusters) = clusters_by_id(&system);
        assert_eq!(source, WitnessSource::Sketch);
        assert_eq!(clusters, [["h", "a", "b", "y"], ["h", "c", "d", "y"]], "{clusters:?}");
        // The pebble game gives the generic clusters: `y` is not on the hinge generically.
        let (_, generic) = clusters_by_id_with(&system, true);
        assert_eq!(generic, [vec!["h", "a", "b"], vec!["h", "c", "d", "y"]], "{generic:?}");
    }
}
