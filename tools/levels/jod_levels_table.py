#!/usr/bin/python3
"""Builds a display model's JOD levels table (docs/methods.md, "Levels chosen by
perception") from `foveal bench --gaze` runs made for it (with JOD, f_x = f_y). Each eye
is scored alone at its true gaze, so each counts at its own level: the dominant (right)
eye at σ_d, the other at σ_d · the run's --efr-ratio. A cell (p, σ) is the mean of every
such eye JOD at that parameter p and σ over the runs' scored frames; tracked rows (gaze
"filtered", as foveald renders) fill the table, fixed rows go to reference.fixed_jod
beside it. Every p must have every σ of the table.

  --method rmfr (default): methods rmfr and fixed, p = the run's RMFR f, one run per f;
    the table NAME.levels.json ("foveal-jod-levels v1").
  --method inset: methods inset and inset-fixed, p = the run's --inset-deg (the inner
    view's half-extent, degrees), one run per extent; the table NAME.inset-levels.json
    ("foveal-jod-inset-levels v1", docs/openxr.md "Sizes").

Usage: jod_levels_table.py OUT.json RUN_DIR... [--method rmfr|inset] [--scenes A,B] [--note TEXT]
  --scenes: only these scenes' rows (the reference set); default all.
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
    if abs(info["fx"] - info["fy"]) > 1e-9:
        fail(f"{d}: f_x {info['fx']} and f_y {info['fy']} differ; the table has one f")
    return info, rows


# Per method: the rows that fill the table and the fixed reference, the run's parameter
# and the table's keys.
METHODS = {
    "rmfr": {"rows": {("rmfr", "filtered"): "tracked", ("fixed", "none"): "fixed"}, "format": "foveal-jod-levels v1",
             "grid_key": "f", "what": "RMFR, fovea tracked as foveald renders it (FilterConfig defaults, one frame of latency)"},
    "inset": {"rows": {("inset", "filtered"): "tracked", ("inset-fixed", "none"): "fixed"}, "format": "foveal-jod-inset-levels v1",
              "grid_key": "extents_deg",
              "what": "the inset (quad views): outer view at 1/σ per axis, inner view at full density over ±extent degrees "
                      "(tangent half-extent tan(extent) per axis), 3 degree blend band, centred on the gaze tracked as foveald "
                      "renders it (FilterConfig defaults, one frame of latency)"},
}


def run_parameter(method, info, d):
    if method == "rmfr":
        return info["fx"]
    deg = info.get("inset_deg")
    if not isinstance(deg, (int, float)) or not deg > 0:
        fail(f"{d}: gaze.json has no inset_deg > 0: run foveal bench with --inset-deg DEG (the inner view's half-extent)")
    return deg


def main(argv):
    opts = {"--note": "", "--scenes": "", "--method": "rmfr"}
    for k in opts:
        if k in argv:
            i = argv.index(k)
            if i + 1 >= len(argv):
                fail(f"{k} needs a value")
            opts[k] = argv[i + 1]
            argv = argv[:i] + argv[i + 2:]
    note, only = opts["--note"], set(filter(None, opts["--scenes"].split(",")))
    if opts["--method"] not in METHODS:
        fail(f"--method: expected rmfr or inset, got {opts['--method']!r}")
    spec = METHODS[opts["--method"]]
    if len(argv) < 2:
        fail(__doc__.strip().splitlines()[-1])
    out, runs = argv[0], argv[1:]
    cells = {}  # ("tracked" | "fixed", p, sigma) -> list of eye JODs
    display, scenes, logs, frames = None, set(), set(), set()
    for d in runs:
        info, rows = read_run(d)
        if display and info["display"] != display:
            fail(f"{d}: display {info['display']}, the others {display}")
        display = info["display"]
        f, ratio = round(run_parameter(opts["--method"], info, d), 6), info["efr_ratio"]
        for r in rows:
            method = spec["rows"].get((r["method"], r["gaze"]))
            if not method or (only and r["scene"] not in only):
                continue
            sigma = float(r["sigma_d"])
            for eye, level in (("jod_right", sigma), ("jod_left", sigma * ratio)):  # the bench's dominant eye is the right
                v = float(r[eye])
                if math.isfinite(v):
                    cells.setdefault((method, f, round(level, 6)), []).append(v)
            scenes.add(r["scene"]), logs.add(r["log"]), frames.add((r["scene"], r["log"], r["frame"]))
    fs = sorted({k[1] for k in cells if k[0] == "tracked"})
    if not fs:
        fail(f"no tracked {opts['--method']} rows in the runs")
    own = {f: sorted(k[2] for k in cells if k[0] == "tracked" and k[1] == f) for f in fs}
    # One σ grid for every f: every level some f was measured at, up to the smallest of
    # the f's largest levels; each f's row is linear in σ between its own levels (and
    # JOD 10 at σ 1, full rendering), so no value is extrapolated.
    top = min(v[-1] for v in own.values())
    sigmas = sorted({s for v in own.values() for s in v if s <= top})

    def curve(method, f, sigma):
        pts = [(1.0, 10.0)] + [(s, sum(v) / len(v)) for (m, ff, s), v in sorted(cells.items()) if m == method and ff == f]
        for (s0, j0), (s1, j1) in zip(pts, pts[1:]):
            if s0 <= sigma <= s1:
                return j0 + (j1 - j0) * (sigma - s0) / (s1 - s0)
        return None

    def grid(method):
        return [[None if (v := curve(method, f, s)) is None else round(min(10.0, v), 4) for s in sigmas] for f in fs]

    doc = {
        "format": spec["format"],
        "display": display,
        "sigmas": sigmas,
        spec["grid_key"]: fs,
        "jod": grid("tracked"),
        "reference": {
            "statistic": "mean over the scored frames and both eyes of each eye's JOD at its true gaze (FovVideoVDP, foveal::perception)",
            "method": spec["what"],
            "scenes": sorted(scenes), "logs": sorted(logs), "frames": len(frames), "runs": [os.path.basename(os.path.normpath(d)) for d in runs],
            "measured_sigmas": {str(f): v for f, v in own.items()},
            "fixed_jod": grid("fixed"),
            "note": note,
        },
    }
    chart_files.write_text(out, json.dumps(doc, indent=1) + "\n")
    print(f"jod_levels_table: {out}: {len(fs)} {spec['grid_key']} x {len(sigmas)} sigma over {len(frames)} frames ({', '.join(sorted(scenes))})")


if __name__ == "__main__":
    chart_files.run(lambda: main(sys.argv[1:]))
