// bench --gaze-video without rendering (tools/bench/src/gaze_video.cpp): the head's mean
// speed over a sequence, and a sequence scored as one video with blinks left out.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/quaternion.hpp>

#include "foveal/bench/gaze_video.hpp"

using namespace foveal;

namespace {

bench::GazeFrame frame_turned(double yaw_deg) {
  bench::GazeFrame f;
  f.head.valid = true;
  f.head.relative.orientation = glm::angleAxis(static_cast<float>(yaw_deg * 3.14159265358979323846 / 180.0), glm::vec3(0, 1, 0));
  f.truth = {glm::dvec2(0.5), glm::dvec2(0.5)};
  return f;
}

image::Image noise(int w, int h, unsigned seed, int amplitude) {
  image::Image img(w, h);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> v(128 - amplitude, 127 + amplitude);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = p[1] = p[2] = static_cast<std::uint8_t>(v(rng));
      p[3] = 255;
    }
  return img;
}

}  // namespace

TEST(GazeVideo, HeadSpeedIsTheTurnOverTheSequencesDuration) {
  // 40 deg/s at 90 Hz: 0.444 deg a frame, over 10 frames; then back and forth.
  std::vector<bench::GazeFrame> turn;
  for (int k = 0; k < 10; ++k) turn.push_back(frame_turned(40.0 * k / 90.0));
  EXPECT_NEAR(bench::mean_head_speed_deg_s(turn, 90), 40.0, 0.05);
  EXPECT_NEAR(bench::mean_head_speed_deg_s(turn, 45), 20.0, 0.03);  // the same turn over twice the time
  std::vector<bench::GazeFrame> shake;
  for (int k = 0; k < 9; ++k) shake.push_back(frame_turned(k % 2 ? 1.0 : -1.0));  // 2 deg a frame, either way
  EXPECT_NEAR(bench::mean_head_speed_deg_s(shake, 90), 180.0, 0.2);
  // A slow turn, 1 deg/s: 0.011 deg a frame, below what a float dot product resolves.
  std::vector<bench::GazeFrame> slow;
  for (int k = 0; k < 12; ++k) slow.push_back(frame_turned(30 + 1.0 * k / 90.0));
  EXPECT_NEAR(bench::mean_head_speed_deg_s(slow, 90), 1.0, 0.02);
  // q and -q are one orientation: no turn.
  std::vector<bench::GazeFrame> flipped = {frame_turned(10), frame_turned(10)};
  flipped[1].head.relative.orientation = -flipped[1].head.relative.orientation;
  EXPECT_NEAR(bench::mean_head_speed_deg_s(flipped, 90), 0.0, 1e-3);
  std::vector<bench::GazeFrame> still(5);  // a static head: no pose
  EXPECT_EQ(bench::mean_head_speed_deg_s(still, 90), 0.0);
  EXPECT_EQ(bench::mean_head_speed_deg_s({frame_turned(3)}, 90), 0.0);
}

TEST(GazeVideo, ASequenceIsOneVideoWithBlinksLeftOut) {
  const int w = 128, h = 64;
  auto jod = bench::StereoJodScorer::create(DisplayModel::vive_pro_eye(), w, h, 1);
  ASSERT_TRUE(jod);
  std::vector<bench::GazeFrame> frames(6, frame_turned(0));
  frames[2].blink = frames[3].blink = true;
  std::vector<image::Image> ref, flicker;
  for (unsigned k = 0; k < frames.size(); ++k) {
    ref.push_back(noise(w, h, k, 40));
    flicker.push_back(k % 2 ? noise(w, h, 100 + k, 40) : ref.back());  // every other frame wrong
  }
  std::vector<std::size_t> asked;
  auto reference = [&](std::size_t k) -> Result<image::Image> { return ref[k]; };
  auto same = [&](std::size_t k) -> Result<image::Image> {
    asked.push_back(k);
    return ref[k];
  };
  auto s = bench::score_gaze_video(*jod, 90, frames, reference, same);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->frames, 4u);
  EXPECT_EQ(s->blink_frames, 2u);
  EXPECT_EQ(asked, (std::vector<std::size_t>{0, 1, 4, 5})) << "frames in a blink are not rendered";
  EXPECT_DOUBLE_EQ(s->jod.combined, 10);
  auto bad = bench::score_gaze_video(*jod, 90, frames, reference, [&](std::size_t k) -> Result<image::Image> { return flicker[k]; });
  ASSERT_TRUE(bad);
  EXPECT_LT(bad->jod.combined, 9.5);
  EXPECT_LT(bad->jod.left, 10);
  EXPECT_LT(bad->jod.right, 10);

  for (auto& f : frames) f.blink = true;
  auto none = bench::score_gaze_video(*jod, 90, frames, reference, same);
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("--gaze-video"), std::string::npos) << none.error().message;
}
