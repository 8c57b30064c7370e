//! `brdfbake._native`: the Python module's native half, a thin layer over the brdfbake
//! library as `src/main.rs` is over `brdfbake::cli` — it runs the CLI's own code paths
//! (argument parsing, presets, guards, baking, encoders, writer) and adds no logic of its
//! own. The Python package (`python/brdfbake/__init__.py`) turns keyword arguments into the
//! CLI's flags and the results into numpy arrays and dicts.
//!
//! Every call runs its work on a thread of its own with the GIL released, while the calling
//! thread waits and checks for signals: on Ctrl-C the work is cancelled through its deadline
//! ([`brdfbake::deadline::cancellable`]: it stops within one texel, nothing is written) and
//! the `KeyboardInterrupt` is raised.
//!
//! Errors map one to one: bad input (the CLI's exit 2) is `ValueError` with the CLI's message;
//! work that ran and failed (exit 1: a tolerance or the time limit missed, `verify` over its
//! tolerance) is [`Failure`] (a `RuntimeError`), holding what the command printed before
//! failing; a write that failed is `OSError`.

use brdfbake::cli::CliError;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::ffi::OsString;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::Duration;

pyo3::create_exception!(
    brdfbake,
    Failure,
    PyRuntimeError,
    "The work ran and failed (the CLI's exit code 1): a table missed its tolerance, the time \
     limit (max_time) was reached, verify found texels over its tolerance. `output` holds what \
     the command printed before failing (verify's JSON document), or None."
);

/// How often the waiting thread checks for signals (Ctrl-C).
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Why a call failed, before it becomes a Python exception.
enum Error {
    /// A command's error, with what it printed before (its JSON document, if any).
    Cli(CliError, String),
    /// Writing the files failed.
    Write(String),
}

impl Error {
    fn into_py(self, py: Python<'_>) -> PyErr {
        match self {
            Error::Cli(e, _) if e.code == brdfbake::cli::EXIT_INPUT => PyValueError::new_err(e.msg),
            Error::Cli(e, out) => {
                let err = Failure::new_err(e.msg);
                let out = (!out.is_empty()).then_some(out);
                // (a fresh exception object: setting an attribute cannot fail)
                let _ = err.value(py).setattr("output", out);
                err
            }
            Error::Write(m) => PyOSError::new_err(m),
        }
    }
}

/// Runs `work` on a thread of its own, cancellable, with the GIL released; the calling thread
/// checks for signals every [`SIGNAL_POLL`] and, when one raises (Ctrl-C), cancels the work,
/// waits for it to stop and raises that exception.
fn run_cancellable<T: Send + 'static>(
    py: Python<'_>,
    work: impl FnOnce() -> Result<T, Error> + Send + 'static,
) -> PyResult<T> {
    let flag = Arc::new(AtomicBool::new(false));
    let (tx, rx) = mpsc::channel();
    let worker = {
        let flag = flag.clone();
        std::thread::Builder::new()
            .name("brdfbake".into())
            .spawn(move || {
                let r = brdfbake::deadline::cancellable(flag, work);
                let _ = tx.send(r);
            })
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start a thread: {e}")))?
    };
    let mut rx = rx;
    loop {
        // (the receiver is not Sync: it goes into the GIL-free closure and comes back)
        let (back, r) = py.detach(move || {
            let r = rx.recv_timeout(SIGNAL_POLL);
            (rx, r)
        });
        rx = back;
        match r {
            Ok(r) => return r.map_err(|e| e.into_py(py)),
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                // the worker ended without sending: it panicked
                let why = match py.detach(move || worker.join()) {
                    Err(p) => p
                        .downcast_ref::<String>()
                        .cloned()
                        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                        .unwrap_or_else(|| "(no message)".into()),
                    Ok(()) => "(no result)".into(),
                };
                return Err(PyRuntimeError::new_err(format!(
                    "brdfbake: internal error (a panic): {why}"
                )));
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    flag.store(true, Ordering::Relaxed);
                    // the work stops at its next deadline check; whatever it returns, the
                    // signal's exception is what the caller sees
                    py.detach(move || {
                        let _ = rx.recv();
                    });
                    return Err(e);
                }
            }
        }
    }
}

/// `brdfbake ARGS` (without the program name) with its output returned, as the CLI runs it:
/// the `--json` document of eval, probe, verify, inspect, compare, list.
#[pyfunction]
fn run(py: Python<'_>, args: Vec<String>) -> PyResult<String> {
    run_cancellable(py, move || {
        let argv =
            std::iter::once(OsString::from("brdfbake")).chain(args.into_iter().map(OsString::from));
        brdfbake::cli::run_captured(argv).map_err(|(e, out)| Error::Cli(e, out))
    })
}

/// The preset to bake: a name or path as `bake` takes it, or a preset's JSON text and the
/// name it gets (its output folder).
#[derive(FromPyObject)]
enum PresetArg {
    #[pyo3(transparent)]
    Named(String),
    Text(String, String),
}

