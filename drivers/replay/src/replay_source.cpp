#include "foveal/drivers/replay_source.hpp"

#include <sys/prctl.h>

#include <cmath>

namespace foveal {

Status ReplayOptions::validate() const {
  if (!std::isfinite(speed) || speed < 0) return bad_input("replay: speed must be >= 0 (0 = as fast as possible)");
  if (start_s && (!std::isfinite(*start_s) || *start_s < 0)) return bad_input("replay: start time must be >= 0 s");
  if (end_s && (!std::isfinite(*end_s) || *end_s <= 0)) return bad_input("replay: end time must be > 0 s");
  if (start_s && end_s && *end_s <= *start_s) return bad_input("replay: end time must be after the start time");
  return {};
}

Status ReplaySource::open() {
  if (Status s = opts_.validate(); !s) return s;
  auto r = GazeLogReader::open(opts_.path);
  if (!r) return r.error();
  reader_.emplace(std::move(r.value()));
  have_pending_ = ended_ = have_t0_ = false;
  loop_offset_ = 0;
  loops_ = 0;
  return {};
}

void ReplaySource::close() {
  reader_.reset();
  started_ = false;
}

Status ReplaySource::start() {
  if (!reader_) return Error{ErrorKind::internal, "replay: start() before open()"};
  auto got = load_next();
  if (!got) return got.error();
  if (!*got) return bad_input(opts_.path + ": no samples inside the requested time window");
  window_first_ = pending_.t_ns;
  // Fine-grained sleeps: the default 50 us timer slack would show in pacing accuracy.
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
  anchored_ = false;  // the clock starts at the first next(), on the reading thread
  started_ = true;
  return {};
}

Status ReplaySource::restart_pass() {
  // The next pass starts one nominal period after the last sample of this one.
  const TimeNs period = static_cast<TimeNs>(1e9 / reader_->header().rate_hz);
  // Log timestamps differ by less than 2^63 (kMaxGazeLogTimeNs); the offset of pass after
  // pass can still pass int64 for a crafted log spanning centuries.
  TimeNs pass = 0;
  if (__builtin_add_overflow(window_last_ - window_first_, period, &pass) || __builtin_add_overflow(loop_offset_, pass, &loop_offset_))
    return bad_input(opts_.path + ": --loop: the log spans too long a time to repeat it (timestamps would pass int64)");
  ++loops_;
  return reader_->rewind();
}

Result<bool> ReplaySource::load_next() {
  for (;;) {
    GazeSample& s = pending_;  // read in place: this is the hot path at speed 0
    auto got = reader_->next(s);
    if (!got) return got.error();
    bool past_end = !*got;
    if (!past_end) {
      if (!have_t0_) {
        log_t0_ = s.t_ns;
        have_t0_ = true;
      }
      const double rel_s = static_cast<double>(s.t_ns - log_t0_) / 1e9;
      if (opts_.start_s && rel_s < *opts_.start_s) continue;
      past_end = opts_.end_s && rel_s > *opts_.end_s;
    }
    if (past_end) {
      if (!opts_.loop || !started_) return false;
      if (Status st = restart_pass(); !st) return st.error();
      continue;
    }
    window_last_ = s.t_ns;
    if (__builtin_add_overflow(s.t_ns, loop_offset_, &s.t_ns))
      return bad_input(opts_.path + ": --loop: the log spans too long a time to repeat it (timestamps would pass int64)");
    have_pending_ = true;
    return true;
  }
}

ReadResult ReplaySource::next(std::chrono::nanoseconds timeout) {
  ReadResult r;
  if (!started_) {
    r.status = ReadStatus::error;
    r.error = {ErrorKind::internal, "replay: next() before start()"};
    return r;
  }
  if (!have_pending_) {
    if (ended_) {
      r.status = ReadStatus::end;
      return r;
    }
    auto got = load_next();
    if (!got) {
      r.status = ReadStatus::error;
      r.error = got.error();
      return r;
    }
    if (!*got) {
      ended_ = true;
      r.status = ReadStatus::end;
      return r;
    }
  }
  if (!anchored_) {
    pacer_.start(window_first_);
    anchored_ = true;
  }
  const TimeNs due = pacer_.due(pending_.t_ns);
  if (!pacer_.wait(due, timeout)) {
    r.status = ReadStatus::timeout;
    return r;
  }
  r.status = ReadStatus::sample;
  r.sample = pending_;
  r.device_t_ns = window_last_;  // the row's own time, before any loop's offset
  r.sample.t_ns = due;
  have_pending_ = false;
  return r;
}

SourceInfo ReplaySource::info() const {
  SourceInfo i;
  i.driver = "replay";
  i.path = opts_.path;
  const auto slash = opts_.path.find_last_of('/');
  i.name = slash == std::string::npos ? opts_.path : opts_.path.substr(slash + 1);
  i.nominal_rate_hz = reader_ ? reader_->header().rate_hz : 0;
  i.head_pose = reader_ && reader_->header().has_head_pose();
  return i;
}

}  // namespace foveal
