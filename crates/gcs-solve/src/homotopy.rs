//! Every isolated complex solution of a square polynomial system, by homotopy continuation
//! (the ESM paper's §2.2 requirement on a node's algebraic solver: all the solutions, not the
//! one Newton reaches from the drawing).
//!
//! The method is the classical total-degree homotopy with the gamma trick:
//!
//! - The start system `G_i(x) = x_i^{d_i} − 1` has `Π d_i` solutions (products of roots of
//!   unity), and Bézout's bound says the target system `F` has at most that many isolated
//!   ones. When the unknowns split into two groups in which the equations have low degrees
//!   ([`Target::groups`]: a plane framework in isotropic coordinates, where a distance is
//!   bilinear), the start system is two-homogeneous instead — each `G_i` a product of random
//!   linear forms, as many in each group as `F_i`'s degree there — and has the (smaller)
//!   two-homogeneous Bézout number of solutions, each found by two linear solves. The homotopy `H(x, t) = (1 − t)·γ·G(x) + t·F(x)` with a random complex `γ` has, with
//!   probability one, no singular point for `t ∈ [0, 1)`: each start solution begins a smooth
//!   path, and every isolated solution of `F` ends one of them.
//! - Paths are tracked in projective space (`x = z / z₀` on a random affine chart
//!   `a·(z₀, z) = 1`), so that the paths whose solutions go to infinity stay bounded and end
//!   where `z₀ = 0`. `F` is given as a black box on affine coordinates; its homogenisation is
//!   `z₀^{d_i} F_i(z / z₀)`, with the derivative in `z₀` from Euler's relation.
//! - Each step predicts with a fourth-order Runge–Kutta step of `dz/dt = −H_z⁻¹ H_t` and
//!   corrects with Newton at the new `t`; the step grows after successes and halves after a
//!   failure. A path whose step underflows before `t = 1` ends there (near a singular end).
//! - At `t = 1` (or where a path stopped), an end with `z₀` negligible is at infinity; any
//!   other end is refined by Newton on `F` itself, and counts as a solution when Newton
//!   converges there quadratically (to a step of 1e-12 of the size, or by a hundredfold drop
//!   to the rounding floor of a large solution) with a well-conditioned Jacobian — from the
//!   end itself, or, for a path tracked to `1 − t = 1e-8` that is still far from a large or
//!   ill-conditioned solution, when the path's distance to it shrinks in proportion to
//!   `1 − t`. A path stopped short of the end whose `z₀` shrinks is at infinity. Any other
//!   path (including one tracked to the end at a finite point Newton does not confirm) goes
//!   to the Cauchy endgame: from where it was at `1 − t = 10⁻²` it is tracked around the circle
//!   `|1 − t| = 10⁻²` until it closes (its cycle number, at most 8 turns), and its end is the
//!   mean over those turns (Cauchy's integral formula) — at infinity, a nonsingular solution
//!   Newton confirms, or a singular solution (the path is decided: singular ends are no
//!   isolated nonsingular solution). Ends the endgame cannot decide (a loop that does not
//!   close) are counted as failed: the caller reports the solution set as incomplete.
//! - Completeness: with a generic `γ` the paths are disjoint for `t < 1` and each isolated
//!   nonsingular solution ends exactly one. Two paths ending at the same nonsingular solution
//!   therefore mean that one jumped to the other (and a solution may be missing): every path
//!   of such a collision is tracked again with smaller steps (a tenth, then a hundredth of
//!   the first), and the paths whose ends still collide count as failed, all but one. The
//!   solution set is [`Ends::complete`] only when no path failed: every path decided (a
//!   distinct nonsingular solution, infinity, or a singular end).
//! - A path that jumped onto a path to infinity or to a singular end leaves no collision.
//!   So every path is tracked through the same values of `t` (the checkpoints 0.1, 0.2, …,
//!   0.9, 0.99: its steps shortened to land on them) and the paths are compared there: two
//!   paths within 1e-6 of the size of each other, and still within 1e-11 once each is
//!   corrected by Newton at that `t` to the rounding, are one path twice (distinct paths do
//!   not meet for `t < 1`). Both are tracked again like a collision's, and what still meets
//!   counts as failed paths, all but one. No checkpoint beyond `t = 0.99`: there the paths
//!   to one singular end or one point at infinity draw together.
//! - Past the last checkpoint, the ends at infinity and at singular solutions are accounted
//!   for by the cycles of the Cauchy endgame's loops ([`account`]): one turn of the loop
//!   around `|1 − t| = 10⁻²` from each such path's point at `t = 0.99` must close at the end
//!   it was tracked to (cycle number 1) or come back at the point of another such path there
//!   (the next of its cycle), each point reached once. A path that jumped past 0.99 onto a
//!   path to infinity or to a singular end has a loop that closes at the nonsingular solution
//!   it should have reached: it is tracked again from 0.99 with finer steps, and counts as
//!   failed if its end still disagrees with its loop (as does a loop that comes back at no
//!   path's point, or at one another loop came back at, once remade with more points).
//!
//! All of this is floating point: the counts are numerical results, reported as such.

use gcs_model::rng::SplitMix64;
use gcs_rank::Complex64 as C;

/// The most paths a system may have (`Π d_i`); beyond, it is not attempted.
pub const MAX_PATHS: usize = 1 << 14;

/// A square polynomial system over affine coordinates: `n` unknowns, one equation per
/// unknown with its total degree, and an evaluation giving the values and the Jacobian
/// (row-major, `n × n`). Scaled so that its solutions and coefficients are of order 1 (the
/// tolerances are relative to 1).
pub struct Target<'a> {
    /// The unknowns (and equations).
    pub n: usize,
    /// The total degree of each equation (at least 1).
    pub degrees: Vec<u32>,
    /// When the unknowns split into two groups (`second[j]`: unknown `j` is in the second)
    /// and each equation has degree `(a, b)` in them (`bidegrees[i]`, `a + b` at least its total
    /// degree): the start system is then two-homogeneous — each equation a product of `a`
    /// random linear forms in the first group and `b` in the second — with far fewer paths
    /// than the total degree where the groups separate the variables of each term (a distance
    /// in isotropic coordinates is bilinear).
    pub groups: Option<(Vec<bool>, Vec<[u32; 2]>)>,
    /// Values and Jacobian at a point.
    pub eval: &'a (dyn Fn(&[C]) -> (Vec<C>, Vec<C>) + Sync),
}

/// What the paths ended at.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Ends {
    /// The paths tracked (`Π d_i`).
    pub paths: usize,
    /// The distinct finite nonsingular solutions, refined by Newton on the target.
    pub solutions: Vec<Vec<C>>,
    /// Paths that ended at infinity.
    pub at_infinity: usize,
    /// Paths that ended at a finite singular solution (found by the Cauchy endgame): decided,
    /// and no isolated nonsingular solution.
    pub singular: usize,
    /// Paths that ended neither at a nonsingular solution nor at infinity nor at a singular
    /// solution: lost, undecided by the endgame, or ending (after re-tracking) at a solution
    /// another path ended at (a jump: each nonsingular solution ends one path).
    pub failed: usize,
    /// Paths found at the same point as another path at a checkpoint `t < 1` on their first
    /// tracking (a jump detected), then tracked again: diagnostic, no path of it is missing
    /// unless counted in `failed`.
    pub met: usize,
    /// Paths to infinity or to a singular end that the cycles of the Cauchy endgame's loops
    /// did not account for on their first tracking (a jump past the last checkpoint detected,
    /// or a loop that did not come back at a path), then tracked or looped again: diagnostic,
    /// no path of it is missing unless counted in `failed`.
    pub unaccounted: usize,
}

impl Ends {
    /// Whether every path was tracked to an end that is a solution or at infinity: then
    /// `solutions` are all the isolated nonsingular solutions of the target.
    pub fn complete(&self) -> bool {
        self.failed == 0
    }
}

/// Solves `a·x = b` (dense, `n × n`, row-major) by Gaussian elimination with partial pivoting;
/// `None` when a pivot vanishes. Also returns the smallest pivot magnitude over the largest
/// (the square root of that ratio), a cheap conditioning estimate, and the smallest pivot
/// magnitude itself.
fn lu_solve(mut a: Vec<C>, mut b: Vec<C>, n: usize) -> Option<(Vec<C>, f64, f64)> {
    let (mut small, mut large) = (f64::INFINITY, 0.0f64);
    for k in 0..n {
        let p =
            (k..n).max_by(|&i, &j| a[i * n + k].norm_sqr().total_cmp(&a[j * n + k].norm_sqr()))?;
        let pivot = a[p * n + k];
        let size = pivot.norm_sqr();
        if size == 0.0 || !size.is_finite() {
            return None;
        }
        small = small.min(size);
        large = large.max(size);
        if p != k {
            for j in 0..n {
                a.swap(k * n + j, p * n + j);
            }
            b.swap(k, p);
        }
        for i in k + 1..n {
            let f = a[i * n + k] / pivot;
            if f.norm_sqr() == 0.0 {
                continue;
            }
            for j in k..n {
                let v = a[k * n + j];
                a[i * n + j] -= f * v;
            }
            let v = b[k];
            b[i] -= f * v;
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for j in k + 1..n {
            s -= a[k * n + j] * b[j];
        }
        b[k] = s / a[k * n + k];
    }
    Some((b, (small / large).sqrt(), small.sqrt()))
}

fn norm(v: &[C]) -> f64 {
    v.iter().map(|c| c.norm_sqr()).sum::<f64>().sqrt()
}

/// Where a path ended: its point, `|z₀| / |z|` there, that ratio where `1 − t` first fell
/// below 1e-2, and what was left of `1 − t`.
struct Track {
    z: Vec<C>,
    ratio: f64,
    early: Option<(f64, f64)>,
    left: f64,
    /// Whether the path was tracked to the end, `1 − t = 1e-8` (not stopped by an underflowing
    /// step or as clearly at infinity).
    reached: bool,
    /// Where the path was when `1 − t` first fell below 1e-7 (`1 − t`, `z`).
    last_decade: Option<(f64, Vec<C>)>,
    /// Where the path was when `1 − t` first fell below 1e-2 (`1 − t`, `z`): the Cauchy
    /// endgame's start.
    endgame: Option<(f64, Vec<C>)>,
    /// Where the path was at each of the [`CHECKPOINTS`] it reached, in order.
    marks: Vec<Vec<C>>,
}

/// The values of `t` every path is tracked through exactly (its steps shortened to land on
/// them), where the paths are compared ([`meetings`]): with a generic `γ` distinct paths never
/// meet for `t < 1`, so two paths at the same point there are one path twice — one of them
/// jumped. Dense enough that a path stopped early (at infinity, or lost) has been compared
/// shortly before; none beyond `1 − t = 10⁻²`, where the paths to one singular end or to one
/// point at infinity draw together (as a power of `1 − t`: two paths of the sphere of 6
/// points, seed 6, to infinity were 1.5e-4 of their size apart at `1 − t = 10⁻²` and 1.5e-6
/// at 10⁻³).
const CHECKPOINTS: [f64; 10] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.99];

