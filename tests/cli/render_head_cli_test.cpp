// foveal render --head and --log --at: the camera follows the pose given, a log's pose at
// a time is the pose bench --gaze would use (relative to the log's first), bad poses refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "foveal/core/gaze_log.hpp"
#include "foveal/image/image.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

const std::string kLog = "data/gaze/vive_pro_eye_TESTNA01.csv";  // a v2 log: the head turns over its first seconds

std::string render_cmd(const std::string& args, const std::string& out) {
  return test::bin("foveal") + " render --scene " + test::source_path("data/scenes/WaterBottle/WaterBottle.gltf") +
         " --size 160x90 --frames 1 --warmup 0 --json " + args + " --out " + out;
}

image::Image load(const std::string& path) {
  auto img = image::load(path);
  EXPECT_TRUE(img) << path;
  return img ? *img : image::Image{};
}

bool same_pixels(const image::Image& a, const image::Image& b) {
  return a.width == b.width && a.height == b.height && a.rgba == b.rgba;
}

// What the test expects --log LOG --at T to use, found without the command: the latest
// sample at or before T, its pose relative to the log's first pose.
Pose relative_pose_at(const std::vector<GazeSample>& s, double at_s) {
  const TimeNs t = s.front().t_ns + static_cast<TimeNs>(at_s * 1e9);
  const auto first = std::find_if(s.begin(), s.end(), [](const GazeSample& g) { return g.head.valid; });
  const GazeSample* latest = nullptr;
  for (const GazeSample& g : s)
    if (g.t_ns <= t && g.head.valid) latest = &g;
  EXPECT_TRUE(first != s.end() && latest);
  return relative_to(first->head.pose, latest->head.pose);
}

std::string pose_arg(const Pose& p) {
  char b[256];
  std::snprintf(b, sizeof b, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", p.position_m.x, p.position_m.y, p.position_m.z,
                p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  return b;
}

}  // namespace

TEST(RenderHead, TwoHeadPosesGiveTwoPicturesAndTheIdentityIsTheScenesView) {
  test::TempDir d;
  auto view = test::run(render_cmd("", d.path("view.png")));
  auto identity = test::run(render_cmd("--head 0,0,0,1,0,0,0", d.path("identity.png")));
  auto turned = test::run(render_cmd("--head 0,0,0,0.9961947,0,0.0871557,0", d.path("turned.png")));  // 10 deg to the left
  auto stepped = test::run(render_cmd("--head 0.05,0,0,1,0,0,0", d.path("stepped.png")));
  for (const auto* r : {&view, &identity, &turned, &stepped}) ASSERT_EQ(r->exit_code, 0) << r->err;
  const auto j = nlohmann::json::parse(turned.out);
  EXPECT_EQ(j["head"]["source"], "head");
  EXPECT_NEAR(j["head"]["orientation_wxyz"][2].get<double>(), 0.0871557, 1e-6);
  EXPECT_EQ(nlohmann::json::parse(view.out)["head"]["source"], "scene");
  const image::Image v = load(d.path("view.png"));
  EXPECT_TRUE(same_pixels(v, load(d.path("identity.png")))) << "the identity pose is the scene's view";
  EXPECT_FALSE(same_pixels(v, load(d.path("turned.png"))));
  EXPECT_LT(image::psnr(v, load(d.path("turned.png"))), 30.0) << "a 10 degree turn moves the picture";
  EXPECT_FALSE(same_pixels(v, load(d.path("stepped.png"))));
  EXPECT_FALSE(same_pixels(load(d.path("turned.png")), load(d.path("stepped.png"))));
}

