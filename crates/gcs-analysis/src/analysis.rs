//! The witness analysis (witness paper §2–§3, §6): rank, degrees of freedom, trivial motions,
//! redundant constraints in file order with their spanning groups.

use gcs_jacobian::{
    Jacobian, JacobianError, Layout, RowOwner, Witness, WitnessOptions, WitnessSource,
    find_witness, motions,
};
use gcs_model::{ConstraintIdx, Dim, EntityIdx, EntityKind, Metric, Signature, System};
use gcs_rank::{
    AMBIGUITY_BAND, BigRational, Echelon, EchelonOptions, Field, Insertion, KernelHint, ModP, ModQ,
    Proof, Rat, RowAnalysis, SparseRow, analyse_rows, analyse_rows_exact, analyse_rows_plain,
    analyse_rows_with_margins, certify_rows, float_rank_qr,
};

use gcs_decompose::{
    Cluster, ClusterMethod, ClusterOptions, Decomposition, DecompositionNode, GroupRigidity,
    PebbleReport, RemovalOrder, Statistics, pebble_game,
};

use crate::error::AnalysisError;
use crate::global::{self, GlobalRigidity};
use crate::sketch::SketchAnalysis;

/// The arithmetic a part of the analysis was decided in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Arithmetic {
    /// Exact rationals.
    Rational,
    /// Modulo the prime 2^61 − 1: exact with overwhelming probability.
    ModP,
    /// `f64` with a relative tolerance.
    Float {
        /// The tolerance.
        tolerance: f64,
    },
    /// No arithmetic: decided combinatorially (the pebble game of a 2D bar framework).
    Combinatorial,
    /// Not computed (not asked for).
    None,
}

/// How the generic rank, the redundancies and the clusters were decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RankMethod {
    /// The witness method: the Jacobian's rank at a generic witness.
    Witness,
    /// The (2,3) pebble game, for 2D frameworks of points and distances between them: by
    /// Laman's theorem the same answer as any generic witness, with certainty and without
    /// arithmetic ([`gcs_decompose::pebble_game`]).
    PebbleGame,
}

impl RankMethod {
    /// The report name: `witness`, `pebble game`.
    pub fn name(self) -> &'static str {
        match self {
            RankMethod::Witness => "witness",
            RankMethod::PebbleGame => "pebble game",
        }
    }
}

impl Arithmetic {
    /// The report name: `rational`, `modp`, `float`, `combinatorial`, `none`.
    pub fn name(self) -> &'static str {
        match self {
            Arithmetic::Rational => "rational",
            Arithmetic::ModP => "modp",
            Arithmetic::Float { .. } => "float",
            Arithmetic::Combinatorial => "combinatorial",
            Arithmetic::None => "none",
        }
    }
}

/// Clusters, and the decomposition when asked for.
type ClusterResult = (Vec<Cluster>, Option<Decomposition>);

/// The clusters of the whole system (and their W-decompositions) at the witness, in `F`.
fn clusters_in<F: Field>(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    echelon: EchelonOptions,
    options: &ClusterOptions,
) -> Result<ClusterResult, AnalysisError> {
    let jacobian: Jacobian<F> = witness.jacobian(system, layout)?;
    let coords: Vec<F> = witness.coords_in()?;
    Ok(gcs_decompose::clusters(system, layout, &jacobian, coords, echelon, options)?)
}

/// The arithmetic the rank is decided in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Backend {
    /// The rank over ℚ, proven: modular elimination certified over ℚ, or rational
    /// elimination when the certificate fails. The default.
    Exact,
    /// Rational elimination with `num-rational`.
    Rational,
    /// Rational elimination with GMP (`rug`); only with the `rug` feature.
    Rug,
    /// Elimination modulo the prime 2^61 − 1: exact with overwhelming probability, not proven.
    ModP,
    /// `f64` elimination; an entry is zero when `|x| <= tolerance · (largest entry of its row)`.
    Float {
        /// The relative tolerance.
        tolerance: f64,
    },
}

impl Backend {
    /// The report name: `exact`, `rational`, `rug`, `modp`, `float`.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Exact => "exact",
            Backend::Rational => "rational",
            Backend::Rug => "rug",
            Backend::ModP => "modp",
            Backend::Float { .. } => "float",
        }
    }

    /// Whether the backend was compiled in (`rug` needs the cargo feature).
    pub fn available(self) -> bool {
        !matches!(self, Backend::Rug) || cfg!(feature = "rug")
    }
}

