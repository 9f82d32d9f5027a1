//! The exact degree of rigidity at a witness (docs/design.md, "Trivial motions").
//!
//! With `T` the generators of the displacements (3 in 2D, 6 in 3D) written as velocities of
//! every unknown at a witness ([`gcs_jacobian::motions::generators`]), the displacements that
//! move a set of entities `X` are the combinations of generators whose velocity on the unknowns
//! of `X` is not zero. So
//!
//! ```text
//! DOR(X) = rank of T restricted to the columns of X
//! ```
//!
//! the number of independent displacements `X` admits, computed at the solution the witness
//! is, where every geometric property holds — those the constraints state, and those that
//! follow from them by a theorem or by incidences no rule table chains. That is the DOR the
//! flow paper's Over-Rigid needs (§2.4: "computing the DOR may be equivalent to geometric
//! theorem proving"), and [`RuleDor`](crate::RuleDor) can only approximate it.
//!
//! # Computing it cheaply
//!
//! Restricted to `X`, `T` has `D` rows (`D` = 3 or 6) and one column per unknown of `X`. Its
//! rank is the rank of its columns, vectors of `ℚ^D`. [`WitnessDor::new`] computes the
//! generators once and keeps, for every entity, an echelon basis of the span of its columns
//! (at most `D` short vectors: a 2D point has 2, a 3D line 4); a query inserts the bases of the
//! set's entities into an [`Echelon`] over `D` columns and stops as soon as the rank reaches
//! `D`. A query on two or three entities costs a few dozen rational operations on numbers of
//! the witness's size, whatever the size of the system. Exact: the arithmetic is over ℚ.
//!
//! Homogeneous coordinates (lines, planes) carry a scale that is not geometry; the generators
//! are projected tangent to each entity's normalisation, so a displacement that maps a line to
//! itself has velocity zero on its coordinates, as it must.

use gcs_jacobian::{Layout, Witness, WitnessOptions, WitnessSource, find_witness, motions};
use gcs_model::{EntityIdx, System};
use gcs_rank::{BigRational, Echelon, EchelonOptions, Field, ModP, ModQ, SparseRow};

use crate::dor::DorOracle;
use crate::error::RigidityError;

/// The degree of rigidity computed exactly at a witness: the rank of the trivial motion
/// generators restricted to the unknowns of the set (see the module documentation).
///
/// A `WitnessDor` answers for the system it was built for; entity indices out of its range are
/// ignored, a segment stands for its two points, and the reference frame is never passed (the
/// algorithms give it the full DOR themselves).
///
/// # Example
/// ```
/// use gcs_model::System;
/// use gcs_rigidity::{DorOracle, RuleDor, WitnessDor};
///
/// // Two lines perpendicular to two secant lines are parallel (3D): no rule says so.
/// let text = r#"System(dim: 3, entities: [
///     Line(id: "M", at: [[0, 0, 0], [1, 0, 0]]), Line(id: "N", at: [[0, 0, 1], [0, 1, 1]]),
///     Line(id: "L1", at: [[0, 0, 0], [0, 0, 1]]), Line(id: "L2", at: [[3, 2, 0], [3, 2, 5]]) ],
///   constraints: [
///     Perpendicular(id: "a", a: "L1", b: "M"), Perpendicular(id: "b", a: "L1", b: "N"),
///     Perpendicular(id: "c", a: "L2", b: "M"), Perpendicular(id: "d", a: "L2", b: "N") ])"#;
/// let system = System::from_ron_str(text, None).unwrap();
/// let witness = WitnessDor::find(&system, 1).unwrap();
/// let l = [2, 3].map(gcs_model::EntityIdx);
/// assert_eq!(witness.name(), "witness");
/// assert_eq!(witness.dor(&system, &l), 5); // parallel lines: translations along them fix both
/// assert_eq!(RuleDor::for_system(&system).dor(&system, &l), 6);
/// ```
#[derive(Clone, Debug)]
pub struct WitnessDor {
    displacements: usize,
    /// Per entity: an echelon basis of the span, in `F^D`, of the columns of `T` on its
    /// unknowns (empty for segments); over ℚ, or modulo the prime at a modular witness.
    spans: Spans,
}

#[derive(Clone, Debug)]
enum Spans {
    Rational(Vec<Vec<SparseRow<BigRational>>>),
    Modular(Vec<Vec<SparseRow<ModP>>>),
    /// Modulo another witness prime: residues that mean something only inside its
    /// `with_modulus`, where they are computed and used.
    OtherPrime(u64, Vec<Vec<SparseRow<ModQ>>>),
}

impl Spans {
    fn len(&self) -> usize {
        match self {
            Spans::Rational(s) => s.len(),
            Spans::Modular(s) => s.len(),
            Spans::OtherPrime(_, s) => s.len(),
        }
    }

    fn entity(&self, e: usize) -> usize {
        match self {
            Spans::Rational(s) => s.get(e).map_or(0, Vec::len),
            Spans::Modular(s) => s.get(e).map_or(0, Vec::len),
            Spans::OtherPrime(_, s) => s.get(e).map_or(0, Vec::len),
        }
    }

    /// The rank of the union of the spans of `entities`.
    fn rank(&self, entities: &[EntityIdx], d: usize) -> usize {
        fn union<F: Field>(spans: &[Vec<SparseRow<F>>], entities: &[EntityIdx], d: usize) -> usize {
            let mut echelon = Echelon::new(d, EchelonOptions::default());
            for e in entities {
                for row in &spans[e.index()] {
                    if echelon.rank() == d {
                        return d;
                    }
                    echelon.insert(row.clone());
                }
            }
            echelon.rank()
        }
        match self {
            Spans::Rational(s) => union(s, entities, d),
            Spans::Modular(s) => union(s, entities, d),
            Spans::OtherPrime(q, s) => gcs_rank::with_modulus(*q, || union(s, entities, d)),
        }
    }
}

