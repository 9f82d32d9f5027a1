//! The witness analysis of a system (witness paper §3–§5).
//!
//! This crate will hold: rank and degrees of freedom at the witness, redundant constraints in
//! file order with their spanning groups (incremental Gauss–Jordan, §3.1), the trivial motions
//! admitted, the maximal rigid subsystems (§4), the well-constrained boundary (§3.2) and the
//! W-decomposition into a DR-plan (§5).
