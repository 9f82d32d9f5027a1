//! Small dense exact linear algebra over ℚ for the constructive placement of one entity
//! (a handful of unknowns), and rational approximations.

use gcs_rank::Rat;

/// The exact rational of the placement: small values stay in machine words.
pub(crate) type Q = Rat;

/// The solution set `{x0 + N t}` of a linear system.
#[derive(Clone, Debug)]
pub(crate) struct Affine {
    pub(crate) x0: Vec<Q>,
    /// Basis of the direction space, one vector per column.
    pub(crate) basis: Vec<Vec<Q>>,
}

/// Solves `a_i · x = b_i` in `n` unknowns; `None` when inconsistent.
pub(crate) fn solve(n: usize, rows: &[(Vec<Q>, Q)]) -> Option<Affine> {
    let mut m: Vec<Vec<Q>> = rows
        .iter()
        .map(|(a, b)| {
            let mut r = a.clone();
            r.resize(n, Q::ZERO);
            r.push(b.clone());
            r
        })
        .collect();
    let mut pivots = Vec::new();
    let mut r = 0;
    for col in 0..n {
        let Some(p) = (r..m.len()).find(|&i| !m[i][col].is_zero()) else { continue };
        m.swap(r, p);
        let inv = Q::ONE / &m[r][col];
        for v in m[r].iter_mut() {
            *v = &*v * &inv;
        }
        for i in 0..m.len() {
            if i != r && !m[i][col].is_zero() {
                let f = m[i][col].clone();
                let pivot_row = m[r].clone();
                for (x, y) in m[i].iter_mut().zip(&pivot_row) {
                    *x -= &f * y;
                }
            }
        }
        pivots.push(col);
        r += 1;
        if r == m.len() {
            break;
        }
    }
    if m[r..].iter().any(|row| !row[n].is_zero()) {
        return None;
    }
    let mut x0 = vec![Q::ZERO; n];
    for (i, &c) in pivots.iter().enumerate() {
        x0[c] = m[i][n].clone();
    }
    let mut basis = Vec::new();
    for f in (0..n).filter(|c| !pivots.contains(c)) {
        let mut v = vec![Q::ZERO; n];
        v[f] = Q::ONE;
        for (i, &c) in pivots.iter().enumerate() {
            v[c] = -m[i][f].clone();
        }
        basis.push(v);
    }
    Some(Affine { x0, basis })
}

impl Affine {
    pub(crate) fn point(&self, t: &[Q]) -> Vec<Q> {
        let mut x = self.x0.clone();
        for (v, ti) in self.basis.iter().zip(t) {
            for (xi, vi) in x.iter_mut().zip(v) {
                *xi += vi * ti;
            }
        }
        x
    }

    /// The parameters of the point of the set closest to `target` (least squares).
    pub(crate) fn project(&self, target: &[Q]) -> Vec<Q> {
        let k = self.basis.len();
        if k == 0 {
            return Vec::new();
        }
        let diff: Vec<Q> = target.iter().zip(&self.x0).map(|(a, b)| a - b).collect();
        let rows: Vec<(Vec<Q>, Q)> = (0..k)
            .map(|i| {
                let a = (0..k).map(|j| dot(&self.basis[i], &self.basis[j])).collect();
                (a, dot(&self.basis[i], &diff))
            })
            .collect();
        // The Gram matrix of a basis is invertible: a unique solution.
        solve(k, &rows).map(|s| s.x0).unwrap_or_else(|| vec![Q::ZERO; k])
    }
}

pub(crate) fn dot(a: &[Q], b: &[Q]) -> Q {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The rational square root of `q` when it has one.
pub(crate) fn sqrt(q: &Q) -> Option<Q> {
    q.sqrt_exact()
}

/// The rational `round(x · den) / den` (0 for a non-finite `x`).
pub(crate) fn approx(x: f64, den: i64) -> Q {
    Q::from_f64_approx(x, den.max(1))
}

pub(crate) fn to_f64(q: &Q) -> f64 {
    q.to_f64()
}

/// Householder reflection `I − 2 v vᵀ / |v|²`: exactly orthogonal for any rational `v ≠ 0`.
pub(crate) fn reflection(v: &[Q]) -> Option<Vec<Vec<Q>>> {
    let vv = dot(v, v);
    if vv.is_zero() {
        return None;
    }
    let two = Q::from(2i64);
    let k = v.len();
    Some(
        (0..k)
            .map(|i| {
                (0..k)
                    .map(|j| {
                        let id = if i == j { Q::ONE } else { Q::ZERO };
                        id - &two * &v[i] * &v[j] / &vv
                    })
                    .collect()
            })
            .collect(),
    )
}

pub(crate) fn matmul(a: &[Vec<Q>], b: &[Vec<Q>]) -> Vec<Vec<Q>> {
    let k = b.first().map_or(0, Vec::len);
    a.iter()
        .map(|row| (0..k).map(|j| row.iter().zip(b).map(|(x, br)| x * &br[j]).sum()).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64) -> Q {
        Q::from(n)
    }

    #[test]
    fn solves_and_projects() {
        // x + y = 2: x0 = (2, 0), direction (−1, 1); closest to (0, 0) is (1, 1).
        let s = solve(2, &[(vec![q(1), q(1)], q(2))]).unwrap();
        assert_eq!(s.basis.len(), 1);
        let t = s.project(&[q(0), q(0)]);
        assert_eq!(s.point(&t), vec![q(1), q(1)]);
        assert!(solve(1, &[(vec![q(1)], q(1)), (vec![q(2)], q(3))]).is_none());
        assert_eq!(sqrt(&Q::new(9, 4).unwrap()), Q::new(3, 2));
        assert_eq!(sqrt(&q(2)), None);
        let r = reflection(&[q(1), q(2), q(2)]).unwrap();
        let rt = matmul(&r, &r);
        assert_eq!(rt[0][0], q(1));
        assert_eq!(rt[0][1], q(0));
    }
}
