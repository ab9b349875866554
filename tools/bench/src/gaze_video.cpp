#include "foveal/bench/gaze_video.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "foveal/image/foveation_plan.hpp"

namespace foveal::bench {

double mean_head_speed_deg_s(const std::vector<GazeFrame>& frames, double fps) {
  if (frames.size() < 2 || !(fps > 0)) return 0;
  double deg = 0;
  for (std::size_t k = 1; k < frames.size(); ++k) {
    const PoseAt &a = frames[k - 1].head, &b = frames[k].head;
    if (!a.valid || !b.valid) continue;
    // The rotation from a to b, r = a⁻¹·b, turns by 2·atan2(|r.xyz|, |r.w|): sign-free (q
    // and −q are one orientation) and, in double, exact for the hundredths of a degree a
    // slow head turns between frames (acos of a float dot product rounds them to 0).
    const glm::dquat r = glm::conjugate(glm::dquat(a.relative.orientation)) * glm::dquat(b.relative.orientation);
    deg += 2.0 * std::atan2(glm::length(glm::dvec3(r.x, r.y, r.z)), std::abs(r.w)) * 180.0 / 3.14159265358979323846;
  }
  return deg / (static_cast<double>(frames.size() - 1) / fps);
}

SaccadeWindows find_saccades(const std::vector<GazeFrame>& frames, const DisplayModel& model, double fps) {
  SaccadeWindows out;
  out.step_deg.assign(frames.size(), 0.0);
  out.post.assign(frames.size(), false);
  const double threshold_deg = kSaccadeDegPerS / fps;
  const GazeFrame* prev = nullptr;
  std::size_t left = 0;  // frames of the current window still to mark
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const GazeFrame& f = frames[k];
    if (f.blink) continue;
    if (prev)
      for (Eye e : kEyes) {
        const std::size_t i = static_cast<std::size_t>(e);
        out.step_deg[k] = std::max(out.step_deg[k], render::eccentricity_deg(model.eye(e), prev->truth[i], f.truth[i]));
      }
    if (out.step_deg[k] > threshold_deg) {
      if (left == 0) ++out.onsets;  // a saccade spanning frames is one
      left = kPostSaccadeFrames + 1;
    }
    if (left > 0) out.post[k] = true, --left;
    prev = &f;
  }
  return out;
}

PostSaccade post_saccade(const SaccadeWindows& windows, const std::vector<VideoFrameFigures>& figures,
                         const std::vector<VideoFrameFigures>* off) {
  PostSaccade out;
  double fpsnr = 0, jod = 0;
  std::size_t jods = 0;
  const bool compare = off && off->size() == figures.size();
  for (std::size_t k = 0; k < figures.size() && k < windows.post.size(); ++k) {
    if (!windows.post[k]) continue;
    const VideoFrameFigures& f = figures[k];
    ++out.frames;
    fpsnr += f.fpsnr_db;
    if (compare) out.fpsnr_worst_vs_off = std::fmin(out.fpsnr_worst_vs_off, f.fpsnr_db - (*off)[k].fpsnr_db);
    if (!f.jod) continue;
    jod += f.jod->combined, ++jods;
    if (compare && (*off)[k].jod) out.jod_worst_vs_off = std::fmin(out.jod_worst_vs_off, f.jod->combined - (*off)[k].jod->combined);
  }
  if (out.frames) out.fpsnr_mean = fpsnr / static_cast<double>(out.frames);
  if (jods) out.jod_mean = jod / static_cast<double>(jods);
  return out;
}

Result<GazeVideoScore> score_gaze_video(StereoJodScorer& jod, double fps, const std::vector<GazeFrame>& frames,
                                        const SequenceImage& reference, const SequenceImage& test, const FrameCheck& check) {
  auto video = jod.video(fps);
  if (!video) return video.error();
  GazeVideoScore out;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const GazeFrame& f = frames[k];
    if (f.blink) {
      ++out.blink_frames;
      continue;
    }
    auto ref = reference(k);
    if (!ref) return ref.error();
    auto img = test(k);
    if (!img) return img.error();
    if (Status s = video->push(*ref, *img, std::array<double, 2>{f.truth[0].x, f.truth[0].y},
                               std::array<double, 2>{f.truth[1].x, f.truth[1].y});
        !s)
      return s.error();
    if (check)
      if (Status s = check(k, *ref, *img); !s) return s.error();
    ++out.frames;
  }
  if (!out.frames) return bad_input("--gaze-video: every frame of the sequence falls in a blink or dropout");
  auto s = video->score();
  if (!s) return s.error();
  out.jod = *s;
  return out;
}

}  // namespace foveal::bench