/// How close (relative to the size, on the chart) two paths at a checkpoint are to be
/// compared more closely: each corrected by Newton at that `t` to the rounding, then the same
/// point when within [`SAME_POINT`] of each other. The corrector leaves a point within 1e-9
/// of the size of its path; distinct paths stay much further apart, and each Newton
/// converges to its own.
const NEAR: f64 = 1e-6;

/// Two points corrected to the rounding at one `t` are on one path within this (relative to
/// the size).
const SAME_POINT: f64 = 1e-11;

/// The largest step a path is first tracked with (a tenth, then a hundredth of it when it is
/// tracked again).
const FIRST_STEP: f64 = 0.1;

/// How far the corrector's first Newton step may reach, a fraction of the size (a larger
/// correction may land on another path).
const REACH: f64 = 0.05;

/// How paths are tracked: [`Tracking::DEFAULT`] in [`solve`]; the tests switch the comparison
/// off and force jumps.
#[derive(Clone, Copy, Debug)]
struct Tracking {
    /// Whether the paths are compared at the [`CHECKPOINTS`].
    compare: bool,
    /// A jump forced, for the tests: `(k, l, always)` tracks path `k` from path `l`'s start
    /// on its first tracking (with `always`, also when tracked again), as if it had jumped to
    /// path `l` at once.
    divert: Option<(usize, usize, bool)>,
    /// Whether the ends past the last checkpoint are accounted for by the endgame's cycles
    /// ([`account`]).
    account: bool,
    /// A jump forced past the last checkpoint, for the tests: `(k, l, always)` tracks path
    /// `k` to the last checkpoint, then on from where path `l` was there (with `always`, also
    /// when tracked again).
    late: Option<(usize, usize, bool)>,
}

impl Tracking {
    const DEFAULT: Tracking = Tracking { compare: true, divert: None, account: true, late: None };
}

impl Track {
    /// Whether a path that did not end at a nonsingular solution goes to infinity: `z₀`
    /// negligible, or small (below 1e-2 of `z`) and shrinking like a positive power of
    /// `1 − t` since `1 − t` fell below 1e-2 (at least five-fold, over at least a halving of
    /// `1 − t`), where a path to a finite end keeps it.
    fn at_infinity(&self) -> bool {
        if self.ratio <= 1e-10 {
            return true;
        }
        let Some((left0, ratio0)) = self.early else { return false };
        self.left <= 0.5 * left0 && self.ratio < 1e-2 && self.ratio <= 0.2 * ratio0
    }
}

/// The homotopy in projective coordinates `z = (z₀, z₁ … z_n)` on the chart `a·z = 1`.
struct Homotopy<'a> {
    target: &'a Target<'a>,
    gamma: C,
    chart: Vec<C>,
    /// The two-homogeneous start system: per equation, its linear factors, each with its
    /// coefficients over `z` (`z₀` first); `None`: `z_i^d − z₀^d`.
    factors: Option<Vec<Vec<Vec<C>>>>,
}

/// The degree used to homogenise equation `i`.
fn hom_degree(h: &Homotopy<'_>, i: usize) -> i32 {
    match (&h.factors, &h.target.groups) {
        (Some(_), Some((_, b))) => (b[i][0] + b[i][1]).max(h.target.degrees[i]) as i32,
        _ => h.target.degrees[i] as i32,
    }
}

impl Homotopy<'_> {
    /// `H(z, t)` (n values, then the chart's), `H_z` ((n+1)², row-major) and `H_t` (n+1).
    fn eval(&self, z: &[C], t: C) -> (Vec<C>, Vec<C>, Vec<C>) {
        let n = self.target.n;
        let m = n + 1;
        let z0 = z[0];
        let x: Vec<C> = z[1..].iter().map(|v| v / z0).collect();
        let (f, jf) = (self.target.eval)(&x);
        let (mut h, mut hz, mut ht) =
            (vec![C::new(0.0, 0.0); m], vec![C::new(0.0, 0.0); m * m], vec![C::new(0.0, 0.0); m]);
        let (s, u) = ((C::new(1.0, 0.0) - t) * self.gamma, t);
        for i in 0..n {
            let d = hom_degree(self, i);
            // Homogenised target: z₀^d F(z/z₀); ∂/∂z_j = z₀^{d−1} ∂F/∂x_j;
            // ∂/∂z₀ = d z₀^{d−1} F − z₀^{d−2} Σ_j z_j ∂F/∂x_j.
            let zd1 = z0.powi(d - 1);
            let fh = zd1 * z0 * f[i];
            let mut euler = C::new(0.0, 0.0);
            for j in 0..n {
                euler += z[1 + j] * jf[i * n + j];
            }
            let dfh0 = C::new(d as f64, 0.0) * zd1 * f[i] - zd1 / z0 * euler;
            // Homogenised start and its gradient over z.
            let (gh, dg) = match &self.factors {
                None => {
                    let mut dg = vec![C::new(0.0, 0.0); m];
                    dg[0] = -C::new(d as f64, 0.0) * z0.powi(d - 1);
                    dg[1 + i] = C::new(d as f64, 0.0) * z[1 + i].powi(d - 1);
                    (z[1 + i].powi(d) - z0.powi(d), dg)
                }
                Some(factors) => {
                    let f = &factors[i];
                    let values: Vec<C> =
                        f.iter().map(|c| c.iter().zip(z).map(|(a, b)| a * b).sum()).collect();
                    let mut dg = vec![C::new(0.0, 0.0); m];
                    for (k, c) in f.iter().enumerate() {
                        let others: C = (0..f.len())
                            .filter(|&l| l != k)
                            .map(|l| values[l])
                            .fold(C::new(1.0, 0.0), |a, b| a * b);
                        for (j, a) in c.iter().enumerate() {
                            dg[j] += a * others;
                        }
                    }
                    (values.iter().fold(C::new(1.0, 0.0), |a, b| a * b), dg)
                }
            };
            h[i] = s * gh + u * fh;
            ht[i] = fh - self.gamma * gh;
            hz[i * m] = s * dg[0] + u * dfh0;
            for j in 0..n {
                hz[i * m + 1 + j] = u * zd1 * jf[i * n + j] + s * dg[1 + j];
            }
        }
        let mut chart = C::new(-1.0, 0.0);
        for (j, a) in self.chart.iter().enumerate() {
            chart += a * z[j];
            hz[n * m + j] = *a;
        }
        h[n] = chart;
        (h, hz, ht)
    }

    /// `dz/dt` at `(z, t)`.
    fn tangent(&self, z: &[C], t: C) -> Option<Vec<C>> {
        let m = self.target.n + 1;
        let (_, hz, ht) = self.eval(z, t);
        let rhs: Vec<C> = ht.iter().map(|v| -v).collect();
        lu_solve(hz, rhs, m).map(|(d, _, _)| d)
    }

    /// Newton at fixed `t` from `z`: the corrected point when it converges in at most three
    /// steps, each at most a quarter of the one before, the first small beside `z` (a larger
    /// correction may land on another path).
    fn correct(&self, z: &[C], t: C) -> Option<Vec<C>> {
        let m = self.target.n + 1;
        let mut z = z.to_vec();
        let size = norm(&z);
        let reach = REACH * size;
        let mut last = reach;
        for _ in 0..3 {
            let (h, hz, _) = self.eval(&z, t);
            let (dz, _, _) = lu_solve(hz, h, m)?;
            let step = norm(&dz);
            if !(step <= 0.25 * last) && last != reach || !(step <= last) {
                return None;
            }
            for (a, d) in z.iter_mut().zip(&dz) {
                *a -= d;
            }
            if step <= 1e-11 * size {
                return Some(z);
            }
            last = step;
        }
        (last <= 1e-9 * size).then_some(z)
    }

    /// Newton at fixed `t` from `z` (a point the corrector left on a path) until its steps
    /// reach the rounding (below 1e-14 of the size, or no longer shrinking; at most eight):
    /// the path's point at `t` to the last digits, to tell two close paths apart.
    fn polish(&self, z: &[C], t: f64) -> Vec<C> {
        let m = self.target.n + 1;
        let mut z = z.to_vec();
        let mut last = f64::INFINITY;
        for _ in 0..8 {
            let (h, hz, _) = self.eval(&z, C::new(t, 0.0));
            let Some((dz, _, _)) = lu_solve(hz, h, m) else { break };
            let step = norm(&dz);
            if step.is_nan() || step >= last {
                break;
            }
            for (a, d) in z.iter_mut().zip(&dz) {
                *a -= d;
            }
            if step <= 1e-14 * norm(&z) {
                break;
            }
            last = step;
        }
        z
    }

    /// Tracks the path from `z` at `t = 0` towards `t = 1`, steps at most `max_step`: they
    /// grow after successes and halve after failures, and near the end they are at most a
    /// half of what is left of `1 − t` (geometric in `−ln(1 − t)`, where the paths to
    /// singular ends slow down). The path stops at `1 − t = 1e-8` (what is left to a
    /// nonsingular end, Newton on the target does), where its step underflows, and where it
    /// is clearly going to infinity ([`Track::at_infinity`]'s test, with margins).
    fn track(&self, z: Vec<C>, max_step: f64) -> Track {
        self.track_from(z, Vec::new(), max_step, 0.5)
    }

    /// [`Homotopy::track`] from the last of the [`CHECKPOINTS`] (`marks`: the path's points
    /// at all of them; `z` the last), its steps at most `fraction` of what is left of `1 − t`
    /// (`track`'s: a half): the path tracked again past the last comparison, more finely.
    fn resume(&self, marks: &[Vec<C>], fraction: f64) -> Option<Track> {
        let z = marks.get(CHECKPOINTS.len() - 1)?.clone();
        Some(self.track_from(z, marks.to_vec(), FIRST_STEP, fraction))
    }

    /// Tracks from `z` at the `t` of the last of `marks` (its checkpoints so far; `t = 0` when
    /// there are none): see [`Homotopy::track`], with steps at most `fraction` of what is left
    /// of `1 − t`.
    fn track_from(
        &self,
        mut z: Vec<C>,
        mut marks: Vec<Vec<C>>,
        max_step: f64,
        fraction: f64,
    ) -> Track {
        let mut t = marks.len().checked_sub(1).map_or(0.0, |c| CHECKPOINTS[c]);
        let mut h = max_step.min(0.02);
        let mut successes = 0;
        let ratio = |z: &[C]| z[0].norm() / norm(z);
        // (Resumed at the last checkpoint, 0.99: the endgame starts there.)
        let mut early: Option<(f64, f64)> =
            (marks.len() == CHECKPOINTS.len()).then(|| (1.0 - t, ratio(&z)));
        let mut endgame: Option<(f64, Vec<C>)> = early.map(|(left, _)| (left, z.clone()));
        let mut last_decade: Option<(f64, Vec<C>)> = None;
        for _ in 0..2_000 {
            let left = 1.0 - t;
            if left <= 1e-8 {
                break;
            }
            let mut dt = h.min(fraction * left);
            // Onto the next checkpoint rather than past it (at exactly its `t`).
            let mark = CHECKPOINTS.get(marks.len()).filter(|&&c| t + dt >= c);
            if let Some(&c) = mark {
                dt = c - t;
            }
            match self.rk4(&z, t, dt).and_then(|p| self.correct(&p, C::new(t + dt, 0.0))) {
                Some(next) if next.iter().all(|c| c.re.is_finite() && c.im.is_finite()) => {
                    z = next;
                    match mark {
                        Some(&c) => {
                            t = c;
                            marks.push(z.clone());
                        }
                        None => t += dt,
                    }
                    successes += 1;
                    if successes >= 3 {
                        h = (h * 2.0).min(max_step);
                        successes = 0;
                    }
                    // (The last checkpoint, 0.99, counts: `1 − 0.99` rounds above 1e-2.)
                    if early.is_none() && 1.0 - t <= 1e-2 * (1.0 + 1e-9) {
                        early = Some((1.0 - t, ratio(&z)));
                        endgame = Some((1.0 - t, z.clone()));
                    }
                    if last_decade.is_none() && 1.0 - t <= 1e-7 {
                        last_decade = Some((1.0 - t, z.clone()));
                    }
                    // Clearly at infinity: z₀ negligible, or shrunk twenty-fold since
                    // `1 − t` fell below 1e-2 and already below 1e-3 of z.
                    let r = ratio(&z);
                    if r < 1e-10
                        || early
                            .is_some_and(|(_, r0)| 1.0 - t <= 1e-4 && r < 1e-3 && r <= r0 / 20.0)
                    {
                        break;
                    }
                }
                _ => {
                    h /= 2.0;
                    successes = 0;
                    if h < 1e-6 * left {
                        break;
                    }
                }
            }
        }
        let left = 1.0 - t;
        Track {
            ratio: ratio(&z),
            early,
            left,
            reached: left <= 1e-8,
            last_decade,
            z,
            endgame,
            marks,
        }
    }

    fn rk4(&self, z: &[C], t: f64, dt: f64) -> Option<Vec<C>> {
        let add = |z: &[C], k: &[C], s: f64| -> Vec<C> {
            z.iter().zip(k).map(|(a, b)| a + b * s).collect()
        };
        let at = |t: f64| C::new(t, 0.0);
        let k1 = self.tangent(z, at(t))?;
        let k2 = self.tangent(&add(z, &k1, dt / 2.0), at(t + dt / 2.0))?;
        let k3 = self.tangent(&add(z, &k2, dt / 2.0), at(t + dt / 2.0))?;
        let k4 = self.tangent(&add(z, &k3, dt), at(t + dt))?;
        Some(
            (0..z.len())
                .map(|i| z[i] + (k1[i] + k2[i] * 2.0 + k3[i] * 2.0 + k4[i]) * (dt / 6.0))
                .collect(),
        )
    }
}

