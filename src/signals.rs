//! SIGINT, SIGTERM and SIGHUP while outputs are being replaced. Outside the write phase the
//! signals keep their default action (the process ends; nothing has been written). Inside it
//! ([`Critical`]), a signal is only recorded: the writer finishes the directory exchange under
//! way or removes what it staged, then [`Critical::finish`] ends the process by the same
//! signal, so the caller (a shell, CI) sees the usual status and every table reads as
//! entirely old or entirely new. A process that is killed outright (SIGKILL) leaves only
//! staging directories that no reader looks at, removed by the next bake.
//!
//! Only the binary installs the handler ([`install`]); the library used from other programs
//! keeps their signal dispositions.

use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};

/// Whether a write phase is under way.
static CRITICAL: AtomicBool = AtomicBool::new(false);
/// The signal that arrived during the write phase (0: none).
static PENDING: AtomicI32 = AtomicI32::new(0);
/// Whether [`install`] ran.
static INSTALLED: AtomicBool = AtomicBool::new(false);

#[cfg(unix)]
const SIGNALS: [libc::c_int; 3] = [libc::SIGINT, libc::SIGTERM, libc::SIGHUP];

#[cfg(unix)]
extern "C" fn on_signal(sig: libc::c_int) {
    if CRITICAL.load(Ordering::SeqCst) {
        PENDING.store(sig, Ordering::SeqCst);
    } else {
        // SAFETY: signal() and raise() are async-signal-safe: the default action ends the
        // process as if no handler had been installed
        unsafe {
            libc::signal(sig, libc::SIG_DFL);
            libc::raise(sig);
        }
    }
}

/// Installs the handler for SIGINT, SIGTERM and SIGHUP (the binary calls it first thing).
pub fn install() {
    #[cfg(unix)]
    for sig in SIGNALS {
        // SAFETY: the handler only touches atomics and calls async-signal-safe functions
        unsafe {
            libc::signal(sig, on_signal as *const () as libc::sighandler_t);
        }
    }
    INSTALLED.store(true, Ordering::SeqCst);
}

/// The write phase: signals are recorded, not acted on, until [`Critical::finish`] (or drop).
pub struct Critical(());

impl Critical {
    /// Enters the write phase.
    pub fn begin() -> Critical {
        CRITICAL.store(true, Ordering::SeqCst);
        Critical(())
    }

    /// The signal received since [`Critical::begin`], if any.
    pub fn interrupted(&self) -> Option<i32> {
        match PENDING.load(Ordering::SeqCst) {
            0 => None,
            s => Some(s),
        }
    }

    /// Leaves the write phase; a signal received during it now takes its default action
    /// (the process ends by it).
    pub fn finish(self) {}
}

impl Drop for Critical {
    fn drop(&mut self) {
        CRITICAL.store(false, Ordering::SeqCst);
        let sig = PENDING.swap(0, Ordering::SeqCst);
        #[cfg(unix)]
        if sig != 0 && INSTALLED.load(Ordering::SeqCst) {
            // SAFETY: restoring the default action and re-raising, as the handler would have
            unsafe {
                libc::signal(sig, libc::SIG_DFL);
                libc::raise(sig);
            }
        }
        #[cfg(not(unix))]
        let _ = sig;
    }
}
