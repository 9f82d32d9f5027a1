//! Global rigidity of distance frameworks by the stress-matrix test (issue 19): do the
//! dimensions determine the shape, up to moving and mirroring the whole, or do they admit other
//! shapes (flips)?
//!
//! # What is covered
//!
//! A *distance framework*: every entity a `Point`, every constraint a `Distance` between two
//! points, a `Coincident` between two points (the two are merged into one vertex: the solutions
//! of the system are those of the merged framework), or a `Fix` of a point — at most one point
//! fixed (pinning one point leaves rotations and mirrors about it, so the question is that of
//! the free framework). Anything else — another entity kind, another constraint, a second
//! fixed point (which grounds a rigid body and mirrors are gone), a distance between two merged
//! points — is outside, and the answer is absent, never a guess.
//!
//! # The test
//!
//! `n` vertices (after merging), `m` bars, `R` the `m × dn` rigidity matrix (the bars' rows of
//! the Jacobian, halved: `p_i − p_j` under `i`, `p_j − p_i` under `j`).
//!
//! - Rigidity first: a framework that is not rigid is not globally rigid. Rigid means
//!   `rank R = dn − d(d+1)/2` for `n ≥ d`, `n(n−1)/2` for fewer points (then only the complete
//!   graph is rigid).
//! - `n ≤ d + 1`: rigid ⇔ complete ⇔ globally rigid.
//! - `n ≥ d + 2`: an equilibrium stress is `ω` with `ωᵀR = 0`; its stress matrix `Ω` (`n × n`,
//!   `Ω_ij = −Σ ω_e` over the bars `e` joining `i` and `j`, rows summing to zero) has rank at most
//!   `n − d − 1`. Connelly (2005) and Gortler–Healy–Thurston (2010): the graph is generically
//!   globally rigid in `R^d` iff a generic configuration has a stress of that rank; Connelly and
//!   Whiteley (2010): an infinitesimally rigid configuration (any, generic or not) with such a
//!   stress already proves it.
//!
//! The stress is a uniformly random vector of the left kernel of `R`
//! ([`random_left_kernel_vector`]: from the dependencies of `R`'s rows), and both ranks are taken modulo `p = 2^61 − 1` ([`ModP`]), first at the analysis'
//! witness, then, when that says no, at a uniformly random configuration modulo `p` (a second
//! draw of both the configuration and the stress).
//!
//! **One-sided error.** *Yes* is proven: the configuration is rational (the witness) or an
//! integer one (the residues of the random draw), the ranks over ℚ are at least those modulo
//! `p`, and the rational kernel reduces onto the kernel modulo `p` (same rank), so a stress of
//! rank `n − d − 1` modulo `p` comes from a rational stress of that rank. *No* can be bad luck:
//! at the random configuration `x` and stress coefficients `t`, a false *no* needs the product of
//! an `r × r` minor of `R(x)` (degree `r = rank R`) and an `(n−d−1)`-minor of the stress matrix
//! of the Cramer stresses (degree at most `(n−d−1)(r+1)` in `(x, t)`) to vanish, which
//! Schwartz–Zippel bounds by `((n−d−1)(r+1) + r) / p` ([`GlobalRigidity::error_bound`]: about
//! 10^-12 at a thousand points in 2D).
//!
//! **A shortcut for the common *no*.** A globally rigid framework is redundantly rigid
//! (Hendrickson 1992): every bar lies in a circuit, so a random stress is nonzero on every bar.
//! When the random stress leaves a bar at zero, the stress matrix is not formed (its
//! elimination is the costly part, the fill-in of a Cholesky factorisation of the graph) and the
//! answer is *no* (`unstressed_bars`). Wrongly so only if the bar is stressed generically: its
//! stress coefficient, times the minor that clears the denominators of the Cramer stresses, is
//! a nonzero polynomial of degree at most `r + 1`, and with that minor's `r` the bound is
//! `(2r + 1)/p`, within the bound above whenever `n ≥ d + 2`.
//!
//! The float backend takes the same ranks in `f64` at the (possibly approximate) witness with
//! its tolerance: an approximate answer, no bound.

use gcs_jacobian::{Layout, Witness, WitnessSource};
use gcs_model::rng::SplitMix64;
use gcs_model::{ConstraintIdx, EntityIdx, EntityKind, Metric, Signature, System};
use gcs_rank::{
    Echelon, EchelonOptions, Field, ModP, ModQ, PrimeField, SparseRow, echelon_rank,
    random_left_kernel_vector,
};

