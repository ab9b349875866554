#include "foveal/core/data_paths.hpp"

#include <cstdlib>
#include <filesystem>

namespace foveal {

namespace {

bool has_data(const std::filesystem::path& root) {
  std::error_code ec;
  return std::filesystem::is_directory(root / "data", ec);
}

}  // namespace

std::string data_root() {
  if (const char* env = std::getenv("FOVEAL_DATA_DIR"); env && *env) return env;
  // An installed binary finds <prefix>/share/foveal next to its own bin/, wherever the
  // prefix was moved to; a build-tree binary falls through to the source tree.
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto beside = exe.parent_path().parent_path() / "share" / "foveal";
    if (has_data(beside)) return beside.string();
  }
  if (has_data(FOVEAL_INSTALL_DATADIR)) return FOVEAL_INSTALL_DATADIR;
  return FOVEAL_SOURCE_DATADIR;
}

std::string data_path(const std::string& relative) { return data_root() + "/" + relative; }

}  // namespace foveal
