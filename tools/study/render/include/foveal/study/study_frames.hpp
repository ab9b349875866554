#pragma once
// What `foveal study run` shows: a trial's two presentations through the compositor,
// and the black between them (docs/study.md). Shared by the headset window and the
// scripted mode, so both show the same frames.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "foveal/core/gaze_sample.hpp"
#include "foveal/render/compositor.hpp"
#include "foveal/render/scene.hpp"
#include "foveal/study/study_design.hpp"

namespace foveal {

class StudyFrames {
 public:
  /// Loads every scene of `o` and a compositor of width x height; needs a current GL context.
  static Result<StudyFrames> create(const StudyOptions& o, Eye dominant, int width, int height);
  /// Renders the trial's presentation (0: first, 1: second) into output_framebuffer().
  Status draw(const PlannedTrial& t, int presentation);
  /// Renders `c` on `scene` (one of the options' scenes) into output_framebuffer().
  Status draw(const std::string& scene, const StudyCondition& c);
  void draw_black();
  render::Compositor& compositor() { return *comp_; }
  GLuint output_framebuffer() { return comp_->output_framebuffer(); }

 private:
  StudyFrames() = default;
  Eye dominant_ = Eye::right;
  std::map<std::string, render::Scene> scenes_;
  std::optional<render::Compositor> comp_;
};

/// Every method named by the options' conditions is one the renderer has.
Status check_study_methods(const StudyOptions& o);

}  // namespace foveal
