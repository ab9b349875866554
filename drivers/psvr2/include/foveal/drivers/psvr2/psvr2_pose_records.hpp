#pragma once
// The PlayStation VR2's motion records, as public reverse engineering (Monado's psvr2
// driver) describes them; Sony documents none of it. docs/headset.md lists the byte
// layouts, the axis conventions and what has never been checked on a headset.
//
//   status interface 7 (alt setting 1), interrupt IN 0x88: a 32-byte header (display
//     state, proximity, button, IPD dial) followed by 24-byte IMU records (2 kHz)
//   SLAM interface 3, bulk IN 0x83: 512-byte records with the headset's own inside-out
//     tracking pose ("SLA" magic)
// All values are little-endian.
#include <cstdint>
#include <span>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/core/imu_sample.hpp"
#include "foveal/core/pose.hpp"

namespace foveal::usb {

namespace psvr2 {
constexpr int kStatusInterface = 7, kStatusAltSetting = 1;
constexpr std::uint8_t kStatusEndpoint = 0x88;
constexpr int kSlamInterface = 3;
constexpr std::uint8_t kSlamEndpoint = 0x83;

constexpr std::size_t kStatusHeaderBytes = 32;
constexpr std::size_t kStatusIpdByte = 5;   ///< IPD dial, mm (59-72 on the headset; 0 unknown)
constexpr std::size_t kImuRecordBytes = 24;  ///< vts u32, accel i16[3], gyro i16[3], 4 x u16
constexpr std::size_t kStatusTransferBytes = 1024;
constexpr double kImuRateHz = 2000;
constexpr double kGyroDegPerSecPerLsb = 2000.0 / 32767.0;
constexpr double kAccelGPerLsb = 4.0 / 32767.0;

constexpr std::size_t kSlamRecordBytes = 512;
constexpr std::size_t kSlamSize = 4, kSlamTime = 8, kSlamState = 12, kSlamPosition = 16, kSlamOrientation = 28;
constexpr std::size_t kSlamMinSize = kSlamOrientation + 16;  ///< the fields this parser reads
}  // namespace psvr2

/// One IMU record as the headset sends it (device axes, raw counts).
struct Psvr2ImuRecord {
  std::uint32_t vts_us = 0;  ///< the headset's video timestamp, µs (wraps)
  std::int16_t accel[3]{}, gyro[3]{};
  std::uint16_t dp_frame = 0, dp_line = 0, imu_ts_us = 0, status = 0;
};

struct Psvr2StatusReport {
  std::uint8_t display_state = 0, proximity = 0, function_button = 0;
  std::uint8_t ipd_mm = 0;  ///< 0: not reported
  std::vector<Psvr2ImuRecord> imu;  ///< oldest first
};

/// A status transfer. Errors (bad_input) name the byte: shorter than the header, a
/// trailing partial IMU record, an IPD dial value outside 50-80 mm.
Result<Psvr2StatusReport> parse_psvr2_status(std::span<const std::uint8_t> data);

/// An IMU record in SI units on the runtime's head axes (Monado's mapping: x = -gyro[1],
/// y = gyro[2], z = -gyro[0], the same for the accelerometer). t_ns is left to the caller.
ImuSample psvr2_imu_to_sample(const Psvr2ImuRecord& r);

/// One SLAM record as sent (the headset's axes).
struct Psvr2SlamRecord {
  std::uint32_t size = 0;    ///< the record's own size field (512 on the headset)
  std::uint32_t vts_us = 0;  ///< µs, same clock as the IMU's vts
  std::uint32_t state = 0;   ///< 3 while tracking, as far as is known
  float position[3]{};       ///< metres
  float orientation[4]{};    ///< quaternion, w first
};

/// A SLAM transfer. Errors (bad_input) name the byte: wrong magic, too short, a size
/// field that does not fit, non-finite values, an orientation that is not a unit
/// quaternion (pose.hpp's tolerance).
Result<Psvr2SlamRecord> parse_psvr2_slam(std::span<const std::uint8_t> data);

/// The SLAM pose on the runtime's axes (Monado's mapping: position (p2, p1, -p0),
/// orientation w = o0, x = -o2, y = -o1, z = o3), renormalised.
Pose psvr2_slam_to_pose(const Psvr2SlamRecord& r);

}  // namespace foveal::usb
