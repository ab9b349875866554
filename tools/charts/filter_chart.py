#!/usr/bin/env python3
"""Draws foveal filter-chart's data: jitter against lag per filter setting on synthetic
scanpaths (after a saccade, in pursuit), and jitter on real recordings (SRanipal exports
or the user's own native logs). Usage: filter_chart.py DIR (reads DIR/filter_chart.csv
and DIR/filter_chart_real.csv when there, writes DIR/filter_chart.png)."""
import csv
import math
import os
import sys

import chart_files
import chart_labels

plt = chart_files.pyplot()

# Method column -> (colour, legend name). "none" is the raw gaze, no filter at all.
SERIES = {"none": ("tab:red", "no filter (raw gaze)"), "one_euro": ("tab:blue", "1€ filter"),
          "saccade_aware": ("tab:green", "saccade-aware pipeline (1€ in fixation)")}
PREFIXES = ("1euro ", "saccade-aware ")


def short_label(row):
    """A point's setting without the method's name, which the colour already says:
    'mc=1 b=0.1'. The raw series keeps its whole label ('no filter')."""
    label = row["label"]
    for p in PREFIXES:
        if label.startswith(p):
            return label[len(p):]
    return label


def plain(unit):
    """Log-axis tick labels as plain numbers with the unit: 0.3 ms, 10 ms, 0.2°."""
    from matplotlib.ticker import FuncFormatter
    return FuncFormatter(lambda v, _: f"{v:g}{unit}")


def log_axis(axis, lo, hi, unit):
    """Ticks of a log axis labelled plainly: at 1-2-5 steps over up to three decades, at
    the powers of ten over more (so that the labels do not run into each other)."""
    from matplotlib.ticker import LogLocator, NullFormatter
    wide = math.log10(hi / lo) > 3
    axis.set_major_locator(LogLocator(base=10, subs=(1.0,) if wide else (1.0, 2.0, 5.0)))
    axis.set_minor_locator(LogLocator(base=10, subs=tuple(range(2, 10)) if wide else (3.0, 4.0, 6.0, 7.0, 8.0, 9.0)))
    axis.set_major_formatter(plain(unit))
    axis.set_minor_formatter(NullFormatter())


def number(row, key, path, line):
    """A finite number; lags may be below 0 (the output ahead of the truth on a short run)."""
    try:
        v = float(row[key])
    except (TypeError, ValueError):
        raise ValueError(f"{path}: line {line}: column {key}: '{row.get(key)}' is not a number") from None
    if not math.isfinite(v) or (v < 0 and not key.endswith("_lag_ms")):
        raise ValueError(f"{path}: line {line}: column {key}: {v} is not a finite value >= 0")
    return v


def synthetic_panel(ax, rows, key, title, path):
    series = []
    for method, (colour, name) in SERIES.items():
        mine = [(i, r) for i, r in enumerate(rows) if r["method"] == method]
        xs = [number(r, key, path, i + 2) for i, r in mine]
        ys = [number(r, "jitter_deg", path, i + 2) for i, r in mine]
        series.append((colour, name, xs, ys, [short_label(r) for _, r in mine]))
    # A log axis cannot show 0 or less (a lag under the resolution of a short run): such a
    # value sits at half the smallest positive one, and its label gives the value.
    xfloor = min([x for s in series for x in s[2] if x > 0] or [1.0]) / 2
    yfloor = min([y for s in series for y in s[3] if y > 0] or [1.0]) / 2
    pts = []
    for colour, name, xs, ys, texts in series:
        texts = [t + (f" (lag {x:g} ms)" if x <= 0 else "") for t, x in zip(texts, xs)]
        xs, ys = [max(x, xfloor) for x in xs], [max(y, yfloor) for y in ys]
        ax.scatter(xs, ys, c=colour, label=name, s=36, zorder=3)
        pts += list(zip(xs, ys, texts))
    ax.set_xscale("log")
    ax.set_yscale("log")
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    xlim, ylim = (min(xs) / 2, max(xs) * 3), (min(ys) / 1.5, max(ys) * 2)  # room for the labels beside the outer points
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    log_axis(ax.xaxis, *xlim, " ms")
    log_axis(ax.yaxis, *ylim, "°")
    ax.set_xlabel(f"lag {title} (ms, log scale)")
    ax.set_ylabel("jitter: RMS error in fixations (degrees, log scale)")
    ax.set_title(f"Synthetic scanpaths, 0.5° noise: lag {title}", fontsize=10)
    ax.grid(alpha=0.35, which="major")
    ax.grid(alpha=0.1, which="minor")
    ax.legend(fontsize=7, loc="upper right")
    return pts


