//! Every real realization of the core (the part of a sketch no closed-form step places: in
//! space, all of it),
//! by homotopy continuation ([`crate::homotopy`]): the candidates of the DR-plan node that the
//! damped Newton solve reaches only one of.
//!
//! The core's equations are the analysis's own ([`Equations::polynomial`]: the polynomial
//! residuals of parameter-free constraints, the squared distance between two points minus the
//! value squared, a radius or coordinate difference minus its value, a distance to a line or
//! between parallel lines and a ratio of lengths cleared of their denominators; a dimension
//! without a value is no equation, as in the solve). An entity with homogeneous coordinates
//! (a line) gets a random complex affine chart on its normal, and its ends are brought back
//! to the layout's normalisation before they are compared. Realizations are counted
//! up to direct isometries, mirror images distinct (as the ESM paper and Capco et al. count):
//! a floating plane core is held by one of its point-to-point distances — its first point where
//! the solve put it, its second at the distance's value along the solved direction — and that
//! distance is left out of the equations; a floating core in space (points and distances) by a
//! triangle of them, its three points placed by their values where the solve put them
//! ([`hold_triangle`]: the six motions of space), its three distances left out. The counts
//! are then those of the literature: in the plane Capco et al.'s (K3,3: 16), in space those of
//! Emiris, Tsigaridas and Varvitsiotis (2009) and Bartzos, Emiris, Legerský and Tsigaridas
//! (2018), who hold a triangle too (the tetrahedron: 2, the octahedron: 16). A floating plane
//! node with no point-to-point distance is held by a point and a direction, or by a line
//! ([`hold_general`]), which the half-turn about a point keeps: each realization is found
//! with its half-turn, and one of the two is kept (the path counts, `finite`, count both).
//! Each unknown is
//! measured from its solved value in
//! units of the core's size, so that the solved realization is the origin and the others are
//! of order 1. Where the equations outnumber the unknowns (a constraint written with more
//! equations than it removes freedoms), the lowest-degree ones are folded into the others by
//! random combinations; every solution is checked against all of them afterwards.

use gcs_jacobian::{Equations, Layout};
use gcs_model::{ConstraintIdx, ConstraintKind, EntityIdx, System};
use gcs_rank::Complex64 as C;
use num_traits::ToPrimitive;

use crate::homotopy::{self, Target};

/// The most unknowns a core may have to be enumerated (beyond, its homotopy would be
/// hopeless anyway: at least 2^(n/2) paths for a framework).
const MAX_UNKNOWNS: usize = 64;

/// The paths of a node's homotopy and what they ended at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PathCounts {
    /// Paths tracked (the total degree of the node's equations).
    pub paths: usize,
    /// Distinct finite nonsingular complex solutions.
    pub finite: usize,
    /// Real ones among them (each a realization).
    pub real: usize,
    /// Paths that ended at a singular solution (the Cauchy endgame's).
    pub singular: usize,
    /// Paths that ended neither at a solution nor at infinity.
    pub failed: usize,
    /// Paths that met another path at a checkpoint `t < 1` (a jump detected) and were tracked
    /// again ([`homotopy::Ends::met`]); those still meeting are in `failed`.
    pub met: usize,
    /// Paths to infinity or to a singular end the endgame's cycles did not account for at
    /// first (a jump past the last checkpoint detected), then tracked again
    /// ([`homotopy::Ends::unaccounted`]); those still unaccounted for are in `failed`.
    pub unaccounted: usize,
}

/// Why a node's candidates may not be all its real solutions (a plan step with `complete`
/// false says which, and how much may be missing).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Shortfall {
    /// Solved from the drawing only, its other solutions not sought: no
    /// [`crate::SolveOptions::all`] nor choice in the core, or
    /// [`crate::SolveOptions::max_paths`] 0.
    NotSought,
    /// The core was not solved to the tolerance (or a part of it has no real solution), and
    /// realizations are enumerated from a solved core only.
    Unsolved,
    /// Not a node homotopy continuation is set up for here: why (a 3D node of other entities
    /// than points, entities with internal relations (3D lines), a dimension whose measure
    /// is not polynomial nor a quotient of polynomials (angles), a node neither held in place
    /// nor floating rigidly with something to hold it by, dimensions without a value, a
    /// flexible node, fewer equations than unknowns).
    Unsupported(&'static str),
    /// More unknowns than a node may have (`max`, [`MAX_UNKNOWNS`]).
    Unknowns {
        /// The node's unknowns.
        unknowns: usize,
        /// The most allowed.
        max: usize,
    },
    /// More homotopy paths than allowed (`max`: [`crate::SolveOptions::max_paths`], a
    /// quarter of it in the autosolve's search, at most [`homotopy::MAX_PATHS`]): none tracked.
    /// `paths` (the start system's count, saturating) bounds the complex solutions missed.
    Paths {
        /// The paths the node's homotopy has.
        paths: usize,
        /// The most allowed.
        max: usize,
    },
    /// The solve's budget of node homotopies (`homotopies` of them) was spent before this one.
    Budget {
        /// The budget.
        homotopies: usize,
    },
    /// Paths that ended neither at a solution nor at infinity: each may have been a solution
    /// (at most `failed` complex solutions missed).
    Failed {
        /// The undecided paths.
        failed: usize,
        /// The paths tracked.
        tracked: usize,
    },
    /// The solve's own realization was not among the paths' ends: added as candidate 0, so
    /// the paths missed at least one real solution.
    DrawingMissed,
}

impl Shortfall {
    /// The report name: `not-sought`, `core-unsolved`, `unsupported`, `too-many-unknowns`,
    /// `too-many-paths`, `homotopy-budget`, `paths-failed`, `drawing-missed`.
    pub fn name(&self) -> &'static str {
        match self {
            Shortfall::NotSought => "not-sought",
            Shortfall::Unsolved => "core-unsolved",
            Shortfall::Unsupported(_) => "unsupported",
            Shortfall::Unknowns { .. } => "too-many-unknowns",
            Shortfall::Paths { .. } => "too-many-paths",
            Shortfall::Budget { .. } => "homotopy-budget",
            Shortfall::Failed { .. } => "paths-failed",
            Shortfall::DrawingMissed => "drawing-missed",
        }
    }
}

