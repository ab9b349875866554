#include <gtest/gtest.h>

#include "foveal/drivers/hid/report_descriptor.hpp"
#include "hid_test_data.hpp"

namespace foveal::hid {
namespace {

constexpr std::uint16_t kEyePage = 0x12;

const Field* find_field(const ReportDescriptor& d, ReportType t, std::uint8_t id, Usage usage) {
  for (const Field& f : d.fields)
    if (f.type == t && f.report_id == id)
      for (std::uint32_t i = 0; i < f.count; ++i)
        if (f.usage_of(i) == usage) return &f;
  return nullptr;
}

TEST(HidDescriptor, RealEyeTrackerDescriptorParses) {
  const auto bytes = test::eye_tracker_descriptor_bytes();
  ASSERT_EQ(bytes.size(), 340u);
  auto d = parse_report_descriptor(bytes);
  ASSERT_TRUE(d) << d.error().message;
  EXPECT_TRUE(d->uses_report_ids);
  EXPECT_TRUE(d->has_application(make_usage(kEyePage, 0x01)));
  // Report sizes on the wire, with the ID byte.
  ASSERT_NE(d->find_report(ReportType::input, 0x10), nullptr);
  EXPECT_EQ(d->find_report(ReportType::input, 0x10)->bytes(true), 65u);
  EXPECT_EQ(d->find_report(ReportType::feature, 0x11)->bytes(true), 22u);
  EXPECT_EQ(d->find_report(ReportType::feature, 0x12)->bytes(true), 19u);
  EXPECT_EQ(d->find_report(ReportType::feature, 0x14)->bytes(true), 2u);
  EXPECT_EQ(d->reports.size(), 6u);
}

TEST(HidDescriptor, TrackerStatusIsBothInputAndFeature) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  const Usage freq = make_usage(kEyePage, 0x0300);
  const Field* in = find_field(*d, ReportType::input, 0x13, freq);
  const Field* feat = find_field(*d, ReportType::feature, 0x13, freq);
  ASSERT_NE(in, nullptr);
  ASSERT_NE(feat, nullptr);
  EXPECT_EQ(in->size, 16u);
  EXPECT_EQ(in->bit_offset, 8u);
  EXPECT_EQ(d->find_report(ReportType::input, 0x13)->bytes(true), 4u);
  EXPECT_EQ(d->find_report(ReportType::feature, 0x13)->bytes(true), 4u);
}

TEST(HidDescriptor, ConstantFlaggedGazeFieldsKeepTheirUsages) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  const Field* gaze = find_field(*d, ReportType::input, 0x10, make_usage(kEyePage, 0x21));
  ASSERT_NE(gaze, nullptr);
  EXPECT_TRUE(gaze->flags & kConstant) << "the real descriptor marks data fields Constant";
  EXPECT_TRUE(gaze->flags & kVariable);
  EXPECT_EQ(gaze->bit_offset, 64u);  // after the 8-byte timestamp
  EXPECT_EQ(gaze->size, 32u);
  EXPECT_EQ(gaze->count, 2u);
  EXPECT_EQ(gaze->usage_of(0), make_usage(kEyePage, 0x21));
  EXPECT_EQ(gaze->usage_of(1), make_usage(kEyePage, 0x22));
  EXPECT_TRUE(gaze->is_signed());
  EXPECT_EQ(gaze->logical_min, -2000000);
  EXPECT_EQ(gaze->logical_max, 2000000);
  EXPECT_EQ(gaze->unit, 0x11u);        // SI linear, length (cm)
  EXPECT_EQ(gaze->unit_exponent, -4);  // cm * 1e-4 = micrometres
  const auto path = d->collection_path(*gaze);
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[0], make_usage(kEyePage, 0x01));  // Eye Tracker
  EXPECT_EQ(path[1], make_usage(kEyePage, 0x10));  // Tracking Data
  EXPECT_EQ(path[2], make_usage(kEyePage, 0x24));  // Gaze Location
}

TEST(HidDescriptor, TimestampIsEightBytesInMicroseconds) {
  auto d = parse_report_descriptor(test::eye_tracker_descriptor_bytes());
  ASSERT_TRUE(d);
  const Field* ts = find_field(*d, ReportType::input, 0x10, make_usage(kEyePage, 0x20));
  ASSERT_NE(ts, nullptr);
  EXPECT_EQ(ts->bit_offset, 0u);
  EXPECT_EQ(ts->size, 8u);
  EXPECT_EQ(ts->count, 8u);
  EXPECT_EQ(ts->unit_exponent, -6);
  EXPECT_EQ(ts->logical_max, 255);  // 26 FF 00: unsigned
}

