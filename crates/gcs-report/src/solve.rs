//! The report of `gcs solve` (format §4, "Solving"): the status, the worst residual, how far
//! the drawing moved, the solved entities in the model file's field names, and each redundant
//! constraint measured at the solution — consistent, or conflicting with its spanning group.

use gcs_jacobian::Layout;
use gcs_model::System;
use gcs_model::entity::Geometry;
use gcs_solve::Solution;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value, json};

use crate::report::SCHEMA;

/// A redundant constraint measured at the solution.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CheckedReport {
    /// Its id.
    pub constraint: String,
    /// Its residual at the solution: for a dimension the measure minus the value (model units
    /// or degrees), for a parameter-free constraint its largest polynomial residual.
    pub residual: f64,
    /// The largest residual that still agrees: the written precision of the values in the
    /// dependency, plus the tolerance.
    pub allowance: f64,
    /// Beyond the tolerance: it contradicts its spanning group.
    pub conflicting: bool,
    /// The constraints it is redundant with.
    pub spanning_group: Vec<String>,
}

/// A part without a real solution.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NoSolutionReport {
    /// Its entities (ids).
    pub entities: Vec<String>,
    /// Its constraints (ids).
    pub constraints: Vec<String>,
}

/// One step of the solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlanReport {
    /// The entities it places (ids).
    pub entities: Vec<String>,
    /// `closed-form` or `newton`.
    pub method: String,
    /// The real candidates.
    pub candidates: usize,
    /// The candidate kept (`null` when there was none).
    pub chosen: Option<usize>,
    /// The constraints it satisfies (ids).
    pub constraints: Vec<String>,
    /// Whether `candidates` are all the step's real solutions (closed form; a core of one
    /// distance), not only the one reached from the drawing.
    #[serde(default)]
    pub complete: bool,
    /// Whether the user fixed the choice (`--choose`).
    #[serde(default)]
    pub fixed: bool,
    /// With `--all`, for a core enumerated by homotopy continuation: its paths.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paths: Option<PathsReport>,
    /// When `complete` is false: why, and how much may be missing (extension; absent when
    /// complete).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub incomplete: Vec<IncompleteReport>,
    /// For a node of the core's DR-plan assembled from others: their steps (indices in
    /// `plan`), whose chosen realizations it places as rigid bodies; absent otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub children: Vec<usize>,
    /// The groups the user declared (ids) whose entities this step is (a node of the core's
    /// DR-plan); absent otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub groups: Vec<String>,
}

/// Why a step's candidates may not be all its real solutions (format §4, "Solving":
/// `incomplete`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct IncompleteReport {
    /// `not-sought`, `core-unsolved`, `unsupported`, `too-many-unknowns`, `too-many-paths`,
    /// `homotopy-budget`, `paths-failed`, `drawing-missed`.
    pub reason: String,
    /// `paths-failed`: the undecided paths; `too-many-paths`: the node's paths (none tracked).
    /// Either way, at most that many complex solutions missed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paths: Option<usize>,
    /// `paths-failed`: the paths tracked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub of: Option<usize>,
    /// `too-many-unknowns`: the node's unknowns.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unknowns: Option<usize>,
    /// The bound exceeded: the most paths, unknowns or node homotopies allowed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub limit: Option<usize>,
    /// `unsupported`: what the node is that the homotopy is not set up for.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

impl IncompleteReport {
    pub(crate) fn new(why: &gcs_solve::alternatives::Shortfall) -> Self {
        use gcs_solve::alternatives::Shortfall;
        let mut r = IncompleteReport {
            reason: why.name().to_owned(),
            paths: None,
            of: None,
            unknowns: None,
            limit: None,
            detail: None,
        };
        match why {
            Shortfall::NotSought | Shortfall::Unsolved | Shortfall::DrawingMissed => {}
            Shortfall::Unsupported(what) => r.detail = Some((*what).to_owned()),
            Shortfall::Unknowns { unknowns, max } => {
                (r.unknowns, r.limit) = (Some(*unknowns), Some(*max))
            }
            Shortfall::Paths { paths, max } => (r.paths, r.limit) = (Some(*paths), Some(*max)),
            Shortfall::Budget { homotopies } => r.limit = Some(*homotopies),
            Shortfall::Failed { failed, tracked } => {
                (r.paths, r.of) = (Some(*failed), Some(*tracked))
            }
        }
        r
    }

