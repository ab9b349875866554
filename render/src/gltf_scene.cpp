// glTF 2.0 through tinygltf: node hierarchy, indexed and non-indexed triangle lists,
// vertex colours and two UV sets, mipmapped textures. Extensions: gltf_extensions.cpp;
// compressed and sparse data: gltf_decode.hpp; materials: gltf_materials.cpp.
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_decode.hpp"
#include "gltf_extensions.hpp"
#include "gltf_json_fixups.hpp"
#include "gltf_materials.hpp"
#include "gltf_topology.hpp"
#include "scene_internal.hpp"

namespace foveal::render::detail {

namespace {

// Reads accessor `index` as `n` floats per element (normalised integers scaled to [0, 1]
// or [-1, 1] as the spec says).
Result<std::vector<float>> read_floats(const tinygltf::Model& m, int index, int n, const std::string& where) {
  if (index < 0 || index >= static_cast<int>(m.accessors.size())) return bad_input(where + ": accessor out of range");
  const tinygltf::Accessor& a = m.accessors[static_cast<std::size_t>(index)];
  if (a.sparse.isSparse) return Error{ErrorKind::unsupported, where + ": sparse accessors are not supported"};
  const int comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  if (comps != n) return bad_input(where + ": expected " + std::to_string(n) + " components, got " + std::to_string(comps));
  std::vector<float> out(a.count * static_cast<std::size_t>(n), 0.0f);
  if (a.bufferView < 0) return out;  // all zeros, as the spec says
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const tinygltf::Buffer& b = m.buffers.at(static_cast<std::size_t>(v.buffer));
  const int csize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (csize <= 0) return bad_input(where + ": bad component type");
  const std::size_t stride = v.byteStride ? v.byteStride : static_cast<std::size_t>(csize * n);
  const std::size_t start = v.byteOffset + a.byteOffset;
  if (a.count > 0 && (start + stride * (a.count - 1) + static_cast<std::size_t>(csize * n) > b.data.size() ||
                      start + stride * (a.count - 1) + static_cast<std::size_t>(csize * n) > v.byteOffset + v.byteLength))
    return bad_input(where + ": accessor reads past the end of its buffer");
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = b.data.data() + start + stride * i;
    for (int c = 0; c < n; ++c) {
      const unsigned char* q = p + c * csize;
      float f = 0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&f, q, 4); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: f = a.normalized ? *q / 255.0f : *q; break;
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
          const auto s = static_cast<std::int8_t>(*q);
          f = a.normalized ? std::max(s / 127.0f, -1.0f) : s;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t s;
          std::memcpy(&s, q, 2);
          f = a.normalized ? s / 65535.0f : s;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
          std::int16_t s;
          std::memcpy(&s, q, 2);
          f = a.normalized ? std::max(s / 32767.0f, -1.0f) : s;
          break;
        }
        default: return Error{ErrorKind::unsupported, where + ": unsupported component type"};
      }
      if (!std::isfinite(f)) return bad_input(where + ": element " + std::to_string(i) + " is not finite");
      out[i * static_cast<std::size_t>(n) + static_cast<std::size_t>(c)] = f;
    }
  }
  return out;
}

Result<std::vector<std::uint32_t>> read_indices(const tinygltf::Model& m, int index, const std::string& where) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<std::size_t>(index));
  if (a.bufferView < 0) return bad_input(where + ": index accessor without a buffer view");
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<std::size_t>(a.bufferView));
  const tinygltf::Buffer& b = m.buffers.at(static_cast<std::size_t>(v.buffer));
  const int csize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (csize != 1 && csize != 2 && csize != 4) return bad_input(where + ": bad index component type");
  const std::size_t stride = v.byteStride ? v.byteStride : static_cast<std::size_t>(csize);
  const std::size_t start = v.byteOffset + a.byteOffset;
  if (a.count > 0 && start + stride * (a.count - 1) + static_cast<std::size_t>(csize) > b.data.size())
    return bad_input(where + ": indices read past the end of their buffer");
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = b.data.data() + start + stride * i;
    if (csize == 1) out[i] = *p;
    else if (csize == 2) { std::uint16_t s; std::memcpy(&s, p, 2); out[i] = s; }
    else std::memcpy(&out[i], p, 4);
  }
  return out;
}

