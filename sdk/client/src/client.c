/* foveal-client: maps foveald's fovea block and reads it with the seqlock protocol of
 * docs/fovea-shm.md. Self-contained C11: it shares only the block's layout header with
 * foveald, so it links into any program without foveal's static libraries. */
#define _XOPEN_SOURCE 700 /* POSIX 2008 with SA_NODEFER and SA_ONSTACK */

#include "foveal/client.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "foveal/runtime/fovea_shm_layout.h"

/* Every try overlaps a write only if the writer publishes faster than a copy takes:
 * at foveald's rates a read succeeds on its first try. */
enum { kTries = 64 };

/* The oldest block this library reads: version 2 brought the settings; version 3's view
 * is read where the block has it (foveal_client_view). */
enum { kOldestVersion = 2 };

struct foveal_client {
  const unsigned char *block; /* `size` bytes, mapped read-only */
  size_t size;                /* FOVEAL_SHM_V2_SIZE, or _V3_SIZE with the view, _V4_SIZE with the motion */
  int cut_short;              /* set (atomically) once a read found the block truncated under the mapping */
};

/* Limits of what foveald writes (runtime/profile Profile::validate, DisplayModel): a value
 * outside them did not come from foveald, so a read says BAD_DATA instead of passing it on. */
#define kMaxEyePixels 65536u /* the display model allows 16384; generous on purpose */
#define kMinSigma 1.0
#define kMaxSigma 16.0
#define kMaxF 100.0
#define kMaxIpdM 0.2f
#define kMaxTangent 100.0f     /* DisplayModel::validate's bound on a frustum tangent */
#define kMinTangentSpan 0.01f  /* and on right - left, top - bottom (about 0.6 degrees) */
/* A gaze sample is measured before foveald publishes it; a time further ahead of the
 * reader's clock than this is no sample of now (an hour ahead would keep a frozen gaze
 * "fresh" for an hour). Loose enough for a tracker clock mapped with some error. */
#define kMaxSampleAheadNs 1000000000LL

/* A block truncated while mapped (ftruncate by its owner, or a foveald of another build
 * taking it over) turns every load from the lost page into SIGBUS. Checking the size with
 * fstat before each read would cost a system call and still leave a window between the
 * check and the loads, so instead reads run under a guard: a SIGBUS handler that, for a
 * fault inside the block this thread is reading, jumps back out of the read (siglongjmp to
 * a thread-local buffer) and the read returns BAD_DATA. Any other SIGBUS goes on to the
 * handler that was there before, or to the default action, as if this library were absent.
 * initial-exec TLS: the handler may run in any thread and must not allocate a TLS block. */
struct read_guard {
  sigjmp_buf *jump; /* non-NULL while this thread reads [lo, hi) */
  const unsigned char *lo, *hi;
};
static _Thread_local struct read_guard tls_guard __attribute__((tls_model("initial-exec")));
static struct sigaction previous_sigbus; /* what the program had before: chained to */
static pthread_mutex_t sigbus_lock = PTHREAD_MUTEX_INITIALIZER;

static void on_sigbus(int sig, siginfo_t *info, void *context) {
  const struct read_guard *g = &tls_guard;
  if (g->jump && info && (const unsigned char *)info->si_addr >= g->lo && (const unsigned char *)info->si_addr < g->hi)
    siglongjmp(*g->jump, 1);
  const struct sigaction *prev = &previous_sigbus;
  if ((prev->sa_flags & SA_SIGINFO) && prev->sa_sigaction) {
    prev->sa_sigaction(sig, info, context);
    return;
  }
  if (prev->sa_handler == SIG_IGN && info && info->si_code <= 0) return; /* sent by kill, and ignored */
  if (prev->sa_handler != SIG_DFL && prev->sa_handler != SIG_IGN) {
    prev->sa_handler(sig);
    return;
  }
  /* The default action (a fault cannot be ignored): die of SIGBUS as without this library. */
  struct sigaction dfl;
  memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(SIGBUS, &dfl, NULL);
  raise(SIGBUS);
}

/* Installs on_sigbus unless it is the handler now (called by every open, so a program
 * that replaced it gets it back, chained in front of its own). 0, or errno. */
