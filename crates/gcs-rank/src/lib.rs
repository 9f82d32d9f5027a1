//! Linear algebra over a field for the witness method: exact rank, redundant rows and their
//! combinations, kernels, pivot exchange. Knows nothing about geometry.
//!
//! # What it does
//!
//! - [`Field`] is the scalar trait, with backends [`BigRational`] (`num`), [`Rat`] (exact
//!   rationals with a machine-word fast path), `rug::Rational` (GMP, cargo feature `rug`),
//!   [`ModP`] (integers modulo the Mersenne prime 2^61 − 1), [`ModPrime`] (any prime below
//!   2^64) and `f64`. The trait is algebra only: its [`Field::is_zero`] is exact, and the float
//!   tolerance is an explicit [`EchelonOptions::tolerance`].
//! - [`Echelon`] is the incremental reduced row echelon form of the witness paper
//!   (`docs/papers.md`), §3.1:
//!   Jacobian rows are inserted constraint by constraint, each [`Insertion`] says whether the
//!   row is independent (new pivot) or dependent, and a dependent row comes with the combination
//!   of earlier rows that produces it (its support is the fundamental circuit, the constraints
//!   it is redundant with). [`Echelon::make_free`] is the pivot exchange that anchors a
//!   reference (§4), [`Echelon::kernel_basis`] gives the infinitesimal motions.
//! - [`analyse_rows_exact`] is the fast exact path asked for by §6 ("the rank of rational
//!   vectors is computable"): elimination modulo a 61-bit prime, certified over ℚ (pivots prove
//!   the lower bound, dependencies lifted by rational reconstruction and checked exactly prove
//!   the upper bound), falling back to multi-modular lifting and then to rational elimination;
//!   the [`Proof`] says which.
//! - [`levenberg_marquardt`] minimises any system of [`Residuals`] (nonlinear least squares,
//!   geometry-free): the witness projection of `gcs-jacobian` stands on it.
//! - [`float_rank_qr`] is the batch numerical rank with faer's column-pivoted QR, the
//!   "epsilon-heuristic" of §6 for witnesses that are only known approximately.
//!
//! # Example: the kite of the witness paper (fig. 4, table 1)
//!
//! ```
//! use gcs_rank::{BigRational, Echelon, EchelonOptions, Field, Insertion, SparseRow};
//!
//! // Rows of dist(pi, pj) at p1=(2,7), p2=(5,6), p3=(1,1), p4=(6,3);
//! // columns x1 y1 x2 y2 x3 y3 x4 y4.
//! let p = [(2, 7), (5, 6), (1, 1), (6, 3)];
//! let dist = |i: usize, j: usize| {
//!     let (dx, dy) = (p[i].0 - p[j].0, p[i].1 - p[j].1);
//!     SparseRow::from_entries(vec![
//!         (2 * i, BigRational::from_i64(dx)),
//!         (2 * i + 1, BigRational::from_i64(dy)),
//!         (2 * j, BigRational::from_i64(-dx)),
//!         (2 * j + 1, BigRational::from_i64(-dy)),
//!     ])
//! };
//! let mut echelon = Echelon::new(8, EchelonOptions::tracked());
//! for (i, j) in [(0, 1), (0, 2), (1, 3), (2, 3), (1, 2)] {
//!     assert!(echelon.insert(dist(i, j)).is_independent());
//! }
//! let redundant = echelon.insert(dist(0, 3));
//! assert_eq!(echelon.rank(), 5);
//! // dist(p1, p4) is redundant with all five other distances.
//! assert_eq!(redundant.combination().map(|c| c.len()), Some(5));
//! assert!(matches!(redundant, Insertion::Dependent { .. }));
//! // x1 = 4/5 y3 + x4 − 4/5 y4: the first row of the RREF.
//! let x1 = echelon.pivot_row(0).unwrap();
//! assert_eq!(x1.get(5), Some(&BigRational::new((-4).into(), 5.into())));
//! ```
//!
//! # Choosing a backend
//!
//! Exactness first: rank is not continuous, so a float rank is a guess. On a rational witness
//! use [`analyse_rows_exact`]; for incremental work (insertions interleaved with
//! [`Echelon::make_free`]) use an [`Echelon`] over [`ModP`] and certify its dependencies with
//! [`lift_dependency`], keeping an exact backend for what does not lift. The rational
//! backends are the reference the others are tested against, and are fine for small systems.
//! The `f64` backend with a tolerance is for approximate witnesses only.
//!
//! [`Rat`] is the exact rational for many small computations on small numbers: evaluating
//! constraints and their derivatives at a rational witness (dual numbers), small exact solves,
//! eliminations whose entries stay small (independent blocks). A value whose numerator and
//! denominator fit in an `i64` lives in two machine words and costs no allocation; a result
//! that does not fit moves to a [`BigRational`] and comes back when it fits again, so nothing
//! is ever rounded. On small fractions it is 25–70 times faster than [`BigRational`] (10^6
//! products, sums and 8-term dot products in `examples/timing.rs`), and 8–15 times faster on
//! the 8×8 blocks below, whose entries stay below 2^63; on an elimination whose coefficients
//! grow past 64 bits (the 200×200 matrix below) nearly every value is big and it costs the
//! same as [`BigRational`], so large eliminations still belong to the modular path. Convert
//! with [`Field::from_rat`], which maps small values into the prime fields and `f64` without
//! big integers.
//!
//! Rough costs (release build, 200×200 random sparse integer matrix of rank 181, 6 entries a
//! row; `examples/timing.rs`): [`ModP`] and `f64` ≈ 4–5 ms, faer's QR ≈ 0.6 ms,
//! [`analyse_rows_exact`] ≈ 13 ms, `rug::Rational` ≈ 1.1 s, [`BigRational`] ≈ 12 s, [`Rat`]
//! within 10 % of it. Rational Gauss-Jordan is slow because of coefficient growth, and
//! tracking combinations over ℚ costs about five times more again (the stored combinations
//! form the dense inverse of the pivot block); modulo a prime both are cheap, which is why the
//! exact path is modular.
//!
//! # Complexity of an insertion
//!
//! Reduction touches only the pivot rows named by the new row's entries; a new pivot touches
//! only the stored rows that have an entry in its column (a column → rows index). Independent
//! blocks therefore cost nothing in each other: 100,000 rows in 8×8 blocks take about 0.08 s
//! over [`ModP`] (0.16 s with combinations).

