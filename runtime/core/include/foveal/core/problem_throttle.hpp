#pragma once
// How drivers log a device's recurring problems: the first ten in full, then one in a
// thousand, so that a misbehaving device cannot flood the log. Not thread-safe: one per
// source, used on its reading thread.
#include <cstdint>

namespace foveal {

class ProblemThrottle {
 public:
  /// Counts one problem; true when this one should be logged.
  bool count() {
    ++n_;
    return n_ <= 10 || n_ % 1000 == 0;
  }
  std::uint64_t problems() const { return n_; }

 private:
  std::uint64_t n_ = 0;
};

}  // namespace foveal