use crate::analysis::{Arithmetic, Backend};

/// How global rigidity was decided (the report's `method`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum GlobalMethod {
    /// The stress-matrix test (Connelly; Gortler–Healy–Thurston), rigidity included.
    StressMatrix,
    /// Jackson and Jordán's characterisation in the plane (3-connected and redundantly rigid,
    /// or complete on at most 3 vertices), here only its necessary half: a 2D framework that
    /// the pebble game shows not rigid, or with a bar in no circuit, on 4 or more vertices, is
    /// not globally rigid — with certainty, without arithmetic.
    JacksonJordan,
}

impl GlobalMethod {
    /// The report name: `stress matrix`, `Jackson–Jordán`.
    pub fn name(self) -> &'static str {
        match self {
            GlobalMethod::StressMatrix => "stress matrix",
            GlobalMethod::JacksonJordan => "Jackson–Jordán",
        }
    }
}

/// The answer of the global rigidity test for one distance framework (a model or a cluster).
#[derive(Clone, Debug, PartialEq)]
pub struct GlobalRigidity {
    /// Whether the generic framework is globally rigid: its dimensions determine its shape up to
    /// moving and mirroring the whole.
    pub globally_rigid: bool,
    /// How it was decided.
    pub method: GlobalMethod,
    /// Where: [`Arithmetic::ModP`] (a *yes* proven) or [`Arithmetic::Float`] (approximate).
    pub arithmetic: Arithmetic,
    /// Vertices after merging coincident points.
    pub points: usize,
    /// Bars (distances).
    pub bars: usize,
    /// Whether the framework is rigid (rank of its rigidity matrix).
    pub rigid: bool,
    /// The rank of the stress matrix found (0 when not computed: not rigid, `n ≤ d + 1`, or
    /// some bar unstressed).
    pub stress_rank: usize,
    /// Bars that the random stress leaves at zero (modulo `p` only; 0 in float): each lies in no
    /// circuit, so removing it leaves the framework flexible — not redundantly rigid, hence not
    /// globally rigid (Hendrickson's necessary condition), decided without the stress matrix.
    pub unstressed_bars: usize,
    /// The rank that proves global rigidity: `n − d − 1` (0 for `n ≤ d + 1`).
    pub target_rank: usize,
    /// Whether the answer was decided at a random configuration (the witness said no).
    pub random_configuration: bool,
    /// For a *no* modulo `p`: the Schwartz–Zippel bound on the probability that it is wrong
    /// (`((n−d−1)(r+1) + r) / p`). `None` for a *yes* (proven) and in float.
    pub error_bound: Option<f64>,
}

/// A distance framework read off a system: vertices (classes of coincident points, each with a
/// representative entity) and bars between them.
#[derive(Clone, Debug, PartialEq)]
pub struct DistanceFramework {
    /// The dimension `d`.
    pub dim: usize,
    /// One representative point per vertex.
    pub vertices: Vec<EntityIdx>,
    /// The bars, as vertex pairs (`u ≠ v`; repeated pairs kept).
    pub bars: Vec<(usize, usize)>,
}

