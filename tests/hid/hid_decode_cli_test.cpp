// foveal hid decode on the real HUTRR74 descriptor (data/hid): the timestamp, declared
// as eight 8-bit fields, reads as one number of seconds, in text and in JSON.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

// A Tracking Data report (ID 0x10, 65 bytes): timestamp 123456789 µs, gaze x -15 cm.
std::string tracking_report_hex() {
  std::string hex = "10 15 cd 5b 07 00 00 00 00 10 b6 fd ff";
  for (int k = 13; k < 65; ++k) hex += " 00";
  return hex;
}

std::string decode_command(const std::string& extra) {
  return test::bin("foveal") + " hid decode --descriptor " + test::source_path("data/hid/ms_gazehid_eye_tracker.desc.hex") +
         " --report '" + tracking_report_hex() + "'" + extra;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(HidDecodeCli, TimestampIsOneValueWithItsUnit) {
  auto r = test::run(decode_command(""));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count(r.out, "Eye and Head Trackers/Timestamp"), 1u) << r.out;
  EXPECT_NE(r.out.find("bit    0 64  Eye and Head Trackers/Timestamp"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("raw    123456789  = 123.456789 s  (8 bytes: 15 cd 5b 07 00 00 00 00)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("raw      -150000  = -15 cm"), std::string::npos) << r.out;
}

TEST(HidDecodeCli, JsonTimestampIsOneValueWithItsBytes) {
  auto r = test::run(decode_command(" --json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << r.out;
  int stamps = 0;
  for (const auto& v : j["values"]) {
    if (v["usage"] != "Eye and Head Trackers/Timestamp") continue;
    ++stamps;
    EXPECT_EQ(v["bit_offset"], 0);
    EXPECT_EQ(v["size"], 64);
    EXPECT_EQ(v["raw"], 123456789);
    EXPECT_NEAR(v["value"].get<double>(), 123.456789, 1e-9);
    EXPECT_EQ(v["unit"], "s");
    EXPECT_EQ(v["decimal"], "123.456789");
    EXPECT_EQ(v["bytes"], (std::vector<int>{0x15, 0xcd, 0x5b, 0x07, 0, 0, 0, 0}));
  }
  EXPECT_EQ(stamps, 1);
  EXPECT_EQ(j["values"].size(), 15u);  // 1 timestamp + 2 gaze + 3 + 3 eye positions + 6 padding
}

}  // namespace
}  // namespace foveal