/// The core's real realizations over the layout's columns (the rest of `x` kept), the one
/// nearest the solved `x` first, with the path counts; why not ([`Shortfall`]) when the core
/// is not one this can enumerate: a 3D core of other entities than points (or without a triangle
/// of distances to hold it by), entities with internal relations (3D lines), a dimension
/// whose measure is not polynomial nor a quotient of polynomials, a core that is neither held
/// in place nor floating rigidly (the motions that move it: [`motions`]) with something to
/// hold it by, more than 64 unknowns, or more paths than `max_paths` (or
/// [`homotopy::MAX_PATHS`]).
pub(crate) fn realizations(
    system: &System,
    layout: &Layout,
    equations: &Equations<'_>,
    core: &[ConstraintIdx],
    x: &[f64],
    (max_paths, tolerance): (usize, f64),
    seed: u64,
) -> Result<(PathCounts, Vec<Vec<f64>>), Shortfall> {
    use Shortfall::Unsupported;
    if max_paths == 0 {
        return Err(Shortfall::NotSought);
    }
    let space = system.dim() == gcs_model::Dim::Three;
    if core.is_empty() {
        return Err(Unsupported("a node without constraints"));
    }
    let mut entities: Vec<EntityIdx> =
        core.iter().flat_map(|&c| system.constraint_base_entities(c)).collect();
    entities.sort();
    entities.dedup();
    // A dimension without a value imposes nothing in the solve (the analysis counts it): it
    // is no equation here either.
    let imposed: Vec<ConstraintIdx> = (core.iter().copied())
        .filter(|&c| {
            let constraint = system.constraint(c);
            !(constraint.kind.is_metric() && constraint.value.is_none())
        })
        .collect();
    let valueless = imposed.len() < core.len();
    let mut dof = 0usize;
    let mut charted: Vec<EntityIdx> = Vec::new();
    for &e in &entities {
        if let Some(repr) = layout.repr(e) {
            if repr.internal_rows() > usize::from(repr.homogeneous()) {
                return Err(Unsupported("entities with internal relations (3D lines)"));
            }
            if repr.homogeneous() {
                charted.push(e);
            }
        }
        if space && system.entity(e).kind() != gcs_model::EntityKind::Point {
            return Err(Unsupported("a 3D node with entities other than points"));
        }
        dof += system.entity(e).kind().dof(system.dim());
    }
    let doc: usize = imposed.iter().map(|&c| system.constraint(c).doc).sum();
    // The motions that move the node: in the plane three, or two when no rotation acts that
    // a translation does not give (parallel lines, concentric circles); in space six.
    let rigid = if space { 6 } else { motions(system, layout, &entities, x) };
    // Held in place (nothing left), or floating as a rigid whole, held by a distance between
    // two of its points (in space, by a triangle of them), or else by a point and a
    // direction, or a line (`hold_general`).
    let floating = match dof.checked_sub(doc) {
        None => return Err(Unsupported("a node with more equations than freedoms")),
        Some(0) => false,
        Some(_) if valueless => {
            return Err(Unsupported(
                "a node with dimensions without a value (the solve imposes none of them: its \
                 realizations are not isolated)",
            ));
        }
        Some(d) if d > rigid => {
            return Err(Unsupported("a flexible node (its realizations are not isolated)"));
        }
        Some(d) if d < rigid => {
            return Err(Unsupported(
                "a node held in place in part, or flexible (its realizations are not isolated)",
            ));
        }
        Some(_) => true,
    };
    let distance = !floating || space || (rigid == 3 && !bars(system, core).is_empty());
    let gauge = if !floating {
        Gauge { base: x.to_vec(), held: Vec::new(), left_out: Vec::new(), ..Gauge::default() }
    } else if space {
        hold_triangle(system, layout, core, x)?
    } else if distance {
        hold_distance(system, layout, core, x)?
    } else {
        hold_general(layout, &entities, x, rigid)?
    };
    let mut unknowns: Vec<usize> = Vec::new();
    for &e in &entities {
        unknowns.extend(layout.columns(e).filter(|c| !gauge.held.contains(c)));
    }
    let n = unknowns.len();
    if n == 0 {
        return Err(Unsupported("a node without unknowns"));
    }
    if n > MAX_UNKNOWNS {
        return Err(Shortfall::Unknowns { unknowns: n, max: MAX_UNKNOWNS });
    }
    let base = gauge.base;
    let size = unknowns.iter().fold(0.0f64, |m, &c| m.max(base[c].abs())).max(1.0);
    // Points only, each an (x, y) pair: isotropic coordinates apply.
    let paired = entities.iter().filter(|&&e| !layout.columns(e).is_empty()).all(|&e| {
        layout.columns(e).len() == 2 && system.entity(e).kind() == gcs_model::EntityKind::Point
    }) && n.is_multiple_of(2);
    let equations_of: Vec<ConstraintIdx> =
        imposed.iter().copied().filter(|c| !gauge.left_out.contains(c)).collect();
    let slot_of = |col: usize| unknowns.iter().position(|&u| u == col);
    let mut extra: Vec<Extra> = Vec::new();
    // The gauge's linear conditions, on the columns' displacements from `base`.
    for condition in &gauge.linear {
        let terms: Vec<(usize, C)> = (condition.iter())
            .filter_map(|&(col, a)| Some((slot_of(col)?, C::new(a, 0.0))))
            .collect();
        extra.push(Extra::Linear(C::new(0.0, 0.0), terms));
    }
    // Homogeneous coordinates (a line's `a, b, c`, a plane's `a, b, c, d`) are defined up to
    // a factor: each such entity gets a random complex affine chart on its normal (all but
    // the last coordinate), `Σ wᵢ (nᵢ − baseᵢ) = 0`, which makes its realizations isolated
    // and leaves out of the chart the "line at infinity" `n = 0` — where a distance to a line
    // cleared of its denominator, `s² − v²|n|²`, holds whatever the rest, a component of
    // solutions that is no line — and only lines of one non-real direction besides; the
    // ends are brought back to the layout's own normalisation (`base · x = |base|²`, all the
    // coordinates) before they are compared ([`Param::renormalise`]).
    let mut rng = gcs_model::rng::SplitMix64::new(seed ^ 0xC4A7_0000);
    for &e in &charted {
        let columns: Vec<(usize, f64)> =
            (layout.columns(e)).filter_map(|col| Some((slot_of(col)?, base[col]))).collect();
        if columns.is_empty() {
            continue;
        }
        let normal = layout.columns(e).end - 1;
        let weights: Vec<(usize, C)> = (layout.columns(e))
            .filter(|&col| col < normal)
            .filter_map(&slot_of)
            .map(|j| (j, C::new(rng.unit_f64() - 0.5, rng.unit_f64() - 0.5)))
            .collect();
        extra.push(Extra::Chart(weights, columns));
    }
    let param = Param {
        n,
        base,
        map: unknowns.iter().enumerate().map(|(i, &c)| (c, vec![(i, size)])).collect(),
        extra,
        paired,
        size,
    };
    let (mut counts, found) = solve_param(
        (system, layout, equations),
        &equations_of,
        &imposed,
        &param,
        x,
        (max_paths, tolerance),
        seed,
    )?;
    // A gauge that holds a point and a direction (or a line) keeps each realization and its
    // half-turn about the held centre: one of each pair is kept, the one nearest the solve's.
    let mut kept: Vec<Vec<f64>> = Vec::new();
    for (_, y) in found {
        let twin = gauge.centre.map(|c| half_turn(layout, &entities, (&y, x), c));
        let seen = twin.is_some_and(|t| {
            kept.iter().any(|k| {
                (entities.iter().flat_map(|&e| layout.columns(e)))
                    .all(|col| (k[col] - t[col]).abs() <= 1e-7 * size)
            })
        });
        if !seen {
            kept.push(y);
        }
    }
    counts.real = kept.len();
    Ok((counts, kept))
}

/// How a floating node is held (the trivial motions modded out).
#[derive(Default)]
struct Gauge {
    /// The configuration to start from.
    base: Vec<f64>,
    /// The columns held (at `base`).
    held: Vec<usize>,
    /// The constraints that then hold by construction (left out of the equations).
    left_out: Vec<ConstraintIdx>,
    /// Linear conditions on the columns' displacements from `base`, `Σ a·(x − base) = 0`, as
    /// (column, a).
    linear: Vec<Vec<(usize, f64)>>,
    /// The centre of the half-turn that keeps the gauge (a point and a direction through it,
    /// or an undirected line, are kept by it): each realization is then found twice.
    centre: Option<[f64; 2]>,
}

/// The dimensioned point-to-point distances of `core` (a positive value), with their points.
fn bars(
    system: &System,
    core: &[ConstraintIdx],
) -> Vec<(ConstraintIdx, EntityIdx, EntityIdx, f64)> {
    (core.iter().copied())
        .filter_map(|c| {
            let constraint = system.constraint(c);
            let value = constraint.value.as_ref()?.to_f64().filter(|v| *v > 0.0)?;
            match constraint.signature.metric() {
                Some(gcs_model::Metric::DistancePointPoint(a, b))
                    if constraint.kind == ConstraintKind::Distance && a != b =>
                {
                    Some((c, a, b, value))
                }
                _ => None,
            }
        })
        .collect()
}

/// A plane node held by its first dimensioned point-to-point distance `a–b`: `a` where the
/// solve put it, `b` at the distance's value along the solved direction. What is left are its
/// realizations up to direct isometries, mirror images distinct (a rotation and a translation
/// of the plane map any placement of `a–b` to this one, and only the identity keeps it).
fn hold_distance(
    system: &System,
    layout: &Layout,
    core: &[ConstraintIdx],
    x: &[f64],
) -> Result<Gauge, Shortfall> {
    let Some(&(g, a, b, d)) = bars(system, core).first() else {
        return Err(Shortfall::Unsupported(
            "a floating node without a dimensioned point-to-point distance to hold it by",
        ));
    };
    let (ca, cb) = (layout.columns(a), layout.columns(b));
    let u = [x[cb.start] - x[ca.start], x[cb.start + 1] - x[ca.start + 1]];
    let len = u[0].hypot(u[1]);
    if !(len > 0.0) {
        return Err(Shortfall::Unsupported("a distance held by two coincident points"));
    }
    let mut base = x.to_vec();
    base[cb.start] = x[ca.start] + d * u[0] / len;
    base[cb.start + 1] = x[ca.start + 1] + d * u[1] / len;
    Ok(Gauge { base, held: ca.chain(cb).collect(), left_out: vec![g], ..Gauge::default() })
}

