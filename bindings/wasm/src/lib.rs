//! `gcs-wasm`: gcs in the browser and in node, through wasm-bindgen. Thin conversions over
//! [`gcs_report::run`], the functions the `gcs` binary calls: every function returns the
//! object of the CLI's JSON line (`JSON.parse` of it), so the web and the CLI cannot disagree.

use gcs_analysis::Backend;
use gcs_report::run::{self, AnalyzeOptions, InputFormat, Model};
use gcs_report::{CheckReport, failure_json};
use serde::Deserialize;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const TYPES: &str = r#"
/** A model: RON text, or a CAD file (.slvs, Onshape JSON as text; .FCStd as bytes). */
export type Input = string | Uint8Array;
/** The options of every function (all optional). */
export interface Options {
  /** The name of the input in reports and errors (default "<string>"); its extension picks the format. */
  file?: string;
  format?: "ron" | "slvs" | "fcstd" | "onshape";
  /** The model of a CAD file with several sketches. */
  sketch?: string;
  backend?: "exact" | "rational" | "modp" | "float";
  tolerance?: number;
  seed?: number;
  structural?: boolean;
  decompose?: boolean;
  maxIterations?: number;
}
/** A redundant constraint (docs/format.md §2). */
export interface Redundant {
  constraint: string; rows: number; doc: number; spanning_group: string[];
  conflicting?: boolean; residual?: number; allowance?: number;
  [field: string]: unknown;
}
/** The line of `gcs analyze --format json` (docs/format.md §2–§4; more fields may be present). */
export interface Report {
  schema: number; model: string; file: string; dim: number; backend: string; witness: string;
  entities: number; constraints: number; unknowns: number; equations: number; rank: number;
  dof_absolute: number; trivial_motions: number; dof: number; rigid: boolean;
  well_constrained: boolean; redundant: Redundant[];
  clusters: { entities: string[]; constraints: string[]; [field: string]: unknown }[];
  [field: string]: unknown;
}
/** The line of a model that failed. */
export interface Failure { schema: number; file: string; error: string; }
/** A redundant constraint measured at the solution. */
export interface Checked {
  constraint: string; residual: number; allowance: number; conflicting: boolean; spanning_group: string[];
}
/** Why a step's candidates may not be all its real solutions (`PlanStep.incomplete`). */
export interface Incomplete {
  reason: "not-sought" | "core-unsolved" | "unsupported" | "too-many-unknowns" | "too-many-paths"
    | "homotopy-budget" | "paths-failed" | "drawing-missed";
  /** paths-failed: the undecided paths; too-many-paths: the node's paths (at most that many complex solutions missed). */
  paths?: number;
  /** paths-failed: the paths tracked. */
  of?: number;
  /** too-many-unknowns: the node's unknowns. */
  unknowns?: number;
  /** The bound exceeded (paths, unknowns or node homotopies). */
  limit?: number;
  /** unsupported: what the node is. */
  detail?: string;
}
/** A homotopy's paths and what they ended at. */
export interface Paths { tracked: number; finite: number; real: number; failed: number; singular?: number; }
/** A step of the solve (`plan`). */
export interface PlanStep {
  entities: string[]; method: "closed-form" | "newton"; candidates: number; chosen: number | null;
  constraints: string[]; complete: boolean; fixed: boolean; paths?: Paths;
  incomplete?: Incomplete[]; children?: number[]; groups?: string[];
}
/** A bound that cut a search of the solve short. */
export interface BoundHit {
  bound: "reversals" | "placements" | "combinations" | "search-homotopies" | "node-homotopies"
    | "max-solutions" | "enumeration-placements";
  limit: number;
}
/** The line of `gcs solve --format json` (docs/format.md §4, "Solving"). */
export interface SolveReport {
  schema: number; model: string; file: string; status: "solved" | "inconsistent" | "failed";
  max_residual: number; moved: number; entities: { id: string; [field: string]: unknown }[];
  conflicting: Checked[]; redundant: Checked[];
  no_solution: { entities: string[]; constraints: string[] }[];
  turned?: string[]; measured?: { [field: string]: unknown }[];
  plan: PlanStep[]; backtracked: number; bound_hit: boolean; combinations?: number;
  bounds_hit?: BoundHit[];
  worst?: string; tolerance: number; scale: number; iterations: number; analysis_backend: string;
  /** With `--all` (the CLI's): the realizations, each in the shape of `entities`. */
  solutions?: { id: string; [field: string]: unknown }[][];
  truncated?: boolean; core_choices?: number[]; node_choices?: number[][];
  [field: string]: unknown;
}
/** The line of `gcs check --format json`. */
export interface CheckReport {
  schema: number; model: string; file: string; dim: number; entities: number; constraints: number;
  entity_dof: number; constraint_doc: number; naive_dof: number; displacements: number;
  [field: string]: unknown;
}
"#;