    /// The words of the text report (and the navigator's).
    pub(crate) fn text(&self) -> String {
        let n = |v: Option<usize>| v.map_or_else(|| "?".to_owned(), |v| v.to_string());
        match self.reason.as_str() {
            "not-sought" => "solved from the drawing only (--all enumerates)".to_owned(),
            "core-unsolved" => "the core was not solved, so not enumerated".to_owned(),
            "unsupported" => format!(
                "not enumerated: {}",
                self.detail.as_deref().unwrap_or("not a node the homotopy is set up for")
            ),
            "too-many-unknowns" => {
                format!(
                    "not enumerated: {} unknowns, more than {}",
                    n(self.unknowns),
                    n(self.limit)
                )
            }
            "too-many-paths" => format!(
                "not enumerated: {} paths, more than {} (--max-paths): up to {} complex solutions not sought",
                n(self.paths),
                n(self.limit),
                n(self.paths)
            ),
            "homotopy-budget" => {
                format!("not enumerated: the solve's {} node homotopies were spent", n(self.limit))
            }
            "paths-failed" => format!(
                "{} of {} paths undecided: up to {} complex solutions missed",
                n(self.paths),
                n(self.of),
                n(self.paths)
            ),
            "drawing-missed" => {
                "the paths missed the solved realization (added): others may be missing too"
                    .to_owned()
            }
            other => other.to_owned(),
        }
    }
}

/// A bound that cut a search of the solve short (format §4, "Solving": `bounds_hit`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BoundReport {
    /// `reversals`, `placements`, `combinations`, `search-homotopies`, `node-homotopies`,
    /// `max-solutions`, `enumeration-placements`.
    pub bound: String,
    /// Its value.
    pub limit: usize,
}

/// The paths of a core's homotopy (`gcs solve --all`) and what they ended at.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PathsReport {
    /// Paths tracked (the total degree of the core's equations).
    pub tracked: usize,
    /// Distinct finite nonsingular complex solutions.
    pub finite: usize,
    /// Real ones among them: the core's realizations (`candidates`).
    pub real: usize,
    /// Paths that ended neither at a solution nor at infinity (`complete` is then false).
    pub failed: usize,
    /// Paths the Cauchy endgame took to a singular solution (decided: no isolated nonsingular
    /// solution there). Absent when none.
    #[serde(default, skip_serializing_if = "crate::report::is_zero")]
    pub singular: usize,
}

