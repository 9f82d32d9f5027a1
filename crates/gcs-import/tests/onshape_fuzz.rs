//! The Onshape reader never panics: real and hand-written files mutated at random, byte by byte
//! and node by node in the JSON tree. Whatever it reads is well formed: every reference of a
//! constraint names an entity of its sketch, by a named point that entity has.

mod common;

use std::io::Read;
use std::path::Path;
use std::sync::OnceLock;

use gcs_import::ir::{Geometry, Part, Sketch};
use proptest::prelude::*;
use serde_json::{Map, Value, json};

/// Seed files: the hand-written ones and SketchGraphs' sample (when the corpus is present).
fn seeds() -> &'static [Vec<u8>] {
    static SEEDS: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/onshape");
        let mut seeds: Vec<Vec<u8>> =
            ["entities.json", "constraints.json", "wrapped.json", "features.json"]
                .iter()
                .map(|name| std::fs::read(dir.join(name)).expect("test file"))
                .collect();
        if let Some(external) = common::external() {
            let archive =
                std::fs::read(external.join("SketchGraphs/tests/testdata/sample_json.tar.xz"))
                    .expect("archive");
            let mut tar = Vec::new();
            lzma_rs::xz_decompress(&mut archive.as_slice(), &mut tar).expect("xz");
            for entry in tar::Archive::new(tar.as_slice()).entries().expect("tar") {
                let mut entry = entry.expect("entry");
                let mut bytes = Vec::new();
                entry.read_to_end(&mut bytes).expect("readable");
                if !bytes.is_empty() {
                    seeds.push(bytes);
                }
            }
        }
        seeds
    })
}

/// What the reader returns must hang together.
fn check(sketches: &[Sketch]) {
    for (i, s) in sketches.iter().enumerate() {
        assert!(s.name.ends_with(&format!("/{i}")), "{}", s.name);
        for c in &s.constraints {
            for r in &c.refs {
                let e = s.entities.iter().find(|e| e.id == r.entity);
                let e = e.unwrap_or_else(|| {
                    panic!("{}: {} names the missing entity {}", s.name, c.id, r.entity)
                });
                let ok = matches!(
                    (&e.geometry, r.part),
                    (_, Part::Whole)
                        | (
                            Geometry::Segment { .. }
                                | Geometry::Arc { .. }
                                | Geometry::EllipticalArc { .. }
                                | Geometry::BSpline { .. },
                            Part::Start | Part::End,
                        )
                        | (
                            Geometry::Circle { .. }
                                | Geometry::Arc { .. }
                                | Geometry::Ellipse { .. }
                                | Geometry::EllipticalArc { .. },
                            Part::Center,
                        )
                );
                assert!(ok, "{}: {} names {:?} of {:?}", s.name, c.id, r.part, e.geometry);
            }
        }
    }
}

fn read_and_check(bytes: &[u8]) {
    if let Ok(sketches) = gcs_import::onshape::read("fuzz/input.json", bytes) {
        check(&sketches);
    }
}

#[derive(Clone, Debug)]
enum ByteEdit {
    Set(usize, u8),
    Delete(usize),
    Insert(usize, u8),
    Truncate(usize),
}

fn byte_edit() -> impl Strategy<Value = ByteEdit> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| ByteEdit::Set(i, b)),
        (any::<usize>(), prop::sample::select(b"{}[]\",:0-.e\\ ".to_vec()))
            .prop_map(|(i, b)| ByteEdit::Set(i, b)),
        any::<usize>().prop_map(ByteEdit::Delete),
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| ByteEdit::Insert(i, b)),
        any::<usize>().prop_map(ByteEdit::Truncate),
    ]
}

/// A replacement for a node of the JSON tree.
fn value() -> impl Strategy<Value = Value> {
    prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        prop::sample::select(vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            1e-300,
            1e300,
            -1e308,
            f64::MAX,
            f64::MIN_POSITIVE,
            1e-17,
            7.0
        ])
        .prop_map(|x| json!(x)),
        any::<i64>().prop_map(|x| json!(x)),
        prop::sample::select(vec![
            "",
            "x",
            "p1",
            "p1.start",
            "s1.end",
            "a2.center",
            "s1.start.start",
            ".",
            "z1.start",
            "#v",
            "15 mm",
            "(1/0) mm",
            "((((1 mm",
            "1e99999 mm",
            "90 rad",
            "newSketch",
            "BTMSketchPoint",
            "BTMSketchCurveSegment",
            "BTCurveGeometryCircle",
            "BTCurveGeometryLine",
            "BTCurveGeometryEllipse",
            "BTCurveGeometrySpline",
            "COINCIDENT",
            "DISTANCE",
            "MIRROR",
            "MIDPOINT",
            "ANGLE",
            "HORIZONTAL",
            "VERTICAL",
            "PROJECTED",
            "localFirst",
            "localSecond",
            "localMirror",
            "localMidpoint",
            "externalSecond",
            "BTMParameterString",
            "BTMParameterQuantity",
        ])
        .prop_map(|s| json!(s)),
        Just(json!([])),
        Just(json!({})),
        Just(json!([1.0, 2.0, 3.0])),
        Just(
            json!({"typeName": "BTMSketchPoint", "message": {"entityId": "p1", "x": 0.0, "y": 0.0}})
        ),
    ]
}

