//! B-spline curves (format §1, `BSpline`): what the degree, knots and weights of a
//! [`Geometry::BSpline`](crate::entity::Geometry::BSpline) mean, their checks, and the curve's
//! points (for drawings).
//!
//! An **open** spline of degree `p` on `n` control points has `n + p + 1` knots `t₀ ≤ … ≤
//! t_{n+p}`; the curve runs over `[t_p, t_n]`. It is *clamped* when its first and last `p + 1`
//! knots are equal: then it starts at its first control point and ends at its last, tangent to
//! the first and last legs of its control polygon. The default knot vector is clamped and
//! uniform: `0` (p + 1 times), `1, 2, …, n − p − 1`, `n − p` (p + 1 times).
//!
//! A **periodic** spline is closed: its control points wrap around (the point after the last is
//! the first). It has the `n + 1` knots of one period, `t₀ < … ≤ t_n`, the period being
//! `t_n − t₀`; the knots beyond repeat by the period. The default is `0, 1, …, n`.
//!
//! Weights (one per control point, positive) make it a NURBS curve; without them every weight
//! is 1. Degree, knots and weights are constants of the entity, not unknowns: the curve's degrees
//! of freedom are its control points'.

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// The largest degree accepted.
pub const MAX_DEGREE: u32 = 32;

/// Checks a B-spline's constants against its number of control points (what the model's
/// reader and builder check). On failure, the field at fault and what is wrong.
pub fn check(
    degree: u32,
    poles: usize,
    knots: Option<&[BigRational]>,
    weights: Option<&[BigRational]>,
    periodic: bool,
) -> Result<(), (&'static str, String)> {
    if !(1..=MAX_DEGREE).contains(&degree) {
        return Err((
            "degree",
            format!("degree {degree}: a B-spline's degree is 1 to {MAX_DEGREE}"),
        ));
    }
    let p = degree as usize;
    if poles < p + 1 {
        return Err((
            "poles",
            format!("{poles} control points: a B-spline of degree {p} needs at least {}", p + 1),
        ));
    }
    if let Some(k) = knots {
        let expected = if periodic { poles + 1 } else { poles + p + 1 };
        if k.len() != expected {
            let shape = if periodic {
                "the knots of one period: control points + 1"
            } else {
                "control points + degree + 1"
            };
            return Err((
                "knots",
                format!("{} knots where {expected} are expected ({shape})", k.len()),
            ));
        }
        if k.windows(2).any(|w| w[1] < w[0]) {
            return Err(("knots", "the knots decrease".into()));
        }
        let (lo, hi) = if periodic { (&k[0], &k[poles]) } else { (&k[p], &k[poles]) };
        if lo >= hi {
            return Err(("knots", "the curve's parameter range is empty".into()));
        }
        // A knot repeated more than the degree (interior) breaks the curve in two.
        let inner = if periodic { k } else { &k[1..k.len() - 1] };
        let mut run = 1;
        for w in inner.windows(2) {
            run = if w[0] == w[1] { run + 1 } else { 1 };
            if run > p {
                return Err((
                    "knots",
                    format!("an interior knot repeated {run} times: at most the degree, {p}"),
                ));
            }
        }
    }
    if let Some(w) = weights {
        if w.len() != poles {
            return Err(("weights", format!("{} weights for {poles} control points", w.len())));
        }
        if w.iter().any(|w| !w.is_positive()) {
            return Err(("weights", "a weight is not positive".into()));
        }
    }
    Ok(())
}

/// The knot vector a spline uses, flat: the given one, or the default (module documentation).
pub fn knots_or_default(
    degree: u32,
    poles: usize,
    knots: Option<&[BigRational]>,
    periodic: bool,
) -> Vec<BigRational> {
    if let Some(k) = knots {
        return k.to_vec();
    }
    let p = degree as usize;
    let int = |i: usize| BigRational::from_integer(i.into());
    if periodic {
        (0..=poles).map(int).collect()
    } else {
        let last = poles.saturating_sub(p);
        (0..poles + p + 1).map(|i| int(i.saturating_sub(p).min(last))).collect()
    }
}

/// Whether the curve starts at its first control point and ends at its last (an open spline
/// whose first and last `degree + 1` knots are equal).
pub fn is_clamped(
    degree: u32,
    poles: usize,
    knots: Option<&[BigRational]>,
    periodic: bool,
) -> bool {
    if periodic {
        return false;
    }
    let p = degree as usize;
    let k = knots_or_default(degree, poles, knots, periodic);
    k.len() == poles + p + 1
        && k[..=p].iter().all(|t| *t == k[0])
        && k[poles..].iter().all(|t| *t == k[poles])
}

