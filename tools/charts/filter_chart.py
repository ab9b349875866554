#!/usr/bin/env python3
"""Draws foveal filter-chart's data: jitter against lag per method, and jitter on real
recordings. Usage: filter_chart.py DIR (reads DIR/filter_chart*.csv, writes DIR/filter_chart.png)."""
import csv
import os
import sys

import chart_files

plt = chart_files.pyplot()

COLOURS = {"none": "tab:red", "one_euro": "tab:blue", "saccade_aware": "tab:green"}


def main(out_dir):
    with open(os.path.join(out_dir, "filter_chart.csv")) as f:
        rows = list(csv.DictReader(f))
    real_path = os.path.join(out_dir, "filter_chart_real.csv")
    real = []
    if os.path.exists(real_path):
        with open(real_path) as f:
            real = list(csv.DictReader(f))

    fig, axes = plt.subplots(1, 3 if real else 2, figsize=(17 if real else 12, 5))
    for ax, key, title in ((axes[0], "step_lag_ms", "after a saccade (step)"),
                           (axes[1], "pursuit_lag_ms", "in smooth pursuit (ramp)")):
        for method in COLOURS:
            pts = [r for r in rows if r["method"] == method]
            ax.scatter([float(r[key]) for r in pts], [float(r["jitter_deg"]) for r in pts],
                       c=COLOURS[method], label=method.replace("_", " "), s=40)
            for r in pts:
                ax.annotate(r["label"].split(" ", 1)[-1], (float(r[key]), float(r["jitter_deg"])),
                            fontsize=7, xytext=(3, 3), textcoords="offset points")
        ax.set_xscale("symlog", linthresh=1.0)  # lags span 0.2 ms to 350 ms
        ax.set_yscale("log")
        ax.set_xlabel(f"lag {title}, ms")
        ax.set_ylabel("jitter: RMS error in fixations, deg")
        ax.set_title(f"Synthetic, 0.5 deg noise: lag {title}", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    if real:
        recordings = sorted({r["recording"] for r in real})
        labels = [r["label"] for r in real if r["recording"] == recordings[0]]
        width = 0.8 / len(recordings)
        ax = axes[2]
        for k, rec in enumerate(recordings):
            vals = [float(r["jitter_deg"]) for r in real if r["recording"] == rec]
            ax.bar([i + k * width for i in range(len(vals))], vals, width, label=rec)
        ax.set_xticks([i + 0.4 - width / 2 for i in range(len(labels))])
        ax.set_xticklabels(labels, rotation=60, ha="right", fontsize=7)
        ax.set_ylabel("jitter in fixations, deg")
        ax.set_title("Real Vive Pro Eye recordings (spread around a 100 ms mean)", fontsize=10)
        ax.legend(fontsize=7)
    fig.tight_layout()
    chart_files.save_figure(fig, os.path.join(out_dir, "filter_chart.png"), dpi=90)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: filter_chart.py DIR")
    sys.exit(chart_files.run(lambda: main(sys.argv[1])))
