//! `gcs`: check, analyse, solve and convert geometric constraint systems (RON models and CAD
//! files).
//!
//! This binary is glue: it reads files, picks what to run, and prints reports. The analysis
//! lives in the library crates (`gcs-model`, `gcs-rank`, `gcs-jacobian`, `gcs-rigidity`,
//! `gcs-decompose`, `gcs-analysis`), the reports and their renderers in `gcs-report`. It is
//! the only crate of the workspace that touches files and terminals.

#![allow(clippy::print_stdout, clippy::print_stderr)]

mod analyze;
mod batch;
mod check;
mod convert;
mod navigate;
mod solve;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use gcs_analysis::Backend;

/// Analyse geometric constraint systems (CAD sketches and assemblies) exactly, and solve them.
///
/// Models are RON files (format: docs/format.md) or CAD files: SolveSpace .slvs, FreeCAD .FCStd,
/// Onshape sketch JSON (one model per sketch). A directory stands for every such file below it,
/// in sorted order. A file that cannot be read or analysed is reported and the others are still
/// processed.
///
/// Exit status: 0 when every file was processed, 1 when some failed, 2 on a usage error.
#[derive(Parser, Debug)]
#[command(name = "gcs", version, about, long_about, max_term_width = 100)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The default of `--jobs`: the cores of this machine.
fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZero::get)
}

/// `--choose STEP=K`: a plan step's index and a candidate.
fn parse_choice(text: &str) -> Result<(usize, usize), String> {
    let parsed = text.split_once('=').and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?)));
    parsed.ok_or_else(|| format!("`{text}` is not STEP=K (two whole numbers, e.g. 3=1)"))
}