static int install_sigbus_guard(void) {
  pthread_mutex_lock(&sigbus_lock);
  struct sigaction now;
  int rc = sigaction(SIGBUS, NULL, &now) == 0 ? 0 : errno;
  if (rc == 0 && !((now.sa_flags & SA_SIGINFO) && now.sa_sigaction == on_sigbus)) {
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_sigaction = on_sigbus;
    /* NODEFER: siglongjmp leaves the handler without restoring the signal mask (sigsetjmp
     * with savemask 0 keeps reads free of system calls), so SIGBUS must not be blocked in it. */
    sa.sa_flags = SA_SIGINFO | SA_NODEFER | SA_ONSTACK;
    sigemptyset(&sa.sa_mask);
    previous_sigbus = now;
    if (sigaction(SIGBUS, &sa, NULL) != 0) rc = errno;
  }
  pthread_mutex_unlock(&sigbus_lock);
  return rc;
}

/* Runs op on c's block under the guard: op's result, or FOVEAL_ERR_BAD_DATA (and the
 * client marked cut short) when the block was truncated under it. */
typedef int (*block_op)(const unsigned char *block, size_t size, void *arg);
static int guarded(foveal_client *c, block_op op, void *arg) {
  if (__atomic_load_n(&c->cut_short, __ATOMIC_RELAXED)) return FOVEAL_ERR_BAD_DATA;
  sigjmp_buf jump;
  struct read_guard *g = &tls_guard;
  if (sigsetjmp(jump, 0)) {
    g->jump = NULL;
    __atomic_store_n(&c->cut_short, 1, __ATOMIC_RELAXED);
    return FOVEAL_ERR_BAD_DATA;
  }
  g->lo = c->block;
  g->hi = c->block + c->size;
  g->jump = &jump;
  __atomic_signal_fence(__ATOMIC_SEQ_CST); /* the guard is set before the first load from the block */
  const int rc = op(c->block, c->size, arg);
  __atomic_signal_fence(__ATOMIC_SEQ_CST);
  g->jump = NULL;
  return rc;
}

static uint32_t load_u32(const unsigned char *block, size_t offset, int order) {
  return __atomic_load_n((const uint32_t *)(const void *)(block + offset), order);
}

static uint64_t load_u64(const unsigned char *block, size_t offset, int order) {
  return __atomic_load_n((const uint64_t *)(const void *)(block + offset), order);
}

/* One consistent copy of a seqlock section's words, or 0 when every try overlapped a write. */
static int seqlock_read(const unsigned char *block, size_t seq_offset, size_t words_offset, uint64_t *words,
                        size_t n) {
  for (int t = 0; t < kTries; ++t) {
    const uint32_t s1 = load_u32(block, seq_offset, __ATOMIC_ACQUIRE);
    if (s1 & 1u) continue; /* a write is in progress */
    /* Acquire loads keep the sequence re-check behind the data. */
    for (size_t i = 0; i < n; ++i) words[i] = load_u64(block, words_offset + 8 * i, __ATOMIC_ACQUIRE);
    if (load_u32(block, seq_offset, __ATOMIC_RELAXED) == s1) return 1;
  }
  return 0;
}

static int64_t monotonic_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* What the writer's words say, for open's messages. */
typedef struct {
  uint32_t state;
  int64_t heartbeat_ns, now_ns;
} writer_words;

/* NO_WRITER once foveald has stopped, DEAD_WRITER when its heartbeat is stale, BAD_DATA
 * for a state or heartbeat foveald never writes, else 0. No arithmetic here can overflow:
 * both clocks are checked to be >= 0 before they are subtracted. */
static int writer_problem(const unsigned char *block, writer_words *w) {
  w->state = load_u32(block, FOVEAL_SHM_WRITER_STATE_OFFSET, __ATOMIC_ACQUIRE);
  if (w->state == FOVEAL_SHM_WRITER_STOPPED) return FOVEAL_ERR_NO_WRITER;
  if (w->state != FOVEAL_SHM_WRITER_LIVE) return FOVEAL_ERR_BAD_DATA;
  w->heartbeat_ns = (int64_t)load_u64(block, FOVEAL_SHM_HEARTBEAT_OFFSET, __ATOMIC_ACQUIRE);
  w->now_ns = monotonic_ns();
  /* CLOCK_MONOTONIC is never negative; a heartbeat ahead of this reader's clock by more
   * than the dead interval is no clock reading (the writer refreshes it just before or
   * after this reader looked, never seconds ahead). */
  if (w->heartbeat_ns < 0 || w->now_ns < 0) return FOVEAL_ERR_BAD_DATA;
  if (w->heartbeat_ns - w->now_ns > FOVEAL_SHM_DEAD_AFTER_NS) return FOVEAL_ERR_BAD_DATA;
  return w->now_ns - w->heartbeat_ns > FOVEAL_SHM_DEAD_AFTER_NS ? FOVEAL_ERR_DEAD_WRITER : 0;
}

