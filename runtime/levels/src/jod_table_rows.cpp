#include "jod_table_rows.hpp"

#include <cmath>
#include <limits>

#include "foveal/core/shown_text.hpp"

namespace foveal::levels_detail {

Result<std::vector<double>> grid(const nlohmann::json& j, const std::string& where, const char* key, double above,
                                 double most, bool closed) {
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
    if (!v.empty() && d <= v.back()) return bad_input(at + ": expected increasing values");
    v.push_back(d);
  }
  return v;
}

Result<std::vector<std::vector<double>>> jod_rows(const nlohmann::json& j, const std::string& where, std::size_t rows,
                                                  const char* row_name, std::size_t sigmas) {
  if (!j.contains("jod") || !j.at("jod").is_array() || j.at("jod").size() != rows)
    return bad_input(where + ": jod: expected one row per " + row_name + " (" + std::to_string(rows) + ")");
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < rows; ++i) {
    const auto& row = j.at("jod")[i];
    const std::string at = where + ": jod[" + std::to_string(i) + "]";
    if (!row.is_array() || row.size() != sigmas)
      return bad_input(at + ": expected one value per sigma (" + std::to_string(sigmas) + ")");
    std::vector<double> r;
    for (const auto& x : row) {
      if (!x.is_number() || !(x.get<double>() >= 0 && x.get<double>() <= 10)) return bad_input(at + ": expected JOD values in [0, 10]");
      r.push_back(x.get<double>());
    }
    out.push_back(std::move(r));
  }
  return out;
}

double predict_on_row(const std::vector<double>& sigmas, const std::vector<double>& row, double sigma) {
  if (!(sigma >= 1) || sigma > sigmas.back()) return std::numeric_limits<double>::quiet_NaN();
  double s0 = 1, j0 = 10;
  for (std::size_t k = 0; k < sigmas.size(); ++k) {
    if (sigma <= sigmas[k]) return j0 + (row[k] - j0) * (sigma - s0) / (sigmas[k] - s0);
    s0 = sigmas[k], j0 = row[k];
  }
  return row.back();
}

double reach_on_row(const std::vector<double>& sigmas, const std::vector<double>& row, double target) {
  double s0 = 1, j0 = 10;
  for (std::size_t k = 0; k < sigmas.size(); ++k) {
    if (row[k] >= target) {
      s0 = sigmas[k], j0 = row[k];
      continue;
    }
    return s0 + (sigmas[k] - s0) * (j0 - target) / (j0 - row[k]);
  }
  return s0;
}

}  // namespace foveal::levels_detail
