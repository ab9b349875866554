#pragma once
// Builds the Vive's IMU and configuration reports byte by byte at the offsets
// docs/headset.md lists: for the parsers' unit tests and the emulated headset of the VM test.
#include <algorithm>
#include <string>

#include "foveal/drivers/vive/vive_reports.hpp"
#include "report_bytes.hpp"

namespace foveal::test {

/// A Vive IMU input report (0x20) with three samples.
struct ViveImuBuilder : Bytes {
  ViveImuBuilder() : Bytes(vive::kImuReportBytes) { b[0] = vive::kImuReportId; }
  void sample(std::size_t slot, const std::int16_t accel[3], const std::int16_t gyro[3], std::uint32_t ticks,
              std::uint8_t seq) {
    const std::size_t o = 1 + slot * vive::kImuSampleBytes;
    for (std::size_t k = 0; k < 3; ++k) {
      i16(o + 2 * k, accel[k]);
      i16(o + 6 + 2 * k, gyro[k]);
    }
    u32(o + 12, ticks);
    b[o + 16] = seq;
  }
};

/// The 0x11 feature reports that carry `json`, compressed, ending with a length-0 one.
inline std::vector<std::vector<std::uint8_t>> vive_config_reports(const std::string& json) {
  const std::vector<std::uint8_t> z = vive::deflate_zlib(json);
  std::vector<std::vector<std::uint8_t>> out;
  for (std::size_t at = 0;; at += vive::kConfigPayloadMax) {
    std::vector<std::uint8_t> r(vive::kConfigReportBytes, 0);
    r[0] = vive::kConfigReadReportId;
    const std::size_t n = at < z.size() ? std::min(vive::kConfigPayloadMax, z.size() - at) : 0;
    r[1] = static_cast<std::uint8_t>(n);
    std::memcpy(r.data() + 2, z.data() + std::min(at, z.size()), n);
    out.push_back(r);
    if (n == 0) break;
  }
  return out;
}

}  // namespace foveal::test
