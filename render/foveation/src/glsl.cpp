// GLSL for applications: the embedded files and the installed folder.
#include <dlfcn.h>

#include <filesystem>

#include "foveal/rmfr.hpp"
#include "glsl_files.hpp"

namespace foveal::rmfr {

std::string_view glsl_source() { return detail::kRmfrGlslExpanded; }

std::string_view glsl_file(std::string_view name) {
  if (name == "foveal/rmfr.glsl") return detail::kRmfrGlsl;
  if (name == "foveal/rmfr_mapping.glsl") return detail::kMappingGlsl;
  return {};
}

std::string glsl_directory() {
  // Relative to this library's file, so an installed tree may move as a whole; the
  // source tree's folder for a library that runs from its build tree.
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&glsl_directory), &info) && info.dli_fname) {
    const auto dir = std::filesystem::path(info.dli_fname).parent_path() / FOVEAL_RMFR_GLSL_FROM_LIBDIR;
    std::error_code ec;
    if (std::filesystem::exists(dir / "foveal" / "rmfr.glsl", ec)) return dir.lexically_normal().string();
  }
  return FOVEAL_RMFR_GLSL_SOURCE_DIR;
}

}  // namespace foveal::rmfr
