/* foveal_client_mark: one `mark` request on foveald's control socket (docs/daemon.md,
 * "Control socket": one JSON object per line, one reply line per request), and the same
 * request to a `foveal record --control` in progress at its default place. libc only: the
 * request is written and the reply scanned by hand, since only three fields matter. */
#define _GNU_SOURCE /* struct ucred, SO_PEERCRED */

#include "foveal/client.h"

#include <errno.h>
#include <limits.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

/* As the runtime's check_marker_text: a marker is one line of printable text. */
enum { kMaxMarkerBytes = 256, kMaxReplyBytes = 4096 };

static int mark_error(foveal_error *err, int code, const char *path, const char *fmt, ...) {
  if (err) {
    err->code = code;
    const int n = snprintf(err->message, sizeof err->message, "%s: ", path);
    if (n >= 0 && (size_t)n < sizeof err->message) {
      va_list ap;
      va_start(ap, fmt);
      vsnprintf(err->message + n, sizeof err->message - (size_t)n, fmt, ap);
      va_end(ap);
    }
  }
  return code;
}

/* foveald's default socket directory, as default_control_socket_path() in the runtime. */
static void default_socket(char *out, size_t size, const char *file) {
  const char *x = getenv("XDG_RUNTIME_DIR");
  if (x && *x) snprintf(out, size, "%s/foveal/%s", x, file);
  else snprintf(out, size, "/tmp/foveal-%u/%s", (unsigned)getuid(), file);
}

static int64_t now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Length of the well-formed UTF-8 sequence at p (RFC 3629: no overlong forms, no
 * surrogates, nothing above U+10FFFF), or 0. foveald's JSON parser refuses anything else
 * as a malformed request, so it is the caller's mistake and said so here. */
static size_t utf8_sequence(const unsigned char *p, size_t left) {
  if (p[0] < 0x80) return 1;
  size_t n;
  unsigned min, cp;
  if ((p[0] & 0xe0) == 0xc0) n = 2, min = 0x80, cp = p[0] & 0x1fu;
  else if ((p[0] & 0xf0) == 0xe0) n = 3, min = 0x800, cp = p[0] & 0x0fu;
  else if ((p[0] & 0xf8) == 0xf0) n = 4, min = 0x10000, cp = p[0] & 0x07u;
  else return 0;
  if (n > left) return 0;
  for (size_t i = 1; i < n; ++i) {
    if ((p[i] & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (p[i] & 0x3fu);
  }
  if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  return n;
}

/* Milliseconds as a timeval, for SO_SNDTIMEO (at least 1 ms: 0 would mean no limit). */
static struct timeval timeval_ms(int64_t ms) {
  if (ms < 1) ms = 1;
  struct timeval tv = {(time_t)(ms / 1000), (suseconds_t)((ms % 1000) * 1000)};
  return tv;
}

/* connect() that gives up at deadline_ms. A Unix stream connect waits while the
 * listener's backlog is full (a stopped foveald); Linux bounds that wait by SO_SNDTIMEO
 * and then fails with EAGAIN, which a non-blocking connect would return at once without
 * a way to poll for room. 0, or -1 with errno (EAGAIN: the deadline passed). */
static int connect_until(int fd, const struct sockaddr_un *addr, int64_t deadline_ms) {
  for (;;) {
    const int64_t left = deadline_ms - now_ms();
    if (left <= 0) {
      errno = EAGAIN;
      return -1;
    }
    const struct timeval tv = timeval_ms(left);
    if (setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv) != 0) return -1;
    if (connect(fd, (const struct sockaddr *)addr, sizeof *addr) == 0) return 0;
    if (errno != EINTR) return -1;
  }
}

/* send() of the whole request by deadline_ms; 0, or -1 with errno (EAGAIN: too late). */
static int send_until(int fd, const char *data, size_t len, int64_t deadline_ms) {
  size_t sent = 0;
  while (sent < len) {
    const int64_t left = deadline_ms - now_ms();
    if (left <= 0) {
      errno = EAGAIN;
      return -1;
    }
    const struct timeval tv = timeval_ms(left);
    if (setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv) != 0) return -1;
    const ssize_t n = send(fd, data + sent, len - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EWOULDBLOCK) errno = EAGAIN;
    if (n < 0) return -1;
    sent += (size_t)n;
  }
  return 0;
}

