//! The user's own drawing (the survey's criterion (f)): the rank of the Jacobian at the sketch
//! against the generic rank, the constraints that are dependent at the drawing although they
//! are not generically (a singular configuration: three collinear points of a triangle, K3,3
//! on a conic), the extra infinitesimal motions the drawing admits, the classical causes when
//! one is recognisable, and whether the drawing satisfies its own constraints.
//!
//! The rank at the sketch is decided in the analysis' arithmetic, exactly by default: the
//! sketch is rational (a decimal is the rational it denotes). The rank at any configuration is
//! at most the generic rank on the constraints' solution set, so a sketch whose rank equals the
//! witness's is not singular; a drop is a proven dependency (its circuit lifted or certified
//! like any other). A drawing that does not satisfy its constraints is off that set, where the
//! rank can also exceed the generic one: it is still reported, with the largest residual.

use gcs_jacobian::{Equations, Layout, Witness, WitnessSource, plan::plan_anywhere, sketch};
use gcs_model::{ConstraintIdx, Dim, EntityClass, EntityIdx, System};
use gcs_rank::{BigRational, Proof, Rat};
use num_traits::{Signed, ToPrimitive, Zero};

use crate::analysis::{Backend, Outcome, Redundancy, rank_at, redundancies};
use crate::error::AnalysisError;

/// The kind of a classical special position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Position {
    /// Two points at the same place.
    Coincident,
    /// Three or more points on one line.
    Collinear,
    /// Four or more points on one plane (3D).
    Coplanar,
    /// Two or more lines (or segments) with the same direction.
    Parallel,
    /// Three or more lines (or the lines of distances between points, with no end point in
    /// common) through one point (2D).
    Concurrent,
}

impl Position {
    /// The report name: `coincident`, `collinear`, `coplanar`, `parallel`, `concurrent`.
    pub fn name(self) -> &'static str {
        match self {
            Position::Coincident => "coincident",
            Position::Collinear => "collinear",
            Position::Coplanar => "coplanar",
            Position::Parallel => "parallel",
            Position::Concurrent => "concurrent",
        }
    }
}

/// A classical special position recognised among the entities of a dependency: the entities
/// in that position, or, for the lines of distances between points, those constraints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Configuration {
    /// Which position.
    pub position: Position,
    /// The points or lines in it, in file order (empty when it is about `constraints`).
    pub entities: Vec<EntityIdx>,
    /// The distances whose lines are in it (concurrent bars), in file order.
    pub constraints: Vec<ConstraintIdx>,
}

impl Configuration {
    fn of(position: Position, entities: Vec<EntityIdx>) -> Self {
        Configuration { position, entities, constraints: Vec::new() }
    }
}

/// A constraint far from what its drawing shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Residual {
    /// The constraint.
    pub constraint: ConstraintIdx,
    /// How far: for a dimension, its measure on the drawing minus its value (model units or
    /// degrees); for another constraint, how far the drawing is from satisfying it to first
    /// order (its residual over the norm of its gradient).
    pub value: f64,
}

/// What the analysis says of the drawing itself.
#[derive(Clone, Debug, PartialEq)]
pub struct SketchAnalysis {
    /// The rank of the Jacobian at the sketch's own coordinates.
    pub rank: usize,
    /// Below the generic rank (the witness's): the drawing is at a special position.
    pub singular: bool,
    /// The constraints independent generically but dependent at the drawing, in file order,
    /// each with its spanning group at the drawing (`rows`: how many of its rows are dependent
    /// beyond the generic ones).
    pub dependent: Vec<Redundancy>,
    /// The infinitesimal motions the drawing admits beyond the generic ones.
    pub extra_motions: usize,
    /// Whether the drawing satisfies its constraints: every dimension to the precision its
    /// value is written with (half a unit of its last decimal; an integer or a fraction to
    /// rounding), every parameter-free constraint to the precision of the coordinates it reads
    /// (exactly, or within the first-order reach Σ |∂row/∂x|·h of moving each coordinate by
    /// h, half a unit of the last decimal its entity is written with: a point written
    /// [1.5, 1.3229] is on the circle of radius 2 about the origin).
    pub satisfied: bool,
    /// The constraint the drawing is farthest from satisfying, when it does not satisfy them.
    pub largest_residual: Option<Residual>,
    /// The special positions recognised among the entities of the dependent constraints.
    pub configurations: Vec<Configuration>,
    /// How the exact backend proved the rank at the sketch (`None` when the sketch is the
    /// witness, whose proof is the analysis', and for the other backends).
    pub proof: Option<Proof>,
}

