#pragma once
// The gaze records the emulated PS VR2 (vm_psvr2.cpp's FunctionFS gadget) sends as its
// k-th record, so a reader can check every decoded value.
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "psvr2_records.hpp"

namespace foveal::vmtest {

constexpr std::uint16_t kPsvr2Vendor = 0x054c, kPsvr2Product = 0x0cde;

/// Headset-frame direction of eye `e` in record k (x left, +z forward).
inline glm::dvec3 psvr2_direction(std::uint64_t k, int e) {
  const double a = static_cast<double>(k % 200) * 0.002 - 0.2 + (e ? 0.05 : -0.05);
  return glm::normalize(glm::dvec3(std::sin(a), 0.1 - 0.001 * static_cast<double>(k % 100), std::cos(a)));
}
/// The left pupil carries k mod 1000, so the reader can find k.
inline float psvr2_pupil(std::uint64_t k) { return 2.0f + static_cast<float>(k % 1000) * 0.001f; }
inline bool psvr2_blink(std::uint64_t k) { return k % 50 == 49; }

inline std::vector<std::uint8_t> psvr2_record(std::uint64_t k) {
  test::RecordBuilder r;
  for (int e = 0; e < 2; ++e) {
    const std::size_t base = e ? usb::psvr2::kRightEye : usb::psvr2::kLeftEye;
    const glm::dvec3 d = psvr2_direction(k, e);
    r.u32(base, 1);
    r.vec3(base + 4, e ? -32.0f : 32.0f, 0.0f, 0.0f);
    r.u32(base + 16, 1);
    r.vec3(base + 20, static_cast<float>(d.x), static_cast<float>(d.y), static_cast<float>(d.z));
    r.u32(base + 32, 1);
    r.f32(base + 36, e ? 4.0f : psvr2_pupil(k));
    r.u32(base + 64, 1);
    r.u32(base + 68, psvr2_blink(k) ? 1 : 0);
  }
  r.u32(usb::psvr2::kCombined + 32, 1);
  r.u32(usb::psvr2::kCombined + 36, static_cast<std::uint32_t>(1'000'000 + k * 8333));
  return r.b;
}

}  // namespace foveal::vmtest
