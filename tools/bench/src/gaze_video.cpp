#include "foveal/bench/gaze_video.hpp"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

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

Result<GazeVideoScore> score_gaze_video(StereoJodScorer& jod, double fps, const std::vector<GazeFrame>& frames,
                                        const SequenceImage& reference, const SequenceImage& test) {
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
    ++out.frames;
  }
  if (!out.frames) return bad_input("--gaze-video: every frame of the sequence falls in a blink or dropout");
  auto s = video->score();
  if (!s) return s.error();
  out.jod = *s;
  return out;
}

}  // namespace foveal::bench
