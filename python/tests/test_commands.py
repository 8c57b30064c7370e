"""The package's commands give the CLI's documents, and its errors are the CLI's: bad input
raises ValueError with the CLI's message (exit 2), work that fails raises brdfbake.Failure
(exit 1), and the interpreter survives both. The `brdfbake` command installed with the wheel
is the CLI. The stubs (.pyi) match the native module."""

import ast
import inspect
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import brdfbake
from brdfbake import _native
from conftest import files


def test_version_is_the_cli_version(cli):
    assert cli.ok("--version").split() == ["brdfbake", brdfbake.__version__]


def test_presets_are_the_built_in_ones(cli):
    names = brdfbake.presets()
    listed = cli.ok("list")
    for n in names["presets"] + names["engine_presets"]:
        assert n in listed
    assert "filament-dfg" in names["presets"] and "nvdiffrec-bsdf-256" in names["engine_presets"]


def test_eval_probe_inspect_are_the_cli_documents(cli, tmp_path):
    assert brdfbake.eval("dfg", roughness=0.5, cos_theta=0.7) == cli.json(
        "eval", "dfg", "--roughness", "0.5", "--cos-theta", "0.7"
    )
    assert brdfbake.eval("g2", alpha=0.3, cos_theta=0.2, cos_theta_l=0.9, ndf="beckmann") == cli.json(
        "eval", "g2", "--alpha", "0.3", "--cos-theta", "0.2", "--cos-theta-l", "0.9", "--ndf", "beckmann"
    )
    cli.ok("bake", "filament-dfg", "--out", "out")
    exr = "out/filament-dfg/dfg.exr"
    at = {"cos_theta_v": 0.5, "roughness": 0.3}
    assert brdfbake.probe(exr, at, filter="hardware") == cli.json(
        "probe", exr, "--at", "cos_theta_v=0.5,roughness=0.3", "--filter", "hardware"
    )
    assert brdfbake.inspect(Path(exr)) == cli.json("inspect", exr)
    v = brdfbake.verify(exr)
    assert v["ok"] is True and v == cli.json("verify", exr)
    assert brdfbake.verify("karis-envbrdf")["ok"] is True


def test_ltc_probe_with_a_polygon(cli):
    cli.ok("bake", "heitz-ltc", "--out", "out")
    ltc = "out/heitz-ltc/ltc_1.exr"
    square = [(0.5, -0.5, 1.0), (0.5, 0.5, 1.0), (-0.5, 0.5, 1.0), (-0.5, -0.5, 1.0)]
    doc = brdfbake.probe(ltc, {"cos_theta_v": 0.8, "roughness": 0.5}, polygon=square, f0=0.04)
    assert doc == cli.json(
        "probe", ltc, "--at", "cos_theta_v=0.8,roughness=0.5",
        "--polygon", "0.5,-0.5,1.0 0.5,0.5,1.0 -0.5,0.5,1.0 -0.5,-0.5,1.0", "--f0", "0.04",
    )
    assert doc["lit"]["polygon_default"] is False


# (the Python call, the same command line) for bad input: both must fail the same way
BAD_INPUTS = [
    (lambda: brdfbake.bake("no-such-preset"), ["bake", "no-such-preset"]),
    (lambda: brdfbake.bake("filament-dfg", threads=0), ["bake", "filament-dfg", "--threads", "0"]),
    (lambda: brdfbake.write("filament-dfg", formats="exr,tga"), ["bake", "filament-dfg", "--format", "exr,tga"]),
    (lambda: brdfbake.write("unreal-preintegrated-gf", formats=["exr"]), ["bake", "unreal-preintegrated-gf", "--format", "exr"]),
    (lambda: brdfbake.bake("filament-dfg", max_memory="1KiB"), ["bake", "filament-dfg", "--format", "npy", "--max-memory", "1KiB"]),
    (lambda: brdfbake.bake("filament-dfg", max_memory="lots"), ["bake", "filament-dfg", "--max-memory", "lots"]),
    (lambda: brdfbake.bake("eevee-bsdf-ggx", max_time=0.001), ["bake", "eevee-bsdf-ggx", "--max-time", "0.001"]),
    (lambda: brdfbake.eval("dfg", roughness=0.5), ["eval", "dfg", "--roughness", "0.5"]),
    (lambda: brdfbake.eval("d", roughness=0.5, cos_theta=1.5), ["eval", "d", "--roughness", "0.5", "--cos-theta", "1.5"]),
    (lambda: brdfbake.eval("sheen", roughness=0.5, cos_theta=0.5, ndf="ggx"), ["eval", "sheen", "--roughness", "0.5", "--cos-theta", "0.5", "--ndf", "ggx"]),
    (lambda: brdfbake.eval("brdf"), ["eval", "brdf"]),
    (lambda: brdfbake.eval("e", alpha=0.5, roughness=0.5, cos_theta=0.5), ["eval", "e", "--alpha", "0.5", "--roughness", "0.5", "--cos-theta", "0.5"]),
    (lambda: brdfbake.verify("missing.exr"), ["verify", "missing.exr"]),
    (lambda: brdfbake.verify("filament-dfg", tolerance=-1.0), ["verify", "filament-dfg", "--tolerance", "-1.0"]),
    (lambda: brdfbake.inspect("missing.exr"), ["inspect", "missing.exr"]),
    (lambda: brdfbake.compare("filament-dfg", "missing.bin"), ["compare", "filament-dfg", "missing.bin"]),
    (lambda: brdfbake.compare("nvdiffrec-bsdf-256", "tiny.bin"), ["compare", "nvdiffrec-bsdf-256", "tiny.bin"]),
]


