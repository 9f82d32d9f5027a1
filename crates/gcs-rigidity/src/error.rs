//! The crate's one error type.
//!
//! Only the low-level calls that take indices from the caller can fail: every analysis of a
//! valid [`System`](gcs_model::System) as a whole succeeds, and a mathematical outcome
//! (over-rigid, under-rigid) is a result, never an error.

use gcs_model::{ConstraintIdx, EntityIdx};

/// What went wrong when a caller handed the network an index it does not know.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum RigidityError {
    /// The entity index is not an object of the network: out of range, a segment (segments
    /// carry no degree of freedom: pass their two points), or outside the subsystem the
    /// network was built for.
    #[error("entity #{} is not an object of this network (a segment, or not in the system)", .0.0)]
    NotAnObject(EntityIdx),
    /// The constraint index is not a constraint node of the network.
    #[error("constraint #{} is not a constraint of this network", .0.0)]
    UnknownConstraint(ConstraintIdx),
    /// The reference frame was asked for but the system has no absolute constraint, so the
    /// network has no frame object.
    #[error("the network has no reference frame (the system has no absolute constraint)")]
    NoFrame,
    /// An overload was to be applied to an empty set of objects.
    #[error("an overload needs at least one object to be attached to")]
    EmptyAttachment,
    /// A witness-based DOR could not be set up: no witness, a layout of another system, or
    /// coordinates that do not fit the layout. The message says which.
    #[error("witness DOR: {0}")]
    Witness(String),
}