impl Homotopy<'_> {
    /// The Cauchy endgame: from `z` at `1 − t = radius` (real), the path is tracked around
    /// the circle `1 − t = radius·e^{iθ}` until it closes (after `c` turns, `c` at most
    /// [`MAX_WINDING`]: the cycle number of its end); by Cauchy's integral formula the end at
    /// `t = 1` is the mean of the path over those turns, sampled at equally spaced angles
    /// (the trapezoidal rule, exponentially accurate on a periodic function). This finds the
    /// end of a path to a singular solution, where the tracker cannot go. `None` when the
    /// path does not close; else the end and where the first turn took the path (back at
    /// `1 − t = radius`: its own point when `c` is 1, else the point of the next path of its
    /// cycle).
    fn cauchy(&self, z: &[C], radius: f64) -> Option<(Vec<C>, Vec<C>)> {
        let start = z.to_vec();
        let mut z = start.clone();
        let mut sum = vec![C::new(0.0, 0.0); z.len()];
        let mut first = None;
        for turn in 1..=MAX_WINDING {
            let (to, part) = self.turn(&z, radius, SAMPLES)?;
            for (s, v) in sum.iter_mut().zip(&part) {
                *s += v;
            }
            z = to;
            let first = first.get_or_insert_with(|| z.clone());
            if closes(&z, &start) {
                let count = (turn * SAMPLES) as f64;
                return Some((sum.iter().map(|s| s / count).collect(), first.clone()));
            }
        }
        None
    }

    /// One turn of the Cauchy endgame's loop from `z` at `1 − t = radius`, in `samples` equal
    /// arcs: where it ends (at `1 − t = radius` again) and the sum of the path's points at the
    /// start of each arc.
    fn turn(&self, z: &[C], radius: f64, samples: usize) -> Option<(Vec<C>, Vec<C>)> {
        let mut z = z.to_vec();
        let mut sum = vec![C::new(0.0, 0.0); z.len()];
        let at = |theta: f64| C::new(1.0, 0.0) - C::new(0.0, theta).exp() * radius;
        for k in 0..samples {
            for (s, v) in sum.iter_mut().zip(&z) {
                *s += v;
            }
            let from = std::f64::consts::TAU * k as f64 / samples as f64;
            z = self.arc(&z, from, std::f64::consts::TAU / samples as f64, &at)?;
        }
        Some((z, sum))
    }

    /// Tracks from `z` at angle `from` along the circle to `from + step`, in substeps that
    /// halve until each corrects.
    fn arc(&self, z: &[C], from: f64, step: f64, at: &dyn Fn(f64) -> C) -> Option<Vec<C>> {
        let mut z = z.to_vec();
        let (mut theta, end) = (from, from + step);
        let mut h = step;
        while theta < end - 1e-15 {
            let dt = h.min(end - theta);
            // dz/dθ = dz/dt · dt/dθ, with dt/dθ = −i·radius·e^{iθ} = i·(t − 1).
            let deriv = |z: &[C], theta: f64| -> Option<Vec<C>> {
                let t = at(theta);
                let dtd = C::new(0.0, 1.0) * (t - C::new(1.0, 0.0));
                self.tangent(z, t).map(|d| d.iter().map(|v| v * dtd).collect())
            };
            let add = |z: &[C], k: &[C], s: f64| -> Vec<C> {
                z.iter().zip(k).map(|(a, b)| a + b * s).collect()
            };
            let predicted = (|| {
                let k1 = deriv(&z, theta)?;
                let k2 = deriv(&add(&z, &k1, dt / 2.0), theta + dt / 2.0)?;
                let k3 = deriv(&add(&z, &k2, dt / 2.0), theta + dt / 2.0)?;
                let k4 = deriv(&add(&z, &k3, dt), theta + dt)?;
                Some(
                    (0..z.len())
                        .map(|i| z[i] + (k1[i] + k2[i] * 2.0 + k3[i] * 2.0 + k4[i]) * (dt / 6.0))
                        .collect::<Vec<C>>(),
                )
            })();
            match predicted.and_then(|p| self.correct(&p, at(theta + dt))) {
                Some(next) => {
                    z = next;
                    theta += dt;
                }
                None => {
                    h /= 2.0;
                    if h < step / 1024.0 {
                        return None;
                    }
                }
            }
        }
        Some(z)
    }
}

/// The most turns the Cauchy endgame makes around a path's end (its cycle number).
const MAX_WINDING: usize = 8;

/// The points per turn of the Cauchy endgame.
const SAMPLES: usize = 64;

/// The points per turn of a loop that accounts for a path's end ([`account`]).
const TURN_SAMPLES: usize = 16;

/// Whether a turn of the Cauchy endgame's loop from `start` that came back at `z` closed.
fn closes(z: &[C], start: &[C]) -> bool {
    same_within(z, start, 1e-6)
}

