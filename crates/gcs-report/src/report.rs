//! The report of `gcs analyze` (format §2, with the sections of §3 and the fields of §4) as
//! data — [`Report`], serialisable both ways, with typed enums — and as text for people
//! ([`text`]).

use gcs_analysis::{
    Analysis, Arithmetic, Backend, GlobalRigidity, Position, RankMethod, Redundancy, SketchAnalysis,
};
use gcs_jacobian::WitnessSource;
use gcs_model::{ConstraintIdx, System};
use gcs_rank::Proof;
use gcs_solve::{Solution, Status as SolveStatus};
use num_traits::ToPrimitive;
use serde::{Deserialize, Serialize};

use crate::clusters::{self, ClusterReport, NodeReport};
use crate::structural::{self, Structural, StructuralReport};

/// The version of the report format (format §2, `schema`).
pub const SCHEMA: u32 = 1;

/// The arithmetic a rank was decided in (`backend`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BackendName {
    /// Proven over ℚ.
    Exact,
    /// `num-rational`.
    Rational,
    /// GMP.
    Rug,
    /// Modulo 2^61 − 1.
    Modp,
    /// `f64` with a tolerance.
    Float,
}

impl From<Backend> for BackendName {
    fn from(b: Backend) -> Self {
        match b {
            Backend::Exact => BackendName::Exact,
            Backend::Rational => BackendName::Rational,
            Backend::Rug => BackendName::Rug,
            Backend::ModP => BackendName::Modp,
            Backend::Float { .. } => BackendName::Float,
        }
    }
}

/// Where the witness came from (`witness`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum WitnessName {
    /// The sketch, exact and generic.
    Sketch,
    /// The sketch moved off a special position.
    Perturbed,
    /// Constructed from the seed.
    Generated,
    /// Constructed modulo the prime (no rational witness exists near the drawing).
    Modular,
    /// A numerical projection (float only).
    Approximate,
}

impl From<WitnessSource> for WitnessName {
    fn from(w: WitnessSource) -> Self {
        match w {
            WitnessSource::Sketch => WitnessName::Sketch,
            WitnessSource::Perturbed => WitnessName::Perturbed,
            WitnessSource::Generated => WitnessName::Generated,
            WitnessSource::Modular => WitnessName::Modular,
            WitnessSource::Approximate => WitnessName::Approximate,
        }
    }
}

/// How the exact backend proved its rank (`proof`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ProofName {
    /// Every dependency lifted modulo one prime and checked.
    Modular,
    /// Some lifted through several primes.
    Multimodular,
    /// Some proven by exact kernel vectors (the displacements).
    Kernel,
    /// Rational elimination.
    Rational,
    /// The pebble game of a 2D bar framework (Laman's theorem): no arithmetic.
    #[serde(rename = "pebble game")]
    PebbleGame,
}

impl From<&Proof> for ProofName {
    fn from(p: &Proof) -> Self {
        match p {
            Proof::Rational => ProofName::Rational,
            Proof::ModularCertified { .. } => ProofName::Modular,
            Proof::MultiModularCertified { .. } => ProofName::Multimodular,
            Proof::KernelCertified { .. } => ProofName::Kernel,
            Proof::PebbleGame => ProofName::PebbleGame,
        }
    }
}

/// The arithmetic the clusters were decided in (`clusters_arithmetic`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ArithmeticName {
    /// Exact rationals.
    Rational,
    /// Modulo the prime.
    Modp,
    /// `f64`.
    Float,
    /// No arithmetic: the pebble game.
    Combinatorial,
    /// Not computed.
    None,
}

/// How the rank, the redundancies and the clusters were decided (`rank_method`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum RankMethodName {
    /// At a generic witness.
    #[default]
    #[serde(rename = "witness")]
    Witness,
    /// By the (2,3) pebble game (2D frameworks of points and distances).
    #[serde(rename = "pebble game")]
    PebbleGame,
}

