#!/usr/bin/env python3
"""A gaze log or a fovea trace over time (`foveal log plot`, docs/gaze-log.md):
gaze x and y per eye, the tracker's state and the blinks, and the markers.

  log_chart.py FILE OUT.png [--trace TRACE] [--start S] [--end S]

FILE is a native gaze log (raw gaze in degrees, validity and eye openness; blinks are
the runs where neither eye has a direction, classified as `foveal log validate` does) or
a fovea trace (foveald's trace.csv, `foveal replay --trace`: the gaze pipeline's output
in viewport pixels and its state per eye). --trace adds a trace of the same log (its
times count from the log's first sample, as replay writes them): the filter output
beside the raw gaze. Exit 0 written, 2 bad input (one line naming file, line, column),
1 could not write."""
import argparse
import os
import sys

import chart_files
import gaze_files

plt = chart_files.pyplot()

EYE_COLOURS = {"left": "tab:blue", "right": "tab:orange"}
RUN_COLOURS = {"blink": "tab:purple", "loss": "0.55", "dropout": "tab:olive"}
STATE_LEVEL = {s: i for i, s in enumerate(gaze_files.STATES)}


def window(t, start, end):
    """Indices of the samples in [start, end] (seconds from the first)."""
    return [i for i, x in enumerate(t) if (start is None or x >= start) and (end is None or x <= end)]


def pick(values, idx):
    return [values[i] for i in idx]


def shade(axes, runs, colour, label):
    for k, (a, b) in enumerate(runs):
        for j, ax in enumerate(axes):
            ax.axvspan(a, b, color=colour, alpha=0.18, linewidth=0, label=label if k == 0 and j == 0 else None)


def mark(axes, markers, start, end):
    for t, text in markers:
        if (start is not None and t < start) or (end is not None and t > end):
            continue
        for ax in axes:
            ax.axvline(t, color="0.3", linestyle="--", linewidth=0.7)
        axes[0].annotate(text[:40], (t, 1.0), xycoords=axes[0].get_xaxis_transform(), xytext=(2, 2), textcoords="offset points",
                         fontsize=6, rotation=30, ha="left", va="bottom")


def log_panels(ax_x, ax_y, ax_state, log, idx):
    t = pick(log["t"], idx)
    for e in gaze_files.EYES:
        eye = log[e]
        # None (no direction) breaks the line: a blink is a gap, not a jump to 0.
        ax_x.plot(t, [v if v is not None else float("nan") for v in pick(eye["x_deg"], idx)], color=EYE_COLOURS[e], linewidth=0.8,
                  label=f"{e} eye")
        ax_y.plot(t, [v if v is not None else float("nan") for v in pick(eye["y_deg"], idx)], color=EYE_COLOURS[e], linewidth=0.8,
                  label=f"{e} eye")
        ax_state.plot(t, [v if v is not None else float("nan") for v in pick(eye["openness"], idx)], color=EYE_COLOURS[e],
                      linewidth=0.8, label=f"{e} eye openness")
        # Validity as a tick row under the openness: a bar where the eye has no direction.
        y0 = -0.12 if e == "left" else -0.24
        bad = [x for x, v in zip(t, pick(eye["valid"], idx)) if not v]
        ax_state.scatter(bad, [y0] * len(bad), marker="|", s=30, color=EYE_COLOURS[e], label=f"{e}: no direction")
    ax_x.set_ylabel("gaze x (degrees,\n+ right)")
    ax_y.set_ylabel("gaze y (degrees,\n+ up)")
    ax_state.set_ylabel("tracker: eye openness\n(0 closed, 1 open)")
    ax_state.set_ylim(-0.32, 1.08)


def trace_panels(ax_x, ax_y, ax_state, trace, idx):
    t = pick(trace["t"], idx)
    for e in gaze_files.EYES:
        eye = trace[e]
        ax_x.plot(t, pick(eye["x_px"], idx), color=EYE_COLOURS[e], linewidth=0.8, label=f"{e} eye fovea")
        ax_y.plot(t, pick(eye["y_px"], idx), color=EYE_COLOURS[e], linewidth=0.8, label=f"{e} eye fovea")
        offset = -0.12 if e == "left" else 0.12
        ax_state.step(t, [STATE_LEVEL[s] + offset for s in pick(eye["state"], idx)], where="post", color=EYE_COLOURS[e],
                      linewidth=0.9, label=f"{e} eye")
    ax_x.set_ylabel("filtered fovea x\n(viewport px)")
    ax_y.set_ylabel("filtered fovea y\n(viewport px, down)")
    ax_y.invert_yaxis()  # pixel y grows downwards: up on the plot is up in the view
    ax_state.set_yticks(range(len(gaze_files.STATES)))
    ax_state.set_yticklabels(gaze_files.STATES)
    ax_state.set_ylabel("pipeline state")