/// Options of [`analyze`].
#[derive(Clone, Debug, PartialEq)]
pub struct AnalysisOptions {
    /// The arithmetic.
    pub backend: Backend,
    /// The witness search (its seed is the report's seed).
    pub witness: WitnessOptions,
    /// Whether to compute the clusters (maximal rigid subsystems). On by default; turning it
    /// off leaves `clusters` empty and saves their cost when only the rank and the
    /// redundancies are wanted.
    pub clusters: bool,
    /// Whether to W-decompose every cluster (witness paper §5); needs `clusters`.
    pub decompose: bool,
    /// Which constraint the W-decomposition tries to remove first.
    pub removal_order: RemovalOrder,
    /// How clusters are found.
    pub cluster_method: ClusterMethod,
    /// The most maximal rigid subsystem computations a W-decomposition may spend (each one
    /// elimination); past it, the subsystems not yet examined are reported as leaves and
    /// the statistics say the decomposition is incomplete.
    pub decomposition_budget: usize,
    /// Whether to analyse the drawing itself (its rank, singular position, residuals):
    /// [`Analysis::sketch`]. On by default.
    pub sketch: bool,
    /// Whether to decide global rigidity (the stress-matrix test) of the system and of each
    /// cluster that is a distance framework: [`Analysis::global_rigidity`]. On by default.
    pub global_rigidity: bool,
    /// Whether a 2D framework of points and distances between them is decided by the pebble
    /// game ([`RankMethod::PebbleGame`]: the generic rank, redundancies and clusters — the
    /// witness's at a generic witness — proven by Laman's theorem, without eliminating the
    /// Jacobian) with the exact and modp backends; with a W-decomposition, its cluster
    /// searches too (its boundaries are still chosen at the witness). On by default; off, the
    /// witness decides everything.
    pub pebble_game: bool,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        AnalysisOptions {
            backend: Backend::Exact,
            witness: WitnessOptions::default(),
            clusters: true,
            decompose: false,
            removal_order: RemovalOrder::default(),
            cluster_method: ClusterMethod::default(),
            decomposition_budget: 20_000,
            sketch: true,
            global_rigidity: true,
            pebble_game: true,
        }
    }
}

/// A constraint whose equations depend on equations of constraints before it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Redundancy {
    /// The constraint.
    pub constraint: ConstraintIdx,
    /// How many of its rows are dependent.
    pub rows: usize,
    /// Its DOC (`rows < doc`: partially redundant).
    pub doc: usize,
    /// The earlier constraints taking part in the dependency (the fundamental circuit minus
    /// the constraint itself), in file order. Deleting any one of them, or the constraint,
    /// removes this dependency.
    pub spanning_group: Vec<ConstraintIdx>,
}

/// The result of the witness analysis of one system (format §2).
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// The backend that decided the rank.
    pub backend: Backend,
    /// How the exact backend proved its rank (`None` for the others).
    pub proof: Option<Proof>,
    /// The witness.
    pub witness: Witness,
    /// At a modular witness ([`WitnessSource::Modular`]): a heuristic bound on the probability
    /// that its rank is not the generic rank ([`modular_error_bound`]); `None` otherwise.
    pub witness_error_bound: Option<f64>,
    /// The seed of the witness search.
    pub seed: u64,
    /// Columns of the Jacobian.
    pub unknowns: usize,
    /// Rows of the Jacobian, entity-internal rows included.
    pub equations: usize,
    /// Entity-internal rows among them (normalisations, Plücker relations).
    pub internal_equations: usize,
    /// Rank of the Jacobian at the witness.
    pub rank: usize,
    /// `unknowns − rank`.
    pub dof_absolute: usize,
    /// Dimension of the displacements admitted: `rank(T) − rank(J·T)`.
    pub trivial_motions: usize,
    /// `dof_absolute − trivial_motions`.
    pub dof: usize,
    /// Redundant constraints in file order.
    pub redundant: Vec<Redundancy>,
    /// The maximal rigid subsystems, sorted by first entity (file order).
    pub clusters: Vec<Cluster>,
    /// The arithmetic the clusters were decided in.
    pub clusters_arithmetic: Arithmetic,
    /// With [`AnalysisOptions::decompose`]: the W-decomposition of every cluster, in the order
    /// of `clusters`.
    pub decomposition: Option<Vec<DecompositionNode>>,
    /// Counters of the W-decomposition.
    pub decomposition_statistics: Option<Statistics>,
    /// With [`AnalysisOptions::decompose`]: each declared group ([`gcs_model::System::groups`]),
    /// rigid on its own constraints (a node of the DR-plan) or not, in their order.
    pub group_rigidity: Option<Vec<GroupRigidity>>,
    /// The drawing itself: its rank against the generic one, the dependencies at a singular
    /// position, whether it satisfies its constraints (`None` when some entity has no sketch
    /// position, or [`AnalysisOptions::sketch`] is off).
    pub sketch: Option<SketchAnalysis>,
    /// For the float backend, the constraints whose decision lies within the ambiguity band of
    /// the tolerance (see [`uncertain`]), in file order; `None` for the exact backends.
    pub uncertain: Option<Vec<ConstraintIdx>>,
    /// For the float backend, the rank by faer's column-pivoted QR (when the matrix is small
    /// enough to be made dense), as a cross-check of the incremental elimination.
    pub float_qr_rank: Option<usize>,
    /// Whether the dimensions determine the shape (global rigidity, by the stress-matrix test):
    /// `None` when the system is not a distance framework ([`crate::global`]) or
    /// [`AnalysisOptions::global_rigidity`] is off.
    pub global_rigidity: Option<GlobalRigidity>,
    /// The same for each cluster, in the order of `clusters`: `None` for a cluster that is not
    /// a distance framework (its own points and distances).
    pub cluster_global_rigidity: Vec<Option<GlobalRigidity>>,
    /// How the rank, the redundancies and the clusters were decided.
    pub rank_method: RankMethod,
}

