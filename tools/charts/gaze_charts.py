#!/usr/bin/python3
"""Chart and table of a `foveal bench --gaze` run (docs/bench.md, "Gaze-driven evaluation").

Reads DIR/gaze.csv (and gaze.json for the settings); writes DIR/gaze.png (quality against
shading cost per scene: FPSNR mean and 5th percentile over frames, the share of frames
whose fovea patch falls below the bound, and, when gaze.csv has them, JOD mean and 5th
percentile, and with gaze_video.csv the sequences' video JOD) and DIR/gaze_table.md (per scene and level, each method's FPSNR (and JOD) and
what eye tracking buys over fixed foveation and uniform resolution at the same cost). Rows
of several logs are averaged (mean over logs of the per-log figures). A run with
--no-jod, or from before JOD, has no JOD row in the chart and no JOD in the table.
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
    "inset": ("tab:cyan", "inset (quad views), eye-tracked"),
    "inset-fixed": ("tab:olive", "inset (quad views), fixed at the centre"),
}
TRACKED = "rmfr"


def num(v):
    if v in ("inf", "-inf"):
        return math.inf if v == "inf" else -math.inf
    return float(v) if v not in ("", "nan") else math.nan


def series(r):
    """The chart's name for a row: the method, or "oracle" for perfect tracking."""
    return "oracle" if r.get("gaze") == "true" else r["method"]


JOD_COLUMNS = ("jod_mean", "jod_p5", "jod_min")  # the last columns of gaze.csv unless --no-jod


def has_jod(rows):
    return bool(rows) and all(k in rows[0] for k in JOD_COLUMNS)


def averaged(rows):
    """(scene, series, sigma_d) -> mean over logs of each numeric column."""
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], series(r), num(r["sigma_d"])), []).append(r)
    columns = ("cost", "gpu_ms", "fpsnr_mean", "fpsnr_p5", "fpsnr_min", "ssim_mean", "patch_exceed_share",
               "patch_psnr_mean", "fovea_error_deg_mean") + (JOD_COLUMNS if has_jod(rows) else ())
    out = {}
    for key, rs in groups.items():
        out[key] = {k: sum(num(r[k]) for r in rs) / len(rs) for k in columns}
        out[key]["logs"] = len(rs)
        out[key]["frames"] = sum(int(r["frames"]) for r in rs)
    return out


def points(avg, scene, method):
    """A series' levels on one scene, in order of falling σ_d (rising cost): [(σ_d, figures)]."""
    return sorted(((s, v) for (sc, m, s), v in avg.items() if sc == scene and m == method), key=lambda p: -p[0])


def video_averaged(rows):
    """gaze_video.csv (--gaze-video): (scene, series, sigma_d, temporal) -> mean video JOD over
    the logs; temporal is "on" or "off" (files from before accumulation: off)."""
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], series(r), num(r["sigma_d"]), r.get("temporal", "off")), []).append(num(r["jod"]))
    return {k: sum(v) / len(v) for k, v in groups.items()}