/// One model's solve report, in the order of its fields in the JSON line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveReport {
    /// [`SCHEMA`].
    pub schema: u32,
    /// The model's name.
    pub model: String,
    /// The file, as given.
    pub file: String,
    /// `solved`, `inconsistent` or `failed`.
    pub status: String,
    /// The largest residual of the constraints solved, relative (as `residual`).
    pub max_residual: f64,
    /// The largest displacement of a coordinate (points, centres, radii), in model units.
    pub moved: f64,
    /// The solved entities with their sketch fields, as the model file names them.
    pub entities: Vec<Value>,
    /// The redundant constraints that conflict (a subset of `redundant`).
    pub conflicting: Vec<CheckedReport>,
    /// Every fully redundant constraint, measured at the solution.
    pub redundant: Vec<CheckedReport>,
    /// The parts without a real solution.
    pub no_solution: Vec<NoSolutionReport>,
    /// The orientation conditions (ids) that do not hold at the solution: no realization the
    /// plan reaches turns their way (status `inconsistent`). Absent when every one holds.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub turned: Vec<String>,
    /// The reference (driven) dimensions, measured at the solution. Absent when there are none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub measured: Vec<crate::measured::MeasuredReport>,
    /// The steps of the solve, in order.
    pub plan: Vec<PlanReport>,
    /// Closed-form choices reversed by backtracking.
    pub backtracked: usize,
    /// Whether backtracking hit its bound (over the closed-form steps, or the search over the
    /// core's combinations).
    pub bound_hit: bool,
    /// How many combinations of the core nodes' candidates the autosolve's search tried
    /// (extension; absent when there was no search).
    #[serde(default, skip_serializing_if = "crate::report::is_zero")]
    pub combinations: usize,
    /// Every bound that cut a search of the solve short (extension; absent when none did).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bounds_hit: Vec<BoundReport>,
    /// When the solve failed: the constraint with the largest residual.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub worst: Option<String>,
    /// The relative tolerance.
    pub tolerance: f64,
    /// The model's size: its largest coordinate (at least 1).
    pub scale: f64,
    /// Gauss–Newton steps.
    pub iterations: usize,
    /// The backend whose analysis named the redundant constraints.
    pub analysis_backend: String,
    /// With `--all`: every realization found, each in the shape of `entities` (see
    /// [`gcs_solve::Solution::solutions`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solutions: Option<Vec<Vec<Value>>>,
    /// With `--all`: whether the enumeration stopped at `--max-solutions`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truncated: Option<bool>,
    /// With `--all`: for each of `solutions`, the core's candidate it is built on (for a core
    /// split into several DR-plan nodes, the candidate of its last node, the whole core).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub core_choices: Option<Vec<usize>>,
    /// With `--all`: for each of `solutions`, the candidate of each node of the core's DR-plan
    /// (the first steps of `plan`), a node's counted among those its children's choices give.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub node_choices: Option<Vec<Vec<usize>>>,
    /// For a model read from a CAD file: the import section (flattened into the line).
    #[serde(default, flatten, skip_serializing_if = "Option::is_none")]
    pub import: Option<crate::ImportReport>,
}

fn numbers(x: &[f64]) -> Value {
    Value::Array(x.iter().map(|v| json!(v)).collect())
}

/// An entity's solved sketch fields, as a JSON object with its id (`None` for entities without
/// coordinates of their own: segments, and the named points their curves carry).
fn entity_json(
    system: &System,
    layout: &Layout,
    e: gcs_model::EntityIdx,
    x: &[f64],
) -> Option<Value> {
    let entity = system.entity(e);
    if entity.owner.is_some() {
        return None;
    }
    let cols = layout.columns(e);
    let c = &x[cols];
    let mut m = Map::new();
    m.insert("id".into(), json!(entity.id));
    let coords_of = |p: gcs_model::EntityIdx| {
        let cols = layout.columns(p);
        numbers(&x[cols])
    };
    match &entity.geometry {
        Geometry::Point { .. } => {
            m.insert("at".into(), numbers(c));
        }
        Geometry::Circle { .. } | Geometry::Sphere { .. } => {
            let n = c.len() - 1;
            m.insert("center".into(), numbers(&c[..n]));
            m.insert("radius".into(), json!(c[n]));
        }
        Geometry::Arc { start, end, .. } => {
            let n = c.len() - 1;
            m.insert("center".into(), numbers(&c[..n]));
            m.insert("radius".into(), json!(c[n]));
            m.insert("start".into(), coords_of(*start));
            m.insert("end".into(), coords_of(*end));
        }
        Geometry::Line { .. } | Geometry::Plane { .. } => {
            // Through the representation back to the file's fields.
            let repr = layout.repr(e)?;
            let q: Option<Vec<_>> =
                c.iter().map(|v| gcs_model::number::rational_from_f64_decimal(*v)).collect();
            let g = repr.to_sketch(&q?, &entity.geometry);
            let (Geometry::Line { at: Some([p, r]) } | Geometry::Plane { at: Some([p, r]) }) = g
            else {
                return None;
            };
            let f = |v: &Vec<gcs_rank::BigRational>| {
                numbers(
                    &v.iter()
                        .map(|q| num_traits::ToPrimitive::to_f64(q).unwrap_or(f64::NAN))
                        .collect::<Vec<_>>(),
                )
            };
            m.insert("at".into(), Value::Array(vec![f(&p), f(&r)]));
        }
        Geometry::Segment { .. } | Geometry::BSpline { .. } => return None,
    }
    Some(Value::Object(m))
}

