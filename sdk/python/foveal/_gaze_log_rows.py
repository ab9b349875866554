"""The native gaze log's sample rows, checked exactly as foveal's reader checks them
(runtime/core/src/gaze_log_reader.cpp): the same number syntax (std::from_chars: no '+',
no 'inf'/'nan', no hex), values that fit a 32-bit float, validity masks of up to three
digits, fields present exactly where their validity bit is set, a head flag of 0 or 1 and
a unit head quaternion, integer timestamps in [-2^62, 2^62).

A fast NumPy pass decides for the whole file; only when it finds something wrong does
the exact per-row pass run, to name the first bad field."""
import math
import re
from typing import Optional, Sequence, Tuple

import numpy as np

MAX_TIME_NS = 1 << 62  # kMaxGazeLogTimeNs
QUAT_TOLERANCE = float(np.float32(1e-3))  # kUnitQuaternionTolerance (a float)

# std::from_chars's decimal syntax as foveal's fast parser takes it (at most 4 exponent digits).
FLOAT = r"-?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]{1,4})?"
INT = r"-?[0-9]+"
MASK = r"[0-9]{1,3}"
_FLOAT_RE, _INT_RE, _MASK_RE = re.compile(FLOAT), re.compile(INT), re.compile(MASK)
# The bits of a block's fields after its mask: direction xyz, origin xyz, pupil, openness.
_EYE_BITS = (1, 1, 1, 2, 2, 2, 4, 8)
_COMBINED_BITS = _EYE_BITS[:6]


def row_regex(version: int) -> "re.Pattern[str]":
    f = f"(?:{FLOAT})?"
    eye = MASK + ("," + f) * 8
    combined = MASK + ("," + f) * 6
    parts = [INT, eye, eye, combined] + (["[01]" + ("," + f) * 7] if version >= 2 else [])
    return re.compile(",".join(parts))


def float_problem(text: str) -> Optional[str]:
    """Why foveal refuses `text` as a float field, or None."""
    if not _FLOAT_RE.fullmatch(text):
        if re.fullmatch(r"[+-]?(?:inf|infinity|nan(?:\([0-9A-Za-z_]*\))?)", text, re.IGNORECASE):
            return f"'{text}' is not finite"  # from_chars reads these; foveal refuses them as values
        return f"'{text}' is not a number"
    x = float(text)
    with np.errstate(over="ignore"):
        f = np.float32(x)
    mantissa = re.split("[eE]", text)[0]
    if not math.isfinite(x) or not np.isfinite(f) or (f == 0 and re.search("[1-9]", mantissa)):
        return f"'{text}' is out of range (a 32-bit float)"
    return None


def row_problem(fields: Sequence[str], columns: Sequence[str], version: int) -> Optional[Tuple[str, str]]:
    """(column, what is wrong) for the first field foveal refuses, or None."""
    n = len(columns)
    if len(fields) < n:
        return columns[len(fields)], f"missing (row has {len(fields)} of {n} fields)"
    if len(fields) > n:
        return "", f"row has {len(fields)} fields, expected {n}"
    if not _INT_RE.fullmatch(fields[0]):
        return columns[0], f"'{fields[0]}' is not an integer"
    if not -MAX_TIME_NS <= int(fields[0]) < MAX_TIME_NS:
        return columns[0], f"{fields[0]} is out of range (timestamps are in [-2^62, 2^62) ns)"
    col = 1
    for bits, max_mask in ((_EYE_BITS, 15), (_EYE_BITS, 15), (_COMBINED_BITS, 3)):
        m = fields[col]
        if not _MASK_RE.fullmatch(m) or int(m) > max_mask:
            return columns[col], f"'{m}' is not a validity mask (0..{max_mask})"
        mask = int(m)
        col += 1
        for bit in bits:
            p = _presence_problem(fields[col], mask & bit != 0, "its validity bit")
            if p:
                return columns[col], p
            col += 1
    if version >= 2:
        flag = fields[col]
        if flag not in ("0", "1"):
            return columns[col], f"'{flag}' is not 0 or 1"
        col += 1
        for _ in range(7):
            p = _presence_problem(fields[col], flag == "1", "head_valid")
            if p:
                return columns[col], p
            col += 1
        if flag == "1":
            q = np.array([float(v) for v in fields[col - 4:col]], dtype=np.float32).astype(np.float64)
            norm = math.sqrt(float(np.sum(q * q)))
            if not abs(norm - 1.0) <= QUAT_TOLERANCE:
                return "head_qw..head_qz", f"quaternion norm {norm:.6g} is not 1 (tolerance 0.001): not a head orientation"
    return None


def _presence_problem(value: str, present: bool, bit_name: str) -> Optional[str]:
    if not present:
        return f"has a value but {bit_name} is {'clear' if bit_name.startswith('its') else '0'}" if value else None
    if not value:
        return f"empty but {bit_name} is {'set' if bit_name.startswith('its') else '1'}"
    return float_problem(value)


def fast_rows_ok(block: str, values: np.ndarray, t_ns: np.ndarray, version: int) -> bool:
    """True when every row passes row_problem, decided for all rows at once. The rows
    already match row_regex (the syntax); block: the rows, each ending in '\n'; values:
    the fields as float64, NaN where empty; t_ns: column 0 exactly."""
    if np.isinf(values).any():
        return False
    with np.errstate(over="ignore"):
        f32 = values.astype(np.float32)
    if (np.isinf(f32) & np.isfinite(values)).any() or ((f32 == 0) & (values != 0)).any():
        return False
    if re.search(r"e-[0-9]{3}", block) or re.search(r"E-[0-9]{3}", block):  # literal prefixes: fast scans
        return False  # below double's range: zero as a double, out of range for foveal (exact pass decides)
    if (t_ns < -MAX_TIME_NS).any() or (t_ns >= MAX_TIME_NS).any():
        return False
    col = 1
    for bits, max_mask in ((_EYE_BITS, 15), (_EYE_BITS, 15), (_COMBINED_BITS, 3)):
        mask = values[:, col]
        if (mask > max_mask).any():
            return False
        mask = mask.astype(np.int64)
        for j, bit in enumerate(bits, start=col + 1):
            if ((mask & bit != 0) != ~np.isnan(values[:, j])).any():
                return False
        col += 1 + len(bits)
    if version >= 2:
        head = values[:, col] == 1
        for j in range(col + 1, col + 8):
            if (head != ~np.isnan(values[:, j])).any():
                return False
        q = f32[head][:, col + 4:col + 8].astype(np.float64)
        if q.size and not (np.abs(np.sqrt(np.sum(q * q, axis=1)) - 1.0) <= QUAT_TOLERANCE).all():
            return False
    return True
