// EXT_meshopt_compression: each compressed buffer view is decoded (meshoptimizer's
// vertex/index codecs and filters) into a new buffer and the view pointed at it, so the
// fallback data (often absent) is never read.
#include <meshoptimizer.h>

#include "gltf_decode.hpp"

namespace foveal::render::detail {

namespace {

std::string text(const tinygltf::Value& v, const char* key, const char* fallback) {
  return v.Has(key) && v.Get(key).IsString() ? v.Get(key).Get<std::string>() : fallback;
}

Result<std::size_t> count_field(const tinygltf::Value& v, const char* key, bool required, const std::string& where) {
  if (!v.Has(key)) {
    if (required) return bad_input(where + ": missing " + key);
    return std::size_t{0};
  }
  const tinygltf::Value& x = v.Get(key);
  if (!x.IsNumber() || x.GetNumberAsDouble() < 0 || x.GetNumberAsDouble() > 9.0e15)
    return bad_input(where + ": " + key + " must be a non-negative integer");
  return static_cast<std::size_t>(x.GetNumberAsDouble());
}

Status decode_view(tinygltf::Model& m, std::size_t index, const tinygltf::Value& ext, const std::string& path,
                   DecodeBudget& budget) {
  const std::string where = path + ": buffer view " + std::to_string(index) + " (EXT_meshopt_compression)";
  auto buffer = count_field(ext, "buffer", true, where);
  auto offset = count_field(ext, "byteOffset", false, where);
  auto length = count_field(ext, "byteLength", true, where);
  auto stride = count_field(ext, "byteStride", true, where);
  auto count = count_field(ext, "count", true, where);
  for (const auto* r : {&buffer, &offset, &length, &stride, &count})
    if (!*r) return r->error();
  const std::string mode = text(ext, "mode", ""), filter = text(ext, "filter", "NONE");
  if (*stride == 0 || *stride > 256 || (mode == "ATTRIBUTES" && *stride % 4 != 0))
    return bad_input(where + ": byteStride " + std::to_string(*stride) + " is invalid for mode " + mode);
  if (*count > kMaxDecodedBytes / *stride) return bad_input(where + ": count " + std::to_string(*count) + " is too large");
  auto src = buffer_span(m, static_cast<int>(*buffer), *offset, *length, where);
  if (!src) return src.error();
  // The codecs cannot expand past a fixed ratio (the EXT_meshopt_compression format:
  // attributes carry at least 2 header bits per byte per 16 vertices, triangles at least
  // one code byte per triangle, index sequences one byte per index), so a claim beyond
  // it is refused before the output is allocated: a 1 KB file claimed 1 GiB here.
  if (mode != "ATTRIBUTES" && mode != "TRIANGLES" && mode != "INDICES")
    return bad_input(where + ": unknown mode \"" + mode + "\" (ATTRIBUTES, TRIANGLES or INDICES)");
  if (mode != "ATTRIBUTES" && *stride != 2 && *stride != 4) return bad_input(where + ": index byteStride must be 2 or 4");
  const std::size_t max_count = mode == "ATTRIBUTES" ? *length * 64 / *stride : mode == "TRIANGLES" ? *length * 3 : *length;
  if (*count > max_count)
    return bad_input(where + ": count " + std::to_string(*count) + " × byteStride " + std::to_string(*stride) + " = " +
                     std::to_string(*count * *stride) + " bytes cannot be decoded from " + std::to_string(*length) +
                     " compressed bytes (mode " + mode + ")");
  if (Status s = budget.take(*count * *stride, where); !s) return s;
  std::vector<unsigned char> out(*count * *stride);
  int rc = 0;
  if (mode == "ATTRIBUTES") rc = meshopt_decodeVertexBuffer(out.data(), *count, *stride, *src, *length);
  else
    rc = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(out.data(), *count, *stride, *src, *length)
                             : meshopt_decodeIndexSequence(out.data(), *count, *stride, *src, *length);
  if (rc != 0) return bad_input(where + ": the compressed data is corrupt (meshopt error " + std::to_string(rc) + ")");
  if (filter == "OCTAHEDRAL") {
    if (*stride != 4 && *stride != 8) return bad_input(where + ": OCTAHEDRAL needs byteStride 4 or 8");
    meshopt_decodeFilterOct(out.data(), *count, *stride);
  } else if (filter == "QUATERNION") {
    if (*stride != 8) return bad_input(where + ": QUATERNION needs byteStride 8");
    meshopt_decodeFilterQuat(out.data(), *count, *stride);
  } else if (filter == "EXPONENTIAL") {
    meshopt_decodeFilterExp(out.data(), *count, *stride);
  } else if (filter != "NONE") {
    return bad_input(where + ": unknown filter \"" + filter + "\"");
  }
  const std::size_t bytes = out.size();
  tinygltf::BufferView& v = m.bufferViews[index];
  v.buffer = append_buffer(m, std::move(out));
  v.byteOffset = 0;
  v.byteLength = bytes;
  v.byteStride = mode == "ATTRIBUTES" ? *stride : 0;
  v.extensions.erase("EXT_meshopt_compression");
  return {};
}

}  // namespace

Status decode_meshopt_views(tinygltf::Model& m, const std::string& path, DecodeBudget& budget) {
  for (std::size_t i = 0; i < m.bufferViews.size(); ++i) {
    auto it = m.bufferViews[i].extensions.find("EXT_meshopt_compression");
    if (it == m.bufferViews[i].extensions.end()) continue;
    const tinygltf::Value ext = it->second;  // a copy: the map entry is erased on success
    if (Status s = decode_view(m, i, ext, path, budget); !s) return s;
  }
  return {};
}

}  // namespace foveal::render::detail
