// A checked tinygltf model to the renderer's triangles: node hierarchy, indexed and
// non-indexed triangle lists, strips and fans, vertex colours and two UV sets; materials
// in gltf_materials.cpp. Every
// accessor's range is checked against its buffer view and buffer (64-bit, no wrap)
// before its output is allocated.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_internal.hpp"
#include "gltf_lights.hpp"
#include "gltf_materials.hpp"
#include "gltf_topology.hpp"

namespace foveal::render::detail {

Status DecodeBudget::take(std::size_t bytes, const std::string& what) {
  if (bytes > limit_ || used_ > limit_ - bytes)
    return bad_input(what + ": decoding it would take the model past " + std::to_string(limit_ >> 20) +
                     " MiB of decoded images and geometry (the loader's bound)");
  used_ += bytes;
  return {};
}

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

// Where an accessor's elements are: element i starts at base + stride * i.
struct AccessorSpan {
  const unsigned char* base = nullptr;  // null: no buffer view, all zeros
  std::size_t stride = 0, count = 0;
  int component_type = 0, comps = 0;
  bool normalized = false;
};

class Builder {
 public:
  Builder(const tinygltf::Model& m, std::string file, const GltfLimits& limits, DecodeBudget& budget, GltfSink& sink)
      : m_(m), file_(std::move(file)), limits_(limits), budget_(budget), sink_(sink) {}

  Result<GltfScene> build() {
    if (Status s = materials(); !s) return s.error();
    if (Status s = variant_names(); !s) return s.error();
    if (m_.scenes.empty()) return bad_input(file_ + ": no scene");
    const std::size_t root = m_.defaultScene >= 0 ? static_cast<std::size_t>(m_.defaultScene) : 0;
    if (root >= m_.scenes.size()) return bad_input(file_ + ": scene: out of range");
    for (int n : m_.scenes[root].nodes)
      if (Status s = node(n, glm::mat4(1.0f), 0); !s) return s.error();
    if (out_.draws.empty() || !have_bounds_) return bad_input(file_ + ": the scene draws no triangles");
    if (!camera_found_) out_.view.source = "framing";
    warn_if_slow();
    return std::move(out_);
  }

 private:
  Error fail(const std::string& path, const std::string& what) const { return bad_input(file_ + ": " + path + ": " + what); }

