#!/usr/bin/env python3
"""Charts a paper could print (issue 39 item 7), on small real-shaped inputs:
- pareto.png / quality_cost.png: the y range is the methods' points (the full
  reference's ∞ dB is a marker on the top edge, not a point at 60 dB); every method point
  carries its σ (σ_d/σ_nd with EFR) and no two labels overlap; the footer holds the run's
  settings from bench.json (frames, warm-up, pipeline, size, display, renderer) and says
  which are not recorded.
- filter_chart.png: the raw series is labelled "no filter" (it read "filter"), no two point
  labels overlap, the log axes read as plain numbers with units, and the real panel
  charts a native log (source "log") with no bar where a setting had no fixation.
- log_chart.py: the bundled gaze log and a fovea trace drawn over time; a malformed row
  refused with exit 2 naming the file, the line and the column, and no PNG written.

Usage: chart_readability_test.py SOURCE_DIR. Exit 0 passed, 1 failed, 77 skipped (no matplotlib).
"""
import csv
import os
import shutil
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


def caught(module):
    figs = {}
    module.chart_files.save_figure = lambda fig, path, **kw: figs.__setitem__(os.path.basename(path), fig)
    return figs


def overlaps(boxes):
    """Pairs of boxes that share area."""
    bad = []
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            if min(a.x1, b.x1) - max(a.x0, b.x0) > 0.5 and min(a.y1, b.y1) - max(a.y0, b.y0) > 0.5:
                bad.append((a, b))
    return bad


BENCH = ["scene", "method", "sigma", "shaded_samples", "cost", "gpu_ms", "cpu_ms", "shadow_ms", "gbuffer_ms", "mapping_ms",
         "lighting_ms", "inverse_ms", "psnr_db", "ssim", "fpsnr_db"]


def bench_rows(efr=False):
    # scene, method, sigma, cost, gpu_ms, fpsnr: methods between 27 and 36 dB, full ∞.
    rows = [("s", "full", 1, 1, 9.0, "inf")]
    for method, base in (("rmfr", 36), ("kfr", 35.8), ("uniform", 33)):  # rmfr and kfr close: labels would collide
        for k, sigma in enumerate((1.4, 1.8, 2.2, 2.6)):
            rows.append(("s", method, sigma, round(1 / sigma ** 2, 3), 4.0 + 1.5 * (3 - k) + (base - 33) * 0.1, base - 2.5 * k))
    out = [[s, m, sg, 100, c, g, g, 0, 0, 0, 0, 0, fp, 0.9, fp] + ([sg * 1.5] if efr else []) for s, m, sg, c, g, fp in rows]
    return BENCH + (["sigma_nd"] if efr else []), out


