#!/usr/bin/env python3
"""An independent NumPy computation of docs/quality.md's per-eye measures, for the tests.

Usage: quality_reference.py LOG [START_S END_S]. Reads the native gaze log with the csv
module (its own parser), takes each valid direction as float32 (what the log stores),
and prints JSON: per eye RMS-S2S, STD, BCEA (68 %), data loss and effective frequency,
following ETDQualitizer's formulas (Niehorster et al.)."""
import csv
import json
import math
import sys

import numpy as np


def read_log(path):
    with open(path, newline="") as f:
        lines = f.read().split("\n")
    rate = next(float(line.split("=", 1)[1]) for line in lines if line.startswith("# rate_hz="))
    lines = [line for line in lines if line and not line.startswith("#")]
    rows = list(csv.DictReader(lines))
    return rows, rate


def fick(rows, eye):
    n = len(rows)
    az = np.full(n, np.nan)
    el = np.full(n, np.nan)
    for i, r in enumerate(rows):
        if int(r[f"{eye}_valid"]) & 1:
            x, y, z = (np.float64(np.float32(r[f"{eye}_dir_{c}"])) for c in "xyz")
            az[i] = math.degrees(math.atan2(x, -z))
            el[i] = math.degrees(math.atan2(y, math.hypot(x, -z)))
    return az, el


def measures(az, el, duration, rate):
    ok = ~np.isnan(az)
    dx2, dy2 = np.diff(az) ** 2, np.diff(el) ** 2
    x, y = az[ok], el[ok]
    k = np.log(1.0 / (1.0 - 0.68))
    rho = np.corrcoef(x, y)[0, 1]
    n_valid = int(np.count_nonzero(ok))
    return {
        "valid": n_valid,
        "rms_s2s_deg": float(np.sqrt(np.nanmean(dx2 + dy2))),
        "std_deg": float(np.hypot(np.std(x, ddof=0), np.std(y, ddof=0))),
        "bcea_deg2": float(2 * k * np.pi * np.std(x, ddof=1) * np.std(y, ddof=1) * np.sqrt(1 - rho**2)),
        "data_loss_pct": float((1 - n_valid / (duration * rate)) * 100),
        "effective_frequency_hz": float(n_valid / duration),
    }


def main():
    rows, rate = read_log(sys.argv[1])
    t = np.array([int(r["t_ns"]) for r in rows], dtype=np.int64)
    t_s = (t - t[0]) / 1e9
    isi = float(np.median(np.diff(t))) / 1e9
    start, end = 0.0, float(t_s[-1] + isi)
    if len(sys.argv) > 3:
        start, end = max(start, float(sys.argv[2])), min(end, float(sys.argv[3]))
    keep = (t_s >= start) & (t_s < end)
    rows = [r for r, k in zip(rows, keep) if k]
    out = {"duration_s": end - start}
    for eye in ("left", "right"):
        az, el = fick(rows, eye)
        out[eye] = measures(az, el, end - start, rate)
    json.dump(out, sys.stdout, indent=1)


main()