def draw(path, out, trace_path=None, start=None, end=None):
    kind = gaze_files.kind_of(path)
    log = gaze_files.read_log(path) if kind == "log" else None
    trace = gaze_files.read_trace(trace_path if trace_path else path) if kind == "trace" or trace_path else None
    if kind == "trace" and trace_path:
        raise gaze_files.InputError(f"{path}: --trace goes with a gaze log; this file is itself a trace")
    if trace_path and gaze_files.kind_of(trace_path) != "trace":
        raise gaze_files.InputError(f"{trace_path}: line 1: --trace expects a fovea trace (foveald's trace.csv, replay --trace)")
    names = ["x", "y"] * ((log is not None) + (trace is not None)) + ["state"] + (["state2"] if log and trace else [])
    fig, axes = plt.subplots(len(names), 1, figsize=(12, 1.9 * len(names) + 1.2), sharex=True, squeeze=False)
    axes = [a[0] for a in axes]
    t_all, markers, runs = [], [], []
    if log is not None:
        idx = window(log["t"], start, end)
        if not idx:
            raise gaze_files.InputError(f"{path}: no samples between {start} s and {end} s")
        log_panels(axes[0], axes[1], axes[-2] if trace else axes[-1], log, idx)
        t_all = pick(log["t"], idx)
        markers += log["markers"]
        runs = gaze_files.invalid_runs(log["t"], log["left"]["valid"], log["right"]["valid"], log["rate_hz"])
    if trace is not None:
        idx = window(trace["t"], start, end)
        if not idx:
            raise gaze_files.InputError(f"{trace_path or path}: no rows between {start} s and {end} s")
        first = 2 if log is not None else 0
        trace_panels(axes[first], axes[first + 1], axes[-1], trace, idx)
        t_all = t_all or pick(trace["t"], idx)
        if log is None:  # the trace's own blinks and losses (a log's are its invalid runs)
            for state in ("blink", "lost"):
                both = gaze_files.state_runs(trace["t"], [a if a == b else "" for a, b in zip(trace["left"]["state"], trace["right"]["state"])], state)
                runs += [(a, b, "blink" if state == "blink" else "loss") for a, b in both]
        markers += [m for m in trace["markers"] if m not in markers]
    lo, hi = t_all[0], t_all[-1]
    blinks = sum(1 for a, b, k in runs if k == "blink" and b >= lo and a <= hi)  # those in the window shown
    for k in ("blink", "loss", "dropout"):
        shade(axes, [(max(a, lo), min(b, hi)) for a, b, kk in runs if kk == k and b >= lo and a <= hi], RUN_COLOURS[k],
              {"blink": "blink (both eyes, 50-500 ms)", "loss": "lost (> 500 ms)", "dropout": "dropout (< 50 ms)"}[k])
    mark(axes, markers, start, end)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper right", ncol=2)
    axes[-1].set_xlabel("time from the first sample (s)")
    axes[0].set_xlim(lo, hi if hi > lo else lo + 1e-3)
    what = "gaze log" if log is not None else "fovea trace"
    extra = f" + trace {os.path.basename(trace_path)}" if trace_path else ""
    source = f", source {log['meta']['source']}" if log is not None and "source" in log["meta"] else ""
    rate = f", {log['rate_hz']:g} Hz" if log is not None else ""
    fig.suptitle(f"{os.path.basename(path)} ({what}{extra}{source}{rate}): {len(t_all)} samples, "
                 f"{t_all[-1] - t_all[0]:.2f} s shown, {blinks} blink{'' if blinks == 1 else 's'}", fontsize=10)
    fig.tight_layout()
    chart_files.save_figure(fig, out, dpi=100)
    return {"samples": len(t_all), "blinks": blinks, "markers": len(markers), "panels": len(axes)}


def main(argv):
    p = argparse.ArgumentParser(prog="log_chart.py", description=__doc__.split("\n")[0])
    p.add_argument("file")
    p.add_argument("out")
    p.add_argument("--trace")
    p.add_argument("--start", type=float)
    p.add_argument("--end", type=float)
    a = p.parse_args(argv)
    if a.start is not None and a.end is not None and a.end <= a.start:
        print(f"log_chart.py: --end {a.end:g} is not after --start {a.start:g}", file=sys.stderr)
        return 2
    for path in [a.file] + ([a.trace] if a.trace else []):
        if not os.path.isfile(path):
            print(f"log_chart.py: {path}: {'not a regular file' if os.path.exists(path) else 'no such file'}", file=sys.stderr)
            return 2
    try:
        draw(a.file, a.out, a.trace, a.start, a.end)
    except gaze_files.InputError as e:
        print(f"log_chart.py: {e}", file=sys.stderr)
        return 2
    except UnicodeDecodeError as e:
        print(f"log_chart.py: {a.file}: not UTF-8 text ({e.reason})", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(chart_files.run(lambda: main(sys.argv[1:])))
