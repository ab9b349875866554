#!/usr/bin/env python3
"""Writes a copy of a glTF scene lit by N KHR_lights_punctual point lights on a grid
through its bounds (a 4x4x4 grid for the default 64, like foveal's own rig): a scene with
many of the file's own lights, for measuring the lighting pass (docs/scenes.md, "Lights").
The copy's buffers and images point back at the original's files; a view file beside the
original is copied.

  tools/scenes/point_lights.py data/scenes/Dungeon/dungeon_simplified.gltf OUT_DIR [--lights 64]

Each light has range 0.35 x the bounds' diagonal (the rig's) and intensity
--intensity x range^2 candela (default 0.1: 1.6 lux at a quarter of the range), with the
rig's four warm and cool tints."""
import argparse
import json
import math
import os
import sys


def mat_mul(a, b):
    """4x4 column-major products, as lists of 16."""
    return [sum(a[k * 4 + r] * b[c * 4 + k] for k in range(4)) for c in range(4) for r in range(4)]


def local_matrix(n):
    if "matrix" in n:
        return list(n["matrix"])
    tx, ty, tz = n.get("translation", [0, 0, 0])
    x, y, z, w = n.get("rotation", [0, 0, 0, 1])
    sx, sy, sz = n.get("scale", [1, 1, 1])
    r = [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w),
         2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
         2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)]
    return [r[0] * sx, r[1] * sx, r[2] * sx, 0, r[3] * sy, r[4] * sy, r[5] * sy, 0,
            r[6] * sz, r[7] * sz, r[8] * sz, 0, tx, ty, tz, 1]


def scene_bounds(g):
    """World bounds of the default scene from the POSITION accessors' min/max."""
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    stack = [(i, [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]) for i in g["scenes"][g.get("scene", 0)]["nodes"]]
    while stack:
        i, parent = stack.pop()
        n = g["nodes"][i]
        world = mat_mul(parent, local_matrix(n))
        if "mesh" in n:
            for p in g["meshes"][n["mesh"]]["primitives"]:
                a = g["accessors"][p["attributes"]["POSITION"]]
                if "min" not in a or "max" not in a:
                    continue
                for c in range(8):
                    v = [a["max"][k] if c >> k & 1 else a["min"][k] for k in range(3)]
                    w = [sum(world[k * 4 + r] * (v + [1])[k] for k in range(4)) for r in range(3)]
                    lo = [min(x, y) for x, y in zip(lo, w)]
                    hi = [max(x, y) for x, y in zip(hi, w)]
        stack += [(c, world) for c in n.get("children", [])]
    if not all(math.isfinite(v) for v in lo + hi):
        sys.exit("point_lights.py: no POSITION accessor with min/max in the default scene")
    return lo, hi


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("gltf", help="source .gltf")
    ap.add_argument("out_dir", help="folder for the copy (created)")
    ap.add_argument("--lights", type=int, default=64, help="number of point lights, 1-64 (default 64)")
    ap.add_argument("--intensity", type=float, default=0.1, help="intensity / range^2 in cd (default 0.1)")
    a = ap.parse_args()
    if not 1 <= a.lights <= 64 or not a.intensity >= 0:
        sys.exit("point_lights.py: --lights must be in 1..64 and --intensity >= 0")
    src_dir = os.path.dirname(os.path.abspath(a.gltf))
    stem = os.path.splitext(os.path.basename(a.gltf))[0]
    try:
        with open(a.gltf) as f:
            g = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"point_lights.py: {e}")
    os.makedirs(a.out_dir, exist_ok=True)
    out_dir = os.path.abspath(a.out_dir)
    for key in ("buffers", "images"):
        for item in g.get(key, []):
            uri = item.get("uri")
            if uri and not uri.startswith("data:"):
                item["uri"] = os.path.relpath(os.path.join(src_dir, uri), out_dir)
    lo, hi = scene_bounds(g)
    size = [h - l for l, h in zip(lo, hi)]
    inner_lo = [l + 0.1 * s for l, s in zip(lo, size)]
    inner_hi = [h - 0.1 * s for h, s in zip(hi, size)]
    rng = 0.35 * math.sqrt(sum(s * s for s in size))
    tints = [[1.0, 0.78, 0.55], [0.65, 0.8, 1.0], [1.0, 0.9, 0.8], [0.9, 0.7, 1.0]]
    lights = []
    scene = g["scenes"][g.get("scene", 0)]
    for i in range(a.lights):
        cell = [i % 4, (i // 4) % 4, i // 16]
        p = [l + (h - l) * (c + 0.5) / 4 for l, h, c in zip(inner_lo, inner_hi, cell)]
        lights.append({"type": "point", "color": tints[i % 4], "intensity": a.intensity * rng * rng, "range": rng})
        g.setdefault("nodes", []).append({"name": f"light_{i}", "translation": p,
                                          "extensions": {"KHR_lights_punctual": {"light": i}}})
        scene["nodes"].append(len(g["nodes"]) - 1)
    g.setdefault("extensions", {})["KHR_lights_punctual"] = {"lights": lights}
    used = g.setdefault("extensionsUsed", [])
    if "KHR_lights_punctual" not in used:
        used.append("KHR_lights_punctual")
    out = os.path.join(out_dir, f"{stem}_lights{a.lights}.gltf")
    with open(out + ".tmp", "w") as f:
        json.dump(g, f)
    os.replace(out + ".tmp", out)
    view_path = os.path.join(src_dir, stem + ".view.json")
    if os.path.exists(view_path):
        with open(view_path) as f:
            view = f.read()
        view_out = os.path.join(out_dir, f"{stem}_lights{a.lights}.view.json")
        with open(view_out + ".tmp", "w") as f:
            f.write(view)
        os.replace(view_out + ".tmp", view_out)
    print(out)


if __name__ == "__main__":
    main()
