//! Witness configurations and the Jacobian at a witness (witness paper §2, DESIGN.md
//! "Numerical decisions").
//!
//! This crate will hold: the polynomial residual equations of every constraint kind, written
//! once generically over the scalar; forward-mode automatic differentiation producing sparse
//! Jacobian rows in any `gcs_rank::Field`; entity-internal normalisation rows; witness
//! generation (the sketch when it is exact and generic, otherwise a constructive random
//! rational placement); the trivial motion generators of every entity kind; and the exact
//! degree of rigidity of a set of entities.