/// Newton on the target from `x`: the solution and whether it is nonsingular there — Newton
/// converges quadratically to a nonsingular solution, only linearly to a singular one, and the
/// pivots of the Jacobian stay apart. Quadratic convergence shows within a dozen steps as a
/// step below 1e-12 of the size, or, where the rounding of the values (of order `ε·|x|²` over
/// a pivot: a large or ill-conditioned solution) keeps the steps above that, as a step below
/// 1e-9 of the size at most a hundredth of the step before (linear convergence to a singular
/// solution halves its steps, a third for a triple root).
fn refine(target: &Target<'_>, x: &[C]) -> Option<(Vec<C>, bool)> {
    let n = target.n;
    let mut x = x.to_vec();
    let mut converged = false;
    let mut last = f64::INFINITY;
    for _ in 0..12 {
        let (f, j) = (target.eval)(&x);
        let (dx, _, _) = lu_solve(j, f, n)?;
        for (a, d) in x.iter_mut().zip(&dx) {
            *a -= d;
        }
        let (step, size) = (norm(&dx), 1.0 + norm(&x));
        if step <= 1e-12 * size || (step <= 1e-9 * size && step <= 1e-2 * last) {
            converged = true;
            break;
        }
        last = step;
    }
    let (f, j) = (target.eval)(&x);
    let scale = 1.0 + norm(&x);
    if !(norm(&f) <= 1e-9 * scale.powi(2)) {
        return None;
    }
    // The target is scaled to order 1: a pivot below 1e-7 is a vanishing one (a double root in
    // one unknown has no other pivot to compare it with).
    let (_, conditioning, smallest) = lu_solve(j, f, n)?;
    Some((x, converged && conditioning > 1e-10 && smallest > 1e-7))
}

/// What a path ended at.
#[derive(Clone, Debug)]
enum End {
    Solution(Vec<C>),
    /// A finite solution where the target's Jacobian is singular (found by the endgame): a
    /// path decided, not one of the isolated nonsingular solutions.
    Singular,
    Infinity,
    Failed,
}

/// What a path ended at, and, when the Cauchy endgame decided it, where the endgame's first
/// turn took it.
fn end_of(homotopy: &Homotopy<'_>, track: &Track) -> (End, Option<Vec<C>>) {
    let target = homotopy.target;
    if track.ratio <= 1e-10 {
        return (End::Infinity, None);
    }
    let end = &track.z;
    let x: Vec<C> = end[1..].iter().map(|v| v / end[0]).collect();
    match refine(target, &x) {
        // (Near the end of its path: Newton from the end of a path to infinity may reach
        // any solution.)
        Some((y, true)) if same_within(&x, &y, 1e-4) => (End::Solution(y), None),
        Some((y, true)) if approaches(target, track, &y) => (End::Solution(y), None),
        // A path stopped short of the end whose `z₀` shrinks is taken to infinity; one tracked
        // to the end with `z₀` not negligible is at a finite point that Newton did not confirm
        // from there (a large or ill-conditioned solution, which the path approaches slowly —
        // as `z₀` shrinks towards its finite value — or a singular one): the endgame decides.
        _ if !track.reached && track.at_infinity() => (End::Infinity, None),
        _ => match &track.endgame {
            Some((radius, z)) => endgame(homotopy, z, *radius),
            None => (End::Failed, None),
        },
    }
}

/// Whether a path tracked to the end approaches the nonsingular solution `y` that Newton on the
/// target reached from its end, though not yet within 1e-4 of it (a large or ill-conditioned
/// solution: near `t = 1` the path is `y + O(1 − t)` with a large constant): within 1e-2 of it
/// at the end, and its distance to `y` shrinking in proportion to `1 − t` over the last decade
/// (within a factor two; a path to a singular end, `y + O((1 − t)^{1/c})`, shrinks slower by
/// the cycle number `c`), where Newton from the start of that decade reaches `y` too.
fn approaches(target: &Target<'_>, track: &Track, y: &[C]) -> bool {
    let affine = |z: &[C]| -> Vec<C> { z[1..].iter().map(|v| v / z[0]).collect() };
    let Some((before, z)) = &track.last_decade else { return false };
    if !track.reached || track.left <= 0.0 {
        return false;
    }
    let distance = |x: &[C]| x.iter().zip(y).map(|(a, b)| (a - b).norm_sqr()).sum::<f64>().sqrt();
    let (x, earlier) = (affine(&track.z), affine(z));
    let (now, then) = (distance(&x), distance(&earlier));
    now <= 1e-2 * (1.0 + norm(y))
        && then >= 0.5 * (before / track.left) * now
        && then <= 2.0 * (before / track.left) * now
        && refine(target, &earlier).is_some_and(|(w, nonsingular)| nonsingular && same(&w, y))
}

/// The end of a path the tracker could not decide, by the Cauchy endgame from where it was at
/// `1 − t = radius` ([`classify`]; failed when the loop does not close), and where the
/// loop's first turn took it.
fn endgame(homotopy: &Homotopy<'_>, z: &[C], radius: f64) -> (End, Option<Vec<C>>) {
    match homotopy.cauchy(z, radius) {
        Some((e, first)) => (classify(homotopy.target, &e), Some(first)),
        None => (End::Failed, None),
    }
}

/// What the end `e` (on the chart) the Cauchy endgame found is: at infinity when `z₀`
/// vanishes there, a nonsingular solution when Newton on the target converges quadratically
/// from it, a singular one when the target vanishes there; failed otherwise.
fn classify(target: &Target<'_>, e: &[C]) -> End {
    let size = norm(e);
    if e[0].norm() <= 1e-8 * size {
        return End::Infinity;
    }
    let x: Vec<C> = e[1..].iter().map(|v| v / e[0]).collect();
    if let Some((y, true)) = refine(target, &x)
        && same_within(&x, &y, 1e-4)
    {
        return End::Solution(y);
    }
    let (f, _) = (target.eval)(&x);
    if norm(&f) <= 1e-6 * (1.0 + norm(&x)).powi(2) { End::Singular } else { End::Failed }
}

/// The paths whose end is a nonsingular solution another path also ended at, in order.
fn collisions(results: &[End]) -> Vec<usize> {
    let solution = |k: usize| match &results[k] {
        End::Solution(x) => Some(x),
        _ => None,
    };
    (0..results.len())
        .filter(|&k| {
            solution(k).is_some_and(|x| {
                (0..results.len()).any(|l| l != k && solution(l).is_some_and(|y| same(x, y)))
            })
        })
        .collect()
}

/// Whether two solutions are the same (relative to their size).
fn same(a: &[C], b: &[C]) -> bool {
    same_within(a, b, 1e-7)
}

fn same_within(a: &[C], b: &[C], tolerance: f64) -> bool {
    let d = a.iter().zip(b).map(|(p, q)| (p - q).norm_sqr()).sum::<f64>().sqrt();
    d <= tolerance * (1.0 + norm(a))
}

/// The start points of the total-degree start system (`z₀ = 1`, then roots of unity);
/// `None` beyond [`MAX_PATHS`].
fn total_degree_starts(target: &Target<'_>) -> Option<Vec<Vec<C>>> {
    let mut paths: usize = 1;
    for &d in &target.degrees {
        paths = paths.checked_mul(d.max(1) as usize).filter(|&p| p <= MAX_PATHS)?;
    }
    let mut index = vec![0u32; target.n];
    let mut starts = Vec::with_capacity(paths);
    for _ in 0..paths {
        let mut z = vec![C::new(1.0, 0.0)];
        for (i, &k) in index.iter().enumerate() {
            let d = target.degrees[i].max(1) as f64;
            let a = std::f64::consts::TAU * f64::from(k) / d;
            z.push(C::new(a.cos(), a.sin()));
        }
        starts.push(z);
        for (i, k) in index.iter_mut().enumerate() {
            *k += 1;
            if *k < target.degrees[i].max(1) {
                break;
            }
            *k = 0;
        }
    }
    Some(starts)
}

/// The start points of a start system of products of linear factors (`z₀ = 1`): one factor of
/// each equation vanishes, as many from the first group's factors as it has unknowns; each
/// choice is two linear systems. `None` beyond [`MAX_PATHS`] (or for a singular choice, which
/// random factors make improbable).
fn product_starts(factors: &[Vec<Vec<C>>], second: &[bool]) -> Option<Vec<Vec<C>>> {
    let n = second.len();
    let in_first = second.iter().filter(|s| !**s).count();
    // Depth first over the equations: (equation, factor) pairs chosen so far.
    let mut starts = Vec::new();
    let mut chosen: Vec<usize> = Vec::new();
    let group = |i: usize, k: usize| -> usize {
        // The factor's group: where its coefficients are nonzero.
        let c = &factors[i][k];
        usize::from((0..n).any(|j| second[j] && c[1 + j] != C::new(0.0, 0.0)))
    };
    let mut next = 0usize;
    loop {
        let depth = chosen.len();
        if depth == factors.len() {
            // Solve the two linear systems.
            let mut z = vec![C::new(1.0, 0.0); n + 1];
            for g in 0..2 {
                let vars: Vec<usize> = (0..n).filter(|&j| usize::from(second[j]) == g).collect();
                let rows: Vec<&Vec<C>> = chosen
                    .iter()
                    .enumerate()
                    .filter(|(i, k)| group(*i, **k) == g)
                    .map(|(i, k)| &factors[i][*k])
                    .collect();
                let k = vars.len();
                let a: Vec<C> = rows.iter().flat_map(|c| vars.iter().map(|&j| c[1 + j])).collect();
                let b: Vec<C> = rows.iter().map(|c| -c[0]).collect();
                let (x, _, _) = lu_solve(a, b, k)?;
                for (v, &j) in x.iter().zip(&vars) {
                    z[1 + j] = *v;
                }
            }
            starts.push(z);
            if starts.len() > MAX_PATHS {
                return None;
            }
            next = chosen.pop().map_or(usize::MAX, |k| k + 1);
        } else if next < factors[depth].len() {
            let firsts = chosen.iter().enumerate().filter(|(i, k)| group(*i, **k) == 0).count();
            let seconds = depth - firsts;
            let g = group(depth, next);
            if (g == 0 && firsts < in_first) || (g == 1 && seconds < n - in_first) {
                chosen.push(next);
                next = 0;
            } else {
                next += 1;
            }
        } else {
            match chosen.pop() {
                Some(k) => next = k + 1,
                None => break,
            }
        }
        if next == usize::MAX {
            break;
        }
    }
    Some(starts)
}

