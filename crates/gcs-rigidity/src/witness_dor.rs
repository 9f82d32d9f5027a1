//! The exact degree of rigidity at a witness (DESIGN.md, "Trivial motions").
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

use gcs_jacobian::{Layout, Witness, WitnessOptions, find_witness, motions};
use gcs_model::{EntityIdx, System};
use gcs_rank::{BigRational, Echelon, EchelonOptions, SparseRow};

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
    /// Per entity: an echelon basis of the span, in `ℚ^D`, of the columns of `T` on its
    /// unknowns (empty for segments).
    spans: Vec<Vec<SparseRow<BigRational>>>,
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
        let t = motions::generators::<BigRational>(system, layout, coords)
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
                    let v: Vec<(usize, BigRational)> =
                        (0..d).map(|g| (g, t[g][col].clone())).collect();
                    echelon.insert(SparseRow::from_entries(v));
                }
                echelon.rref().into_iter().map(|(_, row)| row).collect()
            })
            .collect();
        Ok(WitnessDor { displacements: d, spans })
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
        WitnessDor::new(system, layout, &witness.coords)
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
        self.spans.get(e.index()).map_or(0, Vec::len)
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
            match system.segment_points(e) {
                Some((a, b)) => base.extend([a, b]),
                None => base.push(e),
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
            _ => {
                let mut echelon = Echelon::new(self.displacements, EchelonOptions::default());
                'entities: for e in &base {
                    for row in &self.spans[e.index()] {
                        if echelon.rank() == self.displacements {
                            break 'entities;
                        }
                        echelon.insert(row.clone());
                    }
                }
                echelon.rank()
            }
        }
    }

    fn name(&self) -> &str {
        "witness"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::RuleDor;

    fn system(text: &str) -> System {
        System::from_ron_str(text, None).unwrap()
    }

    fn both(s: &System) -> (WitnessDor, RuleDor) {
        (WitnessDor::find(s, 1).unwrap(), RuleDor::for_system(s))
    }

    fn ids(s: &System, names: &[&str]) -> Vec<EntityIdx> {
        names.iter().map(|n| s.entity_by_id(n).unwrap()).collect()
    }

    /// Every set of 1, 2 and 3 entities.
    fn small_sets(n: usize) -> Vec<Vec<EntityIdx>> {
        let e = |i: usize| EntityIdx(i as u32);
        let mut out = Vec::new();
        for i in 0..n {
            out.push(vec![e(i)]);
            for j in i + 1..n {
                out.push(vec![e(i), e(j)]);
                for k in j + 1..n {
                    out.push(vec![e(i), e(j), e(k)]);
                }
            }
        }
        out
    }

    #[test]
    fn general_position_2d_equals_the_rules() {
        let s = system(
            r#"System(dim: 2, entities: [
                Point(id: "p", at: [0, 0]), Point(id: "q", at: [5, 1]), Point(id: "r", at: [2, 7]),
                Line(id: "A", at: [[1, 3], [4, -2]]), Line(id: "B", at: [[-3, 1], [2, 9]]),
                Line(id: "C", at: [[7, 7], [0, 3]]),
                Circle(id: "k", center: [3, -4], radius: 2) ], constraints: [])"#,
        );
        let (w, r) = both(&s);
        assert_eq!(w.displacements(), 3);
        for set in small_sets(s.entities().len()) {
            assert_eq!(w.dor(&s, &set), r.dor(&s, &set), "{set:?}");
        }
        assert_eq!(w.dor(&s, &[]), 0);
    }

    #[test]
    fn general_position_3d_equals_the_rules() {
        let s = system(
            r#"System(dim: 3, entities: [
                Point(id: "p", at: [0, 0, 0]), Point(id: "q", at: [5, 1, 2]),
                Point(id: "r", at: [2, 7, -3]),
                Line(id: "A", at: [[1, 3, 0], [4, -2, 1]]), Line(id: "B", at: [[-3, 1, 5], [2, 9, 4]]),
                Plane(id: "P", at: [[0, 0, 1], [1, 2, 3]]), Plane(id: "Q", at: [[2, 0, 0], [-1, 4, 1]]),
                Sphere(id: "S", center: [3, -4, 1], radius: 2) ], constraints: [])"#,
        );
        let (w, r) = both(&s);
        assert_eq!(w.displacements(), 6);
        let single: Vec<usize> = s.entity_indices().map(|e| w.entity_dor(e)).collect();
        assert_eq!(single, [3, 3, 3, 4, 4, 3, 3, 3]);
        for set in small_sets(s.entities().len()) {
            assert_eq!(w.dor(&s, &set), r.dor(&s, &set), "{set:?}");
        }
    }

    #[test]
    fn explicit_properties_equal_the_rules() {
        // Properties the constraints state: the rule table and the witness agree.
        let s = system(
            r#"System(dim: 3, entities: [
                Line(id: "L", at: [[0, 0, 0], [1, 0, 0]]), Line(id: "M", at: [[0, 1, 0], [1, 1, 0]]),
                Point(id: "p", at: [0, 0, 0]), Point(id: "q", at: [1, 0, 0]), Point(id: "r", at: [2, 0, 0]),
                Point(id: "off", at: [0, 3, 3]),
                Plane(id: "Pa", at: [[0, 0, 0], [0, 0, 1]]), Plane(id: "Pb", at: [[0, 0, 2], [0, 0, 1]]),
                Line(id: "Z", at: [[0, 0, 0], [0, 0, 1]]), Segment(id: "pq", from: "p", to: "q") ],
              constraints: [
                Parallel(id: "lm", a: "L", b: "M"), Incident(id: "p_on", a: "p", b: "L"),
                Incident(id: "q_on", a: "q", b: "L"), Incident(id: "r_on", a: "r", b: "L"),
                Parallel(id: "ab", a: "Pa", b: "Pb"), Perpendicular(id: "z", a: "Z", b: "Pa"),
                Incident(id: "l_in", a: "L", b: "Pa") ])"#,
        );
        let (w, r) = both(&s);
        let cases: [(&[&str], usize); 12] = [
            (&["L", "M"], 5),
            (&["p", "L"], 5),
            (&["off", "L"], 6),
            (&["p", "q", "r"], 5),
            (&["p", "q", "off"], 6),
            (&["Pa", "Pb"], 3),
            (&["Z", "Pa"], 5),
            (&["L", "Pa"], 5),
            (&["L", "M", "Pa"], 5),
            (&["pq"], 5),
            (&["pq", "r", "L"], 5),
            (&["pq", "off"], 6),
        ];
        for (names, expected) in cases {
            let set = ids(&s, names);
            assert_eq!(w.dor(&s, &set), expected, "{names:?}");
            assert_eq!(r.dor(&s, &set), expected, "{names:?}");
        }
    }

    #[test]
    fn two_points_on_two_planes_and_a_third_are_collinear() {
        // a, b, c on both planes: on their common line. The rules do not chain incidences on
        // planes into collinearity; the witness sees the rotation about that line.
        let text = |extra: &str| {
            format!(
                r#"System(dim: 3, entities: [
                    Plane(id: "P", at: [[0, 0, 0], [0, 0, 1]]), Plane(id: "Q", at: [[0, 0, 0], [0, 1, 0]]),
                    Point(id: "a", at: [0, 0, 0]), Point(id: "b", at: [2, 0, 0]), Point(id: "c", at: [7, 0, 0]),
                    Line(id: "L", at: [[0, 0, 0], [1, 0, 0]]) ],
                  constraints: [
                    Incident(id: "a_P", a: "a", b: "P"), Incident(id: "a_Q", a: "a", b: "Q"),
                    Incident(id: "b_P", a: "b", b: "P"), Incident(id: "b_Q", a: "b", b: "Q"),
                    Incident(id: "c_P", a: "c", b: "P"), Incident(id: "c_Q", a: "c", b: "Q") {extra} ])"#
            )
        };
        let s = system(&text(""));
        let (w, r) = both(&s);
        let abc = ids(&s, &["a", "b", "c"]);
        assert_eq!(r.dor(&s, &abc), 6);
        assert_eq!(w.dor(&s, &abc), 5);
        // The right value: the rules give it once the line is explicit.
        let explicit = system(&text(
            r#", Incident(id: "a_L", a: "a", b: "L"), Incident(id: "b_L", a: "b", b: "L"),
                Incident(id: "c_L", a: "c", b: "L")"#,
        ));
        assert_eq!(RuleDor::for_system(&explicit).dor(&explicit, &abc), 5);
    }

    #[test]
    fn medians_are_concurrent() {
        // Theorem: the medians of a triangle meet at one point. G is put on two medians; it is
        // on the third, so c, its opposite midpoint mc and G are collinear (3D: DOR 5).
        let s = system(
            r#"System(dim: 3, entities: [
                Point(id: "a", at: [0, 0, 0]), Point(id: "b", at: [6, 0, 3]), Point(id: "c", at: [0, 6, 9]),
                Segment(id: "ab", from: "a", to: "b"), Segment(id: "bc", from: "b", to: "c"),
                Segment(id: "ca", from: "c", to: "a"),
                Point(id: "ma", at: [3, 3, 6]), Point(id: "mb", at: [0, 3, 4.5]), Point(id: "mc", at: [3, 0, 1.5]),
                Segment(id: "med_a", from: "a", to: "ma"), Segment(id: "med_b", from: "b", to: "mb"),
                Point(id: "G", at: [2, 2, 4]) ],
              constraints: [
                Midpoint(id: "m_a", point: "ma", segment: "bc"), Midpoint(id: "m_b", point: "mb", segment: "ca"),
                Midpoint(id: "m_c", point: "mc", segment: "ab"),
                Incident(id: "G_a", a: "G", b: "med_a"), Incident(id: "G_b", a: "G", b: "med_b") ])"#,
        );
        let (w, r) = both(&s);
        let set = ids(&s, &["c", "mc", "G"]);
        assert_eq!(r.dor(&s, &set), 6);
        assert_eq!(w.dor(&s, &set), 5);
        // Stated explicitly (the midpoints and G on one segment), the rules agree.
        assert_eq!(r.dor(&s, &ids(&s, &["a", "ma", "G"])), 5);
        assert_eq!(w.dor(&s, &ids(&s, &["a", "ma", "G"])), 5);
        // A control: a, b, G are not collinear.
        assert_eq!(w.dor(&s, &ids(&s, &["a", "b", "G"])), 6);
    }

    #[test]
    fn midline_is_parallel_to_the_base() {
        // 2D theorem: the line through the midpoints of two sides is parallel to the third.
        let s = system(
            r#"System(dim: 2, entities: [
                Point(id: "a", at: [0, 0]), Point(id: "b", at: [8, 2]), Point(id: "c", at: [2, 6]),
                Segment(id: "ab", from: "a", to: "b"), Segment(id: "ac", from: "a", to: "c"),
                Point(id: "m", at: [4, 1]), Point(id: "n", at: [1, 3]),
                Line(id: "mid", at: [[4, 1], [1, 3]]), Line(id: "base", at: [[8, 2], [2, 6]]) ],
              constraints: [
                Midpoint(id: "m_ab", point: "m", segment: "ab"), Midpoint(id: "n_ac", point: "n", segment: "ac"),
                Incident(id: "m_on", a: "m", b: "mid"), Incident(id: "n_on", a: "n", b: "mid"),
                Incident(id: "b_on", a: "b", b: "base"), Incident(id: "c_on", a: "c", b: "base") ])"#,
        );
        let (w, r) = both(&s);
        let set = ids(&s, &["mid", "base"]);
        assert_eq!(r.dor(&s, &set), 3);
        assert_eq!(w.dor(&s, &set), 2);
        // The points are what they are: 3 whatever their alignment in 2D.
        assert_eq!(w.dor(&s, &ids(&s, &["m", "n", "b"])), 3);
    }

    #[test]
    fn perpendicular_to_two_lines_in_3d_means_parallel() {
        // In 3D, two lines perpendicular to one common line need not be parallel; perpendicular
        // to two secant directions, they are.
        // The sketch of L2 is drawn parallel to L1 only when the constraints force it: a
        // witness is a configuration, and one drawn with an accidental parallelism has it.
        let text = |with_n: bool| {
            let (extra, l2) = if with_n {
                (
                    r#", Perpendicular(id: "b", a: "L1", b: "N"), Perpendicular(id: "d", a: "L2", b: "N")"#,
                    "[[3, 2, 0], [3, 2, 5]]",
                )
            } else {
                ("", "[[3, 2, 0], [3, 5, 3]]")
            };
            format!(
                r#"System(dim: 3, entities: [
                    Line(id: "M", at: [[0, 0, 0], [1, 0, 0]]), Line(id: "N", at: [[0, 0, 1], [0, 1, 1]]),
                    Line(id: "L1", at: [[0, 0, 0], [0, 0, 1]]), Line(id: "L2", at: {l2}) ],
                  constraints: [
                    Perpendicular(id: "a", a: "L1", b: "M"), Perpendicular(id: "c", a: "L2", b: "M") {extra} ])"#
            )
        };
        let one = system(&text(false));
        let (w, r) = both(&one);
        let l = ids(&one, &["L1", "L2"]);
        assert_eq!((w.dor(&one, &l), r.dor(&one, &l)), (6, 6));
        let two = system(&text(true));
        let (w, r) = both(&two);
        assert_eq!(r.dor(&two, &l), 6);
        assert_eq!(w.dor(&two, &l), 5);
        // With the parallelism stated, the rules agree with the witness.
        let stated = system(&text(false).replace(
            "Perpendicular(id: \"c\"",
            "Parallel(id: \"par\", a: \"L1\", b: \"L2\"), Perpendicular(id: \"c\"",
        ));
        assert_eq!(RuleDor::for_system(&stated).dor(&stated, &l), 5);
    }

    #[test]
    fn monotone_bounded_and_robust() {
        let s = gcs_model::generate::triangulated_sphere(12, 3);
        let w = WitnessDor::find(&s, 1).unwrap();
        let n = s.entities().len();
        for set in small_sets(n.min(8)) {
            let d = w.dor(&s, &set);
            assert!(d <= 6);
            for drop in 0..set.len() {
                let mut smaller = set.clone();
                smaller.remove(drop);
                assert!(w.dor(&s, &smaller) <= d);
            }
        }
        let all: Vec<EntityIdx> = s.entity_indices().collect();
        assert_eq!(w.dor(&s, &all), 6);
        // Out of range and repeated indices.
        assert_eq!(w.dor(&s, &[EntityIdx(10_000)]), 0);
        assert_eq!(w.dor(&s, &[EntityIdx(0), EntityIdx(0)]), 3);
        // A wrong witness is an error, not a panic.
        let layout = Layout::new(&s);
        assert!(matches!(WitnessDor::new(&s, &layout, &[]), Err(RigidityError::Witness(_))));
        let other = gcs_model::generate::laman(5, 1);
        assert!(
            WitnessDor::new(
                &other,
                &layout,
                &vec![BigRational::from_integer(1.into()); layout.ncols()]
            )
            .is_err()
        );
    }
}
