//! The resource guards every command has: `--max-memory` and `--max-time`, checked against
//! estimates before any work (exit 2, with the estimate and the flag to raise), and the
//! time limit again while the work runs (a [`Deadline`] checked between texels, albedos or
//! fits: exit 1, nothing written). The estimates are in [`crate::resources`].

use super::CliError;
use crate::deadline::Deadline;
use crate::resources::{check_memory_of, check_time_of, TimeEstimate};

#[derive(clap::Args, Debug, Clone, Copy)]
pub struct Guards {
    /// Refuse (exit 2) a run whose estimated peak memory exceeds SIZE: bytes, or with a
    /// unit K, M, G, T (powers of 1024), e.g. 8GiB. Estimated from the requested sizes
    /// before anything is allocated.
    #[arg(long, value_name = "SIZE", default_value = "2GiB", value_parser = crate::resources::parse_size)]
    pub max_memory: u64,
    /// Refuse (exit 2) a run whose estimated wall time exceeds SECONDS (estimated from the
    /// requested sizes and typical costs before any work), and stop one that is still
    /// running after SECONDS (exit 1, nothing written).
    #[arg(long, value_name = "SECONDS", default_value = "600", value_parser = crate::resources::parse_seconds)]
    pub max_time: f64,
}

/// What a command is about to do, estimated.
pub struct Work<'a> {
    /// `"this verify"`: what needs the resources, for messages.
    pub what: &'a str,
    /// Peak bytes, and what they are (for the message).
    pub memory: u64,
    pub memory_detail: String,
    pub time: TimeEstimate,
    /// Threads the work runs on.
    pub threads: usize,
    /// How to ask for less (`"verify fewer texels"`).
    pub smaller: &'a str,
}

impl Guards {
    /// Refuses `work` over either limit (exit 2); otherwise starts the clock: the deadline
    /// the work must check while it runs.
    pub fn admit(&self, work: &Work) -> Result<Deadline, CliError> {
        check_memory_of(
            work.what,
            &work.memory_detail,
            work.smaller,
            work.memory,
            self.max_memory,
        )
        .map_err(CliError::input)?;
        check_time_of(
            work.what,
            work.smaller,
            &work.time,
            work.threads,
            self.max_time,
        )
        .map_err(CliError::input)?;
        Ok(Deadline::after(self.max_time))
    }
}

/// The error of work stopped at its deadline (exit 1).
pub fn stopped(what: &str, d: &Deadline) -> CliError {
    CliError::env(format!(
        "{what} stopped at the time limit of {} (--max-time) before it finished; nothing was written: \
         raise the limit or ask for less",
        crate::numfmt::human_seconds(d.seconds)
    ))
}

/// `--tolerance` of a command that integrates: in the range a table's `tolerance` accepts.
pub fn check_tolerance(t: f64) -> Result<(), CliError> {
    use crate::table::spec::{MAX_TOLERANCE, MIN_TOLERANCE};
    if (MIN_TOLERANCE..=MAX_TOLERANCE).contains(&t) {
        return Ok(());
    }
    Err(CliError::input(format!(
        "--tolerance must be in [{}, {}] (as a table's), got {}",
        crate::numfmt::num(MIN_TOLERANCE),
        crate::numfmt::num(MAX_TOLERANCE),
        crate::numfmt::num(t)
    )))
}
