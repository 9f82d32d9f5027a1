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
    /// Paths that ended neither at a nonsingular solution nor at infinity.
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
    let mut local = vec![usize::MAX; layout.ncols()];
    for (i, &c) in unknowns.iter().enumerate() {
        local[c] = i;
    }
    // The equations (constraint, row, degree), highest degree first.
    let mut rows: Vec<(ConstraintIdx, usize, u32)> = Vec::new();
    for &c in core.iter().filter(|&&c| Some(c) != gauge) {
        let degrees = equations.degrees(c)?;
        rows.extend(degrees.into_iter().enumerate().map(|(k, d)| (c, k, d)));
    }
    rows.retain(|r| r.2 > 0);
    if rows.len() < n {
        return None;
    }
    rows.sort_by_key(|r| std::cmp::Reverse(r.2));
    let size = unknowns.iter().fold(0.0f64, |m, &c| m.max(base[c].abs())).max(1.0);
    let mut rng = gcs_model::rng::SplitMix64::new(seed ^ 0xA17E_57A7);
    // Row i of the square system: equation i plus random multiples of the extra ones.
    let extra: Vec<Vec<C>> = (0..n)
        .map(|_| {
            (n..rows.len()).map(|_| C::new(rng.unit_f64() - 0.5, rng.unit_f64() - 0.5)).collect()
        })
        .collect();
    let degrees: Vec<u32> = rows[..n].iter().map(|r| r.2).collect();
    let complex_base: Vec<C> = base.iter().map(|v| C::new(*v, 0.0)).collect();
    // Configurations to evaluate at, one per thread at a time: the whole configuration, only
    // the unknowns rewritten.
    let pool: std::sync::Mutex<Vec<Vec<C>>> = std::sync::Mutex::new(Vec::new());
    // What each constraint's rows are where it holds (computed once: the rows minus it are
    // `Equations::polynomial`).
    let mut targets: std::collections::HashMap<ConstraintIdx, C> = Default::default();
    for &(c, _, _) in &rows {
        targets.insert(c, C::new(equations.target(c)?.to_f64()?, 0.0));
    }
    let eval = |y: &[C]| -> (Vec<C>, Vec<C>) {
        let taken = pool.lock().ok().and_then(|mut p| p.pop());
        let mut full = taken.unwrap_or_else(|| complex_base.clone());
        for (i, &c) in unknowns.iter().enumerate() {
            full[c] = complex_base[c] + y[i] * size;
        }
        let mut values = vec![C::new(0.0, 0.0); rows.len()];
        let mut jac = vec![C::new(0.0, 0.0); rows.len() * n];
        let mut cache: Option<(ConstraintIdx, gcs_jacobian::Residual<C>)> = None;
        for (k, &(c, row, degree)) in rows.iter().enumerate() {
            if cache.as_ref().is_none_or(|(cc, _)| *cc != c) {
                cache = Some((c, equations.rows(c, &full)));
            }
            let Some((_, r)) = &cache else { continue };
            // In units of the size: F(base + size·y) / size^degree.
            let unit = size.powi(degree as i32);
            values[k] = (r.values[row] - targets[&c]) / unit;
            for (col, v) in r.rows[row].entries() {
                if local[*col] != usize::MAX {
                    jac[k * n + local[*col]] = v * size / unit;
                }
            }
        }
        if let Ok(mut p) = pool.lock() {
            p.push(full);
        }
        let mut f = values[..n].to_vec();
        let mut j = jac[..n * n].to_vec();
        for i in 0..n {
            for (e, w) in extra[i].iter().enumerate() {
                f[i] += w * values[n + e];
                for col in 0..n {
                    j[i * n + col] += w * jac[(n + e) * n + col];
                }
            }
        }
        (f, j)
    };
    // In isotropic coordinates (u, v) = (x + iy, x − iy) of each point, a distance is
    // bilinear, `(u_a − u_b)(v_a − v_b) = d²`: the start system is two-homogeneous in the u
    // and the v (70 paths for K3,3 where the total degree has 256).
    let points_only = entities.iter().filter(|&&e| !layout.columns(e).is_empty()).all(|&e| {
        layout.columns(e).len() == 2 && system.entity(e).kind() == gcs_model::EntityKind::Point
    }) && unknowns.len() % 2 == 0;
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
    let groups = if points_only {
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
    let mut found: Vec<(f64, Vec<f64>)> = Vec::new();
    for s in &ends.solutions {
        let s = if isotropic { to_xy(s) } else { s.clone() };
        let magnitude = 1.0 + s.iter().map(|v| v.norm_sqr()).sum::<f64>().sqrt();
        if s.iter().any(|v| !(v.im.abs() <= 1e-7 * magnitude)) {
            continue;
        }
        let mut y = base.clone();
        for (i, &c) in unknowns.iter().enumerate() {
            y[c] = base[c] + s[i].re * size;
        }
        let holds = core.iter().all(|&c| {
            let (Some(r), Some(degrees)) = (equations.polynomial(c, &y), equations.degrees(c))
            else {
                return false;
            };
            r.values.iter().zip(degrees).all(|(v, d)| v.abs() <= 1e-8 * size.powi(d as i32))
        });
        if holds {
            let distance = unknowns.iter().map(|&c| (y[c] - x[c]).powi(2)).sum::<f64>();
            found.push((distance, y));
        }
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let counts = PathCounts {
        paths: ends.paths,
        finite: ends.solutions.len(),
        real: found.len(),
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
mod tests {
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
