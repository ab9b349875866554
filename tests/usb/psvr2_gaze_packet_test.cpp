#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "foveal/drivers/psvr2/psvr2_gaze_packet.hpp"
#include "psvr2_records.hpp"

namespace foveal::usb {
namespace {

using test::RecordBuilder;

RecordBuilder typical() {
  RecordBuilder r;
  const float s = std::sqrt(0.5f);
  r.eye(psvr2::kLeftEye, 32.0f, s, s, 3.5f, false);    // headset frame: x left, +z forward
  r.eye(psvr2::kRightEye, -32.0f, 0.0f, 1.0f, 3.75f, true);
  const std::size_t c = psvr2::kCombined;
  r.u32(c, 1);
  r.vec3(c + 4, 0, 0, 0);
  r.u32(c + 16, 1);
  r.vec3(c + 20, 0, 0, 1);
  r.u32(c + 32, 1);
  r.u32(c + 36, 123456789u);
  return r;
}

TEST(Psvr2GazePacket, ParsesEveryField) {
  auto rec = parse_psvr2_gaze(typical().b);
  ASSERT_TRUE(rec) << rec.error().message;
  EXPECT_EQ(rec->version, 3);
  EXPECT_EQ(rec->timestamp_us, 123456789u);
  EXPECT_TRUE(rec->eyes[0].origin_valid);
  EXPECT_FLOAT_EQ(rec->eyes[0].origin_mm.x, 32.0f);
  EXPECT_FLOAT_EQ(rec->eyes[0].pupil_mm, 3.5f);
  EXPECT_FALSE(rec->eyes[0].blink);
  EXPECT_TRUE(rec->eyes[1].blink);
  EXPECT_TRUE(rec->combined_valid);
}

TEST(Psvr2GazePacket, ConvertsToTheHeadFrame) {
  auto rec = parse_psvr2_gaze(typical().b);
  ASSERT_TRUE(rec);
  const GazeSample s = psvr2_to_sample(*rec);
  EXPECT_EQ(s.eyes[0].valid, kValidAll);
  // Headset x left / +z forward -> ours x right / -z forward.
  EXPECT_FLOAT_EQ(s.eyes[0].origin_mm.x, -32.0f);   // left eye on the left: x < 0
  EXPECT_FLOAT_EQ(s.eyes[0].direction.x, -std::sqrt(0.5f));
  EXPECT_FLOAT_EQ(s.eyes[0].direction.z, -std::sqrt(0.5f));
  EXPECT_FLOAT_EQ(s.eyes[0].pupil_mm, 3.5f);
  EXPECT_FLOAT_EQ(s.eyes[0].openness, 1.0f);
  EXPECT_FLOAT_EQ(s.eyes[1].openness, 0.0f);  // blinking
  EXPECT_FLOAT_EQ(s.combined.direction.z, -1.0f);
}

TEST(Psvr2GazePacket, InvalidFlagsLeaveBitsClear) {
  RecordBuilder r = typical();
  r.u32(psvr2::kLeftEye + 16, 0);                                  // direction not valid
  r.f32(psvr2::kLeftEye + 20, std::numeric_limits<float>::quiet_NaN());  // and garbage: ignored
  r.u32(psvr2::kRightEye + 64, 0);                                 // blink flag not valid
  auto rec = parse_psvr2_gaze(r.b);
  ASSERT_TRUE(rec) << rec.error().message;
  const GazeSample s = psvr2_to_sample(*rec);
  EXPECT_FALSE(s.eyes[0].has(kValidDirection));
  EXPECT_EQ(s.eyes[0].direction, glm::vec3(0.0f));
  EXPECT_FALSE(s.eyes[1].has(kValidOpenness));
}

TEST(Psvr2GazePacket, MalformedRecordsRejectedWithOffsets) {
  auto expect_error = [](const std::vector<std::uint8_t>& b, const std::string& part) {
    auto rec = parse_psvr2_gaze(b);
    ASSERT_FALSE(rec);
    EXPECT_NE(rec.error().message.find(part), std::string::npos) << rec.error().message;
  };
  expect_error({}, "too short");
  RecordBuilder wrong_magic = typical();
  wrong_magic.b[1] = 'R';
  expect_error(wrong_magic.b, "not a gaze state record");
  auto truncated = typical().b;
  truncated.resize(200);
  expect_error(truncated, "truncated");
  RecordBuilder size = typical();
  size.u32(4, 100000);
  expect_error(size.b, "byte 4: size field");
  RecordBuilder boolean = typical();
  boolean.u32(psvr2::kRightEye + 32, 7);
  expect_error(boolean.b, "byte 196: boolean word is 7");
  RecordBuilder nan = typical();
  nan.f32(psvr2::kLeftEye + 36, std::numeric_limits<float>::infinity());
  expect_error(nan.b, "not finite");
  // Every prefix of a good record fails cleanly (no out-of-bounds read).
  const auto good = typical().b;
  for (std::size_t n = 0; n < good.size(); ++n)
    EXPECT_FALSE(parse_psvr2_gaze(std::span<const std::uint8_t>(good.data(), n)));
}

TEST(Psvr2GazePacket, TimestampWrapIsUnwrapped) {
  WrapCounter w;
  EXPECT_EQ(w.unwrap_ns(0xFFFF'FF00u), std::int64_t{0xFFFF'FF00} * 1000);
  EXPECT_EQ(w.unwrap_ns(0x10u), (std::int64_t{1} << 32) * 1000 + 0x10 * 1000);
  EXPECT_EQ(w.unwrap_ns(0x08u), (std::int64_t{1} << 32) * 1000 + 0x08 * 1000);  // reordered, not wrapped
}

}  // namespace
}  // namespace foveal::usb