/// The analysis of the drawing, beside the generic one (`generic`, `redundant`, `dof` at
/// `witness`). `None` when some entity has no sketch position.
pub(crate) fn analyse(
    system: &System,
    layout: &Layout,
    witness: &Witness,
    backend: Backend,
    generic: &Outcome,
    redundant: &[Redundancy],
    dof: usize,
) -> Result<Option<SketchAnalysis>, AnalysisError> {
    let Some(x) = sketch::drawing_in::<BigRational>(system, layout) else { return Ok(None) };
    let (satisfied, largest_residual) = residuals(system, layout, &x);
    let mut out = SketchAnalysis {
        rank: generic.rank,
        singular: false,
        dependent: Vec::new(),
        extra_motions: 0,
        satisfied,
        largest_residual,
        configurations: Vec::new(),
        proof: None,
    };
    if witness.source == WitnessSource::Sketch {
        // The sketch is the witness, and generic (Moinet's test): nothing more to decide.
        return Ok(Some(out));
    }
    let xr: Vec<Rat> = x.iter().map(Rat::from).collect();
    let sketch_in = |e: EntityIdx| sketch::sketch_coords_in::<Rat>(system, e);
    let plan = plan_anywhere(system, layout, &xr, &sketch_in);
    let drawing = Witness {
        coords: x.clone(),
        source: WitnessSource::Sketch,
        plan,
        genericity_tested: false,
        sketch_rejected: None,
        no_exact_witness: None,
        modulus: None,
        turns: Vec::new(),
    };
    let (outcome, _, _) = rank_at(system, layout, &drawing, backend)?;
    let at_sketch = redundancies(system, layout, &drawing, &outcome);
    for r in at_sketch {
        let generic_rows =
            redundant.iter().find(|g| g.constraint == r.constraint).map_or(0, |g| g.rows);
        if r.rows > generic_rows {
            out.dependent.push(Redundancy { rows: r.rows - generic_rows, ..r });
        }
    }
    out.rank = outcome.rank;
    out.singular = outcome.rank < generic.rank;
    let dof_sketch = layout.ncols().saturating_sub(outcome.rank).saturating_sub(outcome.trivial);
    out.extra_motions = dof_sketch.saturating_sub(dof);
    out.proof = outcome.proof;
    for d in &out.dependent {
        let mut entities: Vec<EntityIdx> = Vec::new();
        for c in std::iter::once(&d.constraint).chain(&d.spanning_group) {
            for e in system.constraint(*c).signature.entities() {
                if !entities.contains(&e) {
                    entities.push(e);
                }
            }
        }
        let constraints: Vec<ConstraintIdx> =
            std::iter::once(d.constraint).chain(d.spanning_group.iter().copied()).collect();
        for found in recognise(system, &entities, &constraints) {
            if !out.configurations.contains(&found) {
                out.configurations.push(found);
            }
        }
    }
    Ok(Some(out))
}

