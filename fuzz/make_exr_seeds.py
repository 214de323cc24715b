#!/usr/bin/env python3
"""Writes the fuzz seeds of target `exr` (README.md): tiny OpenEXR files made byte by byte from
the format's specification (scan lines, no compression, 32-bit float channels), so that no tool
and no model is needed to make them.

    python3 fuzz/make_exr_seeds.py fuzz/seeds/exr
"""
import struct
import sys
from pathlib import Path


def attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def exr(width, height, channels, window=None, values=None):
    """`channels` sorted by name (as EXR stores them); `window` overrides the data window."""
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in channels) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = b"".join([
        attribute("channels", "chlist", chlist),
        attribute("compression", "compression", b"\0"),
        attribute("dataWindow", "box2i", struct.pack("<iiii", *window) if window else box),
        attribute("displayWindow", "box2i", box),
        attribute("lineOrder", "lineOrder", b"\0"),
        attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)),
        attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)),
        attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)),
    ]) + b"\0"
    start = 8 + len(header) + 8 * height
    blocks, offsets = b"", []
    for y in range(height):
        row = b"".join(
            struct.pack("<f", (values or (lambda c, x, y: 0.25 * (x + 2 * y) + c))(k, x, y))
            for k in range(len(channels)) for x in range(width)
        )
        offsets.append(start + len(blocks))
        blocks += struct.pack("<ii", y, len(row)) + row
    return struct.pack("<ii", 20000630, 2) + header + b"".join(struct.pack("<Q", o) for o in offsets) + blocks


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "fuzz/seeds/exr")
    out.mkdir(parents=True, exist_ok=True)
    (out / "rgb_2x2.exr").write_bytes(exr(2, 2, ["B", "G", "R"]))
    (out / "layers_3x1.exr").write_bytes(exr(3, 1, ["B", "G", "R", "caustic.X", "caustic.Y"]))
    (out / "distance_1x2.exr").write_bytes(exr(1, 2, ["distance"]))


if __name__ == "__main__":
    main()
