#!/usr/bin/python3
"""Where eye tracking pays, with JOD as the judge (issue 28 item 5; docs/results/levels/):
from `foveal bench --gaze` runs of tracked RMFR and fixed foveation at several f and σ,
the mean JOD of each eye at its own level (σ_d for the bench's dominant right eye,
σ_d · --efr-ratio for the left), over all scored frames and over the off-centre ones
(true gaze at least --off DEG from the optical centre, default 10). Then, per target T:
the cheapest (largest σ) setting whose tracked off-centre JOD holds T, and the best
fixed foveation at that σ over every f run (fixed may pick its own f). Tracking is said
to pay only where fixed misses T and trails tracking by at least --margin JOD (default
0.1: differences below it are within what a few dozen frames can tell apart).

Usage: tracking_pays.py OUT.md RUN_DIR... [--scenes A,B] [--off DEG] [--margin JOD]
"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "charts"))
import chart_files  # noqa: E402

TARGETS = (9.5, 9.0)


def mean(v):
    return sum(v) / len(v) if v else math.nan


def main(argv):
    opts = {"--scenes": "", "--off": "10", "--margin": "0.1"}
    for k in list(opts):
        if k in argv:
            i = argv.index(k)
            opts[k] = argv[i + 1]
            argv = argv[:i] + argv[i + 2:]
    if len(argv) < 2:
        sys.exit("usage: tracking_pays.py OUT.md RUN_DIR... [--scenes A,B] [--off DEG] [--margin JOD]")
    only, off, margin = set(filter(None, opts["--scenes"].split(","))), float(opts["--off"]), float(opts["--margin"])
    cell = {}  # (method, f, sigma) -> {"all": [...], "off": [...]}
    display = None
    for d in argv[1:]:
        with open(os.path.join(d, "gaze.json")) as f:
            info = json.load(f)
        display = info["display"]
        with open(os.path.join(d, "gaze_frames.csv"), newline="") as f:
            for r in csv.DictReader(f):
                m = {("rmfr", "filtered"): "tracked", ("fixed", "none"): "fixed"}.get((r["method"], r["gaze"]))
                if not m or (only and r["scene"] not in only):
                    continue
                for eye, level in (("jod_right", float(r["sigma_d"])), ("jod_left", float(r["sigma_d"]) * info["efr_ratio"])):
                    c = cell.setdefault((m, round(info["fx"], 3), round(level, 3)), {"all": [], "off": []})
                    c["all"].append(float(r[eye]))
                    if float(r["true_ecc_deg"]) >= off:
                        c["off"].append(float(r[eye]))
    keys = sorted({(k[1], k[2]) for k in cell if k[0] == "tracked"})
    lines = [f"# Where tracking pays ({display})", "",
             f"Mean JOD of each eye at its own level; off-centre: true gaze ≥ {off:g}° from the optical centre.", "",
             "| f | σ | cost | tracked, all | tracked, off-centre | fixed, off-centre (same f) | tracked − fixed, off-centre | eyes scored (off-centre) |",
             "|---|---|---|---|---|---|---|---|"]
    for f, s in keys:
        t, x = cell[("tracked", f, s)], cell.get(("fixed", f, s), {"all": [], "off": []})
        lines.append(f"| {f:g} | {s:g} | {1 / s ** 2:.3f} | {mean(t['all']):.2f} | {mean(t['off']):.2f} | {mean(x['off']):.2f} | "
                     f"{mean(t['off']) - mean(x['off']):+.2f} | {len(t['all'])} ({len(t['off'])}) |")
    lines += [""]
    for target in TARGETS:
        held = [(s, f) for f, s in keys if mean(cell[("tracked", f, s)]["off"]) >= target]
        if not held:
            lines.append(f"- JOD ≥ {target}: no tracked setting of these runs holds it off-centre.")
            continue
        s, f = max(held)
        fixed = [(mean(c["off"]), ff) for (m, ff, ss), c in cell.items() if m == "fixed" and ss == s and c["off"]]
        if not fixed:
            lines.append(f"- JOD ≥ {target}: cheapest tracked setting f {f:g}, σ {s:g}; no fixed foveation was run at σ {s:g}.")
            continue
        best = max(fixed)
        gap = mean(cell[("tracked", f, s)]["off"]) - best[0]
        verdict = "tracking pays" if best[0] < target and gap >= margin else f"fixed matches it (within {margin:g} JOD or above T)"
        lines.append(f"- JOD ≥ {target}: cheapest tracked setting f {f:g}, σ {s:g} (cost {1 / s ** 2:.3f}): off-centre JOD "
                     f"{mean(cell[('tracked', f, s)]['off']):.2f}; best fixed at σ {s:g}: {best[0]:.2f} (f {best[1]}) — {verdict}.")
    chart_files.write_text(argv[0], "\n".join(lines) + "\n")
    print(f"tracking_pays: {argv[0]}")


if __name__ == "__main__":
    chart_files.run(lambda: main(sys.argv[1:]))