def real_panel(ax, real, path):
    recordings = list(dict.fromkeys(r["recording"] for r in real))
    labels = list(dict.fromkeys(r["label"] for r in real))
    source = {r["recording"]: r.get("source") or "SRanipal" for r in real}
    width = 0.8 / len(recordings)
    for k, rec in enumerate(recordings):
        by_label = {r["label"]: r for r in real if r["recording"] == rec}
        xs, vals, missing = [], [], []
        for i, label in enumerate(labels):
            r = by_label.get(label)
            x = i - 0.4 + (k + 0.5) * width
            if r is None or r["jitter_deg"] in ("", None):  # no fixation long enough: no bar, a mark
                missing.append(x)
                continue
            xs.append(x)
            vals.append(number(r, "jitter_deg", path, real.index(r) + 2))
        ax.bar(xs, vals, width, label=f"{rec} ({'native log' if source[rec] == 'log' else 'SRanipal export'})")
        for x in missing:
            ax.annotate("n/a", (x, 0), xytext=(0, 2), textcoords="offset points", ha="center", va="bottom", fontsize=6, rotation=90)
    ax.set_xticks(range(len(labels)))
    ax.set_xticklabels(labels, rotation=45, ha="right", fontsize=7)
    ax.set_ylabel("jitter in fixations (degrees; n/a: no fixation\nrun long enough)")
    kinds = sorted({"native logs" if s == "log" else "SRanipal exports" for s in source.values()})
    ax.set_title(f"Real recordings ({', '.join(kinds)}): spread around the 100 ms centred mean", fontsize=10)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=7)


def read_rows(path, columns):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if rows:
        absent = [c for c in columns if c not in rows[0]]
        if absent:
            raise ValueError(f"{path}: line 1: missing column(s) {', '.join(absent)}")
    return rows


def main(out_dir):
    path = os.path.join(out_dir, "filter_chart.csv")
    rows = read_rows(path, ("method", "label", "jitter_deg", "step_lag_ms", "pursuit_lag_ms"))
    real_path = os.path.join(out_dir, "filter_chart_real.csv")
    real = read_rows(real_path, ("recording", "method", "label", "jitter_deg")) if os.path.exists(real_path) else []

    fig, axes = plt.subplots(1, 3 if real else 2, figsize=(20 if real else 13, 6.2))
    placed = []
    for ax, key, title in ((axes[0], "step_lag_ms", "after a saccade (step)"), (axes[1], "pursuit_lag_ms", "in smooth pursuit (ramp)")):
        placed.append((ax, synthetic_panel(ax, rows, key, title, path)))
    if real:
        real_panel(axes[2], real, real_path)
    fig.tight_layout()
    for ax, pts in placed:  # after the layout: the labels' offsets are in points
        ax.foveal_point_labels = chart_labels.place_labels(ax, pts, fontsize=7, avoid_boxes=[
            ax.get_legend().get_window_extent(fig.canvas.get_renderer())])
    chart_files.save_figure(fig, os.path.join(out_dir, "filter_chart.png"), dpi=90)
    return 0


def run(out_dir):
    try:
        return main(out_dir)
    except (ValueError, KeyError) as e:
        sys.exit(f"filter_chart.py: {e}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: filter_chart.py DIR")
    sys.exit(chart_files.run(lambda: run(sys.argv[1])))
