//! The error type of the crate: what is wrong with a model, where.

use std::fmt;

use crate::kinds::{ConstraintKind, Dim, EntityKind};

/// A position in a model file: 1-based line and column (in characters).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Position {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// A model that cannot be read or is not a valid system.
///
/// Its `Display` is one line, `origin:line:column: message`, naming the file (the origin given
/// to the reader), the position where it is known, and the offending id or field.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelError {
    /// Where the text came from (usually a file path), if the caller said.
    pub origin: Option<String>,
    /// Where in the text, when known.
    pub position: Option<Position>,
    /// What is wrong (boxed: errors travel through many `Result`s and stay small).
    pub kind: Box<ModelErrorKind>,
}

impl ModelError {
    pub(crate) fn new(kind: ModelErrorKind) -> ModelError {
        ModelError { origin: None, position: None, kind: Box::new(kind) }
    }

    /// The same error, located in `origin` at `position` (keeps a position already known).
    pub fn at(mut self, origin: Option<&str>, position: Option<Position>) -> ModelError {
        if self.origin.is_none() {
            self.origin = origin.map(str::to_owned);
        }
        if self.position.is_none() {
            self.position = position;
        }
        self
    }
}

impl fmt::Display for ModelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (&self.origin, &self.position) {
            (Some(o), Some(p)) => write!(f, "{o}:{p}: ")?,
            (Some(o), None) => write!(f, "{o}: ")?,
            (None, Some(p)) => write!(f, "{p}: ")?,
            (None, None) => {}
        }
        write!(f, "{}", self.kind)
    }
}

impl std::error::Error for ModelError {}

/// What is wrong with a model. Every variant names the id or field at fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelErrorKind {
    /// The text is not RON of the expected shape (the message is the RON parser's).
    #[error("RON syntax: {0}")]
    Syntax(String),
    /// `dim` is neither 2 nor 3.
    #[error("field dim: unsupported dimension {0} (expected 2 or 3)")]
    UnsupportedDim(String),
    /// An id is used by two items.
    #[error("duplicate id \"{id}\" (ids must be unique across entities and constraints)")]
    DuplicateId {
        /// The id.
        id: String,
    },
    /// An id is empty.
    #[error("empty id")]
    EmptyId,
    /// A reference to an id that names no entity.
    #[error("{item} \"{owner}\": field {field}: unknown entity id \"{id}\"")]
    UnknownId {
        /// "entity" or "constraint".
        item: &'static str,
        /// The id of the item holding the reference.
        owner: String,
        /// The field holding the reference.
        field: &'static str,
        /// The unknown id.
        id: String,
    },
    /// A reference to an id that names a constraint where an entity is expected.
    #[error("{item} \"{owner}\": field {field}: \"{id}\" is a constraint, not an entity")]
    NotAnEntity {
        /// "entity" or "constraint".
        item: &'static str,
        /// The id of the item holding the reference.
        owner: String,
        /// The field holding the reference.
        field: &'static str,
        /// The id.
        id: String,
    },
    /// An entity kind used in a dimension where it does not exist.
    #[error(
        "entity \"{id}\": a {kind} does not exist in {dim} (circles are 2D, planes and spheres 3D)"
    )]
    KindNotInDim {
        /// The entity id.
        id: String,
        /// Its kind.
        kind: EntityKind,
        /// The system's dimension.
        dim: Dim,
    },
    /// A sketch field with the wrong number of coordinates.
    #[error(
        "entity \"{id}\": field {field}: expected {expected} coordinates in {dim}, found {found}"
    )]
    WrongCoordinateCount {
        /// The entity id.
        id: String,
        /// The field.
        field: &'static str,
        /// Coordinates expected.
        expected: usize,
        /// Coordinates found.
        found: usize,
        /// The system's dimension.
        dim: Dim,
    },
    /// A field expecting a list of two positions (`[[..], [..]]`) got another count.
    #[error("entity \"{id}\": field {field}: expected {expected} positions, found {found}")]
    WrongPositionCount {
        /// The entity id.
        id: String,
        /// The field.
        field: &'static str,
        /// Positions expected.
        expected: usize,
        /// Positions found.
        found: usize,
    },
    /// A segment whose two points are the same entity or coincide in the sketch; a line whose
    /// two sketch points coincide; a plane with a zero normal.
    #[error("entity \"{id}\": {}{what}", field.map(|f| format!("field {f}: ")).unwrap_or_default())]
    Degenerate {
        /// The entity id.
        id: String,
        /// The field at fault, when one is.
        field: Option<&'static str>,
        /// What is degenerate.
        what: String,
    },
    /// A number that is not finite.
    #[error("{item} \"{owner}\": field {field}: not a finite number")]
    NonFinite {
        /// "entity" or "constraint".
        item: &'static str,
        /// The id of the item.
        owner: String,
        /// The field.
        field: &'static str,
    },
    /// A string where a number is expected that does not read as one.
    #[error(
        "{item} \"{owner}\": field {field}: \"{text}\" is not a number (write an integer, a decimal or \"p/q\")"
    )]
    NotANumber {
        /// "entity" or "constraint".
        item: &'static str,
        /// The id of the item.
        owner: String,
        /// The field.
        field: &'static str,
        /// The text found.
        text: String,
    },
    /// A negative distance or radius.
    #[error("{item} \"{owner}\": field {field}: must not be negative, found {value}")]
    Negative {
        /// "entity" or "constraint".
        item: &'static str,
        /// The id of the item.
        owner: String,
        /// The field.
        field: &'static str,
        /// The value as written.
        value: String,
    },
    /// A constraint applied to entity kinds it does not take.
    #[error("constraint \"{id}\": {kind} does not apply to {found} in {dim} (it takes {expected})")]
    KindMismatch {
        /// The constraint id.
        id: String,
        /// Its kind.
        kind: ConstraintKind,
        /// The kinds found, e.g. "point–circle".
        found: String,
        /// What it takes in this dimension.
        expected: String,
        /// The system's dimension.
        dim: Dim,
    },
    /// A constraint whose arguments name the same entity twice.
    #[error("constraint \"{id}\": fields {first} and {second} both name \"{entity}\"")]
    RepeatedEntity {
        /// The constraint id.
        id: String,
        /// The entity named twice.
        entity: String,
        /// First field.
        first: &'static str,
        /// Second field.
        second: &'static str,
    },
    /// A segment endpoint that is not a point.
    #[error(
        "entity \"{id}\": field {field}: a segment joins two points, \"{entity}\" is a {found}"
    )]
    SegmentEndpoint {
        /// The segment id.
        id: String,
        /// `from` or `to`.
        field: &'static str,
        /// The id named there.
        entity: String,
        /// Its kind.
        found: EntityKind,
    },
    /// A reference (driven) constraint that is not a dimension.
    #[error(
        "constraint \"{id}\": field reference: a reference (driven) {kind} is not a dimension: only dimensions (Distance, Angle, Radius, DistanceX, DistanceY, LengthRatio) are measured"
    )]
    NotADimension {
        /// The constraint id.
        id: String,
        /// Its kind.
        kind: crate::kinds::ConstraintKind,
    },
    /// An `Orientation` that is not three points in 2D (four in 3D) with a sign of ±1.
    #[error("constraint \"{id}\": Orientation: field {field}: {why}")]
    Orientation {
        /// The constraint id.
        id: String,
        /// `points` or `sign`.
        field: &'static str,
        /// What is wrong.
        why: String,
    },
    /// A `Group` with no entity, or one named twice.
    #[error("group \"{id}\": field entities: {why}")]
    Group {
        /// The group id.
        id: String,
        /// What is wrong.
        why: String,
    },
    /// A `SplinePoint` whose value is missing or is not one of its spline's knots.
    #[error("constraint \"{id}\": field value: {why}")]
    SplineParameter {
        /// The constraint id.
        id: String,
        /// What is wrong.
        why: String,
    },
    /// A `Fix` on an entity without a sketch position.
    #[error("constraint \"{id}\": Fix on \"{entity}\", which has no sketch position to pin it at")]
    FixWithoutPosition {
        /// The constraint id.
        id: String,
        /// The entity.
        entity: String,
    },
}

