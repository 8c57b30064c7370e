"""brdfbake: exact, documented BRDF lookup tables (split-sum DFG, albedo, D, G, LTC, ...)
baked into numpy arrays.

Each function runs the brdfbake command of the same name, from the same library code as the
``brdfbake`` command line (installed with this package): the same presets, checks, guards,
numbers and error messages. Keyword arguments are the command's flags (``max_memory=`` is
``--max-memory``); the results are what ``--json`` prints, as dicts.

- :func:`bake` bakes a preset in memory: each table a ``numpy.ndarray`` of its texels as
  stored, with its JSON sidecar as a dict.
- :func:`write` bakes a preset into files (EXR, KTX2, .npy, .npz, .bin, ...), as
  ``brdfbake bake`` does.
- :func:`eval`, :func:`probe`, :func:`verify`, :func:`inspect`, :func:`compare` return the
  command's JSON document.

Errors: bad input (the command line's exit code 2) raises ``ValueError`` with the CLI's
message; work that ran and failed (exit code 1) raises :class:`Failure`; a failed write
raises ``OSError``. The GIL is released while brdfbake works, and Ctrl-C stops it within a
texel (``KeyboardInterrupt``; nothing is written). See docs/python.md.
"""

from __future__ import annotations

import io
import json
import os
from typing import Any, Dict, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy

from . import _native
from ._native import Failure

__version__: str = _native.version()

__all__ = [
    "Baked",
    "Failure",
    "bake",
    "compare",
    "eval",
    "inspect",
    "presets",
    "probe",
    "verify",
    "write",
]

#: A preset: a built-in name (``"filament-dfg"``), a path to a preset file, or a dict in the
#: preset schema (``brdfbake.preset/1``, docs/presets.md).
PresetLike = Union[str, "os.PathLike[str]", Mapping[str, Any]]
#: A memory size: bytes, or a string with a unit (``"8GiB"``).
Size = Union[int, str]


class Baked(Mapping[str, numpy.ndarray]):
    """The tables of one preset baked in memory: ``baked[name]`` is table ``name``'s texels.

    Each array holds the texels exactly as the table's files store them (the same bits as
    its EXR or KTX2 texels): dtype ``float32``, ``float16``, ``uint8`` or ``uint16`` (the
    normalized-integer codes: value = code / 255 or / 65535) as the table's ``storage`` says,
    shape ``(ny, nx, channels)`` for a 2D table — the axes in reverse, then the channels, as
    an image's rows: ``baked["dfg"][y, x, c]`` is texel (x, y)'s channel c, x along the
    sidecar's first axis — ``(nx, channels)`` for 1D and ``(nz, ny, nx, channels)`` for 3D.
    Stored values are value × ``scale`` (``sidecars[name]["storage"]["scale"]``).
    """

    def __init__(
        self,
        preset: str,
        arrays: Dict[str, numpy.ndarray],
        sidecars: Dict[str, Dict[str, Any]],
        warnings: List[str],
    ) -> None:
        #: The preset's name.
        self.preset = preset
        self._arrays = arrays
        #: Each table's JSON sidecar (schema ``brdfbake.lut/1``, docs/metadata.md): its axes,
        #: channels, storage, how to sample it and the bake's error estimate. Its ``files``
        #: name the ``.npy`` file whose contents the array is.
        self.sidecars = sidecars
        #: What does not work in the tables' engines (a preset's ``engine`` field).
        self.warnings = warnings

    def __getitem__(self, table: str) -> numpy.ndarray:
        return self._arrays[table]

    def __iter__(self) -> Iterator[str]:
        return iter(self._arrays)

    def __len__(self) -> int:
        return len(self._arrays)

    def __repr__(self) -> str:
        tables = ", ".join(
            f"{n}: {a.dtype}{list(a.shape)}" for n, a in self._arrays.items()
        )
        return f"<brdfbake.Baked {self.preset}: {tables}>"


def _text(value: Any) -> str:
    """A flag's value as the command line spells it (floats exactly: ``repr``)."""
    if isinstance(value, bool):
        raise TypeError("a flag's value cannot be a bool")
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return str(value)


def _flags(**flags: Any) -> List[str]:
    """``--name value`` for every flag that is given (``True``: the flag alone)."""
    out: List[str] = []
    for name, value in flags.items():
        if value is None or value is False:
            continue
        flag = "--" + name.replace("_", "-")
        out += [flag] if value is True else [flag, _text(value)]
    return out


def _json(args: List[str]) -> Dict[str, Any]:
    """The JSON document of ``brdfbake ARGS --json``; a :class:`Failure` gets it as ``result``."""
    try:
        return json.loads(_native.run(args))
    except Failure as e:
        out = getattr(e, "output", None)
        e.result = json.loads(out) if out else None  # type: ignore[attr-defined]
        raise


