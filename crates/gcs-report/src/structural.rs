//! The structural section of a report (format §3, `structural`): the flow-based verdicts and
//! the Dulmage–Mendelsohn decomposition, and where they disagree with the witness analysis.
//!
//! Three counting methods run on one object–constraint network: Dense (Hoffmann et al.),
//! Over-Rigid with the DOR from the rule table, and Over-Rigid with the DOR computed exactly at
//! the witness the analysis used. The witness analysis is the reference: an over-rigid
//! subsystem must contain a redundant constraint (a subsystem with fewer DOF than the
//! displacements it admits has dependent equations), and a method that finds none while the
//! witness finds a redundant constraint was fooled by the geometry.

use gcs_analysis::Analysis;
use gcs_jacobian::Layout;
use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rigidity::{
    DmDecomposition, DmPart, DorOracle, Network, Object, RigidityAnalysis, RuleDor, Subsystem,
    Verdict, WitnessDor, dense_analysis_in, dm_decomposition, object_dor, over_rigid_analysis_in,
};
use serde::{Deserialize, Serialize};

use crate::error::ReportError;

/// What the structural methods say about one system, beside its witness analysis.
pub struct Structural {
    dense: RigidityAnalysis,
    over_rigid: RigidityAnalysis,
    over_rigid_witness: RigidityAnalysis,
    dm: DmDecomposition,
    rules: RuleDor,
    witness: WitnessDor,
    /// Whether the system has absolute constraints (its network has the reference frame).
    grounded: bool,
    /// The DOR of all the network's objects at the witness.
    whole_witness_dor: usize,
}

impl Structural {
    /// Runs the three flow methods (one network, one base flow) and D-M; the witness DOR is
    /// taken at the witness of `analysis`.
    ///
    /// # Errors
    /// When the witness DOR cannot be computed at that witness ([`ReportError::Structural`]).
    pub fn new(system: &System, analysis: &Analysis) -> Result<Structural, ReportError> {
        let layout = Layout::new(system);
        let witness = WitnessDor::from_witness(system, &layout, &analysis.witness)
            .map_err(ReportError::Structural)?;
        let rules = RuleDor::for_system(system);
        let mut network = Network::new(system);
        let dense = dense_analysis_in(&mut network);
        let over_rigid = over_rigid_analysis_in(system, &mut network, &rules);
        let over_rigid_witness = over_rigid_analysis_in(system, &mut network, &witness);
        let whole_witness_dor = object_dor(system, &witness, network.objects());
        Ok(Structural {
            dense,
            over_rigid,
            over_rigid_witness,
            dm: dm_decomposition(system),
            rules,
            witness,
            grounded: network.has_frame(),
            whole_witness_dor,
        })
    }
}

impl Structural {
    /// The `structural` section of format §3, as data.
    pub fn report(&self, system: &System) -> StructuralReport {
        report(system, self)
    }

    /// The text block of the report: one line per method, the witness analysis, and the
    /// disagreements with it, explained.
    pub fn text(&self, system: &System, analysis: &Analysis) -> String {
        text(system, analysis, self)
    }
}

// ---- JSON ----

/// A method's verdict (format §3, `verdict`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum VerdictName {
    /// A subsystem has fewer DOF than the displacements it was charged with.
    OverRigid,
    /// The whole system's DOF equals its DOR.
    WellRigid,
    /// Otherwise.
    UnderRigid,
}

impl From<Verdict> for VerdictName {
    fn from(v: Verdict) -> Self {
        match v {
            Verdict::OverRigid => VerdictName::OverRigid,
            Verdict::WellRigid => VerdictName::WellRigid,
            Verdict::UnderRigid => VerdictName::UnderRigid,
        }
    }
}

/// Where a method's degree of rigidity comes from (format §3, `dor`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DorSource {
    /// The rule table.
    Rules,
    /// Exactly, at the witness.
    Witness,
}