impl From<RankMethod> for RankMethodName {
    fn from(m: RankMethod) -> Self {
        match m {
            RankMethod::Witness => RankMethodName::Witness,
            RankMethod::PebbleGame => RankMethodName::PebbleGame,
        }
    }
}

impl From<Arithmetic> for ArithmeticName {
    fn from(a: Arithmetic) -> Self {
        match a {
            Arithmetic::Rational => ArithmeticName::Rational,
            Arithmetic::ModP => ArithmeticName::Modp,
            Arithmetic::Float { .. } => ArithmeticName::Float,
            Arithmetic::Combinatorial => ArithmeticName::Combinatorial,
            Arithmetic::None => ArithmeticName::None,
        }
    }
}

/// A redundant constraint (format §2, `redundant`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RedundantReport {
    /// Its id.
    pub constraint: String,
    /// How many of its equations are dependent.
    pub rows: usize,
    /// Its DOC.
    pub doc: usize,
    /// The earlier constraints it is redundant with.
    pub spanning_group: Vec<String>,
    /// Whether it contradicts its spanning group at the user's values: measured at the
    /// solution of the model without its redundant constraints (`gcs solve`'s). Absent when
    /// the model was not solved (too large, or the solver did not converge) and for a
    /// constraint only some of whose equations are dependent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub conflicting: Option<bool>,
    /// With `conflicting`: its residual at that solution (for a dimension, the measure minus
    /// the value, in model units or degrees; for a parameter-free constraint, its largest
    /// polynomial residual).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
    /// With `conflicting`: how large the residual may be and the constraint still agree (the
    /// written precision of the values in its dependency, plus the solver's tolerance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub allowance: Option<f64>,
}