/// The curve's parameter range: `[t_p, t_n]` for an open spline of degree `p` on `n` control
/// points, one period `[t_0, t_n]` for a periodic one (`knots` flat, [`knots_or_default`]).
pub fn domain(
    degree: u32,
    poles: usize,
    knots: &[BigRational],
    periodic: bool,
) -> (BigRational, BigRational) {
    let p = degree as usize;
    let at = |i: usize| knots.get(i).cloned().unwrap_or_else(BigRational::zero);
    if periodic { (at(0), at(poles)) } else { (at(p), at(poles)) }
}

/// The curve's point at parameter `u` as an affine combination of its control points, exactly:
/// `(control point index, coefficient)` pairs whose coefficients sum to 1 (the B-spline basis
/// functions `N_{i,p}(u)`, times the weights and divided by their weighted sum for a NURBS
/// curve; Cox–de Boor's recursion, the NURBS Book's A2.2, in rationals). A periodic spline's
/// indices wrap around. `None` when `u` is outside the curve's range ([`domain`]) or the data
/// do not make a curve.
pub fn basis(
    degree: u32,
    poles: usize,
    knots: &[BigRational],
    weights: &[BigRational],
    periodic: bool,
    u: &BigRational,
) -> Option<Vec<(usize, BigRational)>> {
    let p = degree as usize;
    let n = poles;
    // The unwrapped knot vector (as in `sample`): a periodic spline is the open spline of
    // n + p control points on its knots continued by the period.
    let (t, m): (Vec<BigRational>, usize) = if periodic {
        if knots.len() != n + 1 || n == 0 {
            return None;
        }
        let period = &knots[n] - &knots[0];
        let t = (0..n + 2 * p + 1)
            .map(|j| {
                let j = j as isize - p as isize;
                let (q, r) = (j.div_euclid(n as isize), j.rem_euclid(n as isize) as usize);
                &knots[r] + &period * BigRational::from_integer(q.into())
            })
            .collect();
        (t, n + p)
    } else {
        if knots.len() != n + p + 1 {
            return None;
        }
        (knots.to_vec(), n)
    };
    if m <= p || !(t[p] <= *u && *u <= t[m]) || t[p] >= t[m] {
        return None;
    }
    // The span: t[k] ≤ u < t[k + 1], p ≤ k < m (the last span closed at its end).
    let mut k = p;
    while k + 1 < m && t[k + 1] <= *u {
        k += 1;
    }
    // N[j] = N_{k−p+j, p}(u), j = 0..=p.
    let mut nb = vec![BigRational::zero(); p + 1];
    nb[0] = BigRational::from_integer(1.into());
    let mut left = vec![BigRational::zero(); p + 1];
    let mut right = vec![BigRational::zero(); p + 1];
    for j in 1..=p {
        left[j] = u - &t[k + 1 - j];
        right[j] = &t[k + j] - u;
        let mut saved = BigRational::zero();
        for r in 0..j {
            let den = &right[r + 1] + &left[j - r];
            let temp = if den.is_zero() { BigRational::zero() } else { &nb[r] / &den };
            nb[r] = &saved + &right[r + 1] * &temp;
            saved = &left[j - r] * &temp;
        }
        nb[j] = saved;
    }
    let one = BigRational::from_integer(1.into());
    let weight = |i: usize| weights.get(i % n).cloned().unwrap_or_else(|| one.clone());
    let mut out: Vec<(usize, BigRational)> = Vec::new();
    for (j, b) in nb.into_iter().enumerate() {
        let i = (k - p + j) % n;
        let c = b * weight(k - p + j);
        match out.iter_mut().find(|(x, _)| *x == i) {
            Some((_, acc)) => *acc += c,
            None => out.push((i, c)),
        }
    }
    let total: BigRational = out.iter().map(|(_, c)| c.clone()).sum();
    if total.is_zero() {
        return None;
    }
    for (_, c) in &mut out {
        *c = &*c / &total;
    }
    out.retain(|(_, c)| !c.is_zero());
    Some(out)
}