/* {"cmd":"mark","text":"..."}\n with the text escaped; 0 when it does not fit. */
static size_t mark_request(char *out, size_t size, const char *text) {
  size_t n = (size_t)snprintf(out, size, "{\"cmd\":\"mark\",\"text\":\"");
  for (const char *p = text; *p; ++p) {
    if (n + 3 >= size) return 0;
    if (*p == '"' || *p == '\\') out[n++] = '\\';
    out[n++] = *p;
  }
  if (n + 4 > size) return 0;
  memcpy(out + n, "\"}\n", 4);
  return n + 3;
}

/* The string value of "key" in a one-line JSON reply, unescaped into out (\uXXXX kept
 * as written); 0 when absent. */
static int reply_string(const char *reply, const char *key, char *out, size_t size) {
  char pattern[32];
  snprintf(pattern, sizeof pattern, "\"%s\":\"", key);
  const char *p = strstr(reply, pattern);
  if (!p || size == 0) return 0;
  p += strlen(pattern);
  size_t n = 0;
  for (; *p && *p != '"' && n + 1 < size; ++p) {
    if (*p == '\\' && p[1]) ++p;
    out[n++] = *p;
  }
  out[n] = '\0';
  return 1;
}

/* Sends one mark to the socket at path and reads the reply; FOVEAL_OK with *t_ns set, or
 * an error code with err filled. */
static int mark_one(const char *path, const char *request, size_t request_len, int timeout_ms, int64_t *t_ns,
                    foveal_error *err) {
  struct sockaddr_un addr;
  memset(&addr, 0, sizeof addr);
  addr.sun_family = AF_UNIX;
  if (strlen(path) >= sizeof addr.sun_path) return mark_error(err, FOVEAL_ERR_INVALID_ARGUMENT, path, "socket path too long");
  memcpy(addr.sun_path, path, strlen(path) + 1);
  const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return mark_error(err, FOVEAL_ERR_SYSTEM, path, "socket: %s", strerror(errno));
  int code = FOVEAL_OK;
  /* One deadline for connect, send and the reply: a stopped foveald can hold each. */
  const int64_t deadline = now_ms() + timeout_ms;
  if (connect_until(fd, &addr, deadline) != 0) {
    if (errno == EAGAIN)
      code = mark_error(err, FOVEAL_ERR_TIMEOUT, path, "not accepting connections within %d ms (foveald stopped or flooded?)",
                        timeout_ms);
    else
      code = mark_error(err, FOVEAL_ERR_NO_WRITER, path, "cannot connect (is foveald running?): %s", strerror(errno));
    goto done;
  }
  /* Only this user's foveald (or root's) may take the marker: a socket another user
   * planted on the path would otherwise collect it and answer for it. */
  struct ucred peer;
  socklen_t peer_len = sizeof peer;
  if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &peer, &peer_len) != 0) {
    code = mark_error(err, FOVEAL_ERR_SYSTEM, path, "cannot tell who serves the socket: %s", strerror(errno));
    goto done;
  }
  if (peer.uid != geteuid() && peer.uid != 0) {
    code = mark_error(err, FOVEAL_ERR_NOT_FOVEALDS, path, "served by uid %u, not by you (uid %u): not your foveald",
                      (unsigned)peer.uid, (unsigned)geteuid());
    goto done;
  }
  if (send_until(fd, request, request_len, deadline) != 0) {
    if (errno == EAGAIN) code = mark_error(err, FOVEAL_ERR_TIMEOUT, path, "request not taken within %d ms", timeout_ms);
    else code = mark_error(err, FOVEAL_ERR_SYSTEM, path, "send: %s", strerror(errno));
    goto done;
  }
  char reply[kMaxReplyBytes];
  size_t got = 0;
  while (!memchr(reply, '\n', got)) {
    const int64_t left = deadline - now_ms();
    if (left <= 0) {
      code = mark_error(err, FOVEAL_ERR_TIMEOUT, path, "no reply within %d ms", timeout_ms);
      goto done;
    }
    struct pollfd p = {fd, POLLIN, 0};
    if (poll(&p, 1, left > INT_MAX ? INT_MAX : (int)left) <= 0) continue;
    if (got + 1 >= sizeof reply) {
      code = mark_error(err, FOVEAL_ERR_SYSTEM, path, "reply longer than %d bytes", kMaxReplyBytes);
      goto done;
    }
    const ssize_t n = recv(fd, reply + got, sizeof reply - 1 - got, 0);
    if (n <= 0) {
      code = mark_error(err, FOVEAL_ERR_SYSTEM, path, "connection closed before the reply");
      goto done;
    }
    got += (size_t)n;
  }
  reply[got] = '\0';
  if (!strstr(reply, "\"ok\":true")) {
    char why[200] = "a reply without \"ok\"";
    reply_string(reply, "error", why, sizeof why);
    code = mark_error(err, FOVEAL_ERR_REFUSED, path, "%s", why);
    goto done;
  }
  const char *t = strstr(reply, "\"t_ns\":");
  if (t_ns && t) *t_ns = strtoll(t + 7, NULL, 10);