def _preset(preset: PresetLike, name: Optional[str]) -> Union[str, Tuple[str, str]]:
    """What the native module takes: a name or path, or (JSON text, name) for a dict."""
    if isinstance(preset, Mapping):
        return (json.dumps(preset), name if name is not None else "preset")
    if name is not None:
        raise ValueError("name= applies to a preset given as a dict (a file's name is its stem)")
    return os.fspath(preset)


def bake(
    preset: PresetLike,
    *,
    name: Optional[str] = None,
    threads: Optional[int] = None,
    max_memory: Optional[Size] = None,
    max_time: Optional[float] = None,
) -> Baked:
    """Bakes ``preset`` in memory, as ``brdfbake bake PRESET`` does, and returns its tables.

    Args:
        preset: a built-in preset name (``"filament-dfg"``, ``"nvdiffrec-bsdf-256"``; a
            ``presets/`` folder in the working directory comes first, as for the CLI), a
            preset file's path, or a dict in the preset schema.
        name: the name of a dict preset (default ``"preset"``).
        threads: worker threads (default: all cores); the texels are the same for any count.
        max_memory: refuse (``ValueError``) a bake estimated over this (default ``"2GiB"``).
        max_time: seconds; refuse a bake estimated over it (``ValueError``) and stop one still
            running at it (:class:`Failure`) (default 600).

    Returns:
        A :class:`Baked` mapping of table name to texels, with each table's sidecar.
    """
    flags = ["--format", "npy"] + _flags(
        threads=threads, max_memory=max_memory, max_time=max_time
    )
    files, warnings = _native.bake(_preset(preset, name), flags)
    arrays: Dict[str, numpy.ndarray] = {}
    sidecars: Dict[str, Dict[str, Any]] = {}
    preset_name = ""
    for path, data in files:
        folder, file = os.path.split(path)
        preset_name = os.path.basename(folder)
        table, ext = os.path.splitext(file)
        if ext == ".npy":
            arrays[table] = numpy.load(io.BytesIO(data), allow_pickle=False)
        elif ext == ".json":
            sidecars[table] = json.loads(data)
    return Baked(preset_name, arrays, sidecars, warnings)


def write(
    preset: PresetLike,
    out: Union[str, "os.PathLike[str]"] = "out",
    *,
    formats: Union[None, str, Sequence[str]] = None,
    name: Optional[str] = None,
    threads: Optional[int] = None,
    max_memory: Optional[Size] = None,
    max_time: Optional[float] = None,
) -> Dict[str, Any]:
    """Bakes ``preset`` and writes its files into ``out/PRESET/``, as ``brdfbake bake`` does:
    every file of the bake replaced at once, or none (a failure leaves ``out`` as it was).

    Args:
        preset: as for :func:`bake`.
        out: the output directory.
        formats: the formats of every table instead of the preset's: a list or a
            comma-separated string of ``exr``, ``ktx2``, ``png``, ``png-data``, ``h``, ``rs``,
            ``glsl``, ``hlsl``, ``wgsl``, ``npy``, ``npz``, ``bin``. The JSON sidecar is always
            written.
        name, threads, max_memory, max_time: as for :func:`bake`.

    Returns:
        The document ``brdfbake bake --json`` prints: each table's size, axes, channels,
        error estimate, warnings and files.
    """
    if formats is not None and not isinstance(formats, str):
        formats = ",".join(formats)
    flags = _flags(
        out=out, format=formats, threads=threads, max_memory=max_memory, max_time=max_time
    )
    doc, _warnings = _native.write(_preset(preset, name), flags)
    result: Dict[str, Any] = json.loads(doc)
    return result


def eval(
    quantity: str,
    *,
    alpha: Optional[float] = None,
    roughness: Optional[float] = None,
    cos_theta: Optional[float] = None,
    cos_theta_l: Optional[float] = None,
    ndf: Optional[str] = None,
    masking: Optional[str] = None,
    f0: Optional[float] = None,
    tolerance: Optional[float] = None,
    max_memory: Optional[Size] = None,
    max_time: Optional[float] = None,
) -> Dict[str, Any]:
    """One quantity computed directly, without a table (``brdfbake eval``).

    Args:
        quantity: ``d``, ``g1``, ``g2``, ``e``, ``e-avg``, ``dfg`` or ``sheen``.
        alpha: the NDF's alpha, or
        roughness: perceptual roughness (alpha = roughness²).
        cos_theta: n·h for ``d``, n·v for the others.
        cos_theta_l: n·l (``g2``).
        ndf: ``beckmann``, ``ggx`` (default), ``gaussian``, ``blinn-phong``, ``charlie``.
        masking: ``none``, ``v-groove``, ``smith-separable``, ``smith-height-correlated``
            (default), ``ashikhmin``.
        f0: Schlick's F0 (``e``, ``e-avg``).
        tolerance: the quadrature's tolerance (default 1e-10).

    Returns:
        ``{"quantity", "model", "alpha", "values": {channel: value}, "error_estimates": {...}}``.
    """
    return _json(
        ["eval"]
        + _flags(
            alpha=alpha,
            roughness=roughness,
            cos_theta=cos_theta,
            cos_theta_l=cos_theta_l,
            ndf=ndf,
            masking=masking,
            f0=f0,
            tolerance=tolerance,
            max_memory=max_memory,
            max_time=max_time,
        )
        + ["--json", "--", quantity]
    )


