"""Threads, the GIL, the guards and Ctrl-C: bakes give the same texels on any number of
threads and from several Python threads at once, leave the GIL to other Python threads while
they run, are refused over --max-memory as the CLI refuses them, and stop on SIGINT with a
KeyboardInterrupt, writing nothing."""

import json
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy

import brdfbake


def dielectric(size: int, slices: int) -> dict:
    """The built-in dielectric-btdf preset on a size × size × slices grid: ~60 µs a texel on
    one thread here, 2 s for 48 × 48 × 16."""
    return {
        "schema": "brdfbake.preset/1",
        "tables": [
            {
                "name": "btdf",
                "kind": "dielectric-btdf",
                "model": {"ndf": "ggx", "masking": "smith-separable"},
                "tolerance": 1e-6,
                "axes": {
                    "cos_theta_v": {"size": size},
                    "roughness": {"size": size, "quantity": "perceptual"},
                    "fresnel": {
                        "size": slices,
                        "quantity": "eta-reflectance",
                        "range": [-0.5, 0.5],
                        "convention": "endpoints",
                    },
                },
            }
        ],
    }


def test_the_same_texels_on_any_number_of_threads():
    one = brdfbake.bake("fresnel-albedo", threads=1)
    two = brdfbake.bake("fresnel-albedo", threads=2)
    for table in one:
        assert one[table].tobytes() == two[table].tobytes()
        assert one.sidecars[table] == two.sidecars[table]
    # and from two Python threads at once
    results = {}

    def bake(key):
        results[key] = brdfbake.bake("fresnel-albedo", threads=1)

    workers = [threading.Thread(target=bake, args=(k,)) for k in "ab"]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    for key in "ab":
        for table in one:
            assert results[key][table].tobytes() == one[table].tobytes()


def test_the_gil_is_released_while_baking():
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.005)

    ticker = threading.Thread(target=tick)
    ticker.start()
    start = time.monotonic()
    brdfbake.bake(dielectric(48, 16), threads=1, max_time=3600)
    end = time.monotonic()
    stop.set()
    ticker.join()
    # (a bake holding the GIL would let the ticker run not once between start and end)
    assert end - start > 0.5, "the bake is too short to show anything"
    during = [t for t in ticks if start + 0.1 < t < end - 0.1]
    assert len(during) >= 10, f"{len(during)} ticks in a {end - start:.2f} s bake"


def test_the_memory_guard_is_the_clis(cli):
    for limit in [1024, "1KiB"]:
        try:
            brdfbake.bake("filament-dfg", max_memory=limit)
            raise AssertionError("not refused")
        except ValueError as e:
            message = str(e)
        # (the package's bake is `bake PRESET --format npy`, whose estimate counts the .npy)
        cli_message = cli.error("bake", "filament-dfg", "--format", "npy", "--max-memory", str(limit))
        assert message in cli_message
        assert "more than the limit of 1.0 KiB" in message
    assert brdfbake.bake("filament-dfg", max_memory="8GiB")["dfg"].shape == (128, 128, 3)
    assert not any(Path(".").iterdir()), "nothing is written"


CHILD = r"""
import json, sys, time
import brdfbake
preset, how = json.loads(sys.argv[1]), sys.argv[2]
print("started", flush=True)
try:
    if how == "bake":
        brdfbake.bake(preset, name="slow", threads=1, max_time=3600)
    else:
        brdfbake.write(preset, "out", name="slow", threads=1, max_time=3600)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    sys.exit(0)
print("finished", flush=True)
sys.exit(3)
"""

#: A guard against an interrupt that waits for the bake (~30 s on one thread here): the work
#: checks its cancel flag before every texel (~60 µs) and the waiting thread checks for
#: signals every 50 ms, so the interpreter has the KeyboardInterrupt within a tenth of a
#: second; the limit is 50 times that.
PROMPT = 5.0


def interrupt(args, cwd: Path) -> subprocess.CompletedProcess:
    """Runs `args`, sends SIGINT one second after it says "started" (or after its start),
    and returns it once it has ended, at most PROMPT seconds after the signal."""
    p = subprocess.Popen(args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if args[0] == sys.executable:
        assert p.stdout.readline().strip() == "started"
    time.sleep(1.0)
    assert p.poll() is None, "finished before the signal: the bake is too short"
    p.send_signal(signal.SIGINT)
    sent = time.monotonic()
    try:
        out, err = p.communicate(timeout=PROMPT)
    except subprocess.TimeoutExpired:
        p.kill()
        raise AssertionError(f"still running {PROMPT} s after SIGINT")
    assert time.monotonic() - sent < PROMPT
    return subprocess.CompletedProcess(args, p.returncode, out, err)


def test_ctrl_c_interrupts_a_bake_and_writes_nothing(tmp_path):
    slow = json.dumps(dielectric(128, 32))
    for how in ["bake", "write"]:
        r = interrupt([sys.executable, "-c", CHILD, slow, how], tmp_path)
        assert r.returncode == 0 and "interrupted" in r.stdout, (how, r.stdout, r.stderr)
        assert not any(tmp_path.iterdir()), f"{how} wrote {list(tmp_path.rglob('*'))}"


def test_ctrl_c_ends_the_console_script_and_it_writes_nothing(tmp_path):
    (tmp_path / "slow.json").write_text(json.dumps(dielectric(128, 32)))
    exe = str(Path(sys.executable).with_name("brdfbake"))
    r = interrupt([exe, "bake", "slow.json", "--threads", "1", "--max-time", "3600"], tmp_path)
    # ended by the signal, as the binary is (the shell's exit status 130)
    assert r.returncode == -signal.SIGINT, (r.returncode, r.stderr)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["slow.json"]
