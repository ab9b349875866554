#!/usr/bin/python3
"""Charts and the Table-1-style summary of a `foveal bench` run (docs/bench.md).

Reads DIR/bench.csv (and fgrid.csv, rotation.csv, bench.json when present); writes
pareto.png, quality_cost.png, jod_cost.png (when bench.csv has JOD columns), fgrid.png,
rotation.png and stability.png (each with a JOD panel when its table has JOD) and
table.md into DIR.
"""
import csv
import json
import math
import os
import sys

import chart_files
import chart_labels
import run_settings

plt = chart_files.pyplot()

COLORS = {"full": "black", "rmfr": "tab:red", "kfr": "tab:blue", "hyperbolic": "tab:green", "linear": "tab:orange",
          "uniform": "tab:gray", "fixed": "tab:purple"}


def num(v):
    return math.inf if v == "inf" else float(v)


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def scene_axes(n, width, height):
    """One panel per scene, three to a row; unused panels hidden."""
    cols = min(3, n)
    nrows = (n + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(width * cols, height * nrows), squeeze=False)
    flat = [ax for row in axes for ax in row]
    for ax in flat[n:]:
        ax.axis("off")
    return fig, flat


def series(rows, scene, y_key):
    """(method, costs or times, values) per method of one scene, levels in order of σ
    (timings are noisy, the level order is not); rows without `y_key` are left out."""
    out = []
    srows = [r for r in rows if r["scene"] == scene and r.get(y_key) not in (None, "")]
    for method in COLORS:
        m = sorted((r for r in srows if r["method"] == method), key=lambda r: -num(r["sigma"]))
        if m:
            out.append((method, m))
    return out


# What a chart's y axis shows: the column, its label, the reference's label, and a
# threshold line (JOD 9.5: issue 28's "a viewer cannot tell"). A value that is not finite
# (the full reference's FPSNR, ∞ dB) is not on the scale: a marker on the top edge says
# so, and the y range is the methods' points.
FPSNR = ("fpsnr_db", "FPSNR (dB)", "full (reference, ∞ dB: ★ on the top edge)", None)
JOD = ("jod", "JOD (FovVideoVDP, both eyes; 10 = no visible difference)", "full (reference, 10)", 9.5)


def sigma_text(r):
    """A point's level: σ, or σ_d/σ_nd where the row has a different non-dominant level (EFR)."""
    nd = r.get("sigma_nd")
    if nd not in (None, "") and num(nd) != num(r["sigma"]):
        return f"{num(r['sigma']):g}/{num(nd):g}"
    return f"{num(r['sigma']):g}"


def y_range(values, threshold):
    """The methods' finite values (and the threshold line), with room above for labels."""
    v = [y for y in values if math.isfinite(y)] + ([threshold] if threshold is not None else [])
    if not v:
        return None
    lo, hi = min(v), max(v)
    span = (hi - lo) or max(abs(hi) * 0.05, 0.5)
    return lo - 0.08 * span, hi + 0.15 * span


