/* foveal-client: foveald's live fovea and settings for any program (docs/sdk.md).
 *
 * foveald publishes the latest per-eye fovea and the active profile's settings in a
 * shared-memory block (docs/fovea-shm.md). This library maps the block and reads it
 * with the block's seqlock protocol: a read never blocks foveald or the caller, takes
 * no lock, allocates nothing and makes no system call. It also sends event markers to
 * foveald's control socket (foveal_client_mark), the one call that talks to foveald.
 *
 * C11 and C++ (any standard) use the same header. Link with
 * `pkg-config --cflags --libs foveal-client` or, in CMake,
 * `find_package(foveal CONFIG REQUIRED)` and `foveal::client`.
 *
 * Structs may gain fields at their end in later versions (never reordered); such a
 * change comes with a new SONAME major, so a program built against this header keeps
 * running against the library it was built for. */
#ifndef FOVEAL_CLIENT_H
#define FOVEAL_CLIENT_H

#include <stdint.h>

#if defined(__GNUC__)
#define FOVEAL_CLIENT_API __attribute__((visibility("default")))
#else
#define FOVEAL_CLIENT_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Error codes: every function that can fail returns one (0 is success). */
enum foveal_error_code {
  FOVEAL_OK = 0,
  FOVEAL_ERR_INVALID_ARGUMENT = 1, /* a null pointer, or a malformed block name */
  FOVEAL_ERR_NO_WRITER = 2,        /* no foveald publishes there (not running, starting, or stopped) */
  FOVEAL_ERR_WRONG_VERSION = 3,    /* the block is not one this library reads (older foveald, not a fovea block) */
  FOVEAL_ERR_DEAD_WRITER = 4,      /* the foveald that published there died or hangs (no heartbeat for 2 s) */
  FOVEAL_ERR_NOT_FOVEALDS = 5,     /* not one foveald made: another user's, open to other users, or no plain file
                                      (a FIFO, a symbolic link, a device) */
  FOVEAL_ERR_NO_DATA = 6,          /* foveald runs but has published no fovea yet (waiting for its tracker) */
  FOVEAL_ERR_BUSY = 7,             /* every try overlapped a write (practically never): try again */
  FOVEAL_ERR_SYSTEM = 8,           /* an operating-system call failed; the message says which */
  FOVEAL_ERR_REFUSED = 9,          /* foveald answered a request with an error; the message is its reason */
  FOVEAL_ERR_TIMEOUT = 10,         /* foveald did not answer in time */
  FOVEAL_ERR_BAD_DATA = 11         /* the block holds values foveald never writes (NaN, unknown state, a heartbeat
                                      no clock gives...), or was cut short under the mapping: open a new client */
};

/* Fovea states (foveal_fovea.state). */
enum foveal_fovea_state {
  FOVEAL_STATE_FIXATION = 0,
  FOVEAL_STATE_SACCADE = 1,
  FOVEAL_STATE_PURSUIT = 2,
  FOVEAL_STATE_BLINK = 3, /* the fovea holds its last position */
  FOVEAL_STATE_LOST = 4   /* no eye tracked: the fovea is the viewport centre, confidence 0 */
};

/* The latest fovea. Index 0 is the left eye, 1 the right. */
typedef struct {
  int64_t t_ns;                  /* CLOCK_MONOTONIC time of the gaze sample, ns (> 0, at most 1 s ahead of the
                                    reader's clock when read) */
  uint32_t eye_width, eye_height; /* the eye viewport (pixels) that x and y refer to */
  float x[2], y[2];              /* viewport pixels, origin at the top-left corner, y down */
  float confidence[2];           /* 0..1 */
  uint32_t state[2];             /* enum foveal_fovea_state */
  uint64_t frame;                /* increments with every gaze sample foveald publishes */
} foveal_fovea;

/* The active profile's settings; generation increments with every change (a profile
 * switch, `foveal ctl set`, SIGHUP reload). */
typedef struct {
  double sigma_d, sigma_nd; /* RMFR levels of the dominant and the non-dominant eye (>= 1) */
  double f_x, f_y;          /* RMFR's fovea-region parameter per axis; negative: automatic */
  int dominant_eye;         /* 0 left, 1 right */
  uint64_t generation;
} foveal_settings;

/* What the fovea's pixels mean (block version 3, foveald 0.3 and later): each eye's
 * projection as the tangents of its frustum's half-angles, and the IPD. Fixed for as
 * long as one foveald runs. */
typedef struct {
  float tan_left[2], tan_right[2]; /* per eye; left and bottom are negative */
  float tan_bottom[2], tan_top[2];
  float ipd_m;                     /* interpupillary distance, metres */
} foveal_view;

/* What foveald's prediction to display time needs beyond a fovea (block version 4,
 * foveald 0.4 and later): per eye the gaze pipeline's velocity, the smoother's lag and
 * whether the point may be extrapolated. It belongs to the fovea whose frame it names. */
