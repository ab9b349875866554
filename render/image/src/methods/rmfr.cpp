// RMFR's kernel and the methods planned on it (docs/methods.md): rmfr, the rectilinear
// map of Ye et al. 2019 (foveal-rmfr, render/foveation); uniform, RMFR's buffer with the
// identity map (an even W/σ × H/σ grid that the resolve upsamples); fixed, rmfr with the
// fovea pinned at the optical centre; full, every pixel shaded (RMFR's identity at
// W×H: the compositor lights it straight into the output). Their mapping and resolve
// passes are foveal::rmfr::Foveator's; the GLSL here is the lighting and material passes'
// source_pixel, with temporal accumulation's grid jitter (shaders/temporal/jitter.glsl).
#include "foveal/image/method_description.hpp"
#include "foveal/rmfr_mapping.hpp"

namespace foveal::render {

namespace {

Status plan_full(EyePlan& p, const EyeFoveation&) {
  p.f = glm::dvec2(rmfr::kRmfrIdentityF);  // the identity map over the W×H buffer
  return {};
}

void rmfr_buffer(EyePlan& p) {
  p.buffer_w = rmfr::rmfr_buffer_size(p.screen_w, p.sigma), p.buffer_h = rmfr::rmfr_buffer_size(p.screen_h, p.sigma);
}

Status plan_rmfr(EyePlan& p, const EyeFoveation& e) {
  rmfr_buffer(p);
  // f depends on the fovea only through max(c, 1 - c): the same in either vertical frame.
  p.f = {rmfr::rmfr_effective_f(e.fx, p.sigma, p.fovea.x), rmfr::rmfr_effective_f(e.fy, p.sigma, p.fovea.y)};
  return {};
}

Status plan_uniform(EyePlan& p, const EyeFoveation&) {
  rmfr_buffer(p);
  p.f = glm::dvec2(rmfr::kRmfrIdentityF);
  return {};
}

constexpr const char* kKernel = R"glsl(
ivec2 method_source_pixel(ivec2 texel) {
  vec2 t = rmfr_jittered(vec2(texel) + 0.5, u_jitter, u_buffer_size, u_screen_size, u_fovea, u_f);
  return clamp_pixel(foveal_rmfr_inverse(t / u_buffer_size, u_fovea, u_f) * u_screen_size);
}

vec2 method_source_point(vec2 t) {
  return foveal_rmfr_inverse(rmfr_jittered(t, u_jitter, u_buffer_size, u_screen_size, u_fovea, u_f) / u_buffer_size, u_fovea, u_f) * u_screen_size;
}
)glsl";

constexpr MethodKernel kRmfrKernel{"rmfr", kKernel, /*rmfr_passes=*/true, /*repeats_v=*/false, /*built_up_front=*/true};

}  // namespace

const MethodDescription& full_method() {
  static const MethodDescription d{"full", FoveaSource::unused, plan_full, &kRmfrKernel};
  return d;
}

const MethodDescription& rmfr_method() {
  static const MethodDescription d{"rmfr", FoveaSource::gaze, plan_rmfr, &kRmfrKernel};
  return d;
}

const MethodDescription& uniform_method() {
  static const MethodDescription d{"uniform", FoveaSource::optical_centre, plan_uniform, &kRmfrKernel};
  return d;
}

const MethodDescription& fixed_method() {
  static const MethodDescription d{"fixed", FoveaSource::optical_centre, plan_rmfr, &kRmfrKernel};
  return d;
}

}  // namespace foveal::render
