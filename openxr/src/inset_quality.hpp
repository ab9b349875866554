#pragma once
// The quad views' sizes chosen by perception (docs/openxr.md, "Sizes"): with
// FOVEAL_OPENXR_QUALITY=jod:T the outer views' densities and the inner views' extent
// come from the display model's inset levels table (foveal::levels, the table
// tools/levels builds), the cheapest inset whose predicted JOD holds T for the dominant
// eye, with foveald's EFR ratio. The layer chooses itself: the fovea block carries
// foveald's RMFR levels, not the inset's.
#include <memory>
#include <string>

#include "inset.hpp"

namespace foveal::openxr {

class InsetQuality {
 public:
  /// Reads FOVEAL_OPENXR_QUALITY (off or jod:T; unset: off) and FOVEAL_OPENXR_DISPLAY (a
  /// display model's name under data/display or its file; default htc_vive_pro_eye), and
  /// loads the model and its table. Reads files: call it outside any frame loop. A
  /// problem (bad key, missing or mismatched table) leaves the quality off and says why
  /// in problem().
  static InsetQuality from_environment();
  static InsetQuality from(const std::string& quality, const std::string& display);

  bool on() const { return impl_ != nullptr; }
  const std::string& problem() const { return problem_; }

  /// With the quality on, replaces the gaze-following inset's shares in `s` and sets
  /// density[e] (0 left, 1 right) to 1/σ of each eye's chosen level, from foveald's
  /// per-eye levels `sigma` (the smaller is the dominant eye's; their ratio is EFR's).
  /// Returns false (nothing changed) while off. Arithmetic only, no allocation.
  bool apply(const float sigma[2], InsetSettings& s, float density[2]) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
  std::string problem_;
};

}  // namespace foveal::openxr