/// A node in space held by its first triangle of dimensioned point-to-point distances
/// `a–b`, `a–c`, `b–c` (in file order): `a` where the solve put it, `b` at the value of `a–b`
/// along the solved direction, `c` where the three values put it in the half-plane of the
/// solved `c` (the trivial motions of space are six: a proper rotation and a translation map
/// any placement of a triangle to this one, and only the identity keeps it, so what is left
/// are the realizations up to direct isometries, mirror images distinct — the mirror image
/// in the triangle's plane is another realization). Its three distances hold by
/// construction.
fn hold_triangle(
    system: &System,
    layout: &Layout,
    core: &[ConstraintIdx],
    x: &[f64],
) -> Result<Gauge, Shortfall> {
    let bars = bars(system, core);
    let length = |p: EntityIdx, q: EntityIdx| {
        bars.iter().find(|b| (b.1, b.2) == (p, q) || (b.1, b.2) == (q, p)).map(|b| (b.0, b.3))
    };
    let triangle = bars.iter().enumerate().find_map(|(i, &(ab, a, b, dab))| {
        bars[i + 1..].iter().find_map(|&(e, p, q, d)| {
            // A second bar from `a` or from `b` to an apex `c`, and the bar that closes the
            // triangle: as `a, b, c` with the lengths `a–b`, `a–c`, `b–c`.
            let (apex, at_a) = match () {
                () if p == a && q != b => (q, true),
                () if q == a && p != b => (p, true),
                () if p == b && q != a => (q, false),
                () if q == b && p != a => (p, false),
                () => return None,
            };
            if at_a {
                let (bc, dbc) = length(b, apex)?;
                Some((a, b, apex, dab, d, dbc, [ab, e, bc]))
            } else {
                let (ac, dac) = length(a, apex)?;
                Some((a, b, apex, dab, dac, d, [ab, ac, e]))
            }
        })
    });
    let Some((a, b, c, dab, dac, dbc, gauge)) = triangle else {
        return Err(Shortfall::Unsupported(
            "a floating 3D node without a triangle of dimensioned point-to-point distances to \
             hold it by",
        ));
    };
    let at = |p: EntityIdx| {
        let s = layout.columns(p).start;
        [x[s], x[s + 1], x[s + 2]]
    };
    let (pa, pb, pc) = (at(a), at(b), at(c));
    let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let dot = |p: [f64; 3], q: [f64; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    let u = sub(pb, pa);
    let len = dot(u, u).sqrt();
    if len.is_nan() || len <= 0.0 {
        return Err(Shortfall::Unsupported("a triangle held by two coincident points"));
    }
    let u = u.map(|v| v / len);
    let v = sub(pc, pa);
    let w = sub(v, u.map(|e| e * dot(v, u)));
    let wlen = dot(w, w).sqrt();
    // (The third point's offset from the line `a–b`, against rounding: a triangle drawn in
    // line gives no half-plane to hold it in.)
    if wlen.is_nan() || wlen <= 1e-9 * len {
        return Err(Shortfall::Unsupported("a triangle held in line"));
    }
    let w = w.map(|e| e / wlen);
    // c = a + α u + β w, from |c − a| = dac and |c − b| = dbc.
    let alpha = (dab * dab + dac * dac - dbc * dbc) / (2.0 * dab);
    let beta = (dac * dac - alpha * alpha).max(0.0).sqrt();
    let mut base = x.to_vec();
    let (ca, cb, cc) = (layout.columns(a), layout.columns(b), layout.columns(c));
    for k in 0..3 {
        base[cb.start + k] = pa[k] + dab * u[k];
        base[cc.start + k] = pa[k] + alpha * u[k] + beta * w[k];
    }
    Ok(Gauge {
        base,
        held: ca.chain(cb).chain(cc).collect(),
        left_out: gauge.to_vec(),
        ..Gauge::default()
    })
}

/// The number of independent displacements of the plane that move `entities` at `x` (the
/// rank of their velocities, in floating point — a count of motions for the homotopy's
/// gauge, which is floating point throughout, never a rank the analysis reports): 3 for a node
/// with two distinct points, 2 for parallel lines or concentric circles alone.
fn motions(system: &System, layout: &Layout, entities: &[EntityIdx], x: &[f64]) -> usize {
    let Ok(all) = gcs_jacobian::motions::generators(system, layout, x) else { return 0 };
    let k = all.len();
    let columns: Vec<usize> = entities.iter().flat_map(|&e| layout.columns(e)).collect();
    let mut rows: Vec<Vec<f64>> =
        all.iter().map(|g| columns.iter().map(|&c| g[c]).collect()).collect();
    // Gaussian elimination with partial pivoting, relative to the largest velocity.
    let largest = rows.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let width = rows.first().map_or(0, Vec::len);
    let mut rank = 0;
    for col in 0..width {
        let Some(p) = (rank..k).max_by(|&a, &b| rows[a][col].abs().total_cmp(&rows[b][col].abs()))
        else {
            break;
        };
        if !(rows[p][col].abs() > 1e-9 * largest) {
            continue;
        }
        rows.swap(rank, p);
        let pivot = rows[rank].clone();
        for row in &mut rows[rank + 1..] {
            let f = row[col] / pivot[col];
            for (v, p) in row[col..].iter_mut().zip(&pivot[col..]) {
                *v -= f * p;
            }
        }
        rank += 1;
    }
    rank
}

/// A floating plane node with no point-to-point distance to hold it by, held by what it has
/// (`motions`: the displacements that move it, [`motions`]):
/// - a point (a point, or a circle's centre) where the solve put it, and, when rotations move
///   the node, the direction from it to the node's farthest other point (that point kept on
///   the solved line through the first: one linear condition), or else the direction of a
///   line of the node (its normal kept parallel to the solved one);
/// - with no point, a line where the solve put it, and, when translations along it move the
///   node, a second line (not parallel to it) kept through the solved intersection.
///
/// A direction through a point is kept by the half-turn about the point, and a held line by
/// the half-turns about its points: each realization is then found twice, once turned
/// (`centre`), and one of each pair is kept — the counts stay those of realizations up to
/// direct isometries, mirror images distinct.
fn hold_general(
    layout: &Layout,
    entities: &[EntityIdx],
    x: &[f64],
    motions: usize,
) -> Result<Gauge, Shortfall> {
    let unsupported = Shortfall::Unsupported(
        "a floating node without a point and a direction, or lines, to hold it by",
    );
    let mut anchors: Vec<usize> = Vec::new();
    let mut lines: Vec<usize> = Vec::new();
    for &e in entities {
        let start = layout.columns(e).start;
        match layout.repr(e) {
            Some(gcs_jacobian::Repr::Point2 | gcs_jacobian::Repr::Circle) => anchors.push(start),
            Some(gcs_jacobian::Repr::Line2) => lines.push(start),
            _ => {}
        }
    }
    let at = |c: usize| [x[c], x[c + 1]];
    let size = x.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let mut gauge = Gauge { base: x.to_vec(), ..Gauge::default() };
    if let Some(&p) = anchors.first() {
        gauge.held.extend([p, p + 1]);
        if motions == 2 {
            return Ok(gauge);
        }
        let centre = at(p);
        let farthest = (anchors.iter().copied())
            .map(|q| (q, (at(q)[0] - centre[0]).hypot(at(q)[1] - centre[1])))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((q, d)) = farthest.filter(|f| f.1 > 1e-6 * size) {
            let u = [(x[q] - centre[0]) / d, (x[q + 1] - centre[1]) / d];
            gauge.linear.push(vec![(q, u[1]), (q + 1, -u[0])]);
        } else if let Some(&l) = lines.iter().find(|&&l| x[l].hypot(x[l + 1]) > 0.0) {
            gauge.linear.push(vec![(l, x[l + 1]), (l + 1, -x[l])]);
        } else {
            return Err(unsupported);
        }
        gauge.centre = Some(centre);
        return Ok(gauge);
    }
    let Some(&l) = lines.first() else { return Err(unsupported) };
    let (a, b, c) = (x[l], x[l + 1], x[l + 2]);
    let norm = a * a + b * b;
    if !(norm > 0.0) {
        return Err(unsupported);
    }
    gauge.held.extend([l, l + 1, l + 2]);
    if motions == 2 {
        gauge.centre = Some([-c * a / norm, -c * b / norm]);
        return Ok(gauge);
    }
    let second = lines.iter().copied().find(|&m| {
        let cross = a * x[m + 1] - b * x[m];
        cross.abs() > 1e-9 * norm.sqrt() * x[m].hypot(x[m + 1])
    });
    let Some(m) = second else { return Err(unsupported) };
    let (a2, b2, c2) = (x[m], x[m + 1], x[m + 2]);
    let det = a * b2 - b * a2;
    let meet = [(b * c2 - b2 * c) / det, (c * a2 - c2 * a) / det];
    gauge.linear.push(vec![(m, meet[0]), (m + 1, meet[1]), (m + 2, 1.0)]);
    gauge.centre = Some(meet);
    Ok(gauge)
}

/// The configuration `y` with `entities` turned by a half-turn about `centre` (a point and a
/// circle's centre to `2·centre − p`, a line `(a, b, c)` to `(−a, −b, c + 2(a, b)·centre)`,
/// brought back to the layout's normalisation at the solved `x`, `x · y = |x|²`).
fn half_turn(
    layout: &Layout,
    entities: &[EntityIdx],
    (y, x): (&[f64], &[f64]),
    centre: [f64; 2],
) -> Vec<f64> {
    let mut t = y.to_vec();
    for &e in entities {
        let s = layout.columns(e).start;
        match layout.repr(e) {
            Some(gcs_jacobian::Repr::Point2 | gcs_jacobian::Repr::Circle) => {
                t[s] = 2.0 * centre[0] - y[s];
                t[s + 1] = 2.0 * centre[1] - y[s + 1];
            }
            Some(gcs_jacobian::Repr::Line2) => {
                let turned =
                    [-y[s], -y[s + 1], y[s + 2] + 2.0 * (y[s] * centre[0] + y[s + 1] * centre[1])];
                let dot: f64 = (0..3).map(|k| turned[k] * x[s + k]).sum();
                let norm: f64 = (0..3).map(|k| x[s + k] * x[s + k]).sum();
                // (A line whose turned coordinates are orthogonal to its own keeps them.)
                let factor = if dot.abs() > 1e-12 * norm { norm / dot } else { 1.0 };
                for k in 0..3 {
                    t[s + k] = factor * turned[k];
                }
            }
            _ => {}
        }
    }
    t
}

/// Every real placement of rigid bodies and free points that satisfies `constraints` (each as
/// its unknowns: [`place`] gives its positions): a node
/// of the core's DR-plan ([`crate::nodes`]), its children as rigid bodies at the
/// configurations given (`bodies`: each child's points and a configuration they are placed in),
/// the points on no child free (`free`), the node's own constraints between them. The first
/// body is held where it is (the reference: realizations up to direct isometries); each other
/// body moves by a rotation and a translation (four unknowns, `cos² + sin² = 1`), never a
/// reflection (its mirror image is a realization of the child, chosen there); a point two
/// bodies share is where the first of them puts it, and the others must agree (two linear
/// equations). Whole configurations, `x` outside the node, nearest to `x` first.
#[allow(clippy::too_many_arguments)]
pub(crate) fn assemble(
    (system, layout, equations): (&System, &Layout, &Equations<'_>),
    bodies: &[(Vec<EntityIdx>, &[f64])],
    free: &[EntityIdx],
    constraints: &[ConstraintIdx],
    x: &[f64],
    (max_paths, tolerance): (usize, f64),
    seed: u64,
) -> Result<(PathCounts, Vec<Vec<f64>>), Shortfall> {
    if max_paths == 0 {
        return Err(Shortfall::NotSought);
    }
    let param = placement(layout, bodies, free, x)
        .ok_or(Shortfall::Unsupported("a node whose bodies are not of points"))?;
    let (counts, found) = solve_param(
        (system, layout, equations),
        constraints,
        constraints,
        &param,
        x,
        (max_paths, tolerance),
        seed,
    )?;
    Ok((counts, found.into_iter().map(|f| f.0).collect()))
}

/// The configuration of a placement [`assemble`] found (its unknowns `y`: per body after the
/// first its rotation's cosine and sine and its translation, per free point its coordinates,
/// in units of the node's size), the children at `bodies` and `x` elsewhere: positions
/// computed on demand from the constant-size record of each child.
pub(crate) fn place(
    layout: &Layout,
    bodies: &[(Vec<EntityIdx>, &[f64])],
    free: &[EntityIdx],
    x: &[f64],
    y: &[f64],
) -> Option<Vec<f64>> {
    let param = placement(layout, bodies, free, x)?;
    if y.len() != param.n {
        return None;
    }
    let mut config = param.base.clone();
    for (col, terms) in &param.map {
        config[*col] = param.base[*col] + terms.iter().map(|(j, w)| y[*j] * w).sum::<f64>();
    }
    Some(config)
}

/// The unknowns of the placement where every child stays where it is (the identity rotation
/// and no translation; free points where `x` has them).
pub(crate) fn identity_placement(bodies: usize, free: usize) -> Vec<f64> {
    let mut y = Vec::with_capacity(4 * bodies.saturating_sub(1) + 2 * free);
    for _ in 1..bodies {
        y.extend([1.0, 0.0, 0.0, 0.0]);
    }
    y.resize(y.len() + 2 * free, 0.0);
    y
}

/// The parametrisation of [`assemble`].
fn placement(
    layout: &Layout,
    bodies: &[(Vec<EntityIdx>, &[f64])],
    free: &[EntityIdx],
    x: &[f64],
) -> Option<Param> {
    let (reference, moving) = bodies.split_first()?;
    let xy = |config: &[f64], p: EntityIdx| -> Option<[f64; 2]> {
        let cols = layout.columns(p);
        (cols.len() == 2).then(|| [config[cols.start], config[cols.start + 1]])
    };
    let mut base = x.to_vec();
    let mut size = 1.0f64;
    for (points, config) in bodies {
        for &p in points {
            let [a, b] = xy(config, p)?;
            size = size.max(a.abs()).max(b.abs());
        }
    }
    for &p in free {
        let [a, b] = xy(x, p)?;
        size = size.max(a.abs()).max(b.abs());
    }
    // Where each point is, as an affine function of the unknowns: a constant and terms, for
    // x and for y.
    type Affine = ([f64; 2], [Vec<(usize, f64)>; 2]);
    let mut owner: std::collections::HashMap<EntityIdx, Affine> = Default::default();
    for &p in &reference.0 {
        let at = xy(reference.1, p)?;
        let cols = layout.columns(p);
        (base[cols.start], base[cols.start + 1]) = (at[0], at[1]);
        owner.entry(p).or_insert((at, [Vec::new(), Vec::new()]));
    }
    let mut map: Vec<(usize, Vec<(usize, f64)>)> = Vec::new();
    let mut extra: Vec<Extra> = Vec::new();
    let mut n = 0;
    // A point placed twice: its two affine forms agree, as u = x + iy and v = x − iy.
    let agree = |first: &Affine, second: &Affine, extra: &mut Vec<Extra>| {
        for sign in [1.0, -1.0] {
            let i = C::new(0.0, sign);
            let constant =
                (C::new(first.0[0] - second.0[0], 0.0) + i * (first.0[1] - second.0[1])) / size;
            let mut terms: Vec<(usize, C)> = Vec::new();
            for (form, w) in [(first, 1.0), (second, -1.0)] {
                terms.extend(form.1[0].iter().map(|(j, c)| (*j, C::new(w * c / size, 0.0))));
                terms.extend(form.1[1].iter().map(|(j, c)| (*j, i * (w * c / size))));
            }
            extra.push(Extra::Linear(constant, terms));
        }
    };
    for (points, config) in moving {
        let (c, s, tx, ty) = (n, n + 1, n + 2, n + 3);
        n += 4;
        extra.push(Extra::Rotation(c, s));
        let mut centre = [0.0, 0.0];
        for &p in points {
            let at = xy(config, p)?;
            centre[0] += at[0] / points.len() as f64;
            centre[1] += at[1] / points.len() as f64;
        }
        for &p in points {
            let at = xy(config, p)?;
            let (px, py) = (at[0] - centre[0], at[1] - centre[1]);
            let form: Affine =
                (centre, [vec![(c, px), (s, -py), (tx, size)], vec![(c, py), (s, px), (ty, size)]]);
            match owner.get(&p) {
                Some(first) => agree(first, &form, &mut extra),
                None => {
                    let cols = layout.columns(p);
                    (base[cols.start], base[cols.start + 1]) = (centre[0], centre[1]);
                    map.push((cols.start, form.1[0].clone()));
                    map.push((cols.start + 1, form.1[1].clone()));
                    owner.insert(p, form);
                }
            }
        }
    }
    for &p in free {
        if owner.contains_key(&p) {
            continue;
        }
        let cols = layout.columns(p);
        map.push((cols.start, vec![(n, size)]));
        map.push((cols.start + 1, vec![(n + 1, size)]));
        owner.insert(p, ([x[cols.start], x[cols.start + 1]], [Vec::new(), Vec::new()]));
        n += 2;
    }
    Some(Param { n, base, map, extra, paired: true, size })
}

/// An affine parametrisation of part of a configuration by `n` unknowns `y`: layout column
/// `col` of `map` is `base[col] + Σ coefficient·y_j`, every other column stays at `base`. With
/// `paired`, unknowns `2q` and `2q + 1` are the two coordinates of a point, of a translation or
/// the cosine and sine of a rotation — pairs whose isotropic coordinates `a ± ib` make
/// distances bilinear. `extra` are equations of the parametrisation itself. Unknowns are in
/// units of `size`.
struct Param {
    n: usize,
    base: Vec<f64>,
    map: Vec<(usize, Vec<(usize, f64)>)>,
    extra: Vec<Extra>,
    paired: bool,
    size: f64,
}

/// An equation of a parametrisation.
enum Extra {
    /// `y_a² + y_b² − 1 = 0`: the cosine and sine of a rotation.
    Rotation(usize, usize),
    /// `constant + Σ coefficient·y_j = 0`, in units of the size: one of the two isotropic
    /// coordinates of a point two rigid bodies share, the same from both.
    Linear(C, Vec<(usize, C)>),
    /// The chart of an entity with homogeneous coordinates (unknowns `j`, at `base_j`):
    /// `Σ w_j y_j = 0` over its normal with random complex `w` in the homotopy (its solutions
    /// then isolated); on the real equations, the layout's own normalisation,
    /// `Σ base_j y_j / |base| = 0` (`base · x = |base|²`), which the ends are brought to
    /// ([`Param::renormalise`]).
    Chart(Vec<(usize, C)>, Vec<(usize, f64)>),
}

impl Extra {
    fn degree(&self) -> u32 {
        match self {
            Extra::Rotation(..) => 2,
            Extra::Linear(..) | Extra::Chart(..) => 1,
        }
    }

    /// Its value and gradient at a real `y`, as the real equations have it (a chart: the
    /// layout's normalisation); `None` for the complex linear conditions, whose real and
    /// imaginary parts are two equations.
    fn eval_real(&self, y: &[f64], gradient: &mut [f64]) -> Option<f64> {
        match self {
            Extra::Rotation(a, b) => {
                gradient[*a] += 2.0 * y[*a];
                gradient[*b] += 2.0 * y[*b];
                Some(y[*a] * y[*a] + y[*b] * y[*b] - 1.0)
            }
            Extra::Linear(..) => None,
            Extra::Chart(_, base) => {
                let norm =
                    base.iter().map(|(_, b)| b * b).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
                let mut v = 0.0;
                for (j, b) in base {
                    gradient[*j] += b / norm;
                    v += b / norm * y[*j];
                }
                Some(v)
            }
        }
    }

    /// Its value and gradient at `y`.
    fn eval(&self, y: &[C], gradient: &mut [C]) -> C {
        match self {
            Extra::Rotation(a, b) => {
                gradient[*a] += y[*a] * 2.0;
                gradient[*b] += y[*b] * 2.0;
                y[*a] * y[*a] + y[*b] * y[*b] - 1.0
            }
            Extra::Linear(constant, terms) => {
                let mut v = *constant;
                for (j, w) in terms {
                    gradient[*j] += w;
                    v += w * y[*j];
                }
                v
            }
            Extra::Chart(terms, _) => {
                let mut v = C::new(0.0, 0.0);
                for (j, w) in terms {
                    gradient[*j] += w;
                    v += w * y[*j];
                }
                v
            }
        }
    }
}

impl Param {
    /// A complex end `y` with each homogeneous entity's coordinates `base + size·y` rescaled
    /// by the complex factor that puts them on the layout's normalisation,
    /// `base · x = |base|²` (a real solution is then real); `None` when they are orthogonal
    /// to `base` (no such factor).
    fn renormalise(&self, y: &[C]) -> Option<Vec<C>> {
        let mut out = y.to_vec();
        for e in &self.extra {
            let Extra::Chart(_, base) = e else { continue };
            let norm: f64 = base.iter().map(|(_, b)| b * b).sum();
            let coordinate = |j: usize, b: f64| C::new(b, 0.0) + y[j] * self.size;
            let dot: C = base.iter().map(|&(j, b)| coordinate(j, b) * b).sum();
            let length: f64 = base.iter().map(|&(j, b)| coordinate(j, b).norm_sqr()).sum();
            if !(dot.norm() > 1e-9 * (norm * length).sqrt()) {
                return None;
            }
            let factor = C::new(norm, 0.0) / dot;
            for &(j, b) in base {
                out[j] = (coordinate(j, b) * factor - b) / self.size;
            }
        }
        Some(out)
    }
}

/// A row of a node's square system: row `k` of a constraint, or an equation of the
/// parametrisation.
#[derive(Clone, Copy)]
enum Row {
    Constraint(ConstraintIdx, usize),
    Extra(usize),
}

/// A real solution of a node: its unknowns, and the whole configuration they give.
type RealEnd = (Vec<f64>, Vec<f64>);

/// A square complex system: its values and its Jacobian (row-major) at a point.
type Residuals<'a> = dyn Fn(&[C]) -> (Vec<C>, Vec<C>) + 'a;

/// Every real solution of `constraints` (and of the parametrisation's own equations) over
/// `param`, as its unknowns and as a whole configuration (`x` outside the parametrised
/// columns), nearest to `x` first.
///
/// The homotopy's ends are complex. An end whose imaginary parts are within 1e-7 of its size
/// (the complex Newton that ends a path stops at steps of 1e-12 of it: a non-real solution
/// that close to the real space would be a near-double real root) is a candidate: its real
/// parts are refined by Gauss–Newton in real arithmetic on the real equations themselves —
/// every row of `constraints` and of the parametrisation, not the random combinations the
/// square complex system folds them into ([`polish`]) — and it is a real solution when then
/// every constraint of `check` holds within `tolerance`, measured as the solve measures it
/// ([`crate::relative`]: lengths over the node's size, the polynomial residuals of
/// parameter-free constraints over its square, angles over 180°), and the parametrisation's
/// equations within `tolerance`. Two candidates refined to the same point are one.
fn solve_param(
    (system, layout, equations): (&System, &Layout, &Equations<'_>),
    constraints: &[ConstraintIdx],
    check: &[ConstraintIdx],
    param: &Param,
    x: &[f64],
    (max_paths, tolerance): (usize, f64),
    seed: u64,
) -> Result<(PathCounts, Vec<RealEnd>), Shortfall> {
    let n = param.n;
    let size = param.size;
    if n == 0 {
        return Err(Shortfall::Unsupported("a node without unknowns"));
    }
    if n > MAX_UNKNOWNS {
        return Err(Shortfall::Unknowns { unknowns: n, max: MAX_UNKNOWNS });
    }
    let not_polynomial = Shortfall::Unsupported("a constraint that is not polynomial at its value");
    let mut slot = vec![usize::MAX; layout.ncols()];
    for (k, (col, _)) in param.map.iter().enumerate() {
        slot[*col] = k;
    }
    // The equations (row, degree), highest degree first.
    let mut rows: Vec<(Row, u32)> = Vec::new();
    let mut degrees_of: std::collections::HashMap<ConstraintIdx, Vec<u32>> = Default::default();
    for &c in constraints {
        let degrees = equations.degrees(c).ok_or(not_polynomial.clone())?;
        rows.extend(degrees.iter().enumerate().map(|(k, d)| (Row::Constraint(c, k), *d)));
        degrees_of.insert(c, degrees);
    }
    rows.extend(param.extra.iter().enumerate().map(|(k, e)| (Row::Extra(k), e.degree())));
    rows.retain(|r| r.1 > 0);
    if rows.len() < n {
        return Err(Shortfall::Unsupported("fewer equations than unknowns"));
    }
    rows.sort_by_key(|r| std::cmp::Reverse(r.1));
    let mut rng = gcs_model::rng::SplitMix64::new(seed ^ 0xA17E_57A7);
    // Row i of the square system: equation i plus random multiples of the extra ones.
    let folded: Vec<Vec<C>> = (0..n)
        .map(|_| {
            (n..rows.len()).map(|_| C::new(rng.unit_f64() - 0.5, rng.unit_f64() - 0.5)).collect()
        })
        .collect();
    let degrees: Vec<u32> = rows[..n].iter().map(|r| r.1).collect();
    let complex_base: Vec<C> = param.base.iter().map(|v| C::new(*v, 0.0)).collect();
    // Configurations to evaluate at, one per thread at a time: the whole configuration, only
    // the parametrised columns rewritten.
    let pool: std::sync::Mutex<Vec<Vec<C>>> = std::sync::Mutex::new(Vec::new());
    // What each constraint's rows are where it holds (computed once: the rows minus it are
    // `Equations::polynomial`).
    // (A dimension cleared of its denominator has no such constant: its polynomial rows are
    // evaluated, `cleared`, with target 0.)
    let mut targets: std::collections::HashMap<ConstraintIdx, C> = Default::default();
    let mut cleared: std::collections::HashSet<ConstraintIdx> = Default::default();
    for &c in constraints {
        let target = match equations.target(c) {
            Some(t) => t.to_f64().ok_or(not_polynomial.clone())?,
            None => {
                cleared.insert(c);
                0.0
            }
        };
        targets.insert(c, C::new(target, 0.0));
    }
    let eval = |y: &[C]| -> (Vec<C>, Vec<C>) {
        let taken = pool.lock().ok().and_then(|mut p| p.pop());
        let mut full = taken.unwrap_or_else(|| complex_base.clone());
        for (col, terms) in &param.map {
            full[*col] = complex_base[*col] + terms.iter().map(|(j, w)| y[*j] * *w).sum::<C>();
        }
        let mut values = vec![C::new(0.0, 0.0); rows.len()];
        let mut jac = vec![C::new(0.0, 0.0); rows.len() * n];
        let mut cache: Option<(ConstraintIdx, gcs_jacobian::Residual<C>)> = None;
        for (k, &(row, degree)) in rows.iter().enumerate() {
            let gradient = &mut jac[k * n..(k + 1) * n];
            match row {
                Row::Constraint(c, r) => {
                    if cache.as_ref().is_none_or(|(cc, _)| *cc != c) {
                        cache =
                            node_rows(equations, c, &full, cleared.contains(&c)).map(|r| (c, r));
                    }
                    let Some((_, res)) = &cache else { continue };
                    // In units of the size: F(base + size·y) / size^degree.
                    let unit = size.powi(degree as i32);
                    values[k] = (res.values[r] - targets[&c]) / unit;
                    for (col, v) in res.rows[r].entries() {
                        if let Some((_, terms)) = param.map.get(slot[*col]) {
                            for (j, w) in terms {
                                gradient[*j] += v * *w / unit;
                            }
                        }
                    }
                }
                Row::Extra(e) => values[k] = param.extra[e].eval(y, gradient),
            }
        }
        if let Ok(mut p) = pool.lock() {
            p.push(full);
        }
        let mut f = values[..n].to_vec();
        let mut j = jac[..n * n].to_vec();
        for i in 0..n {
            for (e, w) in folded[i].iter().enumerate() {
                f[i] += w * values[n + e];
                for col in 0..n {
                    j[i * n + col] += w * jac[(n + e) * n + col];
                }
            }
        }
        (f, j)
    };
    // In isotropic coordinates (u, v) = (a + ib, a − ib) of each pair, a distance is
    // bilinear, `(u_a − u_b)(v_a − v_b) = d²`, and so is a rotation, `u·v = 1`: the start
    // system is two-homogeneous in the u and the v (70 paths for K3,3 where the total degree
    // has 256).
    let half = C::new(0.5, 0.0);
    let minus_half_i = C::new(0.0, -0.5);
    let to_xy = |w: &[C]| -> Vec<C> {
        let mut y = w.to_vec();
        for q in 0..n / 2 {
            let (u, v) = (w[2 * q], w[2 * q + 1]);
            y[2 * q] = (u + v) * half;
            y[2 * q + 1] = (u - v) * minus_half_i;
        }
        y
    };
    let iso = |w: &[C]| -> (Vec<C>, Vec<C>) {
        let (f, j) = eval(&to_xy(w));
        let mut jw = j.clone();
        for r in 0..n {
            for q in 0..n / 2 {
                let (dx, dy) = (j[r * n + 2 * q], j[r * n + 2 * q + 1]);
                jw[r * n + 2 * q] = dx * half + dy * minus_half_i;
                jw[r * n + 2 * q + 1] = dx * half - dy * minus_half_i;
            }
        }
        (f, jw)
    };
    let groups = if param.paired {
        let second: Vec<bool> = (0..n).map(|j| j % 2 == 1).collect();
        bidegrees(&iso, n, &second, &mut rng).map(|b| (second, b))
    } else {
        None
    };
    let target = match groups {
        Some(groups) if groups.1.iter().zip(&degrees).all(|(b, d)| b[0] + b[1] >= *d) => {
            Target { n, degrees: degrees.clone(), eval: &iso, groups: Some(groups) }
        }
        _ => Target { n, degrees: degrees.clone(), eval: &eval, groups: None },
    };
    let isotropic = target.groups.is_some();
    let max = max_paths.min(homotopy::MAX_PATHS);
    let paths = homotopy::path_count(&target);
    if paths > max {
        return Err(Shortfall::Paths { paths, max });
    }
    let ends = homotopy::solve(&target, seed, max_paths)
        .ok_or(Shortfall::Unsupported("a degenerate start system"))?;
    // The real ones, refined on the real equations, back in the layout's columns, checked
    // against every constraint.
    let real_rows = RealRows {
        equations,
        constraints,
        param,
        slot: &slot,
        targets: &targets,
        cleared: &cleared,
        degrees: &degrees_of,
    };
    let configuration = |real: &[f64]| -> Vec<f64> {
        let mut y = x.to_vec();
        for (col, b) in param.base.iter().enumerate() {
            if slot[col] == usize::MAX && *b != x[col] {
                y[col] = *b;
            }
        }
        for (col, terms) in &param.map {
            y[*col] = param.base[*col] + terms.iter().map(|(j, w)| real[*j] * w).sum::<f64>();
        }
        y
    };
    let mut found: Vec<(f64, RealEnd)> = Vec::new();
    for s in &ends.solutions {
        let s = if isotropic { to_xy(s) } else { s.clone() };
        let Some(s) = param.renormalise(&s) else { continue };
        let magnitude = 1.0 + s.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        if s.iter().any(|v| !(v.im.abs() <= 1e-7 * magnitude)) {
            continue;
        }
        let start: Vec<f64> = s.iter().map(|v| v.re).collect();
        let real = polish(&real_rows, &start);
        let y = configuration(&real);
        let extra_hold = real_rows.extra_residual(&real) <= tolerance;
        let holds = extra_hold
            && check.iter().all(|&c| {
                crate::relative(system, equations, c, &y, size).is_some_and(|r| r <= tolerance)
            });
        let magnitude = 1.0 + real.iter().map(|v| v * v).sum::<f64>().sqrt();
        let seen = found.iter().any(|f| {
            let d = f.1.0.iter().zip(&real).map(|(a, b)| (a - b).powi(2)).sum::<f64>().sqrt();
            d <= 1e-7 * magnitude
        });
        if holds && !seen {
            let distance = param.map.iter().map(|(c, _)| (y[*c] - x[*c]).powi(2)).sum::<f64>();
            found.push((distance, (real, y)));
        }
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let counts = PathCounts {
        paths: ends.paths,
        finite: ends.solutions.len(),
        real: found.len(),
        singular: ends.singular,
        failed: ends.failed,
        met: ends.met,
        unaccounted: ends.unaccounted,
    };
    Ok((counts, found.into_iter().map(|f| f.1).collect()))
}

/// A node's real equations over its unknowns `y` (in units of the size, as the complex
/// system has them): every row of its constraints, `F(base + size·y) / size^degree` minus
/// its target, and the parametrisation's own equations (a rotation's `c² + s² − 1`, and the
/// real and imaginary parts of each isotropic agreement of a shared point) — in `f64`.
struct RealRows<'r> {
    equations: &'r Equations<'r>,
    constraints: &'r [ConstraintIdx],
    param: &'r Param,
    slot: &'r [usize],
    targets: &'r std::collections::HashMap<ConstraintIdx, C>,
    /// The dimensions cleared of their denominators ([`node_rows`]).
    cleared: &'r std::collections::HashSet<ConstraintIdx>,
    /// Each constraint's rows' degrees (`Equations::degrees`, computed once).
    degrees: &'r std::collections::HashMap<ConstraintIdx, Vec<u32>>,
}

impl RealRows<'_> {
    /// The largest residual of the parametrisation's own equations at `y`.
    fn extra_residual(&self, y: &[f64]) -> f64 {
        let complex: Vec<C> = y.iter().map(|v| C::new(*v, 0.0)).collect();
        let mut gradient = vec![C::new(0.0, 0.0); y.len()];
        let mut real_gradient = vec![0.0; y.len()];
        (self.param.extra.iter())
            .map(|e| match e.eval_real(y, &mut real_gradient) {
                Some(v) => v.abs(),
                None => e.eval(&complex, &mut gradient).norm(),
            })
            .fold(0.0f64, f64::max)
    }
}

impl gcs_rank::Residuals for RealRows<'_> {
    fn unknowns(&self) -> usize {
        self.param.n
    }

    fn evaluate(&self, y: &[f64]) -> (Vec<f64>, Vec<gcs_rank::SparseRow<f64>>) {
        let (param, n) = (self.param, self.param.n);
        let mut full = param.base.clone();
        for (col, terms) in &param.map {
            full[*col] = param.base[*col] + terms.iter().map(|(j, w)| y[*j] * w).sum::<f64>();
        }
        let mut values = Vec::new();
        let mut rows = Vec::new();
        for &c in self.constraints {
            let Some(res) = node_rows(self.equations, c, &full, self.cleared.contains(&c)) else {
                continue;
            };
            let Some(degrees) = self.degrees.get(&c) else { continue };
            let target = self.targets.get(&c).map_or(0.0, |t| t.re);
            for (k, row) in res.rows.iter().enumerate() {
                let Some(&degree) = degrees.get(k) else { continue };
                if degree == 0 {
                    continue;
                }
                let unit = param.size.powi(degree as i32);
                let mut gradient = vec![0.0; n];
                for (col, v) in row.entries() {
                    if let Some((_, terms)) = param.map.get(self.slot[*col]) {
                        for (j, w) in terms {
                            gradient[*j] += v * w / unit;
                        }
                    }
                }
                values.push((res.values[k] - target) / unit);
                rows.push(dense_to_sparse(gradient));
            }
        }
        let complex: Vec<C> = y.iter().map(|v| C::new(*v, 0.0)).collect();
        for e in &param.extra {
            let mut real_gradient = vec![0.0; n];
            if let Some(v) = e.eval_real(y, &mut real_gradient) {
                values.push(v);
                rows.push(dense_to_sparse(real_gradient));
                continue;
            }
            let mut gradient = vec![C::new(0.0, 0.0); n];
            let v = e.eval(&complex, &mut gradient);
            values.push(v.re);
            rows.push(dense_to_sparse(gradient.iter().map(|g| g.re).collect()));
            if let Extra::Linear(..) = e {
                values.push(v.im);
                rows.push(dense_to_sparse(gradient.iter().map(|g| g.im).collect()));
            }
        }
        (values, rows)
    }
}

/// The rows of constraint `c` at `x` as a node's equations take them: [`Equations::rows`]
/// (minus the constraint's target, by the caller), or for a dimension cleared of its
/// denominator (`cleared`) its polynomial equation ([`Equations::polynomial`], target 0).
fn node_rows<F: gcs_rank::Field>(
    equations: &Equations<'_>,
    c: ConstraintIdx,
    x: &[F],
    cleared: bool,
) -> Option<gcs_jacobian::Residual<F>> {
    if cleared { equations.polynomial(c, x) } else { Some(equations.rows(c, x)) }
}

fn dense_to_sparse(v: Vec<f64>) -> gcs_rank::SparseRow<f64> {
    gcs_rank::SparseRow::from_entries(
        v.into_iter().enumerate().filter(|(_, a)| *a != 0.0).collect(),
    )
}

/// The real parts `start` of a near-real end refined by Gauss–Newton in real arithmetic on
/// the node's real equations ([`gcs_rank::levenberg_marquardt`] with negligible damping: from
/// within 1e-7 a nonsingular root's digits double each step, so a dozen steps reach the
/// rounding floor, where no step lowers the residuals any more and the last accepted point
/// stays). Never worse than `start`: only steps that lower the sum of squares are taken.
fn polish(rows: &RealRows<'_>, start: &[f64]) -> Vec<f64> {
    let options = gcs_rank::LmOptions {
        // The residuals are relative (order 1 at the node's size): nothing below a few units
        // of rounding means anything.
        tolerance: 4.0 * f64::EPSILON,
        max_iterations: 12,
        initial_damping: 1e-12,
        ..gcs_rank::LmOptions::default()
    };
    gcs_rank::levenberg_marquardt(rows, start, &options).map_or_else(|| start.to_vec(), |o| o.x)
}

/// The degree of each equation of `eval` in each group of unknowns (`second`), numerically:
/// the equations restricted to a random line in one group's unknowns, through a random point,
/// are polynomials in the line's parameter, read off at the eighth roots of unity (a discrete
/// Fourier transform; a coefficient below 1e-9 of the largest is zero, so that rounding can only
/// raise a degree). `None` when a degree may exceed 6.
fn bidegrees(
    eval: &Residuals<'_>,
    n: usize,
    second: &[bool],
    rng: &mut gcs_model::rng::SplitMix64,
) -> Option<Vec<[u32; 2]>> {
    const N: usize = 8;
    let mut random = || C::new(rng.unit_f64() - 0.5, rng.unit_f64() - 0.5);
    let base: Vec<C> = (0..n).map(|_| random()).collect();
    let mut out = vec![[0u32; 2]; n];
    for g in 0..2 {
        let dir: Vec<C> = (0..n)
            .map(|j| if second[j] == (g == 1) { random() } else { C::new(0.0, 0.0) })
            .collect();
        let samples: Vec<Vec<C>> = (0..N)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / N as f64;
                let s = C::new(a.cos(), a.sin());
                let w: Vec<C> = base.iter().zip(&dir).map(|(b, d)| b + d * s).collect();
                eval(&w).0
            })
            .collect();
        for (i, o) in out.iter_mut().enumerate() {
            let coefficients: Vec<f64> = (0..N)
                .map(|j| {
                    let c: C = (0..N)
                        .map(|k| {
                            let a = -std::f64::consts::TAU * (j * k) as f64 / N as f64;
                            samples[k][i] * C::new(a.cos(), a.sin())
                        })
                        .sum();
                    c.norm()
                })
                .collect();
            let largest = coefficients.iter().fold(0.0f64, |m, c| m.max(*c));
            let degree = coefficients.iter().rposition(|c| *c > 1e-9 * largest).unwrap_or(0);
            if degree >= N - 1 {
                return None;
            }
            o[g] = degree as u32;
        }
    }
    Some(out)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A framework of points and distances drawn at `points`, each distance at its drawn
    /// length.
    pub(crate) fn framework(points: &[[f64; 2]], edges: &[(usize, usize)]) -> System {
        let mut text = String::from("System(dim: 2, entities: [");
        for (i, p) in points.iter().enumerate() {
            text += &format!("Point(id: \"p{i}\", at: [{}, {}]),", p[0], p[1]);
        }
        text += "], constraints: [";
        for (a, b) in edges {
            let d = (points[*a][0] - points[*b][0]).hypot(points[*a][1] - points[*b][1]);
            text += &format!("Distance(id: \"d{a}{b}\", a: \"p{a}\", b: \"p{b}\", value: {d}),");
        }
        text += "])";
        System::from_ron_str(&text, None).unwrap()
    }

    fn count(points: &[[f64; 2]], edges: &[(usize, usize)]) -> (PathCounts, Vec<Vec<f64>>) {
        let s = framework(points, edges);
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        let x: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
        let core: Vec<ConstraintIdx> = s.constraint_indices().collect();
        realizations(&s, &layout, &eq, &core, &x, (homotopy::MAX_PATHS, 1e-9), 7).unwrap()
    }

    /// The real polish ([`polish`]) refines a real candidate on the real equations: a point
    /// placed by two distances from two held points, its end off by 1e-6 of the size (a path
    /// near a double root ends that far off), fails the acceptance test (the solve's
    /// tolerance, 1e-9 relative); refined, it holds to the rounding floor, and it is the same
    /// real solution.
    #[test]
    fn the_real_polish_improves_a_real_end() {
        let points = [[0.0, 0.0], [4.0, 0.0], [1.5, 2.5]];
        let s = framework(&points, &[(0, 2), (1, 2)]);
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        let x: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
        let constraints: Vec<ConstraintIdx> = s.constraint_indices().collect();
        let size = 4.0;
        let col = layout.columns(s.entity_by_id("p2").unwrap()).start;
        let mut base = x.clone();
        (base[col], base[col + 1]) = (0.0, 0.0);
        let param = Param {
            n: 2,
            base,
            map: vec![(col, vec![(0, size)]), (col + 1, vec![(1, size)])],
            extra: Vec::new(),
            paired: true,
            size,
        };
        let mut slot = vec![usize::MAX; layout.ncols()];
        (slot[col], slot[col + 1]) = (0, 1);
        let targets = (constraints.iter())
            .map(|&c| (c, C::new(eq.target(c).unwrap().to_f64().unwrap(), 0.0)))
            .collect();
        let degrees = constraints.iter().map(|&c| (c, eq.degrees(c).unwrap())).collect();
        let rows = RealRows {
            equations: &eq,
            constraints: &constraints,
            param: &param,
            slot: &slot,
            targets: &targets,
            cleared: &Default::default(),
            degrees: &degrees,
        };
        let exact = [1.5 / size, 2.5 / size];
        let start = [exact[0] + 1e-6, exact[1] - 1e-6];
        let worst = |y: &[f64]| {
            let mut config = x.clone();
            (config[col], config[col + 1]) = (y[0] * size, y[1] * size);
            (constraints.iter())
                .map(|&c| crate::relative(&s, &eq, c, &config, size).unwrap())
                .fold(0.0f64, f64::max)
        };
        let before = worst(&start);
        let refined = polish(&rows, &start);
        let after = worst(&refined);
        assert!(before > 1e-9, "rejected as it ends: {before:e}");
        assert!(after <= 1e-15, "accepted once refined: {after:e}");
        assert!(refined.iter().zip(&exact).all(|(a, b)| (a - b).abs() <= 1e-14), "{refined:?}");
    }

    /// A framework in space drawn at `points`, each distance at its drawn length, and its
    /// realizations (held by its first triangle).
    fn count_3d(points: &[[f64; 3]], edges: &[(usize, usize)]) -> (PathCounts, Vec<Vec<f64>>) {
        let mut text = String::from("System(dim: 3, entities: [");
        for (i, p) in points.iter().enumerate() {
            text += &format!("Point(id: \"p{i}\", at: [{}, {}, {}]),", p[0], p[1], p[2]);
        }
        text += "], constraints: [";
        for (a, b) in edges {
            let d = (0..3).map(|k| (points[*a][k] - points[*b][k]).powi(2)).sum::<f64>().sqrt();
            text += &format!("Distance(id: \"d{a}{b}\", a: \"p{a}\", b: \"p{b}\", value: {d}),");
        }
        text += "])";
        let s = System::from_ron_str(&text, None).unwrap();
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        let x: Vec<f64> = points.iter().flat_map(|p| *p).collect();
        let core: Vec<ConstraintIdx> = s.constraint_indices().collect();
        let (counts, found) =
            realizations(&s, &layout, &eq, &core, &x, (homotopy::MAX_PATHS, 1e-9), 7).unwrap();
        // Every real one satisfies every distance, and the drawing comes first.
        for y in &found {
            for c in s.constraint_indices() {
                let r = crate::relative(&s, &eq, c, y, 10.0).unwrap();
                assert!(r <= 1e-12, "{r:e}");
            }
        }
        assert!(found[0].iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-9));
        (counts, found)
    }

    /// Bar frameworks in space, held by a triangle (realizations up to direct isometries,
    /// mirror images distinct): the tetrahedron has 2 (its fourth point on either side of the
    /// held face), the triangular bipyramid 4 (each pole on either side). Total degree:
    /// 2^(3·(points − 3)) paths. (The octahedron's 16 — Emiris, Tsigaridas and Varvitsiotis
    /// 2009; Bartzos, Emiris, Legerský and Tsigaridas 2018 — takes 512 paths, several seconds:
    /// `cargo run --release -p gcs-solve --example enumerate -- octahedron 100`.)
    #[test]
    fn bar_frameworks_in_space_have_their_complex_counts() {
        let points = [[0.3, 0.1, 0.2], [5.1, -1.4, 0.7], [2.2, 3.9, -0.4], [1.9, 1.2, 4.1]];
        let k4 = [(0, 1), (0, 2), (1, 2), (0, 3), (1, 3), (2, 3)];
        let (counts, found) = count_3d(&points, &k4);
        assert_eq!((counts.paths, counts.finite, counts.failed, found.len()), (8, 2, 0, 2));
        // The other one is the mirror image of the fourth point in the held face.
        let moved = (9..12).map(|k| (found[1][k] - found[0][k]).powi(2)).sum::<f64>().sqrt();
        assert!(moved > 1.0 && found[1][..9] == found[0][..9], "{found:?}");
        let points = [
            [0.3, 0.1, 0.2],
            [5.1, -1.4, 0.7],
            [2.2, 3.9, -0.4],
            [1.9, 1.2, 4.1],
            [2.7, 0.4, -3.6],
        ];
        let bipyramid = [(0, 1), (0, 2), (1, 2), (0, 3), (1, 3), (2, 3), (0, 4), (1, 4), (2, 4)];
        let (counts, found) = count_3d(&points, &bipyramid);
        assert_eq!((counts.paths, counts.finite, counts.failed, found.len()), (64, 4, 0, 4));
    }

    /// The counts of Capco, Gallet, Grasegger, Koutschan, Lubbes and Schicho (2018), complex
    /// realizations up to direct isometries: K3,3 has 16, the triangular prism 24; the
    /// drawing is one of the real ones, and comes first.
    #[test]
    fn k33_and_the_prism_have_their_complex_counts() {
        let points = [[0.3, 0.1], [5.1, -1.4], [2.2, 3.9], [4.7, 2.3], [-1.7, 3.1], [1.6, 6.7]];
        let k33 = [(0, 1), (0, 3), (0, 5), (2, 1), (2, 3), (2, 5), (4, 1), (4, 3), (4, 5)];
        let (counts, found) = count(&points, &k33);
        // Two-homogeneous in isotropic coordinates: C(8, 4) = 70 paths, not 2^8.
        assert_eq!((counts.paths, counts.finite, counts.failed), (70, 16, 0), "{counts:?}");
        assert_eq!(counts.real, found.len());
        assert!(found.len() >= 2 && found.len() % 2 == 0, "{counts:?}");
        let x: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
        assert!(found[0].iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-9));
        let prism = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)];
        let points = [[0.0, 0.0], [3.1, 0.4], [1.2, 2.9], [4.3, 3.3], [-0.7, 4.1], [2.6, 5.7]];
        let (counts, found) = count(&points, &prism);
        assert_eq!((counts.paths, counts.finite, counts.failed), (70, 24, 0), "{counts:?}");
        assert_eq!(counts.real, found.len());
        // Every real one satisfies every distance.
        let s = framework(&points, &prism);
        let layout = Layout::new(&s);
        let eq = Equations::new(&s, &layout);
        for y in &found {
            for c in s.constraint_indices() {
                let r = eq.residual(c, y).unwrap();
                // (Refined on the real equations: far below the solve's 1e-9.)
                assert!(r.values[0].abs() < 1e-13, "{r:?}");
            }
        }
    }
}
