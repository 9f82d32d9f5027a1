//! What every front end runs on a model — the `gcs` binary, the Python and the WASM bindings —
//! written once so that they cannot disagree: reading the models of a file's bytes, analysing
//! one with the options of `gcs analyze` (with the solve at the values that tells consistent
//! redundant constraints from conflicting ones), solving one as `gcs solve` does, and the
//! Jacobian at the witness as plain numbers.
//!
//! Nothing here computes: it calls the library crates in the order the CLI always has, and
//! returns the reports of this crate. Front ends only read files and convert.
//!
//! # Example
//! ```
//! use gcs_report::run::{AnalyzeOptions, analyze, read_models};
//! let text = r#"System(name: "bar", dim: 2,
//!     entities: [Point(id: "p", at: [0, 0]), Point(id: "q", at: [3, 4])],
//!     constraints: [Distance(id: "d", a: "p", b: "q", value: 5)])"#;
//! let models = read_models("bar.ron", text.as_bytes(), None).unwrap();
//! let m = &models[0];
//! let analyzed = analyze(&m.system, &AnalyzeOptions::default()).unwrap();
//! let report = analyzed.report(&m.system, "bar.ron", m.import.clone());
//! assert_eq!((report.rank, report.dof), (1, 0));
//! ```

use gcs_analysis::{Analysis, AnalysisError, AnalysisOptions, Backend};
use gcs_jacobian::{Layout, RowOwner, WitnessOptions};
use gcs_model::System;
use gcs_solve::{Solution, SolveOptions};
use num_traits::ToPrimitive;

use crate::{ImportReport, Report, ReportError, SolveReport, Structural};

/// One model of a file: the validated system and, for a sketch of a CAD file, its import
/// section.
#[derive(Clone, Debug)]
pub struct Model {
    /// The system.
    pub system: System,
    /// The import section (`None` for a RON model).
    pub import: Option<ImportReport>,
}

impl Model {
    /// How messages name this model when it fails: the file, and the sketch of a CAD file
    /// (which holds several).
    pub fn at(&self, file: &str) -> String {
        match &self.import {
            Some(_) => format!("{file}: {}", self.system.name()),
            None => file.to_owned(),
        }
    }
}

/// How to read a file's bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputFormat {
    /// A gcs model in RON (format §1).
    Ron,
    /// A CAD file of one of the formats of `gcs-import`.
    Cad(gcs_import::Format),
}

impl InputFormat {
    /// The format of a name as front ends accept it: `ron`, `slvs`, `fcstd`/`freecad`,
    /// `onshape`/`json` (any case).
    pub fn from_name(name: &str) -> Option<InputFormat> {
        match name.to_ascii_lowercase().as_str() {
            "ron" => Some(InputFormat::Ron),
            "slvs" | "solvespace" => Some(InputFormat::Cad(gcs_import::Format::Slvs)),
            "fcstd" | "freecad" => Some(InputFormat::Cad(gcs_import::Format::FreeCad)),
            "onshape" | "json" => Some(InputFormat::Cad(gcs_import::Format::Onshape)),
            _ => None,
        }
    }
}

/// The models of one file's bytes: a RON model, or each sketch of a CAD file in the file's
/// order. `file` names the file in reports and errors (and gives the default model name).
/// Without a `format`, a `.ron` file is RON, anything else is recognised by
/// [`gcs_import::Format::detect`] (extension, then content) or else read as RON.
///
/// # Errors
/// The model error (file, line, column, id), the import error (file, line, element), a CAD
/// file without a sketch, or bytes that are neither text nor a CAD file.
pub fn read_models(
    file: &str,
    bytes: &[u8],
    format: Option<InputFormat>,
) -> Result<Vec<Model>, ReportError> {
    let format = format.or_else(|| {
        let is_ron =
            std::path::Path::new(file).extension().is_some_and(|e| e.eq_ignore_ascii_case("ron"));
        match is_ron {
            true => Some(InputFormat::Ron),
            false => gcs_import::Format::detect(file, bytes).map(InputFormat::Cad),
        }
    });
    match format {
        Some(InputFormat::Cad(f)) => {
            let sketches = gcs_import::read(f, file, bytes).map_err(ReportError::Import)?;
            if sketches.is_empty() {
                return Err(ReportError::NoSketch { file: file.to_owned() });
            }
            Ok(sketches
                .iter()
                .map(|s| {
                    let lowered = gcs_import::lower(s);
                    Model { import: Some(ImportReport::new(&lowered)), system: lowered.system }
                })
                .collect())
        }
        Some(InputFormat::Ron) | None => {
            let text = std::str::from_utf8(bytes)
                .map_err(|_| ReportError::NotText { file: file.to_owned() })?;
            let system = System::from_ron_str(text, Some(file)).map_err(ReportError::Model)?;
            Ok(vec![Model { system, import: None }])
        }
    }
}