#[derive(Clone, Debug)]
enum TreeEdit {
    /// Replace the node with a value.
    Replace(Value),
    /// Remove the node from its parent.
    Remove,
    /// Duplicate the node in its parent list (or under another key).
    Duplicate,
}

fn tree_edit() -> impl Strategy<Value = TreeEdit> {
    prop_oneof![
        3 => value().prop_map(TreeEdit::Replace),
        1 => Just(TreeEdit::Remove),
        1 => Just(TreeEdit::Duplicate),
    ]
}

/// The paths of every node of `v`, as lists of child positions.
fn paths(v: &Value, path: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
    out.push(path.clone());
    let children: Vec<&Value> = match v {
        Value::Array(a) => a.iter().collect(),
        Value::Object(o) => o.values().collect(),
        _ => return,
    };
    for (i, c) in children.into_iter().enumerate() {
        path.push(i);
        paths(c, path, out);
        path.pop();
    }
}

fn apply(root: &mut Value, path: &[usize], edit: &TreeEdit) {
    let Some((&last, parent_path)) = path.split_last() else {
        if let TreeEdit::Replace(v) = edit {
            *root = v.clone();
        }
        return;
    };
    let mut parent = root;
    for &i in parent_path {
        parent = match parent {
            Value::Array(a) => &mut a[i],
            Value::Object(o) => o.values_mut().nth(i).expect("a child"),
            _ => unreachable!("a path goes through containers"),
        };
    }
    match (parent, edit) {
        (Value::Array(a), TreeEdit::Replace(v)) => a[last] = v.clone(),
        (Value::Array(a), TreeEdit::Remove) => {
            a.remove(last);
        }
        (Value::Array(a), TreeEdit::Duplicate) => {
            let copy = a[last].clone();
            a.insert(last, copy);
        }
        (Value::Object(o), TreeEdit::Replace(v)) => {
            *o.values_mut().nth(last).expect("a child") = v.clone()
        }
        (Value::Object(o), TreeEdit::Remove) => {
            let key = o.keys().nth(last).expect("a key").clone();
            o.remove(&key);
        }
        (Value::Object(o), TreeEdit::Duplicate) => {
            let (key, copy) =
                o.iter().nth(last).map(|(k, v)| (k.clone(), v.clone())).expect("a child");
            let mut extra = Map::new();
            extra.insert(format!("{key}2"), copy);
            o.extend(extra);
        }
        _ => unreachable!("the parent is a container"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn mutated_bytes_never_panic(seed in any::<usize>(), edits in prop::collection::vec(byte_edit(), 1..8)) {
        let seeds = seeds();
        let mut bytes = seeds[seed % seeds.len()].clone();
        for edit in edits {
            let len = bytes.len().max(1);
            match edit {
                ByteEdit::Set(i, b) => if !bytes.is_empty() { bytes[i % len] = b },
                ByteEdit::Delete(i) => if !bytes.is_empty() { bytes.remove(i % len); },
                ByteEdit::Insert(i, b) => bytes.insert(i % (bytes.len() + 1), b),
                ByteEdit::Truncate(i) => bytes.truncate(i % len),
            }
        }
        read_and_check(&bytes);
    }

    #[test]
    fn mutated_trees_never_panic(
        seed in any::<usize>(),
        edits in prop::collection::vec((any::<usize>(), tree_edit()), 1..6),
    ) {
        let seeds = seeds();
        let mut root: Value = serde_json::from_slice(&seeds[seed % seeds.len()]).expect("seeds are JSON");
        for (pick, edit) in edits {
            let mut all = Vec::new();
            paths(&root, &mut Vec::new(), &mut all);
            apply(&mut root, &all[pick % all.len()], &edit);
        }
        read_and_check(&serde_json::to_vec(&root).expect("serialisable"));
    }

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..256)) {
        read_and_check(&bytes);
    }
}

#[test]
fn the_seeds_read() {
    for seed in seeds() {
        let sketches = gcs_import::onshape::read("seed.json", seed).expect("a seed reads");
        check(&sketches);
    }
}
