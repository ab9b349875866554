#!/usr/bin/env python3
"""The JOD panels of the bench charts (docs/bench.md): tools/charts/bench_charts.py draws
jod_cost.png (JOD against cost, per method) when bench.csv has JOD columns and not
otherwise; tools/charts/gaze_charts.py adds a JOD row to gaze.png and JOD to
gaze_table.md when gaze.csv has jod_mean/jod_p5/jod_min, averaged over the logs. Each
figure is caught before it is saved and its lines' data compared with the CSV's.

Usage: charts_test.py SOURCE_DIR. Exit 0 passed, 1 failed, 77 skipped (no matplotlib).
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


BENCH = ["scene", "method", "sigma", "shaded_samples", "cost", "gpu_ms", "cpu_ms", "shadow_ms", "gbuffer_ms", "mapping_ms",
         "lighting_ms", "inverse_ms", "psnr_db", "ssim", "fpsnr_db"]
# scene, method, sigma, cost, fpsnr, jod
BENCH_ROWS = [("s", "full", 1, 1, "inf", 10), ("s", "rmfr", 1.4, 0.51, 34, 9.7), ("s", "rmfr", 2.6, 0.15, 30, 9.1),
              ("s", "uniform", 1.4, 0.51, 33, 9.6), ("s", "uniform", 2.6, 0.15, 28, 8.8)]

GAZE = ["scene", "log", "display", "method", "gaze", "sigma_d", "sigma_nd", "shaded_samples", "cost", "gpu_ms", "cpu_ms",
        "frames", "blink_frames", "fpsnr_mean", "fpsnr_p5", "fpsnr_min", "ssim_mean", "ssim_p5", "ssim_min", "psnr_mean",
        "patch_psnr_mean", "patch_psnr_p5", "patch_exceed_share", "fovea_error_deg_mean"]
# log, method, gaze, sigma, cost, jod_mean (jod_p5 = jod_mean - 0.3)
GAZE_ROWS = [("a", "rmfr", "true", 2, 0.25, 9.8), ("a", "rmfr", "filtered", 2, 0.25, 9.6), ("a", "fixed", "none", 2, 0.25, 9.3),
             ("a", "uniform", "none", 2, 0.25, 9.0), ("b", "rmfr", "true", 2, 0.25, 9.6), ("b", "rmfr", "filtered", 2, 0.25, 9.4),
             ("b", "fixed", "none", 2, 0.25, 9.3), ("b", "uniform", "none", 2, 0.25, 9.2),
             ("a", "rmfr", "filtered", 3, 0.11, 9.0), ("a", "fixed", "none", 3, 0.11, 8.6), ("a", "uniform", "none", 3, 0.11, 8.1),
             ("b", "rmfr", "filtered", 3, 0.11, 8.8), ("b", "fixed", "none", 3, 0.11, 8.4), ("b", "uniform", "none", 3, 0.11, 8.3),
             ("a", "rmfr", "true", 3, 0.11, 9.2), ("b", "rmfr", "true", 3, 0.11, 9.0)]


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


def bench_csv(path, jod):
    rows = [[s, m, sg, 100, c, 2, 2, 0, 0, 0, 0, 0, fp, 0.9, fp] + ([j - 0.05, j + 0.05, j] if jod else [])
            for s, m, sg, c, fp, j in BENCH_ROWS]
    write_csv(path, BENCH + (["jod_left", "jod_right", "jod"] if jod else []), rows)


def gaze_csv(path, jod):
    rows = [["sc", log, "vive", m, g, sg, sg * 1.5, 100, c, 2, 2, 4, 0, 30 + 2 * j, 29 + 2 * j, 28, 0.9, 0.9, 0.9, 30, 35, 34, 0.1, 1.0] +
            ([j, j - 0.3, j - 0.5] if jod else []) for log, m, g, sg, c, j in GAZE_ROWS]
    write_csv(path, GAZE + (["jod_mean", "jod_p5", "jod_min"] if jod else []), rows)


def png_height(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return int.from_bytes(head[20:24], "big") if head[:8] == b"\x89PNG\r\n\x1a\n" else -1


def caught_figures(module):
    """Replaces the module's save_figure: the figures it would save, by file name."""
    figs = {}
    module.chart_files.save_figure = lambda fig, path, **kw: figs.__setitem__(os.path.basename(path), fig)
    return figs


