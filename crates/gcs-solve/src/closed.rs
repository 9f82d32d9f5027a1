//! The closed-form constructive steps: where a point is determined by two conditions whose
//! intersection is written down directly (ESM paper §3: the constructive steps of a DR-plan),
//! with all its real candidates. A library module: no I/O, no panics.

/// The real intersections of two curves, in a fixed order of the candidates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Intersection {
    /// No real point: the circles are apart, or one inside the other.
    None,
    /// One point (within the tolerance, the curves touch): one candidate.
    Tangent([f64; 2]),
    /// Two points: candidate 0 to the left of the directed line from the first centre to the
    /// second (positive orientation), candidate 1 to the right.
    Two([[f64; 2]; 2]),
}

impl Intersection {
    /// The candidates in order.
    pub fn candidates(&self) -> Vec<[f64; 2]> {
        match *self {
            Intersection::None => Vec::new(),
            Intersection::Tangent(p) => vec![p],
            Intersection::Two(ps) => ps.to_vec(),
        }
    }
}

/// The orientation of the triangle `a, b, p`: twice its signed area, positive when `p` is to
/// the left of the directed line `a → b` (the 3×3 orientation determinant of the ESM paper's
/// chirality, in the plane).
pub fn orientation(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// The intersections of the circle of centre `a`, radius `ra` with the circle of centre `b`,
/// radius `rb`: a point at distances `ra` from `a` and `rb` from `b` (a point by two
/// distances). `tolerance` is relative to the radii: the circles touch when the square of the
/// half chord is within `tolerance · (ra + rb)²` of zero. Coincident centres give `None`
/// (no isolated point).
///
/// # Example
/// ```
/// use gcs_solve::closed::{Intersection, circle_circle};
/// let Intersection::Two([left, right]) = circle_circle([0.0, 0.0], 5.0, [8.0, 0.0], 5.0, 1e-12)
/// else { panic!() };
/// assert!((left[0] - 4.0).abs() < 1e-12 && (left[1] - 3.0).abs() < 1e-12);
/// assert!((right[1] + 3.0).abs() < 1e-12);
/// ```
pub fn circle_circle(a: [f64; 2], ra: f64, b: [f64; 2], rb: f64, tolerance: f64) -> Intersection {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let d2 = dx * dx + dy * dy;
    let d = d2.sqrt();
    if !(d > 0.0) || !ra.is_finite() || !rb.is_finite() {
        return Intersection::None;
    }
    // Along a → b, the foot of the chord; across, the half chord h (h² = ra² − t²).
    let t = (d2 + ra * ra - rb * rb) / (2.0 * d);
    let h2 = ra * ra - t * t;
    let (ux, uy) = (dx / d, dy / d);
    let foot = [a[0] + t * ux, a[1] + t * uy];
    let size = (ra.abs() + rb.abs()).max(d);
    if h2.abs() <= tolerance * size * size {
        return Intersection::Tangent(foot);
    }
    if h2 < 0.0 {
        return Intersection::None;
    }
    let h = h2.sqrt();
    // (−uy, ux) is the left normal of a → b.
    Intersection::Two([[foot[0] - h * uy, foot[1] + h * ux], [foot[0] + h * uy, foot[1] - h * ux]])
}

/// The intersections of the circle of centre `a`, radius `r` with the line `g·p = h` (a point
/// at a distance from a point and on a line): candidate 0 is the one ahead along the line's
/// direction `(−g₁, g₀)` from the foot of the perpendicular from `a`, candidate 1 behind.
/// `tolerance` as for [`circle_circle`], relative to `r²`. A line without a direction gives
/// `None`.
///
/// # Example
/// ```
/// use gcs_solve::closed::{Intersection, circle_line};
/// // The circle of radius 5 about the origin and the horizontal line y = 3.
/// let Intersection::Two([ahead, behind]) = circle_line([0.0, 0.0], 5.0, [0.0, 1.0], 3.0, 1e-12)
/// else { panic!() };
/// assert!((ahead[0] + 4.0).abs() < 1e-12 && (ahead[1] - 3.0).abs() < 1e-12);
/// assert!((behind[0] - 4.0).abs() < 1e-12);
/// ```
pub fn circle_line(a: [f64; 2], r: f64, g: [f64; 2], h: f64, tolerance: f64) -> Intersection {
    let g2 = g[0] * g[0] + g[1] * g[1];
    if g2.is_nan() || g2 <= 0.0 || !r.is_finite() || !h.is_finite() {
        return Intersection::None;
    }
    let t = (h - g[0] * a[0] - g[1] * a[1]) / g2;
    let foot = [a[0] + t * g[0], a[1] + t * g[1]];
    let h2 = r * r - t * t * g2;
    if h2.abs() <= tolerance * r * r {
        return Intersection::Tangent(foot);
    }
    if h2 < 0.0 {
        return Intersection::None;
    }
    let s = (h2 / g2).sqrt();
    let u = [-g[1] * s, g[0] * s];
    Intersection::Two([[foot[0] + u[0], foot[1] + u[1]], [foot[0] - u[0], foot[1] - u[1]]])
}

/// The point of the lines `g₁·p = h₁` and `g₂·p = h₂`; `None` when they are parallel within
/// `tolerance` (the sine of their angle).
pub fn line_line(g1: [f64; 2], h1: f64, g2: [f64; 2], h2: f64, tolerance: f64) -> Option<[f64; 2]> {
    let det = g1[0] * g2[1] - g1[1] * g2[0];
    let n = (g1[0].hypot(g1[1])) * (g2[0].hypot(g2[1]));
    if det.is_nan() || det.abs() <= tolerance * n {
        return None;
    }
    let p = [(h1 * g2[1] - h2 * g1[1]) / det, (g1[0] * h2 - g2[0] * h1) / det];
    p.iter().all(|v| v.is_finite()).then_some(p)
}

/// The point on the line `g·p = h` nearest to the circle of centre `a` when they do not meet:
/// the foot of the perpendicular from `a`.
pub fn foot(a: [f64; 2], g: [f64; 2], h: f64) -> [f64; 2] {
    let g2 = g[0] * g[0] + g[1] * g[1];
    if g2.is_nan() || g2 <= 0.0 {
        return a;
    }
    let t = (h - g[0] * a[0] - g[1] * a[1]) / g2;
    [a[0] + t * g[0], a[1] + t * g[1]]
}

/// The point nearest to satisfying both distances when the circles do not meet: on the line
/// through the centres, halfway across the gap between the circles (the least-squares point
/// of the two residuals `|p − a| − ra`, `|p − b| − rb`).
pub fn nearest_to_both(a: [f64; 2], ra: f64, b: [f64; 2], rb: f64) -> [f64; 2] {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let d = (dx * dx + dy * dy).sqrt();
    if !(d > 0.0) {
        return [a[0] + ra, a[1]];
    }
    let (ux, uy) = (dx / d, dy / d);
    // The distance from a along a → b (negative: behind a).
    let s = if d >= ra + rb {
        // Apart: the middle of the gap.
        (ra + d - rb) / 2.0
    } else if ra >= rb {
        // b's circle inside a's: between b's far side and a's circle.
        (ra + d + rb) / 2.0
    } else {
        // a's circle inside b's: between a's far side and b's circle, behind a.
        -(ra + rb - d) / 2.0
    };
    [a[0] + s * ux, a[1] + s * uy]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
    }

    #[test]
    fn two_candidates_left_then_right() {
        let (a, b) = ([1.0, 2.0], [4.0, 6.0]);
        let Intersection::Two([l, r]) = circle_circle(a, 4.0, b, 3.0, 1e-12) else {
            panic!("two points")
        };
        for p in [l, r] {
            assert!((dist(p, a) - 4.0).abs() < 1e-12 && (dist(p, b) - 3.0).abs() < 1e-12);
        }
        assert!(orientation(a, b, l) > 0.0 && orientation(a, b, r) < 0.0);
    }

    #[test]
    fn tangent_circles_give_one_candidate() {
        // Outside and inside tangency.
        assert_eq!(
            circle_circle([0.0, 0.0], 2.0, [5.0, 0.0], 3.0, 1e-12),
            Intersection::Tangent([2.0, 0.0])
        );
        let Intersection::Tangent(p) = circle_circle([0.0, 0.0], 5.0, [2.0, 0.0], 3.0, 1e-12)
        else {
            panic!()
        };
        assert!((p[0] - 5.0).abs() < 1e-12 && p[1].abs() < 1e-12);
        assert_eq!(circle_circle([0.0, 0.0], 2.0, [5.0, 0.0], 3.0, 1e-12).candidates().len(), 1);
    }

    #[test]
    fn circle_and_line() {
        // The line x + y = 1 and the unit circle about the origin: (1, 0) and (0, 1).
        let Intersection::Two([ahead, behind]) =
            circle_line([0.0, 0.0], 1.0, [1.0, 1.0], 1.0, 1e-12)
        else {
            panic!("two points")
        };
        // Ahead along (−1, 1): (0, 1).
        assert!(dist(ahead, [0.0, 1.0]) < 1e-12 && dist(behind, [1.0, 0.0]) < 1e-12);
        // Tangent, and apart.
        assert_eq!(
            circle_line([0.0, 0.0], 2.0, [0.0, 1.0], 2.0, 1e-12),
            Intersection::Tangent([0.0, 2.0])
        );
        assert_eq!(circle_line([0.0, 0.0], 2.0, [0.0, 1.0], 3.0, 1e-12), Intersection::None);
        assert_eq!(foot([0.0, 0.0], [0.0, 2.0], 6.0), [0.0, 3.0]);
        assert_eq!(circle_line([0.0, 0.0], 2.0, [0.0, 0.0], 3.0, 1e-12), Intersection::None);
    }

    #[test]
    fn two_lines() {
        let p = line_line([1.0, 0.0], 2.0, [1.0, 1.0], 5.0, 1e-12).expect("a point");
        assert!(dist(p, [2.0, 3.0]) < 1e-12);
        assert_eq!(line_line([1.0, 0.0], 2.0, [2.0, 0.0], 5.0, 1e-12), None, "parallel");
    }

    #[test]
    fn no_intersection() {
        // 10, 10, 50: apart; one inside the other; the same centre.
        assert_eq!(circle_circle([0.0, 0.0], 10.0, [50.0, 0.0], 10.0, 1e-12), Intersection::None);
        assert_eq!(circle_circle([0.0, 0.0], 10.0, [1.0, 0.0], 2.0, 1e-12), Intersection::None);
        assert_eq!(circle_circle([0.0, 0.0], 1.0, [0.0, 0.0], 1.0, 1e-12), Intersection::None);
        assert!(Intersection::None.candidates().is_empty());
        let p = nearest_to_both([0.0, 0.0], 10.0, [50.0, 0.0], 10.0);
        assert_eq!(p, [25.0, 0.0]);
        let p = nearest_to_both([0.0, 0.0], 10.0, [1.0, 0.0], 2.0);
        // Halfway between a's circle and b's far side: both residuals 3.5.
        assert_eq!(p, [6.5, 0.0]);
        assert!(((dist(p, [0.0, 0.0]) - 10.0) + (dist(p, [1.0, 0.0]) - 2.0)).abs() < 1e-12);
        let q = nearest_to_both([0.0, 0.0], 2.0, [1.0, 0.0], 10.0);
        assert_eq!(q, [-5.5, 0.0], "behind a, towards b's circle");
    }
}
