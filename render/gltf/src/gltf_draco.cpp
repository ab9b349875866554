// KHR_draco_mesh_compression: each compressed primitive is decoded with Draco and its
// indices and listed attributes replaced by new float (indices: uint32) accessors.
#include <cstring>
#include <limits>

#include <draco/compression/decode.h>

#include "gltf_decode.hpp"

namespace foveal::render::detail {

namespace {

// Draco normalises integer data itself only when it was told to; glTF says per accessor.
float normalisation(draco::DataType t) {
  switch (t) {
    case draco::DT_UINT8: return 1.0f / 255.0f;
    case draco::DT_INT8: return 1.0f / 127.0f;
    case draco::DT_UINT16: return 1.0f / 65535.0f;
    case draco::DT_INT16: return 1.0f / 32767.0f;
    default: return 1.0f;
  }
}

int new_accessor(tinygltf::Model& m, const tinygltf::Accessor& like, int component_type, std::vector<unsigned char> bytes,
                 std::size_t count) {
  tinygltf::Accessor a;
  a.name = like.name;
  a.type = like.type;
  a.componentType = component_type;
  a.count = count;
  a.minValues = like.minValues;
  a.maxValues = like.maxValues;
  a.bufferView = append_buffer_view(m, std::move(bytes), 0);
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

Status decode_primitive(tinygltf::Model& m, tinygltf::Primitive& p, const tinygltf::Value& ext, const std::string& where,
                        DecodeBudget& budget) {
  if (!ext.Has("bufferView") || !ext.Get("bufferView").IsNumber() || !ext.Has("attributes") || !ext.Get("attributes").IsObject())
    return bad_input(where + ": KHR_draco_mesh_compression needs bufferView and attributes");
  const int view = static_cast<int>(ext.Get("bufferView").GetNumberAsDouble());
  if (view < 0 || view >= static_cast<int>(m.bufferViews.size())) return bad_input(where + ": Draco bufferView out of range");
  const std::size_t length = m.bufferViews[static_cast<std::size_t>(view)].byteLength;
  auto data = view_span(m, view, 0, length, where);
  if (!data) return data.error();
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(*data), length);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return bad_input(where + ": Draco data does not decode: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const std::uint32_t points = mesh->num_points();
  if (std::size_t{points} * 16 > kMaxDecodedBytes || mesh->num_faces() * 12 > kMaxDecodedBytes) return bad_input(where + ": Draco mesh is too large");
  if (Status s = budget.take(mesh->num_faces() * 12 + std::size_t{points} * 16 * ext.Get("attributes").Size(), where + " (Draco)"); !s)
    return s;

  if (p.indices >= 0 || mesh->num_faces() > 0) {
    std::vector<unsigned char> bytes(mesh->num_faces() * 3 * 4);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh->face(f)[k].value();
        std::memcpy(&bytes[(f.value() * 3 + static_cast<std::uint32_t>(k)) * 4], &v, 4);
      }
    const tinygltf::Accessor like = p.indices >= 0 ? m.accessors.at(static_cast<std::size_t>(p.indices)) : tinygltf::Accessor{};
    tinygltf::Accessor scalar = like;
    scalar.type = TINYGLTF_TYPE_SCALAR;
    scalar.minValues.clear(), scalar.maxValues.clear();
    p.indices = new_accessor(m, scalar, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, std::move(bytes), mesh->num_faces() * 3);
  }
  for (const auto& [name, id] : ext.Get("attributes").Get<tinygltf::Value::Object>()) {
    auto it = p.attributes.find(name);
    if (it == p.attributes.end() || !id.IsNumber()) continue;  // Draco carries data the primitive does not use
    if (it->second < 0 || it->second >= static_cast<int>(m.accessors.size())) return bad_input(where + ": " + name + ": accessor out of range");
    const tinygltf::Accessor like = m.accessors[static_cast<std::size_t>(it->second)];
    const draco::PointAttribute* att = mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id.GetNumberAsDouble()));
    if (!att) return bad_input(where + ": " + name + ": no Draco attribute with id " + std::to_string(static_cast<int>(id.GetNumberAsDouble())));
    const int comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(like.type));
    if (comps <= 0 || comps > 4 || att->num_components() < comps)
      return bad_input(where + ": " + name + ": Draco attribute has " + std::to_string(att->num_components()) + " components");
    const float scale = like.normalized && !att->normalized() ? normalisation(att->data_type()) : 1.0f;
    std::vector<unsigned char> bytes(std::size_t{points} * static_cast<std::size_t>(comps) * 4);
    float value[4];
    for (draco::PointIndex i(0); i < points; ++i) {
      if (!att->ConvertValue<float>(att->mapped_index(i), static_cast<std::int8_t>(comps), value))
        return bad_input(where + ": " + name + ": Draco value does not convert to float");
      for (int c = 0; c < comps; ++c) value[c] *= scale;
      std::memcpy(&bytes[std::size_t{i.value()} * static_cast<std::size_t>(comps) * 4], value, static_cast<std::size_t>(comps) * 4);
    }
    it->second = new_accessor(m, like, TINYGLTF_COMPONENT_TYPE_FLOAT, std::move(bytes), points);
  }
  p.extensions.erase("KHR_draco_mesh_compression");
  return {};
}

}  // namespace

Status decode_draco_primitives(tinygltf::Model& m, const std::string& path, DecodeBudget& budget) {
  for (std::size_t mi = 0; mi < m.meshes.size(); ++mi)
    for (std::size_t pi = 0; pi < m.meshes[mi].primitives.size(); ++pi) {
      tinygltf::Primitive& p = m.meshes[mi].primitives[pi];
      auto it = p.extensions.find("KHR_draco_mesh_compression");
      if (it == p.extensions.end()) continue;
      const tinygltf::Value ext = it->second;
      const std::string where = path + ": mesh " + std::to_string(mi) + " primitive " + std::to_string(pi);
      if (Status s = decode_primitive(m, p, ext, where, budget); !s) return s;
    }
  return {};
}

}  // namespace foveal::render::detail
