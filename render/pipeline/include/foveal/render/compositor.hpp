#pragma once
// The compositor (docs/rmfr.md, docs/methods.md): per eye, a full-resolution G-buffer,
// then either the full method (lighting on the G-buffer, the reference) or a foveation
// method (RMFR, KFR, hyperbolic or linear fall-off): mapping into the eye's reduced
// G-buffer, lighting there, and a resolve pass with bilinear filtering into the eye's
// half of the side-by-side output. Each eye has its own level σ (EFR).
//
// Thread safety: none; use a Compositor on the thread whose GL context created it, and
// destroy it while that context is current.
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "foveal/core/clock.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/core/pose.hpp"
#include "foveal/image/foveation_plan.hpp"
#include "foveal/image/image.hpp"
#include "foveal/render/gl.hpp"
#include "foveal/render/shader_loader.hpp"

namespace foveal::render {

struct Scene;

/// How an eye's surface samples are made (docs/rmfr.md, "Pipelines"):
/// - gbuffer: a full-resolution G-buffer pass evaluates every material at every pixel;
///   the foveation method's mapping pass then picks the samples it keeps.
/// - visibility: a full-resolution visibility pass keeps only depth and (draw, triangle)
///   per pixel; the material pass evaluates the material at the kept samples only,
///   filtering textures over each sample's footprint.
/// Lighting and resolve are the same in both.
enum class Pipeline { gbuffer, visibility };
const char* pipeline_name(Pipeline p);
/// "gbuffer" or "visibility"; bad_input otherwise.
Result<Pipeline> parse_pipeline(const std::string& s);
/// Both, gbuffer first, and their names in the same order.
const std::vector<Pipeline>& all_pipelines();
const std::vector<std::string>& pipeline_names();
/// The pipeline foveald, `foveal render` and `foveal bench` use without --pipeline: the
/// visibility pipeline, faster on every scene measured and at least as good on most
/// (docs/rmfr.md, "Which pipeline by default"). FrameParams keeps gbuffer, the paper's.
inline constexpr const char* kDefaultPipelineName = "visibility";

/// Where alphaMode BLEND surfaces are shaded (docs/rmfr.md, "Transparency at the kept
/// samples"):
/// - output: after the eye's inverse pass, forward at full output resolution (the blend
///   pass, docs/scenes.md "Transparency").
/// - samples: in the visibility pipeline with a foveation method, depth-peeled at W×H
///   (ids and depth only) and shaded and composited in the eye's reduced buffer before
///   its inverse pass, so only the samples the method keeps are shaded (transmissive
///   surfaces too, reading the eye's opaque samples resolved to W×H). The full method
///   and the G-buffer pipeline blend at output.
enum class BlendAt { output, samples };
const char* blend_at_name(BlendAt b);
/// "output" or "samples"; bad_input otherwise.
Result<BlendAt> parse_blend_at(const std::string& s);
/// bad_input naming the options where `at` is samples and `pipeline` is not visibility
/// (the compositor would blend at output): for commands that refuse rather than fall back.
Status check_blend_at(BlendAt at, Pipeline pipeline);
/// Both names, output first.
const std::vector<std::string>& blend_at_names();

// Method and EyeFoveation: foveal/image/foveation_plan.hpp.
struct FrameParams {
  Method method = Method::rmfr;
  Pipeline pipeline = Pipeline::gbuffer;
  std::array<EyeFoveation, 2> eyes{};  ///< indexed by Eye
  /// The head's pose relative to where the scene's view puts it (docs/scenes.md,
  /// "Camera"): the camera is the scene's head_to_world composed with this pose, the
  /// position in metres (scaled by the scene's units_per_meter). The identity (default)
  /// is the scene's view exactly. A replay passes PoseAt::relative, the pose relative to
  /// the recording's first pose; a non-unit orientation is renormalised, a non-finite
  /// pose or a zero quaternion is bad_input.
  Pose head{};
  /// Inter-pupillary distance, mm (the user profile's). 0: the display model's.
  /// Anything else outside (0, 200] or not finite is bad_input.
  double ipd_mm = 0.0;
  /// Foveated temporal accumulation (docs/rmfr.md, "Temporal accumulation"): RMFR's grid
  /// jittered every frame and each eye's frame accumulated into a full-resolution history.
  /// Applies to RMFR's kernel (rmfr, uniform, fixed) in the visibility pipeline; other
  /// methods and the G-buffer pipeline render as without it. Off by default.
  bool temporal = false;
  /// Where alphaMode BLEND surfaces are shaded (BlendAt); output, today's, by default.
  BlendAt blend_at = BlendAt::output;
};

/// Whether FrameParams::temporal accumulates frames of method `m` through pipeline `p`:
/// RMFR's kernel (rmfr, uniform, fixed) in the visibility pipeline. Thread-safe (no state).
bool temporal_applies(Method m, Pipeline p);

/// EFR: the dominant eye at sigma_d, the other at sigma_nd.
FrameParams efr_frame(Method method, Eye dominant, double sigma_d, double sigma_nd, double fx, double fy);

/// Milliseconds per pass, both eyes summed (the rows of the RMFR paper's Table 3).
/// In the visibility pipeline `gbuffer` is the full-resolution visibility pass and
/// `mapping` the material pass (pass_names says which).
struct PassTimes {
  Pipeline pipeline = Pipeline::gbuffer;
  double shadow = 0, gbuffer = 0, mapping = 0, lighting = 0, inverse = 0;
  /// alphaMode BLEND surfaces shaded forward at output resolution after the inverse pass
  /// (with lens distortion, also the identity resolve through the lens); 0 without any.
  /// With BlendAt::samples: the depth peeling and the composite in the reduced buffers.
  double blend = 0;
  /// Blended fragments composited (GL_SAMPLES_PASSED, both eyes): at output, the blend
  /// pass's (full resolution); at samples, the reduced buffers' texels, all layers.
  std::size_t blend_samples = 0;
  /// BlendAt::samples: depth-peeled layers composited in the reduced buffers, both eyes
  /// (0: blended at output), and the pixels whose blended surfaces went deeper than the
  /// cap (their deeper surfaces are not drawn; docs/rmfr.md).
  int blend_layers = 0;
  std::size_t blend_dropped = 0;
  double gpu_total = 0;  ///< first to last GPU timestamp of the frame
  double cpu = 0;        ///< wall time of render() including the wait for the GPU
  std::size_t shaded_samples = 0;  ///< lighting-pass samples, both eyes
  /// CLOCK_MONOTONIC: render() began; the fovea was latched (FoveaLatch; without one,
  /// when the latch would have run); glFinish returned, the GPU had finished the frame
  /// (an upper bound by the wake-up, docs/latency.md).
  TimeNs start_ns = 0, latch_ns = 0, gpu_done_ns = 0;
};

/// Late latch (docs/latency.md): called once per frame, after the shadow pass and the
/// left eye's full-resolution pass (G-buffer or visibility) have finished on the GPU
/// (render() waits on a fence first), the last point before a pass that depends on the
/// fovea. It may move the eyes' fovea_x/fovea_y (finite values, clamped to [0, 1]);
/// everything else it changes is ignored. Both eyes use what it leaves.
using FoveaLatch = std::function<void(std::array<EyeFoveation, 2>& eyes)>;

/// The names of the passes timed in `gbuffer` and `mapping` for a pipeline:
/// {"gbuffer", "mapping"} or {"visibility", "material"}.
std::array<const char*, 2> pass_names(Pipeline p);

/// Per-field median of several frames' times (the mean of the middle two for an even
/// count; all zero for none).
PassTimes median_pass_times(const std::vector<PassTimes>& frames);

struct CompositorOptions {
  int width = 2880, height = 1600;  ///< side-by-side output; each eye width/2 × height
  DisplayModel model = DisplayModel::vive_pro_eye();
  bool float_output = false;  ///< RGBA32F reduced buffers and output (for NaN/Inf tests)
  int shadow_map_size = 2048;
  int point_lights = 64;
  /// The file's lights through per-tile lists (light_tiles.hpp); false: every light at every sample.
  bool light_tiles = true;
  bool distortion = true;  ///< apply the display model's lens distortion, if it has one
};

/// Bytes held by the render targets right now. `visibility`: the visibility pipeline's
/// id and depth target, and BlendAt::samples's peeled layers (W×H each); its material surfaces count as `transformed` (W×H ones for full
/// as `gbuffer`).
struct TargetMemory {
  std::size_t gbuffer = 0, transformed = 0, reduced = 0, output = 0, shadow = 0, visibility = 0;
  std::size_t temporal = 0;  ///< temporal accumulation's histories (visibility pipeline; 0 until used)
  std::size_t total() const { return gbuffer + transformed + reduced + output + shadow + visibility + temporal; }
};

class Compositor {
 public:
  /// Compiles the shaders and allocates the full-size targets. Needs a current GL 4.5
  /// context. Errors: bad sizes (bad_input), shader files missing (io) or not compiling.
  static Result<Compositor> create(const CompositorOptions& options, const gl::ShaderLoader& shaders = gl::ShaderLoader());
  Compositor(Compositor&&) noexcept;
  Compositor& operator=(Compositor&&) noexcept;
  ~Compositor();