static int writer_op(const unsigned char *block, size_t size, void *arg) {
  (void)size;
  return writer_problem(block, (writer_words *)arg);
}

static void describe(foveal_error *err, int code, const char *name, const char *fmt, va_list ap) {
  if (!err) return;
  err->code = code;
  const int n = snprintf(err->message, sizeof err->message, "shared memory %s: ", name);
  if (n < 0 || (size_t)n >= sizeof err->message) return;
  vsnprintf(err->message + n, sizeof err->message - (size_t)n, fmt, ap);
}

/* Fills err; returns the code. */
static int set_error(foveal_error *err, int code, const char *name, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  describe(err, code, name, fmt, ap);
  va_end(ap);
  return code;
}

/* Fills err; returns NULL, for foveal_client_open. */
static foveal_client *fail(foveal_error *err, int code, const char *name, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  describe(err, code, name, fmt, ap);
  va_end(ap);
  return NULL;
}

/* A POSIX shared-memory name: one leading slash, no other, short enough for a file name. */
static int valid_name(const char *name) {
  const size_t len = strlen(name);
  return name[0] == '/' && len >= 2 && len <= 255 && strchr(name + 1, '/') == NULL;
}

/* Checks who made the block and its header; 0, or an error code with err filled.
 * *map_size: how much of it this library reads (the view from version 3 on).
 * Only a plain file of this user's, 0600, as foveald makes it (runtime/exchange
 * open_for_writing): a FIFO or device another user planted at the name, or their file,
 * could hang the reader or hand it forged gaze. Root reads only its own, as foveald
 * writes only its own. */
static int check_block(int fd, const char *name, size_t *map_size, foveal_error *err) {
  struct stat st;
  if (fstat(fd, &st) != 0) return set_error(err, FOVEAL_ERR_SYSTEM, name, "fstat: %s", strerror(errno));
  if (!S_ISREG(st.st_mode))
    return set_error(err, FOVEAL_ERR_NOT_FOVEALDS, name, "/dev/shm%s is %s, not a plain shared-memory object; not foveald's",
                     name, S_ISFIFO(st.st_mode) ? "a FIFO" : S_ISDIR(st.st_mode) ? "a directory" : "a special file");
  if (st.st_uid != geteuid())
    return set_error(err, FOVEAL_ERR_NOT_FOVEALDS, name, "belongs to uid %u, not to you (uid %u); not foveald's",
                     (unsigned)st.st_uid, (unsigned)geteuid());
  if ((st.st_mode & 077) != 0) /* foveald makes it 0600: a wider block is someone else's bait */
    return set_error(err, FOVEAL_ERR_NOT_FOVEALDS, name, "mode %04o lets other users write it; not a block of foveald's",
                     (unsigned)(st.st_mode & 07777));
  /* The header is read, not mapped: a short or older block is named, never mapped past its end. */
  uint32_t header[3] = {0, 0, 0};
  const ssize_t got = pread(fd, header, sizeof header, 0);
  if (got != (ssize_t)sizeof header || header[0] == 0)
    return set_error(err, FOVEAL_ERR_NO_WRITER, name, "foveald is still setting it up; try again");
  if (header[0] != FOVEAL_SHM_MAGIC)
    return set_error(err, FOVEAL_ERR_WRONG_VERSION, name, "not a fovea block (magic 0x%08x, expected 0x%08x)",
                (unsigned)header[0], FOVEAL_SHM_MAGIC);
  if (header[1] < kOldestVersion)
    return set_error(err, FOVEAL_ERR_WRONG_VERSION, name,
                "a version-%u block, from a foveald without settings in the block; this library reads version %u "
                "and later: update foveald",
                (unsigned)header[1], kOldestVersion);
  if (header[2] < FOVEAL_SHM_V2_SIZE || (off_t)header[2] > st.st_size)
    return set_error(err, FOVEAL_ERR_WRONG_VERSION, name,
                "its header says %u bytes, but a version-%u block has at least %d and the object holds %lld",
                (unsigned)header[2], (unsigned)header[1], (int)FOVEAL_SHM_V2_SIZE, (long long)st.st_size);
  *map_size = header[1] >= 4 && header[2] >= FOVEAL_SHM_V4_SIZE   ? FOVEAL_SHM_V4_SIZE
              : header[1] >= 3 && header[2] >= FOVEAL_SHM_V3_SIZE ? FOVEAL_SHM_V3_SIZE
                                                                   : FOVEAL_SHM_V2_SIZE;
  return 0;
}

