//! `brdfbake completions SHELL` and `brdfbake man`: generated from the clap definition,
//! which the caller passes in (`Cli::command()`).

use super::error::{stdout_error, CliError};
use std::io::Write;

#[derive(clap::Args, Debug)]
pub struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_enum)]
    pub shell: clap_complete::Shell,
}

#[derive(clap::Args, Debug)]
pub struct ManArgs {
    /// The subcommand whose page to print (default: the top-level page, brdfbake(1)).
    pub subcommand: Option<String>,
}

fn write_out(bytes: &[u8]) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    out.write_all(bytes)
        .and_then(|_| out.flush())
        .map_err(stdout_error)
}

/// Prints a completion script: e.g. `brdfbake completions bash > /etc/bash_completion.d/brdfbake`.
pub fn run(a: CompletionsArgs, mut cmd: clap::Command) -> Result<(), CliError> {
    let mut buf = Vec::new();
    clap_complete::generate(a.shell, &mut cmd, "brdfbake", &mut buf);
    write_out(&buf)
}

/// Prints a roff man page: `brdfbake man > brdfbake.1`, `brdfbake man bake > brdfbake-bake.1`.
pub fn run_man(a: ManArgs, mut cmd: clap::Command) -> Result<(), CliError> {
    cmd.build();
    let page = match &a.subcommand {
        None => cmd,
        Some(name) => {
            let names: Vec<String> = cmd
                .get_subcommands()
                .map(|s| s.get_name().to_string())
                .collect();
            let sub = cmd.find_subcommand(name).cloned().ok_or_else(|| {
                CliError::input(format!(
                    "unknown subcommand {name:?} (accepted: {})",
                    names.join(", ")
                ))
            })?;
            // clap names are &'static without its `string` feature; this runs once per process
            sub.name(&*Box::leak(format!("brdfbake-{name}").into_boxed_str()))
        }
    };
    let mut buf = Vec::new();
    clap_mangen::Man::new(page)
        .render(&mut buf)
        .map_err(|e| CliError::env(format!("cannot render the man page: {e}")))?;
    write_out(&buf)
}
