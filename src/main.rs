//! The `brdfbake` command: parses arguments and maps errors to exit codes; the work is in
//! the library.

fn main() {
    // A file-size limit (`ulimit -f`) must surface as a write error (EFBIG: exit 1 with a
    // message, previous outputs intact), not kill the process with SIGXFSZ mid-write.
    // Output piped into a reader that stops early (`brdfbake list | head -1`) ends the
    // process quietly, as for any Unix filter, instead of panicking in `println!` on EPIPE
    // (Rust's runtime ignores SIGPIPE). Files are written atomically, so even a bake whose
    // stdout closes mid-way leaves every output old or new.
    #[cfg(unix)]
    // SAFETY: setting signal dispositions before any thread is started.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // SIGINT/SIGTERM/SIGHUP while outputs are being replaced end the process only once the
    // directory under way is complete (brdfbake::signals)
    brdfbake::signals::install();
    std::process::exit(brdfbake::cli::run(std::env::args_os()));
}
