// foveald with the recorded head pose: frames.csv carries the pose each frame used,
// taken from the log's own rows, and the camera moves with it (a real process, real GL).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/gaze_log.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

using PoseRow = std::array<double, 7>;  // x, y, z, qw, qx, qy, qz

std::vector<PoseRow> frame_poses(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::istringstream h(line); std::getline(h, line, ',');) names.push_back(line);
  const auto col = static_cast<std::size_t>(std::find(names.begin(), names.end(), "head_x") - names.begin());
  EXPECT_LT(col + 6, names.size()) << "frames.csv has the head columns";
  EXPECT_EQ(names.empty() ? "" : names.back(), "blend_ms") << "the blend pass is frames.csv's last column";
  std::vector<PoseRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    for (std::istringstream r(line); std::getline(r, line, ',');) f.push_back(line);
    EXPECT_EQ(f.size(), names.size()) << "a row with as many cells as the header";
    if (f.size() < col + 7) break;
    PoseRow p;
    for (std::size_t i = 0; i < 7; ++i) p[i] = std::stod(f[col + i]);
    rows.push_back(p);
  }
  return rows;
}

test::RunResult foveald(const std::string& dir, const std::string& args) {
  return test::run("XDG_CONFIG_HOME=" + dir + "/cfg " + test::bin("foveald") + " --replay " +
                   test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv") +
                   " --start 2 --end 4 --method full --size 96x54 --no-control --no-shm -q " + args);
}

TEST(FovealdHead, FramesFollowTheRecordedHeadAndTheCameraMoves) {
  test::TempDir d;
  const auto rec = foveald(d.path(), "--out " + d.path("rec"));  // a v2 log with poses: recorded by default
  ASSERT_EQ(rec.exit_code, 0) << rec.err;
  const auto stat = foveald(d.path(), "--head static --out " + d.path("static"));
  ASSERT_EQ(stat.exit_code, 0) << stat.err;
  const auto summary = nlohmann::json::parse(test::read_file(d.path("rec/summary.json")));
  EXPECT_EQ(summary["head"]["mode"], "recorded");
  EXPECT_GT(summary["head"]["poses"].get<int>(), 200);

  // Every frame's pose is one of the log's rows (the frame's gaze sample's), in order.
  std::vector<PoseRow> log;
  auto reader = GazeLogReader::open(test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv"));
  ASSERT_TRUE(reader) << reader.error().message;
  GazeSample s;
  while (true) {
    auto more = reader->next(s);
    ASSERT_TRUE(more) << more.error().message;
    if (!*more) break;
    if (!s.head.valid) continue;
    const Pose& p = s.head.pose;
    log.push_back({p.position_m.x, p.position_m.y, p.position_m.z, p.orientation.w, p.orientation.x, p.orientation.y,
                   p.orientation.z});
  }
  const auto frames = frame_poses(test::read_file(d.path("rec/frames.csv")));
  ASSERT_GE(frames.size(), 3u);
  std::size_t from = 0;
  const PoseRow identity{0, 0, 0, 1, 0, 0, 0};
  for (const PoseRow& f : frames) {
    if (f == identity) continue;  // a frame rendered before the first sample (a loaded machine): no pose yet
    std::size_t k = from;
    const auto same = [&](const PoseRow& l) {
      for (std::size_t i = 0; i < 7; ++i)
        if (std::abs(l[i] - f[i]) > 1e-6) return false;
      return true;
    };
    while (k < log.size() && !same(log[k])) ++k;
    ASSERT_LT(k, log.size()) << "a frame's head pose is not a row of the log (or out of order)";
    from = k;
  }
  ASSERT_NE(frames.back(), identity);
  const PoseRow& first = frames.front() == identity ? frames[1] : frames.front();
  const PoseRow& last = frames.back();
  double moved = 0;
  for (std::size_t i = 0; i < 7; ++i) moved = std::max(moved, std::abs(first[i] - last[i]));
  EXPECT_GT(moved, 1e-3) << "the head moves over these 2 s of the recording";

  // A static camera records the identity, and with full rendering (no fovea) every frame
  // is the same picture; the recorded head's last frame is not.
  for (const PoseRow& f : frame_poses(test::read_file(d.path("static/frames.csv"))))
    EXPECT_EQ(f, identity);
  const auto saved_png = [&](const std::string& dir, bool final_frame) {
    const auto j = nlohmann::json::parse(test::read_file(d.path(dir + "/summary.json")));
    const auto& saved = j["render"]["saved"];
    return test::read_file(d.path(dir + "/" + (final_frame ? saved.back() : saved.front()).get<std::string>()));
  };
  EXPECT_EQ(saved_png("static", true), saved_png("static", false));
  EXPECT_NE(saved_png("rec", true), saved_png("static", true)) << "the recorded head moved the camera";

  // --head recorded on a log without poses is refused, naming it.
  const auto old = test::run("XDG_CONFIG_HOME=" + d.path("cfg") + " " + test::bin("foveald") + " --replay " +
                             test::source_path("tests/vm/data/constant_gaze.csv") + " --head recorded --no-render --out " +
                             d.path("old"));
  EXPECT_EQ(old.exit_code, 2);
  EXPECT_NE(old.err.find("carries no head pose"), std::string::npos) << old.err;
}

}  // namespace
}  // namespace foveal