/// One method's verdict (format §3), with the counts behind it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MethodReport {
    /// The verdict.
    pub verdict: VerdictName,
    /// The over-rigid subsystem's entities (empty when none).
    pub subsystem: Vec<String>,
    /// Where the DOR comes from (Over-Rigid only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dor: Option<DorSource>,
    /// The constraints the subsystem induces.
    pub subsystem_constraints: Vec<String>,
    /// Whether the subsystem includes the reference frame (its absolute constraints).
    pub subsystem_grounded: bool,
    /// The subsystem's DOF by count (when over-rigid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub subsystem_dof: Option<i64>,
    /// The whole system's DOF by count (the frame's included when there is one).
    pub dof: i64,
    /// What `dof` is compared with: D for Dense, the whole system's DOR for Over-Rigid.
    pub displacements: usize,
    /// How many times the flow was asked to distribute an overload.
    pub distribute_calls: usize,
}

/// One part of the Dulmage–Mendelsohn decomposition.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartReport {
    /// The constraints with an equation node in it.
    pub constraints: Vec<String>,
    /// The entities with an unknown node in it.
    pub entities: Vec<String>,
    /// Equation nodes.
    pub equations: usize,
    /// Unknown nodes.
    pub unknowns: usize,
}

/// The Dulmage–Mendelsohn decomposition (format §3, `dm`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DmReport {
    /// Over-determined part.
    pub over: PartReport,
    /// Well-determined part.
    pub well: PartReport,
    /// Under-determined part.
    pub under: PartReport,
    /// The fine blocks of the well-determined part, in solving order.
    pub blocks: Vec<PartReport>,
    /// The size of the maximum matching.
    pub matched: usize,
}

/// The `structural` section of a report (format §3).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StructuralReport {
    /// Hoffmann et al.'s Dense.
    pub dense: MethodReport,
    /// Over-Rigid with the DOR from the rules.
    pub over_rigid: MethodReport,
    /// Over-Rigid with the DOR at the witness.
    pub over_rigid_witness: MethodReport,
    /// The Dulmage–Mendelsohn decomposition.
    pub dm: DmReport,
}

fn entity_ids(system: &System, entities: &[EntityIdx]) -> Vec<String> {
    entities.iter().map(|e| system.entity(*e).id.clone()).collect()
}

fn constraint_ids(system: &System, constraints: &[ConstraintIdx]) -> Vec<String> {
    constraints.iter().map(|c| system.constraint(*c).id.clone()).collect()
}

fn method_report(system: &System, a: &RigidityAnalysis, dor: Option<DorSource>) -> MethodReport {
    let sub = a.subsystem.as_ref();
    MethodReport {
        verdict: a.verdict.into(),
        subsystem: entity_ids(system, &a.subsystem_entities()),
        dor,
        subsystem_constraints: sub
            .map(|s| constraint_ids(system, &s.constraints))
            .unwrap_or_default(),
        subsystem_grounded: sub.is_some_and(|s| s.grounded),
        subsystem_dof: sub.map(|s| s.dof),
        dof: a.dof,
        displacements: a.dor,
        distribute_calls: a.distribute_calls,
    }
}

fn part_report(system: &System, p: &DmPart) -> PartReport {
    PartReport {
        constraints: constraint_ids(system, &p.constraints),
        entities: entity_ids(system, &p.entities),
        equations: p.equations,
        unknowns: p.unknowns,
    }
}

/// The `structural` section of format §3, as data.
pub(crate) fn report(system: &System, s: &Structural) -> StructuralReport {
    StructuralReport {
        dense: method_report(system, &s.dense, None),
        over_rigid: method_report(system, &s.over_rigid, Some(DorSource::Rules)),
        over_rigid_witness: method_report(system, &s.over_rigid_witness, Some(DorSource::Witness)),
        dm: DmReport {
            over: part_report(system, &s.dm.over),
            well: part_report(system, &s.dm.well),
            under: part_report(system, &s.dm.under),
            blocks: s.dm.blocks.iter().map(|b| part_report(system, b)).collect(),
            matched: s.dm.matched,
        },
    }
}

// ---- text ----

/// At most this many ids are listed in a text line.
const LISTED: usize = 10;

fn list(ids: &[String]) -> String {
    if ids.len() <= LISTED {
        ids.join(", ")
    } else {
        format!("{} and {} more", ids[..LISTED].join(", "), ids.len() - LISTED)
    }
}