/// One model's report (format §2–§4), in the order of its fields in the JSON line. Optional
/// fields are left out of the JSON when absent.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The model's name.
    pub model: String,
    /// The file, as given.
    pub file: String,
    /// 2 or 3.
    pub dim: usize,
    /// The arithmetic of the rank.
    pub backend: BackendName,
    /// Where the witness came from.
    pub witness: WitnessName,
    /// Number of entities.
    pub entities: usize,
    /// Number of constraints.
    pub constraints: usize,
    /// Number of orientation conditions (`Orientation` in the constraints list): navigation
    /// constraints, inequalities that prune realizations and remove no DOF — not counted in
    /// `constraints`, `equations` or the DOF. Absent when there are none.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub orientations: usize,
    /// The reference (driven) dimensions, measured at the drawing: no equations, not counted in
    /// `constraints`. Absent when there are none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub measured: Vec<crate::measured::MeasuredReport>,
    /// Columns of the Jacobian.
    pub unknowns: usize,
    /// Rows of the Jacobian (entity-internal rows included).
    pub equations: usize,
    /// Rank at the witness.
    pub rank: usize,
    /// `unknowns − rank`.
    pub dof_absolute: usize,
    /// Displacements admitted.
    pub trivial_motions: usize,
    /// Internal DOF.
    pub dof: usize,
    /// `dof == 0`.
    pub rigid: bool,
    /// Rigid without redundancy.
    pub well_constrained: bool,
    /// Whether the dimensions determine the shape up to moving and mirroring the whole (global
    /// rigidity); absent for a model that is not a 2D or 3D distance framework.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub globally_rigid: Option<bool>,
    /// The test that decided `globally_rigid`: `stress matrix` (or `Jackson–Jordán`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub method: Option<String>,
    /// How `globally_rigid` was decided, in detail.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub global_rigidity: Option<GlobalRigidityReport>,
    /// Redundant constraints in file order.
    pub redundant: Vec<RedundantReport>,
    /// The maximal rigid subsystems.
    pub clusters: Vec<ClusterReport>,
    /// With `--decompose`: one tree per cluster.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decomposition: Option<Vec<NodeReport>>,
    /// With `--decompose`: `false` when the work budget ran out.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub decomposition_complete: Option<bool>,
    /// With `--decompose`, for a model with declared groups: each group, rigid on its own
    /// constraints (then a node of the DR-plan) or not (extension; absent otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub groups: Option<Vec<clusters::GroupReport>>,
    /// The seed of the witness search.
    pub seed: u64,
    /// The float backend's tolerance.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// How the exact backend proved its rank.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub proof: Option<ProofName>,
    /// How the rank, the redundancies and the clusters were decided: `witness` or `pebble
    /// game`.
    #[serde(default)]
    pub rank_method: RankMethodName,
    /// Entity-internal rows among `equations`.
    pub internal_equations: usize,
    /// The float backend's rank by column-pivoted QR (a cross-check).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub float_qr_rank: Option<usize>,
    /// With `--structural`: the counting methods (§3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub structural: Option<StructuralReport>,
    /// The arithmetic the clusters were decided in.
    pub clusters_arithmetic: ArithmeticName,
    /// The drawing itself (absent when some entity has no sketch position).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sketch: Option<SketchReport>,
    /// At a modular witness: the (heuristic) probability bound of a rank below the generic
    /// one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub witness_error_bound: Option<f64>,
    /// At a modular witness: the prime its coordinates are residues modulo (`2^61 − 1`, or
    /// another of the witness primes when the sketch's shape needs a square root that is none
    /// modulo `2^61 − 1`: √3 for an equilateral triangle).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub witness_prime: Option<u64>,
    /// At a modular witness modulo the turn prime (the last resort): the `N` of each turn by
    /// `k/N` of a full turn that the placement took from the drawing, ascending (a regular
    /// hexagon's vertices, turned from placed ones by 60° or 120°: `[3, 6]`). Absent
    /// otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub witness_turns: Vec<u32>,
    /// The float backend's constraints whose decision lies within the ambiguity band of its
    /// tolerance (only with `--backend float`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uncertain: Option<Vec<String>>,
    /// For a model read from a CAD file: `complete_import`, `skipped` and the rest of the
    /// import section (flattened into the line).
    #[serde(default, flatten, skip_serializing_if = "Option::is_none")]
    pub import: Option<crate::ImportReport>,
}

/// The details of the global rigidity test (`global_rigidity`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GlobalRigidityReport {
    /// `modp` (a yes proven) or `float` (approximate).
    pub arithmetic: ArithmeticName,
    /// Vertices of the framework (coincident points merged).
    pub points: usize,
    /// Its distances.
    pub bars: usize,
    /// Whether the framework is rigid.
    pub rigid: bool,
    /// The rank of the random stress matrix (0 when not formed).
    pub stress_rank: usize,
    /// Bars the random stress leaves at zero: not redundant, so not globally rigid, decided
    /// without the stress matrix (Hendrickson).
    #[serde(default)]
    pub unstressed_bars: usize,
    /// The rank that proves global rigidity: `n − d − 1`.
    pub target_rank: usize,
    /// `witness` or `random`: the configuration the answer was decided at (`none` when the
    /// pebble game decided it, without one).
    pub configuration: String,
    /// For a no modulo p: the probability bound that it is wrong (Schwartz–Zippel).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error_bound: Option<f64>,
}

impl From<&GlobalRigidity> for GlobalRigidityReport {
    fn from(g: &GlobalRigidity) -> Self {
        GlobalRigidityReport {
            arithmetic: g.arithmetic.into(),
            points: g.points,
            bars: g.bars,
            rigid: g.rigid,
            stress_rank: g.stress_rank,
            unstressed_bars: g.unstressed_bars,
            target_rank: g.target_rank,
            configuration: match (g.arithmetic, g.random_configuration) {
                (Arithmetic::Combinatorial, _) => "none",
                (_, true) => "random",
                (_, false) => "witness",
            }
            .to_owned(),
            error_bound: g.error_bound,
        }
    }
}