TEST(HidDescriptor, PushPopUsageRangesAndExtendedUsages) {
  const std::vector<std::uint8_t> desc = {
      0x05, 0x01,              // usage page generic desktop
      0x09, 0x02,              // usage mouse
      0xA1, 0x01,              // collection application
      0x05, 0x09,              //   usage page buttons
      0x19, 0x01, 0x29, 0x03,  //   usage min 1, max 3
      0x15, 0x00, 0x25, 0x01,  //   logical 0..1
      0x75, 0x01, 0x95, 0x03,  //   3 x 1 bit
      0x81, 0x02,              //   input data var abs
      0xA4,                    //   push
      0x75, 0x05, 0x95, 0x01,  //   1 x 5 bits padding
      0x81, 0x01,              //   input constant
      0xB4,                    //   pop (size back to 1, count 3)
      0x0B, 0x30, 0x00, 0x01, 0x00,  // extended usage 0x0001:0x0030 (X)
      0x15, 0x81, 0x25, 0x7F,  //   logical -127..127
      0x75, 0x08, 0x95, 0x01,  //   1 x 8 bits
      0x81, 0x06,              //   input data var rel
      0xC0};
  auto d = parse_report_descriptor(desc);
  ASSERT_TRUE(d) << d.error().message;
  ASSERT_EQ(d->fields.size(), 3u);
  EXPECT_EQ(d->fields[0].usage_of(2), make_usage(0x09, 3));
  EXPECT_EQ(d->fields[1].size, 5u);
  EXPECT_EQ(d->fields[1].bit_offset, 3u);
  EXPECT_EQ(d->fields[2].bit_offset, 8u);
  EXPECT_EQ(d->fields[2].usage_of(0), make_usage(0x01, 0x30));
  EXPECT_EQ(d->fields[2].logical_min, -127);
  EXPECT_FALSE(d->uses_report_ids);
  EXPECT_EQ(d->reports.at(0).bytes(false), 2u);
}

struct BadDescriptor {
  const char* name;
  std::vector<std::uint8_t> bytes;
  const char* expect;
};

class HidBadDescriptor : public ::testing::TestWithParam<BadDescriptor> {};

TEST_P(HidBadDescriptor, IsRejectedWithAMessage) {
  auto d = parse_report_descriptor(GetParam().bytes);
  ASSERT_FALSE(d) << GetParam().name;
  EXPECT_NE(d.error().message.find(GetParam().expect), std::string::npos) << d.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, HidBadDescriptor,
    ::testing::Values(
        BadDescriptor{"empty", {}, "no input"},
        BadDescriptor{"truncated item", {0x05, 0x01, 0x27, 0x01, 0x02}, "descriptor ends"},
        BadDescriptor{"unclosed collection", {0x09, 0x01, 0xA1, 0x01, 0x75, 0x08, 0x95, 0x01, 0x81, 0x02}, "not closed"},
        BadDescriptor{"end without collection", {0xC0}, "without a Collection"},
        BadDescriptor{"pop without push", {0xB4}, "Pop without Push"},
        BadDescriptor{"report size 0", {0x95, 0x01, 0x81, 0x02}, "report size 0"},
        BadDescriptor{"report size 33", {0x75, 0x21, 0x95, 0x01, 0x81, 0x02}, "report size 33"},
        BadDescriptor{"report id 0", {0x85, 0x00}, "report ID 0"},
        BadDescriptor{"huge count", {0x75, 0x08, 0x97, 0xFF, 0xFF, 0xFF, 0x7F, 0x81, 0x02}, "report count"}),
    [](const auto& param_info) {
      std::string n = param_info.param.name;
      for (char& c : n)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return n;
    });

TEST(HidDescriptor, EveryTruncationOfTheRealDescriptorFailsCleanly) {
  const auto bytes = test::eye_tracker_descriptor_bytes();
  int rejected = 0;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    auto d = parse_report_descriptor(std::span(bytes.data(), n));
    if (!d) ++rejected;
  }
  // Every strict prefix leaves a collection open (or an item cut), so all must fail.
  EXPECT_EQ(rejected, static_cast<int>(bytes.size()));
}

TEST(HidHex, ParsesSpacesCommasAndPrefixes) {
  auto b = parse_hex_bytes("0x05, 12 09:01\nA1");
  ASSERT_TRUE(b);
  EXPECT_EQ(*b, (std::vector<std::uint8_t>{0x05, 0x12, 0x09, 0x01, 0xA1}));
  EXPECT_FALSE(parse_hex_bytes("05 1"));
  EXPECT_FALSE(parse_hex_bytes("zz"));
}

}  // namespace
}  // namespace foveal::hid
