// Generated normals and tangents (gltf_normals.hpp).
#include "gltf_normals.hpp"

#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace foveal::render::detail {

void generate_normals(std::vector<GltfVertex>& v, const std::vector<std::uint32_t>& idx) {
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

void generate_tangents(std::vector<GltfVertex>& v, const std::vector<std::uint32_t>& idx) {
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

}  // namespace foveal::render::detail