  /// Renders one frame into the output and waits for it. σ < 1 or f <= 0 (or not finite),
  /// a bad head pose or IPD (FrameParams) are bad_input; transformed buffers are (re)allocated when an eye's w×h changes.
  /// `latch`, if given, supplies the fovea points late in the frame (FoveaLatch).
  Result<PassTimes> render(const Scene& scene, const FrameParams& params, const FoveaLatch& latch = {});

  /// The output as 8-bit sRGB, top row first. With float_output, the float pixels
  /// (linear, bottom row first) come from read_float().
  image::Image read_image() const;
  std::vector<float> read_float() const;

  GLuint output_framebuffer() const;
  int width() const;
  int height() const;
  int eye_width() const;
  /// The w×h of an eye's reduced buffer in the last frame (W×H for full).
  std::array<int, 2> buffer_size(Eye e) const;
  /// The plan each eye was rendered with in the last frame.
  const EyePlan& plan(Eye e) const;
  /// Drops temporal accumulation's history: the next frame shows its own samples only
  /// (the jitter sequence goes on).
  void reset_history();
  TargetMemory memory() const;
  /// The targets one pipeline's frames use (those held now; a pipeline not used yet
  /// holds only the shared output and shadow map).
  TargetMemory memory(Pipeline p) const;
  /// "vendor / renderer / version".
  std::string renderer() const;

  /// The shader variant the last frame's scene was drawn with: "metal-rough", plus
  /// "+clearcoat", "+specular", "+sheen", "+anisotropy", "+transmission" for the material features its materials use
  /// (docs/scenes.md, "Materials"), and the bytes per pixel of its G-buffer layout.
  std::string shading_variant() const;
  std::size_t gbuffer_bytes_per_pixel() const;
  /// The MaterialFeature bits the variant draws: the scene's, less those past the G-buffer
  /// targets GL promises (SurfaceLayout in render_targets.hpp: at most three layers).
  unsigned material_features() const;

 private:
  struct Impl;
  explicit Compositor(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace foveal::render
