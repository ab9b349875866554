#pragma once
// The targets file of `foveal log quality --targets` (docs/quality.md): CSV with the
// header `start_s,end_s,azimuth_deg,elevation_deg`, one target per row.
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/quality/gaze_quality.hpp"

namespace foveal {

Result<std::vector<QualityTarget>> read_quality_targets(const std::string& path);

}  // namespace foveal