  // Accessor `index` as `type` with one of `types` as its component type, every byte it
  // reads inside its buffer view, the view inside its buffer.
  Result<AccessorSpan> span(int index, int type, std::initializer_list<int> types, const std::string& use) {
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
    AccessorSpan s;
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

  // The accessor as n floats per element (normalised integers scaled as the spec says).
  Result<std::vector<float>> floats(int index, int n, std::initializer_list<int> types, const std::string& use) {
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

  Result<std::vector<std::uint32_t>> indices(int index, const std::string& use) {
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

  // glTF texture index -> the sink's texture index, once per colour space.
  Result<int> texture(int gltf_index, bool srgb, const std::string& use) {
    if (gltf_index < 0) return -1;
    const auto key = std::make_pair(gltf_index, srgb);
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    if (static_cast<std::size_t>(gltf_index) >= m_.textures.size()) return fail(use, "texture index out of range");
    const tinygltf::Texture& t = m_.textures[static_cast<std::size_t>(gltf_index)];
    if (t.source < 0 || static_cast<std::size_t>(t.source) >= m_.images.size())
      return bad_input(file_ + ": texture " + std::to_string(gltf_index) + " has no image");
    const tinygltf::Image& img = m_.images[static_cast<std::size_t>(t.source)];
    const std::string what = file_ + ": image " + std::to_string(t.source) + (img.uri.empty() ? "" : " (" + img.uri + ")");
    if (img.width <= 0 || img.height <= 0 || img.image.empty()) return bad_input(what + ": not decoded");
    if (img.component != 4 || img.bits != 8 ||
        img.image.size() != static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 4)
      return bad_input(what + ": unexpected pixel data size");
    GltfTexture out;
    out.rgba = img.image.data();
    out.width = img.width;
    out.height = img.height;
    out.srgb = srgb;
    if (t.sampler >= 0 && static_cast<std::size_t>(t.sampler) < m_.samplers.size()) {
      out.wrap_s = m_.samplers[static_cast<std::size_t>(t.sampler)].wrapS;
      out.wrap_t = m_.samplers[static_cast<std::size_t>(t.sampler)].wrapT;
    }
    const int index = sink_.add_texture(out);
    textures_[key] = index;
    return index;
  }

  Status materials() {
    for (std::size_t mi = 0; mi < m_.materials.size(); ++mi) {
      const std::string path = "materials[" + std::to_string(mi) + "]";
      const TextureUploader upload = [&](int index, bool srgb) { return texture(index, srgb, path); };
      auto mat = read_material(m_.materials[mi], upload, file_ + ": " + path, out_.warnings);
      if (!mat) return mat.error();
      out_.materials.push_back(*mat);
    }
    return {};
  }

  // Said before the first frame: a scene this large takes seconds to minutes a frame on
  // llvmpipe (2^20 instanced draws: 182 s; 50,000 BLEND primitives: 82 s, at c0fb9a1).
  static constexpr std::size_t kSlowDraws = 65536, kSlowBlendDraws = 10000;
  void warn_if_slow() {
    std::size_t blend = 0;
    for (const DrawItem& d : out_.draws) blend += blends_.count(d.primitive) && blends_.at(d.primitive);
    if (out_.draws.size() > kSlowDraws)
      warn_once(file_ + ": " + std::to_string(out_.draws.size()) + " draw items (each instance of EXT_mesh_gpu_instancing "
                "is one): past " + std::to_string(kSlowDraws) + ", a frame may take many seconds (minutes on llvmpipe)");
    if (blend > kSlowBlendDraws)
      warn_once(file_ + ": " + std::to_string(blend) + " alphaMode BLEND draw items, sorted and shaded at full resolution: "
                "past " + std::to_string(kSlowBlendDraws) + ", a frame may take many seconds (minutes on llvmpipe)");
  }

  void warn_once(const std::string& w) {
    if (std::find(out_.warnings.begin(), out_.warnings.end(), w) == out_.warnings.end()) out_.warnings.push_back(w);
  }

  static bool reads_uv1(const Material& m) {
    for (int i = 0; i < Material::slot_count; ++i)
      if (m.texture(static_cast<Material::Slot>(i)) >= 0 && m.uv[static_cast<std::size_t>(i)].set == 1) return true;
    return false;
  }

  // KHR_materials_variants: the variants' names (the model's list), then per primitive
  // the material each mapping gives it under which variants.
  Status variant_names() {
    auto it = m_.extensions.find("KHR_materials_variants");
    if (it == m_.extensions.end()) return {};
    const tinygltf::Value& v = it->second;
    if (!v.Has("variants") || !v.Get("variants").IsArray())
      return fail("extensions.KHR_materials_variants", "no variants array");
    const tinygltf::Value& list = v.Get("variants");
    for (std::size_t i = 0; i < list.ArrayLen(); ++i) {
      const tinygltf::Value& e = list.Get(static_cast<int>(i));
      if (!e.Has("name") || !e.Get("name").IsString())
        return fail("extensions.KHR_materials_variants.variants[" + std::to_string(i) + "]", "no name");
      out_.variants.push_back({e.Get("name").Get<std::string>(), {}});
    }
    return {};
  }

  Status primitive_variants(const tinygltf::Primitive& gp, const std::string& where, int primitive) {
    auto it = gp.extensions.find("KHR_materials_variants");
    if (it == gp.extensions.end()) return {};
    const std::string at = where + ".extensions.KHR_materials_variants";
    const tinygltf::Value& v = it->second;
    if (!v.Has("mappings") || !v.Get("mappings").IsArray()) return fail(at, "no mappings array");
    const tinygltf::Value& maps = v.Get("mappings");
    for (std::size_t k = 0; k < maps.ArrayLen(); ++k) {
      const tinygltf::Value& m = maps.Get(static_cast<int>(k));
      const std::string mat_at = at + ".mappings[" + std::to_string(k) + "]";
      if (!m.Has("material") || !m.Get("material").IsInt() || m.Get("material").Get<int>() < 0 ||
          static_cast<std::size_t>(m.Get("material").Get<int>()) >= out_.materials.size())
        return fail(mat_at + ".material", "missing or out of range (" + std::to_string(out_.materials.size()) + " materials)");
      if (!m.Has("variants") || !m.Get("variants").IsArray()) return fail(mat_at, "no variants array");
      const tinygltf::Value& vs = m.Get("variants");
      for (std::size_t j = 0; j < vs.ArrayLen(); ++j) {
        const tinygltf::Value& x = vs.Get(static_cast<int>(j));
        if (!x.IsInt() || x.Get<int>() < 0 || static_cast<std::size_t>(x.Get<int>()) >= out_.variants.size())
          return fail(mat_at + ".variants[" + std::to_string(j) + "]",
                      "not a variant index (" + std::to_string(out_.variants.size()) + " variants)");
        out_.variants[static_cast<std::size_t>(x.Get<int>())].primitive_material.emplace_back(primitive, m.Get("material").Get<int>());
      }
    }
    return {};
  }

  // Hands every primitive of mesh `index` to the sink once; returns the sink's indices.
  Result<std::vector<int>> mesh(int index) {
    if (auto it = meshes_.find(index); it != meshes_.end()) return it->second;
    const tinygltf::Mesh& gm = m_.meshes.at(static_cast<std::size_t>(index));
    std::vector<int> out;
    for (std::size_t pi = 0; pi < gm.primitives.size(); ++pi) {
      const tinygltf::Primitive& gp = gm.primitives[pi];
      const std::string where = "meshes[" + std::to_string(index) + "].primitives[" + std::to_string(pi) + "]";
      const int mode = gp.mode == -1 ? TINYGLTF_MODE_TRIANGLES : gp.mode;
      if (!is_triangle_mode(mode)) {
        warn_once(file_ + ": points and lines are not drawn");
        continue;
      }
      if (gp.material >= static_cast<int>(out_.materials.size()))
        return fail(where + ".material", std::to_string(gp.material) + " is out of range (" +
                                             std::to_string(out_.materials.size()) + " materials)");
      auto pos_it = gp.attributes.find("POSITION");
      if (pos_it == gp.attributes.end()) return fail(where, "no POSITION");
      constexpr auto kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
      // KHR_mesh_quantization also allows (normalised) bytes and shorts.
      const std::initializer_list<int> kQuantized = {kFloat, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                     TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT};
      auto pos = floats(pos_it->second, 3, kQuantized, where + ".attributes.POSITION");
      if (!pos) return pos.error();
      const std::size_t n = pos->size() / 3;
      if (n > UINT32_MAX) return fail(where + ".attributes.POSITION", "more than 2^32 vertices");
      if (Status s = budget_.take(n * sizeof(GltfVertex), file_ + ": " + where); !s) return s.error();
      std::vector<GltfVertex> v(n, GltfVertex{{0, 0, 0}, {0, 0, 0}, {0, 0}, {1, 0, 0, 1}, {0, 0}, {1, 1, 1, 1}});
      for (std::size_t i = 0; i < n; ++i) std::memcpy(v[i].position, &(*pos)[i * 3], 12);
      pos = std::vector<float>();
      std::vector<std::uint32_t> idx;
      if (gp.indices >= 0) {
        auto r = indices(gp.indices, where + ".indices");
        if (!r) return r.error();
        idx = std::move(*r);
        for (std::size_t i = 0; i < idx.size(); ++i)
          if (idx[i] >= n)
            return fail(where + ".indices", "index " + std::to_string(i) + " is " + std::to_string(idx[i]) +
                                                ", not below the vertex count " + std::to_string(n));
      } else {
        if (Status s = budget_.take(n * sizeof(std::uint32_t), file_ + ": " + where); !s) return s.error();
        idx.resize(n);
        for (std::size_t i = 0; i < n; ++i) idx[i] = static_cast<std::uint32_t>(i);
      }
      if (mode != TINYGLTF_MODE_TRIANGLES) idx = triangle_list(mode, idx);
      if (idx.size() % 3 != 0)
        return fail(where + (gp.indices >= 0 ? ".indices" : ".attributes.POSITION"),
                    "count " + std::to_string(idx.size()) + " is not a multiple of 3 (a triangle list)");
      if (idx.size() > INT32_MAX) return fail(where + ".indices", "more than 2^31 - 1 indices");
      auto copy = [&](const char* name, int comps, std::initializer_list<int> types, auto member) -> Result<bool> {
        auto it = gp.attributes.find(name);
        if (it == gp.attributes.end()) return false;
        const std::string use = where + ".attributes." + name;
        auto r = floats(it->second, comps, types, use);
        if (!r) return r.error();
        if (r->size() != n * static_cast<std::size_t>(comps))
          return fail(use, "count " + std::to_string(r->size() / static_cast<std::size_t>(comps)) + " differs from POSITION's " +
                               std::to_string(n));
        for (std::size_t i = 0; i < n; ++i)
          std::memcpy(v[i].*member, &(*r)[i * static_cast<std::size_t>(comps)], static_cast<std::size_t>(comps) * 4);
        return true;
      };
      auto has_n = copy("NORMAL", 3, {kFloat, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT}, &GltfVertex::normal);
      if (!has_n) return has_n.error();
      auto has_uv = copy("TEXCOORD_0", 2, kQuantized, &GltfVertex::uv);
      if (!has_uv) return has_uv.error();
      auto has_t = copy("TANGENT", 4, {kFloat, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT}, &GltfVertex::tangent);
      if (!has_t) return has_t.error();
      auto has_uv1 = copy("TEXCOORD_1", 2, kQuantized, &GltfVertex::uv1);
      if (!has_uv1) return has_uv1.error();
      const auto color_it = gp.attributes.find("COLOR_0");
      const bool color_vec3 = color_it != gp.attributes.end() && color_it->second >= 0 &&
                              static_cast<std::size_t>(color_it->second) < m_.accessors.size() &&
                              m_.accessors[static_cast<std::size_t>(color_it->second)].type == TINYGLTF_TYPE_VEC3;
      auto has_color = copy("COLOR_0", color_vec3 ? 3 : 4,  // alpha stays 1 for vec3
                            {kFloat, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}, &GltfVertex::color);
      if (!has_color) return has_color.error();
      if (!*has_uv1) {
        if (gp.material >= 0 && reads_uv1(out_.materials[static_cast<std::size_t>(gp.material)]))
          warn_once(file_ + ": " + where + ": a texture reads TEXCOORD_1, which the primitive lacks; TEXCOORD_0 is used");
        for (GltfVertex& x : v) std::memcpy(x.uv1, x.uv, sizeof x.uv);
      }
      if (!*has_n) generate_normals(v, idx);
      if (!*has_t) generate_tangents(v, idx);
      const int p = sink_.add_primitive(v, idx, gp.material >= 0 ? gp.material : -1);
      if (Status s = primitive_variants(gp, where, p); !s) return s.error();
      out_.triangles += idx.size() / 3;
      out.push_back(p);
      bounds_[p] = minmax(v);
      blends_[p] = gp.material >= 0 && static_cast<std::size_t>(gp.material) < out_.materials.size() &&
                   out_.materials[static_cast<std::size_t>(gp.material)].blend;
    }
    meshes_[index] = out;
    return out;
  }

  static bool finite(const glm::mat4& m) {
    for (int i = 0; i < 16; ++i)
      if (!std::isfinite(glm::value_ptr(m)[i])) return false;
    return true;
  }

  Status node(int index, const glm::mat4& parent, int depth) {
    const std::string path = "nodes[" + std::to_string(index) + "]";
    if (depth > 64) return fail(path, "node hierarchy deeper than 64");
    if (index < 0 || static_cast<std::size_t>(index) >= m_.nodes.size()) return bad_input(file_ + ": node index out of range");
    const tinygltf::Node& n = m_.nodes[static_cast<std::size_t>(index)];
    const glm::mat4 world = parent * local_matrix(n);
    if (!finite(world)) return fail(path, "its world transform is not finite");
    if (n.mesh >= 0) {
      auto prims = mesh(n.mesh);
      if (!prims) return prims.error();
      auto placed = instances(n, path, prims->size());
      if (!placed) return placed.error();
      for (const glm::mat4& instance : *placed) {
        const glm::mat4 at = world * instance;
        if (!finite(at)) return fail(path, "an instance's world transform is not finite");
        for (int p : *prims) {
          out_.draws.push_back({p, at});
          const auto [lo, hi] = bounds_[p];
          for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 c((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
            const glm::vec3 w(at * glm::vec4(c, 1.0f));
            if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
              return fail(path, "its mesh's bounds are not finite in world space");
            grow(w);
          }
        }
      }
    }
    if (n.camera >= 0 && !camera_found_) {
      glm::mat4 pose = world;
      for (int c = 0; c < 3; ++c) {
        const float len = glm::length(glm::vec3(pose[c]));
        if (!(len > 0) || !std::isfinite(len)) return fail(path, "the camera's transform has a zero axis");
        pose[c] = glm::vec4(glm::vec3(pose[c]) / len, 0.0f);  // drop scale
      }
      camera_found_ = true;
      out_.view.head_to_world = pose;
      out_.view.source = "glTF camera " + (n.name.empty() ? std::to_string(index) : n.name);
    }
    auto lights = node_light(m_, n, world, file_, path);
    if (!lights) return lights.error();
    out_.lights.insert(out_.lights.end(), lights->begin(), lights->end());
    for (int child : n.children)
      if (Status s = node(child, world, depth + 1); !s) return s;
    return {};
  }

  // EXT_mesh_gpu_instancing: the node's mesh is drawn once per instance, at the node's
  // transform times the instance's T·R·S (attributes TRANSLATION, ROTATION (a unit
  // quaternion, float or normalised integers), SCALE; each optional, all of one count;
  // custom "_..." attributes are ignored). Without the extension: one, the identity.
  // Each instance draws the mesh's `primitives` as draw items of their own (no hardware
  // instancing): at most kMaxDraws in the scene.
  Result<std::vector<glm::mat4>> instances(const tinygltf::Node& n, const std::string& path, std::size_t primitives) {
    const auto ext = n.extensions.find("EXT_mesh_gpu_instancing");
    if (ext == n.extensions.end()) return std::vector<glm::mat4>{glm::mat4(1.0f)};
    const std::string where = path + ".extensions.EXT_mesh_gpu_instancing.attributes";
    const tinygltf::Value& attributes = ext->second.Get("attributes");
    // (tinygltf reads an empty object as null: that is "none" below.)
    if (!attributes.IsObject() && attributes.Type() != tinygltf::NULL_TYPE) return fail(where, "is not an object");
    std::vector<float> t, r, s;
    std::size_t count = 0;
    const struct {
      const char* name;
      int comps;
      std::initializer_list<int> types;
      std::vector<float>* out;
    } kinds[] = {{"TRANSLATION", 3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, &t},
                 {"ROTATION", 4, {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT}, &r},
                 {"SCALE", 3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, &s}};
    for (const auto& k : kinds) {
      if (!attributes.Has(k.name)) continue;
      const tinygltf::Value& index = attributes.Get(k.name);
      const double d = index.IsInt() ? index.Get<int>() : index.IsReal() ? index.Get<double>() : -1.0;
      if (!(d >= 0 && d < static_cast<double>(m_.accessors.size()) && d == std::floor(d)))
        return fail(where + "." + k.name, "is not an accessor index (" + std::to_string(m_.accessors.size()) + " accessors)");
      auto values = floats(static_cast<int>(d), k.comps, k.types, where + "." + k.name);
      if (!values) return values.error();
      const std::size_t c = values->size() / static_cast<std::size_t>(k.comps);
      if (count && c != count)
        return fail(where + "." + k.name, std::to_string(c) + " instances where the other attributes have " + std::to_string(count));
      count = c;
      *k.out = std::move(*values);
    }
    if (!count) return fail(where, "has none of TRANSLATION, ROTATION, SCALE");
    if (out_.draws.size() + count * primitives > kMaxDraws)
      return fail(where, std::to_string(count) + " instances of " + std::to_string(primitives) +
                             " primitives take the scene past the " + std::to_string(kMaxDraws) + " draws foveal accepts");
    // An instance far away drives the framing bounds: one at 3e38 m emptied the frame.
    auto g = [](float v) {
      char b[32];
      std::snprintf(b, sizeof b, "%g", static_cast<double>(v));
      return std::string(b);
    };
    for (std::size_t i = 0; i < t.size(); ++i)
      if (!(std::abs(t[i]) <= kMaxInstanceOffset))
        return fail(where + ".TRANSLATION", "element " + std::to_string(i / 3) + " is " + g(t[i]) +
                                                " from the node, beyond the 1e6 units foveal accepts");
    for (std::size_t i = 0; i < s.size(); ++i)
      if (!(std::abs(s[i]) <= kMaxInstanceOffset))
        return fail(where + ".SCALE", "element " + std::to_string(i / 3) + " is " + g(s[i]) +
                                          ", beyond the 1e6 foveal accepts");
    std::vector<glm::mat4> out(count, glm::mat4(1.0f));
    for (std::size_t i = 0; i < count; ++i) {
      glm::mat4& m = out[i];
      if (!t.empty()) m = glm::translate(m, glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
      if (!r.empty()) {
        const glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);  // glm: w first; glTF: x, y, z, w
        const float len = glm::length(q);
        if (!(len > 0.0f)) return fail(where + ".ROTATION", "element " + std::to_string(i) + " is not a rotation (zero quaternion)");
        m *= glm::mat4_cast(q / len);
      }
      if (!s.empty()) m = glm::scale(m, glm::vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
    }
    return out;
  }
  static constexpr std::size_t kMaxDraws = std::size_t{1} << 20;
  static constexpr float kMaxInstanceOffset = 1e6f;

  static glm::mat4 local_matrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
      glm::mat4 m;
      for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(n.matrix[static_cast<std::size_t>(i)]);
      return m;
    }
    glm::mat4 m(1.0f);
    if (n.translation.size() == 3) m = glm::translate(m, glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4)
      m *= glm::mat4_cast(glm::quat(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]),
                                    static_cast<float>(n.rotation[1]), static_cast<float>(n.rotation[2])));
    if (n.scale.size() == 3) m = glm::scale(m, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
  }

  // Per-vertex normals from the triangles, for meshes that have none.
  static void generate_normals(std::vector<GltfVertex>& v, const std::vector<std::uint32_t>& idx) {
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
      const glm::vec3 a = glm::make_vec3(v[idx[t]].position), b = glm::make_vec3(v[idx[t + 1]].position),
                      c = glm::make_vec3(v[idx[t + 2]].position);
      const glm::vec3 n = glm::cross(b - a, c - a);
      for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i) v[idx[t + static_cast<std::size_t>(k)]].normal[i] += n[i];
    }
    for (GltfVertex& x : v) {
      glm::vec3 n = glm::make_vec3(x.normal);
      n = glm::length(n) > 0 && std::isfinite(glm::length(n)) ? glm::normalize(n) : glm::vec3(0, 0, 1);
      std::memcpy(x.normal, glm::value_ptr(n), sizeof x.normal);
    }
  }

