"""Reads the two per-sample files foveal writes, for the time plot (log_chart.py):
a native gaze log (docs/gaze-log.md, v1 or v2: `foveal import`, `record`, `synth`) and a
fovea trace (foveald's trace.csv, `foveal replay --trace`: the gaze pipeline's output).
Every row is checked as it is read; a bad one raises InputError naming the file, the
line and the column, and nothing is drawn."""
import math

EYES = ("left", "right")
_EYE_FIELDS = ("valid", "dir_x", "dir_y", "dir_z", "origin_x_mm", "origin_y_mm", "origin_z_mm", "pupil_mm", "openness")
LOG_COLUMNS = (["t_ns"] + [f"{e}_{f}" for e in EYES for f in _EYE_FIELDS] +
               ["combined_valid"] + [f"combined_{f}" for f in _EYE_FIELDS[1:7]])
LOG_V2_COLUMNS = LOG_COLUMNS + ["head_valid", "head_x_m", "head_y_m", "head_z_m", "head_qw", "head_qx", "head_qy", "head_qz"]
TRACE_COLUMNS = ["t_ns"] + [f"{e}_{f}" for e in EYES for f in ("state", "x_px", "y_px", "confidence")]
STATES = ("fixation", "pursuit", "saccade", "blink", "lost")
VALID_DIRECTION, VALID_OPENNESS = 1, 8  # docs/conventions.md's validity bits
MAGIC = "# foveal-gaze-log v"


class InputError(ValueError):
    pass


def _where(path, line, column=None):
    return f"{path}: line {line}" + (f": column {column}" if column else "")


def _int(text, path, line, column):
    try:
        return int(text)
    except ValueError:
        raise InputError(f"{_where(path, line, column)}: '{text[:40]}' is not an integer") from None


def _float(text, path, line, column):
    try:
        v = float(text)
    except ValueError:
        raise InputError(f"{_where(path, line, column)}: '{text[:40]}' is not a number") from None
    if not math.isfinite(v):
        raise InputError(f"{_where(path, line, column)}: {text} is not finite")
    return v


def _marker(fields, path, line):
    """A `#mark,T_NS,TEXT` row: (t_ns, text)."""
    if len(fields) < 3:
        raise InputError(f"{_where(path, line)}: a marker row is '#mark,T_NS,TEXT'")
    return _int(fields[1], path, line, "T_NS"), ",".join(fields[2:])


def kind_of(path):
    """'log' or 'trace', from the first line; InputError for anything else."""
    try:
        with open(path, encoding="utf-8") as f:
            first = f.readline().rstrip("\n")
    except UnicodeDecodeError:
        raise InputError(f"{_where(path, 1)}: not UTF-8 text (not a gaze log or a trace)") from None
    if first.startswith(MAGIC):
        return "log"
    if first.split(",") == TRACE_COLUMNS:
        return "trace"
    raise InputError(f"{_where(path, 1)}: neither a native gaze log ('{MAGIC}1' or v2) nor a fovea trace "
                     f"('{','.join(TRACE_COLUMNS[:3])},...'): '{first[:60]}'")


def read_log(path):
    """{'t': seconds from the first sample, per eye 'x_deg', 'y_deg' (None where the
    direction is invalid), 'openness', 'valid', plus 'markers', 'rate_hz', 'meta'}."""
    out = {"t": [], "markers": [], "meta": {}, "rate_hz": None}
    for e in EYES:
        out[e] = {"x_deg": [], "y_deg": [], "openness": [], "valid": []}
    t0 = prev = None
    columns = None
    with open(path, encoding="utf-8") as f:
        for line, text in enumerate(f, 1):
            text = text.rstrip("\n")
            if line == 1:
                version = text[len(MAGIC):] if text.startswith(MAGIC) else ""
                if version not in ("1", "2"):
                    raise InputError(f"{_where(path, 1)}: expected '{MAGIC}1' or '{MAGIC}2', not '{text[:60]}'")
                continue
            if columns is None and text.startswith("# "):
                key, sep, value = text[2:].partition("=")
                if not sep:
                    raise InputError(f"{_where(path, line)}: a header line is '# key=value'")
                out["meta"][key] = value
                continue
            if columns is None:
                want = LOG_COLUMNS if version == "1" else LOG_V2_COLUMNS
                if text.split(",") != want:
                    raise InputError(f"{_where(path, line)}: not the v{version} column row ({len(want)} columns from 't_ns')")
                if "rate_hz" not in out["meta"]:
                    raise InputError(f"{_where(path, line)}: the header has no rate_hz")
                out["rate_hz"] = _float(out["meta"]["rate_hz"], path, line, "rate_hz")
                columns = {name: i for i, name in enumerate(want)}
                continue
            fields = text.split(",")
            if fields[0] == "#mark":
                out["markers"].append(_marker(fields, path, line))
                continue
            if len(fields) != len(columns):
                raise InputError(f"{_where(path, line)}: {len(fields)} fields, expected {len(columns)}")
            t = _int(fields[0], path, line, "t_ns")
            if prev is not None and t <= prev:
                raise InputError(f"{_where(path, line, 't_ns')}: {t} is not after the row before ({prev})")
            prev = t
            t0 = t if t0 is None else t0
            out["t"].append((t - t0) / 1e9)
            for e in EYES:
                name = f"{e}_valid"
                bits = _int(fields[columns[name]], path, line, name)
                if not 0 <= bits <= 15:
                    raise InputError(f"{_where(path, line, name)}: {bits} is not a validity mask 0-15")
                eye = out[e]
                eye["valid"].append(bool(bits & VALID_DIRECTION))
                if bits & VALID_DIRECTION:
                    d = [_float(fields[columns[f"{e}_dir_{a}"]], path, line, f"{e}_dir_{a}") for a in "xyz"]
                    # Eye frame: x right, y up, -z forward (docs/conventions.md).
                    eye["x_deg"].append(math.degrees(math.atan2(d[0], -d[2])))
                    eye["y_deg"].append(math.degrees(math.atan2(d[1], -d[2])))
                else:
                    eye["x_deg"].append(None)
                    eye["y_deg"].append(None)
                eye["openness"].append(_float(fields[columns[f"{e}_openness"]], path, line, f"{e}_openness")
                                       if bits & VALID_OPENNESS else None)
    if columns is None or not out["t"]:
        raise InputError(f"{path}: no samples")
    out["markers"] = [((m - t0) / 1e9, text) for m, text in out["markers"]]
    return out