/// Per entity, the echelon basis of [`spans_in`].
type EntitySpans<F> = Vec<Vec<SparseRow<F>>>;

/// Per entity, an echelon basis of the span of the generators' columns on its unknowns.
fn spans_in<F: Field>(
    system: &System,
    layout: &Layout,
    coords: &[F],
) -> Result<(usize, EntitySpans<F>), RigidityError> {
    let t = motions::generators::<F>(system, layout, coords)
        .map_err(|e| RigidityError::Witness(e.to_string()))?;
    let d = t.len();
    let spans = system
        .entity_indices()
        .map(|e| {
            let mut echelon = Echelon::new(d, EchelonOptions::default());
            for col in layout.columns(e) {
                if echelon.rank() == d {
                    break;
                }
                let v: Vec<(usize, F)> = (0..d).map(|g| (g, t[g][col].clone())).collect();
                echelon.insert(SparseRow::from_entries(v));
            }
            echelon.rref().into_iter().map(|(_, row)| row).collect()
        })
        .collect();
    Ok((d, spans))
}

impl WitnessDor {
    /// The oracle of `system` at the witness coordinates `coords` (one rational per column of
    /// `layout`, e.g. [`Witness::coords`]).
    ///
    /// # Errors
    /// [`RigidityError::Witness`] when `layout` is not the layout of `system`, `coords` does
    /// not have one value per column, or a homogeneous entity has all-zero coordinates.
    ///
    /// # Complexity
    /// `O(D · unknowns)` rational operations for the generators, then `O(D²)` per entity.
    pub fn new(
        system: &System,
        layout: &Layout,
        coords: &[BigRational],
    ) -> Result<WitnessDor, RigidityError> {
        if *layout != Layout::new(system) {
            return Err(RigidityError::Witness("the layout is not the system's".into()));
        }
        if coords.len() != layout.ncols() {
            return Err(RigidityError::Witness(format!(
                "{} coordinates for {} unknowns",
                coords.len(),
                layout.ncols()
            )));
        }
        let (displacements, spans) = spans_in(system, layout, coords)?;
        Ok(WitnessDor { displacements, spans: Spans::Rational(spans) })
    }

    /// The oracle at a witness found by [`gcs_jacobian::find_witness`].
    ///
    /// # Errors
    /// As [`WitnessDor::new`].
    pub fn from_witness(
        system: &System,
        layout: &Layout,
        witness: &Witness,
    ) -> Result<WitnessDor, RigidityError> {
        if witness.source != WitnessSource::Modular {
            return WitnessDor::new(system, layout, &witness.coords);
        }
        // A modular witness: the spans modulo its prime.
        if witness.coords.len() != layout.ncols() || *layout != Layout::new(system) {
            return Err(RigidityError::Witness("the layout is not the system's".into()));
        }
        let error = |e: gcs_jacobian::JacobianError| RigidityError::Witness(e.to_string());
        match witness.modulus {
            Some(q) if q != ModP::PRIME => gcs_rank::with_modulus(q, || {
                let coords: Vec<ModQ> = witness.coords_in().map_err(error)?;
                let (displacements, spans) = spans_in(system, layout, &coords)?;
                Ok(WitnessDor { displacements, spans: Spans::OtherPrime(q, spans) })
            }),
            _ => {
                let coords: Vec<ModP> = witness.coords_in().map_err(error)?;
                let (displacements, spans) = spans_in(system, layout, &coords)?;
                Ok(WitnessDor { displacements, spans: Spans::Modular(spans) })
            }
        }
    }

    /// Finds a witness of `system` (the sketch when it is one and is generic, else a rational
    /// configuration built from `seed`) and builds the oracle there.
    ///
    /// # Errors
    /// [`RigidityError::Witness`] when no witness can be found.
    pub fn find(system: &System, seed: u64) -> Result<WitnessDor, RigidityError> {
        let layout = Layout::new(system);
        let options = WitnessOptions { seed, ..WitnessOptions::default() };
        let witness = find_witness(system, &layout, &options)
            .map_err(|e| RigidityError::Witness(e.to_string()))?;
        WitnessDor::new(system, &layout, &witness.coords)
    }

    /// The DOR of one entity (0 for a segment or an index out of range): 2 for a 2D point,
    /// line or circle, 3 for a 3D point, plane or sphere, 4 for a 3D line.
    pub fn entity_dor(&self, e: EntityIdx) -> usize {
        self.spans.entity(e.index())
    }

    /// The number of displacements of the dimension (3 or 6): the largest possible DOR.
    pub fn displacements(&self) -> usize {
        self.displacements
    }
}

impl DorOracle for WitnessDor {
    fn dor(&self, system: &System, entities: &[EntityIdx]) -> usize {
        let mut base: Vec<EntityIdx> = Vec::with_capacity(entities.len() + 1);
        for &e in entities {
            if e.index() >= self.spans.len() || e.index() >= system.entities().len() {
                continue;
            }
            if system.entity(e).kind().is_composite() {
                base.extend(system.base_entities(e));
            } else {
                base.push(e);
            }
        }
        base.sort_unstable();
        base.dedup();
        // The entity with the largest span first: a set often has it all.
        base.sort_by_key(|e| std::cmp::Reverse(self.entity_dor(*e)));
        match base.as_slice() {
            [] => 0,
            [one] => self.entity_dor(*one),
            [first, ..] if self.entity_dor(*first) == self.displacements => self.displacements,
            _ => self.spans.rank(&base, self.displacements),
        }
    }

    fn name(&self) -> &str {
        "witness"
    }
}
