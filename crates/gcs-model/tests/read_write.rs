//! Reading, the DOC table, writing back, and robustness of the reader on arbitrary input.

use std::path::{Path, PathBuf};

use gcs_model::{ConstraintKind, EntityKind, Signature, System};
use proptest::prelude::*;

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> System {
    let text = std::fs::read_to_string(path).unwrap();
    System::from_ron_str(&text, Some(&path.display().to_string())).unwrap()
}

/// The good models of this crate's tests and every model shipped in `data/`.
fn all_models() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut dirs = vec![manifest().join("tests/good"), manifest().join("../../data")];
    while let Some(d) = dirs.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else { continue };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "ron") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// Equality of everything that a file says (positions are where it says it, so they differ).
fn same_model(a: &System, b: &System) {
    assert_eq!(a.name(), b.name());
    assert_eq!(a.dim(), b.dim());
    assert_eq!(a.entities().len(), b.entities().len());
    for (x, y) in a.entities().iter().zip(b.entities()) {
        assert_eq!((&x.id, &x.geometry), (&y.id, &y.geometry));
    }
    assert_eq!(a.constraints().len(), b.constraints().len());
    for (x, y) in a.constraints().iter().zip(b.constraints()) {
        assert_eq!(
            (&x.id, x.kind, &x.args, x.signature, &x.value, x.doc),
            (&y.id, y.kind, &y.args, y.signature, &y.value, y.doc)
        );
    }
}

#[test]
fn zoo_2d_doc_table() {
    let s = read(&manifest().join("tests/good/zoo2d.ron"));
    let doc = |id: &str| s.constraint(s.constraint_by_id(id).unwrap()).doc;
    let table = [
        ("fix", 2),
        ("h", 1),
        ("v", 1),
        ("par", 1),
        ("perp", 1),
        ("w", 1),
        ("pl", 1),
        ("ll", 1),
        ("ang", 1),
        ("co", 2),
        ("mid", 2),
        ("sym", 2),
        ("on", 1),
        ("oc", 1),
        ("t", 1),
        ("tt", 1),
        ("r", 1),
        ("eq", 1),
        ("cc", 2),
        ("er", 1),
        ("dx", 1),
        ("dy", 1),
        ("ta", 1),
        ("cp", 2),
        ("symp", 2),
        ("ratio", 1),
        ("ea", 1),
        ("ed", 1),
        ("sp", 2),
    ];
    for (id, want) in table {
        assert_eq!(doc(id), want, "{id}");
    }
    // Points (the arc's two and the centre `arc.center` named by a constraint among them, the
    // spline's five control points and its point `sq`), lines, circles and the arc.
    assert_eq!(s.dof_sum(), 17 * 2 + 4 * 2 + 3 * 3 + 3);
    // Every constraint kind exists in 2D, and the zoo has them all.
    let kinds: std::collections::BTreeSet<ConstraintKind> =
        s.constraints().iter().map(|c| c.kind).collect();
    assert_eq!(kinds.len(), ConstraintKind::ALL.len());
    // Roles are resolved whatever the argument order: Incident(a: circle, b: point).
    let oc = s.constraint(s.constraint_by_id("oc").unwrap());
    let (k, d) = (s.entity_by_id("k").unwrap(), s.entity_by_id("d").unwrap());
    assert_eq!(oc.signature, Signature::IncidentPointCircle { point: d, circle: k });
    assert_eq!(oc.args, vec![k, d], "args keep the file's order");
    // A segment is the line through its points.
    let ab = s.entity_by_id("ab").unwrap();
    assert_eq!(s.entity(ab).kind(), EntityKind::Segment);
    assert_eq!(
        s.segment_points(ab),
        Some((s.entity_by_id("a").unwrap(), s.entity_by_id("b").unwrap()))
    );
    // Exact numbers: "29/3" and 2.5.
    let k2 = s.entity(s.entity_by_id("k2").unwrap());
    assert_eq!(
        format!("{:?}", k2.geometry),
        "Circle { center: Some([Ratio { numer: 29, denom: 3 }, Ratio { numer: 14, denom: 1 }]), radius: Some(Ratio { numer: 1, denom: 1 }) }"
    );
}

#[test]
fn zoo_3d_doc_table() {
    let s = read(&manifest().join("tests/good/zoo3d.ron"));
    let doc = |id: &str| s.constraint(s.constraint_by_id(id).unwrap()).doc;
    let table = [
        ("fix", 3),
        ("ia", 1),
        ("lab", 2),
        ("il", 2),
        ("is", 1),
        ("pp", 2),
        ("lp", 1),
        ("llp", 2),
        ("pw", 1),
        ("lw", 2),
        ("lab_ac", 1),
        ("dpp", 1),
        ("dpl", 1),
        ("dll", 1),
        ("dpt", 1),
        ("aw", 1),
        ("ap", 1),
        ("all", 1),
        ("co", 3),
        ("mid", 3),
        ("ts", 1),
        ("tss", 1),
        ("r", 1),
        ("eq", 1),
        ("cps", 3),
        ("symp", 3),
        ("ratio", 1),
        ("sp", 3),
    ];
    for (id, want) in table {
        assert_eq!(doc(id), want, "{id}");
    }
    let kinds: std::collections::BTreeSet<ConstraintKind> =
        s.constraints().iter().map(|c| c.kind).collect();
    // All but the 2D-only kinds: Horizontal, Vertical, EqualRadius, DistanceX, DistanceY,
    // TangentAt, EqualAngle, EqualDistance.
    assert_eq!(kinds.len(), ConstraintKind::ALL.len() - 8);
}

#[test]
fn every_model_round_trips() {
    let models = all_models();
    assert!(models.len() >= 2);
    for path in models {
        let s = read(&path);
        let text = s.to_ron();
        let again = System::from_ron_str(&text, None).unwrap_or_else(|e| {
            panic!("{}: written text does not read back: {e}\n{text}", path.display())
        });
        same_model(&s, &again);
        assert_eq!(again.to_ron(), text, "writing is a fixed point");
    }
}

#[test]
fn name_defaults_to_file_stem() {
    let s = System::from_ron_str("System(dim: 3)", Some("some/dir/bracket.ron")).unwrap();
    assert_eq!(s.name(), "bracket");
    assert_eq!(s.entities().len(), 0);
}

fn example_texts() -> Vec<String> {
    all_models().iter().map(|p| std::fs::read_to_string(p).unwrap()).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]

    /// Arbitrary bytes never make the reader panic.
    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        let _ = System::from_ron_str(&text, Some("random.ron"));
    }

    /// Random mutations of real models (deleting, duplicating, replacing characters) never make
    /// the reader panic, and every failure names the origin.
    #[test]
    fn mutated_models_never_panic(
        which in any::<prop::sample::Index>(),
        edits in proptest::collection::vec((any::<prop::sample::Index>(), 0u8..4, any::<char>()), 1..8),
    ) {
        let texts = example_texts();
        let mut chars: Vec<char> = texts[which.index(texts.len())].chars().collect();
        for (at, op, c) in edits {
            if chars.is_empty() { break; }
            let i = at.index(chars.len());
            match op {
                0 => { chars.remove(i); }
                1 => chars.insert(i, c),
                2 => chars[i] = c,
                _ => { let d = chars[i]; chars.insert(i, d); }
            }
        }
        let text: String = chars.into_iter().collect();
        if let Err(e) = System::from_ron_str(&text, Some("mutated.ron")) {
            prop_assert!(e.to_string().starts_with("mutated.ron:"), "{}", e);
        }
    }
}
