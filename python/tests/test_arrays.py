"""brdfbake.bake's arrays are the texels of the CLI's own files, bit for bit: the EXR texels
(read with the official OpenEXR bindings), the KTX2 texels of normalized-integer tables, and
the bytes of the .npy/.npz/.bin files the CLI writes; its sidecars are the CLI's."""

import json
import struct
import zipfile
from pathlib import Path

import numpy
import OpenEXR
import pytest

import brdfbake
from conftest import files

# (preset, what it covers)
FLOAT_PRESETS = [
    ("filament-dfg", "f32, 3 channels"),
    ("threejs-dfg-lut", "f16, axis order (roughness along u)"),
    ("fresnel-albedo", "3D tables (slices stacked in the EXR)"),
    ("energy-albedo", "a 1D table beside a 2D one"),
]


def exr_texels(path: Path, names):
    """The EXR's channels `names` as an array (height, width, channels), as OpenEXR reads it."""
    with OpenEXR.File(str(path), separate_channels=True) as f:
        channels = f.channels()
        return numpy.stack([numpy.asarray(channels[n].pixels) for n in names], axis=-1)


def test_acceptance_the_readme_line():
    dfg = brdfbake.bake("filament-dfg")["dfg"]
    assert dfg.shape == (128, 128, 3) and dfg.dtype == numpy.float32


def test_the_package_is_the_installed_wheel():
    # (not python/brdfbake of the repository: the tests run against what pip installed)
    assert "site-packages" in Path(brdfbake.__file__).parts, brdfbake.__file__


@pytest.mark.parametrize("preset,what", FLOAT_PRESETS)
def test_arrays_are_the_exr_texels(cli, tmp_path, preset, what):
    cli.ok("bake", preset, "--out", "cli", "--format", "exr")
    baked = brdfbake.bake(preset)
    assert set(baked) == {p.stem for p in (tmp_path / "cli" / preset).glob("*.exr")}
    for table, array in baked.items():
        sidecar = baked.sidecars[table]
        names = [c["name"] for c in sidecar["channels"]]
        sizes = [a["size"] for a in sidecar["axes"]]
        # the axes in reverse (rows), then the channels
        assert array.shape == (*reversed(sizes), len(names)), what
        assert array.dtype == {"f32": numpy.float32, "f16": numpy.float16}[
            sidecar["storage"]["texel_type"]
        ]
        exr = exr_texels(tmp_path / "cli" / preset / f"{table}.exr", names)
        # the EXR's image: the rows of every slice stacked downward (a 1D table: one row)
        image = array.reshape(-1, sizes[0], len(names))
        assert exr.dtype == array.dtype
        bits = numpy.uint32 if array.dtype == numpy.float32 else numpy.uint16
        assert numpy.array_equal(exr.view(bits), image.view(bits)), f"{preset}/{table}"


def ktx2_texels(path: Path):
    """The level-0 bytes of an uncompressed KTX 2.0 file and its size, by the container's
    layout (KTX 2.0 specification, section 3: the header, then the level index at byte 80)."""
    data = path.read_bytes()
    assert data[:12] == b"\xabKTX 20\xbb\r\n\x1a\n"
    vk_format, type_size, width, height, depth, layers, faces, levels, scheme = struct.unpack_from(
        "<9I", data, 12
    )
    assert (faces, levels, scheme) == (1, 1, 0)
    offset, length, _ = struct.unpack_from("<3Q", data, 80)
    return data[offset : offset + length], type_size, width, height


@pytest.mark.parametrize(
    "preset", ["unreal-preintegrated-gf", "gltf-lut-ggx"]
)  # unorm16 with 2 channels; unorm8 with 3 (padded to 4 in the KTX2)
def test_unorm_arrays_are_the_ktx2_texels(cli, tmp_path, preset):
    cli.ok("bake", preset, "--out", "cli", "--format", "ktx2")
    baked = brdfbake.bake(preset)
    for table, array in baked.items():
        level, type_size, width, height = ktx2_texels(tmp_path / "cli" / preset / f"{table}.ktx2")
        assert array.dtype == {1: numpy.uint8, 2: numpy.uint16}[type_size]
        components = 4 if array.shape[-1] == 3 else array.shape[-1]
        ktx = numpy.frombuffer(level, dtype=array.dtype.newbyteorder("<")).reshape(
            height, width, components
        )
        assert numpy.array_equal(ktx[..., : array.shape[-1]], array), f"{preset}/{table}"
        if components > array.shape[-1]:
            # the KTX2's padding channel is 1.0; the array has none
            assert (ktx[..., 3] == numpy.iinfo(array.dtype).max).all()