def pareto(rows, out, x_key="gpu_ms", x_label="GPU frame time (ms, median)", title="quality against frame time", y=FPSNR,
           settings=None):
    y_key, y_label, full_label, threshold = y
    scenes = sorted({r["scene"] for r in rows})
    fig, flat = scene_axes(len(scenes), 6.5, 5.2)
    share = run_settings.add_footer(fig, settings) if settings else 0.0
    panels = []
    for ax, scene in zip(flat, scenes):
        labelled, off_scale, xs, ys = [], [], [], []
        for method, m in series(rows, scene, y_key):
            pts = [(num(r[x_key]), num(r[y_key]), r) for r in m]
            xs += [p[0] for p in pts]
            ys += [p[1] for p in pts]
            on = [p for p in pts if math.isfinite(p[1])]
            off_scale += [(p[0], method) for p in pts if not math.isfinite(p[1])]
            if method == "full":
                if on:
                    ax.scatter([p[0] for p in on], [p[1] for p in on], marker="*", s=120, color=COLORS[method], label=full_label)
                continue
            ax.plot([p[0] for p in on], [p[1] for p in on], "o-", color=COLORS[method], label=method, markersize=4)
            labelled += [(p[0], p[1], sigma_text(p[2])) for p in on]
        for x, method in off_scale:  # on the top edge, outside the data range
            ax.scatter([x], [1.0], marker="^" if method != "full" else "*", s=90 if method == "full" else 40, color=COLORS[method],
                       transform=ax.get_xaxis_transform(), clip_on=False, zorder=5,
                       label=full_label if method == "full" else None)
            ax.annotate(f"{method}: ∞", (x, 1.0), xycoords=ax.get_xaxis_transform(),
                        xytext=(-7, -3), textcoords="offset points", ha="right", va="top", fontsize=7)
        if threshold is not None:
            ax.axhline(threshold, color="black", linestyle=":", linewidth=1, label=f"JOD {threshold:g}")
        finite_x = [x for x in xs if math.isfinite(x)]
        if finite_x:  # the off-scale markers are drawn in axes coordinates: the x range must hold them
            lo, hi = min(finite_x), max(finite_x)
            pad = 0.05 * ((hi - lo) or abs(hi) or 1.0)
            ax.set_xlim(lo - pad, hi + pad)
        limits = y_range(ys, threshold)
        if limits:
            ax.set_ylim(*limits)
            for x, _ in off_scale:  # an unseen line under each top-edge marker and its text: the legend keeps off them
                y_text = limits[0] + 0.95 * (limits[1] - limits[0])
                ax.plot([x - 0.15 * (ax.get_xlim()[1] - ax.get_xlim()[0]), x], [y_text] * 2, color="none", label="_off_scale")
        ax.set_title(f"{scene}: {title}")
        ax.set_xlabel(x_label)
        ax.set_ylabel(y_label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, title="labels: σ (σ_d/σ_nd)", title_fontsize=7, loc="best")
        panels.append((ax, labelled))
    fig.tight_layout(rect=(0, share, 1, 1))
    # Labels go on after the layout, which moves the axes; the legend's box is kept clear.
    for ax, labelled in panels:
        ax.foveal_sigma_labels = chart_labels.place_labels(ax, labelled, fontsize=6.5, avoid_boxes=[legend_box(ax)])
    chart_files.save_figure(fig, out, dpi=110)


def legend_box(ax):
    return ax.get_legend().get_window_extent(ax.figure.canvas.get_renderer())


def fgrid(rows, autos, out):
    scenes = sorted({r["scene"] for r in rows})
    fig, flat = scene_axes(len(scenes), 5.0, 4.3)
    for ax, scene in zip(flat, scenes):
        s = [r for r in rows if r["scene"] == scene]
        fxs = sorted({num(r["fx"]) for r in s})
        fys = sorted({num(r["fy"]) for r in s})
        grid = [[math.nan] * len(fxs) for _ in fys]
        for r in s:
            grid[fys.index(num(r["fy"]))][fxs.index(num(r["fx"]))] = num(r["fpsnr_db"])
        # Cells centred on the grid values.
        dx = (fxs[-1] - fxs[0]) / max(len(fxs) - 1, 1) / 2
        dy = (fys[-1] - fys[0]) / max(len(fys) - 1, 1) / 2
        im = ax.imshow(grid, origin="lower", cmap="viridis", aspect="auto",
                       extent=[fxs[0] - dx, fxs[-1] + dx, fys[0] - dy, fys[-1] + dy])
        fig.colorbar(im, ax=ax, label="FPSNR (dB)")
        for a in autos:
            if a["scene"] == scene:
                ax.scatter([a["grid_best_fx"]], [a["grid_best_fy"]], marker="s", facecolors="none", edgecolors="white", s=90, label="grid optimum")
                ax.scatter([a["auto_fx"]], [a["auto_fy"]], marker="x", color="red", s=90, label="automatic f")
        ax.set_title(f"{scene}: RMFR FPSNR over f (σ = {s[0]['sigma']})")
        ax.set_xlabel("f_x (fraction of W)")
        ax.set_ylabel("f_y (fraction of H)")
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    chart_files.save_figure(fig, out, dpi=110)


