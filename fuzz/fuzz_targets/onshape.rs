//! The Onshape JSON reader on arbitrary bytes: an error naming the file or sketches whose
//! constraints refer to their entities.
#![no_main]

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|bytes: &[u8]| {
    common::check("fuzz.json", gcs_import::onshape::read("fuzz.json", bytes));
});
