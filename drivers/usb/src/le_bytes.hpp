#pragma once
// Little-endian reads at fixed offsets of a USB record (the caller checked the length).
#include <cstdint>
#include <cstring>
#include <span>

#include <glm/vec3.hpp>

namespace foveal::usb {

class LeBytes {
 public:
  explicit LeBytes(std::span<const std::uint8_t> d) : d_(d) {}
  std::uint16_t u16(std::size_t at) const {
    return static_cast<std::uint16_t>(d_[at] | d_[at + 1] << 8);
  }
  std::int16_t i16(std::size_t at) const { return static_cast<std::int16_t>(u16(at)); }
  std::uint32_t u32(std::size_t at) const {
    return static_cast<std::uint32_t>(d_[at]) | static_cast<std::uint32_t>(d_[at + 1]) << 8 |
           static_cast<std::uint32_t>(d_[at + 2]) << 16 | static_cast<std::uint32_t>(d_[at + 3]) << 24;
  }
  float f32(std::size_t at) const {
    const std::uint32_t bits = u32(at);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }
  glm::vec3 vec3(std::size_t at) const { return {f32(at), f32(at + 4), f32(at + 8)}; }

 private:
  std::span<const std::uint8_t> d_;
};

}  // namespace foveal::usb