// Per-vertex normals from the triangles, for meshes that have none.
void generate_normals(std::vector<Vertex>& v, const std::vector<std::uint32_t>& idx) {
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const glm::vec3 a = glm::make_vec3(v[idx[t]].position), b = glm::make_vec3(v[idx[t + 1]].position),
                    c = glm::make_vec3(v[idx[t + 2]].position);
    const glm::vec3 n = glm::cross(b - a, c - a);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) v[idx[t + static_cast<std::size_t>(k)]].normal[i] += n[i];
  }
  for (Vertex& x : v) {
    glm::vec3 n = glm::make_vec3(x.normal);
    n = glm::length(n) > 0 ? glm::normalize(n) : glm::vec3(0, 0, 1);
    std::memcpy(x.normal, glm::value_ptr(n), sizeof x.normal);
  }
}

// Per-vertex tangents from uv gradients, for normal-mapped meshes without them.
void generate_tangents(std::vector<Vertex>& v, const std::vector<std::uint32_t>& idx) {
  std::vector<glm::vec3> tan(v.size(), glm::vec3(0)), bit(v.size(), glm::vec3(0));
  for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
    const Vertex &a = v[idx[t]], &b = v[idx[t + 1]], &c = v[idx[t + 2]];
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
    if (glm::length(t) < 1e-12f) t = std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0));
    t = glm::normalize(t);
    const float w = glm::dot(glm::cross(n, t), bit[i]) < 0 ? -1.0f : 1.0f;
    v[i].tangent[0] = t.x, v[i].tangent[1] = t.y, v[i].tangent[2] = t.z, v[i].tangent[3] = w;
  }
}

glm::mat4 local_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(n.matrix[static_cast<std::size_t>(i)]);
    return m;
  }
  glm::mat4 m(1.0f);
  if (n.translation.size() == 3)
    m = glm::translate(m, glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::quat(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]),
                                  static_cast<float>(n.rotation[1]), static_cast<float>(n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

GLenum wrap_mode(int gltf) {
  switch (gltf) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return GL_CLAMP_TO_EDGE;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return GL_MIRRORED_REPEAT;
    default: return GL_REPEAT;
  }
}

class Builder {
 public:
  Builder(const tinygltf::Model& m, std::string path, Scene& s) : m_(m), path_(std::move(path)), s_(s) {}

