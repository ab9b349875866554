"""foveal's files as NumPy arrays: the native gaze log (docs/gaze-log.md) and the fovea
trace that foveald and `foveal replay --trace` write (docs/daemon.md).

Both readers check the format the way foveal does and raise FormatError naming the file,
the line and the column. read_gaze_log accepts exactly the logs foveal's own reader
(`foveal log validate`, runtime/core gaze_log_reader.cpp) accepts: the same number syntax
and 32-bit float range, validity masks and the fields they cover, unit head quaternions,
timestamps in [-2^62, 2^62) that increase strictly, marker rows in time order; the
folder tests/sdk/gaze_log_cases holds the cases both are checked against.
"""
import io
import math
import os
import re
import stat
from dataclasses import dataclass, field
from typing import Dict, List, Tuple

import numpy as np

from . import _gaze_log_rows

_EYE_FIELDS = ("_valid", "_dir_x", "_dir_y", "_dir_z", "_origin_x_mm", "_origin_y_mm", "_origin_z_mm", "_pupil_mm",
               "_openness")
_COMBINED = ("combined_valid", "combined_dir_x", "combined_dir_y", "combined_dir_z", "combined_origin_x_mm",
             "combined_origin_y_mm", "combined_origin_z_mm")
_HEAD = ("head_valid", "head_x_m", "head_y_m", "head_z_m", "head_qw", "head_qx", "head_qy", "head_qz")
_TRACE_COLUMNS = ("t_ns", "left_state", "left_x_px", "left_y_px", "left_confidence", "right_state", "right_x_px",
                  "right_y_px", "right_confidence")
STATE_NAMES = ("fixation", "saccade", "pursuit", "blink", "lost")  # codes 0..4, as in foveal.FIXATION..LOST
_STATE_CODES = {name: str(code) for code, name in enumerate(STATE_NAMES)}


def gaze_log_columns(version: int) -> Tuple[str, ...]:
    """The column row of a native gaze log of this version (1 or 2)."""
    cols = ("t_ns",) + tuple(e + f for e in ("left", "right") for f in _EYE_FIELDS) + _COMBINED
    return cols + _HEAD if version >= 2 else cols


class FormatError(ValueError):
    """A file foveal would refuse: str() is 'PATH:LINE: what is wrong'."""

    def __init__(self, path: str, line: int, message: str):
        super().__init__(f"{path}:{line}: {message}")
        self.path, self.line, self.message = path, line, message


@dataclass
class GazeLog:
    """A native gaze log: samples[column] is one array per column (t_ns int64, *_valid
    uint8, the rest float64 with NaN where the field is empty)."""
    path: str
    version: int
    rate_hz: float
    meta: Dict[str, str]                      # every '# key=value' line, rate_hz included
    samples: np.ndarray                       # structured, one field per column
    markers: List[Tuple[int, str]] = field(default_factory=list)  # (t_ns, text)

    def __len__(self) -> int:
        return len(self.samples)

    def __getitem__(self, column: str) -> np.ndarray:
        return self.samples[column]


@dataclass
class Trace:
    """A fovea trace: t_ns from the first sample (int64), per eye state (uint8 codes,
    STATE_NAMES), x_px and y_px (viewport pixels, origin top-left) and confidence."""
    path: str
    samples: np.ndarray
    markers: List[Tuple[int, str]] = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.samples)

    def __getitem__(self, column: str) -> np.ndarray:
        return self.samples[column]


_MAX_LINE_BYTES = 1 << 20  # LineReader's limit
_MAX_TIME_NS = 1 << 62     # kMaxGazeLogTimeNs: timestamps are in [-2^62, 2^62)
_MAX_MARKER_BYTES = 256    # kMaxMarkerBytes
_MAX_MARKERS = 100_000     # kMaxGazeLogMarkers
_MAX_RATE_HZ = 100_000.0


