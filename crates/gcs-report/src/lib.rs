//! The reports of gcs, in one place, for every front end (the CLI, and the coming Python and
//! WASM bindings and HTML pages): as data — versioned, serialisable both ways, with typed
//! enums where the format has a closed set of values — and as the renderers that print them.
//!
//! - [`Report`]: one model's `gcs analyze` report (format §2–§4) — [`Report::to_json`] is its
//!   JSON line, [`text`] the text report for people;
//! - [`Structural`]: the structural (counting) methods beside the witness analysis, their
//!   section of the report and the disagreements explained (format §3);
//! - [`CheckReport`]: `gcs check`'s counts;
//! - [`clusters`]: clusters and W-decompositions as data, text trees and Graphviz DOT;
//! - [`failure_json`]: the line of a file that failed;
//! - [`run`]: what every front end runs on a model (read, analyse, solve, the Jacobian), so
//!   that the CLI and the bindings call the same functions.
//!
//! The crate computes nothing itself but the comparison of the structural methods with the witness
//! analysis; it never prints and never touches files.
//!
//! # Example
//! ```
//! use gcs_analysis::{AnalysisOptions, analyze};
//! use gcs_report::{Report, WitnessName};
//! let s = gcs_model::System::from_ron_str(r#"System(name: "bar", dim: 2,
//!     entities: [Point(id: "p", at: [0, 0]), Point(id: "q", at: [3, 4])],
//!     constraints: [Distance(id: "d", a: "p", b: "q", value: 5)])"#, None).unwrap();
//! let a = analyze(&s, &AnalysisOptions::default()).unwrap();
//! let report = Report::new(&s, "bar.ron", &a, None);
//! assert_eq!((report.rank, report.dof, report.witness), (1, 0, WitnessName::Sketch));
//! let line = report.to_json();
//! assert!(line.starts_with(r#"{"schema":1,"model":"bar","file":"bar.ron","dim":2,"#));
//! let back: Report = serde_json::from_str(&line).unwrap();
//! assert_eq!(back, report);
//! ```

mod check;
pub mod clusters;
mod error;
mod import;
pub mod measured;
pub mod navigate;
pub mod picture;
mod report;
pub mod run;
mod solve;
mod structural;

pub use check::CheckReport;
pub use error::ReportError;
pub use import::{ImportReport, SkippedReport};
pub use report::{
    ArithmeticName, BackendName, GlobalRigidityReport, ProofName, RankMethodName, RedundantReport,
    Report, SCHEMA, WitnessName, failure_json, text, text_with_solution,
};
pub use solve::{
    BoundReport, CheckedReport, IncompleteReport, NoSolutionReport, PlanReport, SolveReport,
};
pub use structural::{
    DmReport, DorSource, MethodReport, PartReport, Structural, StructuralReport, VerdictName,
};
