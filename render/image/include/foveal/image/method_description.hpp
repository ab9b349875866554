#pragma once
// A foveation method described in one place: its name, where its fovea comes from, its
// plan (buffer-size rule and the mapping data its kernel reads) and its GLSL kernel.
// Every method is one: full, rmfr, uniform and fixed (methods/rmfr.cpp, RMFR's kernel),
// kfr (methods/kfr.cpp), hyperbolic and linear (methods/layers.cpp), inset and
// inset-fixed (methods/inset.cpp). Adding one is a file in render/image/src/methods/ and
// a row in render/image/src/methods/method_list.cpp; the Method value, the command
// lines' and the bench's method lists, plan_eye, the compositor's programs (both
// pipelines) and the shaders take it from here (docs/methods.md, "Described methods";
// docs/conventions.md, "Where a change goes").
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "foveal/core/error.hpp"
#include "foveal/image/foveation_plan.hpp"

namespace foveal::render {

/// A GLSL kernel: the mapping between an eye's reduced buffer and its screen, shared by
/// the methods whose plans it reads (one set of programs per kernel).
struct MethodKernel {
  const char* name;
  /// Spliced into shaders/common/mapping.glsl as the virtual file "method/kernel". It defines
  ///   vec2 method_source_point(vec2 t)   buffer position (texels) -> screen position (px)
  ///   ivec2 method_source_pixel(ivec2 texel)   the pixel whose sample fills the texel
  ///   vec4 method_resolve(sampler2D reduced, vec2 p)   lit colour at screen pixel centre p
  ///                                                    (not with rmfr_passes)
  /// and may read mapping.glsl's uniforms (u_buffer_size, u_screen_size, u_fovea, u_f,
  /// u_kfr, u_tan, u_layer*, u_kernel_params) and helpers (clamp_pixel, eccentricity_deg).
  /// Screen positions are eye-viewport pixels, GL frame (origin bottom-left).
  const char* glsl;
  /// The mapping and resolve passes are foveal::rmfr::Foveator's (RMFR's kernel: the
  /// compositor builds no map or resolve program from this GLSL, only the passes that
  /// read source_pixel: lighting, and the visibility pipeline's material and classify).
  bool rmfr_passes;
  /// The resolve samples the buffer's v axis with wrap-around (KFR's angle axis).
  bool repeats_v;
  /// Its programs are compiled with the compositor and on every change of the scene's
  /// features (the methods a session starts with); false: on first use, so a compositor
  /// does not pay for programs of methods it never runs.
  bool built_up_front;
};

/// Where a method's fovea comes from; plan() sees the result in EyePlan::fovea.
enum class FoveaSource {
  gaze,            ///< the gaze's point (the method follows the gaze)
  optical_centre,  ///< pinned at the optical centre, so that the plan does not depend on the gaze
  unused,          ///< none: the plan keeps the gaze's point, which no pass reads (full)
};

struct MethodDescription {
  const char* name;  ///< on command lines, in bench files and golden names
  FoveaSource fovea;
  /// Fills a plan whose method, screen size, frustum, σ, fovea (normalised, origin top-left,
  /// per `fovea`) and buffer (W×H) are set: buffer_w/h, f, kfr_*, layers (the atlas the passes
  /// draw, innermost first) and kernel_params as the kernel reads them. shaded_samples()
  /// sums the layers when there are any. Errors: bad_input (bad parameter).
  Status (*plan)(EyePlan& plan, const EyeFoveation& eye);
  const MethodKernel* kernel;
};

/// The unit view ray (-z forward) through normalised viewport point p (origin top-left)
/// of the eye's frustum: what eccentricity_deg measures, and the layered methods' cones.
glm::dvec3 view_ray(const EyeFrustum& frustum, glm::dvec2 p);

/// Every method, one row each, in the order of the Method values (full first).
const std::vector<const MethodDescription*>& described_methods();
/// The description of `m`, or nullptr for a value that is not a method.
const MethodDescription* describe(Method m);
/// The Method value of the method at row `row` of described_methods().
Method described_method(std::size_t row);

/// The distinct kernels, in order of first use in described_methods(); kernel_index(m) is
/// m's kernel's position in it (-1 for a value that is not a method).
const std::vector<const MethodKernel*>& method_kernels();
int kernel_index(Method m);

}  // namespace foveal::render