impl Analysis {
    /// `dof == 0`.
    pub fn rigid(&self) -> bool {
        self.dof == 0
    }

    /// Rigid and without redundant constraints.
    pub fn well_constrained(&self) -> bool {
        self.rigid() && self.redundant.is_empty()
    }
}

/// Dense matrices up to this many entries get the faer QR cross-check.
const QR_LIMIT: usize = 1_000_000;

/// Analyses a system: finds a witness, assembles the Jacobian there in the chosen arithmetic,
/// inserts its rows in file order (entity-internal rows first) and reads off the rank, the
/// redundant constraints with their spanning groups, and the trivial motions.
///
/// # Errors
/// No witness ([`AnalysisError::Witness`]), a backend not compiled in, or an arithmetic
/// failure.
pub fn analyze(system: &System, options: &AnalysisOptions) -> Result<Analysis, AnalysisError> {
    if !options.backend.available() {
        return Err(AnalysisError::BackendUnavailable(options.backend.name()));
    }
    let layout = Layout::new(system);
    // A modular witness only serves the prime-field analyses; the others fall back on the
    // numerical projection (float) or refuse (rational: no exact witness).
    let modular = matches!(options.backend, Backend::Exact | Backend::ModP);
    let pebbles = pebble_framework(system, options);
    let witness_options = WitnessOptions {
        modular,
        generic_rank: pebbles.as_ref().map(|p| p.game.rank),
        ..options.witness.clone()
    };
    let witness = find_witness(system, &layout, &witness_options)?;
    if witness.source == WitnessSource::Approximate
        && !matches!(options.backend, Backend::Float { .. })
    {
        let why = witness.no_exact_witness.clone().unwrap_or(gcs_jacobian::NoWitness {
            sketch: witness.sketch_rejected.clone(),
            placement: None,
        });
        return Err(if modular {
            AnalysisError::NoModularWitness(why)
        } else {
            AnalysisError::ApproximateWitness(why)
        });
    }
    analyze_with(system, &layout, witness, options, pebbles)
}

/// A 2D framework of points and distances between distinct points, with nothing else, and its
/// pebble game: what [`RankMethod::PebbleGame`] decides (when the options allow it).
struct PebbleFramework {
    bars: Vec<(usize, usize)>,
    game: PebbleReport,
}

fn pebble_framework(system: &System, options: &AnalysisOptions) -> Option<PebbleFramework> {
    if !options.pebble_game
        || !matches!(options.backend, Backend::Exact | Backend::ModP)
        || system.dim() != Dim::Two
        || system.entities().iter().any(|e| e.kind() != EntityKind::Point)
    {
        return None;
    }
    // Every entity is a point: entity indices are vertex indices.
    let bars = system
        .constraints()
        .iter()
        .map(|c| match c.signature {
            Signature::Metric(Metric::DistancePointPoint(a, b)) if a != b => {
                Some((a.index(), b.index()))
            }
            _ => None,
        })
        .collect::<Option<Vec<_>>>()?;
    let game = pebble_game(system.entities().len(), &bars);
    Some(PebbleFramework { bars, game })
}

/// The outcome of the pebble game in the witness analysis's terms (one row per bar, no
/// entity-internal row), with the trivial motions at the witness; `None` when the witness's
/// equations are not one row per bar (then the witness decides).
fn pebble_outcome(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    backend: Backend,
    pebbles: &PebbleFramework,
) -> Result<Option<(Outcome, usize, usize)>, AnalysisError> {
    if layout.internal_rows() != 0
        || witness.plan.constraints.iter().any(|p| p.rows.len() != 1)
        || witness.source == WitnessSource::Modular
    {
        return Ok(None);
    }
    // Trivial motions, `rank(T) − rank(J·T)` at the witness: a distance is invariant under
    // every motion of the plane, so `J·T = 0`, and `T` (two translations and a rotation) has
    // rank 3 unless all the points are at one place, where the rotation moves them as a
    // translation does (rank 2; 0 without points).
    let coords = &witness.coords;
    let first = system.entity_indices().next().map(|e| &coords[layout.columns(e)]);
    let trivial = match first {
        None => 0,
        Some(p) if system.entity_indices().all(|e| &coords[layout.columns(e)] == p) => 2,
        Some(_) => 3,
    };
    let proof = (backend == Backend::Exact).then_some(Proof::PebbleGame);
    let n = pebbles.bars.len();
    Ok(Some((
        Outcome {
            rank: pebbles.game.rank,
            dependent: pebbles.game.circuits.clone(),
            trivial,
            proof,
            float_qr_rank: None,
            margins: Vec::new(),
            ambiguous_supports: Vec::new(),
        },
        n,
        0,
    )))
}

