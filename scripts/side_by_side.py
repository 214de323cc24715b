#!/usr/bin/env python3
"""Crops the same rectangle out of several PNG images and writes them side by side, left to
right in the order given, with a gap of grey between them (standard library only: 8-bit RGB or
RGBA, non-interlaced PNGs, as `causticlab render` writes them).

    python3 scripts/side_by_side.py OUT.png X Y W H IN1.png IN2.png ...

X, Y, W, H: the rectangle in pixels (from the top left), the same in every input.
"""
import struct
import sys
import zlib

GAP = 4
GREY = (128, 128, 128)


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, idat, header = 8, b"", None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos : pos + 4])
        kind = data[pos + 4 : pos + 8]
        body = data[pos + 8 : pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
    if header is None:
        sys.exit(f"{path}: no IHDR")
    width, height, depth, colour, _, _, interlace = header
    channels = {2: 3, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        sys.exit(f"{path}: only 8-bit RGB or RGBA non-interlaced PNGs are read")
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[i], bytearray(raw[i + 1 : i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - channels] if x >= channels else 0
            b = prev[x]
            c = prev[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x : x + 3]) for x in range(0, stride, channels)])
        prev = line
    return width, height, rows


def write_png(path, rows):
    height, width = len(rows), len(rows[0])
    raw = b"".join(b"\x00" + bytes(v for px in row for v in px) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    if len(sys.argv) < 7:
        sys.exit(__doc__)
    out, (x, y, w, h), inputs = sys.argv[1], map(int, sys.argv[2:6]), sys.argv[6:]
    crops = []
    for path in inputs:
        width, height, rows = read_png(path)
        if x < 0 or y < 0 or w <= 0 or h <= 0 or x + w > width or y + h > height:
            sys.exit(f"{path}: the rectangle {x},{y} {w}x{h} is not inside its {width}x{height}")
        crops.append([row[x : x + w] for row in rows[y : y + h]])
    rows = []
    for r in range(h):
        row = []
        for k, crop in enumerate(crops):
            if k:
                row += [GREY] * GAP
            row += crop[r]
        rows.append(row)
    write_png(out, rows)


if __name__ == "__main__":
    main()
