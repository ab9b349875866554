// `foveal profile ...` end to end, against a private XDG_CONFIG_HOME.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "foveal/runtime/profile.hpp"

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

// Issue 39 item 5: before any profile exists, `show` shows the built-in defaults foveald
// uses (not an error about a profile the user never made), and `set` says how a running
// foveald takes the change.
TEST_F(ProfileCli, ShowBeforeAnyProfileIsTheBuiltInDefaultsAndSetSaysHowFovealdTakesIt) {
  auto r = foveal("show");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("no profile made yet: foveald uses the built-in defaults"), std::string::npos) << r.out;
  r = foveal("show --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["builtin"], true);
  EXPECT_EQ(j["dominant_eye"], "right");
  EXPECT_EQ(foveal("show nobody").exit_code, 2) << "a named profile that is not there is still an error";
  ASSERT_EQ(foveal("create alice").exit_code, 0);
  r = foveal("set alice sigma_nd 3.5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("a running foveald takes it at `foveal ctl use alice` or a reload"), std::string::npos) << r.out;
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

// Issue 15 item 4: two writers racing on one profile. Each `set` prints the profile it
// saved; serialised, the 150 saved states form one chain in which every step applies
// exactly one more update of one writer. A lost update breaks the chain.
TEST_F(ProfileCli, AQualityTargetShowsTheLevelsItChoosesAndNeedsATable) {
  // A display model with a levels table beside it (foveal/runtime/jod_levels.hpp).
  test::write_file(dir_.path("m.json"), test::read_file(test::source_path("data/display/htc_vive_pro_eye.json")));
  test::write_file(dir_.path("m.levels.json"), R"({"format": "foveal-jod-levels v1", "display": "htc_vive_pro_eye",
    "sigmas": [2, 3, 4], "f": [0.2, 0.4], "jod": [[9.5, 9.0, 8.5], [9.8, 9.4, 9.0]]})");
  ASSERT_EQ(foveal("create alice").exit_code, 0);
  ASSERT_EQ(foveal("set alice display_model " + dir_.path("m.json")).exit_code, 0);
  auto r = foveal("set alice quality jod:9.2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = foveal("show alice --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["quality"], "jod:9.2");
  EXPECT_DOUBLE_EQ(j["sigma_d"].get<double>(), 2.0);  // the profile's own pair stays as it was
  EXPECT_NEAR(j["levels"]["sigma_d"].get<double>(), 3.5, 1e-9);
  EXPECT_NEAR(j["levels"]["sigma_nd"].get<double>(), 5.25, 1e-9);  // its EFR ratio 1.5
  EXPECT_DOUBLE_EQ(j["levels"]["f_x"].get<double>(), 0.4);
  EXPECT_NEAR(j["levels"]["predicted_jod_dominant"].get<double>(), 9.2, 1e-9);
  r = foveal("show alice");
  EXPECT_NE(r.out.find("predicted JOD 9.2 dominant"), std::string::npos) << r.out;
  // A model without a table cannot take a target, and a bad target is refused; nothing changes.
  const std::string before = test::read_file(dir_.path("foveal/profiles/alice.json"));
  test::write_file(dir_.path("bare.json"), test::read_file(dir_.path("m.json")));
  r = foveal("set alice display_model " + dir_.path("bare.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bare.levels.json"), std::string::npos) << r.err;
  r = foveal("set alice quality jod:12");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("quality"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_file(dir_.path("foveal/profiles/alice.json")), before);
  ASSERT_EQ(foveal("set alice quality off").exit_code, 0);
  EXPECT_FALSE(nlohmann::json::parse(foveal("show alice --json").out).contains("levels"));
}

TEST_F(ProfileCli, ConcurrentSetsOnOneProfileLoseNoUpdate) {
  ASSERT_EQ(foveal("create alice").exit_code, 0);
  ASSERT_EQ(foveal("set alice ipd_mm 50").exit_code, 0);
  constexpr int kEach = 75;
  const std::string cmd = "XDG_CONFIG_HOME=" + dir_.path() + " " + test::bin("foveal") + " profile set alice ";
  // writer A: sigma_nd = 3 + i/100; writer B: ipd_mm = 50 + i/10
  const std::string n = std::to_string(kEach);
  test::write_file(dir_.path("race.sh"),
                   "a() { for i in $(seq 1 " + n + "); do " + cmd + "sigma_nd $(printf '3.%02d' $i) --json > " +
                       dir_.path("a") + "$i.json || echo fail; done; }\n"
                   "b() { for i in $(seq 1 " + n + "); do " + cmd +
                       "ipd_mm $(awk -v i=$i 'BEGIN { printf \"%.1f\", 50 + i / 10 }') --json > " + dir_.path("b") +
                       "$i.json || echo fail; done; }\n"
                   "a & b & wait\n");
  auto r = test::run("bash " + dir_.path("race.sh"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("fail"), std::string::npos) << r.out << r.err;

  std::vector<std::pair<int, int>> states;  // (A's updates, B's updates) in each saved profile
  for (const char* who : {"a", "b"})
    for (int i = 1; i <= kEach; ++i) {
      const std::string text = test::read_file(dir_.path(std::string(who) + std::to_string(i) + ".json"));
      const auto j = nlohmann::json::parse(text, nullptr, false);
      ASSERT_FALSE(j.is_discarded()) << who << i << ": " << text;
      states.emplace_back(static_cast<int>(std::lround((j["sigma_nd"].get<double>() - 3.0) * 100)),
                          static_cast<int>(std::lround((j["ipd_mm"].get<double>() - 50.0) * 10)));
    }
  std::sort(states.begin(), states.end(), [](auto x, auto y) { return x.first + x.second < y.first + y.second; });
  std::pair<int, int> prev{0, 0};
  int lost = 0;
  for (const auto& s : states) {
    const bool one_step = (s.first == prev.first + 1 && s.second == prev.second) ||
                          (s.first == prev.first && s.second == prev.second + 1);
    if (!one_step) ++lost;
    prev = s;
  }
  EXPECT_EQ(lost, 0) << "saved states that dropped another writer's update";
  auto final_state = nlohmann::json::parse(foveal("show alice --json").out);
  EXPECT_DOUBLE_EQ(final_state["sigma_nd"].get<double>(), 3.75);
  EXPECT_DOUBLE_EQ(final_state["ipd_mm"].get<double>(), 57.5);
}

TEST_F(ProfileCli, AHeldStoreLockTimesOutWithAClearError) {
  ASSERT_EQ(foveal("create alice").exit_code, 0);
  const ProfileStore store(dir_.path("foveal"));
  auto held = store.lock();
  ASSERT_TRUE(held) << held.error().message;
  auto again = store.lock(200);  // a second descriptor: flock excludes it like another process
  ASSERT_FALSE(again);
  EXPECT_NE(again.error().message.find(dir_.path("foveal/lock")), std::string::npos) << again.error().message;
}

TEST_F(ProfileCli, AFifoAsTheActiveFileIsNamedNotWaitedFor) {
  // `profile list` waited in open() for a writer that never came.
  ASSERT_EQ(foveal("create alice").exit_code, 0);
  const std::string active = dir_.path("foveal/active");
  ASSERT_EQ(::mkfifo(active.c_str(), 0600), 0);
  const std::string alice = test::read_file(dir_.path("foveal/profiles/alice.json"));
  for (const char* cmd : {"list", "show", "show alice", "set alice sigma_nd 3.5", "create bob"}) {
    // `timeout` turns the old hang into a failure (exit 124) instead of a stuck test.
    const auto r = test::run("XDG_CONFIG_HOME=" + dir_.path() + " timeout 10 " + test::bin("foveal") + " profile " + cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd << ": " << r.err;
    EXPECT_NE(r.err.find(active + ": the active-profile file is a FIFO"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_EQ(test::read_file(dir_.path("foveal/profiles/alice.json")), alice) << "a refused set writes nothing";
  EXPECT_FALSE(std::filesystem::exists(dir_.path("foveal/profiles/bob.json"))) << "nor does a refused create";
}

}  // namespace
}  // namespace foveal