/// The pebble game's rigid components as clusters: their points in file order, and the
/// distances between two of them.
fn pebble_clusters(pebbles: &PebbleFramework) -> Vec<Cluster> {
    let components = &pebbles.game.components;
    // The components of each vertex (several at a hinge); each bar lies in exactly one.
    let mut member: Vec<Vec<usize>> = Vec::new();
    for (k, comp) in components.iter().enumerate() {
        for &v in comp {
            if member.len() <= v {
                member.resize(v + 1, Vec::new());
            }
            member[v].push(k);
        }
    }
    let mut constraints = vec![Vec::new(); components.len()];
    for (i, &(a, b)) in pebbles.bars.iter().enumerate() {
        let (ma, mb) = (&member[a], &member[b]);
        if let Some(k) = ma.iter().find(|k| mb.contains(k)) {
            constraints[*k].push(ConstraintIdx(i as u32));
        }
    }
    components
        .iter()
        .zip(constraints)
        .map(|(comp, constraints)| Cluster {
            entities: comp.iter().map(|&v| EntityIdx(v as u32)).collect(),
            constraints,
            grounded: false,
        })
        .collect()
}

/// The outcome of inserting the rows, in some field.
pub(crate) struct Outcome {
    pub(crate) rank: usize,
    /// Per row: `None` if independent, else the rows of its combination.
    pub(crate) dependent: Vec<Option<Vec<usize>>>,
    pub(crate) trivial: usize,
    pub(crate) proof: Option<Proof>,
    pub(crate) float_qr_rank: Option<usize>,
    /// Float path: the decision margin of every row ([`gcs_rank::Echelon::margin`]).
    pub(crate) margins: Vec<f64>,
    /// Float path: the dependent rows whose circuit has a coefficient near the noise cutoff.
    pub(crate) ambiguous_supports: Vec<usize>,
}

/// The support of each dependent row's combination. With a tolerance (float backend), the
/// coefficients below `√tolerance` times the largest are rounding noise, not part of the
/// circuit, and are dropped; the rows of those within [`AMBIGUITY_BAND`] of that cutoff, on
/// either side, are returned too (the dependent row, whose spanning group is uncertain).
fn supports<F: Field>(
    analysis: &RowAnalysis<F>,
    tolerance: Option<f64>,
) -> (Vec<Option<Vec<usize>>>, Vec<usize>) {
    let mut ambiguous = Vec::new();
    let dependent = analysis
        .outcomes
        .iter()
        .enumerate()
        .map(|(row, o)| match o {
            Insertion::Independent { .. } => None,
            Insertion::Dependent { combination } => Some(
                combination
                    .as_ref()
                    .map(|c| {
                        let max = c.iter().map(|(_, v)| v.magnitude()).fold(0.0, f64::max);
                        let floor = tolerance.map_or(0.0, |t| t.sqrt() * max);
                        let near =
                            |m: f64| m > floor / AMBIGUITY_BAND && m <= floor * AMBIGUITY_BAND;
                        if tolerance.is_some() && c.iter().any(|(_, v)| near(v.magnitude())) {
                            ambiguous.push(row);
                        }
                        c.iter().filter(|(_, v)| v.magnitude() > floor).map(|(i, _)| *i).collect()
                    })
                    .unwrap_or_default(),
            ),
        })
        .collect();
    (dependent, ambiguous)
}

/// The displacement generators as sparse rows.
fn generator_rows<F: Field>(generators: &[Vec<F>]) -> Vec<SparseRow<F>> {
    generators
        .iter()
        .map(|g| {
            SparseRow::from_entries(
                g.iter()
                    .enumerate()
                    .filter(|(_, v)| !v.is_zero())
                    .map(|(i, v)| (i, v.clone()))
                    .collect(),
            )
        })
        .collect()
}

/// The rows of `J·T`: each Jacobian row applied to the `k` generators. With a tolerance
/// (float), a product below `tolerance · Σ|row entries| · max|generator entries|` is rounding
/// noise and is dropped: a row invariant under a displacement gives exactly 0 over ℚ, and in
/// floating point either a cancellation or a displacement of something the witness has at a
/// distance from the origin that is itself noise (a fixed point drawn at the origin, which a
/// numerical projection leaves 1e-13 away).
fn jt_rows<'j, F: Field>(
    jacobian: &'j Jacobian<F>,
    generators: &'j [Vec<F>],
    tolerance: Option<f64>,
) -> impl Iterator<Item = SparseRow<F>> + 'j {
    let largest: Vec<f64> = match tolerance {
        Some(_) => {
            generators.iter().map(|g| g.iter().map(F::magnitude).fold(0.0, f64::max)).collect()
        }
        None => Vec::new(),
    };
    jacobian.rows.iter().map(move |row| {
        SparseRow::from_entries(
            (0..generators.len())
                .filter_map(|j| {
                    let v = row.dot_dense(&generators[j]);
                    if v.is_zero() {
                        return None;
                    }
                    if let Some(t) = tolerance {
                        let size: f64 = row.entries().iter().map(|(_, a)| a.magnitude()).sum();
                        if v.magnitude() <= t * size * largest[j] {
                            return None;
                        }
                    }
                    Some((j, v))
                })
                .collect(),
        )
    })
}

