"""The ``brdfbake`` command installed with the wheel: the same command line as the binary
(``cargo run --release --``), from the same library code."""

import signal
import sys


def main() -> int:
    """Runs ``brdfbake`` on ``sys.argv`` and returns its exit code (0, 1 or 2)."""
    from . import _native

    # The binary's signal dispositions: Ctrl-C ends the process at once (every output is
    # written atomically, so nothing partial is left), and output piped into a reader that
    # stops early ends it quietly. (Python ignores SIGXFSZ already, as the binary does.)
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    if hasattr(signal, "SIGPIPE"):
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    return _native.main(sys.argv)


if __name__ == "__main__":
    sys.exit(main())
