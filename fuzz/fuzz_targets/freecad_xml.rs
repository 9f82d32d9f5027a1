//! The FreeCAD reader on arbitrary text as a `Document.xml` (the zip layer skipped, so the
//! fuzzer reaches the XML and the sketches directly).
#![no_main]

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|bytes: &[u8]| {
    let Ok(xml) = std::str::from_utf8(bytes) else { return };
    common::check("fuzz.FCStd", gcs_import::freecad::read_document_xml("fuzz.FCStd", xml));
});