/// The options every function takes (all optional; unknown ones are an error).
#[derive(Deserialize, Default)]
#[serde(default, deny_unknown_fields, rename_all = "camelCase")]
struct Options {
    /// The name of the input in reports and errors (default `<string>`; its extension picks
    /// the format when `format` is not given).
    file: Option<String>,
    /// `ron`, `slvs`, `fcstd`, `onshape` (default: by `file`'s extension, then content).
    format: Option<String>,
    /// The model to take from a CAD file with several sketches.
    sketch: Option<String>,
    /// `exact` (default), `rational`, `modp`, `float`.
    backend: Option<String>,
    /// The float backend's relative tolerance (default 1e-9); the solver's (default 1e-9).
    tolerance: Option<f64>,
    /// The witness seed (default 1).
    seed: Option<u64>,
    /// Add the structural section.
    structural: bool,
    /// Add the W-decompositions.
    decompose: bool,
    /// The solver's most steps (default 500).
    max_iterations: Option<usize>,
}

fn options(value: JsValue) -> Result<Options, JsError> {
    if value.is_undefined() || value.is_null() {
        return Ok(Options::default());
    }
    let text: String = js_sys::JSON::stringify(&value)
        .map_err(|_| JsError::new("options: not a plain object"))?
        .into();
    serde_json::from_str(&text).map_err(|e| JsError::new(&format!("options: {e}")))
}

fn parse(line: &str) -> Result<JsValue, JsError> {
    js_sys::JSON::parse(line).map_err(|_| JsError::new("internal error: a report is not JSON"))
}

/// The bytes of a string or a `Uint8Array` (a FreeCAD file is a zip).
fn bytes(input: &JsValue) -> Result<Vec<u8>, JsError> {
    if let Some(s) = input.as_string() {
        return Ok(s.into_bytes());
    }
    if let Some(a) = input.dyn_ref::<js_sys::Uint8Array>() {
        return Ok(a.to_vec());
    }
    Err(JsError::new("input: expected a string or a Uint8Array"))
}

fn read(input: &JsValue, o: &Options) -> Result<(String, Vec<Model>), JsError> {
    let file = o.file.clone().unwrap_or_else(|| "<string>".to_owned());
    let format = match &o.format {
        None => None,
        Some(name) => Some(InputFormat::from_name(name).ok_or_else(|| {
            JsError::new(&format!("format {name:?}: expected ron, slvs, fcstd or onshape"))
        })?),
    };
    let models = run::read_models(&file, &bytes(input)?, format).map_err(error)?;
    Ok((file, models))
}

fn one(input: &JsValue, o: &Options) -> Result<(String, Model), JsError> {
    let (file, models) = read(input, o)?;
    let model = run::pick(models, &file, o.sketch.as_deref()).map_err(error)?;
    Ok((file, model))
}

fn error(e: gcs_report::ReportError) -> JsError {
    JsError::new(&e.to_string())
}