/// `count + 1` points of the curve (`count ≥ 1`), evenly spaced in its parameter, for drawing:
/// de Boor's algorithm in homogeneous coordinates. `poles` are the control points' positions
/// (any dimension), `knots` the flat vector ([`knots_or_default`]), `weights` one per control
/// point or empty for all 1. Returns no point when the data do not make a curve.
pub fn sample(
    degree: u32,
    poles: &[Vec<f64>],
    knots: &[BigRational],
    weights: &[BigRational],
    periodic: bool,
    count: usize,
) -> Vec<Vec<f64>> {
    let p = degree as usize;
    let n = poles.len();
    let f = |x: &BigRational| x.to_f64().unwrap_or(f64::NAN);
    let weight = |i: usize| weights.get(i).map_or(1.0, f);
    // The unwrapped control points and knot vector: a periodic spline of n points is the open
    // spline of n + p points (the first p repeated) on its knots continued by the period.
    let (ctrl, t): (Vec<(Vec<f64>, f64)>, Vec<f64>) = if periodic {
        if knots.len() != n + 1 || n == 0 {
            return Vec::new();
        }
        let period = f(&knots[n]) - f(&knots[0]);
        let ctrl = (0..n + p).map(|i| (poles[i % n].clone(), weight(i % n))).collect();
        let t = (0..n + 2 * p + 1)
            .map(|j| {
                let j = j as isize - p as isize;
                let (q, r) = (j.div_euclid(n as isize), j.rem_euclid(n as isize) as usize);
                f(&knots[r]) + q as f64 * period
            })
            .collect();
        (ctrl, t)
    } else {
        if knots.len() != n + p + 1 {
            return Vec::new();
        }
        ((0..n).map(|i| (poles[i].clone(), weight(i))).collect(), knots.iter().map(f).collect())
    };
    let m = ctrl.len();
    if m <= p || count == 0 || ctrl.iter().any(|(c, _)| c.len() != ctrl[0].0.len()) {
        return Vec::new();
    }
    let dim = ctrl[0].0.len();
    let (lo, hi) = (t[p], t[m]);
    // (Also false for NaN knots.)
    if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
        return Vec::new();
    }
    (0..=count)
        .map(|s| {
            let u = lo + (hi - lo) * s as f64 / count as f64;
            // The span: t[k] ≤ u < t[k + 1], with p ≤ k < m (the last span closed at hi).
            let mut k = p;
            while k + 1 < m && t[k + 1] <= u {
                k += 1;
            }
            // Homogeneous points w·(x, 1) of the p + 1 control points that act on the span.
            let mut d: Vec<Vec<f64>> = (0..=p)
                .map(|j| {
                    let (c, w) = &ctrl[k - p + j];
                    c.iter().map(|x| x * w).chain(std::iter::once(*w)).collect()
                })
                .collect();
            for r in 1..=p {
                for j in (r..=p).rev() {
                    let i = k - p + j;
                    let den = t[i + p + 1 - r] - t[i];
                    let a = if den.is_zero() { 0.0 } else { (u - t[i]) / den };
                    let prev = d[j - 1].clone();
                    for (x, y) in d[j].iter_mut().zip(&prev) {
                        *x = a * *x + (1.0 - a) * y;
                    }
                }
            }
            let h = &d[p];
            (0..dim).map(|i| h[i] / h[dim]).collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(v: i64) -> BigRational {
        BigRational::from_integer(v.into())
    }

    #[test]
    fn default_knots_are_clamped_and_uniform() {
        let k = knots_or_default(3, 5, None, false);
        assert_eq!(k, [0, 0, 0, 0, 1, 2, 2, 2, 2].map(q));
        assert!(is_clamped(3, 5, None, false));
        assert!(!is_clamped(2, 4, Some(&[0, 1, 2, 3, 4, 5, 6].map(q)), false));
        assert_eq!(knots_or_default(2, 4, None, true), [0, 1, 2, 3, 4].map(q));
    }

    #[test]
    fn checks_name_the_field() {
        assert_eq!(check(0, 3, None, None, false).unwrap_err().0, "degree");
        assert_eq!(check(3, 3, None, None, false).unwrap_err().0, "poles");
        assert_eq!(check(1, 2, Some(&[0, 0, 1].map(q)), None, false).unwrap_err().0, "knots");
        assert_eq!(check(1, 2, Some(&[0, 1, 0, 1].map(q)), None, false).unwrap_err().0, "knots");
        assert_eq!(check(1, 2, None, Some(&[q(1), q(0)]), false).unwrap_err().0, "weights");
        assert!(
            check(2, 3, Some(&[0, 0, 0, 1, 1, 1].map(q)), Some(&[q(1), q(2), q(1)]), false).is_ok()
        );
        assert!(check(3, 4, Some(&[0, 1, 1, 1, 2].map(q)), None, true).is_ok());
        assert!(check(2, 4, Some(&[0, 1, 1, 1, 2].map(q)), None, true).is_err());
    }

    #[test]
    fn a_clamped_spline_runs_from_its_first_to_its_last_control_point() {
        let poles = vec![vec![0.0, 0.0], vec![1.0, 2.0], vec![3.0, 2.0], vec![4.0, 0.0]];
        let k = knots_or_default(3, 4, None, false);
        let pts = sample(3, &poles, &k, &[], false, 4);
        assert_eq!(pts.len(), 5);
        assert_eq!(pts[0], vec![0.0, 0.0]);
        assert!((pts[4][0] - 4.0).abs() < 1e-12 && pts[4][1].abs() < 1e-12);
        // A cubic Bézier at t = 1/2: (P0 + 3 P1 + 3 P2 + P3) / 8.
        assert!((pts[2][0] - 2.0).abs() < 1e-12 && (pts[2][1] - 1.5).abs() < 1e-12);
    }

    #[test]
    fn a_quarter_circle_is_a_weighted_quadratic() {
        // Weights 1, √2/2, 1 on (1, 0), (1, 1), (0, 1) draw the quarter of the unit circle; with
        // a rational weight 1/2 the curve is an ellipse arc, so test the exact circle in f64.
        let poles = vec![vec![1.0, 0.0], vec![1.0, 1.0], vec![0.0, 1.0]];
        let k = knots_or_default(2, 3, None, false);
        let w =
            [q(1), BigRational::new(7071067811865476i64.into(), 10000000000000000i64.into()), q(1)];
        for p in sample(2, &poles, &k, &w, false, 8) {
            assert!((p[0].hypot(p[1]) - 1.0).abs() < 1e-9, "{p:?}");
        }
    }

    #[test]
    fn the_exact_basis_agrees_with_the_drawing() {
        let r = |a: i64, b: i64| BigRational::new(a.into(), b.into());
        // A uniform cubic at an interior knot away from the clamped ends: (P₃ + 4 P₄ + P₅) / 6;
        // near an end, the clamped knots weigh otherwise.
        let k = knots_or_default(3, 8, None, false);
        let b = basis(3, 8, &k, &[], false, &q(3)).unwrap();
        assert_eq!(b, vec![(3, r(1, 6)), (4, r(2, 3)), (5, r(1, 6))]);
        let k6 = knots_or_default(3, 6, None, false);
        let b = basis(3, 6, &k6, &[], false, &q(2)).unwrap();
        assert_eq!(b, vec![(2, r(1, 6)), (3, r(7, 12)), (4, r(1, 4))]);
        // The ends of a clamped spline are its end control points.
        assert_eq!(basis(3, 8, &k, &[], false, &q(0)).unwrap(), vec![(0, q(1))]);
        assert_eq!(basis(3, 8, &k, &[], false, &q(5)).unwrap(), vec![(7, q(1))]);
        assert!(basis(3, 8, &k, &[], false, &q(6)).is_none());
        // At any parameter, the combination is the drawn point (non-uniform knots, weights).
        let k = [0, 0, 0, 0, 1, 3, 4, 4, 4, 4].map(q);
        let w = [q(1), q(2), r(1, 2), q(1), q(3), q(1)];
        let poles: Vec<Vec<f64>> =
            (0..6).map(|i| vec![i as f64, ((i * i) % 5) as f64 - 1.0]).collect();
        let drawn = sample(3, &poles, &k, &w, false, 8);
        for (s, point) in drawn.iter().enumerate() {
            let u = r(s as i64, 2);
            let b = basis(3, 6, &k, &w, false, &u).unwrap();
            assert_eq!(b.iter().map(|(_, c)| c.clone()).sum::<BigRational>(), q(1));
            for d in 0..2 {
                let x: f64 = b.iter().map(|(i, c)| c.to_f64().unwrap() * poles[*i][d]).sum();
                assert!((x - point[d]).abs() < 1e-12, "{s} {d}: {x} vs {}", point[d]);
            }
        }
        // Periodic: the indices wrap around, and the combination is the drawing's.
        let k = knots_or_default(3, 4, None, true);
        assert_eq!(basis(3, 4, &k, &[], true, &q(0)).unwrap().len(), 3);
        let poles = vec![vec![0.0, 0.0], vec![2.0, 0.0], vec![2.0, 2.0], vec![0.0, 2.0]];
        let drawn = sample(3, &poles, &k, &[], true, 8);
        for (s, point) in drawn.iter().enumerate() {
            let b = basis(3, 4, &k, &[], true, &r(s as i64, 2)).unwrap();
            for d in 0..2 {
                let x: f64 = b.iter().map(|(i, c)| c.to_f64().unwrap() * poles[*i][d]).sum();
                assert!((x - point[d]).abs() < 1e-12, "{s} {d}: {x} vs {}", point[d]);
            }
        }
    }

    #[test]
    fn a_periodic_spline_closes() {
        let poles = vec![vec![0.0, 0.0], vec![2.0, 0.0], vec![2.0, 2.0], vec![0.0, 2.0]];
        let k = knots_or_default(3, 4, None, true);
        let pts = sample(3, &poles, &k, &[], true, 16);
        let (a, b) = (&pts[0], &pts[16]);
        assert!((a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12);
        // A uniform cubic: at a knot, (P₀ + 4 P₁ + P₂) / 6 of three consecutive control points.
        assert!((a[0] - 5.0 / 3.0).abs() < 1e-12 && (a[1] - 1.0 / 3.0).abs() < 1e-12, "{a:?}");
    }
}
