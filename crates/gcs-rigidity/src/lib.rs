//! Structural rigidity (the flow paper, 003_da7837b37878e133.txt, and the survey's §4.1).
//!
//! This crate will hold: the object-constraint flow network of a system, maximum flow and
//! residual reachability, Hoffmann et al.'s `Distribute`, `Dense` and `Minimal_Dense`,
//! Jermann et al.'s geometrically correct `Distribute` and `Over-Rigid` over DOR-minimal
//! subsets, the degree of rigidity from a rule table, and the Dulmage–Mendelsohn decomposition
//! of the equation–unknown bipartite graph.