/// `rank(T) − rank(J·T)` in the field `F` with the given options.
fn trivial_motions<F: Field>(
    jacobian: &Jacobian<F>,
    generators: &[Vec<F>],
    options: EchelonOptions,
) -> usize {
    let k = generators.len();
    let t_rows = generator_rows(generators);
    let rank_t = analyse_rows(jacobian.ncols, t_rows, options.clone()).rank;
    let jt = jt_rows(jacobian, generators, options.tolerance);
    let mut e = Echelon::new(k, options);
    for r in jt {
        if e.rank() == k {
            break;
        }
        e.insert(r);
    }
    rank_t.saturating_sub(e.rank())
}

fn generic<F: Field>(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    options: EchelonOptions,
) -> Result<(Outcome, usize, usize), AnalysisError> {
    let jacobian: Jacobian<F> = witness.jacobian(system, layout)?;
    let generators = motions::generators::<F>(system, layout, &witness.coords_in()?)?;
    let trivial = trivial_motions(&jacobian, &generators, options.clone());
    let options_tolerance = options.tolerance;
    let n = jacobian.rows.len();
    let internal = jacobian.internal_count();
    // Floats in the reduced form with the tolerance; exact fields in plain row echelon form.
    if options_tolerance.is_some() {
        // The float path always tracks combinations: the margin of an independent row needs
        // the amplification of its reduction ([`Echelon::margin`]), which is what tells a
        // real remainder from cancellation noise.
        let (analysis, margins) =
            analyse_rows_with_margins(jacobian.ncols, jacobian.rows.iter().cloned(), options);
        let (dependent, ambiguous_supports) = supports(&analysis, options_tolerance);
        return Ok((
            Outcome {
                rank: analysis.rank,
                dependent,
                trivial,
                proof: None,
                float_qr_rank: None,
                margins,
                ambiguous_supports,
            },
            n,
            internal,
        ));
    }
    // Exact fields: plain row echelon form, dependencies by backward substitution through the
    // multipliers (the reduced form's tracked combinations fill in to the dense inverse).
    let analysis = analyse_rows_plain(jacobian.ncols, jacobian.rows.iter().cloned());
    Ok((
        Outcome {
            rank: analysis.rank,
            dependent: supports(&analysis, options_tolerance).0,
            trivial,
            proof: None,
            float_qr_rank: None,
            margins: Vec::new(),
            ambiguous_supports: Vec::new(),
        },
        n,
        internal,
    ))
}

/// The rank, the outcome of every row and the trivial motions at `witness` (any
/// configuration with its plan) in the backend's arithmetic; with the number of rows and of
/// entity-internal rows.
pub(crate) fn rank_at(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    backend: Backend,
) -> Result<(Outcome, usize, usize), AnalysisError> {
    let tracked = EchelonOptions::tracked();
    Ok(match backend {
        Backend::Exact => {
            // Assembled in `Rat` (machine words while the numbers are small: a sketch's
            // decimal coordinates), handed to the certificate as `BigRational`s.
            let small: Jacobian<Rat> = witness.jacobian(system, layout)?;
            let small_generators =
                motions::generators::<Rat>(system, layout, &witness.coords_in()?)?;
            // Trivial motions, exactly: T and J·T have at most six columns.
            let trivial = exact_trivial_motions(&small, &small_generators)?;
            let big = |v: &Vec<Rat>| v.iter().map(BigRational::from).collect::<Vec<_>>();
            let rows = small.rows.iter().map(to_big).collect::<Result<Vec<_>, _>>()?;
            // The displacements prove the dependencies of rigid circuits without lifting their
            // coefficients (thousands of digits at a sketch with decimal coordinates).
            let hint = KernelHint {
                vectors: small_generators.iter().map(big).collect(),
                groups: (0..layout.ncols()).map(|c| layout.owner(c).index()).collect(),
                free_rows: small.internal_count(),
            };
            let certified = certify_rows(small.ncols, &rows, Some(&hint))?;
            let n = small.rows.len();
            let internal = small.internal_count();
            (
                Outcome {
                    rank: certified.rank,
                    dependent: certified.circuits,
                    trivial,
                    proof: Some(certified.proof),
                    float_qr_rank: None,
                    margins: Vec::new(),
                    ambiguous_supports: Vec::new(),
                },
                n,
                internal,
            )
        }
        Backend::Rational => generic::<BigRational>(system, layout, witness, tracked)?,
        // Inside the `with_modulus` of a modular witness over another prime: ModQ.
        Backend::ModP if gcs_rank::modulus() != ModP::PRIME => {
            generic::<ModQ>(system, layout, witness, tracked)?
        }
        Backend::ModP => generic::<ModP>(system, layout, witness, tracked)?,
        Backend::Rug => rug_backend(system, layout, witness)?,
        Backend::Float { tolerance } => {
            let (mut outcome, n, internal) =
                generic::<f64>(system, layout, witness, EchelonOptions::float(tolerance))?;
            let jacobian: Jacobian<f64> = witness.jacobian(system, layout)?;
            if jacobian.ncols.saturating_mul(jacobian.rows.len()) <= QR_LIMIT {
                // Rows scaled to a largest entry of 1 first: the QR threshold is relative to
                // |R₀₀|, and constraint rows differ in scale by orders of magnitude.
                let scaled: Vec<SparseRow<f64>> = jacobian
                    .rows
                    .iter()
                    .map(|r| {
                        let m = r.entries().iter().map(|(_, v)| v.abs()).fold(0.0, f64::max);
                        if m > 0.0 { r.scaled(&(1.0 / m)) } else { r.clone() }
                    })
                    .collect();
                outcome.float_qr_rank = Some(float_rank_qr(jacobian.ncols, &scaled, tolerance));
            }
            (outcome, n, internal)
        }
    })
}

