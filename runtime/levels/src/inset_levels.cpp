#include "foveal/runtime/inset_levels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "foveal/core/json_file.hpp"
#include "foveal/core/shown_text.hpp"
#include "jod_table_rows.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal {

using namespace levels_detail;

namespace {

constexpr const char* kFormat = "foveal-jod-inset-levels v1";
constexpr double kPi = 3.14159265358979323846;

}  // namespace

Result<InsetLevelTable> InsetLevelTable::from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) return bad_input(where + ": expected a JSON object");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!std::set<std::string>{"format", "display", "sigmas", "extents_deg", "jod", "reference"}.count(it.key()))
      return bad_input(where + ": unknown key '" + shown_text(it.key(), 40) + "'");
  if (!j.contains("format") || j.at("format") != kFormat) return bad_input(where + ": format: expected \"" + std::string(kFormat) + "\"");
  InsetLevelTable t;
  if (!j.contains("display") || !j.at("display").is_string()) return bad_input(where + ": display: expected a string");
  t.display = j.at("display").get<std::string>();
  auto s = grid(j, where, "sigmas", 1.0, 16.0);
  if (!s) return s.error();
  auto e = grid(j, where, "extents_deg", 0.0, 60.0);
  if (!e) return e.error();
  t.sigmas = std::move(*s), t.extents_deg = std::move(*e);
  auto rows = jod_rows(j, where, t.extents_deg.size(), "extent", t.sigmas.size());
  if (!rows) return rows.error();
  t.jod = std::move(*rows);
  t.reference = j.value("reference", nlohmann::json::object());
  return t;
}

Result<InsetLevelTable> InsetLevelTable::load(const std::string& path) {
  auto j = read_json_file(path, "JOD inset levels table");
  if (!j) return j.error();
  return from_json(*j, path);
}

double InsetLevelTable::predict(std::size_t i, double sigma) const { return predict_on_row(sigmas, jod.at(i), sigma); }

Result<InsetLevels> choose_inset_levels(const InsetLevelTable& t, double target, double efr_ratio, const EyeFrustum& eye) {
  if (!(target > 0 && target <= 10)) return bad_input("quality: the JOD target must be in (0, 10], got " + shown_number(target));
  if (!(efr_ratio >= 1) || !std::isfinite(efr_ratio)) return bad_input("quality: the EFR ratio sigma_nd/sigma_d must be >= 1");
  const double span_x = static_cast<double>(eye.tan_right) - eye.tan_left, span_y = static_cast<double>(eye.tan_top) - eye.tan_bottom;
  if (!(span_x > 0 && span_y > 0)) return bad_input("quality: the display model's field of view is empty");
  InsetLevels best;
  best.target = target;
  best.cost = std::numeric_limits<double>::infinity();
  std::size_t best_i = 0;
  for (std::size_t i = 0; i < t.extents_deg.size(); ++i) {
    const double half = std::tan(t.extents_deg[i] * kPi / 180.0);
    const double sx = std::min(1.0, 2 * half / span_x), sy = std::min(1.0, 2 * half / span_y);
    const double sd = reach_on_row(t.sigmas, t.jod[i], target), snd = std::min(16.0, efr_ratio * sd);
    // Both eyes' outer views and inner views; a tie keeps the smaller extent.
    const double cost = 1 / (sd * sd) + 1 / (snd * snd) + 2 * sx * sy;
    if (cost < best.cost - 1e-12) {
      best.cost = cost, best_i = i;
      best.sigma_d = sd, best.sigma_nd = snd, best.extent_deg = t.extents_deg[i], best.share_x = sx, best.share_y = sy;
    }
  }
  best.jod_d = t.predict(best_i, best.sigma_d);
  best.jod_nd = t.predict(best_i, best.sigma_nd);
  return best;
}

std::string inset_levels_path(const std::string& display_model_path) {
  const std::string& p = display_model_path;
  const bool json = p.size() >= 5 && p.compare(p.size() - 5, 5, ".json") == 0;
  return (json ? p.substr(0, p.size() - 5) : p) + ".inset-levels.json";
}

Result<std::optional<InsetLevels>> inset_quality(const std::string& quality, const std::string& display_model_path, double efr_ratio) {
  auto target = parse_quality(quality, "inset levels");
  if (!target) return target.error();
  if (!*target) return std::optional<InsetLevels>{};
  const std::string path = inset_levels_path(display_model_path);
  auto table = InsetLevelTable::load(path);
  if (!table) return Error{table.error().kind, "quality " + quality + ": " + table.error().message};
  auto model = DisplayModel::load(display_model_path);
  if (!model) return Error{model.error().kind, "quality " + quality + ": " + model.error().message};
  if (table->display != model->name)
    return bad_input("quality " + quality + ": " + path + " is the inset levels table of display '" + shown_text(table->display, 60) +
                     "', but the display model in use is '" + shown_text(model->name, 60) + "' (" + display_model_path +
                     "): its JOD predictions do not hold there; measure a table for it (docs/openxr.md) or set quality off");
  auto levels = choose_inset_levels(*table, **target, efr_ratio, model->eye(Eye::left));
  if (!levels) return levels.error();
  levels->table = path;
  return std::optional<InsetLevels>{*levels};
}

}  // namespace foveal
