#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include "foveal/runtime/profile.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

TEST(Profile, DefaultsAreTheEfrSeedPair) {
  Profile p;
  EXPECT_EQ(p.dominant_eye, Eye::right);
  EXPECT_DOUBLE_EQ(p.sigma_d, 2.0);
  EXPECT_DOUBLE_EQ(p.sigma_nd, 3.0);
  EXPECT_DOUBLE_EQ(p.sigma(Eye::right), 2.0);
  EXPECT_DOUBLE_EQ(p.sigma(Eye::left), 3.0);
  EXPECT_TRUE(p.validate("x"));
}

TEST(Profile, JsonRoundTrip) {
  Profile p;
  p.name = "alice";
  p.dominant_eye = Eye::left;
  p.sigma_d = 2.2;
  p.sigma_nd = 3.4;
  p.f_x.reset();
  p.f_y = 0.25;
  p.filter = {{"min_cutoff_hz", 1.0}};
  auto q = Profile::from_json(p.to_json(), "alice", "test");
  ASSERT_TRUE(q) << q.error().message;
  EXPECT_EQ(q->dominant_eye, Eye::left);
  EXPECT_DOUBLE_EQ(q->sigma(Eye::left), 2.2);
  EXPECT_DOUBLE_EQ(q->sigma(Eye::right), 3.4);
  EXPECT_FALSE(q->f_x.has_value());
  EXPECT_DOUBLE_EQ(*q->f_y, 0.25);
  EXPECT_EQ(q->filter, p.filter);
}

struct BadProfile {
  const char* name;
  const char* json;
  const char* expect;
};

class ProfileRejects : public ::testing::TestWithParam<BadProfile> {};

