#![allow(missing_docs, clippy::print_stdout)]
use gcs_decompose::{AnalysisOptions, DecompositionNode, analyze};
use gcs_model::System;

fn show(s: &System, n: &DecompositionNode, depth: usize) {
    let e: Vec<&str> = n.entities.iter().map(|e| s.entity(*e).id.as_str()).collect();
    println!("{}node {:?} ({} constraints)", "  ".repeat(depth), e, n.constraints.len());
    for c in &n.children {
        show(s, c, depth + 1);
    }
}

#[test]
fn dump() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for dir in ["data/paper", "data/sketches"] {
        let mut files: Vec<_> =
            std::fs::read_dir(root.join(dir)).unwrap().map(|e| e.unwrap().path()).collect();
        files.sort();
        for f in files {
            let s = System::from_ron_str(
                &std::fs::read_to_string(&f).unwrap(),
                Some(f.to_str().unwrap()),
            )
            .unwrap();
            let t = std::time::Instant::now();
            let a = analyze(&s, &AnalysisOptions { decompose: true, ..AnalysisOptions::default() })
                .unwrap();
            println!("== {} ({:?}) arith {}", s.name(), t.elapsed(), a.clusters_arithmetic);
            for c in &a.clusters {
                let e: Vec<&str> = c.entities.iter().map(|e| s.entity(*e).id.as_str()).collect();
                let k: Vec<&str> =
                    c.constraints.iter().map(|e| s.constraint(*e).id.as_str()).collect();
                println!("  cluster {:?} {:?} grounded {}", e, k, c.grounded);
            }
            for n in a.decomposition.as_ref().unwrap() {
                show(&s, n, 1);
            }
        }
    }
}
