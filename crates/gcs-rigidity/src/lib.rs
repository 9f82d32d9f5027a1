//! Structural rigidity of geometric constraint systems: degree-of-freedom counting with flows,
//! without solving anything.
//!
//! This crate implements the flow-based methods of Jermann, Neveu and Trombettoni,
//! *Algorithms for identifying rigid subsystems in geometric constraint systems*
//! (`003_da7837b37878e133.txt`), and the Dulmage–Mendelsohn decomposition of the survey of Hu,
//! Kleiner, Pernot et al. (`001_563b3bfaaef67388.txt`, §4.2.1):
//!
//! | what | where | paper |
//! |---|---|---|
//! | object–constraint network, max flow, residual reachability | [`Network`], [`flow::FlowGraph`] | flow paper §2.5 (Def. 5), §4.1 |
//! | Hoffmann et al.'s `Distribute` (overload on a constraint) | [`Network::distribute_on_constraint`] | §4.2 |
//! | Jermann et al.'s `Distribute` (virtual constraint `R` on a set) | [`Network::distribute`] | §4.2 |
//! | Dense, Minimal_Dense (s_rigidity, Def. 3) | [`dense`], [`minimal_dense`], [`dense_analysis`] | §4.3; survey §4.1 |
//! | degree of rigidity, rule table | [`DorOracle`], [`RuleDor`] | §2.4 (Def. 4), §4.3 (Def. 6); survey Def. 6 |
//! | degree of rigidity, exact at a witness | [`WitnessDor`] | §2.4 ("equivalent to geometric theorem proving"); docs/design.md, "Trivial motions" |
//! | Over-Rigid over DOR-minimal sets (es_rigidity, Def. 4) | [`over_rigid`], [`minimal_over_rigid`], [`over_rigid_analysis`] | §4.3 |
//! | Dulmage–Mendelsohn (Hopcroft–Karp, coarse and fine) | [`dm_decomposition`], [`dm`] | survey §4.2.1 "D-M" |
//! | all of it for a report (docs/format.md §3) | [`structural_analysis`] | |
//!
//! These methods count; they are fooled by geometry, and that is the point of running them
//! beside the witness method: Dense calls two parallel 2D lines at a distance over-rigid
//! (flow paper fig. 1a) and every 3D bar too (two points and a distance: DOF 5 < 6); Over-Rigid
//! fixes that with the degree of rigidity, but no count sees that the double banana flexes or
//! that a theorem makes a constraint redundant (witness paper figs. 5 and 6).
//!
//! # Example
//! ```
//! use gcs_model::System;
//! use gcs_rigidity::{structural_analysis, RuleDor, Verdict};
//!
//! // Flow paper, fig. 1a: three parallel lines at prescribed distances (2D).
//! let text = r#"System(dim: 2, entities: [
//!         Line(id: "A", at: [[1, 1], [5, 4]]),
//!         Line(id: "B", at: [[-0.2, 2.6], [7.8, 8.6]]),
//!         Line(id: "C", at: [[2, 8], [-6, 2]]) ],
//!     constraints: [
//!         Parallel(id: "par_AB", a: "A", b: "B"), Parallel(id: "par_BC", a: "B", b: "C"),
//!         Distance(id: "d_AB", a: "A", b: "B", value: 2), Distance(id: "d_BC", a: "B", b: "C", value: 3) ])"#;
//! let system = System::from_ron_str(text, None).unwrap();
//! let report = structural_analysis(&system, &RuleDor::for_system(&system));
//!
//! // Dense overloads par_AB by 3: lines A and B (4 DOF) cannot take 2 + 3.
//! assert_eq!(report.dense.verdict, Verdict::OverRigid);
//! let ids: Vec<&str> = report.dense.subsystem_entities().iter()
//!     .map(|e| system.entity(*e).id.as_str()).collect();
//! assert_eq!(ids, ["A", "B"]);
//! // Over-Rigid charges parallel lines their DOR, 2: nothing over-rigid, and DOF 2 = DOR 2.
//! assert_eq!(report.over_rigid.verdict, Verdict::WellRigid);
//! assert_eq!((report.over_rigid.dof, report.over_rigid.dor), (2, 2));
//! ```
//!
//! # Design notes
//!
//! - **Incremental flow.** A [`Network`] computes one maximum flow and each `Distribute` adds
//!   its overload on top with at most `K` augmenting paths, then rolls back (a journal of
//!   pushes): `O(K(n + m))` per call instead of a fresh max flow (the flow paper suggests this
//!   at the end of §4.2). The max flow (Dinic) and the matching (Hopcroft–Karp) are written
//!   here on compact adjacency arrays; no graph library is used.
//! - **Absolute constraints.** `Fix`, `Horizontal` and `Vertical` bind a reference-frame object
//!   of DOF = DOR = D, which turns a CAD sketch into the relative system the papers assume (see
//!   [`network`]).
//! - **Objects.** Entities with DOF > 0; a segment is its two points.
//! - **DOR** comes from a [`DorOracle`]; [`RuleDor`] derives its table from the stabiliser
//!   definition and disagrees, on purpose, with two values quoted by the survey (see [`dor`]).
//!   [`WitnessDor`] computes it exactly at a witness, as the rank of the displacement
//!   generators restricted to the set's unknowns; it is the only use this crate makes of
//!   `gcs-jacobian` (see [`witness_dor`]).

pub mod dm;
pub mod dor;
pub mod error;
pub mod flow;
pub mod global;
pub mod network;
mod report;
pub mod rigidity;
pub mod witness_dor;

pub use dm::{DmDecomposition, DmPart, dm_decomposition};
pub use dor::{DorOracle, RuleDor};
pub use error::RigidityError;
pub use gcs_decompose::{PebbleReport, pebble_game};
pub use global::{jackson_jordan, k_connected, laman_rigid, redundantly_rigid};
pub use network::{Network, Object, Share, Subsystem};
pub use report::{StructuralReport, structural_analysis};
pub use rigidity::{
    RigidityAnalysis, Verdict, dense, dense_analysis, dense_analysis_in, dense_in, minimal_dense,
    minimal_over_rigid, object_dor, over_rigid, over_rigid_analysis, over_rigid_analysis_in,
    over_rigid_in,
};
pub use witness_dor::WitnessDor;
