// Checked reads of glTF accessors (gltf_accessors.hpp).
#include "gltf_accessors.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace foveal::render::detail {

namespace {

const char* component_name(int t) {
  switch (t) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "?";
  }
}

const char* type_name(int t) {
  switch (t) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "a matrix";
  }
}

}  // namespace

// Accessor `index` as `type` with one of `types` as its component type, every byte it
// reads inside its buffer view, the view inside its buffer.
Result<AccessorReader::Span> AccessorReader::span(int index, int type, std::initializer_list<int> types,
                                                 const std::string& use) const {
  const std::string path = "accessors[" + std::to_string(index) + "]";
  if (index < 0 || static_cast<std::size_t>(index) >= m_.accessors.size()) return fail(use, "accessor out of range");
  const tinygltf::Accessor& a = m_.accessors[static_cast<std::size_t>(index)];
  if (a.sparse.isSparse) return Error{ErrorKind::unsupported, file_ + ": " + path + " (" + use + "): sparse accessors are not supported"};
  if (a.type != type)
    return fail(path, std::string("type ") + type_name(a.type) + " is not " + type_name(type) + " as " + use + " needs");
  if (std::find(types.begin(), types.end(), a.componentType) == types.end()) {
    std::string list;
    for (int t : types) list += (list.empty() ? "" : ", ") + std::string(component_name(t));
    return fail(path, std::string("component type ") + component_name(a.componentType) + " is not one the renderer reads for " +
                          use + " (" + list + ")");
  }
  Span s;
  s.count = a.count;
  s.component_type = a.componentType;
  s.comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  s.normalized = a.normalized;
  const std::size_t elem =
      static_cast<std::size_t>(s.comps) * static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  if (s.count == 0) return fail(path + ".count", "must be at least 1");
  if (a.bufferView < 0) {
    if (s.count > limits_.max_zero_accessor_count)
      return fail(path + ".count", std::to_string(s.count) + " elements without a buffer view (all zeros) is more than the " +
                                       std::to_string(limits_.max_zero_accessor_count) + " accepted");
    return s;
  }
  const tinygltf::BufferView& v = m_.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const tinygltf::Buffer& b = m_.buffers.at(static_cast<std::size_t>(v.buffer));
  const std::string vpath = "bufferViews[" + std::to_string(a.bufferView) + "]";
  std::size_t view_end = 0;
  if (__builtin_add_overflow(v.byteOffset, v.byteLength, &view_end) || view_end > b.data.size())
    return fail(vpath, "byteOffset " + std::to_string(v.byteOffset) + " + byteLength " + std::to_string(v.byteLength) +
                           " is past the end of buffers[" + std::to_string(v.buffer) + "] (" + std::to_string(b.data.size()) +
                           " bytes)");
  s.stride = v.byteStride ? v.byteStride : elem;
  if (s.stride < elem)
    return fail(vpath + ".byteStride", std::to_string(v.byteStride) + " is less than the " + std::to_string(elem) +
                                          "-byte elements of " + path);
  // The last element ends at byteOffset + stride * (count - 1) + elem, within the view.
  std::size_t last = 0, end = 0;
  if (__builtin_mul_overflow(s.stride, s.count - 1, &last) || __builtin_add_overflow(last, a.byteOffset, &end) ||
      __builtin_add_overflow(end, elem, &end) || end > v.byteLength)
    return fail(path, "count " + std::to_string(s.count) + " × stride " + std::to_string(s.stride) + " from byteOffset " +
                          std::to_string(a.byteOffset) + " reads past the end of " + vpath + " (" +
                          std::to_string(v.byteLength) + " bytes)");
  s.base = b.data.data() + v.byteOffset + a.byteOffset;
  return s;
}

Result<std::vector<float>> AccessorReader::floats(int index, int n, std::initializer_list<int> types, const std::string& use) {
  auto s = span(index, n == 1 ? TINYGLTF_TYPE_SCALAR : n, types, use);
  if (!s) return s.error();
  if (Status st = budget_.take(s->count * static_cast<std::size_t>(n) * sizeof(float), file_ + ": " + use); !st) return st.error();
  std::vector<float> out(s->count * static_cast<std::size_t>(n), 0.0f);
  if (!s->base) return out;  // all zeros, as the spec says
  const int csize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(s->component_type));
  for (std::size_t i = 0; i < s->count; ++i) {
    const unsigned char* p = s->base + s->stride * i;
    for (int c = 0; c < n; ++c) {
      const unsigned char* q = p + c * csize;
      float f = 0;
      switch (s->component_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&f, q, 4); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: f = s->normalized ? *q / 255.0f : *q; break;
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
          const auto v = static_cast<std::int8_t>(*q);
          f = s->normalized ? std::max(v / 127.0f, -1.0f) : v;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t v;
          std::memcpy(&v, q, 2);
          f = s->normalized ? v / 65535.0f : v;
          break;
        }
        default: {  // SHORT: span() allowed nothing else
          std::int16_t v;
          std::memcpy(&v, q, 2);
          f = s->normalized ? std::max(v / 32767.0f, -1.0f) : v;
          break;
        }
      }
      if (!std::isfinite(f)) return fail(use, "element " + std::to_string(i) + " is not finite");
      out[i * static_cast<std::size_t>(n) + static_cast<std::size_t>(c)] = f;
    }
  }
  return out;
}

Result<std::vector<std::uint32_t>> AccessorReader::indices(int index, const std::string& use) {
  auto s = span(index, TINYGLTF_TYPE_SCALAR,
                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                use);
  if (!s) return s.error();
  if (!s->base) return fail(use, "an index accessor needs a buffer view");
  if (Status st = budget_.take(s->count * sizeof(std::uint32_t), file_ + ": " + use); !st) return st.error();
  std::vector<std::uint32_t> out(s->count);
  for (std::size_t i = 0; i < s->count; ++i) {
    const unsigned char* p = s->base + s->stride * i;
    if (s->component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) out[i] = *p;
    else if (s->component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) { std::uint16_t v; std::memcpy(&v, p, 2); out[i] = v; }
    else std::memcpy(&out[i], p, 4);
  }
  return out;
}

}  // namespace foveal::render::detail