TEST_P(ProfileRejects, WithAMessageNamingTheKey) {
  const auto j = nlohmann::json::parse(GetParam().json);
  auto p = Profile::from_json(j, "x", "prof.json");
  ASSERT_FALSE(p) << GetParam().name;
  EXPECT_NE(p.error().message.find("prof.json"), std::string::npos) << p.error().message;
  EXPECT_NE(p.error().message.find(GetParam().expect), std::string::npos) << p.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ProfileRejects,
    ::testing::Values(BadProfile{"unknown_key", R"({"sigma":2})", "unknown key 'sigma'"},
                      BadProfile{"sigma_below_1", R"({"sigma_d":0.9})", "sigma_d"},
                      BadProfile{"sigma_nd_below_sigma_d", R"({"sigma_d":3,"sigma_nd":2})", "must be >= sigma_d"},
                      BadProfile{"eye_not_left_right", R"({"dominant_eye":"both"})", "not left or right"},
                      BadProfile{"eye_not_string", R"({"dominant_eye":1})", "dominant_eye"},
                      BadProfile{"sigma_string", R"({"sigma_d":"2"})", "expected a number"},
                      BadProfile{"f_negative", R"({"f_x":-0.1})", "f_x"},
                      // Issue 38, item 17: f where the compositor is tested only, [0.01, 10].
                      BadProfile{"f_tiny", R"({"f_x":1e-300})", "f_x: 1e-300 is not in [0.01, 10]"},
                      BadProfile{"f_large", R"({"f_y":50})", "f_y: 50 is not in [0.01, 10]"},
                      BadProfile{"f_word", R"({"f_y":"wide"})", "\"auto\""},
                      BadProfile{"ipd_absurd", R"({"ipd_mm":300})", "ipd_mm"},
                      BadProfile{"filter_not_object", R"({"filter":3})", "filter"},
                      BadProfile{"wrong_format", R"({"format":"foveal-profile v9"})", "format"},
                      BadProfile{"not_object", R"([1,2])", "object"}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

TEST(Profile, SetParsesAndValidates) {
  Profile p;
  p.name = "a";
  EXPECT_TRUE(p.set("sigma_nd", "3.5"));
  EXPECT_DOUBLE_EQ(p.sigma_nd, 3.5);
  EXPECT_TRUE(p.set("f_x", "auto"));
  EXPECT_FALSE(p.f_x.has_value());
  EXPECT_TRUE(p.set("dominant_eye", "left"));
  EXPECT_EQ(p.dominant_eye, Eye::left);
  EXPECT_FALSE(p.set("sigma_d", "4"));  // above sigma_nd 3.5
  EXPECT_DOUBLE_EQ(p.sigma_d, 2.0);     // unchanged on failure
  EXPECT_FALSE(p.set("sigma_d", "two"));
  EXPECT_FALSE(p.set("f_x", "1e-300"));  // issue 38, item 17
  EXPECT_TRUE(p.set("f_x", "0.01"));
  EXPECT_TRUE(p.set("f_y", "10"));
  EXPECT_FALSE(p.set("colour", "red"));
}

// Temporal accumulation (docs/rmfr.md): off by default and then not written, so older
// readers and the files they wrote are unchanged; "on" round-trips; anything else is refused.
TEST(Profile, TemporalKeyIsOffByDefaultAndOnOrOff) {
  Profile p;
  p.name = "a";
  EXPECT_FALSE(p.temporal);
  EXPECT_FALSE(p.to_json().contains("temporal"));
  EXPECT_TRUE(p.set("temporal", "on"));
  EXPECT_TRUE(p.temporal);
  auto back = Profile::from_json(p.to_json(), "a", "x");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(back->temporal);
  EXPECT_TRUE(p.set("temporal", "off"));
  EXPECT_FALSE(p.temporal);
  EXPECT_FALSE(p.set("temporal", "yes"));
  EXPECT_FALSE(p.temporal);
  auto bad = Profile::from_json(nlohmann::json{{"temporal", true}}, "a", "f.json");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("temporal"), std::string::npos) << bad.error().message;
}

TEST(ProfileStore, SaveLoadListActiveDelete) {
  test::TempDir dir;
  ProfileStore store(dir.path("foveal"));
  EXPECT_EQ(store.active().value(), "default");
  Profile p;
  p.name = "bob";
  p.sigma_nd = 2.6;
  ASSERT_TRUE(store.save(p));
  p.name = "alice";
  ASSERT_TRUE(store.save(p));
  auto names = store.list();
  ASSERT_TRUE(names);
  EXPECT_EQ(*names, (std::vector<std::string>{"alice", "bob"}));
  auto bob = store.load("bob");
  ASSERT_TRUE(bob) << bob.error().message;
  EXPECT_DOUBLE_EQ(bob->sigma_nd, 2.6);
  ASSERT_TRUE(store.set_active("bob"));
  EXPECT_EQ(store.active().value(), "bob");
  EXPECT_FALSE(store.set_active("nobody"));
  ASSERT_TRUE(store.remove("alice"));
  EXPECT_FALSE(store.exists("alice"));
  EXPECT_FALSE(store.remove("alice"));
}

TEST(ProfileStore, RejectsUnsafeNames) {
  test::TempDir dir;
  ProfileStore store(dir.path());
  Profile p;
  for (const char* bad : {"", "../etc", "a b", "a/b", "x.json"}) {
    p.name = bad;
    EXPECT_FALSE(store.save(p)) << bad;
    EXPECT_FALSE(store.load(bad)) << bad;
  }
}

TEST(ProfileStore, ABrokenFileIsReportedNotLoaded) {
  test::TempDir dir;
  ProfileStore store(dir.path());
  Profile p;
  p.name = "ok";
  ASSERT_TRUE(store.save(p));
  test::write_file(store.path_of("ok"), "{ \"sigma_d\": 2.0, ");  // truncated by hand
  auto q = store.load("ok");
  ASSERT_FALSE(q);
  EXPECT_NE(q.error().message.find("ok.json"), std::string::npos) << q.error().message;
  EXPECT_NE(q.error().message.find("not valid JSON"), std::string::npos) << q.error().message;
}

// A FIFO as the active-profile file hung every reader in open() (foveald with SIGTERM
// masked); a link to a device read it without end. Both are named and refused at once.
TEST(ProfileStore, AFifoOrDeviceAsTheActiveFileIsRefusedNamedWithoutBlocking) {
  test::TempDir dir;
  ProfileStore store(dir.path("foveal"));
  ASSERT_TRUE(std::filesystem::create_directories(dir.path("foveal")));
  const std::string active = dir.path("foveal/active");
  ASSERT_EQ(::mkfifo(active.c_str(), 0600), 0);
  auto a = store.active();
  ASSERT_FALSE(a);
  EXPECT_NE(a.error().message.find(active + ": the active-profile file is a FIFO"), std::string::npos) << a.error().message;
  ASSERT_EQ(::unlink(active.c_str()), 0);
  ASSERT_EQ(::symlink("/dev/zero", active.c_str()), 0);
  a = store.active();
  ASSERT_FALSE(a);
  EXPECT_NE(a.error().message.find("a character device"), std::string::npos) << a.error().message;
  ASSERT_EQ(::unlink(active.c_str()), 0);
  EXPECT_EQ(store.active().value(), "default") << "no file: the default, as before";
}

TEST(ProfileStore, AFifoAsTheLockFileIsRefused) {
  test::TempDir dir;
  ProfileStore store(dir.path("foveal"));
  ASSERT_TRUE(std::filesystem::create_directories(dir.path("foveal")));
  ASSERT_EQ(::mkfifo(dir.path("foveal/lock").c_str(), 0600), 0);
  auto lock = store.lock(100);
  ASSERT_FALSE(lock);
  EXPECT_NE(lock.error().message.find("lock file is not a regular file"), std::string::npos) << lock.error().message;
}

}  // namespace
}  // namespace foveal