/// `--timeout SECONDS`: a positive finite number of seconds.
fn parse_timeout(text: &str) -> Result<std::time::Duration, String> {
    match text.parse::<f64>() {
        Ok(s) if s.is_finite() && s > 0.0 => Ok(std::time::Duration::from_secs_f64(s)),
        _ => Err(format!("`{text}` is not a positive number of seconds")),
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Analyse models by the witness method: rank, degrees of freedom, trivial motions and
    /// redundant constraints with the constraints they are redundant with.
    ///
    /// The rank is decided exactly by default (modular elimination certified over the
    /// rationals, or rational elimination), at a witness: the sketch when it satisfies the
    /// constraints and is generic, otherwise a rational configuration built from the seed.
    Analyze {
        /// The arithmetic that decides the rank: exact (proven), rational (num), rug (GMP,
        /// needs the rug feature), modp (modulo 2^61 − 1, not proven), float (with
        /// --tolerance).
        #[arg(long, value_enum, default_value_t = BackendArg::Exact)]
        backend: BackendArg,
        /// Seed of the random choices of the witness.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Relative tolerance of the float backend: an entry is zero when it is at most this
        /// times the largest entry of its row.
        #[arg(long, default_value_t = 1e-9)]
        tolerance: f64,
        /// Output format: human-readable text, or JSON Lines (one object per model).
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// Also run the structural (degree-of-freedom counting) methods: Dense, Over-Rigid with
        /// the DOR from rules and from the witness, and the Dulmage–Mendelsohn decomposition;
        /// the text report says where they disagree with the witness analysis, and why.
        #[arg(long)]
        structural: bool,
        /// Also W-decompose every rigid cluster into smaller rigid subsystems (witness paper
        /// §5): a tree of rigid subsystems (a DR-plan) whose leaves are W-indecomposable.
        #[arg(long)]
        decompose: bool,
        /// Decide a 2D model of points and distances by the witness too, not by the (2,3)
        /// pebble game (which gives the same rank, redundancies and clusters, proven by Laman's
        /// theorem, faster; the report's `rank_method` says which decided).
        #[arg(long)]
        no_pebble_game: bool,
        /// Write the W-decompositions as a Graphviz DOT graph to FILE (implies --decompose):
        /// one node per rigid subsystem, labelled with its entity ids, an edge to each
        /// subsystem it decomposes into. Render with `dot -Tsvg FILE`.
        #[arg(long, value_name = "FILE")]
        dot: Option<PathBuf>,
        /// Draw each model as SVG to DIR/<file path without extension>.svg (a CAD file's
        /// sketches to DIR/<file path without extension>/<sketch>.svg): the sketch, each rigid cluster in its
        /// own colour, redundant constraints in orange (red when conflicting) and constraints
        /// dependent only at this drawing in magenta, with what they depend on as tooltips;
        /// with --decompose, the W-decomposition as a tree beside it (<...>.plan.svg).
        #[arg(long, value_name = "DIR")]
        svg: Option<PathBuf>,
        /// Files analysed at once, on that many threads (default: the cores of this machine).
        /// The output is the same as one at a time, in the same order.
        #[arg(long, short = 'j', value_name = "N")]
        jobs: Option<usize>,
        /// Analyse only shard I of N of the inputs (`0/4`, `1/4`, …): the k-th input in sorted
        /// path order belongs to shard k mod N, so N machines or jobs of a scheduler (a Slurm
        /// array, a Kubernetes indexed Job, GNU parallel) together analyse every input once.
        #[arg(long, value_name = "I/N", value_parser = batch::parse_shard)]
        shard: Option<(usize, usize)>,
        /// Give each model at most this many seconds: a model over it gets an error line naming
        /// the limit and the batch goes on. Each model is then analysed in a process of its own
        /// (a few milliseconds more per model), which is stopped when its time is up.
        #[arg(long, value_name = "SECONDS", value_parser = parse_timeout)]
        timeout: Option<std::time::Duration>,
        /// Analyse only the model at this index (from 0) of each file: what `--timeout` runs
        /// in each process.
        #[arg(long, value_name = "K", hide = true)]
        only_model: Option<usize>,
        /// Model files or directories.
        #[arg(required = true, value_name = "PATH")]
        paths: Vec<PathBuf>,
    },
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
    /// Solve models at their values, from their drawings: the status (solved, inconsistent,
    /// failed), the worst residual, how far the drawing moved, the solved entities, and each
    /// redundant constraint told consistent or conflicting (with the constraints it conflicts
    /// with).
    ///
    /// The redundant constraints come from the exact analysis (or, where it finds no witness,
    /// the float one); they are left out of the solve and measured at the solution.
    Solve {
        /// Output format: human-readable text, or JSON Lines (one object per model).
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// Also write each solved model as RON to DIR/<model name>.ron (readable by `gcs
        /// analyze`).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Also list the other realizations (`solutions`): each real realization of the core
        /// (found by homotopy continuation where its equations allow: `paths` in the plan;
        /// otherwise the core as solved), and each point placed in closed form at each of its
        /// candidates, every combination under which the consistent redundant constraints
        /// still hold (mirror images distinct).
        #[arg(long)]
        all: bool,
        /// With --all: list at most N realizations (`truncated` says when there were more; at
        /// most 10000, each realization being a copy of the model in the report).
        #[arg(long, value_name = "N", default_value_t = 64,
              value_parser = clap::value_parser!(u32).range(1..=10_000))]
        max_solutions: u32,
        /// Fix the choice of a closed-form step: STEP=K places step STEP of the `plan` list (its
        /// index, from 0) at its candidate K (a point by two distances: 0 left of the line from
        /// its first anchor to its second, 1 right; by a distance and a line: 0 ahead along the
        /// line's direction, 1 behind). A step of the core (the first steps: the nodes of its
        /// DR-plan) takes its candidate K among those the homotopy finds, given its children's
        /// choices (0: the one solved from the drawing). Repeatable; the other steps follow the
        /// drawing.
        #[arg(long, value_name = "STEP=K", value_parser = parse_choice)]
        choose: Vec<(usize, usize)>,
        /// With --all or a choice in the core: the most homotopy paths each node of the core
        /// may track (its start system's solutions; at most 16384, about 150 paths a second on
        /// two cores); 0 keeps the core as solved.
        #[arg(long, value_name = "N", default_value_t = 4096,
              value_parser = clap::value_parser!(u32).range(0..=16384))]
        max_paths: u32,
        /// Files solved at once, on that many threads (default: the cores of this machine;
        /// one with --out). The output is the same as one at a time, in the same order.
        #[arg(long, short = 'j', value_name = "N")]
        jobs: Option<usize>,
        /// Model files or directories.
        #[arg(required = true, value_name = "PATH")]
        paths: Vec<PathBuf>,
    },
    /// Convert CAD files (SolveSpace .slvs, FreeCAD .FCStd, Onshape sketch JSON) to gcs models
    /// in RON, one per sketch; what a sketch holds that cannot be expressed is listed on
    /// standard error.
    ///
    /// Without -o the model is printed (the file must hold one sketch). With -o OUT: a file
    /// with one sketch is written to OUT, unless OUT is an existing directory or ends with `/`;
    /// a file with several (or any file, when OUT is a directory) is written below the directory
    /// OUT, made if needed, one file per sketch named after its model
    /// (`OUT/Bielle/Sketch005.ron`).
    Convert {
        /// The CAD file.
        #[arg(value_name = "FILE")]
        input: PathBuf,
        /// Where to write the RON.
        #[arg(short, long, value_name = "OUT")]
        output: Option<PathBuf>,
    },
    /// Write the solution navigator of one model as a self-contained HTML page: the sketch
    /// solved and drawn, the solve's plan beside it as the DR-plan's tree, each node's
    /// candidates to pick (the core's nodes and the closed-form steps; the realization
    /// re-assembled and redrawn), autosolve (the drawing's choices) and a download of the
    /// realization shown as RON. The realizations are computed in advance (every combination
    /// of the nodes' candidates that keeps the consistent redundant constraints, up to
    /// --max-solutions).
    Navigate {
        /// The model file (RON, or a CAD file: name the sketch with --sketch when it has
        /// several).
        #[arg(value_name = "FILE")]
        input: PathBuf,
        /// The page to write.
        #[arg(short, long, value_name = "PAGE.html")]
        output: PathBuf,
        /// The sketch of a CAD file holding several (its model name).
        #[arg(long, value_name = "NAME")]
        sketch: Option<String>,
        /// Embed at most N realizations (the page says when there were more).
        #[arg(long, value_name = "N", default_value_t = 256,
              value_parser = clap::value_parser!(u32).range(1..=10_000))]
        max_solutions: u32,
        /// The most homotopy paths each node of the core may track to enumerate its
        /// candidates (as `gcs solve --max-paths`); 0 keeps the core as solved.
        #[arg(long, value_name = "N", default_value_t = 4096,
              value_parser = clap::value_parser!(u32).range(0..=16384))]
        max_paths: u32,
    },
    /// Print a generated model of a family of growing size (the benchmark families) as RON.
    Generate {
        /// The family: `rectangles` (N fixed CAD rectangles), `grid` (a connected CAD plate:
        /// N × N rectangular cells sharing sides, a hole in each), `laman` (a random rigid 2D bar
        /// framework on N points), `laman-sketch` (the same as a CAD program writes it:
        /// 10-digit decimal coordinates, one redundant distance), `laman-drawn` (a random
        /// Laman realization drawn with 20% jitter, for the solver), `sphere` (a random
        /// triangulated sphere on N points, 3D).
        #[arg(value_enum)]
        family: Family,
        /// The size.
        size: usize,
        /// Seed of the random families.
        #[arg(long, default_value_t = 1)]
        seed: u64,
    },
}

