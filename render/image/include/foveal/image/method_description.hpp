#pragma once
// A foveation method described in one place: its name, whether it follows the gaze, its
// plan (buffer-size rule and the mapping data its kernel reads) and its GLSL kernel.
// Adding such a method is one file in render/image/src/methods/ and one row in
// render/image/src/methods/method_list.cpp; the Method value, the command lines' and
// the bench's method lists, the compositor's programs (both pipelines) and the shaders
// take it from here (docs/methods.md, "Described methods").
//
// The seven methods before it (full ... fixed) are still written into the Method enum,
// plan_eye's switch and shaders/common/mapping.glsl; the inset is the first described.
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/image/foveation_plan.hpp"

namespace foveal::render {

struct MethodDescription {
  const char* name;  ///< on command lines, in bench files and golden names
  /// Whether the method's fovea follows the gaze (false: plan() gets the optical centre).
  bool follows_gaze;
  /// Fills a plan whose method, screen size, frustum and fovea (normalised, GL frame) are
  /// set: buffer_w/h, layers (the atlas the passes draw, innermost first) and
  /// kernel_params. shaded_samples() sums the layers. Errors: bad_input (bad parameter).
  Status (*plan)(EyePlan& plan, const EyeFoveation& eye);
  /// The GLSL kernel, spliced into shaders/common/mapping.glsl where MAPPING is
  /// MAPPING_DESCRIBED. It defines
  ///   vec2 method_source_point(vec2 t)   buffer position (texels) -> screen position (px)
  ///   ivec2 method_source_pixel(ivec2 texel)   the pixel whose sample fills the texel
  ///   vec4 method_resolve(sampler2D reduced, vec2 p)   lit colour at screen pixel centre p
  /// and may read mapping.glsl's uniforms (u_layer_*, u_screen_size, u_tan, u_kernel_params).
  /// Methods with the same kernel_name share one set of programs.
  const char* kernel_name;
  const char* kernel_glsl;
};

/// The described methods, one row each, in the order they follow the built-in ones.
const std::vector<const MethodDescription*>& described_methods();
/// The description of `m`, or nullptr for the built-in methods (and unknown values).
const MethodDescription* describe(Method m);
/// The Method value of the described method at row `row` of described_methods().
Method described_method(std::size_t row);

/// The distinct kernels of the described methods (by kernel_name), in order of first use;
/// kernel_index(m) is m's position in it (-1 for a built-in method).
const std::vector<const MethodDescription*>& described_kernels();
int kernel_index(Method m);

}  // namespace foveal::render
