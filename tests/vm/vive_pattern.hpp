#pragma once
// What the emulated Vive Pro (vm_vive.cpp) sends: its IMU reports from the motion script
// (hmd_motion.hpp) and its configuration, a JSON text the host reads zlib-compressed
// through feature reports. The device clock is the guest's CLOCK_MONOTONIC in 48 MHz
// ticks, wrapping at 2^32 (every 89.5 s) as the headset's does; sample number s is
// taken at s ms and sits in slot s % 3 of the round-robin report. Layouts:
// docs/headset.md (the builders of tests/support). The calibration is inverted here from
// the formula it documents (value = range / 32768 * scale * count - bias, then the Vive
// Pro's axes: the head's with x and z negated), not taken from the parser.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "hmd_motion.hpp"
#include "vive_report_builders.hpp"

namespace foveal::vmtest {

constexpr std::uint16_t kViveVendor = vive::kValveVendor, kViveProduct = vive::kViveProSensorProduct;
constexpr TimeNs kViveSamplePeriodNs = 1'000'000;  // 1000 Hz; a report every third sample
constexpr int kViveGyroRangeCode = 1, kViveAccelRangeCode = 1;  // ±500 °/s, ±4 g

inline double vive_gyro_range() { return M_PI / 180.0 * (250 << kViveGyroRangeCode); }      // rad/s
inline double vive_accel_range() { return double(kGravity) * (2 << kViveAccelRangeCode); }  // m/s^2

/// The emulated headset's calibration and optics: what its configuration says
/// (vive_config_json), deliberately unlike the built-in display model and a headset's
/// near-identity calibration, so a value not read from it shows.
struct ViveConfig {
  glm::dvec3 gyro_bias{0.010, -0.020, 0.015}, gyro_scale{1.02, 0.96, 1.03};
  glm::dvec3 acc_bias{0.05, -0.03, 0.08}, acc_scale{1.01, 0.99, 1.02};
  int eye_width = 1200, eye_height = 1280;
  double lens_separation_m = 0.0655;
  double aspect_x_over_y = 0.9;
  double eye_x_m[2] = {-0.0321, 0.0321};  ///< eye_to_head translation, x
  /// intrinsics [[fx, 0, cx], [0, fy, cy], [0, 0, -1]] per eye (fy = fx * aspect: square
  /// pixels, as a headset's are)
  double fx = 1.05, fy = 0.945, cx[2] = {-0.06, 0.06}, cy = 0.004;
  /// per colour (red, green, blue): the lens centre and coefficients k1..k3
  double center_x[2] = {-0.012, 0.012}, center_y = 0.006;
  double coeffs[3][3] = {{0.205, 0.245, 0.020}, {0.220, 0.240, 0.015}, {0.238, 0.236, 0.011}};
  double grow_for_undistort = 0.6, undistort_r2_cutoff = 1.15;
};

inline const ViveConfig& vive_config() {
  static const ViveConfig c;
  return c;
}

/// The configuration as the headset stores it (a subset of a Vive Pro's keys).
std::string vive_config_json(const ViveConfig& c);

inline std::uint32_t vive_ticks(TimeNs t) { return static_cast<std::uint32_t>(static_cast<std::uint64_t>(t) * 48 / 1000); }

/// The counts that calibrate to `head` (a head-frame vector) on each IMU axis.
inline void vive_counts(std::int16_t out[3], const glm::dvec3& head, const glm::dvec3& scale, const glm::dvec3& bias,
                        double range) {
  const glm::dvec3 imu(-head.x, head.y, -head.z);
  for (int k = 0; k < 3; ++k)
    out[k] = static_cast<std::int16_t>(
        std::clamp(std::lround((imu[k] + bias[k]) / (scale[k] * range / 32768.0)), -32768L, 32767L));
}

/// The IMU report whose newest sample is number s: samples s-2, s-1 and s.
inline std::vector<std::uint8_t> vive_imu_report(std::uint64_t s) {
  test::ViveImuBuilder r;
  const ViveConfig& c = vive_config();
  for (std::uint64_t k = s - 2; k <= s; ++k) {
    const TimeNs t = static_cast<TimeNs>(k) * kViveSamplePeriodNs;
    const HeadMotion m = vive_motion(t);
    std::int16_t accel[3], gyro[3];
    vive_counts(accel, m.specific_force_head, c.acc_scale, c.acc_bias, vive_accel_range());
    vive_counts(gyro, m.angular_velocity_head, c.gyro_scale, c.gyro_bias, vive_gyro_range());
    r.sample(k % 3, accel, gyro, vive_ticks(t), static_cast<std::uint8_t>(k));
  }
  return r.b;
}

/// The HID report descriptor: vendor page, the IMU input report and the feature reports.
std::vector<std::uint8_t> vive_report_descriptor();

}  // namespace foveal::vmtest
