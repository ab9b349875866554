#include "foveal/study/study_frames.hpp"

namespace foveal {

Status check_study_methods(const StudyOptions& o) {
  std::vector<const StudyCondition*> all = {&o.validation_condition};
  for (const StudyCondition& c : o.conditions) all.push_back(&c);
  for (const StudyCondition* c : all)
    if (auto m = render::parse_method(c->method); !m) return bad_input("study: condition '" + c->label() + "': " + m.error().message);
  return {};
}

Result<StudyFrames> StudyFrames::create(const StudyOptions& o, Eye dominant, int width, int height) {
  StudyFrames f;
  f.dominant_ = dominant;
  for (const std::string& path : o.scenes) {
    if (f.scenes_.count(path)) continue;
    auto scene = render::load_scene(path);
    if (!scene) return scene.error();
    f.scenes_.emplace(path, std::move(*scene));
  }
  render::CompositorOptions co;
  co.width = width;
  co.height = height;
  auto comp = render::Compositor::create(co);
  if (!comp) return comp.error();
  f.comp_.emplace(std::move(*comp));
  return f;
}

Status StudyFrames::draw(const PlannedTrial& t, int presentation) {
  const bool shows_b = (presentation == 0) == t.b_first;
  return draw(t.scene, shows_b ? t.b : t.a);
}

Status StudyFrames::draw(const std::string& scene, const StudyCondition& c) {
  auto method = render::parse_method(c.method);
  if (!method) return method.error();
  const render::FrameParams frame = render::efr_frame(*method, dominant_, c.sigma_d, c.sigma_nd, c.f, c.f);
  if (auto r = comp_->render(scenes_.at(scene), frame); !r) return r.error();
  return {};
}

void StudyFrames::draw_black() {
  const float black[4] = {0, 0, 0, 1};
  glClearNamedFramebufferfv(comp_->output_framebuffer(), GL_COLOR, 0, black);
}

}  // namespace foveal
