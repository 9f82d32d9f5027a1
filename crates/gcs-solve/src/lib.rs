//! Solving a constraint system at the user's values, and telling a redundant constraint that
//! agrees with the others (consistent) from one that contradicts them (conflicting) — the
//! survey's criterion (b), which needs the values — and a part that has no real solution at
//! all from a numerical failure.
//!
//! The solve follows a constructive plan ([`plan`], after the ESM paper §3–4): the points of
//! a plane sketch placed by two conditions on entities placed before them (two distances — a
//! Henneberg type I step —, a distance and a line, two lines, a fix: [`plan::Locus`]) are
//! peeled off; what remains, the core, is solved by damped Gauss–Newton
//! (Levenberg–Marquardt, [`gcs_rank::levenberg_marquardt`], sparse above a few hundred
//! unknowns) from the drawing, on the residuals of [`gcs_jacobian::Equations`] — the same
//! equations the analysis ranks, with the user's values for the dimensions; then the peeled
//! points are placed in closed form ([`closed`]: circle–circle and circle–line intersections,
//! two candidates; line–line, one), each choosing the candidate on the drawing's side (the
//! chirality of the sketch), ties (a drawing that shows no side) by least displacement. Small damped
//! steps from the drawing keep the core's shape: an under-constrained sketch moves as little
//! as it must, and the side of a tangency or the orientation of a triangle is the drawing's.
//!
//! With the analysis of the system ([`gcs_analysis::analyze`]), the fully redundant
//! constraints are left out of the solve (they add no condition a consistent system needs) and
//! then measured at the solution: within the tolerance they are consistent, beyond it they
//! conflict, with their spanning group (the constraints they conflict with). A step whose two
//! circles do not meet, or a rigid cluster of the analysis that the solver cannot satisfy on
//! its own from the drawing nor from two perturbed starts, has no real solution: it is
//! reported with its entities and constraints and left at its least-squares point, and the
//! rest is solved without it.
//!
//! The core is split along its DR-plan ([`nodes`]: a plane framework's rigid bodies,
//! recursively), each node a step of the plan. With [`SolveOptions::all`] (or a choice in the
//! core), every real candidate of each node is found by homotopy continuation ([`alternatives`],
//! [`homotopy`]) when its equations are polynomial and it has at most [`homotopy::MAX_PATHS`]
//! paths — a node with children placing their chosen realizations as rigid bodies — and the
//! core's realizations are every combination of them.
//!
//! Autosolve with backtracking (the ESM paper §3–4): when the solve from the drawing does not
//! hold (a closed-form step finds no point, a redundant constraint disagrees, an orientation
//! condition breaks) or turns a triangle of distances against the drawing, the closed-form
//! steps' sides are searched depth first (the drawing's side first, a placement abandoned as
//! soon as a triangle it completes turns or a redundant constraint it completes disagrees),
//! and then the combinations of the core nodes' candidates ([`nodes::Enumerator`]), each
//! node's ordered by how many wedges of its points turn against the drawing, then by
//! displacement, depth first — the first combination with which the whole solve holds and
//! every triangle keeps its turn is taken (else the first with which it holds). The search
//! is bounded ([`SEARCH_BOUND`] combinations, [`SEARCH_HOMOTOPIES`] homotopies of at most a
//! quarter of [`SolveOptions::max_paths`] paths each) and says when the bound cut it short
//! ([`Solution::bound_hit`], [`Solution::combinations`]).
//!
//! Not built yet: DR-plans of cores other than point-and-distance frameworks (they are one
//! node), closed forms for lines and circles, and a search from a core that the solver does not
//! satisfy from the drawing (its realizations are enumerated from a solved core only).
//!
//! A library: it never panics on input and never prints.

// Tolerance tests are written `!(x <= tolerance)` on purpose: a NaN residual fails them, where
// `x > tolerance` would let it pass.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod alternatives;
pub mod closed;
pub mod henneberg;
pub mod homotopy;
pub mod nodes;
pub mod plan;

use std::cell::RefCell;

use gcs_analysis::Analysis;
use gcs_jacobian::{Equations, Layout};
use gcs_model::{ConstraintIdx, EntityIdx, System};
use gcs_rank::{BigRational, Damping, LmOptions, Residuals, SparseRow, levenberg_marquardt};
use num_traits::ToPrimitive;

/// Steps without `|r|²` halving after which the Levenberg–Marquardt run straight from the
/// drawing gives up (and the homotopy takes over).
const STALL: usize = 20;

/// Above this many unknowns the Levenberg–Marquardt run straight from the drawing takes
/// geodesic acceleration ([`LmOptions::acceleration`]): on 1000-point Laman cores it halves
/// the steps (BENCHMARKS.md, "fifteenth session"); below, where a few steps suffice, the solve
/// is left as it was (the corpus' reports unchanged to the bit).
const ACCELERATE_ABOVE: usize = 400;

/// The fraction of the solve's tolerance ([`SolveOptions::tolerance`]) that the
/// Levenberg–Marquardt runs aim at on the system itself: the run straight from the drawing and
/// the homotopy's last step.
const FINAL_FRACTION: f64 = 1e-5;

/// The fraction of the solve's tolerance at which a step of the homotopy short of the system
/// counts as converged; a run straight from the drawing that stops within it, short of
/// [`FINAL_FRACTION`], has reached the rounding floor of its core and is taken (see
/// [`Problem::direct`]).
const STEP_FRACTION: f64 = 1e-3;

/// Options of [`solve`].
#[derive(Clone, Debug, PartialEq)]
pub struct SolveOptions {
    /// Relative tolerance: a residual counts as zero when it is at most this times the model's
    /// size (lengths), its square (the polynomial residuals of parameter-free constraints) or
    /// 180° (angles).
    pub tolerance: f64,
    /// The most Gauss–Newton steps.
    pub max_iterations: usize,
    /// Larger systems are not attempted.
    pub max_unknowns: usize,
    /// Whether to place the points given by two conditions in closed form ([`plan`]); without
    /// it, the whole system is solved numerically.
    pub constructive: bool,
    /// `Some(n)`: also enumerate the realizations the closed-form steps allow, at most `n`
    /// ([`Solution::solutions`]); `None`: only the one the drawing shows.
    pub all: Option<usize>,
    /// Choices fixed by the user: `(k, c)` places closed-form step `k` of [`Solution::plan`]
    /// (its index in that list) at its candidate `c`, whatever side the drawing shows; the other
    /// steps are chosen by the drawing, with backtracking. Enumeration keeps them too. Step 0,
    /// when it is the core, takes its realization `c` (among those the homotopy enumerates,
    /// the solve's own first: [`PlanStep::paths`]).
    pub choose: Vec<(usize, usize)>,
    /// With [`SolveOptions::all`] (or a choice of the core): the most homotopy paths the
    /// core's enumeration may track ([`alternatives`]; at most [`homotopy::MAX_PATHS`]); 0
    /// keeps the core as solved.
    pub max_paths: usize,
}

/// The default of [`SolveOptions::max_paths`]: about half a minute of paths on two cores.
pub const DEFAULT_PATHS: usize = 4096;

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            tolerance: 1e-9,
            max_iterations: 500,
            max_unknowns: 1_000_000,
            constructive: true,
            all: None,
            choose: Vec::new(),
            max_paths: DEFAULT_PATHS,
        }
    }
}

/// How the solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Every constraint holds at the solution.
    Solved,
    /// The constraints were solved without the redundant ones, and some of those do not hold
    /// there: they conflict; or a part has no real solution ([`Solution::no_solution`]). The
    /// rest is solved.
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
    /// The parts without a real solution, left at their least-squares point.
    pub no_solution: Vec<NoSolution>,
    /// The steps taken, in order.
    pub plan: Vec<PlanStep>,
    /// How many choices backtracking reversed: closed-form steps placed against the drawing's
    /// side, and nodes of the core's DR-plan taken off their candidate 0 (the drawing's).
    pub backtracked: usize,
    /// Whether backtracking stopped at its bound with a step still without a candidate, or
    /// the search over the closed-form steps' sides stopped at its budget of placements
    /// without one that holds, or the search over the core's combinations
    /// ([`Solution::combinations`]) stopped at
    /// [`SEARCH_BOUND`] (or at its budget of homotopies) before one held with the drawing's
    /// chirality.
    pub bound_hit: bool,
    /// How many combinations of the core nodes' candidates the autosolve's search tried (0:
    /// no search — the solve from the drawing held, every triangle of distances turning the
    /// drawing's way). The search runs when the solve does not end solved, or turns a
    /// triangle against the drawing, and the core's DR-plan is enumerated; it takes the first
    /// combination, each node's candidates in the order of their agreement with the
    /// drawing's chirality, with which the whole solve holds and every triangle keeps the
    /// drawing's turn (else the first with which it holds); the nodes it moved off their
    /// candidate 0 count in `backtracked`, and their `chosen` in [`Solution::plan`] says
    /// which.
    pub combinations: usize,
    /// With [`SolveOptions::all`]: the realizations found, each over the layout's columns like
    /// `x` — the core, and every entity no closed-form step places, as solved (the reference:
    /// realizations are counted up to moving the whole, mirror images distinct), then every combination of the closed-form steps' real
    /// candidates (the fixed choices kept) under which every consistent redundant constraint
    /// still holds within its allowance; in the order of the candidates, the first step
    /// outermost. `None` without it. The search visits at most 2^20 partial placements
    /// (`truncated` then).
    pub solutions: Option<Vec<Vec<f64>>>,
    /// With [`SolveOptions::all`]: for each realization of `solutions`, the candidate of each
    /// closed-form step, in the order of the closed-form steps of `plan` (the steps of method
    /// [`Method::ClosedForm`]); `None` without it.
    pub solution_choices: Option<Vec<Vec<usize>>>,
    /// Whether the enumeration stopped at [`SolveOptions::all`]'s limit (or at its budget of
    /// partial placements).
    pub truncated: bool,
    /// Every bound that cut a search of this solve short, in the order of [`Bound`] — the
    /// autosolve's (even when a later candidate then held: the one taken may not be the
    /// first in the search's order) and the enumeration's; empty when none did.
    pub bounds_hit: Vec<Bound>,
    /// With [`SolveOptions::all`]: for each realization of `solutions`, the core's candidate
    /// it is built on (its index among the core's real realizations; 0 where the core was not
    /// enumerated); `None` without it.
    pub core_choices: Option<Vec<usize>>,
    /// With [`SolveOptions::all`]: for each realization of `solutions`, the candidate of each
    /// node of the core's DR-plan (the first steps of `plan`, [`PlanStep::children`]), a
    /// node's candidate counted among those its children's choices give; `None` without it.
    pub node_choices: Option<Vec<Vec<usize>>>,
    /// The orientation conditions ([`System::orientations`], by index) that do not hold at the
    /// solution: no realization the plan reaches turns their way (status `Inconsistent`).
    /// Realizations of `solutions` keep every one.
    pub turned: Vec<usize>,
}

