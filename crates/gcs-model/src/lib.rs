//! Geometric constraint systems as data: entities, constraints, their degrees of freedom, and
//! the RON model format.
//!
//! A model file (format in `docs/format.md` §1) is read into a validated [`System`]: ids are
//! resolved to indices ([`EntityIdx`], [`ConstraintIdx`]), every constraint is checked against
//! the kinds it takes and given its roles ([`Signature`]) and its DOC, segments are resolved to their
//! two points, and sketch coordinates are exact rationals (a decimal is the rational it
//! denotes: `0.1` is 1/10). A system can be written back ([`System::to_ron`]) and built in code
//! ([`SystemBuilder`]) with the same checks.
//!
//! The crate knows nothing about numbers beyond reading them: witnesses, Jacobians and ranks
//! live in `gcs-jacobian` and `gcs-rank`.
//!
//! # Example
//! ```
//! use gcs_model::System;
//!
//! let kite = r#"
//! System(
//!     name: "kite",
//!     dim: 2,
//!     entities: [
//!         Point(id: "p1", at: [2, 7]), Point(id: "p2", at: [5, 6]),
//!         Point(id: "p3", at: [1, 1]), Point(id: "p4", at: [6, 3]),
//!     ],
//!     constraints: [
//!         Distance(id: "c1", a: "p1", b: "p2", value: 3.1623),
//!         Distance(id: "c2", a: "p1", b: "p3", value: 6.0828),
//!         Distance(id: "c3", a: "p2", b: "p4", value: 3.1623),
//!         Distance(id: "c4", a: "p3", b: "p4", value: 5.3852),
//!         Distance(id: "c5", a: "p2", b: "p3", value: 6.4031),
//!         Distance(id: "c6", a: "p1", b: "p4", value: 5.6569),
//!     ],
//! )"#;
//! let system = System::from_ron_str(kite, Some("data/paper/kite.ron")).unwrap();
//! assert_eq!(system.dof_sum(), 8);
//! assert_eq!(system.doc_sum(), 6);
//! // Counting alone says 2 DOF, i.e. "under-constrained" once the 3 displacements are
//! // removed... the witness analysis (gcs-decompose) shows it is rigid with c6 redundant.
//! assert_eq!(system.naive_dof(), 2);
//! ```
//!
//! The DOF and DOC tables follow `docs/format.md`; the notions (DOF of an object, DOC of a
//! constraint) are those of the flow paper (Jermann, Neveu, Trombettoni, §2.3) and the survey's
//! Definitions 3 and 4.

pub mod entity;
pub mod error;
pub mod generate;
pub mod kinds;
mod locate;
pub mod number;
mod read;
pub mod rng;
pub mod signature;
pub mod spline;
pub mod system;
mod write;

pub use entity::{EntityClass, EntityKind, Geometry};
pub use error::{ModelError, ModelErrorKind, Position};
pub use kinds::{ConstraintKind, Dim, Role};
pub use num_rational::BigRational;
pub use signature::{Gap, Metric, Signature};
pub use system::{
    Constraint, ConstraintIdx, Coords, Entity, EntityIdx, Group, Item, Orientation, System,
    SystemBuilder,
};