/// The distance framework of `entities` and `constraints` of `system`, when they form one (see
/// the module docs); `None` otherwise.
pub fn distance_framework(
    system: &System,
    entities: &[EntityIdx],
    constraints: &[ConstraintIdx],
) -> Option<DistanceFramework> {
    if entities.is_empty() || entities.iter().any(|e| system.entity(*e).kind() != EntityKind::Point)
    {
        return None;
    }
    // Each entity's place in `entities` (one lookup per constraint, not a search).
    let mut place = vec![None; system.entities().len()];
    for (i, e) in entities.iter().enumerate() {
        place[e.index()] = Some(i);
    }
    let local = |e: EntityIdx| place[e.index()];
    let mut parent: Vec<usize> = (0..entities.len()).collect();
    fn find(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    let mut pairs = Vec::new();
    let mut fixed = Vec::new();
    for c in constraints {
        match system.constraint(*c).signature {
            Signature::Metric(Metric::DistancePointPoint(a, b)) => {
                pairs.push((local(a)?, local(b)?))
            }
            Signature::CoincidentPoints(a, b) => {
                let (a, b) = (find(&mut parent, local(a)?), find(&mut parent, local(b)?));
                parent[a] = b;
            }
            Signature::Fix(e) => fixed.push(local(e)?),
            _ => return None,
        }
    }
    let roots: Vec<usize> = (0..entities.len()).map(|i| find(&mut parent, i)).collect();
    let mut fixed_roots: Vec<usize> = fixed.iter().map(|i| roots[*i]).collect();
    fixed_roots.sort_unstable();
    fixed_roots.dedup();
    if fixed_roots.len() > 1 {
        return None;
    }
    let mut vertex_of = vec![usize::MAX; entities.len()];
    let mut vertices = Vec::new();
    for i in 0..entities.len() {
        if vertex_of[roots[i]] == usize::MAX {
            vertex_of[roots[i]] = vertices.len();
            vertices.push(entities[i]);
        }
    }
    let mut bars = Vec::with_capacity(pairs.len());
    for (a, b) in pairs {
        let (u, v) = (vertex_of[roots[a]], vertex_of[roots[b]]);
        if u == v {
            return None;
        }
        bars.push((u, v));
    }
    Some(DistanceFramework { dim: system.dim().coords(), vertices, bars })
}

/// The rank of the rigidity matrix of a rigid framework on `n` vertices in dimension `d`.
pub fn rigid_rank(n: usize, d: usize) -> usize {
    if n >= d { d * n - d * (d + 1) / 2 } else { n * n.saturating_sub(1) / 2 }
}

/// The rank a stress matrix must reach: `n − d − 1`, 0 for `n ≤ d + 1`.
fn target_rank(n: usize, d: usize) -> usize {
    n.saturating_sub(d + 1)
}

/// One draw of the test in one field: the rank of `R` and the rank of the stress matrix of one
/// random stress (0 when not rigid or `n ≤ d + 1`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Draw {
    rank: usize,
    stress_rank: usize,
    /// Bars the random stress leaves at zero (then the stress matrix is not formed).
    unstressed: usize,
}

/// A graph in dimension `d`: `n` vertices, bars between them.
#[derive(Clone, Copy)]
struct Graph<'a> {
    n: usize,
    d: usize,
    bars: &'a [(usize, usize)],
}

/// The rows of `Rᵀ` (one per vertex coordinate, columns the bars) at `x` (`x[v]` the
/// coordinates of vertex `v`).
fn transposed_rows<F: Field>(f: Graph<'_>, x: &[Vec<F>]) -> Vec<SparseRow<F>> {
    let d = f.d;
    let mut rows: Vec<Vec<(usize, F)>> = vec![Vec::new(); d * f.n];
    for (e, &(u, v)) in f.bars.iter().enumerate() {
        for k in 0..d {
            let diff = x[u][k].sub(&x[v][k]);
            rows[d * v + k].push((e, diff.neg()));
            rows[d * u + k].push((e, diff));
        }
    }
    rows.into_iter().map(SparseRow::from_entries).collect()
}

/// The rows of `R` (one per bar, columns the vertex coordinates) at `x`.
fn bar_rows<F: Field>(f: Graph<'_>, x: &[Vec<F>]) -> Vec<SparseRow<F>> {
    let d = f.d;
    f.bars
        .iter()
        .map(|&(u, v)| {
            let mut entries = Vec::with_capacity(2 * d);
            for (k, (a, b)) in x[u].iter().zip(&x[v]).enumerate() {
                let diff = a.sub(b);
                entries.push((d * v + k, diff.neg()));
                entries.push((d * u + k, diff));
            }
            SparseRow::from_entries(entries)
        })
        .collect()
}

/// The rows of the stress matrix of `omega`.
fn stress_rows<F: Field>(f: Graph<'_>, omega: &[F]) -> Vec<SparseRow<F>> {
    let mut rows: Vec<Vec<(usize, F)>> = vec![Vec::new(); f.n];
    for (&(u, v), w) in f.bars.iter().zip(omega) {
        rows[u].push((u, w.clone()));
        rows[v].push((v, w.clone()));
        rows[u].push((v, w.neg()));
        rows[v].push((u, w.neg()));
    }
    rows.into_iter().map(SparseRow::from_entries).collect()
}

