#pragma once
// The HTC Vive / Vive Pro headset's HID reports on its Valve sensor device (28de:2000 on
// the Vive, 28de:2300 on the Vive Pro), as Monado's vive driver and ouvrt document them;
// HTC publishes none of it. docs/headset.md lists the byte layouts and what has never
// been checked on a headset. All values are little-endian.
//
//   input report 0x20 (52 bytes): three IMU samples of 17 bytes, round-robin
//   feature 0x01: the IMU's full-scale ranges
//   feature 0x10 then 0x11 (repeated): the zlib-compressed configuration JSON
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::vive {

constexpr std::uint16_t kValveVendor = 0x28de;
constexpr std::uint16_t kViveSensorProduct = 0x2000, kViveProSensorProduct = 0x2300;

constexpr std::uint8_t kImuReportId = 0x20;
constexpr std::size_t kImuReportBytes = 52;
constexpr std::size_t kImuSampleBytes = 17;  ///< accel i16[3], gyro i16[3], time u32, seq u8
constexpr double kImuClockHz = 48e6;         ///< the sample time counter's rate
constexpr double kImuRateHz = 1000;          ///< nominal

constexpr std::uint8_t kRangeReportId = 0x01;
constexpr std::size_t kRangeReportBytes = 64;  ///< id, gyro range code, accel range code, 61 unknown

constexpr std::uint8_t kConfigStartReportId = 0x10, kConfigReadReportId = 0x11;
constexpr std::size_t kConfigReportBytes = 64;   ///< id, payload length, up to 62 payload bytes
constexpr std::size_t kConfigPayloadMax = 62;
constexpr std::size_t kConfigCompressedMax = 64 * 1024;  ///< the headset's is about 4 KiB
constexpr std::size_t kConfigJsonMax = 1024 * 1024;

struct ImuRawSample {
  std::array<std::int16_t, 3> accel{}, gyro{};
  std::uint32_t time = 0;  ///< ticks of kImuClockHz (wraps every ~89 s)
  std::uint8_t seq = 0;
};

struct ImuReport {
  std::array<ImuRawSample, 3> samples{};
};

/// Parses input report 0x20. Errors (bad_input) name the byte: another report id, a
/// length other than 52, three sequence numbers that are not consecutive mod 256 in
/// some rotation.
Result<ImuReport> parse_imu_report(std::span<const std::uint8_t> data);

/// The samples of `r` not yet seen, oldest first: the three slots are rewritten
/// round-robin, so a report repeats up to two samples of the previous one. `last_seq`:
/// the newest sequence number handled so far (none: all three are new).
std::vector<ImuRawSample> new_imu_samples(const ImuReport& r, std::optional<std::uint8_t> last_seq);

/// The IMU's full-scale ranges from feature report 0x01 (MPU-6500 codes 0-4:
/// gyro ±250·2^code °/s, accel ±2·2^code g; Monado's reading).
struct ImuRange {
  double gyro_rad_s = 8.726646;  ///< ±500 °/s, the default when the report is unreadable
  double accel_m_s2 = 39.2266;   ///< ±4 g
};
Result<ImuRange> parse_range_report(std::span<const std::uint8_t> data);

/// Collects the configuration from consecutive 0x11 feature reports (a report with
/// payload length 0 ends it) and inflates it.
class ConfigAssembler {
 public:
  /// Adds one 0x11 report. Errors (bad_input): another id, a payload length over 62 or
  /// longer than the report, more than kConfigCompressedMax bytes in all.
  Status add(std::span<const std::uint8_t> report);
  bool complete() const { return complete_; }
  std::size_t compressed_bytes() const { return data_.size(); }
  /// The JSON text (zlib inflate of everything added). Errors: not complete, not a
  /// zlib stream, truncated, over kConfigJsonMax.
  Result<std::string> json() const;

 private:
  std::vector<std::uint8_t> data_;
  bool complete_ = false;
};

/// zlib-inflates `data` (one complete zlib stream, at most `max_out` bytes out).
Result<std::string> inflate_zlib(std::span<const std::uint8_t> data, std::size_t max_out);
/// zlib-deflates `text` (tests and the emulated headset in the VM test).
std::vector<std::uint8_t> deflate_zlib(const std::string& text);

}  // namespace foveal::vive
