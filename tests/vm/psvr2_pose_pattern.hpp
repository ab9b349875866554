#pragma once
// What the emulated PS VR2 (vm_psvr2.cpp --pose) sends about the head: SLAM pose
// records (512 bytes, bulk, interface 3) and status transfers (a 32-byte header, then
// IMU records of 24 bytes, interrupt, interface 7), from the motion script
// (hmd_motion.hpp) at the guest's CLOCK_MONOTONIC time. The device clock is that time
// in microseconds, wrapping at 2^32 as the headset's does.
//
// The layouts and the headset's axes as Monado's psvr2 driver documents them (facts,
// written out here independently of foveal's parser): all values little-endian;
// SLAM position (p0, p1, p2) is head (z, y, x) with z negated; SLAM orientation
// (o0..o3) is the quaternion w, -y, -x, z of the pose before a fixed correction of
// 90 degrees about z; IMU gyro (g0, g1, g2) is head (-z, -x, y) at 2000/32767 deg/s per
// count, accelerometer likewise at 4 g / 32767.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "hmd_motion.hpp"

namespace foveal::vmtest {

constexpr int kPsvr2SlamInterface = 3, kPsvr2StatusInterface = 7;
constexpr std::size_t kPsvr2SlamBytes = 512, kPsvr2StatusHeaderBytes = 32, kPsvr2ImuBytes = 24;
constexpr TimeNs kPsvr2ImuPeriodNs = 500'000;       // 2000 Hz
constexpr int kPsvr2ImuPerTransfer = 10;             // one status transfer every 5 ms
constexpr TimeNs kPsvr2SlamPeriodNs = 8'000'000;     // 125 Hz
constexpr std::uint8_t kPsvr2IpdDialMm = 66;
constexpr double kPsvr2GyroDegPerCount = 2000.0 / 32767.0, kPsvr2AccelGPerCount = 4.0 / 32767.0;

struct LeBytes {
  std::vector<std::uint8_t> b;
  explicit LeBytes(std::size_t n) : b(n, 0) {}
  void u16(std::size_t at, std::uint16_t v) {
    b[at] = static_cast<std::uint8_t>(v);
    b[at + 1] = static_cast<std::uint8_t>(v >> 8);
  }
  void i16(std::size_t at, std::int16_t v) { u16(at, static_cast<std::uint16_t>(v)); }
  void u32(std::size_t at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) b[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (8 * k));
  }
  void f32(std::size_t at, double d) {
    const float f = static_cast<float>(d);
    std::uint32_t v;
    std::memcpy(&v, &f, 4);
    u32(at, v);
  }
};

inline std::uint32_t psvr2_device_us(TimeNs t) { return static_cast<std::uint32_t>(static_cast<std::uint64_t>(t / 1000)); }

inline std::int16_t counts(double value, double per_count) {
  return static_cast<std::int16_t>(std::clamp(std::lround(value / per_count), -32767L, 32767L));
}

/// The SLAM record of the pose at time t.
inline std::vector<std::uint8_t> psvr2_slam_record(TimeNs t) {
  const HeadMotion m = psvr2_motion(t);
  // Undo the driver-side correction (90 degrees about z) before writing the raw quaternion.
  const glm::dquat correction = glm::angleAxis(M_PI / 2, glm::dvec3(0, 0, 1));
  const glm::dquat q = glm::conjugate(correction) * m.orientation;
  LeBytes r(kPsvr2SlamBytes);
  r.b[0] = 'S';
  r.b[1] = 'L';
  r.b[2] = 'A';
  r.b[3] = 1;
  r.u32(4, kPsvr2SlamBytes);
  r.u32(8, psvr2_device_us(t));
  r.u32(12, 3);
  r.f32(16, -m.position_m.z);
  r.f32(20, m.position_m.y);
  r.f32(24, m.position_m.x);
  r.f32(28, q.w);
  r.f32(32, -q.y);
  r.f32(36, -q.x);
  r.f32(40, q.z);
  return r.b;
}

/// A status transfer: the header, then the IMU records at t0, t0 + period, ...
inline std::vector<std::uint8_t> psvr2_status_transfer(TimeNs t0, int records) {
  LeBytes r(kPsvr2StatusHeaderBytes + static_cast<std::size_t>(records) * kPsvr2ImuBytes);
  r.b[0] = 1;  // display link ready
  r.b[5] = kPsvr2IpdDialMm;
  for (int i = 0; i < records; ++i) {
    const TimeNs t = t0 + i * kPsvr2ImuPeriodNs;
    const HeadMotion m = psvr2_motion(t);
    const glm::dvec3 w = m.angular_velocity_head * (180.0 / M_PI), a = m.specific_force_head / kGravity;
    const std::size_t at = kPsvr2StatusHeaderBytes + static_cast<std::size_t>(i) * kPsvr2ImuBytes;
    r.u32(at, psvr2_device_us(t));
    r.i16(at + 4, counts(-a.z, kPsvr2AccelGPerCount));
    r.i16(at + 6, counts(-a.x, kPsvr2AccelGPerCount));
    r.i16(at + 8, counts(a.y, kPsvr2AccelGPerCount));
    r.i16(at + 10, counts(-w.z, kPsvr2GyroDegPerCount));
    r.i16(at + 12, counts(-w.x, kPsvr2GyroDegPerCount));
    r.i16(at + 14, counts(w.y, kPsvr2GyroDegPerCount));
    r.u16(at + 20, static_cast<std::uint16_t>(psvr2_device_us(t)));  // the IMU's own 16-bit clock
  }
  return r.b;
}

}  // namespace foveal::vmtest