@pytest.mark.parametrize("call,args", BAD_INPUTS, ids=[" ".join(a) for _, a in BAD_INPUTS])
def test_bad_input_is_a_value_error_with_the_cli_message(cli, call, args):
    Path("tiny.bin").write_bytes(b"\0" * 12)
    with pytest.raises(ValueError) as e:
        call()
    # (the package runs the other commands with --json, which clap's usage line repeats)
    message = cli.error(*args, *([] if args[0] == "bake" else ["--json"]), code=2)
    assert str(e.value) and str(e.value) in message, f"python: {e.value}\ncli: {message}"


def test_bad_preset_dicts(cli):
    bad = {"schema": "brdfbake.preset/1", "tables": [{"name": "e", "kind": "albedo", "axes": {}}]}
    Path("bad.json").write_text(json.dumps(bad))
    with pytest.raises(ValueError) as e:
        brdfbake.bake(bad)
    # the CLI names the file where the package names the dict
    message = cli.error("bake", "bad.json")
    assert str(e.value).startswith("the preset dict: ")
    assert str(e.value).split(": ", 1)[1] == message.strip().split(": ", 1)[1]
    for name in ["../up", "", "-x", "a/b"]:
        with pytest.raises(ValueError, match="output folder"):
            brdfbake.bake(bad, name=name)
    with pytest.raises(ValueError, match="dict"):
        brdfbake.bake("filament-dfg", name="other")
    assert [p.name for p in Path(".").iterdir()] == ["bad.json"], "nothing is written"


def test_work_that_fails_is_a_failure_with_its_document(cli):
    with pytest.raises(brdfbake.Failure) as e:
        brdfbake.verify("threejs-dfg-lut", tolerance=1e-12)
    assert isinstance(e.value, RuntimeError)
    message = cli.error("verify", "threejs-dfg-lut", "--tolerance", "1e-12", code=1)
    assert str(e.value) == message.strip()
    assert e.value.result["ok"] is False
    r = cli.run("verify", "threejs-dfg-lut", "--tolerance", "1e-12", "--json")
    assert r.returncode == 1 and e.value.result == json.loads(r.stdout)


def test_a_write_that_fails_is_an_os_error(cli, tmp_path):
    Path("blocked").write_text("a file where the output folder would go")
    with pytest.raises(OSError) as e:
        brdfbake.write("karis-envbrdf", "blocked")
    assert str(e.value) in cli.error("bake", "karis-envbrdf", "--out", "blocked", code=1)
    assert Path("blocked").read_text().startswith("a file")


def console(*args, **kw):
    """The `brdfbake` command the wheel installs (beside this interpreter)."""
    exe = Path(sys.executable).with_name("brdfbake")
    return subprocess.run([str(exe), *args], capture_output=True, text=True, timeout=600, **kw)


def test_the_console_script_is_the_cli(cli, tmp_path):
    r = console("bake", "karis-envbrdf", "filament-dfg", "--out", "py", "--format", "exr,npz,h")
    assert r.returncode == 0, r.stderr
    cli.ok("bake", "karis-envbrdf", "filament-dfg", "--out", "cli", "--format", "exr,npz,h")
    for preset in ["karis-envbrdf", "filament-dfg"]:
        for name in files(tmp_path / "cli" / preset):
            assert (tmp_path / "py" / preset / name).read_bytes() == (
                tmp_path / "cli" / preset / name
            ).read_bytes()
    for args, code in [(["bake", "nope"], 2), (["verify", "threejs-dfg-lut", "--tolerance", "1e-12"], 1), (["eval"], 2)]:
        r, c = console(*args), cli.run(*args)
        assert (r.returncode, r.stderr, r.stdout) == (c.returncode, c.stderr, c.stdout) and r.returncode == code
    # piped into a reader that stops early: quiet, as the binary
    p = subprocess.Popen([str(Path(sys.executable).with_name("brdfbake")), "--help"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    p.stdout.read(1)
    p.stdout.close()
    assert "Traceback" not in p.stderr.read().decode()
    p.wait(timeout=60)


def stub_functions():
    """The functions `_native.pyi` declares, with their parameter names."""
    stub = Path(brdfbake.__file__).with_name("_native.pyi")
    tree = ast.parse(stub.read_text())
    return {
        f.name: [a.arg for a in f.args.args]
        for f in tree.body
        if isinstance(f, ast.FunctionDef)
    }


def test_stubs_match_the_native_module():
    declared = stub_functions()
    native = {n for n in dir(_native) if callable(getattr(_native, n)) and not n.startswith("_")}
    assert set(declared) == native - {"Failure"}
    for name, params in declared.items():
        runtime = list(inspect.signature(getattr(_native, name)).parameters)
        assert runtime == params, name
    assert Path(brdfbake.__file__).with_name("py.typed").exists()
    for name in brdfbake.__all__:
        assert getattr(brdfbake, name).__doc__, f"{name} has no docstring"