TEST(RenderHead, LogAtATimeIsTheHeadPoseTheLogHasThen) {
  test::TempDir d;
  auto samples = read_gaze_log(test::source_path(kLog));
  ASSERT_TRUE(samples) << samples.error().message;
  const double at = 3.0;
  const Pose expected = relative_pose_at(*samples, at);
  ASSERT_GT(glm::length(expected.position_m) + std::abs(1.0f - std::abs(expected.orientation.w)), 1e-3f)
      << "the head has moved by then (else the test shows nothing)";
  const std::string foveae = " --fovea-left 0.4,0.5 --fovea-right 0.6,0.5";
  auto from_log = test::run(render_cmd("--log " + test::source_path(kLog) + " --at 3" + foveae, d.path("log.png")));
  auto given = test::run(render_cmd("--head " + pose_arg(expected) + foveae, d.path("head.png")));
  ASSERT_EQ(from_log.exit_code, 0) << from_log.err;
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_TRUE(same_pixels(load(d.path("log.png")), load(d.path("head.png"))));
  auto still = test::run(render_cmd("--head 0,0,0,1,0,0,0" + foveae, d.path("still.png")));
  ASSERT_EQ(still.exit_code, 0) << still.err;
  EXPECT_FALSE(same_pixels(load(d.path("log.png")), load(d.path("still.png")))) << "the log's head moved the camera";

  const auto j = nlohmann::json::parse(from_log.out);
  EXPECT_EQ(j["head"]["source"], "log");
  EXPECT_DOUBLE_EQ(j["head"]["at_s"].get<double>(), 3.0);
  EXPECT_LE(j["head"]["sample_s"].get<double>(), 3.0);
  EXPECT_GT(j["head"]["sample_s"].get<double>(), 3.0 - 1.0 / 60);  // a 120 Hz log
  EXPECT_EQ(j["head"]["fovea_source"]["left"], "option");
  for (int i = 0; i < 3; ++i)
    EXPECT_FLOAT_EQ(j["head"]["position_m"][i].get<float>(), expected.position_m[i]) << i;
  EXPECT_FLOAT_EQ(j["head"]["orientation_wxyz"][0].get<float>(), expected.orientation.w);

  // Without --fovea-*, the log's filtered fovea: reported, and the same picture as that
  // fovea given with the same pose.
  auto own = test::run(render_cmd("--log " + test::source_path(kLog) + " --at 3", d.path("own.png")));
  ASSERT_EQ(own.exit_code, 0) << own.err;
  const auto o = nlohmann::json::parse(own.out);
  EXPECT_EQ(o["head"]["fovea_source"]["right"], "log");
  std::string fovea_args;
  for (const char* eye : {"left", "right"}) {
    const double x = o["eyes"][eye]["fovea"][0].get<double>(), y = o["eyes"][eye]["fovea"][1].get<double>();
    EXPECT_TRUE(x >= 0 && x <= 1 && y >= 0 && y <= 1) << eye;
    EXPECT_FALSE(x == 0.5 && y == 0.5) << eye << ": the recorded gaze is not exactly at the centre";
    char b[96];
    std::snprintf(b, sizeof b, " --fovea-%s %.17g,%.17g", eye, x, y);
    fovea_args += b;
  }
  auto own_given = test::run(render_cmd("--head " + pose_arg(expected) + fovea_args, d.path("own_given.png")));
  ASSERT_EQ(own_given.exit_code, 0) << own_given.err;
  EXPECT_GT(image::psnr(load(d.path("own.png")), load(d.path("own_given.png"))), 60.0);
  EXPECT_FALSE(same_pixels(load(d.path("own.png")), load(d.path("log.png")))) << "another fovea, another picture";
}

TEST(RenderHead, BadPosesAndTimesAreRefusedNamingWhatAndWhere) {
  test::TempDir d;
  const std::string log = test::source_path(kLog);
  const std::string no_pose = test::source_path("tests/vm/data/constant_gaze.csv");
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"--head 1,2,3", "--head: expected X,Y,Z,QW,QX,QY,QZ"},
      {"--head 0,0,0,nan,0,0,0", "--head: qw: 'nan' is not finite"},
      {"--head 0,0,x,1,0,0,0", "--head: z: 'x' is not a number"},
      {"--head 0,0,0,0.5,0,0,0", "quaternion norm 0.5 is not 1 (tolerance 0.001)"},
      {"--head 0,0,0,1,0,0,0 --log " + log + " --at 1", "--head and --log"},
      {"--at 1", "--at needs --log"},
      {"--log " + log, "--log needs --at"},
      {"--log " + log + " --at soon", "--at: 'soon' is not a number"},
      {"--log " + log + " --at 999", "--at 999: outside " + log + ", whose samples span 0 to"},
      {"--log " + log + " --at -1", "--at -1: outside"},
      {"--log " + no_pose + " --at 0.5", no_pose + " carries no head pose"},
      {"--log " + d.path("missing.csv") + " --at 1", "missing.csv"},
  };
  for (const Case& c : cases) {
    auto r = test::run(render_cmd(c.args, d.path("x.png")));
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(d.path("x.png"))) << c.args;
  }
  // Past --at's own bound (1e7 s) in a log that spans more: the bound is named, not a
  // span the time is inside.
  {
    std::istringstream in(test::read_file(log));
    std::string text, line, first_row;
    while (std::getline(in, line) && (line.empty() || line[0] == '#' || line.rfind("t_ns", 0) == 0)) text += line + "\n";
    first_row = line;
    const std::string long_log = d.path("long.csv");
    test::write_file(long_log, text + first_row + "\n" + "20000000000000000" + first_row.substr(first_row.find(',')) + "\n");
    auto r = test::run(render_cmd("--log " + long_log + " --at 1.5e7", d.path("x.png")));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--at 1.5e+07: more than the 1e7 s (about 116 days) that --at accepts"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("outside"), std::string::npos) << r.err;
  }
  // Within the tolerance a quaternion is renormalised, not refused.
  auto near_unit = test::run(render_cmd("--head 0,0,0,1.0005,0,0,0", d.path("n.png")));
  ASSERT_EQ(near_unit.exit_code, 0) << near_unit.err;
  EXPECT_FLOAT_EQ(nlohmann::json::parse(near_unit.out)["head"]["orientation_wxyz"][0].get<float>(), 1.0f);
}