foveal_client *foveal_client_open(const char *shm_name_or_null, foveal_error *err) {
  char default_name[64];
  const char *name = shm_name_or_null;
  if (!name) name = getenv("FOVEAL_SHM_NAME");
  if (!name || !*name) {
    snprintf(default_name, sizeof default_name, "/foveal-fovea-%u", (unsigned)getuid());
    name = default_name;
  }
  if (!valid_name(name))
    return fail(err, FOVEAL_ERR_INVALID_ARGUMENT, name, "not a shared-memory name (one leading '/', no other, at most 255 bytes)");

  /* NONBLOCK: a FIFO planted at the name would otherwise hold open(2) until a writer
   * comes, before any check can refuse it. NOFOLLOW: a symbolic link there is refused,
   * never followed (glibc's shm_open passes these flags on to open on /dev/shm). */
  const int fd = shm_open(name, O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_NOCTTY | O_CLOEXEC, 0);
  if (fd < 0) {
    const int e = errno;
    if (e == ENOENT) return fail(err, FOVEAL_ERR_NO_WRITER, name, "no such block (/dev/shm%s): is foveald running?", name);
    if (e == EACCES) return fail(err, FOVEAL_ERR_NOT_FOVEALDS, name, "permission denied: another user's block");
    if (e == ELOOP)
      return fail(err, FOVEAL_ERR_NOT_FOVEALDS, name, "/dev/shm%s is a symbolic link, not foveald's block; not followed", name);
    if (e == ENXIO) /* a socket, or a device without its driver */
      return fail(err, FOVEAL_ERR_NOT_FOVEALDS, name, "/dev/shm%s is a socket or a device, not foveald's block", name);
    return fail(err, FOVEAL_ERR_SYSTEM, name, "shm_open: %s", strerror(e));
  }
  size_t size = 0;
  if (check_block(fd, name, &size, err) != 0) {
    close(fd);
    return NULL;
  }
  const int guard_errno = install_sigbus_guard();
  if (guard_errno != 0) {
    close(fd);
    return fail(err, FOVEAL_ERR_SYSTEM, name, "sigaction(SIGBUS): %s", strerror(guard_errno));
  }
  void *p = mmap(NULL, size, PROT_READ, MAP_SHARED, fd, 0);
  const int map_errno = errno;
  close(fd);
  if (p == MAP_FAILED) return fail(err, FOVEAL_ERR_SYSTEM, name, "mmap: %s", strerror(map_errno));

  foveal_client probe = {(const unsigned char *)p, size, 0};
  writer_words w = {0, 0, 0};
  const int problem = guarded(&probe, writer_op, &w);
  const unsigned pid = probe.cut_short ? 0u : (unsigned)load_u32(probe.block, FOVEAL_SHM_WRITER_PID_OFFSET, __ATOMIC_RELAXED);
  if (problem) munmap(p, size);
  if (problem == FOVEAL_ERR_NO_WRITER)
    return fail(err, problem, name, "the foveald that published here (pid %u) has stopped", pid);
  if (problem == FOVEAL_ERR_DEAD_WRITER)
    return fail(err, problem, name,
                "the foveald that published here (pid %u) gave no sign of life for %.1f s: it died or hangs; "
                "start foveald again (it takes the block over)",
                pid, (double)(w.now_ns - w.heartbeat_ns) / 1e9);
  if (problem == FOVEAL_ERR_BAD_DATA && probe.cut_short)
    return fail(err, problem, name, "the block was cut short while it was being read; try again");
  if (problem == FOVEAL_ERR_BAD_DATA && w.state != FOVEAL_SHM_WRITER_LIVE)
    return fail(err, problem, name, "writer state %u is none that foveald writes (1 live, 2 stopped)", (unsigned)w.state);
  if (problem == FOVEAL_ERR_BAD_DATA)
    return fail(err, problem, name, "heartbeat %lld ns is no CLOCK_MONOTONIC time of a live writer (now %lld ns)",
                (long long)w.heartbeat_ns, (long long)w.now_ns);
  foveal_client *c = (foveal_client *)calloc(1, sizeof *c);
  if (!c) {
    munmap(p, size);
    return fail(err, FOVEAL_ERR_SYSTEM, name, "out of memory");
  }
  c->block = probe.block;
  c->size = size;
  return c;
}

