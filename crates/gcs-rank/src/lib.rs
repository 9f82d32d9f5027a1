//! Linear algebra over a field (witness paper §3.1, §6): this crate will hold the `Field` trait
//! and its backends, sparse incremental echelon forms, kernels and the certified exact rank.
