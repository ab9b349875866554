#include "foveal/drivers/psvr2/psvr2_pose_records.hpp"

#include <cmath>
#include <string>

#include "foveal/core/le_bytes.hpp"

namespace foveal::usb {
namespace {

Error at(const char* record, std::size_t offset, const std::string& what) {
  return bad_input(std::string("psvr2 ") + record + ": byte " + std::to_string(offset) + ": " + what);
}

constexpr float kDegToRad = 3.14159265358979323846f / 180.0f;

}  // namespace

Result<Psvr2StatusReport> parse_psvr2_status(std::span<const std::uint8_t> data) {
  using namespace psvr2;
  if (data.size() < kStatusHeaderBytes)
    return at("status report", data.size(),
              "truncated: " + std::to_string(data.size()) + " bytes, the header alone is " +
                  std::to_string(kStatusHeaderBytes));
  const std::size_t body = data.size() - kStatusHeaderBytes;
  if (body % kImuRecordBytes != 0)
    return at("status report", data.size() - body % kImuRecordBytes,
              "truncated IMU record: " + std::to_string(body % kImuRecordBytes) + " of " +
                  std::to_string(kImuRecordBytes) + " bytes");
  Psvr2StatusReport r;
  r.display_state = data[0];
  r.proximity = data[1];
  r.function_button = data[2];
  r.ipd_mm = data[kStatusIpdByte];
  if (r.ipd_mm != 0 && (r.ipd_mm < 50 || r.ipd_mm > 80))
    return at("status report", kStatusIpdByte, "IPD dial " + std::to_string(r.ipd_mm) + " mm is outside 50-80 mm");
  const LeBytes b(data);
  r.imu.reserve(body / kImuRecordBytes);
  for (std::size_t o = kStatusHeaderBytes; o < data.size(); o += kImuRecordBytes) {
    Psvr2ImuRecord m;
    m.vts_us = b.u32(o);
    for (std::size_t k = 0; k < 3; ++k) {
      m.accel[k] = b.i16(o + 4 + 2 * k);
      m.gyro[k] = b.i16(o + 10 + 2 * k);
    }
    m.dp_frame = b.u16(o + 16);
    m.dp_line = b.u16(o + 18);
    m.imu_ts_us = b.u16(o + 20);
    m.status = b.u16(o + 22);
    r.imu.push_back(m);
  }
  return r;
}

ImuSample psvr2_imu_to_sample(const Psvr2ImuRecord& r) {
  const auto g = [&](int k) { return static_cast<float>(r.gyro[k] * psvr2::kGyroDegPerSecPerLsb) * kDegToRad; };
  const auto a = [&](int k) { return static_cast<float>(r.accel[k] * psvr2::kAccelGPerLsb) * kGravity; };
  ImuSample s;
  s.gyro_rad_s = {-g(1), g(2), -g(0)};
  s.accel_m_s2 = {-a(1), a(2), -a(0)};
  return s;
}

Result<Psvr2SlamRecord> parse_psvr2_slam(std::span<const std::uint8_t> data) {
  using namespace psvr2;
  if (data.size() < 4) return at("SLAM record", data.size(), "too short for a header");
  if (data[0] != 'S' || data[1] != 'L' || data[2] != 'A')
    return at("SLAM record", 0, "not a SLAM record (magic is not \"SLA\")");
  if (data.size() < kSlamMinSize)
    return at("SLAM record", data.size(),
              "truncated: " + std::to_string(data.size()) + " of at least " + std::to_string(kSlamMinSize) + " bytes");
  const LeBytes b(data);
  Psvr2SlamRecord r;
  r.size = b.u32(kSlamSize);
  if (r.size < kSlamMinSize || r.size > data.size())
    return at("SLAM record", kSlamSize,
              "size field " + std::to_string(r.size) + " does not fit the " + std::to_string(data.size()) +
                  "-byte transfer");
  r.vts_us = b.u32(kSlamTime);
  r.state = b.u32(kSlamState);
  double norm2 = 0;
  for (std::size_t k = 0; k < 3; ++k) r.position[k] = b.f32(kSlamPosition + 4 * k);
  for (std::size_t k = 0; k < 4; ++k) {
    r.orientation[k] = b.f32(kSlamOrientation + 4 * k);
    norm2 += double(r.orientation[k]) * r.orientation[k];
  }
  for (std::size_t k = 0; k < 3; ++k)
    if (!std::isfinite(r.position[k]) || std::fabs(r.position[k]) > 1e4f)
      return at("SLAM record", kSlamPosition + 4 * k, "position is not a finite distance in metres");
  if (!std::isfinite(norm2) || std::fabs(std::sqrt(norm2) - 1.0) > kUnitQuaternionTolerance)
    return at("SLAM record", kSlamOrientation, "orientation is not a unit quaternion (|q| = " + std::to_string(std::sqrt(norm2)) + ")");
  return r;
}

Pose psvr2_slam_to_pose(const Psvr2SlamRecord& r) {
  Pose p;
  p.position_m = {r.position[2], r.position[1], -r.position[0]};
  p.orientation = renormalized(glm::quat(r.orientation[0], -r.orientation[2], -r.orientation[1], r.orientation[3]));
  return p;
}

}  // namespace foveal::usb