/// One draw modulo `p` at `x`.
fn draw_modp<F: PrimeField>(f: Graph<'_>, x: &[Vec<F>], rng: &mut SplitMix64) -> Draw {
    let (n, d) = (f.n, f.d);
    let mut random = || F::residue(rng.below(F::prime()));
    let (rank, omega) = random_left_kernel_vector(d * n, bar_rows(f, x), &mut random);
    if rank < rigid_rank(n, d) || target_rank(n, d) == 0 {
        return Draw { rank, stress_rank: 0, unstressed: 0 };
    }
    // A bar no stress reaches is not redundant: the framework is not redundantly rigid, hence
    // not globally rigid (Hendrickson), and the stress matrix — the costly part, its
    // elimination fills in as a Cholesky factorisation of the graph — need not be formed.
    let unstressed = omega.iter().filter(|w| w.is_zero()).count();
    if unstressed > 0 {
        return Draw { rank, stress_rank: 0, unstressed };
    }
    let (stress_rank, _) = echelon_rank(n, stress_rows(f, &omega));
    Draw { rank, stress_rank, unstressed }
}

/// One draw in `f64` at `x`: ranks by elimination with the relative `tolerance`.
fn draw_float(f: Graph<'_>, x: &[Vec<f64>], tolerance: f64, rng: &mut SplitMix64) -> Draw {
    let (n, d, m) = (f.n, f.d, f.bars.len());
    let options = EchelonOptions { track_combinations: false, tolerance: Some(tolerance) };
    let mut e = Echelon::<f64>::new(m, options.clone());
    for row in transposed_rows(f, x) {
        e.insert(row);
    }
    let rank = e.rank();
    if rank < rigid_rank(n, d) || target_rank(n, d) == 0 {
        return Draw { rank, stress_rank: 0, unstressed: 0 };
    }
    let mut omega = vec![0.0; m];
    for b in e.kernel_basis() {
        let c = 2.0 * rng.unit_f64() - 1.0;
        for (j, v) in b.entries() {
            omega[*j] += c * v;
        }
    }
    let mut s = Echelon::<f64>::new(n, options);
    for row in stress_rows(f, &omega) {
        s.insert(row);
    }
    Draw { rank, stress_rank: s.rank(), unstressed: 0 }
}

/// The vertices' coordinates at the witness, in `F` (`None` when some has no image in `F`).
fn vertex_coords<F: Field>(
    f: &DistanceFramework,
    layout: &Layout,
    witness: &Witness,
) -> Option<Vec<Vec<F>>> {
    let coords: Vec<F> = witness.coords_in().ok()?;
    Some(f.vertices.iter().map(|v| coords[layout.columns(*v)].to_vec()).collect())
}

/// The stress-matrix test of a distance framework at the witness (see the module docs), in the
/// arithmetic of `backend` (modulo `p` for every exact backend, `f64` for float); `seed` seeds
/// the random stresses and the second configuration.
pub fn stress_test(
    f: &DistanceFramework,
    layout: &Layout,
    witness: &Witness,
    backend: Backend,
    seed: u64,
) -> GlobalRigidity {
    let g = Graph { n: f.vertices.len(), d: f.dim, bars: &f.bars };
    let mut rng = SplitMix64::new(seed ^ 0x5354_5245_5353_u64);
    if let Backend::Float { tolerance } = backend {
        let x =
            vertex_coords::<f64>(f, layout, witness).unwrap_or_else(|| vec![vec![0.0; g.d]; g.n]);
        let draw = draw_float(g, &x, tolerance, &mut rng);
        return answer(g, draw, Arithmetic::Float { tolerance }, false);
    }
    // A modular witness is a configuration modulo p already; a rational one is mapped there.
    // (A modular witness over another prime than ModP's is analysed inside its
    // `with_modulus`, in ModQ.)
    let first = match witness.source {
        WitnessSource::Approximate => None,
        _ if gcs_rank::modulus() != ModP::PRIME => {
            vertex_coords::<ModQ>(f, layout, witness).map(|x| draw_modp(g, &x, &mut rng))
        }
        _ => vertex_coords::<ModP>(f, layout, witness).map(|x| draw_modp(g, &x, &mut rng)),
    };
    if let Some(draw) = first {
        let first = answer(g, draw, Arithmetic::ModP, false);
        if first.globally_rigid {
            return first;
        }
    }
    at_random(g, &mut rng)
}

