#!/usr/bin/env python3
"""Renders every glTF/GLB under the given folders through `foveal render` and prints a
Markdown table: model, loaded / refused (with the reason) / incomplete (files missing),
what it was drawn with (shader variant, G-buffer bytes per pixel, the file's lights or
the rig, a blend pass), warnings, seconds. Usage:

    tools/scene_corpus.py [--foveal build/bin/foveal] [--size 256x128] [--timeout 300] DIR...

A model whose referenced files (buffers, images) are not all present is reported as
"incomplete" and not rendered: such a refusal says nothing about the loader. A model
whose textures' only images are KTX2 is refused by foveal (no KTX2/Basis decoder on
Debian 12) and counted apart. Exit 0 when every other complete model loaded, 1
otherwise."""
import argparse
import json
import os
import platform
import struct
import subprocess
import sys
import tempfile
import time
import urllib.parse


def gltf_json(path):
    """The JSON of a .gltf, or of a .glb's first chunk; None when unreadable."""
    try:
        with open(path, "rb") as f:
            data = f.read()
        if path.lower().endswith(".glb"):
            if len(data) < 20 or data[:4] != b"glTF":
                return None
            length, kind = struct.unpack_from("<II", data, 12)
            if kind != 0x4E4F534A:
                return None
            return json.loads(data[20:20 + length].decode("utf-8"))
        return json.loads(data.decode("utf-8"))
    except (OSError, ValueError, UnicodeDecodeError):
        return None


def missing_files(path):
    """The external files the model references that are absent."""
    doc = gltf_json(path)
    if doc is None:
        return []
    base = os.path.dirname(path)
    missing = []
    for item in doc.get("buffers", []) + doc.get("images", []):
        uri = item.get("uri")
        if not uri or uri.startswith("data:"):
            continue
        if not os.path.exists(os.path.join(base, urllib.parse.unquote(uri))):
            missing.append(uri)
    return missing


def ktx2_only(path):
    """Whether every texture of the model has a KTX2 image only (KHR_texture_basisu, no
    PNG/JPEG fallback): Debian 12 has no KTX2/Basis decoder, so foveal refuses these."""
    doc = gltf_json(path)
    if doc is None or not doc.get("textures"):
        return False
    images = doc.get("images", [])

    def is_ktx2(i):
        if not isinstance(i, int) or not 0 <= i < len(images):
            return False
        img = images[i]
        return img.get("mimeType") == "image/ktx2" or str(img.get("uri", "")).lower().endswith(".ktx2")

    for t in doc["textures"]:
        if "source" in t and not is_ktx2(t["source"]):
            return False
        if "source" not in t and not is_ktx2(t.get("extensions", {}).get("KHR_texture_basisu", {}).get("source")):
            return False
    return True


def render(foveal, path, size, timeout):
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [foveal, "render", "--scene", path, "--method", "full", "--size", size, "--frames", "1",
               "--out", os.path.join(tmp, "frame.png"), "--json"]
        start = time.monotonic()
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return {"rc": None, "seconds": time.monotonic() - start, "warnings": [], "error": f"timed out after {timeout} s",
                    "drawn": ""}
        seconds = time.monotonic() - start
    warnings, errors = [], []
    for line in p.stderr.splitlines():
        if ": warning: " in line:
            warnings.append(line.split(": warning: ", 1)[1].replace(path + ": ", ""))
        elif ": error: " in line:
            errors.append(line.split(": error: ", 1)[1].replace(path + ": ", ""))
    renderer, drawn = None, ""
    if p.returncode == 0:
        try:
            j = json.loads(p.stdout)
            renderer = j.get("renderer")
            # What the scene was drawn with: its shader variant and G-buffer bytes per
            # pixel (docs/scenes.md, "Materials") and whose lights ("Lights").
            v, lights = j.get("material_variant", {}), j.get("lights", {})
            drawn = f"{v.get('shader', '?')}, {v.get('gbuffer_bytes_per_pixel', '?')} B/px; lights: {lights.get('source', '?')}"
            if lights.get("source") == "file":
                drawn += f" ({lights.get('count')})"
            if j.get("passes_ms", {}).get("blend", 0) > 0:
                drawn += "; blend pass"
        except ValueError:
            pass
    return {"rc": p.returncode, "seconds": seconds, "warnings": warnings, "error": "; ".join(errors), "renderer": renderer,
            "drawn": drawn}


def cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--foveal", default=os.path.join(os.path.dirname(__file__), "..", "build", "bin", "foveal"))
    ap.add_argument("--size", default="256x128")
    ap.add_argument("--timeout", type=float, default=300)
    a = ap.parse_args()

    models = []  # (name in the table, path): the path under its folder, named by the folder
    for d in a.dirs:
        d = os.path.abspath(d)
        for root, _, files in os.walk(d):
            models += [(os.path.join(os.path.basename(d), os.path.relpath(os.path.join(root, f), d)), os.path.join(root, f))
                       for f in files if f.lower().endswith((".gltf", ".glb"))]
    models.sort()

    print("| model | result | drawn with | warnings | s |")
    print("|---|---|---|---|---|")
    counts = {"loaded": 0, "refused": 0, "ktx2": 0, "incomplete": 0}
    renderer = None
    for name, path in models:
        missing = missing_files(path)
        if missing:
            counts["incomplete"] += 1
            print(f"| {cell(name)} | incomplete: {cell(', '.join(missing[:3]))}{' ...' if len(missing) > 3 else ''} absent | | | |")
            continue
        r = render(a.foveal, path, a.size, a.timeout)
        renderer = renderer or r.get("renderer")
        result = "loaded" if r["rc"] == 0 else "ktx2" if ktx2_only(path) else "refused"
        counts[result] += 1
        text = {"loaded": "loaded", "ktx2": "KTX2 images only (no decoder on Debian 12)"}.get(result, "refused")
        if r["rc"] != 0:
            text += f" (exit {r['rc']}): {r['error']}"
        print(f"| {cell(name)} | {cell(text)} | {cell(r['drawn'])} | {cell('; '.join(r['warnings']))} | {r['seconds']:.1f} |",
              flush=True)
    print()
    print(f"{len(models)} files: {counts['loaded']} loaded, {counts['refused']} refused, {counts['ktx2']} KTX2-only, "
          f"{counts['incomplete']} incomplete (not rendered). Renderer: {renderer}; host: {platform.node()} "
          f"({platform.machine()}, {os.cpu_count()} CPUs); size {a.size}.")
    return 0 if counts["refused"] == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
