#pragma once
// Fixed-size log-scale histogram of durations: constant memory over hours of samples,
// percentiles to within 2% (64 sub-buckets per power of two).
#include <array>
#include <cstdint>

namespace foveal {

class LatencyHistogram {
 public:
  void add(std::int64_t ns);
  /// Value at percentile p in [0, 1], in ns (0 when empty).
  std::int64_t percentile(double p) const;
  std::uint64_t count() const { return count_; }
  std::int64_t max() const { return max_; }
  void clear() { *this = LatencyHistogram{}; }

 private:
  static constexpr int kSub = 64;
  static constexpr int kOctaves = 40;  // up to ~2^40 ns = 18 minutes
  static int bucket(std::int64_t ns);
  static std::int64_t bucket_value(int b);
  std::array<std::uint32_t, kSub * kOctaves> counts_{};
  std::uint64_t count_ = 0;
  std::int64_t max_ = 0;
};

}  // namespace foveal
