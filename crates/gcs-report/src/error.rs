//! The error type of the crate.

use gcs_rigidity::RigidityError;

/// Why a report section could not be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// The structural section: the degree of rigidity at the witness failed.
    #[error("structural: {0}")]
    Structural(RigidityError),
}