/// The constraints with dependent rows, in file order, each with the earlier constraints of
/// its circuits (entity-internal rows left out).
pub(crate) fn redundancies(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    outcome: &Outcome,
) -> Vec<Redundancy> {
    // Owners do not depend on the field: derived from the plan directly.
    let owners = row_owners(system, layout, witness);
    let mut redundant: Vec<Redundancy> = Vec::new();
    for (row, dep) in outcome.dependent.iter().enumerate() {
        let Some(support) = dep else { continue };
        let RowOwner::Constraint(c) = owners[row] else { continue };
        let group = support.iter().filter_map(|&i| match owners[i] {
            RowOwner::Constraint(d) if d != c => Some(d),
            _ => None,
        });
        match redundant.last_mut() {
            Some(r) if r.constraint == c => {
                r.rows += 1;
                r.spanning_group.extend(group);
            }
            _ => redundant.push(Redundancy {
                constraint: c,
                rows: 1,
                doc: system.constraint(c).doc,
                spanning_group: group.collect(),
            }),
        }
    }
    for r in &mut redundant {
        r.spanning_group.sort();
        r.spanning_group.dedup();
    }
    redundant
}

/// A bound on the probability that a random point of the constraints' solution set modulo the
/// witness's prime `p` (`2^61 − 1`, another of [`gcs_rank::WITNESS_PRIMES`], or
/// [`gcs_rank::TURN_PRIME`]) has a rank below the generic rank `r`: it must then lie on the
/// hypersurface where the `r × r` minors vanish, a polynomial of degree at most `3r` in the
/// coordinates (each Jacobian entry has degree at most 3), which a uniformly random point hits
/// with probability at most `3r / p` (Schwartz–Zippel). Heuristic: the witness's coordinates
/// are built from uniformly random choices, not drawn uniformly themselves.
pub fn modular_error_bound(rank: usize) -> f64 {
    // (The witness's prime: inside its `with_modulus`, the current one.)
    3.0 * rank.max(1) as f64 / gcs_rank::modulus() as f64
}

/// The constraints a float analysis is not sure of: those whose dependent/independent decision
/// has a margin below [`AMBIGUITY_BAND`] ([`gcs_rank::Echelon::margin`]: a tolerance within that
/// factor could have decided otherwise, or an independent remainder is small against what
/// rounding can leave behind), those whose spanning group has a coefficient near the noise
/// cutoff, and, when the rank contradicts the counts — more than the unknowns minus the trivial
/// motions, or other than the column-pivoted QR's — as many of the least certain decisions as
/// the contradiction needs.
fn uncertain(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    outcome: &Outcome,
) -> Vec<ConstraintIdx> {
    let owners = row_owners(system, layout, witness);
    let constraint = |row: usize| match owners.get(row) {
        Some(RowOwner::Constraint(c)) => Some(*c),
        _ => None,
    };
    let mut out: Vec<ConstraintIdx> = Vec::new();
    for (row, m) in outcome.margins.iter().enumerate() {
        if *m < AMBIGUITY_BAND {
            out.extend(constraint(row));
        }
    }
    out.extend(outcome.ambiguous_supports.iter().filter_map(|r| constraint(*r)));
    // Contradictions with the counts: the least certain decisions of the kind in excess.
    let least = |independent: bool, count: usize, out: &mut Vec<ConstraintIdx>| {
        let mut rows: Vec<(f64, usize)> = outcome
            .margins
            .iter()
            .enumerate()
            .filter(|(row, _)| {
                outcome.dependent.get(*row).is_some_and(|d| d.is_none() == independent)
            })
            .map(|(row, m)| (*m, row))
            .collect();
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        out.extend(rows.iter().take(count).filter_map(|(_, r)| constraint(*r)));
    };
    let excess = (outcome.rank + outcome.trivial).saturating_sub(layout.ncols());
    least(true, excess, &mut out);
    if let Some(q) = outcome.float_qr_rank {
        least(true, outcome.rank.saturating_sub(q), &mut out);
        least(false, q.saturating_sub(outcome.rank), &mut out);
    }
    out.sort();
    out.dedup();
    out
}

