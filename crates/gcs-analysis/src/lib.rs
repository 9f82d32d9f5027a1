//! The witness analysis of a geometric constraint system (witness paper §2–§5).
//!
//! [`analyze`] finds a witness (`gcs-jacobian`), assembles the Jacobian there in the chosen
//! arithmetic ([`Backend`]), and inserts its rows in file order into an incremental reduced
//! row echelon form (`gcs-rank`, paper §3.1). From it: the rank, the degrees of freedom
//! counting the placement (`dof_absolute`), the trivial motions the constraints admit, the
//! internal degrees of freedom, every redundant constraint with its spanning group — the
//! earlier constraints it is redundant with (its fundamental circuit) — and the clusters and
//! W-decomposition (`gcs-decompose`); for distance frameworks, global rigidity by the
//! stress-matrix test ([`global`]).
//!
//! # Example: the kite (witness paper, fig. 4)
//! ```
//! use gcs_analysis::{AnalysisOptions, analyze};
//! let system = gcs_model::System::from_ron_str(r#"System(dim: 2,
//!     entities: [Point(id: "p1", at: [2, 7]), Point(id: "p2", at: [5, 6]),
//!                Point(id: "p3", at: [1, 1]), Point(id: "p4", at: [6, 3])],
//!     constraints: [
//!         Distance(id: "c1", a: "p1", b: "p2"), Distance(id: "c2", a: "p1", b: "p3"),
//!         Distance(id: "c3", a: "p2", b: "p4"), Distance(id: "c4", a: "p3", b: "p4"),
//!         Distance(id: "c5", a: "p2", b: "p3"), Distance(id: "c6", a: "p1", b: "p4")])"#,
//!     None).unwrap();
//! let a = analyze(&system, &AnalysisOptions::default()).unwrap();
//! assert_eq!((a.rank, a.dof_absolute, a.trivial_motions, a.dof), (5, 3, 3, 0));
//! assert!(a.rigid() && !a.well_constrained());
//! let c6 = &a.redundant[0];
//! assert_eq!(system.constraint(c6.constraint).id, "c6");
//! assert_eq!(c6.spanning_group.len(), 5);
//! ```

mod analysis;
mod error;
pub mod global;
pub mod motions;
mod sketch;

pub use analysis::{
    Analysis, AnalysisOptions, Arithmetic, Backend, RankMethod, Redundancy, analyze, analyze_at,
    modular_error_bound,
};
pub use error::AnalysisError;
pub use gcs_decompose::{
    Cluster, ClusterMethod, DecompositionNode, GroupRigidity, RemovalOrder, Statistics,
};
pub use global::{GlobalMethod, GlobalRigidity};
pub use sketch::{Configuration, Position, Residual, SketchAnalysis};