pub mod bipartite;
mod echelon;
mod error;
mod exact;
mod field;
mod float;
mod gcd;
mod lsq;
mod modp;
mod rank;
mod rat;
#[cfg(feature = "rug")]
mod rug_field;
mod sparse;

pub use echelon::{
    AMBIGUITY_BAND, Echelon, EchelonOptions, Insertion, RowAnalysis, analyse_rows,
    analyse_rows_with_margins,
};
pub use error::RankError;
pub use exact::{
    CertifiedRows, KernelHint, Proof, SECOND_PRIME, THIRD_PRIME, analyse_rows_exact, certify_rows,
    lift_dependency, rational_reconstruction,
};
pub use field::Field;
pub use float::float_rank_qr;
pub use lsq::{Damping, LmOptions, LmOutcome, Residuals, levenberg_marquardt};
pub use modp::{
    ModP, ModPrime, ModQ, PrimeField, TURN_PERIOD, TURN_PRIME, WITNESS_PRIMES, modulus,
    with_modulus,
};
pub use num_complex::Complex64;
pub use num_rational::BigRational;
pub use rank::{analyse_rows_plain, echelon_rank, random_kernel_vector, random_left_kernel_vector};
pub use rat::Rat;
#[cfg(feature = "rug")]
pub use rug_field::{big_to_rug, rug_to_big};
pub use sparse::SparseRow;
