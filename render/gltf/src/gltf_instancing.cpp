// EXT_mesh_gpu_instancing (gltf_instancing.hpp).
#include "gltf_instancing.hpp"

#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace foveal::render::detail {

namespace {

constexpr std::size_t kMaxDraws = std::size_t{1} << 20;
constexpr float kMaxInstanceOffset = 1e6f;

}  // namespace

Result<std::vector<glm::mat4>> node_instances(const tinygltf::Model& model, AccessorReader& read, const tinygltf::Node& n,
                                              const std::string& path, std::size_t primitives, std::size_t draws) {
  const auto ext = n.extensions.find("EXT_mesh_gpu_instancing");
  if (ext == n.extensions.end()) return std::vector<glm::mat4>{glm::mat4(1.0f)};
  const std::string where = path + ".extensions.EXT_mesh_gpu_instancing.attributes";
  const tinygltf::Value& attributes = ext->second.Get("attributes");
  // (tinygltf reads an empty object as null: that is "none" below.)
  if (!attributes.IsObject() && attributes.Type() != tinygltf::NULL_TYPE) return read.fail(where, "is not an object");
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
    if (!(d >= 0 && d < static_cast<double>(model.accessors.size()) && d == std::floor(d)))
      return read.fail(where + "." + k.name, "is not an accessor index (" + std::to_string(model.accessors.size()) + " accessors)");
    auto values = read.floats(static_cast<int>(d), k.comps, k.types, where + "." + k.name);
    if (!values) return values.error();
    const std::size_t c = values->size() / static_cast<std::size_t>(k.comps);
    if (count && c != count)
      return read.fail(where + "." + k.name, std::to_string(c) + " instances where the other attributes have " + std::to_string(count));
    count = c;
    *k.out = std::move(*values);
  }
  if (!count) return read.fail(where, "has none of TRANSLATION, ROTATION, SCALE");
  if (draws + count * primitives > kMaxDraws)
    return read.fail(where, std::to_string(count) + " instances of " + std::to_string(primitives) +
                                " primitives take the scene past the " + std::to_string(kMaxDraws) + " draws foveal accepts");
  // An instance far away drives the framing bounds: one at 3e38 m emptied the frame.
  auto g = [](float v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", static_cast<double>(v));
    return std::string(b);
  };
  for (std::size_t i = 0; i < t.size(); ++i)
    if (!(std::abs(t[i]) <= kMaxInstanceOffset))
      return read.fail(where + ".TRANSLATION", "element " + std::to_string(i / 3) + " is " + g(t[i]) +
                                                   " from the node, beyond the 1e6 units foveal accepts");
  for (std::size_t i = 0; i < s.size(); ++i)
    if (!(std::abs(s[i]) <= kMaxInstanceOffset))
      return read.fail(where + ".SCALE", "element " + std::to_string(i / 3) + " is " + g(s[i]) +
                                             ", beyond the 1e6 foveal accepts");
  std::vector<glm::mat4> out(count, glm::mat4(1.0f));
  for (std::size_t i = 0; i < count; ++i) {
    glm::mat4& m = out[i];
    if (!t.empty()) m = glm::translate(m, glm::vec3(t[3 * i], t[3 * i + 1], t[3 * i + 2]));
    if (!r.empty()) {
      const glm::quat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);  // glm: w first; glTF: x, y, z, w
      const float len = glm::length(q);
      if (!(len > 0.0f)) return read.fail(where + ".ROTATION", "element " + std::to_string(i) + " is not a rotation (zero quaternion)");
      m *= glm::mat4_cast(q / len);
    }
    if (!s.empty()) m = glm::scale(m, glm::vec3(s[3 * i], s[3 * i + 1], s[3 * i + 2]));
  }
  return out;
}

}  // namespace foveal::render::detail
