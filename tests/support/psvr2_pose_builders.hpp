#pragma once
// Builds the PS VR2's motion records byte by byte at the offsets docs/headset.md lists
// (status/IMU and SLAM): for the parsers' unit tests and the emulated headset of the VM test.
#include "foveal/drivers/psvr2/psvr2_pose_records.hpp"
#include "report_bytes.hpp"

namespace foveal::test {

/// A PS VR2 status transfer: the 32-byte header and `n` IMU records.
struct Psvr2StatusBuilder : Bytes {
  explicit Psvr2StatusBuilder(std::size_t n_imu, std::uint8_t ipd_mm = 63)
      : Bytes(usb::psvr2::kStatusHeaderBytes + n_imu * usb::psvr2::kImuRecordBytes) {
    b[usb::psvr2::kStatusIpdByte] = ipd_mm;
  }
  /// IMU record `i` in raw counts, device axes.
  void imu(std::size_t i, std::uint32_t vts_us, const std::int16_t accel[3], const std::int16_t gyro[3]) {
    const std::size_t o = usb::psvr2::kStatusHeaderBytes + i * usb::psvr2::kImuRecordBytes;
    u32(o, vts_us);
    for (std::size_t k = 0; k < 3; ++k) {
      i16(o + 4 + 2 * k, accel[k]);
      i16(o + 10 + 2 * k, gyro[k]);
    }
  }
};

/// A 512-byte PS VR2 SLAM record (headset axes; orientation w first).
struct Psvr2SlamBuilder : Bytes {
  Psvr2SlamBuilder(std::uint32_t vts_us, const float pos[3], const float quat_wxyz[4])
      : Bytes(usb::psvr2::kSlamRecordBytes) {
    b[0] = 'S', b[1] = 'L', b[2] = 'A', b[3] = 1;
    u32(usb::psvr2::kSlamSize, static_cast<std::uint32_t>(usb::psvr2::kSlamRecordBytes));
    u32(usb::psvr2::kSlamTime, vts_us);
    u32(usb::psvr2::kSlamState, 3);
    for (std::size_t k = 0; k < 3; ++k) f32(usb::psvr2::kSlamPosition + 4 * k, pos[k]);
    for (std::size_t k = 0; k < 4; ++k) f32(usb::psvr2::kSlamOrientation + 4 * k, quat_wxyz[k]);
  }
};

}  // namespace foveal::test
