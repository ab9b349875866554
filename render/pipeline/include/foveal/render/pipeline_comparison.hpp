#pragma once
// Both pipelines measured in one run (docs/rmfr.md, "Pipelines"): each one's full frame
// and foveated frame, and the figures issue 17 reports: the speedup against the faster of
// the two full pipelines, the share of the full-resolution pass, and the Amdahl limit
// that pass leaves.
#include <array>

#include "foveal/render/compositor.hpp"

namespace foveal::render {

struct PipelineComparison {
  std::array<PassTimes, 2> full{}, foveated{};  ///< indexed by Pipeline

  /// GPU milliseconds of the faster full frame.
  double best_full_gpu() const;
  /// Whole-frame GPU speedup of `p`'s foveated frame against the faster full frame.
  double speedup(Pipeline p) const;
  /// Share of `p`'s foveated frame spent in its full-resolution pass.
  double fullres_share(Pipeline p) const;
  /// The speedup if every pass but the full-resolution one scaled with the shaded
  /// samples (full / foveated), that one staying as measured:
  /// best_full / (fullres + (full_gpu − full_fullres) · foveated_samples / full_samples).
  double amdahl_limit(Pipeline p) const;
};

/// Renders `foveated`, and its full frame (method full, same eyes), through both
/// pipelines, `frames` times each after one warm-up, interleaved; medians.
Result<PipelineComparison> compare_pipelines(Compositor& c, const Scene& scene, const FrameParams& foveated, int frames);

}  // namespace foveal::render
