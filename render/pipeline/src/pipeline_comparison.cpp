#include "foveal/render/pipeline_comparison.hpp"

#include <algorithm>
#include <vector>

namespace foveal::render {

namespace {
std::size_t at(Pipeline p) { return static_cast<std::size_t>(p); }
}  // namespace

double PipelineComparison::best_full_gpu() const { return std::min(full[0].gpu_total, full[1].gpu_total); }

double PipelineComparison::speedup(Pipeline p) const { return best_full_gpu() / foveated[at(p)].gpu_total; }

double PipelineComparison::fullres_share(Pipeline p) const { return foveated[at(p)].gbuffer / foveated[at(p)].gpu_total; }

double PipelineComparison::amdahl_limit(Pipeline p) const {
  const PassTimes &f = full[at(p)], &r = foveated[at(p)];
  const double scale = f.shaded_samples ? static_cast<double>(r.shaded_samples) / static_cast<double>(f.shaded_samples) : 1.0;
  return best_full_gpu() / (r.gbuffer + (f.gpu_total - f.gbuffer) * scale);
}

Result<PipelineComparison> compare_pipelines(Compositor& c, const Scene& scene, const FrameParams& foveated, int frames) {
  std::vector<FrameParams> params;
  for (Pipeline p : all_pipelines()) {
    FrameParams full = foveated, fov = foveated;
    full.method = Method::full;
    full.pipeline = fov.pipeline = p;
    params.push_back(full);
    params.push_back(fov);
  }
  std::vector<std::vector<PassTimes>> times(params.size());
  for (int i = 0; i <= frames; ++i)
    for (std::size_t k = 0; k < params.size(); ++k) {
      auto t = c.render(scene, params[k]);
      if (!t) return t.error();
      if (i > 0) times[k].push_back(*t);  // the first round warms up
    }
  PipelineComparison out;
  for (Pipeline p : all_pipelines()) {
    out.full[at(p)] = median_pass_times(times[2 * at(p)]);
    out.foveated[at(p)] = median_pass_times(times[2 * at(p) + 1]);
  }
  return out;
}

}  // namespace foveal::render