/// A constraint far from what its drawing shows (`sketch.largest_residual`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ResidualReport {
    /// Its id.
    pub constraint: String,
    /// For a dimension, its measure on the drawing minus its value (model units or degrees);
    /// for another constraint, how far the drawing is from satisfying it to first order.
    pub value: f64,
}

/// A special position recognised in the drawing (`sketch.configurations`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConfigurationReport {
    /// `coincident`, `collinear`, `coplanar`, `parallel` or `concurrent`.
    pub kind: String,
    /// The entities in that position.
    pub entities: Vec<String>,
    /// The distances whose lines are in it (concurrent bars).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub constraints: Vec<String>,
}

/// The drawing itself (format §4, `sketch`): its rank against the generic one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SketchReport {
    /// The rank of the Jacobian at the sketch's own coordinates.
    pub rank: usize,
    /// Below the generic rank: the drawing is at a special position.
    pub singular: bool,
    /// The constraints independent generically but dependent at the drawing, in file order,
    /// with their spanning groups there.
    pub dependent: Vec<RedundantReport>,
    /// The infinitesimal motions the drawing admits beyond the generic ones.
    pub extra_motions: usize,
    /// Whether the drawing satisfies its constraints (dimensions to the precision they are
    /// written with).
    pub satisfied: bool,
    /// When it does not: the constraint it is farthest from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub largest_residual: Option<ResidualReport>,
    /// The special positions recognised among the entities of the dependent constraints.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub configurations: Vec<ConfigurationReport>,
    /// How the exact backend proved the rank at the drawing (when it is not the witness).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub proof: Option<ProofName>,
}

impl SketchReport {
    fn new(system: &System, s: &SketchAnalysis) -> SketchReport {
        let id = |c: ConstraintIdx| system.constraint(c).id.clone();
        SketchReport {
            rank: s.rank,
            singular: s.singular,
            dependent: s.dependent.iter().map(|r| redundant_report(system, r)).collect(),
            extra_motions: s.extra_motions,
            satisfied: s.satisfied,
            largest_residual: s
                .largest_residual
                .as_ref()
                .map(|r| ResidualReport { constraint: id(r.constraint), value: r.value }),
            configurations: s
                .configurations
                .iter()
                .map(|c| ConfigurationReport {
                    kind: c.position.name().to_owned(),
                    entities: c.entities.iter().map(|e| system.entity(*e).id.clone()).collect(),
                    constraints: c.constraints.iter().map(|k| id(*k)).collect(),
                })
                .collect(),
            proof: s.proof.as_ref().map(ProofName::from),
        }
    }
}

fn redundant_report(system: &System, r: &Redundancy) -> RedundantReport {
    let id = |c: ConstraintIdx| system.constraint(c).id.clone();
    RedundantReport {
        constraint: id(r.constraint),
        rows: r.rows,
        doc: r.doc,
        spanning_group: r.spanning_group.iter().map(|c| id(*c)).collect(),
        conflicting: None,
        residual: None,
        allowance: None,
    }
}

