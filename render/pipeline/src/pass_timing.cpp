// Pass timing's public side: the timed passes' names per pipeline and the per-field
// median of several frames' PassTimes (the timer itself: pass_timer.hpp).
#include <algorithm>
#include <vector>

#include "foveal/render/compositor.hpp"

namespace foveal::render {

std::array<const char*, 2> pass_names(Pipeline p) {
  if (p == Pipeline::visibility) return {"visibility", "material"};
  return {"gbuffer", "mapping"};
}

PassTimes median_pass_times(const std::vector<PassTimes>& frames) {
  PassTimes m;
  if (frames.empty()) return m;
  auto median = [&](double PassTimes::*field) {
    std::vector<double> v;
    for (const PassTimes& t : frames) v.push_back(t.*field);
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  };
  for (double PassTimes::*f : {&PassTimes::shadow, &PassTimes::gbuffer, &PassTimes::mapping, &PassTimes::lighting,
                               &PassTimes::inverse, &PassTimes::blend, &PassTimes::gpu_total, &PassTimes::cpu})
    m.*f = median(f);
  m.shaded_samples = frames.back().shaded_samples;
  m.blend_samples = frames.back().blend_samples;
  m.blend_layers = frames.back().blend_layers;
  m.blend_dropped = frames.back().blend_dropped;
  m.pipeline = frames.back().pipeline;
  return m;
}

}  // namespace foveal::render
