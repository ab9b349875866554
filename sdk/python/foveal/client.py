"""The live fovea, its motion and settings, and foveald's prediction: ctypes over
libfoveal-client (include/foveal/client.h)."""
import ctypes
import os
import warnings
from dataclasses import dataclass
from typing import Optional, Tuple

# enum foveal_error_code
(INVALID_ARGUMENT, NO_WRITER, WRONG_VERSION, DEAD_WRITER, NOT_FOVEALDS, NO_DATA, BUSY, SYSTEM, REFUSED,
 TIMEOUT, BAD_DATA) = range(1, 12)
# enum foveal_fovea_state
FIXATION, SACCADE, PURSUIT, BLINK, LOST = range(5)
# FOVEAL_PREDICT_MAX_HORIZON_NS: foveald predicts at most this far past the sample.
PREDICT_MAX_HORIZON_NS = 50_000_000


class _Fovea(ctypes.Structure):
    _fields_ = [("t_ns", ctypes.c_int64), ("eye_width", ctypes.c_uint32), ("eye_height", ctypes.c_uint32),
                ("x", ctypes.c_float * 2), ("y", ctypes.c_float * 2), ("confidence", ctypes.c_float * 2),
                ("state", ctypes.c_uint32 * 2), ("frame", ctypes.c_uint64)]


class _Settings(ctypes.Structure):
    _fields_ = [("sigma_d", ctypes.c_double), ("sigma_nd", ctypes.c_double), ("f_x", ctypes.c_double),
                ("f_y", ctypes.c_double), ("dominant_eye", ctypes.c_int), ("generation", ctypes.c_uint64)]


class _Motion(ctypes.Structure):
    _fields_ = [("velocity_x", ctypes.c_float * 2), ("velocity_y", ctypes.c_float * 2),
                ("lag_x", ctypes.c_float * 2), ("lag_y", ctypes.c_float * 2),
                ("predictable", ctypes.c_int * 2), ("frame", ctypes.c_uint64)]


class _Error(ctypes.Structure):
    _fields_ = [("code", ctypes.c_int), ("message", ctypes.c_char * 256)]


@dataclass(frozen=True)
class Fovea:
    """The latest fovea; index 0 is the left eye. Pixels of the eye viewport, origin top-left, y down."""
    t_ns: int                       # CLOCK_MONOTONIC of the gaze sample
    eye_width: int
    eye_height: int
    x: Tuple[float, float]
    y: Tuple[float, float]
    confidence: Tuple[float, float]
    state: Tuple[int, int]          # FIXATION, SACCADE, PURSUIT, BLINK, LOST
    frame: int                      # increments with every published sample


@dataclass(frozen=True)
class Motion:
    """What foveald's prediction needs beyond a fovea (block version 4, foveald 0.4 and
    later), per eye (index 0 left): the gaze pipeline's velocity, the smoother's lag and
    whether the point may be extrapolated. It belongs to the fovea whose frame it names."""
    velocity_x: Tuple[float, float]     # viewport px/s, y down
    velocity_y: Tuple[float, float]
    lag_x: Tuple[float, float]          # px the fovea trails the gaze in a steady movement (0 in a fixation)
    lag_y: Tuple[float, float]
    predictable: Tuple[bool, bool]      # fixation or smooth pursuit on the eye's own sample; False: held
    frame: int                          # the Fovea.frame this motion belongs to


