#!/usr/bin/python3
"""Joins `foveal bench --gaze` runs that differ only in their logs into one directory
(docs/bench.md): OUT/gaze.csv, gaze_frames.csv and, from --gaze-video runs, gaze_video.csv (and gaze_video_frames.csv)
(rows concatenated), gaze.json (logs, rows and video rows joined; the settings, the
panel's luminance for JOD included, must agree). Chart it afterwards: tools/charts/gaze_charts.py OUT.

Usage: join_gaze_runs.py OUT RUN_DIR...
"""
import json
import os
import sys

import chart_files

SETTINGS = ("display", "size", "fps", "latency_ms", "start_s", "efr_ratio", "fx", "fy", "patch_deg", "patch_margin_db", "video_frames")


def light(summary):
    """The panel's luminance the JOD columns were scored with (None without JOD)."""
    j = summary.get("jod")
    return (j.get("peak_cd_m2"), j.get("black_cd_m2")) if j else None


def write(path, text):
    chart_files.write_text(path, text)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, runs = sys.argv[1], sys.argv[2:]
    summaries = []
    for r in runs:
        with open(os.path.join(r, "gaze.json")) as f:
            summaries.append(json.load(f))
    joined = summaries[0]
    for r, s in zip(runs[1:], summaries[1:]):
        for k in SETTINGS:
            if s.get(k) != joined.get(k):
                sys.exit(f"{r}/gaze.json: {k} is {s.get(k)!r}, {runs[0]} has {joined.get(k)!r}: not the same settings")
        if light(s) != light(joined):
            sys.exit(f"{r}/gaze.json: JOD's peak and black {light(s)!r}, {runs[0]} has {light(joined)!r}: not the same settings")
        if "video" in joined or "video" in s:
            joined["video"] = joined.get("video", []) + s.get("video", [])
        joined["logs"] += s["logs"]
        joined["rows"] += s["rows"]
        joined["wall_s"] += s["wall_s"]
        joined["peak_rss_mb"] = max(joined["peak_rss_mb"], s["peak_rss_mb"])
    joined["joined_from"] = runs
    os.makedirs(out, exist_ok=True)
    video = [os.path.exists(os.path.join(r, "gaze_video.csv")) for r in runs]
    if any(video) and not all(video):
        sys.exit(f"{runs[video.index(False)]}: no gaze_video.csv, {runs[video.index(True)]} has one (--gaze-video): not joinable")
    # gaze_video_frames.csv: from runs since temporal accumulation (all of them or none).
    frames = all(video) and all(os.path.exists(os.path.join(r, "gaze_video_frames.csv")) for r in runs)
    for name in ("gaze.csv", "gaze_frames.csv") + (("gaze_video.csv",) if all(video) else ()) + (("gaze_video_frames.csv",) if frames else ()):
        lines = []
        for i, r in enumerate(runs):
            with open(os.path.join(r, name)) as f:
                rows = f.read().splitlines()
            # Runs with and without JOD (--no-jod, or from before it) have other columns.
            if i > 0 and rows[:1] != lines[:1]:
                sys.exit(f"{r}/{name}: other columns than {runs[0]}'s (with and without JOD?): not joinable")
            lines += rows if i == 0 else rows[1:]
        write(os.path.join(out, name), "\n".join(lines) + "\n")
    write(os.path.join(out, "gaze.json"), json.dumps(joined, indent=2) + "\n")


if __name__ == "__main__":
    chart_files.run(main)