done:
  close(fd);
  return code;
}

int foveal_client_mark(const char *socket_or_null, const char *text, int timeout_ms, int64_t *t_ns_out,
                       foveal_error *err) {
  if (!text) return mark_error(err, FOVEAL_ERR_INVALID_ARGUMENT, "mark", "the text is NULL");
  const size_t len = strlen(text);
  if (len == 0 || len > kMaxMarkerBytes)
    return mark_error(err, FOVEAL_ERR_INVALID_ARGUMENT, "mark", "the text has %zu bytes; 1 to %d", len, kMaxMarkerBytes);
  for (size_t i = 0; i < len; ++i)
    if ((unsigned char)text[i] < 0x20 || text[i] == 0x7f)
      return mark_error(err, FOVEAL_ERR_INVALID_ARGUMENT, "mark", "byte %zu of the text is a control character", i + 1);
  for (size_t i = 0; i < len;) {
    const size_t n = utf8_sequence((const unsigned char *)text + i, len - i);
    if (n == 0) return mark_error(err, FOVEAL_ERR_INVALID_ARGUMENT, "mark", "byte %zu of the text is not valid UTF-8", i + 1);
    i += n;
  }
  if (timeout_ms <= 0) timeout_ms = 1000;
  char request[2 * kMaxMarkerBytes + 64];
  const size_t request_len = mark_request(request, sizeof request, text);
  if (request_len == 0) return mark_error(err, FOVEAL_ERR_INVALID_ARGUMENT, "mark", "the text does not fit a request");

  if (socket_or_null) return mark_one(socket_or_null, request, request_len, timeout_ms, t_ns_out, err);
  /* The defaults, as `foveal ctl mark`: foveald, and a recording in progress beside it.
   * Success when either takes it; foveald's answer is the one reported. */
  char daemon[sizeof(((struct sockaddr_un *)0)->sun_path) + 32], record[sizeof daemon];
  default_socket(daemon, sizeof daemon, "control.sock");
  default_socket(record, sizeof record, "record.sock");
  foveal_error daemon_err = {0, ""};
  const int daemon_code = mark_one(daemon, request, request_len, timeout_ms, t_ns_out, &daemon_err);
  struct stat st;
  if (stat(record, &st) == 0 && S_ISSOCK(st.st_mode)) {
    int64_t record_t = 0;
    foveal_error record_err = {0, ""};
    const int record_code = mark_one(record, request, request_len, timeout_ms, &record_t, &record_err);
    if (daemon_code != FOVEAL_OK && record_code == FOVEAL_OK) {
      if (t_ns_out) *t_ns_out = record_t;
      return FOVEAL_OK;
    }
  }
  if (daemon_code != FOVEAL_OK && err) *err = daemon_err;
  return daemon_code;
}
