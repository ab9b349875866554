#pragma once
// One time base everywhere: CLOCK_MONOTONIC in nanoseconds (docs/conventions.md).
#include <cstdint>

namespace foveal {

using TimeNs = std::int64_t;

constexpr TimeNs kNsPerMs = 1'000'000;
constexpr TimeNs kNsPerSec = 1'000'000'000;

/// Current CLOCK_MONOTONIC time in ns. Thread-safe.
TimeNs monotonic_now_ns();

/// Sleeps until the absolute CLOCK_MONOTONIC time `t` (returns at once if past).
void sleep_until_ns(TimeNs t);

}  // namespace foveal
