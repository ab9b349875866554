#include <gtest/gtest.h>

#include <cstring>

#include "foveal/drivers/hid/report_decoder.hpp"
#include "hid_test_data.hpp"

namespace foveal::hid {
namespace {

constexpr std::uint16_t kEyePage = 0x12;

void put_i32(std::vector<std::uint8_t>& r, std::size_t at, std::int32_t v) {
  std::uint32_t u;
  std::memcpy(&u, &v, 4);
  for (int k = 0; k < 4; ++k) r[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(u >> (8 * k));
}

std::vector<std::uint8_t> tracking_report() {
  std::vector<std::uint8_t> r(65, 0);
  r[0] = 0x10;
  const std::uint64_t ts = 0x0102030405060708ull;
  for (int k = 0; k < 8; ++k) r[1 + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(ts >> (8 * k));
  put_i32(r, 9, -150000);   // gaze x, um
  put_i32(r, 13, 250000);   // gaze y, um
  put_i32(r, 17, -32000);   // left eye x
  put_i32(r, 29, 32000);    // right eye x
  return r;
}

TEST(HidDecode, TrackingDataReportDecodesGazeInMicrometres) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  auto values = decode_report(*d, ReportType::input, tracking_report());
  ASSERT_TRUE(values) << values.error().message;
  ASSERT_EQ(values->size(), 8u + 2u + 3u + 3u + 6u);
  const DecodedValue& gx = (*values)[8];
  const DecodedValue& gy = (*values)[9];
  EXPECT_EQ(gx.usage, make_usage(kEyePage, 0x21));
  EXPECT_EQ(gx.raw, -150000);
  EXPECT_NEAR(gx.value, -15.0, 1e-9);  // cm
  EXPECT_EQ(gy.raw, 250000);
  EXPECT_EQ((*values)[10].raw, -32000);
  EXPECT_EQ((*values)[13].raw, 32000);
  // The timestamp's bytes in order, least significant first.
  EXPECT_EQ((*values)[0].raw, 0x08);
  EXPECT_EQ((*values)[7].raw, 0x01);
  EXPECT_EQ(unit_name(gx.field->unit), "cm");
}

TEST(HidDecode, SamplingFrequencyFromTrackerStatus) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  const std::vector<std::uint8_t> status = {0x13, 0x01, 0x78, 0x00};  // ready, 120 Hz
  auto values = decode_report(*d, ReportType::feature, status);
  ASSERT_TRUE(values) << values.error().message;
  ASSERT_EQ(values->size(), 2u);
  EXPECT_EQ((*values)[0].usage, make_usage(kEyePage, 0x0301));
  EXPECT_EQ((*values)[0].raw, 1);
  EXPECT_EQ((*values)[1].usage, make_usage(kEyePage, 0x0300));
  EXPECT_EQ((*values)[1].raw, 120);
  EXPECT_EQ(unit_name((*values)[1].field->unit), "s^-1");
}

TEST(HidDecode, TruncatedReportIsAnErrorAtEveryLength) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  const auto full = tracking_report();
  for (std::size_t n = 0; n < full.size(); ++n) {
    auto v = decode_report(*d, ReportType::input, std::span(full.data(), n));
    ASSERT_FALSE(v) << n;
    if (n > 0) {
      EXPECT_NE(v.error().message.find("truncated"), std::string::npos) << v.error().message;
    }
  }
}

TEST(HidDecode, UnknownReportIdIsAnError) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  const std::vector<std::uint8_t> r = {0x42, 0, 0, 0};
  auto v = decode_report(*d, ReportType::input, r);
  ASSERT_FALSE(v);
  EXPECT_NE(v.error().message.find("ID 66"), std::string::npos) << v.error().message;
}

TEST(HidDecode, ExtractBitsAcrossByteBoundaries) {
  const std::vector<std::uint8_t> data = {0b1010'1100, 0b0101'0011, 0xFF, 0x00, 0x80};
  EXPECT_EQ(extract_bits(data, 0, 4), 0b1100u);
  EXPECT_EQ(extract_bits(data, 4, 8), 0b0011'1010u);
  EXPECT_EQ(extract_bits(data, 12, 4), 0b0101u);
  EXPECT_EQ(extract_bits(data, 8, 32), 0x8000FF53u);
}

}  // namespace
}  // namespace foveal::hid
