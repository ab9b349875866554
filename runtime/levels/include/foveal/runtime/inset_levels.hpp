#pragma once
// Levels chosen by perception for the inset (quad views: the OpenXR layer's foveation,
// docs/openxr.md "Sizes"; foveal's `inset` method, docs/methods.md): a display model's
// table of predicted JOD for one eye rendered as a tracked inset at each (inner extent,
// outer σ) of a grid, measured once over a stated reference set like the RMFR table
// (jod_levels.hpp) and stored beside the model as NAME.inset-levels.json.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"

namespace foveal {

/// One display model's inset table. jod[i][j] is the mean JOD over the reference frames
/// and both eyes with the inner view's half-extent extents_deg[i] (tan of it each side of
/// the gaze, per axis) and the outer view at σ = sigmas[j].
struct InsetLevelTable {
  std::string display;
  std::vector<double> sigmas;       ///< increasing, each in (1, 16]
  std::vector<double> extents_deg;  ///< increasing, each in (0, 60]
  std::vector<std::vector<double>> jod;
  nlohmann::json reference;

  /// Errors name the file and the key, as JodLevelTable's do.
  static Result<InsetLevelTable> load(const std::string& path);
  static Result<InsetLevelTable> from_json(const nlohmann::json& j, const std::string& where);

  /// Predicted JOD at (extents_deg[i], σ): linear in σ between grid points, 10 at σ = 1;
  /// NaN beyond the grid's largest σ.
  double predict(std::size_t i, double sigma) const;
};

/// The inset's levels a target chooses, with what the table predicts.
struct InsetLevels {
  double target = 10;
  double sigma_d = 1, sigma_nd = 1;  ///< the outer views' levels: density 1/σ per axis
  double extent_deg = 0;             ///< the inner views' half-extent (degrees)
  double share_x = 1, share_y = 1;   ///< that extent as a share of the eye's tangent extent per axis (the model's field of view)
  double cost = 2;                   ///< shaded samples of both eyes over one eye's full frame
  double jod_d = 10, jod_nd = 10;    ///< predicted; jod_nd is NaN when σ_nd is past the grid
  std::string table;                 ///< the table's path
};

/// The cheapest inset that holds predicted JOD >= target for the dominant eye: for each
/// extent of the grid, the largest σ_d whose prediction holds at every σ up to it (as
/// choose_jod_levels walks RMFR's rows), σ_nd = min(16, efr_ratio · σ_d); then, over the
/// extents, the least cost 1/σ_d² + 1/σ_nd² + 2·share_x·share_y, the shares from `eye`'s
/// frustum (an extent wider than the view is the whole view). Errors: target outside
/// (0, 10], efr_ratio < 1.
Result<InsetLevels> choose_inset_levels(const InsetLevelTable& t, double target, double efr_ratio, const EyeFrustum& eye);

/// Where the inset table of a display model lives: NAME.json -> NAME.inset-levels.json.
std::string inset_levels_path(const std::string& display_model_path);

/// `quality` ("jod:T"; "" or "off": nothing to choose, Result holds no levels) applied to
/// the display model at `display_model_path` and its inset table: loads both, refuses a
/// table of another display (naming both), and chooses with efr_ratio. Reads files: call
/// it outside any frame loop.
Result<std::optional<InsetLevels>> inset_quality(const std::string& quality, const std::string& display_model_path, double efr_ratio);

}  // namespace foveal
