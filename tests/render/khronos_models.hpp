#pragma once
// The Khronos sample models of tests/render/data/khronos (SOURCE.md there) and edits of
// their JSON, so that a feature test can render a model with the feature taken out.
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal::test {

inline std::string khronos(const std::string& model) {
  return source_path("tests/render/data/khronos/" + model + "/glTF/" + model + ".gltf");
}

/// A copy of the glTF (and every file and folder beside it) in `dir`, its JSON passed through `edit`.
inline std::string edited(TempDir& dir, const std::string& gltf, const std::function<void(nlohmann::json&)>& edit) {
  const std::filesystem::path src(gltf);
  std::filesystem::copy(src.parent_path(), dir.path(), std::filesystem::copy_options::recursive);
  const std::string out = dir.path(src.filename().string());
  nlohmann::json j = nlohmann::json::parse(std::ifstream(out));
  edit(j);
  write_file(out, j.dump());
  return out;
}

/// Removes extension `ext` everywhere in the JSON: every "extensions" object and the
/// extensionsUsed / extensionsRequired lists.
inline void strip_extension(nlohmann::json& j, const std::string& ext) {
  std::function<void(nlohmann::json&)> walk = [&](nlohmann::json& v) {
    if (v.is_object()) {
      if (v.contains("extensions")) v["extensions"].erase(ext);
      for (auto& [k, x] : v.items()) walk(x);
    } else if (v.is_array()) {
      for (auto& x : v) walk(x);
    }
  };
  walk(j);
  for (const char* list : {"extensionsUsed", "extensionsRequired"})
    if (j.contains(list)) {
      nlohmann::json kept = nlohmann::json::array();
      for (const auto& e : j[list])
        if (e != ext) kept.push_back(e);
      j[list] = kept;
    }
}

}  // namespace foveal::test
