#include "foveal/core/json_file.hpp"

#include <fstream>

namespace foveal {

Result<nlohmann::json> read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) return io_error(path + ": cannot open " + what);
  nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return bad_input(path + ": not valid JSON");
  return j;
}

}  // namespace foveal
