#!/usr/bin/env python3
"""Compares two builds of `foveal render` on the same scene in one run: frame time per
pass and render-target memory, for each pipeline and method, runs interleaved (A B B A
A B ...) so that the machine's noise falls on both alike. Prints a Markdown table of
medians and B/A ratios (or --json).

    tools/bench/compare_builds.py --a OLD/bin/foveal --b build/bin/foveal \\
        [--scene data/scenes/Dungeon/dungeon_simplified.gltf] [--size 2880x1600] \\
        [--rounds 5] [--frames 3] [--methods full,rmfr] [--pipelines gbuffer,visibility]

Used for "a plain scene is no slower and holds no more render-target memory than before
the material features" (docs/results/render_bench.md). Each run is `foveal render --json
--frames N --warmup 1` with RMFR + EFR at sigma_d 2, sigma_nd 3, f 0.3 (full: the
method alone); its per-pass GPU medians are the run's figure, and the table gives the
median over the rounds. Exit 2 on a bad argument, 1 when a run fails (its stderr shown)."""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

PASS_ORDER = ["shadow", "gbuffer", "visibility", "mapping", "material", "lighting", "inverse", "blend", "gpu_total", "cpu_frame"]


def run_render(foveal, scene, size, method, pipeline, frames, out_dir):
    args = [foveal, "render", "--scene", scene, "--size", size, "--method", method, "--pipeline", pipeline,
            "--frames", str(frames), "--warmup", "1", "--json", "--out", os.path.join(out_dir, "frame.png")]
    if method != "full":
        args += ["--sigma-d", "2", "--sigma-nd", "3", "--fx", "0.3", "--fy", "0.3"]
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        sys.stderr.write(f"compare_builds: {' '.join(args)} failed (exit {p.returncode}):\n{p.stderr}")
        sys.exit(1)
    return json.loads(p.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="the reference build's foveal")
    ap.add_argument("--b", required=True, help="the build compared with it")
    ap.add_argument("--scene", default="data/scenes/Dungeon/dungeon_simplified.gltf")
    ap.add_argument("--size", default="2880x1600")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--methods", default="full,rmfr")
    ap.add_argument("--pipelines", default="gbuffer,visibility")
    ap.add_argument("--json", action="store_true", help="print the medians and ratios as JSON")
    a = ap.parse_args()
    if a.rounds < 1 or a.frames < 1:
        ap.error("--rounds and --frames must be at least 1")
    for exe in (a.a, a.b):
        if not os.access(exe, os.X_OK):
            ap.error(f"{exe}: not an executable")
    configs = [(p, m) for p in a.pipelines.split(",") for m in a.methods.split(",")]
    runs = {(build, p, m): [] for build in "ab" for p, m in configs}
    total = a.rounds * len(configs) * 2
    done = 0
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            for p, m in configs:
                order = "ab" if r % 2 == 0 else "ba"
                for build in order:
                    exe = a.a if build == "a" else a.b
                    runs[(build, p, m)].append(run_render(exe, a.scene, a.size, m, p, a.frames, tmp))
                    done += 1
                    print(f"\rcompare_builds: {done}/{total} runs", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)

    result = []
    for p, m in configs:
        row = {"pipeline": p, "method": m, "passes_ms": {}, "targets_mb": {}, "variant": {}}
        for build in "ab":
            rs = runs[(build, p, m)]
            names = [n for n in PASS_ORDER if n in rs[0]["passes_ms"]]
            row["passes_ms"][build] = {n: statistics.median(x["passes_ms"][n] for x in rs) for n in names}
            row["targets_mb"][build] = rs[0]["targets_mb"]["total"]
            row["variant"][build] = rs[0].get("material_variant", {}).get("shader", "(none)")
        pa, pb = row["passes_ms"]["a"], row["passes_ms"]["b"]
        row["ratio"] = {n: (pb[n] / pa[n] if pa.get(n) else None) for n in pb if n in pa}
        row["targets_ratio"] = row["targets_mb"]["b"] / row["targets_mb"]["a"]
        result.append(row)

    if a.json:
        print(json.dumps({"a": a.a, "b": a.b, "scene": a.scene, "size": a.size, "rounds": a.rounds,
                          "frames": a.frames, "rows": result}, indent=2))
        return
    print(f"A = {a.a}, B = {a.b}; {a.scene} at {a.size}; {a.rounds} rounds of {a.frames} frames, interleaved\n")
    print("| pipeline | method | pass | A ms | B ms | B / A |")
    print("|---|---|---|---|---|---|")
    for row in result:
        for n, ratio in row["ratio"].items():
            if row["passes_ms"]["a"][n] == 0 and row["passes_ms"]["b"][n] == 0:
                continue
            shown = f"{ratio:.3f}" if ratio is not None else "-"
            print(f"| {row['pipeline']} | {row['method']} | {n} | {row['passes_ms']['a'][n]:.1f} | {row['passes_ms']['b'][n]:.1f} | {shown} |")
        print(f"| {row['pipeline']} | {row['method']} | render targets MB | {row['targets_mb']['a']:.2f} | "
              f"{row['targets_mb']['b']:.2f} | {row['targets_ratio']:.3f} |")
    variants = sorted({v for row in result for v in row["variant"].values()})
    print(f"\nshader variants drawn: {', '.join(variants)}")


if __name__ == "__main__":
    main()
