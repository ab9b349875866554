#include "foveal/evaluation/metrics_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <vector>

#include "foveal/core/data_paths.hpp"
#include "foveal/perception/jod.hpp"
#include "foveal/runtime/args.hpp"

namespace foveal::evaluation {

namespace {

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// The bundled models' names, for the message when a name is not one of them.
std::string bundled_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(data_path("data/display"), ec)) {
    const std::string f = e.path().filename().string();
    // NAME.json; NAME.levels.json and the like are a model's tables, not models.
    if (f.size() > 5 && f.ends_with(".json") && f.find('.') == f.size() - 5) names.push_back(f.substr(0, f.size() - 5));
  }
  std::sort(names.begin(), names.end());
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none found" : s;
}

// A display whose eye is the image itself, symmetric, with `ppd` at its centre: --ppd in
// the geometry JOD scores on (eye_geometry gives back that ppd).
DisplayModel display_of_ppd(double ppd, int eye_w, int eye_h) {
  constexpr double kPi = 3.14159265358979323846;
  const double f = 0.5 / std::tan(0.5 / ppd * kPi / 180.0);
  DisplayModel m;
  char name[48];
  std::snprintf(name, sizeof name, "--ppd %g", ppd);
  m.name = name;
  m.eye_width = eye_w;
  m.eye_height = eye_h;
  const auto tx = static_cast<float>(0.5 * eye_w / f), ty = static_cast<float>(0.5 * eye_h / f);
  m.frustum[0] = m.frustum[1] = EyeFrustum{-tx, tx, -ty, ty};
  return m;
}

}  // namespace

Result<DisplayModel> load_metrics_display(const std::string& spec) {
  if (spec.empty()) return DisplayModel::vive_pro_eye();
  const std::string path = display_model_path(spec);
  auto m = DisplayModel::load(path);
  if (m) return m;
  std::string msg = "--display " + spec + ": " + m.error().message;
  if (path != spec) msg += " (a name means data/display/NAME.json; bundled: " + bundled_names() + ")";
  return Error{m.error().kind, msg};
}

Result<MetricsFrame> metrics_frame(const FrameChoice& c, int width, int height) {
  if (c.ppd && !c.display.empty())
    return bad_input("--ppd: not with --display, whose eye gives the ppd (every metric of a call uses one); drop one");
  auto display = load_metrics_display(c.display);
  if (!display) return display.error();
  MetricsFrame f;
  f.width = width;
  f.height = height;
  f.display_name = display->name;
  bool render_default = false;
  if (!c.render_size.empty()) {
    auto render_size = cli::parse_size(c.render_size, "foveal render --size");
    if (!render_size) return render_size.error();
    render_default = width == render_size->first && height == render_size->second;
  }
  const bool display_size = width == display->output_width() && height == display->output_height();
  if (c.stereo || c.mono) {
    f.stereo = c.stereo;
    f.stereo_from = c.stereo ? "--stereo" : "--mono";
  } else {
    f.stereo = display_size || render_default;
    f.stereo_from = "detected";
    f.detected_as = display_size ? display->name + "'s two eyes side by side" : "foveal render's default --size";
  }
  f.eye_width = f.stereo ? width / 2 : width;
  f.eye_height = height;
  if (c.ppd) {
    f.ppd = *c.ppd;
    f.ppd_from = "--ppd";
    if (f.eye_width > 0 && f.eye_height > 0) f.model = display_of_ppd(*c.ppd, f.eye_width, f.eye_height);
  } else {
    f.model = *display;
    f.ppd = perception::eye_geometry(f.model, Eye::left, std::max(f.eye_width, 1), std::max(f.eye_height, 1)).ppd();
    f.ppd_from = "display";
  }
  return f;
}

std::string MetricsFrame::summary() const {
  std::string s;
  if (stereo_from != "detected") {
    s = (stereo ? "stereo (" : "one image (") + stereo_from + ")";
  } else if (stereo) {
    s = "stereo (detected: " + size_text(width, height) + " is " + detected_as + "; --mono for one image)";
  } else {
    s = "one image (detected: not " + display_name + "'s side-by-side size nor foveal render's default; --stereo for two eyes)";
  }
  char ppd_text[48];
  std::snprintf(ppd_text, sizeof ppd_text, "%.2f ppd", ppd);
  s += std::string(", ") + ppd_text;
  s += ppd_from == "--ppd" ? " (--ppd)" : " (" + display_name + "'s eye at " + size_text(eye_width, eye_height) + ")";
  return s;
}

}  // namespace foveal::evaluation