  // glTF texture index -> Scene::textures index, uploaded once per colour space.
  Result<int> texture(int gltf_index, bool srgb) {
    if (gltf_index < 0) return -1;
    const auto key = std::make_pair(gltf_index, srgb);
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    if (gltf_index >= static_cast<int>(m_.textures.size())) return bad_input(path_ + ": texture index out of range");
    const tinygltf::Texture& t = m_.textures[static_cast<std::size_t>(gltf_index)];
    if (t.source < 0 || t.source >= static_cast<int>(m_.images.size()))
      return bad_input(path_ + ": texture " + std::to_string(gltf_index) + " has no image");
    const tinygltf::Image& img = m_.images[static_cast<std::size_t>(t.source)];
    const std::string what = path_ + ": image " + std::to_string(t.source) + (img.uri.empty() ? "" : " (" + img.uri + ")");
    if (img.width <= 0 || img.height <= 0 || img.image.empty()) return bad_input(what + ": not decoded");
    if (img.bits != 8) return Error{ErrorKind::unsupported, what + ": only 8-bit images are supported"};
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 4, 255);
    const int c = img.component;
    if (c < 1 || c > 4 || img.image.size() < rgba.size() / 4 * static_cast<std::size_t>(c))
      return bad_input(what + ": unexpected pixel data size");
    for (std::size_t i = 0; i < rgba.size() / 4; ++i)
      for (int k = 0; k < 4; ++k)
        if (k < c) rgba[i * 4 + static_cast<std::size_t>(k)] = img.image[i * static_cast<std::size_t>(c) + static_cast<std::size_t>(k)];
        else if (k < 3) rgba[i * 4 + static_cast<std::size_t>(k)] = img.image[i * static_cast<std::size_t>(c)];  // grey
    GLenum ws = GL_REPEAT, wt = GL_REPEAT;
    if (t.sampler >= 0 && t.sampler < static_cast<int>(m_.samplers.size())) {
      ws = wrap_mode(m_.samplers[static_cast<std::size_t>(t.sampler)].wrapS);
      wt = wrap_mode(m_.samplers[static_cast<std::size_t>(t.sampler)].wrapT);
    }
    s_.textures.push_back(upload_rgba8(rgba.data(), img.width, img.height, srgb, ws, wt, &s_.texture_bytes));
    const int index = static_cast<int>(s_.textures.size()) - 1;
    textures_[key] = index;
    return index;
  }

  Status materials() {
    const TextureUploader upload = [this](int index, bool srgb) { return texture(index, srgb); };
    for (std::size_t i = 0; i < m_.materials.size(); ++i) {
      auto mat = read_material(m_.materials[i], upload, path_ + ": material " + std::to_string(i), s_.warnings);
      if (!mat) return mat.error();
      s_.materials.push_back(*mat);
    }
    return {};
  }

  // Uploads every primitive of mesh `index` once; returns their Scene::primitives indices.
  Result<std::vector<int>> mesh(int index) {
    if (auto it = meshes_.find(index); it != meshes_.end()) return it->second;
    const tinygltf::Mesh& gm = m_.meshes.at(static_cast<std::size_t>(index));
    std::vector<int> out;
    for (std::size_t pi = 0; pi < gm.primitives.size(); ++pi) {
      const tinygltf::Primitive& gp = gm.primitives[pi];
      const std::string where = path_ + ": mesh " + std::to_string(index) + " primitive " + std::to_string(pi);
      const int mode = gp.mode == -1 ? TINYGLTF_MODE_TRIANGLES : gp.mode;
      if (!is_triangle_mode(mode)) {
        warn_once(path_ + ": points and lines are not drawn");
        continue;
      }
      auto pos_it = gp.attributes.find("POSITION");
      if (pos_it == gp.attributes.end()) return bad_input(where + ": no POSITION");
      auto pos = read_floats(m_, pos_it->second, 3, where + " POSITION");
      if (!pos) return pos.error();
      const std::size_t n = pos->size() / 3;
      std::vector<Vertex> v(n, Vertex{{0, 0, 0}, {0, 0, 0}, {0, 0}, {1, 0, 0, 1}, {0, 0}, {1, 1, 1, 1}});
      for (std::size_t i = 0; i < n; ++i) std::memcpy(v[i].position, &(*pos)[i * 3], 12);
      std::vector<std::uint32_t> idx;
      if (gp.indices >= 0) {
        auto r = read_indices(m_, gp.indices, where + " indices");
        if (!r) return r.error();
        idx = std::move(*r);
        for (std::uint32_t i : idx)
          if (i >= n) return bad_input(where + ": index " + std::to_string(i) + " >= vertex count " + std::to_string(n));
      } else {
        idx.resize(n);
        for (std::size_t i = 0; i < n; ++i) idx[i] = static_cast<std::uint32_t>(i);
      }
      idx = triangle_list(mode, idx);
      auto copy = [&](const char* name, int comps, auto member) -> Result<bool> {
        auto it = gp.attributes.find(name);
        if (it == gp.attributes.end()) return false;
        auto r = read_floats(m_, it->second, comps, where + " " + name);
        if (!r) return r.error();
        if (r->size() != n * static_cast<std::size_t>(comps)) return bad_input(where + ": " + name + " count differs from POSITION");
        for (std::size_t i = 0; i < n; ++i) std::memcpy(v[i].*member, &(*r)[i * static_cast<std::size_t>(comps)], static_cast<std::size_t>(comps) * 4);
        return true;
      };
      auto has_n = copy("NORMAL", 3, &Vertex::normal);
      if (!has_n) return has_n.error();
      auto has_uv = copy("TEXCOORD_0", 2, &Vertex::uv);
      if (!has_uv) return has_uv.error();
      auto has_t = copy("TANGENT", 4, &Vertex::tangent);
      if (!has_t) return has_t.error();
      auto has_uv1 = copy("TEXCOORD_1", 2, &Vertex::uv1);
      if (!has_uv1) return has_uv1.error();
      const bool color_vec3 = gp.attributes.count("COLOR_0") &&
                              m_.accessors.at(static_cast<std::size_t>(gp.attributes.at("COLOR_0"))).type == TINYGLTF_TYPE_VEC3;
      auto has_color = copy("COLOR_0", color_vec3 ? 3 : 4, &Vertex::color);  // alpha stays 1 for vec3
      if (!has_color) return has_color.error();
      if (!*has_n) generate_normals(v, idx);
      if (!*has_t) generate_tangents(v, idx);
      const int material = gp.material >= 0 && gp.material < static_cast<int>(s_.materials.size()) ? gp.material : -1;
      if (!*has_uv1 && material >= 0 && reads_uv1(s_.materials[static_cast<std::size_t>(material)])) {
        warn_once(where + ": a texture reads TEXCOORD_1, which the primitive lacks; TEXCOORD_0 is used");
        for (Vertex& x : v) std::memcpy(x.uv1, x.uv, sizeof x.uv);
      }
      s_.primitives.push_back(upload_primitive(v, idx, material));
      s_.triangles += idx.size() / 3;
      out.push_back(static_cast<int>(s_.primitives.size()) - 1);
      mesh_bounds_[static_cast<std::size_t>(out.back())] = minmax(v);
    }
    meshes_[index] = out;
    return out;
  }

  Status node(int index, const glm::mat4& parent, int depth) {
    if (depth > 64) return bad_input(path_ + ": node hierarchy deeper than 64 (a cycle?)");
    if (index < 0 || index >= static_cast<int>(m_.nodes.size())) return bad_input(path_ + ": node index out of range");
    const tinygltf::Node& n = m_.nodes[static_cast<std::size_t>(index)];
    const glm::mat4 world = parent * local_matrix(n);
    if (n.mesh >= 0) {
      if (n.mesh >= static_cast<int>(m_.meshes.size())) return bad_input(path_ + ": node " + std::to_string(index) + ": mesh out of range");
      auto prims = mesh(n.mesh);
      if (!prims) return prims.error();
      for (int p : *prims) {
        s_.draws.push_back({p, world});
        const auto [lo, hi] = mesh_bounds_[static_cast<std::size_t>(p)];
        for (int corner = 0; corner < 8; ++corner) {
          const glm::vec3 c((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
          grow(glm::vec3(world * glm::vec4(c, 1.0f)));
        }
      }
    }
    if (n.camera >= 0 && !camera_found_) {
      camera_found_ = true;
      glm::mat4 pose = world;
      for (int c = 0; c < 3; ++c) pose[c] = glm::vec4(glm::normalize(glm::vec3(pose[c])), 0.0f);  // drop scale
      s_.view.head_to_world = pose;
      s_.view.source = "glTF camera " + (n.name.empty() ? std::to_string(index) : n.name);
    }
    for (int child : n.children)
      if (Status s = node(child, world, depth + 1); !s) return s;
    return {};
  }

  bool camera_found() const { return camera_found_; }
  void warn_once(const std::string& w) {
    if (std::find(s_.warnings.begin(), s_.warnings.end(), w) == s_.warnings.end()) s_.warnings.push_back(w);
  }
  bool empty_bounds() const { return !have_bounds_; }

 private:
  static bool reads_uv1(const Material& m) {
    const int tex[] = {m.base_color_tex, m.metal_rough_tex, m.normal_tex, m.occlusion_tex, m.emissive_tex};
    for (std::size_t i = 0; i < m.uv.size(); ++i)
      if (tex[i] >= 0 && m.uv[i].set == 1) return true;
    return false;
  }
  static std::pair<glm::vec3, glm::vec3> minmax(const std::vector<Vertex>& v) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const Vertex& x : v) lo = glm::min(lo, glm::make_vec3(x.position)), hi = glm::max(hi, glm::make_vec3(x.position));
    return {lo, hi};
  }
  void grow(glm::vec3 p) {
    if (!have_bounds_) s_.bounds.min = s_.bounds.max = p, have_bounds_ = true;
    s_.bounds.min = glm::min(s_.bounds.min, p);
    s_.bounds.max = glm::max(s_.bounds.max, p);
  }

  const tinygltf::Model& m_;
  std::string path_;
  Scene& s_;
  std::map<std::pair<int, bool>, int> textures_;
  std::map<int, std::vector<int>> meshes_;
  std::map<std::size_t, std::pair<glm::vec3, glm::vec3>> mesh_bounds_;
  bool camera_found_ = false, have_bounds_ = false;
};

}  // namespace

