// Crafted Vive configurations (issue 27, item 5): the JSON goes through the project's one
// entry point (size and depth limits), and no message quotes an unbounded value.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "foveal/drivers/vive/vive_config.hpp"
#include "test_support.hpp"

namespace foveal::vive {
namespace {

std::string example() { return test::read_file(test::source_path("data/headset/vive_pro_config_example.json")); }

// The example with the green distortion type of the left eye replaced by `value` (raw JSON).
std::string with_distortion_type(const std::string& value) {
  nlohmann::json j = nlohmann::json::parse(example());
  j["tracking_to_eye_transform"][0]["distortion"]["type"] = "@TYPE@";
  std::string text = j.dump();
  text.replace(text.find("\"@TYPE@\""), 8, value);
  return text;
}

TEST(ViveConfigLimits, ADeeplyNestedDistortionTypeIsRefusedNotACrash) {
  // 400,000 deep was a SIGSEGV: nlohmann parsed it, then the message dumped it recursively.
  const std::string deep = std::string(400000, '[') + std::string(400000, ']');
  auto c = parse_config(with_distortion_type(deep), "cfg.json");
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().kind, ErrorKind::bad_input);
  EXPECT_NE(c.error().message.find("cfg.json: JSON nested deeper than 64 levels"), std::string::npos) << c.error().message;
  EXPECT_LT(c.error().message.size(), 200u);
}

TEST(ViveConfigLimits, AWrongTypeIsQuotedShortly) {
  std::string big = "[";
  for (int i = 0; i < 100000; ++i) big += (i ? ",1" : "1");
  big += "]";
  auto c = parse_config(with_distortion_type(big), "cfg.json");
  ASSERT_FALSE(c);
  const std::string& m = c.error().message;
  EXPECT_NE(m.find("tracking_to_eye_transform[0].distortion.type: [1,1,1"), std::string::npos) << m.substr(0, 300);
  EXPECT_NE(m.find("… is not DISTORT_DPOLY3"), std::string::npos) << m.substr(0, 300);
  EXPECT_LT(m.size(), 200u) << "the message quotes the whole value";
}

TEST(ViveConfigLimits, OversizedOrLongLabelsAreRefused) {
  auto huge = parse_config(with_distortion_type("\"" + std::string(2 << 20, 'x') + "\""), "cfg.json");
  ASSERT_FALSE(huge);
  EXPECT_NE(huge.error().message.find("more than the 1 MiB accepted"), std::string::npos) << huge.error().message.substr(0, 300);
  nlohmann::json j = nlohmann::json::parse(example());
  j["model_number"] = std::string(100000, 'V');
  auto named = parse_config(j.dump(), "cfg.json");
  ASSERT_FALSE(named);
  EXPECT_NE(named.error().message.find("cfg.json: model_number: 100000 bytes"), std::string::npos) << named.error().message.substr(0, 300);
  EXPECT_LT(named.error().message.size(), 200u);
  j = nlohmann::json::parse(example());
  j["device_serial_number"] = std::string("LHR-\x01", 5);
  auto serial = parse_config(j.dump(), "cfg.json");
  ASSERT_FALSE(serial);
  EXPECT_NE(serial.error().message.find("device_serial_number: \"LHR-\\x01\" contains a control character"), std::string::npos)
      << serial.error().message;
}

TEST(ViveConfigLimits, DevicesFromConfigExitsTwoOnTheDeepFile) {
  test::TempDir dir;
  const std::string cfg = dir.path("deep.json"), out = dir.path("vive.json");
  test::write_file(cfg, with_distortion_type(std::string(400000, '[') + std::string(400000, ']')));
  auto r = test::run(test::bin("foveal") + " devices --from-config " + cfg + " --display-model " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(cfg + ": JSON nested deeper than 64 levels"), std::string::npos) << r.err.substr(0, 300);
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace foveal::vive
