//! Every real realization of the core (the part of a plane sketch no closed-form step places),
//! by homotopy continuation ([`crate::homotopy`]): the candidates of the DR-plan node that the
//! damped Newton solve reaches only one of.
//!
//! The core's equations are the analysis's own ([`Equations::polynomial`]: the polynomial
//! residuals of parameter-free constraints, the squared distance between two points minus the
//! value squared, a radius or coordinate difference minus its value). Realizations are counted
//! up to direct isometries, mirror images distinct (as the ESM paper and Capco et al. count):
//! a floating core is held by one of its point-to-point distances — its first point where the
//! solve put it, its second at the distance's value along the solved direction — and that
//! distance is left out of the equations. Each unknown is measured from its solved value in
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
}

/// The core's real realizations over the layout's columns (the rest of `x` kept), the one
/// nearest the solved `x` first, with the path counts. `None` when the core is not one this
/// can enumerate: a 3D core, entities with homogeneous coordinates or internal relations, a
/// dimension whose measure is not polynomial, a core that is neither held in place nor
/// floating rigidly with a point-to-point distance to hold it by, more than 64 unknowns, or
/// more paths than `max_paths` (or [`homotopy::MAX_PATHS`]).
pub(crate) fn realizations(
    system: &System,
    layout: &Layout,
    equations: &Equations<'_>,
    core: &[ConstraintIdx],
    x: &[f64],
    max_paths: usize,
    seed: u64,
) -> Option<(PathCounts, Vec<Vec<f64>>)> {
    if system.dim() != gcs_model::Dim::Two || core.is_empty() || max_paths == 0 {
        return None;
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
            return None;
        }
        dof += system.entity(e).kind().dof(system.dim());
    }
    let doc: usize = core.iter().map(|&c| system.constraint(c).doc).sum();
    // Held in place (nothing left), or floating as a rigid whole (the three motions of the
    // plane), held by a distance between two of its points.
    let gauge = match dof.checked_sub(doc)? {
        0 => None,
        3 => Some(core.iter().copied().find(|&c| {
            let constraint = system.constraint(c);
            constraint.kind == ConstraintKind::Distance
                && constraint.value.as_ref().is_some_and(|v| v.to_f64().is_some_and(|v| v > 0.0))
                && matches!(
                    constraint.signature.metric(),
                    Some(gcs_model::Metric::DistancePointPoint(..))
                )
        })?),
        _ => return None,
    };
    let mut base = x.to_vec();
    let mut held: Vec<usize> = Vec::new();
    if let Some(g) = gauge {
        let [a, b] = system.constraint_base_entities(g)[..] else { return None };
        let (ca, cb) = (layout.columns(a), layout.columns(b));
        let d = system.constraint(g).value.as_ref()?.to_f64()?;
        let u = [x[cb.start] - x[ca.start], x[cb.start + 1] - x[ca.start + 1]];
        let len = u[0].hypot(u[1]);
        if !(len > 0.0) {
            return None;
        }
        base[cb.start] = x[ca.start] + d * u[0] / len;
        base[cb.start + 1] = x[ca.start + 1] + d * u[1] / len;
        held.extend(ca.chain(cb));
    }
    let mut unknowns: Vec<usize> = Vec::new();
    for &e in &entities {
        unknowns.extend(layout.columns(e).filter(|c| !held.contains(c)));
    }
    let n = unknowns.len();
    if n == 0 || n > MAX_UNKNOWNS {
        return None;
    }
    let size = unknowns.iter().fold(0.0f64, |m, &c| m.max(base[c].abs())).max(1.0);
    // Points only, each an (x, y) pair: isotropic coordinates apply.
    let paired = entities.iter().filter(|&&e| !layout.columns(e).is_empty()).all(|&e| {
        layout.columns(e).len() == 2 && system.entity(e).kind() == gcs_model::EntityKind::Point
    }) && n % 2 == 0;
    let param = Param {
        n,
        base,
        map: unknowns.iter().enumerate().map(|(i, &c)| (c, vec![(i, size)])).collect(),
        extra: Vec::new(),
        paired,
        size,
    };
    let equations_of: Vec<ConstraintIdx> =
        core.iter().copied().filter(|&c| Some(c) != gauge).collect();
    let (counts, found) =
        solve_param(layout, equations, &equations_of, core, &param, x, max_paths, seed)?;
    Some((counts, found.into_iter().map(|f| f.1).collect()))
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
    layout: &Layout,
    equations: &Equations<'_>,
    bodies: &[(Vec<EntityIdx>, &[f64])],
    free: &[EntityIdx],
    constraints: &[ConstraintIdx],
    x: &[f64],
    max_paths: usize,
    seed: u64,
) -> Option<(PathCounts, Vec<Vec<f64>>)> {
    let param = placement(layout, bodies, free, x)?;
    let (counts, found) =
        solve_param(layout, equations, constraints, constraints, &param, x, max_paths, seed)?;
    Some((counts, found.into_iter().map(|f| f.0).collect()))
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

/// Every real solution of `constraints` (and of the parametrisation's own equations) over
/// `param`, as whole configurations (`x` outside the parametrised columns), nearest to `x`
/// first, each checked against every constraint of `check`.
#[allow(clippy::too_many_arguments)]
fn solve_param(
    layout: &Layout,
    equations: &Equations<'_>,
    constraints: &[ConstraintIdx],
    check: &[ConstraintIdx],
    param: &Param,
    x: &[f64],
    max_paths: usize,
    seed: u64,
) -> Option<(PathCounts, Vec<(Vec<f64>, Vec<f64>)>)> {
    let n = param.n;
    let size = param.size;
    if n == 0 || n > MAX_UNKNOWNS {
        return None;
    }
    let mut slot = vec![usize::MAX; layout.ncols()];
    for (k, (col, _)) in param.map.iter().enumerate() {
        slot[*col] = k;
    }
    // The equations (row, degree), highest degree first.
    let mut rows: Vec<(Row, u32)> = Vec::new();
    for &c in constraints {
        let degrees = equations.degrees(c)?;
        rows.extend(degrees.into_iter().enumerate().map(|(k, d)| (Row::Constraint(c, k), d)));
    }
    rows.extend(param.extra.iter().enumerate().map(|(k, e)| (Row::Extra(k), e.degree())));
    rows.retain(|r| r.1 > 0);
    if rows.len() < n {
        return None;
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
        targets.insert(c, C::new(equations.target(c)?.to_f64()?, 0.0));
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
    let ends = homotopy::solve(&target, seed, max_paths)?;
    // The real ones, back in the layout's columns, checked against every equation.
    let mut found: Vec<(f64, (Vec<f64>, Vec<f64>))> = Vec::new();
    for s in &ends.solutions {
        let s = if isotropic { to_xy(s) } else { s.clone() };
        let magnitude = 1.0 + s.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        if s.iter().any(|v| !(v.im.abs() <= 1e-7 * magnitude)) {
            continue;
        }
        let real: Vec<f64> = s.iter().map(|v| v.re).collect();
        let mut y = x.to_vec();
        for (col, b) in param.base.iter().enumerate() {
            if slot[col] == usize::MAX && *b != x[col] {
                y[col] = *b;
            }
        }
        for (col, terms) in &param.map {
            y[*col] = param.base[*col] + terms.iter().map(|(j, w)| real[*j] * w).sum::<f64>();
        }
        let extra_hold = param.extra.iter().all(|e| {
            let complex: Vec<C> = real.iter().map(|v| C::new(*v, 0.0)).collect();
            let mut g = vec![C::new(0.0, 0.0); n];
            e.eval(&complex, &mut g).norm() <= 1e-8
        });
        let holds = extra_hold
            && check.iter().all(|&c| {
                let (Some(r), Some(degrees)) = (equations.polynomial(c, &y), equations.degrees(c))
                else {
                    return false;
                };
                r.values.iter().zip(degrees).all(|(v, d)| v.abs() <= 1e-8 * size.powi(d as i32))
            });
        if holds {
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
    };
    Some((counts, found.into_iter().map(|f| f.1).collect()))
}

/// The degree of each equation of `eval` in each group of unknowns (`second`), numerically:
/// the equations restricted to a random line in one group's unknowns, through a random point,
/// are polynomials in the line's parameter, read off at the eighth roots of unity (a discrete
/// Fourier transform; a coefficient below 1e-9 of the largest is zero, so that rounding can only
/// raise a degree). `None` when a degree may exceed 6.
fn bidegrees(
    eval: &dyn Fn(&[C]) -> (Vec<C>, Vec<C>),
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
        realizations(&s, &layout, &eq, &core, &x, homotopy::MAX_PATHS, 7).unwrap()
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
                assert!(r.values[0].abs() < 1e-9, "{r:?}");
            }
        }
    }
}
