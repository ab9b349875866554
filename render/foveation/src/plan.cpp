// CPU side of foveal-rmfr: plans (buffer size, f, fovea) and automatic f.
#include <cmath>
#include <string>
#include <vector>

#include "foveal/image/auto_f.hpp"
#include "foveal/rmfr.hpp"
#include "foveal/rmfr_mapping.hpp"
#include "rmfr_version.hpp"

namespace foveal::rmfr {

namespace {

constexpr int kMaxViewport = 16384;

bool finite_positive(double v) { return std::isfinite(v) && v > 0; }

bool good_frustum(const Frustum& f) {
  for (double t : {f.tan_left, f.tan_right, f.tan_bottom, f.tan_top})
    if (!std::isfinite(t)) return false;
  return f.tan_left < f.tan_right && f.tan_bottom < f.tan_top;
}

}  // namespace

const char* version() { return kVersion; }

Result<Plan> plan_eye(const EyeParams& e) {
  if (e.width < 1 || e.height < 1 || e.width > kMaxViewport || e.height > kMaxViewport)
    return bad_input("rmfr: viewport " + std::to_string(e.width) + "x" + std::to_string(e.height) +
                     " is not in [1, 16384]");
  if (!std::isfinite(e.sigma) || e.sigma < 1.0) return bad_input("rmfr: sigma " + std::to_string(e.sigma) + " is not a number >= 1");
  if (!finite_positive(e.fx) || !finite_positive(e.fy))
    return bad_input("rmfr: fx " + std::to_string(e.fx) + ", fy " + std::to_string(e.fy) + ": expected numbers > 0");
  if (!good_frustum(e.frustum)) return bad_input("rmfr: the frustum's tangents are not finite with left < right, bottom < top");
  Plan p;
  p.screen_w = e.width, p.screen_h = e.height;
  p.buffer_w = rmfr_buffer_size(e.width, e.sigma), p.buffer_h = rmfr_buffer_size(e.height, e.sigma);
  p.sigma = e.sigma;
  p.fovea_x = sanitize_fovea(e.fovea.x);
  p.fovea_y = 1.0 - sanitize_fovea(e.fovea.y);  // top-left in, GL frame out
  p.fx = rmfr_effective_f(e.fx, e.sigma, p.fovea_x), p.fy = rmfr_effective_f(e.fy, e.sigma, p.fovea_y);
  p.frustum = e.frustum;
  return p;
}

Result<std::array<Plan, 2>> plan_efr(const EfrSettings& s, const std::array<EyeParams, 2>& eyes) {
  if (s.dominant_eye != 0 && s.dominant_eye != 1)
    return bad_input("rmfr: dominant_eye " + std::to_string(s.dominant_eye) + " is neither 0 (left) nor 1 (right)");
  if (!(s.sigma_nd >= s.sigma_d))
    return bad_input("rmfr: sigma_nd " + std::to_string(s.sigma_nd) + " is below sigma_d " + std::to_string(s.sigma_d) +
                     " (EFR renders the non-dominant eye at the coarser level)");
  std::array<Plan, 2> plans;
  for (int i = 0; i < 2; ++i) {
    EyeParams e = eyes[static_cast<std::size_t>(i)];
    e.sigma = i == s.dominant_eye ? s.sigma_d : s.sigma_nd;
    e.fx = s.fx, e.fy = s.fy;
    auto p = plan_eye(e);
    if (!p) return Error{p.error().kind, std::string(i == 0 ? "left" : "right") + " eye: " + p.error().message};
    plans[static_cast<std::size_t>(i)] = *p;
  }
  return plans;
}

Result<AutoF> estimate_f(const ImageView& v, std::array<double, 2> sigma, std::array<Fovea, 2> foveae, double ppd) {
  const std::size_t row = static_cast<std::size_t>(v.width) * 4;
  const std::size_t stride = v.stride ? v.stride : row;
  if (!v.rgba || v.width < 2 || v.height < 1 || v.width % 2) return bad_input("rmfr: automatic f needs a side-by-side frame with an even width");
  if (stride < row) return bad_input("rmfr: automatic f: the row stride " + std::to_string(stride) + " is below width·4");
  if (!finite_positive(ppd)) return bad_input("rmfr: automatic f: pixels per degree must be a number > 0");
  image::Image full(v.width, v.height);
  for (int y = 0; y < v.height; ++y) {
    const int src = v.bottom_up ? v.height - 1 - y : y;
    const std::uint8_t* from = v.rgba + static_cast<std::size_t>(src) * stride;
    std::copy(from, from + row, full.at(0, y));
  }
  image::MetricsOptions mo;
  mo.ppd = ppd;
  mo.fovea = {foveae[0].x, foveae[0].y};
  mo.fovea_right = {foveae[1].x, foveae[1].y};
  auto est = image::estimate_rmfr_f(full, sigma, mo);
  if (!est) return Error{est.error().kind, "rmfr: " + est.error().message};
  return AutoF{est->fx, est->fy, est->predicted_fpsnr_db, est->evaluations, est->ms};
}

}  // namespace foveal::rmfr
