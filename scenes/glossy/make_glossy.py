#!/usr/bin/env python3
# Writes scenes/glossy/glossy.gltf: a glossy floor (roughness 0.3), smooth
# curved occluders with vertex normals (a ball, a torus, a capsule), glTF metallic-roughness
# materials and one EXT_lights_area rect light. scenes/glossy.json places it and adds a textured
# rect light and a sphere light. Deterministic: run it again and the file is the same bytes.
#   python3 scenes/glossy/make_glossy.py
import base64, json, math, os, struct

def uv_sphere(cx, cy, cz, r, seg, rings):
    pos, nrm, idx = [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(seg + 1):
            ph = 2 * math.pi * j / seg
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            pos.append((cx + r * n[0], cy + r * n[1], cz + r * n[2])); nrm.append(n)
    for i in range(rings):
        for j in range(seg):
            a, b = i * (seg + 1) + j, (i + 1) * (seg + 1) + j
            if i > 0: idx.append((a, a + 1, b))
            if i < rings - 1: idx.append((a + 1, b + 1, b))
    return pos, nrm, idx

def torus(cx, cy, cz, R, r, seg, sides, tilt):
    pos, nrm, idx = [], [], []
    ct, st = math.cos(tilt), math.sin(tilt)
    for i in range(seg + 1):
        u = 2 * math.pi * i / seg
        for j in range(sides + 1):
            v = 2 * math.pi * j / sides
            n = (math.cos(u) * math.cos(v), math.sin(v), math.sin(u) * math.cos(v))
            p = ((R + r * math.cos(v)) * math.cos(u), r * math.sin(v), (R + r * math.cos(v)) * math.sin(u))
            rot = lambda q: (q[0], ct * q[1] - st * q[2], st * q[1] + ct * q[2])  # about x
            p, n = rot(p), rot(n)
            pos.append((cx + p[0], cy + p[1], cz + p[2])); nrm.append(n)
    for i in range(seg):
        for j in range(sides):
            a, b = i * (sides + 1) + j, (i + 1) * (sides + 1) + j
            idx += [(a, b, a + 1), (a + 1, b, b + 1)]
    return pos, nrm, idx

def capsule(cx, cy, cz, r, h, seg, rings):
    # A sphere split at the equator, its halves moved apart by h along y: smooth everywhere.
    pos, nrm, idx = uv_sphere(0, 0, 0, r, seg, rings)
    pos = [(cx + p[0], cy + p[1] + (h / 2 if n[1] >= 0 else -h / 2), cz + p[2]) for p, n in zip(pos, nrm)]
    return pos, nrm, idx

def floor(size):
    s = size / 2
    return [(-s, 0, -s), (s, 0, -s), (s, 0, s), (-s, 0, s)], [(0, 1, 0)] * 4, [(0, 2, 1), (0, 3, 2)]

meshes = [
    ("floor", floor(10.0), 0),
    ("ball", uv_sphere(-1.1, 0.55, 0.2, 0.55, 64, 32), 1),
    ("torus", torus(0.6, 0.75, -0.6, 0.5, 0.16, 64, 24, math.radians(70)), 2),
    ("capsule", capsule(1.5, 0.75, 0.9, 0.25, 1.0, 48, 24), 3),
]
materials = [
    {"name": "glossy-floor", "pbrMetallicRoughness": {"baseColorFactor": [0.55, 0.55, 0.6, 1], "metallicFactor": 0.0, "roughnessFactor": 0.3}},
    {"name": "red-plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.12, 0.1, 1], "metallicFactor": 0.0, "roughnessFactor": 0.4}},
    {"name": "gold", "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.78, 0.34, 1], "metallicFactor": 1.0, "roughnessFactor": 0.35}},
    {"name": "blue-rough", "pbrMetallicRoughness": {"baseColorFactor": [0.15, 0.3, 0.7, 1], "metallicFactor": 0.0, "roughnessFactor": 0.8}},
]

blob = bytearray()
views, accessors, gmeshes, nodes = [], [], [], []
def add_view(data, target):
    while len(blob) % 4: blob.append(0)
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
    blob.extend(data)
    return len(views) - 1
for name, (pos, nrm, idx), mat in meshes:
    pv = add_view(b"".join(struct.pack("<3f", *p) for p in pos), 34962)
    nv = add_view(b"".join(struct.pack("<3f", *n) for n in nrm), 34962)
    iv = add_view(b"".join(struct.pack("<3I", *t) for t in idx), 34963)
    lo = [min(p[k] for p in pos) for k in range(3)]; hi = [max(p[k] for p in pos) for k in range(3)]
    accessors += [{"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi},
                  {"bufferView": nv, "componentType": 5126, "count": len(nrm), "type": "VEC3"},
                  {"bufferView": iv, "componentType": 5125, "count": 3 * len(idx), "type": "SCALAR"}]
    a = len(accessors) - 3
    gmeshes.append({"name": name, "primitives": [{"attributes": {"POSITION": a, "NORMAL": a + 1}, "indices": a + 2, "material": mat}]})
    nodes.append({"name": name, "mesh": len(gmeshes) - 1})
# The EXT_lights_area rect light: emission along its local -Z, so the node turns -Z to -Y
# (a rotation of -90 degrees about X), 2.2 above the floor, 1.2 x 0.6.
s = math.sqrt(0.5)
nodes.append({"name": "panel", "translation": [-0.8, 2.6, -1.4], "rotation": [-s, 0, 0, s],
              "extensions": {"EXT_lights_area": {"light": 0}}})
doc = {
    "asset": {"version": "2.0", "generator": "penumbra scenes/glossy/make_glossy.py"},
    "extensionsUsed": ["EXT_lights_area"],
    "extensions": {"EXT_lights_area": {"lights": [{"name": "panel", "type": "rect", "size": 0.6, "rect": {"aspect": 2.0},
                                                   "color": [1.0, 0.95, 0.9], "intensity": 18.0}]}},
    "scene": 0, "scenes": [{"nodes": list(range(len(nodes)))}],
    "nodes": nodes, "meshes": gmeshes, "materials": materials, "accessors": accessors, "bufferViews": views,
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
}
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "glossy.gltf")
with open(out, "w") as f:
    json.dump(doc, f, separators=(",", ":"))
    f.write("\n")
print(out, len(blob), "bytes of buffer,", sum(len(m[1][2]) for m in meshes), "triangles")
