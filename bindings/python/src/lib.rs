//! `gcs._gcs`, the native module of the Python package `gcs`: thin conversions over
//! [`gcs_report::run`], the functions the `gcs` binary calls. Every report crosses as the JSON
//! line of the CLI (the package parses it), so Python and the CLI cannot disagree. The GIL is
//! released while a model is read, analysed or solved.

use gcs_analysis::Backend;
use gcs_report::ReportError;
use gcs_report::run::{self, AnalyzeOptions, InputFormat};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

create_exception!(
    _gcs,
    GcsError,
    PyException,
    "An error of gcs. Attributes: `message`; `file`, `line`, `column`, `id`, `element` where known (else None)."
);
create_exception!(
    _gcs,
    ReadError,
    GcsError,
    "A model or CAD file that cannot be read, or is not a valid model."
);
create_exception!(
    _gcs,
    AnalysisError,
    GcsError,
    "A model that cannot be analysed (no witness, an exact backend at an approximate witness)."
);
create_exception!(_gcs, SolveError, GcsError, "A model that cannot be solved.");

/// The Python exception of an error, with its location as attributes.
fn to_py(e: ReportError) -> PyErr {
    to_py_at(e, None)
}

/// The same for an error of a model read from `file` (the model's `at`: its file, and the
/// sketch of a CAD file), named as the CLI names it: `at: message`.
fn to_py_at(e: ReportError, model: Option<(&str, &str)>) -> PyErr {
    let mut message = e.to_string();
    let mut file = None;
    if let Some((f, at)) = model {
        message = format!("{at}: {message}");
        file = Some(f.to_owned());
    }
    let (mut line, mut column, mut id, mut element) = (None, None, None, None);
    let err = match &e {
        ReportError::Model(m) => {
            file = m.origin.clone();
            line = m.position.map(|p| p.line);
            column = m.position.map(|p| p.column);
            id = m.kind.id().map(str::to_owned);
            ReadError::new_err(message.clone())
        }
        ReportError::Import(i) => {
            file = Some(i.file.clone());
            line = i.line;
            element = i.element.clone();
            ReadError::new_err(message.clone())
        }
        ReportError::NoSketch { file: f }
        | ReportError::NotText { file: f }
        | ReportError::NoSuchSketch { file: f, .. } => {
            file = Some(f.clone());
            ReadError::new_err(message.clone())
        }
        ReportError::Solve(_) => SolveError::new_err(message.clone()),
        _ => AnalysisError::new_err(message.clone()),
    };
    Python::attach(|py| {
        let value = err.value(py);
        let _ = value.setattr("message", message);
        let _ = value.setattr("file", file);
        let _ = value.setattr("line", line);
        let _ = value.setattr("column", column);
        let _ = value.setattr("id", id);
        let _ = value.setattr("element", element);
    });
    err
}

/// One model: a RON model, or one sketch of a CAD file.
#[pyclass(module = "gcs._gcs", frozen)]
struct NativeModel {
    model: run::Model,
    file: String,
}

fn backend(name: &str, tolerance: f64) -> PyResult<Backend> {
    let b = match name {
        "exact" => Backend::Exact,
        "rational" => Backend::Rational,
        "rug" => Backend::Rug,
        "modp" => Backend::ModP,
        "float" => Backend::Float { tolerance },
        _ => {
            return Err(PyValueError::new_err(format!(
                "backend {name:?}: expected exact, rational, rug, modp or float"
            )));
        }
    };
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(PyValueError::new_err("tolerance must be a finite number ≥ 0"));
    }
    if !b.available() {
        return Err(PyValueError::new_err("the rug backend is not in this build"));
    }
    Ok(b)
}

impl NativeModel {
    fn error(&self, e: ReportError) -> PyErr {
        to_py_at(e, Some((&self.file, &self.model.at(&self.file))))
    }
}

#[pymethods]
impl NativeModel {
    /// The model's name.
    #[getter]
    fn name(&self) -> &str {
        self.model.system.name()
    }

    /// The dimension, 2 or 3.
    #[getter]
    fn dim(&self) -> usize {
        match self.model.system.dim() {
            gcs_model::Dim::Two => 2,
            gcs_model::Dim::Three => 3,
        }
    }

    /// The file it was read from, as given (the reports' `file`).
    #[getter]
    fn file(&self) -> &str {
        &self.file
    }

    /// The model as RON text (format §1).
    fn to_ron(&self) -> String {
        self.model.system.to_ron()
    }

    /// `gcs check --format json`'s line.
    fn check_json(&self) -> String {
        gcs_report::CheckReport::new(&self.model.system, &self.file)
            .with_import(self.model.import.clone())
            .to_json()
    }

    /// `gcs analyze --format json`'s line.
    #[pyo3(signature = (backend="exact", tolerance=1e-9, seed=1, structural=false, decompose=false))]
    fn analyze_json(
        &self,
        py: Python<'_>,
        backend: &str,
        tolerance: f64,
        seed: u64,
        structural: bool,
        decompose: bool,
    ) -> PyResult<String> {
        let options = AnalyzeOptions {
            backend: self::backend(backend, tolerance)?,
            seed,
            structural,
            decompose,
            ..AnalyzeOptions::default()
        };
        let system = &self.model.system;
        let result = py.detach(|| {
            run::analyze(system, &options)
                .map(|a| a.report(system, &self.file, self.model.import.clone()).to_json())
        });
        result.map_err(|e| self.error(e))
    }

