#!/usr/bin/env python3
"""Per-level quality of the two pipelines side by side, from two `foveal bench` runs.

    tools/charts/pipeline_quality.py GBUFFER_DIR VISIBILITY_DIR [--fpsnr-margin 0.2] [--ssim-margin 0.005]

GBUFFER_DIR and VISIBILITY_DIR are the output folders of the same sweep run with
`--pipeline gbuffer` and `--pipeline visibility` (each scored against its own pipeline's
full frame, as bench does). Prints a Markdown table per scene: FPSNR and SSIM per method
and level for both pipelines, the visibility pipeline's deltas, and whether each delta
meets issue 17's target (visibility >= gbuffer - margin). Exit 2 on missing or mismatched
rows (the two runs must hold the same scene x method x level points).
"""
import argparse
import csv
import math
import sys
from pathlib import Path


def read_rows(folder):
    path = Path(folder) / "bench.csv"
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"{path}: {e.strerror}")
    out = {}
    for line, r in enumerate(rows, start=2):
        try:
            key = (r["scene"], r["method"], float(r["sigma"]))
            out[key] = (float(r["fpsnr_db"]), float(r["ssim"]))
        except (KeyError, ValueError) as e:
            sys.exit(f"{path}:{line}: bad row ({e})")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gbuffer")
    ap.add_argument("visibility")
    ap.add_argument("--fpsnr-margin", type=float, default=0.2)
    ap.add_argument("--ssim-margin", type=float, default=0.005)
    a = ap.parse_args()
    g, v = read_rows(a.gbuffer), read_rows(a.visibility)
    if set(g) != set(v):
        missing = sorted(set(g) ^ set(v))[:3]
        print(f"the runs hold different points, e.g. {missing}", file=sys.stderr)
        sys.exit(2)
    scenes = sorted({k[0] for k in g})
    failures = total = 0
    for scene in scenes:
        print(f"### {scene}\n")
        print("| method | σ | FPSNR gbuffer | FPSNR visibility | Δ dB | SSIM gbuffer | SSIM visibility | Δ SSIM | target |")
        print("|---|---|---|---|---|---|---|---|---|")
        for key in sorted(k for k in g if k[0] == scene and k[1] != "full"):
            (gf, gs), (vf, vs) = g[key], v[key]
            df, ds = vf - gf, vs - gs
            ok = df >= -a.fpsnr_margin and ds >= -a.ssim_margin
            failures += not ok
            total += 1
            fmt = lambda x, p: "inf" if math.isinf(x) else f"{x:.{p}f}"
            print(f"| {key[1]} | {key[2]:g} | {fmt(gf, 2)} | {fmt(vf, 2)} | {df:+.2f} | {gs:.4f} | {vs:.4f} | {ds:+.4f} | {'met' if ok else '**missed**'} |")
        print()
    print(f"Target (visibility ≥ gbuffer − {a.fpsnr_margin:g} dB FPSNR and − {a.ssim_margin:g} SSIM): met at {total - failures} of {total} points.")


if __name__ == "__main__":
    main()