/* One read of a seqlock section, with the writer's liveness, under the guard. */
typedef struct {
  size_t seq_offset, words_offset, n;
  uint64_t *words;
  uint64_t fovea_frame; /* the fovea's frame counter, read after the section */
  int64_t now_ns;       /* this reader's CLOCK_MONOTONIC when it checked the writer (>= 0) */
} section_read;

static int section_op(const unsigned char *block, size_t size, void *arg) {
  (void)size;
  section_read *r = (section_read *)arg;
  writer_words w;
  const int problem = writer_problem(block, &w);
  if (problem) return problem;
  r->now_ns = w.now_ns;
  if (!seqlock_read(block, r->seq_offset, r->words_offset, r->words, r->n)) return FOVEAL_ERR_BUSY;
  r->fovea_frame = load_u64(block, FOVEAL_SHM_FOVEA_WORDS_OFFSET + offsetof(foveal_shm_fovea, frame), __ATOMIC_ACQUIRE);
  return 0;
}

static int in_range(float v, float lo, float hi) { return v >= lo && v <= hi; } /* false for NaN */

/* Whether a published fovea is one foveald could have written: a sample time of this
 * clock, a viewport, finite pixels inside it (foveald clamps onto the viewport),
 * confidences in [0, 1], known states. */
static int fovea_is_plausible(const foveal_shm_fovea *f, int64_t now_ns) {
  /* A CLOCK_MONOTONIC time: positive, and not ahead of now by more than the margin. Both
   * are positive here, so the difference cannot overflow (t_ns = INT64_MIN never gets to it). */
  if (f->t_ns <= 0 || f->t_ns - now_ns > kMaxSampleAheadNs) return 0;
  if (f->eye_width == 0 || f->eye_height == 0 || f->eye_width > kMaxEyePixels || f->eye_height > kMaxEyePixels) return 0;
  for (int e = 0; e < 2; ++e)
    if (!in_range(f->x[e], 0.0f, (float)f->eye_width) || !in_range(f->y[e], 0.0f, (float)f->eye_height) ||
        !in_range(f->confidence[e], 0.0f, 1.0f) || f->state[e] > FOVEAL_STATE_LOST)
      return 0;
  return 1;
}

int foveal_client_read(foveal_client *c, foveal_fovea *out) {
  if (!c || !out) return FOVEAL_ERR_INVALID_ARGUMENT;
  uint64_t words[FOVEAL_SHM_FOVEA_WORDS];
  section_read r = {FOVEAL_SHM_FOVEA_SEQ_OFFSET, FOVEAL_SHM_FOVEA_WORDS_OFFSET, FOVEAL_SHM_FOVEA_WORDS, words, 0, 0};
  const int rc = guarded(c, section_op, &r);
  if (rc) return rc;
  foveal_shm_fovea f;
  memcpy(&f, words, sizeof f);
  if (f.frame != 0 && !fovea_is_plausible(&f, r.now_ns)) return FOVEAL_ERR_BAD_DATA;
  out->t_ns = f.t_ns;
  out->eye_width = f.eye_width;
  out->eye_height = f.eye_height;
  for (int e = 0; e < 2; ++e) {
    out->x[e] = f.x[e];
    out->y[e] = f.y[e];
    out->confidence[e] = f.confidence[e];
    out->state[e] = f.state[e];
  }
  out->frame = f.frame;
  return f.frame == 0 ? FOVEAL_ERR_NO_DATA : FOVEAL_OK;
}