def line_data(ax):
    return {line.get_label(): (list(line.get_xdata()), list(line.get_ydata())) for line in ax.get_lines()}


def main():
    src = sys.argv[1]
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("skipped: this python3 has no matplotlib (python3-matplotlib), the charts cannot run")
        return 77
    charts = os.path.join(src, "tools", "charts")
    work = tempfile.mkdtemp(prefix="foveal-charts-test-")
    try:
        d = lambda *n: os.path.join(work, *n)  # noqa: E731
        # The scripts as bench runs them, on CSVs with and without JOD.
        for name, jod in (("jod", True), ("old", False)):
            os.makedirs(d("bench-" + name))
            bench_csv(d("bench-" + name, "bench.csv"), jod)
            r = subprocess.run(["/usr/bin/python3", os.path.join(charts, "bench_charts.py"), d("bench-" + name)],
                               capture_output=True, text=True, timeout=120)
            check(r.returncode == 0, f"bench_charts.py on a bench.csv {'with' if jod else 'without'} JOD: {r.stderr.strip()}")
            check(os.path.exists(d("bench-" + name, "jod_cost.png")) == jod,
                  f"jod_cost.png {'drawn' if jod else 'not drawn'} for a bench.csv {'with' if jod else 'without'} JOD")
            check(os.path.exists(d("bench-" + name, "quality_cost.png")), "quality_cost.png drawn as before")
            os.makedirs(d("gaze-" + name))
            gaze_csv(d("gaze-" + name, "gaze.csv"), jod)
            r = subprocess.run(["/usr/bin/python3", os.path.join(charts, "gaze_charts.py"), d("gaze-" + name)],
                               capture_output=True, text=True, timeout=120)
            check(r.returncode == 0, f"gaze_charts.py on a gaze.csv {'with' if jod else 'without'} JOD: {r.stderr.strip()}")
        h_jod, h_old = png_height(d("gaze-jod", "gaze.png")), png_height(d("gaze-old", "gaze.png"))
        check(h_jod > 0 and h_old > 0 and abs(h_jod / h_old - 1.5) < 0.01, f"gaze.png has a third row with JOD ({h_jod} px against {h_old})")
        table = open(d("gaze-jod", "gaze_table.md")).read()
        old_table = open(d("gaze-old", "gaze_table.md")).read()
        check("Δ JOD fixed" in table and "Δ JOD" not in old_table, "gaze_table.md has Δ JOD columns only with JOD")
        # σ 2: rmfr (9.6 + 9.4) / 2 = 9.5, fixed 9.3, uniform 9.1: +0.20 and +0.40 JOD after
        # FPSNR's +0.40 and +0.80 dB (FPSNR is 30 + 2·JOD here).
        line2 = next((l for l in table.splitlines() if l.startswith("| sc | 2 |")), "")
        check(" | +0.40 | +0.80 | +0.20 | +0.40 | " in line2 and "/ 9.50 |" in line2,
              f"gaze_table.md's σ 2 row: rmfr's JOD 9.50, Δ JOD +0.20 / +0.40 after Δ FPSNR ({line2})")

        # The figures themselves: the JOD panel plots the JOD columns against cost.
        sys.path.insert(0, charts)
        import bench_charts
        import gaze_charts
        figs = caught_figures(bench_charts)
        sys.argv = ["bench_charts.py", d("bench-jod")]
        bench_charts.main()
        ax = figs["jod_cost.png"].axes[0]
        lines = line_data(ax)
        check(lines.get("rmfr") == ([0.15, 0.51], [9.1, 9.7]) and lines.get("uniform") == ([0.15, 0.51], [8.8, 9.6]),
              f"jod_cost.png: each method's JOD against cost, levels in order ({lines})")
        check("JOD" in ax.get_ylabel(), f"jod_cost.png's y axis is JOD ({ax.get_ylabel()})")
        # rotation.csv and stability.csv with JOD: a JOD panel beside FPSNR, from the JOD column.
        write_csv(d("bench-jod", "rotation.csv"), ["angle_deg", "method", "sigma", "fpsnr_db", "psnr_db", "ssim", "jod_left", "jod_right", "jod"],
                  [[a, "rmfr", 2, 30 + a / 10, 30, 0.9, 9, 9, 9 - a / 100] for a in (0, 90, 180)])
        write_csv(d("bench-jod", "stability.csv"), ["scene", "path", "t", "fovea_x", "fovea_y", "method", "sigma", "patch_psnr_db", "fpsnr_db",
                                                     "jod_left", "jod_right", "jod"],
                  [["p", p, t, 0.5, 0.5, "uniform", 2, 30, 20 + t, 8, 8, 8 + t / 2] for p in ("diagonal", "vertical") for t in (0, 0.5, 1)])
        bench_charts.main()
        rot = figs["rotation.png"].axes
        check(len(rot) == 2 and line_data(rot[1]).get("rmfr") == ([0.0, 90.0, 180.0], [9.0, 8.1, 7.2]),
              f"rotation.png: a JOD panel from rotation.csv's jod ({[line_data(a) for a in rot]})")
        stab = figs["stability.png"].axes
        check(len(stab) == 6 and line_data(stab[4]).get("uniform") == ([0.0, 0.5, 1.0], [8.0, 8.25, 8.5]),
              f"stability.png: a JOD row from stability.csv's jod ({len(stab)} panels)")
        figs = caught_figures(gaze_charts)
        # A --gaze-video run's sequences: the video JOD per series, averaged over the logs.
        write_csv(d("gaze-jod", "gaze_video.csv"), ["scene", "log", "display", "method", "gaze", "sigma_d", "sigma_nd", "frames",
                                                     "blink_frames", "fps", "head_speed_deg_s", "jod_left", "jod_right", "jod"],
                  [["sc", log, "vive", m, g, sg, sg * 1.5, 6, 0, 90, 12, j - 0.8, j - 0.6, j - 0.7] for log, m, g, sg, c, j in GAZE_ROWS])
        for name in ("jod", "old"):
            sys.argv = ["gaze_charts.py", d("gaze-" + name)]
            gaze_charts.main()
            figs[name + ".png"] = figs.pop("gaze.png")
        axes = figs["jod.png"].axes
        check(len(axes) == 3 and len(figs["old.png"].axes) == 2, f"gaze chart: 3 panels with JOD, 2 without ({len(axes)})")
        check(not any("(video)" in line.get_label() for ax in figs["old.png"].axes for line in ax.get_lines()),
              "no video line without gaze_video.csv")
        lines = line_data(axes[2]) if len(axes) == 3 else {}
        mean = lambda *v: [sum(v) / len(v)]  # noqa: E731
        want = {"fixed foveation (no tracking) (mean)": ([0.11, 0.25], mean(8.6, 8.4) + mean(9.3, 9.3)),
                "RMFR+EFR, eye-tracked (mean)": ([0.11, 0.25], mean(9.0, 8.8) + mean(9.6, 9.4)),
                "RMFR+EFR, perfect tracking (fovea on the true gaze) (5th pct.)": ([0.11, 0.25], mean(8.9, 8.7) + mean(9.5, 9.3)),
                "uniform resolution (no tracking) (video)": ([0.11, 0.25], mean(8.1 - 0.7, 8.3 - 0.7) + mean(9.0 - 0.7, 9.2 - 0.7))}
        for label, (xs, ys) in want.items():
            got = lines.get(label)
            ok = got is not None and got[0] == xs and all(abs(a - b) < 1e-9 for a, b in zip(got[1], ys)) and len(got[1]) == len(ys)
            check(ok, f"gaze JOD panel: '{label}' is the mean over logs against cost ({got})")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