/// The paths of `target`'s homotopy: the solutions of its start system — the total degree
/// `Π d_i`, or the two-homogeneous Bézout number where [`Target::groups`] gives fewer —
/// saturating at `usize::MAX`. An upper bound on its isolated solutions; [`solve`] tracks
/// them when there are at most its `max_paths`.
pub fn path_count(target: &Target<'_>) -> usize {
    start_system(target).1
}

/// The two-homogeneous structure of the start system where it has fewer paths than the total
/// degree (`None`: the total degree's), and the paths.
fn start_system<'t>(target: &'t Target<'_>) -> (Option<&'t (Vec<bool>, Vec<[u32; 2]>)>, usize) {
    let total = target.degrees.iter().fold(1usize, |p, &d| p.saturating_mul(d.max(1) as usize));
    let Some(groups @ (second, bidegrees)) = target.groups.as_ref() else { return (None, total) };
    let in_first = second.iter().filter(|s| !**s).count();
    // Paths: the ways to choose one factor per equation, `in_first` of the first group.
    let mut ways = vec![0usize; in_first + 1];
    ways[0] = 1;
    for b in bidegrees {
        for k in (0..=in_first).rev() {
            let from_first = if k > 0 { ways[k - 1].saturating_mul(b[0] as usize) } else { 0 };
            ways[k] = ways[k].saturating_mul(b[1] as usize).saturating_add(from_first);
        }
    }
    if ways[in_first] < total { (Some(groups), ways[in_first]) } else { (None, total) }
}

/// Every isolated nonsingular solution of `target` (see the module documentation), with
/// random choices (`γ`, the chart) from `seed`. `None` when the system has more than
/// `max_paths` (or [`MAX_PATHS`]) paths.
pub fn solve(target: &Target<'_>, seed: u64, max_paths: usize) -> Option<Ends> {
    solve_tracking(target, seed, max_paths, Tracking::DEFAULT).map(|(ends, _)| ends)
}

/// [`solve`] with the paths tracked as `tracking` says; with each path's cycle number where
/// [`account`] found it.
fn solve_tracking(
    target: &Target<'_>,
    seed: u64,
    max_paths: usize,
    tracking: Tracking,
) -> Option<(Ends, Vec<Option<usize>>)> {
    let n = target.n;
    let mut rng = SplitMix64::new(seed);
    let mut unit = || {
        let a = std::f64::consts::TAU * rng.unit_f64();
        C::new(a.cos(), a.sin())
    };
    let gamma = unit();
    let chart: Vec<C> = (0..=n).map(|_| unit()).collect();
    let (groups, count) = start_system(target);
    if count > max_paths.min(MAX_PATHS) {
        return None;
    }
    let (factors, starts) =
        match groups {
            None => (None, total_degree_starts(target)?),
            Some((second, bidegrees)) => {
                let mut factors: Vec<Vec<Vec<C>>> = Vec::new();
                for b in bidegrees {
                    let mut f = Vec::new();
                    for (group, &count) in b.iter().enumerate() {
                        for _ in 0..count {
                            let mut c = vec![C::new(-1.0, 0.0)];
                            c.extend(second.iter().map(|&s| {
                                if s == (group == 1) { unit() } else { C::new(0.0, 0.0) }
                            }));
                            f.push(c);
                        }
                    }
                    factors.push(f);
                }
                let starts = product_starts(&factors, second)?;
                (Some(factors), starts)
            }
        };
    let paths = starts.len();
    if paths > max_paths {
        return None;
    }
    let homotopy = Homotopy { target, gamma, chart: chart.clone(), factors };
    let mut ends = Ends { paths, ..Ends::default() };
    // On the chart.
    let starts: Vec<Vec<C>> = starts
        .into_iter()
        .map(|z| {
            let s: C = chart.iter().zip(&z).map(|(a, b)| a * b).sum();
            z.iter().map(|v| v / s).collect()
        })
        .collect();
    // (The test's jump after the last checkpoint: path `k` tracked to it, then on from where
    // path `l` was there — as if it had jumped onto `l` right after the comparison.)
    let late = |k: usize, again: bool| match tracking.late {
        Some((from, to, always)) if k == from && (always || !again) => Some(to),
        _ => None,
    };
    let splice = |own: Track, other: Track| -> Track {
        if own.marks.len() == CHECKPOINTS.len() && other.marks.len() == CHECKPOINTS.len() {
            Track { marks: own.marks, early: own.early, endgame: own.endgame, ..other }
        } else {
            own
        }
    };
    let finish = |track: Track| -> Run {
        let (end, turn) = end_of(&homotopy, &track);
        Run { end, marks: track.marks, turn }
    };
    let run = |k: usize, step: f64| -> Run {
        let z = match tracking.divert {
            Some((from, to, always)) if k == from && (always || step == FIRST_STEP) => &starts[to],
            _ => &starts[k],
        };
        let mut track = homotopy.track(z.clone(), step);
        if let Some(l) = late(k, step != FIRST_STEP) {
            track = splice(track, homotopy.track(starts[l].clone(), step));
        }
        finish(track)
    };
    // A path tracked again from the last checkpoint, its steps at most `fraction` of what is
    // left of `1 − t`.
    let resume = |k: usize, marks: &[Vec<C>], fraction: f64| -> Option<Run> {
        let mut track = homotopy.resume(marks, fraction)?;
        if let Some(l) = late(k, true) {
            let other = homotopy.track(starts[l].clone(), FIRST_STEP);
            track = splice(track, homotopy.resume(&other.marks, fraction)?);
        }
        Some(finish(track))
    };
    let first = parallel(starts.len(), &|k| run(k, FIRST_STEP))?;
    let (mut results, mut marks, mut turns) = (Vec::new(), Vec::new(), Vec::new());
    for r in first {
        results.push(r.end);
        marks.push(r.marks);
        turns.push(r.turn);
    }
    // The largest step each path was last tracked with.
    let mut steps = vec![FIRST_STEP; starts.len()];
    // A path the tracker lost is tracked again with smaller steps.
    for k in 0..starts.len() {
        if matches!(results[k], End::Failed) && steps[k] > FIRST_STEP / 10.0 {
            let r = run(k, FIRST_STEP / 10.0);
            (results[k], marks[k], turns[k]) = (r.end, r.marks, r.turn);
            steps[k] = FIRST_STEP / 10.0;
        }
    }
    // Two paths at the same point at a checkpoint `t < 1`, or ending at the same nonsingular
    // solution: with a generic γ the paths are disjoint and each such solution ends exactly
    // one, so one of them jumped to the other on the way (which one is not known) — and
    // whatever its own path ended at (a solution, or infinity, or a singular end) may be
    // missing. Every path of such a meeting or collision is tracked again with smaller steps
    // (a tenth, then a hundredth of the first), until none meet; what then still meets
    // counts as failed paths, all but one.
    let compare = |marks: &[Vec<Vec<C>>]| {
        if tracking.compare {
            meetings(marks, &|z, t| homotopy.polish(z, t))
        } else {
            vec![None; marks.len()]
        }
    };
    let mut met = compare(&marks);
    ends.met = met.iter().filter(|p| p.is_some()).count();
    for step in [FIRST_STEP / 10.0, FIRST_STEP / 100.0] {
        let mut suspects: Vec<usize> = collisions(&results);
        suspects.extend((0..starts.len()).filter(|&k| met[k].is_some()));
        suspects.sort_unstable();
        suspects.dedup();
        if suspects.is_empty() {
            break;
        }
        // (A path tracked with this step already would end where it did.)
        for k in suspects {
            if steps[k] <= step {
                continue;
            }
            let r = run(k, step);
            (results[k], marks[k], turns[k]) = (r.end, r.marks, r.turn);
            steps[k] = step;
        }
        met = compare(&marks);
    }
    // What still meets another path: all but one of each meeting fail.
    for (k, other) in met.iter().enumerate() {
        if other.is_some_and(|l| l < k) {
            results[k] = End::Failed;
        }
    }
    // Past the last checkpoint: the ends accounted for by the cycles of the endgame's loops
    // (`account`). A path whose own loop says it ends elsewhere than it was tracked to (it
    // jumped past the last comparison) is tracked again from there with steps a tenth, then
    // a fiftieth of what is left of `1 − t`; a path whose loop comes back at no path's point,
    // or at one another loop also comes back at, has its loop's turn made again with four
    // times the points. What is still not accounted for then counts as failed.
    let mut cycles = vec![None; starts.len()];
    if tracking.account {
        let radius = 1.0 - CHECKPOINTS[CHECKPOINTS.len() - 1];
        let mut turned: Vec<Option<Turned>> = (0..starts.len()).map(|_| None).collect();
        // (Fewer points than the endgame's: a turn only finds where the path comes back, and
        // the end where it closes, made again with the endgame's points when the classification
        // names none; the arcs halve where they must.)
        let mut samples = vec![TURN_SAMPLES; starts.len()];
        let mut rounds = [0.1, 0.02].into_iter();
        for round in 0.. {
            // The turns not yet made: from the endgame's first one where it ran, else made here
            // (on the cores).
            let wanted: Vec<usize> = (0..starts.len())
                .filter(|&k| turned[k].is_none() && candidate(&results[k], &marks[k]))
                .collect();
            let made = parallel(wanted.len(), &|i| {
                let k = wanted[i];
                let mark = &marks[k][CHECKPOINTS.len() - 1];
                if let Some(to) = turns[k].as_ref().filter(|_| samples[k] == TURN_SAMPLES) {
                    // (Where the endgame closed after one turn, its end is the path's.)
                    return Turned::of(to.clone(), mark, |_| results[k].clone());
                }
                let mut made = samples[k];
                loop {
                    let Some((to, sum)) = homotopy.turn(mark, radius, made) else {
                        return Turned::Lost;
                    };
                    let turned = Turned::of(to, mark, |_| {
                        let e: Vec<C> = sum.iter().map(|v| v / made as f64).collect();
                        classify(target, &e)
                    });
                    if !matches!(turned, Turned::Closed(End::Failed)) || made >= SAMPLES {
                        return turned;
                    }
                    made = SAMPLES;
                }
            })?;
            for (k, t) in wanted.into_iter().zip(made) {
                turned[k] = Some(t);
            }
            let accounting =
                account(&results, &marks, &turned, &|z| homotopy.polish(z, 1.0 - radius));
            cycles = accounting.cycles;
            if round == 0 {
                ends.unaccounted = accounting.wrong.len() + accounting.unverified.len();
            }
            if accounting.wrong.is_empty() && accounting.unverified.is_empty() {
                break;
            }
            let Some(fraction) = rounds.next() else {
                for k in accounting.wrong.into_iter().chain(accounting.unverified) {
                    results[k] = End::Failed;
                }
                break;
            };
            for &k in &accounting.wrong {
                let r =
                    resume(k, &marks[k], fraction).map_or((End::Failed, None), |r| (r.end, r.turn));
                (results[k], turns[k]) = r;
                // (The turn from its point is the same: kept.)
            }
            for &k in &accounting.unverified {
                samples[k] *= 4;
                turned[k] = None;
            }
        }
    }
    for result in results {
        match result {
            End::Solution(x) if !ends.solutions.iter().any(|s| same(s, &x)) => {
                ends.solutions.push(x);
            }
            End::Infinity => ends.at_infinity += 1,
            End::Singular => ends.singular += 1,
            End::Solution(_) | End::Failed => ends.failed += 1,
        }
    }
    Some((ends, cycles))
}

