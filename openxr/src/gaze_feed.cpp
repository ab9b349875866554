#include "gaze_feed.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace foveal::openxr {

namespace {

constexpr std::int64_t kPollNs = 100'000'000;       // how soon a stop or a return is seen
constexpr std::int64_t kMaxBackoffNs = 2'000'000'000;  // retries of an unusable block slow to this
constexpr std::int64_t kStaleNs = 250'000'000;  // a sample this old (paused foveald) is not tracking
constexpr std::int64_t kFutureNs = 1'000'000'000;  // a sample further ahead than this is no sample of now
constexpr std::int64_t kOffsetEveryNs = 1'000'000'000;

std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

bool eye_is_tracked(const foveal_fovea& f, int e) {
  // A blink holds the last position and lost is the viewport centre: neither is gaze.
  return f.state[e] != FOVEAL_STATE_BLINK && f.state[e] != FOVEAL_STATE_LOST && f.confidence[e] > 0.0f;
}

std::uint64_t pack(float a, float b) {
  std::uint32_t x, y;
  std::memcpy(&x, &a, 4);
  std::memcpy(&y, &b, 4);
  return (static_cast<std::uint64_t>(y) << 32) | x;
}

}  // namespace

GazeFeed::GazeFeed(std::function<bool(std::int64_t, XrTime&)> to_xr_time, std::function<void(const char*)> log)
    : to_xr_time_(std::move(to_xr_time)), log_(std::move(log)) {
  if (const char* v = std::getenv("FOVEAL_OPENXR_PREDICT"); v && *v) {
    predict_ = std::strcmp(v, "off") != 0;
    if (!predict_) log_("FOVEAL_OPENXR_PREDICT=off: gaze located at its sample, not predicted to the asked time");
    else if (std::strcmp(v, "on") != 0) log_("FOVEAL_OPENXR_PREDICT: neither on nor off; prediction stays on");
  }
  // An app that starts with foveald running has gaze, and its times, from its first frame.
  const std::int64_t now = monotonic_ns();
  measure_offset(now);
  check_connection(now);
  thread_ = std::thread([this] { run(); });
}

GazeFeed::~GazeFeed() {
  {
    std::lock_guard lock(stop_mutex_);
    stop_ = true;
  }
  stop_wake_.notify_all();
  thread_.join();
  if (Connection* c = current_.exchange(nullptr)) retired_.push_back(c);
  for (Connection* c : retired_) {
    foveal_client_close(c->client);
    delete c;
  }
}

void GazeFeed::measure_offset(std::int64_t now) {
  // The runtime's clock differs from CLOCK_MONOTONIC by its own offset: measured here,
  // used as plain arithmetic on the per-frame paths.
  XrTime xr = 0;
  if (!to_xr_time_(now, xr)) return;
  xr_offset_ns_.store(xr - now, std::memory_order_relaxed);
  offset_known_.store(true, std::memory_order_release);
}

void GazeFeed::run() {
  std::int64_t next_offset = monotonic_ns() + kOffsetEveryNs;
  std::unique_lock lock(stop_mutex_);
  while (!stop_) {
    lock.unlock();
    const std::int64_t now = monotonic_ns();
    if (now >= next_offset) {
      measure_offset(now);
      next_offset = now + kOffsetEveryNs;
    }
    const std::int64_t wait_ns = check_connection(now);
    free_retired();
    lock.lock();
    stop_wake_.wait_for(lock, std::chrono::nanoseconds(wait_ns), [this] { return stop_; });
  }
}

void GazeFeed::say(State s, const char* detail) {
  if (s == state_) return;  // one line per change of state, however often it is seen
  state_ = s;
  char line[400];
  switch (s) {
    case State::serving: std::snprintf(line, sizeof line, "foveald serves: eye gaze active"); break;
    case State::waiting:
      std::snprintf(line, sizeof line, "no gaze from foveald yet (%s); eye gaze inactive until it serves", detail);
      break;
    case State::stopped: std::snprintf(line, sizeof line, "%s: eye gaze inactive until it is back", detail); break;
    case State::bad:
      std::snprintf(line, sizeof line, "foveald's block is unusable (%s): eye gaze inactive; retrying less often", detail);
      break;
    case State::starting: return;
  }
  log_(line);
}

void GazeFeed::retire(Connection* c) {
  current_.store(nullptr, std::memory_order_seq_cst);
  retired_.push_back(c);
}

