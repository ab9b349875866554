#pragma once
// The tracking data the VM feeder sends for its k-th report, so the reader can check
// every decoded value: k is recovered from the timestamp.
#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "hutrr74_reports.hpp"

namespace foveal::vmtest {

constexpr std::uint64_t kBaseUs = 1'000'000;
constexpr std::uint64_t kPeriodUs = 8333;  // 120 Hz
constexpr std::uint16_t kVendor = 0x1209, kProduct = 0xf0ee;

inline test::hutrr74::Tracking pattern(std::uint64_t k) {
  test::hutrr74::Tracking t;
  t.timestamp_us = kBaseUs + k * kPeriodUs;
  const auto i = static_cast<std::int32_t>(k % 100000);
  t.gaze_x_um = 20000 + (i * 7919) % 480000;   // over a 500 x 300 mm plane
  t.gaze_y_um = 10000 + (i * 3571) % 280000;
  t.left_um = {218000 + (i % 7) * 100, 150000 - (i % 5) * 100, 600000 + (i % 11) * 1000};
  t.right_um = {282000 - (i % 3) * 100, 150000 + (i % 13) * 100, 600000 + (i % 11) * 1000};
  return t;
}

/// k from a decoded device timestamp in ns, if it is one of the pattern's.
inline std::optional<std::uint64_t> index_of(std::int64_t device_ns) {
  if (device_ns < 0 || device_ns % 1000 != 0) return std::nullopt;
  const auto us = static_cast<std::uint64_t>(device_ns / 1000);
  if (us < kBaseUs || (us - kBaseUs) % kPeriodUs != 0) return std::nullopt;
  return (us - kBaseUs) / kPeriodUs;
}

/// The expected head-frame direction of one eye (written out here, not taken from the
/// driver): from the eye to the gaze point, screen y down -> head y up.
inline glm::dvec3 expected_direction(const test::hutrr74::Tracking& t, int eye) {
  const auto& e = eye == 0 ? t.left_um : t.right_um;
  const glm::dvec3 v{(t.gaze_x_um - e[0]) / 1000.0, -(t.gaze_y_um - e[1]) / 1000.0, -e[2] / 1000.0};
  return v / glm::length(v);
}

}  // namespace foveal::vmtest