int foveal_client_settings(foveal_client *c, foveal_settings *out) {
  if (!c || !out) return FOVEAL_ERR_INVALID_ARGUMENT;
  uint64_t words[FOVEAL_SHM_SETTINGS_WORDS];
  section_read r = {FOVEAL_SHM_SETTINGS_SEQ_OFFSET, FOVEAL_SHM_SETTINGS_WORDS_OFFSET, FOVEAL_SHM_SETTINGS_WORDS, words, 0, 0};
  const int rc = guarded(c, section_op, &r);
  if (rc) return rc;
  foveal_shm_settings s;
  memcpy(&s, words, sizeof s);
  /* foveald publishes its settings before its first fovea: generation 0 is a foveald
   * still starting, unless a fovea is already out. */
  if (s.generation == 0) return r.fovea_frame == 0 ? FOVEAL_ERR_NO_DATA : FOVEAL_ERR_BAD_DATA;
  const int f_ok = (s.f_x < 0.0 || (s.f_x > 0.0 && s.f_x <= kMaxF)) && (s.f_y < 0.0 || (s.f_y > 0.0 && s.f_y <= kMaxF)) &&
                   isfinite(s.f_x) && isfinite(s.f_y);
  if (!(s.sigma_d >= kMinSigma && s.sigma_d <= kMaxSigma && s.sigma_nd >= s.sigma_d && s.sigma_nd <= kMaxSigma) ||
      !f_ok || s.dominant_eye > 1)
    return FOVEAL_ERR_BAD_DATA;
  out->sigma_d = s.sigma_d;
  out->sigma_nd = s.sigma_nd;
  out->f_x = s.f_x;
  out->f_y = s.f_y;
  out->dominant_eye = (int)s.dominant_eye;
  out->generation = s.generation;
  return FOVEAL_OK;
}

int foveal_client_view(foveal_client *c, foveal_view *out) {
  if (!c || !out) return FOVEAL_ERR_INVALID_ARGUMENT;
  if (c->size < FOVEAL_SHM_V3_SIZE) return FOVEAL_ERR_WRONG_VERSION;
  uint64_t words[FOVEAL_SHM_VIEW_WORDS];
  section_read r = {FOVEAL_SHM_VIEW_SEQ_OFFSET, FOVEAL_SHM_VIEW_WORDS_OFFSET, FOVEAL_SHM_VIEW_WORDS, words, 0, 0};
  const int rc = guarded(c, section_op, &r);
  if (rc) return rc;
  foveal_shm_view v;
  memcpy(&v, words, sizeof v);
  if (v.published == 0) return FOVEAL_ERR_NO_DATA;
  if (v.published != 1) return FOVEAL_ERR_BAD_DATA;
  /* Within the bounds foveald's display model keeps (each comparison fails for NaN, and
   * a bounded tangent is finite): a frustum the right way round, at least 0.01 wide. */
  for (int e = 0; e < 2; ++e) {
    const float t[4] = {v.tan_left[e], v.tan_right[e], v.tan_bottom[e], v.tan_top[e]};
    for (int k = 0; k < 4; ++k)
      if (!(fabsf(t[k]) <= kMaxTangent)) return FOVEAL_ERR_BAD_DATA;
    if (!(t[1] - t[0] >= kMinTangentSpan) || !(t[3] - t[2] >= kMinTangentSpan)) return FOVEAL_ERR_BAD_DATA;
  }
  if (!(v.ipd_m > 0.0f && v.ipd_m <= kMaxIpdM)) return FOVEAL_ERR_BAD_DATA;
  for (int e = 0; e < 2; ++e) {
    out->tan_left[e] = v.tan_left[e];
    out->tan_right[e] = v.tan_right[e];
    out->tan_bottom[e] = v.tan_bottom[e];
    out->tan_top[e] = v.tan_top[e];
  }
  out->ipd_m = v.ipd_m;
  return FOVEAL_OK;
}

int foveal_client_motion(foveal_client *c, foveal_motion *out) {
  if (!c || !out) return FOVEAL_ERR_INVALID_ARGUMENT;
  if (c->size < FOVEAL_SHM_V4_SIZE) return FOVEAL_ERR_WRONG_VERSION;
  uint64_t words[FOVEAL_SHM_MOTION_WORDS];
  section_read r = {FOVEAL_SHM_MOTION_SEQ_OFFSET, FOVEAL_SHM_MOTION_WORDS_OFFSET, FOVEAL_SHM_MOTION_WORDS, words, 0, 0};
  const int rc = guarded(c, section_op, &r);
  if (rc) return rc;
  foveal_shm_motion m;
  memcpy(&m, words, sizeof m);
  if (m.frame == 0) return FOVEAL_ERR_NO_DATA;
  for (int e = 0; e < 2; ++e)
    if (m.predictable[e] > 1) return FOVEAL_ERR_BAD_DATA;
  for (int e = 0; e < 2; ++e) {
    out->velocity_x[e] = m.velocity_x[e];
    out->velocity_y[e] = m.velocity_y[e];
    out->lag_x[e] = m.lag_x[e];
    out->lag_y[e] = m.lag_y[e];
    out->predictable[e] = (int)m.predictable[e];
  }
  out->frame = m.frame;
  return FOVEAL_OK;
}