  // Per-vertex tangents from uv gradients, for normal-mapped meshes without them.
  static void generate_tangents(std::vector<GltfVertex>& v, const std::vector<std::uint32_t>& idx) {
    std::vector<glm::vec3> tan(v.size(), glm::vec3(0)), bit(v.size(), glm::vec3(0));
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
      const GltfVertex &a = v[idx[t]], &b = v[idx[t + 1]], &c = v[idx[t + 2]];
      const glm::vec3 e1 = glm::make_vec3(b.position) - glm::make_vec3(a.position);
      const glm::vec3 e2 = glm::make_vec3(c.position) - glm::make_vec3(a.position);
      const glm::vec2 d1 = glm::make_vec2(b.uv) - glm::make_vec2(a.uv), d2 = glm::make_vec2(c.uv) - glm::make_vec2(a.uv);
      const float det = d1.x * d2.y - d2.x * d1.y;
      if (std::abs(det) < 1e-12f) continue;
      const glm::vec3 tv = (e1 * d2.y - e2 * d1.y) / det, bv = (e2 * d1.x - e1 * d2.x) / det;
      for (int k = 0; k < 3; ++k) tan[idx[t + static_cast<std::size_t>(k)]] += tv, bit[idx[t + static_cast<std::size_t>(k)]] += bv;
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
      const glm::vec3 n = glm::make_vec3(v[i].normal);
      glm::vec3 t = tan[i] - n * glm::dot(n, tan[i]);
      if (!(glm::length(t) >= 1e-12f) || !std::isfinite(glm::length(t)))
        t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
      t = glm::normalize(t);
      const float w = glm::dot(glm::cross(n, t), bit[i]) < 0 ? -1.0f : 1.0f;
      v[i].tangent[0] = t.x, v[i].tangent[1] = t.y, v[i].tangent[2] = t.z, v[i].tangent[3] = w;
    }
  }