void GazeFeed::free_retired() {
  // current_ no longer names them: a reader that counted itself in after the store
  // loads the new pointer, so a zero count means no reader holds a retired one.
  if (retired_.empty() || readers_.load(std::memory_order_seq_cst) != 0) return;
  for (Connection* c : retired_) {
    foveal_client_close(c->client);
    delete c;
    held_.fetch_sub(1, std::memory_order_relaxed);
  }
  retired_.clear();
}

std::int64_t GazeFeed::check_connection(std::int64_t now) {
  if (Connection* c = current_.load(std::memory_order_acquire)) {
    foveal_fovea f;
    const int rc = foveal_client_read(c->client, &f);
    foveal_settings s;
    if (foveal_client_settings(c->client, &s) == FOVEAL_OK) {
      const float left = static_cast<float>(s.dominant_eye == 0 ? s.sigma_d : s.sigma_nd);
      const float right = static_cast<float>(s.dominant_eye == 1 ? s.sigma_d : s.sigma_nd);
      settings_bits_.store(pack(left, right), std::memory_order_relaxed);
    }
    // BAD_DATA: the block was cut short or holds what foveald never writes; a new
    // mapping (of a restarted foveald's block) is the way back, after a backoff.
    if (rc != FOVEAL_ERR_NO_WRITER && rc != FOVEAL_ERR_DEAD_WRITER && rc != FOVEAL_ERR_BAD_DATA) {
      if (rc == FOVEAL_OK) backoff_ns_ = 0;
      return kPollNs;
    }
    retire(c);
    if (rc == FOVEAL_ERR_BAD_DATA) {
      say(State::bad, foveal_error_message(rc));
      backoff_ns_ = std::clamp<std::int64_t>(backoff_ns_ * 2, kPollNs, kMaxBackoffNs);
    } else {
      say(State::stopped, rc == FOVEAL_ERR_NO_WRITER ? "foveald stopped" : "foveald stopped answering");
      backoff_ns_ = 0;
    }
    next_try_ns_ = now + backoff_ns_;
  }
  if (now < next_try_ns_) return std::min(kPollNs, next_try_ns_ - now);
  foveal_error err{};
  foveal_client* client = foveal_client_open(nullptr, &err);
  if (!client) {
    if (err.code == FOVEAL_ERR_NO_WRITER || state_ == State::starting)
      say(state_ == State::starting || state_ == State::waiting ? State::waiting : State::stopped, err.message);
    else
      say(State::bad, err.message);
    // A block that is there but unusable (another user's, a FIFO, bad data) is tried
    // less and less often; a missing one at the poll rate, to see foveald start.
    backoff_ns_ = err.code == FOVEAL_ERR_NO_WRITER ? 0 : std::clamp<std::int64_t>(backoff_ns_ * 2, kPollNs, kMaxBackoffNs);
    next_try_ns_ = now + backoff_ns_;
    return kPollNs;
  }
  auto* c = new Connection{client, {}};
  held_.fetch_add(1, std::memory_order_relaxed);
  foveal_fovea f;
  const int first = foveal_client_read(client, &f);
  if (foveal_client_view(client, &c->view) != FOVEAL_OK || first == FOVEAL_ERR_BAD_DATA) {
    // An older foveald's block, one still starting, or one whose fovea is unusable:
    // dropped at once (no reader saw it), tried again after the backoff.
    foveal_client_close(client);
    delete c;
    held_.fetch_sub(1, std::memory_order_relaxed);
    if (first == FOVEAL_ERR_BAD_DATA) say(State::bad, foveal_error_message(first));
    backoff_ns_ = std::clamp<std::int64_t>(backoff_ns_ * 2, kPollNs, kMaxBackoffNs);
    next_try_ns_ = now + backoff_ns_;
    return kPollNs;
  }
  current_.store(c, std::memory_order_release);
  say(State::serving, nullptr);
  return kPollNs;
}

