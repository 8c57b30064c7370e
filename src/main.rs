//! The `brdfbake` command: parses arguments and maps errors to exit codes; the work is in
//! the library.

fn main() {
    std::process::exit(brdfbake::cli::run(std::env::args_os()));
}