int foveal_client_predict(const foveal_fovea *f, const foveal_motion *m, int64_t t_ns, foveal_fovea *out) {
  if (!f || !m || !out || f->eye_width == 0 || f->eye_height == 0) return FOVEAL_ERR_INVALID_ARGUMENT;
  const foveal_fovea in = *f; /* out may be f */
  *out = in;
  if (m->frame != in.frame) return FOVEAL_ERR_NO_DATA;
  /* The same rule as foveald's predict_fovea (runtime/fovea fovea_prediction.cpp): the
   * difference in floating point, so a garbage time cannot overflow it. */
  double h = ((double)t_ns - (double)in.t_ns) * 1e-9;
  const double max_h = (double)FOVEAL_PREDICT_MAX_HORIZON_NS * 1e-9;
  if (!(h > 0.0)) return FOVEAL_OK;
  if (h > max_h) h = max_h;
  const double w = (double)nextafterf((float)in.eye_width, 0.0f), hh = (double)nextafterf((float)in.eye_height, 0.0f);
  for (int e = 0; e < 2; ++e) {
    if (m->predictable[e] != 1) continue;
    const double x = (double)in.x[e] + m->lag_x[e] + (double)m->velocity_x[e] * h;
    const double y = (double)in.y[e] + m->lag_y[e] + (double)m->velocity_y[e] * h;
    if (!isfinite(x) || !isfinite(y)) continue;
    out->x[e] = (float)(x < 0.0 ? 0.0 : x > w ? w : x);
    out->y[e] = (float)(y < 0.0 ? 0.0 : y > hh ? hh : y);
  }
  return FOVEAL_OK;
}

int foveal_view_direction(const foveal_view *v, const foveal_fovea *f, int eye, float dir[3]) {
  if (!v || !f || !dir || eye < 0 || eye > 1 || f->eye_width == 0 || f->eye_height == 0)
    return FOVEAL_ERR_INVALID_ARGUMENT;
  /* The inverse of the projection foveald maps directions through (DisplayModel::pixel_to_direction). */
  const float tx = v->tan_left[eye] + f->x[eye] / (float)f->eye_width * (v->tan_right[eye] - v->tan_left[eye]);
  const float ty = v->tan_top[eye] - f->y[eye] / (float)f->eye_height * (v->tan_top[eye] - v->tan_bottom[eye]);
  const float inv = 1.0f / sqrtf(tx * tx + ty * ty + 1.0f);
  if (!(inv > 0.0f)) return FOVEAL_ERR_INVALID_ARGUMENT; /* NaN or infinite pixels */
  dir[0] = tx * inv;
  dir[1] = ty * inv;
  dir[2] = -inv;
  return FOVEAL_OK;
}

void foveal_client_close(foveal_client *c) {
  if (!c) return;
  munmap((void *)c->block, c->size);
  free(c);
}

const char *foveal_error_message(int code) {
  switch (code) {
    case FOVEAL_OK: return "ok";
    case FOVEAL_ERR_INVALID_ARGUMENT: return "invalid argument (a null pointer or a malformed block name)";
    case FOVEAL_ERR_NO_WRITER: return "no foveald publishes there (not running, starting, or stopped)";
    case FOVEAL_ERR_WRONG_VERSION: return "not a fovea block this library reads (wrong magic, version or size)";
    case FOVEAL_ERR_DEAD_WRITER: return "the foveald that published there died or hangs (no heartbeat for 2 s)";
    case FOVEAL_ERR_NOT_FOVEALDS:
      return "the block is not foveald's (another user's, open to other users, or a FIFO, link or device)";
    case FOVEAL_ERR_NO_DATA: return "foveald has published no fovea yet";
    case FOVEAL_ERR_BUSY: return "every try overlapped a write; try again";
    case FOVEAL_ERR_SYSTEM: return "a system call failed";
    case FOVEAL_ERR_REFUSED: return "foveald refused the request";
    case FOVEAL_ERR_TIMEOUT: return "foveald did not answer in time";
    case FOVEAL_ERR_BAD_DATA:
      return "the block holds values foveald never writes (a sample time ahead of the clock, a pixel off the viewport...), "
             "or was cut short under the mapping: open a new client";
    default: return "unknown error code";
  }
}
