#include "gltf_decode.hpp"

namespace foveal::render::detail {

Status decode_gltf_model(tinygltf::Model& m, const std::string& path, const GltfLimits& limits, DecodeBudget& budget) {
  // Meshopt first: Draco payloads and sparse indices/values may sit in compressed views.
  if (Status s = decode_meshopt_views(m, path, budget); !s) return s;
  if (Status s = decode_draco_primitives(m, path, budget); !s) return s;
  return densify_sparse_accessors(m, path, limits, budget);
}

Result<const unsigned char*> buffer_span(const tinygltf::Model& m, int buffer, std::size_t offset, std::size_t length,
                                         const std::string& where) {
  if (buffer < 0 || buffer >= static_cast<int>(m.buffers.size())) return bad_input(where + ": buffer index out of range");
  const auto& data = m.buffers[static_cast<std::size_t>(buffer)].data;
  if (offset > data.size() || length > data.size() - offset)
    return bad_input(where + ": reads bytes " + std::to_string(offset) + "+" + std::to_string(length) +
                     " past the end of buffer " + std::to_string(buffer) + " (" + std::to_string(data.size()) + " bytes)");
  return data.data() + offset;
}

Result<const unsigned char*> view_span(const tinygltf::Model& m, int view, std::size_t offset, std::size_t length,
                                       const std::string& where) {
  if (view < 0 || view >= static_cast<int>(m.bufferViews.size())) return bad_input(where + ": buffer view index out of range");
  const tinygltf::BufferView& v = m.bufferViews[static_cast<std::size_t>(view)];
  if (offset > v.byteLength || length > v.byteLength - offset)
    return bad_input(where + ": reads past the end of buffer view " + std::to_string(view));
  return buffer_span(m, v.buffer, v.byteOffset + offset, length, where);
}

int append_buffer(tinygltf::Model& m, std::vector<unsigned char> bytes) {
  tinygltf::Buffer b;
  b.data = std::move(bytes);
  m.buffers.push_back(std::move(b));
  return static_cast<int>(m.buffers.size()) - 1;
}

int append_buffer_view(tinygltf::Model& m, std::vector<unsigned char> bytes, std::size_t stride) {
  tinygltf::BufferView v;
  v.byteLength = bytes.size();
  v.byteStride = stride;
  v.buffer = append_buffer(m, std::move(bytes));
  m.bufferViews.push_back(v);
  return static_cast<int>(m.bufferViews.size()) - 1;
}

}  // namespace foveal::render::detail
