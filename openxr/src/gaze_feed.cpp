#include "gaze_feed.hpp"

#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>

namespace foveal::openxr {

namespace {

constexpr auto kPoll = std::chrono::milliseconds(100);  // how soon a stop or a return is seen
constexpr std::int64_t kStaleNs = 250'000'000;  // a sample this old (paused foveald) is not tracking
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

}  // namespace

GazeFeed::GazeFeed(std::function<bool(std::int64_t, XrTime&)> to_xr_time, std::function<void(const char*)> log)
    : to_xr_time_(std::move(to_xr_time)), log_(std::move(log)) {
  // An app that starts with foveald running has gaze, and its times, from its first frame.
  measure_offset(monotonic_ns());
  check_connection();
  thread_ = std::thread([this] { run(); });
}

void GazeFeed::measure_offset(std::int64_t now) {
  // The runtime's clock differs from CLOCK_MONOTONIC by its own offset: measured here,
  // used as plain arithmetic on the per-frame paths.
  XrTime xr = 0;
  if (!to_xr_time_(now, xr)) return;
  xr_offset_ns_.store(xr - now, std::memory_order_relaxed);
  offset_known_.store(true, std::memory_order_release);
}

GazeFeed::~GazeFeed() {
  stop_.store(true);
  thread_.join();
  if (Connection* c = current_.exchange(nullptr)) retired_.push_back(c);
  for (Connection* c : retired_) {
    foveal_client_close(c->client);
    delete c;
  }
}

void GazeFeed::run() {
  std::int64_t next_offset = monotonic_ns() + kOffsetEveryNs;
  while (!stop_.load()) {
    const std::int64_t now = monotonic_ns();
    if (now >= next_offset) {
      measure_offset(now);
      next_offset = now + kOffsetEveryNs;
    }
    check_connection();
    std::this_thread::sleep_for(kPoll);
  }
}

void GazeFeed::check_connection() {
  if (Connection* c = current_.load(std::memory_order_acquire)) {
    foveal_fovea f;
    const int rc = foveal_client_read(c->client, &f);
    // BAD_DATA: the block was cut short or holds what foveald never writes; a new
    // mapping (of a restarted foveald's block) is the way back.
    if (rc != FOVEAL_ERR_NO_WRITER && rc != FOVEAL_ERR_DEAD_WRITER && rc != FOVEAL_ERR_BAD_DATA) return;
    current_.store(nullptr, std::memory_order_release);
    retired_.push_back(c);
    log_(rc == FOVEAL_ERR_NO_WRITER    ? "foveald stopped: eye gaze inactive until it is back"
         : rc == FOVEAL_ERR_DEAD_WRITER ? "foveald stopped answering: eye gaze inactive until it is back"
                                        : "foveald's block holds bad data: eye gaze inactive until it is back");
    said_lost_ = true;
  }
  foveal_error err{};
  foveal_client* client = foveal_client_open(nullptr, &err);
  if (!client) {
    if (!said_lost_ && !said_waiting_) {
      char line[320];
      std::snprintf(line, sizeof line, "no gaze from foveald yet (%s); eye gaze inactive until it serves", err.message);
      log_(line);
      said_waiting_ = true;
    }
    return;
  }
  auto* c = new Connection{client, {}};
  if (foveal_client_view(client, &c->view) != FOVEAL_OK) {
    // An older foveald's block, or one still starting: try again on the next poll.
    foveal_client_close(client);
    delete c;
    return;
  }
  current_.store(c, std::memory_order_release);
  if (said_lost_ || said_waiting_) log_("foveald serves: eye gaze active");
  said_lost_ = said_waiting_ = false;
}

bool GazeFeed::read(GazeNow& out) const {
  const Connection* c = current_.load(std::memory_order_acquire);
  if (!c) return false;
  foveal_fovea f;
  if (foveal_client_read(c->client, &f) != FOVEAL_OK) return false;
  out = GazeNow{};
  out.t_ns = f.t_ns;
  out.ipd_m = c->view.ipd_m;
  const bool fresh = monotonic_ns() - f.t_ns < kStaleNs;
  XrVector3f sum{0, 0, 0};
  for (int e = 0; e < 2; ++e) {
    float d[3];
    if (!fresh || !eye_is_tracked(f, e) || foveal_view_direction(&c->view, &f, e, d) != FOVEAL_OK) continue;
    out.eye_tracked[e] = true;
    out.eye_dir[e] = {d[0], d[1], d[2]};
    out.confidence[e] = f.confidence[e] > 1.0f ? 1.0f : f.confidence[e];
    sum = {sum.x + d[0], sum.y + d[1], sum.z + d[2]};
  }
  const float n = std::sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z);
  out.tracked = n > 1e-6f;
  if (out.tracked) out.combined = {sum.x / n, sum.y / n, sum.z / n};
  return true;
}

XrTime GazeFeed::to_xr_time(std::int64_t t_ns) const {
  if (!offset_known_.load(std::memory_order_acquire)) return 0;
  return t_ns + xr_offset_ns_.load(std::memory_order_relaxed);
}

}  // namespace foveal::openxr
