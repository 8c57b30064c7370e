//! The `brdfbake` command: parses arguments and maps errors to exit codes; the work is in
//! the library.

fn main() {
    // A file-size limit (`ulimit -f`) must surface as a write error (EFBIG: exit 1 with a
    // message, previous outputs intact), not kill the process with SIGXFSZ mid-write.
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to SIG_IGN before any thread is started.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
    std::process::exit(brdfbake::cli::run(std::env::args_os()));
}
