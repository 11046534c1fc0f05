#!/usr/bin/env python3
"""Writes the alpha-tested textures of scenes/canopy.json and the scene itself (deterministic).

leaf.png (128^2 RGBA): a pointed leaf (two circular arcs meeting at the tips) with a stem, alpha
255 inside and 0 outside, for the canopy's leaf cards. chain-link.png (256^2 RGBA): 8 x 8 diamonds
of wire 1/8 of a cell's side wide, alpha 255 on the wire and 0 in the holes. Both hard-edged, as
foliage and fence cards are authored for alpha MASK. Rerun after changing a parameter:
python3 scenes/textures/make_alpha_textures.py
"""
import json
import math
import os
import random
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write_png(path, size, pixel):
    rows = b""
    for y in range(size):
        rows += b"\0" + b"".join(bytes(pixel(x, y)) for x in range(size))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 6, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def leaf(x, y):
    u, v = (x + 0.5) / 128 - 0.5, (y + 0.5) / 128 - 0.5  # v along the leaf, from tip to stem
    r = 0.62  # radius of the two arcs; their centres at (+-c, 0) make tips at v = +-0.42
    c = math.sqrt(r * r - 0.42 * 0.42)
    inside = math.hypot(u - c, v) < r and math.hypot(u + c, v) < r
    stem = abs(u) < 0.02 and 0.3 < v < 0.5
    return (60, 120, 40, 255) if inside or stem else (60, 120, 40, 0)


def chain_link(x, y):
    cell = 256 / 8
    a, b = (x + 0.5 + y + 0.5) / cell, (x + 0.5 - y - 0.5) / cell  # the two diagonal families
    wire = 1 / 8
    on = abs(a - round(a)) < wire / 2 * math.sqrt(2) or abs(b - round(b)) < wire / 2 * math.sqrt(2)
    return (150, 150, 155, 255) if on else (150, 150, 155, 0)


def canopy_scene():
    rng = random.Random(7)
    leaves = []
    for i in range(48):
        leaves.append({
            "name": "leaf-%02d" % i, "shape": "quad", "size": [0.5, 0.5], "material": "leaf",
            "translate": [round(rng.uniform(-1.4, 0.6), 3), round(rng.uniform(1.7, 2.2), 3), round(rng.uniform(-1.2, 0.8), 3)],
            "rotate": [round(rng.uniform(-25, 25), 1), round(rng.uniform(0, 360), 1), round(rng.uniform(-25, 25), 1)]})
    return {
        "name": "canopy",
        "description": "Alpha-tested occluders (alphaMode MASK): 48 leaf cards of a canopy (textures/leaf.png) and a chain-link fence (textures/chain-link.png, 8 x 8 diamonds) over a floor under a rect light. Camera, shadow maps and the reference test the texture's alpha; the shadow-volume techniques cast whole quads and say so. Made by textures/make_alpha_textures.py.",
        "camera": {"position": [0.0, 2.6, 4.6], "target": [0.0, 0.6, -0.2], "up": [0, 1, 0], "fov": 50, "near": 0.05},
        "resolution": [256, 256],
        "materials": [
            {"name": "floor", "baseColor": [0.8, 0.8, 0.8]},
            {"name": "leaf", "baseColor": 1.0, "texture": "textures/leaf.png", "alphaCutoff": 0.5},
            {"name": "fence", "baseColor": 1.0, "texture": "textures/chain-link.png", "alphaCutoff": 0.5}],
        "objects": [{"name": "floor", "shape": "plane", "size": 12, "material": "floor"},
                    {"name": "fence", "shape": "quad", "size": [2.4, 1.2], "material": "fence",
                     "rotate": [90, 0, 0], "translate": [1.1, 0.6, 0.3]}] + leaves,
        "lights": [{"name": "sky", "type": "rect", "position": [-0.6, 4.0, 2.2], "target": [0.0, 0.0, -0.3],
                    "up": [0, 0, -1], "size": [1.2, 1.2], "intensity": 30.0}]}


if __name__ == "__main__":
    write_png(os.path.join(HERE, "leaf.png"), 128, leaf)
    write_png(os.path.join(HERE, "chain-link.png"), 256, chain_link)
    with open(os.path.join(HERE, "..", "canopy.json"), "w") as f:
        json.dump(canopy_scene(), f, indent=1)
        f.write("\n")
