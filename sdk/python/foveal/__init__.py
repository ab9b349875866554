"""foveal for Python: foveald's live fovea and settings, and foveal's files as NumPy arrays.

    import foveal
    with foveal.Client() as c:          # foveald's block (FOVEAL_SHM_NAME, else /foveal-fovea-<uid>)
        f = c.read()                    # f.x[0], f.y[0]: the left eye's fovea in viewport pixels
        s = c.settings()                # s.sigma_d, s.sigma_nd, s.dominant_eye ('left'/'right'), s.generation
        m = c.motion()                  # right after read(): the fovea's velocity and lag (m.frame == f.frame)
        p = foveal.predict(f, m, f.t_ns + 21_000_000)  # f moved 21 ms on, by foveald's prediction rule
    foveal.mark("trial 1 start")        # an event marker in foveald's trace
    log = foveal.read_gaze_log("data/gaze/vive_pro_eye_TESTNA01.csv")
    log.samples["left_dir_x"]           # one NumPy array per column (NaN where a field is empty)

The live side is ctypes over libfoveal-client (no compiled extension); the readers need
NumPy only. docs/sdk.md.
"""
from .client import (BAD_DATA, BLINK, BUSY, DEAD_WRITER, FIXATION, INVALID_ARGUMENT, LOST, NO_DATA, NO_WRITER,
                     NOT_FOVEALDS, PREDICT_MAX_HORIZON_NS, PURSUIT, REFUSED, SACCADE, SYSTEM, TIMEOUT, WRONG_VERSION,
                     Client, ClientError, Eye, Fovea, Motion, Settings, library_path, mark, predict)
from .files import FormatError, GazeLog, Trace, read_gaze_log, read_trace


def _project_version() -> str:
    """CMake's project(VERSION): written into _install.py by the install; in a source tree,
    read from the repository's CMakeLists.txt, so that the number has one source."""
    try:
        from ._install import VERSION
        return VERSION
    except ImportError:
        pass
    import os
    import re
    top = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "CMakeLists.txt")
    try:
        with open(top, encoding="utf-8") as f:
            m = re.search(r"project\(foveal\s+VERSION\s+([0-9.]+)", f.read())
    except OSError:
        m = None
    return m.group(1) if m else "unknown"


__version__ = _project_version()

__all__ = [
    "Client", "ClientError", "Eye", "Fovea", "Motion", "Settings", "library_path", "mark", "predict",
    "PREDICT_MAX_HORIZON_NS",
    "GazeLog", "Trace", "FormatError", "read_gaze_log", "read_trace",
    "INVALID_ARGUMENT", "NO_WRITER", "WRONG_VERSION", "DEAD_WRITER", "NOT_FOVEALDS", "NO_DATA", "BUSY", "SYSTEM", "REFUSED", "TIMEOUT", "BAD_DATA",
    "FIXATION", "SACCADE", "PURSUIT", "BLINK", "LOST",
]