/// The one model a front end asked for among the models of a file: the model named `sketch`,
/// or, without a name, the file's only model.
///
/// # Errors
/// No model of that name, or several models and no name ([`ReportError::NoSuchSketch`], which
/// lists the names).
pub fn pick(models: Vec<Model>, file: &str, sketch: Option<&str>) -> Result<Model, ReportError> {
    let names = || models.iter().map(|m| m.system.name().to_owned()).collect();
    let found = match sketch {
        Some(name) => models.iter().position(|m| m.system.name() == name),
        None if models.len() == 1 => Some(0),
        None => None,
    };
    match found {
        Some(i) => Ok(models.into_iter().nth(i).expect("an index found in the models")),
        None => Err(ReportError::NoSuchSketch {
            file: file.to_owned(),
            wanted: sketch.map(str::to_owned),
            names: names(),
        }),
    }
}

/// The options of `gcs analyze` that change a report.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalyzeOptions {
    /// The arithmetic (`--backend`; the float backend carries `--tolerance`).
    pub backend: Backend,
    /// The seed of the witness (`--seed`).
    pub seed: u64,
    /// Add the structural section (`--structural`).
    pub structural: bool,
    /// W-decompose every cluster (`--decompose`).
    pub decompose: bool,
    /// Decide 2D bar frameworks by the pebble game (not `--no-pebble-game`; see
    /// [`AnalysisOptions::pebble_game`]).
    pub pebble_game: bool,
}

impl Default for AnalyzeOptions {
    fn default() -> Self {
        AnalyzeOptions {
            backend: Backend::Exact,
            seed: 1,
            structural: false,
            decompose: false,
            pebble_game: true,
        }
    }
}

/// The most unknowns `gcs analyze` solves for to check redundant constraints against the
/// values (the solver's steps are dense: `gcs solve` takes more).
pub const ANALYZE_SOLVE_LIMIT: usize = 1_000;

/// One model analysed: the analysis, the structural methods beside it when asked, and the
/// solve at the values when it has redundant constraints.
pub struct Analyzed {
    /// The witness analysis.
    pub analysis: Analysis,
    /// The structural methods (with [`AnalyzeOptions::structural`]).
    pub structural: Option<Structural>,
    /// The model solved at its values, to tell redundant constraints that agree from those
    /// that conflict (`None` without redundancy, without a complete drawing to start from, or
    /// when it is too large for the solver: the report then says only "redundant").
    pub solution: Option<Solution>,
}

impl Analyzed {
    /// The report as data: the JSON line of `gcs analyze --format json` is its
    /// [`Report::to_json`].
    pub fn report(&self, system: &System, file: &str, import: Option<ImportReport>) -> Report {
        let mut report = Report::new(system, file, &self.analysis, self.structural.as_ref());
        if let Some(sol) = &self.solution {
            report = report.with_solution(system, sol);
        }
        report.with_import(import)
    }

    /// The text report of `gcs analyze`, with the import section of a CAD sketch after its
    /// first line.
    pub fn text(&self, system: &System, file: &str, import: Option<&ImportReport>) -> String {
        let text = crate::text_with_solution(
            system,
            file,
            &self.analysis,
            self.structural.as_ref(),
            self.solution.as_ref(),
        );
        with_import_text(&text, import)
    }
}

/// A text report with the import section of a CAD sketch after its first line.
pub fn with_import_text(text: &str, import: Option<&ImportReport>) -> String {
    let Some(import) = import else { return text.to_owned() };
    match text.split_once('\n') {
        Some((first, rest)) => format!("{first}\n{}{rest}", import.text()),
        None => format!("{text}\n{}", import.text().trim_end()),
    }
}

