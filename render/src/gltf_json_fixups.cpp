#include "gltf_json_fixups.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

namespace foveal::render::detail {

namespace {

using nlohmann::json;

// Returns true when something was changed. A .glb's first buffer without a uri is its
// BIN chunk and stays as it is.
bool mend(json& j, bool binary) {
  bool changed = false;
  if (j.contains("meshes") && j["meshes"].is_array())
    for (json& mesh : j["meshes"])
      if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
        for (json& p : mesh["primitives"]) {
          if (!p.is_object() || !p.contains("extensions") || !p["extensions"].is_object()) continue;
          const json& draco = p["extensions"].value("KHR_draco_mesh_compression", json());
          if (!draco.is_object() || !draco.contains("bufferView") || !p.contains("indices") || !p["indices"].is_number_unsigned()) continue;
          const auto i = p["indices"].get<std::size_t>();
          if (!j.contains("accessors") || !j["accessors"].is_array() || i >= j["accessors"].size()) continue;
          json& a = j["accessors"][i];
          if (a.is_object() && !a.contains("bufferView")) a["bufferView"] = draco["bufferView"], changed = true;  // placeholder
        }
  if (j.contains("buffers") && j["buffers"].is_array())
    for (std::size_t i = binary ? 1 : 0; i < j["buffers"].size(); ++i) {
      json& b = j["buffers"][i];
      if (!b.is_object() || b.contains("uri") || !b.contains("extensions") || !b["extensions"].is_object()) continue;
      const json& m = b["extensions"].value("EXT_meshopt_compression", json());
      if (m.is_object() && m.value("fallback", false)) {
        b["uri"] = "data:application/octet-stream;base64,AAAA";  // 3 placeholder bytes
        b["byteLength"] = 3;
        changed = true;
      }
    }
  return changed;
}

// KTX2 images (KHR_texture_basisu) are left undecoded, not refused: a texture that has
// a PNG/JPEG fallback source uses that; one that has not is refused when built.
bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int w, int h,
                const unsigned char* bytes, int size, void* user) {
  static const unsigned char kKtx2[] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB};
  if (size >= 8 && std::memcmp(bytes, kKtx2, 8) == 0) return true;
  return tinygltf::LoadImageData(image, index, err, warn, w, h, bytes, size, user);
}

std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

}  // namespace

Status load_tinygltf(tinygltf::Model& model, const std::string& path, std::string& warn) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(load_image, nullptr);
  std::string err;
  const bool binary = path.size() >= 4 && path.compare(path.size() - 4, 4, ".glb") == 0;
  auto failed = [&]() -> Status {
    while (!err.empty() && err.back() == '\n') err.pop_back();
    return bad_input(path + ": cannot load glTF: " + (err.empty() ? "unknown error" : err));
  };
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The JSON part: the whole .gltf, or a .glb's first chunk.
  std::size_t json_at = 0, json_len = bytes.size();
  if (binary && bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0 && u32(bytes, 16) == 0x4E4F534Au)
    json_at = 20, json_len = std::min<std::size_t>(u32(bytes, 12), bytes.size() - 20);
  const std::string_view text(bytes.data() + json_at, json_len);
  const bool may_need = in && (text.find("KHR_draco_mesh_compression") != std::string_view::npos ||
                               text.find("EXT_meshopt_compression") != std::string_view::npos);
  json j = may_need ? json::parse(text.begin(), text.end(), nullptr, false) : json();
  if (!may_need || j.is_discarded() || !mend(j, binary)) {
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path) : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    return ok ? Status{} : failed();
  }
  const std::string base = std::filesystem::path(path).parent_path().string();
  std::string mended = j.dump();
  bool ok;
  if (!binary) {
    ok = loader.LoadASCIIFromString(&model, &err, &warn, mended.data(), static_cast<unsigned>(mended.size()), base);
  } else {
    while (mended.size() % 4) mended += ' ';
    const std::string rest = bytes.substr(json_at + json_len);  // the BIN chunk, if any
    std::string glb = bytes.substr(0, 12);
    const std::uint32_t total = static_cast<std::uint32_t>(12 + 8 + mended.size() + rest.size()),
                        len = static_cast<std::uint32_t>(mended.size()), kind = 0x4E4F534Au;
    std::memcpy(glb.data() + 8, &total, 4);
    glb.append(reinterpret_cast<const char*>(&len), 4).append(reinterpret_cast<const char*>(&kind), 4).append(mended).append(rest);
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                     static_cast<unsigned>(glb.size()), base);
  }
  return ok ? Status{} : failed();
}

}  // namespace foveal::render::detail
