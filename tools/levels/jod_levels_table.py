#!/usr/bin/python3
"""Builds a display model's JOD levels table (docs/methods.md, "Levels chosen by
perception") from `foveal bench --gaze` runs made for it: one run per RMFR f (--fx F --fy F),
each over the same σ grid with --efr-ratio 1 (both eyes at σ), methods rmfr and fixed.
Each cell is the mean over the runs' scored frames and both eyes of each eye's JOD at its
true gaze (gaze_frames.csv: jod_left, jod_right); rmfr rows with gaze "filtered" (tracked,
as foveald renders) fill the table, fixed rows go to reference.fixed_jod for comparison.

Usage: jod_levels_table.py OUT.levels.json RUN_DIR... [--note TEXT]
"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "charts"))
import chart_files  # noqa: E402


def fail(msg):
    sys.exit(f"jod_levels_table: {msg}")


def read_run(d):
    try:
        with open(os.path.join(d, "gaze.json")) as f:
            info = json.load(f)
        with open(os.path.join(d, "gaze_frames.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
    except (OSError, ValueError) as e:
        fail(f"{d}: {e}")
    if not rows or "jod_left" not in rows[0]:
        fail(f"{d}: gaze_frames.csv has no JOD columns (run without --no-jod)")
    if abs(info.get("efr_ratio", 0) - 1) > 1e-9:
        fail(f"{d}: made with --efr-ratio {info.get('efr_ratio')}; the table needs both eyes at one level (--efr-ratio 1)")
    if abs(info["fx"] - info["fy"]) > 1e-9:
        fail(f"{d}: f_x {info['fx']} and f_y {info['fy']} differ; the table has one f")
    return info, rows


def main(argv):
    note = ""
    if "--note" in argv:
        i = argv.index("--note")
        note = argv[i + 1]
        argv = argv[:i] + argv[i + 2:]
    if len(argv) < 2:
        fail(__doc__.strip().splitlines()[-1])
    out, runs = argv[0], argv[1:]
    cells = {}  # (method, f, sigma) -> list of eye JODs
    display, scenes, logs, frames = None, set(), set(), set()
    for d in runs:
        info, rows = read_run(d)
        if display and info["display"] != display:
            fail(f"{d}: display {info['display']}, the others {display}")
        display = info["display"]
        f = round(info["fx"], 6)
        for r in rows:
            method = {("rmfr", "filtered"): "rmfr", ("fixed", "none"): "fixed"}.get((r["method"], r["gaze"]))
            if not method:
                continue
            key = (method, f, round(float(r["sigma_d"]), 6))
            for eye in ("jod_left", "jod_right"):
                v = float(r[eye])
                if math.isfinite(v):
                    cells.setdefault(key, []).append(v)
            scenes.add(r["scene"]), logs.add(r["log"]), frames.add((r["scene"], r["log"], r["frame"]))
    fs = sorted({k[1] for k in cells if k[0] == "rmfr"})
    sigmas = sorted({k[2] for k in cells if k[0] == "rmfr"})
    if not fs or not sigmas:
        fail("no tracked rmfr rows in the runs")

    def grid(method):
        table = []
        for f in fs:
            row = []
            for s in sigmas:
                v = cells.get((method, f, s))
                if not v:
                    if method == "rmfr":
                        fail(f"no rmfr rows at f {f}, sigma {s}: every run needs the same --sigmas")
                    row.append(None)
                    continue
                row.append(round(min(10.0, sum(v) / len(v)), 4))
            table.append(row)
        return table

    doc = {
        "format": "foveal-jod-levels v1",
        "display": display,
        "sigmas": sigmas,
        "f": fs,
        "jod": grid("rmfr"),
        "reference": {
            "statistic": "mean over the scored frames and both eyes of each eye's JOD at its true gaze (FovVideoVDP, foveal::perception)",
            "method": "RMFR, fovea tracked as foveald renders it (FilterConfig defaults, one frame of latency)",
            "scenes": sorted(scenes), "logs": sorted(logs), "frames": len(frames), "runs": [os.path.basename(os.path.normpath(d)) for d in runs],
            "fixed_jod": grid("fixed"),
            "note": note,
        },
    }
    chart_files.write_text(out, json.dumps(doc, indent=1) + "\n")
    print(f"jod_levels_table: {out}: {len(fs)} f x {len(sigmas)} sigma over {len(frames)} frames ({', '.join(sorted(scenes))})")


if __name__ == "__main__":
    chart_files.run(lambda: main(sys.argv[1:]))
