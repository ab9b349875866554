"""The run's settings as a chart footer, read from the run's own summary (bench.json,
beside bench.csv): output size, display model, pipeline, timed frames and warm-up,
fovea, renderer, JOD's panel. A setting the file does not hold (runs from before it was
recorded) is said to be unrecorded, never guessed."""
import json
import os
import textwrap


def read_summary(folder, name="bench.json"):
    """The summary object, or None when the file is not there. A file that is there but
    is not a JSON object is an error naming it."""
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    with open(path) as f:
        try:
            j = json.load(f)
        except ValueError as e:
            raise ValueError(f"{path}: not JSON ({e})") from e
    if not isinstance(j, dict):
        raise ValueError(f"{path}: expected a JSON object")
    return j


def _pair(v, sep):
    return sep.join(f"{x:g}" if isinstance(x, (int, float)) else str(x) for x in v) if isinstance(v, list) else str(v)


def settings_text(summary, scenes, source="bench.json"):
    """One or two lines: what was rendered, how it was timed, on what. `scenes`: the
    scenes of the chart (from bench.csv)."""
    if summary is None:
        return f"settings: no {source} beside the table (scenes: {', '.join(scenes)})"
    missing = "not recorded"
    size = summary.get("size")
    frames = summary.get("frames", missing)
    warmup = summary.get("warmup", missing)
    parts = [f"scenes: {', '.join(scenes)}",
             f"output {_pair(size, '×')} side by side" if size else f"output size {missing}",
             f"display {summary.get('display', missing)}",
             f"pipeline {summary.get('pipeline', missing)}",
             f"{frames} timed frame{'' if frames == 1 else 's'} per point (median)" + (f" after {warmup} warm-up" if warmup != missing else f", warm-up {missing}"),
             f"fovea {_pair(summary['fovea'], ',')}" if "fovea" in summary else f"fovea {missing}"]
    jod = summary.get("jod")
    if isinstance(jod, dict):
        parts.append(f"JOD: FovVideoVDP {jod.get('release', '?')}, {jod.get('peak_cd_m2', '?')}/{jod.get('black_cd_m2', '?')} cd/m²")
    return f"{source}: " + "; ".join(parts) + f"; renderer: {summary.get('renderer', missing)}"


def add_footer(fig, text, fontsize=7):
    """The text under the panels, left-aligned. Returns the share of the figure's height
    it takes: lay the panels out above it (tight_layout(rect=(0, share, 1, 1)))."""
    width = max(40, int(fig.get_figwidth() * 72 / (fontsize * 0.56)))  # characters a line holds
    text = "\n".join(textwrap.fill(line, width, subsequent_indent="  ") for line in text.split("\n"))
    lines = text.count("\n") + 1
    share = (lines * fontsize * 1.45 + 6) / 72 / fig.get_figheight()
    fig.text(0.005, 0.004, text, fontsize=fontsize, ha="left", va="bottom", color="0.25")
    return share