fn objects_of(s: &Subsystem) -> Vec<Object> {
    let mut v: Vec<Object> = s.objects.iter().map(|e| Object::Entity(*e)).collect();
    if s.grounded {
        v.push(Object::Frame);
    }
    v
}

/// The subsystem's entity ids, with the reference frame named when it is part of it.
fn subsystem_names(system: &System, s: &Subsystem) -> String {
    let mut ids = entity_ids(system, &s.entities());
    if s.grounded {
        ids.push("the reference frame".to_owned());
    }
    list(&ids)
}

/// The three counting methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Method {
    Dense,
    Rules,
    Witness,
}

impl Method {
    /// The name the text report gives it.
    fn name(self) -> &'static str {
        match self {
            Method::Dense => "Dense",
            Method::Rules => "Over-Rigid (rules DOR)",
            Method::Witness => "Over-Rigid (witness DOR)",
        }
    }
}

fn method_line(
    system: &System,
    name: &str,
    a: &RigidityAnalysis,
    oracle: Option<&dyn DorOracle>,
) -> String {
    // What the DOF is compared with: the DOR for Over-Rigid, D displacements for Dense.
    let compared = |n: usize| match oracle {
        Some(_) => format!("DOR {n}"),
        None => format!("{n} displacements"),
    };
    let detail = match (&a.subsystem, a.verdict) {
        (Some(sub), Verdict::OverRigid) => {
            let charged = match oracle {
                Some(o) => object_dor(system, o, &objects_of(sub)),
                None => system.dim().displacements(),
            };
            format!(": {} (DOF {} < {})", subsystem_names(system, sub), sub.dof, compared(charged))
        }
        (_, Verdict::WellRigid) => format!(" (DOF {} = {})", a.dof, compared(a.dor)),
        _ => format!(" (DOF {} > {}: {} left)", a.dof, compared(a.dor), a.dof - a.dor as i64),
    };
    format!("{name}: {}{detail}", a.verdict)
}

fn dm_line(system: &System, dm: &DmDecomposition) -> String {
    let count = |p: &DmPart| {
        if p.constraints.is_empty() && p.entities.is_empty() {
            "none".to_owned()
        } else {
            format!(
                "{} equation{} on {} unknown{} ({} constraint{}, {} entit{})",
                p.equations,
                plural(p.equations),
                p.unknowns,
                plural(p.unknowns),
                p.constraints.len(),
                plural(p.constraints.len()),
                p.entities.len(),
                if p.entities.len() == 1 { "y" } else { "ies" }
            )
        }
    };
    let over = if dm.over.constraints.is_empty() {
        "none".to_owned()
    } else {
        format!(
            "{} on {}",
            list(&constraint_ids(system, &dm.over.constraints)),
            list(&entity_ids(system, &dm.over.entities))
        )
    };
    let well = match dm.blocks.len() {
        0 | 1 => count(&dm.well),
        n => format!("{} in {n} blocks", count(&dm.well)),
    };
    format!(
        "D-M: over-determined: {over}; well-determined: {well}; under-determined: {}",
        count(&dm.under)
    )
}