/// Whether the drawing satisfies its constraints, and if not the largest residual (see
/// [`SketchAnalysis::satisfied`]): parameter-free constraints first, by how far the drawing is
/// from them; then dimensions, by their difference over the precision of their value.
fn residuals(system: &System, layout: &Layout, x: &[BigRational]) -> (bool, Option<Residual>) {
    let xf: Vec<f64> = x.iter().map(|v| v.to_f64().unwrap_or(f64::NAN)).collect();
    let xr: Vec<Rat> = x.iter().map(Rat::from).collect();
    let equations = Equations::new(system, layout).with_branches_at(&xf);
    // Each coordinate's precision is its entity's: the finest among the entity's decimal
    // coordinates (a point written [1.5, 1.35] is written to two decimals, in x as in y; its
    // integers do not count — [12.3456789, 0] is written to seven).
    let mut h: Vec<f64> = x.iter().map(gcs_model::number::written_precision).collect();
    for e in system.entity_indices() {
        let columns = layout.columns(e);
        let decimals = columns.clone().filter(|&c| !x[c].is_integer());
        let Some(finest) = decimals.map(|c| h[c]).reduce(f64::min) else { continue };
        for c in columns {
            h[c] = finest;
        }
    }
    // (class: 1 for a parameter-free constraint, 0 for a dimension; score; residual)
    let mut worst: Option<(u8, f64, Residual)> = None;
    for c in system.constraint_indices() {
        let constraint = system.constraint(c);
        let (class, score, value) = if constraint.kind.is_metric() {
            let Some(value) = constraint.value.as_ref() else { continue };
            let Some(r) = equations.residual(c, &xf) else { continue };
            let difference = r.values.first().copied().unwrap_or(0.0);
            let tolerance = gcs_model::number::written_precision(value);
            if difference.abs() <= tolerance {
                continue;
            }
            (0, difference.abs() / tolerance, difference)
        } else {
            if equations.rows::<Rat>(c, &xr).values.iter().all(Rat::is_zero) {
                continue;
            }
            let r = equations.rows::<f64>(c, &xf);
            // Within the precision of the coordinates it reads: moving each by at most half a
            // unit of its last written decimal moves the row, to first order, by at most
            // Σ |∂row/∂x|·h — the drawing satisfies the row if its value is within that.
            let within = r.values.iter().zip(&r.rows).all(|(v, g)| {
                let reach: f64 = g.entries().iter().map(|&(col, a)| a.abs() * h[col]).sum();
                v.abs() <= reach
            });
            if within {
                continue;
            }
            let distance = r
                .values
                .iter()
                .zip(&r.rows)
                .map(|(v, g)| {
                    let norm = g.entries().iter().map(|(_, a)| a * a).sum::<f64>().sqrt();
                    if norm > 0.0 { v.abs() / norm } else { v.abs() }
                })
                .fold(0.0, f64::max);
            (1, distance, distance)
        };
        let candidate = (class, score, Residual { constraint: c, value });
        if worst.as_ref().is_none_or(|w| (candidate.0, candidate.1) > (w.0, w.1)) {
            worst = Some(candidate);
        }
    }
    (worst.is_none(), worst.map(|w| w.2))
}

