//! Solving a constraint system at the user's values, and telling a redundant constraint that
//! agrees with the others (consistent) from one that contradicts them (conflicting) — the
//! survey's criterion (b), which needs the values.
//!
//! This first solver works on the whole system: damped Gauss–Newton (Levenberg–Marquardt,
//! [`gcs_rank::levenberg_marquardt`]) from the drawing, on the residuals of
//! [`gcs_jacobian::Equations`] — the same equations the analysis ranks, with the user's values
//! for the dimensions. Small damped steps from the drawing keep its shape: an under-constrained
//! sketch moves as little as it must, and the side of a tangency or the orientation of a
//! triangle is the drawing's.
//!
//! With the analysis of the system ([`gcs_analysis::analyze`]), the fully redundant
//! constraints are left out of the solve (they add no condition a consistent system needs) and
//! then measured at the solution: within the tolerance they are consistent, beyond it they
//! conflict, with their spanning group (the constraints they conflict with). The solving along
//! the DR-plan cluster by cluster, the choice among the solutions and the report of clusters
//! without a real solution are not built yet.
//!
//! A library: it never panics on input and never prints.

use gcs_analysis::Analysis;
use gcs_jacobian::{Equations, Layout};
use gcs_model::{ConstraintIdx, System};
use gcs_rank::{BigRational, LmOptions, Residuals, SparseRow, levenberg_marquardt};
use num_traits::ToPrimitive;

/// Options of [`solve`].
#[derive(Clone, Debug, PartialEq)]
pub struct SolveOptions {
    /// Relative tolerance: a residual counts as zero when it is at most this times the model's
    /// size (lengths), its square (the polynomial residuals of parameter-free constraints) or
    /// 180° (angles).
    pub tolerance: f64,
    /// The most Gauss–Newton steps.
    pub max_iterations: usize,
    /// Larger systems are not attempted (the steps are dense).
    pub max_unknowns: usize,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions { tolerance: 1e-9, max_iterations: 500, max_unknowns: 3_000 }
    }
}

/// How the solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Every constraint holds at the solution.
    Solved,
    /// The constraints were solved without the redundant ones, and some of those do not hold
    /// there: they conflict.
    Inconsistent,
    /// The numerics did not reach the tolerance: see [`Solution::worst`].
    Failed,
}

impl Status {
    /// The name used in reports: `solved`, `inconsistent`, `failed`.
    pub fn name(self) -> &'static str {
        match self {
            Status::Solved => "solved",
            Status::Inconsistent => "inconsistent",
            Status::Failed => "failed",
        }
    }
}

/// A redundant constraint measured at the solution.
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    /// The constraint.
    pub constraint: ConstraintIdx,
    /// Its residual at the solution: for a dimension, the measure minus the value (model
    /// units, or degrees); for a parameter-free constraint, its largest polynomial residual.
    pub residual: f64,
    /// How large the residual may be and the constraint still agree: the written precision of
    /// the values in the dependency (half a unit of the last decimal of each: `3.1623` is
    /// meant to ±0.00005), plus the solver's tolerance.
    pub allowance: f64,
    /// Whether the residual exceeds the allowance: the constraint contradicts its spanning
    /// group.
    pub conflicting: bool,
    /// The constraints it is redundant with (from the analysis).
    pub spanning_group: Vec<ConstraintIdx>,
}

/// The result of [`solve`].
#[derive(Clone, Debug, PartialEq)]
pub struct Solution {
    /// How it ended.
    pub status: Status,
    /// The solved configuration over the layout's columns.
    pub x: Vec<f64>,
    /// The largest residual of the constraints solved, scaled as the tolerance is (a multiple
    /// of the model's size: 1e-13 means 1e-13 of it).
    pub max_residual: f64,
    /// The constraint with the largest residual among those solved, when the solve failed.
    pub worst: Option<ConstraintIdx>,
    /// How far the drawing moved: the largest displacement of a coordinate of a point, centre
    /// or radius, in model units.
    pub moved: f64,
    /// Every fully redundant constraint of the analysis, measured at the solution.
    pub redundant: Vec<Checked>,
    /// Gauss–Newton steps taken.
    pub iterations: usize,
    /// The model's size: the largest coordinate of the drawing (at least 1).
    pub scale: f64,
}

/// Why a system was not solved.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SolveError {
    /// Too many unknowns for the dense solver.
    #[error(
        "{unknowns} unknowns: more than the dense solver takes ({max}); the solver along the decomposition is not built yet"
    )]
    TooLarge {
        /// The unknowns.
        unknowns: usize,
        /// The limit.
        max: usize,
    },
}