/// The preset of `arg`, as `bake` resolves a name or path; JSON text is parsed as a preset
/// file's, under `name`, which must be a valid preset name (it is the output folder).
fn preset(arg: PresetArg) -> Result<brdfbake::preset::Preset, Error> {
    let input = |m: String| Error::Cli(CliError::input(m), String::new());
    match arg {
        PresetArg::Named(n) => brdfbake::cli::resolve_presets(&[n])
            .map(|mut v| v.remove(0))
            .map_err(|e| Error::Cli(e, String::new())),
        PresetArg::Text(text, name) => {
            if !brdfbake::preset::valid_name(&name) {
                return Err(input(format!(
                    "name {name:?}: a preset's name is its output folder; use 1-64 characters from \
                     a-z, A-Z, 0-9, '-', '_', not starting with '-'"
                )));
            }
            brdfbake::preset::parse(&text, "the preset dict", &name)
                .map_err(|e| input(e.to_string()))
        }
    }
}

/// `bake`'s flags (`--threads`, `--format`, `--max-memory`, `--max-time`, `--out`), parsed
/// by the CLI's own parser.
fn bake_args(flags: Vec<String>) -> Result<brdfbake::cli::BakeArgs, Error> {
    let argv = ["brdfbake", "bake"]
        .into_iter()
        .map(OsString::from)
        .chain(flags.into_iter().map(OsString::from));
    match brdfbake::cli::parse(argv) {
        Ok(brdfbake::cli::Cli {
            command: brdfbake::cli::Command::Bake(a),
        }) => Ok(a),
        Ok(_) => unreachable!("`bake` parses as bake"),
        Err(e) => Err(Error::Cli(e, String::new())),
    }
}

/// The files a bake would write (path, bytes), and its warnings.
type BakedFiles = (Vec<(String, Py<PyBytes>)>, Vec<String>);

/// Bakes `preset` in memory as `brdfbake bake PRESET FLAGS` does, writing nothing: the files
/// it would write (path, bytes) and its warnings.
#[pyfunction]
fn bake(py: Python<'_>, preset: PresetArg, flags: Vec<String>) -> PyResult<BakedFiles> {
    let (files, warnings) = run_cancellable(py, move || {
        let args = bake_args(flags)?;
        let preset = self::preset(preset)?;
        let baked = brdfbake::cli::bake_in_memory(&args, std::slice::from_ref(&preset))
            .map_err(|e| Error::Cli(e, String::new()))?;
        Ok((baked.files, baked.warnings))
    })?;
    let files = files
        .into_iter()
        .map(|(p, b)| (p.display().to_string(), PyBytes::new(py, &b).unbind()))
        .collect();
    Ok((files, warnings))
}

/// Bakes `preset` and writes its files as `brdfbake bake PRESET FLAGS --json` does: the
/// document it prints, and its warnings.
#[pyfunction]
fn write(py: Python<'_>, preset: PresetArg, flags: Vec<String>) -> PyResult<(String, Vec<String>)> {
    run_cancellable(py, move || {
        let started = std::time::Instant::now();
        let args = bake_args(flags)?;
        let preset = self::preset(preset)?;
        let baked = brdfbake::cli::bake_in_memory(&args, std::slice::from_ref(&preset))
            .map_err(|e| Error::Cli(e, String::new()))?;
        brdfbake::pipeline::write_files(&baked.files).map_err(|e| Error::Write(e.to_string()))?;
        let doc = brdfbake::cli::summary_json(
            &args.out,
            started.elapsed().as_secs_f64(),
            &baked.tables,
            &baked.table_warnings,
        );
        Ok((doc.to_string(), baked.warnings))
    })
}

/// The `brdfbake` command (the wheel's console script): runs the CLI on `argv` (the program
/// name first) and returns its exit code. The caller restores the default dispositions of
/// SIGINT and SIGPIPE first, as the binary has them.
#[pyfunction]
fn main(py: Python<'_>, argv: Vec<String>) -> i32 {
    py.detach(move || brdfbake::cli::run(argv.into_iter().map(OsString::from)))
}

/// The built-in presets' names and the built-in engine presets' names.
#[pyfunction]
fn presets() -> (Vec<&'static str>, Vec<&'static str>) {
    let names = |v: &[(&'static str, &str)]| v.iter().map(|(n, _)| *n).collect();
    (
        names(brdfbake::presets::BUILTIN),
        names(brdfbake::presets::ENGINES),
    )
}

/// The brdfbake library's version.
#[pyfunction]
fn version() -> &'static str {
    brdfbake::meta::VERSION
}

/// brdfbake's native module: the library's commands, run as the CLI runs them (use the
/// `brdfbake` package, not this module).
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(bake, m)?)?;
    m.add_function(wrap_pyfunction!(write, m)?)?;
    m.add_function(wrap_pyfunction!(main, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    m.add("Failure", m.py().get_type::<Failure>())?;
    Ok(())
}
