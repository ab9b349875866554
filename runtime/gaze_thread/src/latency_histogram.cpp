#include "foveal/runtime/latency_histogram.hpp"

#include <algorithm>
#include <bit>

namespace foveal {

int LatencyHistogram::bucket(std::int64_t ns) {
  if (ns < kSub) return static_cast<int>(std::max<std::int64_t>(ns, 0));
  const auto u = static_cast<std::uint64_t>(ns);
  const int msb = 63 - std::countl_zero(u);  // >= 6
  const int octave = msb - 5;                // 1.. : values [2^msb, 2^(msb+1))
  const int sub = static_cast<int>((u >> (msb - 6)) & (kSub - 1));
  return std::min(octave * kSub + sub, kSub * kOctaves - 1);
}

std::int64_t LatencyHistogram::bucket_value(int b) {
  if (b < kSub) return b;
  const int octave = b / kSub, sub = b % kSub;
  const int msb = octave + 5;
  // The middle of the bucket (the first octave's buckets are one unit wide).
  const std::int64_t half = msb >= 7 ? std::int64_t{1} << (msb - 7) : 0;
  return (std::int64_t{1} << msb) + (static_cast<std::int64_t>(sub) << (msb - 6)) + half;
}

void LatencyHistogram::add(std::int64_t ns) {
  ++counts_[static_cast<std::size_t>(bucket(ns))];
  ++count_;
  max_ = std::max(max_, ns);
}

std::int64_t LatencyHistogram::percentile(double p) const {
  if (count_ == 0) return 0;
  const auto target = static_cast<std::uint64_t>(p * static_cast<double>(count_ - 1)) + 1;
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < counts_.size(); ++b) {
    seen += counts_[b];
    if (seen >= target) return std::min(bucket_value(static_cast<int>(b)), max_);
  }
  return max_;
}

}  // namespace foveal
