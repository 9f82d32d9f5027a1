//! The error type of the crate.

use gcs_rank::RankError;

/// Why a Jacobian or a witness could not be produced.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum JacobianError {
    /// A field operation failed (a witness coordinate whose denominator the prime divides, a
    /// non-finite float).
    #[error("arithmetic: {0}")]
    Rank(#[from] RankError),
    /// No witness could be built. The message says which entity or constraint stopped it.
    #[error("no witness: {0}")]
    NoWitness(String),
    /// The configuration given is not a witness.
    #[error("not a witness: {0}")]
    NotAWitness(String),
}
