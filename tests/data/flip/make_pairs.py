#!/usr/bin/env python3
"""Writes the image pairs flip_test compares (96x64 8-bit PNGs) with the
standard library only; the test's expected values come from NVIDIA's FLIP
tool (github.com/NVlabs/flip, v1.6) run on these files. room_full.png and room_hybrid.png are Glint's own renders:
  glint render scenes/room.json --size 96x64 --samples 16 -o room_full.png
  glint render scenes/room.json --size 96x64 --mask auto -o room_hybrid.png
and the EXR pair for HDR-FLIP:
  glint render scenes/room.json --size 96x64 --samples 16 --mask all --exposure 2 -o room_full.exr
  glint render scenes/room.json --size 96x64 --samples 1 --mask all --exposure 2 -o room_one_sample.exr"""
import struct
import zlib

W, H = 96, 64


def write_png(name, pixel):
    rows = b"".join(b"\0" + bytes(c for x in range(W) for c in pixel(x, y)) for y in range(H))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    with open(name, "wb") as f:
        f.write(png)


def gradient(x, y):
    return (40 + 2 * x, 30 + 3 * y, 200 - x)


def gradient_shifted(x, y):  # the same ramps, red and green traded over the right half
    r, g, b = gradient(x, y)
    return (g, r, b) if x >= W // 2 else (r, g, b)


def checker(x, y):
    v = 190 if (x // 8 + y // 8) % 2 else 60
    return (v, v, v)


def checker_blurred(x, y):  # a 3x3 box blur, clamped at the borders
    total = 0
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            total += checker(min(max(x + dx, 0), W - 1), min(max(y + dy, 0), H - 1))[0]
    v = (total + 4) // 9
    return (v, v, v)


def flat(x, y):
    return (128, 128, 128)


def dotted(x, y):  # single bright pixels on a 7-pixel grid
    return (255, 255, 255) if x % 7 == 3 and y % 7 == 3 else (128, 128, 128)


for name, f in [("gradient", gradient), ("gradient_shifted", gradient_shifted), ("checker", checker),
                ("checker_blurred", checker_blurred), ("flat", flat), ("dotted", dotted)]:
    write_png(name + ".png", f)