typedef struct {
  float velocity_x[2], velocity_y[2]; /* viewport px/s, y down */
  float lag_x[2], lag_y[2];           /* px the fovea trails the gaze in a steady movement (0 in a fixation) */
  int predictable[2];                 /* 1: fixation or smooth pursuit on the eye's own sample; 0: held
                                         (a saccade, a blink, a loss, an eye filled in from the other) */
  uint64_t frame;                     /* the foveal_fovea.frame this motion belongs to */
} foveal_motion;

/* foveald's longest extrapolation (its --predict rule): a time further ahead of the
 * sample is predicted this far only. */
#define FOVEAL_PREDICT_MAX_HORIZON_NS 50000000LL

/* An error as a value: the code and a message naming the block and what is wrong. */
typedef struct {
  int code;
  char message[256];
} foveal_error;

/* Opaque: one mapping of the block. */
typedef struct foveal_client foveal_client;

/* Maps foveald's block.
 *
 * shm_name_or_null: a POSIX shared-memory name ("/name"), or NULL for the environment's
 *   FOVEAL_SHM_NAME when set, else foveald's default "/foveal-fovea-<uid>".
 * err: filled on failure when not NULL (code and message); left alone on success.
 * Returns the client, or NULL on failure with err->code one of INVALID_ARGUMENT,
 *   NO_WRITER (no block: is foveald running?; or foveald stopped), WRONG_VERSION,
 *   NOT_FOVEALDS (anything at the name but a plain file of the calling user's with mode
 *   0600: another user's file, even for root, a FIFO, a symbolic link, a device),
 *   DEAD_WRITER, BAD_DATA (a writer state or heartbeat foveald never writes), SYSTEM.
 * Never blocks: the name is opened non-blocking and not followed if it is a link, so
 *   a FIFO planted there is refused at once instead of waiting for a writer.
 * Thread safety: may be called from any thread. Allocates the client; the only call
 *   that does. A client stays bound to the block it mapped: after foveald restarts,
 *   reads return NO_WRITER (or DEAD_WRITER) and the program opens a new client. */
FOVEAL_CLIENT_API foveal_client *foveal_client_open(const char *shm_name_or_null, foveal_error *err);

/* Copies the latest fovea into *out.
 *
 * Returns FOVEAL_OK, or INVALID_ARGUMENT (c or out NULL), NO_WRITER (foveald stopped),
 *   DEAD_WRITER, NO_DATA (nothing published yet; *out then holds zeros and the viewport
 *   size), BUSY, BAD_DATA (a value foveald never writes: a sample time t_ns that is not
 *   positive or more than 1 s ahead of this reader's CLOCK_MONOTONIC, a non-finite or
 *   off-viewport pixel, a confidence outside [0, 1], an unknown state or writer state, a zero
 *   viewport, a heartbeat no clock gives; or the block was truncated while mapped). On an
 *   error other than NO_DATA, *out is unchanged.
 * Wait-free for the writer; no lock, allocation or system call (the clock is read
 *   through the vDSO). Thread safety: any number of threads may read one client at once.
 *   foveal_error_message(code) gives the code's message.
 * A block truncated under the mapping would raise SIGBUS on the read: foveal_client_open
 *   installs a SIGBUS handler (process-wide, once; again if the program replaced it) that
 *   turns a fault inside a read of this library into BAD_DATA and passes every other
 *   SIGBUS to the handler the program had before (or the default action: the process
 *   dies as it would have). A program that installs its own SIGBUS handler after opening
 *   a client should chain to the one it replaces, as this library does. */
FOVEAL_CLIENT_API int foveal_client_read(foveal_client *c, foveal_fovea *out);

/* Copies the active settings into *out.
 *
 * Returns and thread safety as foveal_client_read. NO_DATA only while foveald starts
 *   (it publishes its settings before its first fovea; generation 0 after a fovea is
 *   BAD_DATA, as are sigmas outside [1, 16] or sigma_nd < sigma_d, f neither negative
 *   (automatic) nor in (0, 100], a dominant eye not 0 or 1). */
FOVEAL_CLIENT_API int foveal_client_settings(foveal_client *c, foveal_settings *out);

/* Copies the display geometry foveald maps gaze with into *out.
 *
 * Returns FOVEAL_OK, or INVALID_ARGUMENT, WRONG_VERSION (an older foveald's block,
 *   without the view), NO_WRITER, DEAD_WRITER, NO_DATA (not yet published), BUSY,
 *   BAD_DATA (a tangent that is not finite or beyond +-100 (the bound of foveald's display
 *   model), right - left or top - bottom under 0.01, an IPD outside (0, 0.2] m, a
 *   published flag not 0 or 1).
 * Wait-free, no lock, allocation or system call. Thread safety as foveal_client_read. */