def _read_bytes(path: str) -> bytes:
    """The file's bytes; a FIFO, device, socket or directory is refused before anything is
    read (opened non-blocking, as foveal's read_file does), so it cannot hang."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as e:
        raise FormatError(path, 1, f"cannot open: {e.strerror}") from None
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise FormatError(path, 1, "not a regular file (a FIFO, device, socket or directory)")
        return f.read()


def _read_lines(path: str) -> List[str]:
    data = _read_bytes(path)
    if not data:
        raise FormatError(path, 1, "file is empty")
    if data.startswith(b"\xef\xbb\xbf"):
        raise FormatError(path, 1, "starts with a UTF-8 byte-order mark; foveal's files have none")
    # foveal reads bytes: text that is not UTF-8 (a file name in a header, say) is kept,
    # its bytes as surrogate escapes (os.fsdecode's convention).
    text = data.decode("utf-8", errors="surrogateescape")
    if "\r\n" in text:
        raise FormatError(path, text[:text.index("\r\n")].count("\n") + 1, "line ends in CRLF; foveal's files use LF")
    if not text.endswith("\n"):
        raise FormatError(path, text.count("\n") + 1, "truncated last row (no line end)")
    lines = text[:-1].split("\n")
    if len(data) > _MAX_LINE_BYTES:
        for number, line in enumerate(lines, start=1):
            if len(line.encode("utf-8", errors="surrogateescape")) > _MAX_LINE_BYTES:
                raise FormatError(path, number, f"line longer than {_MAX_LINE_BYTES} bytes")
    return lines


def _marker(path: str, number: int, line: str) -> Tuple[int, str]:
    if not line.startswith("#mark,"):
        raise FormatError(path, number, "a row starting with '#' is a marker row, '#mark,T_NS,TEXT'")
    t, _, text = line[len("#mark,"):].partition(",")
    if not re.fullmatch(r"-?[0-9]+", t):
        raise FormatError(path, number, f"t_ns: '{t}' is not an integer")
    if not text:
        raise FormatError(path, number, "t_ns: the marker row has no text")
    return int(t), text


def _check_columns(path: str, number: int, got: str, expected: Tuple[str, ...]) -> None:
    names = got.split(",")
    for i, want in enumerate(expected):
        if i >= len(names):
            raise FormatError(path, number, f"column row: column '{want}' is missing")
        if names[i] != want:
            raise FormatError(path, number, f"column row: column {i + 1} is '{names[i]}', expected '{want}'")
    if len(names) > len(expected):
        raise FormatError(path, number, f"column row: unexpected extra column '{names[len(expected)]}'")


def _locate_bad_field(path: str, lines: List[str], numbers: List[int], columns: Tuple[str, ...], optional) -> None:
    """The slow path, after the fast parse failed: finds the first bad field and raises."""
    for number, line in zip(numbers, lines):
        fields = line.split(",")
        if len(fields) < len(columns):
            raise FormatError(path, number, f"{columns[len(fields)]}: missing ({len(fields)} of {len(columns)} fields)")
        if len(fields) > len(columns):
            raise FormatError(path, number, f"{len(fields)} fields, the column row has {len(columns)}")
        for name, value in zip(columns, fields):
            if value == "" and optional(name):
                continue
            try:
                x = float(value)
            except ValueError:
                raise FormatError(path, number, f"{name}: '{value}' is not a number") from None
            if not np.isfinite(x):
                raise FormatError(path, number, f"{name}: '{value}' is not finite")
    raise FormatError(path, numbers[0] if numbers else 1, "unreadable rows")


_NUMBER_BYTES = b"0123456789.,+-eE\n"


def _parse_rows(path: str, lines: List[str], numbers: List[int], columns: Tuple[str, ...], optional):
    """All rows as a float64 matrix (NaN where an optional field is empty), and t_ns as int64."""
    if not lines:
        return np.zeros((0, len(columns))), np.zeros(0, dtype=np.int64)
    block = "\n".join(lines) + "\n"
    try:  # only number characters: no 'nan' or 'inf' may pass for a value
        clean = not block.encode("ascii").translate(None, _NUMBER_BYTES)
    except UnicodeEncodeError:
        clean = False
    if not clean:
        _locate_bad_field(path, lines, numbers, columns, optional)
    filled = block.replace(",,", ",nan,").replace(",,", ",nan,").replace(",\n", ",nan\n")  # empty fields: NaN
    try:
        values = np.loadtxt(io.StringIO(filled), delimiter=",", dtype=np.float64, ndmin=2)
    except ValueError:
        _locate_bad_field(path, lines, numbers, columns, optional)
    if values.shape[1] != len(columns) or np.isnan(values[:, 0]).any():
        _locate_bad_field(path, lines, numbers, columns, optional)
    # An empty field is allowed only where the format allows it.
    for j, name in enumerate(columns):
        if not optional(name):
            empty = np.isnan(values[:, j])
            if empty.any():
                raise FormatError(path, numbers[int(np.argmax(empty))], f"{name}: missing")
    # Integers below 2^53 read exactly as doubles; larger ones are parsed again as integers.
    if np.all(np.abs(values[:, 0]) < 2.0**53):
        t_ns = values[:, 0].astype(np.int64)
    else:
        t_ns = np.array([line[:line.find(",")] for line in lines], dtype=np.int64)
    if not np.array_equal(t_ns.astype(np.float64), values[:, 0]):
        _locate_bad_field(path, lines, numbers, columns, optional)
    return values, t_ns


def _split_markers(path: str, lines: List[str], first_number: int):
    """Sample rows (their texts and line numbers) and marker rows [(t_ns, text)]."""
    if not any(line.startswith("#") for line in lines):
        return lines, range(first_number, first_number + len(lines)), []
    rows, numbers, markers = [], [], []
    for number, line in enumerate(lines, start=first_number):
        if line.startswith("#"):
            markers.append(_marker(path, number, line))
        else:
            rows.append(line)
            numbers.append(number)
    return rows, numbers, markers


def _structured(columns: Tuple[str, ...], values: np.ndarray, t_ns: np.ndarray, kinds) -> np.ndarray:
    out = np.empty(len(t_ns), dtype=[(name, kinds(name)) for name in columns])
    out["t_ns"] = t_ns
    for j, name in enumerate(columns[1:], start=1):
        out[name] = values[:, j]
    return out


def _gaze_header(path: str, lines: List[str]):
    """(version, rate_hz, meta, index of the column row), as foveal's reader takes them:
    every line starting with '#' after the first is a '# key=value' (spaces after the '#'
    optional), up to the first line that does not."""
    m = re.fullmatch(r"# foveal-gaze-log v(-?[0-9]+)", lines[0])
    if not m:
        raise FormatError(path, 1, "expected '# foveal-gaze-log v1' or '... v2'")
    version = int(m.group(1))
    if version not in (1, 2):
        raise FormatError(path, 1, f"format version: v{version} is not supported (this reader reads v1 and v2)")
    meta: Dict[str, str] = {}
    i = 1
    while i < len(lines) and lines[i].startswith("#"):
        key, eq, value = lines[i][1:].lstrip(" ").partition("=")
        if not eq or not key:
            raise FormatError(path, i + 1, "header: expected '# key=value'")
        meta[key] = value
        if key == "rate_hz":
            rate = value[1:] if value.startswith("+") and not value.startswith("+-") else value
            ok = re.fullmatch(_gaze_log_rows.FLOAT, rate) is not None
            rate_hz = float(rate) if ok else float("nan")
            if not (math.isfinite(rate_hz) and 0 < rate_hz <= _MAX_RATE_HZ):
                raise FormatError(path, i + 1, f"rate_hz: '{value}' is not a rate in (0, 100000] Hz")
        i += 1
    if i >= len(lines):
        raise FormatError(path, i + 1, "header: the column row is missing")
    if "rate_hz" not in meta:
        raise FormatError(path, i + 1, "header: rate_hz is required")
    return version, float(meta["rate_hz"].lstrip("+")), meta, i


def _check_markers(path: str, markers, marker_lines, samples_before, t_ns: np.ndarray, numbers) -> None:
    """Marker rows as foveal takes them: text of 1..256 bytes without control characters,
    times in [-2^62, 2^62), no earlier than the row before them; and no sample earlier
    than the marker before it."""
    if len(markers) > _MAX_MARKERS:
        raise FormatError(path, marker_lines[_MAX_MARKERS], f"more than {_MAX_MARKERS} markers; a gaze log holds at most that many")
    previous = None
    for (t, text), number, n in zip(markers, marker_lines, samples_before):
        size = len(text.encode("utf-8", errors="surrogateescape"))
        if size > _MAX_MARKER_BYTES:
            raise FormatError(path, number, f"text: the text has {size} bytes; at most {_MAX_MARKER_BYTES}")
        bad = next((k for k, ch in enumerate(text) if ord(ch) < 0x20 or ord(ch) == 0x7F), None)
        if bad is not None:
            raise FormatError(path, number, f"text: character {bad + 1} of the text is a control character")
        if not -_MAX_TIME_NS <= t < _MAX_TIME_NS:
            raise FormatError(path, number, f"t_ns: marker time {t} is out of range (timestamps are in [-2^62, 2^62) ns)")
        before = [x for x in (previous, int(t_ns[n - 1]) if n > 0 else None) if x is not None]
        if before and t < max(before):
            raise FormatError(path, number, f"t_ns: marker time {t} is earlier than the row before it ({max(before)})")
        if n < len(t_ns) and t_ns[n] < t:
            raise FormatError(path, numbers[n], f"t_ns: {t_ns[n]} is earlier than the marker before it ({t})")
        previous = t


def read_gaze_log(path: str) -> GazeLog:
    """Reads a native gaze log (v1 or v2) into NumPy arrays; raises FormatError. Accepts
    exactly what foveal's reader (`foveal log validate`) accepts."""
    lines = _read_lines(path)
    version, rate_hz, meta, i = _gaze_header(path, lines)
    columns = gaze_log_columns(version)
    _check_columns(path, i + 1, lines[i], columns)

    rows, numbers, markers, marker_lines, samples_before = [], [], [], [], []
    if not any(line.startswith("#") for line in lines[i + 1:]):  # the common case: no marker rows
        rows, numbers = lines[i + 1:], list(range(i + 2, len(lines) + 1))
    for number, line in enumerate(lines[i + 1:] if not rows else [], start=i + 2):
        if line.startswith("#"):
            markers.append(_marker(path, number, line))
            marker_lines.append(number)
            samples_before.append(len(rows))
        else:
            rows.append(line)
            numbers.append(number)
    if not rows:
        raise FormatError(path, len(lines), "no samples: the log has a header only")

    def first_bad_row():
        for number, line in zip(numbers, rows):
            problem = _gaze_log_rows.row_problem(line.split(","), columns, version)
            if problem:
                column, what = problem
                raise FormatError(path, number, f"{column}: {what}" if column else what)
        raise FormatError(path, numbers[0], "unreadable rows")

    values, t_ns, block = None, None, ""
    if all(map(_gaze_log_rows.row_regex(version).fullmatch, rows)):
        block = "\n".join(rows) + "\n"
        filled = block.replace(",,", ",nan,").replace(",,", ",nan,").replace(",\n", ",nan\n")  # empty fields: NaN
        values = np.loadtxt(io.StringIO(filled), delimiter=",", dtype=np.float64, ndmin=2)
        try:  # exact integers: below 2^53 the doubles are, above that the text is parsed again
            t_ns = (values[:, 0].astype(np.int64) if np.all(np.abs(values[:, 0]) < 2.0**53) else
                    np.array([line[:line.find(",")] for line in rows], dtype=np.int64))
        except OverflowError:
            t_ns = None
    if t_ns is None or not _gaze_log_rows.fast_rows_ok(block, values, t_ns, version):
        first_bad_row()
    back = np.flatnonzero(np.diff(t_ns) <= 0)
    markers_checked = False
    if back.size:
        k = int(back[0]) + 1
        # A marker between the two rows may be what is wrong first, as foveal reads in file order.
        _check_markers(path, markers, marker_lines, samples_before, t_ns, numbers)
        markers_checked = True
        what = "repeats the previous timestamp" if t_ns[k] == t_ns[k - 1] else f"goes back from {t_ns[k - 1]}"
        raise FormatError(path, numbers[k], f"t_ns: {t_ns[k]} {what}")
    if not markers_checked:
        _check_markers(path, markers, marker_lines, samples_before, t_ns, numbers)
    kinds = lambda name: np.int64 if name == "t_ns" else np.uint8 if name.endswith("_valid") else np.float64  # noqa: E731
    return GazeLog(path, version, rate_hz, meta, _structured(columns, values, t_ns, kinds), markers)


def read_trace(path: str) -> Trace:
    """Reads a fovea trace (foveald's trace.csv, `foveal replay --trace`); raises FormatError."""
    lines = _read_lines(path)
    _check_columns(path, 1, lines[0], _TRACE_COLUMNS)
    rows, numbers, markers = _split_markers(path, lines[1:], 2)
    # State names to their codes, so that every field is a number.
    for k, line in enumerate(rows):
        fields = line.split(",")
        for j in (1, 5):
            if j < len(fields):
                code = _STATE_CODES.get(fields[j])
                if code is None:
                    raise FormatError(path, numbers[k], f"{_TRACE_COLUMNS[j]}: '{fields[j]}' is not a state "
                                                        f"({', '.join(STATE_NAMES)})")
                fields[j] = code
        rows[k] = ",".join(fields)
    values, t_ns = _parse_rows(path, rows, list(numbers), _TRACE_COLUMNS, lambda name: False)
    kinds = lambda name: np.int64 if name == "t_ns" else np.uint8 if name.endswith("_state") else np.float64  # noqa: E731
    return Trace(path, _structured(_TRACE_COLUMNS, values, t_ns, kinds), markers)