/// A part of the system that has no real solution (with the choices made for the rest).
#[derive(Clone, Debug, PartialEq)]
pub struct NoSolution {
    /// Its entities: the rigid cluster of the analysis it lies in (or, outside any, the
    /// entities of its constraints), in file order.
    pub entities: Vec<EntityIdx>,
    /// Its constraints, in file order.
    pub constraints: Vec<ConstraintIdx>,
}

/// How a step of the plan was solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Written down directly: the intersection of two circles.
    ClosedForm,
    /// Damped Gauss–Newton from the drawing.
    Newton,
}

impl Method {
    /// The report name: `closed-form`, `newton`.
    pub fn name(self) -> &'static str {
        match self {
            Method::ClosedForm => "closed-form",
            Method::Newton => "newton",
        }
    }
}

/// One step of the solve.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanStep {
    /// The entities the step places.
    pub entities: Vec<EntityIdx>,
    /// The constraints it satisfies.
    pub constraints: Vec<ConstraintIdx>,
    /// How.
    pub method: Method,
    /// The real candidates (a closed-form step: 2, 1 when tangent, 0 when there is none; a
    /// numerical step: 1, the one reached from the drawing).
    pub candidates: usize,
    /// The candidate kept (`None` when there was none): closed-form candidate 0 lies to the
    /// left of the directed line from the first anchor to the second, 1 to the right.
    pub chosen: Option<usize>,
    /// Whether `candidates` are all the real solutions of the step (given the steps before it):
    /// true for a closed-form step and for a core of one distance; false for a core solved
    /// numerically, where one solution is found from the drawing and others may exist.
    pub complete: bool,
    /// When not `complete`: why, and how much may be missing (each reason that applies; empty
    /// when `complete`).
    pub shortfall: Vec<alternatives::Shortfall>,
    /// Whether the user fixed the choice ([`SolveOptions::choose`]).
    pub fixed: bool,
    /// For the core with [`SolveOptions::all`]: its homotopy's paths and what they ended at
    /// ([`alternatives`]); `candidates` are then its real realizations, the one the solve
    /// reached from the drawing first, and `complete` says whether every path was decided.
    /// `None` where the core was not enumerated (see the [`alternatives`] module).
    pub paths: Option<alternatives::PathCounts>,
    /// For a node of the core's DR-plan ([`nodes`]) assembled from others: their steps, whose
    /// chosen realizations it places as rigid bodies (empty for every other step).
    pub children: Vec<usize>,
    /// The groups the user declared ([`System::groups`], by index) that this step is.
    pub groups: Vec<usize>,
}

/// Why a system was not solved.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SolveError {
    /// Too many unknowns for the dense solver.
    #[error("{unknowns} unknowns: more than the solver is allowed ({max})")]
    TooLarge {
        /// The unknowns.
        unknowns: usize,
        /// The limit.
        max: usize,
    },
    /// A fixed choice ([`SolveOptions::choose`]) that the plan does not offer.
    #[error("cannot choose candidate {candidate} of step {step}: {why}")]
    Choice {
        /// The step's index in the plan.
        step: usize,
        /// The candidate asked for.
        candidate: usize,
        /// Why not: the plan's steps and their candidates.
        why: String,
    },
}

/// The residuals the solver minimises: the constraints of one step, the metric ones against
/// their values, each scaled to be relative to the model's size, and the internal relations of
/// their entities (not the normalisations of homogeneous coordinates, which the steps leave
/// free); over the columns of those entities, the rest of the configuration held where it is.
struct Problem<'s> {
    system: &'s System,
    layout: &'s Layout,
    equations: &'s Equations<'s>,
    constraints: Vec<ConstraintIdx>,
    /// Entities whose internal relation is a residual.
    internal: Vec<EntityIdx>,
    /// The unknowns: columns of the layout.
    columns: Vec<usize>,
    /// Each layout column's place among the unknowns (`usize::MAX`: held).
    local: Vec<usize>,
    /// The whole configuration, the unknowns overwritten at each evaluation.
    full: RefCell<Vec<f64>>,
    scale: f64,
    /// The homotopy parameter (1: the system itself) and the residuals at its start.
    t: std::cell::Cell<f64>,
    offset: RefCell<Vec<f64>>,
}

/// What a residual of constraint `c` is measured against: the model's size for a length, 180°
/// for an angle, 1 for a ratio, the size squared for the polynomial residuals of
/// parameter-free constraints (to the power of their degree in lengths where it is not 2:
/// [`gcs_jacobian::residual_degree`]).
fn unit(system: &System, c: ConstraintIdx, scale: f64) -> f64 {
    let constraint = system.constraint(c);
    let kind = constraint.kind;
    if !kind.is_metric() {
        scale.powi(gcs_jacobian::residual_degree(constraint.signature))
    } else if kind == gcs_model::ConstraintKind::Angle {
        180.0
    } else if kind == gcs_model::ConstraintKind::LengthRatio {
        1.0
    } else {
        scale
    }
}

/// The residual of one constraint at the whole configuration `x`, relative (over its
/// [`unit`]), as its largest value. `None` for a metric constraint without a value.
pub(crate) fn relative(
    system: &System,
    equations: &Equations<'_>,
    c: ConstraintIdx,
    x: &[f64],
    scale: f64,
) -> Option<f64> {
    let r = equations.residual(c, x)?;
    let unit = unit(system, c, scale);
    Some(r.values.iter().fold(0.0f64, |m, v| m.max((v / unit).abs())))
}

impl<'s> Problem<'s> {
    /// The problem of `constraints` over the columns of their entities, at `x`.
    fn new(
        system: &'s System,
        layout: &'s Layout,
        equations: &'s Equations<'s>,
        constraints: Vec<ConstraintIdx>,
        x: &[f64],
        scale: f64,
    ) -> Self {
        let mut seen = vec![false; system.entities().len()];
        let mut entities = Vec::new();
        for &c in &constraints {
            for e in system.constraint_base_entities(c) {
                if !std::mem::replace(&mut seen[e.index()], true) {
                    entities.push(e);
                }
            }
        }
        entities.sort();
        let mut local = vec![usize::MAX; layout.ncols()];
        let mut columns = Vec::new();
        let mut internal = Vec::new();
        for &e in &entities {
            let Some(repr) = layout.repr(e) else { continue };
            for col in layout.columns(e) {
                local[col] = columns.len();
                columns.push(col);
            }
            if repr.internal_rows() > usize::from(repr.homogeneous()) {
                internal.push(e);
            }
        }
        Problem {
            system,
            layout,
            equations,
            constraints,
            internal,
            columns,
            local,
            full: RefCell::new(x.to_vec()),
            scale,
            t: std::cell::Cell::new(1.0),
            offset: RefCell::new(Vec::new()),
        }
    }

    /// The unknowns' values in `x`.
    fn gather(&self, x: &[f64]) -> Vec<f64> {
        self.columns.iter().map(|&c| x[c]).collect()
    }

    /// Writes the unknowns' values into `x`.
    fn scatter(&self, unknowns: &[f64], x: &mut [f64]) {
        for (&c, v) in self.columns.iter().zip(unknowns) {
            x[c] = *v;
        }
    }

    /// A row over the layout's columns, scaled and over the unknowns.
    fn localise(&self, row: &SparseRow<f64>, unit: f64) -> SparseRow<f64> {
        SparseRow::from_entries(
            row.entries()
                .iter()
                .filter(|(c, _)| self.local[*c] != usize::MAX)
                .map(|(c, v)| (self.local[*c], v / unit))
                .collect(),
        )
    }