/// The stress-matrix test of a bare graph (vertices `0..n`, `edges` between them) in
/// dimension `dim`, at a uniformly random configuration modulo `p` with a random stress
/// (seeded by `seed`): a *yes* is proven, a *no* carries [`GlobalRigidity::error_bound`].
///
/// # Example
/// ```
/// use gcs_analysis::global::graph_globally_rigid;
/// // K4 is globally rigid in the plane; K4 minus an edge is rigid but can flip; a 4-cycle is
/// // not even rigid.
/// let k4 = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
/// assert!(graph_globally_rigid(4, 2, &k4, 1).globally_rigid);
/// let minus = graph_globally_rigid(4, 2, &k4[1..], 1);
/// assert!(minus.rigid && !minus.globally_rigid);
/// assert!(!graph_globally_rigid(4, 2, &[(0, 1), (1, 2), (2, 3), (0, 3)], 1).rigid);
/// ```
pub fn graph_globally_rigid(
    n: usize,
    dim: usize,
    edges: &[(usize, usize)],
    seed: u64,
) -> GlobalRigidity {
    let mut rng = SplitMix64::new(seed ^ 0x5354_5245_5353_u64);
    at_random(Graph { n, d: dim, bars: edges }, &mut rng)
}

/// The second draw: a uniformly random configuration and stress modulo p.
fn at_random(g: Graph<'_>, rng: &mut SplitMix64) -> GlobalRigidity {
    let x: Vec<Vec<ModP>> =
        (0..g.n).map(|_| (0..g.d).map(|_| ModP::new(rng.below(ModP::PRIME))).collect()).collect();
    let draw = draw_modp(g, &x, rng);
    answer(g, draw, Arithmetic::ModP, true)
}

/// The answer of one draw.
fn answer(g: Graph<'_>, draw: Draw, arithmetic: Arithmetic, random: bool) -> GlobalRigidity {
    let (n, d) = (g.n, g.d);
    let target = target_rank(n, d);
    let rigid = draw.rank == rigid_rank(n, d);
    let yes = rigid && draw.stress_rank == target;
    let error_bound = (!yes && matches!(arithmetic, Arithmetic::ModP)).then(|| {
        let r = rigid_rank(n, d) as f64;
        (target as f64 * (r + 1.0) + r) / ModP::PRIME as f64
    });
    GlobalRigidity {
        globally_rigid: yes,
        method: GlobalMethod::StressMatrix,
        arithmetic,
        points: n,
        bars: g.bars.len(),
        rigid,
        stress_rank: draw.stress_rank,
        unstressed_bars: draw.unstressed,
        target_rank: target,
        random_configuration: random,
        error_bound,
    }
}

/// The answer of Jackson and Jordán's necessary condition for a 2D framework on `n` vertices
/// with `bars` bars, which the pebble game found `rigid` or not, `coloops` of its bars in no
/// circuit: *not* globally rigid, certainly, when `n ≥ 4` and it is not redundantly rigid (not
/// rigid, or some bar in no circuit); `None` when the condition holds and the stress test must
/// decide. (`unstressed_bars` counts the bars in no circuit, those a generic stress leaves at
/// zero, as the stress test does for a rigid framework.)
pub(crate) fn not_redundantly_rigid(
    n: usize,
    bars: usize,
    rigid: bool,
    coloops: usize,
) -> Option<GlobalRigidity> {
    if n < 4 || (rigid && coloops == 0) {
        return None;
    }
    Some(GlobalRigidity {
        globally_rigid: false,
        method: GlobalMethod::JacksonJordan,
        arithmetic: Arithmetic::Combinatorial,
        points: n,
        bars,
        rigid,
        stress_rank: 0,
        unstressed_bars: if rigid { coloops } else { 0 },
        target_rank: target_rank(n, 2),
        random_configuration: false,
        error_bound: None,
    })
}

/// The test of the whole system, when it is a distance framework.
pub(crate) fn model(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    backend: Backend,
    seed: u64,
) -> Option<GlobalRigidity> {
    let entities: Vec<EntityIdx> = system.entity_indices().collect();
    let constraints: Vec<ConstraintIdx> = system.constraint_indices().collect();
    let f = distance_framework(system, &entities, &constraints)?;
    Some(stress_test(&f, layout, witness, backend, seed))
}

/// The test of every cluster that is a distance framework, in the order of `clusters`, but
/// for those `decided` answers already (by index: the whole system as one cluster, whose answer
/// is the model's; Jackson and Jordán's condition).
pub(crate) fn clusters(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    backend: Backend,
    seed: u64,
    clusters: &[gcs_decompose::Cluster],
    decided: impl Fn(usize) -> Option<GlobalRigidity>,
) -> Vec<Option<GlobalRigidity>> {
    clusters
        .iter()
        .enumerate()
        .map(|(k, c)| {
            if let Some(answer) = decided(k) {
                return Some(answer);
            }
            let f = distance_framework(system, &c.entities, &c.constraints)?;
            Some(stress_test(&f, layout, witness, backend, seed.wrapping_add(k as u64 + 1)))
        })
        .collect()
}