impl Report {
    /// The report of one model: `file` is the path as given; `structural` adds §3's section.
    pub fn new(system: &System, file: &str, a: &Analysis, s: Option<&Structural>) -> Report {
        Report {
            schema: SCHEMA,
            model: system.name().to_owned(),
            file: file.to_owned(),
            dim: system.dim().coords(),
            backend: a.backend.into(),
            witness: a.witness.source.into(),
            entities: system.written_entities(),
            constraints: system.written_constraints(),
            orientations: system.orientations().len(),
            measured: crate::measured::at_drawing(system),
            unknowns: a.unknowns,
            equations: a.equations,
            rank: a.rank,
            dof_absolute: a.dof_absolute,
            trivial_motions: a.trivial_motions,
            dof: a.dof,
            rigid: a.rigid(),
            well_constrained: a.well_constrained(),
            redundant: a.redundant.iter().map(|r| redundant_report(system, r)).collect(),
            globally_rigid: a.global_rigidity.as_ref().map(|g| g.globally_rigid),
            method: a.global_rigidity.as_ref().map(|g| g.method.name().to_owned()),
            global_rigidity: a.global_rigidity.as_ref().map(GlobalRigidityReport::from),
            clusters: clusters::clusters_report(system, &a.clusters, &a.cluster_global_rigidity),
            decomposition: a
                .decomposition
                .as_ref()
                .map(|trees| trees.iter().map(|t| clusters::tree_report(system, t)).collect()),
            decomposition_complete: a.decomposition_statistics.map(|s| s.complete),
            groups: (a.group_rigidity.as_ref())
                .filter(|g| !g.is_empty())
                .map(|g| clusters::groups_report(system, g)),
            seed: a.seed,
            tolerance: match a.backend {
                Backend::Float { tolerance } => Some(tolerance),
                Backend::Exact | Backend::Rational | Backend::Rug | Backend::ModP => None,
            },
            proof: a.proof.as_ref().map(ProofName::from),
            rank_method: a.rank_method.into(),
            internal_equations: a.internal_equations,
            float_qr_rank: a.float_qr_rank,
            structural: s.map(|s| structural::report(system, s)),
            clusters_arithmetic: a.clusters_arithmetic.into(),
            sketch: a.sketch.as_ref().map(|sk| SketchReport::new(system, sk)),
            witness_error_bound: a.witness_error_bound,
            witness_prime: a.witness.modulus,
            witness_turns: a.witness.turns.clone(),
            uncertain: a
                .uncertain
                .as_ref()
                .map(|u| u.iter().map(|c| system.constraint(*c).id.clone()).collect()),
            import: None,
        }
    }

    /// The same report with the import section of a model read from a CAD file.
    pub fn with_import(mut self, import: Option<crate::ImportReport>) -> Report {
        self.import = import;
        self
    }

    /// The same report with each fully redundant constraint told consistent or conflicting
    /// at the user's values, as measured at `solution` (of the same model and analysis). A
    /// solution that did not converge tells nothing: the report is returned unchanged.
    pub fn with_solution(mut self, system: &System, solution: &Solution) -> Report {
        if solution.status == SolveStatus::Failed {
            return self;
        }
        for r in &mut self.redundant {
            let c = solution
                .redundant
                .iter()
                .find(|k| system.constraint(k.constraint).id == r.constraint);
            if let Some(c) = c {
                r.conflicting = Some(c.conflicting);
                r.residual = Some(c.residual);
                r.allowance = Some(c.allowance);
            }
        }
        self
    }

    /// The report as one line of JSON (JSON Lines).
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }
}

fn describe_constraint(system: &System, c: gcs_model::ConstraintIdx) -> String {
    let con = system.constraint(c);
    let args: Vec<&str> = con.args.iter().map(|e| system.entity(*e).id.as_str()).collect();
    format!("{} ({} {})", con.id, con.kind, args.join("–"))
}

/// The text report of one model, for people: the verdict, the degrees of freedom, each
/// redundant constraint with what to delete, what decided it, the rigid parts, and the
/// optional sections (format §4, "Command line").
pub fn text(system: &System, file: &str, a: &Analysis, s: Option<&Structural>) -> String {
    text_with_solution(system, file, a, s, None)
}

