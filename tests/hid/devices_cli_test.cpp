// foveal devices / foveal record on a machine without trackers (the VM suite covers
// them with emulated devices): help, argument errors, atomic output.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

TEST(DevicesCli, HelpNamesTheOptions) {
  auto d = test::run(test::bin("foveal") + " devices --help");
  EXPECT_EQ(d.exit_code, 0);
  EXPECT_NE(d.out.find("--json"), std::string::npos);
  auto r = test::run(test::bin("foveal") + " record --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--source", "--device", "--out", "--duration", "--json"}) EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(DevicesCli, JsonListIsWellFormed) {
  auto d = test::run(test::bin("foveal") + " devices --json");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const auto j = nlohmann::json::parse(d.out, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << d.out;
  ASSERT_TRUE(j.contains("devices") && j["devices"].is_array());
  for (const auto& dev : j["devices"])
    for (const char* key : {"id", "driver", "spec", "path", "vid_pid", "name", "sample_rate_hz"}) EXPECT_TRUE(dev.contains(key)) << key;
}

TEST(RecordCli, BadArgumentsAndMissingDevicesExitTwoAndWriteNothing) {
  test::TempDir dir;
  const std::string out = dir.path("rec.csv");
  auto zero = test::run(test::bin("foveal") + " record --out " + out + " --duration 0");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("--duration must be > 0"), std::string::npos) << zero.err;
  auto path = test::run(test::bin("foveal") + " record --device /dev/hidraw-none --out " + out + " --duration 1");
  EXPECT_EQ(path.exit_code, 2);
  EXPECT_NE(path.err.find("/dev/hidraw-none"), std::string::npos) << path.err;
  auto id = test::run(test::bin("foveal") + " record --device 99 --out " + out + " --duration 1");
  EXPECT_EQ(id.exit_code, 2);
  EXPECT_NE(id.err.find("hid:99: no such tracker"), std::string::npos) << id.err;
  auto missing = test::run(test::bin("foveal") + " record --duration 1");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace foveal
