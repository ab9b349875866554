#pragma once
// What the RMFR and the inset JOD levels tables share (jod_levels.cpp, inset_levels.cpp):
// their grids, their rows of predicted JOD over σ, and the two readings of a row.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::levels_detail {

/// An increasing grid of 1 to 64 numbers in (above, most], or [above, most] when `closed`.
Result<std::vector<double>> grid(const nlohmann::json& j, const std::string& where, const char* key, double above,
                                 double most, bool closed = false);

/// `jod`: one row per entry of the other grid (`rows`, named `row_name` in messages), each
/// with one JOD in [0, 10] per σ.
Result<std::vector<std::vector<double>>> jod_rows(const nlohmann::json& j, const std::string& where, std::size_t rows,
                                                  const char* row_name, std::size_t sigmas);

/// The row's JOD at `sigma`: linear between grid levels, 10 at σ 1 (every pixel
/// rendered: the reference itself); NaN outside [1, the grid's largest].
double predict_on_row(const std::vector<double>& sigmas, const std::vector<double>& row, double sigma);

/// The largest σ whose predicted JOD holds `target` at every grid level up to it: the
/// crossing, linear between levels, or the grid's largest if never crossed.
double reach_on_row(const std::vector<double>& sigmas, const std::vector<double>& row, double target);

}  // namespace foveal::levels_detail
