//! `gcs analyze --structural`: the flow-based verdicts and the Dulmage–Mendelsohn decomposition
//! (FORMAT.md §3, `structural`), and where they disagree with the witness analysis.
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
use serde::Serialize;

/// What the structural methods say about one system.
pub(crate) struct Structural {
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
    pub(crate) fn new(system: &System, analysis: &Analysis) -> Result<Structural, String> {
        let layout = Layout::new(system);
        let witness = WitnessDor::from_witness(system, &layout, &analysis.witness)
            .map_err(|e| e.to_string())?;
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

// ---- JSON ----

/// One method's verdict (FORMAT.md §3), with the counts behind it.
#[derive(Serialize)]
struct MethodJson {
    verdict: &'static str,
    subsystem: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    dor: Option<String>,
    /// The constraints the subsystem induces.
    subsystem_constraints: Vec<String>,
    /// Whether the subsystem includes the reference frame (its absolute constraints).
    subsystem_grounded: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    subsystem_dof: Option<i64>,
    /// The whole system's DOF by count (the frame's included when there is one).
    dof: i64,
    /// What `dof` is compared with: D for Dense, the whole system's DOR for Over-Rigid.
    displacements: usize,
    distribute_calls: usize,
}

#[derive(Serialize)]
struct PartJson {
    constraints: Vec<String>,
    entities: Vec<String>,
    equations: usize,
    unknowns: usize,
}

#[derive(Serialize)]
struct DmJson {
    over: PartJson,
    well: PartJson,
    under: PartJson,
    blocks: Vec<PartJson>,
    matched: usize,
}

/// The `structural` section of a JSON report.
#[derive(Serialize)]
pub(crate) struct StructuralJson {
    dense: MethodJson,
    over_rigid: MethodJson,
    over_rigid_witness: MethodJson,
    dm: DmJson,
}

fn entity_ids(system: &System, entities: &[EntityIdx]) -> Vec<String> {
    entities.iter().map(|e| system.entity(*e).id.clone()).collect()
}

fn constraint_ids(system: &System, constraints: &[ConstraintIdx]) -> Vec<String> {
    constraints.iter().map(|c| system.constraint(*c).id.clone()).collect()
}

fn method_json(system: &System, a: &RigidityAnalysis, dor: Option<&str>) -> MethodJson {
    let sub = a.subsystem.as_ref();
    MethodJson {
        verdict: a.verdict.as_str(),
        subsystem: entity_ids(system, &a.subsystem_entities()),
        dor: dor.map(str::to_owned),
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

fn part_json(system: &System, p: &DmPart) -> PartJson {
    PartJson {
        constraints: constraint_ids(system, &p.constraints),
        entities: entity_ids(system, &p.entities),
        equations: p.equations,
        unknowns: p.unknowns,
    }
}

/// The `structural` object of FORMAT.md §3.
pub(crate) fn json(system: &System, s: &Structural) -> StructuralJson {
    StructuralJson {
        dense: method_json(system, &s.dense, None),
        over_rigid: method_json(system, &s.over_rigid, Some(&s.over_rigid.dor_source)),
        over_rigid_witness: method_json(
            system,
            &s.over_rigid_witness,
            Some(&s.over_rigid_witness.dor_source),
        ),
        dm: DmJson {
            over: part_json(system, &s.dm.over),
            well: part_json(system, &s.dm.well),
            under: part_json(system, &s.dm.under),
            blocks: s.dm.blocks.iter().map(|b| part_json(system, b)).collect(),
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

/// The method names, the way the text report spells them.
const DENSE: &str = "Dense";
const RULES: &str = "Over-Rigid (rules DOR)";
const WITNESS: &str = "Over-Rigid (witness DOR)";

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
    let methods: [(&str, &RigidityAnalysis, Option<&dyn DorOracle>); 3] = [
        (DENSE, &s.dense, None),
        (RULES, &s.over_rigid, Some(&s.rules)),
        (WITNESS, &s.over_rigid_witness, Some(&s.witness)),
    ];
    // The methods that see no over-rigid subsystem although the witness finds a redundant
    // constraint, with the DOF they count as left.
    let mut blind: Vec<(&str, i64)> = Vec::new();
    for (name, m, oracle) in methods {
        match (&m.subsystem, m.verdict) {
            (Some(sub), Verdict::OverRigid) => {
                if sub.constraints.iter().any(|c| redundant.contains(c)) {
                    continue;
                }
                let exact = object_dor(system, &s.witness, &objects_of(sub));
                let names = subsystem_names(system, sub);
                let none = "no redundant constraint among them";
                out.push(match oracle {
                    None => format!(
                        "{name}: {names}: {exact} displacements admitted, not {d}, and {none}: \
                         Dense charges a subsystem with more displacements than it admits (a \
                         segment in 3D, parallel lines, a circle)"
                    ),
                    Some(o) if o.name() == "rules" => format!(
                        "{name}: {names}: DOR {} by the rules, {exact} at the witness, and {none}: \
                         a parallelism/collinearity the rules cannot see",
                        object_dor(system, o, &objects_of(sub)),
                    ),
                    Some(_) => format!("{name}: {names}: the witness finds {none}"),
                });
            }
            _ if !redundant.is_empty() => blind.push((name, m.dof - m.dor as i64)),
            _ => {
                let counted = m.dof - m.dor as i64;
                if counted == left {
                    continue;
                }
                let exact = s.whole_witness_dor;
                out.push(match oracle {
                    None => format!(
                        "{name} counts {counted} DOF left, the witness {left}: the system admits \
                         {exact} displacements, Dense charges {d}"
                    ),
                    Some(o) if o.name() == "rules" => format!(
                        "{name} counts {counted} DOF left, the witness {left}: the system admits \
                         {exact} displacements, not {}: a parallelism/collinearity the rules \
                         cannot see",
                        m.dor
                    ),
                    Some(_) => {
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
        format!("    {}", method_line(system, DENSE, &s.dense, None)),
        format!("    {}", method_line(system, RULES, &s.over_rigid, Some(&s.rules))),
        format!("    {}", method_line(system, WITNESS, &s.over_rigid_witness, Some(&s.witness))),
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