/// [`text`], with each fully redundant constraint told consistent or conflicting at the
/// user's values as measured at `solution` (see [`Report::with_solution`]).
pub fn text_with_solution(
    system: &System,
    file: &str,
    a: &Analysis,
    s: Option<&Structural>,
    solution: Option<&Solution>,
) -> String {
    let solution = solution.filter(|sol| sol.status != SolveStatus::Failed);
    let mut out = String::new();
    let push = |out: &mut String, s: String| {
        out.push_str(&s);
        out.push('\n');
    };
    push(
        &mut out,
        format!(
            "{file}: {} ({}, {} entities, {} constraints)",
            system.name(),
            system.dim(),
            system.written_entities(),
            system.written_constraints()
        ),
    );
    if let n @ 1.. = system.orientations().len() {
        push(
            &mut out,
            format!(
                "  {n} orientation condition{} besides (navigation constraints: {} the solutions, {} no degree of freedom and {} not counted)",
                plural(n),
                if n == 1 { "it prunes" } else { "they prune" },
                if n == 1 { "removes" } else { "remove" },
                if n == 1 { "is" } else { "are" },
            ),
        );
    }
    if let Some(line) =
        crate::measured::measured_text(&crate::measured::at_drawing(system), "at the drawing")
    {
        push(&mut out, line);
    }
    let verdict = match (a.rigid(), a.redundant.is_empty()) {
        (true, true) => "well-constrained".to_owned(),
        (true, false) => format!(
            "over-constrained: rigid, with {} redundant constraint{}",
            a.redundant.len(),
            if a.redundant.len() == 1 { "" } else { "s" }
        ),
        (false, true) => {
            format!("under-constrained: {} degree{} of freedom left", a.dof, plural(a.dof))
        }
        (false, false) => format!(
            "under-constrained ({} degree{} of freedom left) and over-constrained ({} redundant)",
            a.dof,
            plural(a.dof),
            a.redundant.len()
        ),
    };
    let conflicts =
        solution.map_or(0, |sol| sol.redundant.iter().filter(|k| k.conflicting).count());
    let values = match conflicts {
        0 => String::new(),
        k => format!("; {k} of them conflicting at these values"),
    };
    push(&mut out, format!("  verdict: {verdict}{values}"));
    let placement = match a.trivial_motions {
        0 => "it is fixed in place".to_owned(),
        t if t == system.dim().displacements() => {
            format!("the whole moves freely as a rigid body ({t} displacements)")
        }
        t => format!("the whole can still be displaced in {t} independent ways"),
    };
    push(
        &mut out,
        format!(
            "  DOF: {} internal; {} counting the placement ({placement})",
            a.dof, a.dof_absolute
        ),
    );
    for r in &a.redundant {
        let others: Vec<String> =
            r.spanning_group.iter().map(|c| system.constraint(*c).id.clone()).collect();
        let partial = if r.rows < r.doc {
            format!(" ({} of its {} equations)", r.rows, r.doc)
        } else {
            String::new()
        };
        let fix = if others.is_empty() {
            "remove it (it removes nothing)".to_owned()
        } else {
            format!("remove it or one of: {}", others.join(", "))
        };
        let what = describe_constraint(system, r.constraint);
        let checked =
            solution.and_then(|sol| sol.redundant.iter().find(|k| k.constraint == r.constraint));
        let line = match checked {
            Some(k) if k.conflicting => format!(
                "  conflicting: {what}{partial} {}: change one value or delete one of them",
                crate::solve::off_by(k.residual, k.allowance, &others)
            ),
            Some(_) => format!("  redundant (consistent): {what}{partial}: {fix}"),
            None => format!("  redundant: {what}{partial}: {fix}"),
        };
        push(&mut out, line);
    }
    if let Some(sketch) = &a.sketch {
        for line in drawing_text(system, &verdict, sketch) {
            push(&mut out, line);
        }
    }
    let proof = match (&a.proof, a.witness_error_bound) {
        (Some(p), _) => format!(" ({p})"),
        (None, Some(bound)) => format!(
            " (modulo {} at a modular witness: not proven, wrong with probability below about \
             {bound:.0e})",
            a.witness.modulus.unwrap_or(gcs_rank::ModP::PRIME)
        ),
        (None, None) => String::new(),
    };
    let tol = match a.backend {
        Backend::Float { tolerance } => format!(", tolerance {tolerance:e}"),
        _ => String::new(),
    };
    let turns = match &a.witness.turns[..] {
        [] => String::new(),
        ns => {
            let each: Vec<String> = ns.iter().map(|n| format!("360°/{n}")).collect();
            format!(", turns by multiples of {} taken from the drawing", each.join(" and "))
        }
    };
    let tested = if a.witness.genericity_tested { "" } else { ", genericity not tested" };
    let how = match a.rank_method {
        // No arithmetic decided the verdict, whatever the backend (which still took the
        // drawing's rank and global rigidity).
        RankMethod::PebbleGame => "the (2,3) pebble game of the bar framework (Laman's theorem: \
                                   proven, no arithmetic)"
            .to_owned(),
        RankMethod::Witness => format!("{} arithmetic{proof}{tol}", a.backend.name()),
    };
    push(
        &mut out,
        format!(
            "  decided by: {how}; witness: {}{turns}{tested}, seed {}",
            a.witness.source.name(),
            a.seed
        ),
    );
    if let (Some(u), Backend::Float { tolerance }) = (&a.uncertain, a.backend)
        && !u.is_empty()
    {
        let ids: Vec<&str> = u.iter().map(|c| system.constraint(*c).id.as_str()).collect();
        push(
            &mut out,
            format!(
                "  uncertain at tolerance {tolerance:e}: {} — rerun with --backend exact",
                ids.join(", ")
            ),
        );
    }
    // Where the witness came from, when it is not the drawing itself, and why.
    match a.witness.source {
        WitnessSource::Sketch => {}
        WitnessSource::Perturbed => push(
            &mut out,
            match &a.sketch {
                Some(sk) => format!(
                    "  note: the drawing is at a special position (rank {} there, {} \
                     generically): the verdict was decided at a drawing moved slightly off it",
                    sk.rank, a.rank
                ),
                None => "  note: a perturbation of the drawing raised the rank: the verdict was \
                         decided at a drawing moved slightly off it"
                    .to_owned(),
            },
        ),
        WitnessSource::Generated => {
            let why =
                a.witness.sketch_rejected.as_ref().map_or_else(String::new, |w| w.to_string());
            push(&mut out, format!("  note: sketch not used as witness: {why}"));
        }
        WitnessSource::Modular | WitnessSource::Approximate => {
            if let Some(why) = &a.witness.no_exact_witness {
                push(&mut out, format!("  note: no rational witness: {why}"));
            }
        }
    }
    // What is rigid, and so what still moves: the clusters.
    if !(a.rigid() && a.clusters.len() == 1) {
        for line in clusters::clusters_text(system, &a.clusters) {
            push(&mut out, line);
        }
    } else {
        push(&mut out, "  rigid: the whole system is one rigid body".to_owned());
    }
    for line in global_text(system, a) {
        push(&mut out, line);
    }
    if let Some(trees) = &a.decomposition {
        let complete = a.decomposition_statistics.is_none_or(|s| s.complete);
        push(
            &mut out,
            format!(
                "  W-decomposition (a DR-plan: rigid subsystems by containment){}:",
                if complete { "" } else { " — incomplete, the work budget ran out" }
            ),
        );
        let mut lines = Vec::new();
        for t in trees.iter().filter(|t| t.entities.len() > 1) {
            clusters::tree_text(system, t, &mut lines);
        }
        for line in lines {
            push(&mut out, line);
        }
        for line in clusters::groups_text(system, a.group_rigidity.as_deref().unwrap_or(&[])) {
            push(&mut out, line);
        }
    }
    if let Some(s) = s {
        push(&mut out, structural::text(system, a, s));
    }
    out.pop();
    out
}

