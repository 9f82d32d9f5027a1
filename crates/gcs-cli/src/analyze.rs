//! `gcs analyze`: the witness analysis of each model, as text for people or JSON Lines.

use std::path::PathBuf;
use std::process::ExitCode;

use gcs_analysis::{Analysis, AnalysisOptions, Backend, analyze};
use gcs_jacobian::WitnessOptions;
use gcs_model::System;
use serde::Serialize;

use crate::Format;
use crate::batch::{self, Out};
use crate::decompose;
use crate::structural::{self, Structural, StructuralJson};

/// Options of the analysis, from the command line.
pub(crate) struct Settings {
    pub(crate) backend: Backend,
    pub(crate) seed: u64,
    pub(crate) format: Format,
    /// Add the structural section (`--structural`).
    pub(crate) structural: bool,
    /// Add the W-decomposition (`--decompose`).
    pub(crate) decompose: bool,
    /// Write the W-decompositions as Graphviz DOT to this file (`--dot`).
    pub(crate) dot: Option<PathBuf>,
}

#[derive(Serialize)]
struct RedundantJson {
    constraint: String,
    rows: usize,
    doc: usize,
    spanning_group: Vec<String>,
}

#[derive(Serialize)]
struct ReportJson<'a> {
    schema: u32,
    model: &'a str,
    file: &'a str,
    dim: usize,
    backend: &'static str,
    witness: &'static str,
    entities: usize,
    constraints: usize,
    unknowns: usize,
    equations: usize,
    rank: usize,
    dof_absolute: usize,
    trivial_motions: usize,
    dof: usize,
    rigid: bool,
    well_constrained: bool,
    redundant: Vec<RedundantJson>,
    clusters: Vec<decompose::ClusterJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    decomposition: Option<Vec<decompose::NodeJson>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    decomposition_complete: Option<bool>,
    seed: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    tolerance: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    proof: Option<String>,
    internal_equations: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    float_qr_rank: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    structural: Option<StructuralJson>,
    clusters_arithmetic: &'static str,
}

fn json(system: &System, file: &str, a: &Analysis, s: Option<&Structural>) -> String {
    let id = |c: gcs_model::ConstraintIdx| system.constraint(c).id.clone();
    let report = ReportJson {
        schema: 1,
        model: system.name(),
        file,
        dim: system.dim().coords(),
        backend: a.backend.name(),
        witness: a.witness.source.name(),
        entities: system.entities().len(),
        constraints: system.constraints().len(),
        unknowns: a.unknowns,
        equations: a.equations,
        rank: a.rank,
        dof_absolute: a.dof_absolute,
        trivial_motions: a.trivial_motions,
        dof: a.dof,
        rigid: a.rigid(),
        well_constrained: a.well_constrained(),
        redundant: a
            .redundant
            .iter()
            .map(|r| RedundantJson {
                constraint: id(r.constraint),
                rows: r.rows,
                doc: r.doc,
                spanning_group: r.spanning_group.iter().map(|c| id(*c)).collect(),
            })
            .collect(),
        seed: a.seed,
        tolerance: match a.backend {
            Backend::Float { tolerance } => Some(tolerance),
            _ => None,
        },
        proof: a.proof.as_ref().map(|p| p.name().to_owned()),
        internal_equations: a.internal_equations,
        float_qr_rank: a.float_qr_rank,
        structural: s.map(|s| structural::json(system, s)),
        clusters: decompose::clusters_json(system, &a.clusters),
        decomposition: a
            .decomposition
            .as_ref()
            .map(|trees| trees.iter().map(|t| decompose::tree_json(system, t)).collect()),
        decomposition_complete: a.decomposition_statistics.map(|s| s.complete),
        clusters_arithmetic: a.clusters_arithmetic.name(),
    };
    serde_json::to_string(&report).unwrap_or_default()
}

fn describe_constraint(system: &System, c: gcs_model::ConstraintIdx) -> String {
    let con = system.constraint(c);
    let args: Vec<&str> = con.args.iter().map(|e| system.entity(*e).id.as_str()).collect();
    format!("{} ({} {})", con.id, con.kind, args.join("–"))
}

fn text(system: &System, file: &str, a: &Analysis, s: Option<&Structural>) -> String {
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
            system.entities().len(),
            system.constraints().len()
        ),
    );
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
    push(&mut out, format!("  verdict: {verdict}"));
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
        push(
            &mut out,
            format!("  redundant: {}{partial}: {fix}", describe_constraint(system, r.constraint)),
        );
    }
    let proof = match &a.proof {
        Some(p) => format!(" ({p})"),
        None => String::new(),
    };
    let tol = match a.backend {
        Backend::Float { tolerance } => format!(", tolerance {tolerance:e}"),
        _ => String::new(),
    };
    let tested = if a.witness.genericity_tested { "" } else { ", genericity not tested" };
    push(
        &mut out,
        format!(
            "  decided by: {} arithmetic{proof}{tol}; witness: {}{tested}, seed {}",
            a.backend.name(),
            a.witness.source.name(),
            a.seed
        ),
    );
    if let Some(why) = &a.witness.sketch_rejected {
        push(&mut out, format!("  note: sketch not used as witness: {why}"));
    }
    // What is rigid, and so what still moves: the clusters.
    if !(a.rigid() && a.clusters.len() == 1) {
        for line in decompose::clusters_text(system, &a.clusters) {
            push(&mut out, line);
        }
    } else {
        push(&mut out, "  rigid: the whole system is one rigid body".to_owned());
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
            decompose::tree_text(system, t, &mut lines);
        }
        for line in lines {
            push(&mut out, line);
        }
    }
    if let Some(s) = s {
        push(&mut out, structural::text(system, a, s));
    }
    out.pop();
    out
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

pub(crate) fn run(paths: &[PathBuf], settings: &Settings) -> ExitCode {
    let mut out = Out::new();
    let mut failed = 0;
    let options = AnalysisOptions {
        backend: settings.backend,
        witness: WitnessOptions { seed: settings.seed, ..WitnessOptions::default() },
        decompose: settings.decompose,
        ..AnalysisOptions::default()
    };
    let mut dot = String::new();
    for (file, system) in batch::models(paths) {
        let result = system.and_then(|system| {
            let analysis = analyze(&system, &options).map_err(|e| format!("{file}: {e}"))?;
            let structural = if settings.structural {
                let s = Structural::new(&system, &analysis)
                    .map_err(|e| format!("{file}: structural: {e}"))?;
                Some(s)
            } else {
                None
            };
            Ok((system, analysis, structural))
        });
        match result {
            Ok((system, analysis, s)) => {
                if settings.dot.is_some()
                    && let Some(trees) = &analysis.decomposition
                {
                    dot.push_str(&decompose::dot(&system, trees));
                }
                match settings.format {
                    Format::Json => out.line(&json(&system, &file, &analysis, s.as_ref())),
                    Format::Text => out.line(&text(&system, &file, &analysis, s.as_ref())),
                }
            }
            Err(message) => {
                failed += 1;
                out.failure(settings.format, &file, &message);
            }
        }
    }
    out.flush();
    if let Some(path) = &settings.dot
        && let Err(e) = std::fs::write(path, dot)
    {
        eprintln!("error: cannot write {}: {e}", batch::display(path));
        failed += 1;
    }
    batch::status(failed)
}
