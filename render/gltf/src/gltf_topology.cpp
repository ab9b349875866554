#include "gltf_topology.hpp"

#include <tiny_gltf.h>

namespace foveal::render::detail {

bool is_triangle_mode(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

std::vector<std::uint32_t> triangle_list(int mode, const std::vector<std::uint32_t>& indices) {
  if (mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
    return {indices.begin(), indices.begin() + static_cast<std::ptrdiff_t>(indices.size() / 3 * 3)};
  std::vector<std::uint32_t> out;
  if (indices.size() < 3) return out;
  out.reserve((indices.size() - 2) * 3);
  for (std::size_t i = 2; i < indices.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) out.insert(out.end(), {indices[0], indices[i - 1], indices[i]});
    else if (i % 2 == 0) out.insert(out.end(), {indices[i - 2], indices[i - 1], indices[i]});
    else out.insert(out.end(), {indices[i - 1], indices[i - 2], indices[i]});
  }
  return out;
}

}  // namespace foveal::render::detail
