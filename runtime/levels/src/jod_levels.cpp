#include "foveal/runtime/jod_levels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "foveal/core/display_model.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/shown_text.hpp"
#include "jod_table_rows.hpp"

namespace foveal {

using namespace levels_detail;

namespace {

constexpr const char* kFormat = "foveal-jod-levels v1";

}  // namespace

Result<JodLevelTable> JodLevelTable::from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) return bad_input(where + ": expected a JSON object");
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!std::set<std::string>{"format", "display", "sigmas", "f", "jod", "reference"}.count(it.key()))
      return bad_input(where + ": unknown key '" + shown_text(it.key(), 40) + "'");
  if (!j.contains("format") || j.at("format") != kFormat) return bad_input(where + ": format: expected \"" + std::string(kFormat) + "\"");
  JodLevelTable t;
  if (!j.contains("display") || !j.at("display").is_string()) return bad_input(where + ": display: expected a string");
  t.display = j.at("display").get<std::string>();
  auto s = grid(j, where, "sigmas", 1.0, 16.0);
  if (!s) return s.error();
  auto f = grid(j, where, "f", kMinRmfrF, kMaxRmfrF, true);
  if (!f) return f.error();
  t.sigmas = std::move(*s), t.fs = std::move(*f);
  auto rows = jod_rows(j, where, t.fs.size(), "f", t.sigmas.size());
  if (!rows) return rows.error();
  t.jod = std::move(*rows);
  t.reference = j.value("reference", nlohmann::json::object());
  return t;
}

Result<JodLevelTable> JodLevelTable::load(const std::string& path) {
  auto j = read_json_file(path, "JOD levels table");
  if (!j) return j.error();
  return from_json(*j, path);
}

double JodLevelTable::predict(std::size_t i, double sigma) const { return predict_on_row(sigmas, jod.at(i), sigma); }

Result<JodLevels> choose_jod_levels(const JodLevelTable& t, double target, double efr_ratio) {
  if (!(target > 0 && target <= 10)) return bad_input("quality: the JOD target must be in (0, 10], got " + shown_number(target));
  if (!(efr_ratio >= 1) || !std::isfinite(efr_ratio)) return bad_input("quality: the EFR ratio sigma_nd/sigma_d must be >= 1");
  JodLevels best;
  best.target = target, best.f = t.fs.front();
  for (std::size_t i = 0; i < t.fs.size(); ++i) {
    const double reach = reach_on_row(t.sigmas, t.jod[i], target);
    if (reach > best.sigma_d) best.sigma_d = reach, best.f = t.fs[i];
  }
  const std::size_t fi = static_cast<std::size_t>(std::find(t.fs.begin(), t.fs.end(), best.f) - t.fs.begin());
  best.sigma_nd = std::min(16.0, efr_ratio * best.sigma_d);
  best.jod_d = t.predict(fi, best.sigma_d);
  best.jod_nd = t.predict(fi, best.sigma_nd);
  return best;
}

std::string jod_levels_path(const std::string& display_model_path) {
  const std::string& p = display_model_path;
  const bool json = p.size() >= 5 && p.compare(p.size() - 5, 5, ".json") == 0;
  return (json ? p.substr(0, p.size() - 5) : p) + ".levels.json";
}

Result<Profile> apply_quality(const Profile& p, const std::string& display_model_path, JodLevels* chosen) {
  auto target = parse_quality(p.quality, "profile " + p.name);
  if (!target) return target.error();
  if (!*target) return p;
  const std::string path = jod_levels_path(display_model_path);
  auto table = JodLevelTable::load(path);
  if (!table) return Error{table.error().kind, "quality " + p.quality + ": " + table.error().message};
  // A table measured on another display predicts nothing about this one.
  auto model = DisplayModel::load(display_model_path);
  if (!model) return Error{model.error().kind, "quality " + p.quality + ": " + model.error().message};
  if (table->display != model->name)
    return bad_input("quality " + p.quality + ": " + path + " is the levels table of display '" + shown_text(table->display, 60) +
                     "', but the display model in use is '" + shown_text(model->name, 60) + "' (" + display_model_path +
                     "): its JOD predictions do not hold there; measure a table for it (docs/methods.md) or set quality off");
  auto levels = choose_jod_levels(*table, **target, p.sigma_nd / p.sigma_d);
  if (!levels) return levels.error();
  levels->table = path;
  Profile out = p;
  out.sigma_d = levels->sigma_d, out.sigma_nd = levels->sigma_nd;
  out.f_x = out.f_y = levels->f;
  if (chosen) *chosen = *levels;
  return out;
}

}  // namespace foveal
