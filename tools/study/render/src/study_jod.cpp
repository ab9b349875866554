#include "foveal/study/study_jod.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

namespace foveal {

namespace {

// How study_trials_csv writes a 2AFC side, and so how `study stats` labels it.
std::string two_afc_label(const StudyCondition& c) {
  const bool full = c.method == "full";
  return c.method + " sigma=" + (full ? "1" : level_text(c.sigma_d)) + " f=" + (full ? "" : level_text(c.f));
}

std::string jod_text(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}

}  // namespace

Result<StudyJod> predict_study_jod(StudyFrames& frames, const StudyOptions& o, const DisplayModel& model) {
  render::Compositor& comp = frames.compositor();
  auto scorer = bench::StereoJodScorer::create(model, comp.width(), comp.height());
  if (!scorer) return scorer.error();
  // The study shows every frame with the fovea at the centre of each eye.
  const bench::EyeFovea centre = std::array<double, 2>{0.5, 0.5};
  StudyJod out;
  std::vector<std::string> done;
  for (const std::string& scene : o.scenes) {
    if (std::find(done.begin(), done.end(), scene) != done.end()) continue;
    done.push_back(scene);
    if (Status s = frames.draw(scene, StudyCondition{}); !s) return s.error();
    const image::Image full = comp.read_image();
    for (const StudyCondition& c : o.conditions) {
      if (Status s = frames.draw(scene, c); !s) return s.error();
      auto j = scorer->still(full, comp.read_image(), centre, centre);
      if (!j) return Error{j.error().kind, "study: predicted JOD of '" + c.label() + "' on " + scene + ": " + j.error().message};
      out.rows.push_back({scene, c, *j});
    }
  }
  out.settings = bench::jod_settings(*scorer);
  out.settings["fixation"] = "the centre of each eye";
  return out;
}

std::string study_conditions_csv(const StudyJod& j) {
  std::string out = "scene,condition,method,sigma_d,sigma_nd,f,predicted_jod,predicted_jod_left,predicted_jod_right\n";
  for (const ConditionJod& r : j.rows) {
    const StudyCondition& c = r.condition;
    const bool full = c.method == "full";
    out += r.scene + "," + c.label() + "," + c.method + "," + (full ? "1" : level_text(c.sigma_d)) + "," +
           (full ? "1" : level_text(c.sigma_nd)) + "," + (full ? "" : level_text(c.f)) + "," + jod_text(r.jod.combined) + "," +
           jod_text(r.jod.left) + "," + jod_text(r.jod.right) + "\n";
  }
  return out;
}

nlohmann::json predicted_jod_of(const StudyJod& j, const std::string& label) {
  double sum = 0;
  int n = 0;
  for (const ConditionJod& r : j.rows)
    if (r.condition.label() == label || (r.condition.uniform() && two_afc_label(r.condition) == label))
      sum += r.jod.combined, ++n;
  return n ? nlohmann::json(sum / n) : nlohmann::json(nullptr);
}

}  // namespace foveal