impl SolveReport {
    /// The report of one solved model.
    pub fn new(
        system: &System,
        file: &str,
        solution: &Solution,
        tolerance: f64,
        analysis_backend: &str,
    ) -> SolveReport {
        let layout = Layout::new(system);
        let id = |c: gcs_model::ConstraintIdx| system.constraint(c).id.clone();
        let eid = |e: &gcs_model::EntityIdx| system.entity(*e).id.clone();
        let no_solution = solution
            .no_solution
            .iter()
            .map(|n| NoSolutionReport {
                entities: n.entities.iter().map(eid).collect(),
                constraints: n.constraints.iter().map(|c| id(*c)).collect(),
            })
            .collect();
        let plan = solution
            .plan
            .iter()
            .map(|p| PlanReport {
                entities: p.entities.iter().map(eid).collect(),
                method: p.method.name().to_owned(),
                candidates: p.candidates,
                chosen: p.chosen,
                constraints: p.constraints.iter().map(|c| id(*c)).collect(),
                complete: p.complete,
                fixed: p.fixed,
                paths: p.paths.map(|c| PathsReport {
                    tracked: c.paths,
                    finite: c.finite,
                    real: c.real,
                    failed: c.failed,
                    singular: c.singular,
                }),
                incomplete: p.shortfall.iter().map(IncompleteReport::new).collect(),
                children: p.children.clone(),
                groups: p.groups.iter().map(|g| system.groups()[*g].id.clone()).collect(),
            })
            .collect();
        let shape = |x: &[f64]| -> Vec<Value> {
            system.entity_indices().filter_map(|e| entity_json(system, &layout, e, x)).collect()
        };
        let redundant: Vec<CheckedReport> = solution
            .redundant
            .iter()
            .map(|r| CheckedReport {
                constraint: id(r.constraint),
                residual: r.residual,
                allowance: r.allowance,
                conflicting: r.conflicting,
                spanning_group: r.spanning_group.iter().map(|c| id(*c)).collect(),
            })
            .collect();
        SolveReport {
            schema: SCHEMA,
            model: system.name().to_owned(),
            file: file.to_owned(),
            status: solution.status.name().to_owned(),
            max_residual: solution.max_residual,
            moved: solution.moved,
            entities: shape(&solution.x),
            conflicting: redundant.iter().filter(|r| r.conflicting).cloned().collect(),
            redundant,
            no_solution,
            turned: solution.turned.iter().map(|k| system.orientations()[*k].id.clone()).collect(),
            measured: crate::measured::measured(system, &layout, Some(&solution.x)),
            plan,
            backtracked: solution.backtracked,
            bound_hit: solution.bound_hit,
            combinations: solution.combinations,
            bounds_hit: (solution.bounds_hit.iter())
                .map(|b| BoundReport { bound: b.name().to_owned(), limit: b.limit() })
                .collect(),
            worst: solution.worst.map(id),
            tolerance,
            scale: solution.scale,
            iterations: solution.iterations,
            analysis_backend: analysis_backend.to_owned(),
            solutions: solution
                .solutions
                .as_ref()
                .map(|all| all.iter().map(|x| shape(x)).collect()),
            truncated: solution.solutions.as_ref().map(|_| solution.truncated),
            core_choices: solution.core_choices.clone(),
            node_choices: solution.node_choices.clone(),
            import: None,
        }
    }

