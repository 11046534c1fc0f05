#!/usr/bin/env python3
"""Writes the small glTF/GLB test files of tests/scene_gltf_test.cpp into this folder.

Each file isolates one case (one defect, or one valid layout that a careless loader rejects).
The outputs are committed; rerun this after changing a case: python3 make_gltf.py
"""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

# Unit cube, counter-clockwise seen from outside (same construction as makeBox).
CUBE_POS = [(x, y, z) for z in (-0.5, 0.5) for y in (-0.5, 0.5) for x in (-0.5, 0.5)]


def _corner(s):
    return (1 if s[0] > 0 else 0) | (2 if s[1] > 0 else 0) | (4 if s[2] > 0 else 0)


def _cube_tris():
    faces = [((1, 0, 0), (0, 1, 0), (0, 0, 1)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (0, 0, 1), (1, 0, 0)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (0, 1, 0), (1, 0, 0))]
    tris = []
    for n, u, v in faces:
        def c(a, b):
            return _corner([n[i] + a * u[i] + b * v[i] for i in range(3)])
        c0, c1, c2, c3 = c(-1, -1), c(1, -1), c(1, 1), c(-1, 1)
        tris += [(c0, c1, c2), (c0, c2, c3)]
    return tris


CUBE_TRIS = _cube_tris()


def f32(values):
    return b"".join(struct.pack("<f", v) for v in values)


def u16(values):
    return b"".join(struct.pack("<H", v) for v in values)


def pad4(b):
    return b + b"\0" * (-len(b) % 4)


def data_uri(b):
    return "data:application/octet-stream;base64," + base64.b64encode(b).decode()


def cube_buffer():
    """Positions (96 bytes) then uint16 indices (72 bytes)."""
    pos = f32([c for p in CUBE_POS for c in p])
    idx = u16([i for t in CUBE_TRIS for i in t])
    return pos, idx


def cube_doc(uri=None, nodes=None, scenes=None, extra=None):
    pos, idx = cube_buffer()
    data = pos + idx
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": scenes or [{"nodes": [0]}],
        "nodes": nodes or [{"mesh": 0}],
        "meshes": [{"name": "cube", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data), "uri": uri if uri is not None else data_uri(data)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
             "min": [-0.5] * 3, "max": [0.5] * 3},
            {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
    }
    if extra:
        doc.update(extra)
    return doc


def write(name, doc):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def glb(doc, bin_data, *, length_delta=0, json_len=None, bin_len=None, bin_chunk=True,
        nul_padding=False):
    js = json.dumps(doc).encode()
    js = js + b"\0" * (4 + -len(js) % 4) if nul_padding else pad4(js).replace(b"\0", b" ")
    out = struct.pack("<II", json_len if json_len is not None else len(js), 0x4E4F534A) + js
    if bin_chunk:
        b = pad4(bin_data)
        out += struct.pack("<II", bin_len if bin_len is not None else len(b), 0x004E4942) + b
    total = 12 + len(out)
    return struct.pack("<4sII", b"glTF", 2, total + length_delta) + out


