//! Every real realization of the core (the part of a sketch no closed-form step places: in
//! space, all of it),
//! by homotopy continuation ([`crate::homotopy`]): the candidates of the DR-plan node that the
//! damped Newton solve reaches only one of.
//!
//! The core's equations are the analysis's own ([`Equations::polynomial`]: the polynomial
//! residuals of parameter-free constraints, the squared distance between two points minus the
//! value squared, a radius or coordinate difference minus its value). Realizations are counted
//! up to direct isometries, mirror images distinct (as the ESM paper and Capco et al. count):
//! a floating plane core is held by one of its point-to-point distances — its first point where
//! the solve put it, its second at the distance's value along the solved direction — and that
//! distance is left out of the equations; a floating core in space (points and distances) by a
//! triangle of them, its three points placed by their values where the solve put them
//! ([`hold_triangle`]: the six motions of space), its three distances left out. The counts
//! are then those of the literature: in the plane Capco et al.'s (K3,3: 16), in space those of
//! Emiris, Tsigaridas and Varvitsiotis (2009) and Bartzos, Emiris, Legerský and Tsigaridas
//! (2018), who hold a triangle too (the tetrahedron: 2, the octahedron: 16). Each unknown is
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
    /// than points, entities with
    /// homogeneous coordinates or internal relations, a dimension whose measure is not
    /// polynomial, a node neither held in place nor floating rigidly with a point-to-point
    /// distance to hold it by, fewer equations than unknowns).
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
/// of distances to hold it by), entities with homogeneous coordinates or internal
/// relations, a dimension whose measure is not polynomial, a core that is neither held in
/// place nor floating rigidly with a point-to-point distance to hold it by, more than 64
/// unknowns, or more paths than `max_paths` (or [`homotopy::MAX_PATHS`]).
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
    let mut dof = 0usize;
    for &e in &entities {
        if let Some(repr) = layout.repr(e)
            && (repr.homogeneous() || repr.internal_rows() > 0)
        {
            return Err(Unsupported("entities with homogeneous coordinates or internal relations"));
        }
        if space && system.entity(e).kind() != gcs_model::EntityKind::Point {
            return Err(Unsupported("a 3D node with entities other than points"));
        }
        dof += system.entity(e).kind().dof(system.dim());
    }
    let doc: usize = core.iter().map(|&c| system.constraint(c).doc).sum();
    // The motions of a rigid whole: three in the plane, six in space.
    let rigid = if space { 6 } else { 3 };
    // Held in place (nothing left), or floating as a rigid whole, held by a distance between
    // two of its points (in space, by a triangle of them).
    let floating = match dof.checked_sub(doc) {
        None => return Err(Unsupported("a node with more equations than freedoms")),
        Some(0) => false,
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
    let (base, held, gauge) = if !floating {
        (x.to_vec(), Vec::new(), Vec::new())
    } else if space {
        hold_triangle(system, layout, core, x)?
    } else {
        hold_distance(system, layout, core, x)?
    };
    let mut unknowns: Vec<usize> = Vec::new();
    for &e in &entities {
        unknowns.extend(layout.columns(e).filter(|c| !held.contains(c)));
    }
    let n = unknowns.len();
    if n == 0 {
        return Err(Unsupported("a node without unknowns"));
    }
    if n > MAX_UNKNOWNS {
        return Err(Shortfall::Unknowns { unknowns: n, max: MAX_UNKNOWNS });
    }
    let size = unknowns.iter().fold(0.0f64, |m, &c| m.max(base[c].abs())).max(1.0);
    // Points only, each an (x, y) pair: isotropic coordinates apply.
    let paired = entities.iter().filter(|&&e| !layout.columns(e).is_empty()).all(|&e| {
        layout.columns(e).len() == 2 && system.entity(e).kind() == gcs_model::EntityKind::Point
    }) && n.is_multiple_of(2);
    let equations_of: Vec<ConstraintIdx> =
        core.iter().copied().filter(|c| !gauge.contains(c)).collect();
    let param = Param {
        n,
        base,
        map: unknowns.iter().enumerate().map(|(i, &c)| (c, vec![(i, size)])).collect(),
        extra: Vec::new(),
        paired,
        size,
    };
    let (counts, found) = solve_param(
        (system, layout, equations),
        &equations_of,
        core,
        &param,
        x,
        (max_paths, tolerance),
        seed,
    )?;
    Ok((counts, found.into_iter().map(|f| f.1).collect()))
}

/// How a floating node is held (the trivial motions modded out), as the configuration to
/// start from, the columns held and the constraints that then hold by construction (left out
/// of the equations).
type Held = (Vec<f64>, Vec<usize>, Vec<ConstraintIdx>);

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
) -> Result<Held, Shortfall> {
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
    Ok((base, ca.chain(cb).collect(), vec![g]))
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
) -> Result<Held, Shortfall> {
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
    Ok((base, ca.chain(cb).chain(cc).collect(), gauge.to_vec()))
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
}

impl Extra {
    fn degree(&self) -> u32 {
        match self {
            Extra::Rotation(..) => 2,
            Extra::Linear(..) => 1,
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
        }
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
    let mut targets: std::collections::HashMap<ConstraintIdx, C> = Default::default();
    for &c in constraints {
        let target = equations.target(c).and_then(|t| t.to_f64()).ok_or(not_polynomial.clone())?;
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
                        cache = Some((c, equations.rows(c, &full)));
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
    /// Each constraint's rows' degrees (`Equations::degrees`, computed once).
    degrees: &'r std::collections::HashMap<ConstraintIdx, Vec<u32>>,
}

impl RealRows<'_> {
    /// The largest residual of the parametrisation's own equations at `y`.
    fn extra_residual(&self, y: &[f64]) -> f64 {
        let complex: Vec<C> = y.iter().map(|v| C::new(*v, 0.0)).collect();
        let mut gradient = vec![C::new(0.0, 0.0); y.len()];
        (self.param.extra.iter())
            .map(|e| e.eval(&complex, &mut gradient).norm())
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
            let res = self.equations.rows(c, &full);
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