    /// Damped Gauss–Newton from `x` (the whole configuration), updated in place, along the
    /// Newton homotopy `r(y) − (1 − t)·r(x)` from `t = 0` (the start, where it holds) to
    /// `t = 1` (the system): first in one step; where a step does not converge, in halved
    /// steps (down to 1/1024), each started from the last point reached. Following the path
    /// keeps the drawing's branch (the orientation of its triangles) where a direct solve
    /// from a rough drawing falls into another solution or a local minimum. The steps taken
    /// and whether it converged.
    fn run(&self, x: &mut [f64], options: &SolveOptions, first_step: f64) -> (usize, bool) {
        if self.columns.is_empty() {
            return (0, true);
        }
        *self.full.borrow_mut() = x.to_vec();
        let mut y = self.gather(x);
        self.t.set(1.0);
        if let Some(k) = self.direct(x, options) {
            return (k, true);
        }
        let offset = self.evaluate(&y).0;
        // A rough start (a residual beyond 1% of the model's size) takes `first_step` first.
        let rough = offset.iter().any(|v| !(v.abs() <= 1e-2));
        *self.offset.borrow_mut() = offset;
        let (mut t, mut dt, mut iterations) = (0.0f64, if rough { first_step } else { 1.0f64 }, 0);
        let converged = loop {
            let target = if t + dt >= 1.0 - 1e-12 { 1.0 } else { t + dt };
            let last = target == 1.0;
            self.t.set(target);
            let lm = LmOptions {
                tolerance: options.tolerance * if last { FINAL_FRACTION } else { STEP_FRACTION },
                max_iterations: if last && dt < 1.0 {
                    options.max_iterations
                } else {
                    options.max_iterations.min(60)
                },
                max_unknowns: usize::MAX,
                ..LmOptions::default()
            };
            let Some(outcome) = levenberg_marquardt(self, &y, &lm) else { break false };
            iterations += outcome.iterations;
            if outcome.converged {
                y = outcome.x;
                t = target;
                if last {
                    break true;
                }
                dt = (dt * 2.0).min(1.0);
            } else if dt > 1.0 / 1024.0 {
                dt /= 2.0;
            } else {
                if last {
                    y = outcome.x;
                }
                break false;
            }
        };
        self.t.set(1.0);
        self.scatter(&y, x);
        (iterations, converged)
    }

    /// Levenberg–Marquardt straight at the system from `x`, before any homotopy, with
    /// Nielsen's damping update and sparse steps ([`Damping::Nielsen`], stopped after
    /// [`STALL`] steps without `|r|²` halving): `Some(steps)` with `x` solved when it converges
    /// (within [`FINAL_FRACTION`] of the tolerance, or, where it stops short of that, within
    /// [`STEP_FRACTION`] of it) and turns no triangle of distances among the problem's points
    /// against their turn at `x`; `None` with `x` untouched otherwise (the homotopy then starts
    /// from `x`).
    ///
    /// A run that stops between the two has met the rounding floor of an ill-conditioned core
    /// (`|r|²` no longer halves: 1.5e-14 of the tolerance's unit on a 49-unknown core of the
    /// Onshape sample, 2.4e-13 on an 808-unknown one): the homotopy, aiming at the same floor,
    /// spent hundreds of steps to end at it again, or failed (BENCHMARKS.md, "nineteenth
    /// session").
    fn direct(&self, x: &mut [f64], options: &SolveOptions) -> Option<usize> {
        let y = self.gather(x);
        let outcome = levenberg_marquardt(
            self,
            &y,
            &LmOptions {
                tolerance: options.tolerance * FINAL_FRACTION,
                max_iterations: options.max_iterations,
                max_unknowns: usize::MAX,
                sparse_above: 0,
                damping: Damping::Nielsen { stall: STALL },
                acceleration: y.len() > ACCELERATE_ABOVE,
                ..LmOptions::default()
            },
        )?;
        let floor = outcome.max_residual <= options.tolerance * STEP_FRACTION
            && outcome.x.iter().all(|v| v.is_finite());
        if !outcome.converged && !floor {
            return None;
        }
        let mut solved = x.to_vec();
        self.scatter(&outcome.x, &mut solved);
        let triangles = self.triangles();
        if triangles_against(self.layout, &triangles, x, &solved) > 0 {
            return None;
        }
        x.copy_from_slice(&solved);
        Some(outcome.iterations)
    }

    /// The triangles of distances among the problem's constraints.
    fn triangles(&self) -> Vec<[EntityIdx; 3]> {
        triangles_of(self.system, self.constraints.iter().copied())
    }

    /// The largest relative residual of the constraints at `x`, with its constraint.
    fn worst(&self, x: &[f64]) -> Option<(f64, ConstraintIdx)> {
        let mut worst: Option<(f64, ConstraintIdx)> = None;
        for &c in &self.constraints {
            if let Some(m) = relative(self.system, self.equations, c, x, self.scale)
                && worst.is_none_or(|(w, _)| !(m <= w))
            {
                worst = Some((m, c));
            }
        }
        worst
    }
}