Result<Scene> load_gltf_scene(const std::string& path) {
  tinygltf::Model model;
  std::string warn;
  if (Status s = load_tinygltf(model, path, warn); !s) return s.error();
  Scene scene;
  scene.name = path;
  for (std::size_t a = 0, b; a < warn.size(); a = b + 1) {  // tinygltf's, one per line
    b = warn.find('\n', a);
    if (b == std::string::npos) b = warn.size();
    if (b > a) scene.warnings.push_back(path + ": " + warn.substr(a, b - a));
  }
  if (Status s = check_gltf_extensions(model, path, scene.warnings); !s) return s.error();
  if (Status s = decode_gltf_model(model, path); !s) return s.error();
  Builder b(model, path, scene);
  if (Status s = b.materials(); !s) return s.error();
  const int root = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (model.scenes.empty()) return bad_input(path + ": no scene");
  if (root >= static_cast<int>(model.scenes.size())) return bad_input(path + ": default scene out of range");
  for (int n : model.scenes[static_cast<std::size_t>(root)].nodes)
    if (Status s = b.node(n, glm::mat4(1.0f), 0); !s) return s.error();
  if (scene.draws.empty() || b.empty_bounds()) return bad_input(path + ": the scene draws no triangles");
  if (!b.camera_found()) scene.view.source = "framing";
  return scene;
}

}  // namespace foveal::render::detail
