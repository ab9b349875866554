#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <span>

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

TEST(HidDecode, TheRealDescriptorsTimestampBytesJoinIntoOneValueInSeconds) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  auto values = decode_report(*d, ReportType::input, tracking_report());
  ASSERT_TRUE(values) << values.error().message;
  const std::vector<ReportValue> joined = join_multi_byte_values(*values);
  ASSERT_EQ(joined.size(), 1u + 2u + 3u + 3u + 6u);
  const ReportValue& ts = joined[0];
  EXPECT_EQ(ts.first->usage, make_usage(kEyePage, 0x20));
  EXPECT_EQ(ts.bit_offset, 0u);
  EXPECT_EQ(ts.bits, 64u);
  EXPECT_EQ(ts.raw, 0x0102030405060708);
  EXPECT_TRUE(ts.in_range);
  EXPECT_NEAR(ts.value, 72623859790.382856, 1e-3);  // s (µs on the wire)
  EXPECT_EQ(ts.bytes, (std::vector<std::uint8_t>{8, 7, 6, 5, 4, 3, 2, 1}));
  EXPECT_EQ(scaled_decimal(ts.raw, ts.first->field->unit_exponent), "72623859790.382856");
  // Everything else passes through unchanged.
  EXPECT_FALSE(joined[1].is_run());
  EXPECT_EQ(joined[1].raw, -150000);
  EXPECT_EQ(joined[1].bits, 32u);
  EXPECT_EQ(joined[1].bit_offset, 64u);
}

TEST(HidDecode, OnlyTimestampsAndBufferedBytesJoin) {
  // Vendor page, 4 bytes of usage 1; then the same as Buffered Bytes; then 9 buffered
  // bytes (more than one 64-bit number: not joined).
  auto descriptor = [](std::uint8_t flags_hi, std::uint8_t count) {
    return std::vector<std::uint8_t>{0x06, 0x00, 0xff, 0x09, 0x01, 0xa1, 0x01, 0x09, 0x01, 0x15, 0x00, 0x26, 0xff, 0x00,
                                     0x75, 0x08, 0x95, count, 0x82, 0x02, flags_hi, 0xc0};
  };
  const std::vector<std::uint8_t> report = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09};
  for (bool buffered : {false, true}) {
    auto d = parse_report_descriptor(descriptor(buffered ? 0x01 : 0x00, 4));
    ASSERT_TRUE(d) << d.error().message;
    auto values = decode_report(*d, ReportType::input, std::span(report).first(4));
    ASSERT_TRUE(values) << values.error().message;
    const auto joined = join_multi_byte_values(*values);
    if (buffered) {
      ASSERT_EQ(joined.size(), 1u);
      EXPECT_EQ(joined[0].raw, 0x04030201);
      EXPECT_EQ(joined[0].bits, 32u);
    } else {
      EXPECT_EQ(joined.size(), 4u);
    }
  }
  auto d = parse_report_descriptor(descriptor(0x01, 9));
  ASSERT_TRUE(d);
  auto values = decode_report(*d, ReportType::input, report);
  ASSERT_TRUE(values);
  const auto joined = join_multi_byte_values(*values);
  ASSERT_EQ(joined.size(), 2u);  // 8 bytes, then the ninth alone
  EXPECT_EQ(joined[0].raw, 0x0807060504030201);
  EXPECT_EQ(joined[1].raw, 9);
}

TEST(HidDecode, ScaledDecimalsAreExact) {
  EXPECT_EQ(scaled_decimal(123456789, -6), "123.456789");
  EXPECT_EQ(scaled_decimal(5, -6), "0.000005");
  EXPECT_EQ(scaled_decimal(-150000, -4), "-15");
  EXPECT_EQ(scaled_decimal(-15, 1), "-150");
  EXPECT_EQ(scaled_decimal(0, 3), "0");
  EXPECT_EQ(scaled_decimal(1200, -2), "12");
  EXPECT_EQ(scaled_decimal(std::numeric_limits<std::int64_t>::min(), -19), "-0.9223372036854775808");
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
