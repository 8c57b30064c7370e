//! Command-line interface: one file per command. Exit codes: 0 success, 1 failure of the
//! environment (I/O), 2 bad input (arguments, presets).

mod bake;
mod list;

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
    after_help = "Exit codes: 0 success, 1 I/O or environment failure, 2 bad input."
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

/// Runs the CLI and returns the process exit code.
pub fn run<I: IntoIterator<Item = OsString>>(args: I) -> i32 {
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { EXIT_INPUT } else { EXIT_OK };
            let _ = e.print();
            return code;
        }
    };
    let r = match cli.command {
        Command::Bake(a) => bake::run(a),
        Command::List(a) => list::run(a),
    };
    match r {
        Ok(()) => EXIT_OK,
        Err(e) => {
            eprintln!("error: {}", e.msg);
            e.code
        }
    }
}
