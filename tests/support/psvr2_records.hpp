#pragma once
// Builds PS VR2 gaze state records byte by byte at the offsets docs/drivers.md lists:
// for the parser's unit tests and the FunctionFS gadget in the VM tests.
#include <cstdint>
#include <cstring>
#include <vector>

#include "foveal/drivers/psvr2/psvr2_gaze_packet.hpp"

namespace foveal::test {

/// Writes synthetic records field by field at the documented offsets.
struct RecordBuilder {
  std::vector<std::uint8_t> b = std::vector<std::uint8_t>(usb::psvr2::kRecordBytes, 0);
  RecordBuilder() {
    b[0] = 'G';
    b[1] = 'S';
    b[2] = 3;  // version
    u32(4, usb::psvr2::kRecordBytes);
  }
  void u32(std::size_t at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) b[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (8 * k));
  }
  void f32(std::size_t at, float f) {
    std::uint32_t v;
    std::memcpy(&v, &f, 4);
    u32(at, v);
  }
  void vec3(std::size_t at, float x, float y, float z) {
    f32(at, x);
    f32(at + 4, y);
    f32(at + 8, z);
  }
  /// An eye: origin, direction, pupil and blink, all valid.
  void eye(std::size_t base, float ox, float dx, float dz, float pupil, bool blink) {
    u32(base, 1);
    vec3(base + 4, ox, 0, 0);
    u32(base + 16, 1);
    vec3(base + 20, dx, 0, dz);
    u32(base + 32, 1);
    f32(base + 36, pupil);
    u32(base + 64, 1);
    u32(base + 68, blink ? 1 : 0);
  }
};

}  // namespace foveal::test