impl ModelErrorKind {
    /// The id of the entity or constraint at fault, when the error names one (the duplicated id
    /// for [`ModelErrorKind::DuplicateId`]).
    pub fn id(&self) -> Option<&str> {
        match self {
            ModelErrorKind::DuplicateId { id }
            | ModelErrorKind::KindNotInDim { id, .. }
            | ModelErrorKind::WrongCoordinateCount { id, .. }
            | ModelErrorKind::WrongPositionCount { id, .. }
            | ModelErrorKind::Degenerate { id, .. }
            | ModelErrorKind::KindMismatch { id, .. }
            | ModelErrorKind::RepeatedEntity { id, .. }
            | ModelErrorKind::SegmentEndpoint { id, .. }
            | ModelErrorKind::FixWithoutPosition { id, .. }
            | ModelErrorKind::Orientation { id, .. }
            | ModelErrorKind::NotADimension { id, .. }
            | ModelErrorKind::SplineParameter { id, .. }
            | ModelErrorKind::Group { id, .. } => Some(id),
            ModelErrorKind::UnknownId { owner, .. }
            | ModelErrorKind::NotAnEntity { owner, .. }
            | ModelErrorKind::NonFinite { owner, .. }
            | ModelErrorKind::NotANumber { owner, .. }
            | ModelErrorKind::Negative { owner, .. } => Some(owner),
            ModelErrorKind::Syntax(_)
            | ModelErrorKind::UnsupportedDim(_)
            | ModelErrorKind::EmptyId => None,
        }
    }

    /// The field the error is about, when there is one (used to locate it in the file).
    pub fn field(&self) -> Option<&'static str> {
        match self {
            ModelErrorKind::UnknownId { field, .. }
            | ModelErrorKind::NotAnEntity { field, .. }
            | ModelErrorKind::WrongCoordinateCount { field, .. }
            | ModelErrorKind::WrongPositionCount { field, .. }
            | ModelErrorKind::NonFinite { field, .. }
            | ModelErrorKind::NotANumber { field, .. }
            | ModelErrorKind::Negative { field, .. }
            | ModelErrorKind::SegmentEndpoint { field, .. }
            | ModelErrorKind::Orientation { field, .. } => Some(field),
            ModelErrorKind::RepeatedEntity { second, .. } => Some(second),
            ModelErrorKind::Group { .. } => Some("entities"),
            ModelErrorKind::NotADimension { .. } => Some("reference"),
            ModelErrorKind::SplineParameter { .. } => Some("value"),
            ModelErrorKind::UnsupportedDim(_) => Some("dim"),
            ModelErrorKind::DuplicateId { .. } => Some("id"),
            ModelErrorKind::Degenerate { field, .. } => *field,
            _ => None,
        }
    }
}
