// bench --gaze-video without rendering (tools/bench/src/gaze_video.cpp): the head's mean
// speed over a sequence, a sequence scored as one video with blinks left out, and the
// frames after the recording's saccades.
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
  std::vector<std::size_t> checked;  // the per-frame check sees the frames that joined, in order
  auto check = [&](std::size_t k, const image::Image& r, const image::Image& t) -> Status {
    EXPECT_EQ(r.rgba, ref[k].rgba);
    EXPECT_EQ(t.rgba, ref[k].rgba);
    checked.push_back(k);
    return k == 4 && checked.size() > 3 ? Status(bad_input("frame 4 refused")) : Status{};
  };
  ASSERT_TRUE(bench::score_gaze_video(*jod, 90, frames, reference, same, check));
  EXPECT_EQ(checked, (std::vector<std::size_t>{0, 1, 4, 5}));
  auto refused = bench::score_gaze_video(*jod, 90, frames, reference, same, check);  // its error ends the video
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message, "frame 4 refused");
  EXPECT_EQ(checked, (std::vector<std::size_t>{0, 1, 4, 5, 0, 1, 4}));
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

namespace {

// A frame whose both eyes look at viewport point (x, 0.5).
bench::GazeFrame looking_at(double x) {
  bench::GazeFrame f;
  f.truth = {glm::dvec2(x, 0.5), glm::dvec2(x, 0.5)};
  return f;
}

}  // namespace

TEST(GazeVideo, ASaccadeMarksItsOnsetAndTheFramesAfterIt) {
  const DisplayModel model = DisplayModel::vive_pro_eye();
  const double fps = 90;
  // A fixation drifting 0.001 of the view a frame (about 0.1 deg: 10 deg/s, under the
  // threshold), a jump of 0.2 of the view (tens of degrees) at frame 5 split over frames 5
  // and 6, fixation again, a blink at 15 (never post-saccade, never a step), and a second
  // jump at 20, right after the blink.
  std::vector<bench::GazeFrame> frames;
  for (int k = 0; k < 30; ++k) {
    double x = 0.3 + 0.001 * k;
    if (k >= 5) x += 0.1;
    if (k >= 6) x += 0.1;
    if (k >= 20) x -= 0.3;
    frames.push_back(looking_at(x));
  }
  frames[15].blink = true;
  const bench::SaccadeWindows w = bench::find_saccades(frames, model, fps);
  EXPECT_EQ(w.onsets, 2u);  // the jump over two frames is one saccade
  ASSERT_EQ(w.post.size(), frames.size());
  EXPECT_EQ(w.step_deg[0], 0.0);
  EXPECT_LT(w.step_deg[1], bench::kSaccadeDegPerS / fps);
  EXPECT_GT(w.step_deg[5], 5.0);
  for (int k = 0; k < 30; ++k) {
    // Onset 5, again at 6 (the window restarts there), so frames 5-12; then 20-26.
    const bool expected = (k >= 5 && k <= 6 + static_cast<int>(bench::kPostSaccadeFrames)) ||
                          (k >= 20 && k <= 20 + static_cast<int>(bench::kPostSaccadeFrames));
    EXPECT_EQ(w.post[static_cast<std::size_t>(k)], expected) << "frame " << k;
  }
  EXPECT_EQ(w.step_deg[15], 0.0);
  EXPECT_LT(w.step_deg[16], bench::kSaccadeDegPerS / fps);  // measured from frame 14, the last seen
  // At 30 fps the same drift is three times the speed, still a fixation.
  EXPECT_EQ(bench::find_saccades(frames, model, 30).onsets, 2u);
}

TEST(GazeVideo, PostSaccadeFiguresAreTheMarkedFramesAndTheWorstAgainstOff) {
  bench::SaccadeWindows w;
  w.post = {false, true, true, false};
  auto fig = [](double fpsnr, std::optional<double> jod) {
    bench::VideoFrameFigures f;
    f.fpsnr_db = fpsnr;
    if (jod) f.jod = bench::StereoJod{*jod, *jod, *jod};
    return f;
  };
  const std::vector<bench::VideoFrameFigures> off = {fig(30, {}), fig(20, 8.0), fig(22, 8.5), fig(31, {})};
  const std::vector<bench::VideoFrameFigures> on = {fig(40, {}), fig(21, 8.25), fig(21.5, 8.0), fig(10, {})};
  const bench::PostSaccade a = bench::post_saccade(w, on, &off);
  EXPECT_EQ(a.frames, 2u);
  EXPECT_DOUBLE_EQ(a.fpsnr_mean, 21.25);
  EXPECT_DOUBLE_EQ(a.jod_mean, 8.125);
  EXPECT_DOUBLE_EQ(a.fpsnr_worst_vs_off, -0.5);  // frame 2; frame 3 is not after a saccade
  EXPECT_DOUBLE_EQ(a.jod_worst_vs_off, -0.5);
  const bench::PostSaccade alone = bench::post_saccade(w, off, nullptr);
  EXPECT_DOUBLE_EQ(alone.fpsnr_mean, 21.0);
  EXPECT_TRUE(std::isnan(alone.fpsnr_worst_vs_off));
  EXPECT_TRUE(std::isnan(alone.jod_worst_vs_off));
  EXPECT_EQ(bench::post_saccade(bench::SaccadeWindows{}, on, &off).frames, 0u);
  EXPECT_TRUE(std::isnan(bench::post_saccade(bench::SaccadeWindows{}, on, &off).fpsnr_mean));
}
