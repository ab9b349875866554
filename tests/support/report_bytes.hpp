#pragma once
// Little-endian byte writers for the report builders of the headset tests.
#include <cstdint>
#include <cstring>
#include <vector>

namespace foveal::test {

struct Bytes {
  std::vector<std::uint8_t> b;
  explicit Bytes(std::size_t n = 0) : b(n, 0) {}
  void u16(std::size_t at, std::uint16_t v) {
    b[at] = static_cast<std::uint8_t>(v);
    b[at + 1] = static_cast<std::uint8_t>(v >> 8);
  }
  void i16(std::size_t at, std::int16_t v) { u16(at, static_cast<std::uint16_t>(v)); }
  void u32(std::size_t at, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) b[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (8 * k));
  }
  void f32(std::size_t at, float f) {
    std::uint32_t v;
    std::memcpy(&v, &f, 4);
    u32(at, v);
  }
};

}  // namespace foveal::test