/// Analyses one model as `gcs analyze` does.
///
/// # Errors
/// The analysis failed (no witness, an exact backend at an approximate witness: see
/// [`ReportError::Analysis`]), or the structural section did.
pub fn analyze(system: &System, options: &AnalyzeOptions) -> Result<Analyzed, ReportError> {
    let analysis_options = AnalysisOptions {
        backend: options.backend,
        witness: WitnessOptions { seed: options.seed, ..WitnessOptions::default() },
        decompose: options.decompose,
        pebble_game: options.pebble_game,
        ..AnalysisOptions::default()
    };
    let analysis =
        gcs_analysis::analyze(system, &analysis_options).map_err(ReportError::Analysis)?;
    let structural =
        if options.structural { Some(Structural::new(system, &analysis)?) } else { None };
    let solution = if analysis.sketch.is_none() || analysis.redundant.iter().all(|r| r.rows < r.doc)
    {
        None
    } else {
        let options = SolveOptions { max_unknowns: ANALYZE_SOLVE_LIMIT, ..SolveOptions::default() };
        gcs_solve::solve(system, &analysis, &options).ok()
    };
    Ok(Analyzed { analysis, structural, solution })
}

/// The analysis a solve rests on: the exact one, or, where it finds no exact witness, the
/// float one; with the name of its backend.
///
/// # Errors
/// The analysis failed.
pub fn solving_analysis(
    system: &System,
) -> Result<(gcs_analysis::Analysis, &'static str), ReportError> {
    match gcs_analysis::analyze(system, &AnalysisOptions::default()) {
        Ok(a) => Ok((a, "exact")),
        Err(AnalysisError::ApproximateWitness(_) | AnalysisError::NoModularWitness(_)) => {
            let float = AnalysisOptions {
                backend: Backend::Float { tolerance: 1e-9 },
                ..AnalysisOptions::default()
            };
            Ok((gcs_analysis::analyze(system, &float).map_err(ReportError::Analysis)?, "float"))
        }
        Err(e) => Err(ReportError::Analysis(e)),
    }
}

/// One model solved as `gcs solve` does: the redundant constraints from the exact analysis
/// (or, where it finds no exact witness, the float one), the solve at the values, its report.
///
/// # Errors
/// The analysis or the solve failed.
pub fn solve(
    system: &System,
    file: &str,
    import: Option<ImportReport>,
    options: &SolveOptions,
) -> Result<(SolveReport, Solution), ReportError> {
    let (analysis, backend) = solving_analysis(system)?;
    let solution = gcs_solve::solve(system, &analysis, options).map_err(ReportError::Solve)?;
    let report =
        SolveReport::new(system, file, &solution, options.tolerance, backend).with_import(import);
    Ok((report, solution))
}

/// The Jacobian of a system at the witness of its analysis, as coordinates (row, column,
/// value) of its nonzero entries, with what each row and column stands for.
#[derive(Clone, Debug, PartialEq)]
pub struct JacobianEntries {
    /// Rows: entity-internal rows first, then each constraint's rows in file order.
    pub nrows: usize,
    /// Columns: the coordinates of the entities in file order.
    pub ncols: usize,
    /// The nonzero entries, row by row, as the nearest doubles of the exact values.
    pub entries: Vec<(usize, usize, f64)>,
    /// For each row, the id of its constraint, or of its entity for an internal row.
    pub row_ids: Vec<String>,
    /// For each row, whether it is an entity-internal row (normalisation, Plücker relation).
    pub row_internal: Vec<bool>,
    /// For each column, `entity[k]`: the k-th coordinate of that entity.
    pub columns: Vec<String>,
}

/// The Jacobian at the witness [`analyze`] would take with these options (the one whose rank
/// the report gives; the clusters and the global rigidity, which do not change the witness,
/// are not computed).
///
/// # Errors
/// As [`analyze`] and [`jacobian`].
pub fn jacobian_at_witness(
    system: &System,
    options: &AnalyzeOptions,
) -> Result<JacobianEntries, ReportError> {
    let analysis_options = AnalysisOptions {
        backend: options.backend,
        witness: WitnessOptions { seed: options.seed, ..WitnessOptions::default() },
        clusters: false,
        global_rigidity: false,
        ..AnalysisOptions::default()
    };
    let analysis =
        gcs_analysis::analyze(system, &analysis_options).map_err(ReportError::Analysis)?;
    jacobian(system, &analysis)
}