/// The classical special positions among `entities` (and the distances among `constraints`)
/// at the drawing, exactly.
fn recognise(
    system: &System,
    entities: &[EntityIdx],
    constraints: &[ConstraintIdx],
) -> Vec<Configuration> {
    let mut points: Vec<(EntityIdx, Vec<BigRational>)> = Vec::new();
    let mut lines: Vec<EntityIdx> = Vec::new();
    for &e in entities {
        let entity = system.entity(e);
        match entity.kind().class() {
            EntityClass::Point => {
                if let Some(x) = sketch::sketch_coords(system, e) {
                    points.push((e, x));
                }
            }
            EntityClass::Line => lines.push(e),
            EntityClass::Plane | EntityClass::Circle | EntityClass::Sphere | EntityClass::Curve => {
            }
        }
        // A segment's points take part too.
        for p in entity.geometry.parts() {
            if !points.iter().any(|(q, _)| *q == p)
                && let Some(x) = sketch::sketch_coords(system, p)
            {
                points.push((p, x));
            }
        }
    }
    points.sort_by_key(|(e, _)| *e);
    // (A point that is also a named segment's end point came twice.)
    points.dedup_by_key(|(e, _)| *e);
    lines.sort();
    let mut out = Vec::new();
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            if points[i].1 == points[j].1 {
                out.push(Configuration::of(Position::Coincident, vec![points[i].0, points[j].0]));
            }
        }
    }
    let distinct: Vec<&(EntityIdx, Vec<BigRational>)> = points
        .iter()
        .enumerate()
        .filter(|(i, (_, x))| !points[..*i].iter().any(|(_, y)| y == x))
        .map(|(_, p)| p)
        .collect();
    if let Some(set) = aligned(&distinct, 1) {
        out.push(Configuration::of(Position::Collinear, set));
    } else if system.dim() == Dim::Three
        && let Some(set) = aligned(&distinct, 2)
    {
        out.push(Configuration::of(Position::Coplanar, set));
    }
    if system.dim() == Dim::Two && lines.len() >= 2 {
        let homogeneous: Vec<(EntityIdx, Vec<BigRational>)> =
            lines.iter().filter_map(|l| line2(system, *l).map(|h| (*l, h))).collect();
        let parallel: Vec<EntityIdx> = homogeneous
            .iter()
            .filter(|(_, h)| {
                homogeneous
                    .iter()
                    .filter(|(_, k)| (&h[0] * &k[1] - &h[1] * &k[0]).is_zero())
                    .count()
                    >= 2
            })
            .map(|(l, _)| *l)
            .collect();
        let all_parallel = parallel.len() == homogeneous.len();
        if parallel.len() >= 2 {
            out.push(Configuration::of(Position::Parallel, parallel));
        }
        if homogeneous.len() >= 3 {
            // Concurrent: every 3×3 determinant of (a, b, c) rows vanishes (rank ≤ 2), and the
            // lines are not all parallel.
            let rows: Vec<&Vec<BigRational>> = homogeneous.iter().map(|(_, h)| h).collect();
            if rank3(&rows) == 2 && !all_parallel {
                let lines = homogeneous.iter().map(|(l, _)| *l).collect();
                out.push(Configuration::of(Position::Concurrent, lines));
            }
        }
    }
    if system.dim() == Dim::Two
        && let Some(bars) = concurrent_bars(system, constraints)
    {
        out.push(Configuration {
            position: Position::Concurrent,
            entities: Vec::new(),
            constraints: bars,
        });
    }
    out
}

/// The first three distances between points, with no end point in common, whose lines pass
/// through one point (the joining bars of a prism drawn with them concurrent), in file order.
fn concurrent_bars(system: &System, constraints: &[ConstraintIdx]) -> Option<Vec<ConstraintIdx>> {
    let mut bars: Vec<(ConstraintIdx, [EntityIdx; 2], Vec<BigRational>)> = Vec::new();
    let mut sorted = constraints.to_vec();
    sorted.sort();
    for c in sorted {
        if let gcs_model::Signature::Metric(gcs_model::Metric::DistancePointPoint(a, b)) =
            system.constraint(c).signature
        {
            let (p, q) = (sketch::sketch_coords(system, a)?, sketch::sketch_coords(system, b)?);
            if p != q {
                bars.push((c, [a, b], sketch::line2_through(&p, &q)));
            }
        }
    }
    let disjoint = |x: &[EntityIdx; 2], y: &[EntityIdx; 2]| x.iter().all(|e| !y.contains(e));
    for i in 0..bars.len() {
        for j in i + 1..bars.len() {
            if !disjoint(&bars[i].1, &bars[j].1) {
                continue;
            }
            for k in j + 1..bars.len() {
                if !disjoint(&bars[i].1, &bars[k].1) || !disjoint(&bars[j].1, &bars[k].1) {
                    continue;
                }
                let rows = [&bars[i].2, &bars[j].2, &bars[k].2];
                let parallel = |h: &Vec<BigRational>, g: &Vec<BigRational>| {
                    (&h[0] * &g[1] - &h[1] * &g[0]).is_zero()
                };
                let all_parallel = parallel(rows[0], rows[1]) && parallel(rows[1], rows[2]);
                if rank3(&rows) == 2 && !all_parallel {
                    return Some(vec![bars[i].0, bars[j].0, bars[k].0]);
                }
            }
        }
    }
    None
}

