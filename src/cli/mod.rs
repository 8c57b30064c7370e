//! Command-line interface: one file per command. Exit codes: 0 success, 1 failure of the
//! environment (I/O), 2 bad input (arguments, presets).

/// `println!` that returns a [`CliError`] (exit 1) when stdout cannot be written (a full
/// disk, `> /dev/full`) instead of panicking. For functions returning `Result<_, CliError>`.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*).map_err($crate::cli::stdout_error)?
    }};
}

mod bake;
mod completions;
mod eval;
mod guards;
mod inspect;
mod laws;
mod list;
mod measured;
mod measured_table;
/// The sidecar kind of the tables `measured --out` writes.
pub const MEASURED_TABLE_KIND: &str = measured_table::KIND;
mod probe;
mod report;
mod verify;

use clap::{Parser, Subcommand};
use std::ffi::OsString;

/// Exit code for success.
pub const EXIT_OK: i32 = 0;
/// Exit code for a failure of the environment (I/O, permissions, disk).
pub const EXIT_FAILURE: i32 = 1;
/// Exit code for bad input (arguments, presets).
pub const EXIT_INPUT: i32 = 2;

#[derive(Parser, Debug)]
#[command(
    name = "brdfbake",
    version,
    about = "Bake exact, documented BRDF lookup textures (DFG, albedo, NDF, G) for real-time renderers",
    after_help = "Exit codes: 0 success, 1 failure (I/O, environment, check or verify failed), 2 bad input."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Bake presets into textures + JSON metadata (default: every preset into out/).
    Bake(bake::BakeArgs),
    /// List the available presets and table kinds.
    List(list::ListArgs),
    /// Show what a texture brdfbake wrote holds: kind, model, axes, channels, statistics.
    Inspect(inspect::InspectArgs),
    /// Sample a texture as a GPU would (linear, clamp-to-edge) next to the exact value.
    Probe(probe::ProbeArgs),
    /// Compute a quantity directly (D, G1, G2, E, E_avg, split sum, sheen), without a table.
    Eval(eval::EvalArgs),
    /// Recompute a spread of texels at high accuracy; exit 1 over the tolerance.
    Verify(verify::VerifyArgs),
    /// Write a self-contained HTML report (heatmaps, E curves, Karis' approximation) of presets.
    Report(report::ReportArgs),
    /// Measure the two laws (reciprocity, energy conservation) of models or a MERL file.
    Laws(laws::LawsArgs),
    /// A measured BRDF (MERL file): unmeasured entries, albedo per channel, GGX + Lambert fit.
    Measured(measured::MeasuredArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    Completions(completions::CompletionsArgs),
    /// Print the man page (roff), of brdfbake or of one subcommand.
    Man(completions::ManArgs),
}

/// An error with its exit code.
#[derive(Debug)]
pub struct CliError {
    pub code: i32,
    pub msg: String,
}

impl CliError {
    pub fn input(msg: impl Into<String>) -> Self {
        CliError {
            code: EXIT_INPUT,
            msg: msg.into(),
        }
    }
    pub fn env(msg: impl Into<String>) -> Self {
        CliError {
            code: EXIT_FAILURE,
            msg: msg.into(),
        }
    }
}

impl From<crate::pipeline::PipelineError> for CliError {
    fn from(e: crate::pipeline::PipelineError) -> Self {
        use crate::pipeline::PipelineError as P;
        match e {
            P::Input(m) => CliError::input(m),
            P::Environment(m) | P::Failed(m) => CliError::env(m),
        }
    }
}

/// The error of a table that did not bake: exit 1 for one that ran out of time or missed its
/// tolerance (the inputs were valid), exit 2 for invalid inputs.
pub(crate) fn bake_error(preset: &str, e: crate::table::BakeError) -> CliError {
    use crate::table::BakeError as B;
    let msg = format!("preset {preset}: {e}");
    match e {
        B::TimeLimit { .. } | B::ToleranceMissed { .. } => CliError::env(msg),
        _ => CliError::input(msg),
    }
}

/// The error of a failed write to stdout.
pub(crate) fn stdout_error(e: std::io::Error) -> CliError {
    CliError::env(format!("cannot write to stdout: {e}"))
}

/// Runs the CLI and returns the process exit code.
pub fn run<I: IntoIterator<Item = OsString>>(args: I) -> i32 {
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { EXIT_INPUT } else { EXIT_OK };
            if let Err(w) = e.print() {
                // --help or --version into a full stdout
                if code == EXIT_OK {
                    eprintln!("error: {}", stdout_error(w).msg);
                    return EXIT_FAILURE;
                }
            }
            return code;
        }
    };
    let r = match cli.command {
        Command::Bake(a) => bake::run(a),
        Command::List(a) => list::run(a),
        Command::Inspect(a) => inspect::run(a),
        Command::Probe(a) => probe::run(a),
        Command::Eval(a) => eval::run(a),
        Command::Verify(a) => verify::run(a),
        Command::Report(a) => report::run(a),
        Command::Laws(a) => laws::run(a),
        Command::Measured(a) => measured::run(a),
        Command::Completions(a) => completions::run(a),
        Command::Man(a) => completions::run_man(a),
    };
    match r {
        Ok(()) => EXIT_OK,
        Err(e) => {
            eprintln!("error: {}", e.msg);
            e.code
        }
    }
}
