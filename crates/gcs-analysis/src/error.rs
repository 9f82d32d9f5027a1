//! The error type of the crate.

use gcs_jacobian::JacobianError;
use gcs_rank::RankError;

/// Why a system could not be analysed. A mathematical outcome (redundant, flexible) is never an
/// error: it is in the [`crate::Analysis`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AnalysisError {
    /// No witness (see [`JacobianError`]).
    #[error("{0}")]
    Witness(JacobianError),
    /// A failure of the arithmetic.
    #[error("arithmetic: {0}")]
    Rank(#[from] RankError),
    /// Only an approximate witness exists (a numerical projection), and the backend is exact:
    /// deciding an exact rank at an approximate point would be a silent wrong answer.
    #[error(
        "no exact witness ({0}); a numerical projection of the sketch found an approximate one, which only the float backend analyses"
    )]
    ApproximateWitness(gcs_jacobian::NoWitness),
    /// The prime-field backends: no exact witness, and no modular one either (the same
    /// construction failed modulo the prime in every attempt); only the float backend's
    /// approximate witness exists.
    #[error(
        "no exact witness ({0}), nor a modular one (the construction failed modulo the prime too, in every attempt); a numerical projection of the sketch found an approximate one, which only the float backend analyses"
    )]
    NoModularWitness(gcs_jacobian::NoWitness),
    /// The backend was not compiled in.
    #[error("backend {0} is not available in this build (it needs the cargo feature \"{0}\")")]
    BackendUnavailable(&'static str),
}