def write_bin(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def png_2x2():
    # Red, green / blue, white; 8-bit RGBA, sRGB values 255 and 0 (linear 1 and 0) plus one
    # mid grey 128 in the white texel's alpha to test the alpha channel passes through linearly.
    rows = [bytes([0, 255, 0, 0, 255, 0, 255, 0, 255]), bytes([0, 0, 0, 255, 255, 255, 255, 255, 128])]
    raw = b"".join(rows)

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    ihdr = struct.pack(">IIBBBBB", 2, 2, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) + \
        chunk(b"IEND", b"")


def main():
    pos, idx = cube_buffer()
    data = pos + idx

    # --- valid files
    write("cube.gltf", cube_doc())
    write_bin("cube.bin", data)
    write("cube_external.gltf", cube_doc(uri="cube.bin"))
    write_bin("cube.glb", glb({k: v for k, v in cube_doc().items()} | {
        "buffers": [{"byteLength": len(data)}]}, data))
    # Two instances of the cube: one plain at x=-2, one mirrored (scale x -1) at x=+2.
    write("mirrored.gltf", cube_doc(
        nodes=[{"mesh": 0, "translation": [-2, 0, 0]},
               {"mesh": 0, "translation": [2, 0, 0], "scale": [-1, 1, 1]}],
        scenes=[{"nodes": [0, 1]}]))
    # Hierarchy: parent translated +Y, child rotated 90 degrees about Z and scaled 2.
    write("hierarchy.gltf", cube_doc(
        nodes=[{"children": [1], "translation": [0, 3, 0]},
               {"mesh": 0, "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476],
                "scale": [2, 2, 2]}],
        scenes=[{"nodes": [0]}]))
    # A node with zero scale (dropped with a warning) beside a normal one.
    write("singular_node.gltf", cube_doc(
        nodes=[{"mesh": 0}, {"mesh": 0, "scale": [0, 0, 0], "children": [2]}, {"mesh": 0}],
        scenes=[{"nodes": [0, 1]}]))

    # Strided positions: stride 16 for 12-byte elements. The view ends right after the last
    # element (16 * 2 + 12 = 44 bytes): valid, and rejected by a count * stride bound.
    tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    strided = b"".join(f32(p) + b"\0\0\0\0" for p in tri)[:44]

    def strided_doc(view_len):
        return {
            "asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
            "buffers": [{"byteLength": 44, "uri": data_uri(strided)}],
            "bufferViews": [{"buffer": 0, "byteLength": view_len, "byteStride": 16}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}]}
    write("strided_exact.gltf", strided_doc(44))
    write("strided_short.gltf", strided_doc(43))

    # Strips, fans, points and lines in one mesh over the same 4 vertices (a unit quad).
    quad = f32([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0])
    fan_order = u16([0, 1, 3, 2])
    modes = {
        "asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": 0}, "mode": 5},          # strip: 2 triangles
            {"attributes": {"POSITION": 0}, "mode": 6, "indices": 1},  # fan: 2 triangles
            {"attributes": {"POSITION": 0}, "mode": 0},          # points: ignored
            {"attributes": {"POSITION": 0}, "mode": 1},          # lines: ignored
            {"attributes": {"NORMAL": 0}},                       # no POSITION: dropped
        ]}],
        "buffers": [{"byteLength": len(quad) + 8, "uri": data_uri(quad + fan_order)}],
        "bufferViews": [{"buffer": 0, "byteLength": len(quad)},
                        {"buffer": 0, "byteOffset": len(quad), "byteLength": 8}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5123, "count": 4, "type": "SCALAR"}]}
    write("modes.gltf", modes)
    bad_mode = json.loads(json.dumps(modes))
    bad_mode["meshes"][0]["primitives"] = [{"attributes": {"POSITION": 0}, "mode": 9}]
    write("mode_unknown.gltf", bad_mode)

    # Materials: OPAQUE, MASK below the cutoff, BLEND 0.4, and a textured one (data URI PNG).
    png = png_2x2()
    materials = cube_doc(extra={
        "materials": [
            {"name": "opaque", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 0.2]}},
            {"name": "mask", "alphaMode": "MASK", "alphaCutoff": 0.5,
             "pbrMetallicRoughness": {"baseColorFactor": [0, 1, 0, 0.3]}},
            {"name": "blend", "alphaMode": "BLEND",
             "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 1, 0.4]}},
            {"name": "textured", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}]})
    materials["meshes"] = [{"name": "m%d" % i, "primitives": [
        {"attributes": {"POSITION": 0}, "indices": 1, "material": i}]} for i in range(4)]
    materials["nodes"] = [{"mesh": i, "translation": [2 * i, 0, 0]} for i in range(4)]
    materials["scenes"] = [{"nodes": [0, 1, 2, 3]}]
    write("materials.gltf", materials)

    # An alpha-tested material: MASK, cutoff 0.6, constant alpha 0.9, the 2x2 texture whose
    # alpha 128/255 at one texel puts 0.45 below the cutoff there.
    mask = cube_doc(extra={
        "materials": [{"name": "cut", "alphaMode": "MASK", "alphaCutoff": 0.6,
                       "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.9],
                                                "baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}]})
    mask["meshes"][0]["primitives"][0]["material"] = 0
    write("mask_textured.gltf", mask)

    # Lights: KHR_lights_punctual point, spot, directional; EXT_lights_area rect and disk.
    lights = cube_doc(extra={
        "extensionsUsed": ["KHR_lights_punctual", "EXT_lights_area"],
        "extensions": {
            "KHR_lights_punctual": {"lights": [
                {"type": "point", "color": [1, 0.5, 0.25], "intensity": 10},
                {"type": "spot", "spot": {}}, {"type": "directional"}]},
            "EXT_lights_area": {"lights": [
                {"type": "rect", "size": 2, "rect": {"aspect": 1.5}, "intensity": 5},
                {"type": "disk", "size": 1}]}}})
    # The rect light's node turns local -Z to world -Y (-90 degrees about X).
    s = 0.7071067811865476
    lights["nodes"] = [
        {"mesh": 0, "children": [1, 2, 3, 4, 5]},
        {"translation": [0, 5, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"extensions": {"KHR_lights_punctual": {"light": 2}}},
        {"translation": [0, 4, 0], "rotation": [-s, 0, 0, s],
         "extensions": {"EXT_lights_area": {"light": 0}}},
        {"translation": [1, 4, 0], "extensions": {"EXT_lights_area": {"light": 1}}}]
    write("lights.gltf", lights)

    # One vertex at infinity: recoverable, its triangles are dropped and counted.
    inf_pos = f32([c for p in CUBE_POS[:7] for c in p] + [float("inf"), 0.5, 0.5])
    inf_doc = cube_doc()
    inf_doc["buffers"][0]["uri"] = data_uri(inf_pos + idx)
    write("cube_one_infinite.gltf", inf_doc)

    # --- malformed files: one defect each
    over = cube_doc()
    over["accessors"][0]["count"] = 9  # 9 * 12 = 108 > 96-byte view
    write("accessor_overrun.gltf", over)
    view_over = cube_doc()
    view_over["bufferViews"][1]["byteLength"] = 100  # 96 + 100 > 168
    write("bufferview_overrun.gltf", view_over)
    count0 = cube_doc()
    count0["accessors"][0]["count"] = 0
    write("accessor_count0.gltf", count0)
    misaligned = cube_doc()
    misaligned["accessors"][0]["byteOffset"] = 2
    misaligned["accessors"][0]["count"] = 7
    write("accessor_misaligned.gltf", misaligned)
    wrong_type = cube_doc()
    wrong_type["accessors"][0]["componentType"] = 5123
    write("accessor_wrong_type.gltf", wrong_type)

    # Indices 0..7 are valid; 36 and 40 are not. Two triangles reference them.
    bad_idx = [i for t in CUBE_TRIS for i in t]
    bad_idx[0], bad_idx[5] = 36, 40
    bad_data = pos + u16(bad_idx)
    oob = cube_doc()
    oob["buffers"][0]["uri"] = data_uri(bad_data)
    write("index_out_of_range.gltf", oob)
    not3 = cube_doc()
    not3["accessors"][1]["count"] = 35
    write("index_not_multiple_of_3.gltf", not3)

    write("uri_parent.gltf", cube_doc(uri="../cube.bin"))
    write("uri_percent_parent.gltf", cube_doc(uri="%2e%2e/scene/cube.bin"))
    write("uri_absolute.gltf", cube_doc(uri="/etc/passwd"))
    write("uri_file.gltf", cube_doc(uri="file:///etc/passwd"))
    write("uri_http.gltf", cube_doc(uri="http://example.com/cube.bin"))
    write("uri_shell.gltf", cube_doc(uri="cube.bin;touch pwned"))
    write("uri_missing.gltf", cube_doc(uri="nothere.bin"))
    bad64 = cube_doc()
    bad64["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAAA!!!!"
    write("data_uri_bad_base64.gltf", bad64)
    huge = cube_doc()
    huge["buffers"][0]["byteLength"] = 900000000  # the payload is 168 bytes
    write("buffer_declared_huge.gltf", huge)
    write("basisu_required.gltf", cube_doc(extra={
        "extensionsUsed": ["KHR_texture_basisu"],
        "extensionsRequired": ["KHR_texture_basisu"]}))
    write("node_cycle.gltf", cube_doc(
        nodes=[{"mesh": 0}, {"children": [2]}, {"children": [1]}], scenes=[{"nodes": [0]}]))
    write("node_two_parents.gltf", cube_doc(
        nodes=[{"children": [2]}, {"children": [2]}, {"mesh": 0}], scenes=[{"nodes": [0, 1]}]))
    write("node_self_child.gltf", cube_doc(nodes=[{"mesh": 0, "children": [0]}]))
    write("not_gltf2.gltf", {"asset": {"version": "1.0"}})
    # A repeated key (tinygltf, like nlohmann, would keep the last one silently): the cube's
    # node given its mesh twice.
    text = json.dumps(cube_doc(), indent=1).replace('"mesh": 0', '"mesh": 0, "mesh": 0', 1)
    with open(os.path.join(HERE, "duplicate_key.gltf"), "w") as f:
        f.write(text + "\n")

    doc_glb = {k: v for k, v in cube_doc().items()} | {"buffers": [{"byteLength": len(data)}]}
    write_bin("cube_nul_padded.glb", glb(doc_glb, data, nul_padding=True))
    write_bin("glb_length_beyond_file.glb", glb(doc_glb, data, length_delta=1000))
    write_bin("glb_json_chunk_huge.glb", glb(doc_glb, data, json_len=0x7ffffff0))
    write_bin("glb_bin_chunk_huge.glb", glb(doc_glb, data, bin_len=0x7ffffff0))
    # BIN chunk 8 bytes longer than what is left: tinygltf 2.7 alone would read past the end.
    write_bin("glb_bin_chunk_plus8.glb", glb(doc_glb, data, bin_len=len(pad4(data)) + 8))
    write_bin("glb_missing_bin.glb", glb(doc_glb, data, bin_chunk=False))
    write_bin("glb_truncated.glb", glb(doc_glb, data)[:30])
    write_bin("empty.glb", b"")
    write_bin("empty.gltf", b"")


if __name__ == "__main__":
    main()
