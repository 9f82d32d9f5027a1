//! `gcs`: check and analyse geometric constraint systems written in RON.
//!
//! This binary is glue: it reads files, picks what to run, and prints reports. The analysis
//! lives in the library crates (`gcs-model`, `gcs-rank`, `gcs-jacobian`, `gcs-rigidity`,
//! `gcs-decompose`). It is the only crate of the workspace that touches files and terminals.

#![allow(clippy::print_stdout, clippy::print_stderr)]

mod batch;
mod check;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

/// Analyse geometric constraint systems (CAD sketches and assemblies) without solving them.
///
/// Models are RON files (format: docs/format.md). A directory stands for every *.ron file below
/// it, in sorted order. A file that cannot be read or analysed is reported and the others are
/// still processed.
///
/// Exit status: 0 when every file was processed, 1 when some failed, 2 on a usage error.
#[derive(Parser, Debug)]
#[command(name = "gcs", version, about, long_about, max_term_width = 100)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Validate models and print their counts: entities, constraints, the sum of entity DOF,
    /// the sum of constraint DOC and the naive count DOF − DOC.
    ///
    /// The naive count is what degree-of-freedom counting says; it ignores redundancy and the
    /// displacements of the whole system. `gcs analyze` gives the exact answer.
    Check {
        /// Output format: human-readable text, or JSON Lines (one object per model).
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// Model files or directories.
        #[arg(required = true, value_name = "PATH")]
        paths: Vec<PathBuf>,
    },
}

/// Report formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// Plain text for people.
    Text,
    /// JSON Lines: one JSON object per model.
    Json,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check { format, paths } => check::run(&paths, format),
    }
}
