#pragma once
// The embedded GLSL files (glsl_files.cpp, generated from glsl/foveal/*.glsl).
#include <string_view>

namespace foveal::rmfr::detail {
extern const std::string_view kMappingGlsl;       ///< foveal/rmfr_mapping.glsl
extern const std::string_view kRmfrGlsl;          ///< foveal/rmfr.glsl
extern const std::string_view kRmfrGlslExpanded;  ///< foveal/rmfr.glsl, its #include expanded
}  // namespace foveal::rmfr::detail
