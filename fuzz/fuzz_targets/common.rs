// What every answer of a CAD reader must satisfy (shared by the CAD targets).

use gcs_import::ImportError;
use gcs_import::ir::Sketch;

/// Every constraint refers to an entity of its sketch, the dimension is 2 or 3, and an error
/// names the file and says something; each sketch lowers without panicking.
pub fn check(file: &str, result: Result<Vec<Sketch>, ImportError>) {
    match result {
        Ok(sketches) => {
            for s in &sketches {
                assert!(s.dim == 2 || s.dim == 3, "dimension {}", s.dim);
                for c in &s.constraints {
                    for r in &c.refs {
                        assert!(s.entities.iter().any(|e| e.id == r.entity), "{}", r.entity);
                    }
                }
                let _ = gcs_import::lower(s);
            }
        }
        Err(e) => {
            assert_eq!(e.file, file);
            assert!(!e.message.is_empty());
        }
    }
}
