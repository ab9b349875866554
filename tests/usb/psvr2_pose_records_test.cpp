#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "foveal/drivers/psvr2/psvr2_pose_records.hpp"
#include "psvr2_pose_builders.hpp"

namespace foveal::usb {
namespace {

using test::Psvr2SlamBuilder;
using test::Psvr2StatusBuilder;

TEST(Psvr2Status, ParsesHeaderAndEveryImuRecord) {
  Psvr2StatusBuilder s(3, 64);
  s.b[1] = 1;  // proximity
  const std::int16_t a[3] = {100, -200, 8191}, g[3] = {16, -32, 48};
  for (std::size_t i = 0; i < 3; ++i) s.imu(i, 1000u + 500u * static_cast<std::uint32_t>(i), a, g);
  s.u16(32 + 2 * 24 + 20, 777);  // the last record's imu_ts_us
  auto r = parse_psvr2_status(s.b);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->ipd_mm, 64);
  EXPECT_EQ(r->proximity, 1);
  ASSERT_EQ(r->imu.size(), 3u);
  EXPECT_EQ(r->imu[2].vts_us, 2000u);
  EXPECT_EQ(r->imu[1].accel[1], -200);
  EXPECT_EQ(r->imu[0].gyro[2], 48);
  EXPECT_EQ(r->imu[2].imu_ts_us, 777);
}

TEST(Psvr2Status, HeaderWithoutRecordsIsValid) {
  auto r = parse_psvr2_status(Psvr2StatusBuilder(0).b);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->imu.empty());
}

TEST(Psvr2Status, RejectsTruncatedAndMalformed) {
  Psvr2StatusBuilder s(2);
  for (std::size_t cut : {std::size_t{0}, std::size_t{31}, s.b.size() - 1, s.b.size() - 23}) {
    auto r = parse_psvr2_status(std::span<const std::uint8_t>(s.b.data(), cut));
    ASSERT_FALSE(r) << cut;
    EXPECT_EQ(r.error().kind, ErrorKind::bad_input);
    EXPECT_NE(r.error().message.find("truncated"), std::string::npos) << r.error().message;
  }
  Psvr2StatusBuilder bad_ipd(1, 200);
  auto r = parse_psvr2_status(bad_ipd.b);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("byte 5"), std::string::npos) << r.error().message;
}

TEST(Psvr2Status, ImuInSiUnitsOnHeadAxes) {
  Psvr2ImuRecord m;
  m.gyro[0] = 0, m.gyro[1] = 0, m.gyro[2] = 32767;  // +2000 deg/s about device z
  m.accel[0] = -32767 / 4;                          // -1 g along device x
  const ImuSample s = psvr2_imu_to_sample(m);
  // device z -> head y; device x -> head -z (Monado's mapping).
  EXPECT_NEAR(s.gyro_rad_s.y, 2000.0 * 3.14159265358979323846 / 180.0, 1e-3);
  EXPECT_NEAR(s.gyro_rad_s.x, 0.0, 1e-6);
  EXPECT_NEAR(s.accel_m_s2.z, kGravity, 1e-3);
}

TEST(Psvr2Slam, ParsesAndMapsAxes) {
  const float pos[3] = {0.5f, 1.5f, -0.25f};
  const float h = std::sqrt(0.5f);
  const float q[4] = {h, 0.0f, 0.0f, h};  // w, then the headset's three components
  auto r = parse_psvr2_slam(Psvr2SlamBuilder(4242, pos, q).b);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->vts_us, 4242u);
  EXPECT_EQ(r->state, 3u);
  const Pose p = psvr2_slam_to_pose(*r);
  EXPECT_FLOAT_EQ(p.position_m.x, -0.25f);
  EXPECT_FLOAT_EQ(p.position_m.y, 1.5f);
  EXPECT_FLOAT_EQ(p.position_m.z, -0.5f);
  EXPECT_NEAR(p.orientation.w, h, 1e-6);
  EXPECT_NEAR(p.orientation.z, h, 1e-6);
}

TEST(Psvr2Slam, RejectsTruncatedAndMalformed) {
  const float pos[3] = {0, 0, 0}, q[4] = {1, 0, 0, 0};
  const Psvr2SlamBuilder good(1, pos, q);
  for (std::size_t cut : {std::size_t{0}, std::size_t{3}, std::size_t{43}}) {
    auto r = parse_psvr2_slam(std::span<const std::uint8_t>(good.b.data(), cut));
    ASSERT_FALSE(r) << cut;
  }
  // A transfer cut below its own size field.
  auto cut = parse_psvr2_slam(std::span<const std::uint8_t>(good.b.data(), 100));
  ASSERT_FALSE(cut);
  EXPECT_NE(cut.error().message.find("byte 4"), std::string::npos) << cut.error().message;

  Psvr2SlamBuilder magic = good;
  magic.b[1] = 'X';
  EXPECT_FALSE(parse_psvr2_slam(magic.b));
  Psvr2SlamBuilder nan = good;
  nan.f32(psvr2::kSlamPosition + 4, std::numeric_limits<float>::quiet_NaN());
  auto rn = parse_psvr2_slam(nan.b);
  ASSERT_FALSE(rn);
  EXPECT_NE(rn.error().message.find("byte 20"), std::string::npos) << rn.error().message;
  const float not_unit[4] = {0.5f, 0.0f, 0.0f, 0.0f};
  auto ru = parse_psvr2_slam(Psvr2SlamBuilder(1, pos, not_unit).b);
  ASSERT_FALSE(ru);
  EXPECT_NE(ru.error().message.find("unit quaternion"), std::string::npos);
}

}  // namespace
}  // namespace foveal::usb