/// DOF left according to the witness, in the sense of the structural verdicts: internal DOF
/// for a free system, DOF with respect to the page when absolute constraints tie it to it.
fn witness_left(s: &Structural, a: &Analysis) -> i64 {
    (if s.grounded { a.dof_absolute } else { a.dof }) as i64
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// The disagreements between the counting methods and the witness analysis, one sentence each.
fn disagreements(system: &System, a: &Analysis, s: &Structural) -> Vec<String> {
    let mut out = Vec::new();
    let redundant: Vec<ConstraintIdx> = a.redundant.iter().map(|r| r.constraint).collect();
    let left = witness_left(s, a);
    let d = system.dim().displacements();
    let methods: [(Method, &RigidityAnalysis, Option<&dyn DorOracle>); 3] = [
        (Method::Dense, &s.dense, None),
        (Method::Rules, &s.over_rigid, Some(&s.rules)),
        (Method::Witness, &s.over_rigid_witness, Some(&s.witness)),
    ];
    // The methods that see no over-rigid subsystem although the witness finds a redundant
    // constraint, with the DOF they count as left.
    let mut blind: Vec<(&str, i64)> = Vec::new();
    for (method, m, oracle) in methods {
        let name = method.name();
        match (&m.subsystem, m.verdict) {
            (Some(sub), Verdict::OverRigid) => {
                if sub.constraints.iter().any(|c| redundant.contains(c)) {
                    continue;
                }
                let exact = object_dor(system, &s.witness, &objects_of(sub));
                let names = subsystem_names(system, sub);
                let none = "no redundant constraint among them";
                out.push(match (method, oracle) {
                    (Method::Rules, Some(o)) => format!(
                        "{name}: {names}: DOR {} by the rules, {exact} at the witness, and {none}: \
                         a parallelism/collinearity the rules cannot see",
                        object_dor(system, o, &objects_of(sub)),
                    ),
                    (Method::Witness, _) => format!("{name}: {names}: the witness finds {none}"),
                    (Method::Dense | Method::Rules, _) => format!(
                        "{name}: {names}: {exact} displacements admitted, not {d}, and {none}: \
                         Dense charges a subsystem with more displacements than it admits (a \
                         segment in 3D, parallel lines, a circle)"
                    ),
                });
            }
            _ if !redundant.is_empty() => blind.push((name, m.dof - m.dor as i64)),
            _ => {
                let counted = m.dof - m.dor as i64;
                if counted == left {
                    continue;
                }
                let exact = s.whole_witness_dor;
                out.push(match method {
                    Method::Dense => format!(
                        "{name} counts {counted} DOF left, the witness {left}: the system admits \
                         {exact} displacements, Dense charges {d}"
                    ),
                    Method::Rules => format!(
                        "{name} counts {counted} DOF left, the witness {left}: the system admits \
                         {exact} displacements, not {}: a parallelism/collinearity the rules \
                         cannot see",
                        m.dor
                    ),
                    Method::Witness => {
                        format!("{name} counts {counted} DOF left, the witness {left}")
                    }
                });
            }
        }
    }
    if !blind.is_empty() {
        let names: Vec<&str> = blind.iter().map(|(n, _)| *n).collect();
        let last = names.len() - 1;
        let names = if last == 0 {
            format!("{} finds", names[0])
        } else {
            format!("{} and {} find", names[..last].join(", "), names[last])
        };
        let counted = blind[0].1;
        let dof = if blind.iter().all(|(_, c)| *c == counted) && counted != left {
            format!(" and {left} DOF left, not {counted}")
        } else {
            String::new()
        };
        let ids = constraint_ids(system, &redundant);
        out.push(format!(
            "{names} no over-rigid subsystem, but the witness finds {} redundant{dof}: the \
             count cannot see a geometric dependency (a theorem, or a hinge such as the double \
             banana's)",
            list(&ids)
        ));
    }
    out
}

/// The text block of one model: one line per method, the witness analysis, the disagreements.
pub(crate) fn text(system: &System, a: &Analysis, s: &Structural) -> String {
    let mut lines = vec![
        "  structural:".to_owned(),
        format!("    {}", method_line(system, Method::Dense.name(), &s.dense, None)),
        format!("    {}", method_line(system, Method::Rules.name(), &s.over_rigid, Some(&s.rules))),
        format!(
            "    {}",
            method_line(system, Method::Witness.name(), &s.over_rigid_witness, Some(&s.witness))
        ),
        format!("    {}", dm_line(system, &s.dm)),
    ];
    let left = witness_left(s, a);
    let place = if s.grounded { " (with respect to the page)" } else { "" };
    let redundant = if a.redundant.is_empty() {
        "no redundant constraint".to_owned()
    } else {
        let ids: Vec<String> =
            a.redundant.iter().map(|r| system.constraint(r.constraint).id.clone()).collect();
        format!("redundant: {}", list(&ids))
    };
    lines.push(format!(
        "    witness analysis: {left} DOF left{place}, {redundant} ({} trivial motion{})",
        a.trivial_motions,
        plural(a.trivial_motions)
    ));
    let found = disagreements(system, a, s);
    if found.is_empty() {
        lines.push("    no disagreement with the witness analysis".to_owned());
    }
    for d in found {
        lines.push(format!("    disagreement: {d}"));
    }
    lines.join("\n")
}
