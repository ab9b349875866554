#include "foveal/runtime/jod_levels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "foveal/core/display_model.hpp"
#include "foveal/core/json_file.hpp"
#include "foveal/core/shown_text.hpp"

namespace foveal {

namespace {

constexpr const char* kFormat = "foveal-jod-levels v1";

// An increasing grid of numbers in (above, most], or [above, most] when `closed`.
Result<std::vector<double>> grid(const nlohmann::json& j, const std::string& where, const char* key, double above, double most,
                                 bool closed = false) {
  const std::string at = where + ": " + key;
  if (!j.contains(key) || !j.at(key).is_array() || j.at(key).empty() || j.at(key).size() > 64)
    return bad_input(at + ": expected an array of 1 to 64 numbers");
  std::vector<double> v;
  for (const auto& x : j.at(key)) {
    const double d = x.is_number() ? x.get<double>() : std::numeric_limits<double>::quiet_NaN();
    if (!std::isfinite(d) || (closed ? d < above : d <= above) || d > most)
      return bad_input(at + ": expected numbers in " + (closed ? "[" : "(") + shown_number(above) + ", " + shown_number(most) + "]" +
                       (closed ? " (RMFR's f where the compositor is tested)" : "") +
                       (x.is_number() ? ", got " + shown_number(d) : std::string()));
    if (!v.empty() && x.get<double>() <= v.back()) return bad_input(at + ": expected increasing values");
    v.push_back(x.get<double>());
  }
  return v;
}

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
  if (!j.contains("jod") || !j.at("jod").is_array() || j.at("jod").size() != t.fs.size())
    return bad_input(where + ": jod: expected one row per f (" + std::to_string(t.fs.size()) + ")");
  for (std::size_t i = 0; i < t.fs.size(); ++i) {
    const auto& row = j.at("jod")[i];
    const std::string at = where + ": jod[" + std::to_string(i) + "]";
    if (!row.is_array() || row.size() != t.sigmas.size())
      return bad_input(at + ": expected one value per sigma (" + std::to_string(t.sigmas.size()) + ")");
    std::vector<double> r;
    for (const auto& x : row) {
      if (!x.is_number() || !(x.get<double>() >= 0 && x.get<double>() <= 10)) return bad_input(at + ": expected JOD values in [0, 10]");
      r.push_back(x.get<double>());
    }
    t.jod.push_back(std::move(r));
  }
  t.reference = j.value("reference", nlohmann::json::object());
  return t;
}

Result<JodLevelTable> JodLevelTable::load(const std::string& path) {
  auto j = read_json_file(path, "JOD levels table");
  if (!j) return j.error();
  return from_json(*j, path);
}

double JodLevelTable::predict(std::size_t i, double sigma) const {
  const std::vector<double>& row = jod.at(i);
  if (!(sigma >= 1) || sigma > sigmas.back()) return std::numeric_limits<double>::quiet_NaN();
  double s0 = 1, j0 = 10;  // σ = 1 renders every pixel: the reference itself
  for (std::size_t k = 0; k < sigmas.size(); ++k) {
    if (sigma <= sigmas[k]) return j0 + (row[k] - j0) * (sigma - s0) / (sigmas[k] - s0);
    s0 = sigmas[k], j0 = row[k];
  }
  return row.back();
}

Result<JodLevels> choose_jod_levels(const JodLevelTable& t, double target, double efr_ratio) {
  if (!(target > 0 && target <= 10)) return bad_input("quality: the JOD target must be in (0, 10], got " + shown_number(target));
  if (!(efr_ratio >= 1) || !std::isfinite(efr_ratio)) return bad_input("quality: the EFR ratio sigma_nd/sigma_d must be >= 1");
  JodLevels best;
  best.target = target, best.f = t.fs.front();
  for (std::size_t i = 0; i < t.fs.size(); ++i) {
    // Walk up the grid while the prediction holds; the crossing is where it stops.
    double s0 = 1, j0 = 10, reach = 1;
    for (std::size_t k = 0; k < t.sigmas.size(); ++k) {
      const double s1 = t.sigmas[k], j1 = t.jod[i][k];
      if (j1 >= target) {
        s0 = reach = s1, j0 = j1;
        continue;
      }
      reach = s0 + (s1 - s0) * (j0 - target) / (j0 - j1);
      break;
    }
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