impl Residuals for Problem<'_> {
    fn unknowns(&self) -> usize {
        self.columns.len()
    }

    fn evaluate(&self, unknowns: &[f64]) -> (Vec<f64>, Vec<SparseRow<f64>>) {
        let mut full = self.full.borrow_mut();
        self.scatter(unknowns, &mut full);
        let mut values = Vec::new();
        let mut rows = Vec::new();
        for &c in &self.constraints {
            if let Some(r) = self.equations.residual(c, &full) {
                let unit = unit(self.system, c, self.scale);
                values.extend(r.values.iter().map(|v| v / unit));
                rows.extend(r.rows.iter().map(|row| self.localise(row, unit)));
            }
        }
        for &e in &self.internal {
            let (v, r) = self.equations.internal_residuals(e, &full);
            let unit = self.scale * self.scale;
            // The first internal row is the relation (the normalisation, if any, is last).
            if let (Some(value), Some(row)) = (v.first(), r.first()) {
                values.push(value / unit);
                rows.push(self.localise(row, unit));
            }
        }
        let _ = self.layout;
        let lag = 1.0 - self.t.get();
        if lag != 0.0 {
            for (v, o) in values.iter_mut().zip(self.offset.borrow().iter()) {
                *v -= lag * o;
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

/// The drawn position of a 2D point in `x`.
fn at(layout: &Layout, x: &[f64], p: EntityIdx) -> [f64; 2] {
    let c = layout.columns(p).start;
    [x.get(c).copied().unwrap_or(0.0), x.get(c + 1).copied().unwrap_or(0.0)]
}

/// The value of a dimension as a double.
fn value(system: &System, c: ConstraintIdx) -> f64 {
    system.constraint(c).value.as_ref().and_then(ToPrimitive::to_f64).unwrap_or(f64::NAN)
}

/// The part without a real solution of a closed-form step whose circles do not meet: its
/// point, its anchors and the constraints among the three (those that fix the anchors'
/// distance included).
fn triangle(system: &System, solved: &[ConstraintIdx], step: &plan::Step) -> NoSolution {
    let mut entities = step.anchors.clone();
    entities.push(step.point);
    entities.sort();
    let constraints = solved
        .iter()
        .copied()
        .filter(|&c| {
            let base = system.constraint_base_entities(c);
            !base.is_empty() && base.iter().all(|e| entities.contains(e))
        })
        .collect();
    NoSolution { entities, constraints }
}

/// The loci of a closed-form step's point at a configuration `y` (its anchors placed there):
/// the circles (centre, radius) and the lines `g·p = h` its constraints confine it to.
struct Loci {
    circles: Vec<([f64; 2], f64)>,
    lines: Vec<([f64; 2], f64)>,
}

impl Loci {
    fn at(
        step: &plan::Step,
        system: &System,
        equations: &Equations<'_>,
        layout: &Layout,
        y: &[f64],
    ) -> Self {
        let col = layout.columns(step.point).start;
        let p = [y[col], y[col + 1]];
        let (mut circles, mut lines) = (Vec::new(), Vec::new());
        for &(c, locus) in &step.constraints {
            match locus {
                plan::Locus::Circle => {
                    let Some([u, v]) = plan::distance_points(system, c) else { continue };
                    let other = if u == step.point { v } else { u };
                    circles.push((at(layout, y, other), value(system, c)));
                }
                plan::Locus::Affine { .. } => {
                    // The residual is affine in the point: its linearisation anywhere is it.
                    let Some(res) = equations.residual(c, y) else { continue };
                    for (row, v) in res.rows.iter().zip(&res.values) {
                        let mut g = [0.0; 2];
                        for &(k, a) in row.entries() {
                            if k == col || k == col + 1 {
                                g[k - col] += a;
                            }
                        }
                        lines.push((g, g[0] * p[0] + g[1] * p[1] - v));
                    }
                }
            }
        }
        Loci { circles, lines }
    }

    /// The real candidates, in the order of [`closed`], and where the point goes when there is
    /// none (the least-squares point of the two conditions, or where it is).
    fn candidates(&self, now: [f64; 2]) -> (Vec<[f64; 2]>, [f64; 2]) {
        match (self.circles.as_slice(), self.lines.as_slice()) {
            ([(a, ra), (b, rb)], []) => (
                closed::circle_circle(*a, *ra, *b, *rb, 1e-12).candidates(),
                closed::nearest_to_both(*a, *ra, *b, *rb),
            ),
            ([(a, r)], [(g, h)]) => {
                (closed::circle_line(*a, *r, *g, *h, 1e-12).candidates(), closed::foot(*a, *g, *h))
            }
            ([], [(g1, h1), (g2, h2)]) => {
                let p = closed::line_line(*g1, *h1, *g2, *h2, 1e-12);
                (p.into_iter().collect(), p.unwrap_or(now))
            }
            _ => (Vec::new(), now),
        }
    }

    /// The chirality of `p` with respect to the loci, positive on candidate 0's side, with the
    /// product of lengths that makes it a sine; `None` for a step with one candidate.
    fn side(&self, p: [f64; 2]) -> Option<(f64, f64)> {
        let norm = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).hypot(u[1] - v[1]);
        match (self.circles.as_slice(), self.lines.as_slice()) {
            ([(a, _), (b, _)], []) => {
                Some((closed::orientation(*a, *b, p), norm(*a, *b) * norm(*a, p)))
            }
            ([(a, _)], [(g, _)]) => {
                // Along the line's direction (−g₁, g₀), from the circle's centre.
                let along = -g[1] * (p[0] - a[0]) + g[0] * (p[1] - a[1]);
                Some((along, g[0].hypot(g[1]) * norm(*a, p)))
            }
            _ => None,
        }
    }
}

/// What the drawing shows of a closed-form step: where its point is drawn, and the point's
/// chirality with respect to the step's loci at the drawing ([`Loci::side`]).
struct Drawn {
    at: [f64; 2],
    chirality: Option<(f64, f64)>,
}

impl Drawn {
    fn of(
        step: &plan::Step,
        system: &System,
        equations: &Equations<'_>,
        layout: &Layout,
        x0: &[f64],
    ) -> Self {
        let at = at(layout, x0, step.point);
        Drawn { at, chirality: Loci::at(step, system, equations, layout, x0).side(at) }
    }
}

/// Places the point of a closed-form step: the real candidates, the one on the drawing's side
/// of the anchors (ties by least displacement from the drawing; `flip`: the other, for
/// backtracking; `forced`: the user's), unless it breaks an orientation condition the step
/// completes (`completes`) and the other does not; `None` when there is none.
#[allow(clippy::too_many_arguments)]
fn place(
    step: &plan::Step,
    layout: &Layout,
    system: &System,
    equations: &Equations<'_>,
    drawing: &Drawn,
    x: &[f64],
    (flip, forced): (bool, Option<usize>),
    completes: &[&gcs_model::Orientation],
) -> Placed {
    let now = Loci::at(step, system, equations, layout, x);
    let (candidates, fallback) = now.candidates(at(layout, x, step.point));
    let (drawn, chirality) = (drawing.at, drawing.chirality);
    let norm = |u: [f64; 2], v: [f64; 2]| ((u[0] - v[0]).powi(2) + (u[1] - v[1]).powi(2)).sqrt();
    let flat = chirality.is_none_or(|(side, n)| !(side.abs() > 1e-9 * n));
    let chosen = match candidates.len() {
        0 => None,
        1 => Some(0),
        _ if !flat => Some(if chirality.is_some_and(|(side, _)| side > 0.0) { 0 } else { 1 }),
        _ => Some(if norm(candidates[0], drawn) <= norm(candidates[1], drawn) { 0 } else { 1 }),
    };
    // Backtracking takes the other candidate; a fixed choice stands (none when the step has
    // fewer candidates than it names).
    let chosen = match forced {
        Some(k) => (k < candidates.len()).then_some(k),
        None if flip && candidates.len() == 2 => chosen.map(|k| 1 - k),
        None => chosen,
    };
    // The orientation conditions the step completes: the other candidate when this one turns
    // the wrong way, none when both do.
    let turns = |k: usize| {
        completes.is_empty() || {
            let mut y = x.to_vec();
            let col = layout.columns(step.point).start;
            (y[col], y[col + 1]) = (candidates[k][0], candidates[k][1]);
            completes.iter().all(|o| orientation_holds(layout, &y, o))
        }
    };
    let chosen = match (forced, chosen) {
        (None, Some(k)) if !turns(k) => (candidates.len() == 2 && turns(1 - k)).then(|| 1 - k),
        (_, c) => c,
    };
    Placed {
        at: chosen.map_or(fallback, |k| candidates[k]),
        candidates: candidates.len(),
        chosen,
        confidence: chirality.map_or(0.0, |(side, n)| if n > 0.0 { side.abs() / n } else { 0.0 }),
    }
}

/// The most closed-form choices backtracking may change before giving up.
const BACKTRACK_BOUND: usize = 32;

/// The most combinations of the core nodes' candidates the autosolve's search tries
/// ([`Solution::combinations`]).
pub const SEARCH_BOUND: usize = 256;

/// The most node homotopies the autosolve's search runs (each of at most a quarter of
/// [`SolveOptions::max_paths`] paths).
pub const SEARCH_HOMOTOPIES: usize = 64;

/// The most closed-form placements the autosolve's search over the closed-form steps' sides
/// visits for one realization of the core.
const PLACEMENT_BOUND: usize = 1 << 12;

/// A bound that cut a search of the solve short ([`Solution::bounds_hit`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Bound {
    /// Backtracking over the closed-form steps from the drawing reversed [`BACKTRACK_BOUND`]
    /// choices with a step still without a point.
    Reversals,
    /// The autosolve's depth-first search over the closed-form steps' sides placed
    /// [`PLACEMENT_BOUND`] points for one realization of the core.
    Placements,
    /// The autosolve's search over the core tried [`SEARCH_BOUND`] combinations of its
    /// nodes' candidates.
    Combinations,
    /// The autosolve's search over the core ran [`SEARCH_HOMOTOPIES`] node homotopies.
    SearchHomotopies,
    /// The enumeration of the core's DR-plan ran its budget of node homotopies
    /// ([`nodes::MAX_ASSEMBLIES`]).
    NodeHomotopies,
    /// The enumeration found [`SolveOptions::all`]'s limit of realizations.
    Solutions(usize),
    /// The enumeration over the closed-form steps visited [`ENUMERATION_BUDGET`] partial
    /// placements.
    EnumerationPlacements,
}

impl Bound {
    /// The report name: `reversals`, `placements`, `combinations`, `search-homotopies`,
    /// `node-homotopies`, `max-solutions`, `enumeration-placements`.
    pub fn name(self) -> &'static str {
        match self {
            Bound::Reversals => "reversals",
            Bound::Placements => "placements",
            Bound::Combinations => "combinations",
            Bound::SearchHomotopies => "search-homotopies",
            Bound::NodeHomotopies => "node-homotopies",
            Bound::Solutions(_) => "max-solutions",
            Bound::EnumerationPlacements => "enumeration-placements",
        }
    }

    /// The bound's value.
    pub fn limit(self) -> usize {
        match self {
            Bound::Reversals => BACKTRACK_BOUND,
            Bound::Placements => PLACEMENT_BOUND,
            Bound::Combinations => SEARCH_BOUND,
            Bound::SearchHomotopies => SEARCH_HOMOTOPIES,
            Bound::NodeHomotopies => nodes::MAX_ASSEMBLIES,
            Bound::Solutions(limit) => limit,
            Bound::EnumerationPlacements => ENUMERATION_BUDGET,
        }
    }
}

/// The most unknowns of a cluster that the solver, failing to satisfy it from the drawing and
/// from two other starts, reports as having no real solution.
const SMALL_CLUSTER: usize = 24;

/// Where a closed-form step put its point, and among how many candidates.
struct Placed {
    at: [f64; 2],
    candidates: usize,
    chosen: Option<usize>,
    /// How clearly the drawing shows the side: the sine of the drawn angle at the first
    /// anchor (0: in line).
    confidence: f64,
}

/// The core nodes' homotopies of earlier solves of one model, for the next solve of it
/// ([`solve_cached`]): what a navigator keeps between picks, so that choosing a node's
/// candidate solves again only the nodes whose children changed — its parent chain — instead
/// of every node. Kept while the solved core and its DR-plan are the same (the same model,
/// drawing and tolerance: the solve is deterministic); emptied otherwise.
#[derive(Debug, Default)]
pub struct NodeCache {
    /// The solved core, the nodes and the tolerance the homotopies were run at.
    at: Option<(Vec<u64>, Vec<nodes::Node>, u64)>,
    homotopies: std::cell::RefCell<nodes::Homotopies>,
}

impl NodeCache {
    /// The node homotopies kept.
    pub fn len(&self) -> usize {
        self.homotopies.borrow().len()
    }

    /// Whether none is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Keeps what it has if it was computed at `x` with `nodes` and `tolerance`; else empties.
    fn at(&mut self, x: &[f64], nodes: &[nodes::Node], tolerance: f64) {
        let at = (x.iter().map(|v| v.to_bits()).collect(), nodes.to_vec(), tolerance.to_bits());
        if self.at.as_ref() != Some(&at) {
            self.homotopies.get_mut().clear();
            self.at = Some(at);
        }
    }
}

