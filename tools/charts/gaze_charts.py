#!/usr/bin/python3
"""Chart and table of a `foveal bench --gaze` run (docs/bench.md, "Gaze-driven evaluation").

Reads DIR/gaze.csv (and gaze.json for the settings); writes DIR/gaze.png (quality against
shading cost per scene: FPSNR mean and 5th percentile over frames, and the share of frames
whose fovea patch falls below the bound) and DIR/gaze_table.md (per scene and level, each
method's FPSNR and what eye tracking buys over fixed foveation and uniform resolution at
the same cost). Rows of several logs are averaged (mean over logs of the per-log figures).
"""
import csv
import json
import math
import os
import sys

import chart_files

plt = chart_files.pyplot()

STYLE = {
    "oracle": ("darkred", "RMFR+EFR, perfect tracking (fovea on the true gaze)"),
    "rmfr": ("tab:red", "RMFR+EFR, eye-tracked"),
    "kfr": ("tab:blue", "KFR, eye-tracked"),
    "hyperbolic": ("tab:green", "hyperbolic, eye-tracked"),
    "linear": ("tab:orange", "linear, eye-tracked"),
    "fixed": ("tab:purple", "fixed foveation (no tracking)"),
    "uniform": ("tab:gray", "uniform resolution (no tracking)"),
}
TRACKED = "rmfr"


def num(v):
    if v in ("inf", "-inf"):
        return math.inf if v == "inf" else -math.inf
    return float(v) if v not in ("", "nan") else math.nan


def series(r):
    """The chart's name for a row: the method, or "oracle" for perfect tracking."""
    return "oracle" if r.get("gaze") == "true" else r["method"]


def averaged(rows):
    """(scene, series, sigma_d) -> mean over logs of each numeric column."""
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], series(r), num(r["sigma_d"])), []).append(r)
    out = {}
    for key, rs in groups.items():
        out[key] = {k: sum(num(r[k]) for r in rs) / len(rs)
                    for k in ("cost", "gpu_ms", "fpsnr_mean", "fpsnr_p5", "fpsnr_min", "ssim_mean", "patch_exceed_share",
                              "patch_psnr_mean", "fovea_error_deg_mean")}
        out[key]["logs"] = len(rs)
        out[key]["frames"] = sum(int(r["frames"]) for r in rs)
    return out


def chart(avg, settings, out):
    scenes = sorted({k[0] for k in avg})
    fig, axes = plt.subplots(2, len(scenes), figsize=(max(6 * len(scenes), 9), 8), squeeze=False)
    for col, scene in enumerate(scenes):
        top, bottom = axes[0][col], axes[1][col]
        for method, (color, label) in STYLE.items():
            pts = sorted(((s, v) for (sc, m, s), v in avg.items() if sc == scene and m == method), key=lambda p: -p[0])
            if not pts:
                continue
            xs = [v["cost"] for _, v in pts]
            top.plot(xs, [v["fpsnr_mean"] for _, v in pts], "o-", color=color, label=label + " (mean)", markersize=4)
            top.plot(xs, [v["fpsnr_p5"] for _, v in pts], "v--", color=color, alpha=0.6, markersize=3,
                     label=label + " (5th pct.)")
            bottom.plot(xs, [100 * v["patch_exceed_share"] for _, v in pts], "o-", color=color, label=label, markersize=4)
        top.set_ylabel("FPSNR over frames (dB)")
        bottom.set_title(f"{scene}: fovea patch > {settings.get('patch_margin_db', '?')} dB below perfect tracking")
        bottom.set_ylabel("share of frames (%)")
        top.set_title(f"{scene}: FPSNR at the true gaze against cost", fontsize=10)
        for ax in (top, bottom):
            ax.set_xlabel("shaded samples / full (theoretical cost)")
            ax.grid(alpha=0.3)
        top.legend(fontsize=7)
        bottom.legend(fontsize=7)
    fig.suptitle(f"Gaze-driven evaluation: {settings.get('display', '?')} {settings.get('size', ['?', '?'])[0]}x"
                 f"{settings.get('size', ['?', '?'])[1]}, {settings.get('fps', '?')} Hz, latency "
                 f"{settings.get('latency_ms', 0):.1f} ms\nlogs: {', '.join(l['name'] for l in settings.get('logs', []))}", fontsize=10)
    fig.tight_layout()
    chart_files.save_figure(fig, out, dpi=100)


def table(avg, out):
    scenes = sorted({k[0] for k in avg})
    methods = [m for m in STYLE if any(k[1] == m for k in avg)]
    lines = ["FPSNR mean / 5th percentile over frames (dB), averaged over the logs, at each level σ_d (the same",
             "shaded samples for every method; oracle: RMFR+EFR with its fovea on the true gaze); Δ: eye-tracked",
             "RMFR+EFR minus fixed foveation and minus uniform resolution (mean FPSNR, dB); patch: share of frames",
             "whose fovea patch is more than the margin below the oracle's.", "",
             "| scene | σ_d | cost | " + " | ".join(methods) + " | Δ fixed | Δ uniform | patch rmfr / fixed / uniform |",
             "|---|---|---|" + "---|" * len(methods) + "---|---|---|"]
    for scene in scenes:
        for sigma in sorted({k[2] for k in avg if k[0] == scene}):
            row = {m: avg.get((scene, m, sigma)) for m in methods}
            cost = next(v["cost"] for v in row.values() if v)
            cells = [f"{v['fpsnr_mean']:.2f} / {v['fpsnr_p5']:.2f}" if v else "—" for v in row.values()]

            def delta(other):
                t, o = row.get(TRACKED), row.get(other)
                return f"{t['fpsnr_mean'] - o['fpsnr_mean']:+.2f}" if t and o else "—"

            def share(m):
                return f"{100 * row[m]['patch_exceed_share']:.0f}%" if row.get(m) else "—"

            lines.append(f"| {scene} | {sigma:g} | {cost:.3f} | " + " | ".join(cells) +
                         f" | {delta('fixed')} | {delta('uniform')} | {share('rmfr')} / {share('fixed')} / {share('uniform')} |")
    chart_files.write_text(out, "\n".join(lines) + "\n")


def main():
    d = sys.argv[1]
    with open(os.path.join(d, "gaze.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    settings = {}
    if os.path.exists(os.path.join(d, "gaze.json")):
        with open(os.path.join(d, "gaze.json")) as f:
            settings = json.load(f)
    avg = averaged(rows)
    if not avg:
        sys.exit(f"{d}/gaze.csv: no rows")
    chart(avg, settings, os.path.join(d, "gaze.png"))
    table(avg, os.path.join(d, "gaze_table.md"))


if __name__ == "__main__":
    chart_files.run(main)