class Eye(str):
    """An eye: the string 'left' or 'right' (as profiles and `foveal ctl` name it).
    For code written when Settings.dominant_eye was an int, an Eye also compares equal
    to its index (0 left, 1 right; deprecated, with a DeprecationWarning), and int(eye)
    or using it as an index gives that number. Truth testing is a str's: both are true."""
    __slots__ = ()
    _NAMES = ("left", "right")

    def __new__(cls, value):
        if isinstance(value, Eye):
            return value
        if isinstance(value, int) and not isinstance(value, bool) and value in (0, 1):
            return super().__new__(cls, cls._NAMES[value])
        if isinstance(value, str) and value in cls._NAMES:
            return super().__new__(cls, value)
        raise ValueError(f"an eye is 'left' or 'right' (or 0, 1), not {value!r}")

    @property
    def index(self) -> int:
        """0 for the left eye, 1 for the right (the C API's dominant_eye)."""
        return self._NAMES.index(str(self))

    def __int__(self) -> int:
        return self.index

    __index__ = __int__

    def __eq__(self, other):
        if isinstance(other, int) and not isinstance(other, bool):
            warnings.warn("comparing an Eye with an int: dominant_eye is 'left' or 'right' now", DeprecationWarning,
                          stacklevel=2)
            return self.index == other
        return str.__eq__(self, other)

    def __ne__(self, other):
        equal = self.__eq__(other)
        return equal if equal is NotImplemented else not equal

    __hash__ = str.__hash__

    def __repr__(self) -> str:
        return repr(str(self))


@dataclass(frozen=True)
class Settings:
    """The active profile's settings; generation increments with every change."""
    sigma_d: float
    sigma_nd: float
    f_x: float                      # negative: automatic
    f_y: float
    dominant_eye: Eye               # 'left' or 'right' (a str; == 0 / == 1 still work, deprecated)
    generation: int


class ClientError(OSError):
    """A foveal-client error: .code is one of NO_WRITER, WRONG_VERSION, DEAD_WRITER, ..."""

    def __init__(self, code: int, message: str):
        super().__init__(code, message)
        self.code = code
        self.message = message

    def __str__(self) -> str:
        return self.message


def _candidates():
    explicit = os.environ.get("FOVEAL_CLIENT_LIBRARY")
    if explicit:
        yield explicit
        return
    try:  # written by `cmake --install`: the library relative to this folder
        from . import _install
        yield os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), _install.LIBRARY))
    except ImportError:
        pass
    yield "libfoveal-client.so.0"  # the loader's own search (LD_LIBRARY_PATH, ldconfig)


_lib = None
_lib_path = None


def _library():
    global _lib, _lib_path
    if _lib is not None:
        return _lib
    tried = []
    for path in _candidates():
        try:
            lib = ctypes.CDLL(path)
        except OSError as e:
            tried.append(f"{path} ({e})")
            continue
        lib.foveal_client_open.restype = ctypes.c_void_p
        lib.foveal_client_open.argtypes = [ctypes.c_char_p, ctypes.POINTER(_Error)]
        lib.foveal_client_read.restype = ctypes.c_int
        lib.foveal_client_read.argtypes = [ctypes.c_void_p, ctypes.POINTER(_Fovea)]
        lib.foveal_client_settings.restype = ctypes.c_int
        lib.foveal_client_settings.argtypes = [ctypes.c_void_p, ctypes.POINTER(_Settings)]
        lib.foveal_client_motion.restype = ctypes.c_int
        lib.foveal_client_motion.argtypes = [ctypes.c_void_p, ctypes.POINTER(_Motion)]
        lib.foveal_client_predict.restype = ctypes.c_int
        lib.foveal_client_predict.argtypes = [ctypes.POINTER(_Fovea), ctypes.POINTER(_Motion), ctypes.c_int64,
                                              ctypes.POINTER(_Fovea)]
        lib.foveal_client_close.restype = None
        lib.foveal_client_close.argtypes = [ctypes.c_void_p]
        lib.foveal_client_mark.restype = ctypes.c_int
        lib.foveal_client_mark.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int,
                                           ctypes.POINTER(ctypes.c_int64), ctypes.POINTER(_Error)]
        lib.foveal_error_message.restype = ctypes.c_char_p
        lib.foveal_error_message.argtypes = [ctypes.c_int]
        _lib, _lib_path = lib, path
        return lib
    raise ClientError(SYSTEM, "cannot load libfoveal-client: tried " + "; ".join(tried) +
                      " (set FOVEAL_CLIENT_LIBRARY to its path)")


def library_path() -> str:
    """The libfoveal-client this module loaded (loading it if need be)."""
    _library()
    return _lib_path