def chart(avg, settings, out, video=None):
    scenes = sorted({k[0] for k in avg})
    jod = any("jod_mean" in v for v in avg.values())
    nrows = 3 if jod else 2
    fig, axes = plt.subplots(nrows, len(scenes), figsize=(max(6 * len(scenes), 9), 4 * nrows), squeeze=False)
    for col, scene in enumerate(scenes):
        top, bottom = axes[0][col], axes[1][col]
        for method, (color, label) in STYLE.items():
            pts = points(avg, scene, method)
            if not pts:
                continue
            xs = [v["cost"] for _, v in pts]
            top.plot(xs, [v["fpsnr_mean"] for _, v in pts], "o-", color=color, label=label + " (mean)", markersize=4)
            top.plot(xs, [v["fpsnr_p5"] for _, v in pts], "v--", color=color, alpha=0.6, markersize=3,
                     label=label + " (5th pct.)")
            bottom.plot(xs, [100 * v["patch_exceed_share"] for _, v in pts], "o-", color=color, label=label, markersize=4)
            if jod:
                axes[2][col].plot(xs, [v["jod_mean"] for _, v in pts], "o-", color=color, label=label + " (mean)", markersize=4)
                axes[2][col].plot(xs, [v["jod_p5"] for _, v in pts], "v--", color=color, alpha=0.6, markersize=3,
                                  label=label + " (5th pct.)")
                for temporal, marker, name in (("off", "s:", " (video)"), ("on", "D-.", " (video, temporal accumulation)")):
                    seq = [(v["cost"], video[(scene, method, s, temporal)]) for s, v in pts
                           if video and (scene, method, s, temporal) in video]
                    if seq:
                        axes[2][col].plot([c for c, _ in seq], [j for _, j in seq], marker, color=color, markersize=4,
                                          label=label + name)
        if jod:
            panel = axes[2][col]
            panel.axhline(9.5, color="black", linestyle=":", linewidth=1, label="JOD 9.5")
            panel.set_title(f"{scene}: JOD at the true gaze against cost (FovVideoVDP, both eyes)", fontsize=10)
            panel.set_ylabel("JOD over frames (10 = no visible difference)")
            panel.set_xlabel("shaded samples / full (theoretical cost)")
            panel.grid(alpha=0.3)
            panel.legend(fontsize=7)
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
    jod = any("jod_mean" in v for v in avg.values())
    lines = ["FPSNR mean / 5th percentile over frames (dB)" + (" / JOD mean" if jod else "") +
             ", averaged over the logs, at each level σ_d (the same",
             "shaded samples for every method; oracle: RMFR+EFR with its fovea on the true gaze); Δ: eye-tracked",
             "RMFR+EFR minus fixed foveation and minus uniform resolution (mean FPSNR, dB" + ("; and mean JOD" if jod else "") +
             "); patch: share of frames",
             "whose fovea patch is more than the margin below the oracle's.", "",
             "| scene | σ_d | cost | " + " | ".join(methods) + " | Δ fixed | Δ uniform | " +
             ("Δ JOD fixed | Δ JOD uniform | " if jod else "") + "patch rmfr / fixed / uniform |",
             "|---|---|---|" + "---|" * len(methods) + "---|---|" + ("---|---|" if jod else "") + "---|"]
    for scene in scenes:
        for sigma in sorted({k[2] for k in avg if k[0] == scene}):
            row = {m: avg.get((scene, m, sigma)) for m in methods}
            cost = next(v["cost"] for v in row.values() if v)
            cells = [f"{v['fpsnr_mean']:.2f} / {v['fpsnr_p5']:.2f}" + (f" / {v['jod_mean']:.2f}" if jod else "") if v else "—"
                     for v in row.values()]

            def delta(other, key="fpsnr_mean"):
                t, o = row.get(TRACKED), row.get(other)
                return f"{t[key] - o[key]:+.2f}" if t and o else "—"

            def share(m):
                return f"{100 * row[m]['patch_exceed_share']:.0f}%" if row.get(m) else "—"

            jod_cells = f"{delta('fixed', 'jod_mean')} | {delta('uniform', 'jod_mean')} | " if jod else ""
            lines.append(f"| {scene} | {sigma:g} | {cost:.3f} | " + " | ".join(cells) +
                         f" | {delta('fixed')} | {delta('uniform')} | {jod_cells}{share('rmfr')} / {share('fixed')} / {share('uniform')} |")
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
    video = None
    if os.path.exists(os.path.join(d, "gaze_video.csv")):
        with open(os.path.join(d, "gaze_video.csv"), newline="") as f:
            video = video_averaged(list(csv.DictReader(f)))
    chart(avg, settings, os.path.join(d, "gaze.png"), video)
    table(avg, os.path.join(d, "gaze_table.md"))


if __name__ == "__main__":
    chart_files.run(main)