def read_trace(path):
    """{'t': seconds from the first row, per eye 'x_px', 'y_px', 'state', 'confidence',
    plus 'markers' (trace times are already from the first sample)}."""
    out = {"t": [], "markers": []}
    for e in EYES:
        out[e] = {"x_px": [], "y_px": [], "state": [], "confidence": []}
    prev = None
    with open(path, encoding="utf-8") as f:
        for line, text in enumerate(f, 1):
            text = text.rstrip("\n")
            fields = text.split(",")
            if line == 1:
                if fields != TRACE_COLUMNS:
                    raise InputError(f"{_where(path, 1)}: not a fovea trace's column row ('{','.join(TRACE_COLUMNS[:3])},...')")
                continue
            if fields[0] == "#mark":
                t, label = _marker(fields, path, line)
                out["markers"].append((t / 1e9, label))
                continue
            if len(fields) != len(TRACE_COLUMNS):
                raise InputError(f"{_where(path, line)}: {len(fields)} fields, expected {len(TRACE_COLUMNS)}")
            t = _int(fields[0], path, line, "t_ns")
            if prev is not None and t < prev:
                raise InputError(f"{_where(path, line, 't_ns')}: {t} is before the row before ({prev})")
            prev = t
            out["t"].append(t / 1e9)
            for i, e in enumerate(EYES):
                base = 1 + 4 * i
                state = fields[base]
                if state not in STATES:
                    raise InputError(f"{_where(path, line, f'{e}_state')}: '{state[:40]}' is not one of {', '.join(STATES)}")
                eye = out[e]
                eye["state"].append(state)
                eye["x_px"].append(_float(fields[base + 1], path, line, f"{e}_x_px"))
                eye["y_px"].append(_float(fields[base + 2], path, line, f"{e}_y_px"))
                eye["confidence"].append(_float(fields[base + 3], path, line, f"{e}_confidence"))
    if not out["t"]:
        raise InputError(f"{path}: no samples")
    return out


def invalid_runs(t, valid_left, valid_right, rate_hz=None):
    """Runs where neither eye has a direction: (start_s, end_s, kind) with kind dropout
    (< 50 ms), blink (50-500 ms) or loss, as `foveal log validate` classifies them. A run
    lasts until the next valid sample (or one sample period past the last)."""
    runs, start = [], None
    period = 1.0 / rate_hz if rate_hz else 0.0
    for i, (tl, vl, vr) in enumerate(zip(t, valid_left, valid_right)):
        if not (vl or vr):
            start = i if start is None else start
        elif start is not None:
            runs.append((t[start], tl))
            start = None
    if start is not None:
        runs.append((t[start], t[-1] + period))
    return [(a, b, "dropout" if (b - a) * 1e3 < 50 else "blink" if (b - a) * 1e3 <= 500 else "loss") for a, b in runs]


def state_runs(t, states, state):
    """Runs of one trace state: (start_s, end_s)."""
    runs, start = [], None
    for i, s in enumerate(states):
        if s == state and start is None:
            start = i
        elif s != state and start is not None:
            runs.append((t[start], t[i]))
            start = None
    if start is not None:
        runs.append((t[start], t[-1]))
    return runs
