#pragma once
// What the compositor reads every frame: the EFR pair and f, as plain data so the
// render thread takes it from a SeqLock without blocking.
#include <cstdint>

#include "foveal/runtime/profile.hpp"

namespace foveal::daemon {

struct RenderSettings {
  std::uint8_t dominant_eye = 1;  ///< 0 left, 1 right
  double sigma_d = 2.0, sigma_nd = 3.0;
  double f_x = 0.3, f_y = 0.3;    ///< < 0: automatic
  double ipd_mm = 63.0;           ///< the user's, for the eye cameras
  bool temporal = false;          ///< the profile's temporal accumulation (docs/rmfr.md)
  std::uint32_t generation = 0;   ///< increments with every change

  static RenderSettings from(const Profile& p, std::uint32_t generation) {
    RenderSettings s;
    s.dominant_eye = static_cast<std::uint8_t>(p.dominant_eye);
    s.sigma_d = p.sigma_d;
    s.sigma_nd = p.sigma_nd;
    s.f_x = p.f_x.value_or(-1.0);
    s.f_y = p.f_y.value_or(-1.0);
    s.ipd_mm = p.ipd_mm;
    s.temporal = p.temporal;
    s.generation = generation;
    return s;
  }
};

}  // namespace foveal::daemon
