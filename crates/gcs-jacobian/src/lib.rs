//! Witness configurations and the Jacobian at a witness (witness paper §2; docs/design.md,
//! "Numerical decisions").
//!
//! Given a validated [`gcs_model::System`]:
//!
//! - [`Layout`] gives every entity its coordinates (homogeneous lines and planes with a
//!   normalisation row, Plücker 3D lines with their relation, points, circles, spheres);
//! - [`find_witness`] finds an exact rational witness: the sketch when it satisfies the
//!   parameter-free constraints exactly and passes Moinet's perturbation test, otherwise one
//!   built by constructive placement from a seed ([`WitnessSource`]);
//! - [`Witness::jacobian`] assembles the sparse Jacobian at the witness in any
//!   [`gcs_rank::Field`]: every constraint's equations are written once over dual numbers
//!   ([`Dual`]) and differentiated automatically, and each constraint contributes exactly DOC
//!   rows, independent at a generic witness ([`plan`]);
//! - [`motions::generators`] gives the infinitesimal displacements, whose rank against the
//!   Jacobian counts the trivial motions a system admits.
//!
//! # Example: the kite of the witness paper (fig. 4)
//!
//! ```
//! use gcs_jacobian::{Layout, WitnessOptions, WitnessSource, find_witness};
//! use gcs_rank::{BigRational, Echelon, EchelonOptions};
//!
//! let text = r#"System(dim: 2,
//!     entities: [Point(id: "p1", at: [2, 7]), Point(id: "p2", at: [5, 6]),
//!                Point(id: "p3", at: [1, 1]), Point(id: "p4", at: [6, 3])],
//!     constraints: [
//!         Distance(id: "c1", a: "p1", b: "p2"), Distance(id: "c2", a: "p1", b: "p3"),
//!         Distance(id: "c3", a: "p2", b: "p4"), Distance(id: "c4", a: "p3", b: "p4"),
//!         Distance(id: "c5", a: "p2", b: "p3"), Distance(id: "c6", a: "p1", b: "p4")])"#;
//! let system = gcs_model::System::from_ron_str(text, None).unwrap();
//! let layout = Layout::new(&system);
//! let witness = find_witness(&system, &layout, &WitnessOptions::default()).unwrap();
//! assert_eq!(witness.source, WitnessSource::Sketch);
//! let jacobian = witness.jacobian::<BigRational>(&system, &layout).unwrap();
//! let mut echelon = Echelon::new(jacobian.ncols, EchelonOptions::default());
//! let independent: Vec<bool> =
//!     jacobian.rows.into_iter().map(|r| echelon.insert(r).is_independent()).collect();
//! assert_eq!(independent, [true, true, true, true, true, false]);
//! ```

mod dual;
mod equations;
mod error;
mod jacobian;
mod laws;
mod layout;
pub mod motions;
mod place;
pub mod plan;
mod polysolve;
mod project;
mod qla;
mod repr;
pub mod sketch;
mod square;
mod turns;
mod views;
mod witness;

pub use dual::Dual;
pub use equations::{Equations, Residual};
pub use error::{JacobianError, NoWitness, Rejection};
pub use jacobian::{Jacobian, RowOwner, assemble, relation_row};
pub use laws::residual_degree;
pub use layout::Layout;
pub use repr::Repr;
pub use witness::{Witness, WitnessOptions, WitnessSource, find_witness};