/// A path tracked: its end, its points at the [`CHECKPOINTS`] it reached, and, when the
/// Cauchy endgame decided its end, where the endgame's first turn took it.
struct Run {
    end: End,
    marks: Vec<Vec<C>>,
    turn: Option<Vec<C>>,
}

/// `f` on `0..count`, on the machine's cores (none spawned where threads do not exist, nor
/// for fewer than 8 items), each thread a contiguous share; merged in order, so that the
/// result is the same on any number of cores. `None` when a thread failed.
fn parallel<T: Send>(count: usize, f: &(dyn Fn(usize) -> T + Sync)) -> Option<Vec<T>> {
    let threads = std::thread::available_parallelism().map_or(1, std::num::NonZero::get).min(8);
    let share = count.div_ceil(threads.max(1)).max(1);
    let all: Vec<T> = if threads <= 1 || count < 8 {
        (0..count).map(f).collect()
    } else {
        std::thread::scope(|scope| {
            let handles: Vec<_> = (0..count)
                .step_by(share)
                .map(|from| {
                    let chunk = from..(from + share).min(count);
                    scope.spawn(move || chunk.map(f).collect::<Vec<_>>())
                })
                .collect();
            handles.into_iter().flat_map(|h| h.join().unwrap_or_default()).collect()
        })
    };
    (all.len() == count).then_some(all)
}

/// Whether a path's end is to be accounted for by the endgame's cycles: it ended at
/// infinity or at a singular solution, and was compared at every checkpoint (its point at the
/// last is where its loop starts).
fn candidate(end: &End, marks: &[Vec<C>]) -> bool {
    matches!(end, End::Infinity | End::Singular) && marks.len() == CHECKPOINTS.len()
}

/// One turn of the endgame's loop from a path's point at the last checkpoint.
#[derive(Clone, Debug)]
enum Turned {
    /// Back at the start: cycle number 1, and the loop's end (the mean of the turn).
    Closed(End),
    /// Elsewhere (cycle number at least 2): at the next path of its cycle, if that is where
    /// it is.
    At(Vec<C>),
    /// The loop could not be tracked.
    Lost,
}

impl Turned {
    fn of(to: Vec<C>, start: &[C], end: impl FnOnce(&[C]) -> End) -> Turned {
        if closes(&to, start) { Turned::Closed(end(&to)) } else { Turned::At(to) }
    }
}

/// What the cycles of the endgame's loops say of the paths' ends.
struct Accounting {
    /// Each path's cycle number, where its turns form a cycle of candidates.
    cycles: Vec<Option<usize>>,
    /// Paths whose loop says they end elsewhere than they were tracked to: a path to
    /// infinity or a singular end whose loop closes after one turn at a nonsingular solution
    /// (it jumped after the last checkpoint).
    wrong: Vec<usize>,
    /// Paths whose loop cannot be accounted for: lost, back at no path's point, or at a point
    /// another path's loop also came back at.
    unverified: Vec<usize>,
}

/// Accounts for the ends of the paths to infinity and to singular solutions by the cycles of
/// the Cauchy endgame's loops (Morgan, Sommese and Wampler's cycle numbers): a path whose end
/// has cycle number `c` is one of `c` paths that one loop around `t = 1` permutes
/// cyclically, all ending at that end. So one turn of the loop from each such path's point at
/// the last checkpoint (`turned[k]`) either closes — `c = 1`, and the turn's mean is the end,
/// which must not be a nonsingular solution, since the path was tracked elsewhere — or comes back at another path's point
/// there, each path's point reached from exactly one (a loop around the circle permutes the
/// paths' points on it, whatever is inside). A path that jumped after the last checkpoint
/// onto a path to infinity or to a singular end fails this: its own loop closes at the
/// nonsingular solution it should have reached. (A turn back at the point of a path tracked
/// to a nonsingular solution is no contradiction: a large or ill-conditioned solution has a
/// branch point of the homotopy within the circle, `|1 − t| < 10⁻²`, and its path and a path
/// to infinity are swapped by the loop — `a_large_ill_conditioned_solution_is_found`; were
/// it a path that jumped onto a solution's, the two would collide there. Such a cycle is left
/// open.) The Cauchy endgame's assumption holds here too: a closing turn's mean is the end
/// when no branch point but `t = 1` is within the circle.
/// `polish` corrects a point at the last checkpoint's `t` to the rounding (the points are
/// compared as at the checkpoints: [`NEAR`], then [`SAME_POINT`]).
fn account(
    results: &[End],
    marks: &[Vec<Vec<C>>],
    turned: &[Option<Turned>],
    polish: &dyn Fn(&[C]) -> Vec<C>,
) -> Accounting {
    let last = CHECKPOINTS.len() - 1;
    let n = results.len();
    let index = Index::new(marks.iter().map(|m| m.get(last)).collect());
    let mut next: Vec<Option<usize>> = vec![None; n];
    let mut wrong = Vec::new();
    let mut unverified = Vec::new();
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
    for k in (0..n).filter(|&k| candidate(&results[k], &marks[k])) {
        match &turned[k] {
            // (Only a nonsingular solution contradicts: a closing turn's mean of a path to
            // infinity whose `z₀` is not yet negligible there is no end the classification
            // names, and a path to infinity or a singular end hides no isolated solution.)
            Some(Turned::Closed(End::Solution(_))) => wrong.push(k),
            Some(Turned::Closed(_)) => next[k] = Some(k),
            Some(Turned::At(to)) => match index.find(to, polish) {
                Some(q) if q != k => {
                    next[k] = Some(q);
                    into[q].push(k);
                }
                _ => unverified.push(k),
            },
            Some(Turned::Lost) | None => unverified.push(k),
        }
    }
    for from in &into {
        if from.len() > 1 {
            unverified.extend(from);
        }
    }
    wrong.sort_unstable();
    wrong.dedup();
    unverified.sort_unstable();
    unverified.dedup();
    unverified.retain(|k| wrong.binary_search(k).is_err());
    // The cycles: from each path, along the turns, back to it.
    let cycles = (0..n)
        .map(|k| {
            let mut at = next[k]?;
            let mut length = 1;
            while at != k {
                at = next[at]?;
                length += 1;
                if length > n {
                    return None;
                }
            }
            Some(length)
        })
        .collect();
    Accounting { cycles, wrong, unverified }
}

/// The paths' points at one checkpoint, sorted by a fixed real linear form so that the
/// points near a given one are found among neighbours: `log P` and the points within the
/// window.
struct Index<'a> {
    points: Vec<Option<&'a Vec<C>>>,
    sorted: Vec<(f64, usize)>,
    weights: Vec<C>,
    window: f64,
}