def test_bench(charts, work):
    import bench_charts
    import chart_labels
    figs = caught(bench_charts)
    d = os.path.join(work, "bench")
    os.makedirs(d)
    header, rows = bench_rows()
    write_csv(os.path.join(d, "bench.csv"), header, rows)
    with open(os.path.join(d, "bench.json"), "w") as f:
        f.write('{"renderer": "TestGL 4.6 on a test GPU", "size": [1440, 800], "frames": 7, "warmup": 3, '
                '"pipeline": "visibility", "display": "htc_vive_pro_eye", "fovea": [0.5, 0.5]}\n')
    sys.argv = ["bench_charts.py", d]
    bench_charts.main()
    for name in ("pareto.png", "quality_cost.png"):
        fig = figs[name]
        ax = fig.axes[0]
        lo, hi = ax.get_ylim()
        check(hi < 40 and lo > 20 and hi >= 36, f"{name}: the y range is the methods' 28.5-36 dB, not up to the 60 dB sentinel ({lo:.1f}-{hi:.1f})")
        texts = [t.get_text() for t in ax.texts]
        check("full: ∞" in texts, f"{name}: the full reference is marked ∞ on the top edge ({texts[:3]})")
        labels = sorted(t for t, _ in ax.foveal_sigma_labels)
        want = sorted(["1.4", "1.8", "2.2", "2.6"] * 3)
        check(labels == want, f"{name}: every method point carries its σ ({labels})")
        boxes = chart_labels.label_boxes(ax, ax.foveal_sigma_labels)
        check(not overlaps(boxes), f"{name}: no two σ labels overlap ({len(overlaps(boxes))} pairs do)")
        footer = " ".join(" ".join(t.get_text() for t in fig.texts).split())
        for part in ("7 timed frames", "after 3 warm-up", "1440×800", "pipeline visibility", "display htc_vive_pro_eye",
                     "TestGL 4.6", "scenes: s"):
            check(part in footer, f"{name}: the footer gives the run's settings: '{part}' ({footer[:160]})")
    # A run from before warm-up, pipeline and display were recorded: said so, not guessed.
    with open(os.path.join(d, "bench.json"), "w") as f:
        f.write('{"renderer": "old", "size": [2880, 1600], "frames": 2, "fovea": [0.5, 0.5]}\n')
    bench_charts.main()
    footer = " ".join(" ".join(t.get_text() for t in figs["pareto.png"].texts).split())
    check("warm-up not recorded" in footer and "pipeline not recorded" in footer,
          f"an older bench.json: the missing settings are named as not recorded ({footer[:200]})")
    # EFR rows: σ_d/σ_nd.
    header, rows = bench_rows(efr=True)
    write_csv(os.path.join(d, "bench.csv"), header, rows)
    bench_charts.main()
    labels = {t for t, _ in figs["quality_cost.png"].axes[0].foveal_sigma_labels}
    check(labels == {"1.4/2.1", "1.8/2.7", "2.2/3.3", "2.6/3.9"}, f"EFR rows are labelled σ_d/σ_nd ({sorted(labels)})")


def test_filter_chart(src, work):
    import chart_labels
    import filter_chart
    figs = caught(filter_chart)
    d = os.path.join(work, "filter")
    os.makedirs(d)
    shutil.copy(os.path.join(src, "docs", "results", "filter_chart.csv"), d)  # a real run's numbers
    real = [["mine", m, l, j, "log"] for m, l, j in (("none", "no filter", 0.18), ("one_euro", "1euro mc=0.3 b=0", ""),
                                                    ("saccade_aware", "saccade-aware mc=1", 0.03))]
    write_csv(os.path.join(d, "filter_chart_real.csv"), ["recording", "method", "label", "jitter_deg", "source"], real)
    filter_chart.main(d)
    fig = figs["filter_chart.png"]
    for ax in fig.axes[:2]:
        texts = [t for t, _ in ax.foveal_point_labels]
        check("no filter" in texts and "filter" not in texts, f"the raw series' point reads 'no filter' ({texts[:3]})")
        check(len(texts) == 11 and "mc=1 b=0.1" in texts, f"every filter setting is labelled ({len(texts)})")
        boxes = chart_labels.label_boxes(ax, ax.foveal_point_labels)
        check(not overlaps(boxes), f"'{ax.get_title()}': no two point labels overlap ({len(overlaps(boxes))} pairs do)")
        check(ax.get_xscale() == "log" and ax.get_yscale() == "log", "lag and jitter on log axes")
        fig.canvas.draw()
        ticks = [t.get_text() for t in ax.get_xticklabels() if t.get_text()] + [t.get_text() for t in ax.get_yticklabels() if t.get_text()]
        plain = all("$" not in t and "^" not in t for t in ticks) and any(t.endswith(" ms") for t in ticks) and any(t.endswith("°") for t in ticks)
        check(plain, f"log tick labels are plain numbers with units ({ticks})")
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    check(legend[0] == "no filter (raw gaze)", f"the legend names the raw series ({legend})")
    ax = fig.axes[2]
    check("native logs" in ax.get_title(), f"the real panel says it charts native logs ({ax.get_title()})")
    bars = [p for p in ax.patches if p.get_height() > 0]
    check(len(bars) == 2, f"no bar where a setting had no fixation long enough ({len(bars)} bars)")
    check(any(t.get_text() == "n/a" for t in ax.texts), "the missing bar is marked n/a")