@pytest.mark.parametrize(
    "preset", ["filament-dfg", "threejs-dfg-lut", "unreal-preintegrated-gf", "fresnel-albedo"]
)
def test_npy_npz_bin_files_are_the_cli_bytes(cli, tmp_path, preset):
    cli.ok("bake", preset, "--out", "cli", "--format", "npy,npz,bin")
    doc = brdfbake.write(preset, "py", formats=["npy", "npz", "bin"])
    cli_dir, py_dir = tmp_path / "cli" / preset, tmp_path / "py" / preset
    assert files(cli_dir) == files(py_dir)
    for name in files(cli_dir):
        assert (cli_dir / name).read_bytes() == (py_dir / name).read_bytes(), name
    assert {Path(f).name for t in doc["tables"] for f in t["files"]} == set(files(cli_dir))
    baked = brdfbake.bake(preset)
    for table, array in baked.items():
        # .npy: numpy reads the array, and writes these very bytes for it
        npy = cli_dir / f"{table}.npy"
        loaded = numpy.load(npy, allow_pickle=False)
        assert loaded.dtype == array.dtype and numpy.array_equal(loaded, array)
        with open(Path("resaved.npy"), "wb") as f:
            numpy.save(f, loaded)
        assert Path("resaved.npy").read_bytes() == npy.read_bytes()
        # .bin: the layout the sidecar states
        layout = json.loads((cli_dir / f"{table}.json").read_text())["storage"]["array"]
        raw = numpy.fromfile(cli_dir / f"{table}.bin", dtype=layout["dtype"]).reshape(
            layout["shape"]
        )
        assert numpy.array_equal(raw, array) and list(array.shape) == layout["shape"]
        # .npz: the array and the header attributes
        with numpy.load(cli_dir / f"{table}.npz", allow_pickle=False) as npz:
            assert sorted(npz.files) == sorted([table, "brdfbake.attributes"])
            assert numpy.array_equal(npz[table], array)
            attrs = json.loads(str(npz["brdfbake.attributes"]))
            assert attrs["table"] == table and attrs["preset"] == preset
        with zipfile.ZipFile(cli_dir / f"{table}.npz") as z:
            assert z.testzip() is None
            assert all(i.compress_type == zipfile.ZIP_STORED for i in z.infolist())


def test_sidecars_are_the_cli_sidecars(cli, tmp_path):
    cli.ok("bake", "karis-envbrdf", "--out", "cli", "--format", "npy")
    baked = brdfbake.bake("karis-envbrdf")
    for table, sidecar in baked.sidecars.items():
        assert sidecar == json.loads((tmp_path / "cli/karis-envbrdf" / f"{table}.json").read_text())
        assert sidecar["files"] == {"npy": f"{table}.npy"}
    assert baked.preset == "karis-envbrdf"


def small_preset():
    return {
        "schema": "brdfbake.preset/1",
        "description": "a dict preset",
        "tables": [
            {
                "name": "e",
                "kind": "albedo",
                "model": {"ndf": "beckmann", "masking": "smith-separable"},
                "storage": "f16",
                "axes": {
                    "cos_theta_v": {"size": 24},
                    "roughness": {"size": 10, "quantity": "alpha", "range": [0.05, 1]},
                },
            },
            {
                "name": "d",
                "kind": "ndf",
                "model": {"ndf": "ggx"},
                "scale": 0.01,
                "axes": {
                    "cos_theta_h": {"size": 16},
                    "roughness": {"size": 4, "quantity": "perceptual", "range": [0.3, 1]},
                },
            },
        ],
    }


def test_a_dict_preset_is_a_preset_file(cli, tmp_path):
    Path("mine.json").write_text(json.dumps(small_preset()))
    cli.ok("bake", "mine.json", "--out", "cli", "--format", "npy")
    baked = brdfbake.bake(small_preset(), name="mine")
    assert baked.preset == "mine" and list(baked) == ["e", "d"]
    for table, array in baked.items():
        npy = tmp_path / "cli/mine" / f"{table}.npy"
        assert npy.read_bytes()[128:] == array.tobytes()
        assert baked.sidecars[table] == json.loads(npy.with_suffix(".json").read_text())
    assert baked["e"].dtype == numpy.float16 and baked["e"].shape == (10, 24, 1)
    # the default name of a dict preset
    assert brdfbake.bake(small_preset()).preset == "preset"


def test_nvdiffrec_drop_in_file():
    doc = brdfbake.write("nvdiffrec-bsdf-256", "out", formats="bin")
    (path,) = doc["tables"][0]["files"][:1]
    assert Path(path).name == "bsdf_256_256.bin"
    lut = numpy.fromfile(path, dtype=numpy.float32).reshape(256, 256, 2)
    assert Path(path).stat().st_size == 524288
    assert numpy.array_equal(lut, brdfbake.bake("nvdiffrec-bsdf-256")["bsdf_256_256"])
    # row y is the roughness, column x the n.v (nvdiffrast's u), at texel centres: texel
    # (x, y) holds the split sum there, within the 1e-6 every dfg table meets
    for x, y in [(200, 10), (10, 200), (0, 255)]:
        e = brdfbake.eval("dfg", roughness=(y + 0.5) / 256, cos_theta=(x + 0.5) / 256)
        for c, channel in enumerate(["A", "B"]):
            assert abs(lut[y, x, c] - e["values"][channel]) <= 1e-6, (x, y, channel)
