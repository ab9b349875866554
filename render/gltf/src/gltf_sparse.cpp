// Sparse accessors: the dense base (or zeros) with the listed elements replaced.
#include <cstring>

#include "gltf_decode.hpp"

namespace foveal::render::detail {

namespace {

Status densify(tinygltf::Model& m, std::size_t index, const std::string& path, const GltfLimits& limits, DecodeBudget& budget) {
  tinygltf::Accessor& a = m.accessors[index];
  const std::string where = path + ": accessor " + std::to_string(index) + " (sparse)";
  const int comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  const int csize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (comps <= 0 || csize <= 0) return bad_input(where + ": bad type or component type");
  const std::size_t elem = static_cast<std::size_t>(comps) * static_cast<std::size_t>(csize);
  if (a.count > kMaxDecodedBytes / elem) return bad_input(where + ": count " + std::to_string(a.count) + " is too large");
  // Without a buffer view the base is zeros, bounded as a plain zero accessor is: an
  // 848-byte file asked for 2^27 elements (2.1 GB) here.
  if (a.bufferView < 0 && a.count > limits.max_zero_accessor_count)
    return bad_input(where + ": count " + std::to_string(a.count) + " elements without a buffer view (all zeros) is more than the " +
                     std::to_string(limits.max_zero_accessor_count) + " accepted");
  // Every read is checked before the dense copy is allocated.
  const unsigned char* base = nullptr;
  std::size_t stride = elem;
  if (a.bufferView >= 0 && a.count > 0) {
    const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
    stride = v.byteStride ? v.byteStride : elem;
    std::size_t span = 0;
    if (__builtin_mul_overflow(stride, a.count - 1, &span) || __builtin_add_overflow(span, elem, &span))
      return bad_input(where + ": count " + std::to_string(a.count) + " × stride " + std::to_string(stride) + " is too large");
    auto b = view_span(m, a.bufferView, a.byteOffset, span, where);
    if (!b) return b.error();
    base = *b;
  }
  const auto& sp = a.sparse;
  if (sp.count < 1 || static_cast<std::size_t>(sp.count) > a.count)
    return bad_input(where + ": sparse count " + std::to_string(sp.count) + " outside 1.." + std::to_string(a.count));
  const std::size_t n = static_cast<std::size_t>(sp.count);
  const int isize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(sp.indices.componentType));
  if (isize != 1 && isize != 2 && isize != 4) return bad_input(where + ": sparse indices need an unsigned integer type");
  auto idx = view_span(m, sp.indices.bufferView, static_cast<std::size_t>(sp.indices.byteOffset), n * static_cast<std::size_t>(isize),
                       where + " indices");
  if (!idx) return idx.error();
  auto val = view_span(m, sp.values.bufferView, static_cast<std::size_t>(sp.values.byteOffset), n * elem, where + " values");
  if (!val) return val.error();
  if (Status s = budget.take(a.count * elem, where); !s) return s;
  std::vector<unsigned char> dense(a.count * elem, 0);
  if (base)
    for (std::size_t i = 0; i < a.count; ++i) std::memcpy(&dense[i * elem], base + i * stride, elem);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t k = 0;
    const unsigned char* p = *idx + i * static_cast<std::size_t>(isize);
    if (isize == 1) k = *p;
    else if (isize == 2) { std::uint16_t s; std::memcpy(&s, p, 2); k = s; }
    else std::memcpy(&k, p, 4);
    if (k >= a.count) return bad_input(where + ": sparse index " + std::to_string(k) + " >= count " + std::to_string(a.count));
    std::memcpy(&dense[k * elem], *val + i * elem, elem);
  }
  a.bufferView = append_buffer_view(m, std::move(dense), 0);
  a.byteOffset = 0;
  a.sparse.isSparse = false;
  return {};
}

}  // namespace

Status densify_sparse_accessors(tinygltf::Model& m, const std::string& path, const GltfLimits& limits, DecodeBudget& budget) {
  // Only what a primitive reads is decoded: the builder never meets the others, and a
  // file of unused sparse accessors asked for 4.3 GB.
  std::vector<bool> used(m.accessors.size(), false);
  auto use = [&](int i) {
    if (i >= 0 && static_cast<std::size_t>(i) < used.size()) used[static_cast<std::size_t>(i)] = true;
  };
  for (const tinygltf::Mesh& mesh : m.meshes)
    for (const tinygltf::Primitive& p : mesh.primitives) {
      use(p.indices);
      for (const auto& [name, accessor] : p.attributes) use(accessor);
    }
  for (std::size_t i = 0; i < m.accessors.size(); ++i)
    if (used[i] && m.accessors[i].sparse.isSparse)
      if (Status s = densify(m, i, path, limits, budget); !s) return s;
  return {};
}

}  // namespace foveal::render::detail