    /// The same report with the import section of a model read from a CAD file.
    pub fn with_import(mut self, import: Option<crate::ImportReport>) -> SolveReport {
        self.import = import;
        self
    }

    /// One line of JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_default()
    }

    /// The report for people: the status, the worst residual, how far the drawing moved, the
    /// conflicts in CAD words and the consistent redundancies.
    pub fn text(&self) -> String {
        let mut out = format!("{}: {}\n", self.file, self.model);
        let status = match self.status.as_str() {
            "solved" => "solved: every constraint holds".to_owned(),
            "inconsistent" if self.conflicting.is_empty() && self.no_solution.is_empty() => {
                format!(
                    "INCONSISTENT: {} orientation condition{} cannot hold",
                    self.turned.len(),
                    if self.turned.len() == 1 { "" } else { "s" }
                )
            }
            "inconsistent" if self.conflicting.is_empty() => format!(
                "INCONSISTENT: {} part{} without a real solution (the rest is solved)",
                self.no_solution.len(),
                if self.no_solution.len() == 1 { "" } else { "s" },
            ),
            "inconsistent" => format!(
                "INCONSISTENT: {} redundant constraint{} disagree{} with the others{} (the rest is solved)",
                self.conflicting.len(),
                if self.conflicting.len() == 1 { "" } else { "s" },
                if self.conflicting.len() == 1 { "s" } else { "" },
                match self.no_solution.len() {
                    0 => String::new(),
                    1 => ", 1 part without a real solution".to_owned(),
                    n => format!(", {n} parts without a real solution"),
                }
            ),
            _ => format!(
                "FAILED: the solver did not converge{}",
                self.worst.as_ref().map(|w| format!(" (worst: {w})")).unwrap_or_default()
            ),
        };
        out.push_str(&format!("  status: {status}\n"));
        out.push_str(&format!(
            "  worst residual {:.1e} of the model's size {}; the drawing moved by {:.6} at most\n",
            self.max_residual, self.scale, self.moved
        ));
        if let Some(line) = crate::measured::measured_text(&self.measured, "at the solution") {
            out.push_str(&line);
            out.push('\n');
        }
        for n in &self.no_solution {
            out.push_str(&format!(
                "  no real solution: {} cannot all hold (entities {}): change a value\n",
                n.constraints.join(", "),
                n.entities.join(", ")
            ));
        }
        for o in &self.turned {
            out.push_str(&format!(
                "  orientation {o} does not hold: no realization the plan reaches turns that way (change its sign or a value)\n"
            ));
        }
        let closed = self.plan.iter().filter(|p| p.method == "closed-form").count();
        if closed > 0 {
            out.push_str(&format!(
                "  plan: {} step{}, {closed} of them a point placed in closed form, on the drawing's side{}\n",
                self.plan.len(),
                if self.plan.len() == 1 { "" } else { "s" },
                match self.plan.iter().filter(|p| p.fixed).count() {
                    0 => String::new(),
                    n => format!(" ({n} fixed by --choose)"),
                },
            ));
        }
        if let Some(solutions) = &self.solutions {
            let fixed = self.plan.iter().filter(|p| p.fixed).count();
            let nodes = self.plan.iter().take_while(|p| p.method == "newton").count();
            let core = match self.plan.first().and_then(|p| p.paths.as_ref().map(|c| (p, c))) {
                Some(_) if nodes > 1 => format!(
                    "the core assembled along its DR-plan: {} —",
                    (self.plan[..nodes].iter().enumerate())
                        .map(|(k, p)| {
                            let how = match &p.paths {
                                Some(c) => format!(
                                    "{} real of {} complex on {} paths{}",
                                    p.candidates,
                                    c.finite,
                                    c.tracked,
                                    if c.failed > 0 { ", some undecided" } else { "" }
                                ),
                                None => format!("{} as solved", p.candidates),
                            };
                            if p.children.is_empty() {
                                format!("step {k}: {how}")
                            } else {
                                let children: Vec<String> =
                                    p.children.iter().map(|c| c.to_string()).collect();
                                format!(
                                    "step {k} (steps {} as rigid bodies): {how}",
                                    children.join(", ")
                                )
                            }
                        })
                        .collect::<Vec<_>>()
                        .join("; ")
                ),
                Some((p, c)) => format!(
                    "each of the core's {} real realizations — {} complex, by homotopy continuation on {} paths{} —",
                    p.candidates,
                    c.finite,
                    c.tracked,
                    match c.failed {
                        0 => String::new(),
                        n => format!(", {n} of them undecided: there may be more"),
                    },
                ),
                None => "the core as solved".to_owned(),
            };
            out.push_str(&format!(
                "  realizations: {}{} ({core}, each closed-form point at each of its candidates{}; mirror images distinct)\n",
                solutions.len(),
                if self.truncated == Some(true) { ", more not listed (--max-solutions)" } else { "" },
                match fixed {
                    0 => String::new(),
                    1 => ", one choice fixed".to_owned(),
                    n => format!(", {n} choices fixed"),
                },
            ));
        }
        if self.combinations > 0 {
            // The core's nodes the search took off their candidate 0 (the drawing's).
            let moved: Vec<String> = (self.plan.iter().enumerate())
                .filter(|(_, p)| {
                    p.method == "newton" && !p.fixed && p.chosen.is_some_and(|c| c > 0)
                })
                .map(|(k, p)| format!("step {k} at candidate {}", p.chosen.unwrap_or(0)))
                .collect();
            out.push_str(&format!(
                "  backtracking over the core: {} combination{} of its nodes' candidates tried{}\n",
                self.combinations,
                if self.combinations == 1 { "" } else { "s" },
                if moved.is_empty() {
                    String::new()
                } else {
                    format!(", {} taken (against the drawing's first choice)", moved.join(", "))
                }
            ));
        }
        // Why a step's candidates may not be all (except the default: solved from the
        // drawing, nothing sought).
        for (k, p) in self.plan.iter().enumerate() {
            let why: Vec<String> = (p.incomplete.iter())
                .filter(|i| i.reason != "not-sought")
                .map(IncompleteReport::text)
                .collect();
            if !why.is_empty() {
                out.push_str(&format!(
                    "  step {k} not completely enumerated: {}\n",
                    why.join("; ")
                ));
            }
        }
        if !self.bounds_hit.is_empty() {
            let bounds: Vec<String> =
                self.bounds_hit.iter().map(|b| format!("{} ({})", b.bound, b.limit)).collect();
            out.push_str(&format!("  bounds that cut a search short: {}\n", bounds.join(", ")));
        }
        if self.bound_hit {
            out.push_str(&format!(
                "  backtracking stopped at its bound after reversing {} choices{}\n",
                self.backtracked,
                if self.combinations > 0 {
                    format!(" and trying {} combinations of the core's nodes", self.combinations)
                } else {
                    String::new()
                }
            ));
        }
        for r in &self.redundant {
            if r.conflicting {
                out.push_str(&format!(
                    "  conflicting: {} {}: change one value or delete one of them\n",
                    r.constraint,
                    off_by(r.residual, r.allowance, &r.spanning_group)
                ));
            } else {
                out.push_str(&format!(
                    "  redundant (consistent): {}: remove it or one of: {}\n",
                    r.constraint,
                    r.spanning_group.join(", ")
                ));
            }
        }
        out.truncate(out.trim_end().len());
        out
    }
}

/// How far a conflicting constraint is off, against what its written precision allows, and
/// what it conflicts with: the words `gcs solve` and `gcs analyze` share.
pub(crate) fn off_by(residual: f64, allowance: f64, group: &[String]) -> String {
    format!(
        "is off by {residual:.6} (written precision allows {allowance:.1e}) given {}",
        group.join(", ")
    )
}
