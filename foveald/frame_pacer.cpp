#include "frame_pacer.hpp"

#include <algorithm>

namespace foveal::daemon {

namespace {

constexpr std::size_t kRecentFrames = 16;
// The margin starts at 2 ms, grows by 1 ms on each miss (to a period at most) and gives
// back 0.25 ms after 30 frames in a row on time, never below 1 ms: timer wake-ups and
// the present's own copy live in it.
constexpr TimeNs kStartMargin = 2 * kNsPerMs, kMinMargin = kNsPerMs, kGrow = kNsPerMs, kShrink = kNsPerMs / 4;
constexpr std::uint64_t kHitsToShrink = 30;

}  // namespace

Result<Pacing> parse_pacing(const std::string& s) {
  if (s == "asap") return Pacing::asap;
  if (s == "jit") return Pacing::jit;
  return bad_input("--pacing '" + s + "': expected asap or jit");
}

const char* pacing_name(Pacing p) { return p == Pacing::jit ? "jit" : "asap"; }

FramePacer::FramePacer(Pacing pacing, double refresh_hz)
    : pacing_(pacing),
      period_ns_(refresh_hz > 0 ? static_cast<TimeNs>(1e9 / refresh_hz) : 0),
      margin_ns_(kStartMargin) {}

TimeNs FramePacer::work_estimate() const {
  return recent_work_.empty() ? 0 : *std::max_element(recent_work_.begin(), recent_work_.end());
}

FramePlan FramePacer::plan(TimeNs now, std::optional<TimeNs> last_shown) const {
  const TimeNs work = work_estimate();
  if (period_ns_ <= 0 || !last_shown) return {now, now + work};
  // The first refresh after the last one shown that the frame can still make.
  const TimeNs lead = pacing_ == Pacing::jit ? work + margin_ns_ : work;
  const TimeNs earliest = now + lead;
  const TimeNs periods = std::max<TimeNs>(1, (earliest - *last_shown + period_ns_ - 1) / period_ns_);
  const TimeNs target = *last_shown + periods * period_ns_;
  if (pacing_ == Pacing::asap) return {now, target};
  return {std::max(now, target - lead), target};
}

void FramePacer::shown(TimeNs start, TimeNs ready, TimeNs shown_at, TimeNs target) {
  // The first frame compiles shaders and uploads the scene: neither its work nor its
  // lateness says anything of the next frames.
  if (++frames_ == 1) return;
  recent_work_.push_back(std::max<TimeNs>(0, ready - start));
  if (recent_work_.size() > kRecentFrames) recent_work_.pop_front();
  if (period_ns_ <= 0 || target <= 0) return;
  // Late by more than half a period: it was shown at a later refresh than planned.
  if (shown_at > target + period_ns_ / 2) {
    ++misses_;
    hits_in_a_row_ = 0;
    // A step, not what the frame lacked: the work estimate already follows slow frames,
    // and one hitch must not cost every later frame its latency.
    if (pacing_ == Pacing::jit) margin_ns_ = std::min(period_ns_, margin_ns_ + kGrow);
  } else if (++hits_in_a_row_ >= kHitsToShrink && pacing_ == Pacing::jit) {
    margin_ns_ = std::max(kMinMargin, margin_ns_ - kShrink);
    hits_in_a_row_ = 0;
  }
}

nlohmann::json FramePacer::json() const {
  return {{"pacing", pacing_name(pacing_)},
          {"refresh_hz", period_ns_ > 0 ? 1e9 / static_cast<double>(period_ns_) : 0.0},
          {"margin_ms", pacing_ == Pacing::jit ? nlohmann::json(margin_ms()) : nlohmann::json(nullptr)},
          {"misses", misses_},
          {"frames", frames_},
          {"work_ms_max_recent", static_cast<double>(work_estimate()) * 1e-6}};
}

}  // namespace foveal::daemon