/// The residuals the solver minimises: every constraint not left out, the metric ones against
/// their values, each scaled to be relative to the model's size, and the internal relations
/// (not the normalisations of homogeneous coordinates, which the steps leave free).
struct Problem<'s> {
    system: &'s System,
    layout: &'s Layout,
    equations: Equations<'s>,
    solved: Vec<ConstraintIdx>,
    scale: f64,
}

/// What a residual of constraint `c` is measured against: the model's size for a length, 180°
/// for an angle, the size squared for the polynomial residuals of parameter-free constraints.
fn unit(system: &System, c: ConstraintIdx, scale: f64) -> f64 {
    let kind = system.constraint(c).kind;
    if !kind.is_metric() {
        scale * scale
    } else if kind == gcs_model::ConstraintKind::Angle {
        180.0
    } else {
        scale
    }
}

impl Problem<'_> {
    /// The residual of one constraint, relative (over its [`unit`]). `None` for a metric
    /// constraint without a value (nothing to impose).
    fn residual(&self, c: ConstraintIdx, x: &[f64]) -> Option<(Vec<f64>, Vec<SparseRow<f64>>)> {
        let r = self.equations.residual(c, x)?;
        let unit = unit(self.system, c, self.scale);
        let values = r.values.iter().map(|v| v / unit).collect();
        let rows = r
            .rows
            .iter()
            .map(|row| {
                SparseRow::from_entries(row.entries().iter().map(|(c, v)| (*c, v / unit)).collect())
            })
            .collect();
        Some((values, rows))
    }
}

impl Residuals for Problem<'_> {
    fn unknowns(&self) -> usize {
        self.layout.ncols()
    }

    fn evaluate(&self, x: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
        let mut values = Vec::new();
        let mut rows = Vec::new();
        for &c in &self.solved {
            if let Some((v, r)) = self.residual(c, x) {
                values.extend(v);
                rows.extend(r);
            }
        }
        for e in self.system.entity_indices() {
            let Some(repr) = self.layout.repr(e) else { continue };
            if repr.internal_rows() > usize::from(repr.homogeneous()) {
                let (v, r) = self.equations.internal_residuals(e, x);
                let unit = self.scale * self.scale;
                // The first internal row is the relation (the normalisation, if any, is last).
                if let (Some(value), Some(row)) = (v.first(), r.first()) {
                    values.push(value / unit);
                    rows.push(SparseRow::from_entries(
                        row.entries().iter().map(|(c, v)| (*c, v / unit)).collect(),
                    ));
                }
            }
        }
        (values, rows)
    }
}

/// The drawing over the layout's columns: each entity's sketch, or where it has none the
/// analysis' witness.
fn start(system: &System, layout: &Layout, analysis: &Analysis) -> Vec<f64> {
    let mut drawn = vec![false; layout.ncols()];
    let mut x = vec![0.0; layout.ncols()];
    let mut size: f64 = 1.0;
    for e in system.entity_indices() {
        if let Some(coords) = gcs_jacobian::sketch::sketch_coords_in::<f64>(system, e) {
            for (col, v) in layout.columns(e).zip(coords) {
                (x[col], drawn[col]) = (v, true);
                size = size.max(v.abs());
            }
        }
    }
    // What the drawing leaves out starts at the witness; a modular witness holds residues,
    // which are no real numbers: their pseudo-random images in [−size, size) instead.
    let modular = analysis.witness.source == gcs_jacobian::WitnessSource::Modular;
    let prime = analysis.witness.modulus.unwrap_or(gcs_rank::ModP::PRIME) as f64;
    for (col, q) in analysis.witness.coords.iter().enumerate().take(x.len()) {
        if !drawn[col] {
            let v = q.to_f64().unwrap_or(0.0);
            x[col] = if modular { size * (2.0 * v / prime - 1.0) } else { v };
        }
    }
    x
}