namespace {

/// Directions of the eyes marked tracked, from f's pixels through g.view; an eye whose
/// pixel gives none is dropped. Then the combined direction.
void set_directions(GazeNow& g, const foveal_fovea& f) {
  XrVector3f sum{0, 0, 0};
  for (int e = 0; e < 2; ++e) {
    float d[3];
    if (!g.eye_tracked[e]) continue;
    if (foveal_view_direction(&g.view, &f, e, d) != FOVEAL_OK || !std::isfinite(d[0]) || !std::isfinite(d[1]) ||
        !std::isfinite(d[2])) {
      g.eye_tracked[e] = false;
      continue;
    }
    g.eye_dir[e] = {d[0], d[1], d[2]};
    sum = {sum.x + d[0], sum.y + d[1], sum.z + d[2]};
  }
  const float n = std::sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z);
  g.tracked = n > 1e-6f;
  g.combined = g.tracked ? XrVector3f{sum.x / n, sum.y / n, sum.z / n} : XrVector3f{0, 0, -1};
}

}  // namespace

GazeNow gaze_at(const GazeNow& g, XrTime time) {
  if (!g.predictable || !g.offset_known || time <= 0) return g;
  std::int64_t t_ns = 0;
  if (__builtin_sub_overflow(time, g.xr_offset_ns, &t_ns)) return g;
  GazeNow out = g;
  foveal_fovea p;
  if (foveal_client_predict(&g.fovea, &g.motion, t_ns, &p) != FOVEAL_OK) return g;
  set_directions(out, p);
  // Where the rule stopped: the sample's time plus the horizon it used.
  const std::int64_t h = std::clamp<std::int64_t>(t_ns - std::min(t_ns, g.t_ns), 0, FOVEAL_PREDICT_MAX_HORIZON_NS);
  out.at_ns = g.t_ns + h;
  return out;
}

bool GazeFeed::read(GazeNow& out) const {
  readers_.fetch_add(1, std::memory_order_seq_cst);
  struct Leave {
    std::atomic<int>& n;
    ~Leave() { n.fetch_sub(1, std::memory_order_release); }
  } leave{readers_};
  const Connection* c = current_.load(std::memory_order_seq_cst);
  if (!c) return false;
  foveal_fovea f;
  foveal_motion m{};
  // The motion right after the fovea: the same frame, or foveald published in between
  // (once more then; still apart, this read predicts nothing).
  bool paired = false;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (foveal_client_read(c->client, &f) != FOVEAL_OK) return false;
    if (!predict_ || foveal_client_motion(c->client, &m) != FOVEAL_OK) break;  // off, or an older foveald's block
    paired = m.frame == f.frame;
    if (paired || m.frame < f.frame) break;
  }
  out = GazeNow{};
  out.t_ns = out.at_ns = f.t_ns;
  out.ipd_m = c->view.ipd_m;
  out.fovea = f;
  out.view = c->view;
  out.motion = m;
  out.predictable = paired;
  out.offset_known = offset_known_.load(std::memory_order_acquire);
  out.xr_offset_ns = xr_offset_ns_.load(std::memory_order_relaxed);
  // Both bounds without overflow: a time far in the past or ahead is no fresh sample.
  const std::int64_t now = monotonic_ns();
  const bool fresh = f.t_ns > 0 && f.t_ns <= now + kFutureNs && now - f.t_ns < kStaleNs;
  for (int e = 0; e < 2; ++e) {
    out.eye_tracked[e] = fresh && eye_is_tracked(f, e);
    if (out.eye_tracked[e]) out.confidence[e] = std::clamp(f.confidence[e], 0.0f, 1.0f);
  }
  set_directions(out, f);
  for (int e = 0; e < 2; ++e)
    if (!out.eye_tracked[e]) out.confidence[e] = 0;
  return true;
}

GazeSettings GazeFeed::settings() const {
  GazeSettings s;
  const std::uint64_t bits = settings_bits_.load(std::memory_order_relaxed);
  if (bits == 0) return s;
  const std::uint32_t lo = static_cast<std::uint32_t>(bits), hi = static_cast<std::uint32_t>(bits >> 32);
  std::memcpy(&s.sigma[0], &lo, 4);
  std::memcpy(&s.sigma[1], &hi, 4);
  s.from_foveald = true;
  return s;
}

XrTime GazeFeed::to_xr_time(std::int64_t t_ns) const {
  if (!offset_known_.load(std::memory_order_acquire)) return 0;
  const std::int64_t offset = xr_offset_ns_.load(std::memory_order_relaxed);
  XrTime t = 0;
  if (t_ns <= 0 || __builtin_add_overflow(t_ns, offset, &t) || t <= 0) return 0;
  return t;
}

}  // namespace foveal::openxr
