//! The error type of the crate, and why a configuration is not a witness.

use std::fmt;

use gcs_rank::RankError;

/// Why a configuration (the sketch, or a placement) is not a witness, naming the constraint
/// or entity at fault by its id.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Rejection {
    /// Some entity has no (or an incomplete) sketch position.
    Incomplete,
    /// A parameter-free constraint does not hold there.
    Unsatisfied {
        /// The constraint's id.
        constraint: String,
    },
    /// A distance between lines or planes that are not parallel (circles not concentric).
    NotParallel {
        /// The constraint's id.
        constraint: String,
    },
    /// The constructive placement stopped at an entity: its equations have no rational
    /// solution near the preference (a tangency or a mirror needing a square root).
    Unplaceable {
        /// The entity's id.
        entity: String,
        /// The constraints binding it to the entities already placed, ids in file order.
        constraints: Vec<String>,
    },
}

impl fmt::Display for Rejection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rejection::Incomplete => write!(f, "the sketch is incomplete"),
            Rejection::Unsatisfied { constraint } => {
                write!(f, "constraint \"{constraint}\" does not hold in the sketch")
            }
            Rejection::NotParallel { constraint } => write!(
                f,
                "constraint \"{constraint}\": a distance between lines or planes that are not \
                 parallel, or between circles that are not concentric"
            ),
            Rejection::Unplaceable { entity, constraints } => {
                write!(f, "entity \"{entity}\" cannot be placed rationally under ")?;
                if constraints.is_empty() {
                    write!(f, "its constraints")
                } else {
                    let ids: Vec<String> = constraints.iter().map(|c| format!("\"{c}\"")).collect();
                    write!(f, "{}", ids.join(", "))
                }
            }
        }
    }
}

/// Why no exact witness was found: why the sketch is not one, and why no placement gave one.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoWitness {
    /// Why the sketch is not a witness (`None`: it was, but something else failed).
    pub sketch: Option<Rejection>,
    /// Why the constructive placement found none (`None`: it was not needed or not tried).
    pub placement: Option<Rejection>,
}

impl fmt::Display for NoWitness {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.sketch, &self.placement) {
            (Some(s), Some(p)) => write!(f, "{s}, and {p}"),
            (Some(s), None) => write!(f, "{s}, and no placement found"),
            (None, Some(p)) => write!(f, "{p}"),
            (None, None) => write!(f, "no placement found"),
        }
    }
}

/// Why a Jacobian or a witness could not be produced.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum JacobianError {
    /// A field operation failed (a witness coordinate whose denominator the prime divides, a
    /// non-finite float).
    #[error("arithmetic: {0}")]
    Rank(#[from] RankError),
    /// No witness could be built, exact or approximate.
    #[error("no witness: {0}")]
    NoWitness(NoWitness),
    /// A modular witness was asked for in a field other than the prime field it lives in.
    #[error(
        "the witness is modular (coordinates modulo 2^61 − 1): it cannot be evaluated in the {field} field"
    )]
    ModularWitness {
        /// The field asked for.
        field: &'static str,
    },
    /// An entity's homogeneous coordinates have zero norm in the field (impossible over ℚ,
    /// negligibly likely modulo a large prime).
    #[error("not a witness: the homogeneous coordinates of entity \"{entity}\" have zero norm")]
    ZeroNorm {
        /// The entity's id.
        entity: String,
    },
}
