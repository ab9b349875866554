#!/usr/bin/env python3
"""Writes a copy of a glTF scene with tinted alphaMode BLEND panes in front of the viewer:
a scene with transparency over real opaque content, for measuring the blend pass
(docs/scenes.md, "Transparency"). The copy's buffers and images point back at the
original's files; its view file is copied.

  tools/scenes/blend_panes.py data/scenes/Dungeon/dungeon_simplified.gltf OUT_DIR [--panes 3]

The panes face the viewer on the line from the view file's eye to its target, at equal
steps, the nearest 60 degrees wide in view and each farther one 16 degrees narrower (at
least 12), so they overlap in view at different depths."""
import argparse
import base64
import json
import math
import os
import struct
import sys


def normalise(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def rotation_from_z(d):
    """Unit quaternion (x, y, z, w) turning +z onto unit vector d."""
    z = [0.0, 0.0, 1.0]
    c = sum(a * b for a, b in zip(z, d))
    axis = [z[1] * d[2] - z[2] * d[1], z[2] * d[0] - z[0] * d[2], z[0] * d[1] - z[1] * d[0]]
    if c < -0.999999:
        return [0.0, 1.0, 0.0, 0.0]
    q = axis + [1.0 + c]
    return normalise(q)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("gltf", help="source .gltf with a view file NAME.view.json beside it")
    ap.add_argument("out_dir", help="folder for the copy (created)")
    ap.add_argument("--panes", type=int, default=3, help="number of panes (default 3)")
    ap.add_argument("--alpha", type=float, default=0.35, help="the panes' base colour alpha (default 0.35)")
    a = ap.parse_args()
    if a.panes < 1 or not 0.0 <= a.alpha <= 1.0:
        sys.exit("blend_panes.py: --panes must be >= 1 and --alpha in [0, 1]")
    src_dir = os.path.dirname(os.path.abspath(a.gltf))
    stem = os.path.splitext(os.path.basename(a.gltf))[0]
    view_path = os.path.join(src_dir, stem + ".view.json")
    try:
        with open(a.gltf) as f:
            g = json.load(f)
        with open(view_path) as f:
            view = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"blend_panes.py: {e}")
    os.makedirs(a.out_dir, exist_ok=True)
    out_dir = os.path.abspath(a.out_dir)
    for key in ("buffers", "images"):
        for item in g.get(key, []):
            uri = item.get("uri")
            if uri and not uri.startswith("data:"):
                item["uri"] = os.path.relpath(os.path.join(src_dir, uri), out_dir)

    # One unit quad in the xy plane facing +z: positions, normals, then indices.
    pos = [-0.5, -0.5, 0, 0.5, -0.5, 0, 0.5, 0.5, 0, -0.5, 0.5, 0]
    nrm = [0, 0, 1] * 4
    idx = [0, 1, 2, 0, 2, 3]
    data = struct.pack("<12f", *pos) + struct.pack("<12f", *nrm) + struct.pack("<6H", *idx) + b"\0\0"
    g.setdefault("buffers", []).append(
        {"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()})
    b = len(g["buffers"]) - 1
    views = g.setdefault("bufferViews", [])
    views += [{"buffer": b, "byteOffset": 0, "byteLength": 48}, {"buffer": b, "byteOffset": 48, "byteLength": 48},
              {"buffer": b, "byteOffset": 96, "byteLength": 12}]
    acc = g.setdefault("accessors", [])
    v0 = len(views) - 3
    acc += [{"bufferView": v0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0]},
            {"bufferView": v0 + 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": v0 + 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    a0 = len(acc) - 3
    tints = [[0.6, 0.85, 1.0], [1.0, 0.75, 0.5], [0.7, 1.0, 0.7]]
    mats = g.setdefault("materials", [])
    meshes = g.setdefault("meshes", [])
    eye, target = view["eye"], view["target"]
    d = normalise([t - e for t, e in zip(target, eye)])
    length = math.sqrt(sum((t - e) ** 2 for t, e in zip(target, eye)))
    rot = rotation_from_z([-c for c in d])
    scene = g["scenes"][g.get("scene", 0)]
    for i in range(a.panes):
        mats.append({"name": f"pane_{i}", "alphaMode": "BLEND", "doubleSided": True,
                     "pbrMetallicRoughness": {"baseColorFactor": tints[i % 3] + [a.alpha], "metallicFactor": 0.0,
                                              "roughnessFactor": 0.15}})
        meshes.append({"primitives": [{"attributes": {"POSITION": a0, "NORMAL": a0 + 1}, "indices": a0 + 2,
                                       "material": len(mats) - 1}]})
        dist = length * (i + 1) / (a.panes + 1)
        size = 2 * dist * math.tan(math.radians(max(30 - 8 * i, 6)))  # nearer panes wider in view
        g.setdefault("nodes", []).append({"name": f"pane_{i}", "mesh": len(meshes) - 1,
                                          "translation": [e + c * dist for e, c in zip(eye, d)],
                                          "rotation": rot, "scale": [size, size, 1]})
        scene["nodes"].append(len(g["nodes"]) - 1)
    out = os.path.join(out_dir, stem + "_panes.gltf")
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(g, f)
    os.replace(tmp, out)
    view_out = os.path.join(out_dir, stem + "_panes.view.json")
    with open(view_out + ".tmp", "w") as f:
        json.dump(view, f, indent=2)
    os.replace(view_out + ".tmp", view_out)
    print(out)


if __name__ == "__main__":
    main()
