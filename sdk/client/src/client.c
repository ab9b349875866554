/* foveal-client: maps foveald's fovea block and reads it with the seqlock protocol of
 * docs/fovea-shm.md. Self-contained C11: it shares only the block's layout header with
 * foveald, so it links into any program without foveal's static libraries. */
#define _POSIX_C_SOURCE 200809L

#include "foveal/client.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
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
  size_t size;                /* FOVEAL_SHM_V2_SIZE, or FOVEAL_SHM_V3_SIZE when the block has the view */
};

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

/* NO_WRITER once foveald has stopped, DEAD_WRITER when its heartbeat is stale, else 0. */
static int writer_problem(const unsigned char *block, int64_t *silent_ns) {
  if (load_u32(block, FOVEAL_SHM_WRITER_STATE_OFFSET, __ATOMIC_ACQUIRE) == FOVEAL_SHM_WRITER_STOPPED)
    return FOVEAL_ERR_NO_WRITER;
  const int64_t silent = monotonic_ns() - (int64_t)load_u64(block, FOVEAL_SHM_HEARTBEAT_OFFSET, __ATOMIC_ACQUIRE);
  if (silent_ns) *silent_ns = silent;
  return silent > FOVEAL_SHM_DEAD_AFTER_NS ? FOVEAL_ERR_DEAD_WRITER : 0;
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
 * *map_size: how much of it this library reads (the view from version 3 on). */
static int check_block(int fd, const char *name, size_t *map_size, foveal_error *err) {
  struct stat st;
  if (fstat(fd, &st) != 0) return set_error(err, FOVEAL_ERR_SYSTEM, name, "fstat: %s", strerror(errno));
  if (!S_ISREG(st.st_mode))
    return set_error(err, FOVEAL_ERR_NOT_FOVEALDS, name, "not a plain shared-memory object");
  if ((st.st_mode & 077) != 0) /* foveald makes it 0600: a wider block is someone else's bait */
    return set_error(err, FOVEAL_ERR_NOT_FOVEALDS, name, "mode %04o lets other users write it; not a block of foveald's",
                (unsigned)(st.st_mode & 07777));
  if (st.st_uid != geteuid() && geteuid() != 0)
    return set_error(err, FOVEAL_ERR_NOT_FOVEALDS, name, "belongs to uid %u, not to you (uid %u)", (unsigned)st.st_uid,
                (unsigned)geteuid());
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
  *map_size = header[1] >= 3 && header[2] >= FOVEAL_SHM_V3_SIZE ? FOVEAL_SHM_V3_SIZE : FOVEAL_SHM_V2_SIZE;
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

  const int fd = shm_open(name, O_RDONLY | O_CLOEXEC, 0);
  if (fd < 0) {
    if (errno == ENOENT) return fail(err, FOVEAL_ERR_NO_WRITER, name, "no such block (/dev/shm%s): is foveald running?", name);
    if (errno == EACCES) return fail(err, FOVEAL_ERR_NOT_FOVEALDS, name, "permission denied: another user's block");
    return fail(err, FOVEAL_ERR_SYSTEM, name, "shm_open: %s", strerror(errno));
  }
  size_t size = 0;
  if (check_block(fd, name, &size, err) != 0) {
    close(fd);
    return NULL;
  }
  void *p = mmap(NULL, size, PROT_READ, MAP_SHARED, fd, 0);
  const int map_errno = errno;
  close(fd);
  if (p == MAP_FAILED) return fail(err, FOVEAL_ERR_SYSTEM, name, "mmap: %s", strerror(map_errno));
  const unsigned char *block = (const unsigned char *)p;

  int64_t silent = 0;
  const int problem = writer_problem(block, &silent);
  const unsigned pid = (unsigned)load_u32(block, FOVEAL_SHM_WRITER_PID_OFFSET, __ATOMIC_RELAXED);
  if (problem == FOVEAL_ERR_NO_WRITER) {
    munmap(p, size);
    return fail(err, problem, name, "the foveald that published here (pid %u) has stopped", pid);
  }
  if (problem == FOVEAL_ERR_DEAD_WRITER) {
    munmap(p, size);
    return fail(err, problem, name,
                "the foveald that published here (pid %u) gave no sign of life for %.1f s: it died or hangs; "
                "start foveald again (it takes the block over)",
                pid, (double)silent / 1e9);
  }
  foveal_client *c = (foveal_client *)calloc(1, sizeof *c);
  if (!c) {
    munmap(p, size);
    return fail(err, FOVEAL_ERR_SYSTEM, name, "out of memory");
  }
  c->block = block;
  c->size = size;
  return c;
}

int foveal_client_read(foveal_client *c, foveal_fovea *out) {
  if (!c || !out) return FOVEAL_ERR_INVALID_ARGUMENT;
  const int problem = writer_problem(c->block, NULL);
  if (problem) return problem;
  uint64_t words[FOVEAL_SHM_FOVEA_WORDS];
  if (!seqlock_read(c->block, FOVEAL_SHM_FOVEA_SEQ_OFFSET, FOVEAL_SHM_FOVEA_WORDS_OFFSET, words, FOVEAL_SHM_FOVEA_WORDS))
    return FOVEAL_ERR_BUSY;
  foveal_shm_fovea f;
  memcpy(&f, words, sizeof f);
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
  const int problem = writer_problem(c->block, NULL);
  if (problem) return problem;
  uint64_t words[FOVEAL_SHM_SETTINGS_WORDS];
  if (!seqlock_read(c->block, FOVEAL_SHM_SETTINGS_SEQ_OFFSET, FOVEAL_SHM_SETTINGS_WORDS_OFFSET, words,
                    FOVEAL_SHM_SETTINGS_WORDS))
    return FOVEAL_ERR_BUSY;
  foveal_shm_settings s;
  memcpy(&s, words, sizeof s);
  if (s.generation == 0) return FOVEAL_ERR_NO_DATA;
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
  const int problem = writer_problem(c->block, NULL);
  if (problem) return problem;
  uint64_t words[FOVEAL_SHM_VIEW_WORDS];
  if (!seqlock_read(c->block, FOVEAL_SHM_VIEW_SEQ_OFFSET, FOVEAL_SHM_VIEW_WORDS_OFFSET, words, FOVEAL_SHM_VIEW_WORDS))
    return FOVEAL_ERR_BUSY;
  foveal_shm_view v;
  memcpy(&v, words, sizeof v);
  if (!v.published) return FOVEAL_ERR_NO_DATA;
  for (int e = 0; e < 2; ++e) {
    out->tan_left[e] = v.tan_left[e];
    out->tan_right[e] = v.tan_right[e];
    out->tan_bottom[e] = v.tan_bottom[e];
    out->tan_top[e] = v.tan_top[e];
  }
  out->ipd_m = v.ipd_m;
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
    case FOVEAL_ERR_NOT_FOVEALDS: return "the block is not foveald's (another user's, or open to other users)";
    case FOVEAL_ERR_NO_DATA: return "foveald has published no fovea yet";
    case FOVEAL_ERR_BUSY: return "every try overlapped a write; try again";
    case FOVEAL_ERR_SYSTEM: return "a system call failed";
    case FOVEAL_ERR_REFUSED: return "foveald refused the request";
    case FOVEAL_ERR_TIMEOUT: return "foveald did not answer in time";
    default: return "unknown error code";
  }
}
