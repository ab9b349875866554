#include "gltf_json_fixups.hpp"

#include <cstdint>
#include <cstring>

namespace foveal::render::detail {

using nlohmann::json;

bool mend_for_tinygltf(json& j, bool binary) {
  bool changed = false;
  if (j.contains("meshes") && j["meshes"].is_array())
    for (json& mesh : j["meshes"])
      if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
        for (json& p : mesh["primitives"]) {
          if (!p.is_object() || !p.contains("extensions") || !p["extensions"].is_object()) continue;
          const json draco = p["extensions"].value("KHR_draco_mesh_compression", json());
          if (!draco.is_object() || !draco.contains("bufferView") || !p.contains("indices") || !p["indices"].is_number_unsigned()) continue;
          const auto i = p["indices"].get<std::size_t>();
          if (!j.contains("accessors") || !j["accessors"].is_array() || i >= j["accessors"].size()) continue;
          json& a = j["accessors"][i];
          if (a.is_object() && !a.contains("bufferView")) a["bufferView"] = draco["bufferView"], changed = true;
        }
  if (j.contains("buffers") && j["buffers"].is_array())
    for (std::size_t i = binary ? 1 : 0; i < j["buffers"].size(); ++i) {
      json& b = j["buffers"][i];
      if (!b.is_object() || b.contains("uri") || !b.contains("extensions") || !b["extensions"].is_object()) continue;
      const json m = b["extensions"].value("EXT_meshopt_compression", json());
      if (m.is_object() && m.value("fallback", false) == true) {
        b["uri"] = "data:application/octet-stream;base64,AAAA";  // 3 placeholder bytes
        b["byteLength"] = 3;
        changed = true;
      }
    }
  return changed;
}

std::string glb_with_json(std::string_view glb, std::string_view json_chunk, const std::string& new_json) {
  std::string chunk = new_json;
  while (chunk.size() % 4) chunk += ' ';
  const std::size_t rest_at = static_cast<std::size_t>(json_chunk.data() - glb.data()) + json_chunk.size();
  const std::string_view rest = glb.substr(rest_at);  // the BIN chunk, if any
  std::string out(glb.substr(0, 12));
  const auto total = static_cast<std::uint32_t>(12 + 8 + chunk.size() + rest.size());
  const auto len = static_cast<std::uint32_t>(chunk.size());
  const std::uint32_t kind = 0x4E4F534Au;  // "JSON"
  std::memcpy(out.data() + 8, &total, 4);
  out.append(reinterpret_cast<const char*>(&len), 4).append(reinterpret_cast<const char*>(&kind), 4).append(chunk).append(rest);
  return out;
}

}  // namespace foveal::render::detail
