//! The SolveSpace reader on arbitrary bytes: an error naming the file or sketches whose
//! constraints refer to their entities.
#![no_main]

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|bytes: &[u8]| {
    common::check("fuzz.slvs", gcs_import::slvs::read("fuzz.slvs", bytes));
});