/// Solves `system` at its values, from its drawing, leaving out the constraints `analysis`
/// finds fully redundant and measuring them at the solution.
///
/// # Errors
/// [`SolveError::TooLarge`] beyond [`SolveOptions::max_unknowns`].
pub fn solve(
    system: &System,
    analysis: &Analysis,
    options: &SolveOptions,
) -> Result<Solution, SolveError> {
    let layout = Layout::new(system);
    let x0 = start(system, &layout, analysis);
    let scale = x0.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let fully: Vec<&gcs_analysis::Redundancy> =
        analysis.redundant.iter().filter(|r| r.rows == r.doc).collect();
    let left_out: std::collections::HashSet<ConstraintIdx> =
        fully.iter().map(|r| r.constraint).collect();
    let solved: Vec<ConstraintIdx> =
        system.constraint_indices().filter(|c| !left_out.contains(c)).collect();
    let equations = Equations::new(system, &layout).with_branches_at(&x0);
    let problem = Problem { system, layout: &layout, equations, solved, scale };
    let lm = LmOptions {
        tolerance: options.tolerance * 1e-5,
        max_iterations: options.max_iterations,
        max_unknowns: options.max_unknowns,
        ..LmOptions::default()
    };
    let Some(outcome) = levenberg_marquardt(&problem, &x0, &lm) else {
        return Err(SolveError::TooLarge { unknowns: layout.ncols(), max: options.max_unknowns });
    };
    let x = outcome.x;
    // The worst constraint solved.
    let mut worst: Option<(f64, ConstraintIdx)> = None;
    for &c in &problem.solved {
        if let Some((v, _)) = problem.residual(c, &x) {
            let m = v.iter().fold(0.0f64, |m, r| m.max(r.abs()));
            if worst.is_none_or(|(w, _)| m > w) {
                worst = Some((m, c));
            }
        }
    }
    let max_residual = worst.map_or(0.0, |w| w.0);
    let converged = max_residual <= options.tolerance && x.iter().all(|v| v.is_finite());
    let redundant: Vec<Checked> = fully
        .iter()
        .map(|r| {
            let c = r.constraint;
            let residual = problem.equations.residual(c, &x).map_or(0.0, |res| {
                res.values.iter().fold(0.0f64, |m, v| if v.abs() > m.abs() { *v } else { m })
            });
            // The written precision of every value in the dependency, in the units of this
            // constraint's residual (first order: a parameter-free residual is quadratic in
            // lengths, so a length's precision h moves it by about 2·scale·h).
            let written: f64 = std::iter::once(c)
                .chain(r.spanning_group.iter().copied())
                .filter_map(|g| system.constraint(g).value.as_ref())
                .map(gcs_model::number::written_precision)
                .sum();
            let allowance = options.tolerance * 1e3 * unit(system, c, scale)
                + if system.constraint(c).kind.is_metric() {
                    written
                } else {
                    2.0 * scale * written
                };
            Checked {
                constraint: c,
                residual,
                allowance,
                conflicting: residual.abs() > allowance,
                spanning_group: r.spanning_group.clone(),
            }
        })
        .collect();
    let status = if !converged {
        Status::Failed
    } else if redundant.iter().any(|r| r.conflicting) {
        Status::Inconsistent
    } else {
        Status::Solved
    };
    let mut moved = 0.0f64;
    for e in system.entity_indices() {
        let Some(repr) = layout.repr(e) else { continue };
        if repr.homogeneous() {
            continue;
        }
        for col in layout.columns(e) {
            moved = moved.max((x[col] - x0[col]).abs());
        }
    }
    Ok(Solution {
        status,
        worst: if converged { None } else { worst.map(|w| w.1) },
        max_residual,
        moved,
        redundant,
        iterations: outcome.iterations,
        scale,
        x,
    })
}

/// A solved coordinate as a decimal on the grid of 10^-9 (the lowering's snapping of CAD
/// drawings): the solver's own error is far below it, and a solution that is 50 up to the
/// solver's rounding is written 50, so that the drawing it gives satisfies exact relations
/// exactly. Beyond the range of the grid, the shortest decimal of the double.
fn on_grid(v: f64) -> Option<BigRational> {
    let scaled = (v * 1e9).round();
    if scaled.is_finite() && scaled.abs() < 9e18 {
        let n = num_bigint::BigInt::from(scaled as i64);
        return Some(BigRational::new(n, num_bigint::BigInt::from(1_000_000_000u64)));
    }
    gcs_model::number::rational_from_f64_decimal(v)
}

/// The system with its sketch replaced by the solution (coordinates on the grid of 10^-9, see
/// [`on_grid`]), for writing as RON and analysing again.
pub fn solved_system(system: &System, solution: &Solution) -> System {
    let layout = Layout::new(system);
    let mut out = system.clone();
    for e in system.entity_indices() {
        let Some(repr) = layout.repr(e) else { continue };
        let coords: Option<Vec<BigRational>> =
            layout.columns(e).map(|c| on_grid(solution.x[c])).collect();
        let Some(coords) = coords else { continue };
        let geometry = repr.to_sketch(&coords, &system.entity(e).geometry);
        // A solution the model refuses (a degenerate line) keeps the drawing for that entity.
        let _ = out.set_sketch(e, geometry);
    }
    out
}