def test_log_chart(src, charts, work):
    script = os.path.join(charts, "log_chart.py")
    log = os.path.join(src, "data", "gaze", "vive_pro_eye_TESTNA01.csv")
    out = os.path.join(work, "plots")
    os.makedirs(out)
    import log_chart
    figs = caught(log_chart)
    r = log_chart.draw(log, os.path.join(out, "log.png"))
    fig = figs["log.png"]
    check(r["samples"] == 1518 and r["blinks"] == 1 and r["panels"] == 3,
          f"the bundled log: 1518 samples, its one blink, gaze x, y and the tracker's state ({r})")
    labels = [line.get_label() for ax in fig.axes for line in ax.get_lines()]
    check("left eye" in labels and "right eye" in labels, f"gaze per eye ({labels})")
    spans = [p.get_label() for p in fig.axes[0].patches]
    check(any(l.startswith("blink") for l in spans), f"the blink is shaded ({spans})")
    # A trace as replay writes it, with a blink and a marker.
    trace = os.path.join(out, "trace.csv")
    rows = []
    for i in range(60):
        state = "blink" if 20 <= i < 30 else "saccade" if i == 40 else "fixation"
        rows.append(f"{i * 8333333},{state},{700 + i},{800 - i},1.00,{state},{710 + i},{805 - i},1.00")
    rows.insert(35, "#mark,290000000,trial 1")
    with open(trace, "w") as f:
        f.write("t_ns,left_state,left_x_px,left_y_px,left_confidence,right_state,right_x_px,right_y_px,right_confidence\n" +
                "\n".join(rows) + "\n")
    r = log_chart.draw(trace, os.path.join(out, "trace.png"))
    check(r["samples"] == 60 and r["blinks"] == 1 and r["markers"] == 1, f"a trace: its samples, blink and marker ({r})")
    state_ax = figs["trace.png"].axes[2]
    check([t.get_text() for t in state_ax.get_yticklabels()] == ["fixation", "pursuit", "saccade", "blink", "lost"],
          "the trace's state panel names the pipeline's states")
    # The real program: a PNG on disk, atomically.
    p = subprocess.run(["/usr/bin/python3", script, log, os.path.join(out, "cli.png"), "--start", "1", "--end", "9"],
                       capture_output=True, text=True, timeout=120)
    with open(os.path.join(out, "cli.png"), "rb") as f:
        png = f.read(8) == b"\x89PNG\r\n\x1a\n"
    check(p.returncode == 0 and png, f"log_chart.py writes a PNG ({p.stderr.strip()})")
    # Malformed rows: exit 2, file, line and column named, nothing written.
    with open(log) as f:
        lines = f.read().split("\n")
    fields = lines[9].split(",")
    fields[2] = "x"
    lines[9] = ",".join(fields)
    bad = os.path.join(out, "bad.csv")
    with open(bad, "w") as f:
        f.write("\n".join(lines))
    trace_lines = open(trace).read().split("\n")
    trace_lines[5] = trace_lines[5].replace("fixation", "fixaton", 1)
    bad_trace = os.path.join(out, "bad_trace.csv")
    with open(bad_trace, "w") as f:
        f.write("\n".join(trace_lines))
    for path, where in ((bad, f"{bad}: line 10: column left_dir_x"), (bad_trace, f"{bad_trace}: line 6: column left_state")):
        p = subprocess.run(["/usr/bin/python3", script, path, os.path.join(out, "bad.png")], capture_output=True, text=True, timeout=120)
        check(p.returncode == 2 and where in p.stderr, f"a malformed row: exit 2 naming file, line and column ({p.returncode}: {p.stderr.strip()})")
    check(not os.path.exists(os.path.join(out, "bad.png")), "nothing written for a malformed file")
    left = [n for n in os.listdir(out) if n.endswith(".tmp")]
    check(not left, f"no temporary left behind ({left})")


def main():
    src = sys.argv[1]
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("skipped: this python3 has no matplotlib (python3-matplotlib), the charts cannot run")
        return 77
    charts = os.path.join(src, "tools", "charts")
    sys.path.insert(0, charts)
    work = tempfile.mkdtemp(prefix="foveal-chart-readability-")
    try:
        test_bench(charts, work)
        test_filter_chart(src, work)
        test_log_chart(src, charts, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"{len(failures)} failed" if failures else "all passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
