// `foveal profile ...` end to end, against a private XDG_CONFIG_HOME.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

class ProfileCli : public ::testing::Test {
 protected:
  test::RunResult foveal(const std::string& args) {
    return test::run("XDG_CONFIG_HOME=" + dir_.path() + " " + test::bin("foveal") + " profile " + args);
  }
  test::TempDir dir_;
};

TEST_F(ProfileCli, CreateUseShowSetExportImportDelete) {
  auto r = foveal("create alice --dominant left --sigma-d 2.2 --sigma-nd 3.2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["dominant_eye"], "left");
  ASSERT_EQ(foveal("use alice").exit_code, 0);
  r = foveal("show --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["name"], "alice");
  EXPECT_EQ(j["active"], true);
  EXPECT_DOUBLE_EQ(j["sigma_nd"].get<double>(), 3.2);
  ASSERT_EQ(foveal("set alice f_y auto").exit_code, 0);
  ASSERT_EQ(foveal("export alice " + dir_.path("a.json")).exit_code, 0);
  r = foveal("import " + dir_.path("a.json") + " --name bob");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = foveal("list --json");
  j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["profiles"], nlohmann::json({"alice", "bob"}));
  EXPECT_EQ(j["active"], "alice");
  EXPECT_EQ(foveal("delete bob").exit_code, 0);
  EXPECT_EQ(foveal("show bob").exit_code, 2);
}

TEST_F(ProfileCli, BadValuesExitTwoAndChangeNothing) {
  ASSERT_EQ(foveal("create alice").exit_code, 0);
  const std::string before = test::read_file(dir_.path("foveal/profiles/alice.json"));
  auto r = foveal("set alice sigma_nd 1.5");  // below sigma_d 2.0
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("sigma_nd"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_file(dir_.path("foveal/profiles/alice.json")), before);
  r = foveal("set alice dominant_eye middle");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not left or right"), std::string::npos) << r.err;
  EXPECT_EQ(foveal("create alice").exit_code, 2);  // exists
  EXPECT_EQ(foveal("create ../x").exit_code, 2);
}

}  // namespace
}  // namespace foveal