/// Generated families.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum Family {
    /// Fully constrained CAD rectangles with Fix, Horizontal, Vertical and two dimensions.
    Rectangles,
    /// A connected CAD plate: an N × N grid of cells sharing their sides, a dimensioned hole
    /// in each (about 4N² entities).
    Grid,
    /// A random 2D Laman graph (Henneberg moves) as a bar framework.
    Laman,
    /// A random Laman framework with 10-digit decimal coordinates and one redundant distance.
    LamanSketch,
    /// A random Laman realization drawn with 20% jitter (the solver benchmarks), one redundant
    /// distance.
    LamanDrawn,
    /// A random triangulated sphere as a 3D bar framework.
    Sphere,
}

/// Arithmetic backends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum BackendArg {
    /// The rank over Q, proven (modular elimination certified over Q, or rational).
    Exact,
    /// Rational elimination with num-rational.
    Rational,
    /// Rational elimination with GMP (build with --features rug).
    Rug,
    /// Elimination modulo 2^61 − 1 (exact with overwhelming probability, not proven).
    Modp,
    /// f64 elimination with a relative tolerance.
    Float,
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
        Command::Convert { input, output } => convert::run(&input, output.as_deref()),
        Command::Navigate { input, output, sketch, max_solutions, max_paths } => navigate::run(
            &input,
            &output,
            sketch.as_deref(),
            max_solutions as usize,
            max_paths as usize,
        ),
        Command::Solve { format, out, all, max_solutions, choose, max_paths, jobs, paths } => {
            let options = gcs_solve::SolveOptions {
                all: all.then_some(max_solutions as usize),
                choose,
                max_paths: max_paths as usize,
                ..gcs_solve::SolveOptions::default()
            };
            solve::run(&paths, format, out.as_deref(), &options, jobs.unwrap_or_else(cores))
        }
        Command::Analyze {
            backend,
            seed,
            tolerance,
            format,
            structural,
            decompose,
            no_pebble_game,
            dot,
            svg,
            jobs,
            shard,
            timeout,
            only_model,
            paths,
        } => {
            if !(tolerance.is_finite() && tolerance >= 0.0) {
                eprintln!("error: --tolerance must be a finite number ≥ 0");
                return ExitCode::from(2);
            }
            let backend_arg = backend;
            let backend = match backend {
                BackendArg::Exact => Backend::Exact,
                BackendArg::Rational => Backend::Rational,
                BackendArg::Rug => Backend::Rug,
                BackendArg::Modp => Backend::ModP,
                BackendArg::Float => Backend::Float { tolerance },
            };
            if !backend.available() {
                eprintln!(
                    "error: the rug backend is not in this build; rebuild with --features rug"
                );
                return ExitCode::from(2);
            }
            let decompose = decompose || dot.is_some();
            if timeout.is_some() && dot.is_some() {
                eprintln!("error: --timeout and --dot cannot be combined");
                return ExitCode::from(2);
            }
            // What each model's own process is run with under --timeout.
            let name = |v: Option<clap::builder::PossibleValue>| {
                v.map(|v| v.get_name().to_owned()).unwrap_or_default()
            };
            let mut child_args = vec![
                "analyze".to_owned(),
                "--backend".to_owned(),
                name(backend_arg.to_possible_value()),
                "--tolerance".to_owned(),
                tolerance.to_string(),
                "--seed".to_owned(),
                seed.to_string(),
                "--format".to_owned(),
                name(format.to_possible_value()),
            ];
            if structural {
                child_args.push("--structural".to_owned());
            }
            if decompose {
                child_args.push("--decompose".to_owned());
            }
            if no_pebble_game {
                child_args.push("--no-pebble-game".to_owned());
            }
            if let Some(dir) = &svg {
                child_args.push("--svg".to_owned());
                child_args.push(dir.display().to_string());
            }
            analyze::run(
                &paths,
                &analyze::Settings {
                    backend,
                    seed,
                    format,
                    structural,
                    decompose,
                    pebble_game: !no_pebble_game,
                    dot,
                    svg,
                    jobs: jobs.unwrap_or_else(cores),
                    shard,
                    timeout: timeout.map(|limit| analyze::Timeout { limit, child_args }),
                    only_model,
                },
            )
        }
        Command::Generate { family, size, seed } => {
            let system = match family {
                Family::Rectangles => gcs_model::generate::rectangles(size),
                Family::Grid => gcs_model::generate::grid(size),
                Family::Laman => gcs_model::generate::laman(size, seed),
                Family::LamanSketch => gcs_model::generate::laman_sketch(size, seed),
                Family::LamanDrawn => gcs_model::generate::laman_drawn(size, seed, 0.2).0,
                Family::Sphere => gcs_model::generate::triangulated_sphere(size, seed),
            };
            let mut out = batch::Out::new();
            out.line(system.to_ron().trim_end());
            out.flush();
            ExitCode::SUCCESS
        }
    }
}