/// Solves `system` at its values, from its drawing, leaving out the constraints `analysis`
/// finds fully redundant and measuring them at the solution: the core numerically, then the
/// points given by two conditions in closed form (see the crate documentation).
///
/// # Errors
/// [`SolveError::TooLarge`] beyond [`SolveOptions::max_unknowns`].
pub fn solve(
    system: &System,
    analysis: &Analysis,
    options: &SolveOptions,
) -> Result<Solution, SolveError> {
    solve_cached(system, analysis, options, &mut NodeCache::default())
}

/// [`solve`], reusing the core nodes' homotopies that `cache` keeps from earlier solves of the
/// same model and keeping this solve's there: the same solution, with only the nodes whose
/// children's choices are new solved again (a navigator's pick: the node's parent chain).
///
/// # Errors
/// As [`solve`].
pub fn solve_cached(
    system: &System,
    analysis: &Analysis,
    options: &SolveOptions,
    cache: &mut NodeCache,
) -> Result<Solution, SolveError> {
    let layout = Layout::new(system);
    if layout.ncols() > options.max_unknowns {
        return Err(SolveError::TooLarge { unknowns: layout.ncols(), max: options.max_unknowns });
    }
    let x0 = start(system, &layout, analysis);
    let scale = x0.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let fully: Vec<&gcs_analysis::Redundancy> =
        analysis.redundant.iter().filter(|r| r.rows == r.doc).collect();
    let left_out: std::collections::HashSet<ConstraintIdx> =
        fully.iter().map(|r| r.constraint).collect();
    let solved: Vec<ConstraintIdx> =
        system.constraint_indices().filter(|c| !left_out.contains(c)).collect();
    let equations = Equations::new(system, &layout).with_branches_at(&x0);
    let construction = if options.constructive {
        plan::construction(system, &solved)
    } else {
        plan::Construction { steps: Vec::new(), core: solved.clone() }
    };
    // Each orientation condition's depth: after which closed-form step its points are all
    // placed (0: the core's, or entities no step places).
    let orientations = system.orientations();
    let orientation_depth: Vec<usize> = {
        let placed: std::collections::HashMap<EntityIdx, usize> =
            construction.steps.iter().enumerate().map(|(k, s)| (s.point, k + 1)).collect();
        (orientations.iter())
            .map(|o| o.points.iter().filter_map(|p| placed.get(p).copied()).max().unwrap_or(0))
            .collect()
    };
    let mut x = x0.clone();
    let mut no_solution: Vec<NoSolution> = Vec::new();
    let mut excluded: std::collections::HashSet<ConstraintIdx> = Default::default();
    let mut plan = Vec::new();

    // The core, numerically from the drawing.
    let core = Problem::new(system, &layout, &equations, construction.core.clone(), &x0, scale);
    let mut iterations = core.run(&mut x, options, 1.0).0;
    if core.worst(&x).is_some_and(|w| !(w.0 <= options.tolerance)) {
        // Which rigid cluster cannot be satisfied on its own: from the drawing, and from two
        // starts perturbed by a third of the model's size.
        let in_core: std::collections::HashSet<ConstraintIdx> =
            construction.core.iter().copied().collect();
        let mut rng = gcs_model::rng::SplitMix64::new(0x5eed);
        for cluster in &analysis.clusters {
            let cs: Vec<ConstraintIdx> =
                cluster.constraints.iter().copied().filter(|c| in_core.contains(c)).collect();
            if cs.is_empty() {
                continue;
            }
            let part = Problem::new(system, &layout, &equations, cs.clone(), &x0, scale);
            // A large cluster the solver misses may still have a solution: not claimed.
            if part.columns.len() > SMALL_CLUSTER {
                continue;
            }
            let mut best: Option<(f64, Vec<f64>)> = None;
            let mut solvable = false;
            for attempt in 0..3 {
                let mut y = x0.clone();
                if attempt > 0 {
                    for &c in &part.columns {
                        y[c] += scale * (rng.unit_f64() - 0.5) * 0.66;
                    }
                }
                let (k, ok) = part.run(&mut y, options, 1.0);
                iterations += k;
                let w = part.worst(&y).map_or(0.0, |w| w.0);
                if ok || w <= options.tolerance {
                    solvable = true;
                    break;
                }
                if best.as_ref().is_none_or(|(b, _)| w < *b) {
                    best = Some((w, part.gather(&y)));
                }
            }
            if !solvable {
                if let Some((_, y)) = best {
                    part.scatter(&y, &mut x);
                }
                excluded.extend(cs.iter().copied());
                no_solution.push(NoSolution {
                    entities: cluster.entities.clone(),
                    constraints: cluster.constraints.clone(),
                });
            }
        }
        if !no_solution.is_empty() {
            let rest: Vec<ConstraintIdx> =
                construction.core.iter().copied().filter(|c| !excluded.contains(c)).collect();
            let again = Problem::new(system, &layout, &equations, rest, &x, scale);
            iterations += again.run(&mut x, options, 1.0).0;
        }
    }
    // The core's DR-plan: its nodes are the plan's first steps.
    let core_nodes = if construction.core.is_empty() {
        Vec::new()
    } else {
        nodes::plan(system, &construction.core)
    };
    let enumerable = no_solution.is_empty()
        && core.worst(&x).is_none_or(|w| w.0 <= options.tolerance)
        && options.max_paths > 0;
    for node in &core_nodes {
        let complete = node.single_distance(system);
        // Until the enumeration (if any) says otherwise: the drawing's solution only.
        let shortfall = match () {
            () if complete => Vec::new(),
            () if options.max_paths > 0 && !enumerable => vec![alternatives::Shortfall::Unsolved],
            () => vec![alternatives::Shortfall::NotSought],
        };
        plan.push(PlanStep {
            entities: node.entities.clone(),
            constraints: node.constraints.clone(),
            method: Method::Newton,
            candidates: 1,
            chosen: Some(0),
            complete,
            shortfall,
            fixed: false,
            paths: None,
            children: node.children.clone(),
            groups: node.groups.clone(),
        });
    }
    // With `all`, or when the user chooses among them: every real realization of a solved
    // core, node by node, by homotopy continuation; the fixed choices of its nodes.
    let mut node_forced: Vec<Option<usize>> = vec![None; core_nodes.len()];
    for &(step, candidate) in &options.choose {
        if let Some(f) = node_forced.get_mut(step) {
            *f = Some(candidate);
        }
    }
    let chosen_core = node_forced.iter().any(Option::is_some);
    // The core's realizations to build on, each with its node choices.
    let mut cores: Vec<(Vec<f64>, Vec<usize>)> = vec![(x.clone(), vec![0; core_nodes.len()])];
    let mut core_truncated = false;
    // The bounds that cut the enumeration short.
    let mut enumeration_cut: Vec<Bound> = Vec::new();
    // The orientation conditions on the core's points: when the solved core breaks one, its
    // realizations are searched for one that keeps them all.
    let core_entities: std::collections::HashSet<EntityIdx> =
        core_nodes.last().map(|n| n.entities.iter().copied().collect()).unwrap_or_default();
    let core_orientations: Vec<&gcs_model::Orientation> =
        (orientations.iter().zip(&orientation_depth))
            .filter(|(o, d)| **d == 0 && o.points.iter().all(|p| core_entities.contains(p)))
            .map(|(o, _)| o)
            .collect();
    let core_turned = core_orientations.iter().any(|o| !orientation_holds(&layout, &x, o));
    let mut backtracked = 0;
    // The core's DR-plan at the solved core, to enumerate its nodes' candidates.
    let solved_core = x.clone();
    cache.at(&solved_core, &core_nodes, options.tolerance);
    let cache: &NodeCache = cache;
    let enumerator = enumerable.then(|| {
        let mut enumerator = nodes::Enumerator::new(
            system,
            &layout,
            &equations,
            &core_nodes,
            &solved_core,
            scale,
            options.max_paths,
        );
        enumerator.orientations = core_orientations.clone();
        enumerator.tolerance = options.tolerance;
        enumerator.homotopies = Some(&cache.homotopies);
        enumerator
    });
    // Each node's candidates at the choices `picks`, and the chosen ones, into the plan.
    let record = |plan: &mut Vec<PlanStep>, found: Vec<nodes::Candidates>, picks: &[usize]| {
        for (step, candidates) in plan.iter_mut().zip(found) {
            step.candidates = candidates.list.len();
            step.complete = candidates.complete;
            step.shortfall = candidates.shortfall;
            step.paths = candidates.counts;
        }
        for ((step, forced), pick) in plan.iter_mut().zip(&node_forced).zip(picks) {
            step.chosen = Some(*pick);
            step.fixed = forced.is_some();
        }
    };
    if let Some(enumerator) =
        enumerator.as_ref().filter(|_| options.all.is_some() || chosen_core || core_turned)
    {
        let mut chosen = enumerator.choose(&node_forced);
        // No node choice of the user's: where the drawing's choices give no realization the
        // orientation conditions allow, the first combination that does (depth first: the
        // nodes' other candidates tried before giving up).
        if chosen.is_err() && !chosen_core {
            let (first, _) = enumerator.all(&node_forced, 1);
            if let Some((_, picks)) = first.first() {
                backtracked += picks.iter().filter(|k| **k != 0).count();
                chosen = enumerator.choose(&picks.iter().map(|k| Some(*k)).collect::<Vec<_>>());
            }
        }
        match chosen {
            Ok((at, found, picks)) => {
                record(&mut plan, found, &picks);
                x = at;
                cores = vec![(x.clone(), picks)];
            }
            // The user's choice is not offered: an error.
            Err((step, candidate, why)) if chosen_core => {
                return Err(SolveError::Choice { step, candidate, why });
            }
            // No realization keeps the orientation conditions: the core stays as solved, and
            // the report names the conditions it breaks.
            Err(_) => {}
        }
        if let Some(limit) = options.all {
            let (found, by) = enumerator.all(&node_forced, limit.max(1));
            if !found.is_empty() {
                cores = found;
            }
            core_truncated = !by.is_empty();
            enumeration_cut.extend(by);
        }
    } else if let Some((step, candidate)) =
        node_forced.iter().enumerate().find_map(|(k, f)| f.map(|c| (k, c)))
    {
        let why = if options.max_paths == 0 {
            "the core's realizations are not enumerated with --max-paths 0".to_owned()
        } else {
            "the core was not solved, so its realizations are not enumerated".to_owned()
        };
        return Err(SolveError::Choice { step, candidate, why });
    }
    // The fixed choices, by closed-form step.
    let offset = plan.len();
    let mut forced: Vec<Option<usize>> = vec![None; construction.steps.len()];
    for &(step, candidate) in options.choose.iter().filter(|c| c.0 >= core_nodes.len()) {
        let why = if step < offset || step >= offset + construction.steps.len() {
            Some(format!(
                "the plan has {} step{}, of which {} in closed form (steps {}–{})",
                offset + construction.steps.len(),
                if offset + construction.steps.len() == 1 { "" } else { "s" },
                construction.steps.len(),
                offset,
                (offset + construction.steps.len()).saturating_sub(1),
            ))
        } else if candidate > 1 {
            Some("a closed-form step has candidates 0 and 1".to_owned())
        } else {
            None
        };
        if let Some(why) = why {
            return Err(SolveError::Choice { step, candidate, why });
        }
        forced[step - offset] = Some(candidate);
    }

    // The points given by two conditions, in closed form, each on the drawing's side. When a
    // step finds no real candidate, the choice the drawing shows least clearly among the
    // steps it depends on is reversed and the steps placed again (bounded backtracking, the
    // ESM paper §4).
    let placed_by: std::collections::HashMap<EntityIdx, usize> =
        construction.steps.iter().enumerate().map(|(k, s)| (s.point, k)).collect();
    let mut core_x = x.clone();
    let drawings: Vec<Drawn> = construction
        .steps
        .iter()
        .map(|step| Drawn::of(step, system, &equations, &layout, &x0))
        .collect();
    // The orientation conditions each closed-form step completes.
    let mut completes: Vec<Vec<&gcs_model::Orientation>> =
        vec![Vec::new(); construction.steps.len()];
    for (o, &d) in orientations.iter().zip(&orientation_depth) {
        if d > 0 {
            completes[d - 1].push(o);
        }
    }
    // The bounds that cut a search short.
    let cut_by: RefCell<std::collections::BTreeSet<Bound>> = RefCell::default();
    // Step `k` placed at `x`, flipped or not.
    let place_step = |k: usize, x: &[f64], flip: bool| {
        let step = &construction.steps[k];
        place(step, &layout, system, &equations, &drawings[k], x, (flip, forced[k]), &completes[k])
    };
    // Every closed-form step placed after the core at `core`: the configuration, the steps
    // flipped, whether backtracking hit its bound, and whether every step found a point.
    let place_all = |core: &[f64]| {
        let mut x = core.to_vec();
        let mut flips = vec![false; construction.steps.len()];
        let mut reversed = 0;
        let (placed, bound_hit) = loop {
            x.copy_from_slice(core);
            let mut first_failure = None;
            let mut confidence = vec![f64::INFINITY; construction.steps.len()];
            for (k, step) in construction.steps.iter().enumerate() {
                let placed = place_step(k, &x, flips[k]);
                let col = layout.columns(step.point).start;
                (x[col], x[col + 1]) = (placed.at[0], placed.at[1]);
                if placed.candidates == 2 && forced[k].is_none() {
                    confidence[k] = placed.confidence;
                }
                if placed.chosen.is_none() && first_failure.is_none() {
                    first_failure = Some(k);
                }
            }
            let Some(failed) = first_failure else { break (true, false) };
            // The steps the failed one depends on.
            let mut ancestors = Vec::new();
            let mut stack: Vec<usize> = vec![failed];
            let mut seen = vec![false; construction.steps.len()];
            while let Some(k) = stack.pop() {
                for a in &construction.steps[k].anchors {
                    if let Some(&j) = placed_by.get(a)
                        && !std::mem::replace(&mut seen[j], true)
                    {
                        ancestors.push(j);
                        stack.push(j);
                    }
                }
            }
            let candidate = ancestors
                .into_iter()
                .filter(|&j| !flips[j] && confidence[j].is_finite())
                .min_by(|&i, &j| confidence[i].total_cmp(&confidence[j]));
            let Some(j) = candidate else { break (false, false) };
            if reversed == BACKTRACK_BOUND {
                cut_by.borrow_mut().insert(Bound::Reversals);
                break (false, true);
            }
            flips[j] = true;
            reversed += 1;
        };
        (x, flips, reversed, bound_hit, placed)
    };
    // Each fully redundant constraint measured at `x`.
    let check = |r: &gcs_analysis::Redundancy, x: &[f64]| {
        let c = r.constraint;
        let residual = equations.residual(c, x).map_or(0.0, |res| {
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
            + if system.constraint(c).kind.is_metric() { written } else { 2.0 * scale * written };
        Checked {
            constraint: c,
            residual,
            allowance,
            conflicting: residual.abs() > allowance,
            spanning_group: r.spanning_group.clone(),
        }
    };
    // Whether the whole solve holds at `x` (every step placed, every constraint solved within
    // the tolerance, every redundant one consistent, every orientation condition kept), and
    // how many triangles of distances turn against the drawing there.
    let triangles = distance_triangles(system);
    let holds = |x: &[f64], placed: bool| {
        placed
            && x.iter().all(|v| v.is_finite())
            && solved.iter().filter(|c| !excluded.contains(c)).all(|&c| {
                relative(system, &equations, c, x, scale).is_none_or(|m| m <= options.tolerance)
            })
            && fully.iter().all(|r| !check(r, x).conflicting)
            && orientations.iter().all(|o| orientation_holds(&layout, x, o))
    };
    let against = |x: &[f64]| triangles_against(&layout, &triangles, &x0, x);
    // After which closed-form step each triangle and each fully redundant constraint is
    // complete (0: by the core's).
    let depth_of = |entities: &[EntityIdx]| {
        entities.iter().filter_map(|p| placed_by.get(p)).map(|k| k + 1).max().unwrap_or(0)
    };
    let mut completed: Vec<(Vec<[EntityIdx; 3]>, Vec<&gcs_analysis::Redundancy>)> =
        vec![(Vec::new(), Vec::new()); construction.steps.len() + 1];
    for t in &triangles {
        completed[depth_of(t)].0.push(*t);
    }
    for r in &fully {
        completed[depth_of(&system.constraint_base_entities(r.constraint))].1.push(*r);
    }
    // The closed-form steps after the core at `core` such that the whole solve holds and
    // every triangle keeps the drawing's turn: the drawing's choices with their backtracking
    // first, else a depth-first search over the steps' candidates (the drawing's side first),
    // abandoning a placement as soon as a triangle it completes turns against the drawing or
    // a redundant constraint it completes disagrees, at most `PLACEMENT_BOUND` placements.
    // The configuration and the steps flipped against the drawing's side.
    let settle = |core: &[f64]| -> Option<(Vec<f64>, Vec<bool>)> {
        let (y, flips, _, _, placed) = place_all(core);
        if holds(&y, placed) && against(&y) == 0 {
            return Some((y, flips));
        }
        let steps = construction.steps.len();
        let mut y = core.to_vec();
        let mut flips = vec![false; steps];
        // Per depth, the next flip to try (0: the drawing's side, 1: the other, 2: done).
        let mut next = vec![0u8; steps];
        let mut depth = 0;
        let mut budget = PLACEMENT_BOUND;
        let fits = |y: &[f64], d: usize| {
            triangles_against(&layout, &completed[d].0, &x0, y) == 0
                && completed[d].1.iter().all(|r| !check(r, y).conflicting)
        };
        if !fits(&y, 0) {
            return None;
        }
        loop {
            if depth == steps {
                if holds(&y, true) && against(&y) == 0 {
                    return Some((y, flips));
                }
                if depth == 0 {
                    return None;
                }
                depth -= 1;
                continue;
            }
            if next[depth] == 2 || budget == 0 {
                if budget == 0 && next[..=depth].iter().any(|n| *n < 2) {
                    cut_by.borrow_mut().insert(Bound::Placements);
                }
                if depth == 0 || budget == 0 {
                    return None;
                }
                next[depth] = 0;
                depth -= 1;
                continue;
            }
            budget -= 1;
            let flip = next[depth] == 1;
            next[depth] += 1;
            if flip && forced[depth].is_some() {
                continue;
            }
            let placed = place_step(depth, &y, flip);
            if flip && placed.candidates < 2 {
                continue;
            }
            if placed.chosen.is_none() {
                next[depth] = 2;
                continue;
            }
            let col = layout.columns(construction.steps[depth].point).start;
            (y[col], y[col + 1]) = (placed.at[0], placed.at[1]);
            if fits(&y, depth + 1) {
                flips[depth] = flip;
                depth += 1;
            }
        }
    };
    let (mut combinations, mut search_cut) = (0, false);
    let (flips, reversed, bound_hit) = {
        let (y, mut flips, mut reversed, bound_hit, placed) = place_all(&core_x);
        let ok = holds(&y, placed);
        let settled = if ok && against(&y) == 0 { None } else { settle(&core_x) };
        if let Some((_, f)) = &settled {
            flips.clone_from(f);
            reversed = f.iter().filter(|f| **f).count();
        }
        let turned = settled.is_none() && against(&y) > 0;
        let ok = ok || settled.is_some();
        // The autosolve's search over the core (the ESM paper §3–4): when the solve from the
        // drawing does not hold, or turns a triangle against the drawing, the combinations of
        // the core nodes' candidates, each node's in the order of its chirality's agreement
        // with the drawing, depth first, for the first with which the whole solve holds and
        // every triangle turns the drawing's way (or else, if the drawing's own does not
        // hold, the first with which it holds), at most `SEARCH_BOUND` of them.
        let search = enumerator.as_ref().filter(|_| !ok || turned);
        let mut best: Option<(Vec<f64>, Vec<usize>, Vec<bool>)> = None;
        if let Some(enumerator) = search {
            let mut fallback: Option<(Vec<f64>, Vec<usize>, Vec<bool>)> = None;
            let bounds = (SEARCH_BOUND, options.max_paths / 4, SEARCH_HOMOTOPIES);
            let (tried, cut, by) =
                enumerator.search(&node_forced, &x0, bounds, &mut |core, picks| {
                    if let Some((_, flips)) = settle(core) {
                        best = Some((core.to_vec(), picks.clone(), flips));
                        return true;
                    }
                    let (y, flips, _, _, placed) = place_all(core);
                    if fallback.is_none() && !ok && holds(&y, placed) {
                        fallback = Some((core.to_vec(), picks.clone(), flips));
                    }
                    false
                });
            combinations = tried;
            search_cut = cut;
            cut_by.borrow_mut().extend(by);
            best = best.or(fallback);
        }
        match best.and_then(|(_, picks, flips)| {
            let picks: Vec<Option<usize>> = picks.into_iter().map(Some).collect();
            Some((enumerator.as_ref()?.choose(&picks).ok()?, flips))
        }) {
            Some(((at, found, picks), flips)) => {
                record(&mut plan, found, &picks);
                backtracked += picks.iter().filter(|k| **k != 0).count();
                core_x = at;
                x.copy_from_slice(&core_x);
                if options.all.is_none() {
                    cores = vec![(x.clone(), picks)];
                }
                let reversed = flips.iter().filter(|f| **f).count();
                (flips, reversed, false)
            }
            // (Nothing found: the placement budget, if it cut a search over the closed-form
            // steps' sides, left it short too.)
            None => (flips, reversed, bound_hit || cut_by.borrow().contains(&Bound::Placements)),
        }
    };
    let bound_hit = bound_hit || search_cut;
    backtracked += reversed;
    x.copy_from_slice(&core_x);

    // A point that has no real place taints the points placed from it: when they fail in
    // turn, they join its part.
    let mut tainted: std::collections::HashMap<EntityIdx, usize> = Default::default();
    for (k, step) in construction.steps.iter().enumerate() {
        let placed = place_step(k, &x, flips[k]);
        let col = layout.columns(step.point).start;
        (x[col], x[col + 1]) = (placed.at[0], placed.at[1]);
        if placed.chosen.is_none() {
            let from = step.anchors.iter().find_map(|a| tainted.get(a).copied());
            // The circles do not meet: no real solution when the anchors' distance is itself
            // a dimension (a triangle whose inequality fails) or comes from a part that has
            // none; otherwise the realization reached for the anchors may be the wrong one,
            // and the step is a failure of the solve, not a proof.
            let joined = step.two_distances().is_some()
                && solved.iter().any(|&c| {
                    let base = system.constraint_base_entities(c);
                    system.constraint(c).kind == gcs_model::ConstraintKind::Distance
                        && base.len() == 2
                        && step.anchors.iter().all(|a| base.contains(a))
                });
            let k = match from {
                Some(k) => {
                    let part = &mut no_solution[k];
                    part.entities.push(step.point);
                    part.entities.sort();
                    part.entities.dedup();
                    part.constraints.extend(step.constraint_ids());
                    part.constraints.sort();
                    Some(k)
                }
                None if joined => {
                    no_solution.push(triangle(system, &solved, step));
                    Some(no_solution.len() - 1)
                }
                None => None,
            };
            if let Some(k) = k {
                excluded.extend(step.constraint_ids());
                tainted.insert(step.point, k);
            }
        }
        plan.push(PlanStep {
            entities: vec![step.point],
            constraints: step.constraint_ids(),
            method: Method::ClosedForm,
            candidates: placed.candidates,
            chosen: placed.chosen,
            complete: true,
            shortfall: Vec::new(),
            fixed: forced[k].is_some(),
            paths: None,
            children: Vec::new(),
            groups: Vec::new(),
        });
    }

    // The worst constraint solved (those without a real solution aside).
    let mut worst: Option<(f64, ConstraintIdx)> = None;
    for &c in solved.iter().filter(|c| !excluded.contains(c)) {
        if let Some(m) = relative(system, &equations, c, &x, scale)
            && worst.is_none_or(|(w, _)| !(m <= w))
        {
            worst = Some((m, c));
        }
    }
    let max_residual = worst.map_or(0.0, |w| w.0);
    let converged = max_residual <= options.tolerance && x.iter().all(|v| v.is_finite());
    let redundant: Vec<Checked> = fully.iter().map(|r| check(r, &x)).collect();
    // The orientation conditions that do not hold at the solution.
    let turned: Vec<usize> = (orientations.iter().enumerate())
        .filter(|(_, o)| !orientation_holds(&layout, &x, o))
        .map(|(k, _)| k)
        .collect();
    let status = if !converged {
        Status::Failed
    } else if redundant.iter().any(|r| r.conflicting)
        || !no_solution.is_empty()
        || !turned.is_empty()
    {
        Status::Inconsistent
    } else {
        Status::Solved
    };
    let (solutions, solution_choices, truncated, core_choices, node_choices) = match options.all {
        Some(limit) => {
            // Each consistent redundant constraint is checked as soon as its entities are
            // placed: after the last step that places one of them (before any: depth 0).
            let depth_of: std::collections::HashMap<EntityIdx, usize> =
                construction.steps.iter().enumerate().map(|(k, s)| (s.point, k + 1)).collect();
            let mut checks: Vec<Vec<&Checked>> = vec![Vec::new(); construction.steps.len() + 1];
            for r in redundant.iter().filter(|r| !r.conflicting) {
                let base = system.constraint_base_entities(r.constraint);
                let depth = base.iter().filter_map(|e| depth_of.get(e)).max().copied().unwrap_or(0);
                checks[depth].push(r);
            }
            let holds = |depth: usize, y: &[f64]| {
                checks[depth].iter().all(|r| {
                    equations.residual(r.constraint, y).is_some_and(|res| {
                        res.values.iter().all(|v| v.abs() <= r.allowance.max(r.residual.abs()))
                    })
                }) && (orientations.iter().zip(&orientation_depth))
                    .all(|(o, d)| *d != depth || orientation_holds(&layout, y, o))
            };
            let mut found = Realizations {
                limit,
                solutions: Vec::new(),
                choices: Vec::new(),
                cut: None,
                budget: ENUMERATION_BUDGET,
            };
            let mut core_choices = Vec::new();
            let mut node_choices = Vec::new();
            for (core, choices) in &cores {
                // (A realization is the whole configuration at the core's solve, the core's
                // columns replaced.)
                let mut y = core.clone();
                found.search(
                    &construction.steps,
                    &mut y,
                    (system, &layout, &equations),
                    &forced,
                    &holds,
                );
                core_choices.resize(found.solutions.len(), choices.last().copied().unwrap_or(0));
                node_choices.resize(found.solutions.len(), choices.clone());
                if found.cut.is_some() {
                    break;
                }
            }
            enumeration_cut.extend(found.cut);
            (
                Some(found.solutions),
                Some(found.choices),
                found.cut.is_some() || core_truncated,
                Some(core_choices),
                Some(node_choices),
            )
        }
        None => (None, None, false, None, None),
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
    let mut bounds_hit: Vec<Bound> = cut_by.into_inner().into_iter().collect();
    bounds_hit.extend(enumeration_cut);
    bounds_hit.sort();
    bounds_hit.dedup();
    Ok(Solution {
        bounds_hit,
        status,
        worst: if converged { None } else { worst.map(|w| w.1) },
        max_residual,
        moved,
        redundant,
        iterations,
        scale,
        x,
        no_solution,
        plan,
        backtracked,
        bound_hit,
        combinations,
        solutions,
        solution_choices,
        truncated,
        core_choices,
        node_choices,
        turned,
    })
}

/// The most partial placements the enumeration of [`SolveOptions::all`] visits before it
/// stops (`truncated`): pruning by the redundant constraints can leave few realizations among
/// exponentially many combinations.
const ENUMERATION_BUDGET: usize = 1 << 20;

/// The enumeration of [`SolveOptions::all`]: the realizations found so far, the limit, and the
/// partial placements it may still visit.
struct Realizations {
    limit: usize,
    solutions: Vec<Vec<f64>>,
    /// Per realization, the candidate taken at each step.
    choices: Vec<Vec<usize>>,
    /// The bound that stopped it, if one did.
    cut: Option<Bound>,
    budget: usize,
}

impl Realizations {
    /// Places the steps in every way their real candidates allow (a fixed choice only its
    /// own), depth first, abandoning a placement as soon as `holds(depth, y)` fails — the
    /// redundant constraints completed by the steps before `depth` — and keeping each complete
    /// one. Iterative (a sketch may have thousands of steps).
    fn search(
        &mut self,
        steps: &[plan::Step],
        y: &mut [f64],
        (system, layout, equations): (&System, &Layout, &Equations<'_>),
        forced: &[Option<usize>],
        holds: &dyn Fn(usize, &[f64]) -> bool,
    ) {
        // Per depth: the candidates of its step at the placement above it, and the next to try.
        let mut stack: Vec<(Vec<[f64; 2]>, usize)> = Vec::new();
        let mut entering = true;
        loop {
            let k = stack.len();
            if entering {
                if self.budget == 0 {
                    self.cut = Some(Bound::EnumerationPlacements);
                    return;
                }
                self.budget -= 1;
                let candidates = if !holds(k, y) {
                    Vec::new()
                } else if let Some(step) = steps.get(k) {
                    let now = at(layout, y, step.point);
                    Loci::at(step, system, equations, layout, y).candidates(now).0
                } else {
                    if self.solutions.len() == self.limit {
                        self.cut = Some(Bound::Solutions(self.limit));
                        return;
                    }
                    self.solutions.push(y.to_vec());
                    // Each level's next candidate is one past the one taken.
                    self.choices.push(stack.iter().map(|(_, next)| next - 1).collect());
                    Vec::new()
                };
                stack.push((candidates, 0));
            }
            // The next candidate at the deepest level, or back up.
            let depth = stack.len().saturating_sub(1);
            let Some((candidates, next)) = stack.last_mut() else { return };
            let fixed = forced.get(depth).copied().flatten();
            let chosen = (*next..candidates.len()).find(|c| fixed.is_none_or(|f| f == *c));
            match chosen {
                Some(c) => {
                    *next = c + 1;
                    let p = candidates[c];
                    let col = layout.columns(steps[depth].point).start;
                    (y[col], y[col + 1]) = (p[0], p[1]);
                    entering = true;
                }
                None => {
                    stack.pop();
                    if stack.is_empty() {
                        return;
                    }
                    entering = false;
                }
            }
        }
    }
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
    solved_at(system, &solution.x)
}

/// [`solved_system`] at a configuration `x` over the layout's columns (a realization of
/// [`Solution::solutions`]).
pub fn solved_at(system: &System, x: &[f64]) -> System {
    let layout = Layout::new(system);
    let mut out = system.clone();
    for e in system.entity_indices() {
        let Some(repr) = layout.repr(e) else { continue };
        let coords: Option<Vec<BigRational>> =
            layout.columns(e).map(|c| x.get(c).copied().and_then(on_grid)).collect();
        let Some(coords) = coords else { continue };
        let geometry = repr.to_sketch(&coords, &system.entity(e).geometry);
        // A solution the model refuses (a degenerate line) keeps the drawing for that entity.
        let _ = out.set_sketch(e, geometry);
    }
    out
}

/// The largest residual of the constraints of `system` with a value (or parameter-free) at the
/// configuration `x` over the layout's columns, relative as [`Solution::max_residual`] is (to
/// `scale`, the model's size: [`Solution::scale`]) — to check a realization of
/// [`Solution::solutions`] against every constraint, the redundant ones included.
pub fn max_relative_residual(system: &System, x: &[f64], scale: f64) -> f64 {
    let layout = Layout::new(system);
    if x.len() != layout.ncols() {
        return f64::NAN;
    }
    let equations = Equations::new(system, &layout).with_branches_at(x);
    system
        .constraint_indices()
        .filter_map(|c| relative(system, &equations, c, x, scale))
        .fold(0.0, f64::max)
}

/// Whether an orientation condition holds at the configuration `x` (over the layout's
/// columns): the determinant of its points' differences (`(b − a, c − a)` in 2D,
/// `(b − a, c − a, d − a)` in 3D) has its sign — strictly, beyond 1e-12 of the product of the
/// differences' lengths (points in line, or in a plane, turn neither way).
pub fn orientation_holds(layout: &Layout, x: &[f64], o: &gcs_model::Orientation) -> bool {
    let point = |p: EntityIdx| -> Vec<f64> { layout.columns(p).map(|c| x[c]).collect() };
    let Some((first, rest)) = o.points.split_first() else { return false };
    let a = point(*first);
    let d: Vec<Vec<f64>> =
        rest.iter().map(|p| point(*p).iter().zip(&a).map(|(u, v)| u - v).collect()).collect();
    let length = |v: &Vec<f64>| v.iter().map(|c| c * c).sum::<f64>().sqrt();
    let (det, size) = match d.as_slice() {
        [u, v] if u.len() == 2 && v.len() == 2 => {
            (u[0] * v[1] - u[1] * v[0], length(u) * length(v))
        }
        [u, v, w] if u.len() == 3 && v.len() == 3 && w.len() == 3 => (
            u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]),
            length(u) * length(v) * length(w),
        ),
        _ => return false,
    };
    det * f64::from(o.sign) > 1e-12 * size
}

/// The two points of a plane `Distance` between points.
fn distance_points(system: &System, c: ConstraintIdx) -> Option<[EntityIdx; 2]> {
    let constraint = system.constraint(c);
    if system.dim() != gcs_model::Dim::Two || constraint.kind != gcs_model::ConstraintKind::Distance
    {
        return None;
    }
    let base = system.constraint_base_entities(c);
    let [p, q] = base.as_slice() else { return None };
    if [p, q].iter().any(|e| system.entity(**e).kind() != gcs_model::EntityKind::Point) {
        return None;
    }
    Some([*p, *q])
}

/// The triangles of a plane system's distances: three points joined pairwise by `Distance`s.
fn distance_triangles(system: &System) -> Vec<[EntityIdx; 3]> {
    if system.dim() != gcs_model::Dim::Two {
        return Vec::new();
    }
    triangles_of(system, system.constraint_indices())
}

/// The triangles of the `Distance`s among `constraints` (see [`distance_points`]).
fn triangles_of(
    system: &System,
    constraints: impl Iterator<Item = ConstraintIdx>,
) -> Vec<[EntityIdx; 3]> {
    let mut index: std::collections::HashMap<EntityIdx, usize> = Default::default();
    let mut points: Vec<EntityIdx> = Vec::new();
    let mut edges = Vec::new();
    for c in constraints {
        let Some([p, q]) = distance_points(system, c) else { continue };
        let mut id = |e: EntityIdx| {
            *index.entry(e).or_insert_with(|| {
                points.push(e);
                points.len() - 1
            })
        };
        edges.push((id(p), id(q)));
    }
    (gcs_model::generate::triangles(points.len(), &edges).iter())
        .map(|t| t.map(|i| points[i]))
        .collect()
}

/// How many of `triangles` turn at `x` against their turn in the drawing `x0` (flat at `x`
/// counts as against; a triangle drawn flat, its sine within 1e-6, counts for none).
fn triangles_against(
    layout: &Layout,
    triangles: &[[EntityIdx; 3]],
    x0: &[f64],
    x: &[f64],
) -> usize {
    let sine = |y: &[f64], [a, b, c]: [EntityIdx; 3]| {
        let (a, b, c) = (at(layout, y, a), at(layout, y, b), at(layout, y, c));
        let n = (b[0] - a[0]).hypot(b[1] - a[1]) * (c[0] - a[0]).hypot(c[1] - a[1]);
        if n > 0.0 { closed::orientation(a, b, c) / n } else { 0.0 }
    };
    (triangles.iter())
        .filter(|t| {
            let drawn = sine(x0, **t);
            drawn.abs() > 1e-6 && sine(x, **t) * drawn <= 0.0
        })
        .count()
}

/// The triangles of distances of a plane system (three points joined pairwise by
/// `Distance`s) whose orientation at `x` is the drawing's: `(kept, triangles)`.
pub fn orientation_kept(system: &System, x: &[f64]) -> (usize, usize) {
    let layout = Layout::new(system);
    let drawn: Vec<f64> = {
        let mut d = vec![0.0; layout.ncols()];
        for e in system.entity_indices() {
            if let Some(coords) = gcs_jacobian::sketch::sketch_coords_in::<f64>(system, e) {
                for (col, v) in layout.columns(e).zip(coords) {
                    d[col] = v;
                }
            }
        }
        d
    };
    let triangles = distance_triangles(system);
    let kept = triangles
        .iter()
        .filter(|&&[a, b, c]| {
            let turn = |y: &[f64]| {
                closed::orientation(at(&layout, y, a), at(&layout, y, b), at(&layout, y, c))
            };
            turn(&drawn) * turn(x) > 0.0
        })
        .count();
    (kept, triangles.len())
}