/// The analysis at a given witness.
///
/// # Errors
/// As [`analyze`].
pub fn analyze_at(
    system: &System,
    layout: &Layout,
    witness: Witness,
    options: &AnalysisOptions,
) -> Result<Analysis, AnalysisError> {
    // A modular witness over another prime than ModP's is analysed modulo that prime: ModQ,
    // inside its `with_modulus` (nothing but plain numbers comes out).
    match witness.modulus {
        Some(q) if witness.source == WitnessSource::Modular && q != ModP::PRIME => {
            gcs_rank::with_modulus(q, || analyze_in_field(system, layout, witness, options, None))
        }
        _ => analyze_in_field(system, layout, witness, options, None),
    }
}

/// [`analyze_at`] with the pebble game already played (by [`analyze`]).
fn analyze_with(
    system: &System,
    layout: &Layout,
    witness: Witness,
    options: &AnalysisOptions,
    pebbles: Option<PebbleFramework>,
) -> Result<Analysis, AnalysisError> {
    match (pebbles, witness.source) {
        (Some(p), source) if source != WitnessSource::Modular => {
            analyze_in_field(system, layout, witness, options, Some(&p))
        }
        _ => analyze_at(system, layout, witness, options),
    }
}

/// [`analyze_at`] in the witness's field.
fn analyze_in_field(
    system: &System,
    layout: &Layout,
    witness: Witness,
    options: &AnalysisOptions,
    pebbles: Option<&PebbleFramework>,
) -> Result<Analysis, AnalysisError> {
    // At a modular witness everything is decided modulo the prime (the exact backend cannot
    // certify over ℚ at a point that is not rational).
    let modular = witness.source == WitnessSource::Modular;
    let backend = if modular { Backend::ModP } else { options.backend };
    let fast = match pebbles {
        Some(p) => pebble_outcome(system, layout, &witness, backend, p)?.map(|o| (o, p)),
        None => None,
    };
    let ((outcome, equations, internal), pebbles) = match fast {
        Some((o, p)) => (o, Some(p)),
        None => (rank_at(system, layout, &witness, backend)?, None),
    };
    let redundant = redundancies(system, layout, &witness, &outcome);
    let uncertain = match options.backend {
        Backend::Float { .. } => Some(uncertain(system, layout, &witness, &outcome)),
        Backend::Exact | Backend::Rational | Backend::Rug | Backend::ModP => None,
    };
    let generic_dof = layout.ncols().saturating_sub(outcome.rank).saturating_sub(outcome.trivial);
    let sketch = if options.sketch {
        crate::sketch::analyse(
            system,
            layout,
            &witness,
            options.backend,
            &outcome,
            &redundant,
            generic_dof,
        )?
    } else {
        None
    };
    let cluster_options = ClusterOptions {
        method: options.cluster_method,
        decompose: options.decompose,
        removal_order: options.removal_order,
        decomposition_budget: options.decomposition_budget,
        // (The game decides the cluster searches where it decides the rank.)
        pebble_game: pebbles.is_some(),
    };
    let in_field = |arithmetic: Arithmetic| -> Result<ClusterResult, AnalysisError> {
        let exact = EchelonOptions::default();
        Ok(match arithmetic {
            // (Combinatorial clusters come from the pebble game, never from here.)
            Arithmetic::None | Arithmetic::Combinatorial => (Vec::new(), None),
            Arithmetic::Float { tolerance } => clusters_in::<f64>(
                system,
                layout,
                &witness,
                EchelonOptions::float(tolerance),
                &cluster_options,
            )?,
            Arithmetic::Rational => {
                clusters_in::<Rat>(system, layout, &witness, exact, &cluster_options)?
            }
            Arithmetic::ModP if gcs_rank::modulus() != ModP::PRIME => {
                clusters_in::<ModQ>(system, layout, &witness, exact, &cluster_options)?
            }
            Arithmetic::ModP => {
                clusters_in::<ModP>(system, layout, &witness, exact, &cluster_options)?
            }
        })
    };
    let clusters_arithmetic = match backend {
        _ if !options.clusters => Arithmetic::None,
        _ if pebbles.is_some() => Arithmetic::Combinatorial,
        Backend::Float { tolerance } => Arithmetic::Float { tolerance },
        // Exact rationals (with a machine-word fast path) for the rational backends, and for
        // the exact one on systems small enough that rational fill-in stays cheap.
        Backend::Rational | Backend::Rug => Arithmetic::Rational,
        Backend::Exact if layout.ncols() <= EXACT_CLUSTER_LIMIT && !options.decompose => {
            Arithmetic::Rational
        }
        Backend::Exact | Backend::ModP => Arithmetic::ModP,
    };
    let (clusters, decomposition) = match (clusters_arithmetic, pebbles) {
        (Arithmetic::Combinatorial, Some(p)) if !options.decompose => (pebble_clusters(p), None),
        // The W-decomposition's cluster searches play the pebble game themselves (bar
        // frameworks all the way down); its boundaries are chosen at the witness.
        (Arithmetic::Combinatorial, Some(_)) => in_field(Arithmetic::ModP)?,
        _ => in_field(clusters_arithmetic)?,
    };
    let (decomposition, decomposition_statistics, group_rigidity) = match decomposition {
        Some((d, s, g)) => (Some(d), Some(s), Some(g)),
        None => (None, None, None),
    };
    let seed = options.witness.seed;
    let (global_rigidity, cluster_global_rigidity) = if options.global_rigidity {
        // With the pebble game, Jackson and Jordán's necessary condition (redundant rigidity)
        // decides the common *no* without the stress test.
        let in_circuit = pebbles.map(|p| p.game.in_circuit());
        let whole = match (pebbles, &in_circuit) {
            (Some(p), Some(inside)) => global::not_redundantly_rigid(
                system.entities().len(),
                p.bars.len(),
                p.game.dof(system.entities().len()) == 0,
                inside.iter().filter(|b| !**b).count(),
            ),
            _ => None,
        }
        .or_else(|| global::model(system, layout, &witness, backend, seed));
        let decided = |k: usize| {
            let c = &clusters[k];
            // The whole system as one cluster: its answer is the model's.
            if c.entities.len() == system.entities().len()
                && c.constraints.len() == system.constraints().len()
                && whole.is_some()
            {
                return whole.clone();
            }
            let inside = in_circuit.as_ref()?;
            let coloops = c.constraints.iter().filter(|b| !inside[b.index()]).count();
            // A cluster is rigid by definition.
            global::not_redundantly_rigid(c.entities.len(), c.constraints.len(), true, coloops)
        };
        let each = global::clusters(system, layout, &witness, backend, seed, &clusters, decided);
        (whole, each)
    } else {
        (None, vec![None; clusters.len()])
    };
    let unknowns = layout.ncols();
    let dof_absolute = unknowns - outcome.rank;
    Ok(Analysis {
        backend: options.backend,
        proof: outcome.proof,
        // (Not for a witness whose turns were taken from the drawing and not all held by the
        // constraints: its coordinates are not all random choices.)
        witness_error_bound: (modular && witness.genericity_tested)
            .then(|| modular_error_bound(outcome.rank)),
        seed: options.witness.seed,
        witness,
        unknowns,
        equations,
        internal_equations: internal,
        rank: outcome.rank,
        dof_absolute,
        trivial_motions: outcome.trivial,
        dof: dof_absolute.saturating_sub(outcome.trivial),
        redundant,
        clusters,
        clusters_arithmetic,
        decomposition,
        decomposition_statistics,
        group_rigidity,
        float_qr_rank: outcome.float_qr_rank,
        sketch,
        uncertain,
        global_rigidity,
        cluster_global_rigidity,
        rank_method: if pebbles.is_some() { RankMethod::PebbleGame } else { RankMethod::Witness },
    })
}

