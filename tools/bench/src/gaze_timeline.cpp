#include "foveal/bench/gaze_timeline.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "foveal/core/pose_track.hpp"
#include "foveal/image/foveation_plan.hpp"
#include "foveal/runtime/gaze_pipeline.hpp"

namespace foveal::bench {

namespace {

// The raw recorded direction of one eye at time t, interpolated between the two samples
// around it (normalised viewport point); false where either of them is invalid.
bool raw_gaze_at(const std::vector<GazeSample>& s, const DisplayModel& model, Eye e, TimeNs t, glm::dvec2& out) {
  const auto after = std::upper_bound(s.begin(), s.end(), t, [](TimeNs v, const GazeSample& g) { return v < g.t_ns; });
  if (after == s.begin()) return false;
  const GazeSample& a = *(after - 1);
  const EyeSample& ea = a.eye(e);
  if (!ea.has(kValidDirection)) return false;
  glm::vec3 dir = ea.direction;
  if (a.t_ns != t && after != s.end()) {
    const EyeSample& eb = after->eye(e);
    if (!eb.has(kValidDirection)) return false;
    const float w = static_cast<float>(static_cast<double>(t - a.t_ns) / static_cast<double>(after->t_ns - a.t_ns));
    dir = glm::normalize(glm::mix(ea.direction, eb.direction, w));
  }
  const glm::vec2 px = model.direction_to_pixel(e, dir);
  if (!std::isfinite(px.x) || !std::isfinite(px.y)) return false;
  // A gaze beyond the rendered field of view counts at the nearest border.
  out = glm::clamp(glm::dvec2(px) / glm::dvec2(model.eye_width, model.eye_height), 0.0, 1.0);
  return true;
}

}  // namespace

Result<GazeTimeline> build_gaze_timeline(const std::vector<GazeSample>& samples, const DisplayModel& model,
                                         const FilterConfig& filter, const GazeTimelineOptions& o) {
  if (!(o.fps > 0) || !std::isfinite(o.fps)) return bad_input("--gaze-fps must be a number > 0");
  if (!std::isfinite(o.latency_ms) || o.latency_ms > 10000) return bad_input("--latency-ms must be a number <= 10000");
  if (!(o.start_s >= 0) || !std::isfinite(o.start_s)) return bad_input("--gaze-start must be a number >= 0");
  if (o.frames < 1) return bad_input("--gaze-frames must be >= 1");
  if (samples.size() < 2) return bad_input("the gaze log has fewer than 2 samples");
  GazeTimeline tl;
  tl.latency_ms = o.latency_ms < 0 ? 1000.0 / o.fps : o.latency_ms;
  const TimeNs latency = static_cast<TimeNs>(std::llround(tl.latency_ms * 1e6));
  const TimeNs first = samples.front().t_ns + static_cast<TimeNs>(std::llround(o.start_s * 1e9));
  const TimeNs last_display = samples.back().t_ns;
  const double period_ns = 1e9 / o.fps;
  if (first + latency > last_display) return bad_input("the gaze log is too short for one frame after --gaze-start");
  tl.stream_frames = static_cast<std::size_t>(std::floor(static_cast<double>(last_display - latency - first) / period_ns)) + 1;
  tl.stride = std::max<std::size_t>(1, tl.stream_frames / static_cast<std::size_t>(o.frames));
  const glm::dvec2 size(model.eye_width, model.eye_height);
  auto t_render = [&](std::size_t k) { return first + static_cast<TimeNs>(std::llround(static_cast<double>(k) * period_ns)); };
  // Where both eyes really were at display time, and their mean angle from the optical
  // centres (the fixed method's fovea); false in a blink.
  auto truth_at = [&](TimeNs t, std::array<glm::dvec2, 2>& truth, double& ecc) {
    bool ok = true;
    ecc = 0;
    for (Eye e : kEyes) {
      const std::size_t i = static_cast<std::size_t>(e);
      ok = raw_gaze_at(samples, model, e, t, truth[i]) && ok;
      ecc += 0.5 * render::eccentricity_deg(model.eye(e), render::optical_centre(model.eye(e)), truth[i]);
    }
    return ok;
  };

  std::vector<std::size_t> picked;
  if (o.pick == GazeTimelineOptions::Pick::even) {
    for (std::size_t j = 0; j < static_cast<std::size_t>(o.frames) && j * tl.stride < tl.stream_frames; ++j) picked.push_back(j * tl.stride);
  } else if (o.pick == GazeTimelineOptions::Pick::consecutive) {
    tl.stride = 1;
    for (std::size_t k = 0; k < static_cast<std::size_t>(o.frames) && k < tl.stream_frames; ++k) picked.push_back(k);
  } else {
    if (!(o.spread_max_deg > 0) || !std::isfinite(o.spread_max_deg)) return bad_input("--gaze-spread-max must be a number > 0");
    const double width = o.spread_max_deg / o.frames;
    std::vector<std::optional<std::pair<double, std::size_t>>> best(static_cast<std::size_t>(o.frames));  // (distance, k)
    for (std::size_t k = 0; k < tl.stream_frames; ++k) {
      std::array<glm::dvec2, 2> truth{};
      double ecc = 0;
      if (!truth_at(t_render(k) + latency, truth, ecc) || ecc > o.spread_max_deg) continue;
      const std::size_t b = std::min(best.size() - 1, static_cast<std::size_t>(ecc / width));
      const double d = std::abs(ecc - (static_cast<double>(b) + 0.5) * width);
      if (!best[b] || d < best[b]->first) best[b] = std::pair{d, k};
    }
    for (const auto& b : best)
      if (b) picked.push_back(b->second);
    if (picked.empty()) return bad_input("--gaze-pick spread: no frame of the log has both eyes tracked within " + std::to_string(o.spread_max_deg) + " degrees");
    std::sort(picked.begin(), picked.end());
  }

  GazePipeline pipe(model, filter);
  PoseTrack heads;
  FoveaFrame latest;
  bool have = false;
  std::size_t next = 0;  // the next sample to feed the pipeline
  for (std::size_t k : picked) {
    GazeFrame f;
    f.index = k;
    f.t_render = t_render(k);
    f.t_display = f.t_render + latency;
    // What the exchange holds when the frame starts: every sample up to then, filtered.
    for (; next < samples.size() && samples[next].t_ns <= f.t_render; ++next) {
      latest = pipe.update(samples[next]);
      have = true;
      if (samples[next].head.valid) (void)heads.push({samples[next].t_ns, samples[next].head.pose});
    }
    f.t_sample = have ? latest.t_ns : samples.front().t_ns;
    f.blink = !truth_at(f.t_display, f.truth, f.truth_ecc_deg);
    for (Eye e : kEyes) {
      const std::size_t i = static_cast<std::size_t>(e);
      f.fovea[i] = have ? glm::clamp(glm::dvec2(latest.eye(e).px) / size, 0.0, 1.0) : glm::dvec2(0.5);
    }
    if (f.blink) f.truth = f.fovea;
    if (o.head_recorded) f.head = heads.pose_at(f.t_sample);
    tl.frames.push_back(f);
  }
  return tl;
}

}  // namespace foveal::bench