FOVEAL_CLIENT_API int foveal_client_view(foveal_client *c, foveal_view *out);

/* Copies the motion of the latest fovea into *out (block version 4).
 *
 * Read it right after foveal_client_read: foveald writes each fovea's motion just before
 *   the fovea, so out->frame is then that fovea's frame, or a later one when foveald
 *   published again in between (read both again, or predict nothing this time).
 * Returns FOVEAL_OK, or INVALID_ARGUMENT, WRONG_VERSION (an older foveald's block,
 *   without motion: predict nothing), NO_WRITER, DEAD_WRITER, NO_DATA (no fovea published
 *   yet), BUSY, BAD_DATA (a predictable flag not 0 or 1). On an error *out is unchanged.
 * Wait-free, no lock, allocation or system call. Thread safety as foveal_client_read. */
FOVEAL_CLIENT_API int foveal_client_motion(foveal_client *c, foveal_motion *out);

/* foveald's prediction to display time applied to a fovea read from the block: each eye
 * moved from the sample's time f->t_ns to t_ns (CLOCK_MONOTONIC), as foveald moves the
 * fovea it renders with (docs/filtering.md, "Prediction").
 *
 * Per eye: the horizon h = t_ns - f->t_ns is clamped to [0, FOVEAL_PREDICT_MAX_HORIZON_NS]
 *   (a time not after the sample predicts nothing); a predictable eye moves to
 *   x + lag_x + velocity_x * h (and y alike), clamped inside the viewport; any other eye,
 *   and one whose result would not be finite, is copied unchanged. Everything else is
 *   copied: out->t_ns still names the sample, not t_ns.
 * out may be f. Returns FOVEAL_OK, or INVALID_ARGUMENT (a null pointer, a zero
 *   viewport), NO_DATA (m->frame is not f->frame: the motion is another fovea's;
 *   *out is then *f unchanged).
 * Pure arithmetic: no lock, allocation or system call; any thread. */
FOVEAL_CLIENT_API int foveal_client_predict(const foveal_fovea *f, const foveal_motion *m, int64_t t_ns,
                                            foveal_fovea *out);

/* Turns eye `eye`'s fovea pixel (0 left, 1 right) back into a unit gaze direction in
 * that eye's frame (x right, y up, -z forward: the OpenXR convention), through view v.
 *
 * Returns FOVEAL_OK, or INVALID_ARGUMENT (a null pointer, eye not 0 or 1, a zero
 *   viewport, or a non-finite pixel). Pure arithmetic; any thread. */
FOVEAL_CLIENT_API int foveal_view_direction(const foveal_view *v, const foveal_fovea *f, int eye, float dir[3]);

/* Unmaps the block and frees the client. NULL is allowed (nothing happens).
 * Thread safety: no other call may use c at the same time or after. */
FOVEAL_CLIENT_API void foveal_client_close(foveal_client *c);

/* Puts a timestamped event marker ("trial 3 start") into foveald's trace, as
 * `foveal ctl mark TEXT` does (docs/daemon.md, "Markers"): foveald stamps it on arrival,
 * on the gaze samples' clock, and writes it as its own row before the next sample.
 *
 * socket_or_null: a control socket's path, or NULL for the defaults: foveald's
 *   ($XDG_RUNTIME_DIR/foveal/control.sock, else /tmp/foveal-<uid>/control.sock) and, when
 *   present beside it, a `foveal record --control` in progress (record.sock), which writes
 *   the marker into its recording too. With NULL it succeeds when either takes it.
 * text: 1 to 256 bytes of printable UTF-8 text, one line (no control characters).
 * timeout_ms: how long each socket may take, connecting (a stopped foveald's full
 *   backlog), sending and replying together; 0 or less means 1000.
 * t_ns_out: when not NULL, the marker's CLOCK_MONOTONIC time as foveald stamped it.
 * err: filled on failure when not NULL; left alone on success.
 * Returns FOVEAL_OK, or INVALID_ARGUMENT (text NULL, empty, too long, not UTF-8 or not one
 *   printable line), NO_WRITER (nobody listens: is foveald running?), NOT_FOVEALDS (the socket is
 *   served by another user), REFUSED (foveald said no, e.g. too many markers waiting for
 *   the next sample), TIMEOUT, SYSTEM.
 * Blocking: one connection and one round trip per socket, at most timeout_ms each; not
 *   for a render loop's hot path. Needs no client (it talks to the control socket, not
 *   the shared block). Thread safety: any thread, any number at once. */
FOVEAL_CLIENT_API int foveal_client_mark(const char *socket_or_null, const char *text, int timeout_ms, int64_t *t_ns_out,
                                         foveal_error *err);

/* A static English message for an error code ("no foveald publishes there", ...);
 * never NULL. Thread safety: any thread. */
FOVEAL_CLIENT_API const char *foveal_error_message(int code);

#ifdef __cplusplus
}
#endif

#endif
