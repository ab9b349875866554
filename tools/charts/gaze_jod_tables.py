#!/usr/bin/python3
"""What eye tracking buys, in JOD (docs/results/gaze/README.md): tables of one or more
`foveal bench --gaze` runs (with JOD columns) into OUT.md; each run's gaze_table.md
(gaze_charts.py) has the figures at equal cost.

1. The cost each method needs to hold JOD >= 9.5 and >= 9.0 (JOD: the mean over the
   scored frames of both eyes' JOD at the true gaze): JOD against the shaded share,
   linear between the levels run; "> c" where even the densest level run misses,
   "<= c" where the sparsest holds it (the grid does not tell more).
2. By eccentricity of the true gaze from the optical centre (gaze_frames.csv's
   true_ecc_deg): tracked RMFR+EFR minus fixed foveation, JOD, per 10-degree band.

Usage: gaze_jod_tables.py OUT.md RUN_DIR...
"""
import csv
import math
import os
import sys

import chart_files

ORDER = ["oracle", "rmfr", "fixed", "uniform", "hyperbolic", "kfr", "linear", "inset", "inset-fixed"]
NAMES = {"oracle": "perfect tracking", "rmfr": "RMFR+EFR, tracked", "fixed": "fixed", "uniform": "uniform",
         "hyperbolic": "hyperbolic, tracked", "kfr": "KFR, tracked", "linear": "linear, tracked",
         "inset": "inset, tracked", "inset-fixed": "inset, fixed"}
THRESHOLDS = (9.5, 9.0)


def num(v):
    try:
        return float(v)
    except ValueError:
        return math.nan


def series(r):
    return "oracle" if r["gaze"] == "true" else r["method"]


def read(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"gaze_jod_tables: {path}: {e.strerror}")


def mean(v):
    v = [x for x in v if math.isfinite(x)]
    return sum(v) / len(v) if v else math.nan


def crossing(points, t):
    """The share at which JOD falls to t on (cost, jod) points, cheapest first."""
    pts = sorted(points, reverse=True)  # densest first
    if not pts:
        return "n/a"
    if pts[0][1] < t:
        return f"> {pts[0][0]:.2f}"
    for (c0, j0), (c1, j1) in zip(pts, pts[1:]):
        if j1 < t:
            return f"{c0 + (c1 - c0) * (j0 - t) / (j0 - j1):.3f}"
    return f"<= {pts[-1][0]:.2f}"


def main(argv):
    if len(argv) < 2:
        sys.exit("usage: gaze_jod_tables.py OUT.md RUN_DIR...")
    out, runs = argv[0], argv[1:]
    rows, frames = [], []
    for d in runs:
        run_rows = read(os.path.join(d, "gaze.csv"))
        display = run_rows[0]["display"] if run_rows else "?"
        rows += run_rows
        frames += [dict(f, display=display) for f in read(os.path.join(d, "gaze_frames.csv"))]
    if not rows or "jod_mean" not in rows[0]:
        sys.exit("gaze_jod_tables: the runs have no JOD columns (made with --no-jod?)")
    # (display, scene, series, sigma) -> frame-weighted means over logs
    acc = {}
    for r in rows:
        n = int(r["frames"])
        a = acc.setdefault((r["display"], r["scene"], series(r), num(r["sigma_d"])), {"n": 0, "jod": 0.0, "cost": num(r["cost"])})
        if n and math.isfinite(num(r["jod_mean"])):
            a["n"] += n
            a["jod"] += n * num(r["jod_mean"])
    for a in acc.values():
        a["jod"] = a["jod"] / a["n"] if a["n"] else math.nan
    groups = sorted({(k[0], k[1]) for k in acc})
    present = [s for s in ORDER if any(k[2] == s for k in acc)]
    lines = ["# What eye tracking buys, in JOD", "",
             f"Runs: {', '.join(os.path.basename(os.path.normpath(d)) for d in runs)}. JOD: mean over the scored frames of "
             "both eyes' FovVideoVDP JOD at the true gaze (10 = indistinguishable from full rendering).", ""]

    for t in THRESHOLDS:
        lines += [f"## Shaded share needed to hold JOD ≥ {t}", "", "| display | scene | " + " | ".join(NAMES[s] for s in present) + " |",
                  "|" + "---|" * (2 + len(present))]
        for disp, scene in groups:
            cells = []
            for s in present:
                pts = [(a["cost"], a["jod"]) for k, a in acc.items() if k[:3] == (disp, scene, s) and math.isfinite(a["jod"])]
                cells.append(crossing(pts, t))
            lines.append(f"| {disp} | {scene} | " + " | ".join(cells) + " |")
        lines += [""]

    if frames and "true_ecc_deg" in frames[0]:
        lines += ["## Tracked minus fixed, by the true gaze's eccentricity", "",
                  "JOD of RMFR+EFR tracked minus fixed foveation on the same frames, mean per band (frames in the band).", "",
                  "| display | scene | σ_d | 0-10° | 10-20° | 20-30° |", "|---|---|---|---|---|---|"]
        by = {}
        for f in frames:
            if series(f) not in ("rmfr", "fixed"):
                continue
            key = (f["display"], f["scene"], num(f["sigma_d"]), f["log"], f["frame"])
            by.setdefault(key, {})[series(f)] = (num(f["jod"]), num(f["true_ecc_deg"]))
        bands = {}
        for (disp, scene, sigma, _, _), v in by.items():
            if "rmfr" in v and "fixed" in v:
                b = min(2, int(v["rmfr"][1] // 10))
                bands.setdefault((disp, scene, sigma), [[], [], []])[b].append(v["rmfr"][0] - v["fixed"][0])
        for (disp, scene, sigma), bs in sorted(bands.items()):
            cells = [f"{mean(b):+.2f} ({len(b)})" if b else "–" for b in bs]
            lines.append(f"| {disp} | {scene} | {sigma:g} | " + " | ".join(cells) + " |")
        lines += [""]
    chart_files.write_text(out, "\n".join(lines))
    print(f"gaze_jod_tables: {out}")


if __name__ == "__main__":
    chart_files.run(lambda: main(sys.argv[1:]))
