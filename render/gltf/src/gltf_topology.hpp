#pragma once
// glTF triangle strips and fans as triangle lists (the compositor draws lists only).
#include <cstdint>
#include <vector>

namespace foveal::render::detail {

/// Whether glTF primitive `mode` is drawn: TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN.
bool is_triangle_mode(int mode);

/// `indices` of a primitive in `mode` as a triangle list with glTF's winding (strips
/// alternate the order of every second triangle so all face the same way).
std::vector<std::uint32_t> triangle_list(int mode, const std::vector<std::uint32_t>& indices);

}  // namespace foveal::render::detail
