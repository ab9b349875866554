#pragma once
// What the emulated Vive-class headset (vm_vive.cpp) sends: its IMU reports from the
// motion script (hmd_motion.hpp) and its configuration, a JSON text the host reads
// zlib-compressed through feature reports. The device clock is the guest's
// CLOCK_MONOTONIC in 48 MHz ticks, wrapping at 2^32 (every 89.5 s) as the headset's does.
//
// The reports as Monado's vive driver documents them (facts, written out here
// independently of foveal's parser), all little-endian:
//   0x20 input, 52 bytes: three samples of 17 bytes (accelerometer and gyroscope as
//        three int16 each, a uint32 tick time, a uint8 sequence number), updated
//        round-robin: sample number s sits in slot s % 3;
//   0x01 feature: gyroscope and accelerometer ranges (index i: 250 << i deg/s, 2 << i g);
//   0x10 feature: starts a configuration read; 0x11 feature: [0x11, n, n bytes] with
//        the next n <= 62 bytes of the compressed configuration, n = 0 at the end;
//   0x05 feature: firmware version.
// A calibrated value is range / 32768 * scale * count - bias (per axis, the config's
// "imu" scale and bias); the Vive Pro's IMU axes are the head's with x and z negated.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hmd_motion.hpp"

namespace foveal::vmtest {

constexpr std::uint16_t kViveVendor = 0x28de, kViveProduct = 0x2000;  // the headset's IMU ("Lighthouse FPGA RX")
constexpr std::uint8_t kViveImuReport = 0x20, kViveRangeReport = 0x01, kViveFirmwareReport = 0x05,
                       kViveConfigStart = 0x10, kViveConfigRead = 0x11;
constexpr std::size_t kViveImuReportBytes = 52, kViveFeatureBytes = 64, kViveConfigChunk = 62;
constexpr TimeNs kViveSamplePeriodNs = 1'000'000;  // 1000 Hz; a report every third sample
constexpr int kViveGyroRangeIndex = 1, kViveAccelRangeIndex = 1;  // 500 deg/s, 4 g

inline double vive_gyro_range() { return M_PI / 180.0 * (250 << kViveGyroRangeIndex); }  // rad/s
inline double vive_accel_range() { return kGravity * (2 << kViveAccelRangeIndex); }       // m/s^2

/// The emulated headset's calibration and optics (what its config JSON says).
struct ViveConfig {
  glm::dvec3 gyro_bias{0.010, -0.020, 0.015}, gyro_scale{1.02, 0.96, 1.03};
  glm::dvec3 acc_bias{0.05, -0.03, 0.08}, acc_scale{1.01, 0.99, 1.02};
  int eye_width = 1200, eye_height = 1280;
  double lens_separation_m = 0.0655;
  double eye_x_m[2] = {-0.0321, 0.0321};  ///< eye_to_head translation, x
  /// intrinsics [[fx, 0, cx], [0, fy, cy], [0, 0, -1]] per eye
  double fx = 1.05, fy = 1.18, cx[2] = {-0.06, 0.06}, cy = 0.004;
  /// per colour (red, green, blue): the lens centre and coefficients k1..k3
  double center_x[2] = {-0.012, 0.012}, center_y = 0.006;
  double coeffs[3][3] = {{0.205, 0.245, 0.020}, {0.220, 0.240, 0.015}, {0.238, 0.236, 0.011}};
};

inline const ViveConfig& vive_config() {
  static const ViveConfig c;
  return c;
}

/// The config as the headset stores it (a subset of a Vive Pro's keys).
std::string vive_config_json(const ViveConfig& c);

inline std::uint32_t vive_ticks(TimeNs t) {
  return static_cast<std::uint32_t>(static_cast<std::uint64_t>(t) * 48 / 1000);
}

/// The counts that calibrate to `value` on each axis (IMU frame).
inline void vive_counts(std::uint8_t* out, const glm::dvec3& value, const glm::dvec3& scale, const glm::dvec3& bias,
                        double range) {
  for (int i = 0; i < 3; ++i) {
    const double c = (value[i] + bias[i]) / (scale[i] * range / 32768.0);
    const auto v = static_cast<std::int16_t>(std::clamp(std::lround(c), -32768L, 32767L));
    out[2 * i] = static_cast<std::uint8_t>(v);
    out[2 * i + 1] = static_cast<std::uint8_t>(static_cast<std::uint16_t>(v) >> 8);
  }
}

/// The IMU report whose newest sample is number s (taken at s * period): samples s-2,
/// s-1 and s in their round-robin slots.
inline std::vector<std::uint8_t> vive_imu_report(std::uint64_t s) {
  std::vector<std::uint8_t> r(kViveImuReportBytes, 0);
  r[0] = kViveImuReport;
  const ViveConfig& c = vive_config();
  for (std::uint64_t k = s - 2; k <= s; ++k) {
    const TimeNs t = static_cast<TimeNs>(k) * kViveSamplePeriodNs;
    const HeadMotion m = vive_motion(t);
    const auto imu = [](const glm::dvec3& head) { return glm::dvec3(-head.x, head.y, -head.z); };
    std::uint8_t* p = r.data() + 1 + 17 * (k % 3);
    vive_counts(p, imu(m.specific_force_head), c.acc_scale, c.acc_bias, vive_accel_range());
    vive_counts(p + 6, imu(m.angular_velocity_head), c.gyro_scale, c.gyro_bias, vive_gyro_range());
    const std::uint32_t ticks = vive_ticks(t);
    for (int b = 0; b < 4; ++b) p[12 + b] = static_cast<std::uint8_t>(ticks >> (8 * b));
    p[16] = static_cast<std::uint8_t>(k);
  }
  return r;
}

/// The HID report descriptor: vendor page, the IMU input report and the feature reports.
std::vector<std::uint8_t> vive_report_descriptor();

}  // namespace foveal::vmtest