def probe(
    file: Union[str, "os.PathLike[str]"],
    at: Mapping[str, float],
    *,
    filter: Optional[str] = None,
    polygon: Optional[Sequence[Sequence[float]]] = None,
    f0: Optional[float] = None,
    max_memory: Optional[Size] = None,
    max_time: Optional[float] = None,
) -> Dict[str, Any]:
    """What a GPU reads from a texture brdfbake wrote, next to the exact value (``brdfbake
    probe``).

    Args:
        file: a ``.exr``, ``.ktx2`` or png-data ``.png`` brdfbake wrote, or its sidecar.
        at: one value per axis, by the sidecar's axis names:
            ``{"cos_theta_v": 0.5, "roughness": 0.3}``.
        filter: ``ideal`` (default) or ``hardware`` (weights rounded to 1/256).
        polygon: an ltc table's polygon light, 3 to 8 vertices (x, y, z).
        f0: an ltc table's Schlick F0.
    """
    polygon_text = (
        None
        if polygon is None
        else " ".join(",".join(_text(float(c)) for c in v) for v in polygon)
    )
    at_text = ",".join(f"{k}={_text(float(v))}" for k, v in at.items())
    return _json(
        ["probe", "--at", at_text]
        + _flags(
            filter=filter,
            polygon=polygon_text,
            f0=f0,
            max_memory=max_memory,
            max_time=max_time,
        )
        + ["--json", "--", _text(file)]
    )


def verify(
    target: Union[str, "os.PathLike[str]"],
    *,
    tolerance: Optional[float] = None,
    all: bool = False,
    max_memory: Optional[Size] = None,
    max_time: Optional[float] = None,
) -> Dict[str, Any]:
    """Recomputes a spread of texels (``all=True``: every texel) at 1e-10 and compares
    (``brdfbake verify``).

    Args:
        target: a preset (name or file: baked in memory) or a ``.exr``/``.ktx2``/``.png``/
            ``.json`` file brdfbake wrote.
        tolerance: the largest accepted error per channel (default 1e-6).

    Returns:
        The verification document (``"ok"``, per table and channel the worst texels).

    Raises:
        Failure: a texel is over the tolerance; its ``result`` holds the document.
    """
    return _json(
        ["verify"]
        + _flags(tolerance=tolerance, all=all, max_memory=max_memory, max_time=max_time)
        + ["--json", "--", _text(target)]
    )


def inspect(
    file: Union[str, "os.PathLike[str]"],
    *,
    max_memory: Optional[Size] = None,
    max_time: Optional[float] = None,
) -> Dict[str, Any]:
    """What a texture brdfbake wrote (or its sidecar) holds (``brdfbake inspect``): kind,
    model, axes, channels, statistics, notes."""
    return _json(
        ["inspect"]
        + _flags(max_memory=max_memory, max_time=max_time)
        + ["--json", "--", _text(file)]
    )


def compare(
    preset: Union[str, "os.PathLike[str]"],
    file: Union[str, "os.PathLike[str]"],
    *,
    table: Optional[str] = None,
    max_memory: Optional[Size] = None,
    max_time: Optional[float] = None,
) -> Dict[str, Any]:
    """An engine's shipped table against exact values at its texels, beside brdfbake's
    (``brdfbake compare``): e.g. ``compare("nvdiffrec-bsdf-256", "bsdf_256_256.bin")``.

    Returns:
        The comparison document (schema ``brdfbake.compare/1``).
    """
    return _json(
        ["compare"]
        + _flags(table=table, max_memory=max_memory, max_time=max_time)
        + ["--json", "--", _text(preset), _text(file)]
    )


def presets() -> Dict[str, List[str]]:
    """The built-in presets' names: ``{"presets": [...], "engine_presets": [...]}`` (a bare
    ``brdfbake bake`` bakes the first list; engine presets are baked by name)."""
    builtin, engines = _native.presets()
    return {"presets": list(builtin), "engine_presets": list(engines)}
