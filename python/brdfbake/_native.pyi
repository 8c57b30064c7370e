"""Type stubs of brdfbake's native module (python/src/lib.rs): the library's commands, run
as the command line runs them. Use the ``brdfbake`` package; this module is its native half."""

from typing import List, Optional, Tuple, Union

class Failure(RuntimeError):
    """The work ran and failed (the CLI's exit code 1): a table missed its tolerance, the
    time limit was reached, verify found texels over its tolerance."""

    #: What the command printed before failing (verify's JSON document), or None.
    output: Optional[str]

def run(args: List[str]) -> str:
    """``brdfbake ARGS`` (without the program name); returns what it prints on stdout."""

def bake(
    preset: Union[str, Tuple[str, str]], flags: List[str]
) -> Tuple[List[Tuple[str, bytes]], List[str]]:
    """Bakes a preset (a name or path, or (JSON text, name)) in memory as
    ``brdfbake bake PRESET FLAGS`` does: the files it would write (path, bytes), and its
    warnings."""

def write(preset: Union[str, Tuple[str, str]], flags: List[str]) -> Tuple[str, List[str]]:
    """Bakes and writes a preset as ``brdfbake bake PRESET FLAGS --json`` does: the JSON
    document it prints, and its warnings."""

def main(argv: List[str]) -> int:
    """The ``brdfbake`` command on ``argv`` (the program name first): its exit code."""

def presets() -> Tuple[List[str], List[str]]:
    """The built-in presets' names, and the built-in engine presets' names."""

def version() -> str:
    """The brdfbake library's version."""
