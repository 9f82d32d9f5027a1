//! The FreeCAD reader on arbitrary bytes (as an `.FCStd` zip archive): an error naming the
//! file or sketches whose constraints refer to their entities.
#![no_main]

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|bytes: &[u8]| {
    common::check("fuzz.FCStd", gcs_import::freecad::read("fuzz.FCStd", bytes));
});