fn analyze_options(o: &Options) -> Result<AnalyzeOptions, JsError> {
    let tolerance = o.tolerance.unwrap_or(1e-9);
    let backend = match o.backend.as_deref().unwrap_or("exact") {
        "exact" => Backend::Exact,
        "rational" => Backend::Rational,
        "modp" => Backend::ModP,
        "float" => Backend::Float { tolerance },
        other => {
            return Err(JsError::new(&format!(
                "backend {other:?}: expected exact, rational, modp or float"
            )));
        }
    };
    Ok(AnalyzeOptions {
        backend,
        seed: o.seed.unwrap_or(1),
        structural: o.structural,
        decompose: o.decompose,
        ..AnalyzeOptions::default()
    })
}

/// The analysis of a model (RON text, or a CAD file's text or bytes): the object of the line
/// of `gcs analyze --format json` (docs/format.md §2–§4). Throws an `Error` whose message
/// names the file, line and id when the model cannot be read or analysed.
#[wasm_bindgen(unchecked_return_type = "Report")]
pub fn analyze(
    #[wasm_bindgen(unchecked_param_type = "Input")] input: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Options | undefined")] options: JsValue,
) -> Result<JsValue, JsError> {
    let o = self::options(options)?;
    let settings = analyze_options(&o)?;
    let (file, m) = one(&input, &o)?;
    let analyzed = run::analyze(&m.system, &settings).map_err(error)?;
    parse(&analyzed.report(&m.system, &file, m.import).to_json())
}

/// Every model of the input analysed, as `gcs analyze --format json` prints them: one object
/// per model (per sketch of a CAD file), a model that fails as its failure object
/// (`{"schema", "file", "error"}`).
#[wasm_bindgen(js_name = analyzeAll, unchecked_return_type = "Array<Report | Failure>")]
pub fn analyze_all(
    #[wasm_bindgen(unchecked_param_type = "Input")] input: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Options | undefined")] options: JsValue,
) -> Result<js_sys::Array, JsError> {
    let o = self::options(options)?;
    let settings = analyze_options(&o)?;
    let (file, models) = read(&input, &o)?;
    let out = js_sys::Array::new();
    for m in models {
        let at = m.at(&file);
        let line = match run::analyze(&m.system, &settings) {
            Ok(a) => a.report(&m.system, &file, m.import).to_json(),
            Err(e) => failure_json(&file, &format!("{at}: {e}")),
        };
        out.push(&parse(&line)?);
    }
    Ok(out)
}

/// The solve of a model at its values: the object of the line of `gcs solve --format json`.
#[wasm_bindgen(unchecked_return_type = "SolveReport")]
pub fn solve(
    #[wasm_bindgen(unchecked_param_type = "Input")] input: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Options | undefined")] options: JsValue,
) -> Result<JsValue, JsError> {
    let o = self::options(options)?;
    let solve_options = gcs_solve::SolveOptions {
        tolerance: o.tolerance.unwrap_or(1e-9),
        max_iterations: o.max_iterations.unwrap_or(500),
        ..gcs_solve::SolveOptions::default()
    };
    let (file, m) = one(&input, &o)?;
    let (report, _) = run::solve(&m.system, &file, m.import, &solve_options).map_err(error)?;
    parse(&report.to_json())
}

/// The counts of a model: the object of the line of `gcs check --format json`.
#[wasm_bindgen(unchecked_return_type = "CheckReport")]
pub fn check(
    #[wasm_bindgen(unchecked_param_type = "Input")] input: JsValue,
    #[wasm_bindgen(unchecked_param_type = "Options | undefined")] options: JsValue,
) -> Result<JsValue, JsError> {
    let o = self::options(options)?;
    let (file, m) = one(&input, &o)?;
    parse(&CheckReport::new(&m.system, &file).with_import(m.import).to_json())
}

/// The version of gcs.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_owned()
}
