//! The error type of the crate.

use gcs_rigidity::RigidityError;

/// Why a report could not be made. Each variant's message is the one line a front end shows
/// (it names the file, the position and the id where the cause has them).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// The structural section: the degree of rigidity at the witness failed.
    #[error("structural: {0}")]
    Structural(RigidityError),
    /// A RON model that cannot be read or is not valid (file, line, column, id).
    #[error("{0}")]
    Model(gcs_model::ModelError),
    /// A CAD file that cannot be read (file, line, element).
    #[error("{0}")]
    Import(gcs_import::ImportError),
    /// A CAD file without a sketch.
    #[error("{file}: no sketch in it")]
    NoSketch {
        /// The file.
        file: String,
    },
    /// Bytes that are neither UTF-8 text nor a CAD file.
    #[error("{file}: not UTF-8 text (nor a CAD file this build reads)")]
    NotText {
        /// The file.
        file: String,
    },
    /// A file with several models and no name, or no model of the name asked for.
    #[error(
        "{file}: {}; its models: {}",
        match wanted { Some(w) => format!("no sketch named {w:?}"), None => "several sketches: name one".to_owned() },
        names.join(", ")
    )]
    NoSuchSketch {
        /// The file.
        file: String,
        /// The name asked for.
        wanted: Option<String>,
        /// The names of the file's models, in order.
        names: Vec<String>,
    },
    /// The witness analysis failed.
    #[error("{0}")]
    Analysis(gcs_analysis::AnalysisError),
    /// The solve was not attempted.
    #[error("{0}")]
    Solve(gcs_solve::SolveError),
    /// The navigator has nothing to show.
    #[error("{model}: cannot navigate: {why}")]
    Navigate {
        /// The model.
        model: String,
        /// Why.
        why: String,
    },
    /// The Jacobian at the witness has no rational form (a modular witness).
    #[error("{0}")]
    Jacobian(gcs_jacobian::JacobianError),
}
