//! The CLI's errors and exit codes: 0 success, 1 failure (environment, a check that failed,
//! a tolerance or time limit missed), 2 bad input. Every command returns a [`CliError`];
//! the errors of the library map to it here.

/// Exit code for success.
pub const EXIT_OK: i32 = 0;
/// Exit code for a failure of the environment (I/O, permissions, disk).
pub const EXIT_FAILURE: i32 = 1;
/// Exit code for bad input (arguments, presets).
pub const EXIT_INPUT: i32 = 2;

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

impl From<crate::input::InputError> for CliError {
    fn from(e: crate::input::InputError) -> Self {
        match e {
            crate::input::InputError::Input(m) => CliError::input(m),
            crate::input::InputError::Io(m) => CliError::env(m),
        }
    }
}

impl From<crate::merl::MerlError> for CliError {
    fn from(e: crate::merl::MerlError) -> Self {
        use crate::merl::MerlError as M;
        match e {
            M::Format(m) => CliError::input(m),
            M::Io(m, std::io::ErrorKind::NotFound) => CliError::input(m),
            M::Io(m, _) => CliError::env(m),
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
        B::TimeLimit { .. } | B::ToleranceMissed { .. } | B::FitFailed { .. } => CliError::env(msg),
        _ => CliError::input(msg),
    }
}

/// The error of a failed write to stdout.
pub(crate) fn stdout_error(e: std::io::Error) -> CliError {
    CliError::env(format!("cannot write to stdout: {e}"))
}

/// `s` safe to print on a terminal: control characters (ESC, BEL, NUL, ... but not newline
/// and tab) and the Unicode direction overrides, which could come from a preset's keys or
/// values or a file name, are written as escapes (`\u{1b}`), so a message cannot move the
/// cursor, ring, recolour or reorder what the user reads.
pub fn terminal_safe(s: &str) -> std::borrow::Cow<'_, str> {
    let unsafe_char = |c: char| {
        (c.is_control() && c != '\n' && c != '\t')
            || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{200e}' | '\u{200f}')
    };
    if !s.chars().any(unsafe_char) {
        return std::borrow::Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if unsafe_char(c) {
            out.push_str(&format!("\\u{{{:x}}}", c as u32));
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::terminal_safe;

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(terminal_safe("plain\n\tline"), "plain\n\tline");
        assert_eq!(
            terminal_safe("a\u{1b}[31mb\u{7}\u{0}"),
            "a\\u{1b}[31mb\\u{7}\\u{0}"
        );
        assert_eq!(terminal_safe("a\u{202e}b"), "a\\u{202e}b");
    }
}
