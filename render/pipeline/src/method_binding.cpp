// Method binding: which program variant (kernel) a foveation method runs and its GLSL,
// its plan as foveal-rmfr takes it, and the mapping uniforms of
// shaders/common/mapping.glsl for one eye's plan. Plans are top-left (y down,
// docs/conventions.md); the shaders work in GL's frame (origin bottom-left): the flip
// between the two is here and nowhere else (gl_fovea, gl_rect).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "compositor_impl.hpp"
#include "foveal/image/method_description.hpp"
#include "foveal/rmfr.hpp"
#include "foveal/rmfr_mapping.hpp"
#include "pass_uniforms.hpp"

namespace foveal::render {

namespace {

using detail::set;

// A plan's fovea in GL's frame: normalised, origin bottom-left.
glm::dvec2 gl_fovea(const EyePlan& p) { return {p.fovea.x, 1.0 - p.fovea.y}; }

// A layer's screen rectangle in GL's frame: (x, y of its bottom row, w, h), pixels.
glm::vec4 gl_rect(const Layer& l, int screen_h) { return glm::vec4(l.x, screen_h - l.y - l.h, l.w, l.h); }

}  // namespace

std::size_t mapping_variant_count() { return method_kernels().size(); }

const MethodKernel& mapping_kernel(std::size_t v) { return *method_kernels().at(v); }

std::vector<gl::VirtualFile> mapping_files(std::size_t v) {
  if (v >= mapping_variant_count()) return {};
  return {{"method/kernel", mapping_kernel(v).glsl}};
}

Result<std::size_t> mapping_index(const EyePlan& plan) {
  if (const int k = kernel_index(plan.method); k >= 0) return static_cast<std::size_t>(k);
  return bad_input("no mapping for foveation method " + std::to_string(static_cast<int>(plan.method)));
}

// An RMFR eye's plan as foveal-rmfr takes it (plan_eye computed it with the library's
// formulas, foveal/rmfr_mapping.hpp); rmfr::Plan holds its fovea in GL's frame.
rmfr::Plan rmfr_plan(const EyePlan& p) {
  rmfr::Plan r;
  r.screen_w = p.screen_w, r.screen_h = p.screen_h;
  r.buffer_w = p.buffer_w, r.buffer_h = p.buffer_h;
  r.sigma = p.sigma;
  const glm::dvec2 fovea = gl_fovea(p);
  r.fovea_x = fovea.x, r.fovea_y = fovea.y;
  r.fx = p.f.x, r.fy = p.f.y;
  r.frustum = {p.frustum.tan_left, p.frustum.tan_right, p.frustum.tan_bottom, p.frustum.tan_top};
  return r;
}

rmfr::Lens rmfr_lens(const LensDistortion& l) {
  return {l.center.x, l.center.y, l.k1, l.k2, l.k3, {l.channel_scale.x, l.channel_scale.y, l.channel_scale.z}};
}

// The mapping uniforms of shaders/common/mapping.glsl for one eye's plan.
void set_mapping(GLuint p, const EyePlan& plan, glm::vec2 texture_size) {
  set(p, "u_buffer_size", glm::vec2(plan.buffer_w, plan.buffer_h));
  set(p, "u_texture_size", texture_size);
  set(p, "u_screen_size", glm::vec2(plan.screen_w, plan.screen_h));
  set(p, "u_fovea", glm::vec2(gl_fovea(plan)));
  set(p, "u_f", glm::vec2(plan.f));  // full's plan holds the identity (1e30)
  set(p, "u_kfr", glm::vec2(static_cast<float>(plan.kfr_log_max), static_cast<float>(plan.kfr_alpha)));
  set(p, "u_tan", glm::vec4(plan.frustum.tan_left, plan.frustum.tan_right, plan.frustum.tan_bottom, plan.frustum.tan_top));
  const int n = std::min<int>(static_cast<int>(plan.layers.size()), 8);
  set(p, "u_layer_count", n);
  for (int i = 0; i < n; ++i) {
    const Layer& l = plan.layers[static_cast<std::size_t>(i)];
    const std::string k = "[" + std::to_string(i) + "]";
    set(p, ("u_layer_rect" + k).c_str(), gl_rect(l, plan.screen_h));
    set(p, ("u_layer_atlas" + k).c_str(), glm::vec4(l.atlas_y, l.buffer_w, l.buffer_h, l.pixel_size));
    set(p, ("u_layer_ecc" + k).c_str(), std::isfinite(l.ecc_max_deg) ? static_cast<float>(l.ecc_max_deg) : 1e9f);
  }
  set(p, "u_layer", 0);
  set(p, "u_kernel_params", glm::vec4(plan.kernel_params));
}

}  // namespace foveal::render
