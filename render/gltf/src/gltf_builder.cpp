// A checked tinygltf model to the renderer's triangles: node hierarchy, indexed and
// non-indexed triangle lists, strips and fans, vertex colours and two UV sets,
// KHR_materials_variants, the camera and the bounds. Beside it, one file per concern:
// accessor reads, every range checked before its output is allocated
// (gltf_accessors.cpp), EXT_mesh_gpu_instancing (gltf_instancing.cpp), generated
// normals and tangents (gltf_normals.cpp), materials (gltf_materials.cpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_accessors.hpp"
#include "gltf_instancing.hpp"
#include "gltf_internal.hpp"
#include "gltf_lights.hpp"
#include "gltf_materials.hpp"
#include "gltf_normals.hpp"
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

class Builder {
 public:
  Builder(const tinygltf::Model& m, std::string file, const GltfLimits& limits, DecodeBudget& budget, GltfSink& sink)
      : m_(m), file_(std::move(file)), read_(m, file_, limits, budget), budget_(budget), sink_(sink) {}

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
      auto pos = read_.floats(pos_it->second, 3, kQuantized, where + ".attributes.POSITION");
      if (!pos) return pos.error();
      const std::size_t n = pos->size() / 3;
      if (n > UINT32_MAX) return fail(where + ".attributes.POSITION", "more than 2^32 vertices");
      if (Status s = budget_.take(n * sizeof(GltfVertex), file_ + ": " + where); !s) return s.error();
      std::vector<GltfVertex> v(n, GltfVertex{{0, 0, 0}, {0, 0, 0}, {0, 0}, {1, 0, 0, 1}, {0, 0}, {1, 1, 1, 1}});
      for (std::size_t i = 0; i < n; ++i) std::memcpy(v[i].position, &(*pos)[i * 3], 12);
      pos = std::vector<float>();
      std::vector<std::uint32_t> idx;
      if (gp.indices >= 0) {
        auto r = read_.indices(gp.indices, where + ".indices");
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
        auto r = read_.floats(it->second, comps, types, use);
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
      auto placed = node_instances(m_, read_, n, path, prims->size(), out_.draws.size());
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
  AccessorReader read_;
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