    /// `gcs solve --format json`'s line.
    #[pyo3(signature = (tolerance=1e-9, max_iterations=500, max_unknowns=None))]
    fn solve_json(
        &self,
        py: Python<'_>,
        tolerance: f64,
        max_iterations: usize,
        max_unknowns: Option<usize>,
    ) -> PyResult<String> {
        let default = gcs_solve::SolveOptions::default();
        let options = gcs_solve::SolveOptions {
            tolerance,
            max_iterations,
            max_unknowns: max_unknowns.unwrap_or(default.max_unknowns),
            ..default
        };
        let system = &self.model.system;
        let result = py.detach(|| {
            run::solve(system, &self.file, self.model.import.clone(), &options)
                .map(|(r, _)| r.to_json())
        });
        result.map_err(|e| self.error(e))
    }

    /// The Jacobian at the witness: `(nrows, ncols, rows, cols, values, row_ids, row_internal,
    /// columns)`, its nonzero entries as coordinates.
    #[pyo3(signature = (backend="exact", tolerance=1e-9, seed=1))]
    #[allow(clippy::type_complexity)]
    fn jacobian(
        &self,
        py: Python<'_>,
        backend: &str,
        tolerance: f64,
        seed: u64,
    ) -> PyResult<(
        usize,
        usize,
        Vec<usize>,
        Vec<usize>,
        Vec<f64>,
        Vec<String>,
        Vec<bool>,
        Vec<String>,
    )> {
        let options = AnalyzeOptions {
            backend: self::backend(backend, tolerance)?,
            seed,
            ..AnalyzeOptions::default()
        };
        let system = &self.model.system;
        let j =
            py.detach(|| run::jacobian_at_witness(system, &options)).map_err(|e| self.error(e))?;
        let rows = j.entries.iter().map(|e| e.0).collect();
        let cols = j.entries.iter().map(|e| e.1).collect();
        let values = j.entries.iter().map(|e| e.2).collect();
        Ok((j.nrows, j.ncols, rows, cols, values, j.row_ids, j.row_internal, j.columns))
    }
}

/// The models of `bytes`: all of them, or the one `sketch` names ([`run::pick`]).
fn models(
    file: &str,
    bytes: &[u8],
    format: Option<&str>,
    sketch: Option<&str>,
    all: bool,
) -> PyResult<Vec<NativeModel>> {
    let format = match format {
        None => None,
        Some(name) => Some(InputFormat::from_name(name).ok_or_else(|| {
            PyValueError::new_err(format!("format {name:?}: expected ron, slvs, fcstd or onshape"))
        })?),
    };
    let mut models = run::read_models(file, bytes, format).map_err(to_py)?;
    if !all {
        models = vec![run::pick(models, file, sketch).map_err(to_py)?];
    }
    Ok(models.into_iter().map(|model| NativeModel { model, file: file.to_owned() }).collect())
}

/// A `ReadError` for a file that cannot be read at all.
fn io_error(path: &str, e: &std::io::Error) -> PyErr {
    let message = format!("{path}: cannot read: {e}");
    let err = ReadError::new_err(message.clone());
    Python::attach(|py| {
        let value = err.value(py);
        let _ = value.setattr("message", message);
        let _ = value.setattr("file", path);
        for a in ["line", "column", "id", "element"] {
            let _ = value.setattr(a, py.None());
        }
    });
    err
}

/// Every model of a file: a RON model, or each sketch of a CAD file (by extension, then
/// content); with `sketch`, only the model of that name (a file with one model needs none).
#[pyfunction]
#[pyo3(signature = (path, sketch=None, all=false))]
fn load(py: Python<'_>, path: &str, sketch: Option<&str>, all: bool) -> PyResult<Vec<NativeModel>> {
    let bytes = std::fs::read(path).map_err(|e| io_error(path, &e))?;
    py.detach(|| models(path, &bytes, None, sketch, all))
}

/// Every model of a text or bytes in `format` (`None`: as `load` decides), `file` naming it.
#[pyfunction]
#[pyo3(signature = (data, format=None, file="<string>", sketch=None, all=false))]
fn loads(
    py: Python<'_>,
    data: &Bound<'_, PyAny>,
    format: Option<&str>,
    file: &str,
    sketch: Option<&str>,
    all: bool,
) -> PyResult<Vec<NativeModel>> {
    let bytes: Vec<u8> = if let Ok(b) = data.cast::<PyBytes>() {
        b.as_bytes().to_vec()
    } else {
        data.extract::<String>()?.into_bytes()
    };
    py.detach(|| models(file, &bytes, format, sketch, all))
}

/// The native module.
#[pymodule]
fn _gcs(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeModel>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(loads, m)?)?;
    m.add("GcsError", m.py().get_type::<GcsError>())?;
    m.add("ReadError", m.py().get_type::<ReadError>())?;
    m.add("AnalysisError", m.py().get_type::<AnalysisError>())?;
    m.add("SolveError", m.py().get_type::<SolveError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SCHEMA", gcs_report::SCHEMA)?;
    Ok(())
}