/// What the text report says of global rigidity, in a CAD user's words: whether the dimensions
/// determine the shape, how that was decided, and the clusters that can flip.
fn global_text(system: &System, a: &Analysis) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(g) = &a.global_rigidity {
        let how = match (g.arithmetic, g.error_bound) {
            (Arithmetic::Float { .. }, _) => "approximate, in float".to_owned(),
            (_, Some(b)) => {
                format!("modulo {}, wrong with probability below {b:.0e}", gcs_rank::ModP::PRIME)
            }
            (_, None) => "proven".to_owned(),
        };
        let line = if g.globally_rigid {
            "globally rigid: the dimensions determine the shape (up to moving and mirroring the \
             whole)"
                .to_owned()
        } else if !g.rigid {
            "not globally rigid: the same dimensions admit other shapes (flips); it is not even \
             rigid"
                .to_owned()
        } else {
            "not globally rigid: the same dimensions admit other shapes (flips)".to_owned()
        };
        out.push(format!("  {line} [{}, {how}]", g.method.name()));
    }
    // The clusters that can flip, unless that is only the whole system again.
    let whole_is_one = a.global_rigidity.is_some() && a.clusters.len() == 1;
    if !whole_is_one {
        out.extend(clusters::flips_text(system, &a.clusters, &a.cluster_global_rigidity));
    }
    out
}