def rotation(rows, out):
    """FPSNR per method against the stripes' angle; beside it JOD, when rotation.csv has it."""
    jod = bool(rows) and "jod" in rows[0]
    fig, axes = plt.subplots(1, 2 if jod else 1, figsize=(13 if jod else 7, 4.3), squeeze=False)
    panels = [("fpsnr_db", "FPSNR (dB)", "FPSNR")] + ([("jod", "JOD (both eyes, at the fovea)", "JOD")] if jod else [])
    for ax, (key, label, name) in zip(axes[0], panels):
        for method in COLORS:
            m = sorted((r for r in rows if r["method"] == method), key=lambda r: num(r["angle_deg"]))
            if m:
                ax.plot([num(r["angle_deg"]) for r in m], [num(r[key]) for r in m], "o-", color=COLORS[method], label=method, markersize=4)
        ax.set_title(f"Rotated stripes (σ = {rows[0]['sigma']}): {name} per method")
        ax.set_xlabel("pattern rotation (degrees)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    chart_files.save_figure(fig, out, dpi=110)


def stability(rows, out):
    jod = bool(rows) and "jod" in rows[0]  # a third row: JOD at the fovea
    fig, axes = plt.subplots(3 if jod else 2, 2, figsize=(11, 11 if jod else 7.5), sharex=True)
    for col, path in enumerate(("diagonal", "vertical")):
        for method in COLORS:
            m = sorted((r for r in rows if r["method"] == method and r["path"] == path), key=lambda r: num(r["t"]))
            if not m:
                continue
            t = [num(r["t"]) for r in m]
            axes[0][col].plot(t, [min(num(r["patch_psnr_db"]), 60) for r in m], "o-", color=COLORS[method], label=method, markersize=4)
            axes[1][col].plot(t, [num(r["fpsnr_db"]) for r in m], "o-", color=COLORS[method], label=method, markersize=4)
            if jod:
                axes[2][col].plot(t, [num(r["jod"]) for r in m], "o-", color=COLORS[method], label=method, markersize=4)
        where = "centre -> top-left corner" if path == "diagonal" else "centre -> bottom border"
        axes[0][col].set_title(f"fovea {where}: 64-px patch around the fovea")
        axes[1][col].set_title(f"fovea {where}: whole frame")
        axes[-1][col].set_xlabel("position along the path (0 = centre, 1 = border)")
        axes[0][col].set_ylabel("patch PSNR (dB, ∞ shown at 60)")
        axes[1][col].set_ylabel("FPSNR (dB)")
        if jod:
            axes[2][col].set_title(f"fovea {where}: JOD at the fovea")
            axes[2][col].set_ylabel("JOD")
        for ax in [axes[r][col] for r in range(len(axes))]:
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
    fig.suptitle(f"Stability: quality against fovea position (pattern:checker, σ = {rows[0]['sigma']})")
    fig.tight_layout()
    chart_files.save_figure(fig, out, dpi=110)


def flicker(rows, out):
    """Per scene and camera path: each method's flicker per pipeline and gaze (bars), and
    RMFR's against its prefiltered reference (hatched). Files from before the moving
    camera (no pipeline, camera or flicker column) are a G-buffer run with a still camera."""
    for r in rows:
        r.setdefault("pipeline", "gbuffer")
        r.setdefault("camera", "static")
        r.setdefault("flicker", r["periphery_change"])
        r.setdefault("temporal", "off")
    panels = list(dict.fromkeys((r["scene"], r["camera"]) for r in rows))
    methods = [m for m in COLORS if any(r["method"] == m for r in rows)]
    series = list(dict.fromkeys((r["pipeline"], r["gaze"], r["temporal"]) for r in rows))
    fig, axes = scene_axes(len(panels), 7.5, 4.3)
    width = 0.8 / len(series)
    shades = ["tab:gray", "tab:purple", "tab:olive", "tab:cyan", "tab:brown", "tab:pink"]
    for ax, (scene, camera) in zip(axes, panels):
        mine = [r for r in rows if r["scene"] == scene and r["camera"] == camera]
        for k, (pipeline, gaze, temporal) in enumerate(series):
            x = [i + (k - (len(series) - 1) / 2) * width for i in range(len(methods))]
            pick = [next((r for r in mine if r["method"] == m and r["pipeline"] == pipeline and r["gaze"] == gaze
                          and r["temporal"] == temporal), None) for m in methods]
            label = f"{pipeline}, {gaze} gaze" + (", temporal accumulation" if temporal == "on" else "")
            ax.bar(x, [num(r["flicker"]) if r else 0 for r in pick], width, color=shades[k % len(shades)], label=label)
            pre = [(xi, num(r["prefiltered_flicker"])) for xi, r in zip(x, pick) if r and r.get("prefiltered_flicker")]
            if pre:
                ax.bar([p[0] for p in pre], [p[1] for p in pre], width * 0.5, fill=False, hatch="//", edgecolor="black",
                       label="against RMFR's prefiltered reference" if k == 0 else None)
        ax.set_xticks(range(len(methods)))
        ax.set_xticklabels(methods)
        ax.set_ylabel("flicker: mean |ΔF − ΔR| in the periphery (8-bit)")
        last = mine[-1]
        sigma = last["sigma"] + (f"/{last['sigma_nd']}" if last.get("sigma_nd") not in (None, "", last["sigma"]) else "")
        ax.set_title(f"{scene}, camera {camera}, σ = {sigma}, {mine[0]['frames']} frames", fontsize=9)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle("Flicker against the full-resolution reference along the same path")
    fig.tight_layout()
    chart_files.save_figure(fig, out, dpi=110)


def table(rows, out):
    """Per scene, each method at the level closest to σ = 2.6 (equal shaded samples)."""
    methods = [m for m in ("rmfr", "hyperbolic", "kfr", "linear", "uniform", "fixed") if any(r["method"] == m for r in rows)]
    sigmas = sorted({num(r["sigma"]) for r in rows if r["method"] != "full"})
    if not sigmas or not methods:
        return
    sigma = min(sigmas, key=lambda s: abs(s - 2.6))
    scenes = sorted({r["scene"] for r in rows})
    jod = "jod" in rows[0]  # left out by bench --no-jod (and in runs before it)
    lines = [f"Each method at σ = {sigma:g} (the same number of shaded samples, W·H/σ²), against full." +
             (" JOD: FovVideoVDP, both eyes (docs/bench.md)." if jod else ""), "",
             "| scene | " + " | ".join(f"{m} FPSNR / SSIM" + (" / JOD" if jod else "") for m in methods) + " |",
             "|---|" + "---|" * len(methods)]
    sums = {m: [0.0, 0.0, 0, 0.0] for m in methods}
    tail = lambda v: f" / {v:.2f}" if jod else ""  # noqa: E731
    for scene in scenes:
        cells = []
        for m in methods:
            r = [x for x in rows if x["scene"] == scene and x["method"] == m and abs(num(x["sigma"]) - sigma) < 1e-9]
            if not r:
                cells.append("—")
                continue
            f, s = num(r[0]["fpsnr_db"]), num(r[0]["ssim"])
            sums[m][0] += f
            sums[m][1] += s
            sums[m][2] += 1
            j = num(r[0]["jod"]) if jod else 0.0
            sums[m][3] += j
            cells.append(f"{f:.2f} / {s:.3f}" + tail(j))
        lines.append(f"| {scene} | " + " | ".join(cells) + " |")
    lines.append("| **mean** | " + " | ".join(
        f"**{sums[m][0] / sums[m][2]:.2f} / {sums[m][1] / sums[m][2]:.3f}{tail(sums[m][3] / sums[m][2])}**" if sums[m][2] else "—"
        for m in methods) + " |")
    chart_files.write_text(out, "\n".join(lines) + "\n")


def main():
    d = sys.argv[1]
    rows = read(os.path.join(d, "bench.csv"))
    settings = run_settings.settings_text(run_settings.read_summary(d), sorted({r["scene"] for r in rows}))
    pareto(rows, os.path.join(d, "pareto.png"), settings=settings)
    cost = "shaded samples / full (theoretical cost)"
    pareto(rows, os.path.join(d, "quality_cost.png"), "cost", cost, "quality against shading cost", settings=settings)
    if rows and "jod" in rows[0]:  # left out by bench --no-jod (and in runs before it)
        pareto(rows, os.path.join(d, "jod_cost.png"), "cost", cost, "JOD against shading cost", JOD, settings=settings)
    table(rows, os.path.join(d, "table.md"))
    autos = []
    if os.path.exists(os.path.join(d, "bench.json")):
        with open(os.path.join(d, "bench.json")) as f:
            autos = json.load(f).get("auto_f", [])
    if os.path.exists(os.path.join(d, "fgrid.csv")):
        fgrid(read(os.path.join(d, "fgrid.csv")), autos, os.path.join(d, "fgrid.png"))
    if os.path.exists(os.path.join(d, "flicker.csv")):
        flicker(read(os.path.join(d, "flicker.csv")), os.path.join(d, "flicker.png"))
    if os.path.exists(os.path.join(d, "stability.csv")):
        stability(read(os.path.join(d, "stability.csv")), os.path.join(d, "stability.png"))
    if os.path.exists(os.path.join(d, "rotation.csv")):
        rotation(read(os.path.join(d, "rotation.csv")), os.path.join(d, "rotation.png"))


if __name__ == "__main__":
    chart_files.run(main)
