#!/usr/bin/env python3
"""Writes the seed corpora of the mesh targets (fuzz/corpus/{obj,ply,off,gltf,write_round_trip})
from the shared test meshes, cut down to their first vertices and the faces among them, plus
small glTF files built here. Usage: make_seeds.py MESHES_FOLDER CORPUS_FOLDER

The rig-level seeds (rig, pose, edits, bindings, script) are small files written by hand or
checked against the fuzz scene by tests/fuzz_regressions.rs."""

import base64
import json
import os
import struct
import sys

VERTICES = 200  # vertices kept of each shared mesh


def write(folder, name, data):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def cut_obj(text, n):
    """The first n v/vt/vn statements, the faces whose references all lie among them, and the
    other statements (groups, objects, materials) as they are."""
    out, counts = [], {"v": 0, "vt": 0, "vn": 0}
    for line in text.splitlines():
        words = line.split()
        if not words:
            continue
        key = words[0]
        if key in counts:
            if counts[key] < n:
                counts[key] += 1
                out.append(line)
        elif key == "f":
            refs = [int(x) for w in words[1:] for x in w.split("/") if x]
            if all(0 < r <= n for r in refs):
                out.append(line)
        else:
            out.append(line)
    return "\n".join(out) + "\n"


def read_off(text):
    lines = [l.split("#")[0].split() for l in text.splitlines()]
    lines = [l for l in lines if l]
    nv, nf = int(lines[1][0]), int(lines[1][1])
    vertices = [list(map(float, l[:3])) for l in lines[2 : 2 + nv]]
    faces = [list(map(int, l[1 : 1 + int(l[0])])) for l in lines[2 + nv : 2 + nv + nf]]
    return vertices, faces


def cut(vertices, faces, n):
    return vertices[:n], [f for f in faces if all(i < n for i in f)]


def off_text(vertices, faces, header="OFF"):
    lines = [header, f"{len(vertices)} {len(faces)} 0"]
    lines += [" ".join(repr(c) for c in v) for v in vertices]
    lines += [" ".join(map(str, [len(f)] + f)) for f in faces]
    return "\n".join(lines) + "\n"


def read_ply_ascii(text):
    head, body = text.split("end_header\n", 1)
    nv = int(head.split("element vertex ")[1].split()[0])
    nf = int(head.split("element face ")[1].split()[0])
    rows = body.splitlines()
    vertices = [list(map(float, r.split()[:5])) for r in rows[:nv]]
    faces = [list(map(int, r.split()[1:])) for r in rows[nv : nv + nf]]
    return vertices, faces


def ply(vertices, faces, fmt, scalar="float"):
    head = (
        f"ply\nformat {fmt} 1.0\ncomment cut down\nelement vertex {len(vertices)}\n"
        + "".join(f"property {scalar} {p}\n" for p in ["x", "y", "z", "confidence", "intensity"])
        + f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    if fmt == "ascii":
        body = "".join(" ".join(repr(c) for c in v) + "\n" for v in vertices)
        body += "".join(" ".join(map(str, [len(f)] + f)) + "\n" for f in faces)
        return head.encode() + body.encode()
    end = "<" if fmt == "binary_little_endian" else ">"
    code = "f" if scalar == "float" else "d"
    body = b"".join(struct.pack(end + code * 5, *v) for v in vertices)
    body += b"".join(struct.pack(end + "B" + "i" * len(f), len(f), *f) for f in faces)
    return head.encode() + body


def gltf_document(vertices, faces, uri_of, nodes):
    """A glTF with one mesh (f32 POSITION, u16 indices, triangles) drawn by `nodes`."""
    tris = [[f[0], f[i], f[i + 1]] for f in faces for i in range(1, len(f) - 1)]
    pos = b"".join(struct.pack("<3f", *v[:3]) for v in vertices)
    idx = b"".join(struct.pack("<3H", *t) for t in tris)
    idx += b"\0" * (-len(idx) % 4)
    blob = pos + idx
    lo = [min(v[i] for v in vertices) for i in range(3)]
    hi = [max(v[i] for v in vertices) for i in range(3)]
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": [{"name": "part", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(blob)} | ({"uri": uri_of(blob)} if uri_of else {})],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(tris) * 6, "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(vertices), "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5123, "count": len(tris) * 3, "type": "SCALAR"},
        ],
    }
    return doc, blob