/// What the text report says of the drawing: a singular position in words a CAD user knows,
/// and a drawing that does not satisfy its constraints.
fn drawing_text(system: &System, verdict: &str, s: &SketchAnalysis) -> Vec<String> {
    let mut out = Vec::new();
    if s.singular || !s.dependent.is_empty() {
        let mut ids: Vec<&str> = Vec::new();
        for d in &s.dependent {
            for c in d.spanning_group.iter().chain(std::iter::once(&d.constraint)) {
                let id = system.constraint(*c).id.as_str();
                if !ids.contains(&id) {
                    ids.push(id);
                }
            }
        }
        let named: Vec<String> = s
            .configurations
            .iter()
            .map(|c| {
                let verb = if c.position == Position::Coincident {
                    "coincide".to_owned()
                } else {
                    format!("are {}", c.position.name())
                };
                if c.constraints.is_empty() {
                    let entities: Vec<&str> =
                        c.entities.iter().map(|e| system.entity(*e).id.as_str()).collect();
                    format!("{} {verb}", entities.join(", "))
                } else {
                    let bars: Vec<&str> =
                        c.constraints.iter().map(|k| system.constraint(*k).id.as_str()).collect();
                    format!("the lines of {} {verb}", bars.join(", "))
                }
            })
            .collect();
        let cause =
            if named.is_empty() { String::new() } else { format!(" ({})", named.join("; ")) };
        let moves = match s.extra_motions {
            0 => String::new(),
            1 => ": it can move in one more way than a generic drawing".to_owned(),
            n => format!(": it can move in {n} more ways than a generic drawing"),
        };
        out.push(format!(
            "  singular at this drawing: {} are dependent here{cause}{moves}; generically \
             {verdict} — move a point off the special position, or expect a solver to struggle",
            ids.join(", ")
        ));
    }
    if let Some(r) = &s.largest_residual {
        let c = system.constraint(r.constraint);
        let how = match c.value.as_ref().and_then(|v| v.to_f64()) {
            Some(value) if c.kind.is_metric() => {
                format!("measures {} on the drawing, dimensioned {value}", value + r.value)
            }
            _ => format!("the drawing is {:.3e} from it", r.value),
        };
        out.push(format!(
            "  the drawing does not satisfy its constraints: farthest {}: {how}",
            describe_constraint(system, r.constraint)
        ));
    }
    out
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// The JSON line of a file that failed (format §2): its file and the message.
pub fn failure_json(file: &str, message: &str) -> String {
    #[derive(Serialize)]
    struct Failure<'a> {
        schema: u32,
        file: &'a str,
        error: &'a str,
    }
    serde_json::to_string(&Failure { schema: SCHEMA, file, error: message }).unwrap_or_default()
}

/// Whether a count is zero (a field left out of the JSON then).
pub(crate) fn is_zero(n: &usize) -> bool {
    *n == 0
}