  static std::pair<glm::vec3, glm::vec3> minmax(const std::vector<GltfVertex>& v) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const GltfVertex& x : v) lo = glm::min(lo, glm::make_vec3(x.position)), hi = glm::max(hi, glm::make_vec3(x.position));
    return {lo, hi};
  }

  void grow(glm::vec3 p) {
    if (!have_bounds_) out_.bounds.min = out_.bounds.max = p, have_bounds_ = true;
    out_.bounds.min = glm::min(out_.bounds.min, p);
    out_.bounds.max = glm::max(out_.bounds.max, p);
  }

  const tinygltf::Model& m_;
  std::string file_;
  const GltfLimits& limits_;
  DecodeBudget& budget_;
  GltfSink& sink_;
  GltfScene out_;
  std::map<std::pair<int, bool>, int> textures_;
  std::map<int, std::vector<int>> meshes_;
  std::map<int, std::pair<glm::vec3, glm::vec3>> bounds_;  // by the sink's primitive index
  std::map<int, bool> blends_;                               // its material is alphaMode BLEND
  bool camera_found_ = false, have_bounds_ = false;
};

}  // namespace

Result<GltfScene> build_gltf_scene(const tinygltf::Model& model, const std::string& file, const GltfLimits& limits,
                                   DecodeBudget& budget, GltfSink& sink) {
  return Builder(model, file, limits, budget, sink).build();
}

}  // namespace foveal::render::detail
