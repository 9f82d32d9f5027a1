//! The FreeCAD reader never panics: real and hand-written documents with their XML, their shape
//! files and their raw zip bytes mutated.
#![allow(missing_docs)]

mod common;

use std::io::{Read, Write};
use std::sync::OnceLock;

use gcs_import::freecad::{read, read_document_xml};
use proptest::prelude::*;

/// One document: its `Document.xml` and its shape files (name, text).
struct Doc {
    xml: String,
    shapes: Vec<(String, String)>,
    zip: Vec<u8>,
}

fn data(name: &str) -> String {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/freecad").join(name);
    std::fs::read_to_string(path).unwrap()
}

fn zip_of(xml: &str, shapes: &[(String, String)]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    w.start_file("Document.xml", options).unwrap();
    w.write_all(xml.as_bytes()).unwrap();
    for (name, text) in shapes {
        w.start_file(name.as_str(), options).unwrap();
        w.write_all(text.as_bytes()).unwrap();
    }
    w.finish().unwrap().into_inner()
}

/// The hand-written documents and, when the corpus is there, the real ones (with the shape
/// files their sketches' external geometry links).
fn docs() -> &'static [Doc] {
    static DOCS: OnceLock<Vec<Doc>> = OnceLock::new();
    DOCS.get_or_init(|| {
        let mut out = Vec::new();
        let v1 = data("v1_document.xml");
        out.push(Doc { zip: zip_of(&v1, &[]), xml: v1, shapes: Vec::new() });
        let links = data("links_document.xml");
        let shapes = vec![("PartShape.brp".to_owned(), data("segment.brp"))];
        out.push(Doc { zip: zip_of(&links, &shapes), xml: links, shapes });
        if let Some(dir) = common::external() {
            for f in common::files_with_suffix(&dir.join("FreeCAD_Assembly4"), ".fcstd") {
                let bytes = std::fs::read(&f).unwrap();
                let mut archive =
                    zip::ZipArchive::new(std::io::Cursor::new(bytes.as_slice())).unwrap();
                let mut text = |name: &str| {
                    let mut s = String::new();
                    archive.by_name(name).unwrap().read_to_string(&mut s).unwrap();
                    s
                };
                let xml = text("Document.xml");
                // The shapes of the objects sketches link (a handful; all would be slow).
                let shapes: Vec<(String, String)> = match f.file_name().and_then(|n| n.to_str()) {
                    Some("Triangle.fcstd") => {
                        vec![("PartShape5.brp".to_owned(), text("PartShape5.brp"))]
                    }
                    Some("Bielle.fcstd") => {
                        ["PartShape16.brp", "PartShape18.brp", "PartShape19.brp", "PartShape20.brp"]
                            .iter()
                            .map(|n| ((*n).to_owned(), text(n)))
                            .collect()
                    }
                    _ => Vec::new(),
                };
                out.push(Doc { xml, shapes, zip: bytes });
            }
        }
        out
    })
}

/// A mutation of a text: at a relative position, delete, insert a chosen piece, duplicate a
/// slice, or change a digit.
#[derive(Clone, Debug)]
enum Edit {
    Delete(f64, usize),
    Insert(f64, &'static str),
    Duplicate(f64, usize),
    Digit(f64, u8),
}

fn edit() -> impl Strategy<Value = Edit> {
    let pieces = prop::sample::select(vec![
        "<",
        ">",
        "\"",
        "=",
        "/",
        "-",
        "-2000",
        "-3",
        "-1",
        "0",
        "1",
        "2",
        "3",
        "15",
        "19",
        "99",
        "1e308",
        "nan",
        "inf",
        "-0",
        ".",
        "e",
        " ",
        "\n",
        "*",
        "+1",
        "<Constrain Type=\"5\"/>",
        "<Geometry type=\"Part::GeomCircle\"/>",
        "&amp;",
        "]]>",
        "<!--",
        "Edge1",
        "Vertex9",
        "Face1",
        "2 ",
        "7 ",
        "Locations",
        "TShapes",
        "CN",
    ]);
    prop_oneof![
        (0.0..1.0f64, 1usize..64).prop_map(|(p, n)| Edit::Delete(p, n)),
        (0.0..1.0f64, pieces).prop_map(|(p, s)| Edit::Insert(p, s)),
        (0.0..1.0f64, 1usize..256).prop_map(|(p, n)| Edit::Duplicate(p, n)),
        (0.0..1.0f64, 0u8..10).prop_map(|(p, d)| Edit::Digit(p, d)),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut b = text.as_bytes().to_vec();
    for e in edits {
        let at = |p: f64, len: usize| ((p * len as f64) as usize).min(len);
        match e {
            Edit::Delete(p, n) => {
                let i = at(*p, b.len());
                let j = (i + n).min(b.len());
                b.drain(i..j);
            }
            Edit::Insert(p, s) => {
                let i = at(*p, b.len());
                b.splice(i..i, s.bytes());
            }
            Edit::Duplicate(p, n) => {
                let i = at(*p, b.len());
                let j = (i + n).min(b.len());
                let piece = b[i..j].to_vec();
                b.splice(j..j, piece);
            }
            Edit::Digit(p, d) => {
                let i = at(*p, b.len());
                if let Some(k) = b[i..].iter().position(|c| c.is_ascii_digit()) {
                    b[i + k] = b'0' + d;
                }
            }
        }
    }
    String::from_utf8_lossy(&b).into_owned()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn mutated_xml_never_panics(doc in any::<prop::sample::Index>(), edits in prop::collection::vec(edit(), 1..8)) {
        let d = &docs()[doc.index(docs().len())];
        let xml = apply(&d.xml, &edits);
        let _ = read_document_xml("fuzz.FCStd", &xml);
        let _ = read("fuzz.FCStd", &zip_of(&xml, &d.shapes));
    }

    #[test]
    fn mutated_shapes_never_panic(doc in any::<prop::sample::Index>(), which in any::<prop::sample::Index>(),
                                  edits in prop::collection::vec(edit(), 1..8)) {
        let with_shapes: Vec<&Doc> = docs().iter().filter(|d| !d.shapes.is_empty()).collect();
        let d = with_shapes[doc.index(with_shapes.len())];
        let mut shapes = d.shapes.clone();
        let k = which.index(shapes.len());
        shapes[k].1 = apply(&shapes[k].1, &edits);
        if let Ok(sketches) = read("fuzz.FCStd", &zip_of(&d.xml, &shapes)) {
            prop_assert!(sketches.iter().all(|s| s.dim == 2));
        }
    }

    #[test]
    fn mutated_zip_bytes_never_panic(doc in any::<prop::sample::Index>(),
                                     flips in prop::collection::vec((0.0..1.0f64, any::<u8>()), 1..16),
                                     cut in 0.0..1.0f64) {
        let d = &docs()[doc.index(docs().len())];
        let mut bytes = d.zip.clone();
        for (p, v) in &flips {
            let i = ((p * bytes.len() as f64) as usize).min(bytes.len() - 1);
            bytes[i] ^= v;
        }
        let _ = read("fuzz.FCStd", &bytes);
        let keep = (cut * bytes.len() as f64) as usize;
        let _ = read("fuzz.FCStd", &bytes[..keep]);
    }
}

#[test]
fn every_document_reads_unmutated() {
    for d in docs() {
        read("doc.FCStd", &d.zip).unwrap();
        read_document_xml("doc.FCStd", &d.xml).unwrap();
    }
}
