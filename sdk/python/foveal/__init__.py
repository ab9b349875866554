"""foveal for Python: foveald's live fovea and settings, and foveal's files as NumPy arrays.

    import foveal
    with foveal.Client() as c:          # foveald's block (FOVEAL_SHM_NAME, else /foveal-fovea-<uid>)
        f = c.read()                    # f.x[0], f.y[0]: the left eye's fovea in viewport pixels
        s = c.settings()                # s.sigma_d, s.sigma_nd, s.dominant_eye ('left'/'right'), s.generation
    foveal.mark("trial 1 start")        # an event marker in foveald's trace
    log = foveal.read_gaze_log("data/gaze/vive_pro_eye_TESTNA01.csv")
    log.samples["left_dir_x"]           # one NumPy array per column (NaN where a field is empty)

The live side is ctypes over libfoveal-client (no compiled extension); the readers need
NumPy only. docs/sdk.md.
"""
from .client import (BAD_DATA, BLINK, BUSY, DEAD_WRITER, FIXATION, INVALID_ARGUMENT, LOST, NO_DATA, NO_WRITER,
                     NOT_FOVEALDS, PURSUIT, REFUSED, SACCADE, SYSTEM, TIMEOUT, WRONG_VERSION, Client,
                     ClientError, Eye, Fovea, Settings, library_path, mark)
from .files import FormatError, GazeLog, Trace, read_gaze_log, read_trace

__all__ = [
    "Client", "ClientError", "Eye", "Fovea", "Settings", "library_path", "mark",
    "GazeLog", "Trace", "FormatError", "read_gaze_log", "read_trace",
    "INVALID_ARGUMENT", "NO_WRITER", "WRONG_VERSION", "DEAD_WRITER", "NOT_FOVEALDS", "NO_DATA", "BUSY", "SYSTEM", "REFUSED", "TIMEOUT", "BAD_DATA",
    "FIXATION", "SACCADE", "PURSUIT", "BLINK", "LOST",
]
