#pragma once
// Levels chosen by perception (profile key `quality`, foveald --quality, docs/methods.md):
// a display model's table of predicted JOD (FovVideoVDP, docs/metrics.md) for one eye
// rendered with tracked RMFR at each (σ, f) of a grid, measured once over a stated
// reference set of scenes and recorded gazes and stored beside the model as
// NAME.levels.json, so that choosing levels is a lookup and nothing runs per frame.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal {

/// One display model's table. jod[i][j] is the mean JOD over the reference frames and
/// both eyes at f = fs[i] and σ = sigmas[j] (each eye scored alone at its true gaze).
struct JodLevelTable {
  std::string display;              ///< the display model's name
  std::vector<double> sigmas;       ///< increasing, each > 1 (σ = 1 is full rendering: JOD 10)
  std::vector<double> fs;           ///< RMFR f (f_x = f_y), each in [kMinRmfrF, kMaxRmfrF]
  std::vector<std::vector<double>> jod;
  nlohmann::json reference;         ///< what the table was measured on (scenes, logs, frames, commands)

  /// Reads a table through the project's JSON entry point. Errors name the file and the
  /// key: a wrong format line, grids that are empty, unsorted or out of range, a JOD row
  /// of the wrong length or a value outside [0, 10].
  static Result<JodLevelTable> load(const std::string& path);
  static Result<JodLevelTable> from_json(const nlohmann::json& j, const std::string& where);

  /// Predicted JOD at (σ, f = fs[i]): linear in σ between grid points, 10 at σ = 1;
  /// NaN beyond the grid's largest σ (the table does not say).
  double predict(std::size_t i, double sigma) const;
};

/// The levels a target chooses, with what the table predicts for each eye.
struct JodLevels {
  double target = 10;
  double sigma_d = 1, sigma_nd = 1, f = 0.3;
  double jod_d = 10, jod_nd = 10;   ///< predicted; jod_nd is NaN when σ_nd is past the grid
  std::string table;                ///< the table's path
};

/// The cheapest levels that hold predicted JOD >= target for the dominant eye: over the
/// grid's f, the largest σ_d (RMFR's cost is 1/σ², whatever f) such that the predicted
/// JOD stays >= target at every σ up to it; σ_nd = min(16, efr_ratio · σ_d). The metric
/// scores each eye alone and knows nothing of eye dominance; how much more the
/// non-dominant eye may be foveated is EFR's calibrated ratio, not the metric's.
/// Errors: target outside (0, 10], efr_ratio < 1.
Result<JodLevels> choose_jod_levels(const JodLevelTable& t, double target, double efr_ratio);

/// Where the table of a display model lives: beside it, NAME.json -> NAME.levels.json.
std::string jod_levels_path(const std::string& display_model_path);

/// The profile's levels with its `quality` applied: unchanged when quality is off;
/// otherwise σ_d, σ_nd and f_x = f_y from the display model's table, the EFR ratio taken
/// from the profile's own pair (σ_nd / σ_d). Errors: the table is missing or bad, or it
/// names another display than the model at `display_model_path` (both named).
Result<Profile> apply_quality(const Profile& p, const std::string& display_model_path, JodLevels* chosen = nullptr);

}  // namespace foveal
