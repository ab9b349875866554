#include "commands/filter_args.hpp"

#include "foveal/core/json_file.hpp"
#include "foveal/runtime/profile.hpp"

namespace foveal::cmd {

Result<FilterConfig> filter_config_from(const std::string& config, const std::string& profile, const char* command) {
  if (!config.empty() && !profile.empty())
    return bad_input(std::string(command) + ": give --config or --profile, not both");
  if (!config.empty()) {
    auto j = read_json_file(config, "filter settings");
    if (!j) return j.error();
    return FilterConfig::from_json(*j, config);
  }
  if (!profile.empty()) {
    auto p = ProfileStore::user().load(profile);
    if (!p) return p.error();
    return FilterConfig::from_json(p->filter, "profile " + profile);  // validated at load
  }
  return FilterConfig{};
}

Result<DisplayModel> display_model_from(const std::string& path) {
  if (path.empty()) return DisplayModel::vive_pro_eye();
  return DisplayModel::load(display_model_path(path));
}

}  // namespace foveal::cmd