/// The Jacobian at the witness of `analysis` (the one whose rank the report gives), exactly
/// assembled and rounded to doubles.
///
/// # Errors
/// At a modular witness (the prime-field backends' last resort) there are no rational
/// coordinates to give ([`ReportError::Jacobian`]).
pub fn jacobian(system: &System, analysis: &Analysis) -> Result<JacobianEntries, ReportError> {
    let layout = Layout::new(system);
    let j = analysis
        .witness
        .jacobian::<gcs_rank::BigRational>(system, &layout)
        .map_err(ReportError::Jacobian)?;
    let mut entries = Vec::new();
    for (i, row) in j.rows.iter().enumerate() {
        for (c, v) in row.entries() {
            entries.push((i, *c, v.to_f64().unwrap_or(f64::NAN)));
        }
    }
    let (row_ids, row_internal) = j
        .owners
        .iter()
        .map(|o| match o {
            RowOwner::Internal(e) => (system.entity(*e).id.clone(), true),
            RowOwner::Constraint(c) => (system.constraint(*c).id.clone(), false),
        })
        .unzip();
    let mut columns = Vec::with_capacity(layout.ncols());
    for e in system.entity_indices() {
        for (k, _) in layout.columns(e).enumerate() {
            columns.push(format!("{}[{k}]", system.entity(e).id));
        }
    }
    Ok(JacobianEntries {
        nrows: j.rows.len(),
        ncols: j.ncols,
        entries,
        row_ids,
        row_internal,
        columns,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const BAR: &str = r#"System(name: "bar", dim: 2,
        entities: [Point(id: "p", at: [0, 0]), Point(id: "q", at: [3, 4]),
                   Line(id: "l", at: [[0, 1], [1, 1]])],
        constraints: [Distance(id: "d", a: "p", b: "q", value: 5),
                      Distance(id: "e", a: "q", b: "p", value: 5)])"#;

    #[test]
    fn pick_takes_the_only_model_or_the_named_one() {
        let models = read_models("bar.ron", BAR.as_bytes(), None).unwrap();
        assert_eq!(pick(models.clone(), "bar.ron", None).unwrap().system.name(), "bar");
        assert_eq!(pick(models.clone(), "bar.ron", Some("bar")).unwrap().system.name(), "bar");
        let e = pick(models, "bar.ron", Some("foo")).unwrap_err();
        assert_eq!(e.to_string(), r#"bar.ron: no sketch named "foo"; its models: bar"#);
    }

    #[test]
    fn read_errors_keep_their_location() {
        let e = read_models("x.ron", b"System(dim: 4)", None).unwrap_err();
        assert!(matches!(&e, ReportError::Model(m) if m.position.is_some()), "{e:?}");
        assert!(e.to_string().starts_with("x.ron:1:"), "{e}");
        let e = read_models("x.bin", &[0xff, 0xfe], None).unwrap_err();
        assert_eq!(e, ReportError::NotText { file: "x.bin".into() });
        assert_eq!(
            InputFormat::from_name("FCStd"),
            Some(InputFormat::Cad(gcs_import::Format::FreeCad))
        );
        assert_eq!(InputFormat::from_name("step"), None);
    }

    #[test]
    fn the_jacobian_names_its_rows_and_columns() {
        let m = &read_models("bar.ron", BAR.as_bytes(), None).unwrap()[0];
        let j = jacobian_at_witness(&m.system, &AnalyzeOptions::default()).unwrap();
        assert_eq!(j.columns.len(), j.ncols);
        assert_eq!((j.row_ids.len(), j.row_internal.len()), (j.nrows, j.nrows));
        // The line's internal row (if its representation has one) comes first, then d and e.
        let constraint_rows: Vec<&str> = j
            .row_ids
            .iter()
            .zip(&j.row_internal)
            .filter(|(_, internal)| !**internal)
            .map(|(id, _)| id.as_str())
            .collect();
        assert_eq!(constraint_rows, ["d", "e"]);
        assert!(j.columns.starts_with(&["p[0]".to_owned(), "p[1]".to_owned(), "q[0]".to_owned()]));
        // d and e have the same row: the gradient of |p − q|² (up to the law's scaling).
        let row = |id: &str| -> Vec<(usize, f64)> {
            let i = j.row_ids.iter().position(|r| r == id).unwrap();
            j.entries.iter().filter(|e| e.0 == i).map(|e| (e.1, e.2)).collect()
        };
        assert_eq!(row("d").len(), 4);
        let analyzed = analyze(&m.system, &AnalyzeOptions::default()).unwrap();
        assert_eq!(analyzed.analysis.redundant.len(), 1);
    }
}
