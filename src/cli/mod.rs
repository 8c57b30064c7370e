//! Command-line interface: one file per command. Exit codes: 0 success, 1 failure of the
//! environment (I/O), 2 bad input (arguments, presets).

/// `println!` that returns a [`CliError`] (exit 1) when stdout cannot be written (a full
/// disk, `> /dev/full`) instead of panicking. For functions returning `Result<_, CliError>`.
/// Under [`run_captured`] the line goes to its buffer instead.
macro_rules! outln {
    () => {
        outln!("")
    };
    ($($arg:tt)*) => {{
        $crate::cli::out_line(format_args!($($arg)*)).map_err($crate::cli::stdout_error)?
    }};
}

mod bake;
mod compare;
mod completions;
mod error;
mod eval;
mod fit;
mod guards;
mod inspect;
mod laws;
mod list;
mod measured;
mod measured_table;
mod probe;
mod report;
mod verify;

pub use bake::{bake_in_memory, resolve as resolve_presets, summary_json, BakeArgs, InMemory};
pub(crate) use error::{bake_error, stdout_error};
pub use error::{CliError, EXIT_FAILURE, EXIT_INPUT, EXIT_OK};

use clap::{Parser, Subcommand};
use std::cell::RefCell;
use std::ffi::OsString;

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
    /// Minimax fits of a table as shader functions: the Pareto front, errors against the exact integral.
    Fit(fit::FitArgs),
    /// Recompute a spread of texels at high accuracy; exit 1 over the tolerance.
    Verify(verify::VerifyArgs),
    /// Compare an engine's shipped table with exact values at its texels, beside brdfbake's.
    Compare(compare::CompareArgs),
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

thread_local! {
    /// The output buffer of the [`run_captured`] call running on this thread.
    static CAPTURED: RefCell<Option<Vec<u8>>> = const { RefCell::new(None) };
}

/// Writes one line of a command's output: to stdout, or to [`run_captured`]'s buffer.
pub(crate) fn out_line(line: std::fmt::Arguments) -> std::io::Result<()> {
    use std::io::Write as _;
    CAPTURED.with_borrow_mut(|buf| match buf {
        Some(buf) => writeln!(buf, "{line}"),
        None => writeln!(std::io::stdout().lock(), "{line}"),
    })
}

/// Parses the command line (`args[0]` the program name) as [`run`] does: a usage error is
/// bad input, with clap's message (without its `error: ` prefix and its closing pointer to
/// `--help`).
pub fn parse<I: IntoIterator<Item = OsString>>(args: I) -> Result<Cli, CliError> {
    Cli::try_parse_from(args).map_err(|e| {
        let text = e.render().to_string();
        let text = text.strip_prefix("error: ").unwrap_or(&text).trim_end();
        let text = text
            .strip_suffix("For more information, try '--help'.")
            .unwrap_or(text)
            .trim_end();
        CliError {
            code: if e.use_stderr() { EXIT_INPUT } else { EXIT_OK },
            msg: text.to_string(),
        }
    })
}

/// Runs the CLI on `args` as [`run`] does, for embedders (the Python module): what the
/// command printed on stdout is returned instead (its `--json` document), and its error is
/// returned with whatever it printed before failing (`verify`'s document before exit 1).
/// `--help` and `--version` are returned as the text they print.
pub fn run_captured<I: IntoIterator<Item = OsString>>(
    args: I,
) -> Result<String, (CliError, String)> {
    let cli = match parse(args) {
        Ok(c) => c,
        Err(e) if e.code == EXIT_OK => return Ok(e.msg + "\n"),
        Err(e) => return Err((e, String::new())),
    };
    let previous = CAPTURED.replace(Some(Vec::new()));
    let r = execute(cli);
    let out = CAPTURED.replace(previous).unwrap_or_default();
    let out = String::from_utf8_lossy(&out).into_owned();
    match r {
        Ok(()) => Ok(out),
        Err(e) => Err((e, out)),
    }
}

/// Runs one parsed command.
fn execute(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Bake(a) => bake::run(a),
        Command::List(a) => list::run(a),
        Command::Inspect(a) => inspect::run(a),
        Command::Probe(a) => probe::run(a),
        Command::Eval(a) => eval::run(a),
        Command::Verify(a) => verify::run(a),
        Command::Fit(a) => fit::run(a),
        Command::Report(a) => report::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Laws(a) => laws::run(a),
        Command::Measured(a) => measured::run(a),
        Command::Completions(a) => completions::run(a, <Cli as clap::CommandFactory>::command()),
        Command::Man(a) => completions::run_man(a, <Cli as clap::CommandFactory>::command()),
    }
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
    match execute(cli) {
        Ok(()) => EXIT_OK,
        Err(e) => {
            eprintln!("error: {}", error::terminal_safe(&e.msg));
            e.code
        }
    }
}
