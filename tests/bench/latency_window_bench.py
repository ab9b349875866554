#!/usr/bin/env python3
"""Gaze to photon in a window on Xvfb (docs/latency.md, "The benchmark"): foveald --window
at 90 Hz with a pattern scene small enough for llvmpipe to keep up, on the bundled
recording, once per pacing (asap, jit) and latch (late, early), in one run; prints the
breakdown (p50 / p95 of gaze-to-photon and its four parts) as a Markdown table.

Xvfb has no vsync: a swap returns at once, so "shown" is the swap's return (stated in
each summary as shown_clock "swap") and the refresh grid is --fps's. A benchmark: it
prints figures, it asserts nothing. Starts and stops its own Xvfb (xvfb-run).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

PARTS = ["tracker_to_host_ms", "host_to_latch_ms", "latch_to_gpu_ms", "gpu_to_shown_ms"]


def pct(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, int(round(q * (len(s) - 1))))] if s else float("nan")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--foveald", required=True)
    p.add_argument("--frames", type=int, default=600)
    p.add_argument("--fps", type=float, default=90)
    p.add_argument("--size", default="320x180")
    p.add_argument("--scene", default="pattern:checker")
    a = p.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for pacing in ("asap", "jit"):
            for latch in ("late", "early"):
                out = os.path.join(tmp, f"{pacing}-{latch}")
                cmd = ["xvfb-run", "-a", "-s", "-screen 0 1280x720x24", a.foveald, "--window", "--scene", a.scene,
                       "--size", a.size, "--fps", str(a.fps), "--frames", str(a.frames), "--loop", "--end", "30",
                       "--pacing", pacing, "--latch", latch, "--no-control", "--no-shm", "-q", "--out", out]
                env = dict(os.environ, XDG_CONFIG_HOME=os.path.join(tmp, "config"))
                r = subprocess.run(cmd, env=env, capture_output=True, text=True)
                if r.returncode != 0:
                    print(f"latency_window_bench: {pacing}/{latch}: foveald exit {r.returncode}: {r.stderr[-400:]}")
                    return 1
                with open(os.path.join(out, "frames.csv")) as f:
                    frames = [x for x in csv.DictReader(f) if x["gaze_to_photon_ms"]]
                with open(os.path.join(out, "summary.json")) as f:
                    summary = json.load(f)["render"]
                rows.append((pacing, latch, frames, summary))
    print(f"foveald --window on Xvfb, {a.scene} at {a.size}, {a.fps:g} Hz grid, {a.frames} frames per run, "
          f"shown clock: {rows[0][3]['gaze_to_photon']['shown_clock']}")
    cols = ["gaze_to_photon_ms"] + PARTS
    print("| pacing | latch | frames | missed | margin ms | " + " | ".join(c[:-3] + " p50 / p95" for c in cols) + " |")
    print("|---|---|---|---|---|" + "---|" * len(cols))
    for pacing, latch, frames, summary in rows:
        margin = summary["pacing"].get("margin_ms")
        cells = [f"{pct([float(x[c]) for x in frames], 0.5):.2f} / {pct([float(x[c]) for x in frames], 0.95):.2f}"
                 for c in cols]
        print(f"| {pacing} | {latch} | {len(frames)} | {summary['pacing']['misses']} | "
              f"{'-' if margin is None else f'{margin:.2f}'} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
