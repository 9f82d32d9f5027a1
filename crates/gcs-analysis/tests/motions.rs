//! The drawing's free motions (`gcs_analysis::motions`): for every model of data/ whose
//! drawing satisfies its constraints, as many as its degrees of freedom plus the extra motions
//! of a singular drawing; each is a motion (the Jacobian at the drawing sends it to zero, up
//! to rounding).

use gcs_analysis::{AnalysisOptions, analyze, motions::free_motions};
use gcs_jacobian::{Equations, Layout};

#[test]
fn every_drawing_has_its_degrees_of_freedom_as_free_motions() {
    let mut checked = 0;
    for file in gcs_suite::data_files() {
        let s = gcs_suite::load(&file);
        let a = analyze(&s, &AnalysisOptions::default()).unwrap();
        let Some(sketch) = a.sketch.as_ref().filter(|k| k.satisfied) else { continue };
        let motions = free_motions(&s, 10_000).expect("a drawing");
        assert_eq!(motions.len(), a.dof + sketch.extra_motions, "{file}");
        let layout = Layout::new(&s);
        let x: Vec<f64> = (0..layout.ncols())
            .map(|c| {
                let e = s.entity_indices().find(|e| layout.columns(*e).contains(&c)).unwrap();
                let k = c - layout.columns(e).start;
                gcs_jacobian::sketch::sketch_coords_in::<f64>(&s, e).unwrap()[k]
            })
            .collect();
        let equations = Equations::new(&s, &layout);
        for m in &motions {
            let norm = m.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!(norm > 0.0, "{file}");
            for c in s.constraint_indices() {
                let Some(r) = equations.residual(c, &x) else { continue };
                for row in &r.rows {
                    let dot: f64 = row.entries().iter().map(|(k, v)| v * m[*k]).sum();
                    let scale: f64 = row.entries().iter().map(|(_, v)| v.abs()).sum::<f64>();
                    assert!(dot.abs() <= 1e-9 * scale.max(1.0) * norm, "{file}: {dot}");
                }
            }
        }
        checked += 1;
    }
    assert!(checked >= 10, "{checked} models checked");
}