def _marker_text(text) -> bytes:
    """The text as the C library takes it: UTF-8 without NUL (ctypes would cut the string
    there, and a lone surrogate has no UTF-8 form); the library checks the rest."""
    if not isinstance(text, str):
        raise ClientError(INVALID_ARGUMENT, f"mark: the text must be a str, not {type(text).__name__}")
    if "\0" in text:
        raise ClientError(INVALID_ARGUMENT, f"mark: character {text.index(chr(0)) + 1} of the text is NUL, a control character")
    try:
        return text.encode("utf-8")
    except UnicodeEncodeError as e:
        raise ClientError(INVALID_ARGUMENT, f"mark: character {e.start + 1} of the text (U+{ord(text[e.start]):04X}) is a "
                                            "lone surrogate, not text UTF-8 can hold") from None


def _socket_path(socket) -> Optional[bytes]:
    """A socket path as bytes (os.fsencode: any name the file system holds), without NUL."""
    if socket is None:
        return None
    try:
        path = os.fsencode(socket)
    except TypeError:
        raise ClientError(INVALID_ARGUMENT, f"mark: socket must be a path, not {type(socket).__name__}") from None
    except UnicodeEncodeError:
        raise ClientError(INVALID_ARGUMENT, f"mark: socket {socket!r} cannot be encoded as a file name") from None
    if b"\0" in path:
        raise ClientError(INVALID_ARGUMENT, f"mark: socket {socket!r} holds a NUL character")
    return path


def mark(text: str, socket: Optional[str] = None, timeout_ms: int = 1000) -> int:
    """Puts an event marker into foveald's trace (and a `foveal record --control` recording
    in progress), as `foveal ctl mark TEXT`. socket: a control socket's path, or None for
    the defaults. Returns the marker's CLOCK_MONOTONIC time in ns as foveald stamped it.
    Raises ClientError: INVALID_ARGUMENT (empty, over 256 bytes, not one printable line),
    NO_WRITER (foveald not running), NOT_FOVEALDS, REFUSED (foveald's reason), TIMEOUT.
    A NUL character or a lone surrogate in the text is INVALID_ARGUMENT, as is a text or
    socket of the wrong type."""
    text_bytes, socket_bytes = _marker_text(text), _socket_path(socket)
    lib = _library()
    err = _Error()
    t_ns = ctypes.c_int64(0)
    code = lib.foveal_client_mark(socket_bytes, text_bytes, timeout_ms,
                                  ctypes.byref(t_ns), ctypes.byref(err))
    if code != 0:
        raise ClientError(code, err.message.decode(errors="replace"))
    return t_ns.value


def _fovea_of(f: _Fovea) -> Fovea:
    return Fovea(f.t_ns, f.eye_width, f.eye_height, tuple(f.x), tuple(f.y), tuple(f.confidence), tuple(f.state),
                 f.frame)


def _c_fovea(f: Fovea) -> _Fovea:
    try:
        return _Fovea(f.t_ns, f.eye_width, f.eye_height, (ctypes.c_float * 2)(*f.x), (ctypes.c_float * 2)(*f.y),
                      (ctypes.c_float * 2)(*f.confidence), (ctypes.c_uint32 * 2)(*f.state), f.frame)
    except (TypeError, ValueError) as e:
        raise ClientError(INVALID_ARGUMENT, f"predict: the fovea's fields do not fit foveal_fovea ({e})") from None