impl<'a> Index<'a> {
    fn new(points: Vec<Option<&'a Vec<C>>>) -> Index<'a> {
        let width = points.iter().flatten().map(|z| z.len()).max().unwrap_or(0);
        let weights = key_weights(width);
        let mut sorted: Vec<(f64, usize)> = points
            .iter()
            .enumerate()
            .filter_map(|(k, z)| Some((key(z.as_ref()?, &weights), k)))
            .collect();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        let largest = points.iter().flatten().map(|z| norm(z)).fold(0.0f64, f64::max);
        let window = (width as f64).sqrt() * NEAR * (1.0 + largest);
        Index { points, sorted, weights, window }
    }

    /// The first path whose point is `z`'s: within [`NEAR`], and within [`SAME_POINT`] once
    /// both are corrected by `polish`.
    fn find(&self, z: &[C], polish: &dyn Fn(&[C]) -> Vec<C>) -> Option<usize> {
        let k = key(z, &self.weights);
        let from = self.sorted.partition_point(|&(v, _)| v < k - self.window);
        let polished = polish(z);
        self.sorted[from..]
            .iter()
            .take_while(|&&(v, _)| v <= k + self.window)
            .filter_map(|&(_, l)| Some((l, self.points[l]?)))
            .filter(|(_, p)| same_within(z, p, NEAR))
            .find(|(_, p)| same_within(&polished, &polish(p), SAME_POINT))
            .map(|(l, _)| l)
    }
}

/// A fixed real linear form's weights on points of `width` coordinates: distinct
/// irrational-looking weights, `|w| ≤ √width`.
fn key_weights(width: usize) -> Vec<C> {
    (0..width)
        .map(|j| {
            let a = 0.618_033_988_749_895 * (j + 1) as f64;
            C::new((a * 7.0).sin(), (a * 11.0).cos()) * std::f64::consts::FRAC_1_SQRT_2
        })
        .collect()
}

/// The real linear form of a point.
fn key(z: &[C], weights: &[C]) -> f64 {
    z.iter().zip(weights).map(|(a, w)| a * w).sum::<C>().re
}

/// For each path, the first (lowest) other path it is at the same point as at some
/// checkpoint both reached, if any: within [`NEAR`] of each other, and within [`SAME_POINT`]
/// once each is corrected to the rounding by Newton at that `t` (`polish`). `marks[k]`: path
/// `k`'s points at the [`CHECKPOINTS`] it reached, in order. Sorted by a fixed real linear
/// form per checkpoint, so that only neighbours within the tolerance are compared: about
/// `P log P` per checkpoint for `P` paths.
fn meetings(marks: &[Vec<Vec<C>>], polish: &dyn Fn(&[C], f64) -> Vec<C>) -> Vec<Option<usize>> {
    let mut met: Vec<Option<usize>> = vec![None; marks.len()];
    let width = marks.iter().flatten().map(Vec::len).max().unwrap_or(0);
    let weights = key_weights(width);
    let reach = (width as f64).sqrt();
    for c in 0..CHECKPOINTS.len() {
        let mut at: Vec<(f64, usize)> = marks
            .iter()
            .enumerate()
            .filter_map(|(k, m)| Some((key(m.get(c)?, &weights), k)))
            .collect();
        if at.len() < 2 {
            continue;
        }
        let largest = at.iter().map(|&(_, k)| norm(&marks[k][c])).fold(0.0f64, f64::max);
        // Two points within the tolerance have keys within this (|Re w·(a − b)| ≤ |w| |a − b|).
        let window = reach * NEAR * (1.0 + largest);
        at.sort_by(|a, b| a.0.total_cmp(&b.0));
        for i in 0..at.len() {
            for &(key, l) in &at[i + 1..] {
                if key - at[i].0 > window {
                    break;
                }
                let k = at[i].1;
                let (a, b) = (&marks[k][c], &marks[l][c]);
                if same_within(a, b, NEAR)
                    && same_within(
                        &polish(a, CHECKPOINTS[c]),
                        &polish(b, CHECKPOINTS[c]),
                        SAME_POINT,
                    )
                {
                    let (lo, hi) = (k.min(l), k.max(l));
                    met[hi] = Some(met[hi].map_or(lo, |m| m.min(lo)));
                    met[lo] = Some(met[lo].map_or(hi, |m| m.min(hi)));
                }
            }
        }
    }
    met
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(re: f64) -> C {
        C::new(re, 0.0)
    }

    /// Two circles meet in two points; a circle and a line in two; a parabola and a line
    /// whose second intersection is at infinity in one.
    #[test]
    fn small_systems_have_their_bezout_counts() {
        // x² + y² = 25, (x − 6)² + y² = 25: x = 3, y = ±4 (two paths of four at infinity).
        let eval = |x: &[C]| {
            let f = vec![
                x[0] * x[0] + x[1] * x[1] - c(25.0),
                (x[0] - c(6.0)).powi(2) + x[1] * x[1] - c(25.0),
            ];
            let j = vec![x[0] * 2.0, x[1] * 2.0, (x[0] - c(6.0)) * 2.0, x[1] * 2.0];
            (f, j)
        };
        let t = Target { n: 2, degrees: vec![2, 2], eval: &eval, groups: None };
        let ends = solve(&t, 1, MAX_PATHS).unwrap();
        assert_eq!(ends.paths, 4);
        assert!(ends.complete(), "{ends:?}");
        assert_eq!(ends.solutions.len(), 2, "{ends:?}");
        for s in &ends.solutions {
            assert!((s[0] - c(3.0)).norm() < 1e-9 && (s[1].re.abs() - 4.0).abs() < 1e-9, "{s:?}");
        }
        // y = x², y = 2x − 5: x² − 2x + 5 = 0, x = 1 ± 2i (complex, not real).
        let eval = |x: &[C]| {
            (
                vec![x[1] - x[0] * x[0], x[1] - x[0] * 2.0 + c(5.0)],
                vec![-x[0] * 2.0, c(1.0), c(-2.0), c(1.0)],
            )
        };
        let t = Target { n: 2, degrees: vec![2, 1], eval: &eval, groups: None };
        let ends = solve(&t, 2, MAX_PATHS).unwrap();
        assert!(ends.complete());
        assert_eq!(ends.solutions.len(), 2);
        assert!(ends.solutions.iter().all(|s| (s[0].im.abs() - 2.0).abs() < 1e-9));
    }

    /// A bilinear system with a two-homogeneous start: `uv = 1`, `(u − 1)(v − 2) = 3` has two
    /// paths (the total degree has four) and its two solutions, `u² = −1/2`, `v = −2u`.
    #[test]
    fn a_two_homogeneous_start_has_fewer_paths() {
        let eval = |x: &[C]| {
            let f = vec![x[0] * x[1] - c(1.0), (x[0] - c(1.0)) * (x[1] - c(2.0)) - c(3.0)];
            (f, vec![x[1], x[0], x[1] - c(2.0), x[0] - c(1.0)])
        };
        let groups = Some((vec![false, true], vec![[1, 1], [1, 1]]));
        let t = Target { n: 2, degrees: vec![2, 2], eval: &eval, groups };
        let ends = solve(&t, 5, MAX_PATHS).unwrap();
        assert_eq!((ends.paths, ends.solutions.len(), ends.failed), (2, 2, 0), "{ends:?}");
        for s in &ends.solutions {
            assert!((s[0] * s[0] + c(0.5)).norm() < 1e-9 && (s[1] + s[0] * 2.0).norm() < 1e-9);
        }
    }

    /// A double root ends two paths, where the tracker cannot go (the Jacobian vanishes):
    /// the Cauchy endgame goes around it (cycle number 2) and decides both paths — a singular
    /// solution, no nonsingular one missed. With a simple root beside it, that one is found.
    #[test]
    fn the_endgame_decides_the_paths_to_a_double_root() {
        let eval = |x: &[C]| (vec![(x[0] - c(1.0)).powi(2)], vec![(x[0] - c(1.0)) * 2.0]);
        let t = Target { n: 1, degrees: vec![2], eval: &eval, groups: None };
        let ends = solve(&t, 3, MAX_PATHS).unwrap();
        assert_eq!((ends.singular, ends.solutions.len(), ends.failed), (2, 0, 0), "{ends:?}");
        assert!(ends.complete());
        // (x − 1)²(x + 2) = x³ − 3x + 2: the simple root −2 and the double root 1.
        let eval = |x: &[C]| {
            let v = x[0];
            (vec![v * v * v - v * 3.0 + c(2.0)], vec![v * v * 3.0 - c(3.0)])
        };
        let t = Target { n: 1, degrees: vec![3], eval: &eval, groups: None };
        let ends = solve(&t, 5, MAX_PATHS).unwrap();
        assert_eq!((ends.singular, ends.solutions.len(), ends.failed), (2, 1, 0), "{ends:?}");
        assert!((ends.solutions[0][0] + c(2.0)).norm() < 1e-9);
        // And a system whose paths reach a double root in two unknowns: x² = 0, y = x + 1.
        let eval = |x: &[C]| {
            (vec![x[0] * x[0], x[1] - x[0] - c(1.0)], vec![x[0] * 2.0, c(0.0), -c(1.0), c(1.0)])
        };
        let t = Target { n: 2, degrees: vec![2, 1], eval: &eval, groups: None };
        let ends = solve(&t, 6, MAX_PATHS).unwrap();
        assert_eq!((ends.singular, ends.failed), (2, 0), "{ends:?}");
    }

    /// A large, ill-conditioned solution: `x² − y² = k`, `x − y = δ` meet only at `x + y =
    /// k/δ` (the other path goes to infinity), here `x ≈ y ≈ 250` with a Jacobian of
    /// determinant `−2δ`. The path approaches it slowly (still 1e-4 of its size away at
    /// `1 − t = 1e-8`, as `z₀` shrinks towards its finite value) and Newton there stalls at the
    /// rounding of `x²` above a step of 1e-12 of the size: the path must end at the solution,
    /// neither at infinity nor undecided.
    #[test]
    fn a_large_ill_conditioned_solution_is_found() {
        for (k, delta) in [(5.0, 0.01), (2.0, 0.004), (20.0, 0.05)] {
            let eval = move |x: &[C]| {
                let f = vec![x[0] * x[0] - x[1] * x[1] - c(k), x[0] - x[1] - c(delta)];
                (f, vec![x[0] * 2.0, -x[1] * 2.0, c(1.0), c(-1.0)])
            };
            let t = Target { n: 2, degrees: vec![2, 1], eval: &eval, groups: None };
            for seed in 1..=4 {
                let ends = solve(&t, seed, MAX_PATHS).unwrap();
                assert_eq!(
                    (ends.solutions.len(), ends.failed),
                    (1, 0),
                    "{k} {delta} {seed}: {ends:?}"
                );
                let s = &ends.solutions[0];
                let sum = k / delta;
                assert!((s[0] - c((sum + delta) / 2.0)).norm() < 1e-9 * sum, "{s:?}");
            }
        }
    }

    /// Every path whose end is a nonsingular solution another path also reached is in a
    /// collision (all of them, not only the later: which one jumped is not known).
    #[test]
    fn collisions_name_every_path_at_a_shared_end() {
        let at = |v: f64| End::Solution(vec![c(v), c(1.0)]);
        let results = [at(1.0), End::Infinity, at(2.0), at(1.0 + 1e-12), End::Singular, at(2.5)];
        assert_eq!(collisions(&results), vec![0, 3]);
        let results = [at(1.0), at(2.0), End::Failed, End::Failed];
        assert!(collisions(&results).is_empty());
    }

    /// `n` quadrics in `n` unknowns without squares: random complex combinations of the
    /// products `x_i x_j` (`i < j`), the `x_i` and 1. Their quadratic parts all vanish at the
    /// coordinate points at infinity, so of the `2^n` paths many end there (singular ends).
    fn squarefree_quadrics(n: usize, seed: u64) -> Vec<Vec<C>> {
        let mut rng = SplitMix64::new(seed);
        let terms = n * (n - 1) / 2 + n + 1;
        let mut value = || C::new(rng.unit_f64() - 0.5, rng.unit_f64() - 0.5) * 4.0;
        (0..n).map(|_| (0..terms).map(|_| value()).collect()).collect()
    }

    fn eval_squarefree(coefficients: &[Vec<C>], x: &[C]) -> (Vec<C>, Vec<C>) {
        let n = x.len();
        let (mut f, mut j) = (vec![c(0.0); n], vec![c(0.0); n * n]);
        for (i, row) in coefficients.iter().enumerate() {
            let mut k = 0;
            for a in 0..n {
                for b in a + 1..n {
                    f[i] += row[k] * x[a] * x[b];
                    j[i * n + a] += row[k] * x[b];
                    j[i * n + b] += row[k] * x[a];
                    k += 1;
                }
            }
            for a in 0..n {
                f[i] += row[k] * x[a];
                j[i * n + a] += row[k];
                k += 1;
            }
            f[i] += row[k];
        }
        (f, j)
    }

    /// A path that jumps onto a path going to infinity leaves no two ends at one solution: the
    /// ends alone cannot tell (one solution silently missing), the checkpoints can. The jump
    /// is forced — path `k` tracked from path `l`'s start, so the two are one path throughout
    /// — on three square-free quadrics (5 solutions, 3 paths at infinity): without the
    /// comparison some `(k, l)` loses a solution with every path decided; with it, the pair
    /// is seen at the checkpoints and tracked again — all 5 found when the jump does not
    /// recur, `complete` false when it does.
    #[test]
    fn a_jump_onto_a_path_to_infinity_is_detected() {
        let coefficients = squarefree_quadrics(3, 1);
        let eval = |x: &[C]| eval_squarefree(&coefficients, x);
        let t = Target { n: 3, degrees: vec![2; 3], eval: &eval, groups: None };
        let truth = solve(&t, 7, MAX_PATHS).unwrap();
        assert_eq!((truth.paths, truth.solutions.len(), truth.at_infinity), (8, 5, 3), "{truth:?}");
        assert!(truth.complete() && truth.met == 0, "{truth:?}");
        let with = |divert, compare| {
            let account = compare;
            let tracking = Tracking { divert, compare, account, ..Tracking::DEFAULT };
            solve_tracking(&t, 7, MAX_PATHS, tracking).unwrap().0
        };
        let mut silent = 0;
        for k in 0..8 {
            for l in (0..8).filter(|&l| l != k) {
                let blind = with(Some((k, l, true)), false);
                if !(blind.complete() && blind.solutions.len() == 4) {
                    continue;
                }
                silent += 1;
                // Seen and tracked again: the jump does not recur, every solution is found.
                let once = with(Some((k, l, false)), true);
                assert_eq!((once.solutions.len(), once.failed, once.met), (5, 0, 2), "{once:?}");
                // It recurs: the node is not complete, and says which path failed.
                let always = with(Some((k, l, true)), true);
                assert_eq!((always.solutions.len(), always.failed), (4, 1), "{always:?}");
                assert!(!always.complete());
            }
        }
        // (A path to a solution onto each of the 3 paths to infinity.)
        assert_eq!(silent, 5 * 3);
    }

    /// The cycles of the endgame's loops, on ends whose cycle numbers are known. `x³ = 0`:
    /// the three paths end at 0 as `x ≈ ω·((1 − t)γ)^{1/3}`, one cycle of 3 (a loop around
    /// `t = 1` takes each to the next). `x² = 0, y = x + 1`: one cycle of 2. `y = 0,
    /// y + x² = 0`, a double root at 0 whose two paths are analytic in `t`: near `t = 1` the
    /// homotopy is `y = λ(x − 1)`, `y + x² = λ(y² − 1)` with `λ ≈ −(1 − t)γ`, so `x² + λx −
    /// λy² = 0` with `y ≈ −λ`: `x ≈ −λ` and `x ≈ λ²` — two cycles of 1 at one singular end.
    #[test]
    fn the_endgame_cycles_account_for_singular_ends() {
        let eval = |x: &[C]| (vec![x[0].powi(3)], vec![x[0].powi(2) * 3.0]);
        let t = Target { n: 1, degrees: vec![3], eval: &eval, groups: None };
        let (ends, cycles) = solve_tracking(&t, 3, MAX_PATHS, Tracking::DEFAULT).unwrap();
        assert_eq!((ends.singular, ends.failed, ends.unaccounted), (3, 0, 0), "{ends:?}");
        assert_eq!(cycles, vec![Some(3); 3]);
        let eval = |x: &[C]| {
            (vec![x[0] * x[0], x[1] - x[0] - c(1.0)], vec![x[0] * 2.0, c(0.0), -c(1.0), c(1.0)])
        };
        let t = Target { n: 2, degrees: vec![2, 1], eval: &eval, groups: None };
        let (ends, cycles) = solve_tracking(&t, 6, MAX_PATHS, Tracking::DEFAULT).unwrap();
        assert_eq!((ends.singular, ends.failed, ends.unaccounted), (2, 0, 0), "{ends:?}");
        assert_eq!(cycles, vec![Some(2); 2]);
        let eval =
            |x: &[C]| (vec![x[1], x[1] + x[0] * x[0]], vec![c(0.0), c(1.0), x[0] * 2.0, c(1.0)]);
        let t = Target { n: 2, degrees: vec![1, 2], eval: &eval, groups: None };
        for seed in [1, 2, 5] {
            let (ends, cycles) = solve_tracking(&t, seed, MAX_PATHS, Tracking::DEFAULT).unwrap();
            assert_eq!((ends.singular, ends.failed, ends.unaccounted), (2, 0, 0), "{ends:?}");
            assert_eq!(cycles, vec![Some(1); 2]);
        }
    }

    /// The accounting's rules on turns given: a turn that closes at a nonsingular solution is
    /// a wrong end (one that closes at no end the classification names is no contradiction); two turns back at one path's point, a lost turn and one back
    /// at no path's point are unverified.
    #[test]
    fn the_accounting_names_what_the_cycles_contradict() {
        let point = |v: f64| vec![c(1.0), c(v)];
        let marks: Vec<Vec<Vec<C>>> =
            (0..6).map(|k| vec![point(k as f64); CHECKPOINTS.len()]).collect();
        let polish = |z: &[C]| z.to_vec();
        let at = |k: usize| Some(Turned::At(point(k as f64)));
        let solution = End::Solution(vec![c(0.0)]);
        let results =
            [End::Infinity, End::Infinity, End::Singular, End::Infinity, End::Infinity, solution];
        // 0 → 1 → 0 (a cycle of 2), 2 closed, 3 closes at a solution, 4 → 5 (tracked to a
        // solution: left open).
        let turned = [
            at(1),
            at(0),
            Some(Turned::Closed(End::Failed)),
            Some(Turned::Closed(End::Solution(vec![c(0.0)]))),
            at(5),
            None,
        ];
        let a = account(&results, &marks, &turned, &polish);
        assert_eq!(a.cycles, vec![Some(2), Some(2), Some(1), None, None, None]);
        assert_eq!((a.wrong, a.unverified), (vec![3], vec![]));
        // 0 and 1 both back at 2's point; 3 lost; 4 back at no path's point.
        let results = [
            End::Infinity,
            End::Infinity,
            End::Infinity,
            End::Infinity,
            End::Infinity,
            End::Failed,
        ];
        let far = Some(Turned::At(point(9.5)));
        let turned = [at(2), at(2), at(0), Some(Turned::Lost), far, None];
        let a = account(&results, &marks, &turned, &polish);
        assert_eq!((a.wrong, a.unverified), (vec![], vec![0, 1, 3, 4]));
    }

    /// A path that jumps past the last checkpoint onto a path going to infinity: the
    /// checkpoints cannot see it (one solution silently missing), the endgame's cycles can —
    /// the path's own loop from its point at the last checkpoint closes at the solution it
    /// should have reached. The jump is forced (path `k` tracked to `t = 0.99`, then on from
    /// path `l`'s point there) on the three square-free quadrics of the test above: with the
    /// accounting, the path is tracked again from there — all 5 found when the jump does not
    /// recur, `complete` false when it does.
    #[test]
    fn a_jump_past_the_last_checkpoint_is_detected() {
        let coefficients = squarefree_quadrics(3, 1);
        let eval = |x: &[C]| eval_squarefree(&coefficients, x);
        let t = Target { n: 3, degrees: vec![2; 3], eval: &eval, groups: None };
        let truth = solve(&t, 7, MAX_PATHS).unwrap();
        assert_eq!((truth.solutions.len(), truth.at_infinity), (5, 3), "{truth:?}");
        assert!(truth.complete() && truth.unaccounted == 0, "{truth:?}");
        let with = |late, account| {
            let tracking = Tracking { late, account, ..Tracking::DEFAULT };
            solve_tracking(&t, 7, MAX_PATHS, tracking).unwrap().0
        };
        let mut silent = 0;
        for k in 0..8 {
            for l in (0..8).filter(|&l| l != k) {
                let blind = with(Some((k, l, true)), false);
                if !(blind.complete() && blind.solutions.len() == 4) {
                    continue;
                }
                silent += 1;
                assert_eq!(blind.met, 0, "{blind:?}");
                let once = with(Some((k, l, false)), true);
                assert_eq!(
                    (once.solutions.len(), once.failed, once.unaccounted),
                    (5, 0, 1),
                    "{k} {l}: {once:?}"
                );
                let always = with(Some((k, l, true)), true);
                assert_eq!((always.solutions.len(), always.failed), (4, 1), "{k} {l}: {always:?}");
                assert!(!always.complete());
            }
        }
        assert_eq!(silent, 5 * 3);
    }

    /// Too many paths are refused.
    #[test]
    fn too_many_paths_are_not_attempted() {
        let eval = |x: &[C]| (x.to_vec(), vec![c(1.0); x.len() * x.len()]);
        let t = Target { n: 15, degrees: vec![2; 15], eval: &eval, groups: None };
        assert!(solve(&t, 4, MAX_PATHS).is_none());
        // And a bound below the paths is kept.
        let eval = |x: &[C]| (vec![x[0] * x[0] - c(2.0)], vec![x[0] * 2.0]);
        let t = Target { n: 1, degrees: vec![2], eval: &eval, groups: None };
        assert!(solve(&t, 4, 1).is_none() && solve(&t, 4, 2).is_some());
    }
}
