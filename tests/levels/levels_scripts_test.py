#!/usr/bin/env python3
"""The scripts that turn `foveal bench --gaze` runs into levels and answers, on small
hand-made runs whose answers are known: tools/levels/jod_levels_table.py (each eye at
its own level, f runs on other grids interpolated, and a table foveal::levels reads:
`foveal profile show` chooses from it), tools/levels/tracking_pays.py and
tools/charts/gaze_jod_tables.py (the cost to hold a JOD, the eccentricity bands).

Usage: levels_scripts_test.py SOURCE_DIR FOVEAL_BINARY. Exit 0 passed, 1 failed.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
src, foveal = sys.argv[1], sys.argv[2]
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


FRAMES = ["scene", "log", "frame", "method", "gaze", "sigma_d", "jod_left", "jod_right", "jod", "true_ecc_deg"]
GAZE = ["scene", "log", "display", "method", "gaze", "sigma_d", "cost", "frames", "fpsnr_mean", "jod_mean"]


def run_dir(root, name, fx, efr, frames, gaze_rows=(), **extra):
    d = os.path.join(root, name)
    os.makedirs(d)
    with open(os.path.join(d, "gaze.json"), "w") as f:
        json.dump({"display": "htc_vive_pro_eye", "fx": fx, "fy": fx, "efr_ratio": efr, **extra}, f)
    for file, header, rows in (("gaze_frames.csv", FRAMES, frames), ("gaze.csv", GAZE, gaze_rows)):
        with open(os.path.join(d, file), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(header)
            w.writerows(rows)
    return d


def py(script, *args):
    return subprocess.run([sys.executable, os.path.join(src, script), *args], capture_output=True, text=True)


with tempfile.TemporaryDirectory() as tmp:
    # f 0.2, both eyes at σ (ratio 1): JOD(2) = 9.6, JOD(4) = 9.0 (the left eye 0.1 lower).
    a = run_dir(tmp, "a", 0.2, 1.0, [("s", "l", 1, "rmfr", "filtered", 2, 9.5, 9.7, 0, 15), ("s", "l", 1, "rmfr", "filtered", 4, 8.9, 9.1, 0, 15),
                                     ("s", "l", 1, "fixed", "none", 2, 9.5, 9.5, 0, 15), ("x", "l", 1, "rmfr", "filtered", 2, 1, 1, 0, 15)])
    # f 0.4, ratio 1.5: the right eye at σ_d 2 (9.8), the left at σ 3 (9.5).
    b = run_dir(tmp, "b", 0.4, 1.5, [("s", "l", 1, "rmfr", "filtered", 2, 9.5, 9.8, 0, 5)])
    table = os.path.join(tmp, "m.levels.json")
    r = py("tools/levels/jod_levels_table.py", table, a, b, "--scenes", "s")
    check(r.returncode == 0, "jod_levels_table.py runs: " + r.stderr.strip())
    t = json.load(open(table))
    check(t["sigmas"] == [2.0, 3.0], f"one grid up to the smallest f's largest level: {t['sigmas']}")
    check(t["f"] == [0.2, 0.4], f"the runs' f: {t['f']}")
    check(abs(t["jod"][0][0] - 9.6) < 1e-9 and abs(t["jod"][0][1] - 9.3) < 1e-9, f"f 0.2: both eyes' mean, 3 between 2 and 4: {t['jod'][0]}")
    check(abs(t["jod"][1][0] - 9.8) < 1e-9 and abs(t["jod"][1][1] - 9.5) < 1e-9, f"f 0.4: each eye at its own level: {t['jod'][1]}")
    check(t["reference"]["scenes"] == ["s"], "--scenes keeps the reference set only")
    check(t["reference"]["fixed_jod"][0][0] == 9.5, "fixed rows beside the table")
    # The C++ side reads what the script writes: foveal profile show chooses from it.
    with open(os.path.join(src, "data/display/htc_vive_pro_eye.json")) as f:
        open(os.path.join(tmp, "m.json"), "w").write(f.read())
    env = dict(os.environ, XDG_CONFIG_HOME=os.path.join(tmp, "cfg"))
    for args in (["create", "p"], ["set", "p", "display_model", os.path.join(tmp, "m.json")], ["set", "p", "quality", "jod:9.5"]):
        subprocess.run([foveal, "profile", *args], env=env, capture_output=True, check=True)
    shown = json.loads(subprocess.run([foveal, "profile", "show", "p", "--json"], env=env, capture_output=True, text=True).stdout)
    check(abs(shown["levels"]["sigma_d"] - 3.0) < 1e-9 and shown["levels"]["f_x"] == 0.4, f"foveal chooses from the table: {shown['levels']}")

    # --method inset: one run per inner extent (gaze.json's inset_deg), inset rows only.
    e1 = run_dir(tmp, "e1", 0.3, 1.0, [("s", "l", 1, "inset", "filtered", 2, 9.4, 9.6, 0, 15), ("s", "l", 1, "inset", "filtered", 4, 9.0, 9.0, 0, 15),
                                       ("s", "l", 1, "rmfr", "filtered", 2, 1, 1, 0, 15), ("s", "l", 1, "inset-fixed", "none", 2, 9.3, 9.3, 0, 15)],
                 inset_deg=10)
    e2 = run_dir(tmp, "e2", 0.3, 1.0, [("s", "l", 1, "inset", "filtered", 2, 9.7, 9.9, 0, 15), ("s", "l", 1, "inset", "filtered", 4, 9.5, 9.5, 0, 15)],
                 inset_deg=20)
    inset = os.path.join(tmp, "m.inset-levels.json")
    r = py("tools/levels/jod_levels_table.py", inset, e2, e1, "--method", "inset")
    check(r.returncode == 0, "jod_levels_table.py --method inset runs: " + r.stderr.strip())
    t = json.load(open(inset))
    check(t["format"] == "foveal-jod-inset-levels v1" and t["extents_deg"] == [10, 20] and t["sigmas"] == [2.0, 4.0],
          f"an inset table over the runs' extents: {t.get('extents_deg')} x {t.get('sigmas')}")
    check(t["jod"] == [[9.5, 9.0], [9.8, 9.5]], f"inset rows only, both eyes' mean: {t['jod']}")
    check(t["reference"]["fixed_jod"][0][0] == 9.3, "inset-fixed rows beside the table")
    r = py("tools/levels/jod_levels_table.py", inset, a, "--method", "inset")
    check(r.returncode != 0 and "--inset-deg" in r.stderr, "a run without --inset-deg is refused: " + r.stderr.strip())

    out = os.path.join(tmp, "pays.md")
    r = py("tools/levels/tracking_pays.py", out, a, "--scenes", "s")
    text = open(out).read() if r.returncode == 0 else r.stderr
    check("JOD ≥ 9.5: cheapest tracked setting f 0.2, σ 2" in text and "best fixed at σ 2: 9.50" in text, "tracking_pays: " + text[-300:])

    # gaze_jod_tables: rmfr 9.6 at cost 0.25, 9.0 at 0.11 -> 9.5 at 0.227; fixed misses 9.5 at the densest level.
    rows = [("s", "l", "d", "rmfr", "filtered", 2, 0.25, 1, 30, 9.6), ("s", "l", "d", "rmfr", "filtered", 3, 0.11, 1, 28, 9.0),
            ("s", "l", "d", "fixed", "none", 2, 0.25, 1, 29, 9.4), ("s", "l", "d", "fixed", "none", 3, 0.11, 1, 27, 8.9)]
    frames = [("s", "l", 1, "rmfr", "filtered", 2, 0, 0, 9.6, 25), ("s", "l", 1, "fixed", "none", 2, 0, 0, 9.4, 25)]
    c = run_dir(tmp, "c", 0.3, 1.5, frames, rows)
    out = os.path.join(tmp, "jod.md")
    r = py("tools/charts/gaze_jod_tables.py", out, c)
    text = open(out).read() if r.returncode == 0 else r.stderr
    check("| d | s | 0.227 | > 0.25 |" in text, "the cost to hold 9.5, and '>' where the densest level misses")
    check("| d | s | 2 | – | – | +0.20 (1) |" in text, "tracked minus fixed in the 20-30 degree band")

sys.exit(1 if failures else 0)
