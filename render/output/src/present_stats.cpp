#include "foveal/render/present_stats.hpp"

#include <algorithm>
#include <cmath>

namespace foveal::render {

namespace {
constexpr std::size_t kIntervals = 1024;
}

PresentStats::PresentStats(double refresh_hz) : refresh_hz_(refresh_hz > 0 ? refresh_hz : 0) {}

void PresentStats::record(std::int64_t t_ns, std::optional<std::uint64_t> vblank) {
  if (presented_ > 0 && last_t_) {
    const double dt_ms = static_cast<double>(t_ns - *last_t_) * 1e-6;
    if (intervals_ms_.size() < kIntervals) intervals_ms_.push_back(dt_ms);
    else intervals_ms_[(presented_ - 1) % kIntervals] = dt_ms;
    if (vblank && last_vblank_ && *vblank > *last_vblank_) {
      missed_vblank_ += *vblank - *last_vblank_ - 1;
      ++counted_vblank_;
    } else if (refresh_hz_ > 0) {
      // A frame is late once more than half a period beyond its refresh.
      const double periods = std::round(dt_ms * refresh_hz_ * 1e-3);
      if (periods > 1) missed_clock_ += static_cast<std::uint64_t>(periods) - 1;
      ++counted_clock_;
    }
  }
  if (vblank && last_vblank_ && *vblank <= *last_vblank_) fake_vblank_ = true;
  ++presented_;
  last_t_ = t_ns;
  // Nobody taking them (a caller that does not record latency) must not grow memory.
  if (untaken_.size() >= kIntervals) untaken_.erase(untaken_.begin());
  untaken_.push_back(t_ns);
  last_vblank_ = vblank;
}

std::optional<std::uint64_t> PresentStats::missed() const {
  if (presented_ >= 2 && counted_vblank_ + counted_clock_ == 0) return std::nullopt;
  return missed_vblank_ + missed_clock_;
}

nlohmann::json PresentStats::json() const {
  nlohmann::json j = {{"presented", presented_}, {"refresh_hz", refresh_hz_}};
  const auto m = missed();
  j["missed"] = m ? nlohmann::json(*m) : nlohmann::json(nullptr);
  j["missed_from"] = counted_vblank_ >= counted_clock_ && counted_vblank_ > 0 ? nlohmann::json("vblank")
                     : counted_clock_ > 0                                    ? nlohmann::json("clock")
                                                                             : nlohmann::json(nullptr);
  if (!intervals_ms_.empty()) {
    std::vector<double> v = intervals_ms_;
    std::sort(v.begin(), v.end());
    auto at = [&](double q) { return v[std::min(v.size() - 1, static_cast<std::size_t>(q * double(v.size() - 1) + 0.5))]; };
    j["interval_ms"] = {{"median", at(0.5)}, {"p99", at(0.99)}, {"max", v.back()}};
  }
  return j;
}

std::vector<std::int64_t> PresentStats::take_shown() {
  std::vector<std::int64_t> t;
  t.swap(untaken_);
  return t;
}

}  // namespace foveal::render
