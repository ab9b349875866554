#include "foveal/core/data_paths.hpp"

#include <cstdlib>
#include <filesystem>

namespace foveal {

std::string data_root() {
  if (const char* env = std::getenv("FOVEAL_DATA_DIR"); env && *env) return env;
  std::error_code ec;
  if (std::filesystem::is_directory(FOVEAL_INSTALL_DATADIR "/data", ec)) return FOVEAL_INSTALL_DATADIR;
  return FOVEAL_SOURCE_DATADIR;
}

std::string data_path(const std::string& relative) { return data_root() + "/" + relative; }

}  // namespace foveal