/// Systems with at most this many unknowns get their clusters decided over ℚ by the exact
/// backend; larger ones (and W-decompositions, which compute clusters many times) modulo the
/// 61-bit prime — exact with overwhelming probability; the rank stays proven either way.
const EXACT_CLUSTER_LIMIT: usize = 64;

fn row_owners(system: &System, layout: &Layout, witness: &Witness) -> Vec<RowOwner> {
    let mut owners = Vec::new();
    for e in system.entity_indices() {
        if let Some(r) = layout.repr(e) {
            owners.extend(std::iter::repeat_n(RowOwner::Internal(e), r.internal_rows()));
        }
    }
    for (c, p) in system.constraint_indices().zip(&witness.plan.constraints) {
        owners.extend(std::iter::repeat_n(RowOwner::Constraint(c), p.rows.len()));
    }
    owners
}

/// A row of [`Rat`]s as [`BigRational`]s (the certificate's type).
fn to_big(row: &SparseRow<Rat>) -> Result<SparseRow<BigRational>, gcs_rank::RankError> {
    row.map(|x| Ok(BigRational::from(x)))
}

/// `rank(T) − rank(J·T)` over ℚ, proven by the certified exact path.
fn exact_trivial_motions(
    jacobian: &Jacobian<Rat>,
    generators: &[Vec<Rat>],
) -> Result<usize, AnalysisError> {
    let k = generators.len();
    let t_rows = generator_rows(generators).iter().map(to_big).collect::<Result<Vec<_>, _>>()?;
    let (t, _) = analyse_rows_exact(jacobian.ncols, &t_rows, false)?;
    let jt = jt_rows(jacobian, generators, None)
        .filter(|r| !r.is_zero())
        .map(|r| to_big(&r))
        .collect::<Result<Vec<_>, _>>()?;
    let (jt, _) = analyse_rows_exact(k, &jt, false)?;
    Ok(t.rank - jt.rank)
}

#[cfg(feature = "rug")]
fn rug_backend(
    system: &System,
    layout: &Layout,
    witness: &Witness,
) -> Result<(Outcome, usize, usize), AnalysisError> {
    generic::<rug::Rational>(system, layout, witness, EchelonOptions::tracked())
}

#[cfg(not(feature = "rug"))]
fn rug_backend(
    _system: &System,
    _layout: &Layout,
    _witness: &Witness,
) -> Result<(Outcome, usize, usize), AnalysisError> {
    Err(AnalysisError::BackendUnavailable("rug"))
}

/// Witness errors surface as analysis errors.
impl From<JacobianError> for AnalysisError {
    fn from(e: JacobianError) -> Self {
        AnalysisError::Witness(e)
    }
}
