//! The free motions of the drawing: a basis of its infinitesimal motions modulo the
//! displacements the system admits — where its degrees of freedom are, for a picture
//! (`gcs analyze --svg` draws them as arrows).
//!
//! Computed exactly at the drawing (the sketch's coordinates, rational): the kernel of the
//! Jacobian there by exact elimination, the displacements it contains (the combinations of
//! the translation and rotation generators the Jacobian sends to zero), and the kernel vectors
//! independent of those, each then rounded to doubles for drawing and replaced by the least
//! representative of its class modulo those displacements (orthogonal to them), which shows
//! what moves relative to the rest. At a drawing that satisfies
//! its constraints and is generic there are `dof` of them; at a singular drawing,
//! `dof + extra_motions`.

use gcs_jacobian::plan::plan_anywhere;
use gcs_jacobian::{Layout, assemble, sketch};
use gcs_model::{EntityIdx, System};
use gcs_rank::{Echelon, EchelonOptions, Field, Insertion, Rat, SparseRow};

/// The basis of the drawing's free motions, each a velocity per column of
/// [`Layout::new`]`(system)`, in doubles; `None` when an entity has no sketch position or the
/// system has more than `max_unknowns` unknowns (the elimination is exact).
pub fn free_motions(system: &System, max_unknowns: usize) -> Option<Vec<Vec<f64>>> {
    let layout = Layout::new(system);
    let n = layout.ncols();
    if n > max_unknowns {
        return None;
    }
    let x = sketch::drawing_in::<Rat>(system, &layout)?;
    let sketch_in = |e: EntityIdx| sketch::sketch_coords_in::<Rat>(system, e);
    let plan = plan_anywhere(system, &layout, &x, &sketch_in);
    let j = assemble(system, &layout, &plan, &x, &sketch_in);
    let untracked = || EchelonOptions { track_combinations: false, tolerance: None };
    let mut form = Echelon::<Rat>::new(n, untracked());
    for row in &j.rows {
        form.insert(row.clone());
    }
    let kernel = form.kernel_basis();
    // The displacements in the kernel: t = Σ c_i T_i with J t = 0, from the kernel of the
    // rows (J_r · T_i)_i.
    let generators = gcs_jacobian::motions::generators(system, &layout, &x).ok()?;
    let mut images = Echelon::<Rat>::new(generators.len(), untracked());
    for row in &j.rows {
        let entries: Vec<(usize, Rat)> = generators
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let mut s = Rat::zero();
                for (c, v) in row.entries() {
                    s = s.add(&v.mul(&t[*c]));
                }
                (i, s)
            })
            .filter(|(_, s)| !s.is_zero())
            .collect();
        images.insert(SparseRow::from_entries(entries));
    }
    let mut basis = Echelon::<Rat>::new(n, untracked());
    // The displacements, orthonormalised in doubles (for the drawing only, below).
    let mut displacements: Vec<Vec<f64>> = Vec::new();
    for c in images.kernel_basis() {
        let mut t = vec![Rat::zero(); n];
        for (i, ci) in c.entries() {
            for (k, v) in generators[*i].iter().enumerate() {
                t[k] = t[k].add(&ci.mul(v));
            }
        }
        basis.insert(dense_row(&t));
        let mut u: Vec<f64> = t.iter().map(Rat::to_f64).collect();
        for d in &displacements {
            let along = dot(&u, d);
            u.iter_mut().zip(d).for_each(|(a, b)| *a -= along * b);
        }
        let norm = dot(&u, &u).sqrt();
        if norm > 0.0 {
            displacements.push(u.into_iter().map(|a| a / norm).collect());
        }
    }
    let mut free = Vec::new();
    for v in kernel {
        if let Insertion::Independent { .. } = basis.insert(v.clone()) {
            let mut dense = vec![0.0; n];
            for (c, value) in v.entries() {
                dense[*c] = value.to_f64();
            }
            // The same motion up to a displacement, the least one: what moves relative to the
            // rest (the middle point of three in line, not an end point and a rotation).
            for d in &displacements {
                let along = dot(&dense, d);
                dense.iter_mut().zip(d).for_each(|(a, b)| *a -= along * b);
            }
            free.push(dense);
        }
    }
    Some(free)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn dense_row(v: &[Rat]) -> SparseRow<Rat> {
    SparseRow::from_entries(
        v.iter().enumerate().filter(|(_, x)| !x.is_zero()).map(|(k, x)| (k, x.clone())).collect(),
    )
}