/// The largest set (at least `span + 2` points) whose differences from the first span at most
/// `span` dimensions — collinear for 1, coplanar for 2 — if the points have one: all of them,
/// or else the first such triple (quadruple) in file order.
fn aligned(points: &[&(EntityIdx, Vec<BigRational>)], span: usize) -> Option<Vec<EntityIdx>> {
    let need = span + 2;
    if points.len() < need {
        return None;
    }
    let spans = |set: &[&(EntityIdx, Vec<BigRational>)]| -> bool {
        let origin = &set[0].1;
        let diffs: Vec<Vec<BigRational>> = set[1..]
            .iter()
            .map(|(_, x)| x.iter().zip(origin).map(|(a, b)| a - b).collect())
            .collect();
        let refs: Vec<&Vec<BigRational>> = diffs.iter().collect();
        rank3(&refs) <= span
    };
    if spans(points) {
        return Some(points.iter().map(|(e, _)| *e).collect());
    }
    // The first subset of `need` points in file order.
    let n = points.len();
    let mut idx: Vec<usize> = (0..need).collect();
    loop {
        let set: Vec<&(EntityIdx, Vec<BigRational>)> = idx.iter().map(|&i| points[i]).collect();
        if spans(&set) {
            return Some(set.iter().map(|(e, _)| *e).collect());
        }
        // Next combination.
        let mut k = need;
        loop {
            if k == 0 {
                return None;
            }
            k -= 1;
            if idx[k] < n - need + k {
                break;
            }
        }
        idx[k] += 1;
        for j in k + 1..need {
            idx[j] = idx[j - 1] + 1;
        }
    }
}

/// The rank of a few short rational vectors (at most 3 coordinates).
fn rank3(rows: &[&Vec<BigRational>]) -> usize {
    let mut m: Vec<Vec<BigRational>> = rows.iter().map(|r| (*r).clone()).collect();
    let cols = m.first().map_or(0, Vec::len);
    let mut rank = 0;
    for c in 0..cols {
        let Some(p) = (rank..m.len()).find(|&i| !m[i][c].is_zero()) else { continue };
        m.swap(rank, p);
        let pivot = m[rank].clone();
        for row in m.iter_mut().skip(rank + 1) {
            if !row[c].is_zero() {
                let f = &row[c] / &pivot[c];
                for (a, b) in row.iter_mut().zip(&pivot) {
                    *a -= &f * b;
                }
            }
        }
        rank += 1;
    }
    rank
}

/// A 2D line or segment as homogeneous `(a, b, c)` at the drawing.
fn line2(system: &System, l: EntityIdx) -> Option<Vec<BigRational>> {
    match system.segment_points(l) {
        Some((p, q)) => Some(sketch::line2_through(
            &sketch::sketch_coords(system, p)?,
            &sketch::sketch_coords(system, q)?,
        )),
        None => sketch::sketch_coords(system, l),
    }
}

#[cfg(test)]
mod tests {
    use gcs_model::System;
    use gcs_model::number::parse_exact;

    use super::{Position, recognise};

    #[test]
    fn a_point_named_beside_its_segment_is_not_coincident_with_itself() {
        let s = System::from_ron_str(
            r#"System(dim: 2, entities: [
                Point(id: "a", at: [0, 0]), Point(id: "b", at: [4, 0]), Point(id: "c", at: [4, 0]),
                Segment(id: "s", from: "a", to: "b"),
            ], constraints: [])"#,
            None,
        )
        .unwrap();
        let e = |id: &str| s.entity_by_id(id).unwrap();
        // The segment names a and b; a and c are named again: only b and c coincide.
        let found = recognise(&s, &[e("s"), e("a"), e("c")], &[]);
        let coincident: Vec<_> =
            found.iter().filter(|c| c.position == Position::Coincident).collect();
        assert_eq!(coincident.len(), 1, "{found:?}");
        assert_eq!(coincident[0].entities, vec![e("b"), e("c")]);
    }

    #[test]
    fn precision_follows_the_written_decimals() {
        let p = |s: &str| gcs_model::number::written_precision(&parse_exact(s).unwrap());
        assert!((p("3.1623") - 0.00005).abs() < 1e-15);
        assert!((p("12.5") - 0.05).abs() < 1e-15);
        assert!(p("40") < 1e-7);
        assert!(p("1/3") < 1e-8);
    }
}
