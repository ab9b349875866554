"""Compares two `foveal bench` output directories row for row, timing left out.

Every table (*.csv) and the rows and auto_f lists of bench.json must hold the same rows
in the same order with the same values, except the timing columns: CSV columns and JSON
keys ending in `_ms` (GPU, CPU and per-pass milliseconds, the f search's cost) and
`cost_ratio` (a ratio of two timings). They measure the machine of the moment, not the
sweep; everything else (levels, shaded samples, cost, PSNR, SSIM, FPSNR, the automatic
and the best grid f) is a deterministic function of the sweep and compared exactly, as
text.
"""
import csv
import glob
import json
import os


def is_timing(key):
    return key.endswith("_ms") or key == "cost_ratio"


def strip_timing(value):
    if isinstance(value, dict):
        return {k: strip_timing(v) for k, v in value.items() if not is_timing(k)}
    if isinstance(value, list):
        return [strip_timing(v) for v in value]
    return value


def table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if not is_timing(name)]
    return [[row[i] for i in keep] for row in rows]


def differences(expected_dir, actual_dir):
    """Lists what differs (empty: the same rows); `expected_dir` is the single run."""
    out = []
    names = sorted(os.path.basename(p) for p in glob.glob(os.path.join(expected_dir, "*.csv")))
    got = sorted(os.path.basename(p) for p in glob.glob(os.path.join(actual_dir, "*.csv")))
    if names != got:
        out.append(f"tables: {names} expected, {got} found")
    for name in names:
        if name not in got:
            continue
        a, b = table(os.path.join(expected_dir, name)), table(os.path.join(actual_dir, name))
        if len(a) != len(b):
            out.append(f"{name}: {len(a) - 1} rows expected, {len(b) - 1} found")
        for i, (ra, rb) in enumerate(zip(a, b)):
            if ra != rb:
                out.append(f"{name} line {i + 1}: {ra} expected, {rb} found")
    # bench.json, or gaze.json for a --gaze sweep: its rows, and the settings that shape them.
    name = "bench.json" if os.path.exists(os.path.join(expected_dir, "bench.json")) else "gaze.json"
    with open(os.path.join(expected_dir, name)) as f:
        ja = json.load(f)
    if not os.path.exists(os.path.join(actual_dir, name)):
        return out + [f"{name}: missing in {actual_dir}"]
    with open(os.path.join(actual_dir, name)) as f:
        jb = json.load(f)
    for key in ("rows", "auto_f", "size", "frames", "fovea", "display", "ppd", "logs", "video", "video_frames"):
        if strip_timing(ja.get(key)) != strip_timing(jb.get(key)):
            out.append(f"{name} {key}: {strip_timing(ja.get(key))} expected, {strip_timing(jb.get(key))} found")
    return out


def timing_columns(path):
    """The columns of a table left out of the comparison (the test states them)."""
    with open(path, newline="") as f:
        header = next(csv.reader(f))
    return [name for name in header if is_timing(name)]
