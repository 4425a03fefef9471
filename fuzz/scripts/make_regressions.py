#!/usr/bin/env python3
"""Writes the reproductions of issue 12's parse- and validation-level cases into
fuzz/regressions/<target>/ (run from the fuzz folder, after the seeds exist). Crashing inputs
found by the fuzzers are copied there by hand instead (see README.md). The `.expected` files
are written by `SWEEPFFD_BLESS=1 cargo test --test fuzz_regressions`."""

import json
import os
import struct


def write(target, name, data):
    os.makedirs(os.path.join("regressions", target), exist_ok=True)
    with open(os.path.join("regressions", target, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


TRIANGLE = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)


def gltf_json(nodes, buffer, accessors=None, primitive=None):
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": [{"primitives": [primitive or {"attributes": {"POSITION": 0}}]}],
        "buffers": [buffer],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": accessors
        or [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
    }


def glb(doc, blob):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(blob), b"BIN\0") + blob
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def chain(depth):
    return [{"children": [i]} for i in range(1, depth)] + [{"mesh": 0}]


def doubling(depth):
    nodes = [{"children": [1, 2]}]
    for level in range(1, depth):
        nodes += [{"children": [2 * level + 1, 2 * level + 2]}] * 2
    return nodes + [{"mesh": 0}] * 2


def main():
    # 2: a finite coordinate that overflows f32 in the PLY writer (first byte 0: OBJ input).
    write("write_round_trip", "case02_f32_overflow.obj", b"\0v 1e39 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n")
    # 3: a parent chain deeper than the node depth limit (1024).
    write("gltf", "case03_deep_chain.glb", glb(gltf_json(chain(3000), {"byteLength": 36}), TRIANGLE))
    # 4: shared children doubling the instances at each of 17 levels (2^17 > 2^16 instances).
    write("gltf", "case04_doubling.glb", glb(gltf_json(doubling(17), {"byteLength": 36}), TRIANGLE))
    # 5: buffer uris outside the file's folder.
    for name, uri in [
        ("absolute", "/etc/passwd"),
        ("parent", "../../secret.bin"),
        ("http", "http://example.com/buffer.bin"),
        ("file", "file:///etc/passwd"),
    ]:
        doc = gltf_json([{"mesh": 0}], {"byteLength": 36, "uri": uri})
        write("gltf", f"case05_{name}_uri.gltf", json.dumps(doc))
    # 6: a float index accessor, on which the gltf crate panics inside its validation.
    accessors = gltf_json([], {})["accessors"] + [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "SCALAR"}]
    primitive = {"attributes": {"POSITION": 0}, "indices": 1}
    doc = gltf_json([{"mesh": 0}], {"byteLength": 36}, accessors, primitive)
    write("gltf", "case06_float_indices.glb", glb(doc, TRIANGLE))
    # 8: bindings with θ = 1e300 and d = 1e308 on vertex 0 (record: sweep, zero, t, θ, d, h).
    with open("corpus/bindings/tube.bin", "rb") as f:
        seed = f.read()
    for name, offset, value in [("theta_1e300", 16, 1e300), ("d_1e308", 24, 1e308)]:
        at = 40 + offset
        write("bindings", f"case08_{name}.bin", seed[:at] + struct.pack("<d", value) + seed[at + 8 :])
    # 9: a key with more radii than the limit (4096).
    key = lambda z, m: {"center": [0, 0, z], "rotation": [0, 0, 0, 1], "radii": [0.4] * m}
    rig = {"format": "sweepffd-rig", "version": 1, "sweeps": [{"name": "tube", "vertices": "all", "keys": [key(0, 4097), key(3, 4097)]}]}
    write("rig", "case09_4097_radii.json", json.dumps(rig, separators=(",", ":")))
    # 10: non-finite values in fields other than positions.
    triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    write("obj", "case10_vn_nan.obj", triangle + "vn nan 0 1\nf 1//1 2//1 3//1\n")
    write("obj", "case10_vt_inf.obj", triangle + "vt inf 0\nf 1/1 2/1 3/1\n")
    write("obj", "case10_w_nan.obj", "v 0 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    write("off", "case10_inf_edges.off", "OFF\n3 1 inf\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    # 11: a knot vector with a tiny first interval, and a duplicated PLY property.
    rig = {"format": "sweepffd-rig", "version": 1, "sweeps": [{"name": "tube", "vertices": "all", "keys": [key(0, 8), key(1.5, 8), key(3, 8)], "knots": [0, 1e-300, 1]}]}
    write("rig", "case11_tiny_knot.json", json.dumps(rig))
    write(
        "ply",
        "case11_duplicate_x.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property float x\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0 5\n1 0 0 5\n0 1 0 5\n3 0 1 2\n",
    )
    # Issue 28: a NORMAL on POSITION's own accessor, which a faithful write would overwrite
    # (first byte 4: GLB input), and an OBJ of a group before each of 2,000 faces.
    primitive = {"attributes": {"POSITION": 0, "NORMAL": 0}}
    doc = gltf_json([{"mesh": 0}], {"byteLength": 36}, None, primitive)
    write("write_round_trip", "case28_aliased_normal.glb", b"\4" + glb(doc, TRIANGLE))
    # Issue 28: tiny files whose scene expands far past what they store: a POSITION accessor
    # of 33,554,430 elements backed by 3 sparse values, an index accessor of 201,326,592 backed
    # by 3, and 16 levels of shared children over a 512-vertex mesh (33,554,432 vertices).
    sparse = lambda view_indices, view_values: {"count": 3, "indices": {"bufferView": view_indices, "componentType": 5125}, "values": {"bufferView": view_values}}
    three = struct.pack("<3I", 0, 1, 2)
    views = [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 12}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}]
    accessors = [{"componentType": 5126, "count": 33_554_430, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0], "sparse": sparse(1, 0)}]
    doc = gltf_json([{"mesh": 0}], {"byteLength": 60}, accessors)
    doc["bufferViews"] = views
    write("gltf", "case28_sparse_positions.glb", glb(doc, TRIANGLE + three + three))
    accessors = gltf_json([], {})["accessors"] + [{"componentType": 5125, "count": 201_326_592, "type": "SCALAR", "sparse": sparse(1, 2)}]
    doc = gltf_json([{"mesh": 0}], {"byteLength": 60}, accessors, {"attributes": {"POSITION": 0}, "indices": 1})
    doc["bufferViews"] = views
    write("gltf", "case28_sparse_indices.glb", glb(doc, TRIANGLE + three + three))
    grid = struct.pack("<1536f", *[c for i in range(512) for c in (i % 32, i // 32, 0)])
    accessors = [{"bufferView": 0, "componentType": 5126, "count": 512, "type": "VEC3", "min": [0, 0, 0], "max": [31, 15, 0]}]
    doc = gltf_json(doubling(16), {"byteLength": len(grid)}, accessors)
    doc["bufferViews"] = [{"buffer": 0, "byteLength": len(grid)}]
    write("gltf", "case28_shared_levels.glb", glb(doc, grid))
    groups = "".join(f"g g{i}\nf 1 2 3\n" for i in range(2_000))
    write("obj", "case28_many_groups.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n" + groups)


if __name__ == "__main__":
    main()
