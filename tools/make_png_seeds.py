#!/usr/bin/env python3
"""Writes small PNGs of every colour type and bit depth (and an interlaced one) for the texture
fuzz target's seed corpus (tests/fuzz/corpus/texture). Pure Python (zlib): no image library.
Each image is 3 x 2 with known samples, so the decoder's results can be checked too."""
import struct
import sys
import zlib
from pathlib import Path


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)


def pack_row(samples, depth):
    if depth >= 8:
        fmt = ">" + ("B" if depth == 8 else "H") * len(samples)
        return struct.pack(fmt, *samples)
    bits, out, acc, n = depth, bytearray(), 0, 0
    for s in samples:
        acc = (acc << bits) | s
        n += bits
        if n == 8:
            out.append(acc)
            acc, n = 0, 0
    if n:
        out.append(acc << (8 - n))
    return bytes(out)


def png(width, height, colour_type, depth, rows, extra=b"", interlace=0):
    header = struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, interlace)
    if interlace:
        # Adam7 of a tiny image: pass by pass, each pass's rows filtered with type 0.
        passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
        raw = b""
        per = len(rows[0]) // width
        for x0, y0, dx, dy in passes:
            for y in range(y0, height, dy):
                samples = [s for x in range(x0, width, dx) for s in rows[y][x * per:(x + 1) * per]]
                if samples:
                    raw += b"\x00" + pack_row(samples, depth)
    else:
        raw = b"".join(b"\x00" + pack_row(r, depth) for r in rows)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + extra + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def main(out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    w, h = 3, 2
    for depth in (1, 2, 4, 8, 16):
        top = (1 << depth) - 1
        rows = [[0, top, top // 2], [top, 0, top]]
        (out / f"grey{depth}.png").write_bytes(png(w, h, 0, depth, rows))
    for depth in (8, 16):
        top = (1 << depth) - 1
        rgb = [[top, 0, 0, 0, top, 0, 0, 0, top], [0, 0, 0, top, top, top, top // 2, top // 4, top // 8]]
        (out / f"rgb{depth}.png").write_bytes(png(w, h, 2, depth, rgb))
        ga = [[0, top, top, top // 2, top // 3, 0], [top, top, 0, 0, top // 2, top]]
        (out / f"greyalpha{depth}.png").write_bytes(png(w, h, 4, depth, ga))
        rgba = [[top, 0, 0, top, 0, top, 0, top // 2, 0, 0, top, 0],
                [0, 0, 0, top, top, top, top, top, top // 2, top // 4, top // 8, top // 3]]
        (out / f"rgba{depth}.png").write_bytes(png(w, h, 6, depth, rgba))
    palette = chunk(b"PLTE", bytes([255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0]))
    for depth in (1, 2, 4, 8):
        rows = [[0, 1 % (1 << depth), 0], [1 % (1 << depth), 0, 1 % (1 << depth)]]
        (out / f"palette{depth}.png").write_bytes(png(w, h, 3, depth, rows, palette))
    trns = chunk(b"tRNS", bytes([255, 128]))
    (out / "palette8-trns.png").write_bytes(png(w, h, 3, 8, [[0, 1, 2], [1, 0, 3]], palette + trns))
    (out / "rgb8-interlaced.png").write_bytes(
        png(w, h, 2, 8, [[255, 0, 0, 0, 255, 0, 0, 0, 255], [0, 0, 0, 255, 255, 255, 9, 8, 7]], interlace=1))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tests/fuzz/corpus/texture")
