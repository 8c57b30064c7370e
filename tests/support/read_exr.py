#!/usr/bin/env python3
"""Reads an EXR file with the official OpenEXR Python bindings and prints what it holds as
JSON, for tests/exr_openexr.rs:

    {"parts": 1, "width": W, "height": H, "data_window": [[x0, y0], [x1, y1]],
     "compression": "NO_COMPRESSION", "line_order": "INCREASING_Y", "storage": "scanlineimage",
     "channels": [{"name": ..., "type": "HALF" | "FLOAT" | "UINT",
                   "x_sampling": 1, "y_sampling": 1,
                   "bits": [...],     # raw sample bits, row-major, top row first
                   "values": [...]}], # the same samples as numbers
     "string_attributes": {name: value, ...}}

Channels are listed in the file's order. Only header attributes whose value is a string are
listed in string_attributes (standard attributes come back as other Python types).
"""
import json
import sys

try:
    import numpy as np
    import OpenEXR
except ImportError as e:
    sys.exit(f"read_exr.py: {e}; run `python3 -m pip install openexr numpy`")


def enum_name(value):
    return getattr(value, "name", str(value))


def main(path):
    with OpenEXR.File(path, separate_channels=True) as f:
        header = f.header()
        (x0, y0), (x1, y1) = (tuple(int(v) for v in corner) for corner in header["dataWindow"])
        pixels = f.channels()
        channels = []
        for described in header["channels"]:
            channel = pixels[described.name]
            array = np.ascontiguousarray(channel.pixels)
            bits_type = {np.float16: np.uint16, np.float32: np.uint32, np.uint32: np.uint32}[
                array.dtype.type
            ]
            channels.append(
                {
                    "name": described.name,
                    "type": enum_name(channel.type()),
                    "x_sampling": int(described.xSampling),
                    "y_sampling": int(described.ySampling),
                    "bits": array.view(bits_type).ravel().tolist(),
                    "values": [float(v) for v in array.ravel()],
                }
            )
        out = {
            "parts": len(f.parts),
            "width": x1 - x0 + 1,
            "height": y1 - y0 + 1,
            "data_window": [[x0, y0], [x1, y1]],
            "compression": enum_name(header["compression"]),
            "line_order": enum_name(header["lineOrder"]),
            "storage": enum_name(header["type"]),
            "channels": channels,
            "string_attributes": {k: v for k, v in header.items() if isinstance(v, str)},
        }
    json.dump(out, sys.stdout, allow_nan=False)
    sys.stdout.write("\n")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: read_exr.py FILE.exr")
    main(sys.argv[1])
