//! Maximal rigid subsystems and the W-decomposition (witness paper §4–§5), at a witness.
//!
//! [`clusters`] finds the clusters of a system — the maximal sets of entities that every
//! motion the constraints allow moves as one displacement — from the Jacobian at a witness in
//! any field: by anchoring references (the paper's Algorithms 1 and 2), by restricting the
//! kernel, or by the open-chain shortcut (biconnected blocks, each checked rigid; the default),
//! with absolute constraints rewritten against a frame. With
//! [`ClusterOptions::decompose`] it W-decomposes every cluster into a DR-plan (Algorithm 3):
//! a tree of rigid subsystems whose leaves are W-indecomposable.
//!
//! The whole witness analysis (rank, redundancy, DOF, which calls this) is `gcs-analysis`.
//!
//! # Example: the butterfly (witness paper, fig. 2): two triangles hinged at `p0`
//! ```
//! use gcs_decompose::{ClusterOptions, clusters};
//! use gcs_jacobian::{Jacobian, Layout, WitnessOptions, find_witness};
//! use gcs_rank::{EchelonOptions, ModP};
//! let s = gcs_model::System::from_ron_str(r#"System(dim: 2,
//!     entities: [Point(id: "p0", at: [0, 0]), Point(id: "p1", at: [-4, 3]),
//!                Point(id: "p2", at: [-4, -3]), Point(id: "p3", at: [5, 2]),
//!                Point(id: "p4", at: [4, -4])],
//!     constraints: [
//!         Distance(id: "a", a: "p0", b: "p1"), Distance(id: "b", a: "p0", b: "p2"),
//!         Distance(id: "c", a: "p1", b: "p2"), Distance(id: "d", a: "p0", b: "p3"),
//!         Distance(id: "e", a: "p0", b: "p4"), Distance(id: "f", a: "p3", b: "p4")])"#,
//!     None).unwrap();
//! let layout = Layout::new(&s);
//! let witness = find_witness(&s, &layout, &WitnessOptions::default()).unwrap();
//! let jacobian: Jacobian<ModP> = witness.jacobian(&s, &layout).unwrap();
//! let (found, _) = clusters(&s, &layout, &jacobian, witness.coords_in().unwrap(),
//!     EchelonOptions::default(), &ClusterOptions::default()).unwrap();
//! let ids: Vec<Vec<&str>> = found
//!     .iter()
//!     .map(|c| c.entities.iter().map(|e| s.entity(*e).id.as_str()).collect())
//!     .collect();
//! assert_eq!(ids, [["p0", "p1", "p2"], ["p0", "p3", "p4"]]);
//! ```

mod clusters;
pub mod pebble;
mod rigid;
mod wdec;

pub use clusters::{Cluster, ClusterOptions, Decomposition, GroupRigidity, clusters};
pub use pebble::{PebbleReport, pebble_game};
pub use rigid::ClusterMethod;
pub use wdec::{DecompositionNode, RemovalOrder, Statistics};
