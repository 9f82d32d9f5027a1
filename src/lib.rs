//! Support code shared by the workspace-level integration tests (`tests/`) and the criterion
//! benchmarks (`benches/`) of gcs. Nothing here is published; the library crates live in
//! `crates/`.
