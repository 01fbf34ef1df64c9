#!/usr/bin/env python3
"""Checks that a PNG screenshot is not blank: enough non-white pixels and colours.

Python standard library only (zlib): 8-bit RGB/RGBA, non-interlaced, as Chromium writes.
Usage: check_png.py FILE [--expect-blank]; exit 0 when the expectation holds.
"""
import struct
import sys
import zlib


def pixels(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    pos, idat, w, h, ctype = 8, b"", 0, 0, 0
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos : pos + 4])
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or ctype not in (2, 6) or interlace:
                raise SystemExit(f"{path}: unsupported PNG (depth {depth}, type {ctype})")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    bpp = 3 if ctype == 2 else 4
    raw, stride = zlib.decompress(idat), w * bpp
    prev, rows, i = bytearray(stride), [], 0
    for _ in range(h):
        f, line = raw[i], bytearray(raw[i + 1 : i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], (prev[x - bpp] if x >= bpp else 0)
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def main():
    path, expect_blank = sys.argv[1], "--expect-blank" in sys.argv
    w, h, bpp, rows = pixels(path)
    colours, ink = set(), 0
    for row in rows[::2]:
        for x in range(0, w * bpp, bpp * 2):
            px = row[x : x + 3]
            colours.add(px)
            ink += px != b"\xff\xff\xff"
    total = len(rows[::2]) * len(range(0, w * bpp, bpp * 2))
    frac = ink / max(total, 1)
    blank = frac < 0.02 or len(colours) < 50
    print(f"{path}: {w}x{h}, {frac:.1%} non-white, {len(colours)} colours -> {'blank' if blank else 'content'}")
    sys.exit(0 if blank == expect_blank else 1)


if __name__ == "__main__":
    main()
