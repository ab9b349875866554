#pragma once
// What the emulated PS VR2 (vm_psvr2.cpp --pose) sends about the head: SLAM pose
// records (512 bytes, bulk, interface 3) and status transfers (a 32-byte header, then
// 24-byte IMU records, interrupt, interface 7), from the motion script (hmd_motion.hpp)
// at the guest's CLOCK_MONOTONIC time. The device clock is that time in microseconds,
// wrapping at 2^32 as the headset's does. Layouts: docs/headset.md (the builders of
// tests/support); the axes are written out here from the mapping it documents
// (Monado's), not taken from the parser: SLAM position (p0, p1, p2) = head (-z, y, x),
// SLAM orientation (o0..o3) = (w, -y, -x, z); IMU vectors (v0, v1, v2) = head (-z, -x, y).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hmd_motion.hpp"
#include "psvr2_pose_builders.hpp"

namespace foveal::vmtest {

constexpr TimeNs kPsvr2ImuPeriodNs = 500'000;    // 2000 Hz
constexpr int kPsvr2ImuPerTransfer = 10;         // one status transfer every 5 ms
constexpr TimeNs kPsvr2SlamPeriodNs = 8'000'000;  // 125 Hz
constexpr std::uint8_t kPsvr2IpdDialMm = 66;

inline std::uint32_t psvr2_device_us(TimeNs t) { return static_cast<std::uint32_t>(static_cast<std::uint64_t>(t / 1000)); }

/// The SLAM record of the pose at time t.
inline std::vector<std::uint8_t> psvr2_slam_record(TimeNs t) {
  const HeadMotion m = psvr2_motion(t);
  const glm::dvec3& p = m.position_m;
  const glm::dquat& q = m.orientation;
  const float pos[3] = {static_cast<float>(-p.z), static_cast<float>(p.y), static_cast<float>(p.x)};
  const float quat[4] = {static_cast<float>(q.w), static_cast<float>(-q.y), static_cast<float>(-q.x),
                         static_cast<float>(q.z)};
  return test::Psvr2SlamBuilder(psvr2_device_us(t), pos, quat).b;
}

/// A head-frame vector as the headset's counts, `per_count` units each.
inline void psvr2_counts(std::int16_t out[3], const glm::dvec3& head, double per_count) {
  const double device[3] = {-head.z, -head.x, head.y};
  for (int k = 0; k < 3; ++k)
    out[k] = static_cast<std::int16_t>(std::clamp(std::lround(device[k] / per_count), -32767L, 32767L));
}

/// A status transfer: the header, then the IMU records at t0, t0 + period, ...
inline std::vector<std::uint8_t> psvr2_status_transfer(TimeNs t0, int records) {
  test::Psvr2StatusBuilder r(static_cast<std::size_t>(records), kPsvr2IpdDialMm);
  r.b[0] = 1;  // display link up
  for (int i = 0; i < records; ++i) {
    const TimeNs t = t0 + i * kPsvr2ImuPeriodNs;
    const HeadMotion m = psvr2_motion(t);
    std::int16_t accel[3], gyro[3];
    psvr2_counts(accel, m.specific_force_head / double(kGravity), usb::psvr2::kAccelGPerLsb);
    psvr2_counts(gyro, m.angular_velocity_head * (180.0 / M_PI), usb::psvr2::kGyroDegPerSecPerLsb);
    r.imu(static_cast<std::size_t>(i), psvr2_device_us(t), accel, gyro);
  }
  return r.b;
}

}  // namespace foveal::vmtest