def predict(fovea: Fovea, motion: Motion, t_ns: int) -> Fovea:
    """foveald's prediction to display time (foveal_client_predict): the fovea moved from
    its sample's time to t_ns (CLOCK_MONOTONIC ns), as foveald moves the fovea it renders
    with (docs/filtering.md, "Prediction"). Per eye, the horizon t_ns - fovea.t_ns is
    clamped to [0, PREDICT_MAX_HORIZON_NS] (a time not after the sample predicts nothing);
    a predictable eye moves to x + lag_x + velocity_x * horizon (y alike), clamped inside
    the viewport; any other eye is unchanged. The result's t_ns still names the sample.
    Pure arithmetic: no lock, no system call. Raises ClientError: NO_DATA when the
    motion is another fovea's (motion.frame != fovea.frame: read both again),
    INVALID_ARGUMENT for a zero viewport or arguments of the wrong type."""
    if not isinstance(fovea, Fovea) or not isinstance(motion, Motion):
        raise ClientError(INVALID_ARGUMENT, f"predict: takes a Fovea and a Motion, not {type(fovea).__name__} and "
                                            f"{type(motion).__name__}")
    if not isinstance(t_ns, int) or isinstance(t_ns, bool) or not -2**63 <= t_ns < 2**63:
        raise ClientError(INVALID_ARGUMENT, f"predict: t_ns must be an int64 of CLOCK_MONOTONIC ns, not {t_ns!r}")
    lib = _library()
    f = _c_fovea(fovea)
    try:
        m = _Motion((ctypes.c_float * 2)(*motion.velocity_x), (ctypes.c_float * 2)(*motion.velocity_y),
                    (ctypes.c_float * 2)(*motion.lag_x), (ctypes.c_float * 2)(*motion.lag_y),
                    (ctypes.c_int * 2)(*(1 if p else 0 for p in motion.predictable)), motion.frame)
    except (TypeError, ValueError) as e:
        raise ClientError(INVALID_ARGUMENT, f"predict: the motion's fields do not fit foveal_motion ({e})") from None
    out = _Fovea()
    code = lib.foveal_client_predict(ctypes.byref(f), ctypes.byref(m), t_ns, ctypes.byref(out))
    if code == NO_DATA:
        raise ClientError(code, f"predict: the motion belongs to frame {motion.frame}, the fovea is frame "
                                f"{fovea.frame}: read both again")
    if code != 0:
        raise ClientError(code, "predict: " + lib.foveal_error_message(code).decode())
    return _fovea_of(out)


class Client:
    """One mapping of foveald's block. name: a shared-memory name ("/name"), or None for
    $FOVEAL_SHM_NAME, else foveald's default. Raises ClientError (NO_WRITER when foveald
    is not running). read(), motion() and settings() take no lock and never block foveald."""

    def __init__(self, name: Optional[str] = None):
        self._lib = _library()
        err = _Error()
        handle = self._lib.foveal_client_open(name.encode() if name is not None else None, ctypes.byref(err))
        if not handle:
            raise ClientError(err.code, err.message.decode(errors="replace"))
        self._handle = handle

    def _check(self, code: int) -> None:
        if code != 0:
            raise ClientError(code, self._lib.foveal_error_message(code).decode())

    def read(self) -> Fovea:
        """The latest fovea. Raises ClientError: NO_DATA before the first sample, NO_WRITER
        once foveald stopped, DEAD_WRITER when it died."""
        if self._handle is None:
            raise ClientError(INVALID_ARGUMENT, "the client is closed")
        f = _Fovea()  # one per call: threads may share a client
        self._check(self._lib.foveal_client_read(self._handle, ctypes.byref(f)))
        return _fovea_of(f)

    def motion(self) -> Motion:
        """The motion of the latest fovea, for predict(). Read it right after read(): its
        frame is then that fovea's, or a later one when foveald published in between (read
        both again, or predict nothing this time). Raises ClientError as read(), and
        WRONG_VERSION for a foveald before 0.4 (a block without motion: predict nothing)."""
        if self._handle is None:
            raise ClientError(INVALID_ARGUMENT, "the client is closed")
        m = _Motion()
        self._check(self._lib.foveal_client_motion(self._handle, ctypes.byref(m)))
        return Motion(tuple(m.velocity_x), tuple(m.velocity_y), tuple(m.lag_x), tuple(m.lag_y),
                      tuple(p == 1 for p in m.predictable), m.frame)

    def settings(self) -> Settings:
        """The active settings (raises ClientError as read())."""
        if self._handle is None:
            raise ClientError(INVALID_ARGUMENT, "the client is closed")
        s = _Settings()
        self._check(self._lib.foveal_client_settings(self._handle, ctypes.byref(s)))
        return Settings(s.sigma_d, s.sigma_nd, s.f_x, s.f_y, Eye(s.dominant_eye), s.generation)

    def close(self) -> None:
        if self._handle is not None:
            self._lib.foveal_client_close(self._handle)
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        if getattr(self, "_handle", None) is not None:
            self.close()
