//! The RON model reader on arbitrary text: an error or a model, and a model it reads is
//! written back as text that reads again to the same text.
#![no_main]

use gcs_model::System;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else { return };
    match System::from_ron_str(text, Some("fuzz.ron")) {
        Ok(system) => {
            let written = system.to_ron();
            let again = System::from_ron_str(&written, None)
                .unwrap_or_else(|e| panic!("written text does not read back: {e}\n{written}"));
            assert_eq!(again.to_ron(), written, "writing is a fixed point");
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.ron"), "{e}"),
    }
});