def glb(doc, blob):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(blob), b"BIN\0") + blob
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def data_uri(blob):
    return "data:application/octet-stream;base64," + base64.b64encode(blob).decode()


# A node tree: the root turns and shifts, two children draw the mesh, one scaled.
NODES = [
    {"children": [1, 2], "rotation": [0, 0.3826834, 0, 0.9238795], "translation": [1, 0, 0]},
    {"mesh": 0},
    {"mesh": 0, "scale": [2, 2, 2]},
]


def main(meshes, corpus):
    seeds = {}
    for name in ["spot_control_mesh.obj", "teapot_newell_parts.obj", "bunny_closed.obj", "teapot_mcguire/teapot.obj"]:
        with open(os.path.join(meshes, name)) as f:
            seeds[("obj", os.path.basename(name))] = cut_obj(f.read(), VERTICES)
    for name in ["chair.off", "dino.off"]:
        with open(os.path.join(meshes, name)) as f:
            v, fa = cut(*read_off(f.read()), VERTICES)
        seeds[("off", name)] = off_text(v, fa)
    seeds[("off", "colours.off")] = (
        "COFF\n# colours\n3 1 0\n0 0 0 255 0 0 255\n1 0 0  0 255 0 128 # green\n0 1 0 0 0 255 255\n3 0 1 2 9 9 9\n"
    )
    with open(os.path.join(meshes, "bunny_stanford_zipper.ply")) as f:
        v, fa = cut(*read_ply_ascii(f.read()), VERTICES)
    seeds[("ply", "bunny_ascii.ply")] = ply(v, fa, "ascii")
    seeds[("ply", "bunny_le.ply")] = ply(v[:60], cut(v, fa, 60)[1], "binary_little_endian")
    seeds[("ply", "bunny_be_double.ply")] = ply(v[:60], cut(v, fa, 60)[1], "binary_big_endian", "double")
    with open(os.path.join(meshes, "spot_control_mesh.obj")) as f:
        text = cut_obj(f.read(), 60)
    v = [list(map(float, l.split()[1:4])) for l in text.splitlines() if l.startswith("v ")]
    fa = [[int(w.split("/")[0]) - 1 for w in l.split()[1:]] for l in text.splitlines() if l.startswith("f ")]
    doc, blob = gltf_document(v, fa, None, NODES)
    seeds[("gltf", "spot.glb")] = glb(doc, blob)
    doc, _ = gltf_document(v, fa, data_uri, NODES)
    seeds[("gltf", "spot.gltf")] = json.dumps(doc, indent=1)
    # Accessors that alias: the NORMAL of every primitive on its POSITION accessor.
    doc, blob = gltf_document(v, fa, None, NODES)
    for mesh in doc["meshes"]:
        for primitive in mesh["primitives"]:
            primitive["attributes"]["NORMAL"] = primitive["attributes"]["POSITION"]
    seeds[("gltf", "aliased_normal.glb")] = glb(doc, blob)
    # Many groups: a `g` (or an `o`) before each face of a 16 × 16 grid.
    grid = "".join(f"v {x} {y} 0\n" for y in range(17) for x in range(17))
    for y in range(16):
        for x in range(16):
            a = 17 * y + x + 1
            grid += f"{'g' if (x + y) % 2 else 'o'} part{16 * y + x}\nf {a} {a + 1} {a + 18} {a + 17}\n"
    seeds[("obj", "many_groups.obj")] = grid
    for (target, name), data in seeds.items():
        write(os.path.join(corpus, target), name, data)
        # write_round_trip: the first byte picks the format (obj 0, ply 1, off 2, gltf 3, glb 4).
        pick = {"obj": 0, "ply": 1, "off": 2, "gltf": 3, "glb": 4}[name.rsplit(".", 1)[1]]
        raw = data if isinstance(data, bytes) else data.encode()
        write(os.path.join(corpus, "write_round_trip"), name, bytes([pick]) + raw)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
